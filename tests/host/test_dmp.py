"""The numpy DMP against independent references: the closed-loop law, replay of h_d, scaling."""
from __future__ import annotations

import numpy as np
import pytest

from forceskill import dmp, synthetic
from forceskill.errors import ParamError
from forceskill.fit import FitResult, desired_forcing
from forceskill.params import Gains, derive, goal_prime
from forceskill.skill import Skill

GAIN_SETS = [
    (Gains(), 100.0),
    (Gains(), 600.0),
    (Gains(m_d_kg=10.0, k_d_Nspm=150.0, k_p_Npm=400.0, k_f=1.0, k_i_per_s=5.0), 300.0),
    (Gains(m_d_kg=2.0, k_d_Nspm=60.0, k_p_Npm=300.0, k_f=0.5, k_i_per_s=10.0), 50.0),
]


def law_closed_loop(gains: Gains, k: float, dt: float, x_d: np.ndarray, f_d: np.ndarray) -> np.ndarray:
    """Paper eq. (10) on a spring f = k x, forward Euler in (x, xd, int x, int f_d); returns x_n.

    m_d xdd = k_d (0 - xd) + k_p (x_d - x) + k_f (f_d - f) + k_i (int f_d - k int x).
    """
    m = len(x_d)
    x = xd = ix = F = 0.0
    out = [0.0]
    for n in range(m):
        f = k * x
        xdd = (-gains.k_d_Nspm * xd + gains.k_p_Npm * (x_d[n] - x) + gains.k_f * (f_d[n] - f)
               + gains.k_i_per_s * (F - k * ix)) / gains.m_d_kg
        x, xd, ix, F = x + dt * xd, xd + dt * xdd, ix + dt * x, F + dt * f_d[n]
        out.append(x)
    return np.array(out)


def zero_weight_skill(gains: Gains, k: float, goal: float, tau: float, duration: float) -> Skill:
    p = derive(gains, k)
    c = np.linspace(0.0, 0.99, 10)
    return Skill(dt_s=0.001, tau_s=tau, alpha=p.alpha, beta=p.beta, gamma=p.gamma, stiffness_Npm=k,
                 goal_m=goal, duration_s=duration, m_d_kg=gains.m_d_kg, k_d_Nspm=gains.k_d_Nspm,
                 k_p_Npm=gains.k_p_Npm, k_f=gains.k_f, k_i_per_s=gains.k_i_per_s, surface_m=0.0,
                 centres=c, widths=np.full(10, 0.05), weights=np.zeros(10))


@pytest.mark.parametrize("gains,k", GAIN_SETS)
@pytest.mark.parametrize("time_scale", [1.0, 1.3])
def test_h0_rollout_equals_closed_loop_law_on_a_spring(gains: Gains, k: float, time_scale: float) -> None:
    """Constant x_d and f_d = 0 keep g' constant; tau = 1 s is real time, time_scale stretches dt."""
    p = derive(gains, k)
    x_d = 0.03
    goal = goal_prime(p, gains, x_d, 0.0, 0.0)
    sk = zero_weight_skill(gains, k, goal, tau=1.0, duration=3.0)
    _, f_hat = dmp.rollout(sk, time_scale=time_scale)
    n = f_hat.size - 1
    x_law = law_closed_loop(gains, k, 0.001 / time_scale, np.full(n, x_d), np.zeros(n))
    f_law = k * x_law
    assert np.max(np.abs(f_hat - f_law)) <= 1e-10 * np.max(np.abs(f_law))
    assert np.max(np.abs(f_law)) > 0.1 * k * x_d   # the response is not trivially zero


@pytest.mark.parametrize("gains,k", GAIN_SETS)
def test_h0_transform_with_moving_goal_equals_law_with_varying_references(gains: Gains, k: float) -> None:
    """g'_n from time-varying x_d, f_d and int f_d: the DMP tracks the law to round-off."""
    p = derive(gains, k)
    dt = 0.001
    t = np.arange(4000) * dt
    x_d = 0.01 + 0.02 * np.sin(1.3 * t) ** 2
    f_d = 3.0 + 2.0 * np.sin(0.7 * t)
    F = np.concatenate(([0.0], np.cumsum(dt * f_d)[:-1]))    # forward-Euler int f_d at step n
    g_n = np.array([goal_prime(p, gains, a, b, c) for a, b, c in zip(x_d, f_d, F)])
    x, _, _ = dmp.transform_loop(p.alpha, p.beta, p.gamma, dt, g_n, np.zeros(t.size))
    x_law = law_closed_loop(gains, k, dt, x_d, f_d)
    assert np.max(np.abs(x - x_law)) <= 1e-10 * np.max(np.abs(x_law))


def test_printed_beta_of_the_paper_does_not_reproduce_the_law() -> None:
    gains, k = Gains(), 600.0
    p = derive(gains, k)
    beta_paper = (gains.k_p_Npm + gains.k_f - p.gamma) / (gains.m_d_kg * p.alpha) - 1.0
    goal_ok = goal_prime(p, gains, 0.03, 0.0, 0.0)
    goal_paper = (gains.k_p_Npm * 0.03 / gains.m_d_kg) / (p.alpha * beta_paper)
    n = 3000
    x_good, _, _ = dmp.transform_loop(p.alpha, p.beta, p.gamma, 0.001, goal_ok, np.zeros(n))
    x_bad, _, _ = dmp.transform_loop(p.alpha, beta_paper, p.gamma, 0.001, goal_paper, np.zeros(n))
    x_law = law_closed_loop(gains, k, 0.001, np.full(n, 0.03), np.zeros(n))
    assert np.max(np.abs(x_good - x_law)) <= 1e-10 * np.max(np.abs(x_law))
    # a million times the tolerance the corrected beta meets
    assert np.max(np.abs(x_bad - x_law)) >= 1e-4 * np.max(np.abs(x_law))


def test_replay_of_h_d_reproduces_the_target(press_fit: FitResult) -> None:
    sk = press_fit.skill
    x_star = press_fit.target_N / sk.stiffness_Npm
    a = sk.dt_s / sk.tau_s
    h_d = desired_forcing(x_star, sk.alpha, sk.beta, sk.gamma, a, sk.goal_m)
    np.testing.assert_array_equal(h_d, press_fit.h_d)
    x, _, _ = dmp.transform_loop(sk.alpha, sk.beta, sk.gamma, a, sk.goal_m, h_d)
    assert x_star[0] == 0.0
    assert np.max(np.abs(x - x_star)) <= 1e-9 * np.max(np.abs(x_star))


@pytest.mark.parametrize("scale", [0.5, 1.5, 2.0])
def test_goal_scaling_scales_the_force_exactly(press_fit: FitResult, scale: float) -> None:
    _, f1 = dmp.rollout(press_fit.skill)
    _, fs = dmp.rollout(press_fit.skill, goal_scale=scale)
    assert np.max(np.abs(fs - scale * f1)) <= 1e-9 * np.max(np.abs(scale * f1))


def test_time_scaling_stretches_the_force(engrave_fit: FitResult) -> None:
    sk = engrave_fit.skill
    t1, f1 = dmp.rollout(sk)
    ts, fs = dmp.rollout(sk, time_scale=1.3)
    assert fs.size - 1 == round(1.3 * (f1.size - 1))
    f_stretched = np.interp(ts / 1.3, t1, f1)
    # the same continuous trajectory; only the Euler discretisation differs (dt/tau changes)
    assert np.max(np.abs(fs - f_stretched)) <= 2e-3 * np.max(np.abs(f1))


def test_rollout_equals_the_fit_s_own_evaluation(press_fit: FitResult, engrave_fit: FitResult) -> None:
    for res in (press_fit, engrave_fit):
        t, f = dmp.rollout(res.skill)
        np.testing.assert_allclose(t, res.t_s, rtol=0, atol=1e-12)
        assert np.max(np.abs(f - res.f_hat_N)) <= 1e-9 * np.max(np.abs(f))


def test_phase_reaches_0_99_at_the_duration(press_fit: FitResult) -> None:
    sk = press_fit.skill
    u, v = dmp.phase_loop(sk.alpha, sk.beta, sk.dt_s / sk.tau_s, dmp.default_steps(sk))
    assert u[-1] == pytest.approx(0.99, abs=1e-12)
    assert np.all(np.diff(u) >= 0.0) and np.all(v >= 0.0)


def test_scans_equal_the_loops() -> None:
    p = derive(Gains(), 280.0)
    a = 0.001 / 5.3
    u, v = dmp.phase_loop(p.alpha, p.beta, a, 9000)
    us, vs = dmp.phase_scan(p.alpha, p.beta, a, 9000)
    assert np.max(np.abs(u - us)) <= 1e-12 and np.max(np.abs(v - vs)) <= 1e-12 * np.max(v)
    h = 5.0 * np.sin(np.arange(9000) * 0.002) + 2.0
    x, z, big_i = dmp.transform_loop(p.alpha, p.beta, p.gamma, a, 0.4, h)
    xs, zs, i_s = dmp.transform_scan(p.alpha, p.beta, p.gamma, a, 0.4, h)
    for ref, got in ((x, xs), (z, zs), (big_i, i_s)):
        assert np.max(np.abs(ref - got)) <= 1e-12 * np.max(np.abs(ref))


def full_sum(u: np.ndarray, sk: Skill) -> np.ndarray:
    """S(u) over every kernel with no cutoff (independent of the cutoff and shift rules)."""
    e = (u[:, None] - sk.centres[None, :]) ** 2 / (2.0 * sk.widths ** 2)
    psi = np.exp(-e)
    return (psi @ sk.weights) / psi.sum(axis=1)


def test_cutoff_kernel_sum_equals_the_full_sum(press_fit: FitResult, engrave_fit: FitResult) -> None:
    for res in (press_fit, engrave_fit):
        sk = res.skill
        u, _ = dmp.phase_loop(sk.alpha, sk.beta, sk.dt_s / sk.tau_s, dmp.default_steps(sk))
        s_cut = dmp.forcing_scale(u, sk)
        s_full = full_sum(u, sk)
        assert np.max(np.abs(s_cut - s_full)) <= 1e-9 * np.max(np.abs(s_full))
        dense = dmp._normalised_kernels_dense(u, sk.centres, sk.widths) @ sk.weights
        assert np.max(np.abs(s_cut - dense)) <= 1e-13 * np.max(np.abs(dense))
        active = (dmp.kernel_exponents(u, sk.centres, sk.widths) <= dmp.KERNEL_CUTOFF_EXP).sum(axis=1)
        assert active.max() < sk.n_kernels // 2     # most kernels are skipped on every tick


def test_far_from_every_kernel_the_nearest_kernel_alone_is_used() -> None:
    sk = zero_weight_skill(Gains(), 100.0, 0.5, 1.0, 2.0)
    sk.weights = np.arange(10, dtype=float)
    sk.widths = np.full(10, 0.001)
    u = np.array([0.0, 0.0552, 0.4, 0.99, 1.2, 5.0])
    s = dmp.forcing_scale(u, sk)
    nearest = np.argmin(np.abs(u[:, None] - sk.centres[None, :]), axis=1)
    np.testing.assert_array_equal(s, sk.weights[nearest])
    # unsorted u takes the dense path: same numbers
    np.testing.assert_array_equal(dmp.forcing_scale(u[::-1], sk), s[::-1])


@pytest.mark.parametrize("gs,ts", [(np.nan, 1.0), (1.0, 0.0), (1.0, -1.0), (1.0, np.inf)])
def test_invalid_scales_are_refused(press_fit: FitResult, gs: float, ts: float) -> None:
    with pytest.raises(ParamError) as e:
        dmp.rollout(press_fit.skill, goal_scale=gs, time_scale=ts)
    assert e.value.code == 109


def test_rollout_rows_and_start(press_fit: FitResult) -> None:
    sk = press_fit.skill
    t, f = dmp.rollout(sk, n_steps=17)
    assert t.size == 18 and f[0] == 0.0 and f[1] == 0.0   # v = 0 at t = 0 -> h = 0; x moves from step 2
    assert t[-1] == pytest.approx(0.017)
    assert synthetic.SURFACE_M == sk.surface_m

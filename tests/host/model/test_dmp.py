"""The numpy DMP against independent references: the closed-loop law, replay of h_d, scaling."""

from __future__ import annotations

import numpy as np
import pytest

from forceskill.errors import ParamError
from forceskill.model import dmp, synthetic
from forceskill.model.fit import FitResult, desired_forcing
from forceskill.model.params import Gains, derive, goal
from forceskill.model.skill import Skill


def at_k(m_d: float, k_d: float, k_p: float, k_f: float, k_i: float, k: float) -> Gains:
    """The skill's gains for controller gains k_f, k_i on stiffness k."""
    return Gains(m_d, k_d, k_p, k * k_f, k * k_i)


GAIN_SETS = [
    (Gains(), 100.0),
    (Gains(), 600.0),
    (Gains(), 1e6),
    (at_k(10.0, 150.0, 400.0, 1.0, 5.0, 300.0), 300.0),
    (at_k(2.0, 60.0, 300.0, 0.5, 10.0, 50.0), 50.0),
]


def law_closed_loop(gains: Gains, k: float, dt: float, x_d: np.ndarray, f_d: np.ndarray) -> np.ndarray:
    """Paper eq. (10) on a spring f = k x, forward Euler in (x, xd, int x, int f_d); returns x_n.

    m_d xdd = k_d (0 - xd) + k_p (x_d - x) + k_f (f_d - f) + k_i (int f_d - k int x), written in
    metres with the controller's k_f = kkf/k, k_i = kki/k (independent of the DMP's formulas).
    """
    k_f, k_i = gains.kkf_Npm / k, gains.kki_Npms / k
    m = len(x_d)
    x = xd = ix = F = 0.0
    out = [0.0]
    for n in range(m):
        f = k * x
        xdd = (
            -gains.k_d_Nspm * xd + gains.k_p_Npm * (x_d[n] - x) + k_f * (f_d[n] - f) + k_i * (F - k * ix)
        ) / gains.m_d_kg
        x, xd, ix, F = x + dt * xd, xd + dt * xdd, ix + dt * x, F + dt * f_d[n]
        out.append(x)
    return np.array(out)


def zero_weight_skill(
    gains: Gains,
    k: float,
    goal_N: float,
    tau: float,
    duration: float,
    force0_N: float = 0.0,
) -> Skill:
    p = derive(gains)
    c = np.linspace(0.0, 0.99, 10)
    return Skill(
        dt_s=0.001,
        tau_s=tau,
        alpha=p.alpha,
        beta=p.beta,
        gamma=p.gamma,
        stiffness_Npm=k,
        goal_N=goal_N,
        duration_s=duration,
        m_d_kg=gains.m_d_kg,
        k_d_Nspm=gains.k_d_Nspm,
        k_p_Npm=gains.k_p_Npm,
        kkf_Npm=gains.kkf_Npm,
        kki_Npms=gains.kki_Npms,
        surface_m=0.0,
        force0_N=force0_N,
        centres=c,
        widths=np.full(10, 0.05),
        weights=np.zeros(10),
    )


@pytest.mark.parametrize("gains,k", GAIN_SETS)
@pytest.mark.parametrize("time_scale", [1.0, 1.3])
def test_h0_rollout_equals_closed_loop_law_on_a_spring(gains: Gains, k: float, time_scale: float) -> None:
    """Constant x_d and f_d = 0 keep g' constant; tau = 1 s is real time, time_scale stretches dt."""
    p = derive(gains)
    x_d = 0.03 * 100.0 / k
    sk = zero_weight_skill(gains, k, goal(p, gains, k * x_d, 0.0, 0.0), tau=1.0, duration=3.0)
    _, f_hat = dmp.rollout(sk, time_scale=time_scale)
    n = f_hat.size - 1
    x_law = law_closed_loop(gains, k, 0.001 / time_scale, np.full(n, x_d), np.zeros(n))
    f_law = k * x_law
    assert np.max(np.abs(f_hat - f_law)) <= 1e-10 * np.max(np.abs(f_law))
    assert np.max(np.abs(f_law)) > 0.1 * k * x_d  # the response is not trivially zero


@pytest.mark.parametrize("gains,k", GAIN_SETS)
def test_h0_transform_with_moving_goal_equals_law_with_varying_references(gains: Gains, k: float) -> None:
    """g'_n from time-varying x_d, f_d and int f_d: the DMP tracks the law to round-off."""
    p = derive(gains)
    dt = 0.001
    t = np.arange(4000) * dt
    x_d = (0.01 + 0.02 * np.sin(1.3 * t) ** 2) * 100.0 / k
    f_d = 3.0 + 2.0 * np.sin(0.7 * t)
    F = np.concatenate(([0.0], np.cumsum(dt * f_d)[:-1]))  # forward-Euler int f_d at step n
    g_n = np.array([goal(p, gains, k * a, b, c) for a, b, c in zip(x_d, f_d, F, strict=False)])
    y, _, _ = dmp.transform_loop(p.alpha, p.beta, p.gamma, dt, g_n, np.zeros(t.size))
    f_law = k * law_closed_loop(gains, k, dt, x_d, f_d)
    assert np.max(np.abs(y - f_law)) <= 1e-10 * np.max(np.abs(f_law))


def test_printed_beta_of_the_paper_does_not_reproduce_the_law() -> None:
    gains, k = Gains(), 600.0
    p = derive(gains)
    k_f = gains.kkf_Npm / k
    beta_paper = (gains.k_p_Npm + k_f - p.gamma) / (gains.m_d_kg * p.alpha) - 1.0
    goal_ok = goal(p, gains, k * 0.03, 0.0, 0.0)
    goal_paper = k * (gains.k_p_Npm * 0.03 / gains.m_d_kg) / (p.alpha * beta_paper)
    n = 3000
    y_good, _, _ = dmp.transform_loop(p.alpha, p.beta, p.gamma, 0.001, goal_ok, np.zeros(n))
    y_bad, _, _ = dmp.transform_loop(p.alpha, beta_paper, p.gamma, 0.001, goal_paper, np.zeros(n))
    f_law = k * law_closed_loop(gains, k, 0.001, np.full(n, 0.03), np.zeros(n))
    assert np.max(np.abs(y_good - f_law)) <= 1e-10 * np.max(np.abs(f_law))
    # a million times the tolerance the corrected beta meets
    assert np.max(np.abs(y_bad - f_law)) >= 1e-4 * np.max(np.abs(f_law))


def test_replay_of_h_d_reproduces_the_target(press_fit: FitResult) -> None:
    sk = press_fit.skill
    y_star = press_fit.target_N - sk.force0_N
    a = sk.dt_s / sk.tau_s
    h_d = desired_forcing(y_star, sk.alpha, sk.beta, sk.gamma, a, sk.goal_N)
    np.testing.assert_array_equal(h_d, press_fit.h_d)
    y, _, _ = dmp.transform_loop(sk.alpha, sk.beta, sk.gamma, a, sk.goal_N, h_d)
    assert y_star[0] == 0.0
    assert np.max(np.abs(y - y_star)) <= 1e-9 * np.max(np.abs(y_star))


@pytest.mark.parametrize("scale", [0.5, 1.5, 2.0])
def test_goal_scaling_scales_the_force_exactly(press_fit: FitResult, scale: float) -> None:
    _, f1 = dmp.rollout(press_fit.skill)
    _, fs = dmp.rollout(press_fit.skill, goal_scale=scale)
    assert np.max(np.abs(fs - scale * f1)) <= 1e-9 * np.max(np.abs(scale * f1))
    # starting in contact: the part above the starting force scales exactly
    sk = Skill.from_bytes(press_fit.skill.to_bytes())
    sk.force0_N = 2.5
    _, g1 = dmp.rollout(sk)
    _, gs = dmp.rollout(sk, goal_scale=scale)
    assert g1[0] == gs[0] == 2.5
    assert np.max(np.abs((gs - 2.5) - scale * (g1 - 2.5))) <= 1e-9 * np.max(np.abs(scale * f1))


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
    p = derive(Gains())
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
    e = (u[:, None] - sk.centres[None, :]) ** 2 / (2.0 * sk.widths**2)
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
        assert active.max() < sk.n_kernels // 2  # most kernels are skipped on every tick


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
    assert t.size == 18 and f[0] == 0.0 and f[1] == 0.0  # v = 0 at t = 0 -> h = 0; x moves from step 2
    assert t[-1] == pytest.approx(0.017)
    assert sk.surface_m == synthetic.SURFACE_M


def test_chunked_transform_scan_and_block_passes_give_the_same_numbers(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """The long-fit memory savings change no number beyond round-off: transform_scan in chunks
    (state carried) equals the sequential loop, the phase in blocks equals phase_scan, the kernels
    block by block are the dense ones, and a fit in small blocks is the fit in large ones."""
    from forceskill.model import dmp as D

    rng = np.random.default_rng(3)
    h = rng.normal(0.0, 50.0, 5000)
    ref = D.transform_scan(25.0, 6.25, 40.0, 1e-3 / 3.0, 12.0, h, chunk=1 << 20)
    for chunk in (1, 7, 640, 4999):
        got = D.transform_scan(25.0, 6.25, 40.0, 1e-3 / 3.0, 12.0, h, chunk=chunk)
        for a, b in zip(got, ref, strict=False):
            np.testing.assert_allclose(a, b, rtol=1e-12, atol=1e-12 * np.max(np.abs(b)))
    y_loop = np.empty(h.size + 1)
    y, z, i = 0.0, 0.0, 0.0
    a = 1e-3 / 3.0
    y_loop[0] = 0.0
    for n, hn in enumerate(h):  # the forward-Euler recursion written out (docs/math.md)
        y, z, i = (
            y + a * (z - y - 40.0 * i + hn),
            z + a * 25.0 * (6.25 * (12.0 - y) - z),
            i + a * y,
        )
        y_loop[n + 1] = y
    np.testing.assert_allclose(ref[0], y_loop, rtol=1e-9, atol=1e-9 * np.max(np.abs(y_loop)))
    # the phase in blocks sharing their end sample
    u_ref, v_ref = D.phase_scan(25.0, 6.25, a, 5000)
    for block in (1, 63, 640, 5000, 1 << 15):
        parts = list(D.phase_blocks(25.0, 6.25, a, 5000, block))
        assert [i0 for i0, _, _ in parts] == list(range(0, 5000, block))
        u = np.concatenate([pu[:-1] for _, pu, _ in parts] + [parts[-1][1][-1:]])
        v = np.concatenate([pv[:-1] for _, _, pv in parts] + [parts[-1][2][-1:]])
        assert np.max(np.abs(u - u_ref)) <= 1e-12 and np.max(np.abs(v - v_ref)) <= 1e-12 * np.max(v_ref)
    # kernels block by block: the dense values, whatever the blocks; rows out of reach -> nearest
    u = np.concatenate((np.sort(rng.uniform(0.0, 1.0, 3000)), [1.3, 1.4]))
    c = np.sort(rng.uniform(0.0, 1.0, 40))
    w = 0.65 * np.append(np.diff(c), 0.01)
    e = D.kernel_exponents(u, c, w)
    dense = np.where(e <= D.KERNEL_CUTOFF_EXP, np.exp(-np.minimum(e, D.KERNEL_CUTOFF_EXP + 1.0)), 0.0)
    for budget in (1, 500, 1 << 17):
        got = np.zeros_like(dense)
        for r0, k0, psi in D.kernel_blocks(u, c, w, budget):
            got[r0 : r0 + psi.shape[1], k0 : k0 + psi.shape[0]] = psi.T
        np.testing.assert_array_equal(got, dense)
    weights = rng.normal(0.0, 1.0, 40)
    mixed = D.kernel_mix(u, c, w, [weights])[0]
    np.testing.assert_allclose(mixed, D._normalised_kernels_dense(u, c, w) @ weights, rtol=0, atol=1e-13)
    assert mixed[-1] == weights[np.argmin(e[-1])]  # no kernel within the cutoff
    # a fit in blocks of 700 steps is the fit in one block
    from forceskill.model.fit import fit

    demo = synthetic.wiping(seed=3)
    whole = fit(demo, 100.0, n_kernels=50, surface_m=synthetic.SURFACE_M)
    monkeypatch.setattr(D, "FIT_BLOCK", 700)
    parts_fit = fit(demo, 100.0, n_kernels=50, surface_m=synthetic.SURFACE_M)
    for got_w, ref_w in (
        (parts_fit.skill.weights, whole.skill.weights),
        (parts_fit.skill.y_weights, whole.skill.y_weights),
    ):
        assert got_w is not None and ref_w is not None
        assert np.max(np.abs(got_w - ref_w)) <= 1e-9 * np.max(np.abs(ref_w))
    assert np.max(np.abs(parts_fit.f_hat_N - whole.f_hat_N)) <= 1e-9 * np.max(np.abs(whole.f_hat_N))
    assert parts_fit.err_max_pct == pytest.approx(whole.err_max_pct, rel=1e-9)
    assert parts_fit.y_err_max_mm == pytest.approx(whole.y_err_max_mm, rel=1e-9)

"""Fitting on smooth synthetic demonstrations shaped like the paper's four tasks (8-9 s, 1 kHz).

Bounds on both sides: the default fit must be accurate, and a too-small model must be visibly
worse (so the error measure is not vacuous). Figures measured at the time of writing are in
docs/math.md section 3.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import pytest

from forceskill.errors import DemoError, ParamError
from forceskill.model import dmp, synthetic
from forceskill.model.demo import Demo
from forceskill.model.fit import FitResult, fit, solve_tau
from forceskill.model.params import Gains, derive

TASKS = {
    "press_100_180": (lambda s: synthetic.pressing(s, 8.0, 100.0, 180.0), 100.0, "pressing"),
    "press_500_600": (lambda s: synthetic.pressing(s, 8.0, 500.0, 600.0), 500.0, "pressing"),
    "engrave_100": (lambda s: synthetic.engraving(s, 8.0, 100.0, 6.0), 100.0, "engraving"),
    "engrave_280": (lambda s: synthetic.engraving(s, 9.0, 280.0, 10.0), 280.0, "engraving"),
}
PAPER_BOUND = {"pressing": 4.0, "engraving": 6.0}


def independent_error(res: FitResult) -> tuple[float, float]:
    """max and RMS |f - f_hat| in % of max |f|, from dmp.rollout of the written image."""
    from forceskill.model.skill import Skill

    sk = Skill.from_bytes(res.skill.to_bytes())
    _, f_hat = dmp.rollout(sk)
    e = res.target_N - f_hat
    m = np.max(np.abs(res.target_N))
    return 100 * np.max(np.abs(e)) / m, 100 * np.sqrt(np.mean(e * e)) / m


@pytest.mark.parametrize("task", TASKS)
@pytest.mark.parametrize("seed", [0, 1])
def test_default_fit_n50_is_within_1_2_percent(task: str, seed: int) -> None:
    make, k, _ = TASKS[task]
    res = fit(make(seed), k, surface_m=synthetic.SURFACE_M)
    assert res.skill.n_kernels == 50 and res.method == "ridge"
    e_max, e_rms = independent_error(res)
    assert res.err_max_pct == pytest.approx(e_max, rel=1e-6)
    assert res.err_rms_pct == pytest.approx(e_rms, rel=1e-6)
    assert 0.05 < res.err_max_pct <= 1.2
    assert 0.01 < res.err_rms_pct <= 0.3


@pytest.mark.parametrize("task", TASKS)
def test_ten_kernels_are_clearly_not_enough(task: str) -> None:
    make, k, _ = TASKS[task]
    res = fit(make(0), k, n_kernels=10)
    assert res.err_max_pct >= 5.0


@pytest.mark.parametrize("task", TASKS)
def test_lwr_is_within_the_paper_bounds_at_50_kernels(task: str) -> None:
    make, k, kind = TASKS[task]
    res50 = fit(make(1), k, n_kernels=50, method="lwr")
    # measured 1.1-3.1 % (docs/math.md section 3); the paper's N = 50 bound must hold
    assert 0.5 < res50.err_max_pct <= PAPER_BOUND[kind]
    res = fit(make(1), k, n_kernels=100, method="lwr")
    assert 0.1 < res.err_max_pct <= PAPER_BOUND[kind]
    ridge50 = fit(make(1), k, n_kernels=50)
    assert res50.err_max_pct > res.err_max_pct  # more kernels help LWR
    assert res50.err_max_pct > 2.0 * ridge50.err_max_pct  # ridge is the more accurate method


def test_noisy_sensor_fit_is_limited_by_the_noise() -> None:
    clean = synthetic.engraving(4, 8.0, 100.0, 6.0)
    noisy = synthetic.engraving(4, 8.0, 100.0, 6.0, noise_N=0.02)
    res = fit(noisy, 100.0)
    # against the clean force the learned profile is better than the noise amplitude suggests
    e_clean = 100 * np.max(np.abs(clean.force_N - res.f_hat_N)) / np.max(clean.force_N)
    assert e_clean < 1.0
    assert res.err_max_pct <= 2.5


def reference_kernel_times(y: np.ndarray, dt: float, n: int) -> np.ndarray:
    """docs/math.md section 3, step 3, written out with loops: 50 ms bin means, curvature
    |second difference| (0 in the end bins), moving mean over 13 bins (0.6 s, ends repeated),
    clipped at 2x its mean, density 1 + 0.5*q/mean(q) per bin, t_i where the running integral
    of the density reaches (i-1)/(N-1) of the total (linear within a bin)."""
    hb = 50
    nb = y.size // hb
    means = [sum(y[b * hb : (b + 1) * hb]) / hb for b in range(nb)]
    q = [0.0] + [abs(means[b + 1] - 2 * means[b] + means[b - 1]) for b in range(1, nb - 1)] + [0.0]
    qs = [sum(q[min(max(j, 0), nb - 1)] for j in range(b - 6, b + 7)) / 13 for b in range(nb)]
    mean = sum(qs) / nb
    rho = [1.0 + 0.5 * min(v / mean, 2.0) for v in qs]
    edges = [b * hb * dt for b in range(nb)] + [(y.size - 1) * dt]
    cum = [0.0]
    for b in range(nb):
        cum.append(cum[-1] + rho[b] * (edges[b + 1] - edges[b]))
    out = []
    for i in range(n):
        target = cum[-1] * i / (n - 1)
        b = next(b for b in range(nb) if cum[b + 1] >= target)
        out.append(edges[b] + (target - cum[b]) / rho[b])
    out[0], out[-1] = 0.0, edges[-1]
    return np.array(out)


def test_tau_centres_widths_goal(press_fit: FitResult) -> None:
    sk = press_fit.skill
    # continuous critically damped phase: 1 - u = (1 + s) e^-s = 0.01 at s = alpha T/(2 tau) = 6.638
    assert sk.tau_s / sk.duration_s == pytest.approx(9.0 / (2 * 6.6384), rel=2e-3)
    u, _ = dmp.phase_loop(sk.alpha, sk.beta, sk.dt_s / sk.tau_s, dmp.default_steps(sk))
    assert u[-1] == pytest.approx(0.99, abs=1e-12)
    assert sk.centres[0] == 0.0 and sk.centres[-1] == pytest.approx(0.99, abs=1e-12)
    t_i = reference_kernel_times(press_fit.target_N - sk.force0_N, sk.dt_s, sk.n_kernels)
    np.testing.assert_allclose(sk.centres, np.interp(t_i, np.arange(u.size) * sk.dt_s, u), atol=1e-12)
    gaps = np.diff(sk.centres)
    np.testing.assert_allclose(sk.widths[1:-1], 0.65 * (gaps[:-1] + gaps[1:]) / 2, rtol=1e-14)
    assert sk.widths[0] == pytest.approx(0.65 * gaps[0], rel=1e-14)
    assert sk.widths[-1] == pytest.approx(0.65 * gaps[-1], rel=1e-14)
    # g = k*g'(T) in N with k*x_d(T) = f(T), int f by the left rectangle rule, above f0
    y = press_fit.target_N - sk.force0_N
    g = Gains()
    c = (g.k_p_Npm * y[-1] + g.kkf_Npm * y[-1] + g.kki_Npms * 0.001 * np.sum(y[:-1])) / g.m_d_kg
    assert sk.goal_N == pytest.approx(c / (9.0 * 2.25), rel=1e-12)


@pytest.mark.parametrize("beta_frac", [0.25, 0.2, 0.1])
def test_solve_tau_hits_the_phase_target_for_other_gains(beta_frac: float) -> None:
    alpha = 12.0
    beta = beta_frac * alpha
    for n in (500, 3000, 17000):
        tau = solve_tau(alpha, beta, 0.001, n)
        u, _ = dmp.phase_loop(alpha, beta, 0.001 / tau, n)
        assert u[-1] == pytest.approx(0.99, abs=1e-11)


def test_demo_without_net_push_is_refused() -> None:
    t = np.arange(3000) * 0.001
    f = np.sin(2 * np.pi * t / 3.0)  # pushes, then pulls back: no net impulse
    d = Demo(t, np.zeros_like(t), f)
    with pytest.raises(DemoError) as e:
        fit(d, 100.0)
    assert e.value.code == 611 and "no net push" in str(e.value)


def test_unstable_or_non_monotone_gains_are_refused() -> None:
    d = synthetic.pressing(0, 2.0)
    with pytest.raises(ParamError) as e:
        fit(d, 100.0, gains=Gains(k_p_Npm=1500.0))
    assert e.value.code == 105
    with pytest.raises(ParamError) as e:
        fit(d, 100.0, gains=Gains(k_d_Nspm=20.0))
    assert e.value.code == 103


def test_fit_with_other_valid_gains_is_consistent() -> None:
    gains = Gains(m_d_kg=10.0, k_d_Nspm=150.0, k_p_Npm=400.0, kkf_Npm=100.0, kki_Npms=500.0)
    res = fit(synthetic.engraving(2, 6.0), 100.0, gains=gains)
    p = derive(gains)
    assert (res.skill.alpha, res.skill.beta, res.skill.gamma) == (p.alpha, p.beta, p.gamma)
    assert res.err_max_pct < 1.5


STIFFNESSES = (10.0, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7)


@pytest.mark.parametrize("make", [lambda: synthetic.pressing(3, 12.0), lambda: synthetic.engraving(4, 8.0)])
def test_the_error_does_not_depend_on_the_stiffness(make: Callable[[], Demo]) -> None:
    """Same recording, stiffness 10 .. 1e7 N/m: the same error within 0.2 percentage points, every
    rollout finite (the DMP runs in force units; k only scales the controller's force gains)."""
    d = make()
    errs = []
    for k in STIFFNESSES:
        res = fit(d, k)
        _, f = dmp.rollout(res.skill)
        assert np.all(np.isfinite(f))
        errs.append(100.0 * float(np.max(np.abs(f - res.target_N))) / float(np.max(np.abs(res.target_N))))
        assert res.skill.gamma == 13.5 and res.skill.stiffness_Npm == k
    assert max(errs) - min(errs) <= 0.2, errs
    assert max(errs) < 3.0


def test_the_skill_starts_from_the_demonstration_s_first_force() -> None:
    """A sensor bias (-0.8 N) or a demonstration already in contact (+3 N): the skill starts
    there (f0 stored) and reaches the error of the clean demonstration; from 0 it cannot."""
    base = synthetic.pressing(5, 10.0)
    clean = fit(base, 300.0)
    assert clean.skill.force0_N == 0.0
    for offset in (-0.8, 3.0):
        d = Demo(base.t_s, base.pos_m, base.force_N + offset, "offset")
        res = fit(d, 300.0)
        assert res.skill.force0_N == offset
        _t, f = dmp.rollout(res.skill)
        assert f[0] == offset
        f_max = float(np.max(np.abs(res.target_N)))
        err = 100.0 * float(np.max(np.abs(f - res.target_N))) / f_max
        assert err == pytest.approx(res.err_max_pct, abs=1e-9)
        # the same shape above f0 as the clean skill: the same absolute error
        clean_abs = clean.err_max_pct * float(np.max(np.abs(clean.target_N)))
        assert abs(err * f_max - clean_abs) <= 1e-6 * clean_abs
        zero = fit(d, 300.0, force0_N=0.0)
        assert zero.err_max_pct >= 0.9 * 100.0 * abs(offset) / f_max


def test_gains_are_stored_and_the_inertia_check_applies() -> None:
    d = synthetic.pressing(0, 3.0)
    g = Gains(kkf_Npm=400.0)
    res = fit(d, 200.0, gains=g)
    assert (res.skill.kkf_Npm, res.skill.kki_Npms) == (400.0, 4860.0)
    assert res.skill.gains == g
    fit(d, 200.0, gains=g, object_mass_kg=10.0)  # k_f*m_v/m_d = 2*10/40 = 0.5
    with pytest.raises(ParamError) as e:
        fit(d, 200.0, gains=g, object_mass_kg=25.0)  # 1.25
    assert e.value.code == 112


@pytest.mark.parametrize("kind", ["pressing", "engraving"])
def test_default_fit_at_n50_within_1_5_pct_over_seeds(kind: str) -> None:
    """Profiles like the paper's (8-9 s), ten operator seeds: the default fit (ridge, N = 50,
    kernels denser where the force bends) stays within 1.5 % max error (measured: pressing
    <= 0.39 %, engraving <= 0.32 %; bench/accuracy/accuracy_n50.py), and a third of the kernels
    is visibly worse (the measure is not vacuous)."""
    worst = 0.0
    for seed in range(10):
        T = 8.0 + seed % 2
        d = (
            synthetic.pressing(seed, T)
            if kind == "pressing"
            else synthetic.engraving(seed, T, 100.0, 6.0 + seed % 5)
        )
        worst = max(worst, fit(d, 200.0).err_max_pct)
        if seed == 0:
            assert fit(d, 200.0, n_kernels=16).err_max_pct > 2.0 * fit(d, 200.0).err_max_pct
    assert 0.05 < worst <= 1.5


@pytest.mark.parametrize("seed", [4, 9])
def test_default_fit_follows_a_17_s_engraving_with_many_level_changes(seed: int) -> None:
    """The hardest synthetic profile: 17 s of engraving, ~15 level changes, 50 kernels. Centres
    uniform in time (the layout before) miss 1.5 % on these seeds (measured 2.76 / 2.44 %); the
    default layout, denser where the force bends, stays within it (measured 0.77 / 1.22 %;
    bench/accuracy/accuracy_n50.py) and its error is the one the rollout of its image gives."""
    import forceskill.model.fit as fitmod

    d = synthetic.engraving(seed, 17.0, 100.0, 6.0 + seed % 5)
    res = fit(d, 200.0)
    e_max, _ = independent_error(res)
    assert res.err_max_pct == pytest.approx(e_max, rel=1e-6)
    assert 0.05 < res.err_max_pct <= 1.5
    saved = fitmod.DENSITY_GAIN
    try:
        fitmod.DENSITY_GAIN = 0.0
        uniform = fit(d, 200.0)
    finally:
        fitmod.DENSITY_GAIN = saved
    t_uniform = np.linspace(0.0, uniform.skill.duration_s, 50)
    u, _ = dmp.phase_loop(9.0, 2.25, 0.001 / uniform.skill.tau_s, dmp.default_steps(uniform.skill))
    np.testing.assert_allclose(
        uniform.skill.centres, np.interp(t_uniform / 0.001, np.arange(u.size), u), atol=1e-12
    )
    assert uniform.err_max_pct > 1.5
    # what the device pays for it: kernels per tick at the Cortex-M float cutoff 16 (8 with
    # the uniform layout) and the narrowest kernel against the fixed-point limit 1/sigma <= 4096
    sk = res.skill
    u, _ = dmp.phase_loop(sk.alpha, sk.beta, sk.dt_s / sk.tau_s, dmp.default_steps(sk))
    per_tick = (dmp.kernel_exponents(u, sk.centres, sk.widths) <= 16.0).sum(axis=1)
    assert per_tick.max() <= 12
    assert np.max(1.0 / sk.widths) <= 2048.0


def test_kernel_times_are_uniform_without_bends() -> None:
    from forceskill.model.fit import kernel_times

    t = np.arange(8001) * 0.001
    for y in (2.5 * t, np.zeros_like(t), 3.0 * t[:120]):  # a straight line, flat, shorter than 3 bins
        np.testing.assert_allclose(
            kernel_times(y, 0.001, 50), np.linspace(0.0, (y.size - 1) * 0.001, 50), atol=1e-12
        )
    bend = np.minimum(t, 4.0)  # one corner at 4 s: the kernels gather there
    ti = kernel_times(bend, 0.001, 50)
    assert ti[0] == 0.0 and ti[-1] == 8.0 and np.all(np.diff(ti) > 0.0)
    gaps = np.diff(ti)
    assert gaps[np.searchsorted(ti, 4.0) - 1] < 0.8 * gaps[0]


def test_the_y_path_is_learned_on_the_same_phase_and_kernels() -> None:
    """The wiping demonstration's path: the y DMP's rollout (dmp.rollout_path, the literal loop)
    reproduces it within 0.5 mm at N = 50 and 0.05 mm at N = 100; the force half keeps its goal and
    its accuracy, and the learned path is the fit's own y_hat."""
    d = synthetic.wiping(seed=5, duration_s=6.0, k_v=280.0, f_max_N=8.0, path_m=0.06)
    plain = fit(Demo(d.t_s, d.pos_m, d.force_N), 280.0)
    for n, tol_mm in ((50, 0.5), (100, 0.05)):
        res = fit(d, 280.0, n_kernels=n)
        sk = res.skill
        assert sk.has_y and sk.format_version == 3 and sk.y_weights is not None
        _, y = dmp.rollout_path(sk)
        assert d.y_m is not None
        err_mm = 1e3 * float(np.max(np.abs(y - d.y_m)))
        assert err_mm <= tol_mm, (n, err_mm)
        assert abs(err_mm - res.y_err_max_mm) <= 1e-6
        if n == 50:
            # the kernels follow both curvatures (force and path): the force half keeps its goal
            # and stays as accurate as without the path (measured 0.15 vs 0.11 %)
            assert sk.goal_N == plain.skill.goal_N
            assert res.err_max_pct <= 2.0 * plain.err_max_pct <= 0.5


def test_a_path_that_returns_to_its_start_is_learned() -> None:
    """g_y = 0 (the path ends where it started): the forcing carries the whole path."""
    d = synthetic.engraving(seed=4, duration_s=4.0, k_v=280.0, f_max_N=6.0)
    y = 0.02 * np.sin(np.pi * d.t_s / d.t_s[-1]) ** 2
    res = fit(Demo(d.t_s, d.pos_m, d.force_N, y_m=0.3 + y), 280.0)
    assert abs(res.skill.goal_y_m) < 1e-12 and res.skill.y_start_m == 0.3
    assert res.y_err_max_mm < 0.1


def test_y_gains_that_overshoot_are_refused() -> None:
    """beta_y = k_p/(m_d*alpha) - 1 > alpha/4 (105) refuses a demonstration with a path; the same
    gains fit a force-only skill (the force DMP's beta stays within alpha/4)."""
    d = synthetic.wiping(seed=5, duration_s=3.0, k_v=280.0)
    g = Gains(k_p_Npm=1500.0, kki_Npms=Gains().kki_Npms + 340.0 * 9.0)
    fit(Demo(d.t_s, d.pos_m, d.force_N), 280.0, gains=g)
    with pytest.raises(ParamError) as e:
        fit(d, 280.0, gains=g)
    assert e.value.code == 105


@pytest.mark.parametrize("n", [10, 20, 50, 100])
def test_the_layout_keeps_the_device_kernel_count(n: int) -> None:
    """At most KERNELS_PER_TICK_MAX kernels within the Cortex-M float cutoff 16 at any
    phase, for any N (the denser layout falls back when it would need more), checked by
    counting at every interval start (where the largest overlap of closed intervals begins)."""
    from forceskill.model.fit import KERNELS_PER_TICK_MAX, kernels_per_tick

    for seed in (1, 2):
        sk = fit(synthetic.engraving(seed, 8.0, 100.0, 6.0 + seed), 200.0, n_kernels=n).skill
        starts = sk.centres - np.sqrt(32.0) * sk.widths
        e = dmp.kernel_exponents(starts, sk.centres, sk.widths)
        brute = int((e <= 16.0 * (1 + 1e-9)).sum(axis=1).max())
        assert brute == kernels_per_tick(sk.centres, sk.widths) <= KERNELS_PER_TICK_MAX

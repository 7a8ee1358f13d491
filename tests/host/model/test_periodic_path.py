"""The periodic DMP's y path (docs/math.md section 5): reference rollout against an independent
step, the cycle, the path scale, the fit (ridge and LWR), format v4 with flags bit 1, the CLI."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from forceskill.model import periodic, synthetic
from forceskill.model.periodic_fit import PeriodicFit, fit_periodic
from forceskill.model.skill import FLAG_Y_AXIS, Skill

PATH_M = 0.03


@pytest.fixture(scope="module")
def wipe_y_fit() -> PeriodicFit:
    return fit_periodic(synthetic.wiping_strokes(seed=3, path_m=PATH_M), 100.0)


def _path_cycle(skill: Skill, n: int, s_p: float = 1.0) -> np.ndarray:
    """An independent evaluation: (q, z_q) as one matrix step of the law with gamma = 0, every
    kernel summed (no cutoff), the phase as n*a mod 2*pi, beta_y from the gains."""
    a = skill.dt_s / skill.tau_s
    alpha = skill.alpha
    beta_y = skill.k_p_Npm / (skill.m_d_kg * alpha) - 1.0
    m = np.array([[1.0 - a, a], [-a * alpha * beta_y, 1.0 - a * alpha]])
    phi = (np.arange(n + 1) * a) % (2.0 * math.pi)
    k = np.exp(skill.widths[None, :] * (np.cos(phi[:, None] - skill.centres[None, :]) - 1.0))
    assert skill.y_weights is not None
    h = s_p * (k @ skill.y_weights) / k.sum(axis=1)
    s = s_p * np.array([skill.y_p0_m, skill.y_z0_m])
    out = np.empty(n + 1)
    for j in range(n + 1):
        out[j] = s[0]
        s = m @ s + np.array([a * h[j], 0.0])
    res: np.ndarray = skill.y_start_m + s_p * skill.goal_y_m + out
    return res


def test_the_path_is_periodic_and_matches_an_independent_step(wipe_y_fit: PeriodicFit) -> None:
    sk = wipe_y_fit.skill
    p = int(round(sk.duration_s / sk.dt_s))
    t, y = periodic.rollout_path(sk, cycles=4)
    assert y.size == 4 * p + 1 and t[-1] == pytest.approx(4 * sk.duration_s)
    ext = float(np.max(np.abs(y - sk.y_start_m)))
    assert np.max(np.abs(y - _path_cycle(sk, 4 * p))) <= 1e-9 * ext
    cyc = y[:-1].reshape(4, p)
    assert np.max(np.abs(cyc - cyc[0])) <= 1e-9 * ext
    assert np.max(np.abs(periodic.rollout_path_scan(sk, 4 * p) - y)) <= 1e-12 * ext
    # the path starts where the cycle starts (phi = 0): g_y + q0 = 0 within the fit's error
    assert abs(sk.goal_y_m + sk.y_p0_m) <= 1e-3 * wipe_y_fit.y_err_max_mm


def test_the_mean_is_g_y_and_the_path_scale_scales_about_the_start(wipe_y_fit: PeriodicFit) -> None:
    sk = wipe_y_fit.skill
    p = int(round(sk.duration_s / sk.dt_s))
    _, y = periodic.rollout_path(sk, cycles=1)
    ext = float(np.max(np.abs(y - sk.y_start_m)))
    assert float(np.mean(y[:-1])) - sk.y_start_m == pytest.approx(sk.goal_y_m, abs=1e-4 * ext)
    _, y15 = periodic.rollout_path(sk, cycles=2, path_scale=1.5)
    _, y1 = periodic.rollout_path(sk, cycles=2)
    assert np.max(np.abs((y15 - sk.y_start_m) - 1.5 * (y1 - sk.y_start_m))) <= 1e-12 * ext
    assert np.max(np.abs(y15 - _path_cycle(sk, 2 * p, 1.5))) <= 1e-9 * ext
    # the time scale stretches the path with the force: the same path at 1.3x, within forward Euler's
    # first order in dt/tau off the 1x cycle
    _, y13 = periodic.rollout_path(sk, cycles=1, time_scale=1.3)
    ref = np.interp(np.arange(y13.size) / 1.3, np.arange(y1.size), y1)
    assert np.max(np.abs(y13 - ref)) <= 0.02 * ext


def test_fit_learns_the_mean_y_stroke_and_keeps_the_force(wipe_y_fit: PeriodicFit) -> None:
    sk = wipe_y_fit.skill
    assert sk.periodic and sk.has_y and sk.flags & FLAG_Y_AXIS and sk.format_version == 4
    d = synthetic.wiping_strokes(seed=3, path_m=PATH_M)
    p = int(round(sk.duration_s / sk.dt_s))
    # the y path starts where the first steady stroke starts
    assert sk.y_start_m == pytest.approx(float(np.interp(wipe_y_fit.start_s, d.t_s, d.y_m)), abs=1e-6)
    assert wipe_y_fit.y_err_max_mm < 0.01
    _, y = periodic.rollout_path(sk, cycles=1)
    assert np.max(np.abs(y[:p] - wipe_y_fit.y_mean_stroke_m)) * 1e3 == pytest.approx(
        wipe_y_fit.y_err_max_mm, rel=1e-6
    )
    # the force half is the force-only fit's, to the bit (the path shares only the kernels)
    force_only = fit_periodic(synthetic.wiping_strokes(seed=3), 100.0).skill
    np.testing.assert_array_equal(force_only.weights, sk.weights)
    assert (force_only.e0_N, force_only.goal_N) == (sk.e0_N, sk.goal_N)
    lwr = fit_periodic(d, 100.0, method="lwr")
    assert lwr.y_err_max_mm < 0.05 * 1e3 * PATH_M  # the paper's per-kernel LWR: within 5 % of the stroke


def test_v4_image_with_the_y_path_round_trips(wipe_y_fit: PeriodicFit) -> None:
    sk = wipe_y_fit.skill
    b = sk.to_bytes()
    assert len(b) == 208 + 32 * sk.n_kernels + 4
    back = Skill.from_bytes(b)
    assert back.to_bytes() == b and back.has_y and back.y_p0_m == sk.y_p0_m
    assert Skill.from_json_dict(back.to_json_dict()).to_bytes() == b


def test_cli_fit_periodic_with_y_rollout_and_show(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    from forceskill.cli import main

    d = synthetic.wiping_strokes(seed=5, noise_N=0.02, path_m=PATH_M)
    assert d.y_m is not None
    csv = tmp_path / "wipe.csv"
    np.savetxt(
        csv,
        np.column_stack((d.t_s, d.pos_m, d.force_N, d.y_m)),
        delimiter=",",
        header="t,x,f_contact,y",
        comments="",
    )
    out = tmp_path / "wipe.skill"
    assert main(["fit", str(csv), "-k", "100", "--periodic", "--y-column", "y", "-o", str(out)]) == 0
    text = capsys.readouterr().out
    assert "y path (y): start" in text and "against the mean y stroke" in text
    sk = Skill.read(out)
    assert sk.periodic and sk.has_y
    roll = tmp_path / "r.csv"
    assert main(["rollout", str(out), "--cycles", "2", "--path-scale", "0.5", "-o", str(roll)]) == 0
    r = np.loadtxt(roll, delimiter=",", skiprows=1)
    _, y = periodic.rollout_path(sk, cycles=2, path_scale=0.5)
    assert r.shape == (2 * 1200 + 1, 3)
    np.testing.assert_allclose(r[:, 2], y, rtol=0, atol=1e-12)
    capsys.readouterr()
    assert main(["show", str(out)]) == 0
    assert "periodic position DMP on y" in capsys.readouterr().out


VECTORS = Path(__file__).resolve().parents[2] / "vectors"


def _manifest_y() -> list[tuple[str, float, float, float, float, float, str]]:
    out = []
    for ln in (VECTORS / "manifest_periodic_y.txt").read_text().split("\n"):
        if ln.strip():
            s, g, a, t, c, p, csv = ln.split()
            out.append((s, float(g), float(a), float(t), float(c), float(p), csv))
    return out


@pytest.mark.parametrize("skill,gs,amp,ts,cyc,ps,csv", _manifest_y())
def test_golden_periodic_y_rollouts(
    skill: str, gs: float, amp: float, ts: float, cyc: float, ps: float, csv: str
) -> None:
    sk = Skill.read(VECTORS / skill)
    t, f = periodic.rollout(sk, cycles=cyc, goal_scale=gs, amplitude_scale=amp, time_scale=ts)
    _, y = periodic.rollout_path(sk, cycles=cyc, path_scale=ps, time_scale=ts)
    ref = np.loadtxt(VECTORS / csv, delimiter=",", skiprows=1)
    np.testing.assert_array_equal(ref[:, 0], t)
    assert np.max(np.abs(ref[:, 1] - f)) <= 1e-12 * np.max(np.abs(f))
    assert np.max(np.abs(ref[:, 2] - y)) <= 1e-12 * np.max(np.abs(y - sk.y_start_m))


def test_periodic_y_vectors_regenerate() -> None:
    import sys

    sys.path.insert(0, str(VECTORS))
    import generate

    files, lines = generate.golden_periodic_y()
    assert lines == (VECTORS / "manifest_periodic_y.txt").read_text().split("\n")[:-1]
    for name, data in files.items():
        if name.endswith(".csv"):
            new = np.loadtxt(data.decode().split("\n")[1:-1], delimiter=",")
            old = np.loadtxt(VECTORS / name, delimiter=",", skiprows=1)
            assert new.shape == old.shape
            for col in (1, 2):
                assert np.max(np.abs(new[:, col] - old[:, col])) <= 1e-7 * np.max(np.abs(old[:, col]))


def test_the_ramps_start_and_end_the_path_at_rest(wipe_y_fit):
    """``path_ramp``: 0 at the start, smoothstep 3x^2 - 2x^3 of the turns n*a/(2 pi), 1 from the
    first wrap on; the ramped path starts at rest, equals the DMP's from the second cycle on, and
    asks no more of the axis in its first cycle than later (m_d*|y''|, ``path_peak_N``); the
    ramp-out is its mirror over the last turn."""
    from forceskill.model.limits import path_peak_N, path_problem

    sk = wipe_y_fit.skill
    a = sk.dt_s / sk.tau_s
    n = periodic.cycle_steps(sk, 2.0)
    r = periodic.path_ramp(a, n)
    x = np.arange(n + 1) * a / (2.0 * math.pi)
    want = np.where(x < 1.0, 3.0 * x**2 - 2.0 * x**3, 1.0)
    n1 = int(np.ceil(2.0 * math.pi / a))
    assert r[0] == 0.0 and np.all(r[n1 + 1 :] == 1.0)
    assert np.max(np.abs(r - want)) < 1e-9
    _, y = periodic.rollout_path(sk, cycles=2.0)
    _, yr = periodic.rollout_path(sk, cycles=2.0, ramp_in=True)
    assert np.array_equal(yr[n1 + 1 :], y[n1 + 1 :])
    v, vr = np.diff(y) / sk.dt_s, np.diff(yr) / sk.dt_s
    assert abs(vr[0]) < 1e-3 * np.max(np.abs(v)) < abs(v[0])  # the DMP's own path starts moving
    acc = np.abs(np.diff(yr, 2))
    assert np.max(acc[:n1]) <= np.max(acc[n1:])
    # out over the last turn of a run of n ticks: the mirror image, to rest at its start
    ro = periodic.path_ramp(a, n, ramp_out=True)
    u = np.minimum((n - np.arange(n + 1)) * a / (2.0 * math.pi), 1.0)
    assert np.max(np.abs(ro - r * (3.0 * u**2 - 2.0 * u**3))) < 1e-12
    assert ro[-1] == 0.0 and np.max(np.abs(ro[::-1][1 : n1 - 1] - r[1 : n1 - 1])) < 1e-6
    # the demand is linear in the path scale, and the refusal names the largest scale within
    peak = path_peak_N(sk)
    assert peak == pytest.approx(sk.m_d_kg * np.max(acc) / sk.dt_s**2, rel=1e-12)
    assert path_peak_N(sk, path_scale=2.0) == pytest.approx(2.0 * peak, rel=1e-9)
    limit = 0.5 * peak
    assert path_problem(peak, 1.0, peak) == ""
    msg = path_problem(peak, 1.0, limit)
    assert "above the force limit" in msg and "largest path scale 0.5" in msg

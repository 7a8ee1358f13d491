"""The periodic force DMP (docs/math.md section 5): reference rollout, fit, format v4, golden vectors."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from forceskill.errors import FsError, SkillError
from forceskill.model import periodic, synthetic
from forceskill.model.demo import Demo
from forceskill.model.params import derive
from forceskill.model.periodic_fit import PeriodicFit, autocorr_period, fit_periodic
from forceskill.model.skill import KIND_PERIODIC, Skill

VECTORS = Path(__file__).resolve().parents[2] / "vectors"


@pytest.fixture(scope="module")
def wipe_fit() -> PeriodicFit:
    return fit_periodic(synthetic.wiping_strokes(seed=3), 100.0)


def _law_cycle(skill: Skill, n: int) -> np.ndarray:
    """An independent evaluation: the (e, z, I) recursion as one matrix step, every kernel summed
    (no cutoff), the phase as n*a mod 2*pi."""
    a = skill.dt_s / skill.tau_s
    m = periodic.transform_matrix(skill.alpha, skill.beta, skill.gamma, a)
    phi = (np.arange(n + 1) * a) % (2.0 * math.pi)
    k = np.exp(skill.widths[None, :] * (np.cos(phi[:, None] - skill.centres[None, :]) - 1.0))
    h = skill.amplitude_N * (k @ skill.weights) / k.sum(axis=1)
    s = np.array([skill.e0_N, skill.z0_N, skill.i0_N])
    out = np.empty(n + 1)
    for j in range(n + 1):
        out[j] = s[0]
        s = m @ s + np.array([a * h[j], 0.0, 0.0])
    res: np.ndarray = skill.goal_N + out
    return res


def test_the_rollout_is_periodic_and_matches_an_independent_step(wipe_fit: PeriodicFit) -> None:
    sk = wipe_fit.skill
    p = int(round(sk.duration_s / sk.dt_s))
    t, f = periodic.rollout(sk, cycles=4)
    assert f.size == 4 * p + 1 and t[-1] == pytest.approx(4 * sk.duration_s)
    ref = _law_cycle(sk, 4 * p)
    # the full kernel sum vs the cutoff sum: within 1e-9 of max force
    assert np.max(np.abs(f - ref)) <= 1e-9 * np.max(np.abs(f))
    # a limit cycle: every cycle repeats the first (the stored state is on the cycle)
    cyc = f[:-1].reshape(4, p)
    assert np.max(np.abs(cyc - cyc[0])) <= 1e-9 * np.max(np.abs(f))
    assert np.max(np.abs(periodic.rollout_scan(sk, 4 * p) - f)) <= 1e-12 * np.max(np.abs(f))


def test_the_mean_is_the_goal_and_h0_relaxes_to_it(wipe_fit: PeriodicFit) -> None:
    sk = wipe_fit.skill
    p = int(round(sk.duration_s / sk.dt_s))
    _, f = periodic.rollout(sk, cycles=1)
    assert float(np.mean(f[:p])) == pytest.approx(sk.goal_N, rel=1e-9)
    flat = Skill.from_bytes(sk.to_bytes())
    flat.weights = np.zeros_like(flat.weights)
    _, f0 = periodic.rollout(flat, cycles=10)
    assert abs(f0[-1] - sk.goal_N) <= 1e-6 * sk.goal_N


def test_goal_and_amplitude_scale_exactly_and_time_scale_stretches(wipe_fit: PeriodicFit) -> None:
    sk = wipe_fit.skill
    _, f1 = periodic.rollout(sk, cycles=2)
    _, fs = periodic.rollout(sk, cycles=2, goal_scale=1.5, amplitude_scale=0.5)
    dev1 = f1 - sk.goal_N
    devs = fs - 1.5 * sk.goal_N
    assert np.max(np.abs(devs - 0.5 * dev1)) <= 1e-12 * np.max(np.abs(f1))
    p = int(round(sk.duration_s / sk.dt_s))
    _, ft = periodic.rollout(sk, cycles=2, time_scale=1.5)
    assert ft.size == 3 * p + 1
    # the stretched second cycle against the 1x cycle at 2/3 the index: first order in dt/tau
    idx = np.arange(0, 3 * p, 3)
    assert np.max(np.abs(ft[idx] - f1[: idx.size * 2 : 2])) <= 0.02 * np.max(np.abs(f1))


def test_fit_finds_the_period_and_the_steady_strokes_and_learns_the_stroke(wipe_fit: PeriodicFit) -> None:
    r = wipe_fit
    assert r.skill.kind == KIND_PERIODIC and r.skill.format_version == 4
    assert r.period_s == pytest.approx(1.2, rel=1e-4)
    # 12 strokes from t = 1 s; the approach and the release are out: 11 strokes on the grid
    assert r.strokes_N.shape[0] >= 10
    assert r.start_s >= 1.0 - 1e-6 and r.start_s + r.strokes_N.shape[0] * r.period_s <= 1.0 + 12 * 1.2 + 1e-6
    p = r.strokes_N.shape[1]
    true = synthetic.stroke(2.0 * np.pi * ((r.start_s - 1.0) / 1.2 + np.arange(p) / p), 3)
    assert 100.0 * np.max(np.abs(r.cycle_N[:p] - true)) / np.max(true) <= 0.05
    assert np.max(r.err_stroke_max_pct) <= 0.05


def test_fit_with_noise_within_the_issue_bounds() -> None:
    for seed in (0, 1, 2):
        d = synthetic.wiping_strokes(seed=seed, noise_N=0.05, period_s=0.9 + 0.2 * seed)
        r = fit_periodic(d, 100.0)
        period = 0.9 + 0.2 * seed
        assert abs(r.period_s - period) <= 0.01 * period
        p = r.strokes_N.shape[1]
        ph = 2.0 * np.pi * ((r.start_s - 1.0) / period + np.arange(p) / p)
        true = synthetic.stroke(ph, seed)
        assert 100.0 * np.max(np.abs(r.cycle_N[:p] - true)) / np.max(true) <= 3.0


def test_a_given_period_is_used_and_lwr_fits_too() -> None:
    d = synthetic.wiping_strokes(seed=4, period_s=1.0)
    r = fit_periodic(d, 100.0, period_s=1.0, method="lwr", n_kernels=30)
    assert r.period_s == 1.0 and r.skill.n_kernels == 30
    assert r.err_mean_max_pct < 3.0


def test_autocorrelation_period_of_a_sine() -> None:
    t = np.arange(10000) * 0.001
    assert autocorr_period(np.sin(2 * np.pi * t / 0.77), 0.001) == pytest.approx(0.77, rel=2e-3)


def test_refusals() -> None:
    t = np.arange(6000) * 0.001
    flat = Demo(t, np.zeros_like(t), np.full_like(t, 3.0) + 1e-9 * np.sin(t), "flat")
    with pytest.raises(FsError) as e:
        fit_periodic(flat, 100.0, period_s=1.0)
    assert e.value.code == 682
    neg = Demo(t, np.zeros_like(t), -3.0 + np.sin(2 * np.pi * t), "pull")
    with pytest.raises(FsError) as e:
        fit_periodic(neg, 100.0, period_s=1.0)
    assert e.value.code == 681
    with pytest.raises(FsError) as e:
        fit_periodic(synthetic.wiping_strokes(seed=1), 100.0, period_s=9.0)
    assert e.value.code == 680
    with pytest.raises(FsError) as e:
        fit_periodic(synthetic.wiping_strokes(seed=1), 100.0, n_kernels=1)
    assert e.value.code == 610


def test_v4_image_round_trip_and_discrete_v4_equals_v2(wipe_fit: PeriodicFit) -> None:
    sk = wipe_fit.skill
    b = sk.to_bytes()
    assert len(b) == 208 + 24 * sk.n_kernels + 4
    back = Skill.from_bytes(b)
    assert back.to_bytes() == b and back.periodic and back.amplitude_N == sk.amplitude_N
    assert Skill.from_json_dict(back.to_json_dict()).to_bytes() == b
    d2 = Skill.read(VECTORS / "press_n10_ridge_release.skill")
    d4 = Skill.from_bytes(d2.to_bytes())
    d4.format_version = 4
    b4 = d4.to_bytes()
    back4 = Skill.from_bytes(b4)
    assert back4.kind == 0 and back4.format_version == 4
    back4.format_version = 2
    assert back4.to_bytes() == d2.to_bytes()


def test_derive_matches_the_stored_gains(wipe_fit: PeriodicFit) -> None:
    sk = wipe_fit.skill
    assert derive(sk.gains).alpha == sk.alpha
    assert sk.duration_s == pytest.approx(2.0 * math.pi * sk.tau_s, rel=1e-12)


def _manifest() -> list[tuple[str, float, float, float, float, str]]:
    out = []
    for ln in (VECTORS / "manifest_periodic.txt").read_text().split("\n"):
        if ln.strip():
            s, g, a, t, c, csv = ln.split()
            out.append((s, float(g), float(a), float(t), float(c), csv))
    return out


@pytest.mark.parametrize("skill,gs,amp,ts,cyc,csv", _manifest())
def test_golden_periodic_rollouts(skill: str, gs: float, amp: float, ts: float, cyc: float, csv: str) -> None:
    sk = Skill.read(VECTORS / skill)
    t, f = periodic.rollout(sk, cycles=cyc, goal_scale=gs, amplitude_scale=amp, time_scale=ts)
    ref = np.loadtxt(VECTORS / csv, delimiter=",", skiprows=1)
    np.testing.assert_array_equal(ref[:, 0], t)
    assert np.max(np.abs(ref[:, 1] - f)) <= 1e-12 * np.max(np.abs(f))


def test_periodic_vectors_regenerate() -> None:
    import sys

    sys.path.insert(0, str(VECTORS))
    import generate

    files, lines = generate.golden_periodic(generate.fitted_periodic_skills())
    assert lines == (VECTORS / "manifest_periodic.txt").read_text().split("\n")[:-1]
    for name, data in files.items():
        if name.endswith(".csv"):
            new = np.loadtxt(data.decode().split("\n")[1:-1], delimiter=",")
            old = np.loadtxt(VECTORS / name, delimiter=",", skiprows=1)
            assert new.shape == old.shape
            assert np.max(np.abs(new[:, 1] - old[:, 1])) <= 1e-7 * np.max(np.abs(old[:, 1]))


def test_bad_v4_images_are_refused_with_their_codes() -> None:
    for ln in (VECTORS / "bad" / "manifest.txt").read_text().split("\n"):
        if ln.startswith(("p_", "version_6")):
            name, code = ln.split()
            with pytest.raises(SkillError) as e:
                Skill.from_bytes((VECTORS / "bad" / name).read_bytes())
            assert e.value.code == int(code), name


def test_cli_fit_periodic_and_rollout_cycles(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    from forceskill.cli import main

    d = synthetic.wiping_strokes(seed=5, noise_N=0.02)
    csv = tmp_path / "wipe.csv"
    np.savetxt(
        csv, np.column_stack((d.t_s, d.pos_m, d.force_N)), delimiter=",", header="t,x,f_contact", comments=""
    )
    out = tmp_path / "wipe.skill"
    assert main(["fit", str(csv), "-k", "100", "--periodic", "-o", str(out)]) == 0
    text = capsys.readouterr().out
    assert "11 steady strokes" in text and "period 1.2" in text and "against each stroke" in text
    sk = Skill.read(out)
    assert sk.periodic and sk.duration_s == pytest.approx(1.2)
    roll = tmp_path / "r.csv"
    args = ["rollout", str(out), "--cycles", "3", "--goal-scale", "1.5", "--amplitude-scale", "0.5"]
    assert main([*args, "--time-scale", "1.5", "-o", str(roll)]) == 0
    r = np.loadtxt(roll, delimiter=",", skiprows=1)
    assert r.shape[0] == 3 * 1800 + 1
    assert float(np.mean(r[:-1, 1])) == pytest.approx(1.5 * sk.goal_N, rel=1e-5)
    capsys.readouterr()
    assert (
        main(["rollout", str(VECTORS / "press_n10_ridge_release.skill"), "--cycles", "2", "-o", str(roll)])
        != 0
    )
    assert "683" in capsys.readouterr().err


def test_cli_fit_periodic_plot(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """fit --periodic --plot writes the strokes-against-the-learned-cycle figure with the skill;
    --end does not apply (683)."""
    from forceskill.cli import main

    d = synthetic.wiping_strokes(seed=5, noise_N=0.02)
    csv = tmp_path / "wipe.csv"
    np.savetxt(
        csv, np.column_stack((d.t_s, d.pos_m, d.force_N)), delimiter=",", header="t,x,f_contact", comments=""
    )
    png = tmp_path / "wipe.png"
    args = ["fit", str(csv), "-k", "100", "--periodic", "-o", str(tmp_path / "wipe.skill")]
    assert main([*args, "--plot", str(png)]) == 0
    assert f"plot {png}" in capsys.readouterr().out
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and png.stat().st_size > 20000
    assert main([*args, "--end", "release"]) != 0
    assert "683" in capsys.readouterr().err

"""`forceskill fit` on realistic recordings (tests/helpers/recordings.py): each is learned within its
tolerance, or refused with one line naming the cause and its code (the CLI run as a subprocess,
never a traceback, nothing written). Formats: CSV dialects, CAN logs, ROS 2 bags, reader plugins."""

from __future__ import annotations

import re
import subprocess
import sys
from collections.abc import Callable
from pathlib import Path

import numpy as np
import pytest

from forceskill import cli, readers
from forceskill.errors import (
    ERR_DEMO_COLUMN,
    ERR_DEMO_DURATION,
    ERR_DEMO_FILE,
    ERR_DEMO_FORMAT,
    ERR_DEMO_GAP,
    ERR_DEMO_TARE,
    ERR_DEMO_TOPIC,
    ERR_FIT_GOAL,
    ERR_FIT_INACCURATE,
    ERR_FIT_TOLERANCE,
    ERR_LOG_UNREADABLE,
    ERR_READ_ARGS,
    FsError,
)
from forceskill.model.demo import load_demo
from forceskill.model.skill import MAX_KERNELS, Skill
from forceskill.model.tolerance import sample_error
from forceskill.readers import ReadOptions
from helpers import recordings as R

K = str(R.OBJECT_K_NPM)
SURF = str(R.SURFACE_M)
#: max error of the default fit (N = 50) on the clean press at any rate, % of max force
PRESS_TOL_PCT = 3.0


def run(argv: list[str], capsys: pytest.CaptureFixture[str]) -> tuple[int, str, str]:
    try:
        rc = cli.main(argv)
    except SystemExit as e:
        rc = int(e.code or 0)
    out, err = capsys.readouterr()
    return rc, out, err


def printed_error(out: str) -> float:
    return float(re.search(r"approximation error: max ([0-9.]+) %", out).group(1))  # type: ignore[union-attr]


def fit_ok(path: Path, capsys: pytest.CaptureFixture[str], *args: str) -> tuple[str, Path]:
    skill = path.with_suffix(".skill")
    rc, out, err = run(["fit", str(path), "-k", K, "--surface-m", SURF, "-o", str(skill), *args], capsys)
    assert rc == 0, err
    assert skill.is_file()
    return out, skill


def fit_refused(path: Path, *args: str) -> str:
    """Run the CLI as a subprocess; it must refuse with one line and write nothing."""
    skill = path.with_name("refused.skill")
    r = subprocess.run(
        [
            sys.executable,
            "-m",
            "forceskill",
            "fit",
            str(path),
            "-k",
            K,
            "--surface-m",
            SURF,
            "-o",
            str(skill),
            *args,
        ],
        capture_output=True,
        text=True,
        timeout=300,
        check=False,
    )
    assert r.returncode == 2, (r.stdout, r.stderr)
    assert r.stderr.count("\n") == 1 and r.stderr.startswith("forceskill: error: "), r.stderr
    assert "Traceback" not in r.stderr
    assert not skill.exists() and not Path(f"{skill}.json").exists()
    return r.stderr


# ---- learned within tolerance ------------------------------------------------------------------

SUCCESS: list[tuple[str, Callable[[], R.Rec], tuple[str, ...]]] = [
    ("20Hz", lambda: R.press(rate_hz=20), ()),
    ("100Hz", lambda: R.press(rate_hz=100), ()),
    ("500Hz", lambda: R.press(rate_hz=500), ()),
    ("2kHz", lambda: R.press(rate_hz=2000), ()),
    ("jitter_32Hz_14_49ms", lambda: R.press(t=R.jittered_times(8.0, 14.0, 49.0)), ()),
    ("dropouts", lambda: R.with_dropouts(R.press(rate_hz=100), 12), ()),
    ("noise", lambda: R.with_noise(R.press(rate_hz=500), 0.05), ()),
    ("negative_sign_flipped", lambda: R.with_sign(R.press()), ("--force-sign", "-1")),
    ("bias_tare_auto", lambda: R.with_bias(R.with_noise(R.press(), 0.03), -0.8), ("--tare", "auto")),
    ("bias_tare_0.4s", lambda: R.with_bias(R.press(), -0.8), ("--tare", "0.4")),
    ("gap_250ms_allowed", lambda: R.with_gap(R.press(), 6.2, 0.25), ("--max-gap", "0.3")),
    (
        "kilonewton_scaled",
        lambda: R.Rec(R.press().t, R.press().f / 1000.0, R.press().x),
        ("--force-scale", "1000"),
    ),
]


@pytest.mark.parametrize("name,make,args", SUCCESS, ids=[s[0] for s in SUCCESS])
def test_learned_within_tolerance(
    name: str,
    make: Callable[[], R.Rec],
    args: tuple[str, ...],
    tmp_path: Path,
    capsys: pytest.CaptureFixture[str],
) -> None:
    rec = make()
    out, _ = fit_ok(R.write_csv(tmp_path / f"{name}.csv", rec), capsys, *args)
    assert printed_error(out) <= PRESS_TOL_PCT, out
    if "--tare" in args:
        bias = float(re.search(r"removed a bias of (\S+) N", out).group(1))  # type: ignore[union-attr]
        assert abs(bias + 0.8) < 0.02


def test_printed_error_is_what_the_user_computes_from_the_rollout(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """Jittery 32 Hz recording: the printed max error equals the one computed from `forceskill
    rollout` interpolated at the recording's own sample times (within 0.5 percentage points)."""
    rec = R.with_noise(R.press(t=R.jittered_times(8.0, 14.0, 49.0, seed=3)), 0.05)
    out, skill = fit_ok(R.write_csv(tmp_path / "jitter.csv", rec), capsys)
    roll = tmp_path / "roll.csv"
    assert run(["rollout", str(skill), "-o", str(roll)], capsys)[0] == 0
    data = np.loadtxt(roll, delimiter=",", skiprows=1)
    f_user = np.interp(rec.t - rec.t[0], data[:, 0], data[:, 1])
    user_pct = 100.0 * np.max(np.abs(rec.f - f_user)) / np.max(np.abs(rec.f))
    assert abs(printed_error(out) - user_pct) <= 0.5, (printed_error(out), user_pct)


def test_max_error_picks_the_smallest_kernel_count(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """73 s, 13 strokes: --kernels 50 is refused (above 10 %), the default N (following the
    length) says the N within 10 % it took; --max-error 5 prints the N it chose, that N reaches 5 %
    at the recorded samples and N - 1 does not (checked with the library's fit)."""
    from forceskill.model.fit import fit

    rec = R.strokes()
    p = R.write_csv(tmp_path / "strokes.csv", rec)
    err = fit_refused(p, "--kernels", "50")
    assert f"[{ERR_FIT_INACCURATE}]" in err and "above 10 %" in err and f"N up to {MAX_KERNELS}" in err
    out, _ = fit_ok(p, capsys)
    assert "the smallest within 10 % (the default N = 50 gives" in out
    out, skill = fit_ok(p, capsys, "--max-error", "5")
    n = int(re.search(r"kernels: N = (\d+)", out).group(1))  # type: ignore[union-attr]
    assert Skill.read(skill).n_kernels == n and 2 < n <= MAX_KERNELS
    demo = load_demo(p)
    for n_k, reaches in ((n, True), (n - 1, False)):
        r = fit(demo, R.OBJECT_K_NPM, n_kernels=n_k, surface_m=R.SURFACE_M)
        assert (sample_error(demo, r.t_s, r.f_hat_N).max_pct <= 5.0) == reaches, n_k
    assert printed_error(out) <= 5.0


# ---- refused with the cause --------------------------------------------------------------------

REFUSED: list[tuple[str, Callable[[], R.Rec], tuple[str, ...], int, list[str]]] = [
    ("negative_push", lambda: R.with_sign(R.press()), (), ERR_FIT_GOAL, ["no net push", "--force-sign -1"]),
    ("gap_300ms", lambda: R.with_gap(R.press(), 3.0, 0.3), (), ERR_DEMO_GAP, ["gap of 300 ms at t = 3 s"]),
    (
        "step_within_a_sample",
        # 16 N within one 50 ms sample: 13.8 % at N = 50 (an 8 N step is learned to 9.5 %, within
        # the default 10 %, since the kernels gather where the force bends)
        lambda: R.with_step(R.press(rate_hz=20), 4.0, 16.0),
        (),
        ERR_FIT_INACCURATE,
        ["force step of +", "at t = 3.95 s", "faster than the sample rate"],
    ),
    (
        "step_no_N_reaches",
        lambda: R.with_step(R.press(rate_hz=20), 4.0, 8.0),
        ("--max-error", "0.2"),
        ERR_FIT_TOLERANCE,
        [
            f"no kernel count up to {MAX_KERNELS} reaches max error 0.2 %",
            "best ",
            "at N = ",
            "force step",
            "split the demonstration into a sequence",
        ],
    ),
    (
        "noise_spikes",
        lambda: R.with_spikes(R.with_noise(R.press(), 0.05), [2.0, 5.0], 30.0),
        (),
        ERR_FIT_INACCURATE,
        ["single-sample spike", "t = 2 s"],
    ),
    (
        "stuck_sensor",
        lambda: R.with_stuck(R.with_bias(R.with_noise(R.press(), 0.05), 2.0), 0.0, 1.5),
        (),
        ERR_FIT_INACCURATE,
        ["stuck sensor", "from t = 0 s"],
    ),
    ("tare_window_empty", lambda: R.press(rate_hz=20), ("--tare", "0.01"), ERR_DEMO_TARE, ["hold 1 sample"]),
    (
        "no_time_column",
        R.press,
        ("--time-column", "time"),
        ERR_DEMO_COLUMN,
        ["'time' not in", "--rate HZ"],
    ),
    ("bad_scale", R.press, ("--force-scale", "0"), ERR_READ_ARGS, ["force scale"]),
    ("bad_max_error", R.press, ("--max-error", "-1"), 610, ["--max-error"]),
]


@pytest.mark.parametrize("name,make,args,code,texts", REFUSED, ids=[r[0] for r in REFUSED])
def test_refused_with_the_cause(
    name: str, make: Callable[[], R.Rec], args: tuple[str, ...], code: int, texts: list[str], tmp_path: Path
) -> None:
    err = fit_refused(R.write_csv(tmp_path / f"{name}.csv", make()), *args)
    assert err.rstrip().endswith(f"[{code}]"), err
    for text in texts:
        assert text in err, (text, err)


def test_tare_auto_refuses_a_recording_that_starts_in_contact(tmp_path: Path) -> None:
    t = np.arange(0, 4.0, 0.01)
    f = 5.0 + 3.0 * np.sin(t)
    err = fit_refused(
        R.write_csv(tmp_path / "contact.csv", R.Rec(t, f, R.SURFACE_M + f / R.OBJECT_K_NPM)), "--tare", "auto"
    )
    assert "starts in contact" in err and f"[{ERR_DEMO_TARE}]" in err


def test_duration_limit_is_checked_before_the_body_is_parsed(tmp_path: Path) -> None:
    """A 4,000 s file is refused from its first and last rows: a broken row in between is never read."""
    t = np.arange(0.0, 4000.0, 0.5)
    rec = R.Rec(t, np.full_like(t, 2.0), np.full_like(t, 0.003))
    p = R.write_csv(tmp_path / "long.csv", rec)
    lines = p.read_text().splitlines()
    lines[100] = "1,not a number,3"
    p.write_text("\n".join(lines) + "\n")
    err = fit_refused(p)
    assert f"[{ERR_DEMO_DURATION}]" in err and "lasts 3999.5 s" in err and "3600 s" in err
    err = fit_refused(R.write_csv(tmp_path / "rate.csv", rec, with_time=False), "--rate", "2")
    assert f"[{ERR_DEMO_DURATION}]" in err


# ---- CSV dialects ------------------------------------------------------------------------------

DIALECTS: list[tuple[str, dict[str, object], ReadOptions | None]] = [
    ("semicolon_decimal_comma", {"delimiter": ";", "decimal_comma": True}, None),
    ("tab", {"delimiter": "\t"}, None),
    ("spaces", {"delimiter": "   "}, None),
    (
        "bom_comments_crlf",
        {"bom": True, "comments": ["sensor: ATI mini45", "rate 100 Hz"], "line_end": "\r\n"},
        None,
    ),
    ("units_in_header", {"names": ("t [s]", "x (m)", "f_contact [N]")}, None),
    ("time_in_ms_from_header", {"names": ("t [ms]", "x", "f_contact"), "time_scale": 1e3}, None),
    (
        "time_column_and_unit",
        {"names": ("time", "x", "f_contact"), "time_scale": 1e6},
        ReadOptions(time_column="time", time_unit="us"),
    ),
    ("no_time_column_rate", {"with_time": False}, ReadOptions(rate_hz=100.0)),
]


@pytest.mark.parametrize("name,kw,opts", DIALECTS, ids=[d[0] for d in DIALECTS])
def test_csv_dialects_read_the_same_recording(
    name: str, kw: dict[str, object], opts: ReadOptions | None, tmp_path: Path
) -> None:
    rec = R.with_noise(R.press(rate_hz=100), 0.05)
    plain = load_demo(R.write_csv(tmp_path / "plain.csv", rec))
    d = load_demo(R.write_csv(tmp_path / f"{name}.csv", rec, **kw), read=opts)  # type: ignore[arg-type]
    np.testing.assert_allclose(d.t_s, plain.t_s, rtol=0, atol=1e-9)
    np.testing.assert_allclose(d.force_N, plain.force_N, rtol=1e-8, atol=0)
    np.testing.assert_allclose(d.pos_m, plain.pos_m, rtol=1e-8, atol=0)


def test_without_position_it_is_force_over_stiffness_and_says_so(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    rec = R.press()
    out, _ = fit_ok(
        R.write_csv(tmp_path / "nopos.csv", rec, names=("t", "", "Fz (N)"), with_position=False),
        capsys,
        "--force-column",
        "Fz",
    )
    assert "position taken as surface + f/k" in out and printed_error(out) <= PRESS_TOL_PCT
    d = load_demo(tmp_path / "nopos.csv", force_column="Fz", stiffness_Npm=500.0, surface_m=0.01)
    np.testing.assert_allclose(d.pos_m, 0.01 + rec.f / 500.0, rtol=1e-8)
    with pytest.raises(FsError) as e:
        load_demo(tmp_path / "nopos.csv", force_column="Fz", position_column="x")
    assert e.value.code == ERR_DEMO_COLUMN and "available: t, Fz (N)" in e.value.message


def test_bad_rows_are_named_in_large_files(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """Files above one block are read block by block (rows preallocated): the same numbers, and a
    bad cell is named with its line number."""
    from forceskill.readers import csv as csv_reader

    rec = R.with_noise(R.press(rate_hz=1000), 0.05)
    p = R.write_csv(tmp_path / "big.csv", rec, comments=["a comment"])
    whole = load_demo(p)
    monkeypatch.setattr(csv_reader, "BLOCK_BYTES", 4096)
    blocks = load_demo(p, read=ReadOptions(progress=False))
    assert np.array_equal(whole.t_s, blocks.t_s) and np.array_equal(whole.force_N, blocks.force_N)
    lines = p.read_text().splitlines()
    lines[5000] = lines[5000].replace(",", ",x", 1)
    p.write_text("\n".join(lines) + "\n")
    with pytest.raises(FsError) as e:
        load_demo(p, read=ReadOptions(progress=False))
    assert e.value.code == ERR_DEMO_FORMAT and "line 5001, column 'x'" in e.value.message
    lines[5000] = "1,2"
    p.write_text("\n".join(lines) + "\n")
    with pytest.raises(FsError) as e:
        load_demo(p, read=ReadOptions(progress=False))
    assert "line 5001 has 2 fields, header has 3" in e.value.message


@pytest.mark.parametrize("dialect", ["comma_crlf_comments", "spaces", "semicolon_decimal_comma"])
def test_large_files_read_at_once_give_what_the_blocks_give(
    dialect: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """A file above one block is parsed at once by numpy's parser (only the kept columns), and
    one it refuses (decimal commas) block by block: either way the numbers of the small-file path."""
    from forceskill.readers import csv as csv_reader

    rec = R.with_noise(R.press(rate_hz=1000), 0.05)
    kw: dict[str, object] = {
        "comma_crlf_comments": {"comments": ["a comment"], "line_end": "\r\n", "bom": True},
        "spaces": {"delimiter": " "},
        "semicolon_decimal_comma": {"delimiter": ";", "decimal_comma": True},
    }[dialect]
    p = R.write_csv(tmp_path / "big.csv", rec, **kw)  # type: ignore[arg-type]
    small = load_demo(p)
    monkeypatch.setattr(csv_reader, "BLOCK_BYTES", 4096)
    calls: list[bool] = []
    orig = csv_reader._parse_whole
    monkeypatch.setattr(csv_reader, "_parse_whole", lambda *a: calls.append(True) or orig(*a))
    large = load_demo(p, read=ReadOptions(progress=False))
    assert calls
    for a, b in ((small.t_s, large.t_s), (small.force_N, large.force_N), (small.pos_m, large.pos_m)):
        assert np.array_equal(a, b)


# ---- CAN logs ----------------------------------------------------------------------------------


def _can_rec() -> R.Rec:
    return R.with_noise(R.press(duration_s=6.0, rate_hz=1000, peak_N=8.0), 0.02)


@pytest.mark.parametrize("suffix", [".asc", ".log.gz", ".blf"])
def test_can_log_lost_frames_are_interpolated(
    suffix: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """Lost telemetry frames (1 and 40 ticks) leave the demonstration whole (not its longest
    unbroken stretch); the idle telemetry around TEACH is not part of it."""
    rec = _can_rec()
    drop = [1500, *range(3000, 3040)]
    p = R.write_can_log(tmp_path / f"demo{suffix}", rec, drop_ticks=drop)
    d = load_demo(p)
    assert d.t_s.size == rec.t.size - len(drop)
    assert d.t_s[-1] == pytest.approx(6.0)
    keep = np.setdiff1d(np.arange(rec.t.size), drop)
    np.testing.assert_allclose(d.force_N, np.round(rec.f[keep], 2), atol=1e-9)
    out, _ = fit_ok(p, capsys)
    assert "T = 6.000 s" in out and printed_error(out) <= PRESS_TOL_PCT


def test_can_log_positions_that_pass_their_force_frames_are_paired_by_tick(tmp_path: Path) -> None:
    """On a busy bus the device's position frames of several ticks leave before the force frames
    of the first: every sample still gets its own tick's force, and a lost frame costs one tick."""
    rec = _can_rec()
    drop = [1203, 2500]
    d = load_demo(R.write_can_log(tmp_path / "busy.asc", rec, busy_every=50, drop_ticks=drop))
    keep = np.setdiff1d(np.arange(rec.t.size), drop)
    assert d.t_s.size == keep.size
    np.testing.assert_allclose(d.force_N, np.round(rec.f[keep], 2), atol=1e-9)
    np.testing.assert_allclose(d.pos_m, np.round(rec.x[keep], 6), atol=1e-9)


@pytest.mark.parametrize("suffix", [".asc", ".blf", ".csv", ".db", ".log", ".mf4", ".trc"])
def test_every_python_can_log_format_is_read(
    suffix: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """Each format python-can reads, written by python-can's own writer (can.Logger), gives the
    demonstration exactly (the DBC's 0.01 N force resolution), also through `fit`."""
    if suffix == ".mf4":
        pytest.importorskip("asammdf")
    rec = _can_rec()
    p = R.write_can_log(tmp_path / f"demo{suffix}", rec)
    d = load_demo(p)
    assert d.t_s.size == rec.t.size and d.t_s[-1] == pytest.approx(6.0)
    np.testing.assert_allclose(d.force_N, np.round(rec.f, 2), atol=1e-9)
    out, _ = fit_ok(p, capsys)
    assert "T = 6.000 s" in out and printed_error(out) <= PRESS_TOL_PCT


def test_a_log_format_python_can_cannot_read_is_refused_by_name(tmp_path: Path) -> None:
    """python-can writes .txt (can.Printer) but cannot read it: refused naming the format (691);
    a .txt text table is still read as one."""
    p = R.write_can_log(tmp_path / "demo.txt", _can_rec())
    assert p.read_text().startswith("Timestamp:")
    err = fit_refused(p)
    assert f"[{ERR_LOG_UNREADABLE}]" in err and "demo.txt is a python-can text log (can.Printer, .txt)" in err
    assert "cannot read" in err and ".blf" in err
    table = tmp_path / "table.txt"
    rec = R.press()
    table.write_text(
        "t,x,f_contact\n"
        + "".join(f"{t:.6f},{x:.6g},{f:.6g}\n" for t, x, f in zip(rec.t, rec.x, rec.f, strict=False))
    )
    assert load_demo(table).t_s.size == rec.t.size


def test_can_log_gap_and_sessions(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    rec = _can_rec()
    err = fit_refused(R.write_can_log(tmp_path / "gap.asc", rec, drop_ticks=range(2000, 2150)))
    assert f"[{ERR_DEMO_GAP}]" in err and "gap of 151 ms at t = 1.999 s" in err
    out, _ = fit_ok(R.write_can_log(tmp_path / "two.asc", rec, sessions=2), capsys)
    assert "holds 2 demonstrations" in out and "T = 6.00" in out


@pytest.mark.parametrize("period", [10, 100])
def test_can_log_at_a_telemetry_period_is_told_from_idle_by_the_status_frames(
    period: int, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """`record --telemetry-period P`: TEACH's samples every P ticks (at 100 as often as the idle
    telemetry around them) are the demonstration by the device's status frames (state TEACH and
    their tick): none of the idle samples, all of TEACH's, and `fit` learns it (12 s at 100 ms:
    the 100 samples a demonstration needs)."""
    rec = R.with_noise(R.press(duration_s=12.0, rate_hz=1000, peak_N=8.0), 0.02)
    p = R.write_can_log(tmp_path / f"p{period}.blf", rec, period=period)
    d = load_demo(p)
    assert d.t_s[0] == 0.0 and d.t_s[-1] == pytest.approx(12.0)
    every = np.arange(0, rec.t.size, period)
    np.testing.assert_allclose(d.t_s, rec.t[every], atol=1e-12)
    np.testing.assert_allclose(d.force_N, np.round(rec.f[every], 2), atol=1e-9)
    out, _ = fit_ok(p, capsys)
    assert "T = 12.000 s" in out and f"(recorded: {every.size})" in out
    assert printed_error(out) <= PRESS_TOL_PCT


# ---- ROS 2 bags --------------------------------------------------------------------------------


def test_ros2_bag_wrench_and_pose(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    pytest.importorskip("mcap_ros2")
    rec = R.with_noise(R.press(rate_hz=100), 0.05)
    p = R.write_bag(tmp_path / "demo.mcap", rec)
    d = load_demo(p, read=ReadOptions(topic="/wrench", axis="z", pose_topic="/pose"))
    np.testing.assert_allclose(d.t_s, rec.t, atol=1e-9)
    np.testing.assert_array_equal(d.force_N, rec.f)
    np.testing.assert_allclose(d.pos_m, rec.x, atol=2e-5)  # pose at half rate, interpolated
    out, _ = fit_ok(p, capsys, "--topic", "/wrench", "--axis", "z", "--pose-topic", "/pose")
    assert "force /wrench wrench.force.z" in out and printed_error(out) <= PRESS_TOL_PCT
    # without --topic: the bag's only WrenchStamped topic; --axis x reads another axis
    assert np.array_equal(load_demo(p, stiffness_Npm=1e3).force_N, rec.f)
    assert np.all(load_demo(p, read=ReadOptions(axis="x"), stiffness_Npm=1e3).force_N == 1.5)


def test_ros2_bag_pose_axis_is_the_y_path(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """The pose topic's y axis (column pose_y) is the path a skill learns with --y-column."""
    pytest.importorskip("mcap_ros2")
    rec = R.press(rate_hz=100)
    y = 0.03 * np.sin(np.pi * (rec.t - rec.t[0]) / (rec.t[-1] - rec.t[0])) ** 2
    p = R.write_bag(tmp_path / "wipe.mcap", rec, y_path=y)
    d = load_demo(p, read=ReadOptions(axis="z", pose_topic="/pose"), y_column="pose_y")
    assert d.y_m is not None
    np.testing.assert_allclose(d.y_m, y, atol=2e-5)  # pose at half rate, interpolated
    out, _ = fit_ok(p, capsys, "--axis", "z", "--pose-topic", "/pose", "--y-column", "pose_y")
    assert "y path (pose_y): start 0 m" in out
    assert float(out.split("approximation error max ")[1].split(" mm")[0]) < 0.5


def test_ros2_bag_topic_errors(tmp_path: Path) -> None:
    pytest.importorskip("mcap_ros2")
    rec = R.press(rate_hz=50)
    p = R.write_bag(tmp_path / "two.mcap", rec, extra_wrench="/wrench_raw")
    err = fit_refused(p)
    assert (
        f"[{ERR_DEMO_TOPIC}]" in err
        and "2 geometry_msgs/msg/WrenchStamped topics" in err
        and "/wrench_raw" in err
    )
    err = fit_refused(p, "--topic", "/nope")
    assert "topic '/nope' not in two.mcap" in err
    err = fit_refused(p, "--topic", "/pose")
    assert "is geometry_msgs/msg/PoseStamped, not geometry_msgs/msg/WrenchStamped" in err


# ---- reader plugins ----------------------------------------------------------------------------


def test_readers_are_entry_points_and_plugins(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    from importlib.metadata import entry_points

    names = {ep.name: ep.value for ep in entry_points(group="forceskill.readers")}
    assert names["csv"] == "forceskill.readers.csv:read" and names["mcap"] == "forceskill.readers.rosbag:read"
    for name, target in names.items():
        assert readers._load(name, target) is not None
    rec = R.press()

    def read_npz(path: Path, opts: ReadOptions) -> readers.Columns:
        z = np.load(path)
        return {"t": z["t"], "x": z["x"], "f_contact": z["f"]}

    p = tmp_path / "demo.npz"
    np.savez(p, t=rec.t, x=rec.x, f=rec.f)
    with pytest.raises(FsError) as e:
        load_demo(p)
    assert e.value.code == ERR_DEMO_FILE and ".csv" in e.value.message and ".mcap" in e.value.message
    monkeypatch.setitem(readers._registered, "npz", read_npz)
    assert np.array_equal(load_demo(p, stiffness_Npm=1e3).force_N, rec.f)


def test_every_reader_shows_a_progress_bar_only_when_reading_is_slow(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    """CSV (in blocks), CAN log and ROS 2 bag: a tqdm bar on stderr once reading has taken
    PROGRESS_DELAY_S (2 s; 0 here stands for a slow read), nothing for a quick read."""
    import forceskill.readers.csv as csv_reader

    monkeypatch.setattr(csv_reader, "BLOCK_BYTES", 1 << 14)
    rec = _can_rec()
    files = [
        (R.write_csv(tmp_path / "demo.csv", rec), None),
        (R.write_can_log(tmp_path / "demo.asc", rec), None),
    ]
    try:
        import mcap_ros2  # noqa: F401

        files.append(
            (R.write_bag(tmp_path / "demo.mcap", R.press(rate_hz=1000)), ReadOptions(topic="/wrench"))
        )
    except ImportError:
        pass
    for p, opts in files:
        load_demo(p, read=opts, stiffness_Npm=1e3)
        assert capsys.readouterr().err == "", p.name
    monkeypatch.setattr(readers, "PROGRESS_DELAY_S", 0.0)
    for p, opts in files:
        load_demo(p, read=opts, stiffness_Npm=1e3)
        assert f"reading {p.name}" in capsys.readouterr().err, p.name

"""The forceskill command: fit/rollout/show on a small CSV, and every bad input refused cleanly
(one line on stderr, exit status 2, no output file)."""

from __future__ import annotations

import json
import subprocess
import sys
from collections.abc import Callable
from pathlib import Path

import numpy as np
import pytest

from forceskill import cli
from forceskill.errors import DemoError
from forceskill.model import dmp, synthetic
from forceskill.model.demo import Demo, load_demo, write_csv
from forceskill.model.skill import Skill
from helpers.paths import VECTORS


def write_demo(path: Path, d: Demo, **extra: np.ndarray) -> Path:
    cols = {
        "t": d.t_s,
        "x": d.pos_m,
        "y": np.zeros_like(d.t_s),
        "f_contact": d.force_N,
        "f_operator": 1.2 * d.force_N,
    }
    cols.update(extra)
    write_csv(path, cols)
    return path


@pytest.fixture()
def demo_csv(tmp_path: Path) -> Path:
    return write_demo(tmp_path / "demo.csv", synthetic.pressing(seed=2, duration_s=3.0))


def run(argv: list[str], capsys: pytest.CaptureFixture[str]) -> tuple[int, str, str]:
    try:
        rc = cli.main(argv)
    except SystemExit as e:  # argparse
        rc = int(e.code or 0)
    out, err = capsys.readouterr()
    return rc, out, err


def test_fit_rollout_show(demo_csv: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    sk_path = tmp_path / "press.skill"
    png = tmp_path / "fit.png"
    rc, out, err = run(
        [
            "fit",
            str(demo_csv),
            "--stiffness",
            "100",
            "-o",
            str(sk_path),
            "--kernels",
            "30",
            "--surface-m",
            "0.001",
            "--end",
            "release",
            "--plot",
            str(png),
        ],
        capsys,
    )
    assert rc == 0, err
    assert "approximation error: max" in out and "RMS" in out and "tau =" in out and "g =" in out
    max_pct = float(out.split("approximation error: max ")[1].split(" %")[0])
    assert 0.0 < max_pct < 2.0
    sk = Skill.read(sk_path)
    assert sk.n_kernels == 30 and sk.end_policy == "release" and sk.surface_m == 0.001
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    out_csv = tmp_path / "roll.csv"
    rc, out, err = run(
        ["rollout", str(sk_path), "-o", str(out_csv), "--goal-scale", "1.5", "--time-scale", "1.3"], capsys
    )
    assert rc == 0, err
    assert out_csv.read_text().split("\n", 1)[0] == "t,f_hat"
    data = np.loadtxt(out_csv, delimiter=",", skiprows=1)
    _t, f = dmp.rollout(sk, 1.5, 1.3)
    np.testing.assert_array_equal(data[:, 1], f)
    rc, out, err = run(["show", str(sk_path)], capsys)
    assert rc == 0 and "kernels        30" in out and "release" in out
    rc, out, err = run(["show", str(sk_path), "--json"], capsys)
    assert rc == 0 and json.loads(out)["n_kernels"] == 30


def test_learn_operator_and_force_column(demo_csv: Path, tmp_path: Path) -> None:
    c = load_demo(demo_csv)
    o = load_demo(demo_csv, learn="operator")
    f = load_demo(demo_csv, force_column="f_operator")
    np.testing.assert_array_equal(o.force_N, 1.2 * c.force_N)
    np.testing.assert_array_equal(f.force_N, o.force_N)
    assert c.source.endswith("f_contact") and o.source.endswith("f_operator")


def test_console_script_and_module(demo_csv: Path, tmp_path: Path) -> None:
    exe = Path(sys.executable).parent / "forceskill"
    r = subprocess.run([str(exe), "--help"], capture_output=True, text=True)
    assert r.returncode == 0 and "fit" in r.stdout and "rollout" in r.stdout and "show" in r.stdout
    for cmd in ("fit", "rollout", "show"):
        r = subprocess.run(
            [sys.executable, "-m", "forceskill", cmd, "--help"], capture_output=True, text=True
        )
        assert r.returncode == 0 and f"forceskill {cmd}" in r.stdout
    r = subprocess.run(
        [str(exe), "fit", str(demo_csv), "-k", "0", "-o", str(tmp_path / "x.skill")],
        capture_output=True,
        text=True,
    )
    assert r.returncode == 2 and r.stdout == ""
    assert (
        r.stderr.count("\n") == 1
        and r.stderr.startswith("forceskill: error: ")
        and "Traceback" not in r.stderr
    )
    assert not (tmp_path / "x.skill").exists()


def test_command_modules_are_loaded_lazily_and_a_missing_one_does_not_break(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    monkeypatch.setattr(cli, "COMMAND_MODULES", ["forceskill.no_such_module", "tests_cli_plugin"])
    mod = type(sys)("tests_cli_plugin")

    def register(sub: object) -> None:
        p = sub.add_parser("hello")  # type: ignore[attr-defined]
        p.set_defaults(func=lambda args: print("hello from plugin") or 0)

    mod.register = register  # type: ignore[attr-defined]
    monkeypatch.setitem(sys.modules, "tests_cli_plugin", mod)
    rc, out, _ = run(["hello"], capsys)
    assert rc == 0 and out == "hello from plugin\n"
    _parser, missing = cli.build_parser()
    assert len(missing) == 1 and "no_such_module" in missing[0]


# ---- bad input --------------------------------------------------------------------------------


def _demo(n: int = 2000, dt: float = 0.001) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    t = np.arange(n) * dt
    f = 3.0 * np.sin(np.pi * t / t[-1]) ** 2 + 0.5 * t
    return t, 0.001 + f / 100.0, f


def csv_with(
    tmp: Path, mutate: Callable[[dict[str, np.ndarray]], None], n: int = 2000, dt: float = 0.001
) -> Path:
    t, x, f = _demo(n, dt)
    cols = {"t": t, "x": x, "f_contact": f, "f_operator": f}
    mutate(cols)
    p = tmp / "bad.csv"
    write_csv(p, cols)
    return p


def _set(name: str, i: int, val: float) -> Callable[[dict[str, np.ndarray]], None]:
    def m(c: dict[str, np.ndarray]) -> None:
        c[name] = c[name].copy()
        c[name][i] = val

    return m


def _gap(c: dict[str, np.ndarray]) -> None:
    c["t"] = c["t"].copy()
    c["t"][1000:] += 0.15


def _zero(c: dict[str, np.ndarray]) -> None:
    c["f_contact"] = np.zeros_like(c["f_contact"])


def _pull(c: dict[str, np.ndarray]) -> None:
    c["f_contact"] = -c["f_contact"]
    c["x"] = np.full_like(c["x"], -0.01)


BAD_DEMOS = [
    ("too_few_samples", lambda c: None, {"n": 99}, 603, "99 samples"),
    ("too_short_time", lambda c: None, {"n": 400}, 603, "0.399 s"),
    ("nan_force", _set("f_contact", 500, np.nan), {}, 604, "not finite"),
    ("inf_position", _set("x", 10, np.inf), {}, 604, "not finite"),
    ("time_backwards", _set("t", 700, 0.5), {}, 605, "not strictly increasing"),
    ("time_repeated", _set("t", 700, 0.699), {}, 605, "not strictly increasing"),
    ("gap", _gap, {}, 606, "gap of 151 ms at t = 0.999 s"),
    ("zero_force", _zero, {}, 607, "constant zero"),
    ("no_net_push", _pull, {}, 611, "no net push"),
]


@pytest.mark.parametrize("name,mutate,kw,code,text", BAD_DEMOS, ids=[b[0] for b in BAD_DEMOS])
def test_bad_demonstrations_exit_2_with_one_line(
    name: str,
    mutate: Callable[[dict[str, np.ndarray]], None],
    kw: dict[str, int],
    code: int,
    text: str,
    tmp_path: Path,
    capsys: pytest.CaptureFixture[str],
) -> None:
    p = csv_with(tmp_path, mutate, **kw)
    out_skill = tmp_path / "out.skill"
    rc, out, err = run(
        ["fit", str(p), "-k", "100", "-o", str(out_skill), "--plot", str(tmp_path / "p.png")], capsys
    )
    assert rc == 2
    assert err.count("\n") == 1 and err.startswith("forceskill: error: ") and f"[{code}]" in err, err
    assert text in err, err
    assert out == ""
    assert sorted(x.name for x in tmp_path.iterdir()) == ["bad.csv"]


def _file_cases(tmp: Path) -> list[tuple[list[str], str]]:
    good = csv_with(tmp, lambda c: None)
    (tmp / "noheader.csv").write_text("0,0.001,1\n0.001,0.001,1\n")
    (tmp / "text.csv").write_text("t,x,f_contact\n0,0.001,1\n0.001,abc,1\n")
    (tmp / "ragged.csv").write_text("t,x,f_contact\n0,0.001,1\n0.001,1\n")
    (tmp / "empty.csv").write_text("")
    (tmp / "demo.xyz").write_text("t,x\n")
    o = str(tmp / "out.skill")
    g = str(good)
    return [
        (["fit", str(tmp / "missing.csv"), "-k", "100", "-o", o], "not found"),
        (["fit", str(tmp / "demo.xyz"), "-k", "100", "-o", o], "no reader"),
        (["fit", str(tmp / "noheader.csv"), "-k", "100", "-o", o], "no header"),
        (["fit", str(tmp / "text.csv"), "-k", "100", "-o", o], "not a number: 'abc'"),
        (["fit", str(tmp / "ragged.csv"), "-k", "100", "-o", o], "line 3 has 2 fields"),
        (["fit", str(tmp / "empty.csv"), "-k", "100", "-o", o], "empty"),
        (
            ["fit", g, "-k", "100", "-o", o, "--force-column", "fz"],
            "column 'fz' not in bad.csv (available: t, x, f_contact, f_operator)",
        ),
        (["fit", g, "-k", "100", "-o", o, "--position-column", "px"], "column 'px'"),
        (["fit", g, "-k", "0", "-o", o], "stiffness must be > 0"),
        (["fit", g, "-k", "nan", "-o", o], "not finite"),
        (["fit", g, "-k", "100", "-o", o, "--kernels", "1"], "2..1024: 1"),
        (["fit", g, "-k", "100", "-o", o, "--kernels", "1100"], "2..1024: 1100"),
        (["fit", g, "-k", "100", "-o", o, "--method", "gmr"], "invalid choice: 'gmr'"),
        (["fit", g, "-k", "100", "-o", str(tmp / "nodir" / "x.skill")], "does not exist"),
        (["fit", g, "-o", o], "required: --stiffness"),
        (["fit", g, "-k", "abc", "-o", o], "not a number: 'abc'"),
        (["rollout", str(VECTORS / "bad" / "crc.skill"), "-o", str(tmp / "r.csv")], "CRC-32 mismatch"),
        (
            [
                "rollout",
                str(VECTORS / "press_n10_ridge_release.skill"),
                "-o",
                str(tmp / "r.csv"),
                "--time-scale",
                "0",
            ],
            "time scale",
        ),
        (["rollout", str(tmp / "none.skill"), "-o", str(tmp / "r.csv")], "cannot read skill"),
        (["show", str(VECTORS / "bad" / "version_1.skill")], "format version 1 is not supported"),
        (["nosuchcommand"], "invalid choice"),
    ]


def test_bad_files_and_options_exit_2_with_one_line(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    cases = _file_cases(tmp_path)
    before = sorted(x.name for x in tmp_path.iterdir())
    for argv, text in cases:
        rc, _out, err = run(argv, capsys)
        assert rc == 2, (argv, err)
        assert err.count("\n") == 1 and err.startswith("forceskill: error: "), (argv, err)
        assert text in err, (argv, err)
        assert sorted(x.name for x in tmp_path.iterdir()) == before, argv


def test_resampling_a_500_hz_log(tmp_path: Path) -> None:
    d = synthetic.engraving(seed=3, duration_s=4.0)
    half = Demo(d.t_s[::2], d.pos_m[::2], d.force_N[::2], "500 Hz")
    p = write_demo(tmp_path / "d500.csv", half)
    loaded = load_demo(p)
    from forceskill.model.demo import resample

    r = resample(loaded, 0.001)
    assert r.t_s.size == d.t_s.size
    np.testing.assert_allclose(r.t_s, d.t_s, atol=1e-12)
    # linear interpolation of a smooth profile: midpoints within the second-difference bound
    assert np.max(np.abs(r.force_N - d.force_N)) < 1e-3 * np.max(d.force_N)
    assert np.array_equal(r.force_N[::2], half.force_N)


def test_demo_error_is_one_line_with_code() -> None:
    e = DemoError(603, "demonstration too short:\n  3 samples")
    assert str(e) == "demonstration too short: 3 samples" and e.code == 603

"""The paper's experiments reproduced end to end on the HIL simulator.

`forceskill report` runs for two operator seeds: demonstrate (TEACH), fit (ridge N=50 and LWR),
execute (ideal plant), reuse with and without goal scaling. Bounds on both sides where meaningful:
an error that is suspiciously small (e.g. 0 because nothing ran) fails too.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from forceskill.commands import report as report_mod
from forceskill.commands.report import TASKS, read_log, run_report
from forceskill.model.skill import Skill

SEEDS = (1, 2)
LEARN = [t.name for t in TASKS]
STIFF = [f"stiff_{kind}_{k}" for kind, k in report_mod.STIFF]


@pytest.fixture(scope="module", params=SEEDS, ids=[f"seed{s}" for s in SEEDS])
def report(request, tmp_path_factory, hil_sim: Path, scenarios: Path) -> dict:
    out = tmp_path_factory.mktemp(f"report_seed{request.param}")
    summary = run_report(
        out, hil_sim, scenarios, seed=request.param, plots=(request.param == 1), progress=False
    )
    summary["_dir"] = out
    return summary


def _exp(report: dict, name: str) -> dict:
    return next(e for e in report["experiments"] if e["name"] == name)


def test_report_files(report: dict) -> None:
    out: Path = report["_dir"]
    data = json.loads((out / "summary.json").read_text())
    names = [e["name"] for e in data["experiments"]]
    assert names == [*LEARN, "reuse_200_1x", "reuse_300_1_5x", "reuse_300_1x_unscaled", *STIFF]
    for e in data["experiments"]:
        for key in (
            "name",
            "approx_max_pct",
            "approx_max_pct_lwr",
            "tracking_rms_pct",
            "tracking_max_pct",
            "max_force_N",
        ):
            assert key in e
    md = (out / "report.md").read_text()
    for n in names:
        assert f"| {n} |" in md
    if report["seed"] == 1:
        for f in ["fig_reuse.png"] + [f"fig_{n}.png" for n in LEARN]:
            png = out / f
            assert png.stat().st_size > 20000 and png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


@pytest.mark.parametrize("name", LEARN)
def test_default_fit_within_2_5_pct(report: dict, name: str) -> None:
    e = _exp(report, name)
    # lower bound: the recorded force carries 0.02 N sensor noise, so a few max-noise samples
    # alone are > 0.3 % of a <= 20 N profile: a smaller error means the comparison is broken
    assert 0.3 <= e["approx_max_pct"] <= 2.5
    assert 0.05 <= e["approx_rms_pct"] <= 1.0


@pytest.mark.parametrize("name", LEARN)
def test_lwr_within_paper_bounds(report: dict, name: str) -> None:
    e = _exp(report, name)
    bound = 4.0 if name.startswith("pressing") else 6.0
    # the paper's figure: LWR with N = 50 kernels (measured 1.6-4.2 %, seeds 1-8, docs/math.md 3)
    assert 0.3 <= e["approx_max_pct_lwr"] <= bound, f"{name}: LWR N=50 {e['approx_max_pct_lwr']:.2f} %"
    assert e["lwr_kernels_needed"] is not None and e["lwr_kernels_needed"] <= 100, (
        f"{name}: LWR needs more than 100 kernels (N=50: {e['approx_max_pct_lwr']:.2f} %)"
    )
    assert 0.3 <= e["approx_max_pct_lwr_needed"] <= bound
    # LWR at N = 50 is worse than the default fit at N = 50 (ridge is 2-5x more accurate, docs/math.md)
    assert e["approx_max_pct_lwr"] >= e["approx_max_pct"]


@pytest.mark.parametrize("name", [*LEARN, "reuse_200_1x", "reuse_300_1_5x"])
def test_execution_tracking(report: dict, name: str) -> None:
    e = _exp(report, name)
    assert 0.05 <= e["tracking_rms_pct"] <= 3.0
    assert e["tracking_max_pct"] <= 10.0


@pytest.mark.parametrize("name", STIFF)
def test_execution_on_stiff_objects(report: dict, name: str) -> None:
    """1e4 and 1e5 N/m, surface known to 0.5 mm: tracking RMS <= 2 % of max force, no fault, no
    limit violation (measured 0.3-0.8 % on the ideal plant, docs/hil.md)."""
    e = _exp(report, name)
    assert e["approx_max_pct"] <= 1.5
    assert 0.05 <= e["tracking_rms_pct"] <= 2.0
    assert e["tracking_max_pct"] <= 10.0
    assert e["limit_violations"] == 0 and e["nonfinite_ticks"] == 0 and e["saturated_ticks"] == 0
    log = read_log(Path(e["exec_log"]))
    assert np.all(np.isfinite(log["f_contact"])) and np.max(log["f_contact"]) < 0.5 * e["force_limit_N"]
    # on a stiff object the law's output is the small inertial part: the object carries the force
    assert np.all(np.abs(log["f_cmd"]) <= e["force_limit_N"]) and 1.0 < e["max_force_N"] < 50.0


@pytest.mark.parametrize("name", [*LEARN, "reuse_200_1x", "reuse_300_1_5x", "reuse_300_1x_unscaled"])
def test_force_never_exceeds_the_limit(report: dict, name: str) -> None:
    e = _exp(report, name)
    assert e["force_limit_N"] == 50.0
    assert e["limit_violations"] == 0
    assert 0.5 < e["max_cmd_abs_N"] <= 50.0
    assert 1.0 < e["max_force_N"] < 50.0
    log = read_log(Path(e["exec_log"]))
    assert np.all(np.abs(log["f_cmd"]) <= 50.0)


def test_pressing_demonstrations_reach_the_inner_layer(report: dict) -> None:
    for name in ("pressing_task1", "pressing_task2"):
        e = _exp(report, name)
        assert e["layer_reached_s"] is not None and 0.3 < e["layer_reached_s"] < 3.0
        assert 0.020 < e["deformation_max_m"] + 0.001 < 0.05  # beyond x = 0.020 m, not through


def test_reuse_deformation(report: dict) -> None:
    scaled = _exp(report, "reuse_300_1_5x")
    d, du = scaled["deformation_diff_pct"], scaled["deformation_diff_unscaled_pct"]
    assert 1.0 <= d <= 12.0
    assert du >= 2.0 * d
    # without scaling the stiffer object deforms ~1/3 less (200/300): the comparison is real
    assert 25.0 <= du <= 45.0
    # scaling multiplies the commanded reference force above the starting forces by 1.5: what is
    # not scaled is each skill's starting force f0 (the demonstration's first sample) and the
    # start from the measured contact force, faded out
    a = read_log(Path(_exp(report, "reuse_200_1x")["exec_log"]))
    b = read_log(Path(scaled["exec_log"]))
    out: Path = report["_dir"]
    f0 = [Skill.read(p).force0_N for p in sorted((out / "skills").glob("engraving_task*.skill"))]
    offset = max(abs(f) for f in f0) + max(abs(a["f_hat"][0]), abs(b["f_hat"][0]))
    assert offset < 0.01 * np.max(a["f_hat"])
    assert (
        np.max(np.abs(b["f_hat"] - 1.5 * a["f_hat"])) <= 0.5 * 2.0 * offset + 1e-5 * np.max(b["f_hat"]) + 2e-6
    )

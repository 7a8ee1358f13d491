"""Force and motion in one skill on the HIL simulator, in lockstep: the wiping demonstration
(hil_sim/scenarios/wiping_demo.toml: force levels and a path along y on a surface with Coulomb
friction 0.3 x the contact force) is fitted with its path and executed at 1x and 1.5x goal and at
1.5x path scale; the measured y tracks the learned path within 1 mm RMS, the force as the paper
tasks (RMS <= 3 % of max)."""

from __future__ import annotations

import json
import subprocess
from pathlib import Path

import numpy as np
import pytest

from forceskill.model import dmp
from forceskill.model.demo import load_demo
from forceskill.model.fit import fit
from forceskill.model.params import gains_for_object

REPO = Path(__file__).resolve().parents[2]
SCEN = REPO / "hil_sim" / "scenarios"


@pytest.fixture(scope="module")
def wipe(hil_sim: Path, tmp_path_factory: pytest.TempPathFactory) -> dict:
    d = tmp_path_factory.mktemp("wipe")
    subprocess.run(
        [str(hil_sim), "run", str(SCEN / "wiping_demo.toml"), "-o", str(d / "demo.csv")],
        check=True,
        capture_output=True,
    )
    demo = load_demo(d / "demo.csv", y_column="y")
    res = fit(demo, 280.0, surface_m=0.001, gains=gains_for_object(280.0, 10.0))
    res.skill.write(d / "wipe.skill")
    return {"dir": d, "res": res, "demo": demo}


@pytest.mark.parametrize("goal,path", [(1.0, 1.0), (1.5, 1.0), (1.0, 1.5)])
def test_wiping_path_and_force_tracked(hil_sim: Path, wipe: dict, goal: float, path: float) -> None:
    d, res = wipe["dir"], wipe["res"]
    assert res.y_err_max_mm <= 0.5 and res.err_max_pct <= 2.5
    log = d / f"exec_g{goal:g}_p{path:g}.csv"
    toml = (
        (SCEN / "wiping_exec.toml")
        .read_text()
        .replace("goal_scale = 1.0", f"goal_scale = {goal}\npath_scale = {path}")
    )
    (d / "exec.toml").write_text(toml)
    subprocess.run(
        [str(hil_sim), "run", str(d / "exec.toml"), "-o", str(log), "--skill", str(d / "wipe.skill")],
        check=True,
        capture_output=True,
    )
    summary = json.loads(log.with_suffix(".summary.json").read_text())
    assert summary["tracking_rms_pct"] <= 3.0 and summary["limit_violations"] == 0
    ex = np.genfromtxt(log, delimiter=",", names=True)
    _, y_hat = dmp.rollout_path(res.skill, path_scale=path)
    p = y_hat - res.skill.y_start_m
    e = ex["y"][: p.size] - (ex["y"][0] + p)
    rms_mm, max_mm = 1e3 * float(np.sqrt(np.mean(e * e))), 1e3 * float(np.max(np.abs(e)))
    print(
        f"goal x{goal:g} path x{path:g}: path tracking RMS {rms_mm:.3f} mm, max {max_mm:.3f} mm, "
        f"force tracking RMS {summary['tracking_rms_pct']:.2f} %"
    )
    assert rms_mm <= 1.0 and max_mm <= 3.0
    assert np.ptp(ex["y"]) >= 0.9 * np.ptp(p) > 0.02

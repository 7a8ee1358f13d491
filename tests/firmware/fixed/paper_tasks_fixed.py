#!/usr/bin/env python3
"""Fixed point vs float64 on the four paper tasks (every paper task, goal
1x and 1.5x). Each task's demonstration is recorded by the HIL simulator (scenario
hil_sim/scenarios/<task>_demo.toml, seed 1), fitted with the default method (ridge, N = 50) as
`forceskill report` does, and the skill image is rolled out by fixed_compare at goal 1x and 1.5x.
Then the pressing task 2 demonstration is fitted again at 1e2 and 1e6 N/m: the DMP runs in force
units, so the fixed-point layout holds the same accuracy at any stiffness (<= 0.01 % of float64).

usage: paper_tasks_fixed.py HIL_SIM FIXED_COMPARE OUT_DIR
"""

import subprocess
import sys
from pathlib import Path

from forceskill.commands.report import SURFACE_M, TASKS, run_sim
from forceskill.model.demo import load_demo
from forceskill.model.fit import fit

ROOT = Path(__file__).resolve().parents[3]


def main() -> int:
    hil_sim, compare, out = Path(sys.argv[1]), Path(sys.argv[2]), Path(sys.argv[3])
    out.mkdir(parents=True, exist_ok=True)
    status = 0
    for task in TASKS:
        log = out / f"{task.name}_demo.csv"
        run_sim(hil_sim, ROOT / "hil_sim" / "scenarios" / f"{task.name}_demo.toml", log, "--seed", "1")
        res = fit(
            load_demo(log),
            task.stiffness_Npm,
            n_kernels=50,
            method="ridge",
            surface_m=SURFACE_M,
            end_policy=task.end_policy,
        )
        skill = out / f"{task.name}.skill"
        res.skill.write(skill)
        for goal in ("1", "1.5"):
            r = subprocess.run([str(compare), str(skill), goal, "1"], capture_output=True, text=True)
            print(r.stdout.strip() or r.stderr.strip())
            status |= r.returncode
    demo = load_demo(out / "pressing_task2_demo.csv")
    for k in (1e2, 1e6):
        skill = out / f"pressing_task2_k{k:.0e}.skill"
        fit(demo, k, n_kernels=50, method="ridge", surface_m=SURFACE_M).skill.write(skill)
        for goal in ("1", "1.5"):
            r = subprocess.run([str(compare), str(skill), goal, "1"], capture_output=True, text=True)
            print(r.stdout.strip() or r.stderr.strip())
            status |= r.returncode
    return status


if __name__ == "__main__":
    sys.exit(main())

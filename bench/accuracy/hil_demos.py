#!/usr/bin/env python3
"""The default fit at N = 50 on the HIL simulator's demonstrations: the figures of docs/math.md.

    .venv/bin/python bench/accuracy/hil_demos.py [--hil-sim build/hil_sim/hil_sim] [--seeds 12]

For each of the four tasks of `forceskill report` (pressing 100 / 500 N/m, engraving 100 / 280 N/m
with the path along y) and operator seeds 1..S: `hil_sim run hil_sim/scenarios/<task>_demo.toml
--seed S`, then the fit as `forceskill report` makes it (the task's stiffness, gains for the HIL's
10 kg objects, surface at 1 mm), with centres uniform in time (the layout before) and the default
layout. Prints per task and layout the range over the seeds of the max error (% of max force)
against the recording (it contains the sensor noise, quantisation and the operator's tremor) and
against the recording's 21 ms moving average (what the recording shows without its sample noise),
and the recording's own largest deviation from that average (its sample noise: no smooth skill is
much closer to the recording than that).
"""

from __future__ import annotations

import argparse
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "host"))

from forceskill.commands.report import OBJECT_MASS_KG, SURFACE_M, TASKS  # noqa: E402
from forceskill.model import fit as fitmod  # noqa: E402
from forceskill.model.demo import load_demo  # noqa: E402
from forceskill.model.params import gains_for_object  # noqa: E402

SMOOTH = 21


def moving_average(f: np.ndarray, n: int = SMOOTH) -> np.ndarray:
    pad = np.pad(f, n // 2, mode="edge")
    out: np.ndarray = np.convolve(pad, np.full(n, 1.0 / n), mode="valid")
    return out


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--hil-sim", type=Path, default=ROOT / "build" / "hil_sim" / "hil_sim")
    ap.add_argument("--seeds", type=int, default=12)
    args = ap.parse_args()
    gain = fitmod.DENSITY_GAIN
    layouts = (("uniform (before)", 0.0), ("default", gain))
    print(
        "| task (k) | layout | max error vs recording [%] | vs its 21 ms moving average [%] "
        "| recording vs its moving average [%] |"
    )
    print("|---|---|---:|---:|---:|")
    with tempfile.TemporaryDirectory() as tmp:
        for task in TASKS:
            demos = []
            for seed in range(1, args.seeds + 1):
                log = Path(tmp) / f"{task.name}_{seed}.csv"
                scen = ROOT / "hil_sim" / "scenarios" / f"{task.name}_demo.toml"
                subprocess.run(
                    [str(args.hil_sim), "run", str(scen), "--seed", str(seed), "-o", str(log)],
                    check=True,
                    capture_output=True,
                )
                demos.append(load_demo(log, y_column="y" if task.kind == "engraving" else None))
            gains = gains_for_object(task.stiffness_Npm, OBJECT_MASS_KG)
            for label, g in layouts:
                fitmod.DENSITY_GAIN = g
                raw, smooth, noise = [], [], []
                for d in demos:
                    r = fitmod.fit(
                        d, task.stiffness_Npm, surface_m=SURFACE_M, end_policy=task.end_policy, gains=gains
                    )
                    raw.append(r.err_max_pct)
                    f_max = float(np.max(np.abs(r.target_N)))
                    ma = moving_average(r.target_N)
                    smooth.append(100.0 * float(np.max(np.abs(ma - r.f_hat_N))) / f_max)
                    noise.append(100.0 * float(np.max(np.abs(ma - r.target_N))) / f_max)
                print(
                    f"| {task.name} ({task.stiffness_Npm:g}) | {label} | {min(raw):.2f}-{max(raw):.2f} "
                    f"| {min(smooth):.2f}-{max(smooth):.2f} | {min(noise):.2f}-{max(noise):.2f} |"
                )
            fitmod.DENSITY_GAIN = gain
    return 0


if __name__ == "__main__":
    sys.exit(main())

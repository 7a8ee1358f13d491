#!/usr/bin/env python3
"""The same recording fitted at stiffness 10 .. 1e7 N/m: the figure of docs/math.md section 1.

    .venv/bin/python bench/accuracy/stiffness_sweep.py

Synthetic pressing (12 s) and engraving (8 s) profiles (seeds 3, 4), default gains, N = 50.
Prints, per stiffness, the max error of the rollout against the recording (% of max force),
gamma, the controller's k_f = kkf/k and whether the rollout is finite.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "host"))

from forceskill.model import dmp, synthetic
from forceskill.model.fit import fit

STIFFNESSES = (10.0, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7)


def main() -> int:
    demos = {"pressing 12 s": synthetic.pressing(3, 12.0), "engraving 8 s": synthetic.engraving(4, 8.0)}
    print(
        "| k [N/m] | " + " | ".join(f"{n} max error [%]" for n in demos) + " | gamma | k_f = kkf/k | finite |"
    )
    print("|---:|" + "---:|" * len(demos) + "---:|---:|---|")
    for k in STIFFNESSES:
        cells, finite = [], True
        for d in demos.values():
            res = fit(d, k)
            _, f = dmp.rollout(res.skill)
            finite = finite and bool(np.all(np.isfinite(f)))
            cells.append(f"{100.0 * np.max(np.abs(f - res.target_N)) / np.max(np.abs(res.target_N)):.4f}")
        print(
            f"| {k:.0e} | "
            + " | ".join(cells)
            + f" | {res.skill.gamma:g} | {res.skill.gains.force_gains(k)[0]:.3g} | "
            f"{'yes' if finite else 'NO'} |"
        )
    return 0


if __name__ == "__main__":
    sys.exit(main())

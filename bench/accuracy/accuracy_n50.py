#!/usr/bin/env python3
"""Approximation error of the default fit at N = 50 over operator seeds: the figure of docs/math.md.

    .venv/bin/python bench/accuracy/accuracy_n50.py

Synthetic profiles shaped like the paper's (forceskill.model.synthetic: pressing two-layer 100/180 N/m;
engraving 6-10 N levels), seeds 0-11, durations 8, 9, 12 and 17 s, with and without 0.02 N sensor
noise (engraving), fitted at N = 50 (ridge) for kernel widths sigma_i = w*(c_{i+1} - c_i).
Prints the median / max of the max error (% of max force) and the most kernels evaluated per tick
(cutoff 23 in the float core, 16 in fixed point).
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "host"))

from forceskill.model import dmp, synthetic
from forceskill.model import fit as fitmod

WIDTHS = (0.5, 0.65, 1.0)
DURATIONS = (8.0, 9.0, 12.0, 17.0)


def profiles() -> list[tuple[str, float, object]]:
    out = []
    for seed in range(12):
        for T in DURATIONS:
            out.append(("pressing", T, synthetic.pressing(seed, T)))
            out.append(("engraving", T, synthetic.engraving(seed, T, 100.0, 6.0 + seed % 5)))
            out.append(
                ("engraving+noise", T, synthetic.engraving(seed, T, 100.0, 6.0 + seed % 5, noise_N=0.02))
            )
    return out


def main() -> int:
    demos = profiles()
    kinds = ("pressing", "engraving", "engraving+noise")
    print(
        "| width factor | "
        + " | ".join(f"{k} {T:g} s" for k in kinds for T in DURATIONS)
        + " | kernels per tick (23 / 16) |"
    )
    print("|---:|" + "---:|" * (len(kinds) * len(DURATIONS)) + "---:|")
    default = fitmod.WIDTH_FACTOR
    for wf in WIDTHS:
        fitmod.WIDTH_FACTOR = wf
        errs: dict[tuple[str, float], list[float]] = {}
        act = [0, 0]
        for kind, T, d in demos:
            r = fitmod.fit(d, 200.0)
            errs.setdefault((kind, T), []).append(r.err_max_pct)
            sk = r.skill
            u, _ = dmp.phase_loop(sk.alpha, sk.beta, sk.dt_s / sk.tau_s, dmp.default_steps(sk))
            e = dmp.kernel_exponents(u, sk.centres, sk.widths)
            act = [
                max(act[0], int((e <= dmp.KERNEL_CUTOFF_EXP).sum(axis=1).max())),
                max(act[1], int((e <= 16.0).sum(axis=1).max())),
            ]
        cells = " | ".join(
            f"{np.median(errs[(k, T)]):.2f} / {np.max(errs[(k, T)]):.2f}" for k in kinds for T in DURATIONS
        )
        mark = " (default)" if wf == default else ""
        print(f"| {wf:g}{mark} | {cells} | {act[0]} / {act[1]} |")
    fitmod.WIDTH_FACTOR = default
    return 0


if __name__ == "__main__":
    sys.exit(main())

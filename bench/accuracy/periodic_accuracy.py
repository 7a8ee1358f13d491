#!/usr/bin/env python3
"""Periodic skills on noisy multi-stroke demonstrations: the learned mean stroke's error against
the true (noise-free) stroke in % of max force, and the period error in %.

Synthetic wiping strokes (forceskill.model.synthetic.wiping_strokes: 12 strokes after a 1 s
approach, release 0.8 s), periods 0.6-1.6 s, 0.02 and 0.05 N of white sensor noise, seeds 0-5,
the default fit (ridge, N = 50). Fixed point and float32 against float64, over 60 s of cycles
(drift of phase included), are bench/periodic_drift's (bench_periodic_drift SKILL).
Run: .venv/bin/python bench/accuracy/periodic_accuracy.py
"""

from __future__ import annotations

import sys

import numpy as np

from forceskill.model import synthetic
from forceskill.model.periodic_fit import fit_periodic

PERIODS = (0.6, 1.0, 1.6)
NOISES = (0.02, 0.05)
SEEDS = range(6)


def main() -> int:
    print("| period [s] | noise [N] | mean stroke vs true, max [%] | period error, max [%] | strokes used |")
    print("|---:|---:|---:|---:|---:|")
    for per in PERIODS:
        for noise in NOISES:
            errs, perr, used = [], [], []
            for seed in SEEDS:
                d = synthetic.wiping_strokes(seed=seed, period_s=per, noise_N=noise)
                r = fit_periodic(d, 100.0)
                p = r.strokes_N.shape[1]
                ph = 2.0 * np.pi * ((r.start_s - 1.0) / per + np.arange(p) / p)
                true = synthetic.stroke(ph, seed)
                f_max = float(np.max(synthetic.stroke(np.linspace(0, 2 * np.pi, 4096), seed)))
                errs.append(100.0 * float(np.max(np.abs(r.cycle_N[:p] - true))) / f_max)
                perr.append(100.0 * abs(r.period_s - per) / per)
                used.append(r.strokes_N.shape[0])
            print(f"| {per:g} | {noise:g} | {max(errs):.3f} | {max(perr):.4f} | {min(used)}-{max(used)} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())

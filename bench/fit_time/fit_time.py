#!/usr/bin/env python3
"""Fit time of a 17 s, 1 kHz demonstration with N = 50 (target <= 50 ms, aim 10 ms).

Prints one line per method:
  fit_ms method=ridge N=50 T=17s median=... min=... runs=... err_max=...%
Run: .venv/bin/python bench/fit_time/fit_time.py [--runs 15]
"""

from __future__ import annotations

import argparse
import os
import time

# One BLAS thread: the fit is single-core work, and BLAS threads on a loaded 2-core machine only
# add variance. Set before numpy is imported.
for _v in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_v, "1")

import numpy as np  # noqa: E402

from forceskill.model import synthetic  # noqa: E402
from forceskill.model.fit import fit  # noqa: E402


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--runs", type=int, default=15)
    ap.add_argument("--kernels", type=int, default=50)
    args = ap.parse_args()
    demo = synthetic.engraving(seed=7, duration_s=17.0, k_v=100.0, f_max_N=8.0, noise_N=0.02)
    for method in ("ridge", "lwr"):
        fit(demo, 100.0, n_kernels=args.kernels, method=method)  # warm-up
        times = []
        for _ in range(max(5, args.runs)):
            t0 = time.perf_counter()
            res = fit(demo, 100.0, n_kernels=args.kernels, method=method)
            times.append(time.perf_counter() - t0)
        ms = 1e3 * np.array(times)
        print(
            f"fit_ms method={method} N={args.kernels} T=17s median={np.median(ms):.2f} min={ms.min():.2f} "
            f"runs={ms.size} err_max={res.err_max_pct:.2f}%"
        )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

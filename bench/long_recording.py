#!/usr/bin/env python3
"""A long recording: a 2,000,000-row CSV (100 presses at 1 kHz, ~50 MB) read and fitted.

Makes the file in a temporary folder and prints, each figure measured in a fresh subprocess:
  parse: fit's reader (forceskill.model.demo.load_demo: reading and validating) against
         numpy.loadtxt of the same file (target: the reader at most 1.0x loadtxt's time);
  peak:  the reader's and numpy.loadtxt's peak memory (tracemalloc: numpy's buffers and Python's
         objects) against the file's size;
  fit:   the whole `forceskill fit -k 2000 --surface-m 0.002` (default options otherwise: the
         2,000 s file is refused for accuracy after the kernel search up to N = 1,024) wall time,
         its peak memory against the file's size (target: at most 2.5x) and its verdict.
Times are the best of --runs, each in a fresh interpreter (imports done before the clock starts);
peaks are one run under tracemalloc (which slows Python, so it is not timed).
Run: .venv/bin/python bench/long_recording.py [--rows 2000000] [--runs 3]
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

for _v in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_v, "1")

#: One press: quiet, ramp, hold, release (s at 1 kHz); 100 of them make 2,000,000 rows.
PRESS_S = 20.0

# one measurement in a fresh interpreter: its time untraced, or its peak under tracemalloc
_CHILD = r"""
import json, sys, time, tracemalloc
what, trace, path, rest = sys.argv[1], sys.argv[2] == "1", sys.argv[3], sys.argv[4:]
import numpy as np
from forceskill import cli
from forceskill.model.demo import load_demo
from forceskill.readers import csv
if trace:
    tracemalloc.start()
t0 = time.perf_counter()
if what == "loadtxt":
    a = np.loadtxt(path, delimiter=",", skiprows=1)
elif what == "reader":
    d = load_demo(path)
else:
    rc = cli.main(["fit", path, *rest])
dt = time.perf_counter() - t0
peak = tracemalloc.get_traced_memory()[1] if trace else 0
print(json.dumps({"s": dt, "peak": peak}))
"""


def write_csv(path: Path, rows: int) -> None:
    """t,x,f_contact: presses of 20 s (a 1 s quiet lead, a raised-cosine ramp to a hold of random
    height, release), t in s with 3 decimals, x in m, f in N, written block by block."""
    import numpy as np

    rng = np.random.default_rng(1)
    n_press = int(round(PRESS_S * 1000))
    u = np.arange(n_press) / 1000.0
    with open(path, "w") as fh:
        fh.write("t,x,f_contact\n")
        for k in range(0, rows, n_press):
            m = min(n_press, rows - k)
            peak = rng.uniform(8.0, 20.0)
            up = np.clip((u - 1.0) / 4.0, 0.0, 1.0)
            down = np.clip((u - 15.0) / 3.0, 0.0, 1.0)
            f = peak * (0.5 - 0.5 * np.cos(np.pi * up)) * (0.5 + 0.5 * np.cos(np.pi * down))
            f = (f + rng.normal(0.0, 0.02, f.size))[:m]
            t = (k + np.arange(m)) / 1000.0
            x = 0.002 + np.maximum(f, 0.0) / 2000.0
            np.savetxt(fh, np.column_stack((t, x, f)), fmt=("%.3f", "%.6f", "%.3f"), delimiter=",")


def child(what: str, path: Path, *rest: str, trace: bool = False) -> dict[str, float]:
    out = subprocess.run(
        [sys.executable, "-c", _CHILD, what, "1" if trace else "0", str(path), *rest],
        check=True,
        capture_output=True,
        text=True,
    )
    return dict(json.loads(out.stdout.strip().splitlines()[-1]))


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--rows", type=int, default=2_000_000)
    ap.add_argument("--runs", type=int, default=3)
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "long.csv"
        t0 = time.perf_counter()
        write_csv(path, args.rows)
        size = path.stat().st_size
        print(f"file: {args.rows} rows, {size / 1e6:.1f} MB, written in {time.perf_counter() - t0:.1f} s")
        res: dict[str, list[dict[str, float]]] = {"loadtxt": [], "reader": []}
        for _ in range(args.runs):  # alternated, so that a busy moment hits both alike
            for what, runs in res.items():
                runs.append(child(what, path))
        best = {w: min(r["s"] for r in rs) for w, rs in res.items()}
        peak = {w: child(w, path, trace=True)["peak"] for w in res}
        ratio = best["reader"] / best["loadtxt"]
        print(
            f"parse: reader {best['reader']:.2f} s, numpy.loadtxt {best['loadtxt']:.2f} s: "
            f"{ratio:.2f}x (target <= 1.0x; best of {args.runs})"
        )
        print(
            f"peak memory: reader {peak['reader'] / 2**20:.0f} MiB = {peak['reader'] / size:.2f}x the file, "
            f"numpy.loadtxt {peak['loadtxt'] / 2**20:.0f} MiB = {peak['loadtxt'] / size:.2f}x"
        )
        skill = Path(tmp) / "long.skill"
        fit_args = ("-k", "2000", "--surface-m", "0.002", "-o", str(skill))
        r = child("fit", path, *fit_args)
        r["peak"] = child("fit", path, *fit_args, trace=True)["peak"]
        verdict = "written" if skill.exists() else "refused"
        print(
            f"fit (default options): {r['s']:.2f} s, peak memory {r['peak'] / 2**20:.0f} MiB = "
            f"{r['peak'] / size:.2f}x the file (target <= 2.5x), skill {verdict}"
        )
    return 0


if __name__ == "__main__":
    sys.exit(main())

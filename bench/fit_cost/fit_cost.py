#!/usr/bin/env python3
"""End-to-end cost of `forceskill fit` and `forceskill --help`, relative to `python -c "import numpy"`
measured in the same run, and the peak memory of reading a 10^7-row CSV.

Prints:
  startup_s numpy=... fit=... help=... (medians of --runs interleaved runs, process start to exit)
  startup_ratio fit/numpy=... help/numpy=...
  load_average ... (1/5/15 min, at the start and the end of the start-up runs)
  big_csv rows=... bytes=... read_s=... peak_rss_MB=... rss/size=... progress_bar=yes|no
  big_csv_fit exit=... peak_rss_MB=... rss/size=... wall_s=...
  duration_limit rows=... span_s=10000 refused_in_s=... peak_rss_MB=... code=...
  fit_grid_memory grid_samples=... fit_peak_MB=... (tracemalloc: the fit's own arrays on the 1 ms grid)
Run: .venv/bin/python bench/fit_cost/fit_cost.py [--runs 11] [--rows 10000000] [--keep DIR]
"""

from __future__ import annotations

import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]
BIN = Path(sys.executable).parent
FORCESKILL = (
    [str(BIN / "forceskill")] if (BIN / "forceskill").exists() else [sys.executable, "-m", "forceskill"]
)
# As a user runs them: with bytecode caches (pip writes them on install; the warm-up runs write
# them here), whatever PYTHONDONTWRITEBYTECODE says in the calling shell (with it, every run
# compiles the package's modules again: +0.1-0.6 s measured on this machine).
ENV = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
ENV.update(OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1", MKL_NUM_THREADS="1")


def _wall(cmd: list[str]) -> float:
    t0 = time.perf_counter()
    subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=ENV, check=False)
    return time.perf_counter() - t0


def _peak(cmd: list[str]) -> tuple[int, float, float, str]:
    """(exit status, peak RSS in MB, wall s, stderr) of one run, from GNU time's %M."""
    t0 = time.perf_counter()
    r = subprocess.run(
        ["/usr/bin/time", "-f", "PEAK_KB %M", *cmd], capture_output=True, text=True, env=ENV, check=False
    )
    wall = time.perf_counter() - t0
    m = re.findall(r"PEAK_KB (\d+)", r.stderr)
    return r.returncode, int(m[-1]) / 1024.0 if m else float("nan"), wall, r.stderr


def write_csv(path: Path, rows: int, rate_hz: float, block: int = 1_000_000) -> None:
    """t, x, f_contact: one smooth press (ramp, hold, ramp, release) with sensor noise, in blocks."""
    rng = np.random.default_rng(1)
    dur = (rows - 1) / rate_hz
    with open(path, "w") as fh:
        fh.write("t,x,f_contact\n")
        for i0 in range(0, rows, block):
            t = np.arange(i0, min(rows, i0 + block)) / rate_hz
            s = t / dur
            f = 20.0 * np.sin(np.pi * np.clip(s, 0.0, 1.0)) ** 2 + rng.normal(0.0, 0.02, t.size)
            x = 0.002 + np.maximum(f, 0.0) / 2000.0
            np.savetxt(fh, np.column_stack((t, x, f)), fmt=("%.5f", "%.7f", "%.4f"), delimiter=",")


def grid_memory(duration_s: float) -> None:
    """Peak of the fit's own numpy arrays (tracemalloc) on a smooth press of ``duration_s`` at 1 ms."""
    import tracemalloc

    from forceskill.model.demo import Demo
    from forceskill.model.fit import fit

    t = np.arange(int(round(duration_s * 1000.0)) + 1) * 1e-3
    f = 20.0 * np.sin(np.pi * t / t[-1]) ** 2
    d = Demo(t, 0.002 + f / 2000.0, f)
    tracemalloc.start()
    fit(d, 2000.0, surface_m=0.002)
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    print(
        f"fit_grid_memory grid_samples={t.size} fit_peak_MB={peak / 2**20:.0f} (tracemalloc: the fit's own "
        f"arrays on the 1 ms grid, {peak / t.size:.0f} bytes per sample)"
    )


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--runs", type=int, default=11)
    ap.add_argument("--rows", type=int, default=10_000_000)
    ap.add_argument("--rate", type=float, default=10_000.0, help="sample rate of the big CSV, Hz")
    ap.add_argument("--keep", metavar="DIR", help="keep the generated files here")
    ap.add_argument("--parts", default="startup,big,grid", help="comma-separated subset of startup,big,grid")
    args = ap.parse_args()
    tmp = Path(args.keep) if args.keep else Path(tempfile.mkdtemp(prefix="fit_cost_"))
    tmp.mkdir(parents=True, exist_ok=True)
    try:
        sys.path.insert(0, str(ROOT / "host"))
        from forceskill.model import synthetic
        from forceskill.model.demo import write_csv as write_demo

        d = synthetic.pressing(seed=1, duration_s=17.0)
        small = tmp / "press17.csv"
        write_demo(small, {"t": d.t_s, "x": d.pos_m, "f_contact": d.force_N})
        parts = set(args.parts.split(","))
        if "grid" in parts:
            grid_memory(args.rows / args.rate)
        numpy_cmd = [sys.executable, "-c", "import numpy"]
        fit_cmd = [
            *FORCESKILL,
            "fit",
            str(small),
            "-k",
            "100",
            "--surface-m",
            "0.001",
            "-o",
            str(tmp / "p.skill"),
        ]
        help_cmd = [*FORCESKILL, "--help"]
        for c in (numpy_cmd, fit_cmd, help_cmd) if "startup" in parts else ():  # warm caches and .pyc files
            _wall(c)
        load0 = " ".join(f"{x:.2f}" for x in os.getloadavg())
        tn, tf, th = [1.0], [float("nan")], [float("nan")]
        for _ in range(args.runs if "startup" in parts else 0):
            tn.append(_wall(numpy_cmd))
            tf.append(_wall(fit_cmd))
            th.append(_wall(help_cmd))
        n, f, h = (float(np.median(x[1:] if len(x) > 1 else x)) for x in (tn, tf, th))
        if "startup" in parts:
            print(f"load_average {load0} at start, {' '.join(f'{x:.2f}' for x in os.getloadavg())} at end")
            print(
                f"startup_s numpy={n:.3f} fit={f:.3f} help={h:.3f} (medians of {args.runs} interleaved runs)"
            )
            print(f"startup_ratio fit/numpy={f / n:.2f} help/numpy={h / n:.2f}")

        if "big" not in parts:
            return 0
        big = tmp / "big.csv"
        write_csv(big, args.rows, args.rate)
        size_mb = big.stat().st_size / 2**20
        read_cmd = [
            sys.executable,
            "-c",
            "import sys; from forceskill.model.demo import load_demo; "
            "d = load_demo(sys.argv[1], stiffness_Npm=2000.0); print(d.t_s.size)",
            str(big),
        ]
        rc, peak, wall, err = _peak(read_cmd)
        print(
            f"big_csv rows={args.rows} bytes={big.stat().st_size} read_s={wall:.2f} peak_rss_MB={peak:.0f} "
            f"rss/size={peak / size_mb:.2f} progress_bar={'yes' if 'reading big.csv' in err else 'no'} exit={rc}"
        )
        rc, peak, wall, err = _peak(
            [*FORCESKILL, "fit", str(big), "-k", "2000", "--surface-m", "0.002", "-o", str(tmp / "big.skill")]
        )
        last = next((ln for ln in err.splitlines() if ln.startswith("forceskill: error")), "")
        print(
            f"big_csv_fit exit={rc} peak_rss_MB={peak:.0f} rss/size={peak / size_mb:.2f} wall_s={wall:.2f}"
            + (f" ({last[:160]})" if rc else "")
        )
        # the duration limit: the same file with one more row at 10,000 s is refused from its first
        # and last rows, before the body is parsed
        long = big
        with open(long, "ab") as fh:
            fh.write(b"10000.00000,0.0020000,0.0000\n")
        rc, peak, wall, err = _peak(
            [*FORCESKILL, "fit", str(long), "-k", "2000", "-o", str(tmp / "long.skill")]
        )
        code = re.findall(r"\[(\d+)\]", err)
        print(
            f"duration_limit rows={args.rows + 1} span_s=10000 refused_in_s={wall:.2f} peak_rss_MB={peak:.0f} "
            f"code={code[-1] if code else rc}"
        )
    finally:
        if not args.keep:
            shutil.rmtree(tmp, ignore_errors=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())

"""Demonstrations: reading, validating and resampling a recorded task.

A demonstration is time ``t`` (s), the demonstrated position ``x`` (m, into the object) and
one force (N, pushing positive): the contact (tip) force ``f_contact`` by default, the operator's
(handle) force ``f_operator`` with ``learn="operator"``. CSV files have a header row; the HIL log
columns are ``t,x,y,f_contact,f_operator,f_cmd,f_hat`` in SI units. Readers are chosen by file
suffix from a registry (``register_reader``), so CAN log formats can be added (.blf, .asc, ...).

Validation refuses, with one line naming the problem and the value: fewer than 100 samples or
shorter than 0.5 s, NaN/inf, time not strictly increasing, a gap above 1.5x the median step, a
constant zero force, an unknown column (listing those available). A log not sampled at the fit
step is resampled by linear interpolation (``resample``).
"""

from __future__ import annotations

import csv
import math
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .errors import (
    ERR_DEMO_COLUMN,
    ERR_DEMO_FILE,
    ERR_DEMO_FORMAT,
    ERR_DEMO_GAP,
    ERR_DEMO_NOT_FINITE,
    ERR_DEMO_TIME,
    ERR_DEMO_TOO_SHORT,
    ERR_DEMO_ZERO_FORCE,
    ERR_FIT_ARGS,
    DemoError,
    ParamError,
)

MIN_SAMPLES = 100
MIN_DURATION_S = 0.5
GAP_FACTOR = 1.5
#: A log whose samples sit within this fraction of dt of the grid t0 + n*dt is used as is.
GRID_TOL = 0.01
LEARN_COLUMNS = {"contact": "f_contact", "operator": "f_operator"}

Columns = dict[str, np.ndarray]
Reader = Callable[[Path], Columns]


@dataclass
class Demo:
    """One demonstration: time (s), position (m), the force to learn (N), and where it came from."""

    t_s: np.ndarray
    pos_m: np.ndarray
    force_N: np.ndarray
    source: str = ""


_READERS: dict[str, Reader] = {}


def register_reader(suffix: str, fn: Reader) -> None:
    """Add a reader for files ending in ``suffix`` ('.csv'); it returns named columns including 't'."""
    _READERS[suffix.lower()] = fn


def readers() -> list[str]:
    return sorted(_READERS)


def read_csv_columns(path: Path) -> Columns:
    """Columns of a CSV file with a header row (comma separated, numbers only below the header)."""
    try:
        with open(path, newline="") as f:
            rows = list(csv.reader(f))
    except OSError as e:
        raise DemoError(ERR_DEMO_FILE, f"cannot read demonstration {str(path)!r}: {e.strerror}") from None
    except UnicodeDecodeError:
        raise DemoError(ERR_DEMO_FORMAT, f"demonstration {str(path)!r} is not a text CSV file") from None
    rows = [r for r in rows if r and any(c.strip() for c in r)]
    if not rows:
        raise DemoError(ERR_DEMO_FORMAT, f"demonstration {str(path)!r} is empty")
    header = [c.strip() for c in rows[0]]
    if any(_is_number(c) for c in header):
        raise DemoError(
            ERR_DEMO_FORMAT, f"demonstration {str(path)!r} has no header row (first row: {','.join(header)})"
        )
    data = np.empty((len(rows) - 1, len(header)))
    for i, r in enumerate(rows[1:]):
        if len(r) != len(header):
            raise DemoError(
                ERR_DEMO_FORMAT, f"{path}: line {i + 2} has {len(r)} fields, header has {len(header)}"
            )
        for j, cell in enumerate(r):
            try:
                data[i, j] = float(cell)
            except ValueError:
                raise DemoError(
                    ERR_DEMO_FORMAT,
                    f"{path}: line {i + 2}, column {header[j]!r}: not a number: {cell.strip()!r}",
                ) from None
    return {name: data[:, j] for j, name in enumerate(header)}


def _is_number(s: str) -> bool:
    try:
        float(s)
    except ValueError:
        return False
    return True


register_reader(".csv", read_csv_columns)

_log_readers_loaded = False


def _load_log_readers() -> None:
    """CAN log formats (.blf, .asc, ...) live in forceskill.link (python-can, cantools): import
    it on first use, so ``load_demo`` reads them whether or not the CLI was built first."""
    global _log_readers_loaded
    if not _log_readers_loaded:
        _log_readers_loaded = True
        import forceskill.link.logs  # noqa: F401  (registers its readers on import)


def load_demo(
    path: str | Path, position_column: str = "x", force_column: str | None = None, learn: str = "contact"
) -> Demo:
    """Read and validate a demonstration; ``force_column`` overrides the column ``learn`` selects."""
    if learn not in LEARN_COLUMNS:
        raise ParamError(ERR_FIT_ARGS, f"learn must be one of {', '.join(LEARN_COLUMNS)}: {learn!r}")
    p = Path(path)
    _load_log_readers()
    reader = _READERS.get(p.suffix.lower())
    if reader is None:
        raise DemoError(
            ERR_DEMO_FILE,
            f"no reader for demonstration suffix {p.suffix or '(none)'!r} (known: {', '.join(readers())})",
        )
    if not p.is_file():
        raise DemoError(ERR_DEMO_FILE, f"demonstration file not found: {str(p)!r}")
    cols = reader(p)
    fcol = force_column or LEARN_COLUMNS[learn]
    for name in ("t", position_column, fcol):
        if name not in cols:
            raise DemoError(
                ERR_DEMO_COLUMN, f"column {name!r} not in {p.name} (available: {', '.join(cols)})"
            )
    demo = Demo(
        t_s=np.asarray(cols["t"], float),
        pos_m=np.asarray(cols[position_column], float),
        force_N=np.asarray(cols[fcol], float),
        source=f"{p.name}:{fcol}",
    )
    validate(demo)
    return demo


def validate(demo: Demo) -> None:
    """Refuse a demonstration that cannot be learned from (DemoError, 603-607)."""
    t, x, f = demo.t_s, demo.pos_m, demo.force_N
    if not (t.shape == x.shape == f.shape and t.ndim == 1):
        raise DemoError(
            ERR_DEMO_FORMAT,
            f"demonstration columns differ in length: t {t.shape}, position {x.shape}, force {f.shape}",
        )
    if t.size < MIN_SAMPLES:
        raise DemoError(
            ERR_DEMO_TOO_SHORT, f"demonstration too short: {t.size} samples (need >= {MIN_SAMPLES})"
        )
    for name, arr in (("t", t), ("position", x), ("force", f)):
        bad = np.flatnonzero(~np.isfinite(arr))
        if bad.size:
            raise DemoError(
                ERR_DEMO_NOT_FINITE,
                f"demonstration {name} is not finite at sample {bad[0]} (t = {t[bad[0]]:g} s): {arr[bad[0]]}",
            )
    dt = np.diff(t)
    bad = np.flatnonzero(~(dt > 0.0))
    if bad.size:
        i = int(bad[0])
        raise DemoError(
            ERR_DEMO_TIME,
            f"demonstration time not strictly increasing at sample {i + 1}: "
            f"t = {t[i]:.9g} s then {t[i + 1]:.9g} s",
        )
    duration = float(t[-1] - t[0])
    if duration < MIN_DURATION_S:
        raise DemoError(
            ERR_DEMO_TOO_SHORT, f"demonstration too short: {duration:g} s (need >= {MIN_DURATION_S:g} s)"
        )
    med = float(np.median(dt))
    gaps = np.flatnonzero(dt > GAP_FACTOR * med)
    if gaps.size:
        i = int(gaps[0])
        raise DemoError(
            ERR_DEMO_GAP,
            f"demonstration has a gap of {dt[i] * 1e3:.6g} ms at t = {t[i]:.6g} s "
            f"(median step {med * 1e3:.6g} ms, limit {GAP_FACTOR:g}x)",
        )
    if not np.any(f != 0.0):
        raise DemoError(
            ERR_DEMO_ZERO_FORCE,
            f"demonstration force ({demo.source or 'force'}) is constant zero over {t.size} samples",
        )


def on_grid(t_s: np.ndarray, dt_s: float) -> bool:
    """True when every sample is within GRID_TOL*dt of t0 + n*dt."""
    n = np.arange(t_s.size)
    return bool(np.max(np.abs(t_s - t_s[0] - n * dt_s)) <= GRID_TOL * dt_s)


def resample(demo: Demo, dt_s: float) -> Demo:
    """The demonstration on the grid n*dt from its first sample (time shifted to start at 0).

    Already on the grid (1 kHz log at dt = 1 ms): samples kept as they are. Otherwise position and
    force are linearly interpolated at t0 + n*dt for n = 0..floor((t_end - t0)/dt).
    """
    if not (math.isfinite(dt_s) and dt_s > 0.0):
        raise ParamError(ERR_FIT_ARGS, f"dt must be finite and > 0: {dt_s}")
    t0 = float(demo.t_s[0])
    if on_grid(demo.t_s, dt_s):
        n = demo.t_s.size
        return Demo(np.arange(n) * dt_s, demo.pos_m.copy(), demo.force_N.copy(), demo.source)
    n_last = int(math.floor((float(demo.t_s[-1]) - t0) / dt_s + 1e-9))
    tn = t0 + np.arange(n_last + 1) * dt_s
    return Demo(
        np.arange(n_last + 1) * dt_s,
        np.interp(tn, demo.t_s, demo.pos_m),
        np.interp(tn, demo.t_s, demo.force_N),
        demo.source + f" (resampled to {dt_s * 1e3:g} ms)",
    )


def write_csv(path: str | Path, columns: Columns) -> None:
    """Write named equal-length columns as CSV with a header (%.17g), atomically."""
    from .skill import atomic_write

    names = list(columns)
    data = np.column_stack([np.asarray(columns[k], float) for k in names])
    lines = [",".join(names)]
    lines += [",".join(f"{v:.17g}" for v in row) for row in data.tolist()]
    atomic_write(Path(path), ("\n".join(lines) + "\n").encode())

"""Demonstrations: reading, validating and resampling a recorded task.

A demonstration is time ``t`` (s), the demonstrated position ``x`` (m, into the object) and one
force (N, pushing positive): the contact (tip) force ``f_contact`` by default, the operator's
(handle) force ``f_operator`` with ``learn="operator"``, or any column by name. Files are read by
the reader plugin for their suffix (``forceskill.readers``: CSV, CAN logs, ROS 2 bags). The force
can be sign-flipped and scaled, a sensor bias measured before contact removed (``tare``), and a
recording without position gets ``x = surface + f/k``.

Validation refuses, with one line naming the problem and the value: fewer than 100 samples or
shorter than 0.5 s, NaN/inf, time not strictly increasing, a gap longer than ``max_gap_s``
(100 ms by default), a constant zero force, an unknown column (listing those available).
Irregular or slower sampling is resampled to the fit step by linear interpolation (``resample``).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np

from ..errors import (
    ERR_DEMO_COLUMN,
    ERR_DEMO_FORMAT,
    ERR_DEMO_GAP,
    ERR_DEMO_NOT_FINITE,
    ERR_DEMO_TARE,
    ERR_DEMO_TIME,
    ERR_DEMO_TOO_SHORT,
    ERR_DEMO_ZERO_FORCE,
    ERR_FIT_ARGS,
    ERR_READ_ARGS,
    DemoError,
    FsError,
    ParamError,
)
from ..readers import (
    MAX_GAP_S,
    NOTES_KEY,
    OBJECT_MASS_KEY,
    SECONDS_ASSUMED_KEY,
    Columns,
    ReadOptions,
    read_columns,
    time_unit_hint,
)

MIN_SAMPLES = 100
MIN_DURATION_S = 0.5
#: A log whose samples sit within this fraction of dt of the grid t0 + n*dt is used as is.
GRID_TOL = 0.01
LEARN_COLUMNS = {"contact": "f_contact", "operator": "f_operator"}
_CHUNK = 1 << 16
DEFAULT_POSITION = "x"
#: --tare auto: the quiet stretch before contact ends where the force leaves the first 50 ms'
#: median by more than TARE_CONTACT_REL of the force range (or 6 noise deviations if larger);
#: it must last at least TARE_MIN_S.
TARE_HEAD_S = 0.05
TARE_CONTACT_REL = 0.05
TARE_MIN_S = 0.05
#: ... and its level must be a bias, not a contact: |level| <= this fraction of the force range.
TARE_BIAS_MAX_REL = 0.25


@dataclass
class Demo:
    """One demonstration: time (s), position (m), the force to learn (N), and where it came from.

    ``max_gap_s``: the longest gap between samples that validation accepts; ``notes``: what was
    done to the recording on the way in (tare, position from force, ...), for the user.
    """

    t_s: np.ndarray
    pos_m: np.ndarray
    force_N: np.ndarray
    source: str = ""
    max_gap_s: float = MAX_GAP_S
    notes: list[str] = field(default_factory=list)
    #: the path along the unconstrained axis y (m), learned by the position DMP; None: none
    y_m: np.ndarray | None = None
    #: the object's mass (kg) the recording names (the device's object model in a CAN log of
    #: ``forceskill record``); None: unknown
    object_mass_kg: float | None = None


def read_csv_columns(path: str | Path) -> Columns:
    """Every column of a CSV file with a header row (the CSV reader plugin, default options)."""
    from ..readers import csv

    return csv.read(Path(path), ReadOptions())


def load_demo(
    path: str | Path,
    position_column: str | None = None,
    force_column: str | None = None,
    learn: str = "contact",
    *,
    read: ReadOptions | None = None,
    force_sign: float = 1.0,
    force_scale: float = 1.0,
    tare: str = "none",
    max_gap_s: float = MAX_GAP_S,
    stiffness_Npm: float | None = None,
    surface_m: float = 0.0,
    y_column: str | None = None,
) -> Demo:
    """Read and validate a demonstration.

    ``y_column``: the column holding the path along y (m) that the skill's position DMP learns.

    ``force_column`` overrides the column ``learn`` selects. ``position_column`` None: ``x`` when
    present, else ``surface_m + f/stiffness_Npm`` (a note says so). The force is multiplied by
    ``force_sign*force_scale``, then ``tare`` ('none', 'auto' or seconds) removes a bias.
    """
    if learn not in LEARN_COLUMNS:
        raise ParamError(ERR_FIT_ARGS, f"learn must be one of {', '.join(LEARN_COLUMNS)}: {learn!r}")
    if force_sign not in (1.0, -1.0):
        raise FsError(ERR_READ_ARGS, f"force sign must be 1 or -1: {force_sign:g}")
    if not (math.isfinite(force_scale) and force_scale > 0.0):
        raise FsError(ERR_READ_ARGS, f"force scale must be finite and > 0: {force_scale:g}")
    if not (math.isfinite(max_gap_s) and max_gap_s > 0.0):
        raise FsError(ERR_READ_ARGS, f"--max-gap must be finite and > 0 s: {max_gap_s:g}")
    tare_s = parse_tare(tare)
    p = Path(path)
    fcol = force_column or LEARN_COLUMNS[learn]
    opts = replace(
        read or ReadOptions(),
        columns=(fcol,) + ((position_column,) if position_column else ()) + ((y_column,) if y_column else ()),
        optional=() if position_column else (DEFAULT_POSITION,),
    )
    cols = read_columns(p, opts)
    notes = [str(n) for n in cols.pop(NOTES_KEY, [])]
    seconds_assumed = cols.pop(SECONDS_ASSUMED_KEY, None) is not None
    mass = cols.pop(OBJECT_MASS_KEY, None)
    for name in (
        ("t", fcol) + ((position_column,) if position_column else ()) + ((y_column,) if y_column else ())
    ):
        if name not in cols:
            raise DemoError(
                ERR_DEMO_COLUMN, f"column {name!r} not in {p.name} (available: {', '.join(cols)})"
            )
    f = np.asarray(cols[fcol], float)
    if force_sign * force_scale != 1.0:
        f = f * (force_sign * force_scale)
    t = np.asarray(cols["t"], float)
    if tare_s is not None:
        f, note = _tare(t, f, tare_s, tare == "auto")
        notes.append(note)
    pos_name = position_column or DEFAULT_POSITION
    if pos_name in cols:
        x = np.asarray(cols[pos_name], float)
    else:
        if stiffness_Npm is None or not stiffness_Npm > 0.0:
            raise DemoError(
                ERR_DEMO_COLUMN,
                f"no position column {pos_name!r} in {p.name} and no stiffness "
                f"to derive it (available: {', '.join(cols)})",
            )
        x = surface_m + f / stiffness_Npm
        notes.append(
            f"no position column {pos_name!r}: position taken as surface + f/k (k = {stiffness_Npm:g} N/m)"
        )
    y = None if not y_column else np.asarray(cols[y_column], float)
    demo = Demo(t_s=t, pos_m=x, force_N=f, source=f"{p.name}:{fcol}", max_gap_s=max_gap_s, notes=notes, y_m=y)
    demo.object_mass_kg = float(mass[0]) if mass is not None and len(mass) else None
    try:
        validate(demo)
    except DemoError as e:
        hint = ""
        if e.code == ERR_DEMO_GAP and seconds_assumed and t.size > 1:
            hint = time_unit_hint(float(np.median(np.diff(t[: 1 << 16]))))
        if not hint:
            raise
        raise DemoError(e.code, e.message + hint) from None
    return demo


def parse_tare(tare: str) -> float | None:
    """None for 'none', 0.0 for 'auto' (window found later), else the window in seconds (> 0)."""
    if tare == "none":
        return None
    if tare == "auto":
        return 0.0
    try:
        v = float(tare)
    except ValueError:
        raise FsError(ERR_DEMO_TARE, f"--tare must be auto, none or a window in seconds: {tare!r}") from None
    if not (math.isfinite(v) and v > 0.0):
        raise FsError(ERR_DEMO_TARE, f"--tare window must be finite and > 0 s: {tare!r}")
    return v


def _tare(t: np.ndarray, f: np.ndarray, window_s: float, auto: bool) -> tuple[np.ndarray, str]:
    """Subtract the median force of the first ``window_s`` (auto: of the quiet stretch before
    contact); refuses a window without samples or, for auto, a recording that starts in contact."""
    if t.size < 2:
        raise DemoError(ERR_DEMO_TARE, f"--tare: only {t.size} samples")
    t0 = float(t[0])
    if auto:
        head = f[t <= t0 + TARE_HEAD_S]
        base = float(np.median(head))
        noise = float(np.median(np.abs(head - base))) * 1.4826
        rng = float(np.max(f) - np.min(f))
        thresh = max(TARE_CONTACT_REL * rng, 6.0 * noise)
        away = np.flatnonzero(np.abs(f - base) > thresh)
        end = int(away[0]) if away.size else f.size
        quiet_s = float(t[end - 1] - t0) if end > 0 else 0.0
        if quiet_s < TARE_MIN_S or end >= f.size or abs(base) > TARE_BIAS_MAX_REL * rng:
            raise DemoError(
                ERR_DEMO_TARE,
                f"--tare auto: no quiet stretch before contact (the force leaves "
                f"{base:.4g} N by more than {thresh:.3g} N after {quiet_s * 1e3:.0f} ms, force range "
                f"{rng:.4g} N): the recording starts in contact; give --tare SECONDS or --tare none",
            )
        window = f[:end]
        span = quiet_s
    else:
        window = f[t <= t0 + window_s]
        span = window_s
        if window.size < 2:
            raise DemoError(
                ERR_DEMO_TARE, f"--tare {window_s:g}: the first {window_s:g} s hold {window.size} sample(s)"
            )
        if window_s > 0.5 * float(t[-1] - t0):
            raise DemoError(
                ERR_DEMO_TARE,
                f"--tare {window_s:g}: the window is more than half of the {float(t[-1] - t0):g} s recording",
            )
    bias = float(np.median(window))
    return (
        f - bias,
        f"tare: removed a bias of {bias:.4g} N (median of the first {span:.3g} s, {window.size} samples)",
    )


def validate(demo: Demo) -> None:
    """Refuse a demonstration that cannot be learned from (DemoError, 603-607)."""
    t, x, f = demo.t_s, demo.pos_m, demo.force_N
    y = x if demo.y_m is None else demo.y_m
    if not (t.shape == x.shape == f.shape == y.shape and t.ndim == 1):
        raise DemoError(
            ERR_DEMO_FORMAT,
            f"demonstration columns differ in length: t {t.shape}, position {x.shape}, force {f.shape}"
            + ("" if demo.y_m is None else f", y {y.shape}"),
        )
    if t.size < MIN_SAMPLES:
        raise DemoError(
            ERR_DEMO_TOO_SHORT, f"demonstration too short: {t.size} samples (need >= {MIN_SAMPLES})"
        )
    if _sound(demo):  # then only the duration can be refused
        _check_duration(t)
        return
    for name, arr in (("t", t), ("position", x), ("force", f), ("y", y)):
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
    _check_duration(t)
    gaps = np.flatnonzero(dt > demo.max_gap_s + 1e-9)  # a step of --max-gap itself (in float) passes
    if gaps.size:
        i = int(gaps[0])
        raise DemoError(
            ERR_DEMO_GAP,
            f"demonstration has a gap of {dt[i] * 1e3:.6g} ms at t = {t[i]:.6g} s "
            f"(longer than --max-gap {demo.max_gap_s * 1e3:g} ms; {gaps.size} such gap(s))",
        )
    if not np.any(f != 0.0):
        raise DemoError(
            ERR_DEMO_ZERO_FORCE,
            f"demonstration force ({demo.source or 'force'}) is constant zero over {t.size} samples",
        )


def _check_duration(t: np.ndarray) -> None:
    duration = float(t[-1] - t[0])
    if duration < MIN_DURATION_S:
        raise DemoError(
            ERR_DEMO_TOO_SHORT, f"demonstration too short: {duration:g} s (need >= {MIN_DURATION_S:g} s)"
        )


def _sound(demo: Demo) -> bool:
    """True when every value is finite, time strictly increases by steps of at most max_gap_s and
    the force is not all zero: one pass in blocks of _CHUNK samples, no full-size temporaries
    (``validate`` then names the first problem the usual way)."""
    t, f = demo.t_s, demo.force_N
    n = t.size
    # t needs no sum: a non-finite time makes a step that fails the step check
    arrays = [a for a in (demo.pos_m, f, demo.y_m) if a is not None]
    step = np.empty(min(_CHUNK, n))
    push = False
    for i0 in range(0, n, _CHUNK):
        i1 = min(n, i0 + _CHUNK)
        # a sum is finite only when every term is (a finite sum that overflows is looked at again)
        if not all(math.isfinite(float(np.sum(a[i0:i1]))) for a in arrays):
            return False
        j1 = min(i1, n - 1)  # the steps t[k+1] - t[k] for k in i0..j1-1
        if j1 > i0:
            d = np.subtract(t[i0 + 1 : j1 + 1], t[i0:j1], out=step[: j1 - i0])
            if not (float(np.min(d)) > 0.0 and float(np.max(d)) <= demo.max_gap_s + 1e-9):
                return False
        push = push or bool(np.any(f[i0:i1]))
    return push


def on_grid(t_s: np.ndarray, dt_s: float) -> bool:
    """True when every sample is within GRID_TOL*dt of t0 + n*dt (checked in chunks: no
    full-size temporaries on long recordings)."""
    t0 = float(t_s[0])
    if abs(float(t_s[-1]) - t0 - (t_s.size - 1) * dt_s) > GRID_TOL * dt_s:
        return False
    for i0 in range(0, t_s.size, _CHUNK):
        n = np.arange(i0, min(t_s.size, i0 + _CHUNK))
        if np.max(np.abs(t_s[i0 : i0 + _CHUNK] - t0 - n * dt_s)) > GRID_TOL * dt_s:
            return False
    return True


def _grid(n: int, dt_s: float) -> np.ndarray:
    """n*dt for n = 0..n-1, as np.arange(n)*dt gives it (no integer array on the way)."""
    g = np.arange(n, dtype=float)
    g *= dt_s
    return g


def _is_grid(t_s: np.ndarray, dt_s: float) -> bool:
    """True when t_s is exactly ``_grid(t_s.size, dt_s)`` (checked in chunks)."""
    for i0 in range(0, t_s.size, _CHUNK):
        chunk = t_s[i0 : i0 + _CHUNK]
        g = np.arange(i0, i0 + chunk.size, dtype=float)
        g *= dt_s
        if not np.array_equal(chunk, g):
            return False
    return True


def resample(demo: Demo, dt_s: float, copy: bool = True) -> Demo:
    """The demonstration on the grid n*dt from its first sample (time shifted to start at 0).

    Already on the grid (1 kHz log at dt = 1 ms): samples kept as they are (copies; ``copy``
    False: the same arrays, and the same time array when it is the grid n*dt itself). Otherwise
    position and force are linearly interpolated at t0 + n*dt for n = 0..floor((t_end - t0)/dt).
    """
    if not (math.isfinite(dt_s) and dt_s > 0.0):
        raise ParamError(ERR_FIT_ARGS, f"dt must be finite and > 0: {dt_s}")
    t0 = float(demo.t_s[0])
    if on_grid(demo.t_s, dt_s):
        n = demo.t_s.size
        same = not copy and _is_grid(demo.t_s, dt_s)

        def keep(a: np.ndarray) -> np.ndarray:
            return a.copy() if copy else a

        return Demo(
            demo.t_s if same else _grid(n, dt_s),
            keep(demo.pos_m),
            keep(demo.force_N),
            demo.source,
            demo.max_gap_s,
            list(demo.notes),
            None if demo.y_m is None else keep(demo.y_m),
        )
    n_last = int(math.floor((float(demo.t_s[-1]) - t0) / dt_s + 1e-9))
    tn = t0 + np.arange(n_last + 1) * dt_s
    return Demo(
        np.arange(n_last + 1) * dt_s,
        np.interp(tn, demo.t_s, demo.pos_m),
        np.interp(tn, demo.t_s, demo.force_N),
        demo.source + f" (resampled to {dt_s * 1e3:g} ms)",
        demo.max_gap_s,
        list(demo.notes),
        None if demo.y_m is None else np.interp(tn, demo.t_s, demo.y_m),
    )


def write_csv(path: str | Path, columns: Columns, inputs: Sequence[str | Path] = ()) -> None:
    """Write named equal-length columns as CSV with a header (%.17g) through forceskill.outputs
    (temporary file renamed on success; '-' is standard output)."""
    from ..outputs import write_csv as _write

    names = list(columns)
    data = np.column_stack([np.asarray(columns[k], float) for k in names]) if names else np.zeros((0, 0))
    _write(path, names, [data], inputs=inputs)

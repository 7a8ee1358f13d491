"""Demonstration readers: one plugin per file format, found through ``forceskill.readers`` entry points.

An entry point's name is the file suffix it reads without the leading dot (``csv``, ``blf``, ``mcap``,
``gz``); its value is a function ``read(path, opts) -> Columns`` returning named float columns, one
of them ``"t"`` (seconds, strictly increasing as recorded). Built-in formats (host/pyproject.toml):

- ``csv``: text tables (``forceskill.readers.csv``; python-can CSV logs go to the CAN reader);
- ``blf asc log trc db mf4``: CAN logs through the DBC (``forceskill.readers.canlog``); ``gz``: any of
  these compressed (``forceskill.readers.gz``);
- ``txt``: python-can's text log (which it cannot read) refused by name, else a text table as ``csv``;
- ``mcap``: ROS 2 bags, geometry_msgs/WrenchStamped (``forceskill.readers.rosbag``).

A package adds a format by declaring its own entry point in the ``forceskill.readers`` group (the
installed packages are scanned only for a suffix no built-in reader knows, which keeps start-up
fast); ``register`` adds or replaces one in-process (tests, scripts).
Reader modules import their heavy dependencies (python-can, cantools, mcap) only inside ``read``.
"""

from __future__ import annotations

import importlib
import math
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import ERR_DEMO_DURATION, ERR_DEMO_FILE, ERR_READ_ARGS, ERR_READER_MISSING, DemoError, FsError

Columns = dict[str, np.ndarray]
TIME_UNITS_S = {"s": 1.0, "ms": 1e-3, "us": 1e-6, "ns": 1e-9}
AXES = ("x", "y", "z")
#: Default longest gap between two samples that is interpolated (a longer one is refused).
MAX_GAP_S = 0.1
#: A reader may return notes for the user (printed on stdout) under this key, as an object array.
NOTES_KEY = "__notes__"
#: Present in a reader's columns when nothing named the time column's unit and it was read as
#: seconds (a refusal of the times then hints at --time-unit).
SECONDS_ASSUMED_KEY = "__seconds_assumed__"
#: The object's mass (kg) a reader found in the recording (a CAN log of ``forceskill record``
#: holds the device's answer with its object model, DID 0x0130), as a one-element array.
OBJECT_MASS_KEY = "__object_mass_kg__"

#: The built-in readers, as declared in host/pyproject.toml.
_BUILTIN = {
    "csv": "forceskill.readers.csv:read",
    "blf": "forceskill.readers.canlog:read",
    "asc": "forceskill.readers.canlog:read",
    "log": "forceskill.readers.canlog:read",
    "trc": "forceskill.readers.canlog:read",
    "db": "forceskill.readers.canlog:read",
    "mf4": "forceskill.readers.canlog:read",
    "gz": "forceskill.readers.gz:read",
    "mcap": "forceskill.readers.rosbag:read",
    "txt": "forceskill.readers.txt:read",
}


@dataclass
class ReadOptions:
    """What a reader needs besides the path; readers ignore the options that are not theirs.

    ``columns`` are the columns the caller needs (a CSV reader parses only those and the time),
    ``optional`` those it uses when present. ``time_column`` None: ``t``, else ``time`` (also with
    a unit: ``t_ms``, ``time [ms]``). ``time_unit`` None: the unit in the time column's header
    (``t [ms]``, ``time_ms``), else seconds. ``rate_hz``: no time column, sample n at n/rate.
    ``topic``/``pose_topic``/``axis``: ROS 2 bags. ``max_duration_s`` is checked as soon as the
    time span is known, before the rest of the file is parsed.
    """

    columns: tuple[str, ...] = ()
    optional: tuple[str, ...] = ()
    time_column: str | None = None
    time_unit: str | None = None
    rate_hz: float | None = None
    topic: str | None = None
    pose_topic: str | None = None
    axis: str = "z"
    max_duration_s: float = 3600.0
    progress: bool = True

    def check(self) -> None:
        """Refuse option values no reader can use (ERR_READ_ARGS)."""
        if self.time_unit is not None and self.time_unit not in TIME_UNITS_S:
            raise FsError(
                ERR_READ_ARGS, f"time unit must be one of {', '.join(TIME_UNITS_S)}: {self.time_unit!r}"
            )
        if self.rate_hz is not None and not (np.isfinite(self.rate_hz) and 0.0 < self.rate_hz <= 1e6):
            raise FsError(ERR_READ_ARGS, f"--rate must be in (0, 1e6] Hz: {self.rate_hz:g}")
        if self.axis not in AXES:
            raise FsError(ERR_READ_ARGS, f"axis must be one of {', '.join(AXES)}: {self.axis!r}")


Reader = Callable[[Path, ReadOptions], Columns]
#: A reader's progress bar appears on stderr only once reading has taken this long.
PROGRESS_DELAY_S = 2.0


class _NoBar:
    def update(self, n: float = 1) -> None:
        pass

    def close(self) -> None:
        pass


class _LateBar:
    """A tqdm bar made (tqdm imported) only once PROGRESS_DELAY_S have passed: a quick read pays
    neither the import nor the bar."""

    def __init__(self, desc: str, total: float | None, unit: str) -> None:
        import time

        self._clock = time.monotonic
        self._t0 = self._clock()
        self._args = (desc, total, unit)
        self._n = 0.0
        self._bar: Any = None

    def update(self, n: float = 1) -> None:
        if self._bar is not None:
            self._bar.update(n)
            return
        self._n += n
        if self._clock() - self._t0 >= PROGRESS_DELAY_S:
            from tqdm import tqdm  # type: ignore[import-untyped,unused-ignore]

            desc, total, unit = self._args
            self._bar = tqdm(total=total, initial=self._n, unit=unit, unit_scale=True, desc=desc, leave=False)
            self._bar.refresh()

    def close(self) -> None:
        if self._bar is not None:
            self._bar.close()


def progress_bar(path: Path, opts: ReadOptions, total: float | None = None, unit: str = "B") -> Any:
    """The reading progress bar of every reader: tqdm on stderr, shown only when reading takes
    more than PROGRESS_DELAY_S (``total`` bytes, or a count of ``unit`` without a total); a bar
    that does nothing when ``opts.progress`` is off. Call ``update(n)`` and ``close()``."""
    if not opts.progress:
        return _NoBar()
    return _LateBar(f"reading {path.name}", total, unit)


_registered: dict[str, Reader] = {}
_entry_points: dict[str, str] | None = None


def register(suffix: str, fn: Reader) -> None:
    """Add (or replace) the reader for files ending in ``suffix`` ('.csv' or 'csv') in this process."""
    _registered[suffix.lower().lstrip(".")] = fn


def _discovered() -> dict[str, str]:
    global _entry_points
    if _entry_points is None:
        from importlib.metadata import entry_points

        _entry_points = {
            ep.name.lower().lstrip("."): ep.value for ep in entry_points(group="forceskill.readers")
        }
    return _entry_points


def known_suffixes() -> list[str]:
    """Every suffix with a reader, with its dot ('.csv')."""
    return sorted("." + s for s in set(_BUILTIN) | set(_discovered()) | set(_registered))


def reader_for(path: Path) -> Reader:
    """The reader for ``path``: the longest suffix with a reader wins ('.log.gz' before '.gz').

    In-process registrations first, then the built-in formats (without scanning the installed
    packages: start-up time), then the ``forceskill.readers`` entry points.
    """
    suffixes = [s.lower().lstrip(".") for s in path.suffixes]
    names = [".".join(suffixes[i:]) for i in range(len(suffixes))]
    for name in names:
        if name in _registered:
            return _registered[name]
        if name in _BUILTIN:
            return _load(name, _BUILTIN[name])
    table = _discovered()
    for name in names:
        if name in table:
            return _load(name, table[name])
    raise DemoError(
        ERR_DEMO_FILE,
        f"no reader for demonstration suffix {path.suffix or '(none)'!r} "
        f"(known: {', '.join(known_suffixes())})",
    )


def _load(name: str, target: str) -> Reader:
    module, _, attr = target.partition(":")
    try:
        fn: Reader = getattr(importlib.import_module(module), attr)
    except (ImportError, AttributeError) as e:
        raise FsError(
            ERR_READER_MISSING, f"the reader for .{name} files ({target}) cannot load: {e}"
        ) from None
    return fn


def read_columns(path: Path, opts: ReadOptions | None = None) -> Columns:
    """Read a recording with the reader for its suffix; refuses a missing file (600)."""
    opts = opts or ReadOptions()
    opts.check()
    reader = reader_for(path)
    if not path.is_file():
        raise DemoError(ERR_DEMO_FILE, f"demonstration file not found: {str(path)!r}")
    return reader(path, opts)


def check_duration(duration_s: float, limit_s: float, source: str, step_s: float | None = None) -> None:
    """Refuse a recording longer than ``limit_s`` (ERR_DEMO_DURATION), before it is parsed further;
    ``step_s``: its median sample step as read, for the hint of a time column in another unit."""
    if duration_s > limit_s:
        hint = time_unit_hint(step_s, duration_s, limit_s) if step_s is not None else ""
        raise DemoError(
            ERR_DEMO_DURATION,
            f"{source} lasts {duration_s:.6g} s, longer than the "
            f"{limit_s:g} s a skill can last"
            + (f"{hint}" if hint else ": split it into a sequence of recordings"),
        )


#: The sample steps a force recording has (10 us..100 ms, 100 kHz..10 Hz): a median step read
#: outside them in seconds names the unit that brings it inside.
PLAUSIBLE_STEP_S = (1e-5, 0.1)


def time_unit_hint(step_s: float, duration_s: float | None = None, limit_s: float | None = None) -> str:
    """'; the median sample step reads 1 s: a time column in milliseconds needs --time-unit ms' when
    a median step (read as seconds) of 0.5 s or more is a plausible step in a smaller unit (and
    the duration then within ``limit_s``); '' otherwise."""
    if not (math.isfinite(step_s) and step_s >= 0.5):
        return ""
    for unit, name in (("ms", "milliseconds"), ("us", "microseconds"), ("ns", "nanoseconds")):
        scale = TIME_UNITS_S[unit]
        lo, hi = PLAUSIBLE_STEP_S
        if lo <= step_s * scale <= hi and (
            duration_s is None or limit_s is None or duration_s * scale <= limit_s
        ):
            return (
                f"; the median sample step reads {step_s:.6g} s: a time column in {name} "
                f"needs --time-unit {unit}"
            )
    return ""

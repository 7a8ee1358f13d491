"""Shared plumbing of the CAN commands: bus options, connecting to a node, telemetry figures."""

from __future__ import annotations

import argparse
import signal
import threading
import time
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import can
import numpy as np

from ..errors import ERR_LINK_TIMEOUT, ERR_LOG_FORMAT, FsError, stdout_closed
from ..link.bus import add_bus_args, describe, error_summary, open_bus
from ..link.device import Device, Sample
from ..outputs import Outputs
from ..wire import TICK_S
from ..wire.telemetry import IDLE_PERIOD_TICKS, fast_stretches


def add_common(p: argparse.ArgumentParser) -> None:
    add_bus_args(p)


@contextmanager
def connect(args: argparse.Namespace) -> Iterator[Device]:
    """Open the bus, start listening, and wait for the node's status frame (presence)."""
    bus, cfg = open_bus(args)
    try:
        with Device(
            bus,
            node=args.node,
            channel=describe(cfg),
            timeout_s=args.timeout,
            fd=bool(cfg.get("fd")),
            request_timeout_s=getattr(args, "request_timeout", None),
        ) as dev:
            dev.wait_present()
            yield dev
    finally:
        bus.shutdown()


#: The telemetry columns of a sample, in Sample's field order after the tick.
TELEMETRY_COLUMNS = ("x", "y", "f_contact", "f_operator", "f_cmd", "f_hat")


@dataclass(frozen=True)
class Stream:
    """Where the columns start (the device tick of row 0), the samples that were due at the
    telemetry's period between the first and the last one received but never arrived (lost on
    the bus or by the adapter: interpolated in the columns, counted here; the ticks between two
    samples of a longer period are interpolated but were never sent, so never counted), and the
    longest time without telemetry beyond that period (ms; a lost sample at 10 ms: 10)."""

    first_tick: int = 0
    lost_samples: int = 0
    longest_gap_ms: int = 0
    received: int = 0


#: The states of a device that acts (its telemetry at the host's period; IDLE's is 100 ms).
ACTIVE_STATES = frozenset({"TEACH", "EXECUTE", "FAULT"})


def active_window(ticks: np.ndarray, states: list[tuple[int, str]]) -> np.ndarray | None:
    """Which of the increasing sample ``ticks`` the device sent while it acted (TEACH, EXECUTE,
    FAULT), judged by its status frames (one every 10 ticks, the state after the tick's control,
    as the telemetry of that tick): the samples after the last IDLE status before the first
    active one, and before the first IDLE status after the last active one. None when no status
    reported an active state."""
    if not states:
        return None
    st = np.array([t for t, _ in states], np.int64)
    act = np.array([s in ACTIVE_STATES for _, s in states])
    order = np.argsort(st, kind="stable")
    st, act = st[order], act[order]
    if not act.any():
        return None
    first, last = int(np.argmax(act)), int(act.size - 1 - np.argmax(act[::-1]))
    idle_before = np.flatnonzero(~act[:first])
    idle_after = np.flatnonzero(~act[last + 1 :])
    lo = int(st[idle_before[-1]]) if idle_before.size else -(1 << 62)
    hi = int(st[last + 1 + idle_after[0]]) if idle_after.size else 1 << 62
    return np.asarray((ticks > lo) & (ticks < hi))


def lost_on_bus(ticks: np.ndarray, period: int) -> tuple[int, int]:
    """(samples lost, longest gap in ms beyond the period) of increasing unique ``ticks`` sent
    every ``period`` ticks: the ticks due are those of the samples' phase (the most common
    tick mod period) from the first to the last of them."""
    period = max(1, int(period))
    phase_of = ticks % period
    phase = int(np.bincount(phase_of).argmax())
    on = ticks[phase_of == phase]
    if on.size < 2:
        return 0, 0
    due = int((on[-1] - on[0]) // period) + 1
    return due - int(on.size), int(np.max(np.diff(on))) - period


def columns(
    samples: list[Sample],
    period: int = 1,
    states: list[tuple[int, str]] | None = None,
    max_rows: int | None = None,
) -> tuple[dict[str, np.ndarray], Stream]:
    """Telemetry streamed every ``period`` ticks (TEACH, EXECUTE: the idle samples around it left
    out) as HIL log columns on the device's 1 ms tick grid (t from the tick), the ticks between
    samples linearly interpolated. With the device's ``states`` (tick, state) the samples kept
    are those it sent while it acted (``active_window``), else the stretches the samples' own
    spacing tells from idle telemetry (a period below the idle one's). Samples due that never
    arrived are counted (``lost_on_bus``); a repeated tick keeps its first sample. ``max_rows``:
    the window's length in ticks from its first sample (the samples after it are left out and
    not counted)."""
    empty = {k: np.zeros(0) for k in ("t", *TELEMETRY_COLUMNS, "band_out")}
    if not samples:
        return empty, Stream()
    tick = np.array([s.tick for s in samples], np.int64)
    values = np.array(
        [(s.x_m, s.y_m, s.f_contact_N, s.f_operator_N, s.f_cmd_N, s.f_ref_N, s.band_out) for s in samples],
        float,
    )
    order = np.argsort(tick, kind="stable")
    got, first = np.unique(tick[order], return_index=True)
    values = values[order[first]]
    window = active_window(got, states) if states else None
    if window is not None:
        got, values = got[window], values[window]
        a, b = 0, got.size  # an idle sample whose status was lost: a step longer than the period
        while b - a >= 2 and got[a + 1] - got[a] > max(1, period) and got[a] % IDLE_PERIOD_TICKS == 0:
            a += 1
        while b - a >= 2 and got[b - 1] - got[b - 2] > max(1, period) and got[b - 1] % IDLE_PERIOD_TICKS == 0:
            b -= 1
        if b - a < 2:
            return empty, Stream()
        got, values = got[a:b], values[a:b]
    else:
        starts, ends = fast_stretches(got)
        if starts.size == 0:
            return empty, Stream()
        got, values = got[starts[0] : ends[-1]], values[starts[0] : ends[-1]]
    if max_rows is not None:
        inside = got < got[0] + max(1, max_rows)
        got, values = got[inside], values[inside]
    grid = np.arange(got[0], got[-1] + 1)
    cols = {"t": (grid - grid[0]) * TICK_S}
    for j, name in enumerate(TELEMETRY_COLUMNS):
        cols[name] = np.interp(grid, got, values[:, j])
    # the band's bit of the nearest sample (a tick between two samples: the earlier one's)
    cols["band_out"] = values[np.searchsorted(got, grid, side="right") - 1, len(TELEMETRY_COLUMNS)]
    lost, longest = lost_on_bus(got, period)
    return cols, Stream(int(got[0]), lost, longest, int(got.size))


def tracking(cols: dict[str, np.ndarray]) -> dict[str, float]:
    """Force tracking figures (docs/hil.md): max/RMS |f_contact - f_hat| in % of max f_hat."""
    f, ref = cols["f_contact"], cols["f_hat"]
    peak = float(np.max(ref)) if ref.size else 0.0
    if peak <= 0.0:
        return {
            "max_force_N": float(np.max(f)) if f.size else 0.0,
            "max_ref_N": peak,
            "tracking_max_pct": float("nan"),
            "tracking_rms_pct": float("nan"),
        }
    e = f - ref
    return {
        "max_force_N": float(np.max(f)),
        "max_ref_N": peak,
        "tracking_max_pct": 100.0 * float(np.max(np.abs(e))) / peak,
        "tracking_rms_pct": 100.0 * float(np.sqrt(np.mean(e * e))) / peak,
    }


class ClosableLog(can.Listener):
    """A log writer that a frame still being handed out by the notifier's thread cannot reach
    once it is stopped: python-can's remove_listener does not wait for a dispatch under way, and
    a write after the writer's file closed raised "I/O operation on closed file"."""

    def __init__(self, writer: Any) -> None:
        self._writer = writer
        self._lock = threading.Lock()
        self._stopped = False

    def on_message_received(self, msg: can.Message) -> None:
        with self._lock:
            if not self._stopped:
                self._writer.on_message_received(msg)

    def stop(self) -> None:
        with self._lock:
            self._stopped = True
            self._writer.stop()

    def __getattr__(self, name: str) -> Any:  # the writer's own attributes (e.g. buffer)
        return getattr(self._writer, name)


def open_log(outs: Outputs, path: str) -> Any:
    """A python-can log writer on the temporary file of ``path`` (committed with ``outs``); a
    suffix python-can cannot write (or whose writer is not installed, e.g. .mf4 without asammdf)
    is refused with 664 before anything is connected."""
    tmp = outs.add(path)
    try:
        return ClosableLog(can.Logger(str(tmp)))
    except Exception as e:  # python-can raises ValueError, NotImplementedError, ImportError
        suffix = "".join(Path(path).suffixes[-2:]) if path.lower().endswith(".gz") else Path(path).suffix
        first = (str(e).splitlines() or [type(e).__name__])[0]
        raise FsError(
            ERR_LOG_FORMAT,
            f"cannot write a CAN log as {suffix or 'a file without suffix'!r} "
            f"({Path(path).name}): {first}; use .blf .asc .log .trc or .csv",
        ) from None


def close_log(writer: Any, timeout_s: float = 10.0) -> None:
    """Stop a python-can log writer with every frame it was given written: the .db writer
    (SqliteWriter) queues frames for a thread whose stop drops what is still queued, so its queue
    is drained first (for at most ``timeout_s``)."""
    queue = getattr(writer, "buffer", None)
    end = time.monotonic() + timeout_s
    while queue is not None and not queue.empty() and time.monotonic() < end:
        time.sleep(0.01)
    writer.stop()


@contextmanager
def sigint_flag() -> Iterator[dict[str, bool]]:
    """Ctrl-C sets flag["stop"] instead of raising, while the block runs (main thread only)."""
    flag = {"stop": False}
    try:
        old = signal.signal(signal.SIGINT, lambda *a: flag.__setitem__("stop", True))
    except ValueError:  # not the main thread: Ctrl-C cannot reach us anyway
        yield flag
        return
    try:
        yield flag
    finally:
        signal.signal(signal.SIGINT, old)


@contextmanager
def link_errors(node: int, channel: str) -> Iterator[None]:
    """A bus failure (OSError, can.CanError) inside the block becomes FsError 635, one line."""
    try:
        yield
    except (OSError, can.CanError) as e:
        if isinstance(e, BrokenPipeError) and stdout_closed():
            raise  # the reader of our output went away, not the bus: the CLI ends quietly
        raise FsError(
            ERR_LINK_TIMEOUT, f"link to node {node} on {channel} lost: {error_summary(e)}"
        ) from None

"""Demonstrations from CAN logs: any python-can log format (.blf .asc .log .trc .csv, as written
by ``forceskill record`` or ``python -m can.logger``) read with ``can.LogReader`` and decoded
through the DBC into the HIL log columns ``t,x,y,f_contact,f_operator,f_cmd,f_hat``.

The demonstration is the longest stretch of telemetry sampled every tick (1 kHz, as in TEACH);
``t`` comes from the device's tick counter (1 ms per tick), not from host timestamps."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import can
import numpy as np

from .. import demo as demo_mod
from ..errors import DemoError
from . import ERR_LINK_LOG
from .dbc import load_db

CAN_SUFFIXES = (".blf", ".asc", ".log", ".trc")
TICK_S = 0.001
POS_BASE = 0x190
FORCE_BASE = 0x1A0


def _is_can_csv(path: Path) -> bool:
    with open(path, encoding="utf-8", errors="replace") as f:
        head = f.readline().strip().lower()
    return head.startswith("timestamp,arbitration_id")


def read_can_log(path: Path, node: int | None = None) -> dict[str, np.ndarray]:
    """Decode a CAN log into demonstration columns (see the module comment)."""
    try:
        msgs = [m for m in can.LogReader(str(path)) if not m.is_error_frame and not m.is_extended_id]
    except Exception as e:
        raise DemoError(ERR_LINK_LOG, f"cannot read CAN log {path.name}: {e}") from None
    ids = [m.arbitration_id for m in msgs]
    if node is None:
        counts = {n: ids.count(POS_BASE + n) for n in range(16)}
        node = max(counts, key=lambda n: counts[n])
        if counts[node] == 0:
            raise DemoError(
                ERR_LINK_LOG, f"no device telemetry (ids 0x190-0x19F) in {path.name} ({len(msgs)} frames)"
            )
    db = load_db(node)
    mpos = db.get_message_by_name("TelemetryPosition")
    mforce = db.get_message_by_name("TelemetryForce")
    rows = []
    pending = None
    wraps, last = 0, -1
    for m in msgs:
        if m.arbitration_id == mpos.frame_id and len(m.data) == 8:
            s: Any = mpos.decode(bytes(m.data))
            raw = int(s["Tick"])
            if last >= 0 and raw < last - 32768:
                wraps += 1
            last = raw
            pending = (raw + 65536 * wraps, float(s["PosX"]), float(s["PosY"]))
        elif m.arbitration_id == mforce.frame_id and len(m.data) == 8 and pending is not None:
            s = mforce.decode(bytes(m.data))
            rows.append(
                (
                    pending[0],
                    pending[1],
                    pending[2],
                    float(s["ForceContact"]),
                    float(s["ForceOperator"]),
                    float(s["ForceCmd"]),
                    float(s["ForceRef"]),
                )
            )
            pending = None
    if len(rows) < 2:
        raise DemoError(ERR_LINK_LOG, f"no telemetry of node {node} in {path.name}")
    a = np.array(rows, dtype=float)
    # longest run sampled every tick
    step = np.diff(a[:, 0])
    breaks = np.flatnonzero(step != 1.0)
    starts = np.concatenate(([0], breaks + 1))
    ends = np.concatenate((breaks + 1, [len(a)]))
    k = int(np.argmax(ends - starts))
    a = a[starts[k] : ends[k]]
    t = (a[:, 0] - a[0, 0]) * TICK_S
    return {
        "t": t,
        "x": a[:, 1],
        "y": a[:, 2],
        "f_contact": a[:, 3],
        "f_operator": a[:, 4],
        "f_cmd": a[:, 5],
        "f_hat": a[:, 6],
        "tick": a[:, 0],
    }


def _reader(path: Path) -> dict[str, np.ndarray]:
    return read_can_log(path)


_csv_reader = demo_mod._READERS.get(".csv")


def _csv(path: Path) -> dict[str, np.ndarray]:
    """python-can CSV logs (header 'timestamp,arbitration_id,...') or the HIL/host CSV."""
    if _is_can_csv(path):
        return read_can_log(path)
    if _csv_reader is None:
        raise DemoError(ERR_LINK_LOG, f"no CSV reader for {path.name}")
    return _csv_reader(path)


def register() -> None:
    """Register the CAN log readers with forceskill.demo (idempotent)."""
    for suf in CAN_SUFFIXES:
        demo_mod.register_reader(suf, _reader)
    if _csv_reader is not None and _csv_reader is not _csv:
        demo_mod.register_reader(".csv", _csv)


register()

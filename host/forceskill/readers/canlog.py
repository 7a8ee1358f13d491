"""Demonstrations from CAN logs: any python-can log format (.blf .asc .log .trc .csv .db .mf4, as written by
``forceskill record`` or ``python -m can.logger``), also gzip-compressed (``.asc.gz``), decoded
through the DBC into the HIL log columns ``t,x,y,f_contact,f_operator,f_cmd,f_hat``.

``t`` comes from the device's tick counter (1 ms per tick), not from host timestamps. The device
streams telemetry at the host's period in TEACH (every tick by default, up to 100 ms with
``record --telemetry-period``) and every 100 ms otherwise: the demonstration is told from the
idle telemetry by the device's status frames (state TEACH and their tick, every 10 ms), as
``run`` tells its execution: the samples after the last status before a stretch of TEACH
statuses and before the first status after it. Lost frames stay lost here (the samples around
them are kept with their ticks; ``demo.validate`` refuses a gap above --max-gap, ``resample``
interpolates shorter ones). When the log holds several TEACH stretches the longest is used and a
note says so. A log without TEACH status frames (another logger's, filtered) falls back to the
samples' spacing: the stretches streamed faster than the idle telemetry.

python-can writes one format it cannot read back: ``.txt`` (``can.Printer``); ``forceskill.readers.txt``
refuses such a log by name.
"""

from __future__ import annotations

import gzip
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from ..codes import CAN_ID_STATUS, CAN_ID_TELEM_FORCE, CAN_ID_TELEM_POS, DID_OBJECT, UDS_RESPONSE_BASE
from ..errors import ERR_LINK_LOG, ERR_READER_MISSING, DemoError
from ..wire import TICK_S
from . import NOTES_KEY, OBJECT_MASS_KEY, Columns, ReadOptions, progress_bar

POS_BASE = CAN_ID_TELEM_POS
FORCE_BASE = CAN_ID_TELEM_FORCE
STATUS_BASE = CAN_ID_STATUS
STATE_TEACH = 2


#: Frames between two updates of the progress bar.
_BAR_EVERY = 4096


def _messages(path: Path, opts: ReadOptions) -> list[Any]:
    import can

    suffixes = [s.lower() for s in path.suffixes]
    try:
        if suffixes and suffixes[-1] == ".gz":
            inner = suffixes[-2] if len(suffixes) > 1 else ""
            reader_cls = can.io.player.MESSAGE_READERS.get(inner)
            if reader_cls is None:
                raise ValueError(f"no python-can reader for {inner or '(none)'}.gz")
            fobj = gzip.open(path, mode="rb" if inner == ".blf" else "rt")  # noqa: SIM115 (closed by the reader)
            reader = reader_cls(fobj)  # type: ignore[arg-type]
        else:
            reader = can.LogReader(str(path))
        bar = progress_bar(path, opts, unit=" frames")
        out = []
        try:
            with reader:
                for i, m in enumerate(reader, 1):
                    if not m.is_error_frame and not m.is_extended_id:
                        out.append(m)
                    if not i % _BAR_EVERY:
                        bar.update(_BAR_EVERY)
        finally:
            bar.close()
        return out
    except DemoError:
        raise
    except (NotImplementedError, ImportError) as e:  # python-can's MF4 reader without asammdf
        raise DemoError(
            ERR_READER_MISSING,
            f"cannot read CAN log {path.name}: {e} (pip install asammdf, or forceskill[mf4])",
        ) from None
    except Exception as e:
        raise DemoError(ERR_LINK_LOG, f"cannot read CAN log {path.name}: {e}") from None


def read(path: Path, opts: ReadOptions | None = None, node: int | None = None) -> Columns:
    """Decode a CAN log into demonstration columns (see the module comment)."""
    from ..wire.dbc import load_db
    from ..wire.telemetry import TelemetryPairer

    msgs = _messages(path, opts or ReadOptions())
    ids = np.array([m.arbitration_id for m in msgs], dtype=np.int64)
    if node is None:
        counts = [int(np.count_nonzero(ids == POS_BASE + n)) for n in range(16)]
        node = int(np.argmax(counts))
        if counts[node] == 0:
            raise DemoError(
                ERR_LINK_LOG, f"no device telemetry (ids 0x190-0x19F) in {path.name} ({len(msgs)} frames)"
            )
    db = load_db(node)
    mpos = db.get_message_by_name("TelemetryPosition")
    mforce = db.get_message_by_name("TelemetryForce")
    mstat = db.get_message_by_name("DeviceStatus")
    rows = []
    uds: list[bytes] = []  # the device's UDS response frames (its object model among them)
    leave_teach = []  # message index of status frames with the device not in TEACH
    status: list[tuple[int, int, bool]] = []  # (message index, 24-bit tick, in TEACH) of each status
    pairs: TelemetryPairer[tuple[int, float, float, int]] = TelemetryPairer()
    wraps, last = 0, -1
    for i, m in enumerate(msgs):
        fid = m.arbitration_id
        if fid == mpos.frame_id and len(m.data) == 8:
            s: Any = mpos.decode(bytes(m.data))
            raw = int(s["Tick"])
            if last >= 0 and raw < last - 32768:
                wraps += 1
            last = raw
            pairs.position((raw + 65536 * wraps, float(s["PosX"]), float(s["PosY"]), i))
        elif fid == mforce.frame_id and len(m.data) == 8:
            pending = pairs.force()
            if pending is None:
                continue
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
                    pending[3],
                )
            )
        elif fid == UDS_RESPONSE_BASE + node:
            uds.append(bytes(m.data))
        elif fid == mstat.frame_id and len(m.data) == 8:
            try:
                st: Any = mstat.decode(bytes(m.data), decode_choices=False)
            except Exception:
                continue
            teach = int(st["State"]) == STATE_TEACH
            status.append((i, int(st["Tick"]), teach))
            if not teach:
                leave_teach.append(i)
    if len(rows) < 2:
        raise DemoError(ERR_LINK_LOG, f"no telemetry of node {node} in {path.name}")
    a = np.array(rows, dtype=float)
    a = a[np.concatenate(([True], np.diff(a[:, 0]) > 0.0))]  # a repeated tick: keep the first
    found = _teach_by_status(a, np.array(status, dtype=np.int64).reshape(-1, 3), path.name)
    if found is None:
        found = _demonstration(a, np.array(leave_teach, dtype=float), path.name)
    start, end, notes = found
    a = a[start:end]
    t = (a[:, 0] - a[0, 0]) * TICK_S
    cols = {
        "t": t,
        "x": a[:, 1],
        "y": a[:, 2],
        "f_contact": a[:, 3],
        "f_operator": a[:, 4],
        "f_cmd": a[:, 5],
        "f_hat": a[:, 6],
        "tick": a[:, 0],
    }
    mass = object_mass(uds)
    if mass is not None:
        cols[OBJECT_MASS_KEY] = np.array([mass])
    if notes:
        cols[NOTES_KEY] = np.array(notes, dtype=object)
    return cols


def isotp_messages(frames: list[bytes]) -> list[bytes]:
    """The ISO-TP messages of one identifier's frames in bus order (single frames, classic or
    FD, and first + consecutive frames; flow control and broken sequences skipped)."""
    out: list[bytes] = []
    buf: bytearray | None = None
    need = 0
    for d in frames:
        if not d:
            continue
        pci = d[0] >> 4
        if pci == 0:
            n = d[0] & 0x0F
            if n == 0 and len(d) > 8:  # CAN FD single frame: the length in the second byte
                out.append(d[2 : 2 + d[1]])
            else:
                out.append(d[1 : 1 + n])
            buf = None
        elif pci == 1 and len(d) >= 2:
            need = ((d[0] & 0x0F) << 8) | d[1]
            buf = bytearray(d[2:])
        elif pci == 2 and buf is not None:
            buf += d[1:]
            if len(buf) >= need:
                out.append(bytes(buf[:need]))
                buf = None
    return out


def object_mass(uds_frames: list[bytes]) -> float | None:
    """The object's mass (kg) in the device's last answer with its object model (DID 0x0130)
    among its UDS response frames, when the device uses the model; None otherwise."""
    from ..wire import Object

    head = bytes([0x62, DID_OBJECT >> 8, DID_OBJECT & 0xFF])
    for msg in reversed(isotp_messages(uds_frames)):
        if msg[:3] == head:
            try:
                obj = Object.unpack(msg[3:])
            except Exception:  # a malformed answer: no mass known
                return None
            return float(obj.m_v_kg) if obj.use_model and obj.m_v_kg > 0.0 else None
    return None


def _demonstration(a: np.ndarray, leave_idx: np.ndarray, name: str) -> tuple[int, int, list[str]]:
    """Rows [start, end) of the demonstration in telemetry rows ``a`` (tick, ..., message index)."""
    from ..wire.telemetry import fast_stretches

    starts, ends = fast_stretches(a[:, 0])
    if starts.size == 0:
        raise DemoError(ERR_LINK_LOG, f"no telemetry streamed every tick (TEACH) in {name}")
    # join neighbouring stretches unless the device left TEACH between them
    groups: list[list[int]] = [[int(starts[0]), int(ends[0])]]
    for s, e in zip(starts[1:], ends[1:], strict=False):
        prev_end_msg, next_msg = a[groups[-1][1] - 1, 7], a[s, 7]
        left = np.any((leave_idx > prev_end_msg) & (leave_idx < next_msg))
        if left:
            groups.append([int(s), int(e)])
        else:
            groups[-1][1] = int(e)
    return _longest(a, groups, name)


def _longest(a: np.ndarray, groups: Sequence[Sequence[int]], name: str) -> tuple[int, int, list[str]]:
    """The longest of the demonstrations' row ranges ``groups`` in telemetry rows ``a`` (unwrapped
    tick first), with a note naming them all when there are several."""
    if len(groups) == 1:
        return int(groups[0][0]), int(groups[0][1]), []
    lengths = [(a[e - 1, 0] - a[s, 0]) * TICK_S for s, e in groups]
    k = int(np.argmax(lengths))
    spans = ", ".join(
        f"{(a[s, 0] - a[0, 0]) * TICK_S:.3f}-{(a[e - 1, 0] - a[0, 0]) * TICK_S:.3f} s" for s, e in groups
    )
    note = (
        f"{name} holds {len(groups)} demonstrations (log time {spans}): using the longest, "
        f"number {k + 1} ({lengths[k]:.3f} s)"
    )
    return int(groups[k][0]), int(groups[k][1]), [note]


def _teach_by_status(a: np.ndarray, status: np.ndarray, name: str) -> tuple[int, int, list[str]] | None:
    """Rows [start, end) of the demonstration in telemetry rows ``a`` (unwrapped tick, ...,
    message index) by the device's status frames ``status`` (message index, 24-bit tick, TEACH):
    for each stretch of consecutive TEACH statuses, the samples whose tick lies after the
    preceding status's tick and before the following one's (the status tick unwrapped against
    the telemetry received just before it), idle samples at its edges trimmed (a step longer than
    the stretch's period on the idle grid). The longest stretch when there are several (noted).
    None when no status says TEACH."""
    from ..wire.telemetry import IDLE_PERIOD_TICKS

    if status.size == 0 or not status[:, 2].any():
        return None
    # each status's tick on the telemetry's unwrapped axis
    j = np.clip(np.searchsorted(a[:, 7], status[:, 0]) - 1, 0, a.shape[0] - 1)
    ref = a[j, 0].astype(np.int64)
    d = (status[:, 1] - ref) & 0xFFFF
    tick = ref + np.where(d >= 32768, d - 65536, d)
    teach = status[:, 2].astype(bool)
    edges = np.flatnonzero(np.diff(np.concatenate(([0], teach.astype(np.int8), [0]))))
    ticks = a[:, 0]
    groups: list[tuple[int, int]] = []
    for p, q in zip(edges[::2], edges[1::2], strict=True):  # statuses [p, q) in TEACH
        lo = tick[p - 1] if p > 0 else -np.inf
        hi = tick[q] if q < tick.size else np.inf
        s, e = int(np.searchsorted(ticks, lo, side="right")), int(np.searchsorted(ticks, hi, side="left"))
        if e - s >= 2:
            period = max(1.0, float(np.median(np.diff(ticks[s:e]))))
            while e - s >= 2 and ticks[s + 1] - ticks[s] > period and ticks[s] % IDLE_PERIOD_TICKS == 0:
                s += 1
            while (
                e - s >= 2 and ticks[e - 1] - ticks[e - 2] > period and ticks[e - 1] % IDLE_PERIOD_TICKS == 0
            ):
                e -= 1
        if e - s >= 2:
            groups.append((s, e))
    if not groups:
        raise DemoError(ERR_LINK_LOG, f"no telemetry while the device was in TEACH in {name}")
    return _longest(a, groups, name)

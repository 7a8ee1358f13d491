"""Realistic force recordings made by the tests themselves, and writers for the formats people use.

A recording is time (s), force (N, pushing positive) and position (m, into the object) as a wrist
F/T sensor or a device logs them: smooth presses and multi-stroke wiping at 20 Hz..2 kHz, with the
defects of real logs added one at a time (sensor bias, the negative Fz sign, timer jitter, lost
samples, a long gap, steps within one sample, single-sample spikes, a stuck sensor, noise).
Writers: CSV in its common dialects, python-can CAN logs through the device DBC, ROS 2 bags
(MCAP, geometry_msgs/WrenchStamped and PoseStamped) with mcap-ros2-support's writer.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

SURFACE_M = 0.002
OBJECT_K_NPM = 2000.0


@dataclass
class Rec:
    """One recording: time (s), force (N), position (m)."""

    t: np.ndarray
    f: np.ndarray
    x: np.ndarray


def _smooth(s: np.ndarray) -> np.ndarray:
    s = np.clip(s, 0.0, 1.0)
    return 0.5 - 0.5 * np.cos(np.pi * s)


def _times(duration_s: float, rate_hz: float) -> np.ndarray:
    return np.arange(int(round(duration_s * rate_hz)) + 1) / rate_hz


def _pos(f: np.ndarray) -> np.ndarray:
    return SURFACE_M + np.maximum(f, 0.0) / OBJECT_K_NPM


def press(
    duration_s: float = 8.0,
    rate_hz: float = 100.0,
    peak_N: float = 20.0,
    seed: int = 0,
    t: np.ndarray | None = None,
) -> Rec:
    """Quiet 0.5 s, ramp to a hold, a second higher level, release before the end."""
    rng = np.random.default_rng(seed)
    t = _times(duration_s, rate_hz) if t is None else t
    lo = peak_N * rng.uniform(0.5, 0.7)
    a, b = 0.5, 0.5 + 0.2 * duration_s
    c = 0.45 * duration_s
    f = lo * _smooth((t - a) / (b - a)) + (peak_N - lo) * _smooth((t - c) / (0.2 * duration_s))
    f = f * (1.0 - _smooth((t - 0.85 * duration_s) / (0.1 * duration_s)))
    return Rec(t, f, _pos(f))


def strokes(
    n: int = 13, duration_s: float = 73.0, rate_hz: float = 100.0, peak_N: float = 15.0, seed: int = 0
) -> Rec:
    """Wiping: n contacts of random height, each a raised-cosine stroke, with lifts in between."""
    rng = np.random.default_rng(seed)
    t = _times(duration_s, rate_hz)
    f = np.zeros_like(t)
    period = (duration_s - 1.0) / n
    for i in range(n):
        t0 = 0.5 + i * period
        s = (t - t0) / (0.8 * period)
        inside = (s >= 0.0) & (s <= 1.0)
        f[inside] += peak_N * rng.uniform(0.6, 1.0) * np.sin(np.pi * s[inside]) ** 2
    return Rec(t, f, _pos(f))


def jittered_times(duration_s: float, lo_ms: float, hi_ms: float, seed: int = 0) -> np.ndarray:
    """Sample times with steps drawn uniformly in [lo_ms, hi_ms] (a timer that jitters)."""
    rng = np.random.default_rng(seed)
    steps = rng.uniform(lo_ms, hi_ms, int(duration_s / (lo_ms * 1e-3)) + 2) * 1e-3
    t = np.concatenate(([0.0], np.cumsum(steps)))
    return t[t <= duration_s]


def with_bias(r: Rec, bias_N: float) -> Rec:
    return replace(r, f=r.f + bias_N)


def with_sign(r: Rec) -> Rec:
    """The usual Fz convention: a push reads negative."""
    return replace(r, f=-r.f)


def with_noise(r: Rec, sigma_N: float, seed: int = 0) -> Rec:
    return replace(r, f=r.f + np.random.default_rng(seed).normal(0.0, sigma_N, r.f.size))


def with_dropouts(r: Rec, n: int, max_len: int = 3, seed: int = 0) -> Rec:
    """Lose n short runs (1..max_len samples) at random places after the first second."""
    rng = np.random.default_rng(seed)
    keep = np.ones(r.t.size, bool)
    first = int(np.searchsorted(r.t, 1.0))
    for i in rng.choice(np.arange(first, r.t.size - max_len - 1), n, replace=False):
        keep[i : i + rng.integers(1, max_len + 1)] = False
    return Rec(r.t[keep], r.f[keep], r.x[keep])


def with_gap(r: Rec, at_s: float, length_s: float) -> Rec:
    """Lose every sample in (at_s, at_s + length_s)."""
    keep = ~((r.t > at_s) & (r.t < at_s + length_s))
    return Rec(r.t[keep], r.f[keep], r.x[keep])


def with_step(r: Rec, at_s: float, height_N: float) -> Rec:
    """A force step between two samples (faster than the sample rate)."""
    f = r.f + height_N * (r.t >= at_s) * (r.t < r.t[-1] * 0.8)
    return Rec(r.t, f, _pos(f))


def with_spikes(r: Rec, times_s: Sequence[float], height_N: float) -> Rec:
    """Single-sample spikes (a glitching sensor) at the samples nearest ``times_s``."""
    f = r.f.copy()
    for ts in times_s:
        f[int(np.argmin(np.abs(r.t - ts)))] += height_N
    return replace(r, f=f)


def with_stuck(r: Rec, from_s: float, length_s: float) -> Rec:
    """The sensor repeats one reading from ``from_s`` for ``length_s``."""
    f = r.f.copy()
    i = int(np.searchsorted(r.t, from_s))
    j = int(np.searchsorted(r.t, from_s + length_s))
    f[i:j] = f[i]
    return replace(r, f=f)


# ---- writers ----------------------------------------------------------------------------------


def write_csv(
    path: Path,
    r: Rec,
    *,
    delimiter: str = ",",
    names: Sequence[str] = ("t", "x", "f_contact"),
    time_scale: float = 1.0,
    bom: bool = False,
    comments: Sequence[str] = (),
    decimal_comma: bool = False,
    with_time: bool = True,
    with_position: bool = True,
    line_end: str = "\n",
) -> Path:
    """One recording as a CSV dialect: names for (time, position, force) in the header."""
    cols = []
    header = []
    if with_time:
        cols.append(r.t * time_scale)
        header.append(names[0])
    if with_position:
        cols.append(r.x)
        header.append(names[1])
    cols.append(r.f)
    header.append(names[2])
    lines = [f"# {c}" for c in comments] + [delimiter.join(header)]
    for row in np.column_stack(cols):
        cells = [f"{v:.9g}" for v in row]
        if decimal_comma:
            cells = [c.replace(".", ",") for c in cells]
        lines.append(delimiter.join(cells))
    text = line_end.join(lines) + line_end
    path.write_bytes((b"\xef\xbb\xbf" if bom else b"") + text.encode())
    return path


def write_can_log(
    path: Path,
    r: Rec,
    *,
    node: int = 0,
    drop_ticks: Sequence[int] = (),
    sessions: int = 1,
    busy_every: int = 0,
    period: int = 1,
) -> Path:
    """A python-can log (any suffix it writes, .gz too) of the device's telemetry at 1 kHz in
    TEACH (every ``period`` ticks: ``record --telemetry-period``), status frames every 10 ms, idle
    telemetry every 100 ms before and after; ``r`` must be sampled at 1 kHz. ``drop_ticks``: telemetry frames lost on the bus. ``sessions`` > 1 repeats
    the demonstration with IDLE in between. ``busy_every`` > 0: the bus is busy for 8 ticks in
    every ``busy_every``, so the positions of those ticks pass their force frames (a controller
    with several mailboxes sends the lowest identifier first)."""
    import can

    from forceskill.wire.dbc import load_db

    db = load_db(node)
    mpos, mforce = db.get_message_by_name("TelemetryPosition"), db.get_message_by_name("TelemetryForce")
    mstat = db.get_message_by_name("DeviceStatus")
    dropped = {int(d) for d in drop_ticks}
    tick = 1000
    msgs: list[can.Message] = []

    held: list[can.Message] = []  # force frames waiting while the bus is busy

    def emit(state: int, ticks: range, rows: np.ndarray | None) -> None:
        for k, tk in enumerate(ticks):
            busy = rows is not None and busy_every > 0 and (tk - ticks.start) % busy_every < 8
            if not busy:
                msgs.extend(held)
                held.clear()
            ts = tk * 1e-3
            if tk % 10 == 0:
                data = mstat.encode(
                    {
                        "State": state,
                        "Slot": 0,
                        "FaultCode": 0,
                        "Tick": tk & 0xFFFFFF,
                        "Counter": 0,
                        "ActuatorEnabled": 0,
                        "HostAlive": 1,
                        "SequenceStep": 0,
                        "Crc": 0,
                    }
                )
                msgs.append(
                    can.Message(timestamp=ts, arbitration_id=mstat.frame_id, data=data, is_extended_id=False)
                )
            if tk % (100 if rows is None else period):
                continue
            if rows is not None and (tk - ticks.start) in dropped:
                continue
            x, f = (0.0, 0.0) if rows is None else (float(rows[k, 0]), float(rows[k, 1]))
            msgs.append(
                can.Message(
                    timestamp=ts,
                    arbitration_id=mpos.frame_id,
                    is_extended_id=False,
                    data=mpos.encode({"PosX": x, "PosY": 0.0, "BandOutside": 0, "Tick": tk & 0xFFFF}),
                )
            )
            (held if busy else msgs).append(
                can.Message(
                    timestamp=ts,
                    arbitration_id=mforce.frame_id,
                    is_extended_id=False,
                    data=mforce.encode(
                        {"ForceContact": f, "ForceOperator": f, "ForceCmd": 0.0, "ForceRef": 0.0}
                    ),
                )
            )

    rows = np.column_stack((r.x, r.f))
    for _ in range(sessions):
        emit(1, range(tick, tick + 500), None)
        tick += 500
        emit(2, range(tick, tick + rows.shape[0]), rows)
        tick += rows.shape[0]
    emit(1, range(tick, tick + 500), None)
    from forceskill.commands._common import close_log

    w = can.Logger(str(path))
    for m in msgs:
        w.on_message_received(m)
    close_log(w)  # the .db writer drops what is still queued when stopped
    return path


_SEP = "=" * 80
_HEADER_DEFS = f"""{_SEP}
MSG: std_msgs/Header
builtin_interfaces/Time stamp
string frame_id
{_SEP}
MSG: builtin_interfaces/Time
int32 sec
uint32 nanosec
"""
_XYZ = "float64 x\nfloat64 y\nfloat64 z\n"
WRENCH_MSGDEF = (
    f"std_msgs/Header header\ngeometry_msgs/Wrench wrench\n{_HEADER_DEFS}"
    f"{_SEP}\nMSG: geometry_msgs/Wrench\ngeometry_msgs/Vector3 force\ngeometry_msgs/Vector3 torque\n"
    f"{_SEP}\nMSG: geometry_msgs/Vector3\n{_XYZ}"
)
POSE_MSGDEF = (
    f"std_msgs/Header header\ngeometry_msgs/Pose pose\n{_HEADER_DEFS}"
    f"{_SEP}\nMSG: geometry_msgs/Pose\ngeometry_msgs/Point position\ngeometry_msgs/Quaternion orientation\n"
    f"{_SEP}\nMSG: geometry_msgs/Point\n{_XYZ}{_SEP}\nMSG: geometry_msgs/Quaternion\n{_XYZ}float64 w\n"
)


def write_bag(
    path: Path,
    r: Rec,
    *,
    topic: str = "/wrench",
    pose_topic: str | None = "/pose",
    axis: str = "z",
    t0_ns: int = 1_700_000_000_000_000_000,
    extra_wrench: str | None = None,
    y_path: np.ndarray | None = None,
) -> Path:
    """A ROS 2 bag (MCAP): the force on ``axis`` of a WrenchStamped topic (the other axes carry
    other values), the position on a PoseStamped topic at half the rate. ``extra_wrench``: a
    second WrenchStamped topic; ``y_path``: the pose's y along the recording (else 0.2)."""
    from mcap_ros2.writer import Writer

    def stamp(ts: float) -> dict[str, object]:
        ns = t0_ns + int(round(ts * 1e9))
        return {"stamp": {"sec": ns // 1_000_000_000, "nanosec": ns % 1_000_000_000}, "frame_id": "ft"}

    with open(path, "wb") as fh:
        w = Writer(fh)
        ws = w.register_msgdef("geometry_msgs/msg/WrenchStamped", WRENCH_MSGDEF)
        ps = w.register_msgdef("geometry_msgs/msg/PoseStamped", POSE_MSGDEF)
        for i, (ts, f, x) in enumerate(zip(r.t, r.f, r.x, strict=False)):
            force = {"x": 1.5, "y": -2.5, "z": 7.0}
            force[axis] = float(f)
            log_ns = t0_ns + int(round(ts * 1e9)) + 300_000
            msg = {
                "header": stamp(float(ts)),
                "wrench": {"force": force, "torque": {"x": 0.0, "y": 0.0, "z": 0.0}},
            }
            w.write_message(topic, ws, msg, log_time=log_ns, publish_time=log_ns, sequence=i)
            if extra_wrench:
                w.write_message(extra_wrench, ws, msg, log_time=log_ns, publish_time=log_ns, sequence=i)
            if pose_topic and i % 2 == 0:
                pos = {"x": 0.1, "y": 0.2 if y_path is None else float(y_path[i]), "z": 0.3}
                pos[axis] = float(x)
                w.write_message(
                    pose_topic,
                    ps,
                    {
                        "header": stamp(float(ts)),
                        "pose": {"position": pos, "orientation": {"x": 0.0, "y": 0.0, "z": 0.0, "w": 1.0}},
                    },
                    log_time=log_ns,
                    publish_time=log_ns,
                    sequence=i,
                )
        w.finish()
    return path


def _write_wiping(path: Path, path_m: float) -> Path:
    """synthetic.wiping_strokes(seed=5, noise_N=0.02[, path_m]): t,x,f_contact[,y]."""
    from forceskill.model import synthetic

    d = synthetic.wiping_strokes(seed=5, noise_N=0.02, path_m=path_m)
    cols, names = [d.t_s, d.pos_m, d.force_N], "t,x,f_contact"
    if d.y_m is not None:
        cols, names = [*cols, d.y_m], names + ",y"
    np.savetxt(path, np.column_stack(cols), delimiter=",", header=names, comments="", fmt="%.9g")
    return path


def _write_pressing_set(folder: Path) -> list[Path]:
    """synthetic.pressing_set(seed=1)'s six recordings as d0.csv .. d5.csv (d1 gzip-compressed:
    d1.csv.gz) and an engraving that is no such press as odd.csv: t,x,f_contact."""
    import gzip

    from forceskill.model import synthetic
    from forceskill.model.demo import Demo, write_csv

    _, demos = synthetic.pressing_set(seed=1)
    odd = synthetic.engraving(seed=4, duration_s=6.5, k_v=100.0, f_max_N=4.5, noise_N=0.03)

    def csv(path: Path, d: Demo) -> Path:
        write_csv(path, {"t": d.t_s, "x": d.pos_m, "f_contact": d.force_N})
        return path

    out = [csv(folder / f"d{i}.csv", d) for i, d in enumerate(demos)]
    out[1] = folder / "d1.csv.gz"
    out[1].write_bytes(gzip.compress((folder / "d1.csv").read_bytes()))
    (folder / "d1.csv").unlink()
    return [*out, csv(folder / "odd.csv", odd)]


def write_examples(folder: Path) -> list[Path]:
    """The recordings README.md's and docs/cli.md's examples use: press100.csv (100 Hz),
    fz_bias.csv (push reads negative, -0.8 N bias, ms time column, ';' and decimal commas),
    step20hz.csv, strokes.csv (73 s, 13 strokes), wrench.mcap (ROS 2 bag), wipe.csv and
    wipe_y.csv (12 wiping strokes of 1.2 s, the second with a y path), wipe.mcap (13 strokes in a
    ROS 2 bag, the push reading negative with a +0.8 N bias), and six presses of one task with an
    outlier (d0.csv, d1.csv.gz, d2.csv .. d5.csv, odd.csv: the several-recordings fit)."""
    folder.mkdir(parents=True, exist_ok=True)
    out = [
        write_csv(folder / "press100.csv", with_noise(press(rate_hz=100), 0.05)),
        write_csv(
            folder / "fz_bias.csv",
            with_sign(with_bias(with_noise(press(rate_hz=100), 0.03), 0.8)),
            names=("time [ms]", "z", "Fz (N)"),
            time_scale=1e3,
            delimiter=";",
            decimal_comma=True,
            with_position=False,
        ),
        write_csv(folder / "step20hz.csv", with_step(press(rate_hz=20), 4.0, 8.0)),
        write_csv(folder / "strokes.csv", strokes()),
        _write_wiping(folder / "wipe.csv", 0.0),
        _write_wiping(folder / "wipe_y.csv", 0.03),
        *_write_pressing_set(folder),
    ]
    try:
        out.append(write_bag(folder / "wrench.mcap", with_noise(press(rate_hz=100), 0.05)))
        out.append(write_bag(folder / "wipe.mcap", with_sign(with_bias(with_noise(strokes(), 0.05), 0.8))))
    except ImportError:
        pass
    return out


if __name__ == "__main__":
    import sys

    for p in write_examples(Path(sys.argv[1] if len(sys.argv) > 1 else "recordings")):
        print(p)

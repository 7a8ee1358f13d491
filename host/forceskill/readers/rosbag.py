"""ROS 2 bags in MCAP (``mcap`` and ``mcap-ros2-support``, the ``ros`` extra of the host package).

The force is one axis (``--axis``, z by default) of ``wrench.force`` on a geometry_msgs/WrenchStamped
topic (``--topic``; without it the bag's only WrenchStamped topic). ``t`` is the message's header
stamp (the log time when the stamp is zero), relative to the first message. ``--pose-topic`` adds
the position ``x``: the same axis of a geometry_msgs/PoseStamped (``pose.position``) or
PointStamped (``point``) topic, interpolated at the force's times. Columns: ``t``, ``f_contact``
(the force axis, so the default ``--learn contact`` picks it), ``x`` with a pose topic, and every
axis of the pose as ``pose_x``, ``pose_y``, ``pose_z`` (``fit --y-column pose_y`` learns the path
along y from it).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from ..errors import ERR_DEMO_FORMAT, ERR_DEMO_TOPIC, ERR_READER_MISSING, DemoError, FsError
from . import NOTES_KEY, Columns, ReadOptions, check_duration, progress_bar

WRENCH = "geometry_msgs/msg/WrenchStamped"
POSES = {"geometry_msgs/msg/PoseStamped": ("pose", "position"), "geometry_msgs/msg/PointStamped": ("point",)}


def _norm(datatype: str) -> str:
    """'geometry_msgs/WrenchStamped' and 'geometry_msgs/msg/WrenchStamped' name the same type."""
    parts = datatype.split("/")
    return f"{parts[0]}/msg/{parts[-1]}" if len(parts) == 2 else datatype


def _stamp_ns(msg: Any, log_time_ns: int) -> int:
    st = msg.header.stamp
    ns = int(st.sec) * 1_000_000_000 + int(st.nanosec)
    return ns if ns > 0 else int(log_time_ns)


def read(path: Path, opts: ReadOptions) -> Columns:
    """Force (and position) columns from a ROS 2 bag (see the module comment)."""
    try:
        from mcap.reader import make_reader
        from mcap_ros2.decoder import DecoderFactory
    except ImportError as e:
        raise FsError(
            ERR_READER_MISSING,
            f"reading {path.name} needs the mcap and mcap-ros2-support packages "
            f"(pip install 'forceskill[ros]'): {e}",
        ) from None
    with open(path, "rb") as fh:
        try:
            reader = make_reader(fh, decoder_factories=[DecoderFactory()])
            summary = reader.get_summary()
        except Exception as e:
            raise DemoError(ERR_DEMO_FORMAT, f"{path.name} is not a readable MCAP file: {e}") from None
        if summary is None:
            raise DemoError(
                ERR_DEMO_FORMAT, f"{path.name}: MCAP file without a summary (unfinished recording?)"
            )
        types = {
            ch.topic: _norm(summary.schemas[ch.schema_id].name) if ch.schema_id in summary.schemas else "?"
            for ch in summary.channels.values()
        }
        listing = ", ".join(f"{t} ({ty})" for t, ty in sorted(types.items())) or "none"
        topic = opts.topic
        if topic is None:
            wrenches = [t for t, ty in types.items() if ty == WRENCH]
            if len(wrenches) != 1:
                raise DemoError(
                    ERR_DEMO_TOPIC,
                    f"{path.name} has {len(wrenches)} {WRENCH} topics: choose one "
                    f"with --topic (topics: {listing})",
                )
            topic = wrenches[0]
        for name, allowed in ((topic, (WRENCH,)), (opts.pose_topic, tuple(POSES))):
            if name is None:
                continue
            if name not in types:
                raise DemoError(ERR_DEMO_TOPIC, f"topic {name!r} not in {path.name} (topics: {listing})")
            if types[name] not in allowed:
                raise DemoError(
                    ERR_DEMO_TOPIC,
                    f"topic {name!r} in {path.name} is {types[name]}, not {' or '.join(allowed)}",
                )
        wanted = [topic] + ([opts.pose_topic] if opts.pose_topic else [])
        force_t, force, pose_t, pose = [], [], [], []
        pose_xyz: list[tuple[float, float, float]] = []
        bar = progress_bar(path, opts, unit=" msgs")
        try:
            for i, (_, channel, message, msg) in enumerate(
                reader.iter_decoded_messages(topics=wanted, log_time_order=True), 1
            ):
                if not i % 1024:
                    bar.update(1024)
                if channel.topic == topic:
                    force_t.append(_stamp_ns(msg, message.log_time))
                    force.append(float(getattr(msg.wrench.force, opts.axis)))
                else:
                    obj = msg
                    for attr in POSES[types[channel.topic]]:
                        obj = getattr(obj, attr)
                    pose_t.append(_stamp_ns(msg, message.log_time))
                    pose.append(float(getattr(obj, opts.axis)))
                    pose_xyz.append((float(obj.x), float(obj.y), float(obj.z)))
        except Exception as e:
            raise DemoError(ERR_DEMO_FORMAT, f"{path.name}: cannot decode {topic}: {e}") from None
        finally:
            bar.close()
    if len(force) < 2:
        raise DemoError(ERR_DEMO_TOPIC, f"topic {topic!r} in {path.name} has {len(force)} messages")
    t_ns = np.array(force_t, dtype=np.int64)
    order = np.argsort(t_ns, kind="stable")
    t0_ns = int(t_ns[order[0]])
    t = (t_ns[order] - t0_ns) * 1e-9  # relative first: float64 seconds since 1970 lose 0.2 us
    f = np.array(force)[order]
    check_duration(float(t[-1]), opts.max_duration_s, path.name)
    cols: Columns = {"t": t, "f_contact": f}
    notes = [f"{path.name}: force {topic} wrench.force.{opts.axis}, {t.size} messages"]
    if opts.pose_topic:
        if len(pose) < 2:
            raise DemoError(
                ERR_DEMO_TOPIC, f"pose topic {opts.pose_topic!r} in {path.name} has {len(pose)} messages"
            )
        pt = (np.array(pose_t, dtype=np.int64) - t0_ns) * 1e-9
        po = np.argsort(pt, kind="stable")
        cols["x"] = np.interp(t, pt[po], np.array(pose)[po])
        xyz = np.array(pose_xyz)[po]
        for i, name in enumerate(("pose_x", "pose_y", "pose_z")):
            cols[name] = np.interp(t, pt[po], xyz[:, i])
        notes[0] += f", position {opts.pose_topic} .{opts.axis} ({pt.size} messages, interpolated)"
    cols[NOTES_KEY] = np.array(notes, dtype=object)
    return cols

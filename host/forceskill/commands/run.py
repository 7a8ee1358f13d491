"""forceskill run: execute a skill (or a sequence of skills) on the device, watch it, report the
force tracking from the telemetry."""

from __future__ import annotations

import argparse
import re
import struct
import time
from pathlib import Path
from typing import Any

import can
import numpy as np

from ..demo import write_csv
from ..errors import FsError
from ..link import ERR_LINK_ARGS, ERR_LINK_STATE
from ..link import uds as U
from ..link.device import Device
from ._common import add_common, columns, connect, tracking

_STEP = re.compile(r"^\s*(\d+)\s*:\s*([0-9.]+)\s*(ms|s)?\s*$")


def parse_sequence(text: str) -> list[tuple[int, float]]:
    """'1:8s,2:9s' -> [(1, 8.0), (2, 9.0)] (slot, duration in s; 'ms' allowed)."""
    steps = []
    for part in text.split(","):
        m = _STEP.match(part)
        if not m:
            raise FsError(ERR_LINK_ARGS, f"--sequence step {part.strip()!r} is not SLOT:DURATION (e.g. 1:8s)")
        d = float(m.group(2)) * (1e-3 if m.group(3) == "ms" else 1.0)
        if not 0.0 < d <= 3600.0:
            raise FsError(ERR_LINK_ARGS, f"--sequence duration must be in (0, 3600] s: {part.strip()!r}")
        steps.append((int(m.group(1)), d))
    if not 1 <= len(steps) <= 8:
        raise FsError(ERR_LINK_ARGS, f"--sequence takes 1..8 steps, got {len(steps)}")
    return steps


def _scale(v: float, name: str) -> int:
    if not (0.0 <= v <= 65.535) or (name == "time" and v <= 0.0):
        raise FsError(ERR_LINK_ARGS, f"--{name}-scale out of range (0, 65.5]: {v}")
    return int(round(v * 1000.0))


def run_on_device(dev: Device, args: argparse.Namespace, log_path: str | None = None) -> dict[str, Any]:
    """Start, watch and stop one execution; returns the telemetry columns and figures."""
    st = dev.status
    if st is not None and st.state != "IDLE":
        raise FsError(
            ERR_LINK_STATE,
            f"node {dev.node} is in {st.state}"
            f"{f' (fault {st.fault_code})' if st.fault_code else ''}; run needs IDLE "
            "(clear a fault with: forceskill status --clear)",
        )
    end_code = {"skill": 0, "hold": 1, "release": 2}[args.end]
    g, ts = _scale(args.goal_scale, "goal"), _scale(args.time_scale, "time")
    writer = None
    with U.uds_client(dev) as client:
        directory = {e["slot"]: e for e in U.slot_directory(client, dev.node)}
        if args.sequence:
            steps = parse_sequence(args.sequence)
            data = bytes([end_code])
            for slot, d in steps:
                if slot not in directory or not directory[slot]["valid"]:
                    raise FsError(ERR_LINK_ARGS, f"slot {slot} of node {dev.node} holds no skill")
                data += struct.pack(">BHHI", slot, g, ts, int(round(d * 1000)))
            rid, expected = U.RID_RUN_SEQUENCE, sum(d for _, d in steps)
            last_end = directory[steps[-1][0]]["end"]
        else:
            if args.slot is None:
                raise FsError(ERR_LINK_ARGS, "give --slot N or --sequence SLOT:DURATION,...")
            e = directory.get(args.slot)
            if e is None or not e["valid"]:
                raise FsError(ERR_LINK_ARGS, f"slot {args.slot} of node {dev.node} holds no skill")
            data = struct.pack(">BHHB", args.slot, g, ts, end_code)
            rid, expected = U.RID_RUN_SKILL, float(e["duration_s"]) * args.time_scale
            last_end = e["end"]
        end_policy = args.end if args.end != "skill" else last_end
        tail = args.hold_for if end_policy == "hold" else 0.5 + 0.05
        notifier = dev.notifier
        assert notifier is not None
        if log_path:
            writer = can.Logger(log_path)
            notifier.add_listener(writer)
        tel = dev.start_telemetry()
        dev.start_heartbeat(telemetry_period_ms=1)
        try:
            time.sleep(0.05)
            U.call("start", lambda: client.start_routine(rid, data), dev.node)
            st = dev.wait_state({"EXECUTE", "FAULT"}, 2.0 * args.timeout)
            start_tick = st.tick
            total = expected + tail
            print(
                f"node {dev.node}: executing {'sequence ' + args.sequence if args.sequence else f'slot {args.slot}'}"
                f", goal x{args.goal_scale:g}, time x{args.time_scale:g}, end {end_policy}: "
                f"{expected:.3f} s + {tail:.2f} s",
                flush=True,
            )
            while True:
                time.sleep(0.02)
                cur = dev.status
                assert cur is not None
                if cur.state == "FAULT":
                    raise FsError(
                        ERR_LINK_STATE,
                        f"node {dev.node} faulted during execution: fault "
                        f"{cur.fault_code} at {((cur.tick - start_tick) & 0xFFFFFF) / 1000:.3f} s",
                    )
                if cur.state != "EXECUTE":
                    break
                if ((cur.tick - start_tick) & 0xFFFFFF) >= total * 1000.0:
                    dev.command_until("idle", {"IDLE", "FAULT"}, 2.0 * args.timeout)
                    break
            time.sleep(0.05)
        finally:
            dev.stop_heartbeat()
            if writer is not None:
                notifier.remove_listener(writer)
                writer.stop()
    samples = list(tel.samples)
    ticks = np.array([s.tick for s in samples], float)
    if ticks.size:
        steps_ = np.diff(ticks)
        breaks = np.flatnonzero(steps_ != 1.0)
        starts = np.concatenate(([0], breaks + 1))
        ends = np.concatenate((breaks + 1, [ticks.size]))
        k = int(np.argmax(ends - starts))
        samples = samples[starts[k] : ends[k]]
    cols = columns(samples)
    n_exec = int(round(total * 1000.0))
    cols = {k: v[: n_exec + 1] for k, v in cols.items()}
    fig = tracking(cols)
    return {"columns": cols, "figures": fig, "expected_s": expected}


def _cmd(args: argparse.Namespace) -> int:
    if args.csv and str(Path(args.csv).parent) and not Path(args.csv).parent.is_dir():
        raise FsError(620, f"output folder does not exist: {str(Path(args.csv).parent)!r}")
    with connect(args) as dev:
        r = run_on_device(dev, args, log_path=args.output)
    cols, fig = r["columns"], r["figures"]
    print(
        f"telemetry: {cols['t'].size} samples over {cols['t'][-1] if cols['t'].size else 0:.3f} s; "
        f"max contact force {fig['max_force_N']:.3f} N, max reference {fig['max_ref_N']:.3f} N"
    )
    print(
        f"force tracking: max {fig['tracking_max_pct']:.2f} %, RMS {fig['tracking_rms_pct']:.2f} % of max reference"
    )
    if args.csv:
        write_csv(
            args.csv, {k: cols[k] for k in ("t", "x", "y", "f_contact", "f_operator", "f_cmd", "f_hat")}
        )
        print(f"wrote {args.csv}")
    return 0


def register(sub: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    p = sub.add_parser(
        "run",
        help="execute a skill or a sequence on the device and report tracking",
        description="Start a skill (--slot) or a sequence (--sequence 1:8s,2:9s) with "
        "RoutineControl, keep the host heartbeat, record telemetry at 1 kHz, stop after "
        "the duration (hold: after --hold-for more seconds), and report the force "
        "tracking max/RMS in %% of the maximum reference force.",
    )
    p.add_argument("--slot", type=int, metavar="N", help="slot 1..8")
    p.add_argument("--sequence", metavar="SLOT:DUR,...", help="skills in series, e.g. 1:8s,2:9s")
    p.add_argument("--goal-scale", type=float, default=1.0, metavar="S")
    p.add_argument("--time-scale", type=float, default=1.0, metavar="S")
    p.add_argument(
        "--end",
        choices=("skill", "hold", "release"),
        default="skill",
        help="end policy (default: the skill's own)",
    )
    p.add_argument(
        "--hold-for",
        type=float,
        default=0.5,
        metavar="S",
        help="with hold: seconds to hold the last force before stopping (0.5)",
    )
    p.add_argument("-o", "--output", metavar="LOG", help="also log the bus (.blf .asc .log .trc .csv)")
    p.add_argument(
        "--csv", metavar="CSV", help="write the telemetry as t,x,y,f_contact,f_operator,f_cmd,f_hat"
    )
    add_common(p)
    p.set_defaults(func=_cmd)

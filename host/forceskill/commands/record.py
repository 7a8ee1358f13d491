"""forceskill record: put the device in TEACH and log the bus to any python-can log format."""

from __future__ import annotations

import argparse
import signal
import time
from pathlib import Path

import can

from ..errors import FsError
from ..link import ERR_LINK_ARGS, ERR_LINK_STATE
from ._common import add_common, connect


def _cmd(args: argparse.Namespace) -> int:
    out = Path(args.output)
    if str(out.parent) and not out.parent.is_dir():
        raise FsError(620, f"output folder does not exist: {str(out.parent)!r}")
    try:
        writer = can.Logger(str(out))
    except ValueError as e:
        raise FsError(ERR_LINK_ARGS, f"no python-can writer for {out.name}: {e}") from None
    writer.stop()
    out.unlink(missing_ok=True)
    with connect(args) as dev:
        st = dev.status
        assert st is not None
        if args.teach and st.state != "IDLE":
            raise FsError(
                ERR_LINK_STATE,
                f"node {dev.node} is in {st.state}"
                f"{f' (fault {st.fault_code})' if st.fault_code else ''}; TEACH needs IDLE",
            )
        writer = can.Logger(str(out))
        assert dev.notifier is not None
        dev.notifier.add_listener(writer)
        stop = {"flag": False}
        old = signal.signal(signal.SIGINT, lambda *a: stop.__setitem__("flag", True))
        try:
            dev.start_heartbeat(telemetry_period_ms=1)
            if args.teach:
                st = dev.command_until("teach", {"TEACH"}, 2.0 * args.timeout)
            start_tick = st.tick
            print(
                f"recording node {dev.node} on {dev.channel} to {out}"
                f"{' in TEACH' if args.teach else ''}; "
                + (f"{args.duration:g} s of device time" if args.duration else "Ctrl-C to stop"),
                flush=True,
            )
            while not stop["flag"]:
                time.sleep(0.02)
                cur = dev.status
                if cur is None:
                    continue
                if args.teach and cur.state != "TEACH":
                    raise FsError(
                        ERR_LINK_STATE,
                        f"node {dev.node} left TEACH ({cur.state}, fault "
                        f"{cur.fault_code}) after {((cur.tick - start_tick) & 0xFFFFFF) / 1000:.3f} s",
                    )
                if args.duration and ((cur.tick - start_tick) & 0xFFFFFF) >= args.duration * 1000.0:
                    break
            if args.teach:
                dev.command_until("idle", {"IDLE"}, 2.0 * args.timeout)
        finally:
            signal.signal(signal.SIGINT, old)
            dev.stop_heartbeat()
            dev.notifier.remove_listener(writer)
            writer.stop()
    print(f"wrote {out} ({out.stat().st_size} bytes)")
    return 0


def register(sub: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    p = sub.add_parser(
        "record",
        help="record a demonstration (device in TEACH) to a CAN log",
        description="Put the device in TEACH (it renders m_d and streams telemetry at "
        "1 kHz), keep the host heartbeat, and log every frame with python-can's writer "
        "for the file suffix (.blf .asc .log .trc .csv ...) until --duration seconds of "
        "device time have passed or Ctrl-C; then back to IDLE.",
    )
    p.add_argument("-o", "--output", required=True, metavar="LOG", help="log file (.blf .asc .log .trc .csv)")
    p.add_argument(
        "--duration",
        type=float,
        default=0.0,
        metavar="S",
        help="seconds of device time to record (default: until Ctrl-C)",
    )
    p.add_argument(
        "--no-teach", dest="teach", action="store_false", help="only log (do not command TEACH/IDLE)"
    )
    add_common(p)
    p.set_defaults(func=_cmd)

"""forceskill record: put the device in TEACH and log the bus to any python-can log format."""

from __future__ import annotations

import argparse
import math
import time
from pathlib import Path

import can

from ..errors import ERR_RUN_FAULT, FsError, fault_text
from ..link import ERR_LINK_ARGS, ERR_LINK_STATE, ERR_LINK_TIMEOUT
from ..link import uds as U
from ..link.bus import error_summary
from ..link.device import Device, Status
from ..outputs import Outputs
from ..wire import TICK_HZ
from ._common import add_common, close_log, connect, open_log, sigint_flag

#: Longest --duration (24 h of device time); without it, recording runs until Ctrl-C.
MAX_RECORD_S = 86400.0


def _cmd(args: argparse.Namespace) -> int:
    if not (math.isfinite(args.duration) and 0.0 <= args.duration <= MAX_RECORD_S):
        raise FsError(ERR_LINK_ARGS, f"--duration must be in [0, {MAX_RECORD_S:g}] s: {args.duration:g}")
    with Outputs() as outs:
        # the writer goes to a temporary file: an old log is replaced only by a new recording
        writer = open_log(outs, args.output)
        try:
            dropped = _record(args, writer)
        finally:
            close_log(writer)
        outs.commit()  # what was recorded is kept, also when the link dropped
    size = Path(args.output).stat().st_size
    if dropped is not None:
        raise FsError(
            dropped.code, f"{dropped.message}; kept what was recorded in {args.output} ({size} bytes)"
        )
    print(f"wrote {args.output} ({size} bytes)")
    return 0


def _record(args: argparse.Namespace, writer: can.Listener) -> FsError | None:
    """Connect, (TEACH,) log until the duration or Ctrl-C; the link error that ended it, if any."""
    with connect(args) as dev:
        st = dev.status
        assert st is not None
        if args.teach and st.state != "IDLE":
            raise FsError(
                ERR_LINK_STATE,
                f"node {dev.node} is in {st.state}"
                f"{f' (fault {fault_text(st.fault_code)})' if st.fault_code else ''}; TEACH needs IDLE",
            )
        assert dev.notifier is not None
        with U.uds_client(dev, request_timeout_s=2.0) as client:
            U.motion_session(client, dev)  # authenticated heartbeats and commands
        return _record_session(args, dev, writer, st)


def log_object_model(dev: Device) -> None:
    """Ask the device for its object model (DID 0x0130) while the log listens: its answer is in
    the log, where ``fit`` finds the object's mass (a device without the identifier: nothing)."""
    try:
        with U.uds_client(dev, request_timeout_s=2.0) as client:
            U.read_did(client, U.DID_OBJECT, dev.node)
    except FsError:
        pass


class _LogUntil(can.Listener):
    """The log writer's frames until a status frame of the device shows the recording's last tick:
    every listener sees the frames in bus order, so the log holds --duration of device time (to
    a status period) however far behind the stream the host's own loop reads the status. The
    recording starts at the first status in start_state (TEACH), or at the first one (None)."""

    def __init__(self, writer: can.Listener, duration_ticks: int, start_state: str | None) -> None:
        self.writer = writer
        self.duration_ticks = duration_ticks
        self.start_state = start_state
        self.start_tick: int | None = None
        self.ended = False

    def status(self, st: Status) -> None:
        """Device.on_status: called before the listeners after the Device see that frame."""
        start = self.start_tick
        if start is None:
            if self.start_state is None or st.state == self.start_state:
                self.start_tick = st.tick
        elif self.duration_ticks and ((st.tick - start) & 0xFFFFFF) >= self.duration_ticks:
            self.ended = True

    def on_message_received(self, msg: can.Message) -> None:
        if not self.ended:
            self.writer.on_message_received(msg)

    def stop(self) -> None:
        """Nothing: the writer is closed by the command (close_log)."""


def _record_session(
    args: argparse.Namespace, dev: Device, writer: can.Listener, st: Status
) -> FsError | None:
    """The recording itself, with the motion session established."""
    assert dev.notifier is not None
    log = _LogUntil(writer, int(round(args.duration * TICK_HZ)), "TEACH" if args.teach else None)
    dev.on_status = log.status
    dev.notifier.add_listener(log)
    log_object_model(dev)
    try:
        with sigint_flag() as stop:
            dev.start_heartbeat(telemetry_period_ms=getattr(args, "telemetry_period", 1))
            try:
                if args.teach:
                    st = dev.command_until("teach", {"TEACH"}, 2.0 * args.timeout)
                start_tick = st.tick if log.start_tick is None else log.start_tick
                print(
                    f"recording node {dev.node} on {dev.channel} to {args.output}"
                    f"{' in TEACH' if args.teach else ''}; "
                    + (f"{args.duration:g} s of device time" if args.duration else "Ctrl-C to stop"),
                    flush=True,
                )
                last_frame = time.monotonic()
                seen = dev.frames_seen
                while not stop["stop"]:
                    time.sleep(0.02)
                    dev.check_link()
                    if dev.frames_seen != seen:
                        seen, last_frame = dev.frames_seen, time.monotonic()
                    elif time.monotonic() - last_frame > args.timeout:
                        raise FsError(
                            ERR_LINK_TIMEOUT,
                            f"node {dev.node} on {dev.channel} stopped sending for {args.timeout:g} s",
                        )
                    cur = dev.status
                    if cur is None:
                        continue
                    if args.teach and cur.state != "TEACH":
                        raise FsError(
                            ERR_RUN_FAULT if cur.state == "FAULT" else ERR_LINK_STATE,
                            f"node {dev.node} left TEACH ({cur.state}, fault "
                            f"{fault_text(cur.fault_code)}) after "
                            f"{((cur.tick - start_tick) & 0xFFFFFF) / TICK_HZ:.3f} s",
                        )
                    if args.duration and ((cur.tick - start_tick) & 0xFFFFFF) >= args.duration * TICK_HZ:
                        break
                if args.teach:
                    dev.command_until("idle", {"IDLE", "FAULT"}, 2.0 * args.timeout)
            except (FsError, OSError, can.CanError) as e:
                if args.teach:
                    try:
                        dev.command_until("idle", {"IDLE", "FAULT"}, 0.5)
                    except (FsError, OSError, can.CanError):
                        pass
                if isinstance(e, FsError):
                    return e
                return FsError(
                    ERR_LINK_TIMEOUT,
                    f"link to node {dev.node} on {dev.channel} lost: {error_summary(e)}",
                )
            finally:
                dev.stop_heartbeat()
    finally:
        dev.notifier.remove_listener(log)
        dev.on_status = None
    return None


def register(sub: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    p = sub.add_parser(
        "record",
        help="record a demonstration (device in TEACH) to a CAN log",
        description="Put the device in TEACH (it renders m_d and streams telemetry at "
        "1 kHz), keep the host heartbeat, and log every frame with python-can's writer "
        "for the file suffix (.blf .asc .log .trc .csv ...) until --duration seconds of "
        "device time have passed or Ctrl-C; then back to IDLE. The log is written to a "
        "temporary file and renamed when recording ends: an existing log is replaced only "
        "by a new recording, and what was recorded is kept if the link drops (exit 2).",
    )
    p.add_argument("-o", "--output", required=True, metavar="LOG", help="log file (.blf .asc .log .trc .csv)")
    p.add_argument(
        "--duration",
        type=float,
        default=0.0,
        metavar="S",
        help=f"seconds of device time to record, at most {MAX_RECORD_S:g} (default: until Ctrl-C)",
    )
    p.add_argument(
        "--no-teach", dest="teach", action="store_false", help="only log (do not command TEACH/IDLE)"
    )
    add_common(p)
    p.set_defaults(func=_cmd)

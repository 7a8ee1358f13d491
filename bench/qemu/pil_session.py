#!/usr/bin/env python3
"""Drive the Cortex-M image (`hil_sim pil`) through the ticks bench/qemu_tick.sh counts, over
python-can's slcan interface: IDLE ticks, then a skill download, then an execution of that skill
during which the host reads the skill back (UDS RequestUpload: EXECUTE ticks while a transfer
runs), then more EXECUTE ticks. The image marks each tick's kind (cm_port_mark_*).
Under the exec trace the image runs ~20x slower than real time, so the host paces its own
traffic by the device's clock: one heartbeat per DeviceStatus frame (every 10 ms of device time),
as a host does against a device running in real time.
  pil_session.py PORT SKILL [--exec-s S]"""
from __future__ import annotations

import argparse
import struct
import sys
import time
from pathlib import Path

import can

from forceskill.link import uds as U
from forceskill.link.device import Device


class DevicePacedHeartbeat(can.Listener):
    """Answers each DeviceStatus frame of the node with one host heartbeat."""

    def __init__(self, dev: Device, status_id: int) -> None:
        self.dev, self.status_id = dev, status_id

    def on_message_received(self, msg: can.Message) -> None:
        if msg.arbitration_id == self.status_id:
            self.dev.heartbeat()


def wait_ticks(dev: Device, n: int, timeout_s: float) -> None:
    t0 = dev.status.tick
    end = time.monotonic() + timeout_s
    while ((dev.status.tick - t0) & 0xFFFFFF) < n:
        if time.monotonic() > end:
            raise SystemExit(f"pil_session: the device did not advance {n} ticks in {timeout_s} s")
        time.sleep(0.05)


def main(argv: list[str]) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("port", type=int)
    ap.add_argument("skill", type=Path)
    ap.add_argument("--exec-s", type=float, default=1.0, help="execution length (s of device time)")
    ap.add_argument("--timeout", type=float, default=600.0, help="wall-clock limit of each phase (s)")
    args = ap.parse_args(argv)
    image = args.skill.read_bytes()
    bus = can.Bus(interface="slcan", channel=f"socket://127.0.0.1:{args.port}", sleep_after_open=0.1)
    try:
        with Device(bus, node=0, channel="slcan", timeout_s=args.timeout) as dev:
            dev.wait_present()
            wait_ticks(dev, 1200, args.timeout)          # past the 1 s SecurityAccess delay
            with U.uds_client(dev, request_timeout_s=args.timeout) as client:
                U.unlock(client, 0, 0x02)
                U.download(client, 0, 1, image)
            wait_ticks(dev, 200, args.timeout)
            dev.telemetry_period_ms = 1
            hb = DevicePacedHeartbeat(dev, 0x180)
            assert dev.notifier is not None
            dev.notifier.add_listener(hb)
            try:
                with U.uds_client(dev, request_timeout_s=args.timeout) as client:
                    # RequestUpload needs the programming session, entered while IDLE
                    U.call("session change", lambda: client.change_session(1), 0)
                    U.call("session change", lambda: client.change_session(2), 0)
                    data = struct.pack(">BHHB", 1, 1000, 1000, 2)
                    U.call("start", lambda: client.start_routine(U.RID_RUN_SKILL, data), 0)
                    dev.wait_state({"EXECUTE"}, args.timeout)
                    wait_ticks(dev, int(args.exec_s * 500), args.timeout)
                    U.upload(client, 0, 1, len(image))       # read-back while executing
                    wait_ticks(dev, int(args.exec_s * 500), args.timeout)
                    dev.command_until("idle", {"IDLE", "FAULT"}, args.timeout)
            finally:
                dev.notifier.remove_listener(hb)
            st = dev.status
            print(f"pil_session: done, device {st.state}, fault {st.fault_code}, tick {st.tick}")
            return 0 if st.fault_code == 0 else 1
    finally:
        bus.shutdown()


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

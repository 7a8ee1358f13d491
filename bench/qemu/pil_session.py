#!/usr/bin/env python3
"""Drive the Cortex-M image (`hil_sim pil`) through every state bench/qemu_tick.sh counts, over
python-can's slcan interface: IDLE ticks, a skill download (its commit in slices), TEACH, an
execution of that skill during which the host reads the skill back (UDS RequestUpload), more
EXECUTE ticks, a second execution whose host goes silent (fault 500 latched during EXECUTE, the
safe-stop ramp, FAULT until cleared), a firmware download into the inactive slot through its
transfer exit (the image's verification; not marked for a test boot), then a board reset
(ECUReset: the second boot finds the skill stored). The image marks each tick's kind
(cm_port_mark_*).
The image runs at qemu's speed, not in real time: 20-50 times slower than real time under the
one-instruction trace, about real time under bench/qemu_tick.sh's plugin counter. So the host
heartbeat goes every --heartbeat-ticks ticks of device time (20 ms: as a host against a device
in real time, well inside the 500 ms host timeout), its wall-time period measured from the
device's tick rate during the first 1,200 ticks (or --heartbeat-s of wall time if given).
  pil_session.py PORT SKILL --target TARGET [--exec-s S] [--fw-bytes N] [--path-scale S]"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import can

from forceskill import wire as W
from forceskill.link import uds as U
from forceskill.link.device import Device
from forceskill.link.flash import flash_image
from forceskill.model import fwimage as fw

# A command is repeated when its state has not shown after this long (wall time): under the trace
# the 10 ms between two status frames take 0.2-0.5 s, so the host tools' 0.2 s would repeat a
# command the device took, and after three repeats re-establish the session in the middle of it.
RETRY_S = 3.0


#: The transfer requests by service id, named after the download they belong to.
TRANSFER_REQUESTS = {0x34: "request_download", 0x35: "request_upload", 0x36: "block", 0x37: "transfer_exit"}


class AnswerTimes:
    """The answer time of every UDS request that starts long work on the device (request sent to
    final response, the device's pending answers included), in ms of device time (its ticks: the
    latest status frame's tick after the answer less the latest before the request, +-1 status
    period, whatever qemu's speed), by request: the key check, a skill's commit, the read-back's
    blocks, the firmware download's erase, blocks and verification, a run's start."""

    def __init__(self, dev: Device) -> None:
        self.dev = dev
        self.job = "skill"  # whose download the transfer requests belong to: skill, read_back, firmware
        self.ms: dict[str, list[float]] = {}

    def watch(self, client: object) -> None:
        """Time every request client sends (udsoncan's Client.send_request)."""
        send = client.send_request  # type: ignore[attr-defined]

        def timed(request: object, *a: object, **kw: object) -> object:
            t0 = self.dev.status.tick
            try:
                return send(request, *a, **kw)
            finally:
                name = self.name(request.get_payload())  # type: ignore[attr-defined]
                if name:
                    self.ms.setdefault(name, []).append(float((self.dev.status.tick - t0) & 0xFFFFFF))

        client.send_request = timed  # type: ignore[attr-defined]

    def name(self, p: bytes) -> str | None:
        """The request's name in the report (None: not timed)."""
        sid = p[0]
        if sid == 0x27 and len(p) > 1 and p[1] % 2 == 0:
            return "security_key"
        if sid == 0x31 and len(p) > 3 and p[1] == 0x01:
            return f"routine_start_{p[2]:02X}{p[3]:02X}"
        transfer = TRANSFER_REQUESTS.get(sid)
        return f"{self.job}_{transfer}" if transfer else None

    def report(self, target: str) -> None:
        for name, ms in sorted(self.ms.items()):
            ms.sort()
            print(
                f"uds_answer_ms target={target} request={name} n={len(ms)} median={ms[len(ms) // 2]:.0f} "
                f"max={ms[-1]:.0f}",
                flush=True,
            )


def wait_ticks(dev: Device, n: int, timeout_s: float) -> None:
    t0 = dev.status.tick
    end = time.monotonic() + timeout_s
    while ((dev.status.tick - t0) & 0xFFFFFF) < n:
        if time.monotonic() > end:
            raise SystemExit(f"pil_session: the device did not advance {n} ticks in {timeout_s} s")
        time.sleep(0.05)


def heartbeat(bus: can.BusABC, dev: Device, period_s: float) -> can.broadcastmanager.CyclicSendTaskABC:
    """The host heartbeat every period_s of wall time (freshness, MAC, E2E counter and CRC of the
    motion session)."""
    m = dev._m["HostHeartbeat"]
    return bus.send_periodic(
        can.Message(arbitration_id=m.frame_id, data=bytearray(8), is_extended_id=False),
        period_s,
        store_task=False,
        modifier_callback=dev._heartbeat_update,
    )


def fw_payload(args: argparse.Namespace) -> bytes:
    """A firmware image for the image's target, signed with the development key."""
    payload = bytes((i * 7 + 3) & 0xFF for i in range(args.fw_bytes))
    return fw.build_image(payload, "9.0.0", args.target, fw.DEV_KEY, build_id="qemu_tick")


def fault_on_silence(dev: Device, client: object, hb: object, start: bytes, args: argparse.Namespace) -> None:
    """Start the skill, silence the host's heartbeat until the device latches host silence (500)
    during EXECUTE, stay in FAULT through the ramp for --fault-ticks, then clear it."""
    U.call("start", lambda: client.start_routine(U.RID_RUN_SKILL, start), 0)  # type: ignore[attr-defined]
    dev.wait_state({"EXECUTE"}, args.timeout)
    wait_ticks(dev, 100, args.timeout)
    hb.stop()  # type: ignore[attr-defined]
    st = dev.wait_state({"FAULT"}, args.timeout)
    print(f"pil_session: fault {st.fault_code} latched at tick {st.tick}", flush=True)
    wait_ticks(dev, args.fault_ticks, args.timeout)


def main(argv: list[str]) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("port", type=int)
    ap.add_argument("skill", type=Path)
    ap.add_argument("--exec-s", type=float, default=1.0, help="execution length (s of device time)")
    ap.add_argument(
        "--heartbeat-s",
        type=float,
        default=None,
        help="host heartbeat period (s of wall time)",
    )
    ap.add_argument(
        "--heartbeat-ticks",
        type=float,
        default=20.0,
        help="host heartbeat period (device ticks)",
    )
    ap.add_argument(
        "--timeout",
        type=float,
        default=600.0,
        help="wall-clock limit of each phase (s)",
    )
    ap.add_argument("--target", default="cortex-m4f", help="the image's firmware target")
    ap.add_argument("--fw-bytes", type=int, default=16384, help="payload of the firmware download")
    ap.add_argument(
        "--path-scale",
        type=float,
        default=1.0,
        help="the run's path scale (a y path whose acceleration the axis cannot follow latches "
        "FLT_SLEW_LIMIT; the DMP's cost does not depend on it)",
    )
    # TEACH and FAULT ticks are alike (min = median in both: nothing but the bus varies them):
    # 150 of each cover the stop ramp (40 ticks) and the host's frames several times over
    ap.add_argument("--teach-ticks", type=int, default=150, help="TEACH ticks")
    ap.add_argument("--fault-ticks", type=int, default=150, help="FAULT ticks after the latch")
    args = ap.parse_args(argv)
    # under the trace a consecutive frame can be seconds of wall time apart: ISO-TP's 1 s
    # receive timeouts of the host tools would drop the transfer
    base_params = U.isotp_params
    U.isotp_params = lambda fd=False, timeout_s=2.0: {
        **base_params(fd, timeout_s),
        "rx_flowcontrol_timeout": int(args.timeout * 1000),
        "rx_consecutive_frame_timeout": int(args.timeout * 1000),
    }
    image = args.skill.read_bytes()
    bus = can.Bus(
        interface="slcan",
        channel=f"socket://127.0.0.1:{args.port}",
        sleep_after_open=0.1,
    )
    try:
        with Device(bus, node=0, channel="slcan", timeout_s=args.timeout) as dev:
            dev.wait_present()
            t0, tick0 = time.monotonic(), dev.status.tick
            wait_ticks(dev, 1200, args.timeout)  # past the 1 s SecurityAccess delay
            rate = ((dev.status.tick - tick0) & 0xFFFFFF) / max(time.monotonic() - t0, 1e-3)
            if args.heartbeat_s is None:
                args.heartbeat_s = min(max(args.heartbeat_ticks / rate, 0.005), 0.5)
            print(
                f"pil_session: device at {rate:.0f} ticks/s, heartbeat every {args.heartbeat_s:.3f} s",
                flush=True,
            )
            answers = AnswerTimes(dev)
            with U.uds_client(dev, request_timeout_s=args.timeout) as client:
                answers.watch(client)
                U.unlock(client, 0, 0x02)
                U.download(client, 0, 1, image)
                U.motion_session(client, dev)  # authenticated heartbeats and commands from here
            wait_ticks(dev, 200, args.timeout)
            dev.telemetry_period_ms = 1
            hb = heartbeat(bus, dev, args.heartbeat_s)
            try:
                dev.command_until("teach", {"TEACH"}, args.timeout, RETRY_S)
                wait_ticks(dev, args.teach_ticks, args.timeout)
                dev.command_until("idle", {"IDLE"}, args.timeout, RETRY_S)
                with U.uds_client(dev, request_timeout_s=args.timeout) as client:
                    answers.watch(client)
                    # RequestUpload needs the programming session, entered while IDLE
                    U.call("session change", lambda: client.change_session(1), 0)
                    U.call("session change", lambda: client.change_session(2), 0)
                    U.unlock(client, 0, 0x02)  # a run routine's start needs level 1
                    ps = args.path_scale
                    data = W.RunSkill(1, 1.0, 1.0, 2, ps if ps != 1.0 else None).pack()
                    U.call("start", lambda: client.start_routine(U.RID_RUN_SKILL, data), 0)
                    dev.wait_state({"EXECUTE"}, args.timeout)
                    wait_ticks(dev, int(args.exec_s * 500), args.timeout)
                    answers.job = "read_back"
                    U.upload(client, 0, 1, len(image))  # read-back while executing
                    print(
                        f"pil_session: read-back done at tick {dev.status.tick}",
                        flush=True,
                    )
                    wait_ticks(dev, int(args.exec_s * 500), args.timeout)
                    dev.command_until("idle", {"IDLE", "FAULT"}, args.timeout, RETRY_S)
                    fault_on_silence(dev, client, hb, data, args)
                    hb = heartbeat(bus, dev, args.heartbeat_s)
                    dev.command_until("clear_fault", {"IDLE"}, args.timeout, RETRY_S)
                    answers.job = "firmware"
                    flash_image(client, fw_payload(args), mark_test=False)
                    print(
                        f"pil_session: firmware download done at tick {dev.status.tick}",
                        flush=True,
                    )
            finally:
                hb.stop()
            st = dev.status
            print(f"pil_session: done, device {st.state}, fault {st.fault_code}, tick {st.tick}")
            answers.report(args.target)
            # a board reset: the second boot finds the skill in its flash (bench/qemu_tick.sh
            # counts both boots)
            tick0 = st.tick
            with U.uds_client(dev, request_timeout_s=args.timeout) as client:
                U.call("reset", lambda: client.ecu_reset(1), 0)
            end = time.monotonic() + args.timeout
            while dev.status.tick >= tick0 or dev.status.tick < 50:
                if time.monotonic() > end:
                    raise SystemExit("pil_session: the device did not restart after ECUReset")
                time.sleep(0.05)
            print(f"pil_session: restarted, device {dev.status.state}", flush=True)
            return 0 if st.fault_code == 0 else 1
    finally:
        bus.shutdown()


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

"""Benchmark: the N = 50 skill and a firmware image uploaded over UDS on a SocketCAN interface,
classic CAN (ISO-TP in 8-byte frames) against CAN FD (`hil_sim serve --fd`, the host's `--fd`:
64-byte frames with bit-rate switching), each against its bus's limit.

Bus limit = the sum of the wire times of every UDS frame of the transfer as captured on the
interface (requests, flow controls, responses): classic frames with their actual stuff bits at
the nominal rate (bench/can_upload's frame model); FD frames with the arbitration phase (SOF to
BRS) and the ACK/EOF/IFS tail at the nominal rate and the data phase (ESI, DLC, data, stuff
count, CRC-17/21 with its fixed stuff bits, CRC delimiter) at the data rate, dynamic stuff bits
counted on the frame's actual bits up to the data. Measured = wall time of the transfer (skill:
RequestDownload to RequestTransferExit; firmware: the whole flash_image, sessions and unlock
included). vcan has no bit rate: frames arrive at once, so there the measured time is the
host's and the device's processing, printed beside the limits of the nominal/data rates asked.

With --limits-only it runs nothing: the UDS exchanges' frames are built here by ISO-TP's rules
(classic: SF up to 7 bytes, FF with 6 and CFs with 7; FD: SF up to 62 bytes with the escape
byte, FF with 62 and CFs with 63, the last padded to the next FD length; flow controls 8 bytes)
from the same requests the host sends (skill: RequestDownload, one TransferData, exit; firmware:
sessions, SecurityAccess, RequestDownload, TransferData blocks of 4,093 bytes, exit) and timed
as above.

Usage: fd_upload.py [--iface vcan0] [--hil-sim PATH] [--repeat N] [--fw-bytes N]
                    [--bitrate BPS] [--data-bitrate BPS]      (run in scripts/vm.sh --vcan)
       fd_upload.py --limits-only [--fw-bytes N] [--bitrate BPS] [--data-bitrate BPS]"""

from __future__ import annotations

import argparse
import importlib.util
import os
import statistics
import subprocess
import sys
import threading
import time
from pathlib import Path

import can

REPO = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPO / "host"))

from forceskill.link import flash as F  # noqa: E402
from forceskill.link import uds as U  # noqa: E402
from forceskill.link.device import Device  # noqa: E402
from forceskill.model import fwimage as fw  # noqa: E402
from forceskill.model.skill import Skill  # noqa: E402

SKILL = REPO / "tests" / "vectors" / "press_n50_ridge_release.skill"


def _classic_model():
    spec = importlib.util.spec_from_file_location(
        "can_upload", REPO / "bench" / "can_upload" / "can_upload.py"
    )
    assert spec is not None and spec.loader is not None
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


_classic = _classic_model()
classic_bits = _classic.frame_bits
stuffed = _classic.stuffed


def fd_bits(frame_id: int, data: bytes) -> tuple[float, float]:
    """(nominal-rate bits, data-rate bits) of a CAN FD base-format frame with BRS."""
    arb = [0] + [(frame_id >> (10 - i)) & 1 for i in range(11)] + [0, 0, 1, 0, 1]  # RRS IDE FDF res BRS
    dlc = {8: 8, 12: 9, 16: 10, 20: 11, 24: 12, 32: 13, 48: 14, 64: 15}.get(len(data), len(data))
    dat = [0] + [(dlc >> (3 - i)) & 1 for i in range(4)]  # ESI, DLC
    for byte in data:
        dat += [(byte >> (7 - i)) & 1 for i in range(8)]
    s = stuffed(arb + dat)
    s_arb = stuffed(arb)
    crc = 17 if len(data) <= 16 else 21
    crc_field = 4 + crc + (4 + crc + 3) // 4  # stuff count + CRC + fixed stuff bits
    nominal = len(arb) + s_arb + 0.5 + 12  # half the BRS bit, then ACK, delimiter, EOF, IFS
    data_phase = len(dat) + (s - s_arb) + crc_field + 1 + 0.5  # CRC delimiter, the other half BRS
    return nominal, data_phase


def wire_s(frames: list[can.Message], bitrate: float, data_bitrate: float) -> float:
    t = 0.0
    for m in frames:
        if m.is_fd:
            n, d = fd_bits(m.arbitration_id, bytes(m.data))
            t += n / bitrate + d / data_bitrate
        else:
            t += classic_bits(m.arbitration_id, bytes(m.data)) / bitrate
    return t


class Capture(can.Listener):
    def __init__(self) -> None:
        self.frames: list[can.Message] = []
        self.lock = threading.Lock()

    def on_message_received(self, msg: can.Message) -> None:
        if msg.arbitration_id in (U.UDS_REQUEST_BASE, U.UDS_RESPONSE_BASE):
            with self.lock:
                self.frames.append(msg)

    def take(self) -> list[can.Message]:
        time.sleep(0.3)
        with self.lock:
            fr, self.frames = self.frames, []
        return fr


def run_mode(args: argparse.Namespace, fd: bool, skill: bytes, image: bytes) -> list[str]:
    extra = ["--fd"] if fd else []
    srv = subprocess.Popen(
        [args.hil_sim, "serve", "--socketcan", args.iface, "--host-timeout", "500", *extra],
        stdout=subprocess.PIPE,
        stderr=subprocess.DEVNULL,
        text=True,
    )
    lines = []
    try:
        first = srv.stdout.readline()
        if "on SocketCAN" not in first:
            raise SystemExit(f"fd_upload: hil_sim serve did not start on {args.iface}: {first!r}")
        spy_bus = can.Bus(interface="socketcan", channel=args.iface, fd=True)
        cap = Capture()
        spy = can.Notifier(spy_bus, [cap], timeout=0.05)
        mode = "fd" if fd else "classic"
        try:
            walls, limits, counts = [], [], []
            bus = can.Bus(interface="socketcan", channel=args.iface, fd=fd)
            with Device(bus, node=0, channel=args.iface, timeout_s=args.timeout, fd=fd) as dev:
                dev.wait_present()
                with U.uds_client(dev, request_timeout_s=args.timeout) as client:
                    U.unlock(client, 0, 0x02)
                    for _ in range(args.repeat):
                        cap.take()
                        t0 = time.perf_counter()
                        U.download(client, 0, 1, skill)
                        walls.append(time.perf_counter() - t0)
                        fr = cap.take()
                        limits.append(wire_s(fr, args.bitrate, args.data_bitrate if fd else args.bitrate))
                        counts.append(len(fr))
                    assert U.upload(client, 0, 1, len(skill)) == skill
            bus.shutdown()
            lines.append(report(mode, "skill", len(skill), counts, limits, walls, args, fd))
            ns = argparse.Namespace(
                interface="socketcan", channel=args.iface, fd=fd, node=0, timeout=args.timeout
            )
            walls, limits, counts = [], [], []
            for _ in range(args.repeat):
                with F.Link(ns, None) as client:
                    cap.take()
                    t0 = time.perf_counter()
                    F.flash_image(client, image, mark_test=False)
                    walls.append(time.perf_counter() - t0)
                    fr = cap.take()
                limits.append(wire_s(fr, args.bitrate, args.data_bitrate if fd else args.bitrate))
                counts.append(len(fr))
            lines.append(report(mode, "firmware", len(image), counts, limits, walls, args, fd))
        finally:
            spy.stop()
            spy_bus.shutdown()
    finally:
        srv.terminate()
        srv.wait(timeout=30)
    return lines


def report(mode: str, what: str, n: int, counts, limits, walls, args, fd: bool) -> str:
    rate = (
        f"{args.bitrate / 1e6:g}/{args.data_bitrate / 1e6:g} Mbit/s"
        if fd
        else f"{args.bitrate / 1e6:g} Mbit/s"
    )
    lim, med = statistics.median(limits), statistics.median(walls)
    return (
        f"fd_upload mode={mode} what={what} bytes={n} uds_frames={statistics.median(counts):.0f} "
        f"bus_limit_ms={lim * 1e3:.1f} (at {rate}) measured_median_ms={med * 1e3:.1f} "
        f"measured_best_ms={min(walls) * 1e3:.1f} on {args.iface}"
    )


FD_LENGTHS = (8, 12, 16, 20, 24, 32, 48, 64)


def _pad(data: bytes, fd: bool) -> bytes:
    n = 8 if len(data) <= 8 or not fd else next(x for x in FD_LENGTHS if x >= len(data))
    return data + b"\xcc" * (n - len(data))


def isotp_frames(can_id: int, fc_id: int, payload: bytes, fd: bool) -> list[can.Message]:
    """The frames of one ISO-TP message (and the receiver's one flow control, block size 0)."""
    msg = lambda d, i=can_id: can.Message(arbitration_id=i, data=_pad(d, fd), is_fd=fd, bitrate_switch=fd)  # noqa: E731
    n = len(payload)
    if n <= 7:
        return [msg(bytes([n]) + payload)]
    if fd and n <= 62:
        return [msg(bytes([0, n]) + payload)]
    first = 62 if fd else 6
    per_cf = 63 if fd else 7
    out = [msg(bytes([0x10 | (n >> 8), n & 0xFF]) + payload[:first]), msg(b"\x30\x00\x00", fc_id)]
    sn = 1
    for off in range(first, n, per_cf):
        out.append(msg(bytes([0x20 | sn]) + payload[off : off + per_cf]))
        sn = (sn + 1) & 0x0F
    return out


def exchange(requests: list[tuple[bytes, bytes]], fd: bool) -> list[can.Message]:
    req, resp = U.UDS_REQUEST_BASE, U.UDS_RESPONSE_BASE
    frames: list[can.Message] = []
    for q, a in requests:
        frames += isotp_frames(req, resp, q, fd) + isotp_frames(resp, req, a, fd)
    return frames


def limits_only(args: argparse.Namespace, skill: bytes, image: bytes) -> None:
    rng = __import__("random").Random(1)
    blk = 4093
    crc = bytes(4)
    up = [(bytes([0x34, 0, 0x12, 1]) + len(skill).to_bytes(2, "big"), bytes([0x74, 0x20, 0x0F, 0xFF]))]
    up += [(bytes([0x36, 1]) + skill, b"\x76\x01"), (b"\x37", b"\x77" + crc)]
    fw_x = [(b"\x10\x01", b"\x50\x01" + bytes(4)), (b"\x10\x02", b"\x50\x02" + bytes(4))]
    fw_x += [(b"\x27\x05", b"\x67\x05" + rng.randbytes(16)), (b"\x27\x06" + rng.randbytes(16), b"\x67\x06")]
    fw_x += [
        (bytes([0x34, 0, 0x44]) + bytes(4) + len(image).to_bytes(4, "big"), bytes([0x74, 0x20, 0x0F, 0xFF]))
    ]
    for k, off in enumerate(range(0, len(image), blk)):
        fw_x.append((bytes([0x36, (k + 1) & 0xFF]) + image[off : off + blk], bytes([0x76, (k + 1) & 0xFF])))
    fw_x.append((b"\x37", b"\x77" + crc))
    for what, ex, n in (("skill", up, len(skill)), ("firmware", fw_x, len(image))):
        for fd in (False, True):
            fr = exchange(ex, fd)
            t = wire_s(fr, args.bitrate, args.data_bitrate if fd else args.bitrate)
            rate = (
                f"{args.bitrate / 1e6:g}/{args.data_bitrate / 1e6:g} Mbit/s"
                if fd
                else f"{args.bitrate / 1e6:g} Mbit/s"
            )
            print(
                f"fd_upload mode={'fd' if fd else 'classic'} what={what} bytes={n} uds_frames={len(fr)} "
                f"bus_limit_ms={t * 1e3:.1f} (at {rate}, frames built by ISO-TP's rules)"
            )


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--iface", default=os.environ.get("FORCESKILL_VCAN", "vcan0"))
    ap.add_argument("--hil-sim", default=str(REPO / "build" / "hil_sim" / "hil_sim"))
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--fw-bytes", type=int, default=40000, help="firmware payload bytes (default 40000)")
    ap.add_argument("--bitrate", type=float, default=1e6, help="nominal bit rate of the limits (1 Mbit/s)")
    ap.add_argument(
        "--data-bitrate", type=float, default=5e6, help="CAN FD data bit rate of the limit (5 Mbit/s)"
    )
    ap.add_argument("--timeout", type=float, default=20.0, help="seconds per UDS request (20: a TCG guest)")
    ap.add_argument("--limits-only", action="store_true", help="only the computed bus limits (no bus)")
    args = ap.parse_args()
    skill = Skill.read(SKILL).to_bytes()
    payload = __import__("random").Random(2).randbytes(args.fw_bytes)
    image = fw.build_image(payload, "9.9.9", "host", fw.DEV_KEY, build_id="fd_upload")
    if args.limits_only:
        limits_only(args, skill, image)
        return 0
    lines = run_mode(args, False, skill, image) + run_mode(args, True, skill, image)
    for line in lines:
        print(line)
    if args.iface.startswith("vcan"):
        print(
            f"fd_upload: {args.iface} is virtual (no bit timing): measured = processing, the limits are computed"
        )
    return 0


if __name__ == "__main__":
    sys.exit(main())

"""Benchmark: upload of an N = 50 skill over the simulated 1 Mbit/s bus (hil_sim serve, real time)
with the product's udsoncan/can-isotp client, against the bus-limited time of the same exchange.

Bus-limited time = the sum of the wire times of every frame of the transfer (RequestDownload,
TransferData, RequestTransferExit: requests, flow controls and responses, as captured on the bus)
at 1 Mbit/s, bit stuffing included (computed here from each frame's bits and CRC-15, independently
of the simulator's C model). Measured time = wall time from the RequestDownload request to the
RequestTransferExit response, best and median of --repeat uploads. Target: measured <= 2x bus-limited.

Usage: can_upload.py [--hil-sim PATH] [--repeat N]"""

from __future__ import annotations

import argparse
import logging
import statistics
import subprocess
import sys
import threading
import time
from pathlib import Path

import can

REPO = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPO / "host"))

from forceskill.link import uds as U  # noqa: E402
from forceskill.link.device import Device  # noqa: E402
from forceskill.model.fit import fit  # noqa: E402
from forceskill.model.synthetic import pressing  # noqa: E402

BITRATE = 1_000_000
# python-can's socketcand reader warns whenever a TCP read ends inside a frame (normal streaming)
logging.getLogger("can.interfaces.socketcand.socketcand").setLevel(logging.ERROR)


def crc15(bits: list[int]) -> int:
    crc = 0
    for b in bits:
        nxt = b ^ ((crc >> 14) & 1)
        crc = (crc << 1) & 0x7FFF
        if nxt:
            crc ^= 0x4599
    return crc


def stuffed(bits: list[int]) -> int:
    """Dynamic stuff bits of a bit sequence (one after five equal bits)."""
    stuff, run, last = 0, 1, bits[0]
    for b in bits[1:]:
        if b == last:
            run += 1
        else:
            run, last = 1, b
        if run == 5:
            stuff += 1
            last ^= 1
            run = 1
    return stuff


def frame_bits(frame_id: int, data: bytes) -> int:
    """Wire bits of a classic standard data frame, actual stuffing (SOF..CRC), plus 13 tail bits."""
    bits = [0] + [(frame_id >> (10 - i)) & 1 for i in range(11)] + [0, 0, 0]
    bits += [(len(data) >> (3 - i)) & 1 for i in range(4)]
    for byte in data:
        bits += [(byte >> (7 - i)) & 1 for i in range(8)]
    c = crc15(bits)
    bits += [(c >> (14 - i)) & 1 for i in range(15)]
    return len(bits) + stuffed(bits) + 13


class Capture(can.Listener):
    """Frames of the UDS link seen by a second client on the bus (timestamps are bus times)."""

    def __init__(self, ids: set[int]) -> None:
        self.ids = ids
        self.frames: list[can.Message] = []
        self.lock = threading.Lock()

    def on_message_received(self, msg: can.Message) -> None:
        if msg.arbitration_id in self.ids:
            with self.lock:
                self.frames.append(msg)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--hil-sim", default=str(REPO / "build" / "hil_sim" / "hil_sim"))
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--kernels", type=int, default=50)
    args = ap.parse_args()
    image = fit(
        pressing(seed=3, duration_s=8.0), 100.0, n_kernels=args.kernels, surface_m=0.001
    ).skill.to_bytes()
    srv = subprocess.Popen(
        [args.hil_sim, "serve", "--port", "0", "--speed", "1", "--host-timeout", "500"],
        stdout=subprocess.PIPE,
        stderr=subprocess.DEVNULL,
        text=True,
    )
    try:
        line = srv.stdout.readline()
        port = int(line.split("127.0.0.1:")[1].split()[0])
        bus = can.Bus(interface="socketcand", host="127.0.0.1", port=port, channel="can0", tcp_tune=True)
        spy_bus = can.Bus(interface="socketcand", host="127.0.0.1", port=port, channel="can0")
        cap = Capture({U.UDS_REQUEST_BASE, U.UDS_RESPONSE_BASE})
        spy = can.Notifier(spy_bus, [cap], timeout=0.05)
        walls, bus_limited, on_bus = [], [], []
        with Device(bus, node=0, channel="can0", timeout_s=3.0) as dev:
            dev.wait_present()
            with U.uds_client(dev) as client:
                U.unlock(client, 0, 0x02)
                for _ in range(args.repeat):
                    time.sleep(0.2)
                    with cap.lock:
                        cap.frames.clear()
                    t0 = time.perf_counter()
                    U.download(client, 0, 1, image)
                    walls.append(time.perf_counter() - t0)
                    time.sleep(0.2)
                    with cap.lock:
                        fr = list(cap.frames)
                    bits = sum(frame_bits(m.arbitration_id, bytes(m.data)) for m in fr)
                    bus_limited.append(bits / BITRATE)
                    on_bus.append(
                        fr[-1].timestamp
                        - fr[0].timestamp
                        + frame_bits(fr[0].arbitration_id, bytes(fr[0].data)) / BITRATE
                    )
                assert U.upload(client, 0, 1, len(image)) == image
        spy.stop()
        spy_bus.shutdown()
        bus.shutdown()
    finally:
        srv.terminate()
        srv.wait()
    n_frames = len(fr)
    best, med = min(walls), statistics.median(walls)
    limit = statistics.median(bus_limited)
    print(
        f"can_upload kernels={args.kernels} bytes={len(image)} frames={n_frames} "
        f"bus_limited_ms={limit * 1e3:.2f} measured_best_ms={best * 1e3:.2f} measured_median_ms={med * 1e3:.2f} "
        f"bus_span_median_ms={statistics.median(on_bus) * 1e3:.2f} ratio_median={med / limit:.2f} (must be <= 2)"
    )
    return 0 if med <= 2.0 * limit else 1


if __name__ == "__main__":
    sys.exit(main())

"""Benchmark: the device's safety frames on a bus flooded by frames it ignores.

Runs `hil_sim serve` (real time, the device's default 100 ms host-silence timeout), puts the
device in TEACH (1 kHz telemetry) with the product's Device heartbeat, then floods the bus from a
raw socketcand client with 8-byte frames of one identifier, more than the bus can carry:
  phase UDS:       id 0x640 (below the device's UDS answers, 0x680): a ReadDataByIdentifier
                   request sent just before leaves its multi-frame answer queued behind the flood;
  phase telemetry: id 0x185 (between status 0x180 and telemetry 0x190/0x1A0): every telemetry
                   frame queues behind it; the heartbeat then stops, the device latches fault 500
                   (host silence) and sends its emergency frame (0x080) during the flood.
A recorder client keeps every frame with its bus timestamp (the simulator's bus time). Printed:
the flood's bus load, the largest gap between status frames (period 10 ms) in each phase, the
emergency frame's latency after the tick that latched the fault, and whether the UDS answer was
held until the flood ended (it may be: it has the lowest priority).

Usage: flood.py [--hil-sim PATH] [--seconds S]   (tests/can/test_priority.py asserts the figures)"""

from __future__ import annotations

import argparse
import itertools
import logging
import re
import socket
import subprocess
import sys
import threading
import time
from dataclasses import dataclass, field
from pathlib import Path

import can

REPO = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPO / "host"))

from forceskill.link import uds as U  # noqa: E402
from forceskill.link.device import Device  # noqa: E402
from forceskill.wire.dbc import load_db  # noqa: E402

logging.getLogger("can.interfaces.socketcand.socketcand").setLevel(logging.ERROR)

FRAME_RE = re.compile(rb"< frame ([0-9A-F]+) (\d+)\.(\d+) ([0-9A-F]*) >")
ID_EMCY, ID_STATUS, ID_UDS_REQ, ID_UDS_RESP = 0x080, 0x180, 0x600, 0x680


class Raw:
    """A raw socketcand client: handshake, then send text commands and/or record everything."""

    def __init__(self, port: int) -> None:
        self.s = socket.create_connection(("127.0.0.1", port))
        self.buf = bytearray()
        self._expect(b"< hi >")
        self.s.sendall(b"< open can0 >")
        self._expect(b"< ok >")
        self.s.sendall(b"< rawmode >")
        self._expect(b"< ok >")
        self.stop = threading.Event()
        self.t = threading.Thread(target=self._read, daemon=True)
        self.t.start()

    def _expect(self, token: bytes) -> None:
        while token not in self.buf:
            chunk = self.s.recv(4096)
            if not chunk:
                raise RuntimeError("socketcand closed")
            self.buf += chunk
        self.buf = self.buf[self.buf.index(token) + len(token) :]

    def _read(self) -> None:
        self.s.settimeout(0.2)
        while not self.stop.is_set():
            try:
                chunk = self.s.recv(1 << 16)
            except TimeoutError:
                continue
            except OSError:
                return
            if not chunk:
                return
            self.buf += chunk

    def frames(self) -> list[tuple[int, float, bytes]]:
        return [
            (
                int(m.group(1), 16),
                int(m.group(2)) + int(m.group(3)) * 1e-6,
                bytes.fromhex(m.group(4).decode()),
            )
            for m in FRAME_RE.finditer(bytes(self.buf))
        ]

    def close(self) -> None:
        self.stop.set()
        self.t.join(timeout=2)
        self.s.close()


class Flooder(Raw):
    """Sends frames of one identifier faster than the bus carries them (the server's queue for
    this client stays full; what does not fit is dropped there)."""

    def __init__(self, port: int, frame_id: int) -> None:
        super().__init__(port)
        self.frame_id = frame_id
        self.running = threading.Event()
        self.sender = threading.Thread(target=self._send, daemon=True)
        self.sender.start()

    def _read(self) -> None:  # drain what the server broadcasts; keep nothing
        self.s.settimeout(0.2)
        while not self.stop.is_set():
            try:
                if not self.s.recv(1 << 16):
                    return
            except TimeoutError:
                continue
            except OSError:
                return

    def _send(self) -> None:
        batch = (f"< send {self.frame_id:X} 8 55 55 55 55 55 55 55 55 >".encode()) * 1500
        while not self.stop.is_set():
            if self.running.is_set():
                try:
                    self.s.sendall(batch)
                except OSError:
                    return
            time.sleep(0.1)


@dataclass
class Result:
    phases: dict = field(default_factory=dict)  # name -> (t0, t1)
    flood_load: dict = field(default_factory=dict)  # name -> share of the bus time
    status_gap_ms: dict = field(default_factory=dict)
    emcy_latency_ms: float = float("nan")
    emcy_code: int = -1
    uds_answer_t: float = float("nan")
    frames: int = 0

    def lines(self) -> list[str]:
        out = [f"frames recorded: {self.frames}"]
        for name, (t0, t1) in self.phases.items():
            out.append(
                f"phase {name}: {t1 - t0:.2f} s flooded, flood {100 * self.flood_load[name]:.1f} % "
                f"of the bus, largest status gap {self.status_gap_ms[name]:.2f} ms (period 10 ms)"
            )
        out.append(
            f"emergency frame (fault {self.emcy_code}) {self.emcy_latency_ms:.3f} ms after the tick "
            "that latched the fault"
        )
        uds_t0, uds_t1 = self.phases["UDS"]
        out.append(
            "UDS answer: first frame at "
            + (
                f"{self.uds_answer_t - uds_t0:.3f} s into the UDS flood"
                if self.uds_answer_t == self.uds_answer_t
                else "never"
            )
            + f" (flood ended at {uds_t1 - uds_t0:.3f} s)"
        )
        return out


def _phase_window(frames, frame_id, lo, hi):
    ts = [t for i, t, _ in frames if i == frame_id and lo <= t <= hi]
    return (ts[0], ts[-1]) if ts else (lo, lo)


def measure(port: int, seconds: float = 1.5) -> Result:
    db = load_db(0)
    status_msg = db.get_message_by_frame_id(ID_STATUS)
    emcy_msg = db.get_message_by_frame_id(ID_EMCY)
    rec = Raw(port)
    host = can.Bus(interface="socketcand", host="127.0.0.1", port=port, channel="can0")
    res = Result()
    try:
        with Device(host) as dev:
            dev.wait_present()
            with U.uds_client(dev) as client:
                U.motion_session(client, dev)  # authenticated heartbeats and commands
            dev.start_heartbeat(telemetry_period_ms=1)
            dev.command_until("teach", {"TEACH"}, 5.0)
            # phase UDS: flood at 0x640, then request the slot directory (0x600 wins over the
            # flood; the 129-byte answer's first frame, 0x680, queues behind it)
            f1 = Flooder(port, 0x640)
            f1.running.set()
            time.sleep(0.2)
            host.send(
                can.Message(
                    arbitration_id=ID_UDS_REQ,
                    is_extended_id=False,
                    data=[0x03, 0x22, 0x02, 0x00, 0xCC, 0xCC, 0xCC, 0xCC],
                )
            )
            time.sleep(seconds)
            f1.close()
            time.sleep(0.3)
            # phase telemetry: flood at 0x185, then the host goes silent -> fault 500
            f2 = Flooder(port, 0x185)
            f2.running.set()
            time.sleep(seconds / 2)
            dev.stop_heartbeat()
            time.sleep(seconds / 2)
            f2.close()
            time.sleep(0.3)
    finally:
        host.shutdown()
        time.sleep(0.2)
        rec.close()
    frames = rec.frames()
    res.frames = len(frames)
    end = frames[-1][1] if frames else 0.0
    res.phases["UDS"] = _phase_window(frames, 0x640, 0.0, end)
    res.phases["telemetry"] = _phase_window(frames, 0x185, 0.0, end)
    for name, fid in (("UDS", 0x640), ("telemetry", 0x185)):
        t0, t1 = res.phases[name]
        bits = sum(111 for i, t, _ in frames if i == fid and t0 <= t <= t1)  # unstuffed 8-byte frame
        res.flood_load[name] = bits * 1e-6 / max(t1 - t0, 1e-9)
        st = [t for i, t, _ in frames if i == ID_STATUS and t0 - 0.02 <= t <= t1 + 0.02]
        res.status_gap_ms[name] = (
            max((b - a) * 1e3 for a, b in itertools.pairwise(st)) if len(st) > 1 else float("inf")
        )
    # device epoch: the bus time of tick 0 (a status frame leaves at the earliest its own wire
    # time, >= 111 bits = 0.111 ms, after its tick: the latency below is an upper bound)
    epoch = min(t - status_msg.decode(d)["Tick"] * 1e-3 for i, t, d in frames if i == ID_STATUS) - 111e-6
    for i, t, d in frames:
        if i == ID_EMCY:
            sig = emcy_msg.decode(d, decode_choices=False)
            res.emcy_code = int(sig["FaultCode"])
            res.emcy_latency_ms = (t - (epoch + sig["Tick"] * 1e-3)) * 1e3
            break
    uds = [t for i, t, _ in frames if i == ID_UDS_RESP and t >= res.phases["UDS"][0] - 0.01]
    res.uds_answer_t = uds[0] if uds else float("nan")
    return res


def start_server(hil_sim: Path) -> tuple[subprocess.Popen, int]:
    proc = subprocess.Popen(
        [
            str(hil_sim),
            "serve",
            "--port",
            "0",
            "--scenario",
            str(REPO / "hil_sim" / "scenarios" / "pressing_task1_demo.toml"),
            "--host-timeout",
            "100",
        ],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    line = proc.stdout.readline() if proc.stdout else ""
    if "listening on 127.0.0.1:" not in line:
        raise RuntimeError(f"hil_sim serve did not start: {line!r}")
    return proc, int(line.split("127.0.0.1:")[1].split()[0])


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--hil-sim", default=str(REPO / "build" / "hil_sim" / "hil_sim"))
    ap.add_argument("--seconds", type=float, default=1.5, help="length of each flood phase")
    a = ap.parse_args()
    proc, port = start_server(Path(a.hil_sim))
    try:
        res = measure(port, a.seconds)
    finally:
        proc.terminate()
        _, err = proc.communicate(timeout=10)
    for line in res.lines():
        print(line)
    print(err.strip().splitlines()[-1] if err.strip() else "")
    return 0


if __name__ == "__main__":
    sys.exit(main())

"""A third-party node on the simulator's bus, written from docs/protocol.md alone: python-can
directly, frames built from the public DBC layout with its own AUTOSAR CRC-8 and raw ISO-TP, nothing
of forceskill's frame code. It sniffs every frame and sends whatever it builds."""

from __future__ import annotations

import struct
import subprocess
import sys
import time
from pathlib import Path

import can
import udsoncan
from udsoncan.client import Client
from udsoncan.connections import PythonIsoTpConnection

from helpers.canbus import REPO

SKILL = REPO / "tests" / "vectors" / "press_n50_lwr_hold.skill"
CMD, HB, STATUS = 0x100, 0x110, 0x180
IDLE, TEACH, EXECUTE, RUN_OPTIONS = 1, 2, 3, 5
STATE_NAMES = {1: "IDLE", 2: "TEACH", 3: "EXECUTE", 4: "FAULT"}


def crc8_autosar(data: bytes) -> int:
    """Crc_CalculateCRC8 (SAE J1850): poly 0x1D, init 0xFF, xorout 0xFF; "123456789" -> 0x4B."""
    crc = 0xFF
    for b in data:
        crc ^= b
        for _ in range(8):
            crc = ((crc << 1) ^ 0x1D) & 0xFF if crc & 0x80 else (crc << 1) & 0xFF
    return crc ^ 0xFF


def e2e_valid(frame_id: int, payload: bytes, fv_low: int, mac: bytes = b"\0\0\0") -> bytes:
    """The attacker's frame: payload bytes 0..2, a MAC guess, freshness/counter byte, CRC-8."""
    b = bytearray(payload[:3].ljust(3, b"\0") + mac + bytes([fv_low & 0xFF]))
    b.append(crc8_autosar(bytes([frame_id & 0xFF, frame_id >> 8]) + bytes(b)))
    return bytes(b)


class Attacker:
    """A raw python-can client: sniffs every frame, sends whatever it builds."""

    def __init__(self, port: int) -> None:
        self.bus = can.Bus(interface="socketcand", host="127.0.0.1", port=port, channel="can0")
        self.seen: list[can.Message] = []
        self.state = 0
        self.notifier = can.Notifier(self.bus, [self._on])

    def _on(self, m: can.Message) -> None:
        self.seen.append(m)
        if m.arbitration_id == STATUS:
            self.state = m.data[0] & 0x0F

    def send(self, frame_id: int, data: bytes) -> None:
        self.bus.send(can.Message(arbitration_id=frame_id, data=data, is_extended_id=False))

    def stats(self) -> dict[str, int]:
        """DID 0x0303 read with udsoncan (reading is open to any node)."""
        import isotp

        tp = isotp.NotifierBasedCanStack(
            self.bus,
            self.notifier,
            address=isotp.Address(isotp.AddressingMode.Normal_11bits, txid=0x600, rxid=0x680),
            params={"tx_padding": 0xCC, "tx_data_min_length": 8},
        )
        cfg = dict(udsoncan.configs.default_client_config)
        cfg["data_identifiers"] = {0x0303: _Raw35()}
        with Client(PythonIsoTpConnection(tp), config=cfg) as c:
            r = bytes(c.read_data_by_identifier(0x0303).service_data.values[0x0303])
        keys = (
            "accepted",
            "wrong_mac",
            "replay",
            "no_key",
            "discarded",
            "last",
            "keyed",
            "fv_cmd",
            "fv_hb",
            "foreign",
        )
        return dict(zip(keys, struct.unpack(">IIIIIHBIII", r), strict=True))

    def close(self) -> None:
        self.notifier.stop()
        self.bus.shutdown()


class _Raw35(udsoncan.DidCodec):
    def decode(self, payload: bytes) -> bytes:
        return bytes(payload)

    def __len__(self) -> int:
        return 35


def forge_motion(a: Attacker, fv0: int) -> None:
    """Heartbeats, TEACH, and RUN_OPTIONS + EXECUTE of slot 1 at goal x3, every freshness value
    and a different MAC guess each time, for 0.5 s."""
    for i in range(50):
        fv = fv0 + i
        mac = struct.pack(">I", (i * 2654435761) & 0xFFFFFF)[1:]
        a.send(HB, e2e_valid(HB, bytes([1]), fv, mac))
        if i % 10 == 0:
            a.send(CMD, e2e_valid(CMD, bytes([TEACH]), fv, mac))
        if i % 10 == 5:
            ts = 1000 << 4  # TimeScale 1.000 in bits 4..19
            a.send(CMD, e2e_valid(CMD, bytes([RUN_OPTIONS | ts & 0xF0, ts >> 8 & 0xFF, ts >> 16]), fv, mac))
            goal = 3000
            a.send(CMD, e2e_valid(CMD, bytes([EXECUTE | 1 << 4, goal & 0xFF, goal >> 8]), fv + 1, mac))
        time.sleep(0.01)


def flood(port: int, rate_hz: float, seconds: float) -> None:
    """A node of its own (run it in another process): forged heartbeats and commands (valid CRC,
    wrong MACs, any freshness) at rate_hz for seconds, in bursts every 5 ms."""
    bus = can.Bus(interface="socketcand", host="127.0.0.1", port=port, channel="can0")
    try:
        per = max(1, round(rate_hz * 0.005))
        i = 0
        t0 = nxt = time.monotonic()
        while time.monotonic() - t0 < seconds:
            for _ in range(per):
                fid = HB if i % 2 else CMD
                mac = struct.pack(">I", (i * 2654435761) & 0xFFFFFF)[1:]
                bus.send(
                    can.Message(
                        arbitration_id=fid,
                        data=e2e_valid(fid, bytes([fid == HB]), i, mac),
                        is_extended_id=False,
                    )
                )
                i += 1
            nxt += 0.005
            time.sleep(max(0.0, nxt - time.monotonic()))
    finally:
        bus.shutdown()


def refused(stats: dict[str, int]) -> int:
    """Host frames the device refused for their MAC: wrong, replayed, or without a key."""
    return stats["wrong_mac"] + stats["replay"] + stats["no_key"]


def flood_node(port: int, rate_hz: float, seconds: float) -> subprocess.Popen[bytes]:
    """flood() in a process of its own (its own interpreter: the host under test keeps its GIL)."""
    tests = str(Path(__file__).resolve().parents[1])
    code = f"import sys; sys.path.insert(0, {tests!r}); from helpers.attacker import flood; flood({port}, {rate_hz}, {seconds})"
    return subprocess.Popen([sys.executable, "-c", code])


def wait_flood(
    a: Attacker, node: subprocess.Popen[bytes], frames: int = 300, timeout_s: float = 20.0
) -> None:
    """Until the device has refused `frames` more forged frames than before (the flood began)."""
    start = refused(a.stats())
    end = time.monotonic() + timeout_s
    while refused(a.stats()) < start + frames:
        assert node.poll() is None, f"the flooding node ended ({node.returncode})"
        assert time.monotonic() < end, "the flood never reached the device"
        time.sleep(0.05)

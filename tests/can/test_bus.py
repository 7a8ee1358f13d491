"""The simulator's bus as python-can sees it: socketcand handshake, several clients seeing each
other's frames (not their own), the frame format, and the bitrate model's pacing."""

from __future__ import annotations

import importlib.util
import itertools
import re
import socket
import time
from pathlib import Path

import can

_spec = importlib.util.spec_from_file_location(
    "can_upload", Path(__file__).resolve().parents[2] / "bench" / "can_upload" / "can_upload.py"
)
_bench = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(_bench)
frame_bits = _bench.frame_bits  # independent (Python) CAN frame length with bit stuffing


def open_bus(server) -> can.BusABC:
    return can.Bus(interface="socketcand", host="127.0.0.1", port=server.port, channel="can0")


def recv_id(bus: can.BusABC, frame_id: int, timeout: float = 2.0):
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        m = bus.recv(0.1)
        if m is not None and m.arbitration_id == frame_id:
            return m
    return None


def test_handshake_replies_alone(server):
    s = socket.create_connection(("127.0.0.1", server.port), timeout=2)
    assert s.recv(256) == b"< hi >"
    s.sendall(b"< open can0 >")
    assert s.recv(256) == b"< ok >"
    s.sendall(b"< rawmode >")
    assert s.recv(256) == b"< ok >"  # alone: no frame in the same read
    time.sleep(0.3)
    data = s.recv(65536).decode()
    # then frames, '< frame ID SEC.USEC HEXDATA >': whichever of the device's comes first (its
    # telemetry, status or contact frame, by the tick the connection landed in), 8 bytes each
    first = data.split(">")[0] + ">"
    m = re.fullmatch(r"< frame (180|190|1A0) \d+\.\d{6} ([0-9A-F]{16}) >", first)
    assert m, data[:200]
    s.close()


def test_wrong_channel_refused(server):
    s = socket.create_connection(("127.0.0.1", server.port), timeout=2)
    assert s.recv(256) == b"< hi >"
    s.sendall(b"< open can7 >")
    assert s.recv(256).startswith(b"< error")
    s.close()


def test_clients_see_each_other(server):
    a, b = open_bus(server), open_bus(server)
    try:
        time.sleep(0.2)
        a.send(can.Message(arbitration_id=0x7A1, data=[1, 2, 3, 0xFF], is_extended_id=False))
        m = recv_id(b, 0x7A1)
        assert m is not None and bytes(m.data) == bytes([1, 2, 3, 0xFF]) and not m.is_extended_id
        b.send(can.Message(arbitration_id=0x1ABCDE, data=[9], is_extended_id=True))
        m = recv_id(a, 0x1ABCDE)
        assert m is not None and m.is_extended_id and bytes(m.data) == b"\x09"
        assert recv_id(a, 0x7A1, timeout=0.5) is None  # no echo of its own frame
    finally:
        a.shutdown()
        b.shutdown()


def test_bus_time_paced_by_bitrate(server):
    """100 frames of 8 bytes sent at once arrive spaced by their bit time at 1 Mbit/s."""
    a, b = open_bus(server), open_bus(server)
    try:
        time.sleep(0.2)
        for i in range(100):
            a.send(can.Message(arbitration_id=0x7B0, data=[i, 0, 0, 0, 0, 0, 0, 0], is_extended_id=False))
        got = []
        end = time.monotonic() + 5
        while len(got) < 100 and time.monotonic() < end:
            m = b.recv(0.2)
            if m is not None and m.arbitration_id == 0x7B0:
                got.append(m)
        assert [m.data[0] for m in got] == list(range(100))  # in order
        dt = [(y.timestamp - x.timestamp) * 1e6 for x, y in itertools.pairwise(got)]
        # 8-byte standard frame: 111 bits unstuffed, 135 worst case; other traffic may interleave
        assert min(dt) >= 111 - 1 and sorted(dt)[len(dt) // 2] <= 135 + 1
        # back to back, a frame ends exactly its own wire time (actual stuff bits) after the previous
        exact = [
            d for d, y in zip(dt, got[1:], strict=False) if abs(d - frame_bits(0x7B0, bytes(y.data))) < 0.5
        ]
        assert len(exact) >= 80, sorted(dt)[:10]
    finally:
        a.shutdown()
        b.shutdown()


def test_burst_larger_than_server_input_buffer(server):
    """600 frames written in one go (~24 KB of '< send >' commands, about three times the
    server's 8 KB input buffer, as can-isotp sends a 4095-byte message with BS 0 / STmin 0): every frame
    reaches the bus, in order."""
    a = socket.create_connection(("127.0.0.1", server.port), timeout=2)
    b = open_bus(server)
    try:
        assert a.recv(256) == b"< hi >"
        a.sendall(b"< open can0 >")
        assert a.recv(256) == b"< ok >"
        a.sendall(b"< rawmode >")
        assert a.recv(256) == b"< ok >"
        time.sleep(0.2)
        burst = "".join(f"< send 7C1 8 {i >> 8:x} {i & 0xFF:x} aa bb cc dd ee ff >" for i in range(600))
        assert len(burst) > 2 * 8192
        a.sendall(burst.encode())
        got = []
        end = time.monotonic() + 10
        while len(got) < 600 and time.monotonic() < end:
            m = b.recv(0.2)
            if m is not None and m.arbitration_id == 0x7C1:
                got.append((m.data[0] << 8) | m.data[1])
        assert got == list(range(600))
    finally:
        a.close()
        b.shutdown()

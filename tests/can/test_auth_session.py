"""The unlocked UDS session belongs to the tester that unlocked it. Two udsoncan clients on the
simulator's bus, each with its own python-can connection and tester id (0x600/0x680 and the
second tester's 0x640/0x6C0, docs/protocol.md), both knowing the level-1 secret: once tester A's
SecurityAccess unlocks the extended session, tester B's writes (a DID, a routine start, a session
change, its own SecurityAccess, a download) are refused with 0x33 and counted (DID 0x0303, last
refusal 558), its reads still answered; A's own writes go on. Once A's session ends, B can unlock
it and then owns it: A's writes are refused in turn."""

from __future__ import annotations

import struct
import time
from collections.abc import Iterator
from contextlib import contextmanager

import can
import isotp
import pytest
import udsoncan
from udsoncan.client import Client
from udsoncan.connections import PythonIsoTpConnection
from udsoncan.exceptions import NegativeResponseException

from forceskill.link.uds import security_key
from helpers.canbus import SCENARIOS, Server

TESTER_A = (0x600, 0x680)
TESTER_B = (0x640, 0x6C0)
DID_STIFFNESS_MAX, DID_AUTH_STATS = 0x0140, 0x0303


class _Raw(udsoncan.DidCodec):
    def __init__(self, n: int) -> None:
        self.n = n

    def encode(self, value: bytes) -> bytes:
        return bytes(value)

    def decode(self, payload: bytes) -> bytes:
        return bytes(payload)

    def __len__(self) -> int:
        return self.n


@contextmanager
def open_tester(port: int, ids: tuple[int, int]) -> Iterator[Client]:
    """A udsoncan client of its own python-can connection, on the tester ids (request, response)."""
    bus = can.Bus(interface="socketcand", host="127.0.0.1", port=port, channel="can0")
    notifier = can.Notifier(bus, [])
    tp = isotp.NotifierBasedCanStack(
        bus,
        notifier,
        address=isotp.Address(isotp.AddressingMode.Normal_11bits, txid=ids[0], rxid=ids[1]),
        params={"tx_padding": 0xCC, "tx_data_min_length": 8},
    )
    cfg = dict(udsoncan.configs.default_client_config)
    cfg["data_identifiers"] = {DID_STIFFNESS_MAX: _Raw(4), DID_AUTH_STATS: _Raw(35)}
    cfg["security_algo"] = lambda level, seed, params: security_key(bytes(seed))
    cfg["request_timeout"] = 5.0
    cfg["p2_timeout"] = 2.0
    cfg["p2_star_timeout"] = 5.0
    cfg["use_server_timing"] = False
    try:
        with Client(PythonIsoTpConnection(tp), config=cfg) as c:
            yield c
    finally:
        notifier.stop()
        bus.shutdown()


def unlock(c: Client) -> None:
    """Extended session and SecurityAccess level 1 (the device answers 0x37 for 1 s at power-up)."""
    c.change_session(3)
    end = time.monotonic() + 5.0
    while True:
        try:
            c.unlock_security_access(1)
            return
        except NegativeResponseException as e:
            if e.response.code != 0x37 or time.monotonic() > end:
                raise
            time.sleep(0.2)


def refused_0x33(fn) -> None:  # type: ignore[no-untyped-def]
    with pytest.raises(NegativeResponseException) as e:
        fn()
    assert e.value.response.code == 0x33, hex(e.value.response.code)


def stats(c: Client) -> tuple[int, int]:
    """(last refusal code, UDS writes refused for the other tester) of DID 0x0303."""
    r = bytes(c.read_data_by_identifier(DID_AUTH_STATS).service_data.values[DID_AUTH_STATS])
    v = struct.unpack(">IIIIIHBIII", r)
    return v[5], v[9]


@pytest.fixture(scope="module")
def server() -> Iterator[Server]:
    s = Server(SCENARIOS / "pressing_task1_demo.toml")
    time.sleep(0.2)
    yield s
    s.stop()


def test_the_session_belongs_to_the_tester_that_unlocked_it(server: Server) -> None:
    with open_tester(server.port, TESTER_A) as a, open_tester(server.port, TESTER_B) as b:
        unlock(a)
        k = bytes(a.read_data_by_identifier(DID_STIFFNESS_MAX).service_data.values[DID_STIFFNESS_MAX])
        _, before = stats(b)
        refused_0x33(lambda: b.write_data_by_identifier(DID_STIFFNESS_MAX, k))
        refused_0x33(lambda: b.start_routine(0x0201, data=bytes([1, 0x03, 0xE8, 0x03, 0xE8, 0])))
        refused_0x33(lambda: b.change_session(2))
        refused_0x33(lambda: b.request_seed(1))
        refused_0x33(
            lambda: b.request_download(
                udsoncan.MemoryLocation(0x01, 64, address_format=32, memorysize_format=32)
            )
        )
        last, after = stats(b)  # reads stay open to every tester
        assert (last, after - before) == (558, 5)
        # the owner's own writes and session go on
        a.write_data_by_identifier(DID_STIFFNESS_MAX, k)
        a.tester_present()
        # A's session ends (back to the default session): B may unlock it and owns it then
        a.change_session(1)
        unlock(b)
        b.write_data_by_identifier(DID_STIFFNESS_MAX, k)
        refused_0x33(lambda: a.write_data_by_identifier(DID_STIFFNESS_MAX, k))
        refused_0x33(lambda: a.change_session(3))
        b.change_session(1)
        assert stats(a) == (558, after + 2)

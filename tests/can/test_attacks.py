"""A node without any key (tests/helpers/attacker.py: python-can, its own CRC-8 and ISO-TP frames,
written from docs/protocol.md alone) against `hil_sim serve` while the genuine host works. It
cannot block the host's stop, make a command the host sent and lost act later, take a session with
a key read off the bus, or delay the host-silence stop by flooding the bus. Each attack has its
positive control: the same path acting when it should (the attack's frames reach the device and
are counted; the genuine frames on time act; the genuine key unlocks)."""

from __future__ import annotations

import hashlib
import hmac
import re
import time
from collections.abc import Iterator
from contextlib import contextmanager
from typing import Any

import can
import pytest

from forceskill import cli
from helpers.attacker import (
    CMD,
    EXECUTE,
    HB,
    SKILL,
    STATE_NAMES,
    Attacker,
    e2e_valid,
    flood_node,
    refused,
    wait_flood,
)
from helpers.canbus import SCENARIOS, SPEED, Server

IDLE_S, EXECUTE_S, FAULT_S = 1, 3, 4
EMERGENCY = 0x080
FLT_HOST_SILENCE = 500


@pytest.fixture(scope="module")
def loaded():
    s = Server(SCENARIOS / "pressing_task1_demo.toml")
    time.sleep(0.2)
    assert cli.main(["upload", str(SKILL), "--slot", "1", "-q", *s.bus_args()]) == 0
    yield s
    s.stop()


@contextmanager
def genuine_host(port: int) -> Iterator[Any]:
    """The product's host: the motion key established, its heartbeat running."""
    from forceskill.link import uds as U
    from forceskill.link.device import Device

    bus = can.Bus(interface="socketcand", host="127.0.0.1", port=port, channel="can0")
    try:
        with Device(bus, timeout_s=3.0) as dev, U.uds_client(dev) as client:
            dev.wait_present()
            U.motion_session(client, dev)
            dev.start_heartbeat(telemetry_period_ms=10)
            try:
                yield dev
            finally:
                dev.stop_heartbeat()
    finally:
        bus.shutdown()


def wait_state(a: Attacker, state: int, timeout_s: float) -> bool:
    end = time.monotonic() + timeout_s / min(SPEED, 1.0)
    while time.monotonic() < end:
        if a.state == state:
            return True
        time.sleep(0.002)
    return a.state == state


def test_a_forged_frame_never_blocks_the_hosts_stop(loaded):
    """A forged command carrying the counter the host's next frame will carry (valid CRC, wrong
    MAC) once moved the device's E2E counter and made the host's stop a "repeat": now the host's
    single IDLE frame stops the run at once, in every round."""
    a = Attacker(loaded.port)
    try:
        with genuine_host(loaded.port) as dev:
            for _ in range(3):
                dev.command("execute", slot=1, goal_scale=1.0)
                assert wait_state(a, EXECUTE_S, 2.0), STATE_NAMES.get(a.state)
                before = a.stats()
                host_cmds = [m for m in a.seen if m.arbitration_id == CMD]
                nxt = (host_cmds[-1].data[6] + 1) & 0xFF
                for k in range(3):  # the next values the host's IDLE may carry
                    a.send(CMD, e2e_valid(CMD, bytes([0]), nxt + k, bytes([0x5A, k, 0xA5])))
                time.sleep(0.05)
                assert a.state == EXECUTE_S
                dev.command("idle")  # one frame, not repeated
                assert wait_state(a, IDLE_S, 0.5), STATE_NAMES.get(a.state)
                after = a.stats()
                # positive control: the forged frames reached the device (refused by their MAC)
                assert after["wrong_mac"] - before["wrong_mac"] == 3, (before, after)
                time.sleep(0.05)
    finally:
        a.close()


def test_a_lost_command_never_acts_later(loaded):
    """RUN_OPTIONS + EXECUTE the host sent and lost (recorded by the attacker, never delivered):
    delivered on time they run the skill (positive control); delivered 1 s later, after the host
    gave up with IDLE and its heartbeat went on, or after the host went silent, never."""
    a = Attacker(loaded.port)
    try:
        with genuine_host(loaded.port) as dev:
            # positive control: the frames, built by the host and delivered by the attacker at once
            pair = [dev._frame("HostCommand", {"Mode": 5, "TimeScale": 1.0})[0]]
            pair.append(dev._frame("HostCommand", {"Mode": EXECUTE, "Slot": 1, "GoalScale": 1.0})[0])
            for data in pair:
                a.send(CMD, data)
            assert wait_state(a, EXECUTE_S, 1.0), STATE_NAMES.get(a.state)
            dev.command_until("idle", {"IDLE"}, 3.0)

            def lost_pair() -> list[bytes]:
                """The host sends the pair; the bus loses it (the attacker keeps it)."""
                kept: list[bytes] = []
                send = dev.bus.send

                def lose(msg: can.Message, timeout: float | None = None) -> None:
                    if msg.arbitration_id == CMD:
                        kept.append(bytes(msg.data))
                    else:
                        send(msg, timeout)

                dev.bus.send = lose
                try:
                    dev.command("execute", slot=1, goal_scale=1.0)
                finally:
                    dev.bus.send = send
                assert len(kept) == 2
                return kept

            # the host gives up with IDLE, its heartbeat goes on; the pair a second later
            kept = lost_pair()
            dev.command("idle")
            time.sleep(1.0)
            before = a.stats()
            for data in kept:
                a.send(CMD, data)
            time.sleep(0.3)
            assert a.state == IDLE_S, STATE_NAMES.get(a.state)
            after = a.stats()
            # refused: the heartbeats voided them. A replay is counted as such when its check runs
            # alone; the first of two frames that arrive in one tick takes the check without the
            # replay block while the second waits (secoc_verify_begin_fast), a wrong MAC there
            refused = [after[k] - before[k] for k in ("replay", "wrong_mac")]
            assert sum(refused) == 2 and refused[0] >= 1, refused
            # the host goes silent right after losing the pair: a second later it is refused as late
            kept = lost_pair()
            dev.stop_heartbeat()
            time.sleep(1.0)
            for data in kept:
                a.send(CMD, data)
            time.sleep(0.3)
            assert a.state == IDLE_S, STATE_NAMES.get(a.state)
            assert a.stats()["last"] == 559  # SEC_ERR_STALE
    finally:
        a.close()


class RawTester:
    """ISO-TP by hand on one request/response id pair (classic CAN, 8-byte frames)."""

    def __init__(self, a: Attacker, req: int, resp: int) -> None:
        self.a, self.req, self.resp = a, req, resp

    def frames(self, since: int) -> list[bytes]:
        return [bytes(m.data) for m in self.a.seen[since:] if m.arbitration_id == self.resp]

    def request(self, payload: bytes, timeout_s: float = 2.0) -> bytes:
        """Send payload (SF, or FF + CFs after the device's FC), return the response's payload
        (FC sent for a multi-frame one; 0x78 answers skipped)."""
        mark = len(self.a.seen)
        self.send_ff(payload) if len(payload) > 7 else self.a.send(
            self.req, pad(bytes([len(payload)]) + payload)
        )
        if len(payload) > 7:
            self.wait_fc(mark)
            self.send_cfs(payload)
        return self.response(mark, timeout_s)

    def send_ff(self, payload: bytes) -> None:
        self.a.send(self.req, bytes([0x10 | len(payload) >> 8, len(payload) & 0xFF]) + payload[:6])

    def wait_fc(self, mark: int, timeout_s: float = 1.0) -> None:
        end = time.monotonic() + timeout_s
        while not any(f[0] >> 4 == 3 for f in self.frames(mark)):
            assert time.monotonic() < end, "no flow control"
            time.sleep(0.001)

    def send_cfs(self, payload: bytes, sn: int = 1) -> None:
        for i in range(6, len(payload), 7):
            self.a.send(self.req, pad(bytes([0x20 | sn & 0x0F]) + payload[i : i + 7]))
            sn += 1

    def response(self, mark: int, timeout_s: float) -> bytes:
        end = time.monotonic() + timeout_s
        out = b""
        want = -1
        while time.monotonic() < end:
            for f in self.frames(mark):
                kind = f[0] >> 4
                if kind == 0 and not (f[1] == 0x7F and f[3] == 0x78):
                    return f[1 : 1 + (f[0] & 0x0F)]
                if kind == 1 and want < 0:
                    want = (f[0] & 0x0F) << 8 | f[1]
                    out = f[2:8]
                    self.a.send(self.req, pad(b"\x30\x00\x00"))
                elif kind == 2 and want >= 0 and len(out) < want:
                    out += f[1:8]
            if want >= 0 and len(out) >= want:
                return out[:want]
            time.sleep(0.002)
        raise AssertionError(f"no response on 0x{self.resp:03X}")


def pad(b: bytes) -> bytes:
    return b.ljust(8, b"\xcc")


def key_of(seed: bytes) -> bytes:
    """The level-1 key the genuine host computes (docs/protocol.md: HMAC-SHA256(secret, seed)[:16],
    the simulator's published development secret)."""
    from forceskill.link.uds import device_secret

    return hmac.new(device_secret(1), seed, hashlib.sha256).digest()[:16]


def test_a_seed_belongs_to_its_tester(loaded):
    """The host asks a seed on 0x600 and starts its sendKey; the attacker aborts the reception with
    a wrong CF, reads the key off the bus and sends it on 0x640 (refused 0x24: no seed of that
    tester), and asks a seed on 0x640 itself; the host's key, sent again whole, still unlocks
    (positive control: the aborted reception and the other tester's seed voided nothing)."""
    time.sleep(5.5)  # the sessions of the tests before have timed out (S3)
    a = Attacker(loaded.port)
    try:
        host = RawTester(a, 0x600, 0x680)
        thief = RawTester(a, 0x640, 0x6C0)
        assert host.request(b"\x10\x03")[0] == 0x50
        assert thief.request(b"\x10\x03")[0] == 0x50
        seed_resp = host.request(b"\x27\x01")
        assert seed_resp[:2] == b"\x67\x01", seed_resp.hex()
        key_req = b"\x27\x02" + key_of(seed_resp[2:18])
        mark = len(a.seen)
        host.send_ff(key_req)
        a.send(0x600, pad(b"\x25" + b"\0" * 7))  # the attacker's wrong CF: the reception ends
        host.wait_fc(mark)
        host.send_cfs(key_req)  # the host's CFs, read by the attacker, land on no reception
        time.sleep(0.05)
        stolen = thief.request(key_req)
        assert stolen == b"\x7f\x27\x24", stolen.hex()
        assert thief.request(b"\x27\x01")[:2] == b"\x67\x01"  # its own seed: the host's stays
        ok = host.request(key_req)
        assert ok == b"\x67\x02", ok.hex()
        # the session is the host's: the attacker's writes are refused (0x33)
        assert thief.request(b"\x31\x01\x02\x04") == b"\x7f\x31\x33"
        assert host.request(b"\x10\x01")[0] == 0x50  # the host ends its session
    finally:
        a.close()


@pytest.mark.skipif(SPEED != 1.0, reason="the flood's rate is wall-clock: the simulator at real time")
def test_a_flood_neither_stops_a_run_nor_delays_the_silence_stop(loaded):
    """3,000 forged frames a second on the host's ids: a genuine run of the skill holds EXECUTE
    for 2 s (no fault), and once the host goes silent the device latches host silence within
    102 ms of the host's last heartbeat on the bus (the bus's timestamps: the simulator's
    clock)."""
    a = Attacker(loaded.port)
    node = None
    try:
        with genuine_host(loaded.port) as dev:
            node = flood_node(loaded.port, 3000.0, 8.0)
            wait_flood(a, node)
            dev.command("execute", slot=1, goal_scale=1.0)
            assert wait_state(a, EXECUTE_S, 2.0), STATE_NAMES.get(a.state)
            mark = len(a.seen)
            w0, t0 = a.stats(), time.monotonic()
            time.sleep(2.0)
            emcy = [bytes(m.data).hex() for m in a.seen[mark:] if m.arbitration_id == EMERGENCY]
            assert a.state == EXECUTE_S, (STATE_NAMES.get(a.state), emcy, a.stats())  # it goes on
            w1, t1 = a.stats(), time.monotonic()
            rate = (w1["wrong_mac"] - w0["wrong_mac"]) / (t1 - t0)
            assert rate >= 2500.0, rate  # positive control: the flood reached the device's check
            dev.stop_heartbeat()
            assert wait_state(a, FAULT_S, 1.0), STATE_NAMES.get(a.state)
            time.sleep(0.05)
        frames = a.seen[mark:]  # the attacker's own frames are not echoed to it: these are the others'
        last_hb = max((m for m in frames if m.arbitration_id == HB), key=lambda m: m.timestamp)
        emcy = next(m for m in frames if m.arbitration_id == EMERGENCY)
        assert emcy.data[0] | emcy.data[1] << 8 == FLT_HOST_SILENCE
        # the bus's timestamps are the simulator's clock (hil_sim/bus/scand.c)
        latency_ms = (emcy.timestamp - last_hb.timestamp) * 1000.0
        print(f"under the flood, host silence latched {latency_ms:.1f} ms after the last heartbeat")
        assert latency_ms <= 102.0, latency_ms
    finally:
        if node is not None:
            node.kill()
            node.wait()
        a.close()


@pytest.mark.skipif(SPEED != 1.0, reason="the flood's rate is wall-clock: the simulator at real time")
def test_a_genuine_run_completes_under_a_flood_with_its_accuracy(loaded, capsys, tmp_path):
    """`forceskill run` of the slot's skill to its end, once on a quiet bus and once beside 3,000
    forged frames a second from another node: both complete (exit 0) and the flood's run tracks
    the reference as well: RMS error within 0.5 point of the quiet run's, max within 1.5 (the max
    is one sample of the telemetry, which shares the flooded bus: one late frame moves it)."""

    def run() -> tuple[float, float]:
        capsys.readouterr()
        rc = cli.main(["run", "--slot", "1", "--end", "release", *loaded.bus_args()])
        out = capsys.readouterr().out
        assert rc == 0, out
        m = re.search(r"force tracking: max ([0-9.]+) %, RMS ([0-9.]+) %", out)
        assert m, out
        return float(m.group(1)), float(m.group(2))

    assert cli.main(["status", "--clear", *loaded.bus_args()]) in (0, 2)  # the test before faulted
    quiet = run()
    a = Attacker(loaded.port)
    node = flood_node(loaded.port, 3000.0, 30.0)
    try:
        before = a.stats()
        wait_flood(a, node)
        flooded = run()
        assert refused(a.stats()) - refused(before) > 6000  # it went on through the run
    finally:
        node.kill()
        node.wait()
        a.close()
    print(
        f"force tracking max / RMS: {quiet[0]:.2f} / {quiet[1]:.2f} % quiet, "
        f"{flooded[0]:.2f} / {flooded[1]:.2f} % beside the flood"
    )
    assert flooded[1] <= quiet[1] + 0.5 and flooded[0] <= quiet[0] + 1.5, (quiet, flooded)

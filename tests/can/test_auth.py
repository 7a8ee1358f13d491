"""Only the host that established the motion key moves the device. A third-party node on the bus
(python-can directly, frames built here from the public DBC layout with its own AUTOSAR CRC-8,
nothing of forceskill's frame code) that forges E2E-valid HostCommand and HostHeartbeat frames,
or replays the genuine host's frames it sniffed, neither starts, changes nor teaches motion:
every such frame is refused and counted in DID 0x0303; its UDS start of a run is refused (0x33)
without the level-1 session. The genuine host's own session keeps working alongside."""

from __future__ import annotations

import struct
import time

import can
import pytest
import udsoncan
from udsoncan.client import Client
from udsoncan.connections import PythonIsoTpConnection

from forceskill import cli
from helpers.attacker import (
    CMD,
    EXECUTE,
    RUN_OPTIONS,
    SKILL,
    STATE_NAMES,
    TEACH,
    Attacker,
    crc8_autosar,
    e2e_valid,
    forge_motion,
)
from helpers.canbus import SCENARIOS, SPEED, Server


@pytest.fixture(scope="module")
def loaded():
    s = Server(SCENARIOS / "pressing_task1_demo.toml")
    time.sleep(0.2)
    assert cli.main(["upload", str(SKILL), "--slot", "1", "-q", *s.bus_args()]) == 0
    yield s
    s.stop()


def test_crc8_is_autosar():
    assert crc8_autosar(b"123456789") == 0x4B


def test_forged_frames_without_the_key_never_move_the_device(loaded):
    a = Attacker(loaded.port)
    try:
        time.sleep(0.3)
        before = a.stats()
        forge_motion(a, 1)
        time.sleep(0.2)
        assert a.state == 1, STATE_NAMES.get(a.state)  # still IDLE: nothing started or taught
        after = a.stats()
        refused = sum(after[k] - before[k] for k in ("wrong_mac", "no_key", "replay"))
        assert refused >= 60 and after["accepted"] == before["accepted"], (before, after)
        assert after["last"] in (553, 555)  # wrong MAC or no key
    finally:
        a.close()


def test_replayed_and_forged_frames_are_refused_while_the_host_has_a_session(loaded):
    from forceskill.link import uds as U
    from forceskill.link.device import Device

    a = Attacker(loaded.port)
    bus = can.Bus(interface="socketcand", host="127.0.0.1", port=loaded.port, channel="can0")
    try:
        with Device(bus, timeout_s=3.0) as dev:
            dev.wait_present()
            with U.uds_client(dev) as client:
                U.motion_session(client, dev)
                dev.start_heartbeat(telemetry_period_ms=10)
                try:
                    dev.command_until("teach", {"TEACH"}, 3.0)
                    dev.command_until("idle", {"IDLE"}, 3.0)
                finally:
                    dev.stop_heartbeat()
            time.sleep(0.2)
            genuine = [bytes(m.data) for m in a.seen if m.arbitration_id == CMD and m.data[0] & 0x0F == TEACH]
            assert genuine
            before = a.stats()
            assert before["keyed"] == 1
            for data in genuine:  # the sniffed TEACH frames, sent again (E2E-valid as they are)
                a.send(CMD, data)
                time.sleep(0.02)
            time.sleep(0.2)
            assert a.state == 1, STATE_NAMES.get(a.state)
            mid = a.stats()
            assert mid["replay"] - before["replay"] == len(genuine) and mid["last"] == 554, (before, mid)
            assert mid["accepted"] == before["accepted"]
            for k in range(4):  # the next freshness values, MACs guessed: 260 frames
                forge_motion(a, before["fv_cmd"] + 1 + 50 * k)
            time.sleep(0.2)
            assert a.state == 1, STATE_NAMES.get(a.state)
            after = a.stats()
            assert after["accepted"] == mid["accepted"], (mid, after)
            # 256 wrong MACs in a row discard the key (the rest is refused as keyless)
            assert after["wrong_mac"] - mid["wrong_mac"] == 256 and after["discarded"] == mid["discarded"] + 1
            assert after["keyed"] == 0 and after["last"] in (553, 555)
    finally:
        bus.shutdown()
        a.close()


def test_forged_run_routine_is_refused_without_the_level_1_session(loaded):
    import isotp

    a = Attacker(loaded.port)
    try:
        # the genuine host's unlocked extended session of the test before ends after S3 (5 s
        # without requests); within it, a node sending on the same request id would share it
        # (docs/protocol.md, limits)
        time.sleep(9 / SPEED)  # S3 is 5 s of the device; a margin for a loaded machine
        tp = isotp.NotifierBasedCanStack(
            a.bus,
            a.notifier,
            address=isotp.Address(isotp.AddressingMode.Normal_11bits, txid=0x600, rxid=0x680),
            params={"tx_padding": 0xCC, "tx_data_min_length": 8},
        )
        with Client(PythonIsoTpConnection(tp), config=dict(udsoncan.configs.default_client_config)) as c:
            with pytest.raises(udsoncan.exceptions.NegativeResponseException) as e:
                c.start_routine(0x0201, data=bytes([1, 0x0B, 0xB8, 0x03, 0xE8, 0]))
            assert e.value.response.code == 0x33
        time.sleep(0.1)
        assert a.state == 1
    finally:
        a.close()


@pytest.mark.parametrize("bus_off_s", [0.3, 3.5])
def test_freshness_resynchronises_after_a_bus_off(bus_off_s):
    """TEACH, then the device's controller bus-off (fault 501) while the host's heartbeats keep
    counting: 0.3 s is inside the freshness window (30 lost heartbeats), 3.5 s beyond it (350:
    the key is discarded or the MAC fails). The same host's CLEAR_FAULT and next TEACH work
    either way: command_until re-establishes the session when its commands have no effect."""
    from forceskill.link import uds as U
    from forceskill.link.device import Device

    srv = Server(
        SCENARIOS / "pressing_task1_demo.toml",
        extra=("--bus-off-at", "1.5", "--bus-off-for", str(bus_off_s)),
    )
    bus = can.Bus(interface="socketcand", host="127.0.0.1", port=srv.port, channel="can0")
    try:
        with Device(bus, timeout_s=6.0) as dev:  # no status while bus-off
            dev.wait_present()
            with U.uds_client(dev, request_timeout_s=2.0) as client:
                U.motion_session(client, dev)
                dev.start_heartbeat(telemetry_period_ms=10)
                try:
                    dev.command_until("teach", {"TEACH"}, 3.0)
                    st = dev.wait_state({"FAULT"}, 5.0 / SPEED)
                    assert st.fault_code == 501
                    time.sleep((bus_off_s + 0.5) / SPEED)  # the controller is back on the bus
                    keyed_before = dev.session
                    st = dev.command_until("clear_fault", {"IDLE"}, 10.0)
                    assert st.state == "IDLE"
                    dev.command_until("teach", {"TEACH"}, 5.0)
                    dev.command_until("idle", {"IDLE"}, 3.0)
                finally:
                    dev.stop_heartbeat()
                resynced = dev.session is not keyed_before
        assert resynced == (bus_off_s > 2.5), "re-established only when the window was exceeded"
    finally:
        bus.shutdown()
        srv.stop()


def test_a_running_motion_is_not_changed_and_its_start_not_replayed(loaded):
    """The genuine host runs slot 1 at goal x1; meanwhile the attacker forges RUN_OPTIONS +
    EXECUTE at goal x3 and TEACH with guessed MACs at the freshness values that follow the sniffed
    ones: refused (wrong MAC), the run goes on unchanged (EXECUTE of slot 1). Once the device is
    IDLE again, the sniffed genuine RUN_OPTIONS + EXECUTE pair replayed starts nothing."""
    from forceskill.link import uds as U
    from forceskill.link.device import Device

    a = Attacker(loaded.port)
    bus = can.Bus(interface="socketcand", host="127.0.0.1", port=loaded.port, channel="can0")
    try:
        with Device(bus, timeout_s=3.0) as dev:
            dev.wait_present()
            with U.uds_client(dev) as client:
                U.motion_session(client, dev)
                dev.start_heartbeat(telemetry_period_ms=10)
                try:
                    dev.command("execute", slot=1, goal_scale=1.0)
                    dev.wait_state({"EXECUTE"}, 3.0)
                    before = a.stats()
                    fv = before["fv_cmd"] + 1
                    for i in range(20):
                        mac = struct.pack(">I", (i * 40503 + 7) & 0xFFFFFF)[1:]
                        ts = 1000 << 4
                        a.send(
                            CMD,
                            e2e_valid(
                                CMD,
                                bytes([RUN_OPTIONS | ts & 0xF0, ts >> 8 & 0xFF, ts >> 16]),
                                fv + 2 * i,
                                mac,
                            ),
                        )
                        a.send(
                            CMD,
                            e2e_valid(
                                CMD, bytes([EXECUTE | 1 << 4, 3000 & 0xFF, 3000 >> 8]), fv + 2 * i + 1, mac
                            ),
                        )
                        time.sleep(0.01)
                    during = a.stats()
                    assert a.state == 3 and dev.status.slot == 1, (a.state, dev.status)
                    assert during["wrong_mac"] > before["wrong_mac"], (before, during)
                    dev.command_until("idle", {"IDLE"}, 3.0)
                finally:
                    dev.stop_heartbeat()
            time.sleep(0.2)
            pair = [
                bytes(m.data)
                for m in a.seen
                if m.arbitration_id == CMD and m.data[0] & 0x0F in (RUN_OPTIONS, EXECUTE)
            ]
            genuine = [d for d in pair if d[0] & 0x0F == RUN_OPTIONS and (d[0] >> 4 | d[1] << 4) == 1000][:1]
            assert genuine
            k = pair.index(genuine[0])
            mid = a.stats()
            for _ in range(3):
                a.send(CMD, pair[k])
                a.send(CMD, pair[k + 1])
                time.sleep(0.05)
            time.sleep(0.2)
            assert a.state == 1, STATE_NAMES.get(a.state)
            after = a.stats()
            assert after["accepted"] == mid["accepted"], (mid, after)
    finally:
        bus.shutdown()
        a.close()

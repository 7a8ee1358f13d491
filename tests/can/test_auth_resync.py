"""The freshness values resynchronise, through the authenticated exchange (SecurityAccess level 1
and DID 0x0302, `motion_session` / `command_until`'s resync), after what loses them: an ECUReset
(soft) and a hard reset, which on the host port is the device's power-up (app_init from scratch,
RAM lost, flash kept), and frames lost or corrupted on the bus (`hil_sim serve --drop`,
`--corrupt`: lost heartbeats and commands inside the 256-value window are absorbed, corrupted
ones fail the E2E check). The bus-off case is tests/can/test_auth.py's."""

from __future__ import annotations

import dataclasses
import time

import can
import pytest

from forceskill.codes import DID_AUTH_STATS
from helpers.canbus import SCENARIOS, SPEED, Server


def auth_stats(client) -> dict[str, int]:  # type: ignore[no-untyped-def]
    from forceskill import wire as W
    from forceskill.link import uds as U

    return dataclasses.asdict(W.AuthStats.unpack(U.read_did(client, DID_AUTH_STATS, 0)))


@pytest.mark.parametrize("reset_type", [0x03, 0x01])
def test_freshness_resynchronises_after_an_ecu_reset_or_power_up(reset_type: int) -> None:
    from forceskill.link import uds as U
    from forceskill.link.device import Device

    srv = Server(SCENARIOS / "pressing_task1_demo.toml")
    bus = can.Bus(interface="socketcand", host="127.0.0.1", port=srv.port, channel="can0")
    try:
        with Device(bus, timeout_s=6.0) as dev:
            dev.wait_present()
            with U.uds_client(dev, request_timeout_s=2.0) as client:
                U.motion_session(client, dev)
                dev.start_heartbeat(telemetry_period_ms=10)
                try:
                    dev.command_until("teach", {"TEACH"}, 5.0)
                    dev.command_until("idle", {"IDLE"}, 3.0)
                    before = dev.session
                    U.call("reset", lambda: client.ecu_reset(reset_type), 0)
                    dev.wait_present()
                    # the device forgot the key: commands without effect, then the session again
                    dev.command_until("teach", {"TEACH"}, 15.0)
                    dev.command_until("idle", {"IDLE"}, 3.0)
                finally:
                    dev.stop_heartbeat()
                assert dev.session is not before, "a new session after the reset"
                st = auth_stats(client)
                assert st["keyed"] == 1 and st["accepted"] > 0
                assert st["fv_command"] >= 1  # the new session's TEACH (a stop needs no MAC)
    finally:
        bus.shutdown()
        srv.stop()


def test_lost_and_corrupted_frames_are_absorbed_by_the_freshness_window() -> None:
    from forceskill.link import uds as U
    from forceskill.link.device import Device

    srv = Server(SCENARIOS / "pressing_task1_demo.toml", extra=("--drop", "0.05", "--corrupt", "0.05"))
    bus = can.Bus(interface="socketcand", host="127.0.0.1", port=srv.port, channel="can0")
    try:
        with Device(bus, timeout_s=6.0) as dev:
            dev.wait_present()
            with U.uds_client(dev, request_timeout_s=1.0) as client:
                U.motion_session(client, dev, tries=30)
                session = dev.session
                dev.start_heartbeat(telemetry_period_ms=10)
                try:
                    dev.command_until("teach", {"TEACH"}, 10.0)
                    time.sleep(2.0 / SPEED)
                    st = dev.status
                    assert st.state == "TEACH", (st.state, st.fault_code)  # no host silence
                    dev.command_until("idle", {"IDLE"}, 5.0)
                finally:
                    dev.stop_heartbeat()
                assert dev.session is session, "losses inside the window need no new session"
                st = U._again(lambda: auth_stats(client), 30)
                sent = st["fv_heartbeat"]
                # ~10 % of the heartbeats lost or corrupted, the rest accepted: gaps absorbed
                assert st["accepted"] > 0.8 * sent > 100, st
                assert st["wrong_mac"] == 0 and st["replayed"] == 0, st
    finally:
        bus.shutdown()
        srv.stop()

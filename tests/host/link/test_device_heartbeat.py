"""Device.start_heartbeat on python-can's virtual bus: the first heartbeat, with the telemetry
period asked, is on the bus when start_heartbeat returns, whatever the periodic task's thread
does (here it never sends), so a command sent next finds the period already set."""

from __future__ import annotations

from typing import Any

import can

from forceskill.link.device import Device
from forceskill.wire.dbc import check, load_db


def test_first_heartbeat_goes_before_start_heartbeat_returns(monkeypatch: Any) -> None:
    db = load_db(0)
    hb = db.get_message_by_name("HostHeartbeat")
    with (
        can.Bus(interface="virtual", channel="hb_first", receive_own_messages=False) as host_bus,
        can.Bus(interface="virtual", channel="hb_first") as device_side,
    ):
        started: list[float] = []

        class Idle:  # a periodic task whose thread has not sent yet
            def stop(self) -> None:
                pass

        def send_periodic(msg: can.Message, period: float, **kw: Any) -> Idle:
            started.append(period)
            return Idle()

        monkeypatch.setattr(host_bus, "send_periodic", send_periodic)
        with Device(host_bus) as dev:
            dev.start_heartbeat(telemetry_period_ms=10)
            first = device_side.recv(1.0)
            dev.stop_heartbeat()
    assert started, "the periodic task was started as well"
    assert first is not None and first.arbitration_id == hb.frame_id
    assert check(first.arbitration_id, bytes(first.data))  # counter and CRC valid
    assert hb.decode(bytes(first.data), decode_choices=False)["TelemetryPeriod"] == 10

"""record's log ends at --duration of device time, judged in bus order (the Device's status
callback runs before the log sees the same frame), not when the command's own loop, which can lag
the stream by seconds on a slow host, reads the status: frames after the status frame that shows
the last tick are not logged."""

from __future__ import annotations

import can

from forceskill.commands.record import _LogUntil
from forceskill.link.device import Status


class Keep(can.Listener):
    def __init__(self) -> None:
        self.frames: list[can.Message] = []

    def on_message_received(self, msg: can.Message) -> None:
        self.frames.append(msg)


def status(state: str, tick: int) -> Status:
    return Status(state, 0, 0, tick, True, True, 0, 0.0)


def test_log_ends_at_the_status_of_the_last_tick() -> None:
    keep = Keep()
    log = _LogUntil(keep, duration_ticks=50, start_state="TEACH")
    # IDLE before the command (logged), TEACH from tick 0xFFFFF0 (the 24-bit tick wraps), a
    # telemetry frame between the status frames of every 10 ticks
    ticks = [(s, t & 0xFFFFFF) for s, t in [("IDLE", 0xFFFFD0), ("IDLE", 0xFFFFE0)]]
    ticks += [("TEACH", (0xFFFFF0 + 10 * i) & 0xFFFFFF) for i in range(10)]
    for state, tick in ticks:
        log.status(status(state, tick))  # the Device's callback first, as the Notifier does
        log.on_message_received(can.Message(arbitration_id=0x180, data=tick.to_bytes(3, "little")))
        log.on_message_received(can.Message(arbitration_id=0x190, data=tick.to_bytes(3, "little")))
    got = [int.from_bytes(m.data, "little") for m in keep.frames if m.arbitration_id == 0x180]
    # TEACH started at 0xFFFFF0; 50 ticks later (0x000022) is the first status not logged
    assert log.start_tick == 0xFFFFF0
    assert got == [0xFFFFD0, 0xFFFFE0] + [(0xFFFFF0 + 10 * i) & 0xFFFFFF for i in range(5)]
    assert len(keep.frames) == 2 * len(got)  # nothing after that status either


def test_without_a_duration_everything_is_logged() -> None:
    keep = Keep()
    log = _LogUntil(keep, duration_ticks=0, start_state=None)
    for tick in range(0, 100_000, 10):
        log.status(status("TEACH", tick))
        log.on_message_received(can.Message(arbitration_id=0x180))
    assert len(keep.frames) == 10_000 and not log.ended

"""Pairing the device's two telemetry frames. Every tick the device queues TelemetryPosition
(0x190 + node, carrying the tick) and then TelemetryForce (0x1A0 + node, no tick). Frames of one
identifier keep their order on CAN, but a controller with several transmit mailboxes sends the
lowest identifier first: when the bus is busy the positions of several ticks can pass the force
frame of the first (P(n) P(n+1) P(n+2) F(n) F(n+1) F(n+2)). So a force frame belongs to the
oldest position not yet paired, never simply to the latest one.

A frame lost on its way (an adapter that misses frames) is found by the queue's length: in
steady state a force frame finds one position waiting; if it keeps finding two or more for
RESYNC_PAIRS frames in a row, a force frame was lost and the oldest position is dropped. A lost
position makes a force frame find none (dropped) or pair one tick late until the queue empties.
Either way the pairing converges within RESYNC_PAIRS ticks, and a lost sample is a missing tick
that the callers interpolate and count."""

from __future__ import annotations

from collections import deque
from typing import Generic, TypeVar

import numpy as np

T = TypeVar("T")

#: Telemetry period outside TEACH/EXECUTE (APP_IDLE_TELEMETRY_PERIOD_MS): steps this long or
#: longer separate stretches of 1 kHz telemetry.
IDLE_PERIOD_TICKS = 100
#: A stretch needs this many samples to be 1 kHz telemetry (idle telemetry comes one at a time).
MIN_STRETCH = 10

#: Force frames in a row that find >= 2 positions waiting before the oldest is taken as unpaired.
RESYNC_PAIRS = 50
#: Positions kept waiting at most (a stream of positions without force frames is not telemetry).
MAX_WAITING = 256


class TelemetryPairer(Generic[T]):
    """Positions in, force frames matched to them (see the module comment)."""

    def __init__(self) -> None:
        self._waiting: deque[T] = deque()
        self._behind = 0
        self.unpaired = 0  # positions or force frames left without their other half

    def position(self, pos: T) -> None:
        """A TelemetryPosition frame (decoded, with its tick)."""
        if len(self._waiting) >= MAX_WAITING:
            self._waiting.popleft()
            self.unpaired += 1
        self._waiting.append(pos)

    def force(self) -> T | None:
        """A TelemetryForce frame arrived: the position it belongs to, or None (its position was
        lost)."""
        if not self._waiting:
            self.unpaired += 1
            return None
        self._behind = self._behind + 1 if len(self._waiting) >= 2 else 0
        if self._behind >= RESYNC_PAIRS:  # a force frame was lost: its position is unpaired
            self._waiting.popleft()
            self.unpaired += 1
            self._behind = 0
        return self._waiting.popleft()

    def clear(self) -> None:
        """Forget the waiting positions (the stream restarts)."""
        self._waiting.clear()
        self._behind = 0


def fast_stretches(ticks: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Rows [starts[k], ends[k]) of increasing ``ticks`` streamed every tick, or every few ticks
    where the host asked for a longer period (TEACH, EXECUTE): split where the step reaches the
    idle period, an idle sample next to a stretch trimmed off (a step longer than the stretch's
    own, its median), stretches shorter than MIN_STRETCH left out. Lost samples inside a stretch
    stay in it."""
    step = np.diff(ticks)
    cut = np.flatnonzero(step >= IDLE_PERIOD_TICKS)
    starts = np.concatenate(([0], cut + 1))
    ends = np.concatenate((cut + 1, [ticks.size]))
    # an idle sample within 100 ticks of the stream joins the stretch: trim edges farther apart
    # than the stream's period (1 tick unless the host asked for another)
    for k in range(starts.size):
        inner = step[starts[k] : max(starts[k], ends[k] - 1)]
        period = max(1.0, float(np.median(inner))) if inner.size else 1.0
        while ends[k] - starts[k] >= 2 and step[starts[k]] > period:
            starts[k] += 1
        while ends[k] - starts[k] >= 2 and step[ends[k] - 2] > period:
            ends[k] -= 1
    keep = (ends - starts) >= MIN_STRETCH
    return starts[keep], ends[keep]

"""Pairing the device's telemetry frames (forceskill.wire.telemetry) against streams built by
hand: the order a multi-mailbox controller puts on a busy bus, and frames lost by an adapter."""

from __future__ import annotations

from forceskill.wire.telemetry import RESYNC_PAIRS, TelemetryPairer


def pair(stream: list[tuple[str, int]]) -> list[tuple[int, int]]:
    """Feed ("P", tick) / ("F", tick) frames; returns (position tick, force tick) pairs."""
    p: TelemetryPairer[int] = TelemetryPairer()
    out = []
    for kind, tick in stream:
        if kind == "P":
            p.position(tick)
        else:
            got = p.force()
            if got is not None:
                out.append((got, tick))
    return out


def in_order(ticks: range) -> list[tuple[str, int]]:
    return [f for n in ticks for f in (("P", n), ("F", n))]


def test_positions_that_pass_their_force_frames_are_paired_in_order():
    burst = [("P", n) for n in range(10, 20)] + [("F", n) for n in range(10, 20)]
    pairs = pair(in_order(range(10)) + burst + in_order(range(20, 30)))
    assert pairs == [(n, n) for n in range(30)]


def test_a_lost_force_frame_is_resynchronised():
    stream = [f for f in in_order(range(500)) if f != ("F", 100)]
    pairs = pair(stream)
    wrong = [p for p in pairs if p[0] != p[1]]
    assert len(wrong) <= RESYNC_PAIRS and all(f - p == 1 for p, f in wrong)
    assert all(p == f for p, f in pairs if f > 101 + RESYNC_PAIRS)
    assert 100 not in {f for _, f in pairs}


def test_a_lost_position_frame_loses_only_its_sample():
    pairs = pair([f for f in in_order(range(300)) if f != ("P", 40)])
    assert [f for _, f in pairs] == [n for n in range(300) if n != 40]
    assert all(p == f for p, f in pairs)


def test_a_lost_position_inside_a_burst_converges_when_the_queue_empties():
    burst = [("P", n) for n in range(10, 20) if n != 12] + [("F", n) for n in range(10, 20)]
    pairs = pair(in_order(range(10)) + burst + in_order(range(20, 40)))
    assert all(p == f for p, f in pairs if f >= 20) and len(pairs) == 39

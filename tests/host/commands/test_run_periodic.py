"""forceskill run's periodic options: cycles in a sequence, the 12-byte start and its refusals."""

from __future__ import annotations

import pytest

from forceskill import wire as W
from forceskill.commands.run import CYCLES_MAX, parse_sequence, resolve_cycles
from forceskill.errors import FsError
from forceskill.link import ERR_LINK_ARGS


def test_sequence_cycles_resolve_to_periods() -> None:
    steps = parse_sequence("1:1.5s,2:20c,3:800ms")
    assert steps == [(1, 1.5), (2, -20.0), (3, 0.8)]
    directory = {1: {"duration_s": 3.0}, 2: {"duration_s": 0.5}, 3: {"duration_s": 1.0}}
    assert resolve_cycles(steps, directory, 1.5) == [(1, 1.5), (2, 20 * 0.5 * 1.5), (3, 0.8)]


@pytest.mark.parametrize("text", ["2:0c", "2:1.5c", f"2:{CYCLES_MAX + 1}c"])
def test_sequence_cycles_refused(text: str) -> None:
    with pytest.raises(FsError) as e:
        parse_sequence(text)
    assert e.value.code == ERR_LINK_ARGS


def test_sequence_cycles_beyond_an_hour_refused() -> None:
    with pytest.raises(FsError) as e:
        resolve_cycles([(1, -10000.0)], {1: {"duration_s": 1.0}}, 1.0)
    assert e.value.code == ERR_LINK_ARGS


def test_periodic_start_layout() -> None:
    """The run_periodic start: run_skill's 8 bytes with the path scale, cycles, amplitude scale."""
    data = W.RunPeriodic(2, 1.5, 1.0, 1, 1.0, 20, 0.8).pack()
    assert data == bytes([2, 0x05, 0xDC, 0x03, 0xE8, 1, 0x03, 0xE8, 0, 20, 0x03, 0x20])
    assert len(data) == 12 and len(W.RunSkill(2, 1.5, 1.0, 1, 0.5).pack()) == 8

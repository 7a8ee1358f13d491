"""The telemetry of a run on the device's tick grid: frames lost on the bus are interpolated from
their neighbours and counted, never a reason to drop the rest of the run."""

from __future__ import annotations

import numpy as np
import pytest

from forceskill.commands._common import TELEMETRY_COLUMNS, columns
from forceskill.link.device import Sample, Telemetry


def samples_at(ticks: list[int]) -> list[Sample]:
    """Samples whose values are known functions of the tick (x = tick, forces = 2 tick, ...)."""
    return [Sample(t, 1e-3 * t, -1e-3 * t, 2.0 * t, 3.0 * t, 4.0 * t, 5.0 * t) for t in ticks]


def test_lost_ticks_are_interpolated_and_counted():
    ticks = [*range(100, 103), *range(105, 107), *range(110, 130)]  # 2 lost after 102, 3 after 106
    cols, stream = columns(samples_at(ticks))
    assert np.allclose(cols["t"], np.arange(30) * 1e-3)
    grid = np.arange(100, 130)
    assert np.allclose(cols["x"], 1e-3 * grid) and np.allclose(cols["f_hat"], 5.0 * grid)
    assert (stream.lost_samples, stream.longest_gap_ms) == (5, 3)


def test_the_idle_samples_around_the_stream_are_left_out():
    """Outside TEACH/EXECUTE the device sends one sample per 100 ticks: not part of the run."""
    ticks = [0, 100, 200, *range(250, 400), 500, 600]
    cols, stream = columns(samples_at(ticks))
    assert cols["t"].size == 150 and np.allclose(cols["f_contact"], 2.0 * np.arange(250, 400))
    assert stream.first_tick == 250
    assert stream.lost_samples == 0


def test_a_stream_interrupted_longer_than_the_idle_period_is_one_run_with_its_gap_counted():
    cols, stream = columns(samples_at([*range(0, 50), *range(300, 350)]))
    assert cols["t"].size == 350 and (stream.lost_samples, stream.longest_gap_ms) == (250, 250)


def test_out_of_order_and_repeated_ticks_keep_the_first_sample():
    s = samples_at([10, 12, 11, 12, *range(13, 30)])
    s[3] = Sample(12, 9.0, 9.0, 9.0, 9.0, 9.0, 9.0)  # a late repeat of tick 12
    cols, stream = columns(s)
    assert np.allclose(cols["f_contact"], 2.0 * np.arange(10, 30)) and stream.lost_samples == 0


def test_no_samples_gives_empty_columns():
    cols, stream = columns([])
    assert set(cols) == {"t", *TELEMETRY_COLUMNS, "band_out"} and all(v.size == 0 for v in cols.values())
    assert stream.lost_samples == 0


def states_of(idle_until: int, active_until: int, end: int, state: str = "EXECUTE") -> list[tuple[int, str]]:
    """Status frames every 10 ticks: IDLE up to idle_until, then state up to active_until, IDLE after."""
    return [(t, "IDLE" if t <= idle_until or t > active_until else state) for t in range(0, end + 1, 10)]


@pytest.mark.parametrize("period", [10, 100, 7])
def test_a_longer_period_counts_only_the_samples_it_was_due(period: int) -> None:
    """The execution at ticks 1000..3000 sends every `period` ticks (multiples of it), the idle
    device every 100 ticks around it: the run's samples are told from the idle ones by the
    device's states, whatever the period; the ticks between are interpolated but never lost."""
    execution = [t for t in range(1000, 3001) if t % period == 0]
    lost = execution[5:8] if period < 100 else execution[5:6]
    ticks = list(range(0, 1000, 100)) + [t for t in execution if t not in lost] + list(range(3100, 4001, 100))
    cols, stream = columns(samples_at(ticks), period, states_of(999, 3000, 4000))
    assert stream.first_tick == execution[0] and stream.lost_samples == len(lost)
    assert stream.received == len(execution) - len(lost)
    assert stream.longest_gap_ms == len(lost) * period
    grid = np.arange(execution[0], execution[-1] + 1)
    assert cols["t"].size == grid.size and np.allclose(cols["f_hat"], 5.0 * grid)


def test_without_states_a_period_of_the_idle_telemetrys_length_finds_nothing_but_states_find_it() -> None:
    ticks = list(range(0, 4001, 100))
    assert columns(samples_at(ticks), 100)[0]["t"].size == 0
    cols, stream = columns(samples_at(ticks), 100, states_of(995, 3005, 4000))
    assert cols["t"].size == 2001 and stream.first_tick == 1000 and stream.lost_samples == 0


def test_samples_past_the_runs_window_are_neither_kept_nor_counted() -> None:
    execution = [t for t in range(1000, 5001, 10) if t != 4500]  # one lost after the window
    cols, stream = columns(samples_at(execution), 10, states_of(995, 5005, 6000), max_rows=2001)
    assert cols["t"].size == 2001 and stream.lost_samples == 0 and stream.received == 201


def test_ticks_unwrap_across_the_16_bit_wrap_also_a_little_out_of_order() -> None:
    tel = Telemetry()
    raw = [65530, 65534, 2, 65535, 5, 1, 9]  # a status or position frame behind the latest one
    assert [tel.unwrap(t) for t in raw] == [65530, 65534, 65538, 65535, 65541, 65537, 65545]

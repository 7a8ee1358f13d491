"""The telemetry of a run on the device's tick grid: frames lost on the bus are interpolated from
their neighbours and counted, never a reason to drop the rest of the run."""

from __future__ import annotations

import numpy as np

from forceskill.commands._common import TELEMETRY_COLUMNS, columns
from forceskill.link.device import Sample


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
    assert set(cols) == {"t", *TELEMETRY_COLUMNS} and all(v.size == 0 for v in cols.values())
    assert stream.lost_samples == 0

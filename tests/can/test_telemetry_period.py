"""`run --telemetry-period MS` over the documented range 1..100 ms: the execution's telemetry is
found at any period (at 100 ms it comes as often as the idle telemetry, and is told from it by
the device's status), the CSV covers the run's window on the 1 ms grid and ends with the
execution, and "samples lost on the bus" counts only samples that were due at the period."""

from __future__ import annotations

import math
import re
import time
from collections.abc import Iterator
from pathlib import Path

import numpy as np
import pytest

from forceskill import cli
from helpers.canbus import REPO, SCENARIOS, Server

SKILL = REPO / "tests" / "vectors" / "press_n50_lwr_hold.skill"  # 1.5 s, peak 4.84 N, end hold
RUN_S = 1.5 + 0.5  # the skill and the default --hold-for


def run(capsys: pytest.CaptureFixture[str], *argv: str) -> tuple[int, str, str]:
    rc = cli.main(list(argv))
    out, err = capsys.readouterr()
    return rc, out, err


def load_csv(path: Path) -> dict[str, np.ndarray]:
    a = np.genfromtxt(path, delimiter=",", names=True)
    return {n: np.asarray(a[n]) for n in a.dtype.names or ()}


def summary(out: str) -> tuple[int, int, float, int]:
    """(samples received, rows, tracking max %, samples lost) from run's summary lines."""
    m = re.search(r"telemetry: (\d+) samples every \d+ ms, (\d+) rows on the 1 ms grid", out)
    assert m, out
    track = re.search(r"force tracking: max ([0-9.na]+) %", out)
    assert track, out
    lost = re.search(r"telemetry: (\d+) samples lost on the bus", out)
    return int(m.group(1)), int(m.group(2)), float(track.group(1)), int(lost.group(1)) if lost else 0


def server(*extra: str) -> Iterator[Server]:
    s = Server(SCENARIOS / "pressing_task1_demo.toml", extra=extra)
    time.sleep(0.2)
    assert cli.main(["upload", str(SKILL), "--slot", "1", "-q", *s.bus_args()]) == 0
    yield s
    s.stop()


@pytest.fixture(scope="module")
def loaded() -> Iterator[Server]:
    yield from server()


@pytest.mark.parametrize("period", [100, 10, 7])
def test_every_documented_period_gives_the_runs_telemetry(
    period: int, loaded: Server, capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    csv = tmp_path / "r.csv"
    rc, out, err = run(
        capsys, "run", "--slot", "1", "--telemetry-period", str(period), "--csv", str(csv), *loaded.bus_args()
    )
    assert rc == 0, err
    received, rows, track_max, lost = summary(out)
    # the rows run from the first sample of the execution to its last (each up to a period
    # inside the run's window), the samples due between them received or counted lost
    assert int(RUN_S * 1000) + 1 - 2 * period <= rows <= int(RUN_S * 1000) + 1, rows
    assert received + lost == (rows - 1) // period + 1, (received, lost, rows)
    assert math.isfinite(track_max) and track_max < 15.0
    cols = load_csv(csv)
    assert cols["t"].size == rows and np.allclose(np.diff(cols["t"]), 1e-3)
    # the window is the execution's: its reference from the start to the held force at the end
    # (an idle row has f_hat 0), the skill's peak inside it
    assert 4.6 < cols["f_hat"].max() < 5.1
    assert cols["f_hat"][-1] > 0.5 * cols["f_hat"].max()


def test_lost_counts_only_the_samples_due_at_the_period(
    capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    """An adapter that misses 5 % of the frames at 10 ms telemetry: lost is about 5-10 % of the
    ~200 samples due (a sample is two frames), never the ~1,800 ticks between them that the
    device was asked not to send."""
    gen = server("--drop-telemetry", "0.05")
    srv = next(gen)
    try:
        rc, out, err = run(
            capsys,
            "run",
            "--slot",
            "1",
            "--telemetry-period",
            "10",
            "--csv",
            str(tmp_path / "r.csv"),
            *srv.bus_args(),
        )
        assert rc == 0, err
        received, rows, _, lost = summary(out)
        due = (rows - 1) // 10 + 1
        assert int(RUN_S * 1000) + 1 - 60 <= rows <= int(RUN_S * 1000) + 1, rows
        assert received + lost == due and 0 < lost < 0.25 * due, (received, lost, due)
    finally:
        err = srv.stop()
    injected = int(err.split(" telemetry frames lost")[0].rsplit(", ", 1)[1])
    assert lost <= injected

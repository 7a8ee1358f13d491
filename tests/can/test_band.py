"""The device's check of a run against the demonstrated band, over CAN: a pressing skill fitted
from six HIL demonstrations of pressing_task1_demo.toml (seeds 1..6, each its own timing and
levels) carries the band; run on hil_sim/scenarios/pressing_layer_gives.toml, whose inner layer
gives way 3 s into the execution, the contact force leaves the band and ``run --band-action
stop`` stops the run with fault 515 within 100 ms of the layer failing (``report``: the run goes
on, the time outside reported; its CSV marks the ticks outside in ``band_out`` and ``--plot`` draws
them); on the normal object at 1x and 1.5x ten runs raise no alarm; ``forceskill journey`` ends
with the same stop."""

from __future__ import annotations

import json
import subprocess
import time

import numpy as np
import pytest

from forceskill import cli
from forceskill.plot import outside_spans
from helpers.canbus import JOURNEY_HOST_TIMEOUT_MS, SCENARIOS, Server, forceskill
from helpers.doc_examples import documented_step, run, workspace
from helpers.paths import hil_sim_path

K_NPM = 100.0
GIVES_AT_S = 3.0  # pressing_layer_gives.toml's gives_at_s
BAND_MS = 30  # ms outside the band in one piece that stop a run
FLT_BAND = 515
#: The journey's whole run (about 40 s on a quiet 2-core machine; minutes beside busy loops).
JOURNEY_TIMEOUT_S = 600


@pytest.fixture(scope="module")
def band_skill(tmp_path_factory: pytest.TempPathFactory) -> str:
    d = tmp_path_factory.mktemp("band")
    demos = []
    for seed in range(1, 7):
        demo = d / f"press{seed}.csv"
        subprocess.run(
            [
                str(hil_sim_path()),
                "run",
                str(SCENARIOS / "pressing_task1_demo.toml"),
                "--seed",
                str(seed),
                "-o",
                str(demo),
            ],
            check=True,
            capture_output=True,
        )
        demos.append(str(demo))
    out = d / "press.skill"
    assert cli.main(["fit", *demos, "-k", str(K_NPM), "--object-mass", "10", "-o", str(out)]) == 0
    return str(out)


def _band_line(out: str) -> tuple[float, int, float]:
    """The run's band line: % outside, the longest piece (ms), the largest excursion (widths)."""
    line = next(ln for ln in out.splitlines() if ln.startswith("outside the demonstrated band"))
    pct = float(line.split(": ")[1].split(" %")[0])
    longest = int(line.split("longest ")[1].split(" ms")[0])
    widths = float(line.split("largest ")[1].split(" band")[0])
    return pct, longest, widths


def test_a_layer_that_gives_way_is_detected_and_stopped_within_100_ms(band_skill, tmp_path, capsys) -> None:  # type: ignore[no-untyped-def]
    server = Server(SCENARIOS / "pressing_layer_gives.toml", host_timeout_ms=JOURNEY_HOST_TIMEOUT_MS)
    try:
        time.sleep(0.2)
        bus = server.bus_args()
        assert "verified by read-back" in forceskill(capsys, "upload", band_skill, "--slot", "1", "-q", *bus)
        csv, png = tmp_path / "report.csv", tmp_path / "report.png"
        out = forceskill(
            capsys, "run", "--slot", "1", "--end", "release", "--csv", str(csv), "--plot", str(png), *bus
        )
        pct, longest, widths = _band_line(out)
        # the CSV marks every row the device reported outside: band_out, 0/1, after the fault column
        assert csv.read_text().split("\n", 1)[0] == "t,x,y,f_contact,f_operator,f_cmd,f_hat,fault,band_out"
        assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
        cols = np.genfromtxt(csv, delimiter=",", names=True)
        band_out = np.asarray(cols["band_out"])
        assert set(np.unique(band_out)) == {0.0, 1.0}
        # its longest piece is the device's own (DID_BAND), to within a tick the bus lost
        spans = outside_spans(np.asarray(cols["t"]), band_out)
        assert abs(1e3 * float(np.max(spans[:, 1] - spans[:, 0])) - longest) <= 2.0, (spans, longest)
        first = float(cols["t"][np.argmax(band_out > 0.5)])
        print(f"report: {out.splitlines()[-2]}; first sample outside at {first:.3f} s")
        assert pct > 5.0 and longest > 500 and widths > 0.5, out
        assert GIVES_AT_S <= first <= GIVES_AT_S + 0.1
        assert not np.any(band_out[: int((GIVES_AT_S - 0.05) * 1000)] > 0.5)
        # stop: fault 515 within 100 ms of the layer giving way
        time.sleep(0.5)
        csv = tmp_path / "stop.csv"
        argv = [
            "run",
            "--slot",
            "1",
            "--end",
            "release",
            "--band-action",
            "stop",
            "--band-ms",
            str(BAND_MS),
        ]
        rc = cli.main([*argv, "--csv", str(csv), *bus])
        out, err = capsys.readouterr()
        assert rc != 0 and "515" in err, err
        cols = np.genfromtxt(csv, delimiter=",", names=True)
        fault = np.asarray(cols["fault"])
        t_fault = float(cols["t"][np.argmax(fault == FLT_BAND)])
        print(
            f"stop: fault {FLT_BAND} at {t_fault:.3f} s, {1e3 * (t_fault - GIVES_AT_S):.0f} ms after the layer gave way"
        )
        assert GIVES_AT_S < t_fault <= GIVES_AT_S + 0.1, err
    finally:
        server.stop()


def test_the_normal_object_raises_no_alarm_at_1x_and_1_5x(band_skill, tmp_path, capsys) -> None:  # type: ignore[no-untyped-def]
    server = Server(SCENARIOS / "pressing_task1_demo.toml", host_timeout_ms=JOURNEY_HOST_TIMEOUT_MS)
    try:
        time.sleep(0.2)
        bus = server.bus_args()
        assert "verified by read-back" in forceskill(capsys, "upload", band_skill, "--slot", "1", "-q", *bus)
        worst = []
        for i in range(10):
            g = "1.5" if i % 2 else "1"
            out = forceskill(
                capsys, "run", "--slot", "1", "--goal-scale", g, "--end", "release",
                "--band-action", "stop", "--band-ms", str(BAND_MS), *bus,
            )  # fmt: skip
            pct, longest, widths = _band_line(out)
            worst.append((g, pct, longest, widths))
            time.sleep(0.3)
        print(
            "normal object, 10 runs (goal, % outside, longest ms, largest widths):",
            worst,
        )
        assert all(longest < BAND_MS for _, _, longest, _ in worst)
    finally:
        server.stop()


def test_the_journey_ends_with_the_band_stopping_the_layer_that_gives_way(tmp_path) -> None:  # type: ignore[no-untyped-def]
    """forceskill journey as docs/cli.md shows it, what it prints compared with the document; its
    band step (six simulator demonstrations, fit, run with --band-action stop on
    pressing_layer_gives.toml): its summary and report say where it stopped."""
    step = documented_step("docs/cli.md", "forceskill journey", "tests/can/test_band.py")
    ws = workspace(tmp_path)
    failures = run([step], ws, timeout_s=JOURNEY_TIMEOUT_S)
    assert not failures, "\n".join(failures)
    out = ws / "can_journey"
    band = json.loads((out / "can_summary.json").read_text())["band"]
    print(f"journey: {band}")
    assert band["fault"] == FLT_BAND and band["gives_at_s"] == GIVES_AT_S
    assert GIVES_AT_S < band["stopped_at_s"] <= GIVES_AT_S + 0.1
    assert "## The demonstrated band" in (out / "can_report.md").read_text()
    assert (out / "can_band.png").is_file() and (out / "can_band_fit.png").is_file()

"""Force and motion in one skill over CAN: a wiping demonstration (force levels + a path along y on
a surface with Coulomb friction, hil_sim/scenarios/wiping_demo.toml) is recorded in TEACH, fitted
with its path (fit --y-column y, skill format v3), uploaded and replayed at 1x and 1.5x goal;
`run` reports force tracking (%) and path tracking (mm) and both are checked, the path also
independently from the telemetry CSV."""

from __future__ import annotations

import time

import numpy as np
import pytest

from forceskill.model import dmp
from forceskill.model.demo import load_demo
from forceskill.model.skill import Skill
from helpers.canbus import JOURNEY_HOST_TIMEOUT_MS, SCENARIOS, Server, forceskill

K_NPM = 280.0
OBJECT_MASS_KG = 10.0


@pytest.fixture(scope="module")
def server():
    s = Server(SCENARIOS / "wiping_demo.toml", host_timeout_ms=JOURNEY_HOST_TIMEOUT_MS)
    time.sleep(0.2)
    yield s
    s.stop()


def _figure(out: str, label: str) -> tuple[float, float]:
    line = out.split(label)[1]
    mx = float(line.split("max ")[1].split()[0])
    rms = float(line.split("RMS ")[1].split()[0])
    return mx, rms


def test_wiping_recorded_fitted_uploaded_replayed(server, tmp_path, capsys):
    bus = server.bus_args()
    out = forceskill(capsys, "record", "-o", str(tmp_path / "wipe.blf"), "--duration", "5", *bus)
    assert "in TEACH" in out
    demo = load_demo(tmp_path / "wipe.blf", y_column="y")
    assert demo.y_m is not None and np.ptp(demo.y_m) > 0.03  # the operator moved along y
    out = forceskill(
        capsys,
        "fit",
        str(tmp_path / "wipe.blf"),
        "--stiffness",
        str(K_NPM),
        "--surface-m",
        "0.001",
        "--object-mass",
        str(OBJECT_MASS_KG),
        "--y-column",
        "y",
        "-o",
        str(tmp_path / "wipe.skill"),
    )
    assert float(out.split("approximation error: max ")[1].split(" %")[0]) <= 2.5
    assert float(out.split("approximation error max ")[1].split(" mm")[0]) <= 0.5
    sk = Skill.read(tmp_path / "wipe.skill")
    assert sk.has_y and sk.format_version == 3
    out = forceskill(capsys, "upload", str(tmp_path / "wipe.skill"), "--slot", "1", "-q", *bus)
    assert "verified by read-back" in out
    _, y_ref = dmp.rollout_path(sk)
    p = y_ref - sk.y_start_m
    peaks = {}
    for g in ("1", "1.5"):
        csv = tmp_path / f"run_{g}.csv"
        out = forceskill(capsys, "run", "--slot", "1", "--goal-scale", g, "--csv", str(csv), *bus)
        f_max, f_rms = _figure(out, "force tracking:")
        y_max, y_rms = _figure(out, "path tracking:")
        assert f_rms <= 3.0 and f_max <= 10.0, out
        assert y_rms <= 1.0 and y_max <= 3.0, out
        cols = np.genfromtxt(csv, delimiter=",", names=True)
        # independent check: the best alignment of the measured y with the learned path
        y = np.asarray(cols["y"])
        # (the telemetry may start a little before the execution: the first 200 ms are searched)
        best = min(
            float(np.sqrt(np.mean((y[i : i + m] - y[i] - p[:m]) ** 2)))
            for i in range(0, 200)
            for m in [min(p.size, y.size - i)]
            if m >= p.size // 2
        )
        assert best <= 1e-3, f"goal x{g}: path RMS {best * 1e3:.2f} mm"
        assert np.ptp(y) > 0.8 * np.ptp(p)
        peaks[g] = float(np.max(cols["f_hat"]))
    assert abs(peaks["1.5"] / peaks["1"] - 1.5) < 0.05

"""A periodic force skill over CAN: a wiping demonstration with repeated strokes
(hil_sim/scenarios/wiping_strokes_demo.toml: a 1 s approach, 0.8 s strokes about 5 N, a release)
is recorded in TEACH, fitted with ``fit --periodic`` (period by autocorrelation, the approach and
the release left out), uploaded and run for 20 cycles at goal 1x and 1.5x (``run --cycles 20``).
The device's reference force f_hat (telemetry) is checked against the fitted skill's own rollout
(``periodic.rollout``, the Python reference) over all 20 cycles, and the measured contact force
against the same rollout."""

from __future__ import annotations

import time

import numpy as np
import pytest

from forceskill.model import periodic
from forceskill.model.skill import Skill
from helpers.canbus import JOURNEY_HOST_TIMEOUT_MS, SCENARIOS, Server, forceskill

K_NPM = 2000.0
PERIOD_S = 0.8  # the scenario's stroke period (each stroke 1 +- 1 % of it)
CYCLES = 20
BLEND_S = 1.0  # the executor fades the start's difference to the measured force out over 1 s
F_HAT_RMS_MAX_N = 0.01  # one step of the telemetry's ForceRef (0.01 N)


@pytest.fixture(scope="module")
def server():
    s = Server(SCENARIOS / "wiping_strokes_demo.toml", host_timeout_ms=JOURNEY_HOST_TIMEOUT_MS)
    time.sleep(0.2)
    yield s
    s.stop()


def _figure(out: str, label: str) -> tuple[float, float]:
    line = out.split(label)[1]
    return float(line.split("max ")[1].split()[0]), float(line.split("RMS ")[1].split()[0])


def _aligned_error(meas: np.ndarray, ref: np.ndarray, skip: int) -> tuple[float, int]:
    """The smallest RMS of meas[i + n] - ref[n] over n >= skip and the execution's start i within
    the first 300 rows of the telemetry (it may start a little before the execution). ref is the
    device's f_hat per tick: the rollout's row n + 1 at the n-th tick of the execution."""
    best, at = np.inf, 0
    for i in range(300):
        m = min(ref.size, meas.size - i)
        if m <= skip + 100:
            break
        rms = float(np.sqrt(np.mean((meas[i + skip : i + m] - ref[skip:m]) ** 2)))
        if rms < best:
            best, at = rms, i
    return best, at


def test_wiping_strokes_recorded_fitted_uploaded_run_20_cycles(server, tmp_path, capsys):
    bus = server.bus_args()
    out = forceskill(capsys, "record", "-o", str(tmp_path / "wipe.blf"), "--duration", "16", *bus)
    assert "in TEACH" in out
    out = forceskill(
        capsys, "fit", str(tmp_path / "wipe.blf"), "--stiffness", str(K_NPM), "--periodic",
        "-o", str(tmp_path / "wipe.skill"),
    )  # fmt: skip
    strokes = int(out.split(" steady strokes")[0].split()[-1])
    assert strokes >= 8, out
    sk = Skill.read(tmp_path / "wipe.skill")
    assert sk.periodic and sk.format_version == 4
    assert abs(sk.duration_s - PERIOD_S) <= 0.01 * PERIOD_S, out
    assert sk.amplitude_N > 0.5  # the strokes reach the contact force
    out = forceskill(capsys, "upload", str(tmp_path / "wipe.skill"), "--slot", "1", "-q", *bus)
    assert "verified by read-back" in out
    peaks = {}
    for g in (1.0, 1.5):
        csv = tmp_path / f"run_{g:g}.csv"
        out = forceskill(
            capsys, "run", "--slot", "1", "--cycles", str(CYCLES), "--goal-scale", f"{g:g}",
            "--amplitude-scale", f"{g:g}", "--csv", str(csv), *bus,
        )  # fmt: skip
        assert f"{CYCLES} cycles" in out
        f_max_pct, f_rms_pct = _figure(out, "force tracking:")
        cols = np.genfromtxt(csv, delimiter=",", names=True)
        _, rollout = periodic.rollout(sk, cycles=CYCLES, goal_scale=g, amplitude_scale=g)
        ref = rollout[1:]  # the n-th tick's f_hat is the state after n + 1 steps
        skip = int(BLEND_S / sk.dt_s)
        # the device's reference against the Python rollout of the fitted skill, every cycle
        e_hat, i0 = _aligned_error(np.asarray(cols["f_hat"]), ref, skip)
        span = float(np.ptp(ref))
        # (the telemetry's ForceRef has a 0.01 N step: the bound is one of them)
        assert e_hat <= F_HAT_RMS_MAX_N, f"goal x{g:g}: f_hat RMS {e_hat:.4f} N off the rollout"
        assert cols["t"].size - i0 >= ref.size  # the telemetry covers the 20 cycles
        # the measured contact force follows the rollout within a few % of max force
        e_meas, _ = _aligned_error(np.asarray(cols["f_contact"]), ref, skip)
        print(
            f"goal x{g:g}: f_hat vs rollout RMS {e_hat:.2e} N, contact vs rollout RMS {e_meas:.3f} N "
            f"({100 * e_meas / np.max(ref):.2f} % of max, stroke span {span:.2f} N); "
            f"run: tracking max {f_max_pct} %, RMS {f_rms_pct} %"
        )
        assert e_meas <= 0.05 * float(np.max(ref)), out
        assert f_rms_pct <= 5.0, out
        peaks[g] = float(np.max(cols["f_hat"]))
    # goal and amplitude x1.5: the whole cycle scales by 1.5 (f0 = 0)
    assert abs(peaks[1.5] / peaks[1.0] - 1.5) < 0.05

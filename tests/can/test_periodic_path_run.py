"""A periodic skill with the y path over CAN: a synthetic wiping demonstration with repeated
strokes and a path along y in time with them (``synthetic.wiping_strokes(path_m=...)``: 0.8 s
strokes about 5 N, a 5 mm two-harmonic path) is fitted with ``fit --periodic --y-column y``
(format v4, flags bit 1), uploaded to the HIL device (hil_sim/scenarios/wiping_strokes_demo.toml
once its operator has let go: the surface at k = 2000 N/m) and run for 6 cycles at path scale 1 and 1.5 (``run --cycles 6
--path-scale S``). The device's f_hat (telemetry) is checked against the skill's force rollout
(``periodic.rollout``) and the measured y against the path rollout as the device ramps it in
over the first cycle and out over the last (``periodic.rollout_path(ramp_in=True,
ramp_out=True)``), both the Python reference, and
run's own path tracking figure over every cycle."""

from __future__ import annotations

import time

import numpy as np
import pytest

from forceskill.model import periodic, synthetic
from forceskill.model.skill import Skill
from helpers.canbus import JOURNEY_HOST_TIMEOUT_MS, SCENARIOS, Server, forceskill

K_NPM = 2000.0
PERIOD_S = 0.8
CYCLES = 6
PATH_M = 0.005
BLEND_S = 1.0  # the executor fades the start's difference to the measured force out over 1 s
F_HAT_RMS_MAX_N = 0.01  # one step of the telemetry's ForceRef (0.01 N)
SCENARIO_S = 16.5
Y_RMS_MAX_M = 1e-3  # the measured y about its offset against the learned path
# the path ramped in, y starts at rest and keeps up from the start: every cycle within this of
# the ramped path (measured 0.098 mm at 1x; 0.96 mm when the path started at its stroke speed)
PATH_RMS_MAX_MM = 0.3
# and no offset is left after the first cycle (measured -0.002 mm; -0.020 mm without the ramp)
Y_OFFSET_MAX_M = 1e-4


@pytest.fixture(scope="module")
def server():
    s = Server(SCENARIOS / "wiping_strokes_demo.toml", host_timeout_ms=JOURNEY_HOST_TIMEOUT_MS)
    time.sleep(SCENARIO_S)  # the scenario's operator demonstrates for 16 s, then lets go
    yield s
    s.stop()


def _figure(out: str, label: str) -> tuple[float, float]:
    line = out.split(label)[1]
    return float(line.split("max ")[1].split()[0]), float(line.split("RMS ")[1].split()[0])


def _aligned(meas: np.ndarray, ref: np.ndarray, skip: int, relative: bool) -> tuple[float, int]:
    """The smallest RMS of meas[i + n] (- meas[i] if relative) - ref[n] over n >= skip and the
    execution's start i within the first 300 rows of the telemetry; ref is per tick of the
    execution (the rollout's row n + 1 at the n-th tick)."""
    best, at = np.inf, 0
    for i in range(300):
        m = min(ref.size, meas.size - i)
        if m <= skip + 100:
            break
        base = meas[i] if relative else 0.0
        rms = float(np.sqrt(np.mean((meas[i + skip : i + m] - base - ref[skip:m]) ** 2)))
        if rms < best:
            best, at = rms, i
    return best, at


def test_periodic_skill_with_y_path_runs_and_follows_its_rollout(server, tmp_path, capsys):
    bus = server.bus_args()
    d = synthetic.wiping_strokes(
        seed=2, n_strokes=10, period_s=PERIOD_S, mean_N=5.0, amplitude_N=1.5, k_v=K_NPM, path_m=PATH_M
    )
    assert d.y_m is not None
    csv = tmp_path / "wipe.csv"
    np.savetxt(
        csv, np.column_stack((d.t_s, d.pos_m, d.force_N, d.y_m)), delimiter=",",
        header="t,x,f_contact,y", comments="",
    )  # fmt: skip
    out = forceskill(
        capsys, "fit", str(csv), "--stiffness", str(K_NPM), "--periodic", "--y-column", "y",
        "-o", str(tmp_path / "wipe.skill"),
    )  # fmt: skip
    assert "against the mean y stroke" in out
    sk = Skill.read(tmp_path / "wipe.skill")
    assert sk.periodic and sk.has_y and sk.format_version == 4
    out = forceskill(capsys, "upload", str(tmp_path / "wipe.skill"), "--slot", "1", "-q", *bus)
    assert "verified by read-back" in out
    extents = {}
    report: list[str] = []  # printed at the end (capsys takes each command's output)
    for ps in (1.0, 1.5):
        run_csv = tmp_path / f"run_{ps:g}.csv"
        out = forceskill(
            capsys, "run", "--slot", "1", "--cycles", str(CYCLES), "--path-scale", f"{ps:g}",
            "--csv", str(run_csv), *bus,
        )  # fmt: skip
        assert f"{CYCLES} cycles" in out
        y_max_mm, y_rms_mm = _figure(out, "path tracking:")
        cols = np.genfromtxt(run_csv, delimiter=",", names=True)
        _, f_roll = periodic.rollout(sk, cycles=CYCLES)
        _, y_roll = periodic.rollout_path(sk, cycles=CYCLES, path_scale=ps, ramp_in=True, ramp_out=True)
        skip = int(BLEND_S / sk.dt_s)
        e_f, i_f = _aligned(np.asarray(cols["f_hat"]), f_roll[1:], skip, relative=False)
        p_ref = y_roll[1:] - sk.y_start_m
        e_y0, i_y = _aligned(np.asarray(cols["y"]), p_ref, 0, relative=True)
        y = np.asarray(cols["y"])[i_y : i_y + p_ref.size]
        extents[ps] = float(np.ptp(y))
        # after the first cycle: the measured path's offset from the rollout and its RMS about it
        n1 = int(round(sk.duration_s / sk.dt_s))
        e = (y - y[0] - p_ref[: y.size])[n1:]
        offset = float(np.mean(e))
        e_y = float(np.sqrt(np.mean((e - offset) ** 2)))
        report.append(
            f"path x{ps:g}: f_hat vs rollout RMS {e_f:.2e} N; y vs path rollout RMS {e_y0 * 1e3:.3f} mm, "
            f"after the first cycle offset {offset * 1e3:.3f} mm and RMS {e_y * 1e3:.3f} mm about it "
            f"(path span {np.ptp(p_ref) * 1e3:.2f} mm, measured {extents[ps] * 1e3:.2f} mm); run: path "
            f"tracking max {y_max_mm} mm, RMS {y_rms_mm} mm"
        )
        assert e_f <= F_HAT_RMS_MAX_N, f"path x{ps:g}: f_hat RMS {e_f:.4f} N off the rollout"
        assert e_y <= Y_RMS_MAX_M, f"path x{ps:g}: y RMS {e_y * 1e3:.3f} mm off the path rollout"
        assert abs(offset) <= Y_OFFSET_MAX_M * ps, f"path x{ps:g}: y offset {offset * 1e3:.3f} mm"
        assert y_rms_mm <= PATH_RMS_MAX_MM * ps, f"path x{ps:g}: run's path tracking RMS {y_rms_mm} mm"
        assert cols["t"].size - i_f >= f_roll.size - 1  # the telemetry covers the cycles
    print("\n".join(report))
    # the path scale scales the whole path about its start
    assert abs(extents[1.5] / extents[1.0] - 1.5) < 0.05

"""`run` on the simulator when things go wrong: a goal scale that takes the skill above the force
limit, or a y path whose acceleration asks more than it, is refused before anything moves; Ctrl-C commands IDLE, keeps the telemetry and exits 130; a
fault keeps the telemetry through its stop ramp (at 1 kHz) and names the fault; after a fault the simulated
drive parks the handle so that `status --clear` succeeds; a refused clear names its cause."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from forceskill import cli
from helpers.canbus import REPO, SCENARIOS, Server

SKILL = REPO / "tests" / "vectors" / "press_n50_lwr_hold.skill"  # 1.5 s, peak 4.84 N at goal 1


def run(capsys, *argv: str) -> tuple[int, str, str]:
    rc = cli.main(list(argv))
    out, err = capsys.readouterr()
    return rc, out, err


def load_csv(path: Path) -> dict[str, np.ndarray]:
    a = np.genfromtxt(path, delimiter=",", names=True)
    return {n: np.asarray(a[n]) for n in a.dtype.names}


@pytest.fixture(scope="module")
def loaded():
    s = Server(SCENARIOS / "pressing_task1_demo.toml")
    time.sleep(0.2)
    assert cli.main(["upload", str(SKILL), "--slot", "1", "-q", *s.bus_args()]) == 0
    yield s
    s.stop()


def test_goal_scale_above_the_force_limit_is_refused_before_anything_moves(loaded, capsys, tmp_path):
    csv = tmp_path / "r.csv"
    rc, out, err = run(
        capsys, "run", "--slot", "1", "--goal-scale", "50", "--csv", str(csv), *loaded.bus_args()
    )
    assert rc == 2 and "[662]" in err and "above the force limit 50 N" in err and "nothing was started" in err
    assert "executing" not in out and not csv.exists()
    rc, out, err = run(capsys, "status", *loaded.bus_args())
    assert rc == 0 and "IDLE, fault none" in out
    # a lower limit refuses what the default allows
    rc, out, err = run(
        capsys, "run", "--slot", "1", "--goal-scale", "2", "--force-limit", "9", *loaded.bus_args()
    )
    assert rc == 2 and "[662]" in err and "largest goal scale 1.8" in err


def test_a_y_path_the_axis_cannot_follow_is_refused_before_anything_moves(loaded, capsys):
    """A periodic skill whose y path asks m_d*|y''| = 418 N of the law (a 64 mm stroke at 2 Hz):
    refused with the largest path scale within the limit; nothing moves."""
    wipe_y = REPO / "tests" / "vectors" / "periodic_y_n20_ridge.skill"
    assert cli.main(["upload", str(wipe_y), "--slot", "3", "-q", *loaded.bus_args()]) == 0
    capsys.readouterr()
    rc, out, err = run(capsys, "run", "--slot", "3", "--cycles", "2", *loaded.bus_args())
    assert rc == 2 and "[662]" in err and "its y path asks 417.9 N" in err
    assert "largest path scale 0.1197" in err and "nothing was started" in err
    rc, out, err = run(
        capsys, "run", "--slot", "3", "--cycles", "2", "--path-scale", "0.5", *loaded.bus_args()
    )
    assert rc == 2 and "at path scale 0.5" in err and "largest path scale 0.1197" in err
    rc, out, err = run(capsys, "status", *loaded.bus_args())
    assert rc == 0 and "IDLE, fault none" in out


def test_ctrl_c_commands_idle_and_writes_the_telemetry(loaded, tmp_path):
    csv = tmp_path / "r.csv"
    env = dict(os.environ, PYTHONPATH=str(REPO / "host"))
    p = subprocess.Popen(
        [
            sys.executable,
            "-m",
            "forceskill",
            "run",
            "--slot",
            "1",
            "--end",
            "hold",
            "--hold-for",
            "30",
            "--csv",
            str(csv),
            "-o",
            str(tmp_path / "r.blf"),
            *loaded.bus_args(),
        ],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env=env,
    )
    line = p.stdout.readline()  # "node 0: executing ..."
    assert "executing" in line, line + p.stderr.read()
    time.sleep(1.0)
    p.send_signal(signal.SIGINT)
    _out, err = p.communicate(timeout=30)
    assert p.returncode == 130, err
    assert "interrupted: node 0 commanded to IDLE" in err and "Traceback" not in err
    cols = load_csv(csv)
    assert cols["t"].size > 500 and np.all(cols["fault"] == 0)
    assert (tmp_path / "r.blf").stat().st_size > 1000
    time.sleep(0.3)
    rc = cli.main(["status", *loaded.bus_args()])
    assert rc == 0


def test_fault_keeps_the_telemetry_then_the_handle_is_parked_and_cleared(capsys, tmp_path):
    # bus-off at 8 s of simulated time: inside a long hold started right after the upload
    srv = Server(SCENARIOS / "pressing_task1_demo.toml", extra=("--bus-off-at", "8", "--bus-off-for", "0.2"))
    try:
        time.sleep(0.2)
        assert cli.main(["upload", str(SKILL), "--slot", "1", "-q", *srv.bus_args()]) == 0
        csv = tmp_path / "r.csv"
        rc, out, err = run(
            capsys,
            "run",
            "--slot",
            "1",
            "--end",
            "hold",
            "--hold-for",
            "30",
            "--csv",
            str(csv),
            *srv.bus_args(),
        )
        assert rc == 2 and "[665]" in err and "fault 501 (bus-off)" in err and f"written to {csv}" in err
        cols = load_csv(csv)
        i = int(np.flatnonzero(cols["fault"])[0])  # the fault's row, then its stop ramp
        assert np.all(cols["fault"][i:] == 501) and np.all(cols["fault"][:i] == 0) and i > 100
        assert np.all(np.diff(cols["t"]) > 0)
        # after the stop ramp the simulated drive parks the handle at the start (a free handle
        # drifted away at 3.5 cm/s, out of the workspace within 15 s: no clear possible)
        x = parked_positions(srv)
        assert np.all(np.abs(x - cols["x"][0]) < 1e-4), x
        rc, out, err = run(capsys, "status", "--clear", *srv.bus_args())
        assert rc == 0 and "latched faults: 501 (bus-off)" in out and "faults cleared" in out, out + err
        rc, out, err = run(capsys, "status", *srv.bus_args())
        assert rc == 0 and "IDLE, fault none" in out
    finally:
        srv.stop()


def test_a_fault_keeps_the_telemetry_at_1khz_through_the_stop_ramp(loaded, capsys, tmp_path, monkeypatch):
    """The host's heartbeat stops 0.75 s into the 1.5 s press (while the command moves the carriage;
    timed from the device's EXECUTE, after the run's sliced SecurityAccess): the device latches
    host silence (500)
    and ramps the force down in 40 ticks (out_k = from x (40 - k)/40, k = 1..40, from = the
    previous tick's command). The CSV keeps every tick of the ramp: f_cmd measured at 1 kHz."""
    import threading

    from forceskill.link.device import Device

    start = Device.start_heartbeat

    def go_silent_mid_press(dev: Device) -> None:
        end = time.monotonic() + 30.0
        while time.monotonic() < end and (dev.status is None or dev.status.state != "EXECUTE"):
            time.sleep(0.005)
        time.sleep(0.75)
        dev.stop_heartbeat()

    def start_then_go_silent(self: Device, telemetry_period_ms: int = 0) -> None:
        start(self, telemetry_period_ms)
        threading.Thread(target=go_silent_mid_press, args=(self,), daemon=True).start()

    monkeypatch.setattr(Device, "start_heartbeat", start_then_go_silent)
    csv = tmp_path / "r.csv"
    rc, out, err = run(
        capsys,
        "run",
        "--slot",
        "1",
        "--end",
        "hold",
        "--hold-for",
        "30",
        "--csv",
        str(csv),
        *loaded.bus_args(),
    )
    assert rc == 2 and "fault 500 (host silence)" in err, out + err
    cols = load_csv(csv)
    i = int(np.flatnonzero(cols["fault"])[0])
    assert np.all(cols["fault"][i:] == 500) and np.all(cols["fault"][:i] == 0)
    assert cols["t"].size - i == 51, cols["t"].size - i  # the fault's row and 50 after it
    assert np.all(np.diff(cols["t"]) > 0.0009) and np.all(np.diff(cols["t"]) < 0.0011)  # 1 kHz
    c0 = cols["f_cmd"][i - 1]
    assert abs(c0) > 0.2, c0  # the command holding the press (the contact force near 4.84 N)
    k = np.arange(1, 41)
    ramp = c0 * (40 - k) / 40.0
    # 0.01 N telemetry counts: c0 and each sample within half a count of the device's value
    assert np.max(np.abs(cols["f_cmd"][i : i + 40] - ramp)) <= 0.011, cols["f_cmd"][i - 1 : i + 41]
    assert np.all(cols["f_cmd"][i + 39 :] == 0.0)
    rc, out, err = run(capsys, "status", "--clear", *loaded.bus_args())
    assert rc == 0 and "faults cleared" in out, out + err


def parked_positions(srv: Server) -> np.ndarray:
    """x of the FAULT-state telemetry (every 100 ms) from 1 s to 3 s after now."""
    import argparse

    from forceskill.commands._common import connect

    ns = argparse.Namespace(
        interface="socketcand",
        channel="can0",
        bus_kwargs={"host": "127.0.0.1", "port": srv.port},
        node=0,
        timeout=3.0,
    )
    with connect(ns) as dev:
        time.sleep(1.0)
        tel = dev.start_telemetry()
        time.sleep(2.0)
        assert dev.status is not None and dev.status.state == "FAULT"
        return np.array([s.x_m for s in tel.samples])


def test_a_refused_clear_names_the_cause_that_persists():
    import udsoncan
    from udsoncan.exceptions import NegativeResponseException

    from forceskill.commands.status import clear_faults
    from forceskill.errors import FsError

    class Client:
        def start_routine(self, rid: int) -> None:
            r = udsoncan.Response(service=udsoncan.services.RoutineControl, code=0x22)
            raise NegativeResponseException(r)

        def read_data_by_identifier(self, did: int):  # latched 507 and 509; 509 and 500 present
            class R:
                class service_data:
                    values = {did: (1 << 7 | 1 << 9).to_bytes(4, "big") + (1 << 9 | 1).to_bytes(4, "big")}  # noqa: RUF012

            return R

    with pytest.raises(FsError) as e:
        clear_faults(Client(), 0, "FAULT")
    assert e.value.code == 666
    assert "cause still present: 509 (outside workspace)" in e.value.message
    assert "latched: 507 (contact force above limit), 509 (outside workspace)" in e.value.message


def test_a_skill_stiffer_than_the_device_limit_is_refused_by_host_and_device(loaded, capsys, tmp_path):
    """The device (ideal plant: limit 5e5 N/m, DID 0x0140) refuses a skill fitted for a stiffer
    object at commit (227) and at start; upload and run refuse it first, before anything is sent
    or started (690)."""
    import struct

    from forceskill.errors import FsError
    from forceskill.link import uds as U
    from forceskill.link.device import Device
    from forceskill.model import synthetic
    from forceskill.model.fit import fit

    stiff = tmp_path / "stiff.skill"
    fit(synthetic.pressing(7, 2.0), 1e6, surface_m=0.001).skill.write(stiff)
    rc, _out, err = run(capsys, "upload", str(stiff), "--slot", "2", "-q", *loaded.bus_args())
    assert rc == 2 and err.count("\n") == 1, err
    assert (
        "[690]" in err
        and "nominal stiffness 1e+06 N/m is above the stiffness limit 5e+05 N/m of node 0" in err
    )
    assert "nothing was sent" in err
    import can

    bus = can.Bus(interface="socketcand", channel="can0", host="127.0.0.1", port=loaded.port)
    with Device(bus, node=0) as dev, U.uds_client(dev) as client:
        assert U.stiffness_limit(client, 0) == 5e5
        assert not U.slot_directory(client, 0)[1]["valid"]
        # the device itself: the commit is refused with 227, slot 2 stays empty
        U.unlock(client, 0, 0x02)
        with pytest.raises(FsError) as e:
            U.download(client, 0, 2, stiff.read_bytes())
        assert "device status 227: stiffness above the device's limit" in e.value.message
        assert not U.slot_directory(client, 0)[1]["valid"]
        # a lower limit (written as a setting) makes the 100 N/m skill of slot 1 too stiff
        client.write_data_by_identifier(U.DID_STIFFNESS_MAX, struct.pack(">f", 50.0))
        try:
            rc2, _out2, err2 = run(capsys, "run", "--slot", "1", *loaded.bus_args())
            assert rc2 == 2 and "[690]" in err2 and "slot 1: nominal stiffness 100 N/m" in err2
            assert "limit 50 N/m of node 0" in err2 and "nothing was started" in err2
            # and the device refuses the start routine itself (in the unlocked session a run needs;
            # the run command's own session replaced ours)
            U.unlock(client, 0, 0x02)
            with pytest.raises(Exception) as e2:
                client.start_routine(U.RID_RUN_SKILL, data=struct.pack(">BHHB", 1, 1000, 1000, 0))
            assert e2.value.response.code == 0x31
            assert dev.status is not None and dev.status.state == "IDLE"
        finally:
            U.unlock(client, 0, 0x02)
            client.write_data_by_identifier(U.DID_STIFFNESS_MAX, struct.pack(">f", 5e5))
        assert U.stiffness_limit(client, 0) == 5e5
    bus.shutdown()


def test_lost_telemetry_frames_are_interpolated_and_counted_not_truncated(capsys, tmp_path):
    """An adapter that misses 2 % of the telemetry frames: the run's CSV still covers the whole
    execution on the 1 ms grid, the lost samples are reported, and the reference is the skill's."""
    srv = Server(SCENARIOS / "pressing_task1_demo.toml", extra=("--drop-telemetry", "0.02"))
    try:
        time.sleep(0.2)
        assert cli.main(["upload", str(SKILL), "--slot", "1", "-q", *srv.bus_args()]) == 0
        csv = tmp_path / "r.csv"
        rc, out, err = run(capsys, "run", "--slot", "1", "--csv", str(csv), *srv.bus_args())
        assert rc == 0, err
        lost = int(out.split(" samples lost on the bus")[0].rsplit("telemetry: ", 1)[1])
        cols = load_csv(csv)
        assert np.allclose(np.diff(cols["t"]), 1e-3) and abs(cols["t"][-1] - (1.5 + 0.5)) < 0.01
        assert 0.5 * 0.02 * cols["t"].size < lost < 4 * 0.02 * cols["t"].size  # ~2-4 % of the samples
        assert 4.6 < cols["f_hat"].max() < 5.1  # the skill's peak (4.84 N) is in the run
    finally:
        err = srv.stop()
    injected = int(err.split(" telemetry frames lost")[0].rsplit(", ", 1)[1])
    assert lost <= injected


def test_a_run_without_telemetry_is_an_error_not_an_empty_report(capsys, tmp_path):
    srv = Server(SCENARIOS / "pressing_task1_demo.toml", extra=("--drop-telemetry", "1"))
    try:
        time.sleep(0.2)
        assert cli.main(["upload", str(SKILL), "--slot", "1", "-q", *srv.bus_args()]) == 0
        rc, out, err = run(capsys, "run", "--slot", "1", *srv.bus_args())
        assert rc == 2 and "[692]" in err and "no telemetry arrived" in err, out + err
    finally:
        srv.stop()

"""The user's day over CAN against the simulator, through python-can's socketcand interface only:
record a pressing demonstration (TEACH) to .blf, fit it, upload it with udsoncan (read-back
verified), run it at 1x and 1.5x, and check the tracking figures of docs/hil.md on the recorded telemetry.
Also: a log written by `python -m can.logger` is accepted by `forceskill fit`, and cantools decodes
every cyclic frame the device sends."""

from __future__ import annotations

import signal
import subprocess
import sys
import time
from pathlib import Path

import can
import cantools
import numpy as np
import pytest

from forceskill.model.demo import load_demo
from forceskill.model.skill import Skill
from forceskill.wire.dbc import dbc_path
from helpers.canbus import (
    JOURNEY_HOST_TIMEOUT_MS,
    PRESS_K_NPM,
    PRESS_SURFACE_M,
    SCENARIOS,
    TELEMETRY_PERIOD_MS,
    Server,
    fit_press,
    forceskill,
    socketcand_args,
)


@pytest.fixture(scope="module")
def server():
    """The journey's simulator: host-silence timeout JOURNEY_HOST_TIMEOUT_MS (helpers.canbus: suited to CI)."""
    s = Server(SCENARIOS / "pressing_task1_demo.toml", host_timeout_ms=JOURNEY_HOST_TIMEOUT_MS)
    time.sleep(0.2)
    yield s
    s.stop()


@pytest.fixture(scope="module")
def journey(server, tmp_path_factory):
    d = tmp_path_factory.mktemp("journey")
    return {"dir": d, "server": server}


def test_record_fit_upload_run(journey, capsys):
    d, srv = journey["dir"], journey["server"]
    bus = srv.bus_args()
    out = forceskill(capsys, "record", "-o", str(d / "demo.blf"), "--duration", "6", *bus)
    assert "in TEACH" in out
    demo = load_demo(d / "demo.blf")
    # the log ends at the duration however far the command's own loop lags behind the stream
    # (in the qemu guest TEACH runs on for seconds: helpers.canbus.RECORD_OVERRUN_S)
    assert 5.9 <= demo.t_s[-1] <= 6.1 and np.allclose(np.diff(demo.t_s), TELEMETRY_PERIOD_MS * 1e-3)
    assert 3.5 < demo.force_N.max() < 6.0  # the seeded operator's high level (4.5 N +- 10 %)
    out = fit_press(capsys, d / "demo.blf", d / "press.skill")
    err_max = float(out.split("approximation error: max ")[1].split(" %")[0])
    # against the recorded force, its sensor noise included: the noise drawn depends on the
    # server's ticks before TEACH, so the figure varies from run to run (1.77-2.51 % in five runs)
    assert err_max <= 3.0
    out = forceskill(capsys, "upload", str(d / "press.skill"), "--slot", "1", "-q", *bus)
    assert "verified by read-back" in out
    status = forceskill(capsys, "status", *bus)
    sk = Skill.read(d / "press.skill")
    assert f"slot 1: {len(sk.to_bytes())} bytes" in status
    results = {}
    for g in ("1", "1.5"):
        csv = d / f"run_{g}.csv"
        out = forceskill(
            capsys,
            "run",
            "--slot",
            "1",
            "--goal-scale",
            g,
            "--csv",
            str(csv),
            "-o",
            str(d / f"run_{g}.blf"),
            *bus,
        )
        results[g] = load_csv(csv)
    journey["results"] = results
    journey["skill"] = sk
    # the whole journey ran under the device's host-silence supervision of JOURNEY_HOST_TIMEOUT_MS
    import argparse

    from forceskill.commands._common import connect
    from forceskill.link import uds as U
    from forceskill.link.bus import add_bus_args

    parser = argparse.ArgumentParser()
    add_bus_args(parser)
    ns = parser.parse_args(bus)  # the server's bus, whatever its interface
    with connect(ns) as dev, U.uds_client(dev) as client:
        comm = U.read_did(client, U.DID_COMM, 0)
    assert int.from_bytes(comm[1:3], "big") == srv.host_timeout_ms == JOURNEY_HOST_TIMEOUT_MS


#: How far a run's CSV may end from the motion's duration: 10 ms at 1 kHz telemetry; with a
#: longer --telemetry-period the first and the last sample each sit up to a period less one tick
#: inside the motion (the device sends on its tick grid), and the CSV spans first to last.
SPAN_TOL_S = 0.01 + 2 * (TELEMETRY_PERIOD_MS - 1) * 1e-3


def load_csv(path: Path) -> dict[str, np.ndarray]:
    a = np.genfromtxt(path, delimiter=",", names=True)
    return {n: np.asarray(a[n]) for n in a.dtype.names}


def tracking(cols):
    peak = cols["f_hat"].max()
    e = cols["f_contact"] - cols["f_hat"]
    return 100 * np.abs(e).max() / peak, 100 * np.sqrt(np.mean(e * e)) / peak


def test_tracking_figures_1x_and_1_5x(journey):
    res = journey["results"]
    for g, cols in res.items():
        mx, rms = tracking(cols)
        # execution force tracking RMS <= 3 % of max force (ideal plant)
        assert rms <= 3.0, f"goal x{g}: tracking RMS {rms:.2f} %"
        # max: 2.7 % (1x) and 1.7 % (1.5x) measured; 6 % catches a run that starts before the
        # handle is parked (a too slow simulated park gave 6.9 % at 1.5x, the start transient)
        i = int(np.argmax(np.abs(cols["f_contact"] - cols["f_hat"])))
        assert mx <= 6.0, (
            f"goal x{g}: tracking max {mx:.2f} % at row {i} of {cols['t'].size} (t {cols['t'][i]:.3f} s: "
            f"f_contact {cols['f_contact'][i]:.3f} N, f_hat {cols['f_hat'][i]:.3f} N, f_cmd {cols['f_cmd'][i]:.3f} N)"
        )
        assert np.all(np.abs(cols["f_cmd"]) <= 50.0 + 1e-9)  # F_max at the last stage
    # goal scaling scales the force by 1.5 (reference exactly, measured within 3 %)
    r_ref = res["1.5"]["f_hat"].max() / res["1"]["f_hat"].max()
    r_meas = res["1.5"]["f_contact"].max() / res["1"]["f_contact"].max()
    assert abs(r_ref - 1.5) < 0.01 and abs(r_meas - 1.5) < 0.045
    # executed for the skill's duration, then the release (0.5 s) and back to IDLE (1 kHz stream ends)
    assert abs(res["1"]["t"][-1] - (journey["skill"].duration_s + 0.5)) < SPAN_TOL_S
    assert res["1"]["f_hat"][-1] < 0.05 * res["1"]["f_hat"].max()


def test_sequence_in_series(journey, capsys):
    """run --sequence: two steps of the uploaded skill in series; the force is continuous at the
    switch and the second step starts the profile again."""
    d, srv = journey["dir"], journey["server"]
    csv = d / "seq.csv"
    out = forceskill(capsys, "run", "--sequence", "1:2s,1:2.5s", "--csv", str(csv), *srv.bus_args())
    assert "sequence 1:2s,1:2.5s" in out
    cols = load_csv(csv)
    t, ref = cols["t"], cols["f_hat"]
    assert abs(t[-1] - (4.5 + 0.5)) < SPAN_TOL_S  # both steps, then the release
    i_switch = int(round(2.0 / 1e-3))
    assert abs(ref[i_switch + 1] - ref[i_switch - 1]) < 0.05 * ref.max()  # continuous at the switch
    _mx, rms = tracking(cols)
    assert rms <= 3.0


def test_cantools_decodes_every_device_frame(journey):
    db = cantools.database.load_file(str(dbc_path()))
    device_ids = {m.frame_id for m in db.messages if m.senders == ["Device"]}
    seen: dict[int, int] = {}
    for log in sorted(journey["dir"].glob("*.blf")):
        for msg in can.LogReader(str(log)):
            if msg.arbitration_id in device_ids:
                decoded = db.decode_message(msg.arbitration_id, msg.data, decode_choices=False)
                assert all(np.isfinite(float(v)) for v in decoded.values() if not isinstance(v, str))
                seen[msg.arbitration_id] = seen.get(msg.arbitration_id, 0) + 1
            elif msg.arbitration_id == 0x680:  # UDS responses: ISO-TP, not DBC frames
                assert msg.dlc == 8 and (msg.data[0] >> 4) in (0, 1, 2, 3)
    names = {db.get_message_by_frame_id(i).name for i in seen}
    assert {"DeviceStatus", "TelemetryPosition", "TelemetryForce"} <= names
    # 1 kHz telemetry of record, run x2 and the sequence; fewer where --telemetry-period asks
    n_min = 15000 // TELEMETRY_PERIOD_MS
    assert seen[0x190] > n_min and seen[0x1A0] > n_min


def wait_caught_up(log: Path, timeout_s: float = 30.0) -> None:
    """Wait until the logger has written what it received while the device streamed at 1 kHz:
    a loaded machine leaves it seconds behind, and SIGINT drops what it has not read yet. Caught
    up, it grows at the idle rate (~110 frames/s, ~5 KB/s); behind, at >= 1,000 frames/s."""
    t_end, last = time.monotonic() + timeout_s, -1
    while time.monotonic() < t_end:
        size = log.stat().st_size if log.exists() else 0
        if last >= 0 and size - last < 15_000:
            return
        last = size
        time.sleep(1.0)


#: python-can's logger (`python -m can.logger ARGS`) with Ctrl-C's default: a child inherits an
#: ignored or blocked SIGINT across exec, and Python then keeps it so (the logger ran on after
#: SIGINT, waiting in its receive loop, when the test's process had it so).
LOGGER_MAIN = (
    "import runpy, signal; signal.signal(signal.SIGINT, signal.default_int_handler); "
    "signal.pthread_sigmask(signal.SIG_UNBLOCK, [signal.SIGINT]); "
    "runpy.run_module('can.logger', run_name='__main__', alter_sys=True)"
)


def stop_logger(p: subprocess.Popen[bytes], err: Path) -> None:
    """Stop python-can's logger as its user does (Ctrl-C: it closes the log). Once, on a fresh
    clone's loaded machine, it was still running 20 s after SIGINT: a second SIGINT follows, and
    if that does not end it either, its threads' stacks (faulthandler, SIGABRT) go into the
    failure, so the cause can be read."""
    for wait_s in (15.0, 10.0):
        p.send_signal(signal.SIGINT)
        try:
            p.wait(timeout=wait_s)
            return
        except subprocess.TimeoutExpired:
            continue
    p.send_signal(signal.SIGABRT)
    p.wait(timeout=10)
    here = (signal.getsignal(signal.SIGINT), signal.pthread_sigmask(signal.SIG_BLOCK, []))
    pytest.fail(
        f"can.logger still ran 25 s after SIGINT (this process: SIGINT handler, blocked {here}); "
        f"its stderr:\n{err.read_text()[-4000:]}"
    )


def test_can_logger_log_accepted_by_fit(server, tmp_path, capsys):
    log = tmp_path / "logger.asc"
    err = tmp_path / "logger.stderr"
    with err.open("wb") as err_f:
        p = subprocess.Popen(
            [
                sys.executable,
                "-X",
                "faulthandler",
                "-c",
                LOGGER_MAIN,
                *socketcand_args(server.port),
                "-f",
                str(log),
            ],
            stdout=subprocess.DEVNULL,
            stderr=err_f,
        )
    try:
        time.sleep(1.5)
        forceskill(
            capsys, "record", "-o", str(tmp_path / "driver.log"), "--duration", "5", *server.bus_args()
        )
        wait_caught_up(log)
    finally:
        stop_logger(p, err)
    out = forceskill(
        capsys,
        "fit",
        str(log),
        "--stiffness",
        str(PRESS_K_NPM),
        "--surface-m",
        str(PRESS_SURFACE_M),
        "-o",
        str(tmp_path / "from_logger.skill"),
    )
    assert "logger.asc:f_contact" in out and "T = 5.0" in out
    # the python-can logger's copy and forceskill's own .log record the same demonstration
    a, b = load_demo(log), load_demo(tmp_path / "driver.log")
    n = min(a.t_s.size, b.t_s.size)
    assert n > 4900 and np.array_equal(a.force_N[:n], b.force_N[:n])


@pytest.mark.parametrize("suffix", [".asc", ".log", ".trc", ".csv"])
def test_every_log_format_reads_the_same_demo(journey, suffix):
    """The recorded .blf rewritten by python-can's writer for each suffix gives the same
    demonstration through the DBC (record -o accepts all of them)."""
    src = journey["dir"] / "demo.blf"
    dst = journey["dir"] / f"demo_copy{suffix}"
    with can.Logger(str(dst)) as w:
        for m in can.LogReader(str(src)):
            w.on_message_received(m)
    a, b = load_demo(src), load_demo(dst)
    assert a.t_s.size == b.t_s.size and np.array_equal(a.force_N, b.force_N)
    assert np.allclose(a.pos_m, b.pos_m, atol=1e-12)

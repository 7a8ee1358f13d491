"""Bus faults injected by `hil_sim serve` on the frames reaching the device: corrupted frames are
rejected by the E2E check (no command is ever taken from them), a bus-off latches fault 501 and
stops the demonstration, lost heartbeats within the timeout do not."""

from __future__ import annotations

import time

from forceskill import cli
from helpers.canbus import SCENARIOS, Server


def run(capsys, *argv: str) -> tuple[int, str, str]:
    rc = cli.main(list(argv))
    out, err = capsys.readouterr()
    return rc, out, err


def test_corrupted_frames_never_command(capsys, tmp_path):
    srv = Server(SCENARIOS / "pressing_task1_demo.toml", extra=("--corrupt", "1"))
    try:
        time.sleep(0.2)
        rc, out, err = run(
            capsys, "record", "-o", str(tmp_path / "x.blf"), "--duration", "1", *srv.bus_args()
        )
        # every frame corrupted: the motion key's exchange fails too (no answer, or a corrupted
        # request refused: 635/694), or TEACH is never reached; nothing moves
        assert rc == 2 and "recording node" not in out, err
        assert "[635]" in err or "[694]" in err or ("did not reach TEACH" in err and "state IDLE" in err)
    finally:
        log = srv.stop()
    assert "corrupted" in log and " 0 corrupted" not in log


def test_bus_off_latches_fault_501(capsys, tmp_path):
    srv = Server(
        SCENARIOS / "pressing_task1_demo.toml", extra=("--bus-off-at", "2.5", "--bus-off-for", "0.3")
    )
    try:
        time.sleep(0.2)
        rc, out, err = run(
            capsys, "record", "-o", str(tmp_path / "x.blf"), "--duration", "5", *srv.bus_args()
        )
        assert rc == 2 and "left TEACH (FAULT, fault 501 (bus-off))" in err and "[665]" in err
        # what was recorded up to the fault is kept
        assert "kept what was recorded" in err and (tmp_path / "x.blf").stat().st_size > 10000
        time.sleep(0.5)
        rc, out, err = run(capsys, "status", "--clear", *srv.bus_args())
        assert rc == 0 and "FAULT, fault 501" in out and "faults cleared" in out
        rc, out, err = run(capsys, "status", *srv.bus_args())
        assert rc == 0 and "IDLE, fault none" in out
    finally:
        srv.stop()


def test_lost_heartbeats_tolerated(capsys, tmp_path):
    srv = Server(SCENARIOS / "pressing_task1_demo.toml", extra=("--drop", "0.2"))
    try:
        time.sleep(0.2)
        rc, _out, err = run(
            capsys, "record", "-o", str(tmp_path / "x.blf"), "--duration", "2", *srv.bus_args()
        )
        assert rc == 0, err
    finally:
        log = srv.stop()
    assert " 0 lost" not in log

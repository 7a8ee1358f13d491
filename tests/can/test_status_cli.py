"""`forceskill status` as a Unix tool against the simulator: cut by `head -1` it ends quietly, and
`--clear` with nothing latched is success (the state the user asked for already holds)."""

from __future__ import annotations

import os
import subprocess
import sys

import pytest

from forceskill import cli
from helpers.canbus import Server

EXE = [sys.executable, "-m", "forceskill"]


def test_status_cut_by_head_ends_quietly(server: Server) -> None:
    p = subprocess.Popen(
        [*EXE, "status", *server.bus_args()], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True
    )
    assert p.stdout is not None and p.stderr is not None
    first = p.stdout.readline()
    p.stdout.close()
    err = p.stderr.read()
    rc = p.wait(timeout=60)
    assert first.startswith("node 0 on can0") and ": IDLE, fault none" in first
    assert err == "" and rc in (0, cli.EXIT_PIPE_CLOSED), (rc, err)
    # the reader gone before anything is printed: still no error line, the device left as it was
    r, w = os.pipe()
    os.close(r)
    try:
        done = subprocess.run(
            [*EXE, "status", *server.bus_args()], stdout=w, stderr=subprocess.PIPE, text=True, timeout=60
        )
    finally:
        os.close(w)
    assert done.stderr == "" and done.returncode == cli.EXIT_PIPE_CLOSED


def test_clear_with_no_fault_is_success(server: Server, capsys: pytest.CaptureFixture[str]) -> None:
    rc = cli.main(["status", "--clear", *server.bus_args()])
    out, err = capsys.readouterr()
    assert rc == 0 and err == ""
    lines = out.splitlines()
    assert ": IDLE, fault none" in lines[0]
    assert lines[1] == "no fault to clear (state IDLE)"
    assert lines[2].startswith("firmware ")

"""`hil_sim serve` on a free port, driven only through python-can's socketcand interface (the
product's commands and third-party clients). $FORCESKILL_CAN_SPEED sets the simulator's speed
factor (default 1: real time, as robust as possible on a busy machine)."""

from __future__ import annotations

import argparse
import os
import subprocess
from pathlib import Path
from typing import Any

from helpers.paths import REPO, SCENARIOS, hil_sim_path  # noqa: F401  (re-exported for the CAN tests)

SPEED = float(os.environ.get("FORCESKILL_CAN_SPEED", "1"))
# The device stops safely after this much host silence (product default 100 ms, documented in
# docs/protocol.md and tested in C: tests/firmware/proto/test_app.c). The host tools here run in
# Python on a shared machine: on 2 cores at load ~19 (CI beside two CPU-bound processes and other
# jobs) a plain `time.sleep(0.01)` loop was measured waking up to 324 ms late, and the heartbeat's
# worst gap (bench/can_heartbeat/heartbeat_gap.py) was 86-245 ms. No host can promise 100 ms
# there, so every CAN test, the journey included, runs the simulated device with the largest
# timeout it accepts; FORCESKILL_CAN_JOURNEY_HOST_TIMEOUT_MS=100 runs the journey at the product
# default on an idle machine.
HOST_TIMEOUT_MS = int(os.environ.get("FORCESKILL_CAN_HOST_TIMEOUT_MS", "500"))
JOURNEY_HOST_TIMEOUT_MS = int(os.environ.get("FORCESKILL_CAN_JOURNEY_HOST_TIMEOUT_MS", str(HOST_TIMEOUT_MS)))
# The host tools' --timeout (seconds without the device's frames before a command gives up):
# scripts/test_linux_can.sh raises it in its qemu guest, where a Python thread under TCG on a
# loaded machine can stall for seconds.
LINK_TIMEOUT_S = os.environ.get("FORCESKILL_CAN_TIMEOUT_S", "3")
# Each UDS request's wait (--request-timeout; unset: the commands' own 2-5 s): scripts/test_linux_can.sh
# sets it in its qemu guest, where an answer on the bus can reach a stalled Python thread seconds late.
REQUEST_TIMEOUT_S = os.environ.get("FORCESKILL_CAN_REQUEST_TIMEOUT_S", "")
# The telemetry period record and run ask of the device on a SocketCAN interface
# (--telemetry-period; default 1 ms, the product's): scripts/test_linux_can.sh asks 10 in its qemu
# guest, where Python reads about 150 frames/s (bench figure in docs/hil.md), not the 2,100 of 1 kHz.
TELEMETRY_PERIOD_MS = int(os.environ.get("FORCESKILL_CAN_TELEMETRY_PERIOD_MS", "1"))
# How much longer than record's --duration another logger's log of it may come out (candump):
# record stops TEACH when its own loop reads the device's status at the duration, so a reader
# behind the stream leaves TEACH on for longer (0.5-2.2 s of device time seen in the qemu guest,
# where scripts/test_linux_can.sh allows 3 s; 0 here). record's own log ends at the duration.
RECORD_OVERRUN_S = float(os.environ.get("FORCESKILL_CAN_RECORD_OVERRUN_S", "0"))


def socketcand_args(port: int) -> list[str]:
    """python-can's command-line options for the simulator's socketcand bus on port."""
    return ["-i", "socketcand", "-c", "can0", "--bus-kwargs", "host=127.0.0.1", f"port={port}"]


def serve(
    bus: list[str], scenario: Path, node: int, speed: float, host_timeout_ms: int, extra: tuple
) -> subprocess.Popen:
    """Start `hil_sim serve` with the bus options bus (--port 0, or --socketcan IFACE); its first
    stdout line says where it listens."""
    return subprocess.Popen(
        [
            str(hil_sim_path()),
            "serve",
            *bus,
            "--speed",
            str(speed),
            "--scenario",
            str(scenario),
            "--node",
            str(node),
            "--host-timeout",
            str(host_timeout_ms),
            *extra,
        ],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )


class Server:
    """A running `hil_sim serve` (terminated by the fixture)."""

    def __init__(
        self,
        scenario: Path,
        speed: float = SPEED,
        node: int = 0,
        extra: tuple = (),
        host_timeout_ms: int = HOST_TIMEOUT_MS,
    ) -> None:
        self.host_timeout_ms = host_timeout_ms
        self.proc = serve(["--port", "0"], scenario, node, speed, host_timeout_ms, extra)
        line = self.proc.stdout.readline()
        assert "listening on 127.0.0.1:" in line, (
            f"hil_sim serve did not start: {line!r} {self.proc.stderr.read()}"
        )
        self.port = int(line.split("127.0.0.1:")[1].split()[0])
        self.node = node
        self.speed = speed

    def bus_args(self, node: int | None = None) -> list[str]:
        """The CLI's bus options for this server (node: the server's unless given)."""
        node = self.node if node is None else node
        return [*socketcand_args(self.port), "--node", str(node), "--timeout", LINK_TIMEOUT_S]

    def namespace(self, node: int = 0) -> argparse.Namespace:
        """The parsed form of bus_args, for link functions that take the CLI's arguments."""
        return argparse.Namespace(
            interface="socketcand",
            channel="can0",
            bus_kwargs={"host": "127.0.0.1", "port": self.port},
            node=node,
            timeout=3.0,
        )

    def stop(self) -> str:
        self.proc.terminate()
        try:
            _, err = self.proc.communicate(timeout=10)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            _, err = self.proc.communicate()
        return err


def forceskill(capsys: Any, *argv: str) -> str:
    """Run the forceskill CLI in-process; its stdout (a failure names the command and stderr)."""
    from forceskill import cli

    rc = cli.main(list(argv))
    out, err = capsys.readouterr()
    assert rc == 0, f"forceskill {' '.join(argv)} failed ({rc}): {err}"
    return out


# Pressing task 1's outer layer (hil_sim/scenarios/pressing_task1_demo.toml), shared by the CAN
# journeys: stiffness, surface, and the object's mass m_v_kg the default force gains adapt to.
PRESS_K_NPM = 100.0
PRESS_SURFACE_M = 0.001
PRESS_OBJECT_MASS_KG = 10.0


def fit_press(capsys: Any, demo: Path, skill: Path) -> str:
    """`forceskill fit` of a pressing-task-1 recording into a skill ending in a release; its stdout."""
    return forceskill(
        capsys,
        "fit",
        str(demo),
        "--stiffness",
        str(PRESS_K_NPM),
        "--surface-m",
        str(PRESS_SURFACE_M),
        "--object-mass",
        str(PRESS_OBJECT_MASS_KG),
        "--end",
        "release",
        "-o",
        str(skill),
    )

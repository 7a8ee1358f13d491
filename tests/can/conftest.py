"""Fixtures of the CAN end-to-end tests: `hil_sim serve` on a free port, driven only through
python-can's socketcand interface (the product's commands and third-party clients).

The binary is $FORCESKILL_HIL_SIM, else build/hil_sim/hil_sim (the README's build); a missing
binary is a failure naming the build command. $FORCESKILL_CAN_SPEED sets the simulator's speed
factor (default 1: real time, as robust as possible on a busy machine)."""
from __future__ import annotations

import os
import subprocess
import time
from pathlib import Path
from typing import Iterator

import pytest

REPO = Path(__file__).resolve().parents[2]
SCENARIOS = REPO / "hil_sim" / "scenarios"
SPEED = float(os.environ.get("FORCESKILL_CAN_SPEED", "1"))
# The device stops safely after this much host silence (default 100 ms). The tests' host tools
# run in Python on a shared, loaded machine, where a process can stall for long; the journey
# (tests/can/test_journey.py) runs with the product default (JOURNEY_HOST_TIMEOUT_MS: the worst
# heartbeat gap measured over 60 s in TEACH is 17-86 ms, bench/can_heartbeat/heartbeat_gap.py),
# the other modules with the configurable maximum. The product default itself is also tested in
# C (tests/firmware/app/test_app.c).
HOST_TIMEOUT_MS = int(os.environ.get("FORCESKILL_CAN_HOST_TIMEOUT_MS", "500"))
JOURNEY_HOST_TIMEOUT_MS = int(os.environ.get("FORCESKILL_CAN_JOURNEY_HOST_TIMEOUT_MS", "100"))


def hil_sim_path() -> Path:
    p = Path(os.environ.get("FORCESKILL_HIL_SIM", str(REPO / "build" / "hil_sim" / "hil_sim")))
    assert p.is_file() and os.access(p, os.X_OK), (
        f"hil_sim not built at {p}: run `cmake -S . -B build -G Ninja && ninja -C build hil_sim` "
        "or set FORCESKILL_HIL_SIM")
    return p


class Server:
    """A running `hil_sim serve` (terminated by the fixture)."""

    def __init__(self, scenario: Path, speed: float = SPEED, node: int = 0, extra: tuple = (),
                 host_timeout_ms: int = HOST_TIMEOUT_MS) -> None:
        self.host_timeout_ms = host_timeout_ms
        self.proc = subprocess.Popen([str(hil_sim_path()), "serve", "--port", "0", "--speed", str(speed),
                                      "--scenario", str(scenario), "--node", str(node),
                                      "--host-timeout", str(host_timeout_ms), *extra],
                                     stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        line = self.proc.stdout.readline()
        assert "listening on 127.0.0.1:" in line, f"hil_sim serve did not start: {line!r} {self.proc.stderr.read()}"
        self.port = int(line.split("127.0.0.1:")[1].split()[0])
        self.node = node
        self.speed = speed

    def bus_args(self, node: int | None = None) -> list[str]:
        return ["-i", "socketcand", "-c", "can0", "--bus-kwargs", "host=127.0.0.1", f"port={self.port}",
                "--node", str(self.node if node is None else node), "--timeout", "3"]

    def stop(self) -> str:
        self.proc.terminate()
        try:
            _, err = self.proc.communicate(timeout=10)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            _, err = self.proc.communicate()
        return err


@pytest.fixture(scope="module")
def server() -> Iterator[Server]:
    s = Server(SCENARIOS / "pressing_task1_demo.toml")
    time.sleep(0.2)
    yield s
    s.stop()

"""`hil_sim serve --socketcan IFACE` for the CAN tests: the device on a SocketCAN interface
(vcan0 by default, $FORCESKILL_VCAN to change), driven through python-can's `socketcan`
interface. `vcan_or_skip()` skips with a message where the kernel has no AF_CAN or the interface
is missing."""

from __future__ import annotations

import os
import socket
from pathlib import Path

import pytest

from helpers.canbus import (
    HOST_TIMEOUT_MS,
    LINK_TIMEOUT_S,
    REQUEST_TIMEOUT_S,
    SPEED,
    TELEMETRY_PERIOD_MS,
    Server,
    serve,
)

VCAN = os.environ.get("FORCESKILL_VCAN", "vcan0")
VCAN_HOWTO = (
    f"sudo modprobe vcan && sudo ip link add dev {VCAN} type vcan && sudo ip link set up {VCAN} (docs/hil.md)"
)


def af_can_error() -> str | None:
    """Why this kernel cannot open a CAN raw socket, or None if it can."""
    family = getattr(socket, "AF_CAN", None)
    if family is None:
        return "this Python has no socket.AF_CAN"
    try:
        socket.socket(family, socket.SOCK_RAW, socket.CAN_RAW).close()
    except OSError as e:
        return f"socket(AF_CAN): {e.strerror or e}"
    return None


def vcan_or_skip() -> str:
    """The interface name, or skip the test saying what is missing and how to add it."""
    why = af_can_error()
    if why is not None:
        pytest.skip(f"no SocketCAN in this kernel ({why}); where it exists: {VCAN_HOWTO}")
    s = socket.socket(socket.AF_CAN, socket.SOCK_RAW, socket.CAN_RAW)
    try:
        s.bind((VCAN,))
    except OSError as e:
        pytest.skip(f"no interface {VCAN} ({e.strerror or e}): {VCAN_HOWTO}")
    finally:
        s.close()
    return VCAN


class SocketCANServer(Server):
    """A running `hil_sim serve --socketcan IFACE` (stop(), from Server, ends it)."""

    def __init__(
        self,
        scenario: Path,
        iface: str,
        node: int = 0,
        extra: tuple = (),
        host_timeout_ms: int = HOST_TIMEOUT_MS,
        speed: float = SPEED,
    ) -> None:
        # not Server.__init__: no TCP port, the interface instead
        self.iface = iface
        self.speed = speed
        self.node = node
        self.host_timeout_ms = host_timeout_ms
        self.proc = serve(["--socketcan", iface], scenario, node, speed, host_timeout_ms, extra)
        self.first_line = self.proc.stdout.readline()
        assert f"on SocketCAN {iface}" in self.first_line, (
            f"hil_sim serve --socketcan did not start: {self.first_line!r} {self.proc.stderr.read()}"
        )

    def bus_args(self, node: int | None = None) -> list[str]:
        return [
            "-i",
            "socketcan",
            "-c",
            self.iface,
            "--node",
            str(self.node if node is None else node),
            "--timeout",
            LINK_TIMEOUT_S,
            "--telemetry-period",
            str(TELEMETRY_PERIOD_MS),
            *(["--request-timeout", REQUEST_TIMEOUT_S] if REQUEST_TIMEOUT_S else []),
        ]

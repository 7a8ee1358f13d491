"""`hil_sim serve --socketcan`: refusals with one line (here, where the kernel has no AF_CAN, the
command fails naming it), and where vcan exists: third-party python-can clients see the device
like a controller, a --bitrate request on an interface without bit timing is refused with one
line while the device runs on, and the stop line reports the interface's counters. The port's
code paths themselves run here in C over a socket pair (ctest -R "cansock|socketcan")."""

from __future__ import annotations

import subprocess
import time

import can
import pytest

from helpers.canbus import LINK_TIMEOUT_S, SCENARIOS, hil_sim_path
from helpers.socketcan import SocketCANServer, af_can_error, vcan_or_skip


def serve(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([str(hil_sim_path()), "serve", *args], capture_output=True, text=True, timeout=30)


def one_line(p: subprocess.CompletedProcess) -> str:
    lines = p.stderr.strip().splitlines()
    assert len(lines) == 1, p.stderr
    return lines[0]


def test_without_af_can_fails_with_one_line():
    why = af_can_error()
    if why is None:
        pytest.skip("this kernel has SocketCAN: the refusal without AF_CAN cannot happen here")
    p = serve("--socketcan", "vcan0", "--duration", "1")
    assert p.returncode == 1 and p.stdout == ""
    line = one_line(p)
    assert line.startswith("hil_sim serve: socket(AF_CAN) failed:") and "no SocketCAN" in line


def test_missing_interface_fails_with_one_line():
    p = serve("--socketcan", "fsnocan7", "--duration", "1")
    assert p.returncode == 1
    line = one_line(p)
    assert "AF_CAN" in line or "no CAN interface 'fsnocan7'" in line


@pytest.mark.parametrize(
    "args, needle",
    [
        (("--socketcan", "vcan0", "--port", "0"), "--port applies to the simulated bus"),
        (("--socketcan", "vcan0", "--bus-off-at", "1"), "--bus-off-at applies to the simulated bus"),
        (("--socketcan", "vcan0", "--channel", "can0"), "--channel applies to the simulated bus"),
        (("--socketcan", "can/0"), "needs an interface name of 1..15 characters"),
        (("--socketcan", "averyverylongcan0"), "needs an interface name"),
        (("--socketcan", "vcan0", "--bitrate", "2000000"), "--bitrate must be 10000..1000000"),
        (("--socketcan",), "--socketcan needs a value"),
    ],
)
def test_refusals(args, needle):
    p = serve(*args)
    assert p.returncode == 2
    assert needle in one_line(p)


@pytest.fixture(scope="module")
def vcan_server():
    iface = vcan_or_skip()
    s = SocketCANServer(SCENARIOS / "pressing_task1_demo.toml", iface, node=3, extra=("--bitrate", "500000"))
    time.sleep(0.2)
    yield s
    if s.proc.poll() is None:  # the test stops it to read its stderr
        s.stop()


def test_bitrate_on_vcan_refused_and_device_runs(vcan_server):
    """vcan has no bit timing: the request is one line on stderr, the device serves anyway."""
    assert "bitrate as configured" in vcan_server.first_line
    status: list[can.Message] = []
    # a status frame every 10 ms of device time; a guest under TCG may stall for seconds
    deadline = time.monotonic() + max(5.0, float(LINK_TIMEOUT_S))
    with can.Bus(interface="socketcan", channel=vcan_server.iface) as bus:
        while len(status) < 5 and time.monotonic() < deadline:
            m = bus.recv(0.5)
            if m is not None and m.arbitration_id == 0x183:  # DeviceStatus of node 3
                status.append(m)
    assert len(status) == 5 and all(m.dlc == 8 and not m.is_extended_id for m in status)
    err = vcan_server.stop()
    first = err.splitlines()[0]
    assert "no bit timing" in first and "--bitrate ignored" in first
    assert "SocketCAN " + vcan_server.iface in err.splitlines()[-1]

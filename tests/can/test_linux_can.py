"""The device on Linux CAN beyond vcan, run in the qemu guest of scripts/test_linux_can.sh:

- two emulated SJA1000 controllers (qemu's kvaser_pci, Linux's sja1000 driver) on one qemu
  can-bus, can0 for `hil_sim serve --socketcan can0 --bitrate` (the rate set through
  libsocketcan) and can1 for the host tools; the fault table's bus-off row (501 latched, nothing
  sent while off, the restart through the driver, the emergency frame first after it, once);
- can-utils: `candump -l` logs the device, `forceskill fit` reads that log, `cansniffer` lists
  the device's identifiers;
- CAN FD on vcan0 (MTU 72): `hil_sim serve --fd` and `forceskill upload --fd` (ISO-TP in 64-byte
  FD frames with bit-rate switching, read back), classic CAN unchanged without the option.

Each group skips with a message where its interfaces are missing (no SocketCAN here, no
kvaser_pci controllers, no can-utils, vcan0 without the FD MTU) or configuring them needs root."""

from __future__ import annotations

import itertools
import os
import shutil
import signal
import socket
import struct
import subprocess
import time
from pathlib import Path

import can
import numpy as np
import pytest

from forceskill.model.demo import load_demo
from forceskill.wire.dbc import UDS_REQUEST_BASE, UDS_RESPONSE_BASE, load_db
from helpers.canbus import (
    PRESS_K_NPM,
    PRESS_SURFACE_M,
    RECORD_OVERRUN_S,
    REPO,
    SCENARIOS,
    TELEMETRY_PERIOD_MS,
    forceskill,
    hil_sim_path,
)
from helpers.socketcan import SocketCANServer, af_can_error, vcan_or_skip

SCENARIO = SCENARIOS / "pressing_task1_demo.toml"
DB = load_db(0)
ID = {m.name: m.frame_id for m in DB.messages}
FAULT_BUS_OFF = 501
CAN_ERR_FLAG, CAN_ERR_BUSOFF, CAN_ERR_RESTARTED = 0x20000000, 0x00000040, 0x00000100


def sys_net(iface: str) -> Path:
    return Path("/sys/class/net") / iface


def sja1000_pair_or_skip() -> tuple[str, str]:
    """can0 and can1 of qemu's kvaser_pci controllers (driven by sja1000), or skip."""
    why = af_can_error()
    if why is not None:
        pytest.skip(f"no SocketCAN in this kernel ({why}): scripts/test_linux_can.sh runs this in a VM")
    for iface in ("can0", "can1"):
        drv = sys_net(iface) / "device" / "driver"
        if not drv.exists() or os.path.basename(os.readlink(drv)) != "kvaser_pci":
            pytest.skip(f"no kvaser_pci controller {iface} (scripts/vm.sh --kvaser 2)")
    if os.geteuid() != 0:
        pytest.skip("configuring can0/can1 needs root (the guest of scripts/vm.sh is root)")
    return "can0", "can1"


def ip(*args: str) -> str:
    p = subprocess.run(["ip", *args], capture_output=True, text=True, timeout=30)
    assert p.returncode == 0, f"ip {' '.join(args)}: {p.stderr.strip()}"
    return p.stdout


def link_details(iface: str) -> str:
    return ip("-details", "link", "show", iface)


@pytest.fixture(scope="module")
def pair():
    """can1 (the host's) at 500 kbit/s with restart-ms 100; can0 left down without a rate for
    hil_sim's --bitrate to set."""
    dev_if, host_if = sja1000_pair_or_skip()
    for iface in (dev_if, host_if):
        ip("link", "set", iface, "down")
    ip("link", "set", host_if, "type", "can", "bitrate", "500000", "restart-ms", "100")
    ip("link", "set", host_if, "up")
    yield dev_if, host_if
    for iface in (dev_if, host_if):
        subprocess.run(["ip", "link", "set", iface, "down"], capture_output=True, timeout=30)


@pytest.fixture(scope="module")
def sja_server(pair):
    dev_if, _ = pair
    s = SocketCANServer(SCENARIO, dev_if, extra=("--bitrate", "500000"))
    time.sleep(0.5)
    yield s
    if s.proc.poll() is None:
        s.stop()


def test_sja1000_bitrate_set_by_hil_sim_and_status_on_can1(pair, sja_server, capsys):
    """--bitrate reaches the real driver through libsocketcan (can0 was down with no rate), and
    the host on the other controller sees the device."""
    dev_if, host_if = pair
    if "bitrate 500000" not in sja_server.first_line:
        pytest.fail(f"{sja_server.first_line.strip()}; stderr: {sja_server.stop().strip()}")
    details = link_details(dev_if)
    assert "bitrate 500000" in details and "UP" in details.split(">")[0]
    out = forceskill(capsys, "status", *sja_server.bus_args(), "-c", host_if)
    assert "IDLE" in out


def inject_bus_off(iface: str, off_s: float) -> None:
    """The error frames a controller's driver sends with restart-ms: CAN_ERR_BUSOFF, then
    CAN_ERR_RESTARTED off_s later. Written on the device's interface, Linux's local echo hands
    them to the device's socket (qemu's SJA1000 model has no error states of its own: its
    controller never goes bus-off by itself)."""
    with socket.socket(socket.AF_CAN, socket.SOCK_RAW, socket.CAN_RAW) as s:
        s.bind((iface,))
        s.send(struct.pack("=IB3x8s", CAN_ERR_FLAG | CAN_ERR_BUSOFF, 8, bytes(8)))
        time.sleep(off_s)
        s.send(struct.pack("=IB3x8s", CAN_ERR_FLAG | CAN_ERR_RESTARTED, 8, bytes(8)))


def test_sja1000_bus_off_row(pair, sja_server):
    """The fault table's bus-off row on the real driver's error frames: 501 latched, silence
    while off (the port's restart requests refused by the driver: its controller is not bus-off),
    the "restarted" frame ends it, then the emergency frame first, once, the fault still latched."""
    dev_if, host_if = pair
    frames: list[can.Message] = []
    with can.Bus(interface="socketcan", channel=host_if) as bus:
        t_end = time.monotonic() + 3.0
        while time.monotonic() < t_end:  # the device's idle stream before
            m = bus.recv(0.2)
            if m is not None:
                frames.append(m)
        assert any(m.arbitration_id == ID["DeviceStatus"] for m in frames)
        t_inject = time.time()
        inject_bus_off(dev_if, 1.0)
        after: list[can.Message] = []
        t_end = time.monotonic() + 15.0
        while time.monotonic() < t_end and sum(m.arbitration_id == ID["DeviceStatus"] for m in after) < 5:
            m = bus.recv(0.5)
            if m is not None and m.timestamp > t_inject and m.arbitration_id not in (0x040, 0x100):
                after.append(m)  # (0x040, 0x100: the injected frames, on the bus as data frames)
    assert after, "nothing from the device after the bus-off"
    # the device's frames queued before it read the error frame come first; then the silence
    # while bus-off (1 s), and the first frame after it is the emergency frame
    times = [t_inject] + [m.timestamp for m in after]
    k = next((i for i, (a, b) in enumerate(itertools.pairwise(times)) if b - a > 0.5), None)
    assert k is not None, f"no silence while bus-off: {[hex(m.arbitration_id) for m in after[:20]]}"
    assert all(m.arbitration_id != ID["Emergency"] for m in after[:k])
    after = after[k:]
    first = after[0]
    assert first.arbitration_id == ID["Emergency"], [hex(m.arbitration_id) for m in after[:5]]
    emcy = DB.decode_message(first.arbitration_id, first.data, decode_choices=False)
    assert emcy["FaultCode"] == FAULT_BUS_OFF
    assert sum(m.arbitration_id == ID["Emergency"] for m in after) == 1
    status = [
        DB.decode_message(m.arbitration_id, m.data, decode_choices=False)
        for m in after
        if m.arbitration_id == ID["DeviceStatus"]
    ]
    assert status and all(st["FaultCode"] == FAULT_BUS_OFF for st in status)
    err = sja_server.stop()
    assert f"{dev_if} bus-off at" in err and f"{dev_if} back on the bus at" in err
    stop = err.strip().splitlines()[-1]
    assert "1 bus-off" in stop and "2 error frames" in stop, stop


# -- can-utils ---------------------------------------------------------------------------------


def can_utils_or_skip() -> None:
    for tool in ("candump", "cansniffer"):
        if shutil.which(tool) is None:
            pytest.skip(f"no {tool} (can-utils: scripts/vm.sh --setup installs it)")


@pytest.fixture(scope="module")
def vcan_server():
    iface = vcan_or_skip()
    s = SocketCANServer(SCENARIO, iface)
    time.sleep(0.5)
    yield s
    if s.proc.poll() is None:
        s.stop()


def _shift_to_equal(a: np.ndarray, b: np.ndarray, min_n: int) -> int | None:
    """The shift k (0, then +-1, +-2) with a[k + i] == b[i] over more than min_n samples of
    their overlap, or None."""
    for k in (0, 1, -1, 2, -2):
        x, y = (a[k:], b) if k >= 0 else (a, b[-k:])
        n = min(x.size, y.size)
        if n > min_n and np.array_equal(x[:n], y[:n]):
            return k
    return None


def test_candump_log_read_by_fit(vcan_server, tmp_path, capsys):
    """`candump -l` logs a recording; `forceskill fit` reads the log, the same demonstration as
    forceskill's own recording of it."""
    can_utils_or_skip()
    dump = subprocess.Popen(
        ["candump", "-l", vcan_server.iface],
        cwd=tmp_path,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
    )
    try:
        time.sleep(1.0)
        forceskill(
            capsys, "record", "-o", str(tmp_path / "own.blf"), "--duration", "5", *vcan_server.bus_args()
        )
        time.sleep(1.0)
    finally:
        dump.send_signal(signal.SIGINT)
        dump.wait(timeout=30)
    (log,) = tmp_path.glob("candump-*.log")
    out = forceskill(
        capsys,
        "fit",
        str(log),
        "--stiffness",
        str(PRESS_K_NPM),
        "--surface-m",
        str(PRESS_SURFACE_M),
        "-o",
        str(tmp_path / "from_candump.skill"),
    )
    t_s = float(out.split(f"{log.name}:f_contact, T = ")[1].split()[0])
    # 5 s: the operator holds the high force by then (at 3 s it is still ramping up to it, an end
    # the default fit does not reach within 10 %: 13.1 % at t = 3 s in the guest)
    assert 4.9 <= t_s <= 5.1 + RECORD_OVERRUN_S, out
    a, b = load_demo(log), load_demo(tmp_path / "own.blf")
    # the same samples; record's own log may begin a sample or two later than candump's (its loop
    # had not yet seen TEACH when the first frames of it went by)
    assert _shift_to_equal(a.force_N, b.force_N, 4900 // TELEMETRY_PERIOD_MS) is not None


def test_cansniffer_sees_the_device(vcan_server):
    """cansniffer lists the device's status identifier (it runs until interrupted)."""
    can_utils_or_skip()
    p = subprocess.Popen(
        ["cansniffer", "-c", vcan_server.iface],
        stdin=subprocess.DEVNULL,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
    )
    time.sleep(4.0)
    p.send_signal(signal.SIGINT)
    out, _ = p.communicate(timeout=30)
    text = out.decode(errors="replace")
    assert f"{ID['DeviceStatus']:03X}" in text.upper() or f"{ID['DeviceStatus']:03x}" in text


# -- CAN FD --------------------------------------------------------------------------------------


def fd_vcan_or_skip() -> str:
    iface = vcan_or_skip()
    mtu = int((sys_net(iface) / "mtu").read_text())
    if mtu != 72:
        pytest.skip(f"{iface} has MTU {mtu}, CAN FD needs 72 (ip link set {iface} mtu 72)")
    return iface


def test_fd_refused_on_a_classic_interface():
    """--fd on an interface with the classic MTU: one line, exit 1."""
    iface = vcan_or_skip()
    if os.geteuid() != 0:
        pytest.skip("adding a classic vcan needs root")
    name = "vcanc7"
    subprocess.run(["ip", "link", "add", "dev", name, "type", "vcan"], capture_output=True, timeout=30)
    try:
        ip("link", "set", name, "mtu", "16")
        ip("link", "set", name, "up")
        p = subprocess.run(
            [str(hil_sim_path()), "serve", "--socketcan", name, "--fd", "--duration", "1"],
            capture_output=True,
            text=True,
            timeout=60,
        )
    finally:
        subprocess.run(["ip", "link", "del", name], capture_output=True, timeout=30)
    assert iface  # the FD interface itself is untouched
    assert p.returncode == 1
    (line,) = p.stderr.strip().splitlines()
    assert "not CAN FD capable (MTU 16" in line


def test_fd_upload_in_64_byte_frames(capsys, figure):
    """A skill uploaded with --fd: verified by read-back, the device's UDS responses in 64-byte
    FD frames with BRS, the host's requests too; status reads the slot. Its time is printed
    among pytest's figures."""
    iface = fd_vcan_or_skip()
    skill = REPO / "tests" / "vectors" / "press_n50_ridge_release.skill"  # the N = 50 skill
    s = SocketCANServer(SCENARIO, iface, extra=("--fd",))
    seen: list[can.Message] = []
    try:
        assert "(CAN FD)" in s.first_line
        with can.Bus(interface="socketcan", channel=iface, fd=True) as mon:
            notifier = can.Notifier(mon, [seen.append], timeout=0.1)
            try:
                from forceskill import cli

                rc = cli.main(["upload", str(skill), "--slot", "2", "-q", *s.bus_args(), "--fd"])
                out, log = capsys.readouterr()
                if rc != 0:
                    kinds = sorted({(hex(m.arbitration_id), m.is_fd, len(m.data)) for m in seen})
                    pytest.fail(
                        f"upload --fd failed: {log.strip()}; frames seen {kinds[:12]}; {s.stop().strip()}"
                    )
                status = forceskill(capsys, "status", *s.bus_args(), "--fd")
            finally:
                notifier.stop()
    finally:
        err = s.stop() if s.proc.poll() is None else ""
    assert "verified by read-back" in out
    assert f"slot 2: {skill.stat().st_size} bytes" in status
    resp = [m for m in seen if m.arbitration_id == UDS_RESPONSE_BASE]
    req = [m for m in seen if m.arbitration_id == UDS_REQUEST_BASE]
    assert resp and req
    assert all(m.is_fd and m.bitrate_switch for m in resp + req)
    assert max(len(m.data) for m in req) == 64  # the skill's TransferData in 64-byte frames
    stop = err.strip().splitlines()[-1]
    assert "FD)" in stop
    (line,) = [ln for ln in out.splitlines() if "verified by read-back" in ln]
    figure(
        f"CAN FD upload on {iface} (64-byte BRS frames, {len(req)} frames from the host, {len(resp)} from the device): {line}"
    )

"""`forceskill flash` over python-can + can-isotp + udsoncan against the real firmware update path.

The device is firmware code (tests/boot/uds_device.c: UDS server firmware/proto/uds.c, SecurityAccess,
fwu_/boot_ through the fwu_uds binding, RAM flash with power-loss injection) built as a shared
library and served on a python-can virtual bus by can-isotp. The host side is the product's own
`forceskill flash` command and its udsoncan client. The socketcand/HIL variant needs the
simulator's UDS server to route to fwu_uds (docs/update.md, "Integration").
"""

from __future__ import annotations

import argparse
import ctypes
import itertools
import subprocess
import threading
import time
from pathlib import Path

import can
import isotp
import pytest

from forceskill import cli
from forceskill.errors import FsError
from forceskill.link import flash as fl
from forceskill.model import fwimage as fw

ROOT = Path(__file__).resolve().parents[2]
FW = ROOT / "firmware"
SECRET = bytes(range(0xA0, 0xC0))
SOURCES = [
    "proto/uds.c",
    "proto/generated/fs_wire.c",
    "boot/fwu_uds.c",
    "boot/fwu.c",
    "boot/boot.c",
    "boot/boot_image.c",
    "boot/boot_verify.c",
    "boot/boot_fls_window.c",
    "security/sec_sha256.c",
    "security/sec_access.c",
    "storage/nvm.c",
    "storage/fls_ram.c",
]
_channels = itertools.count()


@pytest.fixture(scope="module")
def lib(tmp_path_factory) -> ctypes.CDLL:
    out = tmp_path_factory.mktemp("fsdev") / "libfsdev.so"
    inc = [f"-I{FW / d}" for d in ("base", "boot", "proto", "proto/generated", "security", "storage")]
    subprocess.run(
        [
            "cc",
            "-std=c11",
            "-O1",
            "-shared",
            "-fPIC",
            "-Wall",
            "-Wextra",
            "-Werror",
            *inc,
            str(Path(__file__).parent / "uds_device.c"),
            *[str(FW / s) for s in SOURCES],
            "-o",
            str(out),
        ],
        check=True,
    )
    so = ctypes.CDLL(str(out))
    so.dev_handle.restype = ctypes.c_uint16
    so.dev_handle.argtypes = [
        ctypes.c_char_p,
        ctypes.c_uint16,
        ctypes.c_char_p,
        ctypes.c_uint16,
        ctypes.c_uint32,
    ]
    so.dev_running_version.restype = ctypes.c_uint32
    return so


class Device:
    """Serves the library's UDS server on a virtual CAN channel through can-isotp."""

    def __init__(self, so: ctypes.CDLL, channel: str) -> None:
        self.so = so
        self.bus = can.Bus(interface="virtual", channel=channel)
        self.notifier = can.Notifier(self.bus, [], timeout=0.1)
        addr = isotp.Address(
            isotp.AddressingMode.Normal_11bits, txid=fl.UDS_RESPONSE_BASE, rxid=fl.UDS_REQUEST_BASE
        )
        self.stack = isotp.NotifierBasedCanStack(
            self.bus,
            self.notifier,
            address=addr,
            params={
                "tx_padding": 0xCC,
                "max_frame_size": 4095,
                "blocking_send": False,
                "stmin": 0,
                "blocksize": 0,
            },
        )
        self.stop = threading.Event()
        self.t0 = time.monotonic()
        self.thread = threading.Thread(target=self._run, daemon=True)

    def _run(self) -> None:
        resp = ctypes.create_string_buffer(4095)
        while not self.stop.is_set():
            req = self.stack.recv(block=True, timeout=0.05)
            if not req:
                continue
            now = int((time.monotonic() - self.t0) * 1000)
            n = self.so.dev_handle(bytes(req), len(req), resp, 4095, now)
            if n:
                self.stack.send(resp.raw[:n])
            self.so.dev_after_response()

    def __enter__(self) -> Device:
        self.stack.start()
        self.thread.start()
        return self

    def __exit__(self, *exc) -> None:
        self.stop.set()
        self.thread.join(2)
        self.stack.stop()
        self.notifier.stop()
        self.bus.shutdown()


def image(version: str, n: int = 20000, key: bytes = fw.DEV_KEY, target: str = "host") -> bytes:
    payload = bytes((i * 13 + n) & 0xFF for i in range(n))
    return fw.build_image(payload, version, target, key, build_id=f"host-{version}")


@pytest.fixture
def device(lib, tmp_path):
    assert lib.dev_create(SECRET, len(SECRET)) == 0
    assert lib.dev_factory(image("1.0.0"), len(image("1.0.0"))) == 0
    assert lib.dev_running_version() == fw.pack_version("1.0.0")
    channel = f"fwu{next(_channels)}"
    with Device(lib, channel) as d:
        d.channel = channel
        yield d


def secret_file(tmp_path: Path) -> str:
    p = tmp_path / "secret.hex"
    p.write_text(SECRET.hex())
    return str(p)


def run_cli(tmp_path, device, img: bytes, *extra: str) -> int:
    f = tmp_path / "fw.fwimg"
    f.write_bytes(img)
    return cli.main(
        [
            "flash",
            str(f),
            "-i",
            "virtual",
            "-c",
            device.channel,
            "--secret",
            secret_file(tmp_path),
            "-q",
            "--confirm-timeout",
            "5",
            *extra,
        ]
    )


def link_args(device) -> argparse.Namespace:
    return argparse.Namespace(interface="virtual", channel=device.channel, node=0, timeout=2.0)


def test_full_update_over_udsoncan(lib, device, tmp_path, capsys):
    assert run_cli(tmp_path, device, image("1.1.0")) == 0
    out = capsys.readouterr().out
    assert "image:  firmware 1.1.0 for host" in out
    assert "device: firmware 1.0.0 on host, slot A, first boot" in out
    assert "written and verified by the device: 20160 bytes in 5 blocks" in out
    assert "after reset: device: firmware 1.1.0 on host, slot B" in out and "confirmed" in out
    assert lib.dev_running_version() == fw.pack_version("1.1.0")
    assert lib.dev_running_slot() == 1
    # and the next one goes to slot A
    assert run_cli(tmp_path, device, image("1.2.0", n=9000)) == 0
    assert lib.dev_running_slot() == 0 and lib.dev_running_version() == fw.pack_version("1.2.0")


def test_revert_when_the_new_image_fails_its_self_test(lib, device, tmp_path, capsys):
    lib.dev_set_selftest(0)
    assert run_cli(tmp_path, device, image("1.1.0")) == 2
    err = capsys.readouterr().err
    assert "device reverted to 1.0.0: the new image 1.1.0 did not confirm itself" in err, err
    assert "[638]" in err
    assert lib.dev_running_version() == fw.pack_version("1.0.0")
    assert lib.dev_path() == 3  # BOOT_PATH_REVERTED


def _flip_byte(b: bytes, i: int) -> bytes:
    """b with bit 0 of byte i flipped."""
    return b[:i] + bytes([b[i] ^ 1]) + b[i + 1 :]


@pytest.mark.parametrize(
    "name, img, nrc, code",
    [
        ("wrong tag", lambda: image("1.1.0", key=bytes(32)), 0xF4, fw.ERR_TAG),
        ("wrong target", lambda: image("1.1.0", target="cortex-m3"), 0xF1, fw.ERR_TARGET),
        ("truncated", lambda: image("1.1.0")[:-500], 0xF2, fw.ERR_TRUNCATED),
        (
            "corrupted",
            lambda: _flip_byte(image("1.1.0"), 5000),
            0xF3,
            fw.ERR_HASH,
        ),
        ("downgrade", lambda: image("0.9.0"), 0xF5, fw.ERR_DOWNGRADE),
    ],
)
def test_each_refusal_has_its_own_nrc(lib, device, name, img, nrc, code):
    # straight to the device (the CLI would refuse target and downgrade before writing)
    with fl.Link(link_args(device), SECRET) as client:
        with pytest.raises(FsError) as e:
            fl.flash_image(client, img())
        assert f"NRC 0x{nrc:02X}" in str(e.value), str(e.value)
        assert e.value.code == code
        st = fl.read_status(client)
        assert st.running_version == fw.pack_version("1.0.0") and not st.on_test
        assert st.test_slot == 0xFF  # nothing marked for a test boot
    lib.dev_power_cycle()
    assert lib.dev_running_version() == fw.pack_version("1.0.0")


def test_downgrade_with_the_flag(lib, device, tmp_path, capsys):
    assert run_cli(tmp_path, device, image("0.9.0")) == 2
    assert "older than the running 1.0.0: refused (use --allow-downgrade) [707]" in capsys.readouterr().err
    assert run_cli(tmp_path, device, image("0.9.0"), "--allow-downgrade") == 0
    assert lib.dev_running_version() == fw.pack_version("0.9.0")


def test_locked_device_refuses(lib, device):
    with fl.Link(link_args(device), bytes(32)) as client:  # wrong secret: SecurityAccess fails
        with pytest.raises(FsError) as e:
            fl.flash_image(client, image("1.1.0"))
        assert "SecurityAccess" in str(e.value) and "NRC 0x35" in str(e.value)


def test_dry_run_reads_the_device_and_writes_nothing(lib, device, tmp_path, capsys):
    f = tmp_path / "fw.fwimg"
    f.write_bytes(image("1.1.0"))
    assert cli.main(["flash", str(f), "-i", "virtual", "-c", device.channel, "--dry-run"]) == 0
    out = capsys.readouterr().out
    assert "device: firmware 1.0.0 on host, slot A" in out
    assert "dry run: would write 20160 bytes into slot B; nothing written" in out
    with fl.Link(link_args(device), None) as client:
        st = fl.read_status(client)
    assert st.phase == 0 and st.received_version == 0


def test_power_loss_during_flash_then_retry(lib, device, tmp_path, capsys):
    lib.dev_power_loss_at(4)  # a few sectors into the download
    assert run_cli(tmp_path, device, image("1.1.0")) == 2
    assert "NRC 0x72" in capsys.readouterr().err
    lib.dev_power_cycle()
    assert lib.dev_running_version() == fw.pack_version("1.0.0")
    assert run_cli(tmp_path, device, image("1.1.0")) == 0
    assert lib.dev_running_version() == fw.pack_version("1.1.0")


def test_absent_device_and_bad_interface_are_one_line_errors(tmp_path, capsys):
    f = tmp_path / "fw.fwimg"
    f.write_bytes(image("1.1.0"))
    assert (
        cli.main(["flash", str(f), "-i", "virtual", "-c", "nobody-here", "--dry-run", "--timeout", "0.2"])
        == 2
    )
    err = capsys.readouterr().err
    assert err.strip() == "forceskill: error: no response from node 0 on nobody-here (virtual) [631]", err
    with pytest.raises(SystemExit) as e:  # python-can's own option parsing names it
        cli.main(["flash", str(f), "-i", "no-such-interface", "--dry-run"])
    assert e.value.code == 2
    err = capsys.readouterr().err
    assert err.startswith("forceskill: error: argument -i/--interface: invalid choice: 'no-such-interface'")
    assert len(err.strip().splitlines()) == 1

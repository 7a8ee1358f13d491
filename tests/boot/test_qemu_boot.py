"""The Cortex-M bootloader under qemu-system-arm (mps2-an385 Cortex-M3 and mps2-an386 Cortex-M4F,
semihosting).

Builds firmware/ports/mps2/boot with arm-none-eabi-gcc, wraps the test application into signed
images with the host tool (forceskill.model.fwimage), loads bootloader + slot images (+ an optional
boot-state record) into qemu's code memory and checks what the bootloader starts or refuses.
Layout: firmware/ports/mps2/boot/qemu_layout.h.
"""

from __future__ import annotations

import shutil
import struct
import subprocess
import zlib
from pathlib import Path

import pytest

from forceskill.model import fwimage as fw

ROOT = Path(__file__).resolve().parents[2]
SRC = ROOT / "firmware" / "ports" / "mps2" / "boot"
SLOT_A, SLOT_B, STATE = 0x20000, 0x60000, 0x10000
ENTRY_OFFSET = 0x180
OTHER_KEY = bytes(range(32))


def _cross_args(target: str) -> list[str]:
    tc = ROOT / "cmake" / "arm-none-eabi.cmake"
    if tc.exists():
        return [f"-DCMAKE_TOOLCHAIN_FILE={tc}", f"-DFS_CORTEX_TARGET={target}"]
    # the shared toolchain file not there: the same settings on the command line
    return [
        "-DCMAKE_SYSTEM_NAME=Generic",
        "-DCMAKE_SYSTEM_PROCESSOR=arm",
        f"-DFS_CORTEX_TARGET={target}",
        "-DCMAKE_C_COMPILER=arm-none-eabi-gcc",
        "-DCMAKE_TRY_COMPILE_TARGET_TYPE=STATIC_LIBRARY",
    ]


class Build:
    """Bootloader + test application built for one target, and the qemu machine to run it."""

    def __init__(self, out: Path, target: str, machine: str, other: str) -> None:
        self.out, self.target, self.machine, self.other_target = out, target, machine, other

    def __truediv__(self, name: str) -> Path:
        return self.out / name


# Cortex-M3 on mps2-an385 (the fixed-point target) and Cortex-M4F on mps2-an386
@pytest.fixture(
    scope="module",
    params=[("cortex-m3", "mps2-an385", "cortex-m4f"), ("cortex-m4f", "mps2-an386", "cortex-m3")],
    ids=["cortex-m3", "cortex-m4f"],
)
def build(request, tmp_path_factory) -> Build:
    target, machine, other = request.param
    for tool in ("arm-none-eabi-gcc", "qemu-system-arm", "cmake", "ninja"):
        assert shutil.which(tool), f"{tool} not installed (scripts/setup.sh installs it)"
    out = tmp_path_factory.mktemp(f"boot-qemu-{target}")
    subprocess.run(
        ["cmake", "-S", str(SRC), "-B", str(out), "-G", "Ninja", *_cross_args(target)],
        check=True,
        capture_output=True,
    )
    subprocess.run(["ninja", "-C", str(out), "-j2"], check=True, capture_output=True)
    return Build(out, target, machine, other)


def app_image(
    build: Build, slot: str, version: str, key: bytes = fw.DEV_KEY, target: str | None = None
) -> bytes:
    payload = (build / f"fs_test_app_{slot}.bin").read_bytes()
    return fw.build_image(
        payload,
        version,
        target or build.target,
        key,
        build_id=f"qemu-{slot}-{version}",
        entry_offset=ENTRY_OFFSET,
    )


def state_record(
    active: int, test: int = 0xFF, attempts: int = 0, flags: int = 0, active_version: int = 0
) -> bytes:
    """Boot state as firmware/storage/nvm.h stores it (record 0, seq 1, write unit 4),
    written independently of the C code from the documented layouts."""
    payload = bytes([1, active, test, attempts, 1, flags, 0, 0]) + struct.pack("<II", active_version, 0)
    head = struct.pack("<IHHII", 0x524D564E, 1, 0, 1, len(payload))
    crc = zlib.crc32(head + payload)
    return head + struct.pack("<I", crc) + b"\xff" * 12 + payload + struct.pack("<I", 0x00C0FFEE)


def run_qemu(
    build: Build,
    tmp_path: Path,
    slot_a: bytes | None = None,
    slot_b: bytes | None = None,
    state: bytes | None = None,
) -> tuple[int, str]:
    cmd = [
        "qemu-system-arm",
        "-M",
        build.machine,
        "-nographic",
        "-monitor",
        "none",
        "-serial",
        "none",
        "-semihosting-config",
        "enable=on,target=native",
        "-kernel",
        str(build / "fs_bootloader.elf"),
    ]
    for name, data, addr in (("a", slot_a, SLOT_A), ("b", slot_b, SLOT_B), ("state", state, STATE)):
        if data is not None:
            f = tmp_path / f"{name}.bin"
            f.write_bytes(data)
            cmd += ["-device", f"loader,file={f},addr={addr:#x},force-raw=on"]
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=60)
    return p.returncode, p.stdout + p.stderr


def test_bootloader_starts_a_valid_image(build, tmp_path):
    rc, out = run_qemu(build, tmp_path, slot_a=app_image(build, "a", "1.4.0"))
    assert "boot: slot A: version 1.4.0 build 'qemu-a-1.4.0' verified" in out, out
    assert "boot: starting slot A, version 1.4.0" in out, out
    assert (
        "app: forceskill test application running from slot A, vector table 0x00020200, version 1.4.0" in out
    ), out
    assert rc == 0, out


def test_bootloader_refuses_a_tampered_image(build, tmp_path):
    img = bytearray(app_image(build, "a", "1.4.0"))
    img[fw.HEADER_SIZE + 0x300] ^= 0x01  # one bit of the code
    rc, out = run_qemu(build, tmp_path, slot_a=bytes(img))
    assert "boot: slot A: refused: payload SHA-256 mismatch (705)" in out, out
    assert "boot: no bootable image: staying in the bootloader" in out, out
    assert "app:" not in out, out
    assert rc == 3, out


def test_bootloader_refuses_an_image_signed_with_another_key(build, tmp_path):
    # consistent hash, tag from another key: only the device key makes an image authorised
    rc, out = run_qemu(build, tmp_path, slot_a=app_image(build, "a", "1.4.0", key=OTHER_KEY))
    assert "boot: slot A: refused: authentication tag wrong (706)" in out, out
    assert "app:" not in out and rc == 3, out


def test_bootloader_refuses_an_image_for_another_target(build, tmp_path):
    rc, out = run_qemu(build, tmp_path, slot_a=app_image(build, "a", "1.4.0", target=build.other_target))
    assert "boot: slot A: refused: wrong target (703)" in out, out
    assert "app:" not in out and rc == 3, out


def test_tampered_slot_a_falls_back_to_slot_b(build, tmp_path):
    img = bytearray(app_image(build, "a", "1.4.0"))
    img[-1] ^= 0x80  # the tag itself
    rc, out = run_qemu(build, tmp_path, slot_a=bytes(img), slot_b=app_image(build, "b", "1.3.0"))
    assert "boot: slot A: refused: authentication tag wrong (706)" in out, out
    assert "boot: starting slot B, version 1.3.0" in out, out
    assert "running from slot B, vector table 0x00060200" in out, out
    assert rc == 0, out


def test_test_image_boots_once_and_confirms(build, tmp_path):
    state = state_record(active=0, test=1, attempts=0, active_version=0x01040000)
    rc, out = run_qemu(
        build,
        tmp_path,
        slot_a=app_image(build, "a", "1.4.0"),
        slot_b=app_image(build, "b", "1.5.0"),
        state=state,
    )
    assert "boot: starting slot B, version 1.5.0, path test (first boot, must confirm)" in out, out
    assert "test boot confirmed: this image is now the active one" in out, out
    assert rc == 0, out


def test_unconfirmed_test_image_is_reverted(build, tmp_path):
    # the test image was started once (attempts = 1) and never confirmed: back to slot A
    state = state_record(active=0, test=1, attempts=1, active_version=0x01040000)
    rc, out = run_qemu(
        build,
        tmp_path,
        slot_a=app_image(build, "a", "1.4.0"),
        slot_b=app_image(build, "b", "1.5.0"),
        state=state,
    )
    assert "boot: starting slot A, version 1.4.0, path reverted (test image did not confirm)" in out, out
    assert "already the active image" in out, out
    assert rc == 0, out


@pytest.mark.parametrize(
    "flags, started",
    [(0, "A, version 1.4.0, path active (test image refused)"), (1, "B, version 1.2.0, path test")],
)
def test_downgrade_needs_the_flag(build, tmp_path, flags, started):
    state = state_record(active=0, test=1, attempts=0, flags=flags, active_version=0x01040000)
    rc, out = run_qemu(
        build,
        tmp_path,
        slot_a=app_image(build, "a", "1.4.0"),
        slot_b=app_image(build, "b", "1.2.0"),
        state=state,
    )
    assert f"boot: starting slot {started}" in out, out
    assert rc == 0, out

"""The firmware update path over UDS (docs/update.md), used by ``forceskill flash``.

Read the device's update status (DID 0xF1B0), show image and device version and target,
refuse a wrong target or a downgrade here already (the device refuses them too), then over
udsoncan + can-isotp: programming session, SecurityAccess level 3, RequestDownload at
0xF0000000 (the inactive slot), TransferData with a progress bar, RequestTransferExit (device
checks hash and tag; its CRC-32 is compared with ours), RoutineControl 0x0F01 (mark for a test
boot; option bit 0 = allow downgrade), ECUReset, then read back the running version until the
new image has confirmed itself (or the device reports it reverted).
"""

from __future__ import annotations

import argparse
import time
import zlib
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from .. import wire as W
from ..codes import DID_FWU_STATUS as DID_STATUS
from ..codes import (  # noqa: F401
    DOWNLOAD_ADDRESS,
    RID_CONFIRM,
    RID_MARK_TEST,
    SEC_LEVEL_FIRMWARE,
    UDS_REQUEST_BASE,
    UDS_RESPONSE_BASE,
)
from ..errors import ERR_FLASH_NOT_CONFIRMED as ERR_NOT_CONFIRMED
from ..errors import ERR_IO, ERR_LINK_BUS, ERR_LINK_NEGATIVE, ERR_LINK_NO_RESPONSE, ERR_LINK_TIMEOUT, FsError  # noqa: F401
from ..model import fwimage as fw

STATUS_LEN = W.FwuStatus.SIZE
SESSION_PROGRAMMING = 0x02
FWU_OPT_ALLOW_DOWNGRADE = 0x01  # the mark-test option (firmware/boot/fwu.h)
PENDING_TIMEOUT_S = 5.0  # after "response pending" (NRC 0x78): erasing a slot takes a while

PATHS = {
    0: "none",
    1: "active",
    2: "test boot (must confirm)",
    3: "reverted (test image did not confirm)",
    4: "active (test image refused)",
    5: "recovered (other slot)",
    6: "first boot",
}
PHASES = {0: "idle", 1: "receiving", 2: "received", 3: "marked for test"}


@dataclass
class DeviceStatus:
    """Decoded DID 0xF1B0 (firmware/boot/fwu.h, fwu_status)."""

    running_version: int
    running_slot: int
    on_test: bool
    active_slot: int
    test_slot: int
    path: int
    target_id: int
    last_refusal: int
    received_version: int
    phase: int

    @classmethod
    def decode(cls, b: bytes) -> DeviceStatus:
        """From the DID's record (wire.toml fwu_status); FsError 668/669 for a malformed one."""
        s = W.FwuStatus.unpack(b)
        return cls(
            s.running_version,
            s.running_slot,
            bool(s.on_test),
            s.active_slot,
            s.test_slot,
            s.path,
            s.target,
            s.last_refusal,
            s.received_version,
            s.phase,
        )

    @property
    def version(self) -> str:
        return fw.unpack_version(self.running_version)

    @property
    def target(self) -> str:
        return fw.TARGET_NAMES.get(self.target_id, f"unknown({self.target_id})")

    def describe(self) -> str:
        slot = "AB"[self.running_slot] if self.running_slot < 2 else "-"
        path = PATHS.get(self.path, str(self.path))
        if self.path == 2 and not self.on_test:
            path = "test boot, confirmed"
        s = f"device: firmware {self.version} on {self.target}, slot {slot}, {path}"
        if self.last_refusal:
            s += f", last refusal {self.last_refusal}"
        return s


def nrc_error(code: int, step: str) -> FsError:
    """The FsError for a negative response code of the update path."""
    err, text = fw.NRC.get(code, (ERR_LINK_NEGATIVE, f"negative response 0x{code:02X}"))
    return FsError(err, f"{step}: device refused (NRC 0x{code:02X}): {text}")


def load_secret(path: str | None) -> bytes:
    """Level-3 (firmware) SecurityAccess secret: hex text from PATH, else
    link.uds.device_secret(3) ($FORCESKILL_FW_SECRET, or the simulator's documented secret)."""
    if not path:
        from .uds import SEC_LEVEL_FIRMWARE, device_secret

        return device_secret(SEC_LEVEL_FIRMWARE)
    try:
        text = Path(path).read_text()
    except OSError as e:
        raise FsError(fw.ERR_KEY, f"secret file {path}: {e.strerror}") from None
    try:
        secret = bytes.fromhex("".join(text.split()))
    except ValueError:
        raise FsError(fw.ERR_KEY, f"secret file {path} is not hex") from None
    if not 16 <= len(secret) <= 64:
        raise FsError(fw.ERR_KEY, f"device secret is {len(secret)} bytes, need 16..64")
    return secret


def check_plan(
    img: fw.FwImage,
    dev: DeviceStatus | None,
    allow_downgrade: bool,
    stored_skills: tuple[int, int] | None = None,
) -> list[str]:
    """Lines shown before writing; raises FsError for what the device would refuse anyway:
    another target, a downgrade, an image on test, and skill formats ``stored_skills`` (the
    range the device declares for its stored skills) outside the image's [oldest, native]."""
    lines = [
        f"image:  firmware {img.version} for {img.target}, build '{img.build_id or '-'}', "
        f"{len(img.to_bytes())} bytes"
    ]
    if dev is None:
        return lines
    lines.append(dev.describe())
    if dev.on_test:
        raise FsError(
            fw.ERR_TEST_PENDING,
            f"device runs {dev.version} on test (not confirmed yet): "
            "wait for it to confirm or reset it, then flash again",
        )
    if dev.target_id != img.target_id:
        raise FsError(fw.ERR_TARGET, f"image is for {img.target}, device is {dev.target}")
    if img.fw_version < dev.running_version:
        if not allow_downgrade:
            raise FsError(
                fw.ERR_DOWNGRADE,
                f"image {img.version} is older than the running "
                f"{dev.version}: refused (use --allow-downgrade)",
            )
        lines.append(f"downgrade {dev.version} -> {img.version} allowed by --allow-downgrade")
    if stored_skills is not None:
        lo, hi = stored_skills
        if not (img.skill_format_oldest <= lo and hi <= img.skill_format):
            raise FsError(
                fw.ERR_SKILL_FORMAT,
                f"image {img.version} reads skill formats {img.skill_format_oldest}..{img.skill_format} "
                f"but the device stores skills of formats {lo}..{hi} (it would refuse the image, 708): "
                f"build it with --skill-format {max(hi, img.skill_format)}:{min(lo, img.skill_format_oldest)}; "
                "nothing written",
            )
    return lines


def status_codecs() -> dict[int, Any]:
    """The data identifier the update path reads: DID 0xF1B0 (read-only), decoded."""
    import udsoncan

    class StatusCodec(udsoncan.DidCodec):
        """DID 0xF1B0, read-only."""

        def decode(self, payload: bytes) -> DeviceStatus:
            return DeviceStatus.decode(payload)

        def __len__(self) -> int:
            return STATUS_LEN

    from .uds import DID_CODECS, DID_SLOT_DIR

    return {DID_STATUS: StatusCodec(), DID_SLOT_DIR: DID_CODECS[DID_SLOT_DIR]}


def stored_skill_formats(client: Any) -> tuple[int, int] | None:
    """The skill formats the device's bootloader checks an image against: the product's range
    (fwimage.SKILL_FORMAT_OLDEST .. SKILL_FORMAT) while any slot holds a skill (the firmware
    declares that range for its stored skills), None with every slot empty or no skill store."""
    from udsoncan.exceptions import NegativeResponseException

    from .. import wire as W
    from .uds import DID_SLOT_DIR

    try:
        r = client.read_data_by_identifier(DID_SLOT_DIR)
    except NegativeResponseException:  # a device without a skill store (a boot-only image)
        return None
    d = W.SlotDir.unpack(bytes(r.service_data.values[DID_SLOT_DIR]))
    if not any(e.valid for e in d.entries):
        return None
    return fw.SKILL_FORMAT_OLDEST, fw.SKILL_FORMAT


def read_status(client: Any) -> DeviceStatus:
    resp = client.read_data_by_identifier(DID_STATUS)
    status: DeviceStatus = resp.service_data.values[DID_STATUS]
    return status


def _refused(step: str, e: Any) -> FsError:
    """The update path's refusal policy for link.uds.call: each NRC its own code."""
    return nrc_error(int(e.response.code), step)


def request(step: str, fn: Callable[..., Any], *a: Any, node: int = 0) -> Any:
    """Run one UDS request (link.uds.call); negative responses and timeouts become FsError."""
    from .uds import call

    return call(step, lambda: fn(*a), node, _refused)


def flash_image(
    client: Any,
    image: bytes,
    allow_downgrade: bool = False,
    progress: Callable[[int], None] | None = None,
    block_size: int = 0,
    node: int = 0,
    mark_test: bool = True,
) -> int:
    """Write image into the inactive slot of node and (mark_test) mark it for a test boot; returns
    the blocks sent. The caller then resets the device (ECUReset) and reads the status back."""
    from udsoncan import MemoryLocation

    from .uds import unlock

    # through the default session: ends any transfer a previous, interrupted run left open
    request("DiagnosticSessionControl(default)", client.change_session, 0x01, node=node)
    request("DiagnosticSessionControl(programming)", client.change_session, SESSION_PROGRAMMING, node=node)
    # SecurityAccess level 3, waiting out the device's delay (NRC 0x37: the 1 s after power-up,
    # e.g. right after a previous update's reset, or after a wrong key)
    unlock(client, node, None, SEC_LEVEL_FIRMWARE, _refused)
    resp = request(
        "RequestDownload",
        client.request_download,
        MemoryLocation(DOWNLOAD_ADDRESS, len(image), 32, 32),
        node=node,
    )
    block = int(resp.service_data.max_length) - 2
    if block_size > 0:
        block = min(block, block_size)
    if block < 1:
        raise FsError(ERR_LINK_NEGATIVE, f"device announced a block length of {block + 2}")
    seq, n_blocks = 1, 0
    for off in range(0, len(image), block):
        chunk = image[off : off + block]
        request(
            f"TransferData(block {n_blocks + 1}, offset {off})", client.transfer_data, seq, chunk, node=node
        )
        seq = (seq + 1) & 0xFF
        n_blocks += 1
        if progress:
            progress(len(chunk))
    # the device verifies the image (hash and tag) in slices, answering "response pending"
    # (0x78) meanwhile: wait as long as it keeps saying so (each wait bounded by P2*)
    overall = client.config["request_timeout"]
    client.set_config("request_timeout", None)
    try:
        resp = request("RequestTransferExit", client.request_transfer_exit, node=node)
    finally:
        client.set_config("request_timeout", overall)
    rec = bytes(resp.service_data.parameter_records or b"")
    if rec:
        crc = W.TransferExit.unpack(rec).crc32
        if crc != zlib.crc32(image):
            raise FsError(
                ERR_LINK_NEGATIVE,
                f"device CRC-32 0x{crc:08X} differs from the image's 0x{zlib.crc32(image):08X}",
            )
    if not mark_test:
        return n_blocks
    request(
        "RoutineControl(mark test)",
        client.start_routine,
        RID_MARK_TEST,
        W.MarkTest(FWU_OPT_ALLOW_DOWNGRADE if allow_downgrade else 0).pack(),
        node=node,
    )
    return n_blocks


def wait_confirmed(client: Any, version: int, timeout_s: float) -> DeviceStatus:
    """After ECUReset: poll the status until the new image runs and has confirmed itself."""
    from udsoncan.exceptions import NegativeResponseException, TimeoutException

    deadline = time.monotonic() + timeout_s
    last: DeviceStatus | None = None
    while time.monotonic() < deadline:
        try:
            last = read_status(client)
        except (TimeoutException, NegativeResponseException):
            time.sleep(0.05)
            continue
        if last.running_version == version and not last.on_test:
            return last
        if last.running_version != version and last.path in (3, 4):
            raise FsError(
                ERR_NOT_CONFIRMED,
                f"device reverted to {last.version}: the new image "
                f"{fw.unpack_version(version)} did not confirm itself ({PATHS[last.path]})",
            )
        time.sleep(0.05)
    got = last.describe() if last else "no status"
    raise FsError(ERR_NOT_CONFIRMED, f"new image not confirmed within {timeout_s:g} s ({got})")


class Link:
    """Bus (link.bus.open_bus: python-can options, one-line errors) + the link.uds client for one
    node, with the update path's data identifier and 32-bit addresses; a context manager yielding
    the client. secret None: no SecurityAccess expected (the default secret is used if asked)."""

    def __init__(self, args: argparse.Namespace, secret: bytes | None) -> None:
        import can

        from .bus import describe, open_bus
        from .uds import open_client

        self.bus, cfg = open_bus(args)
        self.channel = describe(cfg)
        self.node = args.node
        self.notifier = can.Notifier(self.bus, [], timeout=0.1)
        self.client = open_client(
            self.bus,
            self.notifier,
            args.node,
            secret=secret,
            dids=status_codecs(),
            timeout_s=args.timeout,
            pending_timeout_s=PENDING_TIMEOUT_S,
            address_format=32,
            memorysize_format=32,
            fd=bool(cfg.get("fd")),
        )

    def __enter__(self) -> Any:
        self.client.open()
        return self.client

    def __exit__(self, *exc: Any) -> None:
        try:
            self.client.close()
        finally:
            self.notifier.stop()
            self.bus.shutdown()

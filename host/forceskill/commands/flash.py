"""``forceskill flash IMAGE`` and ``forceskill image build|show`` (docs/update.md).

Flash: read the device's update status (DID 0xF1B0), show image and device version and target,
refuse a wrong target or a downgrade here already (the device refuses them too), then over
udsoncan + can-isotp: programming session, SecurityAccess level 3, RequestDownload at
0xF0000000 (the inactive slot), TransferData with a progress bar, RequestTransferExit (device
checks hash and tag; its CRC-32 is compared with ours), RoutineControl 0x0F01 (mark for a test
boot; option bit 0 = allow downgrade), ECUReset, then read back the running version until the
new image has confirmed itself (or the device reports it reverted).
"""

from __future__ import annotations

import argparse
import os
import struct
import sys
import time
import zlib
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

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

STATUS_LEN = 17
SESSION_PROGRAMMING = 0x02
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
        if len(b) < STATUS_LEN:
            raise FsError(ERR_LINK_NEGATIVE, f"update status record is {len(b)} bytes, expected {STATUS_LEN}")
        rv, rs, ot, a, t, p, tg, lr, recv, ph = struct.unpack(">IBBBBBBHIB", b[:STATUS_LEN])
        return cls(rv, rs, bool(ot), a, t, p, tg, lr, recv, ph)

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
        from ..link.uds import SEC_LEVEL_FIRMWARE, device_secret

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


def check_plan(img: fw.FwImage, dev: DeviceStatus | None, allow_downgrade: bool) -> list[str]:
    """Lines shown before writing; raises FsError for what the device would refuse anyway."""
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

    return {DID_STATUS: StatusCodec()}


def read_status(client: Any) -> DeviceStatus:
    resp = client.read_data_by_identifier(DID_STATUS)
    status: DeviceStatus = resp.service_data.values[DID_STATUS]
    return status


def _refused(step: str, e: Any) -> FsError:
    """The update path's refusal policy for link.uds.call: each NRC its own code."""
    return nrc_error(int(e.response.code), step)


def _call(step: str, fn: Callable[..., Any], *a: Any, node: int = 0) -> Any:
    """Run one UDS request (link.uds.call); negative responses and timeouts become FsError."""
    from ..link.uds import call

    return call(step, lambda: fn(*a), node, _refused)


def flash_image(
    client: Any,
    image: bytes,
    allow_downgrade: bool = False,
    progress: Callable[[int], None] | None = None,
    block_size: int = 0,
    node: int = 0,
) -> int:
    """Write image into the inactive slot of node and mark it for a test boot; returns the blocks
    sent. The caller then resets the device (ECUReset) and reads the status back."""
    from udsoncan import MemoryLocation

    from ..link.uds import unlock

    # through the default session: ends any transfer a previous, interrupted run left open
    _call("DiagnosticSessionControl(default)", client.change_session, 0x01, node=node)
    _call("DiagnosticSessionControl(programming)", client.change_session, SESSION_PROGRAMMING, node=node)
    # SecurityAccess level 3, waiting out the device's delay (NRC 0x37: the 1 s after power-up,
    # e.g. right after a previous update's reset, or after a wrong key)
    unlock(client, node, None, SEC_LEVEL_FIRMWARE, _refused)
    resp = _call(
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
        _call(
            f"TransferData(block {n_blocks + 1}, offset {off})", client.transfer_data, seq, chunk, node=node
        )
        seq = (seq + 1) & 0xFF
        n_blocks += 1
        if progress:
            progress(len(chunk))
    resp = _call("RequestTransferExit", client.request_transfer_exit, node=node)
    rec = bytes(resp.service_data.parameter_records or b"")
    if len(rec) >= 4:
        crc = int.from_bytes(rec[:4], "big")
        if crc != zlib.crc32(image):
            raise FsError(
                ERR_LINK_NEGATIVE,
                f"device CRC-32 0x{crc:08X} differs from the image's 0x{zlib.crc32(image):08X}",
            )
    _call(
        "RoutineControl(mark test)",
        client.start_routine,
        RID_MARK_TEST,
        bytes([1 if allow_downgrade else 0]),
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


# ---- connection ------------------------------------------------------------------------------


class Link:
    """Bus (link.bus.open_bus: python-can options, one-line errors) + the link.uds client for one
    node, with the update path's data identifier and 32-bit addresses; a context manager yielding
    the client. secret None: no SecurityAccess expected (the default secret is used if asked)."""

    def __init__(self, args: argparse.Namespace, secret: bytes | None) -> None:
        import can

        from ..link.bus import describe, open_bus
        from ..link.uds import open_client

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


# ---- commands --------------------------------------------------------------------------------


def _read_image(path: str, key_path: str | None, verify: bool) -> fw.FwImage:
    try:
        data = Path(path).read_bytes()
    except OSError as e:
        raise FsError(fw.ERR_ARGS, f"image {path}: {e.strerror}") from None
    return fw.parse_image(data, fw.load_key(key_path) if verify else None)


def _cmd_flash(args: argparse.Namespace) -> int:
    img = _read_image(args.image, args.key, verify=args.key is not None or bool(os.environ.get(fw.KEY_ENV)))
    data = img.to_bytes()
    from ..link.bus import bus_config

    try:
        bus_config(args)
        have_bus = True
    except FsError:
        if not args.dry_run:
            raise
        have_bus = False
    if not have_bus:
        for line in check_plan(img, None, args.allow_downgrade):
            print(line)
        print("dry run: no device contacted, nothing written")
        return 0
    secret = None if args.dry_run else load_secret(args.secret)
    link = Link(args, secret)
    with link as client:
        from udsoncan.exceptions import NegativeResponseException, TimeoutException

        try:
            dev = read_status(client)  # presence = the device's answer
        except TimeoutException:
            raise FsError(
                ERR_LINK_NO_RESPONSE, f"no response from node {args.node} on {link.channel}"
            ) from None
        except NegativeResponseException as e:
            if e.response.code == 0x31:
                raise FsError(
                    ERR_LINK_NEGATIVE,
                    f"node {args.node} does not know DID 0xF1B0: its "
                    "firmware has no update support (docs/update.md, Integration)",
                ) from None
            raise nrc_error(int(e.response.code or 0), "ReadDataByIdentifier(0xF1B0)") from None
        for line in check_plan(img, dev, args.allow_downgrade):
            print(line)
        if args.dry_run:
            slot = "BA"[dev.running_slot] if dev.running_slot < 2 else "A"
            print(f"dry run: would write {len(data)} bytes into slot {slot}; nothing written")
            return 0
        from tqdm import tqdm

        t0 = time.monotonic()
        with tqdm(
            total=len(data), unit="B", unit_scale=True, desc="flash", disable=args.quiet, file=sys.stderr
        ) as bar:
            n = flash_image(
                client,
                data,
                args.allow_downgrade,
                progress=bar.update,
                block_size=args.block_size,
                node=args.node,
            )
        dt = time.monotonic() - t0
        print(
            f"written and verified by the device: {len(data)} bytes in {n} blocks, {dt:.2f} s "
            f"({len(data) / max(dt, 1e-9) / 1024:.1f} KiB/s); marked for a test boot"
        )
        # ISO 14229-1: the device answers before it resets (the response is not suppressed here)
        _call("ECUReset(hard)", client.ecu_reset, 1, node=args.node)
        st = wait_confirmed(client, img.fw_version, args.confirm_timeout)
        print(f"after reset: {st.describe()}: new image confirmed")
    return 0


def _cmd_image_build(args: argparse.Namespace) -> int:
    try:
        payload = Path(args.binary).read_bytes()
    except OSError as e:
        raise FsError(fw.ERR_ARGS, f"binary {args.binary}: {e.strerror}") from None

    def fmt(s: str, name: str) -> tuple[int, int]:
        try:
            parts = [int(p) for p in s.split(":")]
        except ValueError:
            raise FsError(fw.ERR_ARGS, f"--{name}-format {s!r} is not N or N:OLDEST") from None
        return (parts[0], parts[-1]) if len(parts) in (1, 2) else (0, 0)

    img = fw.build_image(
        payload,
        args.version,
        args.target,
        fw.load_key(args.key),
        args.build_id,
        fmt(args.skill_format, "skill"),
        fmt(args.config_format, "config"),
        int(args.entry_offset, 0),
    )
    out = Path(args.output)
    from ..outputs import write_file

    write_file(out, img, inputs=[args.binary])
    print(fw.describe(fw.parse_image(img, fw.load_key(args.key))))
    print(f"written: {out} ({len(img)} bytes)")
    return 0


def _cmd_image_show(args: argparse.Namespace) -> int:
    print(
        fw.describe(
            _read_image(
                args.image,
                args.key,
                verify=args.key is not None or bool(os.environ.get(fw.KEY_ENV)) or args.dev_key,
            )
        )
    )
    return 0


def register(sub: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    p = sub.add_parser("flash", help="flash a signed firmware image over CAN (UDS), test-boot it, read back")
    p.add_argument("image", help="signed image (forceskill image build)")
    from ..link.bus import add_bus_args

    add_bus_args(p)
    p.add_argument(
        "--secret",
        help="level-3 (firmware) SecurityAccess secret, hex file (default: $FORCESKILL_FW_SECRET "
        "or the simulator's secret, as the other CAN commands)",
    )
    p.add_argument(
        "--key", help="image key, hex file, to check the tag before sending (or $FORCESKILL_FW_KEY)"
    )
    p.add_argument(
        "--allow-downgrade", action="store_true", help="accept an image older than the running one"
    )
    p.add_argument("--dry-run", action="store_true", help="show image and device, check, write nothing")
    p.add_argument(
        "--confirm-timeout", type=float, default=15.0, help="s to wait for the new image to confirm"
    )
    p.add_argument(
        "--block-size",
        type=int,
        default=0,
        metavar="BYTES",
        help="data bytes per TransferData (default: the device's maximum)",
    )
    p.add_argument("-q", "--quiet", action="store_true", help="no progress bar")
    p.set_defaults(func=_cmd_flash)

    img = sub.add_parser("image", help="build or inspect a signed firmware image")
    isub = img.add_subparsers(dest="image_command", metavar="ACTION", parser_class=sub._parser_class)

    def _usage(a: argparse.Namespace) -> int:
        img.print_help()
        return 2

    img.set_defaults(func=_usage)
    b = isub.add_parser("build", help="wrap a firmware binary into a signed image")
    b.add_argument("binary", help="raw payload (objcopy -O binary output, or a host build)")
    b.add_argument("-o", "--output", required=True, help="image file to write")
    b.add_argument("--version", required=True, help="firmware version MAJOR.MINOR.PATCH")
    b.add_argument("--target", required=True, choices=sorted(fw.TARGETS), help="device target")
    b.add_argument("--key", help="device key, hex file (or $FORCESKILL_FW_KEY; default: the development key)")
    b.add_argument("--build-id", default="", help="free text, <= 31 ASCII bytes (e.g. git describe)")
    b.add_argument(
        "--skill-format", default=str(fw.SKILL_FORMAT), help="N or N:OLDEST skill format read/migrated"
    )
    b.add_argument(
        "--config-format", default=str(fw.CONFIG_FORMAT), help="N or N:OLDEST configuration format"
    )
    b.add_argument("--entry-offset", default="0", help="vector table offset in the payload (Cortex-M: 0x180)")
    b.set_defaults(func=_cmd_image_build)
    s = isub.add_parser("show", help="print an image's header; with a key, check its tag")
    s.add_argument("image")
    s.add_argument("--key", help="device key, hex file (or $FORCESKILL_FW_KEY)")
    s.add_argument("--dev-key", action="store_true", help="check the tag with the development key")
    s.set_defaults(func=_cmd_image_show)

"""Firmware image, format version 1: build, parse and verify (docs/update.md).

An image is ``header (128 bytes) || payload || tag (32 bytes)``, little-endian. The tag is
HMAC-SHA256(device key, header || payload) from Python's standard library (``hmac``, ``hashlib``);
the firmware checks it with firmware/security's SHA-256/HMAC (tested against FIPS 180-4 and
RFC 4231 vectors) in firmware/boot/boot_image.c. Codes 7xx are the firmware's (firmware/base/boot_status.h).
"""

from __future__ import annotations

import hashlib
import hmac
import os
import re
import struct
from dataclasses import dataclass
from pathlib import Path

from .. import codes as C

# 7xx: firmware image and update, the firmware's boot_status.h; 73x host only (codes.py)
from ..codes import BOOT_ERR_CONFIG_FORMAT as ERR_CONFIG_FORMAT
from ..codes import BOOT_ERR_DOWNGRADE as ERR_DOWNGRADE
from ..codes import BOOT_ERR_FLASH as ERR_FLASH
from ..codes import BOOT_ERR_FORMAT as ERR_FORMAT
from ..codes import BOOT_ERR_HASH as ERR_HASH
from ..codes import BOOT_ERR_MAGIC as ERR_MAGIC
from ..codes import BOOT_ERR_SKILL_FORMAT as ERR_SKILL_FORMAT
from ..codes import BOOT_ERR_TAG as ERR_TAG
from ..codes import BOOT_ERR_TARGET as ERR_TARGET
from ..codes import BOOT_ERR_TRUNCATED as ERR_TRUNCATED
from ..codes import ERR_IMAGE_ARGS as ERR_ARGS
from ..codes import ERR_IMAGE_KEY as ERR_KEY
from ..codes import FWU_ERR_BLOCK_COUNTER as ERR_BLOCK_COUNTER
from ..codes import FWU_ERR_LOCKED as ERR_LOCKED
from ..codes import FWU_ERR_OVERRUN as ERR_OVERRUN
from ..codes import FWU_ERR_RANGE as ERR_RANGE
from ..codes import FWU_ERR_SEQUENCE as ERR_SEQUENCE
from ..codes import FWU_ERR_TEST_PENDING as ERR_TEST_PENDING
from ..errors import FsError
from ..wire import TARGET_CORTEX_M3, TARGET_CORTEX_M4F, TARGET_HOST

MAGIC = 0x57465346  # bytes "FSFW"
FORMAT_VERSION = 1
HEADER_SIZE = 128
TAG_SIZE = 32
HEADER_STRUCT = struct.Struct("<IHHIIIIHHHHI28s32s32s")
assert HEADER_STRUCT.size == HEADER_SIZE

TARGETS = {"cortex-m4f": TARGET_CORTEX_M4F, "cortex-m3": TARGET_CORTEX_M3, "host": TARGET_HOST}
TARGET_NAMES = {v: k for k, v in TARGETS.items()}

# Data formats this product writes today (docs/skill_format.md v3, reading v2 too; configuration
# record v1).
SKILL_FORMAT = 5
SKILL_FORMAT_OLDEST = 2
CONFIG_FORMAT = 1

# Development key of the simulator and the qemu demo (docs/update.md: never ship it).
DEV_KEY = bytes(range(0x40, 0x60))
KEY_ENV = "FORCESKILL_FW_KEY"

# Negative response codes of the device's update path (codes.toml's NRC table, docs/update.md).
NRC = {
    C.NRC_CONDITIONS_NOT_CORRECT: (
        ERR_TEST_PENDING,
        "conditions not correct: the running image is still on test (not "
        "confirmed), or the device is busy (not idle, a transfer open)",
    ),
    C.NRC_REQUEST_SEQUENCE_ERROR: (ERR_SEQUENCE, "request sequence error"),
    C.NRC_REQUEST_OUT_OF_RANGE: (ERR_RANGE, "request out of range (address, size or data format)"),
    C.NRC_SECURITY_ACCESS_DENIED: (
        ERR_LOCKED,
        "security access denied: programming session and unlock required",
    ),
    C.NRC_TRANSFER_SUSPENDED: (ERR_OVERRUN, "transfer data suspended: more data than announced"),
    C.NRC_PROGRAMMING_FAILURE: (ERR_FLASH, "general programming failure (flash write)"),
    C.NRC_WRONG_BLOCK_COUNTER: (ERR_BLOCK_COUNTER, "wrong block sequence counter"),
    C.NRC_FW_HEADER: (ERR_FORMAT, "image header malformed (magic, format version or reserved bytes)"),
    C.NRC_FW_TARGET: (ERR_TARGET, "image is for another target"),
    C.NRC_FW_TRUNCATED: (ERR_TRUNCATED, "image truncated"),
    C.NRC_FW_HASH: (ERR_HASH, "payload SHA-256 mismatch (corrupted transfer)"),
    C.NRC_FW_TAG: (ERR_TAG, "authentication tag wrong (image not signed with this device's key)"),
    C.NRC_FW_DOWNGRADE: (ERR_DOWNGRADE, "downgrade refused (use --allow-downgrade)"),
    C.NRC_FW_SKILL_FORMAT: (
        ERR_SKILL_FORMAT,
        "stored skills use a format the new image cannot read or migrate",
    ),
    C.NRC_FW_CONFIG_FORMAT: (
        ERR_CONFIG_FORMAT,
        "stored configuration uses a format the new image cannot read or migrate",
    ),
}


class ImageError(FsError):
    """A firmware image that is malformed, for another device, or not authentic (7xx)."""


def pack_version(text: str) -> int:
    """'MAJOR.MINOR.PATCH' -> major<<24 | minor<<16 | patch (major, minor < 256; patch < 65536)."""
    m = re.fullmatch(r"(\d+)\.(\d+)\.(\d+)", text.strip())
    if not m:
        raise ImageError(ERR_ARGS, f"version {text!r} is not MAJOR.MINOR.PATCH")
    major, minor, patch = (int(g) for g in m.groups())
    if major > 255 or minor > 255 or patch > 65535:
        raise ImageError(ERR_ARGS, f"version {text!r} out of range (255.255.65535 at most)")
    return (major << 24) | (minor << 16) | patch


def unpack_version(v: int) -> str:
    """Inverse of pack_version."""
    return f"{(v >> 24) & 0xFF}.{(v >> 16) & 0xFF}.{v & 0xFFFF}"


def load_key(path: str | os.PathLike[str] | None = None) -> bytes:
    """Device key: hex text from PATH, else from $FORCESKILL_FW_KEY (hex), else the development key."""
    text = None
    if path is not None:
        try:
            text = Path(path).read_text()
        except OSError as e:
            raise ImageError(ERR_KEY, f"key file {path}: {e.strerror}") from None
    elif os.environ.get(KEY_ENV):
        text = os.environ[KEY_ENV]
    if text is None:
        return DEV_KEY
    try:
        key = bytes.fromhex("".join(text.split()))
    except ValueError:
        raise ImageError(ERR_KEY, f"key {path or KEY_ENV} is not hex") from None
    if not 32 <= len(key) <= 64:
        raise ImageError(ERR_KEY, f"key is {len(key)} bytes, need 32..64")
    return key


@dataclass
class FwImage:
    """A parsed image; ``authentic`` is None when no key was given."""

    fw_version: int
    target_id: int
    payload: bytes
    payload_sha256: bytes
    skill_format: int
    skill_format_oldest: int
    config_format: int
    config_format_oldest: int
    entry_offset: int
    build_id: str
    tag: bytes
    header: bytes
    authentic: bool | None = None

    @property
    def version(self) -> str:
        return unpack_version(self.fw_version)

    @property
    def target(self) -> str:
        return TARGET_NAMES.get(self.target_id, f"unknown({self.target_id})")

    def to_bytes(self) -> bytes:
        return self.header + self.payload + self.tag


def build_image(
    payload: bytes,
    version: str,
    target: str,
    key: bytes,
    build_id: str = "",
    skill_format: tuple[int, int] = (SKILL_FORMAT, SKILL_FORMAT_OLDEST),
    config_format: tuple[int, int] = (CONFIG_FORMAT, CONFIG_FORMAT),
    entry_offset: int = 0,
) -> bytes:
    """Wrap a firmware binary into a signed image. skill_format/config_format = (native, oldest
    stored version the firmware migrates from); entry_offset = offset of the Cortex-M vector table
    from the payload start (0 for the host target)."""
    if target not in TARGETS:
        raise ImageError(ERR_ARGS, f"target {target!r} unknown (one of {', '.join(TARGETS)})")
    bid = build_id.encode("ascii", "replace")
    if len(bid) > 31:
        raise ImageError(ERR_ARGS, f"build id {build_id!r} longer than 31 bytes")
    for name, (native, oldest) in (("skill", skill_format), ("config", config_format)):
        if not 1 <= oldest <= native <= 0xFFFF:
            raise ImageError(ERR_ARGS, f"{name} format ({native}, oldest {oldest}) invalid")
    if not payload or not 0 <= entry_offset < len(payload) or entry_offset % 4:
        raise ImageError(ERR_ARGS, f"entry offset {entry_offset} not a multiple of 4 inside the payload")
    header = HEADER_STRUCT.pack(
        MAGIC,
        FORMAT_VERSION,
        HEADER_SIZE,
        pack_version(version),
        len(payload),
        TARGETS[target],
        0,
        skill_format[0],
        skill_format[1],
        config_format[0],
        config_format[1],
        entry_offset,
        bytes(28),
        hashlib.sha256(payload).digest(),
        bid.ljust(32, b"\0"),
    )
    tag = hmac.new(key, header + payload, hashlib.sha256).digest()
    return header + bytes(payload) + tag


def parse_image(data: bytes, key: bytes | None = None) -> FwImage:
    """Parse and check an image in the firmware's order (700..706); with a key, check the tag."""
    if len(data) < HEADER_SIZE:
        raise ImageError(
            ERR_TRUNCATED, f"image is {len(data)} bytes, shorter than the {HEADER_SIZE}-byte header"
        )
    (
        magic,
        fmt,
        hsize,
        fw_version,
        length,
        target_id,
        flags,
        sk,
        sk_old,
        cf,
        cf_old,
        entry_offset,
        reserved,
        sha,
        bid,
    ) = HEADER_STRUCT.unpack_from(data)
    if magic != MAGIC:
        raise ImageError(ERR_MAGIC, f"magic 0x{magic:08X} is not 'FSFW' (0x{MAGIC:08X})")
    if (
        fmt != FORMAT_VERSION
        or hsize != HEADER_SIZE
        or flags != 0
        or any(reserved)
        or length == 0
        or entry_offset % 4
        or entry_offset >= length
        or not 1 <= sk_old <= sk
        or not 1 <= cf_old <= cf
    ):
        raise ImageError(
            ERR_FORMAT,
            f"header format {fmt} size {hsize} flags {flags:#x} entry "
            f"{entry_offset}: not a valid format-1 header",
        )
    if target_id not in TARGET_NAMES:
        raise ImageError(ERR_TARGET, f"target id {target_id} unknown")
    if len(data) < HEADER_SIZE + length + TAG_SIZE:
        raise ImageError(
            ERR_TRUNCATED, f"image is {len(data)} bytes, header says {HEADER_SIZE + length + TAG_SIZE}"
        )
    if len(data) > HEADER_SIZE + length + TAG_SIZE:
        raise ImageError(
            ERR_FORMAT,
            f"image is {len(data)} bytes, header says {HEADER_SIZE + length + TAG_SIZE} (trailing bytes)",
        )
    payload = bytes(data[HEADER_SIZE : HEADER_SIZE + length])
    if hashlib.sha256(payload).digest() != sha:
        raise ImageError(ERR_HASH, "payload SHA-256 does not match the header")
    tag = bytes(data[HEADER_SIZE + length :])
    img = FwImage(
        fw_version,
        target_id,
        payload,
        sha,
        sk,
        sk_old,
        cf,
        cf_old,
        entry_offset,
        bid.rstrip(b"\0").decode("ascii", "replace"),
        tag,
        bytes(data[:HEADER_SIZE]),
    )
    if key is not None:
        want = hmac.new(key, img.header + payload, hashlib.sha256).digest()
        img.authentic = hmac.compare_digest(want, tag)
        if not img.authentic:
            raise ImageError(ERR_TAG, "authentication tag wrong for this key")
    return img


def describe(img: FwImage) -> str:
    """Human-readable summary (``forceskill image show``)."""
    auth = {None: "not checked (no key)", True: "valid", False: "WRONG"}[img.authentic]
    return "\n".join(
        [
            f"firmware version  {img.version}",
            f"target            {img.target}",
            f"build id          {img.build_id or '-'}",
            f"payload           {len(img.payload)} bytes, sha256 {img.payload_sha256.hex()}",
            f"skill format      {img.skill_format} (migrates from {img.skill_format_oldest})",
            f"config format     {img.config_format} (migrates from {img.config_format_oldest})",
            f"entry offset      {img.entry_offset}",
            f"tag (HMAC-SHA256) {auth}",
        ]
    )

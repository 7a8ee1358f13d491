"""The DBC of the device (the single source of truth, firmware/proto/forceskill.dbc, installed
as forceskill/data/forceskill.dbc) and the E2E protection of safety frames.

Identifiers in the DBC are for node 0; node n uses id + n. Safety frames (Emergency,
HostCommand, HostHeartbeat, DeviceStatus) carry a 4-bit rolling counter in bits 48..51 and a
CRC-8 SAE J1850 (poly 0x1D, init 0xFF, xorout 0xFF) in byte 7 over the identifier (low byte,
high byte) and data bytes 0..6 (docs/protocol.md).
"""

from __future__ import annotations

import copy
import functools
from pathlib import Path

import cantools

from ..codes import UDS_REQUEST_BASE, UDS_RESPONSE_BASE  # noqa: F401
from ..errors import ERR_IO, FsError

SAFETY_FRAMES = ("Emergency", "HostCommand", "HostHeartbeat", "DeviceStatus")
STATES = {0: "BOOT", 1: "IDLE", 2: "TEACH", 3: "EXECUTE", 4: "FAULT"}
MODES = {"none": 0, "idle": 1, "teach": 2, "execute": 3, "clear_fault": 4, "run_options": 5}
#: The frames that carry a MAC and a freshness value, each its own channel (docs/protocol.md).
AUTH_FRAMES = ("HostCommand", "HostHeartbeat")
#: The label of the motion key's derivation (firmware/security/secoc.h SECOC_LABEL).
SECOC_LABEL = b"forceskill secoc v3"
MAC_LEN = 3
END_POLICIES = {"skill": 0, "hold": 1, "release": 2}


def dbc_path() -> Path:
    """Path of the DBC packaged with forceskill (forceskill/data/forceskill.dbc); FsError naming
    the path when the installation lacks it."""
    from importlib.resources import files

    path = Path(str(files("forceskill") / "data" / "forceskill.dbc"))
    if not path.is_file():
        raise FsError(
            ERR_IO, f"the device's DBC is missing from the installed package: {path}; reinstall forceskill"
        )
    return path


@functools.cache
def _base_db() -> cantools.database.can.Database:
    db = cantools.database.load_file(str(dbc_path()), strict=True)
    assert isinstance(db, cantools.database.can.Database)
    return db


@functools.cache
def load_db(node: int = 0) -> cantools.database.can.Database:
    """The DBC with every frame id moved to node ``node`` (0..15)."""
    if not 0 <= node <= 15:
        raise ValueError(f"node must be 0..15: {node}")
    db = copy.deepcopy(_base_db())
    for m in db.messages:
        m.frame_id = m.frame_id + node
    db.refresh()
    return db


def crc8_j1850(data: bytes) -> int:
    """CRC-8 SAE J1850: poly 0x1D, init 0xFF, xorout 0xFF (check "123456789" -> 0x4B)."""
    crc = 0xFF
    for b in data:
        crc ^= b
        for _ in range(8):
            crc = ((crc << 1) ^ 0x1D) & 0xFF if crc & 0x80 else (crc << 1) & 0xFF
    return crc ^ 0xFF


def frame_crc(frame_id: int, data: bytes | bytearray) -> int:
    """CRC byte of a safety frame: over id (LE, 2 bytes) then data[0..6]."""
    return crc8_j1850(bytes([frame_id & 0xFF, (frame_id >> 8) & 0x07]) + bytes(data[:7]))


def protect(frame_id: int, data: bytes, counter: int) -> bytes:
    """Put counter (low nibble of byte 6) and the CRC (byte 7) into an 8-byte safety frame."""
    b = bytearray(data)
    b[6] = (b[6] & 0xF0) | (counter & 0x0F)
    b[7] = frame_crc(frame_id, b)
    return bytes(b)


def derive_motion_key(secret: bytes, dev_nonce: bytes, host_nonce: bytes) -> bytes:
    """The session's motion key (AES-128): the first 16 bytes of HMAC-SHA256(level-1 secret,
    label || device nonce || host nonce)."""
    import hashlib
    import hmac

    return hmac.new(secret, SECOC_LABEL + dev_nonce + host_nonce, hashlib.sha256).digest()[:16]


def cmac(key: bytes, msg: bytes) -> bytes:
    """AES-128-CMAC (NIST SP 800-38B) of msg under the 16-byte key: the 16-byte tag
    (the `cryptography` package's CMAC)."""
    from cryptography.hazmat.primitives.ciphers.algorithms import AES
    from cryptography.hazmat.primitives.cmac import CMAC

    c = CMAC(AES(key))
    c.update(msg)
    return c.finalize()


#: The message of the motion key's confirmation (firmware/security/secoc.h SECOC_CONFIRM_LABEL).
SECOC_CONFIRM_LABEL = b"forceskill key confirm"


def key_confirmation(key: bytes) -> int:
    """The motion key's confirmation the device reads out with its nonce (DID 0x0302): the first 4
    bytes of AES-128-CMAC(key, SECOC_CONFIRM_LABEL), big-endian."""
    return int.from_bytes(cmac(key, SECOC_CONFIRM_LABEL)[:4], "big")


def frame_mac(key: bytes, frame_id: int, data: bytes | bytearray, fv: int) -> bytes:
    """The 24-bit MAC of an authenticated frame: AES-128-CMAC(key, id low, id high, data bytes
    0..2, freshness value u32 big-endian), first 3 bytes."""
    msg = bytes([frame_id & 0xFF, (frame_id >> 8) & 0x07]) + bytes(data[:3]) + fv.to_bytes(4, "big")
    return cmac(key, msg)[:MAC_LEN]


def authenticate(frame_id: int, data: bytes, fv: int, key: bytes) -> bytes:
    """An 8-byte authenticated frame: the freshness value's low 8 bits in byte 6 (its low nibble
    is the E2E counter), the MAC in bytes 3..5, then the CRC (byte 7)."""
    b = bytearray(data)
    b[6] = fv & 0xFF
    b[3:6] = frame_mac(key, frame_id, b, fv)
    b[7] = frame_crc(frame_id, b)
    return bytes(b)


def check(frame_id: int, data: bytes) -> bool:
    """True if a safety frame's CRC is right."""
    return len(data) == 8 and frame_crc(frame_id, data) == data[7]

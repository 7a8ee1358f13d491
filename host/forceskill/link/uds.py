"""UDS client of the device: udsoncan over can-isotp (sharing the Device's python-can Notifier),
configured here, not re-implemented. Padding 0xCC to 8 bytes, BS 0, STmin 0 (docs/protocol.md).

SecurityAccess key = first 16 bytes of HMAC-SHA256(secret of the level, seed). Each level has its
own secret: level 1 (skills, settings) from $FORCESKILL_SECRET (hex), level 3 (firmware) from
$FORCESKILL_FW_SECRET (hex); by default the simulator's documented secrets."""

from __future__ import annotations

import hashlib
import hmac
import logging
import os
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from functools import partial
from typing import Any

import isotp
import udsoncan
from udsoncan.client import Client
from udsoncan.connections import PythonIsoTpConnection
from udsoncan.exceptions import NegativeResponseException, TimeoutException, UnexpectedResponseException

from .. import wire as W
from ..codes import (  # noqa: F401
    DID_AUTH_STATS,
    DID_BAND,
    DID_COMM,
    DID_CONTACT_WAIT,
    DID_DEVICE_STATE,
    DID_FAULT_CAUSES,
    DID_FWU_STATUS,
    DID_GAINS_X,
    DID_GAINS_Y,
    DID_LAST_TRANSFER,
    DID_LIMITS_X,
    DID_LIMITS_Y,
    DID_MOTION_KEY,
    DID_OBJECT,
    DID_SLOT_DIR,
    DID_STIFFNESS_MAX,
    DID_SW_VERSION,
    DID_VERSIONS,
    ERR_LINK_AUTH,
    ERR_LINK_PROTOCOL,
    RID_CLEAR_FAULTS,
    RID_ERASE_SLOT,
    RID_RUN_SEQUENCE,
    RID_RUN_SKILL,
    RID_SELF_TEST,
    SEC_LEVEL_FIRMWARE,
    SEC_LEVEL_WRITE,
    SKILL_STATUS_TEXT,
)
from ..errors import FsError
from ..wire.dbc import UDS_REQUEST_BASE, UDS_RESPONSE_BASE
from . import ERR_LINK_NEGATIVE, ERR_LINK_TIMEOUT, ERR_LINK_VERIFY
from .device import Device

SIM_SECRET = b"forceskill-simulator-secret-0001"  # level 1
SIM_FW_SECRET = b"forceskill-simulator-fwsecret-03"  # level 3

# udsoncan logs every negative response; the commands report them as one line themselves
logging.getLogger("UdsClient").setLevel(logging.CRITICAL)
logging.getLogger("isotp").setLevel(logging.CRITICAL)

N_SLOTS = W.SLOT_COUNT

STATUS_NAMES = {
    W.TRANSFER_IN_PROGRESS: "transfer in progress",
    W.TRANSFER_INTERRUPTED: "transfer interrupted",
    W.TRANSFER_NONE: "none since power-up",
    0: "ok",
    **SKILL_STATUS_TEXT,
}


class Raw(udsoncan.DidCodec):
    """Bytes as they are, of a fixed length (the records of ``forceskill.wire`` decode them)."""

    def __init__(self, n: int) -> None:
        self.n = n

    def encode(self, value: Any) -> bytes:
        return bytes(value)

    def decode(self, payload: bytes) -> bytes:
        return bytes(payload)

    def __len__(self) -> int:
        return self.n


DID_CODECS = {
    DID_SW_VERSION: Raw(19),
    DID_FWU_STATUS: Raw(17),  # docs/update.md: the update status record
    DID_VERSIONS: Raw(W.Versions.SIZE),
    DID_GAINS_X: Raw(W.Gains.SIZE),
    DID_GAINS_Y: Raw(W.Gains.SIZE),
    DID_LIMITS_X: Raw(W.Limits.SIZE),
    DID_LIMITS_Y: Raw(W.Limits.SIZE),
    DID_COMM: Raw(W.Comm.SIZE),
    DID_OBJECT: Raw(W.Object.SIZE),
    DID_SLOT_DIR: Raw(W.SlotDir.SIZE + W.SLOT_COUNT * W.SlotEntry.SIZE),
    DID_LAST_TRANSFER: Raw(W.LastTransfer.SIZE),
    DID_DEVICE_STATE: Raw(W.DeviceState.SIZE),
    DID_FAULT_CAUSES: Raw(W.FaultCauses.SIZE),
    DID_STIFFNESS_MAX: Raw(W.StiffnessMax.SIZE),
    DID_MOTION_KEY: Raw(W.MotionKey.SIZE),  # the write: W.MotionKeyWrite.SIZE bytes, passed as they are
    DID_AUTH_STATS: Raw(W.AuthStats.SIZE),
    DID_CONTACT_WAIT: Raw(W.ContactWait.SIZE),
    DID_BAND: Raw(W.Band.SIZE),
}

#: The protocol major version this host speaks (DID 0xF1A0 byte 0): 4 = the heartbeat carries the
#: last command's freshness and commands are fresh in time (3: AES-CMAC without them; 2:
#: HMAC-SHA256).
PROTO_MAJOR = 4
SESSION_EXTENDED = 0x03


def mask_codes(mask: int) -> list[int]:
    """Fault codes of a cause/latched mask (bit n is fault 500 + n)."""
    return [500 + n for n in range(32) if mask >> n & 1]


def fault_causes(client: Client, node: int) -> tuple[list[int], list[int]]:
    """(latched faults, causes present at the device's last tick), from DID 0x0301."""
    c = W.FaultCauses.unpack(read_did(client, DID_FAULT_CAUSES, node))
    return mask_codes(c.latched_mask), mask_codes(c.present_mask)


def device_secret(level: int = SEC_LEVEL_WRITE) -> bytes:
    """The SecurityAccess secret of a level (1 or 3) from the environment, else the simulator's."""
    var, default = (
        ("FORCESKILL_FW_SECRET", SIM_FW_SECRET)
        if level == SEC_LEVEL_FIRMWARE
        else ("FORCESKILL_SECRET", SIM_SECRET)
    )
    env = os.environ.get(var)
    if env:
        try:
            return bytes.fromhex(env)
        except ValueError:
            raise FsError(ERR_LINK_NEGATIVE, f"{var} is not hex") from None
    return default


def security_key(seed: bytes, secret: bytes | None = None, level: int = SEC_LEVEL_WRITE) -> bytes:
    """The SecurityAccess key for a seed: HMAC-SHA256(secret of the level, seed)[:16]."""
    key = secret if secret is not None else device_secret(level)
    return hmac.new(key, bytes(seed), hashlib.sha256).digest()[:16]


def isotp_params(fd: bool = False, timeout_s: float = 2.0) -> dict[str, Any]:
    """can-isotp's parameters for the device's ISO-TP: classic 8-byte frames padded with 0xCC, or
    with fd (the bus opened with ``--fd``, the device served with ``--fd``) 64-byte CAN FD frames
    with bit-rate switching, short frames padded to the next FD length. The waits for a flow
    control and for the next consecutive frame are ISO 15765-2's 1000 ms, or half of a longer
    timeout_s (``--timeout``: a slow host, e.g. a qemu guest, whose threads stall for seconds)."""
    wait_ms = int(max(1000.0, 500.0 * timeout_s))
    return {
        "tx_padding": 0xCC,
        "tx_data_min_length": 8,
        "stmin": 0,
        "blocksize": 0,
        "rx_flowcontrol_timeout": wait_ms,
        "rx_consecutive_frame_timeout": wait_ms,
        "max_frame_size": 4095,
        "can_fd": fd,
        "tx_data_length": 64 if fd else 8,
        "bitrate_switch": fd,
        "blocking_send": False,
        "wftmax": 0,
    }


def open_client(
    bus: Any,
    notifier: Any,
    node: int,
    *,
    secret: bytes | None = None,
    dids: dict[int, Any] | None = None,
    timeout_s: float = 5.0,
    pending_timeout_s: float | None = None,
    address_format: int = 8,
    memorysize_format: int = 16,
    fd: bool = False,
) -> Client:
    """A udsoncan Client (not yet opened) for node over can-isotp on bus, sharing notifier.
    SecurityAccess keys use secret, or the requested level's device_secret(level) when it is None; dids maps data identifiers
    to codecs (default: the application's); timeout_s bounds every request (server timing ignored:
    a 4 KiB request takes longer than the server's P2 to cross a slow or simulated bus), and
    pending_timeout_s (default timeout_s) each wait after a "response pending" (NRC 0x78), and then
    the whole request; fd: ISO-TP in CAN FD frames (isotp_params)."""
    addr = isotp.Address(
        isotp.AddressingMode.Normal_11bits, txid=UDS_REQUEST_BASE + node, rxid=UDS_RESPONSE_BASE + node
    )
    stack = isotp.NotifierBasedCanStack(bus, notifier, address=addr, params=isotp_params(fd, timeout_s))
    conn = PythonIsoTpConnection(stack)

    def algo(level: int, seed: bytes, params: Any = None) -> bytes:
        return security_key(bytes(seed), secret, level=level)

    cfg: Any = dict(udsoncan.configs.default_client_config)
    cfg.update(
        {
            "security_algo": algo,
            "data_identifiers": DID_CODECS if dids is None else dids,
            "request_timeout": timeout_s if pending_timeout_s is None else max(timeout_s, pending_timeout_s),
            "p2_timeout": timeout_s,
            "p2_star_timeout": timeout_s if pending_timeout_s is None else pending_timeout_s,
            "use_server_timing": False,
            "server_address_format": address_format,
            "server_memorysize_format": memorysize_format,
            "exception_on_negative_response": True,
        }
    )
    return Client(conn, config=cfg)


@contextmanager
def uds_client(
    dev: Device, request_timeout_s: float = 5.0, pending_timeout_s: float | None = None
) -> Iterator[Client]:
    """A connected udsoncan Client for dev (whose Notifier must be running); each request waits
    request_timeout_s (a lost request is sent again sooner than the device's 5 s session timeout:
    the link's ``--timeout`` is not used here), or dev's own (``--request-timeout``) where given;
    pending_timeout_s as open_client's."""
    assert dev.notifier is not None
    with open_client(
        dev.bus,
        dev.notifier,
        dev.node,
        timeout_s=request_timeout_s if dev.request_timeout_s is None else dev.request_timeout_s,
        pending_timeout_s=pending_timeout_s,
        fd=dev.fd,
    ) as client:
        yield client


def describe_nrc(e: NegativeResponseException) -> str:
    r = e.response
    return f"{r.service.get_name() if r.service else 'request'} refused: {r.code_name} (0x{r.code:02X})"


#: Turns a refused request (its step name and the exception) into the FsError to raise.
NrcPolicy = Callable[[str, NegativeResponseException], FsError]


def _refusal(what: str, e: NegativeResponseException, node: int, on_nrc: NrcPolicy | None) -> FsError:
    return on_nrc(what, e) if on_nrc else FsError(ERR_LINK_NEGATIVE, f"{what}: node {node} {describe_nrc(e)}")


#: How long a request answered 0x21 busyRepeatRequest is repeated (the device is finishing a
#: request it answered 0x78, e.g. a sliced key check, 32 ticks) before it counts as refused.
BUSY_RETRY_S = 10.0


def call(what: str, fn: Callable[[], Any], node: int, on_nrc: NrcPolicy | None = None) -> Any:
    """Run a udsoncan call; negative responses and timeouts become one-line FsErrors (a refusal
    through on_nrc when given, else ERR_LINK_NEGATIVE naming the response code). A request
    answered 0x21 busyRepeatRequest is repeated (ISO 14229-1) for up to BUSY_RETRY_S."""
    end = time.monotonic() + BUSY_RETRY_S
    while True:
        try:
            return fn()
        except NegativeResponseException as e:
            if e.response.code == 0x21 and time.monotonic() < end:
                time.sleep(0.05)
                continue
            raise _refusal(what, e, node, on_nrc) from None
        except TimeoutException:
            raise FsError(ERR_LINK_TIMEOUT, f"{what}: no UDS response from node {node}") from None
        except UnexpectedResponseException as e:
            raise FsError(ERR_LINK_NEGATIVE, f"{what}: unexpected response from node {node}: {e}") from None


def unlock(
    client: Client,
    node: int,
    session: int | None,
    level: int = SEC_LEVEL_WRITE,
    on_nrc: NrcPolicy | None = None,
    wait_s: float = 15.0,
    key_retries: int = 0,
) -> None:
    """Enter session (unless None) and unlock level; waits out the device's power-up/failed-key
    delay (NRC 0x37) for up to wait_s. A key refused (0x35) is tried again with a fresh seed up
    to key_retries times (a seed or key altered on the bus: ISO-TP has no checksum); a wrong
    secret is refused every time, each refusal counted by the device."""
    if session is not None:
        call("session change", lambda: client.change_session(session), node, on_nrc)
    what = "security access" if on_nrc is None else f"SecurityAccess(level {level})"
    end = time.monotonic() + wait_s
    while True:
        try:
            client.unlock_security_access(level)
            return
        except NegativeResponseException as e:
            if e.response.code in (0x21, 0x37) and time.monotonic() < end:
                time.sleep(0.2)  # a delay running, or the device busy finishing a request
                continue
            if e.response.code == 0x35 and key_retries > 0:
                key_retries -= 1
                continue
            raise _refusal(what, e, node, on_nrc) from None
        except TimeoutException:
            raise FsError(ERR_LINK_TIMEOUT, f"{what}: no UDS response from node {node}") from None


def check_protocol(client: Client, node: int) -> None:
    """FsError(693) unless the device speaks this host's protocol major version."""
    major = read_did(client, DID_VERSIONS, node)[0]
    if major != PROTO_MAJOR:
        raise FsError(
            ERR_LINK_PROTOCOL,
            f"node {node} speaks protocol {major}, this host {PROTO_MAJOR} (authenticated motion): "
            "update the firmware or the host tools",
        )


def _again(fn: Callable[[], Any], tries: int) -> Any:
    """fn(), repeated while it fails for a request without an answer (a frame lost on the bus)."""
    for attempt in range(tries):
        try:
            return fn()
        except FsError as e:
            if e.code != ERR_LINK_TIMEOUT or attempt == tries - 1:
                raise
    raise AssertionError("unreachable")


def motion_session(client: Client, dev: Device, tries: int = 10) -> None:
    """Establish the motion key with dev (docs/protocol.md): check the protocol version, unlock
    level 1 in the extended session, write a fresh host nonce to DID 0x0302, read the device's
    nonce and the key's confirmation back, derive the key from the level-1 secret (a confirmation
    that differs from the key's own: a new exchange); commands and heartbeats are authenticated
    from then on. Also installs it as dev.resync (the same exchange again). A request without an
    answer is sent again, up to tries times. FsError 693/694."""
    from ..wire.dbc import derive_motion_key, key_confirmation

    node = dev.node
    _again(lambda: check_protocol(client, node), tries)

    def refused(what: str, e: NegativeResponseException) -> FsError:
        err = FsError(ERR_LINK_AUTH, f"motion key with node {node}: {what}: {describe_nrc(e)}")
        # the session or its unlock ended between two requests (requests lost on the bus for
        # longer than the device's S3 timeout): the exchange starts again from the unlock
        err.session_lost = e.response.code in (0x33, 0x7E, 0x7F)  # type: ignore[attr-defined]
        return err

    def exchange(client: Client) -> bytes | None:
        _again(lambda: unlock(client, node, SESSION_EXTENDED, on_nrc=refused, key_retries=1), tries)
        host_nonce = os.urandom(16)
        payload = W.MotionKeyWrite(host_nonce).pack()
        _again(
            lambda: call(
                "write 0x0302",
                lambda: client.write_data_by_identifier(DID_MOTION_KEY, payload),
                node,
                on_nrc=refused,
            ),
            tries,
        )
        mk = W.MotionKey.unpack(_again(lambda: read_did(client, DID_MOTION_KEY, node), tries))
        if mk.keyed != 1:
            raise FsError(ERR_LINK_AUTH, f"node {node} did not establish the motion key")
        key = derive_motion_key(device_secret(SEC_LEVEL_WRITE), mk.nonce, host_nonce)
        return key if key_confirmation(key) == mk.confirm else None

    def establish(client: Client) -> None:
        # ISO-TP carries no checksum: a nonce altered on the bus gives the two sides different
        # keys, which the confirmation shows; a new exchange then starts, as after a lost session
        for attempt in range(tries):
            try:
                key = exchange(client)
            except FsError as e:
                if not getattr(e, "session_lost", False) or attempt == tries - 1:
                    raise
                continue
            if key is not None:
                dev.set_session(key)
                return
        raise FsError(ERR_LINK_AUTH, f"node {node}: the motion key's confirmation never matched")

    def resync() -> None:
        # a lost request is sent again after 2 s; the key check and derivation answer 0x78 and
        # take 32 device ticks each (longer than 2 s of a traced qemu image)
        with uds_client(dev, request_timeout_s=2.0, pending_timeout_s=30.0) as c:
            establish(c)

    establish(client)
    dev.resync = resync


def read_did(client: Client, did: int, node: int) -> bytes:
    r = call(f"read 0x{did:04X}", lambda: client.read_data_by_identifier(did), node)
    return bytes(r.service_data.values[did])


def stiffness_limit(client: Client, node: int) -> float:
    """The device's skill stiffness limit in N/m (DID 0x0140): it refuses stiffer skills."""
    return W.StiffnessMax.unpack(read_did(client, DID_STIFFNESS_MAX, node)).stiffness_max_Npm


def slot_directory(client: Client, node: int) -> list[dict[str, Any]]:
    d = W.SlotDir.unpack(read_did(client, DID_SLOT_DIR, node))
    return [
        {
            "slot": i + 1,
            "valid": bool(e.valid),
            "length": e.length,
            "crc32": e.crc32,
            "n_kernels": e.n_kernels,
            "duration_s": e.duration_s,
            "end": "release" if e.end else "hold",
        }
        for i, e in enumerate(d.entries[: d.count])
    ]


def last_transfer_status(client: Client, node: int) -> int:
    return W.LastTransfer.unpack(read_did(client, DID_LAST_TRANSFER, node)).status


def download(
    client: Client, node: int, slot: int, image: bytes, progress: Callable[[int], None] | None = None
) -> int:
    """RequestDownload + TransferData + RequestTransferExit of image into slot; returns the CRC-32
    the device reports. On refusal the device keeps the slot's previous skill."""
    loc = udsoncan.MemoryLocation(address=slot, memorysize=len(image), address_format=8, memorysize_format=16)
    r = call("request download", lambda: client.request_download(loc), node)
    block = int(r.service_data.max_length) - 2
    seq = 1
    for off in range(0, len(image), block):
        chunk = image[off : off + block]
        call("transfer data", partial(client.transfer_data, seq & 0xFF, chunk), node)
        seq += 1
        if progress:
            progress(len(chunk))
    try:
        r = client.request_transfer_exit()
    except NegativeResponseException as e:
        code = last_transfer_status(client, node)
        raise FsError(
            ERR_LINK_NEGATIVE,
            f"node {node} rejected the skill at transfer exit "
            f"({describe_nrc(e)}; device status {code}: {STATUS_NAMES.get(code, 'storage error')}); "
            f"slot {slot} keeps its previous skill",
        ) from None
    except TimeoutException:
        raise FsError(ERR_LINK_TIMEOUT, f"transfer exit: no UDS response from node {node}") from None
    params = bytes(r.service_data.parameter_records or b"")
    return W.TransferExit.unpack(params).crc32 if params else -1


def upload(client: Client, node: int, slot: int, size: int) -> bytes:
    """RequestUpload + TransferData until size bytes + RequestTransferExit: read a slot back."""
    loc = udsoncan.MemoryLocation(address=slot, memorysize=size, address_format=8, memorysize_format=16)
    call("request upload", lambda: client.request_upload(loc), node)
    data = bytearray()
    seq = 1
    while len(data) < size:
        r = call("transfer data", partial(client.transfer_data, seq & 0xFF), node)
        data += bytes(r.service_data.parameter_records or b"")
        seq += 1
    call("transfer exit", client.request_transfer_exit, node)
    return bytes(data)


def verify(node: int, slot: int, sent: bytes, read: bytes) -> None:
    if sent != read:
        first = next(
            (i for i, (a, b) in enumerate(zip(sent, read, strict=False)) if a != b), min(len(sent), len(read))
        )
        raise FsError(
            ERR_LINK_VERIFY,
            f"read-back of slot {slot} on node {node} differs from the file "
            f"at byte {first} ({len(read)} of {len(sent)} bytes read)",
        )

"""forceskill status: state, fault, versions and the slot directory of a node; --clear clears faults."""

from __future__ import annotations

import argparse
from typing import Any

from udsoncan.exceptions import NegativeResponseException

from .. import wire as W
from ..errors import ERR_CLEAR_BLOCKED, FsError, fault_text
from ..link import uds as U
from ._common import add_common, connect


def _names(codes: list[int]) -> str:
    return ", ".join(fault_text(c) for c in codes) or "none"


def clear_faults(client: Any, node: int, state: str) -> bool:
    """RoutineControl clear faults: True when cleared, False when the device had no fault to clear
    (not an error: the wanted state holds); a refusal names the condition that blocks it (666),
    read from the device's fault-cause identifier."""
    try:
        client.start_routine(U.RID_CLEAR_FAULTS)
        return True
    except NegativeResponseException as e:
        code = e.response.code
        if code == 0x24:
            return False
        if code != 0x22:
            raise FsError(632, f"clear faults: node {node} {U.describe_nrc(e)}") from None
    try:
        latched, present = U.fault_causes(client, node)
    except FsError:
        raise FsError(
            ERR_CLEAR_BLOCKED,
            f"faults of node {node} not cleared: a cause persists (the device does not report which)",
        ) from None
    blocking = [c for c in present if c != 500]  # a clear request is host activity itself
    raise FsError(
        ERR_CLEAR_BLOCKED,
        f"faults of node {node} not cleared: cause still present: "
        f"{_names(blocking) if blocking else 'none now (it ended at the request; try again)'}; "
        f"latched: {_names(latched)}",
    )


def running_image(client: Any, node: int, build: str) -> str:
    """The firmware's version as it runs: the version in the header of the image the device
    booted from its update slots (after ``forceskill flash``), with the build's own name; the
    build's name alone when it runs no image from a slot (or does not know DID 0xF1B0)."""
    from ..link.flash import DeviceStatus

    try:
        st = DeviceStatus.decode(U.read_did(client, U.DID_FWU_STATUS, node))
    except FsError:
        return build
    if st.running_slot > 1:
        return build
    state = "on test" if st.on_test else "confirmed"
    return f"{st.version} (image in slot {'AB'[st.running_slot]}, {state}; build {build})"


def _cmd(args: argparse.Namespace) -> int:
    with connect(args) as dev:
        st = dev.status
        assert st is not None
        print(
            f"node {dev.node} on {dev.channel}: {st.state}, fault {fault_text(st.fault_code)}, "
            f"actuator {'on' if st.actuator_enabled else 'off'}, tick {st.tick}"
        )
        with U.uds_client(dev) as client:
            if st.state == "FAULT":
                try:
                    latched, present = U.fault_causes(client, dev.node)
                    print(f"latched faults: {_names(latched)}; causes present: {_names(present)}")
                except FsError:
                    pass
            if args.clear:
                if clear_faults(client, dev.node, st.state):
                    print("faults cleared")
                else:
                    print(f"no fault to clear (state {st.state})")
            ver = U.read_did(client, U.DID_SW_VERSION, dev.node).decode("ascii", "replace")
            ver = running_image(client, dev.node, ver)
            v = W.Versions.unpack(U.read_did(client, U.DID_VERSIONS, dev.node))
            print(
                f"firmware {ver}; protocol {v.proto_major}.{v.proto_minor}, skill format "
                f"v{v.skill_format}, up to {v.max_kernels} kernels, {v.slots} slots"
            )
            last = U.last_transfer_status(client, dev.node)
            for e in U.slot_directory(client, dev.node):
                if e["valid"]:
                    print(
                        f"  slot {e['slot']}: {e['length']} bytes, CRC-32 0x{e['crc32']:08X}, "
                        f"N = {e['n_kernels']}, T = {e['duration_s']:.3f} s, end {e['end']}"
                    )
                else:
                    print(f"  slot {e['slot']}: empty")
            print(f"last download: {U.STATUS_NAMES.get(last, f'storage code {last}')}")
    return 0


def register(sub: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    p = sub.add_parser(
        "status",
        help="show a device's state, versions and skill slots",
        description="Wait for the node's status frame (presence), then read its "
        "versions and slot directory over UDS.",
    )
    p.add_argument(
        "--clear", action="store_true", help="clear latched faults (refused while a cause persists)"
    )
    add_common(p)
    p.set_defaults(func=_cmd)

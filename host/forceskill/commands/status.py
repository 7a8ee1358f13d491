"""forceskill status: state, fault, versions and the slot directory of a node; --clear clears faults."""

from __future__ import annotations

import argparse
import struct

from ..errors import fault_text
from ..link import uds as U
from ._common import add_common, connect


def _cmd(args: argparse.Namespace) -> int:
    with connect(args) as dev:
        st = dev.status
        assert st is not None
        print(
            f"node {dev.node} on {dev.channel}: {st.state}, fault {fault_text(st.fault_code)}, "
            f"actuator {'on' if st.actuator_enabled else 'off'}, tick {st.tick}"
        )
        with U.uds_client(dev) as client:
            if args.clear:
                U.call("clear faults", lambda: client.start_routine(U.RID_CLEAR_FAULTS), dev.node)
                print("faults cleared")
            ver = U.read_did(client, U.DID_SW_VERSION, dev.node).decode("ascii", "replace")
            v = U.read_did(client, U.DID_VERSIONS, dev.node)
            print(
                f"firmware {ver}; protocol {v[0]}.{v[1]}, skill format v{v[2]}, "
                f"up to {struct.unpack('>H', v[3:5])[0]} kernels, {v[5]} slots"
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

"""forceskill upload: a skill image into a slot over UDS (RequestDownload/TransferData/Exit),
then read back (RequestUpload) and compared."""

from __future__ import annotations

import argparse
import time
from pathlib import Path
from typing import Any

from tqdm import tqdm

from ..errors import FsError
from ..link import ERR_LINK_ARGS, ERR_LINK_STATE
from ..link import uds as U
from ..link.device import Device
from ..model.limits import check_skill_force, check_skill_stiffness
from ..model.skill import Skill, image_crc32
from ._args import add_force_limit
from ._common import add_common, connect


def upload_skill(
    dev: Device, image: bytes, slot: int, progress: bool = True, verify: bool = True
) -> dict[str, Any]:
    """Download image into slot and verify; returns timing figures. Old skill kept on failure.
    A skill stiffer than the device's stiffness limit is refused before anything is sent (690)."""
    st = dev.status
    if st is not None and st.state != "IDLE":
        raise FsError(ERR_LINK_STATE, f"node {dev.node} is in {st.state}; uploads need IDLE")
    with U.uds_client(dev) as client:
        check_skill_stiffness(
            Skill.from_bytes(image), f"skill for slot {slot}", U.stiffness_limit(client, dev.node), dev.node
        )
        U.unlock(client, dev.node, 0x02)
        bar = tqdm(
            total=len(image), unit="B", unit_scale=True, desc=f"slot {slot}", disable=not progress, leave=True
        )
        t0 = time.perf_counter()
        try:
            crc = U.download(client, dev.node, slot, image, progress=bar.update)
        except KeyboardInterrupt:
            raise FsError(
                ERR_LINK_STATE,
                f"upload interrupted: slot {slot} of node {dev.node} keeps its "
                "previous skill (the device commits only a complete, valid image)",
            ) from None
        finally:
            bar.close()
        t_download = time.perf_counter() - t0
        t1 = time.perf_counter()
        if verify:
            back = U.upload(client, dev.node, slot, len(image))
            U.verify(dev.node, slot, image, back)
        t_verify = time.perf_counter() - t1
        try:
            client.change_session(0x01)
        except Exception:
            pass
    return {"crc32": crc, "download_s": t_download, "verify_s": t_verify, "bytes": len(image)}


def _cmd(args: argparse.Namespace) -> int:
    if not 1 <= args.slot <= U.N_SLOTS:
        raise FsError(ERR_LINK_ARGS, f"--slot must be 1..{U.N_SLOTS}: {args.slot}")
    sk = Skill.read(args.skill)  # validates (CRC, version, ranges) before anything is sent
    check_skill_force(sk, args.skill, force_limit_N=args.force_limit)  # finite, peak within the limit
    image = Path(args.skill).read_bytes()
    with connect(args) as dev:
        r = upload_skill(dev, image, args.slot, progress=not args.quiet, verify=not args.no_verify)
    expect = image_crc32(image)
    if r["crc32"] != expect:
        raise FsError(633, f"device reports CRC-32 0x{r['crc32']:08X}, file has 0x{expect:08X}")
    print(
        f"uploaded {args.skill} ({r['bytes']} bytes, N = {sk.n_kernels}) to slot {args.slot} of node "
        f"{args.node}: CRC-32 0x{r['crc32']:08X} {'verified by read-back' if not args.no_verify else ''} "
        f"in {r['download_s'] * 1e3:.1f} ms (+{r['verify_s'] * 1e3:.1f} ms read-back)"
    )
    return 0


def register(sub: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    p = sub.add_parser(
        "upload",
        help="upload a skill into a device slot (UDS over ISO-TP)",
        description="Validate SKILL, download it into --slot over UDS (programming "
        "session, SecurityAccess), then read it back and compare. A skill whose rollout is "
        "not finite or peaks above --force-limit, or whose nominal stiffness is above the "
        "device's stiffness limit (read from it), is refused before anything is sent. A "
        "refused or interrupted upload leaves the slot's previous skill in place.",
    )
    p.add_argument("skill", metavar="SKILL")
    p.add_argument("--slot", type=int, required=True, metavar="N", help=f"slot 1..{U.N_SLOTS}")
    p.add_argument("--no-verify", action="store_true", help="skip the read-back")
    p.add_argument("-q", "--quiet", action="store_true", help="no progress bar")
    add_force_limit(p)
    add_common(p)
    p.set_defaults(func=_cmd)

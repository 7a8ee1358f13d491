"""``forceskill flash IMAGE`` and ``forceskill image build|show`` (docs/update.md); the update
protocol itself is ``forceskill.link.flash``."""

from __future__ import annotations

import argparse
import os
import sys
import time
from pathlib import Path

from ..errors import ERR_LINK_NEGATIVE, ERR_LINK_NO_RESPONSE, FsError
from ..link.flash import (
    Link,
    check_plan,
    flash_image,
    load_secret,
    nrc_error,
    read_status,
    request,
    stored_skill_formats,
    wait_confirmed,
)
from ..model import fwimage as fw


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
        for line in check_plan(img, dev, args.allow_downgrade, stored_skill_formats(client)):
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
        request("ECUReset(hard)", client.ecu_reset, 1, node=args.node)
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
    b.add_argument(
        "binary",
        help="the firmware binary: build/cortex-m4f/... objcopy output for Cortex-M (docs/cortex-m.md); "
        "for --target host the simulator's build/hil_sim/hil_sim (scripts/setup.sh builds it)",
    )
    b.add_argument("-o", "--output", required=True, help="image file to write")
    b.add_argument("--version", required=True, help="firmware version MAJOR.MINOR.PATCH")
    b.add_argument("--target", required=True, choices=sorted(fw.TARGETS), help="device target")
    b.add_argument("--key", help="device key, hex file (or $FORCESKILL_FW_KEY; default: the development key)")
    b.add_argument("--build-id", default="", help="free text, <= 31 ASCII bytes (e.g. git describe)")
    b.add_argument(
        "--skill-format",
        default=f"{fw.SKILL_FORMAT}:{fw.SKILL_FORMAT_OLDEST}",
        help=f"N or N:OLDEST skill formats read/migrated (default {fw.SKILL_FORMAT}:{fw.SKILL_FORMAT_OLDEST}: "
        "every format fit writes)",
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

#!/usr/bin/env python3
"""Write the two host firmware images of the power-cut runner (`hil_sim powercut`, docs/safety.md):
tests/vectors/powercut_fw_1.0.0.fwimg (the installed image) and powercut_fw_1.1.0.fwimg (the
update), signed with the development key, 3,000 and 3,500 bytes of payload.

usage: tests/vectors/powercut_fw_generate.py [--check]   (--check: exit 1 if they differ)
"""

from __future__ import annotations

import sys
from pathlib import Path

from forceskill.model import fwimage as fw

HERE = Path(__file__).parent


def images() -> dict[Path, bytes]:
    out = {}
    for version, n, k in (("1.0.0", 3000, 5), ("1.1.0", 3500, 11)):
        payload = bytes((i * k + 1) & 0xFF for i in range(n))
        out[HERE / f"powercut_fw_{version}.fwimg"] = fw.build_image(
            payload, version, "host", fw.DEV_KEY, build_id=f"powercut-{version}"
        )
    return out


def main(argv: list[str]) -> int:
    if "--check" in argv:
        bad = [p.name for p, b in images().items() if not p.is_file() or p.read_bytes() != b]
        if bad:
            print(f"{', '.join(bad)} differ: run {Path(__file__).name}", file=sys.stderr)
        return 1 if bad else 0
    for p, b in images().items():
        p.write_bytes(b)
        print(f"wrote {p}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

#!/usr/bin/env python3
"""The one mechanism that gives the float32 builds (fs_core_f32, fs_safety_f32) their _f32
symbols: every function declared in the public headers of a module built twice is renamed by a
macro `#define name name_f32` under FS_REAL_FLOAT, in a header written from those declarations.
A new function is renamed without anyone keeping a list; tests/firmware/core's f32_symbols test
checks with nm that the float libraries export only _f32 symbols.

usage: tools/gen_f32_names.py            write firmware/core/fs_f32_names.h, firmware/safety/saf_f32_names.h
       tools/gen_f32_names.py --check    exit 1 if either differs from the headers' declarations
"""

from __future__ import annotations

import argparse
import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
# output -> the public headers whose functions it renames (the modules built twice)
OUTPUTS = {
    "firmware/core/fs_f32_names.h": [
        "firmware/core/dmp.h",
        "firmware/core/pfc.h",
        "firmware/core/skill.h",
        "firmware/core/skill_check.h",
    ],
    "firmware/safety/saf_f32_names.h": [
        "firmware/safety/lim.h",
        "firmware/safety/sen.h",
        "firmware/safety/wdg.h",
        "firmware/safety/saf.h",
    ],
    "firmware/safety/saf_fx_names.h": [
        "firmware/safety/lim.h",
        "firmware/safety/sen.h",
        "firmware/safety/wdg.h",
        "firmware/safety/saf.h",
    ],
}
# the suffix each output gives (the safety layer's integer build: SAF_FIXED, _fx)
SUFFIX = {"firmware/safety/saf_fx_names.h": "_fx"}
COMMENT = re.compile(r"/\*.*?\*/", re.S)
# a declaration at column 0: return type words and stars, then the name and "(";
# static (inline) functions, typedefs and preprocessor lines are not external symbols
DECL = re.compile(r"^(?!static\b|typedef\b|extern\b|#)[A-Za-z_][\w \*]*?\b(\w+)\s*\(", re.M)


def functions(text: str) -> list[str]:
    return [m.group(1) for m in DECL.finditer(COMMENT.sub("", text))]


def render(out: str, headers: list[str], root: Path) -> str:
    guard = re.sub(r"[^A-Z0-9]", "_", Path(out).name.upper())
    suffix = SUFFIX.get(out, "_f32")
    build = "integer build" if suffix == "_fx" else "float32 build"
    flag = "SAF_FIXED" if suffix == "_fx" else "FS_REAL_FLOAT"
    lines = [
        f"/* The {suffix} names of the {build} of {', '.join(Path(h).name for h in headers)}",
        f" * ({flag}): generated from their declarations by tools/gen_f32_names.py;",
        " * do not edit. */",
        f"#ifndef {guard}",
        f"#define {guard}",
        "",
    ]
    for h in headers:
        for name in functions((root / h).read_text()):
            lines.append(f"#define {name} {name}{suffix}")
    lines += ["", f"#endif /* {guard} */", ""]
    return "\n".join(lines)


def check(root: Path = ROOT) -> list[str]:
    """One line per output that differs from what the headers give."""
    return [
        f"{out} differs from the declarations in {', '.join(h)}: run tools/gen_f32_names.py"
        for out, h in OUTPUTS.items()
        if not (root / out).is_file() or (root / out).read_text() != render(out, h, root)
    ]


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--check", action="store_true", help="compare instead of writing")
    args = ap.parse_args(argv)
    if args.check:
        problems = check()
        for p in problems:
            print(p, file=sys.stderr)
        if not problems:
            print("f32 names: both rename headers agree with the declarations")
        return 1 if problems else 0
    for out, headers in OUTPUTS.items():
        text = render(out, headers, ROOT)
        path = ROOT / out
        if not path.is_file() or path.read_text() != text:
            path.write_text(text)
            print(f"wrote {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())

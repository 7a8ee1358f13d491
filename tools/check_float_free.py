#!/usr/bin/env python3
"""Float-free check of the Cortex-M3 image's executor tick: builds the cortex-m3 preset's fs_pil
(unless --no-build), disassembles the ELF (arm-none-eabi-objdump -d) and walks the call graph
from each root (default exec_tick_q_fx, the integer tick, and exec_contact_hold_ms_fx) over its
bl/blx/b targets, tail calls included. Fails (exit 1) if a software floating-point helper
(__aeabi_f*, __aeabi_d*, __*sf*, __*df*, __aeabi_[il]2[fd], __aeabi_ul2[fd]) or a libm function
is reachable, or if a root makes an indirect call (blx/bx to a register other than lr: its
target is unknown). As a control, it also walks the executor's start (exec_start_run_fx), which
must reach software double: otherwise the walk is not seeing calls and the check fails too.

usage: tools/check_float_free.py [--build-dir build/cortex-m3] [--no-build] [--root NAME ...]
"""

from __future__ import annotations

import argparse
import re
import subprocess
import sys
from collections import deque
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
FLOAT_HELPER = re.compile(
    r"^(__aeabi_[fd]\w*|__aeabi_u?[il]2[fd]|__\w*[sd]f\w*|"
    r"(floor|ceil|ldexp|frexp|sqrt|exp|log|sin|cos|pow|fabs|round|lround|llround|fmod)f?)$"
)
FUNC_RE = re.compile(r"^([0-9a-f]+) <([^>]+)>:$")
CALL_RE = re.compile(
    r"\t(bl|blx|b|b\.w|b\.n|beq\.w|bne\.w|b[a-z]{2}(?:\.w|\.n)?)\s+[0-9a-f]+ <([^>+]+)(\+0x[0-9a-f]+)?>"
)
INDIRECT_RE = re.compile(r"\t(blx|bx)\s+(r\d+|ip|sl|fp)\b")


def disassemble(objdump: str, elf: Path) -> tuple[dict[str, set[str]], dict[str, list[str]]]:
    """Each function's call/tail-call targets and its indirect branches, from the disassembly."""
    out = subprocess.run([objdump, "-d", str(elf)], check=True, capture_output=True, text=True)
    edges: dict[str, set[str]] = {}
    indirect: dict[str, list[str]] = {}
    fn = ""
    for line in out.stdout.splitlines():
        m = FUNC_RE.match(line)
        if m:
            fn = m.group(2)
            edges.setdefault(fn, set())
            indirect.setdefault(fn, [])
            continue
        if not fn:
            continue
        c = CALL_RE.search(line)
        if c and c.group(2) != fn:
            edges[fn].add(c.group(2))
        i = INDIRECT_RE.search(line)
        if i:
            indirect[fn].append(line.strip())
    return edges, indirect


def reachable(edges: dict[str, set[str]], root: str) -> tuple[dict[str, str | None], set[str]]:
    """The functions reachable from root (each with the caller it was first reached from)."""
    parent: dict[str, str | None] = {root: None}
    queue = deque([root])
    while queue:
        f = queue.popleft()
        for g in sorted(edges.get(f, ())):
            if g not in parent:
                parent[g] = f
                queue.append(g)
    return parent, set(parent)


def path_to(parent: dict[str, str | None], f: str) -> str:
    chain = [f]
    while parent[chain[-1]] is not None:
        chain.append(parent[chain[-1]] or "")
    return " < ".join(chain)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--build-dir", default=str(ROOT / "build" / "cortex-m3"))
    ap.add_argument("--no-build", action="store_true", help="check the ELF as it is")
    ap.add_argument("--objdump", default="arm-none-eabi-objdump")
    ap.add_argument("--root", action="append", help="function(s) to check (exec_tick_q_fx)")
    ap.add_argument("--control", default="exec_start_run_fx", help="must reach software float")
    a = ap.parse_args()
    build = Path(a.build_dir)
    if not a.no_build:
        if not (build / "build.ninja").exists():
            subprocess.run(["cmake", "--preset", "cortex-m3"], cwd=ROOT, check=True)
        subprocess.run(
            ["cmake", "--build", str(build), "--target", "fs_pil", "-j2"],
            cwd=ROOT,
            check=True,
        )
    elf = build / "hil_sim" / "pil" / "fs_pil.elf"
    edges, indirect = disassemble(a.objdump, elf)
    ok = True
    for root in a.root or ["exec_tick_q_fx", "exec_contact_hold_ms_fx"]:
        if root not in edges:
            print(f"float-free {elf.name}: {root} not in the image")
            return 1
        parent, fns = reachable(edges, root)
        bad = sorted(f for f in fns if FLOAT_HELPER.match(f))
        ind = [(f, x) for f in sorted(fns) for x in indirect.get(f, [])]
        print(f"float-free {elf.name} {root}: {len(fns)} functions reachable: " + " ".join(sorted(fns)))
        for f in bad:
            print(f"  software float reachable: {path_to(parent, f)}")
        for f, x in ind:
            print(f"  indirect branch in {f}: {x}")
        ok = ok and not bad and not ind
    parent, fns = reachable(edges, a.control)
    ctl = sorted(f for f in fns if FLOAT_HELPER.match(f))
    print(f"control {a.control}: {len(ctl)} software float functions reachable ({' '.join(ctl[:6])} ...)")
    if not ctl:
        print("  the walk found no software float in the control: the call graph is not seen")
        ok = False
    print("float-free check: " + ("PASS" if ok else "FAIL"))
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/env python3
"""Post-link report of a Cortex-M image: flash/RAM size, a heap check and the worst-case stack
per entry point.

- size: `arm-none-eabi-size -A`; flash = sections loaded into FLASH (.text, .ARM.exidx, .data
  image), RAM = .data + .bss + .stack.
- heap: the link wraps malloc & co. to undefined symbols, so a reference already fails the link;
  this also fails the build if any of them (or __wrap_ variants) appears in the symbol table.
- stack: GCC's -fcallgraph-info=su writes one .ci (VCG) file per object with each function's
  frame size and its calls. The worst case of an entry point is its frame plus the worst callee,
  over the call graph (which must be acyclic: recursion fails the build). Functions without .ci
  information (libgcc, libm, libc) get their frame from their prologue in the disassembly
  (push/vpush/sub sp) and their calls from their bl/b.w targets: marked "(prologue)".
"""

import argparse
import os
import re
import subprocess
import sys

ENTRY_POINTS = [
    "Reset_Handler",
    "SysTick_Handler",
    "UART0RX_Handler",
    "UART0TX_Handler",
    "NMI_Handler",
    "HardFault_Handler",
    "Default_Handler",
    "app_tick",
]


def run(cmd):
    return subprocess.run(cmd, check=True, capture_output=True, text=True).stdout


def size_report(size_tool, elf, target):
    out = run([size_tool, "-A", elf])
    sec = {}
    for line in out.splitlines():
        parts = line.split()
        if len(parts) >= 3 and parts[0].startswith(".") and parts[1].isdigit():
            sec[parts[0]] = int(parts[1])
    flash = sec.get(".text", 0) + sec.get(".ARM.exidx", 0) + sec.get(".data", 0)
    ram = sec.get(".data", 0) + sec.get(".bss", 0) + sec.get(".stack", 0)
    print(
        f"size {os.path.basename(elf)} target={target} flash={flash} ram={ram} "
        f"(text={sec.get('.text', 0)} data={sec.get('.data', 0)} bss={sec.get('.bss', 0)} "
        f"stack_reserved={sec.get('.stack', 0)})"
    )


def heap_check(nm_tool, elf, heap_syms):
    out = run([nm_tool, elf])
    names = set()
    for line in out.splitlines():
        parts = line.split()
        if parts:
            names.add(parts[-1])
    bad = sorted(
        n
        for n in names
        if n in heap_syms
        or (n.startswith("__wrap_") and n[7:] in heap_syms)
        or (n.startswith("__real_") and n[7:] in heap_syms)
    )
    if bad:
        print(f"heap check FAILED: {os.path.basename(elf)} references {' '.join(bad)}")
        sys.exit(1)
    print(f"heap check {os.path.basename(elf)}: no allocator symbol ({len(heap_syms)} checked)")
    return names


NODE_RE = re.compile(r'node:\s*\{\s*title:\s*"([^"]+)"\s*label:\s*"([^"]*)"')
EDGE_RE = re.compile(r'edge:\s*\{\s*sourcename:\s*"([^"]+)"\s*targetname:\s*"([^"]+)"')
SU_RE = re.compile(r"(\d+) bytes \((static|dynamic|dynamic,bounded)\)")


def load_callgraph(roots):
    frames, kinds, edges = {}, {}, {}
    for dirpath, _, files in (w for r in roots for w in os.walk(r)):
        for f in files:
            if not f.endswith(".ci"):
                continue
            with open(os.path.join(dirpath, f), encoding="utf-8", errors="replace") as fh:
                text = fh.read()
            for title, label in NODE_RE.findall(text):
                m = SU_RE.search(label.replace("\\n", "\n"))
                if m:
                    frames[title] = max(frames.get(title, 0), int(m.group(1)))
                    kinds[title] = m.group(2)
            for src, dst in EDGE_RE.findall(text):
                edges.setdefault(src, set()).add(dst)
    return frames, kinds, edges


FUNC_RE = re.compile(r"^[0-9a-f]+ <([^>]+)>:$")
CALL_RE = re.compile(r"\s(?:bl|blx|b\.w|b)\s+[0-9a-f]+ <([^>+]+)>")
PUSH_RE = re.compile(r"\s(?:push|stmdb\s+sp!,)\s*\{([^}]*)\}")
VPUSH_RE = re.compile(r"\svpush\s*\{([^}]*)\}")
SUBSP_RE = re.compile(r"\ssub(?:\.w)?\s+sp,\s*(?:sp,\s*)?#(\d+)")


def reg_count(reglist):
    n = 0
    for raw in reglist.split(","):
        part = raw.strip()
        if "-" in part:
            a, b = part.split("-")
            n += int(b.strip()[1:]) - int(a.strip()[1:]) + 1
        elif part:
            n += 1
    return n


def prologue_frames(objdump, elf, wanted):
    """Frame size and callees of library functions from the disassembly (first 12 lines)."""
    out = run([objdump, "-d", elf])
    frames, edges = {}, {}
    cur, lines = None, 0
    for line in out.splitlines():
        m = FUNC_RE.match(line)
        if m:
            cur, lines = m.group(1), 0
            if cur in wanted:
                frames[cur] = 0
            continue
        if cur not in wanted:
            continue
        lines += 1
        c = CALL_RE.search(line)
        if c and c.group(1) != cur:
            edges.setdefault(cur, set()).add(c.group(1))
        if lines <= 12:
            for rx, size in ((PUSH_RE, 4), (VPUSH_RE, 4)):
                p = rx.search(line)
                if p:
                    frames[cur] += size * reg_count(p.group(1))
            q = SUBSP_RE.search(line)
            if q:
                frames[cur] += int(q.group(1))
    return frames, edges


def worst_stack(fn, frames, edges, memo, stack, unknown):
    if fn in memo:
        return memo[fn]
    if fn in stack:
        print(f"stack report FAILED: recursion through {' -> '.join([*stack, fn])}")
        sys.exit(1)
    if fn not in frames:
        unknown.add(fn)
        return 0, [fn]
    stack.append(fn)
    best, path = 0, []
    for callee in sorted(edges.get(fn, ())):
        d, p = worst_stack(callee, frames, edges, memo, stack, unknown)
        if d > best:
            best, path = d, p
    stack.pop()
    memo[fn] = (frames[fn] + best, [fn, *path])
    return memo[fn]


def stack_report(roots, elf, names, objdump):
    frames, kinds, edges = load_callgraph(roots)
    dyn = sorted(f for f, k in kinds.items() if k == "dynamic")
    # library functions: frames from their prologues, transitively over their calls
    estimated = set()
    todo = {d for ds in edges.values() for d in ds if d not in frames and d in names}
    while todo:
        lib_frames, lib_edges = prologue_frames(objdump, elf, todo)
        frames.update(lib_frames)
        estimated.update(lib_frames)
        for k, v in lib_edges.items():
            edges.setdefault(k, set()).update(v)
        todo = {
            d
            for ds in lib_edges.values()
            for d in ds
            if d not in frames and d in names and d not in estimated
        }
    memo, unknown = {}, set()
    for ep in ENTRY_POINTS:
        if ep not in names or ep not in frames:
            continue  # absent, or an alias of Default_Handler (weak SysTick_Handler)
        depth, path = worst_stack(ep, frames, edges, memo, [], unknown)
        print(
            f"stack {os.path.basename(elf)} entry={ep} worst={depth} bytes via "
            f"{' > '.join(p + ('(prologue)' if p in estimated else '') for p in path)}"
        )
    if dyn:
        print(f"stack report FAILED: dynamic frames (VLA/alloca) in {' '.join(dyn)}")
        sys.exit(1)
    linked_unknown = sorted(u for u in unknown if u in names)
    if linked_unknown:
        print("stack: no frame information (counted 0): " + " ".join(linked_unknown))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--elf", required=True)
    ap.add_argument("--nm", required=True)
    ap.add_argument("--size", required=True)
    ap.add_argument("--objdump", required=True)
    ap.add_argument("--target", required=True)
    ap.add_argument(
        "--ci-dirs",
        required=True,
        nargs="+",
        help="object directories of the image (their .ci files form the call graph)",
    )
    ap.add_argument("--heap-syms", required=True)
    a = ap.parse_args()
    heap_syms = set(a.heap_syms.replace(";", " ").split())
    size_report(a.size, a.elf, a.target)
    names = heap_check(a.nm, a.elf, heap_syms)
    stack_report(a.ci_dirs, a.elf, names, a.objdump)


if __name__ == "__main__":
    main()

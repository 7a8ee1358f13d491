#!/usr/bin/env python3
"""Include check of the firmware layers: every `#include "..."` in firmware/ and hil_sim/ must
point to the same module or to a lower layer, and no header may include itself through others.

    base (codes, types)  <-  core (maths, numeric layer)  <-  fixed, hal
        <-  safety, storage, security, proto  <-  boot  <-  app  <-  ports  <-  hil_sim

Modules of one layer do not include each other. Some lower modules are open only in part (safety
and hal use only the core's fs_real.h), and a module's private header (app_internal.h) is open
only to its own files and the simulator. Prints the module graph; exit 1 on an upward or sideways
include, an include cycle, or an include that names an ambiguous header.
usage: tools/check_layers.py [--graph]
"""
from __future__ import annotations

import argparse
import re
import sys
from collections import defaultdict
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
RANK = {"base": 0, "core": 1, "fixed": 2, "hal": 2,
        "safety": 3, "storage": 3, "security": 3, "proto": 3,
        "boot": 4, "app": 5, "ports": 6, "hil_sim": 7}
# (from, to): the only headers of `to` that `from` may include
ONLY = {("safety", "core"): {"fs_real.h"}, ("hal", "core"): {"fs_real.h"}}
# a module's private headers: only these other modules may include them (the simulator is a
# white-box user of the application; ports use app.h)
PRIVATE = {"app_internal.h": {"hil_sim"}}
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)


def module(rel: Path) -> str:
    """Layer module of a file: the folder under firmware/ (target folders are ports)."""
    parts = rel.parts
    if parts[0] == "hil_sim":
        return "hil_sim"
    if parts[1] == "ports" or (parts[1] == "boot" and len(parts) > 3 and parts[2] == "cortex-m"):
        return "ports"
    return parts[1]


def sources(root: Path) -> list[Path]:
    out = []
    for top in ("firmware", "hil_sim"):
        out += [p.relative_to(root) for p in sorted((root / top).rglob("*"))
                if p.suffix in (".c", ".h")]
    return out


def resolve(inc: str, src: Path, by_name: dict[str, list[Path]], root: Path) -> Path | None:
    """The header an include names: beside the includer first, else the one file of that name
    (the one in the includer's module when several share it). None for a header not in the tree."""
    here = src.parent / inc
    if (root / here).is_file():
        return here
    found = by_name.get(Path(inc).name, [])
    if len(found) > 1:
        found = [f for f in found if module(f) == module(src)] or found
    if len(found) > 1:
        raise LookupError(f"{src}: #include \"{inc}\" is ambiguous: {', '.join(map(str, found))}")
    return found[0] if found else None


def cycles(edges: dict[Path, set[Path]]) -> list[list[Path]]:
    """Include cycles between files (iterative depth-first search, one cycle per back edge)."""
    state: dict[Path, int] = {}
    found = []
    for start in sorted(edges):
        if start in state:
            continue
        stack = [(start, iter(sorted(edges.get(start, ()))))]
        path = [start]
        state[start] = 1
        while stack:
            node, it = stack[-1]
            nxt = next(it, None)
            if nxt is None:
                state[node] = 2
                stack.pop()
                path.pop()
            elif state.get(nxt) == 1:
                found.append(path[path.index(nxt):] + [nxt])
            elif nxt not in state:
                state[nxt] = 1
                stack.append((nxt, iter(sorted(edges.get(nxt, ())))))
                path.append(nxt)
    return found


def check(root: Path = ROOT) -> tuple[list[str], dict[tuple[str, str], set[str]]]:
    """Violations (one line each) and the module graph {(from, to): headers}."""
    files = sources(root)
    by_name: dict[str, list[Path]] = defaultdict(list)
    for f in files:
        by_name[f.name].append(f)
    problems: list[str] = []
    graph: dict[tuple[str, str], set[str]] = defaultdict(set)
    edges: dict[Path, set[Path]] = defaultdict(set)
    for src in files:
        for m in INCLUDE.finditer((root / src).read_text(errors="replace")):
            try:
                dst = resolve(m.group(1), src, by_name, root)
            except LookupError as e:
                problems.append(str(e))
                continue
            if dst is None:
                continue
            edges[src].add(dst)
            a, b = module(src), module(dst)
            if a == b:
                continue
            graph[(a, b)].add(dst.name)
            if a not in RANK or b not in RANK:
                problems.append(f"{src}: module {a if a not in RANK else b} has no layer")
            elif RANK[b] >= RANK[a]:
                kind = "sideways" if RANK[b] == RANK[a] else "upward"
                problems.append(f"{src}: {kind} include of {dst} ({a} -> {b})")
            elif dst.name in PRIVATE and a not in PRIVATE[dst.name]:
                problems.append(f"{src}: {dst.name} is private to {b} (use {b}.h)")
            elif (a, b) in ONLY and dst.name not in ONLY[(a, b)]:
                problems.append(f"{src}: {a} may use only {', '.join(sorted(ONLY[(a, b)]))} "
                                f"of {b}, not {dst.name}")
    for c in cycles(edges):
        problems.append("include cycle: " + " -> ".join(map(str, c)))
    return problems, graph


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--graph", action="store_true", help="print every module edge and header")
    args = ap.parse_args(argv)
    problems, graph = check()
    if args.graph:
        for (a, b), names in sorted(graph.items(), key=lambda kv: (RANK.get(kv[0][0], 99), kv[0])):
            print(f"  {a:8} -> {b:8} {' '.join(sorted(names))}")
    for p in problems:
        print(p, file=sys.stderr)
    print(f"layers: {len(graph)} module edges, {len(problems)} violations "
          "(upward/sideways includes, cycles)")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/env python3
"""Include check of the firmware layers: every `#include "..."` in firmware/ and hil_sim/ must
point to the same module or to a lower layer, and no header may include itself through others.

    base (codes, types)  <-  core (maths, numeric layer)  <-  fixed, hal
        <-  safety, storage, security, proto, control  <-  boot  <-  app  <-  ports  <-  hil_sim

Modules of one layer do not include each other. Some lower modules are open only in part (safety
and hal use only the core's fs_real.h), and a module's private header (app_internal.h) is open
only to its own files. Inside a
firmware folder the .c files call each other without a circle (a file that calls another's
function sits above it), so each file's concern has one direction. The host package
host/forceskill is checked the same way on its imports (those inside functions too):

    codes, errors, outputs, sim  <-  wire  <-  readers  <-  model  <-  link  <-  plot  <-  commands  <-  cli

(wire: the constants and payload codecs generated from wire.toml, the DBC and the telemetry
pairing, which the CAN-log reader and the link both use), with no exception, and no module
imports itself through others.

No firmware file depends on the simulator at link time either: a firmware source that names a
function or variable hil_sim defines (with external linkage) and no firmware file defines is an
upward link edge (the port declares what it needs, e.g. cm_plant.h, and hil_sim implements it).
`--objects BUILD_DIR` checks the same on a build's object files (nm): an undefined symbol of an
object built from firmware/ that only an object built from hil_sim/ defines.

Prints the module graph; exit 1 on an upward or sideways include, import or link edge, a cycle
(of includes, or of calls between the files of a folder), or an include that names an ambiguous
header.
usage: tools/check_layers.py [--graph] [--objects BUILD_DIR]...
"""

from __future__ import annotations

import argparse
import ast
import re
import shutil
import subprocess
import sys
from collections import defaultdict
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
RANK = {
    "base": 0,
    "core": 1,
    "fixed": 2,
    "hal": 2,
    "safety": 3,
    "storage": 3,
    "security": 3,
    "proto": 3,
    "control": 3,
    "boot": 4,
    "app": 5,
    "ports": 6,
    "hil_sim": 7,
}
# (from, to): the only headers of `to` that `from` may include
ONLY = {("safety", "core"): {"fs_real.h"}, ("hal", "core"): {"fs_real.h"}}
# a module's private headers: only these other modules or files may include them (the simulator
# configures the application through app_config.h, ports use app.h)
PRIVATE: dict[str, set[str]] = {"app_internal.h": set()}
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)
# a function defined at file level with external linkage: its name (a definition's line starts
# with its return type, not with `static`)
DEFINITION = re.compile(r"^(?!static\b)[A-Za-z_][\w \t*]*?\b([A-Za-z_]\w*)\s*\([^;{}]*\)\s*\{", re.M)
COMMENT = re.compile(r"/\*.*?\*/|//[^\n]*|\"(?:\\.|[^\"\\])*\"", re.S)
# a variable defined at file level with external linkage (`T name = ...;`, `T name[N];`)
DATA = re.compile(
    r"^(?!static\b|extern\b|typedef\b|return\b)(?:const\s+)?[A-Za-z_]\w*[\s*]+(?:const\s+)?([A-Za-z_]\w*)"
    r"\s*(?:\[[^\]]*\])?\s*(?:=|;)",
    re.M,
)


def module(rel: Path) -> str:
    """Layer module of a file: the folder under firmware/ (target folders are ports)."""
    parts = rel.parts
    if parts[0] == "hil_sim":
        return "hil_sim"
    if parts[1] == "ports":
        return "ports"
    return parts[1]


def sources(root: Path) -> list[Path]:
    out = []
    for top in ("firmware", "hil_sim"):
        out += [p.relative_to(root) for p in sorted((root / top).rglob("*")) if p.suffix in (".c", ".h")]
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
        raise LookupError(f'{src}: #include "{inc}" is ambiguous: {", ".join(map(str, found))}')
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
                found.append([*path[path.index(nxt) :], nxt])
            elif nxt not in state:
                state[nxt] = 1
                stack.append((nxt, iter(sorted(edges.get(nxt, ())))))
                path.append(nxt)
    return found


def call_edges(files: list[Path], root: Path) -> dict[Path, set[Path]]:
    """Calls between the .c files of each firmware folder: file a -> file b when a calls a
    function b defines (a shared private header such as app_internal.h hides such a circle from
    the include graph)."""
    edges: dict[Path, set[Path]] = defaultdict(set)
    by_dir: dict[Path, list[Path]] = defaultdict(list)
    for f in files:
        if f.suffix == ".c" and f.parts[0] == "firmware":
            by_dir[f.parent].append(f)
    for group in by_dir.values():
        text = {f: COMMENT.sub(" ", (root / f).read_text(errors="replace")) for f in group}
        owner = {m.group(1): f for f in group for m in DEFINITION.finditer(text[f])}
        for f in group:
            for name in set(re.findall(r"\b([A-Za-z_]\w*)\s*\(", text[f])):
                g = owner.get(name)
                if g is not None and g != f:
                    edges[f].add(g)
    return edges


def defined_names(text: str) -> set[str]:
    """Functions and variables a C file (comments and strings removed) defines with external linkage."""
    names = {m.group(1) for m in DEFINITION.finditer(text)} | {m.group(1) for m in DATA.finditer(text)}
    return names - {"main"}


def link_edges(files: list[Path], root: Path) -> list[str]:
    """Firmware files that name a function or variable defined (with external linkage) only in
    hil_sim: firmware -> hil_sim at link time, one line each."""
    text = {f: COMMENT.sub(" ", (root / f).read_text(errors="replace")) for f in files}
    sim: dict[str, Path] = {}
    fw: set[str] = set()
    for f in files:
        if f.suffix != ".c":
            continue
        for name in defined_names(text[f]):
            if f.parts[0] == "hil_sim":
                sim.setdefault(name, f)
            else:
                fw.add(name)
    upward = {n: f for n, f in sim.items() if n not in fw}
    out = []
    for f in files:
        if f.parts[0] != "firmware":
            continue
        for name in sorted(set(re.findall(r"\b[A-Za-z_]\w*\b", text[f])) & set(upward)):
            out.append(f"{f}: upward link edge: {name} is defined in {upward[name]} (firmware -> hil_sim)")
    return out


def object_symbols(build: Path, nm: str = "nm") -> dict[str, tuple[set[str], set[str]]]:
    """{"firmware" | "hil_sim": (defined, undefined)}: the global symbols of a build's objects, by
    the source folder their build folder mirrors (build/<preset>/firmware/..., .../hil_sim/...)."""
    out: dict[str, tuple[set[str], set[str]]] = {"firmware": (set(), set()), "hil_sim": (set(), set())}
    nested = {c.parent for c in build.rglob("CMakeCache.txt") if c.parent != build}  # other builds
    objs = [p for p in sorted(build.rglob("*")) if p.suffix in (".o", ".obj") and p.is_file()]
    for obj in objs:
        if any(d in obj.parents for d in nested):
            continue
        rel = obj.relative_to(build).parts
        side = "hil_sim" if "hil_sim" in rel else "firmware" if "firmware" in rel else None
        if side is None:
            continue
        res = subprocess.run([nm, "-g", str(obj)], capture_output=True, text=True)
        for line in res.stdout.splitlines():
            parts = line.split()
            if len(parts) == 2 and parts[0] == "U":
                out[side][1].add(parts[1])
            elif len(parts) == 3 and parts[1] not in ("U", "w", "v"):
                out[side][0].add(parts[2])
    return out


def check_objects(build: Path, nm: str = "nm") -> list[str]:
    """Undefined symbols of objects built from firmware/ that only objects from hil_sim/ define."""
    syms = object_symbols(build, nm)
    fw_def, fw_undef = syms["firmware"]
    sim_def = syms["hil_sim"][0]
    return [
        f"{build}: upward link edge: firmware objects use {s}, defined only in hil_sim (firmware -> hil_sim)"
        for s in sorted((fw_undef & sim_def) - fw_def - {"main"})
    ]


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
            elif dst.name in PRIVATE and not {a, str(src)} & PRIVATE[dst.name]:
                problems.append(f"{src}: {dst.name} is private to {b} (use {b}.h)")
            elif (a, b) in ONLY and dst.name not in ONLY[(a, b)]:
                problems.append(
                    f"{src}: {a} may use only {', '.join(sorted(ONLY[(a, b)]))} of {b}, not {dst.name}"
                )
    for c in cycles(edges):
        problems.append("include cycle: " + " -> ".join(map(str, c)))
    for c in cycles(call_edges(files, root)):
        problems.append("call cycle between the files of a module: " + " -> ".join(map(str, c)))
    problems += link_edges(files, root)
    return problems, graph


# ---- host package ------------------------------------------------------------------------------

HOST_PKG = "forceskill"
HOST_RANK = {"base": 0, "wire": 1, "readers": 2, "model": 3, "link": 4, "plot": 5, "commands": 6, "cli": 7}
HOST_BASE = {"forceskill", "forceskill.codes", "forceskill.errors", "forceskill.outputs", "forceskill.sim"}


def host_layer(mod: str) -> str | None:
    """Layer of a module of the host package; None for a module no layer names."""
    if mod in HOST_BASE:
        return "base"
    parts = mod.split(".")
    if len(parts) >= 2 and parts[1] in ("wire", "readers", "model", "link", "commands"):
        return parts[1]
    return {"forceskill.plot": "plot", "forceskill.cli": "cli", "forceskill.__main__": "cli"}.get(mod)


def host_modules(pkg_dir: Path) -> dict[str, Path]:
    """Every module of the package under pkg_dir (host/forceskill), by dotted name."""
    out = {}
    for p in sorted(pkg_dir.rglob("*.py")):
        parts = (pkg_dir.name, *p.relative_to(pkg_dir).with_suffix("").parts)
        if parts[-1] == "__init__":
            parts = parts[:-1]
        out[".".join(parts)] = p
    return out


def host_imports(mod: str, path: Path, known: dict[str, Path]) -> set[str]:
    """Modules of the package that a module imports, anywhere in it (functions included)."""
    pkg = mod if path.name == "__init__.py" else mod.rpartition(".")[0]
    found: set[str] = set()
    for node in ast.walk(ast.parse(path.read_text(), str(path))):
        if isinstance(node, ast.Import):
            names = [a.name for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = pkg.split(".")[: len(pkg.split(".")) - node.level + 1]
                target = ".".join(base + ([node.module] if node.module else []))
            else:
                target = node.module or ""
            subs = [f"{target}.{a.name}" for a in node.names if f"{target}.{a.name}" in known]
            names = subs if subs and len(subs) == len(node.names) else [target, *subs]
        else:
            continue
        for name in names:
            n = name
            while n and n not in known and "." in n:
                n = n.rpartition(".")[0]
            if n in known and n != mod:
                found.add(n)
    return found


def check_host(root: Path = ROOT) -> tuple[list[str], dict[tuple[str, str], set[str]]]:
    """Violations of the host package's layers (one line each) and its layer graph {(from, to): modules}."""
    pkg_dir = root / "host" / HOST_PKG
    if not pkg_dir.is_dir():
        return [f"{pkg_dir}: the host package is missing"], {}
    known = host_modules(pkg_dir)
    problems: list[str] = []
    graph: dict[tuple[str, str], set[str]] = defaultdict(set)
    edges: dict[Path, set[Path]] = defaultdict(set)
    for mod, path in known.items():
        a = host_layer(mod)
        if a is None:
            problems.append(f"{mod}: module has no layer (add it to tools/check_layers.py)")
            continue
        for dst in sorted(host_imports(mod, path, known)):
            edges[Path(mod)].add(Path(dst))
            b = host_layer(dst)
            if b is None or a == b:
                continue
            graph[(a, b)].add(dst)
            if HOST_RANK[b] >= HOST_RANK[a]:
                kind = "sideways" if HOST_RANK[b] == HOST_RANK[a] else "upward"
                problems.append(f"{mod}: {kind} import of {dst} ({a} -> {b})")
    for c in cycles(edges):
        problems.append("import cycle: " + " -> ".join(map(str, c)))
    return problems, graph


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--graph", action="store_true", help="print every module edge and header")
    ap.add_argument(
        "--objects",
        action="append",
        default=[],
        metavar="BUILD_DIR",
        help="also check a build's object files (nm) for firmware -> hil_sim symbols",
    )
    ap.add_argument(
        "--nm", default=None, help="nm program (default: arm-none-eabi-nm for a cross build, else nm)"
    )
    args = ap.parse_args(argv)
    problems, graph = check()
    for b in args.objects:
        build = Path(b)
        cross = (
            "arm-none-eabi" in (build / "CMakeCache.txt").read_text()
            if (build / "CMakeCache.txt").is_file()
            else False
        )
        nm = args.nm or ("arm-none-eabi-nm" if cross and shutil.which("arm-none-eabi-nm") else "nm")
        problems += check_objects(build, nm)
    host_problems, host_graph = check_host()
    if args.graph:
        for (a, b), names in sorted(graph.items(), key=lambda kv: (RANK.get(kv[0][0], 99), kv[0])):
            print(f"  {a:8} -> {b:8} {' '.join(sorted(names))}")
        for (a, b), names in sorted(host_graph.items(), key=lambda kv: HOST_RANK[kv[0][0]]):
            print(f"  host {a:8} -> {b:8} {' '.join(sorted(names))}")
    for p in problems + host_problems:
        print(p, file=sys.stderr)
    print(
        f"layers: {len(graph)} module edges, {len(problems)} violations "
        "(upward/sideways includes, firmware -> hil_sim link edges, cycles)"
    )
    print(
        f"host layers: {len(host_graph)} layer edges, {len(host_problems)} violations "
        "(upward/sideways imports, cycles)"
    )
    return 1 if problems or host_problems else 0


if __name__ == "__main__":
    sys.exit(main())

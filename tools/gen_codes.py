#!/usr/bin/env python3
"""Write every file that carries a numbered code or identifier from the one table,
firmware/base/codes.toml: the C headers in firmware/base/, host/forceskill/codes.py,
docs/codes.md, and the marked tables of docs/protocol.md, docs/safety.md and docs/update.md
(between `<!-- begin codes:NAME ... -->` and `<!-- end codes:NAME -->`; the text around them is
kept); and, from the table beside it, firmware/base/wire.toml, the shared constants and the UDS
payload codecs (tools/gen_wire.py: firmware/base/fs_wire_const.h,
firmware/proto/generated/fs_wire.{c,h}, host/forceskill/wire/generated.py). Standard library
only (tomllib, Python 3.11+).

usage: tools/gen_codes.py            write the files
       tools/gen_codes.py --check    exit 1 (one line per file) if a file differs from the table,
                                     or the DBC's frame identifiers (or its HostCommand scale
                                     factors) differ from the tables's
"""

from __future__ import annotations

import argparse
import importlib.util
import re
import sys
import textwrap
from pathlib import Path

import tomllib

ROOT = Path(__file__).resolve().parents[1]
TABLE = "firmware/base/codes.toml"
BASE = "firmware/base"
PY_OUT = "host/forceskill/codes.py"
DOC_OUT = "docs/codes.md"
DBC = "firmware/proto/forceskill.dbc"
# the marked regions each document holds, in order
DOC_REGIONS = {
    "docs/protocol.md": ["can_ids", "routines", "dids", "nrcs"],
    "docs/safety.md": ["faults", "results"],
    "docs/update.md": ["update_nrcs"],
}
STAMP = f"generated from {TABLE} by tools/gen_codes.py; do not edit"
WIDTH = 100


def _wire():  # type: ignore[no-untyped-def]
    """tools/gen_wire.py: the constants and UDS payload codecs of firmware/base/wire.toml."""
    spec = importlib.util.spec_from_file_location("gen_wire", Path(__file__).with_name("gen_wire.py"))
    assert spec is not None and spec.loader is not None
    mod = importlib.util.module_from_spec(spec)
    sys.modules.setdefault("gen_wire", mod)
    spec.loader.exec_module(mod)
    return mod


class TableError(Exception):
    """The table contradicts itself (duplicate value or name, unordered rows, bad fault range)."""


def _rows(group: dict) -> list[tuple[int, str, str, str]]:
    out = []
    for row in group["codes"]:
        value, name, text = row[0], row[1], row[2]
        short = row[3] if len(row) > 3 else ""
        out.append((int(value), str(name), str(text), str(short)))
    return out


def validate(table: dict) -> None:
    """Every code value and name once, rows ascending, faults consecutive (they index a bitmask)."""
    seen_v: dict[int, str] = {}
    seen_n: set[str] = set()
    for g in table["status"]:
        rows = _rows(g)
        values = [r[0] for r in rows]
        if values != sorted(values):
            raise TableError(f"{g['title']}: codes not in ascending order")
        for value, name, _, _ in rows:
            if value in seen_v:
                raise TableError(f"code {value} is both {seen_v[value]} and {name}")
            if name in seen_n:
                raise TableError(f"name {name} used twice")
            seen_v[value] = name
            seen_n.add(name)
        if "bitmask" in g and values != list(range(values[0], values[0] + len(values))):
            raise TableError(f"{g['title']}: bitmask codes must be consecutive")
        if "bitmask" in g and len(values) > 32:
            raise TableError(f"{g['title']}: more than 32 bitmask codes")
    names = [r[1] for r in table["uds"]["ids"]] + [r[1] for r in table["can"]["ids"]]
    if len(names) != len(set(names)):
        raise TableError("an identifier name is used twice")
    _validate_docs(table, seen_n)


def _same_keys(what: str, have: set[str], want: set[str]) -> None:
    if have != want:
        extra, missing = sorted(have - want), sorted(want - have)
        raise TableError(f"{what}: no such name {extra}" if extra else f"{what}: missing {missing}")


def _validate_docs(table: dict, code_names: set[str]) -> None:
    """Every documented row has its doc entry, every doc entry a row; NRC values once, and every
    NRC a code maps to is in the NRC table."""
    can = table["can"]
    _same_keys("[can.doc]", set(can["doc"]), {r[1] for r in can["ids"]})
    uds = table["uds"]
    _same_keys("[uds.doc]", set(uds["doc"]), {r[1] for r in uds["ids"] if r[3] in ("DID", "RID")})
    nrcs = [int(r[0]) for r in uds["nrc"]["codes"]]
    if len(nrcs) != len(set(nrcs)) or nrcs != sorted(nrcs):
        raise TableError("[uds.nrc]: values repeated or not ascending")
    for g in table["status"]:
        names = {r[1] for r in _rows(g)}
        if "doc" in g:
            _same_keys(f"{g['title']}: [status.doc]", set(g["doc"]), names)
        if "nrc" in g:
            mapped = {k: v for k, v in g["nrc"].items() if k != "nrc_default"}
            if not set(mapped) <= names:
                raise TableError(f"{g['title']}: [status.nrc] names {sorted(set(mapped) - names)}")
            for v in [*mapped.values(), g["nrc"]["nrc_default"]]:
                if int(v) not in nrcs:
                    raise TableError(f"{g['title']}: NRC 0x{int(v):02X} not in [uds.nrc]")


def py_name(group: dict, name: str) -> str:
    strip = group.get("py_strip", "")
    return name[len(strip) :] if strip and name.startswith(strip) else name


def _c_line(code: str, text: str, column: int) -> list[str]:
    """`code  /* text */` when it fits the width, else the comment on the lines before."""
    one = f"{code:<{column}} /* {text} */"
    if len(one) <= WIDTH:
        return [one]
    indent = code[: len(code) - len(code.lstrip())]
    wrapped = textwrap.wrap(text, WIDTH - len(indent) - 6)
    body = [f"{indent}/* {wrapped[0]}"] + [f"{indent} * {w}" for w in wrapped[1:]]
    body[-1] += " */"
    return [*body, code]


def _guard(header: str) -> str:
    return re.sub(r"[^A-Z0-9]", "_", header.upper())


def _c_file(header: str, what: str, body: list[str], includes: list[str]) -> str:
    g = _guard(header)
    lines = [f"/* {what}", f" * {STAMP}. */", f"#ifndef {g}", f"#define {g}", ""]
    if includes:
        lines += [f"#include {i}" for i in includes] + [""]
    lines += body
    lines += [f"#endif /* {g} */", ""]
    return "\n".join(lines)


def c_status_headers(table: dict) -> dict[str, str]:
    """One header per `header` of the status groups (several groups may share one)."""
    by_header: dict[str, list[dict]] = {}
    for g in table["status"]:
        if "header" in g:
            by_header.setdefault(g["header"], []).append(g)
    out = {}
    for header, groups in by_header.items():
        body: list[str] = []
        includes: list[str] = []
        for g in groups:
            body += _doc_comment(g["title"])
            body.append("typedef enum {")
            body.append(f"    {g['ok']} = 0,")
            sections = {int(v): t for v, t in g.get("sections", [])}
            column = max(len(f"    {r[1]} = {r[0]},") for r in _rows(g))
            for value, name, text, _ in _rows(g):
                if value in sections:
                    body += ["", f"    /* {sections[value]} */"]
                body += _c_line(f"    {name} = {value},", text, column)
            body += [f"}} {g['enum']};", ""]
            if "bitmask" in g:
                p = g["bitmask"]
                rows = _rows(g)
                includes.append("<stdint.h>")
                body += [
                    f"#define {p}_CODE_FIRST {rows[0][0]}u",
                    f"#define {p}_COUNT {len(rows)}u /* codes {p}_CODE_FIRST .. {p}_CODE_FIRST + "
                    f"{p}_COUNT - 1 */",
                    "",
                    f"/** Bit of a code in a cause/latched mask (0 for {g['ok']} or an unknown code). */",
                    f"#define {p}_BIT(code) \\",
                    f"    (((uint32_t)(code) >= {p}_CODE_FIRST && (uint32_t)(code) < {p}_CODE_FIRST"
                    f" + {p}_COUNT) \\",
                    f"         ? (1u << ((uint32_t)(code) - {p}_CODE_FIRST)) : 0u)",
                    "",
                ]
            if "nrc" in g:
                includes += [i for i in ("<stdint.h>", '"uds_nrc.h"') if i not in includes]
                body += _c_nrc_function(table, g)
        what = "; ".join(g["title"].split(" (")[0] for g in groups)
        out[header] = _c_file(header, f"Status codes: {what}.", body, includes)
    return out


def _c_nrc_function(table: dict, g: dict) -> list[str]:
    """`<prefix>_status_nrc()`: the UDS negative response code of each status of the group."""
    fn = g["enum"].removesuffix("_t") + "_nrc"
    nrc = g["nrc"]
    c_name = {int(v): n for v, n, _, _ in table["uds"]["nrc"]["codes"]}
    body = [
        f"/** The UDS negative response code of a status (UDS_NRC_OK for {g['ok']}). */",
        f"static inline uint8_t {fn}({g['enum']} st)",
        "{",
        "    switch (st) {",
        f"    case {g['ok']}: return UDS_NRC_OK;",
    ]
    for _, name, _, _ in _rows(g):
        if name in nrc:
            body.append(f"    case {name}: return {c_name[int(nrc[name])]};")
    body += [f"    default: return {c_name[int(nrc['nrc_default'])]};", "    }", "}", ""]
    return body


def c_uds_nrc(table: dict) -> str:
    body = ["#define UDS_NRC_OK 0x00u /* positive response */"]
    for value, name, iso, _ in table["uds"]["nrc"]["codes"]:
        body += _c_line(f"#define {name} 0x{int(value):02X}u", iso, 44)
    body.append("")
    return _c_file(
        "uds_nrc.h",
        "UDS negative response codes the device answers (ISO 14229-1 values; docs/protocol.md).",
        body,
        [],
    )


def _doc_comment(text: str) -> list[str]:
    wrapped = textwrap.wrap(text + ".", WIDTH - 4)
    if len(wrapped) == 1:
        return [f"/** {wrapped[0]} */"]
    return [f"/** {wrapped[0]}"] + [f" *  {w}" for w in wrapped[1:-1]] + [f" *  {wrapped[-1]} */"]


def c_proto_ids(table: dict) -> str:
    can = table["can"]
    body = [
        f"#define PROTO_NODE_MAX {can['node_max']}u",
        f"#define PROTO_DEFAULT_NODE {can['default_node']}u",
        "",
    ]
    for value, name, _, _, text in can["ids"]:
        body += _c_line(f"#define PROTO_ID_{name}(node) (0x{value:03X}u + (uint32_t)(node))", text, 0)
    body.append("")
    return _c_file(
        "proto_ids.h",
        "CAN identifiers of one node: id = base + node, node 0.."
        "PROTO_NODE_MAX (docs/codes.md);\n * the DBC lists the cyclic frames of node 0 "
        "with the same bases.",
        body,
        ["<stdint.h>", '"proto_status.h"'],
    )


def c_uds_ids(table: dict) -> str:
    body = []
    kind = None
    for value, name, _, k, text in table["uds"]["ids"]:
        if k != kind:
            if kind is not None:
                body.append("")
            kind = k
        digits = 8 if value > 0xFFFF else (4 if value > 0xFF else 2)
        body += _c_line(f"#define {name} 0x{value:0{digits}X}u", text, 38)
    body.append("")
    return _c_file(
        "fs_uds_ids.h",
        "UDS identifiers of the device: data identifiers (0x22/0x2E), "
        "routine identifiers (0x31),\n * security levels (0x27) and the firmware "
        "download address (0x34).",
        body,
        [],
    )


def python_module(table: dict) -> str:
    lines = [
        '"""Every numbered code and identifier of forceskill.',
        "",
        f"{STAMP[0].upper()}{STAMP[1:]}.",
        '"""',
        "from __future__ import annotations",
        "",
    ]
    names: list[str] = []
    for g in table["status"]:
        lines.append(f"# {g['title']}")
        for value, name, text, _ in _rows(g):
            n = py_name(g, name)
            names.append(n)
            entry = f"{n} = {value}  # {text}"
            lines.append(entry if len(entry) <= WIDTH else f"{n} = {value}")
        lines.append("")
        if "py_texts" in g:
            names.append(g["py_texts"])
            lines.append(f"{g['py_texts']}: dict[int, str] = {{")
            for value, _, _, short in _rows(g):
                if short:
                    lines.append(f"    {value}: {short!r},")
            lines += ["}", ""]
    can = table["can"]
    lines += [
        "# CAN identifiers of node 0; node n uses id + n",
        f"NODE_MAX = {can['node_max']}",
        f"DEFAULT_NODE = {can['default_node']}",
    ]
    names += ["NODE_MAX", "DEFAULT_NODE"]
    for value, _, n, _, text in can["ids"]:
        names.append(n)
        lines.append(f"{n} = 0x{value:03X}  # {text}")
    lines += ["", "# UDS identifiers of the device"]
    for value, _, n, _, text in table["uds"]["ids"]:
        names.append(n)
        digits = 8 if value > 0xFFFF else (4 if value > 0xFF else 2)
        entry = f"{n} = 0x{value:0{digits}X}  # {text}"
        lines.append(entry if len(entry) <= WIDTH else f"{n} = 0x{value:0{digits}X}")
    lines += ["", "# UDS negative response codes the device answers"]
    for value, name, iso, _ in table["uds"]["nrc"]["codes"]:
        n = name.removeprefix("UDS_")
        names.append(n)
        lines.append(f"{n} = 0x{int(value):02X}  # {iso}")
    for g in table["status"]:
        if "nrc" in g:
            n = g["enum"].removesuffix("_t").upper() + "_NRC"
            names.append(n)
            lines += [
                "",
                f"# {g['title']}: the negative response code of each status "
                f"(others: 0x{int(g['nrc']['nrc_default']):02X})",
                f"{n}: dict[int, int] = {{",
            ]
            for value, name, _, _ in _rows(g):
                if name in g["nrc"]:
                    lines.append(f"    {value}: 0x{int(g['nrc'][name]):02X},")
            lines.append("}")
    lines += ["", "__all__ = ["]
    lines += [f"    {n!r}," for n in names]
    lines += ["]", ""]
    return "\n".join(lines)


def _md_cell(text: str) -> str:
    return text.replace("|", "\\|")


def markdown(table: dict) -> str:
    out = [
        "# Codes and identifiers",
        "",
        f"<!-- {STAMP} -->",
        "",
        "Every numbered status code, CAN identifier and UDS identifier of the device and the "
        "host, "
        f"from one table (`{TABLE}`). `tools/gen_codes.py` writes the C headers "
        "(`firmware/base/*.h`), the host's constants (`host/forceskill/codes.py`, re-exported "
        "by `forceskill.errors`) and this page; `tools/gen_codes.py --check` (run by "
        "`scripts/test.sh`) fails when any of them differs from the table or the DBC's frame "
        "identifiers differ from the ones below. Codes are stable: never renumbered, only "
        "appended.",
        "",
        "The CLI prints a refusal as one line ending in `[code]` (`forceskill.errors.FsError`).",
        "",
    ]
    for g in table["status"]:
        where = f"`{g['header']}`, `{g['enum']}`" if "header" in g else "host only"
        out += [
            f"## {g['title']}",
            "",
            f"C: {where}.",
            "",
            "| code | name | host name | meaning |",
            "|---:|---|---|---|",
        ]
        for value, name, text, short in _rows(g):
            meaning = text + (f' (host text: "{short}")' if short else "")
            host = py_name(g, name)
            out.append(f"| {value} | `{name}` | `{host}` | {_md_cell(meaning)} |")
        out.append("")
    can = table["can"]
    out += [
        "## CAN identifiers",
        "",
        f"Node n (0..{can['node_max']}, default {can['default_node']}) uses base + n. C: "
        "`proto_ids.h`, `PROTO_ID_<name>(node)`.",
        "",
        "| base | C macro | host name | DBC frame | what |",
        "|---:|---|---|---|---|",
    ]
    for value, name, host, frame, text in can["ids"]:
        out.append(f"| 0x{value:03X} | `PROTO_ID_{name}` | `{host}` | {frame or '-'} | {_md_cell(text)} |")
    out += [
        "",
        "## UDS identifiers",
        "",
        "C: `fs_uds_ids.h`. Services and sessions are ISO 14229's "
        "(`firmware/proto/uds.h`, [protocol.md](protocol.md)).",
        "",
        "| value | kind | C name | host name | what |",
        "|---:|---|---|---|---|",
    ]
    for value, name, host, kind, text in table["uds"]["ids"]:
        digits = 8 if value > 0xFFFF else (4 if value > 0xFF else 2)
        out.append(f"| 0x{value:0{digits}X} | {kind} | `{name}` | `{host}` | {_md_cell(text)} |")
    out += [
        "",
        "## UDS negative response codes",
        "",
        "C: `uds_nrc.h`; the update path's mapping is `boot_status_nrc()` ([update.md](update.md)).",
        "",
    ]
    out += region_nrcs(table).splitlines()
    out.append("")
    return "\n".join(out)


# ---------------------------------------------------------------- marked regions of the docs


def _hex(value: int) -> str:
    digits = 8 if value > 0xFFFF else (4 if value > 0xFF else 2)
    return f"0x{value:0{digits}X}"


def _table(head: list[str], align: list[str], rows: list[list[str]]) -> str:
    lines = ["| " + " | ".join(head) + " |", "|" + "|".join(align) + "|"]
    lines += ["| " + " | ".join(_md_cell(c) for c in r) + " |" for r in rows]
    return "\n".join(lines)


def region_can_ids(table: dict) -> str:
    can = table["can"]
    rows = []
    for value, name, _, frame, _ in can["ids"]:
        d = can["doc"][name]
        rows.append([f"0x{value:03X} + n", frame or d["frame"], d["sender"], d["period"], d["protected"]])
    return _table(
        ["id", "frame", "sender", "period", "protected"], ["---:", "---", "---", "---", "---"], rows
    )


def _uds(table: dict, kind: str) -> list[tuple[int, str, str, dict]]:
    doc = table["uds"]["doc"]
    return [(v, n, text, doc[n]) for v, n, _, k, text in table["uds"]["ids"] if k == kind]


def region_routines(table: dict) -> str:
    rows = [[_hex(v), d["label"], d["start"], d["stop"], d["results"]] for v, _, _, d in _uds(table, "RID")]
    return _table(
        ["RID", "routine", "start data", "stop", "results"], ["---:", "---", "---", "---", "---"], rows
    )


def region_dids(table: dict) -> str:
    rows = [
        [_hex(v), d.get("content", text), str(d["length"]), d["write"]]
        for v, _, text, d in _uds(table, "DID")
    ]
    return _table(["DID", "content", "length", "write"], ["---:", "---", "---:", "---"], rows)


def region_nrcs(table: dict) -> str:
    rows = [[f"0x{int(v):02X}", f"`{n}`", iso, when] for v, n, iso, when in table["uds"]["nrc"]["codes"]]
    return _table(["NRC", "C name", "ISO 14229-1 name", "given when"], ["---:", "---", "---", "---"], rows)


def region_faults(table: dict) -> str:
    g = next(g for g in table["status"] if "bitmask" in g)
    rows = [
        [
            str(v),
            name.removeprefix(g["bitmask"] + "_"),
            g["doc"][name]["detection"],
            g["doc"][name]["clearing"],
        ]
        for v, name, _, _ in _rows(g)
    ]
    return _table(
        ["code", "name", "detection (per tick)", "clearing condition"], ["---:", "---", "---", "---"], rows
    )


def region_results(table: dict) -> str:
    rows = [
        [str(v), f"`{name}`", text]
        for g in table["status"]
        if "header" in g
        for v, name, text, _ in _rows(g)
        if 520 <= v < 600
    ]
    return _table(["code", "name", "meaning"], ["---:", "---", "---"], rows)


def region_update_nrcs(table: dict) -> str:
    iso = {int(v): name for v, _, name, _ in table["uds"]["nrc"]["codes"]}
    rows = []
    for g in table["status"]:
        if "nrc" not in g:
            continue
        for v, name, text, _ in _rows(g):
            nrc = int(g["nrc"].get(name, g["nrc"]["nrc_default"]))
            label = f"0x{nrc:02X}" + ("" if nrc >= 0xF0 else f" {iso[nrc]}")
            rows.append([str(v), f"`{name}`", label, text])
    return _table(["status", "name", "NRC", "meaning"], ["---:", "---", "---", "---"], rows)


REGIONS = {
    "can_ids": region_can_ids,
    "routines": region_routines,
    "dids": region_dids,
    "nrcs": region_nrcs,
    "faults": region_faults,
    "results": region_results,
    "update_nrcs": region_update_nrcs,
}


def _begin(name: str) -> str:
    return f"<!-- begin codes:{name} ({STAMP}) -->"


def _end(name: str) -> str:
    return f"<!-- end codes:{name} -->"


def fill_regions(rel: str, text: str, table: dict) -> str:
    """The document with each of its marked regions replaced by the table's text; TableError if
    a marker is missing, repeated or out of order."""
    for name in DOC_REGIONS[rel]:
        begin = re.compile(rf"^<!-- begin codes:{name}\b.*-->$", re.M)
        found = list(begin.finditer(text))
        end_at = text.find(_end(name))
        if len(found) != 1 or end_at < found[0].end():
            raise TableError(f"{rel}: needs one '{_begin(name)}' ... '{_end(name)}' pair")
        text = text[: found[0].start()] + _begin(name) + "\n" + REGIONS[name](table) + "\n" + text[end_at:]
    return text


def outputs(table: dict, root: Path = ROOT) -> dict[str, str]:
    """Every file the table gives, by path relative to the repository (the documents with
    marked regions as they are under root, their regions filled)."""
    files = {f"{BASE}/{h}": text for h, text in c_status_headers(table).items()}
    files[f"{BASE}/proto_ids.h"] = c_proto_ids(table)
    files[f"{BASE}/fs_uds_ids.h"] = c_uds_ids(table)
    files[f"{BASE}/uds_nrc.h"] = c_uds_nrc(table)
    files[PY_OUT] = python_module(table)
    files[DOC_OUT] = markdown(table)
    for rel in DOC_REGIONS:
        files[rel] = fill_regions(rel, (root / rel).read_text(), table)
    files.update(_wire().outputs(root))
    return files


def dbc_mismatches(table: dict, dbc_text: str) -> list[str]:
    """Frames whose identifier in the DBC differs from the table's (or that one side lacks)."""
    dbc = {m.group(2): int(m.group(1)) for m in re.finditer(r"^BO_ (\d+) (\w+):", dbc_text, re.M)}
    want = {frame: value for value, _, _, frame, _ in table["can"]["ids"] if frame}
    bad = []
    for frame in sorted(set(dbc) | set(want)):
        if dbc.get(frame) != want.get(frame):
            bad.append(f"{DBC}: frame {frame} id {dbc.get(frame)}, {TABLE} {want.get(frame)}")
    return bad


def load(root: Path = ROOT) -> dict:
    with open(root / TABLE, "rb") as f:
        table = tomllib.load(f)
    validate(table)
    return table


def check(root: Path = ROOT) -> list[str]:
    """One line per stale or missing file and per DBC disagreement; empty when all agree."""
    table = load(root)
    problems = []
    for rel, text in outputs(table, root).items():
        path = root / rel
        if not path.is_file() or path.read_text() != text:
            problems.append(f"{rel} differs from {TABLE}: run tools/gen_codes.py")
    problems += dbc_mismatches(table, (root / DBC).read_text())
    problems += _wire().dbc_scale_mismatches(root, DBC)
    return problems


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--check", action="store_true", help="compare instead of writing")
    args = ap.parse_args(argv)
    try:
        if args.check:
            problems = check()
            for p in problems:
                print(p, file=sys.stderr)
            if not problems:
                print(f"codes: every generated file agrees with {TABLE}")
            return 1 if problems else 0
        table = load()
        for rel, text in outputs(table).items():
            path = ROOT / rel
            if not path.is_file() or path.read_text() != text:
                tmp = path.with_suffix(path.suffix + ".tmp")
                tmp.write_text(text)
                tmp.replace(path)
                print(f"wrote {rel}")
        bad = dbc_mismatches(table, (ROOT / DBC).read_text()) + _wire().dbc_scale_mismatches(ROOT, DBC)
        for b in bad:
            print(b, file=sys.stderr)
        return 1 if bad else 0
    except (OSError, tomllib.TOMLDecodeError, TableError, _wire().WireError, KeyError, IndexError) as e:
        print(f"gen_codes: {TABLE}: {e}", file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main())

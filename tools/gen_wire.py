"""The wire half of tools/gen_codes.py: from firmware/base/wire.toml, the shared constants
(firmware/base/fs_wire_const.h, and the host's), the C codecs of the UDS payloads
(firmware/proto/generated/fs_wire.{c,h}) and the host's (host/forceskill/wire/generated.py).
Standard library only; gen_codes.py writes and checks these files with its own."""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from pathlib import Path

import tomllib

TABLE = "firmware/base/wire.toml"
C_CONST = "firmware/base/fs_wire_const.h"
C_HDR = "firmware/proto/generated/fs_wire.h"
C_SRC = "firmware/proto/generated/fs_wire.c"
PY_OUT = "host/forceskill/wire/generated.py"
STAMP = f"generated from {TABLE} by tools/gen_codes.py; do not edit"

SIZE = {"u8": 1, "u16": 2, "u32": 4, "f32": 4, "u16s": 2, "u32s": 4}
CTYPE = {
    "u8": "uint8_t",
    "u16": "uint16_t",
    "u32": "uint32_t",
    "f32": "float",
    "u16s": "uint16_t",
    "u32s": "uint32_t",
}
UMAX = {"u8": 0xFF, "u16": 0xFFFF, "u32": 0xFFFFFFFF, "u16s": 0xFFFF, "u32s": 0xFFFFFFFF}
PYFMT = {"u8": "B", "u16": "H", "u32": "I", "f32": "f", "u16s": "H", "u32s": "I"}


def _is_bytes(f: Field) -> bool:
    """A byte-array field (`type = "bytes"`, `size = N` in the table; type bN here)."""
    return f.type.startswith("b") and f.type[1:].isdigit()


def _bytes_type(n: int) -> str:
    """The type name of an n-byte array field, registered in the size and format tables."""
    name = f"b{n}"
    SIZE[name] = n
    CTYPE[name] = "uint8_t"
    PYFMT[name] = f"{n}s"
    return name


class WireError(Exception):
    """The wire table contradicts itself (unknown type or constant, bad range, bad scale)."""


@dataclass
class Field:
    name: str
    type: str  # a scalar type of SIZE, or the name of a record (an array of it)
    unit: str = ""
    lo: float | None = None  # inclusive lower bound (physical)
    hi: float | None = None  # inclusive upper bound
    above: float | None = None  # exclusive lower bound
    default: float | None = None
    min_count: int = 0
    max_count: int = 0


@dataclass
class Record:
    name: str
    what: str
    fields: list[Field]
    optional: int = 0
    finite: bool = False
    sub: dict[str, Record] = field(default_factory=dict)

    @property
    def array(self) -> Field | None:
        return self.fields[-1] if self.fields and self.fields[-1].type not in SIZE else None

    def fixed_size(self) -> int:
        return sum(SIZE[f.type] for f in self.fields if f.type in SIZE)


@dataclass
class Wire:
    scale: float
    steps: int  # 1 / scale, an integer
    consts: list[tuple[str, int | float, str]]
    records: dict[str, Record]


def _camel(name: str) -> str:
    return "".join(p.capitalize() for p in name.split("_"))


def load(root: Path) -> Wire:
    with open(root / TABLE, "rb") as f:
        t = tomllib.load(f)
    scale = float(t["scale"])
    steps = round(1.0 / scale)
    if steps < 1 or 1.0 / steps != scale:
        raise WireError(f"{TABLE}: scale {scale} is not 1/n for an integer n")
    consts = [(str(n), v, str(w)) for n, v, w in t["const"]]
    names = [c[0] for c in consts]
    if len(names) != len(set(names)):
        raise WireError(f"{TABLE}: a constant is named twice")
    values = {n: v for n, v, _ in consts}

    def num(v: object, where: str) -> float | None:
        if v is None:
            return None
        if isinstance(v, str):
            if v not in values:
                raise WireError(f"{TABLE}: {where}: no constant {v}")
            return float(values[v])
        if isinstance(v, int | float):
            return float(v)
        raise WireError(f"{TABLE}: {where}: not a number: {v!r}")

    records: dict[str, Record] = {}
    for r in t["record"]:
        fields = []
        for fd in r["fields"]:
            where = f"{r['name']}.{fd['name']}"
            ty = fd["type"]
            if ty == "bytes":
                n = int(fd.get("size", 0))
                if not 1 <= n <= 64 or int(r.get("optional", 0)):
                    raise WireError(
                        f"{TABLE}: {where}: bytes need 1 <= size <= 64, in a record without optional fields"
                    )
                ty = _bytes_type(n)
            if ty not in SIZE and ty not in records:
                raise WireError(f"{TABLE}: {where}: unknown type {ty}")
            fl = Field(
                fd["name"],
                ty,
                fd.get("unit", ""),
                num(fd.get("min"), where),
                num(fd.get("max"), where),
                num(fd.get("above"), where),
                num(fd.get("default"), where),
                int(num(fd.get("min_count", 0), where) or 0),
                int(num(fd.get("max_count", 0), where) or 0),
            )
            if ty not in SIZE and (fd is not r["fields"][-1] or fl.max_count < max(1, fl.min_count)):
                raise WireError(f"{TABLE}: {where}: an array is the last field, 0 < max_count >= min_count")
            if ty in UMAX and fl.above is not None:
                raise WireError(f"{TABLE}: {where}: `above` is for f32 fields")
            fields.append(fl)
        rec = Record(r["name"], r["what"], fields, int(r.get("optional", 0)), bool(r.get("finite", False)))
        if rec.array is not None:
            rec.sub[rec.array.type] = records[rec.array.type]
            if rec.optional:
                raise WireError(f"{TABLE}: {rec.name}: optional fields and an array do not mix")
        for f_opt in fields[len(fields) - rec.optional :]:
            if f_opt.default is None:
                raise WireError(f"{TABLE}: {rec.name}.{f_opt.name}: an optional field needs a default")
        records[rec.name] = rec
    return Wire(scale, steps, consts, records)


def constants(w: Wire) -> list[tuple[str, int | float, str, bool]]:
    """(name, value, what, derived): the table's constants, each _US one followed by its value in
    seconds (_S) and, when 1 s is a whole number of periods, its rate (_HZ)."""
    out: list[tuple[str, int | float, str, bool]] = []
    for n, v, what in w.consts:
        out.append((n, v, what, False))
        if n.endswith("_US") and isinstance(v, int):
            out.append((f"{n[:-3]}_S", v / 1e6, f"{n} in seconds", True))
            if 1_000_000 % v == 0:
                out.append((f"{n[:-3]}_HZ", 1_000_000 // v, f"{n} as a rate, per second", True))
    return out


def _steps(w: Wire, v: float) -> int:
    return round(v * w.steps)


# ---------------------------------------------------------------- C


def _c_num(v: int | float) -> str:
    return f"{v}u" if isinstance(v, int) else repr(float(v))


def c_const(w: Wire) -> str:
    g = "FS_WIRE_CONST_H"
    lines = [
        "/* The values the device and the host share (docs/protocol.md).",
        f" * {STAMP}. */",
        f"#ifndef {g}",
        f"#define {g}",
        "",
        "/* One step of every scaled wire field (goal, time and path scales, durations): value =",
        " * count * FS_WIRE_SCALE; also the factor of the DBC's HostCommand scales. */",
        f"#define FS_WIRE_SCALE {w.scale!r}",
        f"#define FS_WIRE_SCALE_STEPS {w.steps}u /* counts per unit, 1 / FS_WIRE_SCALE */",
        "",
    ]
    for n, v, what, derived in constants(w):
        if derived:
            lines.append(f"#define FS_{n} {_c_num(v)} /* FS_{what} */")
        else:
            lines += [f"/* {what} */", f"#define FS_{n} {_c_num(v)}"]
    lines += ["", f"#endif /* {g} */", ""]
    return "\n".join(lines)


def _c_bound(f: Field, w: Wire, v: float) -> str:
    if f.type == "f32":
        return f"{float(v)!r}f"
    return f"{_steps(w, v) if f.type.endswith('s') else int(v)}u"


def _c_checks(f: Field, w: Wire, var: str, finite: bool) -> list[str]:
    """Conditions that are all true when the field is inside its range."""
    out = []
    if f.type == "f32" and (finite or f.lo is not None or f.hi is not None or f.above is not None):
        out.append(f"isfinite({var})")
    if f.lo is not None and (f.type == "f32" or (_steps(w, f.lo) if f.type.endswith("s") else f.lo) > 0):
        out.append(f"{var} >= {_c_bound(f, w, f.lo)}")
    if f.above is not None:
        out.append(f"{var} > {_c_bound(f, w, f.above)}")
    if f.hi is not None:
        hi = _steps(w, f.hi) if f.type.endswith("s") else f.hi
        if f.type == "f32" or hi < UMAX[f.type]:
            out.append(f"{var} <= {_c_bound(f, w, f.hi)}")
    return out


def _c_struct(r: Record, w: Wire) -> list[str]:
    lines = [f"/** {r.what}. */", "typedef struct {"]
    for f in r.fields:
        if _is_bytes(f):
            lines.append(f"    uint8_t {f.name}[{SIZE[f.type]}];" + (f" /* {f.unit} */" if f.unit else ""))
        elif f.type in SIZE:
            note = f.unit
            if f.type.endswith("s"):
                note = f"count of FS_WIRE_SCALE{' ' + f.unit if f.unit else ''}"
            lines.append(f"    {CTYPE[f.type]} {f.name};" + (f" /* {note} */" if note else ""))
        else:
            lines.append(f"    uint8_t n_{f.name}; /* {f.min_count}..{f.max_count} */")
            lines.append(f"    fs_wire_{f.type}_t {f.name}[{f.max_count}];")
    for f in r.fields[len(r.fields) - r.optional :]:
        lines.append(f"    uint8_t has_{f.name}; /* 0: absent (unpack: the default {f.default:g}) */")
    lines.append(f"}} fs_wire_{r.name}_t;")
    return lines


def _len_macros(r: Record) -> list[str]:
    up = r.name.upper()
    fixed = r.fixed_size()
    if r.array is not None:
        sub = r.sub[r.array.type].fixed_size()
        return [
            f"#define FS_WIRE_{up}_LEN_MIN {fixed + sub * r.array.min_count}u",
            f"#define FS_WIRE_{up}_LEN_MAX {fixed + sub * r.array.max_count}u",
        ]
    opt = sum(SIZE[f.type] for f in r.fields[len(r.fields) - r.optional :])
    if opt:
        return [f"#define FS_WIRE_{up}_LEN_MIN {fixed - opt}u", f"#define FS_WIRE_{up}_LEN_MAX {fixed}u"]
    return [f"#define FS_WIRE_{up}_LEN {fixed}u"]


def _count_macros(r: Record, w: Wire) -> list[str]:
    """FS_WIRE_<RECORD>_<FIELD>_COUNT(T, v) of each scaled field: the count of a value v of the real
    type T, rounded to the nearest step and held within the field's range (NaN: its lowest)."""
    out = []
    for f in r.fields:
        if f.type not in ("u16s", "u32s"):
            continue
        lo = _steps(w, f.lo) if f.lo is not None else 0
        hi = _steps(w, f.hi) if f.hi is not None else UMAX[f.type]
        lo_v = f"(T){lo / w.steps!r}"
        hi_v = f"(T){hi / w.steps!r}"
        ct = CTYPE[f.type]
        out += [
            f"/** The count of {r.name}.{f.name} for a value v of the real type T (nearest step, {lo}..{hi}). */",
            f"#define FS_WIRE_{r.name.upper()}_{f.name.upper()}_COUNT(T, v)"
            f" (({ct})(!((v) > {lo_v}) ? {lo}u : ((v) >= {hi_v}) ? {hi}u"
            f" : (uint32_t)((v) * (T)FS_WIRE_SCALE_STEPS + (T)0.5)))",
        ]
    return out


def c_header(w: Wire) -> str:
    g = "FS_WIRE_H"
    lines = [
        "/* Codecs of the device's UDS payloads (DIDs, routine start and results; docs/protocol.md):",
        " * big-endian, float32 for reals, scaled fields as counts of FS_WIRE_SCALE. An unpack checks",
        " * the length and every field's range and changes *v only when both are right; a pack",
        " * refuses a field outside its range.",
        f" * {STAMP}. */",
        f"#ifndef {g}",
        f"#define {g}",
        "",
        "#include <stdint.h>",
        '#include "fs_wire_const.h"',
        '#include "proto_status.h"',
        "",
        "/** The value of a scaled field's count in the real type T: count * FS_WIRE_SCALE computed in T. */",
        "#define FS_WIRE_REAL(T, count) ((T)(count) * (T)FS_WIRE_SCALE)",
        "",
        "/* The records, for code that handles each the same way: X(name) per record. */",
        "#define FS_WIRE_RECORDS(X) " + " ".join(f"X({n})" for n in w.records),
        "",
    ]
    for r in w.records.values():
        lines += _len_macros(r)
        lines += _count_macros(r, w)
        lines += _c_struct(r, w)
        lines += [
            "/** Unpack len bytes: PROTO_OK, PROTO_ERR_WIRE_LENGTH or PROTO_ERR_WIRE_RANGE (v unchanged). */",
            f"proto_status_t fs_wire_{r.name}_unpack(fs_wire_{r.name}_t *v, const uint8_t *d, uint16_t len);",
            "/** Pack into out (cap bytes): the length, 0 if it does not fit or a field is out of range. */",
            f"uint16_t fs_wire_{r.name}_pack(const fs_wire_{r.name}_t *v, uint8_t *out, uint16_t cap);",
            "",
        ]
    lines += [f"#endif /* {g} */", ""]
    return "\n".join(lines)


_C_HELPERS = """\
static uint32_t get_be(const uint8_t *p, unsigned n)
{
    uint32_t v = 0u;
    for (unsigned i = 0; i < n; i++) {
        v = (v << 8) | p[i];
    }
    return v;
}

static void put_be(uint8_t *p, uint32_t v, unsigned n)
{
    for (unsigned i = 0; i < n; i++) {
        p[i] = (uint8_t)(v >> (8u * (n - 1u - i)));
    }
}

static float get_f32(const uint8_t *p)
{
    const uint32_t u = get_be(p, 4u);
    float f;
    memcpy(&f, &u, sizeof(f));
    return f;
}

static void put_f32(uint8_t *p, float f)
{
    uint32_t u;
    memcpy(&u, &f, sizeof(u));
    put_be(p, u, 4u);
}
"""


def _c_get(f: Field, at: str) -> str:
    if _is_bytes(f):
        raise AssertionError("a byte array is copied, not read (_c_fields_get)")
    if f.type == "f32":
        return f"get_f32(&d[{at}])"
    return f"({CTYPE[f.type]})get_be(&d[{at}], {SIZE[f.type]}u)"


def _c_put(f: Field, var: str, at: str) -> str:
    if _is_bytes(f):
        return f"memcpy(&out[{at}], {var}, {SIZE[f.type]}u);"
    if f.type == "f32":
        return f"put_f32(&out[{at}], {var});"
    return f"put_be(&out[{at}], {var}, {SIZE[f.type]}u);"


def _c_range_fn(r: Record, w: Wire) -> list[str]:
    lines = [f"static int {r.name}_in_range(const fs_wire_{r.name}_t *v)", "{"]
    conds = []
    for f in r.fields:
        if f.type in SIZE:
            conds += _c_checks(f, w, f"v->{f.name}", r.finite)
    arr = r.array
    if arr is not None:
        low = f"v->n_{arr.name} < {arr.min_count}u || " if arr.min_count > 0 else ""
        lines += [
            f"    if ({low}v->n_{arr.name} > {arr.max_count}u) {{",
            "        return 0;",
            "    }",
            f"    for (unsigned i = 0; i < v->n_{arr.name}; i++) {{",
            f"        if (!{arr.type}_in_range(&v->{arr.name}[i])) {{",
            "            return 0;",
            "        }",
            "    }",
        ]
    if conds:
        lines.append("    return " + " &&\n           ".join(conds) + ";")
    else:
        lines += ["    (void)v;", "    return 1;"]
    lines += ["}", ""]
    return lines


def _c_fields_get(r: Record, base: str, tgt: str, first: int) -> tuple[list[str], int]:
    lines, at = [], first
    for f in r.fields:
        if f.type in SIZE:
            off = f"{base} + {at}u" if base else f"{at}u"
            if _is_bytes(f):
                lines.append(f"    memcpy({tgt}{f.name}, &d[{off}], {SIZE[f.type]}u);")
            else:
                lines.append(f"    {tgt}{f.name} = {_c_get(f, off)};")
            at += SIZE[f.type]
    return lines, at


def c_source(w: Wire) -> str:
    lines = [
        "/* Codecs of the device's UDS payloads (see fs_wire.h).",
        f" * {STAMP}. */",
        '#include "fs_wire.h"',
        "",
        "#include <math.h>",
        "#include <string.h>",
        "",
        _C_HELPERS,
    ]
    for r in w.records.values():
        lines += _c_range_fn(r, w)
        lines += _c_unpack(r, w)
        lines += _c_pack(r, w)
    return "\n".join(lines).rstrip() + "\n"


def _c_unpack(r: Record, w: Wire) -> list[str]:
    up = r.name.upper()
    lines = [
        f"proto_status_t fs_wire_{r.name}_unpack(fs_wire_{r.name}_t *v, const uint8_t *d, uint16_t len)",
        "{",
    ]
    fixed = r.fixed_size()
    arr = r.array
    if arr is not None:
        sub = r.sub[arr.type].fixed_size()
        lines += [
            f"    if (len < FS_WIRE_{up}_LEN_MIN || len > FS_WIRE_{up}_LEN_MAX || (len - {fixed}u) % {sub}u != 0u) {{",
        ]
    elif r.optional:
        lines += [f"    if (len != FS_WIRE_{up}_LEN_MIN && len != FS_WIRE_{up}_LEN_MAX) {{"]
    else:
        lines += [f"    if (len != FS_WIRE_{up}_LEN) {{"]
    lines += [
        "        return PROTO_ERR_WIRE_LENGTH;",
        "    }",
        f"    fs_wire_{r.name}_t t;",
        "    memset(&t, 0, sizeof(t));",
    ]
    body, _ = _c_fields_get(r, "", "t.", 0)
    if r.optional:
        n_req = len(r.fields) - r.optional
        req = Record(r.name, r.what, r.fields[:n_req])
        opt = r.fields[n_req:]
        body, at = _c_fields_get(req, "", "t.", 0)
        lines += body
        lines.append(f"    if (len == FS_WIRE_{up}_LEN_MAX) {{")
        for f in opt:
            lines.append(f"        t.has_{f.name} = 1u;")
            lines.append(f"        t.{f.name} = {_c_get(f, f'{at}u')};")
            at += SIZE[f.type]
        lines.append("    } else {")
        for f in opt:
            dv = f"{_steps(w, f.default)}u" if f.type.endswith("s") else _c_bound(f, w, f.default or 0.0)
            lines.append(f"        t.{f.name} = {dv};")
        lines.append("    }")
    else:
        lines += body
    if arr is not None:
        sub = r.sub[arr.type]
        lines += [
            f"    t.n_{arr.name} = (uint8_t)((len - {fixed}u) / {sub.fixed_size()}u);",
            f"    for (unsigned i = 0; i < t.n_{arr.name}; i++) {{",
            f"        const unsigned at = {fixed}u + {sub.fixed_size()}u * i;",
        ]
        sb, _ = _c_fields_get(sub, "at", f"t.{arr.name}[i].", 0)
        lines += ["    " + s for s in sb]
        lines.append("    }")
    lines += [
        f"    if (!{r.name}_in_range(&t)) {{",
        "        return PROTO_ERR_WIRE_RANGE;",
        "    }",
        "    *v = t;",
        "    return PROTO_OK;",
        "}",
        "",
    ]
    return lines


def _c_pack(r: Record, w: Wire) -> list[str]:
    lines = [f"uint16_t fs_wire_{r.name}_pack(const fs_wire_{r.name}_t *v, uint8_t *out, uint16_t cap)", "{"]
    arr = r.array
    n_req = len(r.fields) - r.optional
    size = f"{r.fixed_size()}u"
    if arr is not None:
        size = f"{r.fixed_size()}u + {r.sub[arr.type].fixed_size()}u * (unsigned)v->n_{arr.name}"
    elif r.optional:
        opt = sum(SIZE[f.type] for f in r.fields[n_req:])
        size = f"{r.fixed_size() - opt}u + (v->has_{r.fields[-1].name} != 0u ? {opt}u : 0u)"
    lines += [
        f"    const unsigned n = {size};",
        f"    if (!{r.name}_in_range(v) || n > cap) {{",
        "        return 0u;",
        "    }",
    ]
    at = 0
    for i, f in enumerate(r.fields):
        if f.type not in SIZE:
            continue
        stmt = _c_put(f, f"v->{f.name}", f"{at}u")
        if i >= n_req:
            stmt = f"if (v->has_{f.name} != 0u) {{ {stmt} }}"
        lines.append(f"    {stmt}")
        at += SIZE[f.type]
    if arr is not None:
        sub = r.sub[arr.type]
        lines += [
            f"    for (unsigned i = 0; i < v->n_{arr.name}; i++) {{",
            f"        const unsigned at = {at}u + {sub.fixed_size()}u * i;",
        ]
        sat = 0
        for f in sub.fields:
            lines.append(f"        {_c_put(f, f'v->{arr.name}[i].{f.name}', f'at + {sat}u')}")
            sat += SIZE[f.type]
        lines.append("    }")
    lines += ["    return (uint16_t)n;", "}", ""]
    return lines


# ---------------------------------------------------------------- Python


def _py_num(v: int | float) -> str:
    return f"0x{v:04X}" if isinstance(v, int) and v > 0xFFF else repr(v)


def _py_checks(f: Field, w: Wire, var: str, finite: bool) -> list[str]:
    """Python conditions true when the field is inside its range (on counts for scaled fields)."""
    out: list[str] = []
    if _is_bytes(f):
        return [f"isinstance({var}, bytes) and len({var}) == {SIZE[f.type]}"]
    if f.type in UMAX:
        lo = 0
        hi = UMAX[f.type]
        if f.lo is not None:
            lo = max(lo, _steps(w, f.lo) if f.type.endswith("s") else int(f.lo))
        if f.hi is not None:
            hi = min(hi, _steps(w, f.hi) if f.type.endswith("s") else int(f.hi))
        out.append(f"{lo} <= {var} <= {hi}")
        return out
    if finite or f.lo is not None or f.hi is not None or f.above is not None:
        out.append(f"math.isfinite({var})")
    if f.lo is not None:
        out.append(f"{var} >= {float(f.lo)!r}")
    if f.above is not None:
        out.append(f"{var} > {float(f.above)!r}")
    if f.hi is not None:
        out.append(f"{var} <= {float(f.hi)!r}")
    return out


def _py_type(f: Field, optional: bool) -> str:
    if f.type not in SIZE:
        return f"tuple[{_camel(f.type)}, ...]"
    if _is_bytes(f):
        return "bytes"
    t = "float" if f.type == "f32" or f.type.endswith("s") else "int"
    return f"{t} | None" if optional else t


def _py_class(r: Record, w: Wire) -> list[str]:
    cls = _camel(r.name)
    n_req = len(r.fields) - r.optional
    req = [f for f in r.fields[:n_req] if f.type in SIZE]
    fmt = ">" + "".join(PYFMT[f.type] for f in req)
    lines = [
        f"_{r.name.upper()} = struct.Struct({fmt!r})",
        "",
        "",
        "@dataclass(frozen=True)",
        f"class {cls}:",
        f'    """{r.what}."""',
        "",
        f"    SIZE: ClassVar[int] = {sum(SIZE[f.type] for f in req)}  # bytes of the fields always present",
    ]
    for i, f in enumerate(r.fields):
        opt = i >= n_req
        unit = f"  # {f.unit}" if f.unit else ""
        lines.append(f"    {f.name}: {_py_type(f, opt)}" + (" = None" if opt else "") + unit)
    lines += [
        "",
        "    def check(self) -> None:",
        '        """FsError ERR_WIRE_RANGE if a field is outside its range."""',
    ]
    for i, f in enumerate(r.fields):
        if f.type not in SIZE:
            continue
        var = f"to_steps(self.{f.name})" if f.type.endswith("s") else f"self.{f.name}"
        conds = _py_checks(f, w, var, r.finite)
        if not conds:
            continue
        if i >= n_req:
            lines.append(f"        if self.{f.name} is not None:")
            ind = "            "
        else:
            ind = "        "
        lines.append(f"{ind}_in_range({r.name!r}, {f.name!r}, {' and '.join(conds)}, self.{f.name})")
    arr = r.array
    if arr is not None:
        lines += [
            f"        _in_range({r.name!r}, 'n_{arr.name}', {arr.min_count} <= len(self.{arr.name}) <= {arr.max_count}, len(self.{arr.name}))",
            f"        for e in self.{arr.name}:",
            "            e.check()",
        ]
    # pack
    lines += [
        "",
        "    def pack(self) -> bytes:",
        '        """The payload; FsError ERR_WIRE_RANGE if a field is outside its range."""',
        "        self.check()",
    ]
    args = ", ".join(f"to_steps(self.{f.name})" if f.type.endswith("s") else f"self.{f.name}" for f in req)
    lines.append(f"        out = _{r.name.upper()}.pack({args})")
    for f in r.fields[n_req:]:
        lines.append(f"        if self.{f.name} is not None:")
        val = f"to_steps(self.{f.name})" if f.type.endswith("s") else f"self.{f.name}"
        lines.append(f"            out += struct.pack('>{PYFMT[f.type]}', {val})")
    if arr is not None:
        lines.append(f"        out += b''.join(e.pack() for e in self.{arr.name})")
    lines.append("        return out")
    # unpack
    lines += [
        "",
        "    @classmethod",
        f"    def unpack(cls, data: bytes) -> {cls}:",
        '        """Decode a payload; FsError ERR_WIRE_LENGTH or ERR_WIRE_RANGE."""',
        "        data = bytes(data)",
        f"        n = _{r.name.upper()}.size",
    ]
    if arr is not None:
        sub = _camel(arr.type)
        lines += [
            f"        m = {sub}.SIZE",
            "        count = (len(data) - n) // m",
            f"        if len(data) < n or (len(data) - n) % m or not {arr.min_count} <= count <= {arr.max_count}:",
            f"            raise FsError(ERR_WIRE_LENGTH, f'{r.name}: {{len(data)}} bytes is not {{n}} + {{m}} x {arr.min_count}..{arr.max_count}')",
        ]
    elif r.optional:
        opt = sum(SIZE[f.type] for f in r.fields[n_req:])
        lines += [
            f"        if len(data) not in (n, n + {opt}):",
            f"            raise FsError(ERR_WIRE_LENGTH, f'{r.name}: {{len(data)}} bytes, not {{n}} or {{n + {opt}}}')",
        ]
    else:
        lines += [
            "        if len(data) != n:",
            f"            raise FsError(ERR_WIRE_LENGTH, f'{r.name}: {{len(data)}} bytes, not {{n}}')",
        ]
    lines.append(f"        raw = _{r.name.upper()}.unpack(data[:n])")
    vals = []
    for i, f in enumerate(req):
        vals.append(f"from_steps(raw[{i}])" if f.type.endswith("s") else f"raw[{i}]")
    for f in r.fields[n_req:]:
        fm = PYFMT[f.type]
        conv = (
            "from_steps(struct.unpack_from('>" + fm + "', data, n)[0])"
            if f.type.endswith("s")
            else f"struct.unpack_from('>{fm}', data, n)[0]"
        )
        vals.append(f"{conv} if len(data) > n else None")
    if arr is not None:
        sub = _camel(arr.type)
        vals.append(f"tuple({sub}.unpack(data[n + m * i : n + m * (i + 1)]) for i in range(count))")
    lines.append(f"        v = cls({', '.join(vals)})")
    lines += ["        v.check()", "        return v"]
    lines += ["", ""]
    return lines


def python_module(w: Wire) -> str:
    lines = [
        '"""The values the device and the host share, and the codecs of the device\'s UDS payloads',
        "(big-endian, float32 for reals, scaled fields as counts of SCALE; docs/protocol.md).",
        "",
        f"{STAMP[0].upper()}{STAMP[1:]}.",
        '"""',
        "",
        "from __future__ import annotations",
        "",
        "import math",
        "import struct",
        "from dataclasses import dataclass",
        "from typing import ClassVar",
        "",
        "from ..errors import ERR_WIRE_LENGTH, ERR_WIRE_RANGE, FsError",
        "",
        "#: One step of every scaled field (goal, time and path scales, durations): value = count * SCALE.",
        f"SCALE = {w.scale!r}",
        f"SCALE_STEPS = {w.steps}  # counts per unit, 1 / SCALE",
    ]
    for n, v, what, derived in constants(w):
        if derived:
            lines.append(f"{n} = {_py_num(v)}  # {what}")
        else:
            lines += [f"#: {what}", f"{n} = {_py_num(v)}"]
    lines += [
        "",
        "",
        "def to_steps(value: float) -> int:",
        '    """A scaled field\'s count for a value (rounded to the nearest step)."""',
        "    return int(round(value * SCALE_STEPS))",
        "",
        "",
        "def from_steps(count: int) -> float:",
        '    """The value of a scaled field\'s count."""',
        "    return count / SCALE_STEPS",
        "",
        "",
        "def _in_range(record: str, name: str, ok: bool, value: object) -> None:",
        "    if not ok:",
        "        raise FsError(ERR_WIRE_RANGE, f'{record}.{name} outside its range: {value!r}')",
        "",
        "",
    ]
    body: list[str] = []
    for r in w.records.values():
        body += _py_class(r, w)
    text = "\n".join(lines + body)
    names = ["SCALE", "SCALE_STEPS", *[c[0] for c in constants(w)]]
    names += ["from_steps", "to_steps", *[_camel(n) for n in w.records]]
    text = text.rstrip() + "\n\n\n__all__ = [\n" + "".join(f"    {n!r},\n" for n in names) + "]\n"
    return text


def outputs(root: Path) -> dict[str, str]:
    w = load(root)
    return {
        C_CONST: c_const(w),
        C_HDR: c_header(w),
        C_SRC: c_source(w),
        PY_OUT: python_module(w),
    }


def dbc_scale_mismatches(root: Path, dbc_rel: str) -> list[str]:
    """The DBC's HostCommand scale signals whose factor is not the table's scale."""
    w = load(root)
    text = (root / dbc_rel).read_text()
    bad = []
    for sig in ("GoalScale", "TimeScale"):
        m = re.search(rf"^\s*SG_ {sig}(?: m\d+)? : \S+ \(([^,]+),", text, re.M)
        if m is None or float(m.group(1)) != w.scale:
            bad.append(
                f"{dbc_rel}: signal {sig} factor {m.group(1) if m else 'missing'}, {TABLE} scale {w.scale}"
            )
    return bad

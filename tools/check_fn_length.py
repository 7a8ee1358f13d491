#!/usr/bin/env python3
"""Function length check for the C sources of firmware/ and hil_sim/ (generated code excluded).

Lists every function whose definition spans more than LIMIT lines (from the line of its name to
its closing brace) and fails unless the function carries a `/* long: reason */` comment on one of
the three lines above its name or between its name and its opening brace.

A simple brace-counting scanner: comments, strings and character literals are blanked first;
a `{` at file depth 0 that follows a `)` opens a function body (struct, enum and array
initialisers follow `=`, a name or a keyword instead).

usage: tools/check_fn_length.py [--limit N] [--all] [FILE ...]
  --all   also list the long functions that carry a reason (exit status unchanged)
Exit 0 when every long function carries a reason, 1 otherwise.
"""

from __future__ import annotations

import argparse
import re
import sys
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
LIMIT = 80
TOPS = ("firmware", "hil_sim")
GENERATED = ("firmware/proto/generated/",)
REASON = re.compile(r"/\*\s*long:\s*\S[^*]*\*/")
NAME_BEFORE_PAREN = re.compile(r"([A-Za-z_]\w*)\s*$")


@dataclass
class Function:
    path: str
    name: str
    first_line: int  # 1-based line of the name
    last_line: int  # 1-based line of the closing brace
    reason: str | None

    @property
    def lines(self) -> int:
        return self.last_line - self.first_line + 1


def blank(text: str) -> str:
    """The text with comments, strings and character literals replaced by spaces (newlines kept),
    so that braces and parentheses inside them are not counted."""
    out = list(text)
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        two = text[i : i + 2]
        if two == "/*":
            end = text.find("*/", i + 2)
            end = n if end < 0 else end + 2
        elif two == "//":
            end = text.find("\n", i)
            end = n if end < 0 else end
        elif c in "\"'":
            end = i + 1
            while end < n and text[end] != c and text[end] != "\n":
                end += 2 if text[end] == "\\" else 1
            end = min(end + 1, n)
        elif c == "#" and (i == 0 or text[i - 1] == "\n"):
            # preprocessor line (with continuations): macros may hold unbalanced braces
            end = i
            while end < n and text[end] != "\n":
                end += 2 if text[end] == "\\" else 1
        else:
            i += 1
            continue
        for j in range(i, end):
            if out[j] != "\n":
                out[j] = " "
        i = end
    return "".join(out)


def open_paren(code: str, close: int) -> int:
    """Index of the `(` matching the `)` at close (-1 if none)."""
    depth = 0
    for j in range(close, -1, -1):
        if code[j] == ")":
            depth += 1
        elif code[j] == "(":
            depth -= 1
            if depth == 0:
                return j
    return -1


def functions(path: Path, rel: str) -> list[Function]:
    """Every function definition of one C file."""
    text = path.read_text(encoding="utf-8", errors="replace")
    code = blank(text)
    lines = text.split("\n")
    line_at = [0] * (len(code) + 1)
    ln = 1
    for k, ch in enumerate(code):
        line_at[k] = ln
        if ch == "\n":
            ln += 1
    found: list[Function] = []
    depth = 0
    i = 0
    while i < len(code):
        ch = code[i]
        if ch == "{":
            if depth == 0:
                before = code[:i].rstrip()
                if before.endswith(")"):
                    start = open_paren(code, len(before) - 1)
                    m = NAME_BEFORE_PAREN.search(code[:start]) if start > 0 else None
                    if m is not None:
                        name = m.group(1)
                        first = line_at[m.start(1)]
                        end = close_brace(code, i)
                        last = line_at[end]
                        window = "\n".join(lines[max(0, first - 4) : line_at[i]])
                        r = REASON.search(window)
                        found.append(Function(rel, name, first, last, r.group(0) if r else None))
                        i = end + 1
                        continue
            depth += 1
        elif ch == "}":
            depth = max(0, depth - 1)
        i += 1
    return found


def close_brace(code: str, open_at: int) -> int:
    """Index of the `}` matching the `{` at open_at (last index if unbalanced)."""
    depth = 0
    for j in range(open_at, len(code)):
        if code[j] == "{":
            depth += 1
        elif code[j] == "}":
            depth -= 1
            if depth == 0:
                return j
    return len(code) - 1


def sources(root: Path) -> list[Path]:
    out: list[Path] = []
    for top in TOPS:
        for p in sorted((root / top).rglob("*")):
            rel = p.relative_to(root).as_posix()
            if p.suffix in (".c", ".h") and not rel.startswith(GENERATED):
                out.append(p)
    return out


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--limit", type=int, default=LIMIT)
    ap.add_argument("--all", action="store_true")
    ap.add_argument("files", nargs="*", type=Path)
    args = ap.parse_args(argv)
    paths = [p.resolve() for p in args.files] or sources(ROOT)
    bad = 0
    reasoned = 0
    for p in paths:
        try:
            rel = p.relative_to(ROOT).as_posix()
        except ValueError:
            rel = str(p)
        for f in functions(p, rel):
            if f.lines <= args.limit:
                continue
            if f.reason is None:
                bad += 1
                print(
                    f"{f.path}:{f.first_line}: {f.name}() is {f.lines} lines "
                    f"(over {args.limit}) without a /* long: reason */ comment"
                )
            else:
                reasoned += 1
                if args.all:
                    print(f"{f.path}:{f.first_line}: {f.name}() is {f.lines} lines: {f.reason}")
    print(
        f"{bad} function(s) over {args.limit} lines without a reason, {reasoned} with one",
        file=sys.stderr if bad else sys.stdout,
    )
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())

"""tools/check_fn_length.py: the tree passes; a function over the limit is reported with its
file, line, name and length unless it carries a `/* long: reason */` comment; braces inside
strings, comments, macros and initialisers are not mistaken for function bodies."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from types import ModuleType

ROOT = Path(__file__).resolve().parents[2]


def _function(name: str, body_lines: int, before: str = "") -> str:
    body = "".join(f"    x += {i};\n" for i in range(body_lines))
    return f"{before}static int {name}(int x)\n{{\n{body}    return x;\n}}\n"


def test_the_tree_passes(tool: Callable[[str], ModuleType]) -> None:
    assert tool("check_fn_length").main([]) == 0


def test_lengths_names_and_reasons(tmp_path: Path, tool: Callable[[str], ModuleType]) -> None:
    mod = tool("check_fn_length")
    src = tmp_path / "a.c"
    src.write_text(
        '#define BRACE "{"\n'
        "static const int TABLE[] = {1, 2, 3};\n"
        'static const char *S = "} {";\n'
        "/* { not a body */\n"
        + _function("short_one", 10)
        + _function("long_one", 90)
        + _function("long_with_reason", 90, before="/* long: one table of cases */\n")
        + "struct s { int a; };\n"
    )
    found = {f.name: f for f in mod.functions(src, "a.c")}
    assert set(found) == {"short_one", "long_one", "long_with_reason"}
    # name line to closing brace: signature, {, body, return, }
    assert found["short_one"].lines == 10 + 4
    assert found["long_one"].lines == 94 and found["long_one"].reason is None
    assert found["long_with_reason"].reason == "/* long: one table of cases */"
    assert found["long_one"].first_line == 5 + 14


def test_main_fails_on_a_long_function(tmp_path: Path, tool: Callable[[str], ModuleType], capsys) -> None:  # type: ignore[no-untyped-def]
    mod = tool("check_fn_length")
    src = tmp_path / "b.c"
    src.write_text(_function("too_long", 85))
    assert mod.main([str(src)]) == 1
    out = capsys.readouterr().out
    assert "too_long() is 89 lines (over 80) without a /* long: reason */ comment" in out
    assert mod.main(["--limit", "100", str(src)]) == 0

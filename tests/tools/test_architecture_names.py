"""docs/architecture.md names only functions and types that exist: every C identifier it mentions
(a lower-case name with an underscore: app_run_start, exec_tick, cm_main, app_run_request_t, ...)
is defined in firmware/ or hil_sim/ (a function, a type or an object), and its templates
(`fs_wire_<record>_pack`) have an instance."""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
DOC = ROOT / "docs" / "architecture.md"
# words of the page with an underscore that name no C identifier
NOT_CODE = {"hil_sim": "the simulator's folder", "m_d": "the desired mass, a quantity of the control law"}
COMMENT = re.compile(r"/\*.*?\*/|//[^\n]*", re.S)


def _names(text: str) -> set[str]:
    """Lower-case identifiers with an underscore, not part of a path or a file name (upper case:
    build options and placeholders)."""
    pat = r"(?<![\w/.<-])([a-z][a-z0-9]*(?:_[a-z0-9]+)+)(?![\w.>/-])"
    return {m.group(1) for m in re.finditer(pat, text)} - set(NOT_CODE)


def _code() -> str:
    files = [
        p for top in ("firmware", "hil_sim") for p in (ROOT / top).rglob("*") if p.suffix in (".c", ".h")
    ]
    return "\n".join(COMMENT.sub(" ", p.read_text(errors="replace")) for p in files)


def _defined(name: str, code: str) -> bool:
    n = re.escape(name)
    return bool(
        re.search(rf"^[\w \t*]*\b{n}\s*\([^;{{}}]*\)\s*\{{", code, re.M)  # a function's definition
        or re.search(rf"^\s*#\s*define\s+{n}\b", code, re.M)  # a macro
        or re.search(rf"}}\s*{n}\s*;", code)  # a typedef'd struct or enum
        or re.search(rf"^(?!\s*extern\b)[\w \t*]*\b{n}\s*(\[[^\]]*\])?\s*=", code, re.M)  # an object
    )


def test_every_identifier_the_page_names_exists() -> None:
    text = DOC.read_text()
    code = _code()
    names = _names(text)
    assert {"app_tick", "app_run_start", "exec_tick", "saf_step", "cm_main"} <= names
    missing = sorted(n for n in names if not _defined(n, code))
    assert missing == [], f"docs/architecture.md names what the code does not define: {missing}"


def test_the_templates_have_an_instance() -> None:
    text = DOC.read_text()
    code = _code()
    for tpl in re.findall(r"`([a-z_]+<[a-z]+>[a-z_]*)", text):
        pattern = re.escape(tpl).replace(r"<record>", r"[a-z0-9_]+")
        pattern = re.sub(r"\\<[a-z]+\\>", r"[a-z0-9_]+", pattern)
        found = re.search(rf"^[\w \t*]*\b{pattern}\s*\(", code, re.M)
        assert found, f"docs/architecture.md: no function matches {tpl}"


def test_a_name_the_code_lacks_is_found() -> None:
    code = _code()
    assert _defined("app_run_start", code) and _defined("app_run_request_t", code)
    assert not _defined("app_run_begin_nowhere", code)

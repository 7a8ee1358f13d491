"""tools/gen_f32_names.py: the rename headers match the declarations, and a function added to a
header the float build renames makes the check fail until the header is regenerated."""

from __future__ import annotations

import shutil
from collections.abc import Callable
from pathlib import Path
from types import ModuleType

ROOT = Path(__file__).resolve().parents[2]


def test_rename_headers_are_up_to_date(tool: Callable[[str], ModuleType]) -> None:
    assert tool("gen_f32_names").check(ROOT) == []


def test_a_new_function_is_caught_and_renamed(tmp_path: Path, tool: Callable[[str], ModuleType]) -> None:
    mod = tool("gen_f32_names")
    for out, headers in mod.OUTPUTS.items():
        for rel in [out, *headers]:
            (tmp_path / rel).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy(ROOT / rel, tmp_path / rel)
    pfc = tmp_path / "firmware/core/pfc.h"
    new = "/** New. */\nvoid pfc_new_thing(int x);\n\n#endif /* PFC_H */"
    pfc.write_text(pfc.read_text().replace("#endif /* PFC_H */", new))
    assert any("fs_f32_names.h" in p for p in mod.check(tmp_path))
    text = mod.render("firmware/core/fs_f32_names.h", mod.OUTPUTS["firmware/core/fs_f32_names.h"], tmp_path)
    assert "#define pfc_new_thing pfc_new_thing_f32" in text
    assert "static" not in text and "#define pfc_step pfc_step_f32" in text

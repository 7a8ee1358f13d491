"""tools/gen_f32_names.py: the rename headers match the declarations, and a function added to a
header the float build renames makes the check fail until the header is regenerated."""
from __future__ import annotations

import importlib.util
import shutil
import sys
from pathlib import Path
from types import ModuleType

ROOT = Path(__file__).resolve().parents[2]


def _tool() -> ModuleType:
    spec = importlib.util.spec_from_file_location("gen_f32_names", ROOT / "tools/gen_f32_names.py")
    assert spec and spec.loader
    mod = importlib.util.module_from_spec(spec)
    sys.modules["gen_f32_names"] = mod
    spec.loader.exec_module(mod)
    return mod


def test_rename_headers_are_up_to_date() -> None:
    assert _tool().check(ROOT) == []


def test_a_new_function_is_caught_and_renamed(tmp_path: Path) -> None:
    tool = _tool()
    for out, headers in tool.OUTPUTS.items():
        for rel in [out, *headers]:
            (tmp_path / rel).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy(ROOT / rel, tmp_path / rel)
    pfc = tmp_path / "firmware/core/pfc.h"
    pfc.write_text(pfc.read_text().replace("#endif /* PFC_H */",
                                           "/** New. */\nvoid pfc_new_thing(int x);\n\n#endif /* PFC_H */"))
    assert any("fs_f32_names.h" in p for p in tool.check(tmp_path))
    text = tool.render("firmware/core/fs_f32_names.h", tool.OUTPUTS["firmware/core/fs_f32_names.h"],
                       tmp_path)
    assert "#define pfc_new_thing pfc_new_thing_f32" in text
    assert "static" not in text and "#define pfc_step pfc_step_f32" in text

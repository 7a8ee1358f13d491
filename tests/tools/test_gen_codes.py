"""tools/gen_codes.py's marked regions: the tables of docs/protocol.md, docs/safety.md and
docs/update.md come from firmware/base/codes.toml; a hand edit inside a region, a lost marker or
a table row without its doc entry is reported; the text around the regions is kept."""

from __future__ import annotations

import shutil
from collections.abc import Callable
from pathlib import Path
from types import ModuleType

import pytest

ROOT = Path(__file__).resolve().parents[2]


def _copy(tmp: Path, gen: ModuleType) -> Path:
    tables = ["firmware/base/codes.toml", "firmware/base/wire.toml", "firmware/proto/forceskill.dbc"]
    for rel in [*tables, *gen.outputs(gen.load(ROOT))]:
        (tmp / rel).parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(ROOT / rel, tmp / rel)
    return tmp


def test_regions_agree_and_hold_the_table(tool: Callable[[str], ModuleType]) -> None:
    gen = tool("gen_codes")
    assert gen.check(ROOT) == []
    protocol = (ROOT / "docs/protocol.md").read_text()
    table = gen.load(ROOT)
    for value, name, _, kind, _ in table["uds"]["ids"]:
        if kind in ("DID", "RID"):
            assert f"| {gen._hex(value)} | " in protocol, name
    for value, _, iso, _ in table["uds"]["nrc"]["codes"]:
        assert f"| 0x{value:02X} | " in protocol and iso in protocol
    update = (ROOT / "docs/update.md").read_text()
    assert "| 702 | `BOOT_ERR_FORMAT` | 0xF0 |" in update
    assert "| 704 | `BOOT_ERR_TOO_LARGE` | 0x70 uploadDownloadNotAccepted |" in update
    safety = (ROOT / "docs/safety.md").read_text()
    assert "| 500 | HOST_SILENCE | no host command/heartbeat" in safety
    assert "| 526 | `SAF_ERR_FORCE_MAX` |" in safety and "| 552 | `SEC_ERR_CONFIG` |" in safety


def test_hand_edit_and_lost_marker_are_reported(tmp_path: Path, tool: Callable[[str], ModuleType]) -> None:
    gen = tool("gen_codes")
    root = _copy(tmp_path, gen)
    assert gen.check(root) == []
    doc = root / "docs/protocol.md"
    text = doc.read_text()
    doc.write_text(text.replace("| 0x0203 | self-test |", "| 0x0203 | selftest |"))
    assert gen.check(root) == [
        "docs/protocol.md differs from firmware/base/codes.toml: run tools/gen_codes.py"
    ]
    # writing restores the region and keeps the prose around it
    doc.write_text(text.replace("| 0x0203 | self-test |", "| 0x0203 | selftest |") + "\nA closing line.\n")
    filled = gen.fill_regions("docs/protocol.md", doc.read_text(), gen.load(root))
    assert "| 0x0203 | self-test |" in filled and filled.endswith("\nA closing line.\n")
    doc.write_text(text.replace("<!-- end codes:dids -->", ""))
    with pytest.raises(gen.TableError, match=r"docs/protocol\.md: needs one"):
        gen.check(root)


def test_a_row_without_its_doc_entry_is_refused(tmp_path: Path, tool: Callable[[str], ModuleType]) -> None:
    gen = tool("gen_codes")
    root = _copy(tmp_path, gen)
    toml = root / "firmware/base/codes.toml"
    text = toml.read_text()
    toml.write_text(text.replace("DID_COMM = { content", "DID_COMMS = { content"))
    with pytest.raises(gen.TableError, match=r"\[uds.doc\]: no such name \['DID_COMMS'\]"):
        gen.load(root)
    toml.write_text(text.replace("FWU_ERR_RANGE = 0x31", "FWU_ERR_RANGE = 0x32"))
    with pytest.raises(gen.TableError, match="NRC 0x32 not in"):
        gen.load(root)

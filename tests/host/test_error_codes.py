"""One table of codes and identifiers (firmware/base/codes.toml): the generated C headers, the
host's constants and docs/codes.md agree with it, and the C headers read back independently (a
regex over the enums and macros, not the generator) give the same numbers as the host."""

from __future__ import annotations

import re
from collections.abc import Callable
from pathlib import Path
from types import ModuleType

import tomllib

from forceskill import codes, errors

ROOT = Path(__file__).resolve().parents[2]
BASE = ROOT / "firmware/base"


def _c_enum(path: Path, prefix: str) -> dict[str, int]:
    text = path.read_text()
    return {m.group(1): int(m.group(2)) for m in re.finditer(rf"\b({prefix}\w+)\s*=\s*(\d+)", text)}


def _c_defines(path: Path) -> dict[str, int]:
    text = path.read_text()
    return {
        m.group(1): int(m.group(2), 16)
        for m in re.finditer(r"#define (\w+)(?:\(node\))? \(?0x([0-9A-F]+)u", text)
    }


def test_generated_files_are_up_to_date(tool: Callable[[str], ModuleType]) -> None:
    assert tool("gen_codes").check(ROOT) == []


def test_fs_status_codes_are_mirrored(tool: Callable[[str], ModuleType]) -> None:
    c = _c_enum(BASE / "fs_status.h", "FS_ERR_")
    assert len(c) > 20
    for name, value in c.items():
        py = getattr(errors, name.replace("FS_ERR_", "ERR_"), None)
        assert py == value, f"{name} = {value} in fs_status.h, errors.py has {py}"


def test_every_c_status_code_is_in_the_host(tool: Callable[[str], ModuleType]) -> None:
    headers = {
        "flt_codes.h": "(?:FLT|SAF)_",
        "nvm_status.h": "NVM_ERR_",
        "sec_status.h": "SEC_ERR_",
        "proto_status.h": "PROTO_ERR_",
        "boot_status.h": "(?:BOOT|FWU)_ERR_",
    }
    for header, prefix in headers.items():
        c = {k: v for k, v in _c_enum(BASE / header, prefix).items() if v}
        assert c, header
        for name, value in c.items():
            assert getattr(codes, name) == value, f"{name} in {header}"


def test_codes_are_unique_and_ranges_hold(tool: Callable[[str], ModuleType]) -> None:
    table = tomllib.loads((BASE / "codes.toml").read_text())
    values = [row[0] for g in table["status"] for row in g["codes"]]
    assert len(values) == len(set(values))
    host = [row[0] for g in table["status"] if "header" not in g for row in g["codes"]]
    assert all(600 <= v < 700 or 730 <= v < 750 for v in host), "host codes outside 6xx/73x-74x"
    firmware = [row[0] for g in table["status"] if "header" in g for row in g["codes"]]
    assert all(v < 600 or 700 <= v < 730 for v in firmware)


def test_device_fault_table_matches_flt_codes(tool: Callable[[str], ModuleType]) -> None:
    c = _c_enum(BASE / "flt_codes.h", "FLT_")
    faults = {v for k, v in c.items() if k != "FLT_NONE" and 500 <= v < 520}
    assert faults == set(errors.DEVICE_FAULTS), "errors.DEVICE_FAULTS differs from flt_codes.h"
    assert errors.fault_text(0) == "none"
    assert errors.fault_text(500) == "500 (host silence)"


def test_uds_and_can_identifiers_match_the_c_headers(tool: Callable[[str], ModuleType]) -> None:
    c = _c_defines(BASE / "fs_uds_ids.h")
    assert c["DID_GAINS_X"] == codes.DID_GAINS_X == 0x0100
    assert c["FWU_DID_STATUS"] == codes.DID_FWU_STATUS
    assert c["UDS_RID_RUN_SKILL"] == codes.RID_RUN_SKILL
    assert c["FWU_RID_CONFIRM"] == codes.RID_CONFIRM
    assert c["FWU_DOWNLOAD_ADDRESS"] == codes.DOWNLOAD_ADDRESS
    ids = _c_defines(BASE / "proto_ids.h")
    assert ids["PROTO_ID_UDS_REQUEST"] == codes.UDS_REQUEST_BASE == 0x600
    assert ids["PROTO_ID_STATUS"] == codes.CAN_ID_STATUS


def test_dbc_frame_ids_match_the_table(tool: Callable[[str], ModuleType]) -> None:
    import cantools

    db = cantools.database.load_file(str(ROOT / "firmware/proto/forceskill.dbc"))
    assert isinstance(db, cantools.database.can.Database)
    assert db.get_message_by_name("DeviceStatus").frame_id == codes.CAN_ID_STATUS
    assert db.get_message_by_name("HostCommand").frame_id == codes.CAN_ID_HOST_COMMAND
    assert db.get_message_by_name("Emergency").frame_id == codes.CAN_ID_EMERGENCY


def test_check_reports_a_stale_file(tmp_path: Path, tool: Callable[[str], ModuleType]) -> None:
    gen = tool("gen_codes")
    tables = ["firmware/base/codes.toml", "firmware/base/wire.toml", "firmware/proto/forceskill.dbc"]
    for rel in [*tables, *gen.outputs(gen.load(ROOT))]:
        (tmp_path / rel).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / rel).write_text((ROOT / rel).read_text())
    assert gen.check(tmp_path) == []
    p = tmp_path / "firmware/base/fs_status.h"
    p.write_text(p.read_text().replace("= 204,", "= 214,"))
    dbc = tmp_path / "firmware/proto/forceskill.dbc"
    dbc.write_text(dbc.read_text().replace("BO_ 384 DeviceStatus", "BO_ 385 DeviceStatus"))
    w = tmp_path / "host/forceskill/wire/generated.py"
    w.write_text(w.read_text().replace("SLOT_COUNT = 8", "SLOT_COUNT = 9"))
    dbc.write_text(
        dbc.read_text().replace("SG_ GoalScale m3 : 8|16@1+ (0.001,0)", "SG_ GoalScale m3 : 8|16@1+ (0.01,0)")
    )
    problems = gen.check(tmp_path)
    assert any("fs_status.h" in p for p in problems)
    assert any("DeviceStatus" in p for p in problems)
    assert any("wire/generated.py" in p for p in problems)
    assert any("GoalScale" in p for p in problems)

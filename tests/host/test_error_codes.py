"""The host's numbered codes mirror the firmware's C headers exactly (one list, two languages)."""
from __future__ import annotations

import re
from pathlib import Path

from forceskill import errors

ROOT = Path(__file__).resolve().parents[2]


def _c_enum(path: Path, prefix: str) -> dict[str, int]:
    text = path.read_text()
    return {m.group(1): int(m.group(2)) for m in re.finditer(rf"\b({prefix}\w+)\s*=\s*(\d+)", text)}


def test_fs_status_codes_are_mirrored() -> None:
    c = _c_enum(ROOT / "firmware/base/fs_status.h", "FS_ERR_")
    assert len(c) > 20
    for name, value in c.items():
        py = getattr(errors, name.replace("FS_ERR_", "ERR_"), None)
        assert py == value, f"{name} = {value} in fs_status.h, errors.py has {py}"


def test_device_fault_table_matches_flt_codes() -> None:
    c = _c_enum(ROOT / "firmware/base/flt_codes.h", "FLT_")
    faults = {v for k, v in c.items() if k != "FLT_NONE" and 500 <= v < 520}
    assert faults == set(errors.DEVICE_FAULTS), "errors.DEVICE_FAULTS differs from flt_codes.h"
    assert errors.fault_text(0) == "none"
    assert errors.fault_text(500) == "500 (host silence)"

"""The installed package finds its data inside itself (forceskill/data): nothing in it assumes the
repository around it."""

from __future__ import annotations

import re
from pathlib import Path

import forceskill
from forceskill.sim import scenario_dir
from forceskill.wire.dbc import dbc_path

PKG = Path(forceskill.__file__).resolve().parent


def test_the_data_is_found_inside_the_package() -> None:
    assert dbc_path().is_file() and PKG / "data" in dbc_path().parents
    scenarios = scenario_dir(None)
    assert Path(str(scenarios)).is_relative_to(PKG / "data") and any(scenarios.glob("*.toml"))


def test_no_module_climbs_out_of_the_package() -> None:
    climbing = re.compile(r"__file__.*(parents\[|\.parent\.parent)|parents\[\d\].*__file__")
    found = [
        f"{p.relative_to(PKG)}:{i}"
        for p in sorted(PKG.rglob("*.py"))
        for i, line in enumerate(p.read_text().splitlines(), 1)
        if climbing.search(line)
    ]
    assert found == []

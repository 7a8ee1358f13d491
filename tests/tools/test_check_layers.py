"""tools/check_layers.py: the tree and the host package pass, and an upward include or import, a sideways include, a narrow
layer used beyond its opening, an include cycle and a firmware -> hil_sim link edge (in the sources or a
build's objects) are each reported."""

from __future__ import annotations

import shutil
import subprocess
from collections.abc import Callable
from pathlib import Path
from types import ModuleType

import pytest

ROOT = Path(__file__).resolve().parents[2]


def _copy(tmp: Path) -> Path:
    for top in ("firmware", "hil_sim"):
        shutil.copytree(ROOT / top, tmp / top, ignore=shutil.ignore_patterns("*.png", "*.toml"))
    return tmp


def _add_include(path: Path, header: str) -> None:
    path.write_text(f'#include "{header}"\n' + path.read_text())


def test_the_tree_has_no_upward_include_and_no_cycle(tool: Callable[[str], ModuleType]) -> None:
    problems, graph = tool("check_layers").check(ROOT)
    assert problems == []
    assert ("app", "core") in graph and ("core", "fixed") not in graph


def test_violations_are_reported(tmp_path: Path, tool: Callable[[str], ModuleType]) -> None:
    mod = tool("check_layers")
    root = _copy(tmp_path)
    _add_include(root / "firmware/core/fs_num.h", "fs_num_fixed.h")  # upward
    _add_include(root / "firmware/storage/nvm.h", "flt_codes.h")  # fine: base
    _add_include(root / "firmware/security/sec_access.h", "nvm.h")  # sideways
    _add_include(root / "firmware/safety/lim.h", "pfc.h")  # beyond fs_real.h
    _add_include(root / "firmware/core/dmp.h", "skill.h")  # skill.h -> dmp.h: cycle
    problems, _ = mod.check(root)
    text = "\n".join(problems)
    assert "upward include of firmware/fixed/fs_num_fixed.h (core -> fixed)" in text
    assert "sideways include of firmware/storage/nvm.h (security -> storage)" in text
    assert "safety may use only fs_real.h of core, not pfc.h" in text
    assert "include cycle" in text and "firmware/core/skill.h" in text
    assert not any(p.startswith("firmware/storage/nvm.h:") for p in problems)


def test_a_private_header_outside_its_module_is_reported(
    tmp_path: Path, tool: Callable[[str], ModuleType]
) -> None:
    mod = tool("check_layers")
    root = _copy(tmp_path)
    _add_include(root / "firmware/ports/host/hal_host.c", "app_internal.h")  # a port: app.h only
    _add_include(root / "firmware/ports/host/hal_can_sim.c", "app.h")  # fine
    problems, _ = mod.check(root)
    assert problems == ["firmware/ports/host/hal_host.c: app_internal.h is private to app (use app.h)"]


def _copy_host(tmp: Path) -> Path:
    shutil.copytree(
        ROOT / "host" / "forceskill",
        tmp / "host" / "forceskill",
        ignore=shutil.ignore_patterns("__pycache__", "data"),
    )
    return tmp


def test_the_host_package_imports_only_downwards(tool: Callable[[str], ModuleType]) -> None:
    problems, graph = tool("check_layers").check_host(ROOT)
    assert problems == []
    assert ("commands", "link") in graph and ("link", "model") in graph
    assert ("model", "link") not in graph and ("link", "commands") not in graph


def test_host_violations_are_reported(tmp_path: Path, tool: Callable[[str], ModuleType]) -> None:
    mod = tool("check_layers")
    pkg = _copy_host(tmp_path) / "host" / "forceskill"

    def prepend(rel: str, line: str) -> None:
        p = pkg / rel
        p.write_text(line + "\n" + p.read_text())

    prepend("model/skill.py", "from ..link import device")  # upward
    prepend("link/bus.py", "def f():\n    from ..commands import run")  # upward, inside a function
    prepend("model/tolerance.py", "from ..readers import canlog")  # fine: lower layer
    prepend("readers/csv.py", "from ..link import uds")  # readers use no module of link
    prepend("model/params.py", "from . import fit")  # fit -> params: cycle
    (pkg / "extra.py").write_text("")  # no layer
    problems, _ = mod.check_host(tmp_path)
    text = "\n".join(problems)
    assert "forceskill.model.skill: upward import of forceskill.link.device (model -> link)" in text
    assert "forceskill.link.bus: upward import of forceskill.commands.run (link -> commands)" in text
    assert "forceskill.readers.csv: upward import of forceskill.link.uds (readers -> link)" in text
    assert "import cycle" in text and "forceskill.model.params -> forceskill.model.fit" in text
    assert "forceskill.extra: module has no layer" in text
    assert not any(p.startswith("forceskill.model.tolerance:") for p in problems)
    assert not any("forceskill.wire.dbc" in p for p in problems)


def test_a_firmware_call_into_the_simulator_is_reported(
    tmp_path: Path, tool: Callable[[str], ModuleType]
) -> None:
    mod = tool("check_layers")
    root = _copy(tmp_path)
    main = root / "firmware/ports/mps2/mps2_main.c"
    main.write_text(
        main.read_text() + "\nvoid cm_extra(void);\nvoid cm_extra(void)\n{\n    sim_rng_seed(0);\n}\n"
    )
    problems, _ = mod.check(root)
    assert problems == [
        "firmware/ports/mps2/mps2_main.c: upward link edge: sim_rng_seed is defined in "
        "hil_sim/src/sim_rng.c (firmware -> hil_sim)"
    ]


def test_a_firmware_object_using_a_simulator_symbol_is_reported(
    tmp_path: Path, tool: Callable[[str], ModuleType]
) -> None:
    mod = tool("check_layers")
    cc, nm = shutil.which("cc"), shutil.which("nm")
    if cc is None or nm is None:
        pytest.skip("no cc/nm")
    sources = {
        "firmware/ports/b/CMakeFiles/img.dir/loop.c": "void plant_step(void);\nvoid loop(void) { plant_step(); }\n",
        "firmware/ports/b/CMakeFiles/img.dir/hal.c": "int hal_x(void) { return 1; }\n",
        "hil_sim/pil/CMakeFiles/plant.dir/plant.c": "int hal_x(void);\nvoid plant_step(void) { (void)hal_x(); }\n",
    }
    for rel, text in sources.items():
        src = tmp_path / rel
        src.parent.mkdir(parents=True, exist_ok=True)
        src.write_text(text)
        subprocess.run([cc, "-c", str(src), "-o", str(src.with_suffix(".c.o"))], check=True)
    assert mod.check_objects(tmp_path, nm) == [
        f"{tmp_path}: upward link edge: firmware objects use plant_step, defined only in hil_sim "
        "(firmware -> hil_sim)"
    ]

"""`load("name")` imports tools/name.py (the repository's scripts are not a package) so a test can
call its functions."""

from __future__ import annotations

import importlib.util
import sys
from types import ModuleType

from helpers.paths import TOOLS


def load(name: str) -> ModuleType:
    """tools/<name>.py as a module (registered in sys.modules under its name)."""
    spec = importlib.util.spec_from_file_location(name, TOOLS / f"{name}.py")
    assert spec and spec.loader
    mod = importlib.util.module_from_spec(spec)
    sys.modules[name] = mod
    spec.loader.exec_module(mod)
    return mod

"""Shared by every test folder: the `tool` fixture (`tool("name")` imports tools/name.py). Shared
helpers are the `helpers` package (tests/helpers), importable from any folder."""

from __future__ import annotations

import os
import sys
from collections.abc import Callable
from types import ModuleType

import pytest

from helpers.tools import load

# FORCESKILL_TEST_NO_MF4=1 (scripts/test_linux_can.sh, in the VM): python-can's import loads its MF4
# support, asammdf with pandas, whenever asammdf is installed: 6-7 s of the 7 s of `import can` here,
# 16-20 times that under qemu's TCG. Marked absent, python-can leaves MF4 out (the tests run there
# read and write no .mf4).
# The CLI the tests start as a process runs this checkout's package too (pytest.ini puts host/
# first on this interpreter's path).
_HOST = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "host")
os.environ["PYTHONPATH"] = os.pathsep.join(p for p in (_HOST, os.environ.get("PYTHONPATH", "")) if p)

if os.environ.get("FORCESKILL_TEST_NO_MF4") == "1":
    sys.modules.setdefault("asammdf", None)


@pytest.fixture
def tool() -> Callable[[str], ModuleType]:
    return load

"""Shared by every test folder: the `tool` fixture (`tool("name")` imports tools/name.py). Shared
helpers are the `helpers` package (tests/helpers), importable from any folder."""

from __future__ import annotations

from collections.abc import Callable
from types import ModuleType

import pytest

from helpers.tools import load


@pytest.fixture
def tool() -> Callable[[str], ModuleType]:
    return load

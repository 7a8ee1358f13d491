"""Fixtures of the CAN end-to-end tests: `hil_sim serve` on a free port (helpers.canbus.Server),
driven only through python-can's socketcand interface; `figure(line)`: a measured figure that
pytest prints in a "figures" section before its summary line (shown with -q too)."""

from __future__ import annotations

import time
from collections.abc import Callable, Iterator
from typing import Any

import pytest

from helpers.canbus import SCENARIOS, Server


@pytest.fixture(scope="module")
def server() -> Iterator[Server]:
    s = Server(SCENARIOS / "pressing_task1_demo.toml")
    time.sleep(0.2)
    yield s
    s.stop()


_FIGURES: list[str] = []


@pytest.fixture
def figure() -> Callable[[str], None]:
    return _FIGURES.append


def pytest_terminal_summary(terminalreporter: Any) -> None:
    if _FIGURES:
        terminalreporter.section("figures")
        for line in _FIGURES:
            terminalreporter.write_line(line)

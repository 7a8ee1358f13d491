"""Fixtures of the CAN end-to-end tests: `hil_sim serve` on a free port (helpers.canbus.Server),
driven only through python-can's socketcand interface."""

from __future__ import annotations

import time
from collections.abc import Iterator

import pytest

from helpers.canbus import SCENARIOS, Server


@pytest.fixture(scope="module")
def server() -> Iterator[Server]:
    s = Server(SCENARIOS / "pressing_task1_demo.toml")
    time.sleep(0.2)
    yield s
    s.stop()

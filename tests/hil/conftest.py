"""Fixtures of the HIL tests: the built hil_sim binary and the paper scenarios (helpers.paths)."""

from __future__ import annotations

from pathlib import Path

import pytest

from helpers.paths import SCENARIOS, hil_sim_path


@pytest.fixture(scope="session")
def hil_sim() -> Path:
    return hil_sim_path()


@pytest.fixture(scope="session")
def scenarios() -> Path:
    return SCENARIOS

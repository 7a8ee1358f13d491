"""Fixtures of the HIL tests: the built hil_sim binary and the paper scenarios.

The binary is $FORCESKILL_HIL_SIM, else build/hil_sim/hil_sim (the README's build). A missing
binary is a failure with the command that builds it, not a skip.
"""
from __future__ import annotations

import os
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
SCENARIOS = REPO / "hil_sim" / "scenarios"


@pytest.fixture(scope="session")
def hil_sim() -> Path:
    p = Path(os.environ.get("FORCESKILL_HIL_SIM", str(REPO / "build" / "hil_sim" / "hil_sim")))
    assert p.is_file() and os.access(p, os.X_OK), (
        f"hil_sim not built at {p}: run `cmake -S . -B build -G Ninja && ninja -C build hil_sim` "
        "or set FORCESKILL_HIL_SIM")
    return p


@pytest.fixture(scope="session")
def scenarios() -> Path:
    return SCENARIOS

"""Shared fixtures of the host tests: synthetic demonstrations and fitted skills."""

from __future__ import annotations

import pytest

from forceskill.model import synthetic
from forceskill.model.fit import FitResult, fit


@pytest.fixture(scope="session")
def press_fit() -> FitResult:
    return fit(
        synthetic.pressing(seed=5, duration_s=8.0),
        100.0,
        n_kernels=50,
        method="ridge",
        surface_m=synthetic.SURFACE_M,
    )


@pytest.fixture(scope="session")
def engrave_fit() -> FitResult:
    return fit(
        synthetic.engraving(seed=6, duration_s=8.0, k_v=280.0),
        280.0,
        n_kernels=50,
        method="lwr",
        surface_m=synthetic.SURFACE_M,
        end_policy="release",
    )

"""Parameter derivation (corrected eq. 14, docs/math.md) and its refusals."""
from __future__ import annotations

import math

import pytest

from forceskill.errors import ParamError
from forceskill.params import Gains, derive, goal_prime


@pytest.mark.parametrize("k", [1.0, 100.0, 280.0, 600.0, 5000.0])
def test_default_gains_give_alpha_9_beta_2_25_gamma_0_075k(k: float) -> None:
    p = derive(Gains(), k)
    assert p.alpha == pytest.approx(9.0, rel=1e-15)
    assert p.beta == pytest.approx(2.25, rel=1e-13)
    assert p.gamma == pytest.approx(0.075 * k, rel=1e-15)


def test_defaults_are_the_spec_values() -> None:
    g = Gains()
    assert (g.m_d_kg, g.k_d_Nspm, g.k_p_Npm, g.k_f, g.k_i_per_s) == (40.0, 400.0, 1170.0, 3.0, 27.0)


def test_derivation_matches_the_formulas_for_other_gains() -> None:
    g = Gains(m_d_kg=10.0, k_d_Nspm=150.0, k_p_Npm=400.0, k_f=1.0, k_i_per_s=5.0)
    k = 300.0
    alpha = 150.0 / 10.0 - 1.0
    gamma = k * 5.0 / (10.0 * alpha)
    beta = (400.0 + k * 1.0 - 10.0 * gamma) / (10.0 * alpha) - 1.0
    p = derive(g, k)
    assert (p.alpha, p.beta, p.gamma) == pytest.approx((alpha, beta, gamma), rel=1e-15)


@pytest.mark.parametrize("gains,k,code", [
    (Gains(m_d_kg=math.nan), 100.0, 101),
    (Gains(), math.inf, 101),
    (Gains(m_d_kg=0.0), 100.0, 102),
    (Gains(k_d_Nspm=40.0), 100.0, 103),
    (Gains(k_d_Nspm=30.0), 100.0, 103),
    (Gains(k_p_Npm=0.0, k_f=0.0), 100.0, 104),
    (Gains(k_p_Npm=1500.0), 100.0, 105),
    (Gains(), 0.0, 106),
    (Gains(), -5.0, 106),
    (Gains(k_i_per_s=-1.0), 100.0, 107),
])
def test_invalid_gains_are_refused_with_their_code(gains: Gains, k: float, code: int) -> None:
    with pytest.raises(ParamError) as e:
        derive(gains, k)
    assert e.value.code == code
    assert "\n" not in str(e.value)


def test_goal_prime_is_c_over_alpha_beta() -> None:
    g = Gains()
    p = derive(g, 100.0)
    c = (1170.0 * 0.02 + 3.0 * 4.0 + 27.0 * 10.0) / 40.0
    assert goal_prime(p, g, 0.02, 4.0, 10.0) == pytest.approx(c / (9.0 * 2.25), rel=1e-14)

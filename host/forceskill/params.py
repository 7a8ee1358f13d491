"""Gains of the parallel force/position law and the DMP parameters derived from them.

The paper's eq. 14, corrected for the stiffness k (docs/math.md):
``alpha = k_d/m_d - 1``, ``gamma = k*k_i/(m_d*alpha)``,
``beta = (k_p + k*k_f - m_d*gamma)/(m_d*alpha) - 1``; valid only if alpha > 0, beta > 0 and
``beta <= alpha/4`` (the phase is then monotone). Mirrors ``dmp_params_from_gains`` in
firmware/core/dmp.h, with the same error codes.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from .errors import (
    ERR_BETA_NONPOSITIVE,
    ERR_GAIN_NEGATIVE,
    ERR_KD_LE_MD,
    ERR_MASS_NONPOSITIVE,
    ERR_NOT_FINITE,
    ERR_PHASE_NOT_MONOTONE,
    ERR_STIFFNESS_NONPOSITIVE,
    ParamError,
)

#: beta <= alpha/4 is checked with this relative tolerance (DMP_MONOTONE_REL_TOL in dmp.h): the
#: default gains give beta = alpha/4 exactly in real numbers.
MONOTONE_REL_TOL = 1e-9


@dataclass(frozen=True)
class Gains:
    """Gains of one axis. Units: m_d kg, k_d N*s/m, k_p N/m, k_f dimensionless, k_i 1/s.

    Defaults (the paper gives none): alpha = 9, beta = 2.25 = alpha/4 for every k.
    """

    m_d_kg: float = 40.0
    k_d_Nspm: float = 400.0
    k_p_Npm: float = 1170.0
    k_f: float = 3.0
    k_i_per_s: float = 27.0


@dataclass(frozen=True)
class DmpParams:
    """DMP constants of the transformation and phase systems."""

    alpha: float
    beta: float
    gamma: float


def derive(gains: Gains, stiffness_Npm: float) -> DmpParams:
    """alpha, beta, gamma from gains and nominal stiffness; raises ParamError (1xx) if invalid."""
    values = {
        "m_d": gains.m_d_kg,
        "k_d": gains.k_d_Nspm,
        "k_p": gains.k_p_Npm,
        "k_f": gains.k_f,
        "k_i": gains.k_i_per_s,
        "stiffness": stiffness_Npm,
    }
    for name, val in values.items():
        if not math.isfinite(val):
            raise ParamError(ERR_NOT_FINITE, f"{name} is not finite: {val}")
    if gains.m_d_kg <= 0.0:
        raise ParamError(ERR_MASS_NONPOSITIVE, f"m_d must be > 0 kg: {gains.m_d_kg:g}")
    if stiffness_Npm <= 0.0:
        raise ParamError(ERR_STIFFNESS_NONPOSITIVE, f"stiffness must be > 0 N/m: {stiffness_Npm:g}")
    for name in ("k_d", "k_p", "k_f", "k_i"):
        if values[name] < 0.0:
            raise ParamError(ERR_GAIN_NEGATIVE, f"gain {name} must be >= 0: {values[name]:g}")
    if gains.k_d_Nspm <= gains.m_d_kg:
        raise ParamError(
            ERR_KD_LE_MD,
            f"k_d must exceed m_d (alpha > 0), got k_d = {gains.k_d_Nspm:g}, m_d = {gains.m_d_kg:g}",
        )
    m_d = gains.m_d_kg
    alpha = gains.k_d_Nspm / m_d - 1.0
    gamma = stiffness_Npm * gains.k_i_per_s / (m_d * alpha)
    beta = (gains.k_p_Npm + stiffness_Npm * gains.k_f - m_d * gamma) / (m_d * alpha) - 1.0
    if not beta > 0.0:
        raise ParamError(ERR_BETA_NONPOSITIVE, f"derived beta must be > 0 (unstable system): beta = {beta:g}")
    if beta > 0.25 * alpha * (1.0 + MONOTONE_REL_TOL):
        raise ParamError(
            ERR_PHASE_NOT_MONOTONE,
            f"beta must be <= alpha/4 for a monotone phase: beta = {beta:g}, alpha/4 = {0.25 * alpha:g}",
        )
    return DmpParams(alpha=alpha, beta=beta, gamma=gamma)


def goal_prime(
    p: DmpParams, gains: Gains, pos_d_m: float, force_d_N: float, force_d_integral_Ns: float
) -> float:
    """g'(t) = c/(alpha*beta), c = (k_p*x_d + k_f*f_d + k_i*int f_d)/m_d."""
    c = (
        gains.k_p_Npm * pos_d_m + gains.k_f * force_d_N + gains.k_i_per_s * force_d_integral_Ns
    ) / gains.m_d_kg
    return c / (p.alpha * p.beta)

"""Gains of the parallel force/position law and the DMP parameters derived from them.

The force gains scale with the nominal stiffness k: a skill stores ``kkf = k*k_f`` (N/m) and
``kki = k*k_i`` (N/(m s)), so with the DMP in force units (``y = k*x``) nothing in it depends on k
(docs/math.md section 1):
``alpha = k_d/m_d - 1``, ``gamma = kki/(m_d*alpha)``, ``beta = (k_p + kkf - kki/alpha)/(m_d*alpha) - 1``;
valid only if alpha > 0, beta > 0 (which implies the closed loop is stable, Routh-Hurwitz) and
``beta <= alpha/4`` (the phase is then monotone). Mirrors ``dmp_derive_f64`` in firmware/core/dmp.h,
with the same error codes.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields
from pathlib import Path
from typing import Any

from ..errors import (
    ERR_BETA_NONPOSITIVE,
    ERR_FIT_ARGS,
    ERR_FORCE_GAIN_INERTIA,
    ERR_GAIN_NEGATIVE,
    ERR_GAINS_FILE,
    ERR_KD_LE_MD,
    ERR_MASS_NONPOSITIVE,
    ERR_NOT_FINITE,
    ERR_PHASE_NOT_MONOTONE,
    ERR_STIFFNESS_NONPOSITIVE,
    FsError,
    ParamError,
)

#: beta <= alpha/4 is checked with this relative tolerance (DMP_MONOTONE_REL_TOL in dmp.h): the
#: default gains give beta = alpha/4 exactly in real numbers.
MONOTONE_REL_TOL = 1e-9


@dataclass(frozen=True)
class Gains:
    """Gains of the constrained axis, stiffness-independent. Units: m_d kg, k_d N*s/m, k_p N/m,
    kkf_Npm = k*k_f in N/m, kki_Npms = k*k_i in N/(m*s) (k_f = kkf/k dimensionless, k_i = kki/k 1/s).

    Defaults (the paper gives none): alpha = 9, beta = 2.25 = alpha/4, gamma = 13.5 for every k
    (k_f = 3, k_i = 27 at the paper's 180 N/m).
    """

    m_d_kg: float = 40.0
    k_d_Nspm: float = 400.0
    k_p_Npm: float = 1170.0
    kkf_Npm: float = 540.0
    kki_Npms: float = 4860.0

    def force_gains(self, stiffness_Npm: float) -> tuple[float, float]:
        """(k_f, k_i) the controller uses on an object of nominal stiffness k."""
        return self.kkf_Npm / stiffness_Npm, self.kki_Npms / stiffness_Npm


@dataclass(frozen=True)
class DmpParams:
    """DMP constants of the transformation and phase systems."""

    alpha: float
    beta: float
    gamma: float


def derive(gains: Gains) -> DmpParams:
    """alpha, beta, gamma from the gains; raises ParamError (1xx) if invalid or unstable."""
    values = {
        "m_d": gains.m_d_kg,
        "k_d": gains.k_d_Nspm,
        "k_p": gains.k_p_Npm,
        "kkf": gains.kkf_Npm,
        "kki": gains.kki_Npms,
    }
    for name, val in values.items():
        if not math.isfinite(val):
            raise ParamError(ERR_NOT_FINITE, f"{name} is not finite: {val}")
    if gains.m_d_kg <= 0.0:
        raise ParamError(ERR_MASS_NONPOSITIVE, f"m_d must be > 0 kg: {gains.m_d_kg:g}")
    for name in ("k_d", "k_p", "kkf", "kki"):
        if values[name] < 0.0:
            raise ParamError(ERR_GAIN_NEGATIVE, f"gain {name} must be >= 0: {values[name]:g}")
    if gains.k_d_Nspm <= gains.m_d_kg:
        raise ParamError(
            ERR_KD_LE_MD,
            f"k_d must exceed m_d (alpha > 0), got k_d = {gains.k_d_Nspm:g}, m_d = {gains.m_d_kg:g}",
        )
    m_d = gains.m_d_kg
    alpha = gains.k_d_Nspm / m_d - 1.0
    if not alpha > 0.0:
        raise ParamError(ERR_KD_LE_MD, f"k_d must exceed m_d (alpha > 0), got alpha = {alpha:g}")
    if not math.isfinite(alpha):
        raise ParamError(ERR_NOT_FINITE, f"derived alpha = k_d/m_d - 1 is not finite: {alpha}")
    gamma = gains.kki_Npms / (m_d * alpha)
    beta = (gains.k_p_Npm + (gains.kkf_Npm - gains.kki_Npms / alpha)) / (m_d * alpha) - 1.0
    if not (math.isfinite(gamma) and math.isfinite(beta)):
        raise ParamError(ERR_NOT_FINITE, f"derived gamma/beta not finite: {gamma}, {beta}")
    if not beta > 0.0:
        raise ParamError(ERR_BETA_NONPOSITIVE, f"derived beta must be > 0 (unstable system): beta = {beta:g}")
    if beta > 0.25 * alpha * (1.0 + MONOTONE_REL_TOL):
        raise ParamError(
            ERR_PHASE_NOT_MONOTONE,
            f"beta must be <= alpha/4 for a monotone phase: beta = {beta:g}, alpha/4 = {0.25 * alpha:g}",
        )
    return DmpParams(alpha=alpha, beta=beta, gamma=gamma)


def check_stiffness(stiffness_Npm: float) -> None:
    """k finite (101) and > 0 (106)."""
    if not math.isfinite(stiffness_Npm):
        raise ParamError(ERR_NOT_FINITE, f"stiffness is not finite: {stiffness_Npm}")
    if stiffness_Npm <= 0.0:
        raise ParamError(ERR_STIFFNESS_NONPOSITIVE, f"stiffness must be > 0 N/m: {stiffness_Npm:g}")


def check_inertia(gains: Gains, stiffness_Npm: float, object_mass_kg: float) -> None:
    """k_f*m_v/m_d < 1 (code 112): a sampled force sensor feeds the object's inertia m_v back
    through k_f; at or above 1 that loop is unstable."""
    k_f = gains.force_gains(stiffness_Npm)[0]
    ratio = k_f * object_mass_kg / gains.m_d_kg
    if not ratio < 1.0:
        raise ParamError(
            ERR_FORCE_GAIN_INERTIA,
            f"k_f*m_v/m_d = {ratio:.3g} must be < 1 (k_f = kkf/k = "
            f"{k_f:.4g}, m_v = {object_mass_kg:g} kg, m_d = {gains.m_d_kg:g} kg): lower kkf_Npm "
            "or raise m_d_kg",
        )


#: When the default force gains are adapted to a known object mass, k_f*m_v/m_d is brought down to
#: this (a margin below the stability bound 1).
INERTIA_MARGIN = 0.75


def gains_for_object(stiffness_Npm: float, object_mass_kg: float, base: Gains = Gains()) -> Gains:
    """``base`` if k_f*m_v/m_d <= INERTIA_MARGIN on this object (k_f = kkf/k), else ``base`` with kkf
    and kki scaled down together so that it equals INERTIA_MARGIN (for the default gains beta stays
    alpha/4: kkf = kki/alpha is kept). Soft, heavy objects need this: the defaults give k_f = 5.4
    at 100 N/m, 1.35 with a 10 kg object and m_d = 40 kg; scaled, k_f = 3, k_i = 27 (the paper's)."""
    check_stiffness(stiffness_Npm)
    if not (math.isfinite(object_mass_kg) and object_mass_kg > 0.0):
        raise ParamError(ERR_FIT_ARGS, f"object mass must be > 0 kg: {object_mass_kg:g}")
    ratio = base.force_gains(stiffness_Npm)[0] * object_mass_kg / base.m_d_kg
    if ratio <= INERTIA_MARGIN:
        return base
    kkf = INERTIA_MARGIN * base.m_d_kg * stiffness_Npm / object_mass_kg
    return Gains(base.m_d_kg, base.k_d_Nspm, base.k_p_Npm, kkf, kkf * (base.kki_Npms / base.kkf_Npm))


def goal(
    p: DmpParams, gains: Gains, ref_force_N: float, force_d_N: float, force_d_integral_Ns: float
) -> float:
    """Goal in N, k*g'(t) = c/(alpha*beta), c = (k_p*(k*x_d) + kkf*f_d + kki*int f_d)/m_d, with the
    position reference given as the force k*x_d it corresponds to."""
    c = (
        gains.k_p_Npm * ref_force_N + gains.kkf_Npm * force_d_N + gains.kki_Npms * force_d_integral_Ns
    ) / gains.m_d_kg
    return c / (p.alpha * p.beta)


#: Keys of a gains file (TOML); ``m_v_kg``, the object's mass, enables the k_f*m_v/m_d < 1 check.
GAIN_KEYS = tuple(f.name for f in fields(Gains))


def load_gains(path: str) -> tuple[Gains, float | None]:
    """Read a TOML gains file: any of m_d_kg, k_d_Nspm, k_p_Npm, kkf_Npm, kki_Npms (the rest keep
    their defaults) and optionally m_v_kg; validated with ``derive``. Returns (gains, m_v or None).
    Unreadable file, bad TOML, unknown key or non-number: FsError 613."""
    try:
        import tomllib
    except ModuleNotFoundError:  # Python < 3.11
        import tomli as tomllib  # type: ignore[no-redef,unused-ignore]
    try:
        raw = Path(path).read_bytes()
    except OSError as e:
        raise FsError(ERR_GAINS_FILE, f"cannot read gains file {path!r}: {e.strerror}") from None
    try:
        doc: dict[str, Any] = tomllib.loads(raw.decode("utf-8"))
    except (UnicodeDecodeError, tomllib.TOMLDecodeError) as e:
        raise FsError(ERR_GAINS_FILE, f"gains file {path!r} is not valid TOML: {e}") from None
    if isinstance(doc.get("gains"), dict) and len(doc) == 1:
        doc = doc["gains"]
    allowed = (*GAIN_KEYS, "m_v_kg")
    kw: dict[str, float] = {}
    for key, val in doc.items():
        if key not in allowed:
            raise FsError(
                ERR_GAINS_FILE, f"gains file {path!r}: unknown key {key!r} (known: {', '.join(allowed)})"
            )
        if isinstance(val, bool) or not isinstance(val, (int, float)):
            raise FsError(ERR_GAINS_FILE, f"gains file {path!r}: {key} must be a number, got {val!r}")
        kw[key] = float(val)
    m_v = kw.pop("m_v_kg", None)
    if m_v is not None and not (math.isfinite(m_v) and m_v > 0.0):
        raise FsError(ERR_GAINS_FILE, f"gains file {path!r}: m_v_kg must be > 0: {m_v:g}")
    gains = Gains(**kw)
    derive(gains)
    return gains, m_v

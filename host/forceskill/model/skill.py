"""Skill image v2/v3/v4 (docs/skill_format.md): bytes, validation and the JSON twin.

Version 3 adds the optional position DMP on y (start, goal and one weight per kernel, sharing the
force DMP's phase and kernels); a skill without it is written as version 2, readable by every
device that reads force-only skills. Version 4 adds the kind (discrete or periodic) and the
periodic DMP's amplitude and state on the cycle, and the optional contact wait (a phase that
waits while the contact force is lost); only periodic skills and skills with a contact wait are
written as version 4. Version 5 adds the demonstrated band: a lower and an upper force bound at
points uniform over the skill's normalised time (``fit`` of several recordings); only skills
with a band are written as version 5.

A skill is plain data (dmpbbo style): fitting produces it, the firmware parses and evaluates it.
Validation runs the same checks, in the same order, with the same codes as ``skill_parse`` in
firmware/core/skill.c; the bad images in tests/vectors/bad/ prove it.
"""

from __future__ import annotations

import json
import math
import struct
import zlib
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from ..errors import (
    ERR_IO,
    ERR_SKILL_AMPLITUDE,
    ERR_SKILL_BAND,
    ERR_SKILL_CENTRES,
    ERR_SKILL_CONTACT_WAIT,
    ERR_SKILL_CRC,
    ERR_SKILL_GAINS,
    ERR_SKILL_HEADER_SIZE,
    ERR_SKILL_KERNELS,
    ERR_SKILL_KIND,
    ERR_SKILL_LENGTH,
    ERR_SKILL_MAGIC,
    ERR_SKILL_NOT_FINITE,
    ERR_SKILL_PERIOD,
    ERR_SKILL_PHASES,
    ERR_SKILL_RANGE,
    ERR_SKILL_TOO_SHORT,
    ERR_SKILL_UNSUPPORTED,
    ERR_SKILL_VERSION,
    ParamError,
    SkillError,
)
from .params import MONOTONE_REL_TOL, DmpParams, Gains, derive

if TYPE_CHECKING:
    from ..outputs import Outputs

MAGIC = 0x4C4B5346  # bytes "FSKL"
FORMAT_VERSION = 5
#: the oldest version this reads (v1 stored metres and stiffness-dependent gains)
FORMAT_VERSION_MIN = 2
HEADER_SIZE_V2 = 136
HEADER_SIZE = 152  # version 3: the v2 header, then y_start_m and goal_y_m
HEADER_SIZE_V4 = 208  # version 4: the v3 header, six f64 of the periodic DMP, kind, contact wait
HEADER_SIZE_V5 = 216  # version 5: the v4 header, the band's point count and three reserved u16
#: the band's points (version 5): at least two, at most this many
BAND_MIN_POINTS = 2
BAND_MAX_POINTS = 128
CRC_SIZE = 4
MAX_KERNELS = 1024  # DMP_MAX_KERNELS
FLAG_END_RELEASE = 0x0001
FLAG_Y_AXIS = 0x0002  # version 3: the position DMP on y is present (refused in version 2)
KNOWN_FLAGS = {
    2: FLAG_END_RELEASE,
    3: FLAG_END_RELEASE | FLAG_Y_AXIS,
    4: FLAG_END_RELEASE | FLAG_Y_AXIS,
    5: FLAG_END_RELEASE | FLAG_Y_AXIS,
}
KIND_DISCRETE = 0
KIND_PERIODIC = 1
KINDS = {KIND_DISCRETE: "discrete", KIND_PERIODIC: "periodic"}
#: v4's contact wait: threshold in steps of 0.01 N (u16), time constant in ms (u16) up to this
CONTACT_THRESHOLD_STEP_N = 0.01
CONTACT_TAU_MS_MAX = 10000
#: a periodic skill's duration is its period: |T - 2*pi*tau| within this of T
PERIOD_REL_TOL = 1e-9
RELEASE_TIME_S = 0.5
GAINS_REL_TOL = 1e-9  # stored alpha/beta/gamma vs derived from stored gains
DT_MAX_S = 0.1
DURATION_MAX_S = 3600.0

# magic u32, version u16, header_size u16, total_length u32, n u16, flags u16, then 15 f64 (v2)
# or 17 f64 (v3)
_HEADER_V2 = struct.Struct("<IHHIHH15d")
_HEADER_V3 = struct.Struct("<IHHIHH17d")
# v4: the v3 fields, 6 f64 more (amplitude_N, e0_N, z0_N, i0_N, y_p0_m, y_z0_m), kind u16,
# contact-wait threshold u16 (0.01 N), its time constant u16 (ms), reserved u16 (0)
_HEADER_V4 = struct.Struct("<IHHIHH23dHHHH")
# v5: the v4 fields, the band's point count M u16 and three reserved u16 (0)
_HEADER_V5 = struct.Struct("<IHHIHH23dHHHHHHHH")
_HEADERS = {2: _HEADER_V2, 3: _HEADER_V3, 4: _HEADER_V4, 5: _HEADER_V5}
#: the fixed part every version shares (magic, version): enough to name an old image's version
_PREFIX = struct.Struct("<IH")
assert _HEADER_V2.size == HEADER_SIZE_V2 and _HEADER_V3.size == HEADER_SIZE
assert _HEADER_V4.size == HEADER_SIZE_V4 and _HEADER_V5.size == HEADER_SIZE_V5
_F64_NAMES = (
    "dt_s",
    "tau_s",
    "alpha",
    "beta",
    "gamma",
    "stiffness_Npm",
    "goal_N",
    "duration_s",
    "m_d_kg",
    "k_d_Nspm",
    "k_p_Npm",
    "kkf_Npm",
    "kki_Npms",
    "surface_m",
    "force0_N",
)
#: the version-3 header's two more fields (the y half; 0 in a force-only v3 image)
_F64_NAMES_Y = ("y_start_m", "goal_y_m")
#: the version-4 header's six more (the periodic DMP; 0 in a discrete v4 image)
_F64_NAMES_P = ("amplitude_N", "e0_N", "z0_N", "i0_N", "y_p0_m", "y_z0_m")


def _f64_names(version: int) -> tuple[str, ...]:
    """The header's float64 fields of a format version, in image order."""
    return _F64_NAMES + (_F64_NAMES_Y if version >= 3 else ()) + (_F64_NAMES_P if version >= 4 else ())


PathLike = str | Path


def image_size(n_kernels: int, version: int = 2, has_y: bool = False, band_points: int = 0) -> int:
    """Total image length in bytes for N kernels: v2 136 + 24 N + 4; v3 152 + 24 N (+ 8 N with
    the y DMP) + 4; v4 the same arrays after a 208-byte header; v5 after a 216-byte header, then
    the band's M lower and M upper bounds (+ 16 M)."""
    if version == 2:
        return HEADER_SIZE_V2 + 24 * n_kernels + CRC_SIZE
    header = HEADER_SIZE_V5 if version >= 5 else HEADER_SIZE_V4 if version >= 4 else HEADER_SIZE
    band = 16 * band_points if version >= 5 else 0
    return header + (32 if has_y else 24) * n_kernels + band + CRC_SIZE


def derive_beta_y(gains: Gains) -> float:
    """beta of the position DMP on y (the law with k_f = k_i = 0): k_p/(m_d*alpha) - 1; the same
    alpha, gamma = 0. Raises ParamError (1xx) for gains derive refuses, 104/105 for beta_y."""
    from ..errors import ERR_BETA_NONPOSITIVE, ERR_PHASE_NOT_MONOTONE

    alpha = derive(gains).alpha
    beta_y = gains.k_p_Npm / (gains.m_d_kg * alpha) - 1.0
    if not beta_y > 0.0:
        raise ParamError(ERR_BETA_NONPOSITIVE, f"y DMP beta = k_p/(m_d*alpha) - 1 must be > 0: {beta_y:g}")
    if beta_y > 0.25 * alpha * (1.0 + MONOTONE_REL_TOL):
        raise ParamError(
            ERR_PHASE_NOT_MONOTONE,
            f"y DMP beta must be <= alpha/4: beta_y = {beta_y:g}, alpha/4 = {0.25 * alpha:g}",
        )
    return beta_y


def image_crc32(image: bytes) -> int:
    """The CRC-32 a skill image stores in its last 4 bytes (little-endian, over the body before it)."""
    return int(struct.unpack_from("<I", image, len(image) - 4)[0])


@dataclass
class Skill:
    """One learned force skill; fields as docs/skill_format.md (flags bit 0 = end policy release)."""

    dt_s: float
    tau_s: float
    alpha: float
    beta: float
    gamma: float
    stiffness_Npm: float
    goal_N: float
    duration_s: float
    m_d_kg: float
    k_d_Nspm: float
    k_p_Npm: float
    kkf_Npm: float
    kki_Npms: float
    surface_m: float
    centres: np.ndarray
    widths: np.ndarray
    weights: np.ndarray
    force0_N: float = 0.0
    flags: int = 0
    format_version: int = field(default=0)
    #: the position DMP on y (version 3, flags bit 1): y_hat = y_start + p, p its state (m),
    #: goal_y_m its goal, y_weights in m (h_y = v~*S_y(u~)); None: a force-only skill
    y_start_m: float = 0.0
    goal_y_m: float = 0.0
    y_weights: np.ndarray | None = None
    #: version 4: KIND_DISCRETE or KIND_PERIODIC. A periodic skill (docs/math.md section 5):
    #: centres are phases in [0, 2*pi), widths the von Mises concentrations kappa_i, duration_s
    #: the period 2*pi*tau, goal_N the mean force, amplitude_N the stroke's amplitude r (h =
    #: r*S(phi)), (e0, z0, i0) the state on the cycle at phi = 0 (N); with the y path (flags
    #: bit 1) y_p0_m, y_z0_m its (q, z_q) on the cycle at phi = 0 (m; 0 without one)
    kind: int = KIND_DISCRETE
    amplitude_N: float = 0.0
    e0_N: float = 0.0
    z0_N: float = 0.0
    i0_N: float = 0.0
    y_p0_m: float = 0.0
    y_z0_m: float = 0.0
    #: version 4, any kind: the contact wait (docs/math.md, "A phase that waits for contact"):
    #: contact is lost while f_hat - f_contact > contact_cN/100 N, and the phase rate goes to 0
    #: (back to 1 when contact returns) with the time constant contact_tau_ms; 0: off
    contact_cN: int = 0
    contact_tau_ms: int = 0
    #: version 5: the demonstrated band, lower and upper force bounds (N) at M points uniform over
    #: the normalised time t/T in [0, 1] (a periodic skill: over one period); None: no band
    band_lo_N: np.ndarray | None = None
    band_hi_N: np.ndarray | None = None

    def __post_init__(self) -> None:
        self.centres = np.ascontiguousarray(self.centres, dtype=np.float64).reshape(-1)
        self.widths = np.ascontiguousarray(self.widths, dtype=np.float64).reshape(-1)
        self.weights = np.ascontiguousarray(self.weights, dtype=np.float64).reshape(-1)
        if self.y_weights is not None:
            self.y_weights = np.ascontiguousarray(self.y_weights, dtype=np.float64).reshape(-1)
            self.flags |= FLAG_Y_AXIS
        if self.band_lo_N is not None or self.band_hi_N is not None:
            self.band_lo_N = np.ascontiguousarray(self.band_lo_N, dtype=np.float64).reshape(-1)
            self.band_hi_N = np.ascontiguousarray(self.band_hi_N, dtype=np.float64).reshape(-1)
        if self.format_version == 0:  # v2 unless it needs v3 (y), v4 (periodic, contact wait), v5 (band)
            v4 = self.kind != KIND_DISCRETE or self.contact_cN != 0 or self.contact_tau_ms != 0
            v = 4 if v4 else 3 if self.y_weights is not None else 2
            self.format_version = 5 if self.band_lo_N is not None else v

    # -- derived views ---------------------------------------------------------------------
    @property
    def n_kernels(self) -> int:
        return int(self.centres.size)

    @property
    def end_policy(self) -> str:
        """'hold' (keep the last force after T) or 'release' (ramp to zero in 0.5 s)."""
        return "release" if self.flags & FLAG_END_RELEASE else "hold"

    @property
    def periodic(self) -> bool:
        """True for a periodic (rhythmic) skill (format v4, kind 1)."""
        return self.kind == KIND_PERIODIC

    @property
    def contact_wait(self) -> bool:
        """True if the phase waits for contact (format v4, a threshold above 0)."""
        return self.contact_cN > 0

    @property
    def contact_threshold_N(self) -> float:
        """The contact-wait threshold: contact is lost while f_hat - f_contact exceeds it."""
        return self.contact_cN * CONTACT_THRESHOLD_STEP_N

    @property
    def contact_tau_s(self) -> float:
        """The contact wait's time constant of the phase rate (s)."""
        return self.contact_tau_ms / 1000.0

    @property
    def has_band(self) -> bool:
        """True if the skill carries the demonstrated band (format v5)."""
        return self.band_lo_N is not None

    @property
    def band_points(self) -> int:
        """The band's point count M (0 without a band)."""
        return 0 if self.band_lo_N is None else int(self.band_lo_N.size)

    def band_at(
        self, t_s: np.ndarray, goal_scale: float = 1.0, time_scale: float = 1.0, amplitude_scale: float = 1.0
    ) -> tuple[np.ndarray, np.ndarray]:
        """The band's bounds at run times t_s (linear between points, the end points held), scaled
        as f_hat is: a discrete skill's about the starting force, f0 + goal_scale*(b - f0); a
        periodic one's (repeating every period) goal_scale*g + amplitude_scale*(b - g), g its
        mean force."""
        if self.band_lo_N is None or self.band_hi_N is None:
            raise ValueError("skill has no band")
        period = self.duration_s * time_scale
        s = np.asarray(t_s, dtype=float) / period
        if self.periodic:
            s = s - np.floor(s)
        x = np.linspace(0.0, 1.0, self.band_lo_N.size)
        lo = np.interp(np.clip(s, 0.0, 1.0), x, self.band_lo_N)
        hi = np.interp(np.clip(s, 0.0, 1.0), x, self.band_hi_N)
        if self.periodic:
            g = self.goal_N
            return goal_scale * g + amplitude_scale * (lo - g), goal_scale * g + amplitude_scale * (hi - g)
        f0 = self.force0_N
        return f0 + goal_scale * (lo - f0), f0 + goal_scale * (hi - f0)

    @property
    def has_y(self) -> bool:
        """True if the skill carries the position DMP on y."""
        return self.y_weights is not None

    @property
    def beta_y(self) -> float:
        """beta of the y DMP, derived from the stored gains (alpha and gamma = 0 as said)."""
        return self.k_p_Npm / (self.m_d_kg * self.alpha) - 1.0

    @property
    def gains(self) -> Gains:
        return Gains(self.m_d_kg, self.k_d_Nspm, self.k_p_Npm, self.kkf_Npm, self.kki_Npms)

    @property
    def params(self) -> DmpParams:
        return DmpParams(self.alpha, self.beta, self.gamma)

    # -- bytes -----------------------------------------------------------------------------
    def to_bytes(self, validate: bool = True) -> bytes:
        """The image (v2 for a force-only skill, v3 with the y DMP; little-endian, CRC-32 last).
        Validates first unless told not to."""
        n = self.n_kernels
        yw = self.y_weights
        if not (self.widths.size == n and self.weights.size == n and (yw is None or yw.size == n)):
            raise SkillError(
                ERR_SKILL_LENGTH,
                f"centres/widths/weights/y_weights lengths differ: {n}/{self.widths.size}/"
                f"{self.weights.size}/{n if yw is None else yw.size}",
            )
        version = self.format_version
        header = _HEADERS.get(version, _HEADER_V3)
        hv = next(v for v, h in _HEADERS.items() if h is header)
        lo, hi = self.band_lo_N, self.band_hi_N
        m = 0 if lo is None or hi is None or hv < 5 else lo.size
        if m and (hi is None or hi.size != m):
            raise SkillError(ERR_SKILL_BAND, "band lower and upper bounds differ in length")
        head = header.pack(
            MAGIC,
            version,
            header.size,
            image_size(n, hv, yw is not None, m),
            n,
            self.flags,
            *(float(getattr(self, k)) for k in _f64_names(hv)),
            *((self.kind, self.contact_cN, self.contact_tau_ms, 0) if hv >= 4 else ()),
            *((m, 0, 0, 0) if hv >= 5 else ()),
        )
        body = (
            head
            + self.centres.astype("<f8").tobytes()
            + self.widths.astype("<f8").tobytes()
            + self.weights.astype("<f8").tobytes()
            + (b"" if yw is None else yw.astype("<f8").tobytes())
            + (
                b""
                if not m or lo is None or hi is None
                else lo.astype("<f8").tobytes() + hi.astype("<f8").tobytes()
            )
        )
        image = body + struct.pack("<I", zlib.crc32(body) & 0xFFFFFFFF)
        if validate:
            Skill.from_bytes(image)
        return image

    @staticmethod
    def from_bytes(buf: bytes) -> Skill:
        """Parse and validate an image (v2, v3 or v4); raises SkillError with the firmware's code
        (200-211, 228-231)."""
        buf = bytes(buf)
        if len(buf) < _PREFIX.size:
            raise SkillError(
                ERR_SKILL_TOO_SHORT, f"skill image too short: {len(buf)} bytes, header is {HEADER_SIZE_V2}"
            )
        magic, version = _PREFIX.unpack_from(buf, 0)
        if magic != MAGIC:
            raise SkillError(
                ERR_SKILL_MAGIC, f"skill image magic is 0x{magic:08X}, expected 0x{MAGIC:08X} ('FSKL')"
            )
        if not FORMAT_VERSION_MIN <= version <= FORMAT_VERSION:
            hint = (
                " (fitted before skills ran in force units: fit the demonstration again)"
                if version < FORMAT_VERSION_MIN
                else ""
            )
            raise SkillError(
                ERR_SKILL_VERSION,
                f"skill image format version {version} is not supported: this "
                f"reads versions {FORMAT_VERSION_MIN} to {FORMAT_VERSION}{hint}",
            )
        header = _HEADERS[version]
        if len(buf) < header.size:
            raise SkillError(
                ERR_SKILL_TOO_SHORT, f"skill image too short: {len(buf)} bytes, header is {header.size}"
            )
        fields = header.unpack_from(buf, 0)
        _, _, header_size, total_length, n, flags = fields[:6]
        names = _f64_names(version)
        f64 = dict(zip(names, fields[6 : 6 + len(names)], strict=True))
        tail = [int(x) for x in fields[6 + len(names) :]]
        kind, contact_cn, contact_ms, reserved = tail[:4] if version >= 4 else (KIND_DISCRETE, 0, 0, 0)
        band_m, band_reserved = (tail[4], tail[5:]) if version >= 5 else (0, [0])
        if header_size != header.size:
            raise SkillError(
                ERR_SKILL_HEADER_SIZE, f"skill header_size is {header_size}, expected {header.size}"
            )
        has_y = version >= 3 and bool(flags & FLAG_Y_AXIS)
        size = image_size(n, version, has_y, band_m)
        if total_length != len(buf) or total_length != size:
            raise SkillError(
                ERR_SKILL_LENGTH,
                f"skill length field {total_length} disagrees with buffer "
                f"({len(buf)} bytes) or with N = {n} ({size} bytes)",
            )
        body_len = total_length - CRC_SIZE
        (stored_crc,) = struct.unpack_from("<I", buf, body_len)
        crc = zlib.crc32(buf[:body_len]) & 0xFFFFFFFF
        if crc != stored_crc:
            raise SkillError(
                ERR_SKILL_CRC, f"skill CRC-32 mismatch: stored 0x{stored_crc:08X}, computed 0x{crc:08X}"
            )
        if not 1 <= n <= MAX_KERNELS:
            raise SkillError(ERR_SKILL_KERNELS, f"skill kernel count {n} outside 1..{MAX_KERNELS}")
        if kind not in KINDS or reserved != 0:
            raise SkillError(
                ERR_SKILL_KIND,
                f"skill kind {kind} (reserved 0x{reserved:X}) is not 0 (discrete) or 1 (periodic), "
                "or the reserved field not 0",
            )
        if version >= 5 and (not BAND_MIN_POINTS <= band_m <= BAND_MAX_POINTS or any(band_reserved)):
            raise SkillError(
                ERR_SKILL_BAND,
                f"skill band of {band_m} points (reserved {band_reserved}): the count must be in "
                f"{BAND_MIN_POINTS}..{BAND_MAX_POINTS} and the reserved fields 0",
            )
        n_arr = 4 if has_y else 3
        arrays = np.frombuffer(buf, dtype="<f8", count=n_arr * n + 2 * band_m, offset=header.size).astype(
            np.float64
        )
        centres, widths, weights = arrays[:n].copy(), arrays[n : 2 * n].copy(), arrays[2 * n : 3 * n].copy()
        y_weights = arrays[3 * n : n_arr * n].copy() if has_y else None
        band_lo = arrays[n_arr * n : n_arr * n + band_m].copy() if band_m else None
        band_hi = arrays[n_arr * n + band_m :].copy() if band_m else None
        for name, val in f64.items():
            if not math.isfinite(val):
                raise SkillError(ERR_SKILL_NOT_FINITE, f"skill field {name} is not finite: {val}")
        named = [("centres", centres), ("widths", widths), ("weights", weights)]
        if y_weights is not None:
            named.append(("y_weights", y_weights))
        if band_lo is not None and band_hi is not None:
            named += [("band_lo_N", band_lo), ("band_hi_N", band_hi)]
        for name, arr in named:
            bad = np.flatnonzero(~np.isfinite(arr))
            if bad.size:
                raise SkillError(
                    ERR_SKILL_NOT_FINITE, f"skill {name}[{bad[0]}] is not finite: {float(arr[bad[0]])}"
                )
        kw: dict[str, Any] = dict(f64)
        skill = Skill(
            centres=centres,
            widths=widths,
            weights=weights,
            flags=flags,
            format_version=version,
            y_weights=y_weights,
            kind=kind,
            contact_cN=contact_cn,
            contact_tau_ms=contact_ms,
            band_lo_N=band_lo,
            band_hi_N=band_hi,
            **kw,
        )
        skill._validate_values()
        return skill

    def _validate_values(self) -> None:
        """Checks 207-210 (ranges, centres, gains, flags) and 228-231 (kind, periodic), in the
        firmware's order."""
        checks = (
            ("dt_s", 0.0 < self.dt_s <= DT_MAX_S, f"(0, {DT_MAX_S:g}]"),
            ("tau_s", self.tau_s > 0.0, "> 0"),
            ("duration_s", 0.0 < self.duration_s <= DURATION_MAX_S, f"(0, {DURATION_MAX_S:g}]"),
            ("stiffness_Npm", self.stiffness_Npm > 0.0, "> 0"),
            ("goal_N", self.goal_N > 0.0, "> 0"),
        )
        for name, ok, rng in checks:
            if not ok:
                raise SkillError(ERR_SKILL_RANGE, f"skill {name} = {getattr(self, name)!r} outside {rng}")
        bad = np.flatnonzero(~(self.widths > 0.0))
        if bad.size:
            raise SkillError(
                ERR_SKILL_RANGE, f"skill widths[{bad[0]}] = {float(self.widths[bad[0]])!r} must be > 0"
            )
        c = self.centres
        if self.kind == KIND_PERIODIC:
            _validate_phases(c)
        elif c[0] < 0.0 or c[-1] > 1.0:
            raise SkillError(
                ERR_SKILL_CENTRES,
                f"skill centres must lie in [0, 1]: first {float(c[0])!r}, last {float(c[-1])!r}",
            )
        bad = np.flatnonzero(~(np.diff(c) > 0.0))
        if bad.size and self.kind != KIND_PERIODIC:
            i = int(bad[0]) + 1
            raise SkillError(
                ERR_SKILL_CENTRES,
                f"skill centres not strictly increasing at {i}: {float(c[i - 1])!r} then {float(c[i])!r}",
            )
        try:
            p = derive(self.gains)
        except ParamError as e:
            raise SkillError(ERR_SKILL_GAINS, f"skill gains invalid: {e.message}") from None
        for name, stored, derived in (
            ("alpha", self.alpha, p.alpha),
            ("beta", self.beta, p.beta),
            ("gamma", self.gamma, p.gamma),
        ):
            if abs(stored - derived) > GAINS_REL_TOL * abs(derived):
                raise SkillError(
                    ERR_SKILL_GAINS,
                    f"skill {name} = {stored!r} disagrees with {derived!r} derived from its gains",
                )
        if self.beta > 0.25 * self.alpha * (1.0 + MONOTONE_REL_TOL):
            raise SkillError(ERR_SKILL_GAINS, f"skill beta = {self.beta!r} > alpha/4 = {0.25 * self.alpha!r}")
        if self.has_y:
            beta_y = self.beta_y
            if not (0.0 < beta_y <= 0.25 * self.alpha * (1.0 + MONOTONE_REL_TOL)):
                raise SkillError(
                    ERR_SKILL_GAINS,
                    f"skill y DMP beta = k_p/(m_d*alpha) - 1 = {beta_y!r} outside (0, alpha/4 = "
                    f"{0.25 * self.alpha!r}]",
                )
        known = KNOWN_FLAGS.get(self.format_version, FLAG_END_RELEASE)
        if self.flags & ~known & 0xFFFF:
            raise SkillError(
                ERR_SKILL_UNSUPPORTED,
                f"skill flags 0x{self.flags:04X} carry unsupported bits "
                f"0x{self.flags & ~known & 0xFFFF:04X} (format version {self.format_version})",
            )
        if self.format_version >= 4:
            self._validate_kind()
        if self.band_lo_N is not None and self.band_hi_N is not None:
            bad = np.flatnonzero(~(self.band_lo_N <= self.band_hi_N))
            if bad.size:
                j = int(bad[0])
                raise SkillError(
                    ERR_SKILL_BAND,
                    f"skill band point {j}: lower bound {float(self.band_lo_N[j])!r} N above the upper "
                    f"{float(self.band_hi_N[j])!r} N",
                )

    def _validate_kind(self) -> None:
        """v4 (the kind itself is checked with the kernel count): the contact wait's time
        constant at most 10 s and 0 without a threshold (233); a discrete skill with its
        periodic fields 0 (228); a periodic one with amplitude > 0 (230),
        T = 2*pi*tau (229)."""
        if self.contact_tau_ms > CONTACT_TAU_MS_MAX or (self.contact_cN == 0 and self.contact_tau_ms != 0):
            raise SkillError(
                ERR_SKILL_CONTACT_WAIT,
                f"contact wait: time constant {self.contact_tau_ms} ms with threshold "
                f"{self.contact_cN} x 0.01 N (the time constant must be <= {CONTACT_TAU_MS_MAX} ms, "
                "and 0 without a threshold)",
            )
        if self.kind == KIND_DISCRETE:
            nonzero = [k for k in _F64_NAMES_P if getattr(self, k) != 0.0]
            if nonzero:
                raise SkillError(
                    ERR_SKILL_KIND, f"discrete skill carries periodic fields: {', '.join(nonzero)} not 0"
                )
            return
        if not self.amplitude_N > 0.0:
            raise SkillError(
                ERR_SKILL_AMPLITUDE, f"periodic skill amplitude_N = {self.amplitude_N!r} must be > 0"
            )
        period = 2.0 * math.pi * self.tau_s
        if abs(self.duration_s - period) > PERIOD_REL_TOL * self.duration_s:
            raise SkillError(
                ERR_SKILL_PERIOD,
                f"periodic skill duration_s = {self.duration_s!r} is not its period 2*pi*tau = {period!r}",
            )

    # -- JSON twin -------------------------------------------------------------------------
    def to_json_dict(self) -> dict[str, Any]:
        """The same fields, human-readable (floats round-trip exactly: repr)."""
        d: dict[str, Any] = {
            "format": "forceskill skill image",
            "format_version": self.format_version,
            "n_kernels": self.n_kernels,
            "flags": self.flags,
            "end_policy": self.end_policy,
        }
        for k in _F64_NAMES:
            d[k] = float(getattr(self, k))
        d["centres"] = [float(x) for x in self.centres]
        d["widths"] = [float(x) for x in self.widths]
        d["weights"] = [float(x) for x in self.weights]
        if self.format_version >= 3:
            for k in _F64_NAMES_Y:
                d[k] = float(getattr(self, k))
        if self.format_version >= 4:
            d["kind"] = KINDS.get(self.kind, str(self.kind))
            for k in _F64_NAMES_P:
                d[k] = float(getattr(self, k))
            d["contact_cN"] = self.contact_cN
            d["contact_tau_ms"] = self.contact_tau_ms
        if self.y_weights is not None:
            d["y_weights"] = [float(x) for x in self.y_weights]
        if self.format_version >= 5 and self.band_lo_N is not None and self.band_hi_N is not None:
            d["band_lo_N"] = [float(x) for x in self.band_lo_N]
            d["band_hi_N"] = [float(x) for x in self.band_hi_N]
        image = self.to_bytes(validate=False)
        d["image_bytes"] = len(image)
        d["crc32"] = f"0x{image_crc32(image):08X}"
        return d

    def to_json(self) -> str:
        return json.dumps(self.to_json_dict(), indent=1) + "\n"

    @staticmethod
    def from_json_dict(d: dict[str, Any]) -> Skill:
        """Rebuild from the JSON twin (validated like an image)."""
        kw: dict[str, Any] = {k: float(d[k]) for k in _F64_NAMES}
        kw.update({k: float(d[k]) for k in _F64_NAMES_Y + _F64_NAMES_P if k in d})
        kinds = {v: k for k, v in KINDS.items()}
        if "kind" in d:
            kw["kind"] = kinds.get(d["kind"], -1)
        kw.update({k: int(d[k]) for k in ("contact_cN", "contact_tau_ms") if k in d})
        yw = d.get("y_weights")
        for k in ("band_lo_N", "band_hi_N"):
            if k in d:
                kw[k] = np.array(d[k], dtype=float)
        s = Skill(
            centres=np.array(d["centres"], dtype=float),
            widths=np.array(d["widths"], dtype=float),
            weights=np.array(d["weights"], dtype=float),
            flags=int(d["flags"]),
            format_version=int(d.get("format_version", 0)),
            y_weights=None if yw is None else np.array(yw, dtype=float),
            **kw,
        )
        return Skill.from_bytes(s.to_bytes(validate=False))

    # -- files -----------------------------------------------------------------------------
    def write(self, path: PathLike, outs: Outputs | None = None, inputs: Sequence[PathLike] = ()) -> None:
        """Write the image to ``path`` and its JSON twin to ``path.json`` as one unit: into ``outs``
        (committed by the caller) or committed here; neither file changes unless both are written."""
        from ..outputs import Outputs

        image = self.to_bytes()
        twin = self.to_json().encode()
        if outs is not None:
            outs.write_bytes(path, image)
            outs.write_bytes(str(path) + ".json", twin)
            return
        with Outputs(inputs) as own:
            own.write_bytes(path, image)
            own.write_bytes(str(path) + ".json", twin)
            own.commit()

    @staticmethod
    def read(path: PathLike) -> Skill:
        """Read and validate an image file."""
        try:
            data = Path(path).read_bytes()
        except OSError as e:
            raise SkillError(ERR_IO, f"cannot read skill {str(path)!r}: {e.strerror}") from None
        return Skill.from_bytes(data)


def _validate_phases(c: np.ndarray) -> None:
    """A periodic skill's centres: phases strictly increasing in [0, 2*pi) (231)."""
    bad = np.flatnonzero(~(np.diff(c) > 0.0))
    if c[0] < 0.0 or not c[-1] < 2.0 * math.pi or bad.size:
        where = f"at {int(bad[0]) + 1}" if bad.size else f"first {float(c[0])!r}, last {float(c[-1])!r}"
        raise SkillError(
            ERR_SKILL_PHASES, f"periodic skill centres must increase strictly in [0, 2*pi): {where}"
        )


def atomic_write(path: Path, data: bytes) -> None:
    """One output file through forceskill.outputs (temporary file in the same folder, renamed on
    success; refuses special files)."""
    from ..outputs import write_file

    write_file(path, data)

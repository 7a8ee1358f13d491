"""Skill image v2 (docs/skill_format.md): bytes, validation and the JSON twin.

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
    ERR_SKILL_CENTRES,
    ERR_SKILL_CRC,
    ERR_SKILL_GAINS,
    ERR_SKILL_HEADER_SIZE,
    ERR_SKILL_KERNELS,
    ERR_SKILL_LENGTH,
    ERR_SKILL_MAGIC,
    ERR_SKILL_NOT_FINITE,
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
FORMAT_VERSION = 2
HEADER_SIZE = 136
CRC_SIZE = 4
MAX_KERNELS = 1024  # DMP_MAX_KERNELS
FLAG_END_RELEASE = 0x0001
FLAG_Y_AXIS = 0x0002  # reserved, refused
KNOWN_FLAGS = FLAG_END_RELEASE
RELEASE_TIME_S = 0.5
GAINS_REL_TOL = 1e-9  # stored alpha/beta/gamma vs derived from stored gains
DT_MAX_S = 0.1
DURATION_MAX_S = 3600.0

# magic u32, version u16, header_size u16, total_length u32, n u16, flags u16, then 15 f64
_HEADER = struct.Struct("<IHHIHH15d")
#: the fixed part every version shares (magic, version): enough to name an old image's version
_PREFIX = struct.Struct("<IH")
assert _HEADER.size == HEADER_SIZE
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

PathLike = str | Path


def image_size(n_kernels: int) -> int:
    """Total image length in bytes for N kernels: 136 + 24 N + 4."""
    return HEADER_SIZE + 24 * n_kernels + CRC_SIZE


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
    format_version: int = field(default=FORMAT_VERSION)

    def __post_init__(self) -> None:
        self.centres = np.ascontiguousarray(self.centres, dtype=np.float64).reshape(-1)
        self.widths = np.ascontiguousarray(self.widths, dtype=np.float64).reshape(-1)
        self.weights = np.ascontiguousarray(self.weights, dtype=np.float64).reshape(-1)

    # -- derived views ---------------------------------------------------------------------
    @property
    def n_kernels(self) -> int:
        return int(self.centres.size)

    @property
    def end_policy(self) -> str:
        """'hold' (keep the last force after T) or 'release' (ramp to zero in 0.5 s)."""
        return "release" if self.flags & FLAG_END_RELEASE else "hold"

    @property
    def gains(self) -> Gains:
        return Gains(self.m_d_kg, self.k_d_Nspm, self.k_p_Npm, self.kkf_Npm, self.kki_Npms)

    @property
    def params(self) -> DmpParams:
        return DmpParams(self.alpha, self.beta, self.gamma)

    # -- bytes -----------------------------------------------------------------------------
    def to_bytes(self, validate: bool = True) -> bytes:
        """The v2 image (little-endian, CRC-32 last). Validates first unless told not to."""
        n = self.n_kernels
        if not (self.widths.size == n and self.weights.size == n):
            raise SkillError(
                ERR_SKILL_LENGTH,
                f"centres/widths/weights lengths differ: {n}/{self.widths.size}/{self.weights.size}",
            )
        head = _HEADER.pack(
            MAGIC,
            self.format_version,
            HEADER_SIZE,
            image_size(n),
            n,
            self.flags,
            *(float(getattr(self, k)) for k in _F64_NAMES),
        )
        body = (
            head
            + self.centres.astype("<f8").tobytes()
            + self.widths.astype("<f8").tobytes()
            + self.weights.astype("<f8").tobytes()
        )
        image = body + struct.pack("<I", zlib.crc32(body) & 0xFFFFFFFF)
        if validate:
            Skill.from_bytes(image)
        return image

    @staticmethod
    def from_bytes(buf: bytes) -> Skill:
        """Parse and validate an image; raises SkillError with the firmware's code (200-211)."""
        buf = bytes(buf)
        if len(buf) < _PREFIX.size:
            raise SkillError(
                ERR_SKILL_TOO_SHORT, f"skill image too short: {len(buf)} bytes, header is {HEADER_SIZE}"
            )
        magic, version = _PREFIX.unpack_from(buf, 0)
        if magic != MAGIC:
            raise SkillError(
                ERR_SKILL_MAGIC, f"skill image magic is 0x{magic:08X}, expected 0x{MAGIC:08X} ('FSKL')"
            )
        if version != FORMAT_VERSION:
            hint = (
                " (fitted before skills ran in force units: fit the demonstration again)"
                if version < FORMAT_VERSION
                else ""
            )
            raise SkillError(
                ERR_SKILL_VERSION,
                f"skill image format version {version} is not supported: this "
                f"reads version {FORMAT_VERSION}{hint}",
            )
        if len(buf) < HEADER_SIZE:
            raise SkillError(
                ERR_SKILL_TOO_SHORT, f"skill image too short: {len(buf)} bytes, header is {HEADER_SIZE}"
            )
        fields = _HEADER.unpack_from(buf, 0)
        _, _, header_size, total_length, n, flags = fields[:6]
        f64 = dict(zip(_F64_NAMES, fields[6:], strict=True))
        if header_size != HEADER_SIZE:
            raise SkillError(
                ERR_SKILL_HEADER_SIZE, f"skill header_size is {header_size}, expected {HEADER_SIZE}"
            )
        if total_length != len(buf) or total_length != image_size(n):
            raise SkillError(
                ERR_SKILL_LENGTH,
                f"skill length field {total_length} disagrees with buffer "
                f"({len(buf)} bytes) or with N = {n} ({image_size(n)} bytes)",
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
        arrays = np.frombuffer(buf, dtype="<f8", count=3 * n, offset=HEADER_SIZE).astype(np.float64)
        centres, widths, weights = arrays[:n].copy(), arrays[n : 2 * n].copy(), arrays[2 * n :].copy()
        for name, val in f64.items():
            if not math.isfinite(val):
                raise SkillError(ERR_SKILL_NOT_FINITE, f"skill field {name} is not finite: {val}")
        for name, arr in (("centres", centres), ("widths", widths), ("weights", weights)):
            bad = np.flatnonzero(~np.isfinite(arr))
            if bad.size:
                raise SkillError(
                    ERR_SKILL_NOT_FINITE, f"skill {name}[{bad[0]}] is not finite: {float(arr[bad[0]])}"
                )
        kw: dict[str, Any] = dict(f64)
        skill = Skill(
            centres=centres, widths=widths, weights=weights, flags=flags, format_version=version, **kw
        )
        skill._validate_values()
        return skill

    def _validate_values(self) -> None:
        """Checks 207-210 (ranges, centres, gains, flags), in the firmware's order."""
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
        if c[0] < 0.0 or c[-1] > 1.0:
            raise SkillError(
                ERR_SKILL_CENTRES,
                f"skill centres must lie in [0, 1]: first {float(c[0])!r}, last {float(c[-1])!r}",
            )
        bad = np.flatnonzero(~(np.diff(c) > 0.0))
        if bad.size:
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
        if self.flags & ~KNOWN_FLAGS & 0xFFFF:
            raise SkillError(
                ERR_SKILL_UNSUPPORTED,
                f"skill flags 0x{self.flags:04X} carry unsupported bits "
                f"0x{self.flags & ~KNOWN_FLAGS & 0xFFFF:04X}",
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
        d["image_bytes"] = image_size(self.n_kernels)
        d["crc32"] = (
            f"0x{struct.unpack_from('<I', self.to_bytes(validate=False), image_size(self.n_kernels) - 4)[0]:08X}"
        )
        return d

    def to_json(self) -> str:
        return json.dumps(self.to_json_dict(), indent=1) + "\n"

    @staticmethod
    def from_json_dict(d: dict[str, Any]) -> Skill:
        """Rebuild from the JSON twin (validated like an image)."""
        kw: dict[str, Any] = {k: float(d[k]) for k in _F64_NAMES}
        s = Skill(
            centres=np.array(d["centres"], dtype=float),
            widths=np.array(d["widths"], dtype=float),
            weights=np.array(d["weights"], dtype=float),
            flags=int(d["flags"]),
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


def atomic_write(path: Path, data: bytes) -> None:
    """One output file through forceskill.outputs (temporary file in the same folder, renamed on
    success; refuses special files)."""
    from ..outputs import write_file

    write_file(path, data)

"""Skill image v1 (docs/skill_format.md): bytes, validation and the JSON twin.

A skill is plain data (dmpbbo style): fitting produces it, the firmware parses and evaluates it.
Validation runs the same checks, in the same order, with the same codes as ``skill_parse`` in
firmware/core/skill.c; the bad images in tests/vectors/bad/ prove it.
"""

from __future__ import annotations

import json
import math
import os
import struct
import tempfile
import zlib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Union

import numpy as np

from .errors import (
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
    FsError,
    ParamError,
    SkillError,
)
from .params import MONOTONE_REL_TOL, DmpParams, Gains, derive

MAGIC = 0x4C4B5346  # bytes "FSKL"
FORMAT_VERSION = 1
HEADER_SIZE = 128
CRC_SIZE = 4
MAX_KERNELS = 256  # DMP_MAX_KERNELS
FLAG_END_RELEASE = 0x0001
FLAG_Y_AXIS = 0x0002  # reserved, refused in v1
KNOWN_FLAGS = FLAG_END_RELEASE
RELEASE_TIME_S = 0.5
GAINS_REL_TOL = 1e-9  # stored alpha/beta/gamma vs derived from stored gains
DT_MAX_S = 0.1
DURATION_MAX_S = 3600.0

# magic u32, version u16, header_size u16, total_length u32, n u16, flags u16, then 14 f64
_HEADER = struct.Struct("<IHHIHH14d")
assert _HEADER.size == HEADER_SIZE
_F64_NAMES = (
    "dt_s",
    "tau_s",
    "alpha",
    "beta",
    "gamma",
    "stiffness_Npm",
    "goal_m",
    "duration_s",
    "m_d_kg",
    "k_d_Nspm",
    "k_p_Npm",
    "k_f",
    "k_i_per_s",
    "surface_m",
)

PathLike = Union[str, "os.PathLike[str]"]


def image_size(n_kernels: int) -> int:
    """Total image length in bytes for N kernels: 128 + 24 N + 4."""
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
    goal_m: float
    duration_s: float
    m_d_kg: float
    k_d_Nspm: float
    k_p_Npm: float
    k_f: float
    k_i_per_s: float
    surface_m: float
    centres: np.ndarray
    widths: np.ndarray
    weights: np.ndarray
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
        return Gains(self.m_d_kg, self.k_d_Nspm, self.k_p_Npm, self.k_f, self.k_i_per_s)

    @property
    def params(self) -> DmpParams:
        return DmpParams(self.alpha, self.beta, self.gamma)

    # -- bytes -----------------------------------------------------------------------------
    def to_bytes(self, validate: bool = True) -> bytes:
        """The v1 image (little-endian, CRC-32 last). Validates first unless told not to."""
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
        if len(buf) < HEADER_SIZE:
            raise SkillError(
                ERR_SKILL_TOO_SHORT, f"skill image too short: {len(buf)} bytes, header is {HEADER_SIZE}"
            )
        fields = _HEADER.unpack_from(buf, 0)
        magic, version, header_size, total_length, n, flags = fields[:6]
        f64 = dict(zip(_F64_NAMES, fields[6:], strict=True))
        if magic != MAGIC:
            raise SkillError(
                ERR_SKILL_MAGIC, f"skill image magic is 0x{magic:08X}, expected 0x{MAGIC:08X} ('FSKL')"
            )
        if version != FORMAT_VERSION:
            raise SkillError(
                ERR_SKILL_VERSION, f"unsupported skill format version {version} (this reads {FORMAT_VERSION})"
            )
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
            ("goal_m", self.goal_m > 0.0, "> 0"),
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
            p = derive(self.gains, self.stiffness_Npm)
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
    def write(self, path: PathLike) -> None:
        """Write the image to ``path`` and its JSON twin to ``path.json``, each atomically."""
        p = Path(path)
        image = self.to_bytes()
        atomic_write(p, image)
        atomic_write(Path(str(p) + ".json"), self.to_json().encode())

    @staticmethod
    def read(path: PathLike) -> Skill:
        """Read and validate an image file."""
        try:
            data = Path(path).read_bytes()
        except OSError as e:
            raise SkillError(ERR_IO, f"cannot read skill {str(path)!r}: {e.strerror}") from None
        return Skill.from_bytes(data)


def atomic_write(path: Path, data: bytes) -> None:
    """Write via a temporary file in the same folder and rename, so a failure leaves no file."""
    path = Path(path)
    folder = path.parent if str(path.parent) else Path(".")
    try:
        fd, tmp = tempfile.mkstemp(prefix="." + path.name + ".", suffix=".tmp", dir=folder)
    except OSError as e:
        raise FsError(ERR_IO, f"cannot write {str(path)!r}: {e.strerror}") from None
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data)
        os.replace(tmp, path)
    except BaseException as e:
        try:
            os.unlink(tmp)
        except OSError:
            pass
        if isinstance(e, OSError):
            raise FsError(ERR_IO, f"cannot write {str(path)!r}: {e.strerror or e}") from None
        raise

"""The benchmark demonstration: a deterministic force-like profile every library fits.

One 1-D contact-force profile sampled at 1 kHz, shaped like the paper's tasks: a smooth
ramp to a low force, a hold, a ramp to a higher force, engraving-like level changes every
0.6-1.4 s with smooth 0.7 s transitions, a release over the last 0.8 s, and 1 % tremor. The
random parts come from numpy's PCG64 with a fixed seed, so every run and every machine gets the
same samples. The position is that of a spring object (surface at 1 mm, stiffness K): the
learning target ``x* = f/K`` (docs/math.md) is what the peer libraries imitate, and forceskill
fits the force and position columns.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

DT_S = 0.001
STIFFNESS_NPM = 180.0
SURFACE_M = 0.001
SEED = 20240607


@dataclass(frozen=True)
class Demo:
    """One demonstration: time (s), position (m), contact force (N), object stiffness (N/m)."""

    t_s: np.ndarray
    pos_m: np.ndarray
    force_N: np.ndarray
    stiffness_Npm: float = STIFFNESS_NPM
    surface_m: float = SURFACE_M

    @property
    def duration_s(self) -> float:
        return float(self.t_s[-1] - self.t_s[0])

    @property
    def target_m(self) -> np.ndarray:
        """The learning target x* = f/k (what the peers imitate)."""
        return self.force_N / self.stiffness_Npm


def _smoothstep(s: np.ndarray) -> np.ndarray:
    s = np.clip(s, 0.0, 1.0)
    return s * s * (3.0 - 2.0 * s)


def make_demo(duration_s: float = 17.0, seed: int = SEED) -> Demo:
    """The deterministic demonstration of the given length (>= 3 s), samples at 0, 1 ms, ..., T."""
    if duration_s < 3.0:
        raise ValueError(f"duration {duration_s} s: the profile needs at least 3 s")
    rng = np.random.default_rng(seed)
    n = int(round(duration_s / DT_S)) + 1
    t = np.arange(n) * DT_S
    T = t[-1]
    # phase 1: ramp to a low force over 1.5 s, hold; phase 2: ramp to a higher force
    t_up2 = min(0.25 * T, 5.0)
    f = 4.0 * _smoothstep(t / 1.5) + 5.0 * _smoothstep((t - t_up2) / 1.0)
    # phase 3: engraving-like levels every 0.6-1.4 s with smooth 0.7 s transitions
    t_lv = t_up2 + 1.5
    level_prev = 0.0
    while t_lv < T - 1.5:
        level = float(rng.uniform(-3.0, 6.0))
        f = f + (level - level_prev) * _smoothstep((t - t_lv) / 0.7)
        level_prev = level
        t_lv += float(rng.uniform(0.6, 1.4))
    # release over the last 0.8 s
    f = f * (1.0 - _smoothstep((t - (T - 0.8)) / 0.8))
    # 1 % tremor (8-12 Hz, seeded phases), faded in and out with the force
    fmax = float(np.max(f))
    freqs = rng.uniform(8.0, 12.0, size=3)
    phases = rng.uniform(0.0, 2.0 * np.pi, size=3)
    tremor = sum(np.sin(2.0 * np.pi * fr * t + ph) for fr, ph in zip(freqs, phases, strict=False)) / 3.0
    f = f + 0.01 * fmax * tremor * np.clip(f / fmax, 0.0, 1.0)
    f = np.maximum(f, 0.0)
    pos = SURFACE_M + f / STIFFNESS_NPM
    return Demo(t_s=t, pos_m=pos, force_N=f)


def write_csv(demo: Demo, path: str) -> None:
    """CSV with a header row: t (s), x (m), f (N) — the columns forceskill's CSV reader takes."""
    data = np.column_stack([demo.t_s, demo.pos_m, demo.force_N])
    np.savetxt(path, data, delimiter=",", header="t,x,f", comments="", fmt="%.9g")


if __name__ == "__main__":
    d = make_demo()
    print(
        f"samples={d.t_s.size} duration_s={d.duration_s:.3f} max_force_N={d.force_N.max():.3f} "
        f"impulse_Ns={np.trapezoid(d.force_N, d.t_s):.3f} checksum={d.force_N.sum():.9e}"
    )

"""Analytic, seeded demonstrations shaped like the paper's tasks (the operator profiles of docs/hil.md).

Smooth force profiles with positions from a static two-layer spring object (surface at 1 mm,
inner layer at 20 mm). Used by the golden-vector generator, the tests and the benchmark; the HIL
simulator produces the realistic ones.
"""

from __future__ import annotations

import numpy as np

from .demo import Demo

SURFACE_M = 0.001
INNER_LAYER_M = 0.020


def _smooth(s: np.ndarray) -> np.ndarray:
    """0 -> 1 over s in [0, 1], C1 (raised cosine)."""
    s = np.clip(s, 0.0, 1.0)
    return 0.5 - 0.5 * np.cos(np.pi * s)


def _position(f: np.ndarray, k_v1: float, k_v2: float) -> np.ndarray:
    """Static two-layer spring: deformation p for force f, x = surface + p."""
    f1 = k_v1 * (INNER_LAYER_M - SURFACE_M)
    p = np.where(f <= f1, f / k_v1, (INNER_LAYER_M - SURFACE_M) + (f - f1) / k_v2)
    return SURFACE_M + np.maximum(p, 0.0)


def pressing(
    seed: int = 0,
    duration_s: float = 17.0,
    k_v1: float = 100.0,
    k_v2: float = 180.0,
    dt_s: float = 0.001,
    noise_N: float = 0.0,
) -> Demo:
    """Smooth ramp to a low force that reaches the inner layer, reaction time, ramp to a higher force."""
    rng = np.random.default_rng(seed)
    t = np.arange(int(round(duration_s / dt_s)) + 1) * dt_s
    f_low = k_v1 * (INNER_LAYER_M - SURFACE_M) * rng.uniform(1.1, 1.3)
    f_high = f_low + k_v2 * rng.uniform(0.010, 0.020)
    t1 = rng.uniform(0.15, 0.25) * duration_s  # ramp 1 duration
    t2 = t1 + rng.uniform(0.2, 0.35) + 0.15 * duration_s  # reaction time + hold, then ramp 2
    r2 = rng.uniform(0.15, 0.25) * duration_s
    f = f_low * _smooth(t / t1) + (f_high - f_low) * _smooth((t - t2) / r2)
    x = _position(f, k_v1, k_v2)
    if noise_N > 0.0:
        f = f + rng.normal(0.0, noise_N, f.size)
    return Demo(t, x, f, f"synthetic pressing seed={seed} k_v={k_v1:g}/{k_v2:g}")


def engraving(
    seed: int = 0,
    duration_s: float = 8.0,
    k_v: float = 100.0,
    f_max_N: float = 6.0,
    dt_s: float = 0.001,
    noise_N: float = 0.0,
) -> Demo:
    """Random force levels every 0.6-1.4 s with 0.7 s transitions; ramp-up 1 s, release over 0.8 s."""
    rng = np.random.default_rng(seed)
    t = np.arange(int(round(duration_s / dt_s)) + 1) * dt_s
    level = rng.uniform(0.4, 1.0) * f_max_N
    f = level * _smooth(t / 1.0)
    tc = 1.0 + rng.uniform(0.6, 1.4)
    t_release = duration_s - 0.8
    while tc + 0.7 < t_release:
        new = rng.uniform(0.3, 1.0) * f_max_N
        f = f + (new - level) * _smooth((t - tc) / 0.7)
        level = new
        tc += 0.7 + rng.uniform(0.6, 1.4)
    f = f * (1.0 - _smooth((t - t_release) / 0.8))
    x = _position(f, k_v, k_v)
    if noise_N > 0.0:
        f = f + rng.normal(0.0, noise_N, f.size)
    return Demo(t, x, f, f"synthetic engraving seed={seed} k_v={k_v:g}")

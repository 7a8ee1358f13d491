"""Analytic, seeded demonstrations shaped like the paper's tasks (the operator profiles of docs/hil.md).

Smooth force profiles with positions from a static two-layer spring object (surface at 1 mm,
inner layer at 20 mm). Used by the golden-vector generator, the tests and the benchmark; the HIL
simulator produces the realistic ones.
"""

from __future__ import annotations

import numpy as np

from ..wire import TICK_S
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
    dt_s: float = TICK_S,
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
    dt_s: float = TICK_S,
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


def wiping(
    seed: int = 0,
    duration_s: float = 8.0,
    k_v: float = 100.0,
    f_max_N: float = 6.0,
    path_m: float = 0.05,
    dt_s: float = TICK_S,
) -> Demo:
    """The engraving force profile with a path along y (paper Fig. 6: the operator moves along the
    surface while varying the force): from y = 0, random waypoints in [-path_m/2, path_m] every
    0.8-1.6 s reached over 0.6 s transitions (C1), back near the start before the release."""
    d = engraving(seed, duration_s, k_v, f_max_N, dt_s)
    rng = np.random.default_rng(seed + 1000)
    t = d.t_s
    y = np.zeros_like(t)
    here = 0.0
    tc = 0.4
    t_end = duration_s - 1.0
    while tc + 0.6 < t_end:
        new = rng.uniform(-0.5, 1.0) * path_m
        y = y + (new - here) * _smooth((t - tc) / 0.6)
        here = new
        tc += 0.6 + rng.uniform(0.2, 1.0)
    y = y + (0.1 * path_m - here) * _smooth((t - t_end) / 0.6)
    return Demo(t, d.pos_m, d.force_N, f"synthetic wiping seed={seed} k_v={k_v:g} path={path_m:g} m", y_m=y)


def stroke_profile(
    seed: int = 0, mean_N: float = 6.0, amplitude_N: float = 2.0
) -> tuple[np.ndarray, np.ndarray]:
    """One wiping stroke as Fourier coefficients (cos, sin) of harmonics 1..4: a seeded, smooth,
    zero-mean shape scaled so that (max - min)/2 = amplitude_N; ``stroke(phase)`` adds mean_N."""
    rng = np.random.default_rng(seed + 2000)
    decay = np.array([1.0, 0.45, 0.25, 0.12])
    a = rng.normal(0.0, 1.0, 4) * decay
    b = rng.normal(0.0, 1.0, 4) * decay
    a[0], b[0] = 1.0, rng.uniform(-0.3, 0.3)  # the fundamental leads
    s = _stroke_shape(np.linspace(0.0, 2.0 * np.pi, 4097), a, b)
    k = amplitude_N / (0.5 * float(np.max(s) - np.min(s)))
    return k * a, k * b


def _stroke_shape(phase: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    h = np.arange(1, a.size + 1)[:, None]
    out: np.ndarray = a @ np.cos(h * phase[None, :]) + b @ np.sin(h * phase[None, :])
    return out


def stroke(phase: np.ndarray, seed: int = 0, mean_N: float = 6.0, amplitude_N: float = 2.0) -> np.ndarray:
    """The noise-free force of ``wiping_strokes`` at stroke phase ``phase`` (rad, 0 = a stroke's start)."""
    a, b = stroke_profile(seed, mean_N, amplitude_N)
    return mean_N + _stroke_shape(np.asarray(phase, dtype=float), a, b)


def wiping_strokes(
    seed: int = 0,
    n_strokes: int = 12,
    period_s: float = 1.2,
    mean_N: float = 6.0,
    amplitude_N: float = 2.0,
    approach_s: float = 1.0,
    release_s: float = 0.8,
    k_v: float = 100.0,
    dt_s: float = TICK_S,
    noise_N: float = 0.0,
    path_m: float = 0.0,
) -> Demo:
    """A multi-stroke wiping demonstration: the operator presses up to the stroke's force over
    ``approach_s`` (raised cosine from 0), repeats the stroke (``stroke``) ``n_strokes`` times
    with period ``period_s``, then releases over ``release_s``. The strokes start at t =
    approach_s (phase 0); the force ramps are multiplied onto the stroke, so the approach and the
    release are not strokes. Positions from a one-layer static spring; optional white sensor noise.
    path_m > 0: a path along y (Demo.y_m) with the stroke's period, 20 mm + path_m*(sin(phi) +
    0.3*cos(2 phi + 0.5)) under the same ramps."""
    rng = np.random.default_rng(seed)
    duration = approach_s + n_strokes * period_s + release_s
    t = np.arange(int(round(duration / dt_s)) + 1) * dt_s
    t_end = approach_s + n_strokes * period_s
    phase = 2.0 * np.pi * (t - approach_s) / period_s
    env = _smooth(t / approach_s) * (1.0 - _smooth((t - t_end) / release_s))
    f = env * stroke(phase, seed, mean_N, amplitude_N)
    x = _position(f, k_v, k_v)
    if noise_N > 0.0:
        f = f + rng.normal(0.0, noise_N, f.size)
    src = f"synthetic wiping strokes seed={seed} n={n_strokes} period={period_s:g} s k_v={k_v:g}"
    y = None
    if path_m > 0.0:
        y = 0.02 + env * path_m * (np.sin(phase) + 0.3 * np.cos(2.0 * phase + 0.5))
        src += f" path={path_m:g} m"
    return Demo(t, x, f, src, y_m=y)


def pressing_set(
    seed: int = 0,
    n: int = 6,
    duration_s: float = 6.0,
    amplitude_rel: float = 0.05,
    timing_rel: float = 0.12,
    warp_s: float = 0.5,
    bias_N: float = 0.05,
    noise_N: float = 0.03,
    dt_s: float = TICK_S,
) -> tuple[Demo, list[Demo]]:
    """Several demonstrations of one pressing task through the two-layer object, with a known
    truth: the intended profile (``pressing``, noise-free) and ``n`` recordings of it, each with
    its own idle lead (0.2-0.8 s), speed (an overall stretch within +-timing_rel and a smooth
    non-linear warp: two half-sine bends of up to warp_s and warp_s/2), amplitude (uniform within +-amplitude_rel), bias
    (normal, bias_N) and
    white sensor noise (noise_N). Returns (truth, recordings)."""
    truth = pressing(seed=seed, duration_s=duration_s)
    rng = np.random.default_rng(seed + 7000)
    demos = []
    for i in range(n):
        lead = rng.uniform(0.2, 0.8)
        stretch = 1.0 + rng.uniform(-timing_rel, timing_rel)
        gain = 1.0 + rng.uniform(-amplitude_rel, amplitude_rel)
        bias = rng.normal(0.0, bias_N)
        bend = rng.uniform(-1.0, 1.0, 2) * warp_s
        t = np.arange(int(round((duration_s * stretch + lead + 0.3) / dt_s)) + 1) * dt_s
        tau = np.clip((t - lead) / stretch, 0.0, duration_s)
        # the operator's own speed profile: monotone while (|b1| + 2|b2|)*pi/T < 1
        tau = (
            tau
            + bend[0] * np.sin(np.pi * tau / duration_s)
            + 0.5 * bend[1] * np.sin(2.0 * np.pi * tau / duration_s)
        )
        f = gain * np.interp(tau, truth.t_s, truth.force_N) * (t >= lead)
        x = np.interp(tau, truth.t_s, truth.pos_m)
        f = f + bias + rng.normal(0.0, noise_N, t.size)
        demos.append(Demo(t, x, f, f"synthetic pressing set seed={seed} #{i}"))
    return truth, demos

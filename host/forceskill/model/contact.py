"""A phase that waits for contact (docs/math.md, "A phase that waits for contact"): the Python
reference of the device's contact wait (dmp_contact_rate, dmp_slowdown_at_rate in
firmware/core/dmp.c, run by the executor every tick).

Every tick n, with f_c the measured contact force and f_prev the previous tick's reference
(0 before the first):

    lost  = f_prev - f_c[n] > threshold
    r    += dt/(tau_c + dt) * ((0 if lost else 1) - r)          r = 1 before the first tick
    tau_e = tau*time_scale*(1 + (1/r - 1))                      (every state frozen at r = 0)
    one DMP step with tau_e (discrete or periodic), f_hat[n] = f0 + ... after it
    hold += (1 - r)*dt

Every state of the DMP (phase, force, integrator) advances at the rate r, so f_hat holds where
it was while the contact is lost and continues from there, without a step, when it returns; the
hold is how far the phase fell behind the nominal run (in s).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

from . import dmp, periodic
from .scales import check_scales
from .skill import Skill


def rate_step(rate: float, f_hat_N: float, f_contact_N: float, threshold_N: float, gain: float) -> float:
    """The phase rate after one tick (dmp_contact_rate): towards 0 by gain while
    f_hat - f_contact > threshold (NaN: lost), towards 1 otherwise."""
    target = 1.0 if f_hat_N - f_contact_N <= threshold_N else 0.0
    return rate + gain * (target - rate)


def slowdown_at_rate(slowdown: float, rate: float) -> float:
    """(1 + slowdown)/rate - 1 (dmp_slowdown_at_rate): slowdown at rate >= 1, inf at rate <= 0."""
    if rate >= 1.0:
        return slowdown
    if not rate > 0.0:
        return math.inf
    return (1.0 + slowdown) / rate - 1.0


def rollout(
    skill: Skill,
    f_contact_N: np.ndarray | Callable[[int, float], float],
    n_steps: int | None = None,
    threshold_N: float | None = None,
    tau_s: float | None = None,
    goal_scale: float = 1.0,
    time_scale: float = 1.0,
    amplitude_scale: float = 1.0,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, float]:
    """The measured contact force, f_hat and the rate r of every tick, and the hold (s): the
    literal loop of the module docstring, with the skill's own contact wait unless threshold_N /
    tau_s are given, a periodic skill from its stored cycle state. f_contact_N is one value a
    tick, or a function of (tick, previous f_hat) giving it (n_steps ticks)."""
    check_scales(goal_scale, time_scale)
    if callable(f_contact_N):
        measure = f_contact_N
        n = int(n_steps or 0)
    else:
        arr = np.asarray(f_contact_N, dtype=float).reshape(-1).tolist()
        n = len(arr) if n_steps is None else int(n_steps)

        def measure(i: int, _f: float) -> float:
            return float(arr[i])

    thr = skill.contact_threshold_N if threshold_N is None else float(threshold_N)
    tau_c = skill.contact_tau_s if tau_s is None else float(tau_s)
    dt = skill.dt_s
    gain = dt / (tau_c + dt)
    alpha, beta, gamma = skill.alpha, skill.beta, skill.gamma
    tau_n = skill.tau_s * time_scale
    fc, f_hat, rates = np.empty(n), np.empty(n), np.empty(n)
    r, f_prev, hold = 1.0, 0.0, 0.0
    s = amplitude_scale if skill.periodic else 0.0
    # discrete: (y, z, I, u, v) from zero; periodic: (e, z, I, phi) from the cycle state
    yy, zz, ii, uu, vv = s * skill.e0_N, s * skill.z0_N, s * skill.i0_N, 0.0, 0.0
    for j in range(n):
        f_c = measure(j, f_prev)
        if thr > 0.0:
            r = rate_step(r, f_prev, f_c, thr, gain)
        a = dt / (tau_n * (1.0 + slowdown_at_rate(0.0, r)))
        if skill.periodic:
            k = periodic.normalised_kernels(np.array([uu]), skill.centres, skill.widths)
            h = amplitude_scale * skill.amplitude_N * float((k @ skill.weights)[0])
            yy, zz, ii = (
                yy + a * (zz - yy - gamma * ii + h),
                zz + a * alpha * (-beta * yy - zz),
                ii + a * yy,
            )
            uu += a
            if uu >= periodic.TWO_PI:
                uu -= periodic.TWO_PI
            f = skill.force0_N + goal_scale * skill.goal_N + yy
        else:
            g_e = skill.goal_N * goal_scale
            k = dmp.normalised_kernels(np.array([uu]), skill.centres, skill.widths)
            h = g_e * vv * float((k @ skill.weights)[0])
            yy, zz, ii, uu, vv = (
                yy + a * (zz - yy - gamma * ii + h),
                zz + a * alpha * (beta * (g_e - yy) - zz),
                ii + a * yy,
                uu + a * vv,
                vv + a * alpha * (beta * (1.0 - uu) - vv),
            )
            f = skill.force0_N + yy
        fc[j], f_hat[j], rates[j] = f_c, f, r
        hold += (1.0 - r) * dt
        f_prev = f
    return fc, f_hat, rates, hold


def loss_window(
    skill: Skill, n_steps: int, t_lost_s: tuple[float, float], *options: Any, **named: Any
) -> tuple[np.ndarray, np.ndarray, np.ndarray, float]:
    """``rollout`` against a contact that tracks the reference (f_contact = the previous tick's
    f_hat) but for the window t_lost_s = [start, end) where it is 0 (the surface gone); the
    contact wait and the scales (threshold_N, tau_s, goal_scale, ...) as ``rollout`` takes them."""
    dt = skill.dt_s

    def measure(j: int, f_prev: float) -> float:
        return 0.0 if t_lost_s[0] <= j * dt < t_lost_s[1] else f_prev

    return rollout(skill, measure, n_steps, *options, **named)

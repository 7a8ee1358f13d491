"""The periodic force DMP in numpy (docs/math.md section 5): the reference of a rhythmic skill.

The same parallel force/position law as the discrete DMP, written about the stroke's mean force g:
e = y - g is the deviation, the law's integrator integrates e (bounded in periodic steady state),
and the forcing is a function of a rhythmic phase phi (phi' = 1/tau, period 2*pi*tau) through
von Mises kernels. One step (dt), every right-hand side at the old state, a = dt/tau_e,
tau_e = tau*time_scale:

    h    = s_a * r * S(phi)         S = sum psi_i w_i / sum psi_i,  psi_i = exp(-kappa_i (1 - cos(phi - c_i)))
    e'   = e + a*(z - e - gamma*I + h)
    z'   = z + a*alpha*(-beta*e - z)
    I'   = I + a*e
    phi' = phi + a  (mod 2*pi)
    f_hat = f0 + s_g*g + e'

from the stored state on the cycle, scaled by the amplitude scale: (e, z, I)_0 = s_a*(e0, z0, I0).
r is the stroke's amplitude (N), s_g the goal scale (mean force), s_a the amplitude scale: e is
linear in (h, state_0), so f_hat - f0 - s_g*g scales exactly by s_a.

A periodic skill with the y path (flags bit 1) adds the position DMP on y on the same phase and
kernels (the law with k_f = k_i = 0: gamma = 0, beta_y = k_p/(m_d*alpha) - 1), written about the
path's mean g_y (m above the path at phi = 0), q = p - g_y its deviation, weights in m:

    h_y  = s_p * S_y(phi)           S_y = sum psi_i w_y_i / sum psi_i (the same psi_i)
    q'   = q + a*(z_q - q + h_y)
    z_q' = z_q + a*alpha*(-beta_y*q - z_q)
    y_hat = y_start + s_p*g_y + q'

from (q, z_q)_0 = s_p*(y_p0, y_z0), the path's own state on the cycle: the path scale s_p scales
the whole path (mean and stroke) about its position at phi = 0 exactly.
"""

from __future__ import annotations

import math

import numpy as np

from .dmp import KERNEL_CUTOFF_EXP, linear_scan
from .scales import check_scales, check_steps
from .skill import Skill

TWO_PI = 2.0 * math.pi
#: --amplitude-scale: the goal scale's range
AMPLITUDE_SCALE_MAX = 65.535


def kernel_exponents(phi: np.ndarray, centres: np.ndarray, kappa: np.ndarray) -> np.ndarray:
    """e[n, i] = kappa_i*(1 - cos(phi_n - c_i)), in [0, 2*kappa_i] (psi_i = exp(-e))."""
    d = np.asarray(phi, dtype=float).reshape(-1)[:, None] - centres[None, :]
    e: np.ndarray = kappa[None, :] * (1.0 - np.cos(d))
    return e


def normalised_kernels(phi: np.ndarray, centres: np.ndarray, kappa: np.ndarray) -> np.ndarray:
    """K[n, i] = psi_i(phi_n)/sum_j psi_j(phi_n), kernels with e_i > 23 skipped, psi_i =
    exp(-(e_i - e_min)); a phase with no kernel within the cutoff takes the nearest kernel (the
    discrete DMP's rule, docs/math.md section 2)."""
    e = kernel_exponents(phi, centres, kappa)
    e_act = np.where(e <= KERNEL_CUTOFF_EXP, e, np.inf)
    e_min = e_act.min(axis=1)
    none = ~np.isfinite(e_min)
    e_min[none] = 0.0
    psi = np.exp(-(e_act - e_min[:, None]))
    if none.any():
        rows = np.flatnonzero(none)
        psi[rows] = 0.0
        psi[rows, np.argmin(e[rows], axis=1)] = 1.0
    k: np.ndarray = psi / psi.sum(axis=1, keepdims=True)
    return k


def phases(a: float, n_steps: int) -> np.ndarray:
    """phi_n for n = 0..n_steps: the phase advanced by a per step and wrapped into [0, 2*pi)
    (phi_{n+1} = phi_n + a, minus 2*pi once it reaches 2*pi: the literal recursion)."""
    out = np.empty(n_steps + 1)
    p = 0.0
    for n in range(n_steps + 1):
        out[n] = p
        p += a
        if p >= TWO_PI:
            p -= TWO_PI
    return out


def check_amplitude_scale(s: float) -> None:
    """Amplitude scale finite and in [0, 65.535] (ParamError 109, as the goal scale)."""
    from ..errors import ERR_SCALE_INVALID, ParamError

    if not (math.isfinite(s) and 0.0 <= s <= AMPLITUDE_SCALE_MAX):
        raise ParamError(
            ERR_SCALE_INVALID, f"amplitude scale must be finite and in [0, {AMPLITUDE_SCALE_MAX:g}]: {s:g}"
        )


def cycle_steps(skill: Skill, cycles: float, time_scale: float = 1.0) -> int:
    """round(cycles * period * time_scale / dt): the rollout of ``cycles`` writes rows 0..this."""
    return int(round(cycles * skill.duration_s * time_scale / skill.dt_s))


def transform_matrix(alpha: float, beta: float, gamma: float, a: float) -> np.ndarray:
    """The step of (e, z, I) without forcing: s' = A s + (a*h, 0, 0)."""
    return np.array([[1.0 - a, a, -a * gamma], [-a * alpha * beta, 1.0 - a * alpha, 0.0], [a, 0.0, 1.0]])


def rollout(
    skill: Skill,
    cycles: float = 1.0,
    goal_scale: float = 1.0,
    amplitude_scale: float = 1.0,
    time_scale: float = 1.0,
    n_steps: int | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """t_n = n*dt and f_hat_n for n = 0..n_steps (default: ``cycles`` periods at the time scale),
    the literal loop of the module docstring from the stored state on the cycle."""
    check_scales(goal_scale, time_scale)
    check_amplitude_scale(amplitude_scale)
    n = cycle_steps(skill, cycles, time_scale) if n_steps is None else int(n_steps)
    check_steps(n)
    a = skill.dt_s / (skill.tau_s * time_scale)
    phi = phases(a, n)
    with np.errstate(all="ignore"):
        hl = (
            amplitude_scale
            * skill.amplitude_N
            * (normalised_kernels(phi, skill.centres, skill.widths) @ skill.weights)
        ).tolist()
    alpha, beta, gamma = skill.alpha, skill.beta, skill.gamma
    ee, zz, ii = (amplitude_scale * skill.e0_N, amplitude_scale * skill.z0_N, amplitude_scale * skill.i0_N)
    el = [0.0] * (n + 1)
    for j in range(n + 1):
        el[j] = ee
        ee, zz, ii = (
            ee + a * (zz - ee - gamma * ii + hl[j]),
            zz + a * alpha * (-beta * ee - zz),
            ii + a * ee,
        )
    with np.errstate(all="ignore"):
        f = skill.force0_N + goal_scale * skill.goal_N + np.asarray(el)
    return np.arange(n + 1) * skill.dt_s, f


def path_ramp(a: float, n_steps: int, ramp_out: bool = False) -> np.ndarray:
    """The executor's ramps of a periodic path, r_n for n = 0..n_steps (the device's y reference
    is y(start) + r_n*p_n): in, smoothstep of the phase in turns, x_n = n*a/(2*pi), over the
    first turn (r = 3x^2 - 2x^3: the path starts at rest where y is), 1 from the first wrap on;
    ramp_out (a run of n_steps ticks, not until stopped), times the smoothstep of the ticks left
    over a turn's, (n_steps - n)*a/(2*pi), over the last turn: it ends at rest at its start."""
    x = phases(a, n_steps) / TWO_PI
    r: np.ndarray = x * x * (3.0 - 2.0 * x)
    wrapped = np.flatnonzero(np.diff(x) < 0.0)
    if wrapped.size:
        r[wrapped[0] + 1 :] = 1.0
    if ramp_out:
        u = np.minimum((n_steps - np.arange(n_steps + 1)) * a / TWO_PI, 1.0)
        r *= u * u * (3.0 - 2.0 * u)
    return r


def rollout_path(
    skill: Skill,
    cycles: float = 1.0,
    path_scale: float = 1.0,
    time_scale: float = 1.0,
    n_steps: int | None = None,
    ramp_in: bool = False,
    ramp_out: bool = False,
) -> tuple[np.ndarray, np.ndarray]:
    """t_n = n*dt and y_hat_n for n = 0..n_steps of a periodic skill's y path (the module
    docstring's literal loop from the stored state on the cycle); a skill without the y path
    gives y_start. ramp_in (and ramp_out: a run of these n_steps ticks): the path as the device
    runs it, y_start + r_n*(y_hat_n - y_start) (``path_ramp``)."""
    from .scales import check_path_scale

    check_scales(1.0, time_scale)
    check_path_scale(path_scale)
    n = cycle_steps(skill, cycles, time_scale) if n_steps is None else int(n_steps)
    check_steps(n)
    t = np.arange(n + 1) * skill.dt_s
    if skill.y_weights is None:
        return t, np.full(n + 1, skill.y_start_m)
    a = skill.dt_s / (skill.tau_s * time_scale)
    phi = phases(a, n)
    with np.errstate(all="ignore"):
        hl = (path_scale * (normalised_kernels(phi, skill.centres, skill.widths) @ skill.y_weights)).tolist()
    alpha, beta_y = skill.alpha, skill.beta_y
    qq, zz = path_scale * skill.y_p0_m, path_scale * skill.y_z0_m
    ql = [0.0] * (n + 1)
    for j in range(n + 1):
        ql[j] = qq
        qq, zz = qq + a * (zz - qq + hl[j]), zz + a * alpha * (-beta_y * qq - zz)
    with np.errstate(all="ignore"):
        p = path_scale * skill.goal_y_m + np.asarray(ql)
        if ramp_in:
            p = p * path_ramp(a, n, ramp_out)
        y = skill.y_start_m + p
    return t, y


def path_matrix(alpha: float, beta_y: float, a: float) -> np.ndarray:
    """The step of the y path's (q, z_q) without forcing: s' = A s + (a*h_y, 0)."""
    return np.array([[1.0 - a, a], [-a * alpha * beta_y, 1.0 - a * alpha]])


def path_cycle_start(alpha: float, beta_y: float, a: float, h_y: np.ndarray) -> np.ndarray:
    """The y path's (q, z_q) at phi = 0 of the periodic orbit driven by one period h_y_0..h_y_{P-1}
    (``cycle_start``'s (1 - A^P)^-1 s_P(from rest) with the 2x2 step)."""
    m = path_matrix(alpha, beta_y, a)
    b = np.zeros((h_y.size, 2))
    b[:, 0] = a * h_y
    free = linear_scan(m, b)[-1]
    s0: np.ndarray = np.linalg.solve(np.eye(2) - np.linalg.matrix_power(m, h_y.size), free)
    return s0


def rollout_path_scan(skill: Skill, n_steps: int) -> np.ndarray:
    """y_hat_n, n = 0..n_steps, at scales 1: ``rollout_path`` by the blocked linear scan."""
    assert skill.y_weights is not None
    a = skill.dt_s / skill.tau_s
    phi = phases(a, n_steps)
    b = np.zeros((n_steps, 2))
    b[:, 0] = a * (normalised_kernels(phi[:-1], skill.centres, skill.widths) @ skill.y_weights)
    s = linear_scan(path_matrix(skill.alpha, skill.beta_y, a), b, np.array([skill.y_p0_m, skill.y_z0_m]))
    out: np.ndarray = skill.y_start_m + skill.goal_y_m + s[:, 0]
    return out


def rollout_scan(skill: Skill, n_steps: int) -> np.ndarray:
    """f_hat_n, n = 0..n_steps, at scales 1: ``rollout`` by a blocked linear scan (the fit's fast
    evaluation; equal to the loop within round-off, tests/host/model/test_periodic.py)."""
    a = skill.dt_s / skill.tau_s
    phi = phases(a, n_steps)
    h = skill.amplitude_N * (normalised_kernels(phi[:-1], skill.centres, skill.widths) @ skill.weights)
    b = np.zeros((n_steps, 3))
    b[:, 0] = a * h
    s = linear_scan(
        transform_matrix(skill.alpha, skill.beta, skill.gamma, a),
        b,
        np.array([skill.e0_N, skill.z0_N, skill.i0_N]),
    )
    out: np.ndarray = skill.force0_N + skill.goal_N + s[:, 0]
    return out


def cycle_state(
    e_star: np.ndarray, alpha: float, beta: float, gamma: float, a: float
) -> tuple[np.ndarray, np.ndarray]:
    """z_n and I_n, n = 0..P, on the cycle driven by one period e*_0..e*_{P-1} of a zero-mean
    deviation: z the periodic solution of z' = z + a*alpha*(-beta*e* - z) (z_P = z_0), I the
    running sum a*sum e* shifted to zero mean over the cycle (periodic because sum e* = 0)."""
    p = e_star.size
    q = 1.0 - a * alpha
    b = -a * alpha * beta * e_star
    z_free = linear_scan(np.array([[q]]), b[:, None])[:, 0]  # from z_0 = 0
    z0 = z_free[-1] / (1.0 - q**p)
    z: np.ndarray = z_free + z0 * q ** np.arange(p + 1)
    big_i = np.concatenate(([0.0], np.cumsum(a * e_star)))
    big_i -= float(np.mean(big_i[:-1]))
    return z, big_i


def cycle_start(params: tuple[float, float, float], a: float, h: np.ndarray) -> np.ndarray:
    """The state (e, z, I) at phi = 0 of the periodic orbit driven by one period of forcing
    h_0..h_{P-1}: s_0 = (1 - A^P)^-1 * s_P(from rest), unique because every eigenvalue of the
    stable step A lies inside the unit circle. On that orbit sum e_n = 0 (I returns to itself):
    the mean of f_hat over a cycle is exactly the goal."""
    alpha, beta, gamma = params
    m = transform_matrix(alpha, beta, gamma, a)
    b = np.zeros((h.size, 3))
    b[:, 0] = a * h
    free = linear_scan(m, b)[-1]
    s0: np.ndarray = np.linalg.solve(np.eye(3) - np.linalg.matrix_power(m, h.size), free)
    return s0

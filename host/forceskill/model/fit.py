"""Fitting a force skill from one demonstration (docs/math.md section 3).

Steps: resample to dt; starting force f0 (the first sample unless given); learning target
y* = f - f0 in N (the DMP runs in force units, so nothing below depends on the stiffness k); goal
g = k*g'(T) in N with the position reference the executor will use (k*x_d = f) and the force
integral by the left rectangle rule (the forward-Euler sum the control law's integrator uses); tau by a bracketing
search so the discrete phase gives u~(T) = 0.99 (``lwr``: 0.95); kernel times denser where the
demonstration bends (``kernel_times``) mapped to phase, widths sigma_i = 0.65*(c_{i+1} - c_{i-1})/2
(``lwr``: times uniform, sigma_i = 0.35*(c_{i+1} - c_i)); h_d from the same
discrete recursion as the rollout; regression of h_d on g*v~*S(u~) by ``ridge`` (joint
Tikhonov-regularised least squares, the default) or ``lwr`` (the paper's per-kernel weighted LS);
then the learned force is rolled out and compared with the demonstration.

A demonstration with a path along y (``Demo.y_m``) also gets the position DMP on y (paper eq. 9:
the same law with k_f = k_i = 0, so gamma = 0 and beta_y = k_p/(m_d*alpha) - 1), fitted on the
same phase, tau and kernels: target p* = y - y(0) in m, goal g_y = k_p*p*(T)/(m_d*alpha*beta_y)
(the DMP's rest point is p*(T)), h_d from the same recursion with gamma = 0, and the regression of
h_d on v~*S_y(u~) (no goal factor: a wiping path may end where it started, g_y = 0) with the
force's method and kernels. The weights are in m.

Memory: after the goal and the kernel times, the recording is gone through in blocks of steps
(``dmp.phase_blocks``, the recursions' states carried from block to block): once for h_d and the
regression's sums (the kernels of each block evaluated only where they reach, ``dmp.kernel_blocks``),
once for the rollout. Grid-sized arrays: y* until the passes, then the learned force (and y path);
the numbers are those of whole-array passes to round-off.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..errors import ERR_FIT_ARGS, ERR_FIT_GOAL, ERR_FIT_NUMERIC, DemoError, FsError, ParamError
from ..wire import TICK_S
from . import dmp
from .demo import Demo, resample, validate
from .params import DmpParams, Gains, check_inertia, check_stiffness, derive, goal
from .skill import FLAG_END_RELEASE, MAX_KERNELS, Skill, derive_beta_y

PHASE_AT_END = 0.99
#: sigma_i = WIDTH_FACTOR * (c_{i+1} - c_i)
WIDTH_FACTOR = 0.65
#: The paper's LWR (local constants) uses its own phase end and narrower kernels: its bias grows
#: with the kernel width and with the 1/v~ growth of h_d/(g*v~) near the end of the phase, times
#: g/max|x*| (measured on the HIL demonstrations, docs/math.md section 3).
LWR_PHASE_AT_END = 0.95
LWR_WIDTH_FACTOR = 0.35
#: g must exceed this fraction of max|y*|: below, the phase-normalised forcing needs huge weights.
GOAL_MIN_REL = 1e-3
#: Tikhonov term of the ridge fit, relative to the mean diagonal of the normal matrix
#: (measured on the synthetic tasks, docs/math.md section 3).
RIDGE_LAMBDA_REL = 1e-6
#: Kernel density (``kernel_times``, ridge): rho = 1 + DENSITY_GAIN*curvature/mean curvature, the
#: curvature of DENSITY_BIN_S bin means smoothed over DENSITY_SMOOTH_S (docs/math.md section 3).
DENSITY_GAIN = 0.5
DENSITY_BIN_S = 0.05
DENSITY_SMOOTH_S = 0.6
#: curvature above this multiple of its mean counts as this multiple (bounds the narrowest gap)
DENSITY_CLIP = 2.0
#: The denser layout is used only while at most this many kernels are within the Cortex-M float
#: images' cutoff (DEVICE_CUTOFF_EXP; the fixed point's 12 sums fewer) at any phase; otherwise the
#: gain is halved, then the layout is uniform in time (the M4F tick budget, docs/math.md section 3).
KERNELS_PER_TICK_MAX = 12
DEVICE_CUTOFF_EXP = 16.0
METHODS = ("ridge", "lwr")
END_POLICIES = ("hold", "release")


@dataclass
class FitResult:
    """The skill and how well it reproduces the demonstration (errors in % of max |force|)."""

    skill: Skill
    t_s: np.ndarray
    target_N: np.ndarray
    f_hat_N: np.ndarray
    err_max_pct: float
    err_rms_pct: float
    pos_m: np.ndarray = field(default_factory=lambda: np.zeros(0))
    method: str = "ridge"
    #: the y half (a demonstration with a path along y): demonstrated and learned path (m) and the
    #: learned path's error in mm; empty / nan without one
    y_target_m: np.ndarray = field(default_factory=lambda: np.zeros(0))
    y_hat_m: np.ndarray = field(default_factory=lambda: np.zeros(0))
    y_err_max_mm: float = math.nan
    y_err_rms_mm: float = math.nan

    @property
    def h_d(self) -> np.ndarray:
        """The desired forcing of the target (``desired_forcing``), made when asked for: a
        grid-sized array the fit itself only forms block by block."""
        sk = self.skill
        y_star = self.target_N - sk.force0_N
        return desired_forcing(y_star, sk.alpha, sk.beta, sk.gamma, sk.dt_s / sk.tau_s, sk.goal_N)


def _phase_end(alpha: float, beta: float, a: float, n: int) -> float:
    """u~ after n forward-Euler steps of the phase from rest, via powers of its 2x2 matrix."""
    m = np.array([[1.0, a], [-a * alpha * beta, 1.0 - a * alpha]])
    e_n = np.linalg.matrix_power(m, n) @ np.array([-1.0, 0.0])  # error state (u - 1, v)
    return 1.0 + float(e_n[0])


def solve_tau(alpha: float, beta: float, dt_s: float, n_steps: int, target: float = PHASE_AT_END) -> float:
    """tau with u~_{n_steps} = target for the discrete phase (bracketing: regula falsi, Illinois).

    u~_n decreases monotonically with tau; the bracket is widened until it holds the root.
    """
    if n_steps < 1:
        raise ParamError(ERR_FIT_ARGS, f"need at least one step to fit tau: {n_steps}")
    T = n_steps * dt_s

    def r(tau: float) -> float:
        return _phase_end(alpha, beta, dt_s / tau, n_steps) - target

    lo, hi = 0.2 * T, 2.0 * T
    lo = max(lo, 2.0 * alpha * dt_s)  # keep dt/tau*alpha < 0.5: stable, monotone Euler phase
    r_lo, r_hi = r(lo), r(hi)
    for _ in range(60):
        if r_hi < 0.0:
            break
        hi *= 2.0
        r_hi = r(hi)
    if not (r_lo > 0.0 > r_hi):
        raise ParamError(
            ERR_FIT_ARGS,
            f"cannot place the phase: u~(T) = {target} unreachable for "
            f"T = {T:g} s (alpha = {alpha:g}, beta = {beta:g})",
        )
    side = 0
    tau = lo
    for _ in range(200):
        tau = (lo * r_hi - hi * r_lo) / (r_hi - r_lo)
        if not lo < tau < hi:
            tau = 0.5 * (lo + hi)
        rt = r(tau)
        if rt == 0.0 or (hi - lo) <= 1e-14 * hi:
            break
        if rt > 0.0:
            lo, r_lo = tau, rt
            if side == 1:
                r_hi *= 0.5
            side = 1
        else:
            hi, r_hi = tau, rt
            if side == -1:
                r_lo *= 0.5
            side = -1
        if abs(rt) < 1e-15:
            break
    return tau


def _curvature(signal: np.ndarray, hb: int, nb: int, ks: int) -> np.ndarray:
    """|second difference| of hb-sample bin means (0 in the end bins), moving mean over ks bins."""
    yb = signal[: nb * hb].reshape(nb, hb).mean(axis=1)
    q = np.zeros(nb)
    q[1:-1] = np.abs(yb[2:] - 2.0 * yb[1:-1] + yb[:-2])
    q = np.convolve(np.pad(q, ks // 2, mode="edge"), np.full(ks, 1.0 / ks), mode="valid")
    return q


def kernel_times(
    y_star: np.ndarray,
    dt_s: float,
    n_kernels: int,
    density_gain: float = DENSITY_GAIN,
    path: np.ndarray | None = None,
) -> np.ndarray:
    """Kernel times t_1 = 0 < ... < t_N = T, denser where the demonstration bends.

    Density rho(t) = 1 + density_gain*min(q(t)/mean(q), DENSITY_CLIP), q the curvature |y*''| of
    DENSITY_BIN_S bin means (the binning averages sensor noise out) smoothed over
    DENSITY_SMOOTH_S; with a ``path`` (the y DMP shares the kernels) q is the sum of both
    curvatures, each relative to its own mean. t_i is where the cumulative density reaches
    (i-1)/(N-1) of its total. density_gain 0, a flat recording or one shorter than three bins:
    uniform in time (linspace(0, T, N)).
    """
    n_t = y_star.size - 1
    duration = n_t * dt_s
    hb = max(1, int(round(DENSITY_BIN_S / dt_s)))
    nb = (n_t + 1) // hb
    if density_gain <= 0.0 or nb < 3:
        return np.linspace(0.0, duration, n_kernels)
    ks = max(1, int(round(DENSITY_SMOOTH_S / (hb * dt_s)))) | 1
    q = np.zeros(nb)
    for sig in (y_star,) if path is None else (y_star, path):
        qs = _curvature(sig, hb, nb, ks)
        qs_mean = float(np.mean(qs))
        # round-off of a straight line is no bend: curvature below 1e-9 of the signal counts as none
        if qs_mean > 1e-9 * _max_abs(sig) and math.isfinite(qs_mean):
            q += qs / qs_mean
    q_mean = float(np.mean(q))
    if not q_mean > 0.0:
        return np.linspace(0.0, duration, n_kernels)
    rho = 1.0 + density_gain * np.minimum(q / q_mean, DENSITY_CLIP)
    edges = np.arange(nb + 1) * (hb * dt_s)
    edges[-1] = duration  # the last bin takes the samples a whole bin leaves over
    cum = np.concatenate(([0.0], np.cumsum(rho * np.diff(edges))))
    t_i: np.ndarray = np.interp(np.linspace(0.0, cum[-1], n_kernels), cum, edges)
    t_i[0], t_i[-1] = 0.0, duration
    return t_i


def kernels_per_tick(centres: np.ndarray, widths: np.ndarray, cutoff: float = DEVICE_CUTOFF_EXP) -> int:
    """The most kernels with (u - c_i)^2/(2 sigma_i^2) <= cutoff at any one phase u (the largest
    overlap of the intervals c_i -+ sqrt(2*cutoff)*sigma_i)."""
    r = math.sqrt(2.0 * cutoff) * widths
    pos = np.concatenate((centres - r, centres + r))
    step = np.concatenate((np.ones(centres.size), -np.ones(centres.size)))
    order = np.lexsort((-step, pos))  # closed intervals: at a tie the start counts first
    return int(np.max(np.cumsum(step[order])))


def kernel_layout(
    u_i: np.ndarray, width_factor: float = WIDTH_FACTOR, uniform: bool = True
) -> tuple[np.ndarray, np.ndarray]:
    """Centres c_i = u_i, the discrete phase at the kernel times t_i (``phase_at`` of t_i/dt;
    t_i = linspace(0, T, N) for the uniform layout, else ``kernel_times``). Widths: uniform (the
    ``lwr`` layout), sigma_i = width_factor*(c_{i+1} - c_i), sigma_N = sigma_{N-1}; otherwise
    sigma_i = width_factor*(c_{i+1} - c_{i-1})/2 (the mean of the two gaps; one gap at either end),
    so neighbours of unequal gaps get comparable widths."""
    centres = np.asarray(u_i, dtype=float)
    gaps = np.diff(centres)
    if uniform:
        widths = width_factor * np.append(gaps, gaps[-1])
    else:
        widths = width_factor * 0.5 * (np.append(gaps[:1], gaps) + np.append(gaps, gaps[-1:]))
    return centres, widths


def phase_at(alpha: float, beta: float, a: float, n_steps: int, x: np.ndarray) -> np.ndarray:
    """The discrete phase u~ at fractional steps ``x`` (linear interpolation over n = 0..n_steps,
    as ``np.interp`` of the whole phase gives it), from one pass of ``dmp.phase_blocks``."""
    x = np.asarray(x, dtype=float)
    out = np.empty(x.size)
    for i0, u, _ in dmp.phase_blocks(alpha, beta, a, n_steps):
        i1 = i0 + u.size - 1
        sel = ((x >= i0) | (i0 == 0)) & ((x < i1) | (i1 >= n_steps))
        out[sel] = np.interp(x[sel], np.arange(i0, i1 + 1, dtype=float), u)
    return out


def desired_forcing(
    y_star: np.ndarray, alpha: float, beta: float, gamma: float, a: float, goal_N: float
) -> np.ndarray:
    """h_d,n = (y*_{n+1} - y*_n)/a - (z_n - y*_n - gamma*I_n), n = 0..M-1, z and I driven by y*.

    The forward-Euler y-update solved for h, so replaying h_d reproduces y* to round-off.
    """
    m = y_star.size - 1
    big_i = np.empty(m + 1)
    big_i[0] = 0.0
    np.cumsum(a * y_star[:-1], out=big_i[1:])
    b = a * alpha * (beta * (goal_N - y_star[:-1]))
    z = dmp.linear_scan(np.array([[1.0 - a * alpha]]), b[:, None])[:, 0]
    f_target: np.ndarray = (y_star[1:] - y_star[:-1]) / a - (z[:-1] - y_star[:-1] - gamma * big_i[:-1])
    return f_target


def _forcing_block(
    ys: np.ndarray, alpha: float, beta: float, gamma: float, a: float, goal_N: float, state: np.ndarray
) -> np.ndarray:
    """``desired_forcing`` of one block of steps: ``ys`` holds y* of its steps and of the step
    after the last; ``state`` = (z, I) at its first step, updated to the next block's."""
    q = 1.0 - a * alpha
    b = a * alpha * (beta * (goal_N - ys[:-1]))
    z = dmp.linear_scan(np.array([[q]]), b[:, None], state[:1])[:, 0]
    # I by the same running sum as a cumsum over the whole target
    big_i = np.cumsum(np.concatenate((state[1:], a * ys[:-1])))
    state[0], state[1] = z[-1], big_i[-1]
    h_d: np.ndarray = (ys[1:] - ys[:-1]) / a - (z[:-1] - ys[:-1] - gamma * big_i[:-1])
    return h_d


class _Normal:
    """The regression's sums over the rows, added block by block: ridge's normal equations
    K^T diag(s^2) K and K^T (s h_d) of the normalised kernels K, or LWR's per-kernel sums of the
    raw psi."""

    def __init__(self, n_kernels: int, lwr: bool) -> None:
        self.lwr = lwr
        self.lhs = np.zeros(n_kernels) if lwr else np.zeros((n_kernels, n_kernels))
        self.rhs = np.zeros(n_kernels)

    def add(self, k0: int, psi: np.ndarray, s: np.ndarray, h_d: np.ndarray) -> None:
        """The rows of one kernel block (``dmp.kernel_blocks``, kernel-major): psi raw for LWR,
        normalised for ridge; s and h_d of the same rows."""
        k1 = k0 + psi.shape[0]
        self.rhs[k0:k1] += psi @ (s * h_d)
        if self.lwr:
            self.lhs[k0:k1] += psi @ (s * s)
        else:
            self.lhs[k0:k1, k0:k1] += (psi * (s * s)) @ psi.T

    def solve(self, lam_rel: float) -> np.ndarray:
        """Weights w with h_d ~ s*S(u): ridge (joint, Tikhonov relative to the mean diagonal) or
        the paper's per-kernel LWR (w_i = sum psi_i s h_d / sum psi_i s^2)."""
        if not self.lwr:
            lam = lam_rel * float(np.trace(self.lhs)) / self.lhs.shape[0]
            self.lhs[np.diag_indices_from(self.lhs)] += lam  # in place: N x N is 8 MiB at N = 1024
            w: np.ndarray = np.linalg.solve(self.lhs, self.rhs)
            return w
        den = self.lhs
        w = np.where(den > 0.0, self.rhs / np.where(den > 0.0, den, 1.0), 0.0)
        return w


def _max_abs(x: np.ndarray) -> float:
    """max |x| without a full-size |x|."""
    return max(float(np.max(x)), -float(np.min(x))) if x.size else 0.0


def prepare(
    demo: Demo,
    stiffness_Npm: float,
    n_kernels: int,
    method: str,
    gains: Gains,
    surface_m: float,
    dt_s: float,
    object_mass_kg: float | None,
    copy: bool = True,
) -> tuple[DmpParams, Demo]:
    """The checks every fit makes before it learns (method, kernels, surface, stiffness, gains,
    the demonstration), then the law's derived parameters and the demonstration at dt_s
    (``resample``; ``copy`` False: a demonstration already on the grid keeps its arrays)."""
    if method not in METHODS:
        raise ParamError(ERR_FIT_ARGS, f"method must be one of {', '.join(METHODS)}: {method!r}")
    if not (isinstance(n_kernels, (int, np.integer)) and 2 <= n_kernels <= MAX_KERNELS):
        raise ParamError(ERR_FIT_ARGS, f"number of kernels must be in 2..{MAX_KERNELS}: {n_kernels}")
    if not math.isfinite(surface_m):
        raise ParamError(ERR_FIT_ARGS, f"surface position must be finite: {surface_m}")
    check_stiffness(stiffness_Npm)
    p = derive(gains)
    if object_mass_kg is not None:
        check_inertia(gains, stiffness_Npm, object_mass_kg)
    validate(demo)
    return p, resample(demo, dt_s, copy=copy)


def law_fields(
    p: DmpParams, gains: Gains, dt_s: float, tau_s: float, stiffness_Npm: float, surface_m: float
) -> dict[str, Any]:
    """The skill fields every kind takes from the law: its time base, DMP gains and the device's
    control-law gains."""
    return {
        "dt_s": dt_s,
        "tau_s": tau_s,
        "alpha": p.alpha,
        "beta": p.beta,
        "gamma": p.gamma,
        "stiffness_Npm": stiffness_Npm,
        "m_d_kg": gains.m_d_kg,
        "k_d_Nspm": gains.k_d_Nspm,
        "k_p_Npm": gains.k_p_Npm,
        "kkf_Npm": gains.kkf_Npm,
        "kki_Npms": gains.kki_Npms,
        "surface_m": surface_m,
    }


def fit(
    demo: Demo,
    stiffness_Npm: float,
    n_kernels: int = 50,
    method: str = "ridge",
    gains: Gains = Gains(),
    surface_m: float = 0.0,
    end_policy: str = "hold",
    dt_s: float = TICK_S,
    ridge_lambda_rel: float | None = None,
    force0_N: float | None = None,
    object_mass_kg: float | None = None,
) -> FitResult:
    """Learn a skill from one demonstration; raises ParamError/DemoError (one-line, numbered).

    ``force0_N``: the starting force (None: the demonstration's first resampled force).
    ``object_mass_kg``: when known, k_f*m_v/m_d < 1 is checked (code 112).
    """
    if end_policy not in END_POLICIES:
        raise ParamError(ERR_FIT_ARGS, f"end policy must be one of {', '.join(END_POLICIES)}: {end_policy!r}")
    if force0_N is not None and not math.isfinite(force0_N):
        raise ParamError(ERR_FIT_ARGS, f"starting force must be finite: {force0_N}")
    lam_rel = RIDGE_LAMBDA_REL if ridge_lambda_rel is None else float(ridge_lambda_rel)
    p, d = prepare(demo, stiffness_Npm, n_kernels, method, gains, surface_m, dt_s, object_mass_kg, copy=False)
    n_t = d.t_s.size - 1
    duration = n_t * dt_s
    f = d.force_N
    f0 = float(f[0]) if force0_N is None else float(force0_N)
    # y* = f - f0 whole only for the goal, its scale and the kernel times; the passes below make
    # it block by block (a long recording's fit holds few grid-sized arrays)
    y_star = f - f0
    # goal: g = k*g'(T) with k*x_d(T) = f(T) (the executor's reference), int f by the left rectangle
    # rule (what the integrator of the law accumulates); all of it above the starting force
    f_int = dt_s * float(np.sum(y_star[:-1]))
    goal_N = goal(p, gains, float(y_star[-1]), float(y_star[-1]), f_int)
    y_scale = _max_abs(y_star)
    if not (goal_N > GOAL_MIN_REL * y_scale):
        raise DemoError(
            ERR_FIT_GOAL,
            f"goal g = {goal_N:.4g} N is not > {GOAL_MIN_REL:g} x max|f - f0| = "
            f"{GOAL_MIN_REL * y_scale:.4g} N (f0 = {f0:.4g} N): the demonstration has no net push "
            "above its starting force to learn",
        )
    lwr = method == "lwr"
    tau = solve_tau(p.alpha, p.beta, dt_s, n_t, LWR_PHASE_AT_END if lwr else PHASE_AT_END)
    a = dt_s / tau
    # kernel times: uniform (lwr, and the fallback of the denser layout), then the denser ones
    n_k = int(n_kernels)
    times = [np.linspace(0.0, duration, n_k)]
    gains_tried = () if lwr or DENSITY_GAIN <= 0.0 else (DENSITY_GAIN, 0.5 * DENSITY_GAIN)
    times += [kernel_times(y_star, dt_s, n_k, gain, d.y_m) for gain in gains_tried]
    del y_star
    u_i = phase_at(p.alpha, p.beta, a, n_t, np.concatenate(times) / dt_s).reshape(len(times), n_k)
    centres, widths = kernel_layout(u_i[0], LWR_WIDTH_FACTOR if lwr else WIDTH_FACTOR)
    for u_g in u_i[1:]:
        c_g, w_g = kernel_layout(u_g, WIDTH_FACTOR, uniform=False)
        if kernels_per_tick(c_g, w_g) <= KERNELS_PER_TICK_MAX:
            centres, widths = c_g, w_g
            break
    if not (np.all(np.diff(centres) > 0.0) and centres[0] >= 0.0 and centres[-1] <= 1.0):
        raise ParamError(
            ERR_FIT_ARGS,
            f"{n_kernels} kernels do not fit a {duration:g} s demonstration "
            f"at dt = {dt_s:g} s (centres collide)",
        )
    # the regression: h_d and the kernels block by block, the normal equations summed
    y_path = d.y_m
    beta_y = goal_y = y0 = 0.0
    if y_path is not None:
        beta_y = derive_beta_y(gains)
        y0 = float(y_path[0])
        goal_y = gains.k_p_Npm * (float(y_path[-1]) - y0) / (gains.m_d_kg * p.alpha * beta_y)
    normal, normal_y = _Normal(n_k, lwr), None if y_path is None else _Normal(n_k, lwr)
    state, state_y = np.zeros(2), np.zeros(2)
    for i0, u, v in dmp.phase_blocks(p.alpha, p.beta, a, n_t):
        i1 = i0 + u.size - 1
        h_d = _forcing_block(f[i0 : i1 + 1] - f0, p.alpha, p.beta, p.gamma, a, goal_N, state)
        s = goal_N * v[:-1]  # h = s_n * S(u_n)
        h_d_y = None
        if y_path is not None:
            h_d_y = _forcing_block(y_path[i0 : i1 + 1] - y0, p.alpha, beta_y, 0.0, a, goal_y, state_y)
        for r0, k0, psi in dmp.kernel_blocks(u[:-1], centres, widths):
            rows = slice(r0, r0 + psi.shape[1])
            if not lwr:
                dmp.normalise_rows(psi)
            normal.add(k0, psi, s[rows], h_d[rows])
            if normal_y is not None and h_d_y is not None:
                normal_y.add(k0, psi, v[:-1][rows], h_d_y[rows])
    weights = normal.solve(lam_rel)
    del normal
    if not np.all(np.isfinite(weights)):
        raise FsError(ERR_FIT_NUMERIC, f"regression gave a non-finite weight ({method}, N = {n_kernels})")
    y_kw: dict[str, Any] = {}
    if normal_y is not None:
        y_weights = normal_y.solve(lam_rel)
        del normal_y
        if not np.all(np.isfinite(y_weights)):
            raise FsError(
                ERR_FIT_NUMERIC, f"y regression gave a non-finite weight ({method}, N = {n_kernels})"
            )
        y_kw = {"y_start_m": y0, "goal_y_m": goal_y, "y_weights": y_weights}
    skill = Skill(
        **law_fields(p, gains, dt_s, tau, stiffness_Npm, surface_m),
        goal_N=goal_N,
        duration_s=duration,
        force0_N=f0,
        centres=centres,
        widths=widths,
        weights=weights,
        flags=FLAG_END_RELEASE if end_policy == "release" else 0,
        **y_kw,
    )
    skill.to_bytes()  # validates exactly as the firmware will
    # the rollout on the same blocks: the learned force (and y path) and their errors
    f_hat = np.empty(n_t + 1)
    f_hat[0] = f0
    y_hat = None if y_path is None else np.empty(n_t + 1)
    mix = [weights] if skill.y_weights is None else [weights, skill.y_weights]
    tstate, pstate = np.zeros(3), np.zeros(3)
    err_max = abs(float(f[0]) - f0)
    err_sq = err_max * err_max
    e_y_max = e_y_sq = 0.0
    for i0, u, v in dmp.phase_blocks(p.alpha, p.beta, a, n_t):
        i1 = i0 + u.size - 1
        scales = dmp.kernel_mix(u[:-1], centres, widths, mix)
        out = dmp.transform_block(p.alpha, p.beta, p.gamma, a, goal_N, goal_N * v[:-1] * scales[0], tstate)
        tstate = out[-1]
        f_hat[i0 + 1 : i1 + 1] = f0 + out[1:, 0]
        err = f[i0 + 1 : i1 + 1] - f_hat[i0 + 1 : i1 + 1]
        err_max = max(err_max, _max_abs(err))
        err_sq += float(err @ err)
        if y_hat is not None and y_path is not None:
            out = dmp.transform_block(p.alpha, beta_y, 0.0, a, goal_y, v[:-1] * scales[1], pstate)
            pstate = out[-1]
            y_hat[i0 + 1 : i1 + 1] = y0 + out[1:, 0]
            e_y = y_path[i0 + 1 : i1 + 1] - y_hat[i0 + 1 : i1 + 1]
            e_y_max = max(e_y_max, _max_abs(e_y))
            e_y_sq += float(e_y @ e_y)
    f_max = _max_abs(f)
    y_res: dict[str, Any] = {}
    if y_hat is not None:
        y_hat[0] = y0
        y_res = {
            "y_target_m": y_path,
            "y_hat_m": y_hat,
            "y_err_max_mm": 1e3 * e_y_max,
            "y_err_rms_mm": 1e3 * math.sqrt(e_y_sq / (n_t + 1)),
        }
    return FitResult(
        skill=skill,
        t_s=d.t_s,
        target_N=f,
        f_hat_N=f_hat,
        err_max_pct=100.0 * err_max / f_max,
        err_rms_pct=100.0 * math.sqrt(err_sq / (n_t + 1)) / f_max,
        pos_m=d.pos_m,
        method=method,
        **y_res,
    )

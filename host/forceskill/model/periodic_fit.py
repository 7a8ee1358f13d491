"""Fitting a periodic force skill from a multi-stroke demonstration (docs/math.md section 5).

Steps: resample to dt; the period by autocorrelation of the middle half of the recording (unless
given); the steady strokes: consecutive windows of one period around the middle whose shape and
mean stay close to the middle strokes' median (the approach and the release fail that and are
left out); each stroke resampled onto P = round(period/dt) samples and averaged (the mean
stroke); its mean force is the goal g, its deviation e* = mean stroke - g; the state on the cycle
and the desired forcing from the exact recursion of ``periodic``; the regression of h_d on
r*S(phi) (ridge or the paper's per-kernel LWR) over the cycle. The least squares over every
steady stroke's samples is that over the mean stroke (each stroke has the same phases), so the
fit learns the mean stroke.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..errors import (
    ERR_FIT_ARGS,
    ERR_FIT_NUMERIC,
    ERR_PERIODIC_AMPLITUDE,
    ERR_PERIODIC_GOAL,
    ERR_PERIODIC_STROKES,
    DemoError,
    FsError,
    ParamError,
)
from ..wire import TICK_S
from . import periodic
from .demo import Demo
from .fit import law_fields, prepare
from .params import Gains
from .skill import KIND_PERIODIC, Skill, derive_beta_y

#: sigma_i = WIDTH_FACTOR * 2*pi/N as the equivalent Gaussian width: kappa_i = 1/sigma_i^2
WIDTH_FACTOR = 0.65
RIDGE_LAMBDA_REL = 1e-6
#: the shortest period searched, s, and the fewest steady strokes a fit uses
PERIOD_MIN_S = 0.1
MIN_STROKES = 2
#: a window is a steady stroke while its largest distance to the median stroke is at most this
#: fraction of the median stroke's amplitude plus STROKE_NOISE_SIGMAS of the middle strokes'
#: spread about the median (the sensor noise)
STROKE_SHAPE_TOL = 0.03
STROKE_NOISE_SIGMAS = 4.0


@dataclass
class PeriodicFit:
    """The skill, the strokes it was learned from and its errors (in % of max |force|)."""

    skill: Skill
    period_s: float
    start_s: float
    strokes_N: np.ndarray  # (K, P): each steady stroke on the P-sample cycle grid
    mean_stroke_N: np.ndarray  # (P,)
    cycle_N: np.ndarray  # (P + 1,): the learned cycle, rows 0..P of the rollout
    err_mean_max_pct: float
    err_mean_rms_pct: float
    err_stroke_max_pct: np.ndarray  # (K,)
    f_max_N: float
    method: str = "ridge"
    #: the y path (a recording with a y column): the mean y stroke (P,) and the learned path's
    #: cycle (P + 1,) in m, the cycle's max and RMS error against the mean stroke in mm; empty /
    #: nan without one
    y_mean_stroke_m: np.ndarray = field(default_factory=lambda: np.zeros(0))
    y_cycle_m: np.ndarray = field(default_factory=lambda: np.zeros(0))
    y_err_max_mm: float = math.nan
    y_err_rms_mm: float = math.nan


def autocorr_period(f: np.ndarray, dt_s: float, period_min_s: float = PERIOD_MIN_S) -> float:
    """The period of f (s): the first autocorrelation peak within 0.8 of the highest at lags from
    period_min_s to a third of the signal, refined by a parabola through the peak and its neighbours."""
    x = f - float(np.mean(f))
    n = x.size
    m = 1 << int(math.ceil(math.log2(2 * n)))
    spec = np.fft.rfft(x, m)
    ac = np.fft.irfft(spec * np.conj(spec), m)[:n]
    lo = max(2, int(math.ceil(period_min_s / dt_s)))
    hi = n // 3
    if hi <= lo + 2 or not ac[0] > 0.0:
        raise DemoError(
            ERR_PERIODIC_STROKES, "recording too short or flat to find a period by autocorrelation"
        )
    seg = ac[lo:hi]
    peaks = np.flatnonzero((seg[1:-1] > seg[:-2]) & (seg[1:-1] >= seg[2:]) & (seg[1:-1] > 0.0)) + 1
    if peaks.size == 0:
        raise DemoError(
            ERR_PERIODIC_STROKES, "no period found: the autocorrelation has no peak (not repeated strokes?)"
        )
    best = float(np.max(seg[peaks]))
    k = int(peaks[np.flatnonzero(seg[peaks] >= 0.8 * best)[0]]) + lo
    y0, y1, y2 = ac[k - 1], ac[k], ac[k + 1]
    den = y0 - 2.0 * y1 + y2
    frac = 0.5 * (y0 - y2) / den if den < 0.0 else 0.0
    return (k + float(np.clip(frac, -0.5, 0.5))) * dt_s


def _window(f: np.ndarray, dt_s: float, start_s: float, period_s: float, p: int) -> np.ndarray:
    """f at start_s + j*period_s/p, j = 0..p-1 (linear interpolation on the dt grid)."""
    tj = (start_s + np.arange(p) * (period_s / p)) / dt_s
    out: np.ndarray = np.interp(tj, np.arange(f.size, dtype=float), f)
    return out


def steady_strokes(f: np.ndarray, dt_s: float, period_s: float) -> tuple[float, int, np.ndarray]:
    """(start_s, K, strokes (K, P)): the longest run of consecutive steady strokes around the
    middle of the recording, the first starting at start_s; P = round(period_s/dt_s)."""
    p = int(round(period_s / dt_s))
    duration = (f.size - 1) * dt_s
    # windows on a grid through the middle; the reference is the median of the middle half's
    mid = 0.5 * duration
    k_lo = -int(math.floor(mid / period_s))
    k_hi = int(math.floor((duration - mid) / period_s)) - 1
    starts = mid + period_s * np.arange(k_lo, k_hi + 1)
    starts = starts[(starts >= 0.0) & (starts + period_s <= duration)]
    if starts.size < MIN_STROKES:
        raise DemoError(
            ERR_PERIODIC_STROKES,
            f"recording of {duration:.3g} s holds fewer than {MIN_STROKES} periods of {period_s:.4g} s",
        )
    wins = np.stack([_window(f, dt_s, s, period_s, p) for s in starts])
    central = np.abs(starts + 0.5 * period_s - mid) <= 0.25 * duration
    ref = np.median(wins[central] if np.count_nonzero(central) >= 1 else wins, axis=0)
    amp = 0.5 * float(np.max(ref) - np.min(ref))
    sigma = (
        float(np.median(np.sqrt(np.mean((wins[central] - ref[None, :]) ** 2, axis=1))))
        if central.any()
        else 0.0
    )
    dist = np.max(np.abs(wins - ref[None, :]), axis=1)
    ok = dist <= STROKE_SHAPE_TOL * amp + STROKE_NOISE_SIGMAS * sigma
    c = int(np.argmin(np.abs(starts + 0.5 * period_s - mid)))
    if not ok[c]:
        raise DemoError(ERR_PERIODIC_STROKES, "the middle of the recording is not a steady stroke")
    a = c
    while a > 0 and ok[a - 1]:
        a -= 1
    b = c
    while b + 1 < ok.size and ok[b + 1]:
        b += 1
    if b - a + 1 < MIN_STROKES:
        raise DemoError(
            ERR_PERIODIC_STROKES, f"only {b - a + 1} steady stroke(s) of {period_s:.4g} s, need {MIN_STROKES}"
        )
    return float(starts[a]), b - a + 1, wins[a : b + 1]


def refine_period(f: np.ndarray, dt_s: float, start_s: float, k: int, period_s: float) -> float:
    """The period over the k steady strokes from start_s (the approach and the release
    excluded): the P that minimises the spread of the strokes started at start_s + j*P around
    their mean (zero for an exactly periodic force), by golden-section search within +-1 % of
    period_s. Each stroke is sampled at the same round(period_s/dt) phases, so the spread is a
    smooth function of P."""
    p = int(round(period_s / dt_s))
    grid = np.arange(f.size, dtype=float)
    phase = np.arange(p) / p
    starts = np.arange(k)
    end = (f.size - 1) * dt_s

    def spread(per: float) -> float:
        s0 = min(start_s, end - k * per)  # keep the last stroke inside the recording
        tj = (s0 + (starts[:, None] + phase[None, :]) * per) / dt_s
        w = np.interp(tj.ravel(), grid, f).reshape(k, p)
        return float(np.mean((w - w.mean(axis=0)) ** 2))

    lo, hi = 0.99 * period_s, 1.01 * period_s
    g = 0.5 * (math.sqrt(5.0) - 1.0)
    x1, x2 = hi - g * (hi - lo), lo + g * (hi - lo)
    f1, f2 = spread(x1), spread(x2)
    while hi - lo > 1e-9 * period_s:
        if f1 <= f2:
            hi, x2, f2 = x2, x1, f1
            x1 = hi - g * (hi - lo)
            f1 = spread(x1)
        else:
            lo, x1, f1 = x1, x2, f2
            x2 = lo + g * (hi - lo)
            f2 = spread(x2)
    return 0.5 * (lo + hi)


def kernel_layout(n_kernels: int, width_factor: float = WIDTH_FACTOR) -> tuple[np.ndarray, np.ndarray]:
    """Centres 2*pi*i/N, i = 0..N-1, and concentrations kappa = 1/(width_factor*2*pi/N)^2 (a von
    Mises kernel is a Gaussian of variance 1/kappa near its centre)."""
    centres = 2.0 * math.pi * np.arange(n_kernels) / n_kernels
    sigma = width_factor * 2.0 * math.pi / n_kernels
    return centres, np.full(n_kernels, 1.0 / (sigma * sigma))


def desired_forcing(e_star: np.ndarray, alpha: float, beta: float, gamma: float, a: float) -> np.ndarray:
    """h_d,n, n = 0..P-1, solving the e-update for h on the cycle (e*_P = e*_0) with z and I on
    their cycle (``periodic.cycle_state``): replaying h_d from (e*_0, z_0, I_0) reproduces e*
    every cycle."""
    z, big_i = periodic.cycle_state(e_star, alpha, beta, gamma, a)
    e_next = np.roll(e_star, -1)
    h: np.ndarray = (e_next - e_star) / a - (z[:-1] - e_star - gamma * big_i[:-1])
    return h


def _regress(kmat: np.ndarray, raw_e: np.ndarray, scale: float, h_d: np.ndarray, method: str) -> np.ndarray:
    """Weights w of h_d ~ scale*kmat@w: ridge (relative Tikhonov) or the paper's per-kernel LWR
    weighted by the raw kernels exp(-raw_e)."""
    if method == "ridge":
        phi_m = scale * kmat
        gram = phi_m.T @ phi_m
        lam = RIDGE_LAMBDA_REL * float(np.trace(gram)) / gram.shape[0]
        w: np.ndarray = np.linalg.solve(gram + lam * np.eye(gram.shape[0]), phi_m.T @ h_d)
    else:
        psi = np.exp(-raw_e)
        w = (psi.T @ h_d) / (scale * psi.sum(axis=0))
    if not np.all(np.isfinite(w)):
        raise FsError(ERR_FIT_NUMERIC, f"regression gave a non-finite weight ({method}, N = {w.size})")
    return w


def _path_fields(
    y_m: np.ndarray, start: float, k: int, period: float, dt_s: float, fit: tuple[Any, ...]
) -> tuple[dict[str, Any], np.ndarray]:
    """The y path's skill fields (y_start_m, goal_y_m, y_weights, y_p0_m, y_z0_m) from the k
    steady strokes of y from start and the mean y stroke; fit = (gains, alpha, a, kmat, raw_e,
    method)."""
    gains, alpha, a, kmat, raw_e, method = fit
    n_p = kmat.shape[0]
    strokes = np.stack([_window(y_m, dt_s, start + j * period, period, n_p) for j in range(k)])
    mean_y = strokes.mean(axis=0)
    p_star = mean_y - float(mean_y[0])
    goal_y = float(np.mean(p_star))
    q_star = p_star - goal_y
    beta_y = derive_beta_y(gains)
    h_d = desired_forcing(q_star, alpha, beta_y, 0.0, a)
    w_y = _regress(kmat, raw_e, 1.0, h_d, method)
    q0, zq0 = (float(x) for x in periodic.path_cycle_start(alpha, beta_y, a, kmat @ w_y))
    kw = {"y_start_m": float(mean_y[0]), "goal_y_m": goal_y, "y_weights": w_y, "y_p0_m": q0, "y_z0_m": zq0}
    return kw, mean_y


def fit_periodic(
    demo: Demo,
    stiffness_Npm: float,
    n_kernels: int = 50,
    method: str = "ridge",
    gains: Gains = Gains(),
    surface_m: float = 0.0,
    dt_s: float = TICK_S,
    period_s: float | None = None,
    object_mass_kg: float | None = None,
) -> PeriodicFit:
    """Learn a periodic skill from the steady strokes of ``demo``; raises ParamError/DemoError."""
    if period_s is not None and not (math.isfinite(period_s) and period_s >= PERIOD_MIN_S):
        raise ParamError(ERR_FIT_ARGS, f"--period must be a number >= {PERIOD_MIN_S:g} s: {period_s:g}")
    p, d = prepare(demo, stiffness_Npm, n_kernels, method, gains, surface_m, dt_s, object_mass_kg)
    f = d.force_N
    if period_s is None:
        n = f.size
        period0 = autocorr_period(f[n // 4 : n - n // 4], dt_s)
        period = period0
        for _ in range(2):  # the strokes at the estimate, then the period over those strokes
            start, k, _ = steady_strokes(f, dt_s, period)
            period = refine_period(f, dt_s, start, k, period)
    else:
        period = float(period_s)
    start, k, strokes = steady_strokes(f, dt_s, period)
    return fit_strokes(
        d, strokes, (period, start), stiffness_Npm, n_kernels, method, gains, surface_m, p, dt_s
    )


def fit_strokes(
    d: Demo,
    strokes: np.ndarray,
    timing: tuple[float, float],
    stiffness_Npm: float,
    n_kernels: int,
    method: str,
    gains: Gains,
    surface_m: float,
    p: Any,
    dt_s: float = TICK_S,
) -> PeriodicFit:
    """The periodic skill of the mean of ``strokes`` (K, P) (the steady strokes of ``d``, or the
    aligned strokes of several recordings); ``timing`` the period and the first stroke's start
    (s); ``d`` gives the maximum force and, with its y path, the y strokes from the same start."""
    f = d.force_N
    period, start = timing
    k = strokes.shape[0]
    n_p = strokes.shape[1]
    if n_p < 2 * n_kernels:
        raise ParamError(
            ERR_FIT_ARGS, f"{n_kernels} kernels need a period of at least {2 * n_kernels} steps: {n_p}"
        )
    mean_stroke = strokes.mean(axis=0)
    goal_N = float(np.mean(mean_stroke))
    f_max = float(np.max(np.abs(f)))
    if not goal_N > 1e-3 * f_max:
        raise DemoError(
            ERR_PERIODIC_GOAL,
            f"the strokes' mean force {goal_N:.4g} N is not a push (> 0.1 % of max {f_max:.4g} N)",
        )
    e_star = mean_stroke - goal_N
    amp = 0.5 * float(np.max(e_star) - np.min(e_star))
    if not amp > 1e-3 * f_max:
        raise DemoError(
            ERR_PERIODIC_AMPLITUDE,
            f"the strokes' amplitude {amp:.4g} N is below 0.1 % of max force: no stroke to learn",
        )
    tau = n_p * dt_s / (2.0 * math.pi)
    a = dt_s / tau
    h_d = desired_forcing(e_star, p.alpha, p.beta, p.gamma, a)
    phi = periodic.phases(a, n_p - 1)
    centres, kappa = kernel_layout(int(n_kernels))
    kmat = periodic.normalised_kernels(phi, centres, kappa)
    raw_e = periodic.kernel_exponents(phi, centres, kappa) if method != "ridge" else kmat
    weights = _regress(kmat, raw_e, amp, h_d, method)
    y_kw: dict[str, Any] = {}
    mean_y = np.zeros(0)
    if d.y_m is not None:
        y_kw, mean_y = _path_fields(d.y_m, start, k, period, dt_s, (gains, p.alpha, a, kmat, raw_e, method))
    e0, z0, i0 = (
        float(x) for x in periodic.cycle_start((p.alpha, p.beta, p.gamma), a, amp * (kmat @ weights))
    )
    skill = Skill(
        **law_fields(p, gains, dt_s, tau, stiffness_Npm, surface_m),
        goal_N=goal_N,
        duration_s=n_p * dt_s,
        centres=centres,
        widths=kappa,
        weights=weights,
        kind=KIND_PERIODIC,
        amplitude_N=amp,
        e0_N=e0,
        z0_N=z0,
        i0_N=i0,
        **y_kw,
    )
    skill.to_bytes()  # validates as the firmware will
    cycles = periodic.rollout_scan(skill, k * n_p)
    err = strokes - cycles[:-1].reshape(k, n_p)
    e_mean = mean_stroke - cycles[:n_p]
    y_res: dict[str, Any] = {}
    if mean_y.size:
        y_cycle = periodic.rollout_path_scan(skill, n_p)
        e_y = mean_y - y_cycle[:n_p]
        y_res = {
            "y_mean_stroke_m": mean_y,
            "y_cycle_m": y_cycle,
            "y_err_max_mm": 1e3 * float(np.max(np.abs(e_y))),
            "y_err_rms_mm": 1e3 * float(np.sqrt(np.mean(e_y * e_y))),
        }
    return PeriodicFit(
        skill=skill,
        period_s=period,
        start_s=start,
        strokes_N=strokes,
        mean_stroke_N=mean_stroke,
        cycle_N=cycles[: n_p + 1],
        err_mean_max_pct=100.0 * float(np.max(np.abs(e_mean))) / f_max,
        err_mean_rms_pct=100.0 * float(np.sqrt(np.mean(e_mean * e_mean))) / f_max,
        err_stroke_max_pct=100.0 * np.max(np.abs(err), axis=1) / f_max,
        f_max_N=f_max,
        method=method,
        **y_res,
    )

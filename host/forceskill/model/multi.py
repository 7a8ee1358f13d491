"""Several demonstrations of one task: alignment, mean profile, spread and band (docs/math.md
section 7).

Steps, on the fit grid (dt): each recording's idle lead is trimmed (``trim_lead``: the force
leaves its first 50 ms' level by more than LEAD_REL of its range or LEAD_NOISE_SIGMAS noise
deviations; from there back to where the rise began; LEAD_KEEP_S of the quiet lead before it is
kept); the recordings are registered in time, recording time ``t = stretch*tau + lag +
offset(tau)`` on the reference's time ``tau``: the affine part first (``register``: a vectorised
grid search over stretch and lag minimising the squared distance to the reference after the best
gain, then finer grids around the best), then a piecewise-linear offset over WARP_KNOTS knots
(``refine_warp``: Gauss-Newton with the gain and bias free, the warp's curvature penalised,
coarse to fine; the operator's speed varies within a stroke). The reference is first the
recording closest to the others, then the mean of the aligned recordings (ALIGN_ITERATIONS
passes, each refining the last pass's warps). The mean of the used recordings' warps is the
common time (the mean timing, not the reference's: mean stretch 1, mean lag 0), from where the
earliest recording starts to the reference's end; each recording's map is reported against it
as a line (stretch, lag) and the largest departure from that line (warp). The mean profile and
its spread (standard deviation across recordings, a moving RMS over SIGMA_SMOOTH_S) are taken
per sample of the common time. A recording whose RMS deviation from the mean of the others
exceeds OUTLIER_FACTOR times the median deviation (and OUTLIER_MIN_PCT of the maximum force; both
against the per-sample median of all recordings) is named an outlier and, unless kept, left out
of the mean and the band.

The band (``band_from_spread``): ``mean +- max(k*sigma, floor)`` with ``floor = max(k*noise,
floor_rel*max|mean|)``, noise the sensor noise (robust deviation of the recordings' sample
differences); defaults BAND_K = 3, BAND_FLOOR_REL = 5 %. It is stored as BAND_POINTS points
uniform over the skill's normalised time ``t/T`` (a periodic skill: over one period), each point
the envelope of the band over its two neighbouring intervals, so the device's linear
interpolation between points never narrows it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..errors import ERR_FIT_ARGS, FsError
from .demo import Demo

#: idle lead: the force has left the first LEAD_HEAD_S' median by LEAD_REL of its range (or
#: LEAD_NOISE_SIGMAS noise deviations if larger); LEAD_KEEP_S of the quiet lead stays
LEAD_HEAD_S = 0.05
LEAD_REL = 0.05
LEAD_NOISE_SIGMAS = 6.0
LEAD_KEEP_S = 0.1
#: the rise's start: the force, a moving mean over LEAD_SMOOTH_S, last within LEAD_BACK_SIGMAS
#: noise deviations of the quiet level before it crossed the threshold above
LEAD_SMOOTH_S = 0.02
LEAD_BACK_SIGMAS = 2.0
#: registration: stretch in [1/STRETCH_MAX, STRETCH_MAX], lag within LAG_MAX_REL of the duration;
#: coarse grid of GRID_STRETCH x GRID_LAG candidates, signals at most ALIGN_SAMPLES samples
STRETCH_MAX = 1.6
LAG_MAX_REL = 0.25
GRID_STRETCH = 61
GRID_LAG = 61
ALIGN_SAMPLES = 600
ALIGN_ITERATIONS = 3
#: the non-linear refinement: a piecewise-linear time offset over WARP_KNOTS interior knots added
#: to the affine map, within +-WARP_MAX_REL of the duration of it, by Gauss-Newton (at most
#: WARP_ITERATIONS steps per scale) on the signals smoothed over each of WARP_SCALES_S in turn,
#: the curvature penalised by WARP_SMOOTH of the data term's scale
WARP_KNOTS = 20
WARP_MAX_REL = 0.15
WARP_SCALES_S = (0.2, 0.08, 0.03)
WARP_ITERATIONS = 12
WARP_SMOOTH = 0.01
#: an outlier: RMS deviation from the others' mean above OUTLIER_FACTOR x the median deviation
#: and above OUTLIER_MIN_PCT % of max force (three recordings or more)
OUTLIER_FACTOR = 4.0
OUTLIER_MIN_PCT = 15.0
#: the band: mean +- max(BAND_K*sigma, floor), floor = max(BAND_K*noise, BAND_FLOOR_REL*max|mean|)
BAND_K = 3.0
BAND_FLOOR_REL = 0.05
BAND_POINTS = 64  # every image holds it (the Cortex-M3 at most 64: SKILL_BAND_MAX_POINTS)
#: the spread per sample is smoothed (moving RMS) over this window
SIGMA_SMOOTH_S = 0.05
BAND_POINTS_MAX = 128  # the skill format's cap (skill.BAND_MAX_POINTS)


@dataclass
class Alignment:
    """How one recording sits on the common time ``tau``: recording time ``t = stretch*tau +
    lag_s`` (the line closest to its warp; after its idle lead ``lead_s`` is trimmed), its deviation from the mean of the others (RMS
    and max, % of the mean's max |force|) and whether it is an outlier / used."""

    source: str
    lead_s: float
    duration_s: float
    stretch: float = 1.0
    lag_s: float = 0.0
    #: the largest |time offset| of the warp from that line (s): the non-linear part
    warp_s: float = 0.0
    gain: float = 1.0
    dev_rms_pct: float = 0.0
    dev_max_pct: float = 0.0
    outlier: bool = False
    used: bool = True


@dataclass
class MeanProfile:
    """The mean of several aligned recordings on the dt grid (a Demo: t from 0, force, position
    and y the means), the spread per sample, every recording aligned (rows, outliers included),
    the alignments and the sensor noise estimate."""

    demo: Demo
    sigma_N: np.ndarray
    aligned_N: np.ndarray
    alignments: list[Alignment]
    noise_N: float
    band_lo_N: np.ndarray = field(default_factory=lambda: np.zeros(0))
    band_hi_N: np.ndarray = field(default_factory=lambda: np.zeros(0))


def noise_sigma(f: np.ndarray) -> float:
    """White sensor noise of a sampled force: the robust deviation of its first differences / sqrt 2."""
    d = np.diff(np.asarray(f, dtype=float))
    if d.size < 2:
        return 0.0
    return float(1.4826 * np.median(np.abs(d - np.median(d))) / math.sqrt(2.0))


def trim_lead(demo: Demo, dt_s: float) -> tuple[Demo, float]:
    """The demonstration (on the dt grid) without its idle lead, and the seconds trimmed."""
    f = demo.force_N
    head = f[: max(1, int(round(LEAD_HEAD_S / dt_s)))]
    level = float(np.median(head))
    thr = max(LEAD_REL * float(np.max(f) - np.min(f)), LEAD_NOISE_SIGMAS * noise_sigma(f))
    moved = np.flatnonzero(np.abs(f - level) > thr)
    onset = int(moved[0]) if moved.size else 0
    # back from that crossing to where the rise began (the force, averaged over LEAD_SMOOTH_S,
    # last within LEAD_BACK_SIGMAS noise deviations of the level): a slow rise crosses the
    # threshold well after the contact began, and the mean must keep its whole rise
    width = max(1, int(round(LEAD_SMOOTH_S / dt_s)))
    sm = np.convolve(f[: onset + 1], np.full(width, 1.0 / width), mode="same")
    quiet = np.flatnonzero(np.abs(sm[: onset + 1] - level) <= LEAD_BACK_SIGMAS * noise_sigma(f))
    onset = int(quiet[-1]) if quiet.size else onset
    start = max(0, onset - int(round(LEAD_KEEP_S / dt_s)))
    if start == 0:
        return demo, 0.0
    t = demo.t_s[start:] - demo.t_s[start]
    y = None if demo.y_m is None else demo.y_m[start:]
    out = Demo(t, demo.pos_m[start:], f[start:], demo.source, demo.max_gap_s, list(demo.notes), y)
    return out, float(demo.t_s[start] - demo.t_s[0])


def _warp(t: np.ndarray, f: np.ndarray, tau: np.ndarray, stretch: np.ndarray, lag: np.ndarray) -> np.ndarray:
    """f sampled at t = stretch*tau + lag for every (stretch, lag) pair: shape (pairs, tau)."""
    q = stretch[:, None] * tau[None, :] + lag[:, None]
    out: np.ndarray = np.interp(q.ravel(), t, f).reshape(q.shape)
    return out


def _best(ref: np.ndarray, cand: np.ndarray) -> tuple[int, float]:
    """Index of the candidate row closest to ref after its best gain, and that gain."""
    xx = np.einsum("ij,ij->i", cand, cand)
    xr = cand @ ref
    gain = np.where(xx > 0.0, xr / np.where(xx > 0.0, xx, 1.0), 0.0)
    resid = float(ref @ ref) - gain * xr
    i = int(np.argmin(resid))
    return i, float(gain[i])


def register(
    t: np.ndarray, f: np.ndarray, tau: np.ndarray, ref: np.ndarray, duration_s: float
) -> tuple[float, float, float]:
    """The affine map t = stretch*tau + lag of recording (t, f) that best matches ref(tau) after a
    gain: a coarse grid, then two finer grids around the best. Returns (stretch, lag, gain)."""
    lag_max = LAG_MAX_REL * duration_s
    ls = np.linspace(-math.log(STRETCH_MAX), math.log(STRETCH_MAX), GRID_STRETCH)
    lags = np.linspace(-lag_max, lag_max, GRID_LAG)
    d_ls, d_lag = ls[1] - ls[0], lags[1] - lags[0]
    centre_ls, centre_lag = 0.0, 0.0
    grid_ls, grid_lag = ls, lags
    gain = 1.0
    for _ in range(3):
        s_all = np.exp(np.repeat(grid_ls, grid_lag.size))
        l_all = np.tile(grid_lag, grid_ls.size)
        i, gain = _best(ref, _warp(t, f, tau, s_all, l_all))
        centre_ls, centre_lag = float(np.log(s_all[i])), float(l_all[i])
        grid_ls = centre_ls + np.linspace(-d_ls, d_ls, 11)
        grid_lag = centre_lag + np.linspace(-d_lag, d_lag, 11)
        d_ls, d_lag = d_ls / 5.0, d_lag / 5.0
    return math.exp(centre_ls), centre_lag, gain


def _hat_basis(tau: np.ndarray, knots: np.ndarray) -> np.ndarray:
    """The piecewise-linear hat functions over ``knots`` sampled at tau (held beyond the ends):
    (tau, knots), so a warp with values w at the knots is ``basis @ w``."""
    idx = np.clip(np.searchsorted(knots, tau, side="right") - 1, 0, knots.size - 2)
    frac = np.clip((tau - knots[idx]) / (knots[idx + 1] - knots[idx]), 0.0, 1.0)
    out = np.zeros((tau.size, knots.size))
    rows = np.arange(tau.size)
    out[rows, idx] = 1.0 - frac
    out[rows, idx + 1] += frac
    return out


def _gauss_smooth(x: np.ndarray, sigma_samples: float) -> np.ndarray:
    """x smoothed by a Gaussian of sigma_samples (the ends held): the coarse scales of the
    registration see only the large features, whose basin of attraction is wide."""
    if sigma_samples < 0.5:
        return x
    half = int(math.ceil(3.0 * sigma_samples))
    k = np.exp(-0.5 * (np.arange(-half, half + 1) / sigma_samples) ** 2)
    k /= k.sum()
    out: np.ndarray = np.convolve(np.pad(x, half, mode="edge"), k, mode="valid")
    return out


def refine_warp(
    t: np.ndarray,
    f: np.ndarray,
    tau: np.ndarray,
    ref: np.ndarray,
    affine: tuple[float, float],
    knots: np.ndarray,
    start: np.ndarray | None = None,
) -> np.ndarray:
    """Time offsets at ``knots`` of the piecewise-linear warp t = stretch*tau + lag + offset(tau)
    (held beyond the end knots) that best matches ref after a gain and a bias, so neither the
    operator's amplitude nor the sensor's offset pulls the timing. Gauss-Newton on the squared
    distance plus WARP_SMOOTH times a penalty on the warp's curvature (second differences at the
    knots: a knot on a plateau, where the force says nothing of the timing, follows its
    neighbours; an affine warp costs nothing), coarse to fine over WARP_SCALES_S (both signals
    Gaussian-smoothed: the coarse scales see the large features, whose basin is wide), each step
    halved until the warp increases, stays within WARP_MAX_REL of the duration of the affine map
    and lowers the cost. ``start``: the offsets to start from (default 0, the affine map)."""
    stretch, lag = affine
    w0 = stretch * knots + lag
    w = w0 + (0.0 if start is None else start)
    basis = _hat_basis(tau, knots)
    n_k = knots.size
    d2 = np.diff(np.eye(n_k), 2, axis=0)
    curv = np.zeros((n_k + 2, n_k + 2))  # the warp's values, then the gain and the bias
    curv[:n_k, :n_k] = d2.T @ d2
    dt_rec = float(np.median(np.diff(t))) if t.size > 1 else 1.0
    dt_tau = float(tau[1] - tau[0]) if tau.size > 1 else 1.0
    off_max = WARP_MAX_REL * float(knots[-1] - knots[0])
    slope_lo, slope_hi = 1.0 / STRETCH_MAX**2, STRETCH_MAX**2

    for scale in WARP_SCALES_S:
        fs = _gauss_smooth(f, scale / dt_rec)
        rs = _gauss_smooth(ref, scale / dt_tau)
        dfs = np.gradient(fs, t)
        a, c = _gain_bias(np.interp(basis @ w, t, fs), rs)
        p = np.concatenate([w, [a, c]])
        lam = -1.0
        for _ in range(WARP_ITERATIONS):
            q = basis @ p[:n_k]
            x = np.interp(q, t, fs)
            jac = np.hstack(
                [(p[n_k] * np.interp(q, t, dfs))[:, None] * basis, x[:, None], np.ones((q.size, 1))]
            )
            jtj = jac.T @ jac
            if lam < 0.0:  # the penalty's weight against the data term's scale, fixed per scale
                lam = WARP_SMOOTH * float(np.trace(jtj[:n_k, :n_k])) / n_k + 1e-12
            r = p[n_k] * x + p[n_k + 1] - rs
            # a trace of damping: a flat recording's warp has no gradient, the system no inverse
            hess = jtj + lam * curv + 1e-9 * np.diag(np.diag(jtj) + 1.0)
            step = np.linalg.solve(hess, -(jac.T @ r + lam * curv @ p))
            c0, moved = _warp_cost(p, basis, t, fs, rs, lam * curv), False
            for _ in range(8):
                cand = p + step
                slopes = np.diff(cand[:n_k]) / np.diff(knots)
                ok = bool(np.all((slopes > slope_lo) & (slopes < slope_hi)))
                if (
                    ok
                    and float(np.max(np.abs(cand[:n_k] - w0))) < off_max
                    and _warp_cost(cand, basis, t, fs, rs, lam * curv) < c0
                ):
                    p, moved = cand, True
                    break
                step = 0.5 * step
            if not moved or float(np.max(np.abs(step[:n_k]))) < 1e-4 * dt_tau:
                break
        w = p[:n_k]
    out: np.ndarray = w - w0
    return out


def _warp_cost(
    p: np.ndarray, basis: np.ndarray, t: np.ndarray, f: np.ndarray, ref: np.ndarray, pen: np.ndarray
) -> float:
    """The registration's cost at p (the warp at the knots, the gain, the bias): the squared
    distance of the warped, scaled and offset recording to ref plus the quadratic penalty p'Pp."""
    n_k = basis.shape[1]
    e = p[n_k] * np.interp(basis @ p[:n_k], t, f) + p[n_k + 1] - ref
    return float(e @ e) + float(p @ pen @ p)


def _gain_bias(x: np.ndarray, ref: np.ndarray) -> tuple[float, float]:
    """The gain and bias a, c minimising |a*x + c - ref|^2 (gain 1 for a flat x)."""
    xm, rm = float(np.mean(x)), float(np.mean(ref))
    xc = x - xm
    vx = float(xc @ xc)
    a = float(xc @ (ref - rm)) / vx if vx > 0.0 else 1.0
    return a, rm - a * xm


def _dev(aligned: np.ndarray, used: np.ndarray, f_max: float) -> tuple[np.ndarray, np.ndarray]:
    """Each row's RMS and max deviation from the mean of the other used rows, % of f_max."""
    k = aligned.shape[0]
    rms, mx = np.zeros(k), np.zeros(k)
    tot = aligned[used].sum(axis=0)
    n_used = int(np.count_nonzero(used))
    for i in range(k):
        others = (tot - aligned[i]) / (n_used - 1) if used[i] else tot / n_used
        e = aligned[i] - others
        rms[i] = 100.0 * math.sqrt(float(np.mean(e * e))) / f_max
        mx[i] = 100.0 * float(np.max(np.abs(e))) / f_max
    return rms, mx


def mean_profile(demos: list[Demo], dt_s: float, keep_outliers: bool = False) -> MeanProfile:
    """Align several recordings of one task (each on the dt grid) and take their mean and spread."""
    if len(demos) < 2:
        raise FsError(ERR_FIT_ARGS, "a mean profile needs at least two recordings")
    trimmed, aligns = [], []
    for d in demos:
        dd, lead = trim_lead(d, dt_s)
        trimmed.append(dd)
        aligns.append(Alignment(d.source, lead, float(dd.t_s[-1])))
    durations = np.array([a.duration_s for a in aligns])
    i_ref = _medoid(trimmed, durations, dt_s)
    t_ref = durations[i_ref]
    n_s = min(ALIGN_SAMPLES, int(t_ref / dt_s) + 1)
    tau = np.linspace(0.0, t_ref, n_s)
    ref = np.interp(tau, trimmed[i_ref].t_s, trimmed[i_ref].force_N)
    used = np.ones(len(demos), dtype=bool)
    # the affine map once, against the first reference; every pass refines the warps from there
    maps = np.array([register(d.t_s, d.force_N, tau, ref, t_ref) for d in trimmed])
    knots = np.linspace(0.0, t_ref, WARP_KNOTS + 2)
    offs = np.zeros((len(demos), knots.size))
    for _ in range(ALIGN_ITERATIONS):
        offs = np.stack(
            [
                refine_warp(d.t_s, d.force_N, tau, ref, (m[0], m[1]), knots, o)
                for d, m, o in zip(trimmed, maps, offs, strict=True)
            ]
        )
        rows = _warp_rows(trimmed, tau, maps, knots, offs)
        if len(demos) >= 3 and not keep_outliers:
            used = ~_outliers(rows)
        ref = rows[used].mean(axis=0)
    # the common time on the mean timing of the used recordings: the mean warp W(tau) is the
    # common time, each recording's map is w_i(W^-1(common time)) (every warp increases: so does W)
    w_knots = maps[:, 0:1] * knots[None, :] + maps[:, 1:2] + offs  # each warp at the knots
    fine = np.linspace(-0.5 * t_ref, 1.5 * t_ref, 8 * n_s)
    w_fine = maps[:, 0:1] * fine[None, :] + maps[:, 1:2] + np.stack([np.interp(fine, knots, o) for o in offs])
    w_bar = w_fine[used].mean(axis=0)
    # it starts where the earliest used recording starts (its kept quiet lead included: the mean,
    # as one recording, begins before the contact) and ends at the reference's end
    starts = np.array([np.interp(np.interp(0.0, w, fine), fine, w_bar) for w in w_fine])
    c0 = float(np.min(starts[used]))
    t_end = float(np.interp(t_ref, fine, w_bar))
    n = int(round((t_end - c0) / dt_s)) + 1
    grid = np.arange(n) * dt_s
    tau_of_grid = np.interp(grid + c0, w_bar, fine)
    rows = _warp_rows(trimmed, tau_of_grid, maps, knots, offs)
    # each recording's map against the common time, as a line and what is left of it: the mean
    # of the used maps is the common time itself (mean stretch 1, mean lag 0)
    c_knots = w_knots[used].mean(axis=0)
    coef = np.polyfit(c_knots, w_knots.T, 1)
    stretch, lag = coef[0], coef[1]
    resid = w_knots - (stretch[:, None] * c_knots[None, :] + lag[:, None])
    mean_f = rows[used].mean(axis=0)
    sigma = rows[used].std(axis=0, ddof=1) if np.count_nonzero(used) > 1 else np.zeros(n)
    sigma = _smooth_rms(sigma, max(1, int(round(SIGMA_SMOOTH_S / dt_s))))
    f_max = float(np.max(np.abs(mean_f))) or 1.0
    all_used = np.ones(len(demos), dtype=bool)
    rms, mx = _dev(rows, used if np.count_nonzero(used) > 1 else all_used, f_max)
    flagged = _outliers(rows) if len(demos) >= 3 else np.zeros(len(demos), dtype=bool)
    for i, a in enumerate(aligns):
        a.stretch, a.lag_s, a.gain = float(stretch[i]), float(lag[i]), float(maps[i, 2])
        a.warp_s = float(np.max(np.abs(resid[i])))
        a.dev_rms_pct, a.dev_max_pct = float(rms[i]), float(mx[i])
        a.outlier = bool(flagged[i])
        a.used = bool(used[i])
    pos = _warp_rows(trimmed, tau_of_grid, maps, knots, offs, "pos_m")[used].mean(axis=0)
    y = None
    if all(d.y_m is not None for d in trimmed):
        y = _warp_rows(trimmed, tau_of_grid, maps, knots, offs, "y_m")[used].mean(axis=0)
    src = f"mean of {int(np.count_nonzero(used))} recordings"
    mean_demo = Demo(grid, pos, mean_f, src, max(d.max_gap_s for d in demos), [], y)
    noise = float(np.median([noise_sigma(d.force_N) for d in demos]))
    return MeanProfile(mean_demo, sigma, rows, aligns, noise)


def _smooth_rms(sigma: np.ndarray, width: int) -> np.ndarray:
    """sqrt of the moving mean of sigma^2 over ``width`` samples (the ends held): the spread
    without the sample-to-sample scatter of its estimate."""
    if width < 2 or sigma.size < width:
        return sigma
    v = np.pad(sigma * sigma, (width // 2, width - 1 - width // 2), mode="edge")
    out: np.ndarray = np.sqrt(np.convolve(v, np.full(width, 1.0 / width), mode="valid"))
    return out


def _outliers(rows: np.ndarray) -> np.ndarray:
    """Rows whose RMS distance to the per-sample median of all rows is above OUTLIER_FACTOR x the
    median such distance and above OUTLIER_MIN_PCT % of the median's max |force| (at most all
    but two rows)."""
    med = np.median(rows, axis=0)
    f_max = float(np.max(np.abs(med))) or 1.0
    d = 100.0 * np.sqrt(np.mean((rows - med[None, :]) ** 2, axis=1)) / f_max
    bad = (d > OUTLIER_FACTOR * float(np.median(d))) & (d > OUTLIER_MIN_PCT)
    if rows.shape[0] - np.count_nonzero(bad) < 2:
        bad[:] = False
    out: np.ndarray = bad
    return out


def _medoid(demos: list[Demo], durations: np.ndarray, dt_s: float) -> int:
    """The recording closest to the others after registering each pair (the first reference: an
    outlier never is)."""
    k = len(demos)
    cost = np.zeros(k)
    for i in range(k):
        tau = np.linspace(0.0, durations[i], min(ALIGN_SAMPLES // 2, int(durations[i] / dt_s) + 1))
        ref = np.interp(tau, demos[i].t_s, demos[i].force_N)
        for j in range(k):
            if j != i:
                s, lag, _ = register(demos[j].t_s, demos[j].force_N, tau, ref, float(durations[i]))
                e = np.interp(s * tau + lag, demos[j].t_s, demos[j].force_N) - ref
                cost[i] += float(np.sqrt(np.mean(e * e)))
    return int(np.argmin(cost))


def _warp_rows(
    demos: list[Demo],
    tau: np.ndarray,
    maps: np.ndarray,
    knots: np.ndarray,
    offs: np.ndarray,
    attr: str = "force_N",
) -> np.ndarray:
    """Each recording's column ``attr`` at t = stretch_i*tau + lag_i + offset_i(tau) (the offsets
    0 outside the knots): (recordings, tau)."""
    out = np.empty((len(demos), tau.size))
    for i, d in enumerate(demos):
        q = maps[i, 0] * tau + maps[i, 1] + np.interp(tau, knots, offs[i])
        out[i] = np.interp(q, d.t_s, getattr(d, attr))
    return out


def band_from_spread(
    mean_N: np.ndarray,
    sigma_N: np.ndarray,
    noise_N: float,
    k: float = BAND_K,
    floor_rel: float = BAND_FLOOR_REL,
) -> tuple[np.ndarray, np.ndarray]:
    """The band per sample: mean +- max(k*sigma, max(k*noise, floor_rel*max|mean|))."""
    floor = max(k * noise_N, floor_rel * float(np.max(np.abs(mean_N))))
    half = np.maximum(k * sigma_N, floor)
    return mean_N - half, mean_N + half


def band_points(
    lo_N: np.ndarray, hi_N: np.ndarray, n_points: int = BAND_POINTS
) -> tuple[np.ndarray, np.ndarray]:
    """The band at n_points uniform over the normalised time [0, 1]: each point the lowest lo and
    the highest hi over its neighbouring intervals (so the linear interpolation between points
    encloses the per-sample band)."""
    if not 2 <= n_points <= BAND_POINTS_MAX:
        raise FsError(ERR_FIT_ARGS, f"band points must be in 2..{BAND_POINTS_MAX}: {n_points}")
    n = lo_N.size
    edges = np.rint(np.linspace(0.0, n - 1, n_points)).astype(int)
    lo_p, hi_p = np.empty(n_points), np.empty(n_points)
    for j in range(n_points):
        a = edges[max(j - 1, 0)]
        b = edges[min(j + 1, n_points - 1)] + 1
        lo_p[j] = float(np.min(lo_N[a:b]))
        hi_p[j] = float(np.max(hi_N[a:b]))
    return lo_p, hi_p


def band_at(lo_p: np.ndarray, hi_p: np.ndarray, s: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The stored band's bounds at normalised times s (clamped to [0, 1]), linearly interpolated."""
    x = np.linspace(0.0, 1.0, lo_p.size)
    sc = np.clip(s, 0.0, 1.0)
    return np.interp(sc, x, lo_p), np.interp(sc, x, hi_p)


def pooled_strokes(
    demos: list[Demo], dt_s: float, period_s: float | None = None, keep_outliers: bool = False
) -> tuple[np.ndarray, float, list[Alignment], np.ndarray]:
    """The steady strokes of every recording (each on the dt grid) on one cycle grid: each
    recording's period (autocorrelation and refinement, as for one recording, unless given),
    its strokes resampled to the common period (the median) and rotated in phase onto the
    recording with the most strokes (circular cross-correlation of the mean strokes). Returns
    the used strokes (K, P), the period, the alignments (stretch = the recording's period over
    the common one, lag = the phase shift in s) and which recording each used stroke came from."""
    from .periodic_fit import autocorr_period, refine_period, steady_strokes

    per, sets = [], []
    for d in demos:
        f = d.force_N
        if period_s is None:
            n = f.size
            p_i = autocorr_period(f[n // 4 : n - n // 4], dt_s)
            for _ in range(2):
                start, k, _ = steady_strokes(f, dt_s, p_i)
                p_i = refine_period(f, dt_s, start, k, p_i)
        else:
            p_i = float(period_s)
        start, k, strokes = steady_strokes(f, dt_s, p_i)
        per.append(p_i)
        sets.append((start, strokes))
    period = float(np.median(per)) if period_s is None else float(period_s)
    n_p = int(round(period / dt_s))
    phase = np.arange(n_p) / n_p
    res = []
    for _, st in sets:
        src = np.arange(st.shape[1]) / st.shape[1]
        res.append(np.stack([np.interp(phase, src, row, period=1.0) for row in st]))
    i_ref = int(np.argmax([r.shape[0] for r in res]))
    ref = res[i_ref].mean(axis=0)
    aligns = []
    for i, r in enumerate(res):
        m = r.mean(axis=0)
        xc = np.fft.irfft(np.fft.rfft(ref) * np.conj(np.fft.rfft(m)), n_p)
        shift = int(np.argmax(xc))
        res[i] = np.roll(r, shift, axis=1)
        lag = (shift if shift <= n_p // 2 else shift - n_p) * dt_s
        aligns.append(
            Alignment(demos[i].source, float(sets[i][0]), per[i] * r.shape[0], per[i] / period, -lag)
        )
    means = np.stack([r.mean(axis=0) for r in res])
    f_max = float(np.max(np.abs(means.mean(axis=0)))) or 1.0
    all_used = np.ones(len(demos), dtype=bool)
    rms, mx = _dev(means, all_used, f_max)
    med = float(np.median(rms))
    used = all_used.copy()
    for i, a in enumerate(aligns):
        a.dev_rms_pct, a.dev_max_pct = float(rms[i]), float(mx[i])
        a.outlier = bool(len(demos) >= 3 and rms[i] > OUTLIER_FACTOR * med and rms[i] > OUTLIER_MIN_PCT)
        used[i] = not (a.outlier and not keep_outliers)
        a.used = bool(used[i])
    strokes = np.concatenate([res[i] for i in range(len(res)) if used[i]])
    origin = np.concatenate([np.full(res[i].shape[0], i) for i in range(len(res)) if used[i]])
    return strokes, period, aligns, origin

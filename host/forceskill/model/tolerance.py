"""How well a fitted skill reproduces the recording, and the kernel count that reaches a tolerance.

``sample_error`` is the error a user computes: the fit's rollout (1 ms grid) linearly interpolated
at the recording's own sample times, against the recorded force there, in % of the recording's max
|force|. ``fit_to_tolerance`` finds the smallest kernel count whose error is <= the tolerance: it
doubles N from 2 up to the skill format's kernel cap, then bisects between the last count that
missed and the first that reached it, so the N it returns reaches the tolerance and N - 1 does not.
``diagnose`` names what in a recording a smooth skill cannot follow (a step within one sample, a
single-sample spike, a stuck sensor) for the refusal's hint.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from ..errors import ERR_FIT_ARGS, FsError
from .demo import Demo

#: Without --max-error, `fit` refuses a skill whose max error is above this (% of max force).
DEFAULT_MAX_ERROR_PCT = 10.0
#: A change between two samples above this fraction of max |force| is a step the skill rounds off.
STEP_REL = 0.25
#: A run of identical, non-zero readings at least this long (and >= STUCK_MIN_SAMPLES) is stuck.
STUCK_MIN_S = 0.2
STUCK_MIN_SAMPLES = 10
#: ... provided at most this fraction of the other sample-to-sample changes are exactly zero.
STUCK_REST_REL = 0.05
CHUNK = 1 << 16


@dataclass
class SampleError:
    """Max and RMS error in % of max |force| at the recording's samples; where the max is."""

    max_pct: float
    rms_pct: float
    t_at_max_s: float


def sample_error(demo: Demo, grid_t_s: np.ndarray, f_hat_N: np.ndarray) -> SampleError:
    """Error of a rollout on ``grid_t_s`` (from 0) at the samples of ``demo`` (times from t0).

    Evaluated in chunks of CHUNK samples, so a 10^7-sample recording needs no full-size temporaries."""
    t0 = float(demo.t_s[0])
    f_max = max(float(np.max(demo.force_N)), -float(np.min(demo.force_N)))
    worst, i_worst, sq = -1.0, 0, 0.0
    for i0 in range(0, demo.t_s.size, CHUNK):
        t = demo.t_s[i0 : i0 + CHUNK] - t0
        err = np.abs(demo.force_N[i0 : i0 + CHUNK] - np.interp(t, grid_t_s, f_hat_N))
        k = int(np.argmax(err))
        if err[k] > worst:
            worst, i_worst = float(err[k]), i0 + k
        sq += float(np.dot(err, err))
    return SampleError(
        max_pct=100.0 * worst / f_max,
        rms_pct=100.0 * math.sqrt(sq / demo.t_s.size) / f_max,
        t_at_max_s=float(demo.t_s[i_worst]) - t0,
    )


FitFn = Callable[[int], tuple[object, np.ndarray, np.ndarray]]


def fit_to_tolerance(
    fit_n: FitFn, demo: Demo, max_error_pct: float, n_max: int, n_min: int = 2
) -> tuple[int, object, SampleError, list[tuple[int, float]]]:
    """Smallest N in n_min..n_max with ``sample_error`` <= ``max_error_pct`` (see the module comment).

    ``fit_n(N)`` returns (result, grid times, rollout). Returns (N, result, error, tried), N = 0
    when none reaches it: then result/error are those of the best N tried. ``tried`` lists (N, max %).
    """
    tried: list[tuple[int, float]] = []
    cache: dict[int, tuple[object, SampleError]] = {}

    def at(n: int) -> tuple[object, SampleError]:
        if n not in cache:
            try:
                res, t, f_hat = fit_n(n)
            except FsError as e:
                if n == n_min or e.code != ERR_FIT_ARGS:
                    raise
                # more kernels than this recording holds (centres collide): counts as a miss
                cache[n] = (None, SampleError(math.inf, math.inf, 0.0))
                return cache[n]
            cache[n] = (res, sample_error(demo, t, f_hat))
            tried.append((n, cache[n][1].max_pct))
            _forget()
        return cache[n]

    def _forget() -> None:
        """Drop the results (grid-sized arrays) no answer can be: only the smallest N that passes
        keeps its own, or while none passes the best N so far (memory flat over the search: one
        result besides the fit being made)."""
        ok = [k for k in cache if cache[k][1].max_pct <= max_error_pct]
        keep = {min(ok)} if ok else {min(cache, key=lambda k: cache[k][1].max_pct)}
        for k in cache:
            if k not in keep and cache[k][0] is not None:
                cache[k] = (None, cache[k][1])

    lo = n_min - 1  # largest N known to miss (n_min - 1: none yet)
    n = n_min
    while True:
        if at(n)[1].max_pct <= max_error_pct:
            hi = n
            break
        lo = n
        if n >= n_max:
            best = min(cache, key=lambda k: cache[k][1].max_pct)
            return 0, cache[best][0], cache[best][1], tried
        n = min(2 * n, n_max)
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if at(mid)[1].max_pct <= max_error_pct:
            hi = mid
        else:
            lo = mid
    return hi, cache[hi][0], cache[hi][1], tried


def diagnose(demo: Demo) -> str | None:
    """The first feature a smooth skill cannot follow, as a phrase with its time; None if none.

    One float array of the steps and a few boolean masks (no other full-size copies: it runs on
    10^7-sample recordings too)."""
    f = demo.force_N
    t0 = float(demo.t_s[0])

    def t(i: int) -> float:
        return float(demo.t_s[i]) - t0

    f_max = max(float(np.max(f)), -float(np.min(f))) if f.size else 0.0
    if f.size < 3 or f_max <= 0.0:
        return None
    thresh = STEP_REL * f_max
    a = np.diff(f)
    down = np.signbit(a)
    zero = a == 0.0
    n_zero = int(np.count_nonzero(zero))
    np.abs(a, out=a)  # a = |step| from here on
    large = a > thresh
    # a spike: up then straight back down (both steps large, opposite signs)
    spike = np.flatnonzero(large[:-1] & large[1:] & (down[:-1] != down[1:]))
    if spike.size:
        i = int(spike[0]) + 1
        return (
            f"a single-sample spike to {f[i]:.4g} N at t = {t(i):.4g} s (between {f[i - 1]:.4g} and "
            f"{f[i + 1]:.4g} N): a sensor glitch; remove it from the recording"
        )
    # stuck: identical non-zero readings for a while, in a recording whose readings otherwise
    # change from sample to sample (a noiseless simulated hold is not a stuck sensor)
    if n_zero:
        same = np.concatenate(([False], zero)) & (f != 0.0)
        # runs of `same`: from the sample before its first true to one past its last
        starts = np.flatnonzero(same & ~np.concatenate(([False], same[:-1]))) - 1
        ends = np.flatnonzero(same & ~np.concatenate((same[1:], [False]))) + 1
        del same
        for s, e in zip(starts.tolist(), ends.tolist(), strict=False):
            if e - s >= STUCK_MIN_SAMPLES and t(e - 1) - t(s) >= STUCK_MIN_S:
                rest = n_zero - (e - s - 1)
                if rest <= STUCK_REST_REL * a.size:
                    return (
                        f"the force reads exactly {f[s]:.6g} N for {t(e - 1) - t(s):.3g} s from "
                        f"t = {t(s):.4g} s: a stuck sensor; record again or cut that part"
                    )
    big = np.flatnonzero(large)
    if big.size:
        i = int(big[np.argmax(a[big])])
        step = float(f[i + 1] - f[i])
        return (
            f"a force step of {step:+.4g} N within one sample ({(t(i + 1) - t(i)) * 1e3:.3g} ms) at "
            f"t = {t(i):.4g} s: steps faster than the sample rate cannot be learned; record faster"
        )
    return None

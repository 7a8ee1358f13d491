#!/usr/bin/env python3
"""Learning from several demonstrations: the figures of docs/math.md section 7.

    .venv/bin/python bench/accuracy/multi_demo.py [--sets N]

Synthetic sets with a known truth (``synthetic.pressing_set``: six demonstrations of one pressing
task through the two-layer object, each with its own idle lead, speed (stretch +-12 % and a
non-linear speed profile of up to 0.5 s), amplitude (uniform within +-5 %), bias (0.05 N) and
sensor noise (0.03 N)). Per set it prints:

- fidelity: the max error of a skill's rollout against the intended profile, in % of its maximum,
  after the best affine time alignment (stretch and lag searched on a grid, the max error
  minimised), for the skill fitted from each recording alone (as ``fit`` does with one) and for
  the skill of their mean (``fit`` with all six); required: the median of the mean skills' figures at most
  half the median single-recording figure;
- the amplitude of the mean: the mean over the six of each recording's final plateau above its
  quiet start (medians of its last second and first 50 ms) over the truth's final level, less 1,
  in %: what no alignment takes out of the mean skill (its plateaus carry it);
- band coverage: each recording held out in turn, the band of the other five (the defaults:
  mean +- max(3 sigma, 5 % of max), 64 points) against the held-out recording aligned onto the
  skill's time: the fraction of its samples above 10 % of the maximum force inside the band;
  required: at least 90 % of all held-out samples.
"""

from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "host"))

from forceskill.model import dmp, multi, synthetic
from forceskill.model.demo import Demo, resample
from forceskill.model.fit import fit
from forceskill.model.skill import Skill

DT = 0.001
K = 100.0


def fidelity_pct(t: np.ndarray, f: np.ndarray, truth: Demo) -> float:
    """min over (stretch, lag) of max |f(stretch*tau + lag) - truth(tau)|, % of max truth."""
    tau = np.linspace(0.0, float(truth.t_s[-1]), 800)
    ref = np.interp(tau, truth.t_s, truth.force_N)
    s0, l0, _ = multi.register(t, f, tau, ref, float(truth.t_s[-1]))
    best = math.inf
    span_s, span_l = 0.04, 0.1
    for _ in range(3):  # refine around the L2 optimum on the max error itself
        ss = np.exp(np.linspace(math.log(s0) - span_s, math.log(s0) + span_s, 41))
        ll = np.linspace(l0 - span_l, l0 + span_l, 41)
        s_all, l_all = np.repeat(ss, ll.size), np.tile(ll, ss.size)
        q = s_all[:, None] * tau[None, :] + l_all[:, None]
        e = np.max(np.abs(np.interp(q.ravel(), t, f).reshape(q.shape) - ref[None, :]), axis=1)
        i = int(np.argmin(e))
        best, s0, l0 = float(e[i]), float(s_all[i]), float(l_all[i])
        span_s, span_l = span_s / 8.0, span_l / 8.0
    return 100.0 * best / float(np.max(np.abs(truth.force_N)))


def amplitude_pct(grids: list[Demo], truth: Demo) -> float:
    """The mean recording's amplitude against the truth, less 1, in %: each recording's final
    plateau above its quiet start (medians: the noise and the bias cancel) over the truth's."""
    n_end, n_start = int(round(1.0 / DT)), int(round(0.05 / DT))
    amps = [
        (float(np.median(g.force_N[-n_end:])) - float(np.median(g.force_N[:n_start])))
        / float(truth.force_N[-1])
        for g in grids
    ]
    return 100.0 * (float(np.mean(amps)) - 1.0)


def skill_of(d: Demo) -> Skill:
    return fit(d, K, n_kernels=50).skill


def coverage(held: Demo, others: list[Demo]) -> tuple[int, int]:
    """The held-out recording's samples above 10 % of max inside the others' band, and their
    count (the held-out recording aligned onto the skill's time as fit aligns one: affine, then
    the piecewise-linear refinement)."""
    mp = multi.mean_profile(others, DT)
    sk = skill_of(mp.demo)
    lo, hi = multi.band_from_spread(mp.demo.force_N, mp.sigma_N, mp.noise_N)
    sk.band_lo_N, sk.band_hi_N = multi.band_points(lo, hi)
    h, _ = multi.trim_lead(held, DT)
    t_m = mp.demo.t_s
    tau = np.linspace(0.0, float(t_m[-1]), 600)
    ref = np.interp(tau, t_m, mp.demo.force_N)
    s, lag, _ = multi.register(h.t_s, h.force_N, tau, ref, float(t_m[-1]))
    knots = np.linspace(0.0, float(t_m[-1]), multi.WARP_KNOTS + 2)
    off = multi.refine_warp(h.t_s, h.force_N, tau, ref, (s, lag), knots)
    f = np.interp(s * t_m + lag + np.interp(t_m, knots, off), h.t_s, h.force_N)  # on the skill's time
    b_lo, b_hi = sk.band_at(t_m)
    mask = np.abs(f) > 0.1 * float(np.max(np.abs(f)))
    inside = (f >= b_lo) & (f <= b_hi)
    return int(np.count_nonzero(inside & mask)), int(np.count_nonzero(mask))


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--sets", type=int, default=4)
    args = ap.parse_args()
    print(
        "| set (seed) | single recording: fidelity min..max (median) [%] | mean of 6 [%] | mean/median | "
        "amplitude of the mean [%] | held-out band coverage min..median [%] |"
    )
    print("|---:|---|---:|---:|---:|---|")
    singles_all, means, covs_all, ratios = [], [], [], []
    cov_in, cov_n = 0, 0
    for seed in range(1, args.sets + 1):
        truth, demos = synthetic.pressing_set(seed=seed, n=6)
        grids = [resample(d, DT) for d in demos]
        singles = []
        for g in grids:
            t, f = dmp.rollout(skill_of(g))
            singles.append(fidelity_pct(t, f, truth))
        mp = multi.mean_profile(grids, DT)
        t, f = dmp.rollout(skill_of(mp.demo))
        mean_fid = fidelity_pct(t, f, truth)
        cov = [coverage(grids[i], grids[:i] + grids[i + 1 :]) for i in range(len(grids))]
        covs = [100.0 * a / b for a, b in cov]
        cov_in += sum(a for a, _ in cov)
        cov_n += sum(b for _, b in cov)
        med = float(np.median(singles))
        amp = amplitude_pct(grids, truth)
        print(
            f"| {seed} | {min(singles):.2f}..{max(singles):.2f} ({med:.2f}) | {mean_fid:.2f} | "
            f"{mean_fid / med:.2f} | {amp:+.2f} | {min(covs):.1f}..{float(np.median(covs)):.1f} |",
            flush=True,
        )
        singles_all += singles
        means.append(mean_fid)
        ratios.append(mean_fid / med)
        covs_all += covs
    med_all = float(np.median(singles_all))
    print()
    print(
        f"fidelity: single recordings {min(singles_all):.2f} to {max(singles_all):.2f} % (median {med_all:.2f} %), "
        f"mean of six {min(means):.2f} to {max(means):.2f} % (median {float(np.median(means)):.2f} %): "
        f"{float(np.median(means)) / med_all:.2f} of the single median (required <= 0.5)"
    )
    print(f"per set, the mean's figure over the single median: {', '.join(f'{r:.2f}' for r in ratios)}")
    total = 100.0 * cov_in / cov_n
    print(
        f"held-out band coverage: {total:.1f} % of all held-out samples above 10 % of max (required >= 90); per "
        f"recording {min(covs_all):.1f} to {max(covs_all):.1f} % (median {float(np.median(covs_all)):.1f} %)"
    )
    ok = float(np.median(means)) <= 0.5 * med_all and total >= 90.0
    print("PASS" if ok else "FAIL")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())

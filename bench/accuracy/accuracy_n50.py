#!/usr/bin/env python3
"""Approximation error of the default fit at N = 50 over operator seeds: the figures of docs/math.md.

    .venv/bin/python bench/accuracy/accuracy_n50.py [--layout GAIN,CLIP,BIN_S[,MAX_PER_TICK] ...]

Synthetic profiles shaped like the paper's (forceskill.model.synthetic: pressing two-layer 100/180 N/m;
engraving 6-10 N levels), seeds 0-11, durations 8, 9, 12 and 17 s, with and without 0.02 N sensor
noise, fitted at N = 50 (ridge) with three kernel layouts: centres uniform in time with
sigma_i = w*(c_{i+1} - c_i) (the layout before, w = 0.65 and 1.0), and the default (centres denser
where the force bends, ``fit.kernel_times``). Table 1: median / max of the max error (% of max
force, against the recording: with noise it includes the noise), the most kernels evaluated per
tick (cutoff 23 in the float core, 16 in fixed point and on the Cortex-M images) and the largest
1/sigma (the fixed-point format holds up to 4096). Table 2, the noisy profiles with the default fit:
the error against the recording, against the noise-free profile the noise was added to, and the
noise alone (max |noise| / max |recording|). ``--layout`` replaces the rows by curvature-density
rows with other constants (``fit.DENSITY_GAIN``, ``DENSITY_CLIP``, ``DENSITY_BIN_S`` and
optionally ``KERNELS_PER_TICK_MAX``; width 0.65).
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "host"))

from forceskill.model import dmp, synthetic
from forceskill.model import fit as fitmod
from forceskill.model.demo import Demo

DURATIONS = (8.0, 9.0, 12.0, 17.0)
KINDS = ("pressing", "engraving", "pressing+noise", "engraving+noise")
NOISE_N = 0.02
DEFAULT = (
    fitmod.DENSITY_GAIN,
    fitmod.DENSITY_CLIP,
    fitmod.DENSITY_BIN_S,
    fitmod.WIDTH_FACTOR,
    fitmod.KERNELS_PER_TICK_MAX,
)
#: (label, density gain, clip, bin, width factor, most kernels per tick)
LAYOUTS = [
    ("uniform, 0.65 (before)", 0.0, *DEFAULT[1:3], 0.65, DEFAULT[4]),
    ("uniform, 1.0", 0.0, *DEFAULT[1:3], 1.0, DEFAULT[4]),
    ("curvature density, 0.65 (default)", *DEFAULT),
]


def make(kind: str, seed: int, T: float, noise_N: float) -> Demo:
    if kind.startswith("pressing"):
        return synthetic.pressing(seed, T, noise_N=noise_N)
    return synthetic.engraving(seed, T, 100.0, 6.0 + seed % 5, noise_N=noise_N)


def cell(v: list[float]) -> str:
    return f"{np.median(v):.2f} / {np.max(v):.2f}"


def main() -> int:
    args = sys.argv[1:]
    if args:
        LAYOUTS.clear()
    while args:
        vals = args[1].split(",") if len(args) >= 2 else []
        if args[0] != "--layout" or len(vals) not in (3, 4):
            print("usage: accuracy_n50.py [--layout GAIN,CLIP,BIN_S[,MAX_PER_TICK] ...]", file=sys.stderr)
            return 2
        gain, clip, bin_s = (float(x) for x in vals[:3])
        cap = int(vals[3]) if len(vals) == 4 else fitmod.KERNELS_PER_TICK_MAX
        LAYOUTS.append(
            (
                f"density gain {gain:g}, clip {clip:g}, bin {bin_s:g} s, cap {cap}",
                gain,
                clip,
                bin_s,
                0.65,
                cap,
            )
        )
        args = args[2:]
    cases = [(k, T, s) for s in range(12) for T in DURATIONS for k in KINDS]
    print(
        "| layout | "
        + " | ".join(f"{k} {T:g} s" for k in KINDS for T in DURATIONS)
        + " | kernels per tick (23 / 16) | max 1/sigma |"
    )
    print("|---|" + "---:|" * (len(KINDS) * len(DURATIONS)) + "---:|---:|")
    noisy: dict[float, list[tuple[float, float, float]]] = {}
    for label, gain, clip, bin_s, wf in LAYOUTS:
        fitmod.DENSITY_GAIN, fitmod.DENSITY_CLIP, fitmod.DENSITY_BIN_S, fitmod.WIDTH_FACTOR = (
            gain,
            clip,
            bin_s,
            wf,
        )
        errs: dict[tuple[str, float], list[float]] = {}
        act = [0, 0]
        inv_sigma = 0.0
        for kind, T, seed in cases:
            noise = NOISE_N if kind.endswith("+noise") else 0.0
            r = fitmod.fit(make(kind, seed, T, noise), 200.0)
            errs.setdefault((kind, T), []).append(r.err_max_pct)
            sk = r.skill
            u, _ = dmp.phase_loop(sk.alpha, sk.beta, sk.dt_s / sk.tau_s, dmp.default_steps(sk))
            e = dmp.kernel_exponents(u, sk.centres, sk.widths)
            act = [
                max(act[0], int((e <= dmp.KERNEL_CUTOFF_EXP).sum(axis=1).max())),
                max(act[1], int((e <= 16.0).sum(axis=1).max())),
            ]
            inv_sigma = max(inv_sigma, float(np.max(1.0 / sk.widths)))
            if noise > 0.0 and (gain, clip, bin_s, wf, cap) == DEFAULT:
                clean = make(kind, seed, T, 0.0).force_N
                f_max = float(np.max(np.abs(r.target_N)))
                noisy.setdefault(T, []).append(
                    (
                        r.err_max_pct,
                        100.0 * float(np.max(np.abs(clean - r.f_hat_N))) / f_max,
                        100.0 * float(np.max(np.abs(r.target_N - clean))) / f_max,
                    )
                )
        cells = " | ".join(cell(errs[(k, T)]) for k in KINDS for T in DURATIONS)
        print(f"| {label} | {cells} | {act[0]} / {act[1]} | {inv_sigma:.0f} |")
    fitmod.DENSITY_GAIN, fitmod.DENSITY_CLIP, fitmod.DENSITY_BIN_S, fitmod.WIDTH_FACTOR = DEFAULT[:4]
    fitmod.KERNELS_PER_TICK_MAX = DEFAULT[4]
    if not noisy:
        return 0
    print()
    print(
        "| noisy profiles (pressing and engraving, 24 per duration), default fit | "
        + " | ".join(f"{T:g} s" for T in DURATIONS)
        + " |"
    )
    print("|---|" + "---:|" * len(DURATIONS))
    for j, what in enumerate(("against the recording", "against the noise-free profile", "the noise alone")):
        print(f"| {what} | " + " | ".join(cell([x[j] for x in noisy[T]]) for T in DURATIONS) + " |")
    return 0


if __name__ == "__main__":
    sys.exit(main())

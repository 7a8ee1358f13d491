#!/usr/bin/env python3
"""Write a skill whose default layout has the most kernels per tick, for bench/qemu_tick.sh --skill.

    .venv/bin/python bench/accuracy/dense_skill.py OUT.skill
    bench/qemu_tick.sh cortex-m4f --skill OUT.skill --exec-s 7

The 8 s synthetic engraving of seed 2 (levels up to 8 N, 100 N/m, gains for the HIL's 10 kg
objects, release at the end), fitted at N = 50 by the default fit: its release is where the
kernels crowd (12 within the Cortex-M cutoff 16 from 5.7 s on, the most of the accuracy bench's
profiles). Prints the kernels per tick, where, and the fit's max error.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "host"))

from forceskill.model import dmp, synthetic
from forceskill.model.fit import DEVICE_CUTOFF_EXP, fit
from forceskill.model.params import gains_for_object


def main() -> int:
    if len(sys.argv) != 2:
        print("usage: dense_skill.py OUT.skill", file=sys.stderr)
        return 2
    d = synthetic.engraving(2, 8.0, 100.0, 8.0)
    r = fit(d, 100.0, gains=gains_for_object(100.0, 10.0), end_policy="release")
    sk = r.skill
    u, _ = dmp.phase_loop(sk.alpha, sk.beta, sk.dt_s / sk.tau_s, dmp.default_steps(sk))
    per_tick = (dmp.kernel_exponents(u, sk.centres, sk.widths) <= DEVICE_CUTOFF_EXP).sum(axis=1)
    Path(sys.argv[1]).write_bytes(sk.to_bytes())
    first = int(np.argmax(per_tick == per_tick.max()))
    print(
        f"dense_skill N={sk.n_kernels} kernels_per_tick={int(per_tick.max())} from_t={first * sk.dt_s:.3f}s "
        f"err_max={r.err_max_pct:.2f}% -> {sys.argv[1]}"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())

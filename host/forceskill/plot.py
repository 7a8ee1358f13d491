"""Figures like the paper's Fig. 5a: demonstrated vs learned force, approximation error, position."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .model.fit import FitResult
from .outputs import Outputs, save_figure


def fit_figure(res: FitResult, path: str | Path, title: str = "", outs: Outputs | None = None) -> None:
    """Write a PNG (into ``outs``, committed with the other outputs, or on its own): force (demonstrated dashed black, learned green), error in % of
    max force, and the demonstrated position with the object surface."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    t = res.t_s
    f_max = float(np.max(np.abs(res.target_N)))
    fig, ax = plt.subplots(3, 1, figsize=(7.0, 7.0), sharex=True)
    ax[0].plot(t, res.target_N, "k--", lw=1.2, label="demonstrated")
    ax[0].plot(t, res.f_hat_N, "g-", lw=1.0, label="learned")
    ax[0].set_ylabel("force [N]")
    ax[0].legend(loc="best", fontsize=8)
    ax[0].set_title(
        title
        or f"{res.method}, N = {res.skill.n_kernels}: max error {res.err_max_pct:.2f} %, "
        f"RMS {res.err_rms_pct:.2f} %"
    )
    ax[1].plot(t, 100.0 * (res.target_N - res.f_hat_N) / f_max, "r-", lw=0.8)
    ax[1].set_ylabel("error [% of max]")
    if res.pos_m.size == t.size:
        ax[2].plot(t, 1e3 * res.pos_m, "b-", lw=1.0, label="position")
        ax[2].axhline(1e3 * res.skill.surface_m, color="0.5", ls=":", lw=0.8, label="surface")
        ax[2].legend(loc="best", fontsize=8)
    ax[2].set_ylabel("x [mm]")
    ax[2].set_xlabel("t [s]")
    for a in ax:
        a.grid(True, lw=0.3)
    fig.tight_layout()
    try:
        if outs is not None:
            save_figure(outs, fig, path, dpi=110)
        else:
            with Outputs() as own:
                save_figure(own, fig, path, dpi=110)
                own.commit()
    finally:
        plt.close(fig)

"""Figures like the paper's Fig. 5a: demonstrated vs learned force, approximation error, position."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from .model.fit import FitResult
from .outputs import Outputs, write_figure

if TYPE_CHECKING:
    from .model.multi import MeanProfile
    from .model.periodic_fit import PeriodicFit


def fit_figure(res: FitResult, path: str | Path, title: str = "", outs: Outputs | None = None) -> None:
    """Write a PNG (into ``outs``, committed with the other outputs, or on its own): force (demonstrated dashed black, learned green), error in % of
    max force, and the demonstrated position with the object surface; a skill with a y DMP adds
    the y path (demonstrated dashed black, learned green)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    t = res.t_s
    f_max = float(np.max(np.abs(res.target_N)))
    has_y = res.y_hat_m.size == t.size
    fig, ax = plt.subplots(4 if has_y else 3, 1, figsize=(7.0, 9.0 if has_y else 7.0), sharex=True)
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
    if has_y:
        ax[3].plot(t, 1e3 * res.y_target_m, "k--", lw=1.2, label="demonstrated")
        ax[3].plot(t, 1e3 * res.y_hat_m, "g-", lw=1.0, label="learned")
        ax[3].set_ylabel("y path [mm]")
        ax[3].set_title(f"y: max error {res.y_err_max_mm:.3f} mm, RMS {res.y_err_rms_mm:.3f} mm", fontsize=9)
        ax[3].legend(loc="best", fontsize=8)
    ax[-1].set_xlabel("t [s]")
    for a in ax:
        a.grid(True, lw=0.3)
    write_figure(fig, path, outs=outs)


def multi_figure(
    res: FitResult,
    multi: MeanProfile,
    band: tuple[np.ndarray, np.ndarray] | None,
    path: str | Path,
    title: str = "",
    outs: Outputs | None = None,
) -> None:
    """Write a PNG of a fit from several recordings: every recording on the common time (thin
    grey; an outlier left out dotted red), their mean (dashed black), the demonstrated band
    (shaded, with the stored points' envelope as thin green lines) and the learned force (green);
    below, the spread (1 sigma) and the band's half-width, then the learned force's error
    against the mean in % of max force."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    t = multi.demo.t_s
    mean = multi.demo.force_N
    f_max = float(np.max(np.abs(mean))) or 1.0
    fig, ax = plt.subplots(3, 1, figsize=(7.5, 8.0), sharex=True, gridspec_kw={"height_ratios": [3, 1, 1]})
    first = True
    for a, row in zip(multi.alignments, multi.aligned_N, strict=True):
        if a.used:
            ax[0].plot(t, row, "-", color="0.6", lw=0.6, label="recordings (aligned)" if first else None)
            first = False
        else:
            ax[0].plot(t, row, ":", color="r", lw=0.8, label=f"outlier left out: {a.source}")
    if band is not None:
        ax[0].fill_between(t, band[0], band[1], color="tab:green", alpha=0.18, lw=0, label="band")
        sk = res.skill
        if sk.band_lo_N is not None and sk.band_hi_N is not None:
            tp = np.linspace(0.0, sk.duration_s, sk.band_lo_N.size)
            ax[0].plot(tp, sk.band_lo_N, "-", color="tab:green", lw=0.5)
            ax[0].plot(tp, sk.band_hi_N, "-", color="tab:green", lw=0.5)
    ax[0].plot(t, mean, "k--", lw=1.2, label="mean")
    ax[0].plot(res.t_s, res.f_hat_N, "g-", lw=1.0, label="learned")
    ax[0].set_ylabel("force [N]")
    ax[0].legend(loc="best", fontsize=7)
    ax[0].set_title(title, fontsize=9)
    ax[1].plot(t, multi.sigma_N, "b-", lw=0.8, label="spread (1 sigma)")
    if band is not None:
        ax[1].plot(t, 0.5 * (band[1] - band[0]), "g-", lw=0.8, label="band half-width")
    ax[1].set_ylabel("N")
    ax[1].legend(loc="best", fontsize=7)
    n = min(res.f_hat_N.size, mean.size)
    ax[2].plot(t[:n], 100.0 * (mean[:n] - res.f_hat_N[:n]) / f_max, "r-", lw=0.8)
    ax[2].set_ylabel("error vs mean [% of max]")
    ax[2].set_xlabel("t [s] (common time)")
    for a2 in ax:
        a2.grid(True, lw=0.3)
    write_figure(fig, path, outs=outs)


def periodic_figure(
    res: PeriodicFit,
    path: str | Path,
    outs: Outputs | None = None,
    band: tuple[np.ndarray, np.ndarray] | None = None,
) -> None:
    """Write a PNG of a periodic fit: over one period, every steady stroke of the demonstration
    (thin grey), their mean (dashed black), the band when given (shaded) and the learned cycle
    (green); below, the learned
    cycle's error against the mean stroke (green) and against each stroke (grey), in % of max
    force."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    p = res.mean_stroke_N.size
    t = np.arange(p) * res.skill.dt_s
    cycle = res.cycle_N[:p]
    f_max = res.f_max_N
    fig, ax = plt.subplots(2, 1, figsize=(7.0, 6.0), sharex=True)
    for j, stroke in enumerate(res.strokes_N):
        ax[0].plot(t, stroke, "-", color="0.65", lw=0.6, label="demonstrated strokes" if j == 0 else None)
    if band is not None:
        ax[0].fill_between(t, band[0], band[1], color="tab:green", alpha=0.18, lw=0, label="band")
    ax[0].plot(t, res.mean_stroke_N, "k--", lw=1.2, label="mean stroke")
    ax[0].plot(t, cycle, "g-", lw=1.1, label="learned cycle")
    ax[0].set_ylabel("force [N]")
    ax[0].legend(loc="best", fontsize=8)
    ax[0].set_title(
        f"periodic, {res.method}, N = {res.skill.n_kernels}: period {res.period_s:.4g} s, "
        f"{res.strokes_N.shape[0]} strokes; vs mean stroke max {res.err_mean_max_pct:.2f} %",
        fontsize=9,
    )
    for stroke in res.strokes_N:
        ax[1].plot(t, 100.0 * (stroke - cycle) / f_max, "-", color="0.65", lw=0.5)
    ax[1].plot(t, 100.0 * (res.mean_stroke_N - cycle) / f_max, "g-", lw=1.0)
    ax[1].set_ylabel("error [% of max]")
    ax[1].set_xlabel("t within the period [s]")
    for a in ax:
        a.grid(True, lw=0.3)
    write_figure(fig, path, outs=outs)


def outside_spans(t: np.ndarray, outside: np.ndarray) -> np.ndarray:
    """The pieces of a run outside the band: (pieces, 2) start and end times, each piece from
    its first row outside to one row past its last (a row stands for its tick)."""
    if t.size == 0:
        return np.zeros((0, 2))
    dt = float(t[1] - t[0]) if t.size > 1 else 1e-3
    edges = np.diff(np.concatenate([[0], (np.asarray(outside) > 0.5).astype(np.int8), [0]]))
    first, past = np.flatnonzero(edges == 1), np.flatnonzero(edges == -1)
    return np.column_stack([t[first], t[past - 1] + dt])


def run_figure(
    cols: dict[str, np.ndarray],
    path: str | Path,
    title: str = "",
    band: tuple[np.ndarray, np.ndarray] | None = None,
    fault_t: float | None = None,
    outs: Outputs | None = None,
) -> None:
    """Write a PNG of a run's telemetry: the contact force (blue) and the reference f_hat (dashed
    black), the band when given (shaded green, on the run's rows), every piece the device reported
    outside it (the CSV's band_out, shaded red over the whole height) and the fault's time (a red
    line); below, the position x."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    t = cols["t"]
    fig, ax = plt.subplots(2, 1, figsize=(8.0, 6.0), sharex=True, gridspec_kw={"height_ratios": [3, 1]})
    if band is not None:
        ax[0].fill_between(t, band[0], band[1], color="tab:green", alpha=0.18, lw=0, label="band")
    if "band_out" in cols:
        spans = outside_spans(t, cols["band_out"])
        if spans.size:
            # one collection for every piece: a chattering excursion is thousands of them
            ax[0].broken_barh(
                list(zip(spans[:, 0], spans[:, 1] - spans[:, 0], strict=True)),
                (0.0, 1.0),
                transform=ax[0].get_xaxis_transform(),
                color="tab:red",
                alpha=0.2,
                lw=0,
                label="outside the band",
            )
    ax[0].plot(t, cols["f_contact"], "-", color="tab:blue", lw=1.0, label="contact force")
    ax[0].plot(t, cols["f_hat"], "k--", lw=0.9, label="reference f_hat")
    if fault_t is not None:
        for a in ax:
            a.axvline(fault_t, color="tab:red", lw=1.0)
        ax[0].text(
            fault_t,
            0.98,
            " fault",
            color="tab:red",
            fontsize=8,
            va="top",
            transform=ax[0].get_xaxis_transform(),
        )
    ax[0].set_ylabel("force [N]")
    ax[0].legend(loc="best", fontsize=8)
    ax[0].set_title(title, fontsize=9)
    ax[1].plot(t, 1e3 * cols["x"], "b-", lw=0.8)
    ax[1].set_ylabel("x [mm]")
    ax[1].set_xlabel("t [s] (from the start of the execution)")
    for a in ax:
        a.grid(True, lw=0.3)
    write_figure(fig, path, outs=outs)

"""forceskill fit: learn a force skill from one demonstration (CSV, CAN log, ROS 2 bag)."""

from __future__ import annotations

import argparse
import math
from pathlib import Path
from typing import Any

from ..errors import FsError
from ..wire import TICK_S
from ._args import add_force_limit, float_arg, int_arg

#: the band's defaults (forceskill.model.multi: BAND_K, BAND_FLOOR_REL, BAND_POINTS)
BAND_K = 3.0
BAND_FLOOR_REL = 0.05
BAND_POINTS = 64  # every image holds it (the Cortex-M3 at most 64: SKILL_BAND_MAX_POINTS)
#: --contact-wait's time constant when only the threshold is given (s)
CONTACT_TAU_DEFAULT_S = 0.05


#: The recording's length the default N = 50 covers; a longer one may take proportionally more.
DEFAULT_N_SPAN_S = 10.0


def contact_wait_arg(text: str) -> tuple[int, int]:
    """--contact-wait THRESHOLD_N[,TAU_S] as the image's (threshold in 0.01 N, tau in ms):
    threshold in (0, 655.35] N, tau in [0, 10] s (default CONTACT_TAU_DEFAULT_S)."""
    from ..model.skill import CONTACT_TAU_MS_MAX

    parts = text.split(",")
    try:
        thr = float(parts[0])
        tau = float(parts[1]) if len(parts) == 2 else CONTACT_TAU_DEFAULT_S
    except ValueError:
        thr, tau = 0.0, -1.0
    if not (math.isfinite(thr) and math.isfinite(tau)):
        thr, tau = 0.0, -1.0
    cn, ms = round(thr * 100.0), round(tau * 1000.0)
    if len(parts) > 2 or not (1 <= cn <= 0xFFFF) or not (0 <= ms <= CONTACT_TAU_MS_MAX):
        raise argparse.ArgumentTypeError(
            f"expected THRESHOLD_N[,TAU_S] with a threshold in (0, 655.35] N and a time constant "
            f"in [0, {CONTACT_TAU_MS_MAX // 1000}] s: {text!r}"
        )
    return int(cn), int(ms)


def _apply_contact_wait(sk: Any, args: argparse.Namespace) -> None:
    """--contact-wait into the skill (then written as format v4)."""
    if args.contact_wait is not None:
        sk.contact_cN, sk.contact_tau_ms = args.contact_wait
        sk.format_version = max(sk.format_version, 4)


def _contact_line(sk: Any) -> str:
    """What fit prints of the skill's contact wait."""
    if not sk.contact_wait:
        return "contact wait: off"
    return (
        f"contact wait: the phase waits while f_hat - f_contact > {sk.contact_threshold_N:g} N, "
        f"rate time constant {sk.contact_tau_s:g} s (format v4)"
    )


def _cmd_fit(args: argparse.Namespace) -> int:
    import numpy as np

    from ..errors import ERR_FIT_ARGS, ERR_FIT_INACCURATE, ERR_FIT_TOLERANCE
    from ..model import tolerance as tol
    from ..model.demo import resample
    from ..model.limits import check_skill_force
    from ..model.multi import mean_profile
    from ..model.params import Gains, gains_for_object, load_gains
    from ..model.skill import DURATION_MAX_S, MAX_KERNELS
    from ..outputs import Outputs, check_target
    from ..readers import ReadOptions

    out = Path(args.output)
    targets = [args.output, args.output + ".json"] + ([args.plot] if args.plot else [])
    for i, t in enumerate(targets):  # refuse bad outputs before the work
        real = check_target(t, list(args.demo))
        if real in (check_target(u, ()) for u in targets[:i]):
            raise FsError(660, f"output {t!r} is given twice")
    if args.max_error is not None:
        if args.kernels is not None:
            raise FsError(ERR_FIT_ARGS, "give --kernels N or --max-error PCT, not both")
        if not (np.isfinite(args.max_error) and 0.0 < args.max_error <= 100.0):
            raise FsError(ERR_FIT_ARGS, f"--max-error must be in (0, 100] %: {args.max_error:g}")
    gains, object_mass_kg = load_gains(args.gains) if args.gains else (Gains(), None)
    if args.object_mass is not None:
        object_mass_kg = args.object_mass
        if not args.gains:  # the defaults are adapted to the object; given gains are only checked
            gains = gains_for_object(args.stiffness, args.object_mass)
            if gains != Gains():
                print(
                    f"force gains scaled to the {args.object_mass:g} kg object: kkf = {gains.kkf_Npm:.4g} N/m, "
                    f"kki = {gains.kki_Npms:.4g} N/(m s) (k_f*m_v/m_d = 0.75)"
                )
    args.fit_gains, args.fit_object_mass_kg = gains, object_mass_kg
    ropts = ReadOptions(
        time_column=args.time_column,
        time_unit=args.time_unit,
        rate_hz=args.rate,
        topic=args.topic,
        pose_topic=args.pose_topic,
        axis=args.axis,
        max_duration_s=DURATION_MAX_S,
    )
    demos = [_load(path, args, ropts) for path in args.demo]
    recorded_mass = next((d.object_mass_kg for d in demos if d.object_mass_kg is not None), None)
    if object_mass_kg is None and recorded_mass is not None:
        # a recording of the device that names its object (record's CAN log): the gains are
        # made for it as with --object-mass, given gains are checked against it
        object_mass_kg = args.fit_object_mass_kg = recorded_mass
        scaled = gains if args.gains else gains_for_object(args.stiffness, object_mass_kg)
        note = f"object mass {object_mass_kg:g} kg from the recording (the device's object model)"
        if scaled != gains:
            gains = args.fit_gains = scaled
            note += (
                f": force gains scaled to it: kkf = {gains.kkf_Npm:.4g} N/m, kki = {gains.kki_Npms:.4g} "
                "N/(m s) (k_f*m_v/m_d = 0.75)"
            )
        print(note)
    multi = None
    if len(demos) == 1:
        demo = demos[0]
        for note in demo.notes:
            print(note)
        # the fit works on the dt grid; the recording's own time and force stay for the error at
        # its samples, its position is not needed any more (memory on long recordings: a
        # recording on the grid lends the fit its arrays)
        grid_demo = resample(demo, args.dt, copy=False)
        demo.pos_m = np.zeros(0)
    else:
        for d in demos:
            for note in d.notes:
                print(f"{d.source}: {note}")
        grids = [resample(d, args.dt) for d in demos]
        del demos
        if args.periodic:
            return _fit_periodic_multi(grids, args, out)
        multi = mean_profile(grids, args.dt, keep_outliers=args.keep_outliers)
        _print_alignment(multi, args.keep_outliers)
        demo = grid_demo = multi.demo
    if args.periodic:
        return _fit_periodic(grid_demo, demo.source, args, out)

    def fit_n(n: int) -> tuple[Any, np.ndarray, np.ndarray]:
        r = _fit_with_hint(grid_demo, args, n)
        return r, r.t_s, r.f_hat_N

    if args.max_error is None:
        n_k = 50 if args.kernels is None else args.kernels
        res, grid, f_hat = fit_n(n_k)
        err = tol.sample_error(demo, grid, f_hat)
        del grid, f_hat
        searched = False
        # the default count follows the recording's length: 50 kernels per 10 s (a long smooth
        # recording); a recording with a defect (a step, a spike, a stuck sensor) is refused
        # with its cause rather than fitted with kernels spent on the defect
        n_cap = min(MAX_KERNELS, int(np.ceil(n_k * (float(demo.t_s[-1] - demo.t_s[0]) / DEFAULT_N_SPAN_S))))
        if err.max_pct > tol.DEFAULT_MAX_ERROR_PCT:
            res = None  # refused or replaced below: its grid-sized arrays go before the search
        if (
            err.max_pct > tol.DEFAULT_MAX_ERROR_PCT
            and args.kernels is None
            and n_cap > n_k
            and not tol.diagnose(demo)
        ):
            # the smallest N above the default within the default error, as --max-error 10 would
            # search it, up to the length's count
            n2, res2, err2, tried = tol.fit_to_tolerance(
                fit_n, demo, tol.DEFAULT_MAX_ERROR_PCT, n_cap, n_min=n_k + 1
            )
            searched = True
            if n2:
                print(
                    f"kernels: N = {n2}, the smallest within {tol.DEFAULT_MAX_ERROR_PCT:g} % (the default "
                    f"N = {n_k} gives {err.max_pct:.3g} %; --kernels N sets it)"
                )
                n_k, res, err = n2, res2, err2
            del res2  # else the best N's: the refusal needs its error only
        if err.max_pct > tol.DEFAULT_MAX_ERROR_PCT:
            cause = tol.diagnose(demo)
            raise FsError(
                ERR_FIT_INACCURATE,
                f"approximation error {err.max_pct:.3g} % of max force at N = {n_k} "
                f"(largest at t = {err.t_at_max_s:.4g} s) is above {tol.DEFAULT_MAX_ERROR_PCT:g} %: "
                + (f"{cause}; " if cause else "")
                + (
                    f"no N up to {n_cap} (50 per 10 s of recording) reaches it; --max-error PCT searches N up to "
                    f"{MAX_KERNELS}, or split the demonstration into a sequence of "
                    "shorter skills (run --sequence)"
                    if searched
                    else f"--max-error PCT searches N up to {MAX_KERNELS}"
                )
                + "; nothing written",
            )
    else:
        n_k, res_any, err, tried = tol.fit_to_tolerance(fit_n, demo, args.max_error, MAX_KERNELS)
        if n_k == 0:
            best_n = min(tried, key=lambda nt: nt[1])[0]
            cause = tol.diagnose(demo)
            raise FsError(
                ERR_FIT_TOLERANCE,
                f"no kernel count up to {MAX_KERNELS} reaches max error "
                f"{args.max_error:g} %: best {err.max_pct:.3g} % at N = {best_n} (largest at t = "
                f"{err.t_at_max_s:.4g} s); "
                + (f"{cause}; " if cause else "")
                + "split the demonstration into a sequence of shorter skills (run --sequence); "
                "nothing written",
            )
        res = res_any
        print(
            f"kernels: N = {n_k}, the smallest reaching max error {args.max_error:g} % "
            f"({len(tried)} fits: " + ", ".join(f"{n} -> {e:.3g} %" for n, e in sorted(tried)) + ")"
        )
    sk = res.skill
    _apply_contact_wait(sk, args)
    band = None
    if multi is not None:
        band = _attach_band(sk, multi.demo.force_N, multi.sigma_N, multi.noise_N, args)
    check_skill_force(sk, str(out), force_limit_N=args.force_limit)
    with Outputs(inputs=list(args.demo)) as outs:  # skill, JSON twin and plot: all or nothing
        sk.write(out, outs=outs)
        if args.plot:
            from ..plot import fit_figure, multi_figure

            title = (
                f"{demo.source}: {args.method}, N = {sk.n_kernels}, "
                f"max {err.max_pct:.2f} %, RMS {err.rms_pct:.2f} %"
            )
            if multi is None:
                fit_figure(res, args.plot, title=title, outs=outs)
            else:
                multi_figure(res, multi, band, args.plot, title=title, outs=outs)
        outs.commit()
    f_max = max(float(np.max(demo.force_N)), -float(np.min(demo.force_N)))
    print(
        f"demonstration: {demo.source}, T = {sk.duration_s:.3f} s, {res.t_s.size} samples at "
        f"{sk.dt_s * 1e3:g} ms (recorded: {demo.t_s.size}), max force {f_max:.4g} N"
    )
    print(
        f"skill: method {res.method}, N = {sk.n_kernels}, k = {sk.stiffness_Npm:g} N/m, tau = {sk.tau_s:.6g} s, "
        f"g = {sk.goal_N:.6g} N, f0 = {sk.force0_N:.4g} N, alpha = {sk.alpha:g}, beta = {sk.beta:g}, "
        f"gamma = {sk.gamma:g}, end {sk.end_policy}"
    )
    print(
        f"approximation error: max {err.max_pct:.3f} %, RMS {err.rms_pct:.3f} % of max force "
        f"(at the {demo.t_s.size} recorded samples)"
    )
    if sk.contact_wait:
        print(_contact_line(sk))
    if sk.has_band:
        print(_band_line(sk, args))
    if sk.y_weights is not None:
        print(
            f"y path ({args.y_column}): start {sk.y_start_m:.6g} m, goal g_y {sk.goal_y_m:.6g} m, "
            f"beta_y {sk.beta_y:g}; approximation error max {res.y_err_max_mm:.4f} mm, "
            f"RMS {res.y_err_rms_mm:.4f} mm (on the {sk.dt_s * 1e3:g} ms grid)"
        )
    print(
        f"wrote {out} ({out.stat().st_size} bytes) and {out}.json"
        + (f", plot {args.plot}" if args.plot else "")
    )
    return 0


def _load(path: str, args: argparse.Namespace, ropts: Any) -> Any:
    """One recording read with the command's reading options."""
    from ..model.demo import load_demo

    return load_demo(
        path,
        position_column=args.position_column,
        force_column=args.force_column,
        learn=args.learn,
        read=ropts,
        force_sign=float(args.force_sign),
        force_scale=args.force_scale,
        tare=args.tare,
        max_gap_s=args.max_gap,
        stiffness_Npm=args.stiffness,
        surface_m=args.surface_m,
        y_column=args.y_column,
    )


def _attach_band(sk: Any, mean_N: Any, sigma_N: Any, noise_N: float, args: argparse.Namespace) -> Any:
    """The band mean +- max(k*sigma, floor) into the skill (format v5); returns the per-sample
    (lo, hi) for the plot."""
    from ..model.multi import band_from_spread, band_points

    lo, hi = band_from_spread(mean_N, sigma_N, noise_N, k=args.band_k, floor_rel=args.band_floor / 100.0)
    sk.band_lo_N, sk.band_hi_N = band_points(lo, hi, args.band_points)
    sk.format_version = 5
    return lo, hi


def _band_line(sk: Any, args: argparse.Namespace) -> str:
    """What fit prints of the skill's band."""
    import numpy as np

    w = sk.band_hi_N - sk.band_lo_N
    return (
        f"band: mean +- max({args.band_k:g} sigma, floor {args.band_floor:g} % of max force or "
        f"{args.band_k:g} noise deviations) at {sk.band_points} points over the skill's time, width "
        f"{float(np.min(w)):.3g}..{float(np.max(w)):.3g} N (format v5)"
    )


def _print_alignment(multi: Any, keep_outliers: bool) -> None:
    """Each recording's alignment on the common time and its deviation from the others' mean;
    the outliers named."""
    import numpy as np

    print(
        f"{len(multi.alignments)} recordings aligned on the mean timing (affine registration, then a "
        "piecewise-linear time warp):"
    )
    for a in multi.alignments:
        mark = ""
        if a.outlier:
            mark = (
                "  OUTLIER (kept: --keep-outliers)"
                if a.used
                else "  OUTLIER: left out (--keep-outliers keeps it)"
            )
        print(
            f"  {a.source}: idle lead {a.lead_s:.3f} s trimmed, stretch {a.stretch:.4f}, lag "
            f"{a.lag_s * 1e3:+.1f} ms, warp +-{a.warp_s * 1e3:.0f} ms, deviation from the others' mean RMS {a.dev_rms_pct:.2f} %, "
            f"max {a.dev_max_pct:.2f} % of max force{mark}"
        )
    used = [a for a in multi.alignments if a.used]
    sig = multi.sigma_N
    f_max = float(np.max(np.abs(multi.demo.force_N))) if multi.demo.force_N.size else 1.0
    print(
        f"mean profile of {len(used)} recordings: T = {multi.demo.t_s[-1]:.3f} s, max force {f_max:.4g} N, "
        f"spread (1 sigma) mean {float(np.mean(sig)):.3g} N, largest {float(np.max(sig)):.3g} N, "
        f"sensor noise {multi.noise_N:.3g} N"
    )


def _fit_periodic_multi(demos: list[Any], args: argparse.Namespace, out: Path) -> int:
    """fit --periodic with several recordings: the mean of the steady strokes of every recording."""
    import numpy as np

    from ..errors import ERR_FIT_ARGS
    from ..model.fit import prepare
    from ..model.multi import noise_sigma, pooled_strokes
    from ..model.periodic_fit import fit_strokes

    if args.y_column is not None:
        raise FsError(ERR_FIT_ARGS, "--y-column with --periodic learns from one recording: give one")
    n0 = 50 if args.kernels is None else args.kernels
    prep = [
        prepare(
            d,
            args.stiffness,
            n0,
            args.method,
            args.fit_gains,
            args.surface_m,
            args.dt,
            args.fit_object_mass_kg,
        )
        for d in demos
    ]
    strokes, period, aligns, origin = pooled_strokes(
        [d for _, d in prep], args.dt, args.period, keep_outliers=args.keep_outliers
    )
    print(f"{len(aligns)} recordings, strokes aligned in phase on the common period {period:.6g} s:")
    for a in aligns:
        mark = ""
        if a.outlier:
            mark = (
                "  OUTLIER (kept: --keep-outliers)"
                if a.used
                else "  OUTLIER: left out (--keep-outliers keeps it)"
            )
        print(
            f"  {a.source}: {int((origin == aligns.index(a)).sum())} steady strokes from t = {a.lead_s:.3f} s, "
            f"period stretch {a.stretch:.4f}, phase lag {a.lag_s * 1e3:+.1f} ms, mean stroke's deviation "
            f"from the others' RMS {a.dev_rms_pct:.2f} %, max {a.dev_max_pct:.2f} % of max force{mark}"
        )
    i0 = int(origin[0])
    d0 = prep[i0][1]
    d0.y_m = None

    args.multi_noise_N = float(np.median([noise_sigma(d.force_N) for _, d in prep]))

    def fit_n(n: int) -> Any:
        p, _ = prepare(
            demos[i0],
            args.stiffness,
            n,
            args.method,
            args.fit_gains,
            args.surface_m,
            args.dt,
            args.fit_object_mass_kg,
        )
        return fit_strokes(
            d0,
            strokes,
            (period, 0.0),
            args.stiffness,
            n,
            args.method,
            args.fit_gains,
            args.surface_m,
            p,
            args.dt,
        )

    return _fit_periodic(d0, f"{len(aligns)} recordings", args, out, fit_n)


def _fit_periodic(demo: Any, source: str, args: argparse.Namespace, out: Path, fit_n: Any = None) -> int:
    """fit --periodic: the mean stroke of the steady strokes as a periodic skill (format v4)."""
    from ..errors import ERR_FIT_TOLERANCE, ERR_PERIODIC_ARGS
    from ..model.limits import check_skill_force
    from ..model.periodic_fit import fit_periodic
    from ..outputs import Outputs

    if args.end != "hold":
        raise FsError(
            ERR_PERIODIC_ARGS, "--periodic runs until stopped or for --cycles: --end does not apply"
        )

    def fit_one(n: int) -> Any:
        return fit_periodic(
            demo,
            args.stiffness,
            n_kernels=n,
            method=args.method,
            gains=args.fit_gains,
            surface_m=args.surface_m,
            dt_s=args.dt,
            period_s=args.period,
            object_mass_kg=args.fit_object_mass_kg,
        )

    fit_n = fit_one if fit_n is None else fit_n

    if args.max_error is None:
        res = fit_n(50 if args.kernels is None else args.kernels)
    else:  # the smallest N (doubling, then bisection) whose mean-stroke error is within the bound
        tried: dict[int, Any] = {}
        n = 5
        while True:
            tried[n] = fit_n(n)
            if tried[n].err_mean_max_pct <= args.max_error or 2 * n > tried[n].strokes_N.shape[1] // 2:
                break
            n *= 2
        if tried[n].err_mean_max_pct > args.max_error:
            raise FsError(
                ERR_FIT_TOLERANCE,
                f"no kernel count up to {n} reaches max error {args.max_error:g} % of the mean stroke "
                f"(best {min(r.err_mean_max_pct for r in tried.values()):.3g} %); nothing written",
            )
        lo = n // 2
        while n - lo > 1:
            mid = (lo + n) // 2
            tried[mid] = fit_n(mid)
            if tried[mid].err_mean_max_pct <= args.max_error:
                n = mid
            else:
                lo = mid
        res = tried[n]
        print(
            f"kernels: N = {n}, the smallest reaching max error {args.max_error:g} % of the mean stroke ("
            + ", ".join(f"{k} -> {r.err_mean_max_pct:.3g} %" for k, r in sorted(tried.items()))
            + ")"
        )
    sk = res.skill
    _apply_contact_wait(sk, args)
    band = None
    if len(args.demo) > 1:
        sigma = res.strokes_N.std(axis=0, ddof=1)
        band = _attach_band(sk, res.mean_stroke_N, sigma, args.multi_noise_N, args)
    check_skill_force(sk, str(out), force_limit_N=args.force_limit)
    with Outputs(inputs=list(args.demo)) as outs:  # skill, JSON twin and plot: all or nothing
        sk.write(out, outs=outs)
        if args.plot:
            from ..plot import periodic_figure

            periodic_figure(res, args.plot, outs=outs, band=band)
        outs.commit()
    k = res.strokes_N.shape[0]
    print(
        f"demonstration: {source}, period {res.period_s:.6g} s"
        + (" (given)" if args.period is not None else " (autocorrelation)")
        + f", {k} steady strokes from t = {res.start_s:.4g} s (approach and release left out), "
        f"max force {res.f_max_N:.4g} N"
    )
    print(
        f"skill: periodic, method {res.method}, N = {sk.n_kernels}, k = {sk.stiffness_Npm:g} N/m, "
        f"period {sk.duration_s:.6g} s ({int(round(sk.duration_s / sk.dt_s))} steps), tau = {sk.tau_s:.6g} s, "
        f"mean force g = {sk.goal_N:.6g} N, amplitude {sk.amplitude_N:.6g} N"
    )
    print(
        f"approximation error against the mean stroke: max {res.err_mean_max_pct:.3f} %, "
        f"RMS {res.err_mean_rms_pct:.3f} % of max force"
    )
    print(
        "against each stroke (max, % of max force): "
        + ", ".join(f"{e:.3f}" for e in res.err_stroke_max_pct.tolist())
    )
    if sk.y_weights is not None:
        print(
            f"y path ({args.y_column}): start {sk.y_start_m:.6g} m, mean g_y {sk.goal_y_m:.6g} m, "
            f"beta_y {sk.beta_y:g}; against the mean y stroke max {res.y_err_max_mm:.4f} mm, "
            f"RMS {res.y_err_rms_mm:.4f} mm"
        )
    if sk.contact_wait:
        print(_contact_line(sk))
    if sk.has_band:
        print(_band_line(sk, args))
    print(
        f"wrote {out} ({out.stat().st_size} bytes) and {out}.json"
        + (f", plot {args.plot}" if args.plot else "")
    )
    return 0


def _fit_with_hint(demo: Any, args: argparse.Namespace, n_kernels: int) -> Any:
    """fit() with the fit options of ``args``; a refusal for no net push on a force that reads
    negative says to flip the sign."""
    import numpy as np

    from ..errors import ERR_FIT_GOAL
    from ..model.fit import fit

    try:
        return fit(
            demo,
            args.stiffness,
            n_kernels=n_kernels,
            method=args.method,
            gains=args.fit_gains,
            surface_m=args.surface_m,
            end_policy=args.end,
            dt_s=args.dt,
            force0_N=0.0 if args.start_force == "zero" else None,
            object_mass_kg=args.fit_object_mass_kg,
        )
    except FsError as e:
        f = demo.force_N
        lo, hi = float(np.min(f)) or 0.0, float(np.max(f)) or 0.0
        if e.code == ERR_FIT_GOAL and -lo > hi:
            raise FsError(
                e.code,
                f"{e.message}; the force reads negative (min {lo:.4g} N, max {hi:.4g} N): "
                f"a push measured negative (the usual Fz sign) needs --force-sign -1",
            ) from None
        raise


def register(sub: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    """Add ``forceskill fit``."""
    p = sub.add_parser(
        "fit",
        help="learn a force skill from one demonstration or the mean of several",
        description="Learn a force skill from one demonstration, or from the aligned mean of several "
        "recordings of one task (CSV with a header row, a "
        "CAN log or a ROS 2 bag). Prints the approximation error in % of the maximum "
        "demonstrated force at the recorded samples; writes SKILL and SKILL.json. Refuses "
        "(nothing written) when the error is above 10 % or above --max-error.",
    )
    p.add_argument(
        "demo",
        metavar="DEMO",
        nargs="+",
        help="demonstration file (.csv, .blf/.asc/.log/.trc[.gz], .mcap, "
        "or a format added by a forceskill.readers plugin); several recordings of one task are "
        "aligned in time and their mean is learned",
    )
    mg = p.add_argument_group("several recordings: the mean and the demonstrated band (format v5)")
    mg.add_argument(
        "--keep-outliers",
        action="store_true",
        help="keep a recording named an outlier in the mean and the band (default: left out)",
    )
    mg.add_argument(
        "--band-k",
        type=float_arg,
        default=BAND_K,
        metavar="K",
        help=f"band half-width in standard deviations of the recordings about their mean ({BAND_K:g})",
    )
    mg.add_argument(
        "--band-floor",
        type=float_arg,
        default=100.0 * BAND_FLOOR_REL,
        metavar="PCT",
        help="the band's smallest half-width in %% of the mean's max force (at least K sensor noise "
        f"deviations; {100.0 * BAND_FLOOR_REL:g})",
    )
    mg.add_argument(
        "--band-points",
        type=int_arg,
        default=BAND_POINTS,
        metavar="M",
        help=f"points of the stored band over the skill's time, 2..128 ({BAND_POINTS})",
    )
    p.add_argument(
        "--stiffness",
        "-k",
        type=float_arg,
        required=True,
        metavar="K",
        help="nominal object stiffness k in N/m (execution: x_d = surface + f_hat/k, k_f = kkf/k)",
    )
    p.add_argument("-o", "--output", required=True, metavar="SKILL", help="skill image to write")
    p.add_argument(
        "--method",
        choices=("ridge", "lwr"),
        default="ridge",
        help="regression: ridge (joint regularised LS, default) or lwr (the paper's)",
    )
    p.add_argument(
        "--kernels",
        "-n",
        type=int_arg,
        default=None,
        metavar="N",
        help="kernels, 2..the format's cap 1024 (50)",
    )
    p.add_argument(
        "--max-error",
        type=float_arg,
        default=None,
        metavar="PCT",
        help="use the smallest N whose max error is <= PCT %% of max force",
    )
    p.add_argument(
        "--learn",
        choices=("contact", "operator"),
        default="contact",
        help="force to learn: contact (tip sensor, f_contact; default) or operator (f_operator)",
    )
    p.add_argument(
        "--position-column",
        default=None,
        metavar="C",
        help="position column (x; without one, position = surface + f/k)",
    )
    p.add_argument("--force-column", default=None, metavar="C", help="force column (overrides --learn)")
    p.add_argument(
        "--y-column",
        default=None,
        metavar="NAME",
        help="the path along y (m) to learn as the skill's position DMP (format v3; with --periodic the "
        "periodic y path, v4); "
        "a ROS 2 bag's pose axis is pose_x, pose_y or pose_z (with --pose-topic)",
    )
    g = p.add_argument_group("reading the recording")
    g.add_argument(
        "--time-column",
        default=None,
        metavar="NAME",
        help="CSV time column (default t, else time; also t_ms, time [ms], ...)",
    )
    g.add_argument(
        "--time-unit",
        choices=("s", "ms", "us", "ns"),
        default=None,
        help="CSV time unit (default: the unit in the header, 't [ms]' or 'time_ms', else s)",
    )
    g.add_argument(
        "--rate",
        type=float_arg,
        default=None,
        metavar="HZ",
        help="CSV without a time column: sample n is at n/HZ",
    )
    g.add_argument(
        "--topic",
        default=None,
        metavar="TOPIC",
        help="ROS 2 bag: geometry_msgs/WrenchStamped topic (default: the only one)",
    )
    g.add_argument(
        "--pose-topic",
        default=None,
        metavar="TOPIC",
        help="ROS 2 bag: PoseStamped/PointStamped topic for the position",
    )
    g.add_argument("--axis", choices=("x", "y", "z"), default="z", help="ROS 2 bag: force/pose axis (z)")
    g.add_argument(
        "--force-sign", type=int, choices=(1, -1), default=1, help="-1 when a push reads negative (1)"
    )
    g.add_argument(
        "--force-scale",
        type=float_arg,
        default=1.0,
        metavar="S",
        help="multiply the force by S, e.g. to convert to N (1)",
    )
    g.add_argument(
        "--tare",
        default="none",
        metavar="auto|SECONDS|none",
        help="remove a sensor bias: the median force before contact (auto) or over the first SECONDS (none)",
    )
    g.add_argument(
        "--max-gap",
        type=float_arg,
        default=0.1,
        metavar="S",
        help="longest gap between samples that is interpolated, s (0.1)",
    )
    p.add_argument(
        "--surface-m",
        type=float_arg,
        default=0.0,
        metavar="S",
        help="object surface position during the demonstration, m (0)",
    )
    p.add_argument(
        "--end",
        choices=("hold", "release"),
        default="hold",
        help="after the skill's duration: hold the last force or release to 0 in 0.5 s",
    )
    p.add_argument(
        "--gains",
        metavar="FILE.toml",
        help="controller gains (m_d_kg, k_d_Nspm, k_p_Npm, kkf_Npm = k*k_f, kki_Npms = k*k_i; "
        "optional m_v_kg, the object's mass), validated and stored in the skill",
    )
    p.add_argument(
        "--object-mass",
        type=float_arg,
        default=None,
        metavar="KG",
        help="object mass m_v if known: k_f*m_v/m_d < 1 is checked, and the default force "
        "gains are scaled down when needed (soft, heavy objects)",
    )
    p.add_argument(
        "--start-force",
        choices=("first", "zero"),
        default="first",
        help="starting force of the skill: the demonstration's first force (default) or 0 N",
    )
    per = p.add_argument_group("periodic skills (wiping, polishing: repeated strokes)")
    per.add_argument(
        "--periodic",
        action="store_true",
        help="learn the mean stroke of the recording's steady strokes as a periodic skill (format v4; "
        "--max-error then bounds the error against the mean stroke)",
    )
    per.add_argument(
        "--period",
        type=float_arg,
        default=None,
        metavar="S",
        help="the stroke period in s (default: found by autocorrelation)",
    )
    p.add_argument(
        "--contact-wait",
        type=contact_wait_arg,
        default=None,
        metavar="THRESHOLD_N[,TAU_S]",
        help="a phase that waits for contact: while the contact force is more than THRESHOLD_N "
        "below the reference the skill's phase slows to a stop (first order, time constant TAU_S, "
        f"default {CONTACT_TAU_DEFAULT_S:g} s) and resumes when contact returns (format v4)",
    )
    p.add_argument("--dt", type=float_arg, default=TICK_S, help=argparse.SUPPRESS)
    p.add_argument("--plot", metavar="PNG", help="write demonstrated vs learned force, error, position")
    add_force_limit(p)
    p.set_defaults(func=_cmd_fit)

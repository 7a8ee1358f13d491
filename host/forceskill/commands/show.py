"""forceskill show: validate a skill image and print a summary (or its JSON form)."""

from __future__ import annotations

import argparse
import sys

from ._args import add_force_limit


def _cmd_show(args: argparse.Namespace) -> int:
    import numpy as np

    from ..errors import ERR_SKILL_PEAK
    from ..model.dmp import rollout
    from ..model.limits import check_force_limit, peak_problem
    from ..model.skill import Skill

    check_force_limit(args.force_limit)
    sk = Skill.read(args.skill)
    if args.json:
        sys.stdout.write(sk.to_json())
        return 0
    d = sk.to_json_dict()
    _, f = rollout(sk)
    finite = bool(np.all(np.isfinite(f)))
    peak = float(np.max(np.abs(f))) if finite else float("inf")
    print(f"{args.skill}: skill image v{sk.format_version}, {len(sk.to_bytes())} bytes, CRC-32 {d['crc32']}")
    print(f"  duration       {sk.duration_s:g} s at dt {sk.dt_s * 1e3:g} ms, end policy {sk.end_policy}")
    print(
        f"  kernels        {sk.n_kernels}, centres {sk.centres[0]:.4g}..{sk.centres[-1]:.4g}, "
        f"widths {sk.widths.min():.3g}..{sk.widths.max():.3g}"
    )
    print(f"  tau            {sk.tau_s:.6g} s")
    print(f"  goal g         {sk.goal_N:.6g} N, starting force f0 {sk.force0_N:.6g} N")
    print(f"  stiffness k    {sk.stiffness_Npm:g} N/m, surface {sk.surface_m:g} m")
    print(f"  alpha/beta/gamma {sk.alpha:g} / {sk.beta:g} / {sk.gamma:g}")
    if sk.contact_wait:
        print(
            f"  contact wait   the phase waits while f_hat - f_contact > {sk.contact_threshold_N:g} N "
            f"(rate to 0, back to 1 on contact, time constant {sk.contact_tau_s:g} s)"
        )
    else:
        print("  contact wait   off (the phase runs on without contact)")
    if sk.band_lo_N is not None and sk.band_hi_N is not None:
        w = sk.band_hi_N - sk.band_lo_N
        print(
            f"  band           demonstrated band at {sk.band_points} points over the skill's time: lower "
            f"{float(np.min(sk.band_lo_N)):.4g}..{float(np.max(sk.band_lo_N)):.4g} N, upper "
            f"{float(np.min(sk.band_hi_N)):.4g}..{float(np.max(sk.band_hi_N)):.4g} N, width "
            f"{float(np.min(w)):.4g}..{float(np.max(w)):.4g} N"
        )
    else:
        print("  band           none (a skill from one recording)")
    k_f, k_i = sk.gains.force_gains(sk.stiffness_Npm)
    print(
        f"  gains          m_d {sk.m_d_kg:g} kg, k_d {sk.k_d_Nspm:g} Ns/m, k_p {sk.k_p_Npm:g} N/m, "
        f"k*k_f {sk.kkf_Npm:g} N/m, k*k_i {sk.kki_Npms:g} N/(m s) (k_f {k_f:.4g}, "
        f"k_i {k_i:.4g} 1/s at k)"
    )
    print(f"  rollout        peak |f_hat| {peak:.6g} N, final {float(f[-1]):.6g} N")
    if sk.has_y and sk.periodic:
        from ..model.periodic import rollout_path as periodic_path

        _, y = periodic_path(sk)
        print(
            f"  y path         periodic position DMP on y: start {sk.y_start_m:.6g} m, mean g_y "
            f"{sk.goal_y_m:.6g} m above it, beta_y {sk.beta_y:g}, cycle state q0 {sk.y_p0_m:.6g} m, "
            f"z0 {sk.y_z0_m:.6g} m; one cycle {float(np.min(y)):.6g}..{float(np.max(y)):.6g} m"
        )
    elif sk.has_y:
        from ..model.dmp import rollout_path

        _, y = rollout_path(sk)
        ext = float(np.max(np.abs(y - sk.y_start_m)))
        print(
            f"  y path         position DMP on y: start {sk.y_start_m:.6g} m, goal g_y {sk.goal_y_m:.6g} m, "
            f"beta_y {sk.beta_y:g}, gamma 0; rollout {float(np.min(y)):.6g}..{float(np.max(y)):.6g} m, "
            f"extent {ext * 1e3:.4g} mm from the start, final {float(y[-1]):.6g} m"
        )
    else:
        print("  y path         none (force only: y holds its position)")
    problem = peak_problem(peak, 1.0, args.force_limit)
    if problem:
        print(f"  REFUSED        {problem}: fit, upload and run refuse this skill [{ERR_SKILL_PEAK}]")
    else:
        print(
            f"  force limit    {args.force_limit:g} N: goal scale up to {args.force_limit / peak if peak > 0 else float('inf'):.4g}"
        )
    return 0


def register(sub: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    """Add ``forceskill show``."""
    p = sub.add_parser(
        "show",
        help="summarise a skill image",
        description="Validate a skill image and print a summary (or its JSON twin with --json).",
    )
    p.add_argument("skill", metavar="SKILL")
    p.add_argument("--json", action="store_true", help="print the JSON form")
    add_force_limit(p)
    p.set_defaults(func=_cmd_show)

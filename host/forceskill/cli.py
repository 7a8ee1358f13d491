"""The ``forceskill`` command: fit, rollout and show here; other commands come from modules.

Each module named in ``COMMAND_MODULES`` exposes ``register(subparsers)`` and adds its sub-command
with ``set_defaults(func=handler)``, ``handler(args) -> int``. Modules are imported lazily when the
parser is built; one that is missing or fails to import does not break the others.

Bad input never gives a traceback: one line ``forceskill: error: ...`` on stderr, exit status 2,
and no output file (outputs are written to a temporary file and renamed on success).
"""
from __future__ import annotations

import argparse
import importlib
import sys
from pathlib import Path
from typing import NoReturn, Optional, Sequence

import numpy as np

from .errors import ERR_IO, ERR_UNEXPECTED, FsError

#: Sub-command modules added by other parts of the host package (report, record, upload, run,
#: status, monitor, ...): append "forceskill.<module>" here.
COMMAND_MODULES: list[str] = [
    "forceskill.report",
    "forceskill.commands.record",
    "forceskill.commands.upload",
    "forceskill.commands.run",
    "forceskill.commands.status",
    "forceskill.commands.monitor",
    "forceskill.commands.journey",
    "forceskill.flash",
]

EXIT_BAD_INPUT = 2


class _Parser(argparse.ArgumentParser):
    """argparse with a one-line error (no usage dump), exit status 2."""

    def error(self, message: str) -> NoReturn:
        sys.stderr.write(f"forceskill: error: {message}\n")
        sys.exit(EXIT_BAD_INPUT)


def _positive_int(s: str) -> int:
    try:
        v = int(s)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not an integer: {s!r}") from None
    return v


def _float(s: str) -> float:
    try:
        return float(s)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a number: {s!r}") from None


def _limits():  # type: ignore[no-untyped-def]
    from . import limits
    return limits


# ---- fit -------------------------------------------------------------------------------------

def _cmd_fit(args: argparse.Namespace) -> int:
    from .demo import load_demo
    from .fit import fit
    from .limits import check_skill_force
    from .outputs import Outputs, check_target
    from .params import Gains

    out = Path(args.output)
    targets = [args.output, args.output + ".json"] + ([args.plot] if args.plot else [])
    for i, t in enumerate(targets):          # refuse bad outputs before the work
        real = check_target(t, [args.demo])
        if real in (check_target(u, ()) for u in targets[:i]):
            raise FsError(660, f"output {t!r} is given twice")
    demo = load_demo(args.demo, position_column=args.position_column, force_column=args.force_column,
                     learn=args.learn)
    res = fit(demo, args.stiffness, n_kernels=args.kernels, method=args.method, gains=Gains(),
              surface_m=args.surface_m, end_policy=args.end, dt_s=args.dt)
    sk = res.skill
    check_skill_force(sk, str(out), force_limit_N=args.force_limit)
    with Outputs(inputs=[args.demo]) as outs:   # skill, JSON twin and plot: all or nothing
        sk.write(out, outs=outs)
        if args.plot:
            from .plot import fit_figure
            fit_figure(res, args.plot, title=f"{demo.source}: {args.method}, N = {sk.n_kernels}, "
                       f"max {res.err_max_pct:.2f} %, RMS {res.err_rms_pct:.2f} %", outs=outs)
        outs.commit()
    f_max = float(np.max(np.abs(res.target_N)))
    print(f"demonstration: {demo.source}, T = {sk.duration_s:.3f} s, {res.t_s.size} samples at "
          f"{sk.dt_s * 1e3:g} ms, max force {f_max:.4g} N")
    print(f"skill: method {res.method}, N = {sk.n_kernels}, k = {sk.stiffness_Npm:g} N/m, tau = {sk.tau_s:.6g} s, "
          f"g = {sk.goal_m:.6g} m, alpha = {sk.alpha:g}, beta = {sk.beta:g}, gamma = {sk.gamma:g}, "
          f"end {sk.end_policy}")
    print(f"approximation error: max {res.err_max_pct:.3f} %, RMS {res.err_rms_pct:.3f} % of max force")
    print(f"wrote {out} ({out.stat().st_size} bytes) and {out}.json" + (f", plot {args.plot}" if args.plot else ""))
    return 0


def _register_fit(sub: "argparse._SubParsersAction[_Parser]") -> None:
    p = sub.add_parser("fit", help="learn a force skill from one demonstration",
                       description="Learn a force skill from one demonstration (CSV with a header row: "
                       "t [s], position [m], force [N]). Prints the approximation error in % of the "
                       "maximum demonstrated force; writes SKILL and SKILL.json.")
    p.add_argument("demo", metavar="DEMO", help="demonstration file (.csv, or a registered log format)")
    p.add_argument("--stiffness", "-k", type=_float, required=True, metavar="K",
                   help="nominal object stiffness k in N/m (f_hat = k*x)")
    p.add_argument("-o", "--output", required=True, metavar="SKILL", help="skill image to write")
    p.add_argument("--method", choices=("ridge", "lwr"), default="ridge",
                   help="regression: ridge (joint regularised LS, default) or lwr (the paper's)")
    p.add_argument("--kernels", "-n", type=_positive_int, default=50, metavar="N", help="kernels, 2..256 (50)")
    p.add_argument("--learn", choices=("contact", "operator"), default="contact",
                   help="force to learn: contact (tip sensor, f_contact; default) or operator (f_operator)")
    p.add_argument("--position-column", default="x", metavar="C", help="position column (x)")
    p.add_argument("--force-column", default=None, metavar="C", help="force column (overrides --learn)")
    p.add_argument("--surface-m", type=_float, default=0.0, metavar="S",
                   help="object surface position during the demonstration, m (0)")
    p.add_argument("--end", choices=("hold", "release"), default="hold",
                   help="after the skill's duration: hold the last force or release to 0 in 0.5 s")
    p.add_argument("--dt", type=_float, default=0.001, help=argparse.SUPPRESS)
    p.add_argument("--plot", metavar="PNG", help="write demonstrated vs learned force, error, position")
    _limits().add_force_limit(p)
    p.set_defaults(func=_cmd_fit)


# ---- rollout ---------------------------------------------------------------------------------

def _cmd_rollout(args: argparse.Namespace) -> int:
    from .dmp import rollout_blocks
    from .outputs import STDOUT, check_target, write_csv
    from .skill import Skill

    if args.output != STDOUT:
        check_target(args.output, [args.skill])
    sk = Skill.read(args.skill)
    stats = {"peak": -np.inf, "t_end": 0.0}

    def blocks():  # type: ignore[no-untyped-def]
        for t, f in rollout_blocks(sk, goal_scale=args.goal_scale, time_scale=args.time_scale, n_steps=args.steps):
            if f.size:
                stats["peak"] = max(stats["peak"], float(np.max(f)))
                stats["t_end"] = float(t[-1])
            yield np.column_stack((t, f))

    n = write_csv(args.output, ["t", "f_hat"], blocks(), inputs=[args.skill])
    msg = f"wrote {args.output}: {n} rows, t = 0..{stats['t_end']:.6g} s, peak f_hat {stats['peak']:.6g} N"
    print(msg, file=sys.stderr if args.output == STDOUT else sys.stdout)
    return 0


def _register_rollout(sub: "argparse._SubParsersAction[_Parser]") -> None:
    p = sub.add_parser("rollout", help="evaluate a skill offline (the firmware's DMP in numpy)",
                       description="Evaluate a skill at its dt from zero state, as the firmware does, and "
                       "write t,f_hat (s, N) as CSV.")
    p.add_argument("skill", metavar="SKILL")
    p.add_argument("-o", "--output", required=True, metavar="OUT.csv", help="CSV to write ('-': standard output)")
    p.add_argument("--goal-scale", type=_float, default=1.0, metavar="S",
                   help="multiply the goal (force) by S, 0..65.535")
    p.add_argument("--time-scale", type=_float, default=1.0, metavar="S", help="stretch time by S, 0.001..65.535")
    p.add_argument("--steps", type=_positive_int, default=None, metavar="N",
                   help="number of steps, at most 10^7 (default round(T*time_scale/dt))")
    p.set_defaults(func=_cmd_rollout)


# ---- show ------------------------------------------------------------------------------------

def _cmd_show(args: argparse.Namespace) -> int:
    from .dmp import rollout
    from .limits import check_force_limit, peak_problem
    from .skill import Skill, image_size

    check_force_limit(args.force_limit)
    sk = Skill.read(args.skill)
    if args.json:
        sys.stdout.write(sk.to_json())
        return 0
    d = sk.to_json_dict()
    _, f = rollout(sk)
    finite = bool(np.all(np.isfinite(f)))
    peak = float(np.max(np.abs(f))) if finite else float("inf")
    print(f"{args.skill}: skill image v{sk.format_version}, {image_size(sk.n_kernels)} bytes, CRC-32 {d['crc32']}")
    print(f"  duration       {sk.duration_s:g} s at dt {sk.dt_s * 1e3:g} ms, end policy {sk.end_policy}")
    print(f"  kernels        {sk.n_kernels}, centres {sk.centres[0]:.4g}..{sk.centres[-1]:.4g}, "
          f"widths {sk.widths.min():.3g}..{sk.widths.max():.3g}")
    print(f"  tau            {sk.tau_s:.6g} s")
    print(f"  goal g         {sk.goal_m:.6g} m")
    print(f"  stiffness k    {sk.stiffness_Npm:g} N/m, surface {sk.surface_m:g} m")
    print(f"  alpha/beta/gamma {sk.alpha:g} / {sk.beta:g} / {sk.gamma:g}")
    print(f"  gains          m_d {sk.m_d_kg:g} kg, k_d {sk.k_d_Nspm:g} Ns/m, k_p {sk.k_p_Npm:g} N/m, "
          f"k_f {sk.k_f:g}, k_i {sk.k_i_per_s:g} 1/s")
    print(f"  rollout        peak |f_hat| {peak:.6g} N, final {float(f[-1]):.6g} N")
    problem = peak_problem(peak, 1.0, args.force_limit)
    if problem:
        print(f"  REFUSED        {problem}: fit, upload and run refuse this skill [662]")
    else:
        print(f"  force limit    {args.force_limit:g} N: goal scale up to {args.force_limit / peak if peak > 0 else float('inf'):.4g}")
    return 0


def _register_show(sub: "argparse._SubParsersAction[_Parser]") -> None:
    p = sub.add_parser("show", help="summarise a skill image", description="Validate a skill image and "
                       "print a summary (or its JSON twin with --json).")
    p.add_argument("skill", metavar="SKILL")
    p.add_argument("--json", action="store_true", help="print the JSON form")
    _limits().add_force_limit(p)
    p.set_defaults(func=_cmd_show)


# ---- parser and entry point -------------------------------------------------------------------

def build_parser() -> tuple[argparse.ArgumentParser, list[str]]:
    """The parser with every available command, and the command modules that failed to load."""
    from . import __version__
    parser = _Parser(prog="forceskill", description="Learn force skills from demonstration and run them "
                     "on a force controller over CAN.")
    parser.add_argument("--version", action="version", version=f"forceskill {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)
    _register_fit(sub)
    _register_rollout(sub)
    _register_show(sub)
    missing: list[str] = []
    for name in COMMAND_MODULES:
        try:
            mod = importlib.import_module(name)
            mod.register(sub)
        except Exception as e:  # an optional command must not break the others
            missing.append(f"{name} ({type(e).__name__}: {e})")
    return parser, missing


def main(argv: Optional[Sequence[str]] = None) -> int:
    parser, missing = build_parser()
    args = parser.parse_args(argv)
    if not getattr(args, "func", None):
        parser.print_help()
        if missing:
            sys.stderr.write("forceskill: unavailable commands: " + "; ".join(missing) + "\n")
        return EXIT_BAD_INPUT
    try:
        return int(args.func(args) or 0)
    except FsError as e:
        sys.stderr.write(f"forceskill: error: {e.message} [{e.code}]\n")
        return EXIT_BAD_INPUT
    except OSError as e:
        where = f": {e.filename}" if e.filename else ""
        sys.stderr.write(f"forceskill: error: {e.strerror or e}{where} [{ERR_IO}]\n")
        return EXIT_BAD_INPUT
    except KeyboardInterrupt:
        sys.stderr.write("forceskill: interrupted\n")
        return 130
    except Exception as e:  # a failure no check foresaw (a library's own error): still one line
        first = (str(e).splitlines() or [""])[0]
        sys.stderr.write(f"forceskill: error: unexpected {type(e).__name__}: {first} [{ERR_UNEXPECTED}]\n")
        return EXIT_BAD_INPUT


if __name__ == "__main__":
    sys.exit(main())

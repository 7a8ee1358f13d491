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
from collections.abc import Sequence
from pathlib import Path
from typing import NoReturn

import numpy as np

from .errors import FsError

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


# ---- fit -------------------------------------------------------------------------------------


def _cmd_fit(args: argparse.Namespace) -> int:
    from .demo import load_demo
    from .fit import fit
    from .params import Gains

    out = Path(args.output)
    if not out.parent.is_dir() and str(out.parent):
        raise FsError(620, f"output folder does not exist: {str(out.parent)!r}")
    if args.plot and not Path(args.plot).parent.is_dir() and str(Path(args.plot).parent):
        raise FsError(620, f"plot folder does not exist: {str(Path(args.plot).parent)!r}")
    demo = load_demo(
        args.demo, position_column=args.position_column, force_column=args.force_column, learn=args.learn
    )
    res = fit(
        demo,
        args.stiffness,
        n_kernels=args.kernels,
        method=args.method,
        gains=Gains(),
        surface_m=args.surface_m,
        end_policy=args.end,
        dt_s=args.dt,
    )
    sk = res.skill
    if args.plot:
        from .plot import fit_figure

        fit_figure(
            res,
            args.plot,
            title=f"{demo.source}: {args.method}, N = {sk.n_kernels}, "
            f"max {res.err_max_pct:.2f} %, RMS {res.err_rms_pct:.2f} %",
        )
    try:
        sk.write(out)
    except BaseException:
        if args.plot:  # no partial output: the plot goes with the skill
            Path(args.plot).unlink(missing_ok=True)
        raise
    f_max = float(np.max(np.abs(res.target_N)))
    print(
        f"demonstration: {demo.source}, T = {sk.duration_s:.3f} s, {res.t_s.size} samples at "
        f"{sk.dt_s * 1e3:g} ms, max force {f_max:.4g} N"
    )
    print(
        f"skill: method {res.method}, N = {sk.n_kernels}, k = {sk.stiffness_Npm:g} N/m, tau = {sk.tau_s:.6g} s, "
        f"g = {sk.goal_m:.6g} m, alpha = {sk.alpha:g}, beta = {sk.beta:g}, gamma = {sk.gamma:g}, "
        f"end {sk.end_policy}"
    )
    print(f"approximation error: max {res.err_max_pct:.3f} %, RMS {res.err_rms_pct:.3f} % of max force")
    print(
        f"wrote {out} ({out.stat().st_size} bytes) and {out}.json"
        + (f", plot {args.plot}" if args.plot else "")
    )
    return 0


def _register_fit(sub: argparse._SubParsersAction[_Parser]) -> None:
    p = sub.add_parser(
        "fit",
        help="learn a force skill from one demonstration",
        description="Learn a force skill from one demonstration (CSV with a header row: "
        "t [s], position [m], force [N]). Prints the approximation error in % of the "
        "maximum demonstrated force; writes SKILL and SKILL.json.",
    )
    p.add_argument("demo", metavar="DEMO", help="demonstration file (.csv, or a registered log format)")
    p.add_argument(
        "--stiffness",
        "-k",
        type=_float,
        required=True,
        metavar="K",
        help="nominal object stiffness k in N/m (f_hat = k*x)",
    )
    p.add_argument("-o", "--output", required=True, metavar="SKILL", help="skill image to write")
    p.add_argument(
        "--method",
        choices=("ridge", "lwr"),
        default="ridge",
        help="regression: ridge (joint regularised LS, default) or lwr (the paper's)",
    )
    p.add_argument(
        "--kernels", "-n", type=_positive_int, default=50, metavar="N", help="kernels, 2..256 (50)"
    )
    p.add_argument(
        "--learn",
        choices=("contact", "operator"),
        default="contact",
        help="force to learn: contact (tip sensor, f_contact; default) or operator (f_operator)",
    )
    p.add_argument("--position-column", default="x", metavar="C", help="position column (x)")
    p.add_argument("--force-column", default=None, metavar="C", help="force column (overrides --learn)")
    p.add_argument(
        "--surface-m",
        type=_float,
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
    p.add_argument("--dt", type=_float, default=0.001, help=argparse.SUPPRESS)
    p.add_argument("--plot", metavar="PNG", help="write demonstrated vs learned force, error, position")
    p.set_defaults(func=_cmd_fit)


# ---- rollout ---------------------------------------------------------------------------------


def _cmd_rollout(args: argparse.Namespace) -> int:
    from .demo import write_csv
    from .dmp import rollout
    from .skill import Skill

    out = Path(args.output)
    if str(out.parent) and not out.parent.is_dir():
        raise FsError(620, f"output folder does not exist: {str(out.parent)!r}")
    sk = Skill.read(args.skill)
    t, f = rollout(sk, goal_scale=args.goal_scale, time_scale=args.time_scale, n_steps=args.steps)
    write_csv(out, {"t": t, "f_hat": f})
    print(f"wrote {out}: {t.size} rows, t = 0..{t[-1]:.6g} s, peak f_hat {float(np.max(f)):.6g} N")
    return 0


def _register_rollout(sub: argparse._SubParsersAction[_Parser]) -> None:
    p = sub.add_parser(
        "rollout",
        help="evaluate a skill offline (the firmware's DMP in numpy)",
        description="Evaluate a skill at its dt from zero state, as the firmware does, and "
        "write t,f_hat (s, N) as CSV.",
    )
    p.add_argument("skill", metavar="SKILL")
    p.add_argument("-o", "--output", required=True, metavar="OUT.csv")
    p.add_argument(
        "--goal-scale", type=_float, default=1.0, metavar="S", help="multiply the goal (force) by S"
    )
    p.add_argument("--time-scale", type=_float, default=1.0, metavar="S", help="stretch time by S")
    p.add_argument(
        "--steps",
        type=_positive_int,
        default=None,
        metavar="N",
        help="number of steps (default round(T*time_scale/dt))",
    )
    p.set_defaults(func=_cmd_rollout)


# ---- show ------------------------------------------------------------------------------------


def _cmd_show(args: argparse.Namespace) -> int:
    from .dmp import rollout
    from .skill import Skill, image_size

    sk = Skill.read(args.skill)
    if args.json:
        sys.stdout.write(sk.to_json())
        return 0
    d = sk.to_json_dict()
    _, f = rollout(sk)
    print(
        f"{args.skill}: skill image v{sk.format_version}, {image_size(sk.n_kernels)} bytes, CRC-32 {d['crc32']}"
    )
    print(f"  duration       {sk.duration_s:g} s at dt {sk.dt_s * 1e3:g} ms, end policy {sk.end_policy}")
    print(
        f"  kernels        {sk.n_kernels}, centres {sk.centres[0]:.4g}..{sk.centres[-1]:.4g}, "
        f"widths {sk.widths.min():.3g}..{sk.widths.max():.3g}"
    )
    print(f"  tau            {sk.tau_s:.6g} s")
    print(f"  goal g         {sk.goal_m:.6g} m")
    print(f"  stiffness k    {sk.stiffness_Npm:g} N/m, surface {sk.surface_m:g} m")
    print(f"  alpha/beta/gamma {sk.alpha:g} / {sk.beta:g} / {sk.gamma:g}")
    print(
        f"  gains          m_d {sk.m_d_kg:g} kg, k_d {sk.k_d_Nspm:g} Ns/m, k_p {sk.k_p_Npm:g} N/m, "
        f"k_f {sk.k_f:g}, k_i {sk.k_i_per_s:g} 1/s"
    )
    print(f"  rollout        peak f_hat {float(np.max(f)):.6g} N, final {float(f[-1]):.6g} N")
    return 0


def _register_show(sub: argparse._SubParsersAction[_Parser]) -> None:
    p = sub.add_parser(
        "show",
        help="summarise a skill image",
        description="Validate a skill image and print a summary (or its JSON twin with --json).",
    )
    p.add_argument("skill", metavar="SKILL")
    p.add_argument("--json", action="store_true", help="print the JSON form")
    p.set_defaults(func=_cmd_show)


# ---- parser and entry point -------------------------------------------------------------------


def build_parser() -> tuple[argparse.ArgumentParser, list[str]]:
    """The parser with every available command, and the command modules that failed to load."""
    from . import __version__

    parser = _Parser(
        prog="forceskill",
        description="Learn force skills from demonstration and run them on a force controller over CAN.",
    )
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


def main(argv: Sequence[str] | None = None) -> int:
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
        sys.stderr.write(f"forceskill: error: {e.strerror or e}: {e.filename or ''}\n")
        return EXIT_BAD_INPUT
    except KeyboardInterrupt:
        sys.stderr.write("forceskill: interrupted\n")
        return 130


if __name__ == "__main__":
    sys.exit(main())

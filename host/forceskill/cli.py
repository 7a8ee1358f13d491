"""The ``forceskill`` command: fit, rollout and show here; other commands come from modules.

Each module named in ``COMMAND_MODULES`` exposes ``register(subparsers)`` and adds its sub-command
with ``set_defaults(func=handler)``, ``handler(args) -> int``. Modules are imported lazily when the
parser is built, only the one a command line needs (``LAZY_COMMANDS``); one that is missing or
fails to import does not break the others.

Bad input never gives a traceback: one line ``forceskill: error: ...`` on stderr, exit status 2,
and no output file (outputs are written to a temporary file and renamed on success).
"""

from __future__ import annotations

import argparse
import importlib
import sys
import types
from collections.abc import Iterator, Sequence
from pathlib import Path
from typing import Any, NoReturn

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
#: Commands of those modules with their one-line help: a command line naming one of them imports
#: only its module; ``forceskill --help`` lists them without importing any (python-can, cantools,
#: udsoncan and matplotlib stay unloaded). A module not in this table is imported for the help.
LAZY_COMMANDS: dict[str, tuple[str, str]] = {
    "report": ("forceskill.report", "run every paper experiment on the HIL simulator"),
    "record": ("forceskill.commands.record", "record a demonstration (device in TEACH) to a CAN log"),
    "upload": ("forceskill.commands.upload", "upload a skill into a device slot (UDS over ISO-TP)"),
    "run": ("forceskill.commands.run", "execute a skill or a sequence on the device and report tracking"),
    "status": ("forceskill.commands.status", "show a device's state, versions and skill slots"),
    "monitor": ("forceskill.commands.monitor", "live values of a device (--plot for a live plot)"),
    "journey": (
        "forceskill.commands.journey",
        "record -> fit -> upload -> run 1x/1.5x over CAN on the simulator",
    ),
    "flash": ("forceskill.flash", "flash a signed firmware image over CAN (UDS), test-boot it, read back"),
    "image": ("forceskill.flash", "build or inspect a signed firmware image"),
}
BUILTIN_COMMANDS = ("fit", "rollout", "show")

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


def _limits() -> types.ModuleType:
    from . import limits

    return limits


# ---- fit -------------------------------------------------------------------------------------


def _cmd_fit(args: argparse.Namespace) -> int:
    import numpy as np

    from . import tolerance as tol
    from .demo import load_demo, resample
    from .errors import ERR_FIT_ARGS, ERR_FIT_INACCURATE, ERR_FIT_TOLERANCE
    from .limits import check_skill_force
    from .outputs import Outputs, check_target
    from .params import Gains, gains_for_object, load_gains
    from .readers import ReadOptions
    from .skill import DURATION_MAX_S, MAX_KERNELS

    out = Path(args.output)
    targets = [args.output, args.output + ".json"] + ([args.plot] if args.plot else [])
    for i, t in enumerate(targets):  # refuse bad outputs before the work
        real = check_target(t, [args.demo])
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
    demo = load_demo(
        args.demo,
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
    for note in demo.notes:
        print(note)
    # the fit works on the dt grid; the recording's own time and force stay for the error at its
    # samples, its position is not needed any more (memory on long recordings)
    grid_demo = resample(demo, args.dt)
    demo.pos_m = np.zeros(0)

    def fit_n(n: int) -> tuple[Any, np.ndarray, np.ndarray]:
        r = _fit_with_hint(grid_demo, args, n)
        return r, r.t_s, r.f_hat_N

    if args.max_error is None:
        n_k = 50 if args.kernels is None else args.kernels
        res, grid, f_hat = fit_n(n_k)
        err = tol.sample_error(demo, grid, f_hat)
        if err.max_pct > tol.DEFAULT_MAX_ERROR_PCT:
            cause = tol.diagnose(demo)
            raise FsError(
                ERR_FIT_INACCURATE,
                f"approximation error {err.max_pct:.3g} % of max force at N = {n_k} "
                f"(largest at t = {err.t_at_max_s:.4g} s) is above {tol.DEFAULT_MAX_ERROR_PCT:g} %: "
                + (f"{cause}; " if cause else "")
                + f"--max-error PCT searches N up to {MAX_KERNELS}; nothing written",
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
    check_skill_force(sk, str(out), force_limit_N=args.force_limit)
    with Outputs(inputs=[args.demo]) as outs:  # skill, JSON twin and plot: all or nothing
        sk.write(out, outs=outs)
        if args.plot:
            from .plot import fit_figure

            fit_figure(
                res,
                args.plot,
                title=f"{demo.source}: {args.method}, N = {sk.n_kernels}, "
                f"max {err.max_pct:.2f} %, RMS {err.rms_pct:.2f} %",
                outs=outs,
            )
        outs.commit()
    f_max = float(np.max(np.abs(demo.force_N)))
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


def _fit_with_hint(demo: Any, args: argparse.Namespace, n_kernels: int) -> Any:
    """fit() with the fit options of ``args``; a refusal for no net push on a force that reads
    negative says to flip the sign."""
    import numpy as np

    from .errors import ERR_FIT_GOAL
    from .fit import fit

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


def _register_fit(sub: argparse._SubParsersAction[_Parser]) -> None:
    p = sub.add_parser(
        "fit",
        help="learn a force skill from one demonstration",
        description="Learn a force skill from one demonstration (CSV with a header row, a "
        "CAN log or a ROS 2 bag). Prints the approximation error in % of the maximum "
        "demonstrated force at the recorded samples; writes SKILL and SKILL.json. Refuses "
        "(nothing written) when the error is above 10 % or above --max-error.",
    )
    p.add_argument(
        "demo",
        metavar="DEMO",
        help="demonstration file (.csv, .blf/.asc/.log/.trc[.gz], .mcap, "
        "or a format added by a forceskill.readers plugin)",
    )
    p.add_argument(
        "--stiffness",
        "-k",
        type=_float,
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
        type=_positive_int,
        default=None,
        metavar="N",
        help="kernels, 2..the format's cap 1024 (50)",
    )
    p.add_argument(
        "--max-error",
        type=_float,
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
        help="the path along y (m) to learn as the skill's position DMP (format v3); "
        "a ROS 2 bag's pose axis is pose_x, pose_y or pose_z (with --pose-topic)",
    )
    g = p.add_argument_group("reading the recording")
    g.add_argument("--time-column", default="t", metavar="NAME", help="CSV time column (t)")
    g.add_argument(
        "--time-unit",
        choices=("s", "ms", "us", "ns"),
        default=None,
        help="CSV time unit (default: the unit in the header, 't [ms]', else s)",
    )
    g.add_argument(
        "--rate",
        type=_float,
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
        type=_float,
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
        type=_float,
        default=0.1,
        metavar="S",
        help="longest gap between samples that is interpolated, s (0.1)",
    )
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
    p.add_argument(
        "--gains",
        metavar="FILE.toml",
        help="controller gains (m_d_kg, k_d_Nspm, k_p_Npm, kkf_Npm = k*k_f, kki_Npms = k*k_i; "
        "optional m_v_kg, the object's mass), validated and stored in the skill",
    )
    p.add_argument(
        "--object-mass",
        type=_float,
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
    p.add_argument("--dt", type=_float, default=0.001, help=argparse.SUPPRESS)
    p.add_argument("--plot", metavar="PNG", help="write demonstrated vs learned force, error, position")
    _limits().add_force_limit(p)
    p.set_defaults(func=_cmd_fit)


# ---- rollout ---------------------------------------------------------------------------------


def _cmd_rollout(args: argparse.Namespace) -> int:
    import numpy as np

    from .dmp import rollout_blocks, rollout_path
    from .limits import check_path_scale
    from .outputs import STDOUT, check_target, write_csv
    from .skill import Skill

    if args.output != STDOUT:
        check_target(args.output, [args.skill])
    check_path_scale(args.path_scale)
    sk = Skill.read(args.skill)
    stats = {"peak": -np.inf, "t_end": 0.0}
    y_all: np.ndarray | None = None
    if sk.has_y:
        _, y_all = rollout_path(
            sk, time_scale=args.time_scale, path_scale=args.path_scale, n_steps=args.steps
        )

    def blocks() -> Iterator[np.ndarray]:
        row = 0
        for t, f in rollout_blocks(
            sk, goal_scale=args.goal_scale, time_scale=args.time_scale, n_steps=args.steps
        ):
            if f.size:
                stats["peak"] = max(stats["peak"], float(np.max(f)))
                stats["t_end"] = float(t[-1])
            if y_all is None:
                yield np.column_stack((t, f))
            else:
                yield np.column_stack((t, f, y_all[row : row + t.size]))
            row += t.size

    names = ["t", "f_hat"] + (["y_hat"] if y_all is not None else [])
    n = write_csv(args.output, names, blocks(), inputs=[args.skill])
    msg = f"wrote {args.output}: {n} rows, t = 0..{stats['t_end']:.6g} s, peak f_hat {stats['peak']:.6g} N"
    if y_all is not None and y_all.size:
        msg += f", y_hat {float(np.min(y_all)):.6g}..{float(np.max(y_all)):.6g} m"
    print(msg, file=sys.stderr if args.output == STDOUT else sys.stdout)
    return 0


def _register_rollout(sub: argparse._SubParsersAction[_Parser]) -> None:
    p = sub.add_parser(
        "rollout",
        help="evaluate a skill offline (the firmware's DMP in numpy)",
        description="Evaluate a skill at its dt from zero state, as the firmware does, and "
        "write t,f_hat (s, N) as CSV; a skill with a y DMP adds y_hat (m).",
    )
    p.add_argument("skill", metavar="SKILL")
    p.add_argument(
        "-o", "--output", required=True, metavar="OUT.csv", help="CSV to write ('-': standard output)"
    )
    p.add_argument(
        "--goal-scale",
        type=_float,
        default=1.0,
        metavar="S",
        help="multiply the goal (force) by S, 0..65.535",
    )
    p.add_argument(
        "--time-scale", type=_float, default=1.0, metavar="S", help="stretch time by S, 0.001..65.535"
    )
    p.add_argument(
        "--path-scale",
        type=_float,
        default=1.0,
        metavar="S",
        help="scale the y path about its start by S, 0..65.535 (skills with a y DMP)",
    )
    p.add_argument(
        "--steps",
        type=_positive_int,
        default=None,
        metavar="N",
        help="number of steps, at most 10^7 (default round(T*time_scale/dt))",
    )
    p.set_defaults(func=_cmd_rollout)


# ---- show ------------------------------------------------------------------------------------


def _cmd_show(args: argparse.Namespace) -> int:
    import numpy as np

    from .dmp import rollout
    from .limits import check_force_limit, peak_problem
    from .skill import Skill

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
    print(
        f"  gains          m_d {sk.m_d_kg:g} kg, k_d {sk.k_d_Nspm:g} Ns/m, k_p {sk.k_p_Npm:g} N/m, "
        f"k*k_f {sk.kkf_Npm:g} N/m, k*k_i {sk.kki_Npms:g} N/(m s) (k_f {sk.kkf_Npm / sk.stiffness_Npm:.4g}, "
        f"k_i {sk.kki_Npms / sk.stiffness_Npm:.4g} 1/s at k)"
    )
    print(f"  rollout        peak |f_hat| {peak:.6g} N, final {float(f[-1]):.6g} N")
    if sk.has_y:
        from .dmp import rollout_path

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
        print(f"  REFUSED        {problem}: fit, upload and run refuse this skill [662]")
    else:
        print(
            f"  force limit    {args.force_limit:g} N: goal scale up to {args.force_limit / peak if peak > 0 else float('inf'):.4g}"
        )
    return 0


def _register_show(sub: argparse._SubParsersAction[_Parser]) -> None:
    p = sub.add_parser(
        "show",
        help="summarise a skill image",
        description="Validate a skill image and print a summary (or its JSON twin with --json).",
    )
    p.add_argument("skill", metavar="SKILL")
    p.add_argument("--json", action="store_true", help="print the JSON form")
    _limits().add_force_limit(p)
    p.set_defaults(func=_cmd_show)


# ---- parser and entry point -------------------------------------------------------------------


def _modules_for(argv: Sequence[str] | None) -> tuple[list[str], list[str]]:
    """(modules to import, commands to list from LAZY_COMMANDS without importing) for ``argv``."""
    if argv is None:
        return list(COMMAND_MODULES), []
    cmd = next((a for a in argv if not a.startswith("-")), None)
    if cmd in BUILTIN_COMMANDS:
        return [], []
    if cmd in LAZY_COMMANDS and LAZY_COMMANDS[cmd][0] in COMMAND_MODULES:
        return [LAZY_COMMANDS[cmd][0]], []
    if cmd is None:  # help, version or nothing: list the known commands, import the others
        lazy = {m for m, _ in LAZY_COMMANDS.values()}
        return (
            [m for m in COMMAND_MODULES if m not in lazy],
            [c for c, (m, _) in LAZY_COMMANDS.items() if m in COMMAND_MODULES],
        )
    return list(COMMAND_MODULES), []


def build_parser(argv: Sequence[str] | None = None) -> tuple[argparse.ArgumentParser, list[str]]:
    """The parser for ``argv`` (every command when None), and the command modules that failed to load."""
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
    modules, listed = _modules_for(argv)
    for name in listed:
        sub.add_parser(name, help=LAZY_COMMANDS[name][1])
    missing: list[str] = []
    for name in modules:
        try:
            mod = importlib.import_module(name)
            mod.register(sub)
        except Exception as e:  # an optional command must not break the others
            missing.append(f"{name} ({type(e).__name__}: {e})")
    return parser, missing


def main(argv: Sequence[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else list(argv)
    parser, missing = build_parser(argv)
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

"""forceskill rollout: evaluate a skill offline (the firmware's DMP in numpy) and write t,f_hat (and
y_hat for a skill with a y DMP) as CSV."""

from __future__ import annotations

import argparse
import sys
from collections.abc import Iterator

from ._args import add_path_scale, add_scales, float_arg, int_arg


def _cmd_rollout(args: argparse.Namespace) -> int:
    import numpy as np

    from ..model.dmp import rollout_blocks, rollout_path
    from ..model.scales import check_path_scale
    from ..model.skill import Skill
    from ..outputs import STDOUT, check_target, write_csv

    if args.output != STDOUT:
        check_target(args.output, [args.skill])
    check_path_scale(args.path_scale)
    sk = Skill.read(args.skill)
    if args.contact_loss is not None:
        return _rollout_contact_loss(sk, args)
    if sk.periodic or args.cycles is not None or args.amplitude_scale != 1.0:
        return _rollout_periodic(sk, args)
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
            cols = [t, f]
            if sk.has_band:
                cols += list(sk.band_at(t, args.goal_scale, args.time_scale))
            if y_all is not None:
                cols.append(y_all[row : row + t.size])
            yield np.column_stack(cols)
            row += t.size

    names = ["t", "f_hat"] + (["f_band_lo", "f_band_hi"] if sk.has_band else [])
    names += ["y_hat"] if y_all is not None else []
    n = write_csv(args.output, names, blocks(), inputs=[args.skill])
    msg = f"wrote {args.output}: {n} rows, t = 0..{stats['t_end']:.6g} s, peak f_hat {stats['peak']:.6g} N"
    if y_all is not None and y_all.size:
        msg += f", y_hat {float(np.min(y_all)):.6g}..{float(np.max(y_all)):.6g} m"
    print(msg, file=sys.stderr if args.output == STDOUT else sys.stdout)
    return 0


def _rollout_periodic(sk: object, args: argparse.Namespace) -> int:
    """A periodic skill for --cycles periods (1 by default) at the goal (mean force), amplitude
    and time (period) scales."""
    import numpy as np

    from ..errors import ERR_PERIODIC_ARGS, FsError
    from ..model import periodic
    from ..model.skill import Skill
    from ..outputs import STDOUT, write_csv

    assert isinstance(sk, Skill)
    if not sk.periodic:
        raise FsError(ERR_PERIODIC_ARGS, "--cycles and --amplitude-scale apply to periodic skills only")
    if args.path_scale != 1.0 and not sk.has_y:
        raise FsError(ERR_PERIODIC_ARGS, "this periodic skill has no y path: --path-scale does not apply")
    cycles = 1.0 if args.cycles is None else args.cycles
    if not (np.isfinite(cycles) and cycles > 0.0):
        raise FsError(ERR_PERIODIC_ARGS, f"--cycles must be a number > 0: {cycles:g}")
    t, f = periodic.rollout(
        sk,
        cycles=cycles,
        goal_scale=args.goal_scale,
        amplitude_scale=args.amplitude_scale,
        time_scale=args.time_scale,
        n_steps=args.steps,
    )
    cols, names, y_msg = [t, f], ["t", "f_hat"], ""
    if sk.has_band:
        cols += list(sk.band_at(t, args.goal_scale, args.time_scale, args.amplitude_scale))
        names += ["f_band_lo", "f_band_hi"]
    if sk.has_y:
        _, y = periodic.rollout_path(
            sk, cycles=cycles, path_scale=args.path_scale, time_scale=args.time_scale, n_steps=args.steps
        )
        cols, names = [t, f, y], [*names, "y_hat"]
        y_msg = f", y_hat {float(np.min(y)):.6g}..{float(np.max(y)):.6g} m"
    n = write_csv(args.output, names, iter([np.column_stack(cols)]), inputs=[args.skill])
    print(
        f"wrote {args.output}: {n} rows, t = 0..{float(t[-1]):.6g} s ({cycles:g} cycles of "
        f"{sk.duration_s * args.time_scale:.6g} s), f_hat {float(np.min(f)):.6g}..{float(np.max(f)):.6g} N, "
        f"mean {float(np.mean(f[:-1])):.6g} N" + y_msg,
        file=sys.stderr if args.output == STDOUT else sys.stdout,
    )
    return 0


def contact_loss_arg(text: str) -> tuple[float, float]:
    """--contact-loss FROM_S,TO_S: 0 <= from < to, both finite."""
    import math

    try:
        a, b = (float(x) for x in text.split(","))
    except ValueError:
        a = b = math.nan
    if not (math.isfinite(a) and math.isfinite(b) and 0.0 <= a < b):
        raise argparse.ArgumentTypeError(f"expected FROM_S,TO_S with 0 <= FROM_S < TO_S: {text!r}")
    return a, b


def _rollout_contact_loss(sk: object, args: argparse.Namespace) -> int:
    """The skill against a contact that follows its reference but is lost in the window
    --contact-loss (forceskill.model.contact.loss_window): t, f_hat, f_contact, rate, the hold."""
    import numpy as np

    from ..errors import ERR_PERIODIC_ARGS, FsError
    from ..model import contact
    from ..model.scales import check_steps
    from ..model.skill import Skill
    from ..outputs import STDOUT, write_csv

    assert isinstance(sk, Skill)
    if args.path_scale != 1.0:
        raise FsError(
            ERR_PERIODIC_ARGS, "--contact-loss evaluates the force alone: --path-scale does not apply"
        )
    a, b = args.contact_loss
    cycles = 1.0 if args.cycles is None else args.cycles
    nominal_s = sk.duration_s * args.time_scale * (cycles if sk.periodic else 1.0)
    n = args.steps if args.steps is not None else int(round((nominal_s + (b - a)) / sk.dt_s))
    check_steps(n)
    fc, f_hat, rate, hold = contact.loss_window(
        sk,
        n,
        (a, b),
        goal_scale=args.goal_scale,
        time_scale=args.time_scale,
        amplitude_scale=args.amplitude_scale,
    )
    t = np.arange(n) * sk.dt_s
    rows = write_csv(
        args.output,
        ["t", "f_hat", "f_contact", "rate"],
        iter([np.column_stack((t, f_hat, fc, rate))]),
        inputs=[args.skill],
    )
    wait = (
        f"contact wait {sk.contact_threshold_N:g} N, {sk.contact_tau_s:g} s: the phase held {hold * 1e3:.1f} ms"
        if sk.contact_wait
        else "no contact wait: the phase ran on"
    )
    print(
        f"wrote {args.output}: {rows} rows, contact lost {a:g}..{b:g} s; {wait}",
        file=sys.stderr if args.output == STDOUT else sys.stdout,
    )
    return 0


def register(sub: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    """Add ``forceskill rollout``."""
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
    add_scales(p)
    add_path_scale(p)
    p.add_argument(
        "--steps",
        type=int_arg,
        default=None,
        metavar="N",
        help="number of steps, at most 10^7 (default round(T*time_scale/dt))",
    )
    p.add_argument(
        "--cycles",
        type=float_arg,
        default=None,
        metavar="N",
        help="periodic skills: the number of periods to evaluate (1)",
    )
    p.add_argument(
        "--amplitude-scale",
        type=float_arg,
        default=1.0,
        metavar="S",
        help="periodic skills: multiply the stroke's amplitude by S (--goal-scale sets the mean force, "
        "--time-scale the period)",
    )
    p.add_argument(
        "--contact-loss",
        type=contact_loss_arg,
        default=None,
        metavar="FROM_S,TO_S",
        help="simulate a contact that follows the reference but is lost from FROM_S to TO_S: the "
        "skill's contact wait holds its phase (columns t, f_hat, f_contact, rate; the hold printed)",
    )
    p.set_defaults(func=_cmd_rollout)

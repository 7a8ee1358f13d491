"""forceskill rollout: evaluate a skill offline (the firmware's DMP in numpy) and write t,f_hat as CSV."""

from __future__ import annotations

import argparse
import sys
from collections.abc import Iterator

from ._args import add_scales, int_arg


def _cmd_rollout(args: argparse.Namespace) -> int:
    import numpy as np

    from ..model.dmp import rollout_blocks
    from ..model.skill import Skill
    from ..outputs import STDOUT, check_target, write_csv

    if args.output != STDOUT:
        check_target(args.output, [args.skill])
    sk = Skill.read(args.skill)
    stats = {"peak": -np.inf, "t_end": 0.0}

    def blocks() -> Iterator[np.ndarray]:
        for t, f in rollout_blocks(
            sk, goal_scale=args.goal_scale, time_scale=args.time_scale, n_steps=args.steps
        ):
            if f.size:
                stats["peak"] = max(stats["peak"], float(np.max(f)))
                stats["t_end"] = float(t[-1])
            yield np.column_stack((t, f))

    n = write_csv(args.output, ["t", "f_hat"], blocks(), inputs=[args.skill])
    msg = f"wrote {args.output}: {n} rows, t = 0..{stats['t_end']:.6g} s, peak f_hat {stats['peak']:.6g} N"
    print(msg, file=sys.stderr if args.output == STDOUT else sys.stdout)
    return 0


def register(sub: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    """Add ``forceskill rollout``."""
    p = sub.add_parser(
        "rollout",
        help="evaluate a skill offline (the firmware's DMP in numpy)",
        description="Evaluate a skill at its dt from zero state, as the firmware does, and "
        "write t,f_hat (s, N) as CSV.",
    )
    p.add_argument("skill", metavar="SKILL")
    p.add_argument(
        "-o", "--output", required=True, metavar="OUT.csv", help="CSV to write ('-': standard output)"
    )
    add_scales(p)
    p.add_argument(
        "--steps",
        type=int_arg,
        default=None,
        metavar="N",
        help="number of steps, at most 10^7 (default round(T*time_scale/dt))",
    )
    p.set_defaults(func=_cmd_rollout)

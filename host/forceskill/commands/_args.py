"""Argument types and options shared by the commands (no heavy imports: the parser is built for
every command line)."""

from __future__ import annotations

import argparse

from ..model.limits import FORCE_LIMIT_N
from ..model.scales import GOAL_SCALE_MAX, TIME_SCALE_MAX, TIME_SCALE_MIN


def int_arg(s: str) -> int:
    """argparse type: an integer, refused in one line otherwise (the command checks its range)."""
    try:
        v = int(s)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not an integer: {s!r}") from None
    return v


def float_arg(s: str) -> float:
    """argparse type: a number, refused in one line otherwise (the command checks its range)."""
    try:
        return float(s)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a number: {s!r}") from None


def add_force_limit(p: argparse.ArgumentParser) -> None:
    """The --force-limit option (N, default the device's 50 N)."""
    p.add_argument(
        "--force-limit",
        type=float_arg,
        default=FORCE_LIMIT_N,
        metavar="N",
        help=f"refuse a skill whose rollout is not finite or peaks above N newtons ({FORCE_LIMIT_N:g})",
    )


def add_scales(p: argparse.ArgumentParser, goal_note: str = "") -> None:
    """--goal-scale and --time-scale (default 1), their ranges in the help taken from model.scales;
    goal_note is appended to the goal scale's help."""
    p.add_argument(
        "--goal-scale",
        type=float_arg,
        default=1.0,
        metavar="S",
        help=f"multiply the goal (force) by S, 0..{GOAL_SCALE_MAX:g}"
        + (f"; {goal_note}" if goal_note else ""),
    )
    p.add_argument(
        "--time-scale",
        type=float_arg,
        default=1.0,
        metavar="S",
        help=f"stretch time by S, {TIME_SCALE_MIN:g}..{TIME_SCALE_MAX:g}",
    )

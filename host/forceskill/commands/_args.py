"""Argument types and options shared by the commands (no heavy imports: the parser is built for
every command line)."""

from __future__ import annotations

import argparse

from ..model.limits import FORCE_LIMIT_N


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

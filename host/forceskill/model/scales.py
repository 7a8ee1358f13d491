"""The goal, time and path scales a skill is executed at, and the length of a rollout: the ranges the
device's command encodes (1/1000 steps in 16 bits; code 109 as the firmware) and the rollout cap
(663). Used by the DMP, the limits and every command."""

from __future__ import annotations

import math

from ..errors import ERR_ROLLOUT_CAP, ERR_SCALE_INVALID, FsError, ParamError
from ..wire import SCALE, from_steps

#: the largest 16-bit count of the wire's scale steps
GOAL_SCALE_MAX = from_steps(0xFFFF)
TIME_SCALE_MIN = SCALE
TIME_SCALE_MAX = GOAL_SCALE_MAX
#: 10^7 steps: 2.8 h at 1 ms (a skill is at most 3600 s); about 10 s of CPU and a few 100 MB of CSV.
MAX_ROLLOUT_STEPS = 10_000_000


def check_scales(goal_scale: float, time_scale: float) -> None:
    """Goal scale in [0, 65.535], time scale in [0.001, 65.535], both finite (ParamError 109)."""
    if not (math.isfinite(goal_scale) and 0.0 <= goal_scale <= GOAL_SCALE_MAX):
        raise ParamError(
            ERR_SCALE_INVALID, f"goal scale must be finite and in [0, {GOAL_SCALE_MAX:g}]: {goal_scale:g}"
        )
    if not (math.isfinite(time_scale) and TIME_SCALE_MIN <= time_scale <= TIME_SCALE_MAX):
        raise ParamError(
            ERR_SCALE_INVALID,
            f"time scale must be finite and in [{TIME_SCALE_MIN:g}, {TIME_SCALE_MAX:g}]: {time_scale:g}",
        )


#: --path-scale (the y path of a skill with a y DMP, about its start): the goal scale's range
PATH_SCALE_MAX = GOAL_SCALE_MAX


def check_path_scale(path_scale: float) -> None:
    """Path scale in [0, 65.535], finite (ParamError 109, as the device's scale check)."""
    if not (math.isfinite(path_scale) and 0.0 <= path_scale <= PATH_SCALE_MAX):
        raise ParamError(
            ERR_SCALE_INVALID, f"path scale must be finite and in [0, {PATH_SCALE_MAX:g}]: {path_scale:g}"
        )


def check_steps(n_steps: int) -> None:
    """0 <= n_steps <= MAX_ROLLOUT_STEPS (663)."""
    if not 0 <= n_steps <= MAX_ROLLOUT_STEPS:
        raise FsError(
            ERR_ROLLOUT_CAP,
            f"rollout of {n_steps} steps outside 0..{MAX_ROLLOUT_STEPS} "
            "(give fewer --steps or a smaller --time-scale)",
        )

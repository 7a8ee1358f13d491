"""The host's limits on scales, rollout length and a skill's force, checked the same way by every
command (fit, show, rollout, upload, run) before anything is written or sent.

- Goal scale and path scale (the y path about its start): finite, 0 <= S <= 65.535; time scale: finite, 0.001 <= S <= 65.535 (the range the
  device's command encodes, 1/1000 steps in 16 bits; code 109 as the firmware).
- Rollout length: at most ``MAX_ROLLOUT_STEPS`` steps (663); the rollout is computed and written
  in blocks, so memory does not grow with the length.
- Force: a skill's rollout must be finite and its peak |f_hat| at most the force limit (50 N by
  default, the device's default ``force_max_N``); a goal scale multiplies the force exactly, so a
  run at goal scale S needs S * peak <= limit (662).
- Path: the force a y path asks of the law in perfect tracking, m_d*|y_d''| (the law's
  feed-forward; periodic: ramped in and out as the executor runs it), at most the force limit: a path
  the axis cannot follow saturates the command and latches FLT_SLEW_LIMIT (662).
- Stiffness: a skill's nominal stiffness at most the device's stiffness limit (read from the
  device, DID 0x0140), above which its force loop does not track (690); ``fit`` accepts any.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from .. import wire as W
from ..errors import (
    ERR_SKILL_PEAK,
    ERR_SKILL_STIFFNESS,
    FsError,
    ParamError,
)
from .scales import (  # noqa: F401  (re-exported: every limit a command checks)
    GOAL_SCALE_MAX,
    MAX_ROLLOUT_STEPS,
    PATH_SCALE_MAX,
    TIME_SCALE_MAX,
    TIME_SCALE_MIN,
    check_path_scale,
    check_scales,
    check_steps,
)

if TYPE_CHECKING:
    from .skill import Skill

#: The device's default |force command| limit (its force_max_N).
FORCE_LIMIT_N = W.FORCE_LIMIT_N


def check_force_limit(force_limit_N: float) -> None:
    """A usable force limit: finite and > 0 (ParamError 110)."""
    from ..errors import ERR_LIMIT_INVALID

    if not (math.isfinite(force_limit_N) and force_limit_N > 0.0):
        raise ParamError(ERR_LIMIT_INVALID, f"force limit must be finite and > 0 N: {force_limit_N:g}")


def skill_peak_N(skill: Skill, time_scale: float = 1.0) -> float:
    """max |f_hat| of the skill's rollout at goal 1 (inf when the rollout is not finite); a
    periodic skill: over one cycle from its state on the cycle."""
    from .dmp import rollout_peak

    if skill.periodic:
        import numpy as np

        from .periodic import rollout as periodic_rollout

        _, f = periodic_rollout(skill, cycles=1.0, time_scale=time_scale)
        return float(np.max(np.abs(f))) if np.all(np.isfinite(f)) else math.inf

    return rollout_peak(skill, time_scale=time_scale)


def peak_problem(peak_N: float, goal_scale: float, force_limit_N: float) -> str:
    """'' when goal_scale * peak is finite and within the limit, else what is wrong (one phrase)."""
    if not math.isfinite(peak_N):
        return "its rollout is not finite"
    if goal_scale * peak_N > force_limit_N:
        at = f" at goal scale {goal_scale:g}" if goal_scale != 1.0 else ""
        return (
            f"its rollout peaks at {goal_scale * peak_N:.4g} N{at}, above the force limit {force_limit_N:g} N"
        )
    return ""


def check_skill_force(
    skill: Skill,
    name: str,
    goal_scale: float = 1.0,
    time_scale: float = 1.0,
    force_limit_N: float = FORCE_LIMIT_N,
) -> float:
    """The skill's peak at goal 1; FsError 662 if its rollout at goal_scale is not finite or above
    the limit."""
    check_scales(goal_scale, time_scale)
    check_force_limit(force_limit_N)
    peak = skill_peak_N(skill, time_scale)
    problem = peak_problem(peak, goal_scale, force_limit_N)
    if problem:
        raise FsError(ERR_SKILL_PEAK, f"skill {name}: {problem}")
    return peak


def check_skill_stiffness(
    skill: Skill, name: str, limit_Npm: float, node: int, outcome: str = "nothing was sent"
) -> None:
    """FsError 690 if the skill's nominal stiffness is above the device's limit ``limit_Npm``."""
    if not skill.stiffness_Npm <= limit_Npm:
        raise FsError(
            ERR_SKILL_STIFFNESS,
            f"{name}: nominal stiffness {skill.stiffness_Npm:.4g} N/m is above the stiffness limit "
            f"{limit_Npm:.4g} N/m of node {node} (its force loop does not track stiffer objects); {outcome}",
        )


def path_peak_N(skill: Skill, path_scale: float = 1.0, time_scale: float = 1.0) -> float:
    """m_d * max |y_d''| of the skill's y path at the path and time scales (0 without one, inf when
    not finite): the force its acceleration alone asks of the law; a periodic path over three
    cycles as the device runs it (ramped in over the first, out over the last)."""
    if skill.y_weights is None or path_scale == 0.0:
        return 0.0
    import numpy as np

    if skill.periodic:
        from .periodic import rollout_path as periodic_path

        _, y = periodic_path(
            skill, cycles=3.0, path_scale=path_scale, time_scale=time_scale, ramp_in=True, ramp_out=True
        )
    else:
        from .dmp import rollout_path

        _, y = rollout_path(skill, time_scale=time_scale, path_scale=path_scale)
    if not np.all(np.isfinite(y)):
        return math.inf
    acc = np.diff(y, 2) / (skill.dt_s * skill.dt_s)
    return skill.m_d_kg * float(np.max(np.abs(acc))) if acc.size else 0.0


def path_problem(peak_N: float, path_scale: float, force_limit_N: float) -> str:
    """'' when the y path's demand peak_N (path_peak_N at path_scale) is within the limit, else
    what is wrong and the largest path scale that is (one phrase)."""
    if not math.isfinite(peak_N):
        return "its y path's rollout is not finite"
    if peak_N <= force_limit_N:
        return ""
    at = f" at path scale {path_scale:g}" if path_scale != 1.0 else ""
    return (
        f"its y path asks {peak_N:.4g} N (m_d*|y''|){at}, above the force limit {force_limit_N:g} N; "
        f"largest path scale {path_scale * force_limit_N / peak_N:.4g}"
    )

"""Errors of the host package, each with a stable number.

Codes 1xx-3xx are the firmware's (firmware/base/fs_status.h): a skill refused here is refused
there with the same number. Codes 6xx are host-only (demonstration files and fitting); the firmware
never sees a demonstration.
"""

from __future__ import annotations

import sys

# Every numbered code (1xx-3xx as the firmware's fs_status.h, 5xx faults, 6xx host only, ...) is
# generated from firmware/base/codes.toml into forceskill.codes and re-exported here, so
# `errors.ERR_SKILL_CRC` is the firmware's FS_ERR_SKILL_CRC; docs/codes.md lists them all.
from .codes import *  # noqa: F403
from .codes import DEVICE_FAULTS


def fault_text(code: int) -> str:
    """'500 (host silence)' for a device fault code, 'none' for 0."""
    if code == 0:
        return "none"
    return f"{code} ({DEVICE_FAULTS.get(code, 'unknown fault')})"


class FsError(Exception):
    """A refusal with a stable number (``code``) and a one-line message naming the problem and value."""

    def __init__(self, code: int, message: str) -> None:
        super().__init__(message)
        self.code = int(code)
        self.message = " ".join(str(message).split())

    def __str__(self) -> str:
        return self.message


class ParamError(FsError):
    """Gains, stiffness, scales or fit options that give an invalid or unstable system (1xx, 610)."""


class SkillError(FsError):
    """A corrupt or inconsistent skill image (2xx)."""


class DemoError(FsError):
    """A demonstration that cannot be learned from (60x, 611)."""


def stdout_closed() -> bool:
    """True when standard output is a pipe whose reader has gone (``forceskill status | head -1``
    after head's first line): the pipe then reports an error condition to poll()."""
    try:
        fd = sys.stdout.fileno()
    except (AttributeError, ValueError, OSError):  # replaced or closed (a test's capture)
        return False
    import select

    if not hasattr(select, "poll"):
        return False
    p = select.poll()
    p.register(fd, 0)  # POLLERR and POLLHUP are reported whatever the mask
    return any(ev & select.POLLERR for _, ev in p.poll(0))

"""Errors of the host package, each with a stable number.

Codes 1xx and 2xx are the firmware's (firmware/core/fs_status.h): a skill refused here is refused
there with the same number. Codes 6xx are host-only (demonstration files and fitting); the firmware
never sees a demonstration.
"""
from __future__ import annotations

# 1xx: gains and parameters (fs_status.h)
ERR_NULL_ARG = 100
ERR_NOT_FINITE = 101
ERR_MASS_NONPOSITIVE = 102
ERR_KD_LE_MD = 103
ERR_BETA_NONPOSITIVE = 104
ERR_PHASE_NOT_MONOTONE = 105
ERR_STIFFNESS_NONPOSITIVE = 106
ERR_GAIN_NEGATIVE = 107
ERR_DT_INVALID = 108
ERR_SCALE_INVALID = 109

# 2xx: skill image (fs_status.h)
ERR_SKILL_TOO_SHORT = 200
ERR_SKILL_MAGIC = 201
ERR_SKILL_VERSION = 202
ERR_SKILL_LENGTH = 203
ERR_SKILL_CRC = 204
ERR_SKILL_KERNELS = 205
ERR_SKILL_NOT_FINITE = 206
ERR_SKILL_RANGE = 207
ERR_SKILL_CENTRES = 208
ERR_SKILL_GAINS = 209
ERR_SKILL_UNSUPPORTED = 210
ERR_SKILL_HEADER_SIZE = 211

ERR_LIMIT_INVALID = 110
ERR_FORCE_GAIN_INERTIA = 112   # k_f*m_v/m_d >= 1: the force loop feeds back the object's inertia

# 3xx: fixed-point conversion (fs_status.h)
ERR_FIXED_OVERFLOW = 300
ERR_FIXED_WINDOW = 301
ERR_FIXED_STEP = 302
ERR_FIXED_CONFIG = 303

#: 5xx: latched device faults (firmware/safety/flt_codes.h), as the status and emergency frames
#: report them. tests/host/test_error_codes.py checks this table against the C header.
DEVICE_FAULTS: dict[int, str] = {
    500: "host silence",
    501: "bus-off",
    502: "sensor reading not finite",
    503: "sensor reading out of range",
    504: "force sensor stuck",
    505: "force sensor spike",
    506: "encoder jump",
    507: "contact force above limit",
    508: "force slew limit held",
    509: "outside workspace",
    510: "velocity above limit",
    511: "tick overrun",
    512: "skill invalid",
    513: "force command not finite",
    514: "storage error",
}


def fault_text(code: int) -> str:
    """'500 (host silence)' for a device fault code, 'none' for 0."""
    if code == 0:
        return "none"
    return f"{code} ({DEVICE_FAULTS.get(code, 'unknown fault')})"


# 6xx: host only -- demonstrations and fitting
ERR_DEMO_FILE = 600          # file missing, unreadable, or no reader for its suffix
ERR_DEMO_FORMAT = 601        # no header row, a non-numeric cell, ragged rows
ERR_DEMO_COLUMN = 602        # a requested column is not in the file
ERR_DEMO_TOO_SHORT = 603     # shorter than 0.5 s or fewer than 100 samples
ERR_DEMO_NOT_FINITE = 604    # NaN or infinite sample
ERR_DEMO_TIME = 605          # time not strictly increasing
ERR_DEMO_GAP = 606           # a sampling gap above 1.5x the median step
ERR_DEMO_ZERO_FORCE = 607    # the learned force is constant zero
ERR_FIT_ARGS = 610           # kernels, method, end policy or dt out of range
ERR_FIT_GOAL = 611           # g <= 0 or tiny: no net push to phase-normalise
ERR_FIT_NUMERIC = 612        # the regression produced a non-finite weight
ERR_GAINS_FILE = 613         # --gains file unreadable, not TOML, an unknown key or a non-number
ERR_IO = 620                 # an output file could not be written
ERR_REPORT = 621             # a step of `forceskill report` failed (simulator, fit, execution)
# 63x: the CAN link (forceskill.link and the commands on it)
ERR_LINK_BUS = 630           # interface, channel, port or bus options unusable
ERR_LINK_NO_RESPONSE = 631   # the node sent nothing within the timeout
ERR_LINK_NEGATIVE = 632      # the device refused a request (UDS negative response)
ERR_LINK_VERIFY = 633        # read-back after upload differs
ERR_LINK_LOG = 634           # a CAN log without the device's telemetry
ERR_LINK_TIMEOUT = 635       # the device stopped answering during an operation
ERR_LINK_STATE = 636         # the device is not in the state the operation needs (e.g. FAULT)
ERR_LINK_ARGS = 637          # a bad option value (slot, sequence, scale)


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

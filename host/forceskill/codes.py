"""Every numbered code and identifier of forceskill.

Generated from firmware/base/codes.toml by tools/gen_codes.py; do not edit.
"""
from __future__ import annotations

# Core: parameters, skill image, fixed point (1xx-3xx)
ERR_NULL_ARG = 100  # a required pointer was NULL
ERR_NOT_FINITE = 101  # a parameter is NaN or infinite
ERR_MASS_NONPOSITIVE = 102  # m_d <= 0
ERR_KD_LE_MD = 103  # k_d <= m_d, so alpha <= 0 (unstable)
ERR_BETA_NONPOSITIVE = 104  # derived beta <= 0 (unstable)
ERR_PHASE_NOT_MONOTONE = 105  # beta > alpha/4: the phase overshoots
ERR_STIFFNESS_NONPOSITIVE = 106  # k <= 0
ERR_GAIN_NEGATIVE = 107  # a gain that must be >= 0 is negative
ERR_DT_INVALID = 108  # dt <= 0 or not finite
ERR_SCALE_INVALID = 109  # goal/time scale not finite, or time scale <= 0
ERR_LIMIT_INVALID = 110  # a controller limit (force_max, integral_max) is <= 0
ERR_FORCE_GAIN_INERTIA = 112  # k_f*m_v/m_d >= 1: the force loop feeds back the object's inertia
ERR_SKILL_TOO_SHORT = 200  # fewer bytes than the fixed header
ERR_SKILL_MAGIC = 201  # magic is not "FSKL"
ERR_SKILL_VERSION = 202  # unsupported format version
ERR_SKILL_LENGTH = 203  # length field disagrees with the buffer or with N
ERR_SKILL_CRC = 204  # CRC-32 mismatch
ERR_SKILL_KERNELS = 205  # N == 0 or N > DMP_MAX_KERNELS
ERR_SKILL_NOT_FINITE = 206  # a stored value is NaN or infinite
ERR_SKILL_RANGE = 207  # a value outside its physical range (dt, tau, T, widths)
ERR_SKILL_CENTRES = 208  # centres not strictly increasing in [0, 1]
ERR_SKILL_GAINS = 209  # stored alpha/beta/gamma disagree with the stored gains
ERR_SKILL_UNSUPPORTED = 210  # a flag this firmware does not implement
ERR_SKILL_HEADER_SIZE = 211  # header_size field is not the v1 header size
ERR_SKCHK_RANGE = 220  # a parameter outside the device's documented range (skill_check.h)
ERR_SKCHK_STEP = 221  # dt/(tau*time_scale) too large for the DMP's Euler step
ERR_SKCHK_NOT_FINITE = 222  # the rollout at goal scale 1 is not finite
ERR_SKCHK_PEAK = 223  # the rollout at goal scale 1 peaks above the force limit
ERR_SKCHK_GOAL_SCALE = 224  # goal_scale * peak above the force limit: run refused
ERR_SKCHK_PATH = 225
ERR_SKCHK_PATH_SCALE = 226
ERR_SKCHK_STIFFNESS = 227
ERR_SKILL_KIND = 228
ERR_SKILL_PERIOD = 229  # periodic skill: its duration (the period) is not 2*pi*tau
ERR_SKILL_AMPLITUDE = 230  # periodic skill: amplitude not > 0
ERR_SKILL_PHASES = 231  # periodic skill: centres not strictly increasing in [0, 2*pi)
ERR_SKILL_NO_PERIODIC = 232  # a periodic skill on a device build that cannot run one
ERR_SKILL_CONTACT_WAIT = 233
ERR_SKILL_BAND = 234
ERR_FIXED_OVERFLOW = 300  # a value does not fit its fixed-point format
ERR_FIXED_WINDOW = 301  # more kernels overlap than the fixed build evaluates
ERR_FIXED_STEP = 302  # dt/tau too small or too large for Q1.31
ERR_FIXED_CONFIG = 303  # a controller gain/limit does not fit Q16.16

SKILL_STATUS_TEXT: dict[int, str] = {
    200: 'image too short',
    201: 'bad magic',
    202: 'unsupported format version',
    203: 'length mismatch',
    204: 'CRC-32 mismatch',
    205: 'bad kernel count',
    206: 'non-finite value',
    207: 'value out of range',
    208: 'bad centres',
    209: 'gains inconsistent with alpha/beta/gamma',
    210: 'unsupported flag',
    211: 'bad header size',
    220: "parameter outside the device's range",
    221: 'Euler step too large',
    222: 'rollout not finite',
    223: 'rollout above the force limit',
    224: 'goal scale above the force limit',
    225: "y path outside the device's y range",
    226: "path scale outside the device's y range",
    227: "stiffness above the device's limit",
    228: 'unknown skill kind',
    229: 'period disagrees with tau',
    230: 'bad amplitude',
    231: 'bad phase centres',
    232: 'periodic skills not supported by this device',
    233: 'bad contact-wait parameters',
    234: 'bad demonstrated band',
}

# Protocol: E2E protection, ISO-TP (4xx)
PROTO_ERR_E2E_CRC = 400  # safety frame CRC-8 mismatch
PROTO_ERR_E2E_COUNTER = 401  # rolling counter repeated (stale or replayed frame)
PROTO_ERR_DLC = 402  # frame shorter than its DBC length
PROTO_ERR_ISOTP_TIMEOUT_BS = 410  # sender: no flow control within N_Bs
PROTO_ERR_ISOTP_TIMEOUT_CR = 411  # receiver: no consecutive frame within N_Cr
PROTO_ERR_ISOTP_WRONG_SN = 412  # receiver: consecutive frame out of sequence
PROTO_ERR_ISOTP_OVERFLOW = 413  # message longer than the buffer (FC overflow sent/received)
PROTO_ERR_ISOTP_UNEXPECTED = 414  # frame type not valid in the current state (ignored/aborted)
PROTO_ERR_ISOTP_BUSY = 415  # a transmission is already in progress
PROTO_ERR_ISOTP_WFT = 416  # too many FC WAIT frames
PROTO_ERR_ISOTP_FORMAT = 417  # malformed PCI (length 0, SF too long, reserved type)
PROTO_ERR_WIRE_LENGTH = 418  # a UDS payload of a length its record (wire.toml) does not allow
PROTO_ERR_WIRE_RANGE = 419  # a UDS payload field outside its range (wire.toml)

# Safety: latched device faults (500-519)
FLT_HOST_SILENCE = 500  # no host heartbeat/command for wdg timeout (default 100 ms)
FLT_BUS_OFF = 501  # CAN controller reported bus-off
FLT_SENSOR_NAN = 502  # a position, velocity or force reading is NaN or infinite
FLT_SENSOR_RANGE = 503  # a reading outside the sensor's physical range
FLT_SENSOR_STUCK = 504  # non-zero force reading bit-identical for sen stuck_ticks
FLT_SENSOR_SPIKE = 505  # force reading changed by more than spike_N in one tick
FLT_ENCODER_JUMP = 506  # position changed by more than jump_m in one tick
FLT_FORCE_LIMIT = 507  # measured contact force above contact_force_max_N
FLT_SLEW_LIMIT = 508  # command request held at the slew limit for slew_fault_ticks
FLT_WORKSPACE = 509  # measured position outside the workspace
FLT_VELOCITY = 510  # |measured velocity| above vel_max_mps
FLT_TICK_OVERRUN = 511  # a control tick did not finish before the next one was due
FLT_SKILL_INVALID = 512  # the active skill failed validation or could not be loaded
FLT_CMD_NOT_FINITE = 513  # the control law produced a NaN or infinite force request
FLT_STORAGE = 514  # flash error while the device was running (erase/program/read)
FLT_BAND = 515

DEVICE_FAULTS: dict[int, str] = {
    500: 'host silence',
    501: 'bus-off',
    502: 'sensor reading not finite',
    503: 'sensor reading out of range',
    504: 'force sensor stuck',
    505: 'force sensor spike',
    506: 'encoder jump',
    507: 'contact force above limit',
    508: 'force slew limit held',
    509: 'outside workspace',
    510: 'velocity above limit',
    511: 'tick overrun',
    512: 'skill invalid',
    513: 'force command not finite',
    514: 'storage error',
    515: 'outside the demonstrated band',
}

# Safety configuration (520-529: saf_config_validate and the modules' *_config_validate)
SAF_ERR_NULL_ARG = 520  # a required pointer was NULL
SAF_ERR_NOT_FINITE = 521  # a limit is NaN or infinite
SAF_ERR_NONPOSITIVE = 522  # a limit that must be > 0 is <= 0
SAF_ERR_WORKSPACE = 523  # workspace or sensor range with min >= max
SAF_ERR_TIMEOUT = 524  # host-silence timeout outside 20..500 ms
SAF_ERR_RAMP = 525
SAF_ERR_FORCE_MAX = 526  # force_max above the hardware ceiling LIM_FORCE_CEILING_N

# Storage: slot records (530-549, nvm_*)
NVM_ERR_NULL_ARG = 530  # a required pointer was NULL
NVM_ERR_SLOT = 531  # slot index out of range
NVM_ERR_TOO_LARGE = 532  # payload larger than a slot holds
NVM_ERR_EMPTY = 533  # the slot holds no valid record
NVM_ERR_FLASH = 534  # the flash HAL reported an erase/program/read failure
NVM_ERR_VERIFY = 535  # read-back after programming differs from what was written
NVM_ERR_REC_MAGIC = 536  # record magic wrong (or erased flash)
NVM_ERR_REC_VERSION = 537  # unsupported record format version
NVM_ERR_REC_LENGTH = 538  # record length field impossible for the buffer/sector
NVM_ERR_REC_CRC = 539  # record CRC-32 mismatch
NVM_ERR_REC_UNCOMMITTED = 540  # commit word not written: an interrupted write
NVM_ERR_GEOMETRY = 541  # flash geometry unusable (sector too small, too few sectors)
NVM_ERR_BUFFER = 542  # caller's buffer too small for the record
NVM_ERR_PAYLOAD = 543  # payload rejected by the content check (e.g. skill_parse)

# Security (550-569, sec_*): results that are not UDS negative response codes
SEC_ERR_NULL_ARG = 550  # a required pointer was NULL
SEC_ERR_RNG = 551  # the random source failed or returned a degenerate seed
SEC_ERR_CONFIG = 552  # configuration invalid (secret length, attempts, delays)
SEC_ERR_MAC = 553
SEC_ERR_REPLAY = 554
SEC_ERR_NO_KEY = 555
SEC_ERR_FRESHNESS = 556
SEC_ERR_EXECUTE_OPTIONS = 557
SEC_ERR_SESSION_OWNER = 558
SEC_ERR_STALE = 559
SEC_ERR_KEY_SEQUENCE = 560

# Host: demonstrations, fitting, files, the CAN link (6xx)
ERR_DEMO_FILE = 600  # file missing, unreadable, or no reader for its suffix
ERR_DEMO_FORMAT = 601  # no header row, a non-numeric cell, ragged rows
ERR_DEMO_COLUMN = 602  # a requested column is not in the file
ERR_DEMO_TOO_SHORT = 603  # shorter than 0.5 s or fewer than 100 samples
ERR_DEMO_NOT_FINITE = 604  # NaN or infinite sample
ERR_DEMO_TIME = 605  # time not strictly increasing
ERR_DEMO_GAP = 606  # a sampling gap longer than --max-gap (100 ms)
ERR_DEMO_ZERO_FORCE = 607  # the learned force is constant zero
ERR_FIT_ARGS = 610  # kernels, method, end policy or dt out of range
ERR_FIT_GOAL = 611  # g <= 0 or tiny: no net push to phase-normalise
ERR_FIT_NUMERIC = 612  # the regression produced a non-finite weight
ERR_GAINS_FILE = 613  # a --gains file unreadable, not TOML, or with an unknown or non-numeric key
ERR_IO = 620  # an output file could not be written
ERR_REPORT = 621  # a step of `forceskill report` failed (simulator, fit, execution)
ERR_LINK_BUS = 630  # interface, channel, port or bus options unusable
ERR_LINK_NO_RESPONSE = 631  # the node sent nothing within the timeout
ERR_LINK_NEGATIVE = 632  # the device refused a request (UDS negative response)
ERR_LINK_VERIFY = 633  # read-back after upload differs
ERR_LINK_LOG = 634  # a CAN log without the device's telemetry
ERR_LINK_TIMEOUT = 635  # the device stopped answering during an operation
ERR_LINK_STATE = 636  # the device is not in the state the operation needs (e.g. FAULT)
ERR_LINK_ARGS = 637  # a bad option value (slot, sequence, scale)
ERR_FLASH_NOT_CONFIRMED = 638
ERR_FIT_TOLERANCE = 640  # no kernel count up to the cap reaches --max-error
ERR_FIT_INACCURATE = 641  # approximation error above 10 % without --max-error
ERR_DEMO_DURATION = 642  # the recording is longer than the skill's 3,600 s limit
ERR_DEMO_TARE = 643  # --tare: no quiet stretch before contact, or a bad window
ERR_READ_ARGS = 644  # a reader option out of range (time unit, rate, axis, sign, scale, gap)
ERR_DEMO_TOPIC = 645  # a bag without the requested topic, or of another message type
ERR_READER_MISSING = 646  # the reader for this format needs a package that is not installed
ERR_OUTPUT_IS_INPUT = 660  # an output is one of the inputs (same file), or given twice
ERR_OUTPUT_SPECIAL = 661  # an output is a device, FIFO, directory or system file
ERR_SKILL_PEAK = 662  # a rollout not finite or peaking above the force limit
ERR_ROLLOUT_CAP = 663  # rollout steps above the cap
ERR_LOG_FORMAT = 664  # no CAN log writer for the output's suffix
ERR_RUN_FAULT = 665  # the device faulted during a run or a recording
ERR_CLEAR_BLOCKED = 666  # a fault cannot be cleared: its cause persists
ERR_UNEXPECTED = 667  # an error no check foresaw (e.g. from a library), reported as one line
ERR_WIRE_LENGTH = 668  # a device payload of a length its record (wire.toml) does not allow
ERR_WIRE_RANGE = 669
ERR_PERIODIC_STROKES = 680  # fit --periodic: no period found, or fewer than two steady strokes
ERR_PERIODIC_GOAL = 681  # fit --periodic: the strokes' mean force is not a push
ERR_PERIODIC_AMPLITUDE = 682  # fit --periodic: the strokes have no amplitude to learn
ERR_PERIODIC_ARGS = 683
ERR_SKILL_STIFFNESS = 690
ERR_LOG_UNREADABLE = 691
ERR_TELEMETRY_GAP = 692
ERR_LINK_PROTOCOL = 693
ERR_LINK_AUTH = 694

# Firmware image and update (700-729, firmware/boot)
BOOT_ERR_TRUNCATED = 700  # fewer bytes than header + payload_length + tag
BOOT_ERR_MAGIC = 701  # magic is not "FSFW"
BOOT_ERR_FORMAT = 702  # format version, header size, flags or reserved bytes wrong
BOOT_ERR_TARGET = 703  # image built for another target
BOOT_ERR_TOO_LARGE = 704  # image larger than a slot
BOOT_ERR_HASH = 705  # SHA-256 of the payload differs from the header's
BOOT_ERR_TAG = 706  # HMAC-SHA256 tag wrong: not authorised for this device
BOOT_ERR_DOWNGRADE = 707  # older than the running image and not forced
BOOT_ERR_SKILL_FORMAT = 708  # stored skills in a format the image can neither read nor migrate
BOOT_ERR_CONFIG_FORMAT = 709  # stored configuration likewise
BOOT_ERR_NO_IMAGE = 710  # no slot holds a bootable, authorised image
BOOT_ERR_FLASH = 711  # the flash HAL refused a read, erase or write
BOOT_ERR_ARG = 712  # NULL pointer or slot index out of range
FWU_ERR_LOCKED = 720  # not in the programming session with SecurityAccess unlocked
FWU_ERR_SEQUENCE = 722  # service out of order (no download active, exit too early, ...)
FWU_ERR_BLOCK_COUNTER = 723  # TransferData block sequence counter not the expected one
FWU_ERR_OVERRUN = 724  # more data than announced in RequestDownload
FWU_ERR_TEST_PENDING = 725  # running image not yet confirmed: its fallback must not be overwritten
FWU_ERR_RANGE = 726  # address, size or data format of RequestDownload not accepted

# Host image tools (730-749, `forceskill image`, `forceskill flash`)
ERR_IMAGE_KEY = 730  # key or secret file missing, unreadable, not hex, or of the wrong length
ERR_IMAGE_ARGS = 731  # bad version string, target name, build id, format or input file

# CAN identifiers of node 0; node n uses id + n
NODE_MAX = 15
DEFAULT_NODE = 0
CAN_ID_EMERGENCY = 0x080  # device: once on every new fault
CAN_ID_HOST_COMMAND = 0x100  # host: one command per valid frame
CAN_ID_HOST_HEARTBEAT = 0x110  # host: heartbeat while it drives the device
CAN_ID_STATUS = 0x180  # device: status every 10 ms
CAN_ID_TELEM_POS = 0x190  # device: telemetry, position part
CAN_ID_TELEM_FORCE = 0x1A0  # device: telemetry, force part
UDS_REQUEST_BASE = 0x600  # host -> device UDS request (ISO-TP)
UDS_RESPONSE_BASE = 0x680  # device -> host UDS response (ISO-TP)
UDS_REQUEST_2_BASE = 0x640  # second tester -> device UDS request (ISO-TP)
UDS_RESPONSE_2_BASE = 0x6C0  # device -> second tester UDS response (ISO-TP)

# UDS identifiers of the device
DID_SW_VERSION = 0xF189  # software version, ASCII
DID_VERSIONS = 0xF1A0  # proto major, minor, skill format, max kernels u16, slots u8
DID_GAINS_X = 0x0100  # gains x: m_d, k_d, k_p, k_f, k_i (f32 x5)
DID_GAINS_Y = 0x0101  # gains y
DID_LIMITS_X = 0x0110  # limits x: force_max, slew_max, pos_min, pos_max, vel_max, contact_max
DID_LIMITS_Y = 0x0111  # limits y
DID_COMM = 0x0120  # telemetry period ms u8, host timeout ms u16
DID_OBJECT = 0x0130  # use_model u8, m_v, d_v, k1, k2, layer, surface (f32 x6)
DID_SLOT_DIR = 0x0200  # n u8; per slot: valid u8, length u32, crc u32, N u16, T f32, end u8
DID_LAST_TRANSFER = 0x0201  # status code u16 of the last download (0 ok)
DID_DEVICE_STATE = 0x0300  # state u8, fault u16, slot u8, step u8, tick u32
DID_STIFFNESS_MAX = 0x0140  # highest nominal skill stiffness the device accepts, N/m (f32)
DID_FAULT_CAUSES = 0x0301  # latched mask u32, causes present mask u32 (bit n: fault 500+n)
DID_MOTION_KEY = 0x0302
DID_AUTH_STATS = 0x0303
DID_CONTACT_WAIT = 0x0304
DID_BAND = 0x0305
DID_FWU_STATUS = 0xF1B0  # update status: FWU_STATUS_LEN bytes, see fwu_status()
RID_RUN_SKILL = 0x0201  # start: slot u8, goal_scale u16 (1e-3), time_scale u16 (1e-3), end u8
RID_RUN_SEQUENCE = 0x0202
RID_SELF_TEST = 0x0203  # start: runs the checks; results: status u8, code u16
RID_CLEAR_FAULTS = 0x0204  # start: clear latched faults (refused while a cause persists)
RID_ERASE_SLOT = 0xFF00  # start: slot u8 (security level 1)
RID_MARK_TEST = 0x0F01  # start; option u8: bit 0 allow downgrade
RID_CONFIRM = 0x0F02  # start; the running image confirms itself
SEC_LEVEL_WRITE = 0x01  # skills, gains, limits: extended or programming session
SEC_LEVEL_FIRMWARE = 0x03  # firmware images: programming session only
DOWNLOAD_ADDRESS = 0xF0000000  # RequestDownload memoryAddress of "the inactive slot"

# UDS negative response codes the device answers
NRC_GENERAL_REJECT = 0x10  # generalReject
NRC_SERVICE_NOT_SUPPORTED = 0x11  # serviceNotSupported
NRC_SUBFUNCTION_NOT_SUPPORTED = 0x12  # subFunctionNotSupported
NRC_INCORRECT_LENGTH = 0x13  # incorrectMessageLengthOrInvalidFormat
NRC_RESPONSE_TOO_LONG = 0x14  # responseTooLong
NRC_BUSY_REPEAT_REQUEST = 0x21  # busyRepeatRequest
NRC_CONDITIONS_NOT_CORRECT = 0x22  # conditionsNotCorrect
NRC_REQUEST_SEQUENCE_ERROR = 0x24  # requestSequenceError
NRC_REQUEST_OUT_OF_RANGE = 0x31  # requestOutOfRange
NRC_SECURITY_ACCESS_DENIED = 0x33  # securityAccessDenied
NRC_INVALID_KEY = 0x35  # invalidKey
NRC_EXCEEDED_ATTEMPTS = 0x36  # exceededNumberOfAttempts
NRC_DELAY_NOT_EXPIRED = 0x37  # requiredTimeDelayNotExpired
NRC_UPLOAD_DOWNLOAD_NOT_ACCEPTED = 0x70  # uploadDownloadNotAccepted
NRC_TRANSFER_SUSPENDED = 0x71  # transferDataSuspended
NRC_PROGRAMMING_FAILURE = 0x72  # generalProgrammingFailure
NRC_WRONG_BLOCK_COUNTER = 0x73  # wrongBlockSequenceCounter
NRC_RESPONSE_PENDING = 0x78  # requestCorrectlyReceived-ResponsePending
NRC_SUBFUNCTION_NOT_IN_SESSION = 0x7E  # subFunctionNotSupportedInActiveSession
NRC_SERVICE_NOT_IN_SESSION = 0x7F  # serviceNotSupportedInActiveSession
NRC_FW_HEADER = 0xF0  # vehicleManufacturerSpecific
NRC_FW_TARGET = 0xF1  # vehicleManufacturerSpecific
NRC_FW_TRUNCATED = 0xF2  # vehicleManufacturerSpecific
NRC_FW_HASH = 0xF3  # vehicleManufacturerSpecific
NRC_FW_TAG = 0xF4  # vehicleManufacturerSpecific
NRC_FW_DOWNGRADE = 0xF5  # vehicleManufacturerSpecific
NRC_FW_SKILL_FORMAT = 0xF6  # vehicleManufacturerSpecific
NRC_FW_CONFIG_FORMAT = 0xF7  # vehicleManufacturerSpecific

# Firmware image and update (700-729, firmware/boot): the negative response code of each status (others: 0x10)
BOOT_STATUS_NRC: dict[int, int] = {
    700: 0xF2,
    701: 0xF0,
    702: 0xF0,
    703: 0xF1,
    704: 0x70,
    705: 0xF3,
    706: 0xF4,
    707: 0xF5,
    708: 0xF6,
    709: 0xF7,
    711: 0x72,
    720: 0x33,
    722: 0x24,
    723: 0x73,
    724: 0x71,
    725: 0x22,
    726: 0x31,
}

__all__ = [
    'ERR_NULL_ARG',
    'ERR_NOT_FINITE',
    'ERR_MASS_NONPOSITIVE',
    'ERR_KD_LE_MD',
    'ERR_BETA_NONPOSITIVE',
    'ERR_PHASE_NOT_MONOTONE',
    'ERR_STIFFNESS_NONPOSITIVE',
    'ERR_GAIN_NEGATIVE',
    'ERR_DT_INVALID',
    'ERR_SCALE_INVALID',
    'ERR_LIMIT_INVALID',
    'ERR_FORCE_GAIN_INERTIA',
    'ERR_SKILL_TOO_SHORT',
    'ERR_SKILL_MAGIC',
    'ERR_SKILL_VERSION',
    'ERR_SKILL_LENGTH',
    'ERR_SKILL_CRC',
    'ERR_SKILL_KERNELS',
    'ERR_SKILL_NOT_FINITE',
    'ERR_SKILL_RANGE',
    'ERR_SKILL_CENTRES',
    'ERR_SKILL_GAINS',
    'ERR_SKILL_UNSUPPORTED',
    'ERR_SKILL_HEADER_SIZE',
    'ERR_SKCHK_RANGE',
    'ERR_SKCHK_STEP',
    'ERR_SKCHK_NOT_FINITE',
    'ERR_SKCHK_PEAK',
    'ERR_SKCHK_GOAL_SCALE',
    'ERR_SKCHK_PATH',
    'ERR_SKCHK_PATH_SCALE',
    'ERR_SKCHK_STIFFNESS',
    'ERR_SKILL_KIND',
    'ERR_SKILL_PERIOD',
    'ERR_SKILL_AMPLITUDE',
    'ERR_SKILL_PHASES',
    'ERR_SKILL_NO_PERIODIC',
    'ERR_SKILL_CONTACT_WAIT',
    'ERR_SKILL_BAND',
    'ERR_FIXED_OVERFLOW',
    'ERR_FIXED_WINDOW',
    'ERR_FIXED_STEP',
    'ERR_FIXED_CONFIG',
    'SKILL_STATUS_TEXT',
    'PROTO_ERR_E2E_CRC',
    'PROTO_ERR_E2E_COUNTER',
    'PROTO_ERR_DLC',
    'PROTO_ERR_ISOTP_TIMEOUT_BS',
    'PROTO_ERR_ISOTP_TIMEOUT_CR',
    'PROTO_ERR_ISOTP_WRONG_SN',
    'PROTO_ERR_ISOTP_OVERFLOW',
    'PROTO_ERR_ISOTP_UNEXPECTED',
    'PROTO_ERR_ISOTP_BUSY',
    'PROTO_ERR_ISOTP_WFT',
    'PROTO_ERR_ISOTP_FORMAT',
    'PROTO_ERR_WIRE_LENGTH',
    'PROTO_ERR_WIRE_RANGE',
    'FLT_HOST_SILENCE',
    'FLT_BUS_OFF',
    'FLT_SENSOR_NAN',
    'FLT_SENSOR_RANGE',
    'FLT_SENSOR_STUCK',
    'FLT_SENSOR_SPIKE',
    'FLT_ENCODER_JUMP',
    'FLT_FORCE_LIMIT',
    'FLT_SLEW_LIMIT',
    'FLT_WORKSPACE',
    'FLT_VELOCITY',
    'FLT_TICK_OVERRUN',
    'FLT_SKILL_INVALID',
    'FLT_CMD_NOT_FINITE',
    'FLT_STORAGE',
    'FLT_BAND',
    'DEVICE_FAULTS',
    'SAF_ERR_NULL_ARG',
    'SAF_ERR_NOT_FINITE',
    'SAF_ERR_NONPOSITIVE',
    'SAF_ERR_WORKSPACE',
    'SAF_ERR_TIMEOUT',
    'SAF_ERR_RAMP',
    'SAF_ERR_FORCE_MAX',
    'NVM_ERR_NULL_ARG',
    'NVM_ERR_SLOT',
    'NVM_ERR_TOO_LARGE',
    'NVM_ERR_EMPTY',
    'NVM_ERR_FLASH',
    'NVM_ERR_VERIFY',
    'NVM_ERR_REC_MAGIC',
    'NVM_ERR_REC_VERSION',
    'NVM_ERR_REC_LENGTH',
    'NVM_ERR_REC_CRC',
    'NVM_ERR_REC_UNCOMMITTED',
    'NVM_ERR_GEOMETRY',
    'NVM_ERR_BUFFER',
    'NVM_ERR_PAYLOAD',
    'SEC_ERR_NULL_ARG',
    'SEC_ERR_RNG',
    'SEC_ERR_CONFIG',
    'SEC_ERR_MAC',
    'SEC_ERR_REPLAY',
    'SEC_ERR_NO_KEY',
    'SEC_ERR_FRESHNESS',
    'SEC_ERR_EXECUTE_OPTIONS',
    'SEC_ERR_SESSION_OWNER',
    'SEC_ERR_STALE',
    'SEC_ERR_KEY_SEQUENCE',
    'ERR_DEMO_FILE',
    'ERR_DEMO_FORMAT',
    'ERR_DEMO_COLUMN',
    'ERR_DEMO_TOO_SHORT',
    'ERR_DEMO_NOT_FINITE',
    'ERR_DEMO_TIME',
    'ERR_DEMO_GAP',
    'ERR_DEMO_ZERO_FORCE',
    'ERR_FIT_ARGS',
    'ERR_FIT_GOAL',
    'ERR_FIT_NUMERIC',
    'ERR_GAINS_FILE',
    'ERR_IO',
    'ERR_REPORT',
    'ERR_LINK_BUS',
    'ERR_LINK_NO_RESPONSE',
    'ERR_LINK_NEGATIVE',
    'ERR_LINK_VERIFY',
    'ERR_LINK_LOG',
    'ERR_LINK_TIMEOUT',
    'ERR_LINK_STATE',
    'ERR_LINK_ARGS',
    'ERR_FLASH_NOT_CONFIRMED',
    'ERR_FIT_TOLERANCE',
    'ERR_FIT_INACCURATE',
    'ERR_DEMO_DURATION',
    'ERR_DEMO_TARE',
    'ERR_READ_ARGS',
    'ERR_DEMO_TOPIC',
    'ERR_READER_MISSING',
    'ERR_OUTPUT_IS_INPUT',
    'ERR_OUTPUT_SPECIAL',
    'ERR_SKILL_PEAK',
    'ERR_ROLLOUT_CAP',
    'ERR_LOG_FORMAT',
    'ERR_RUN_FAULT',
    'ERR_CLEAR_BLOCKED',
    'ERR_UNEXPECTED',
    'ERR_WIRE_LENGTH',
    'ERR_WIRE_RANGE',
    'ERR_PERIODIC_STROKES',
    'ERR_PERIODIC_GOAL',
    'ERR_PERIODIC_AMPLITUDE',
    'ERR_PERIODIC_ARGS',
    'ERR_SKILL_STIFFNESS',
    'ERR_LOG_UNREADABLE',
    'ERR_TELEMETRY_GAP',
    'ERR_LINK_PROTOCOL',
    'ERR_LINK_AUTH',
    'BOOT_ERR_TRUNCATED',
    'BOOT_ERR_MAGIC',
    'BOOT_ERR_FORMAT',
    'BOOT_ERR_TARGET',
    'BOOT_ERR_TOO_LARGE',
    'BOOT_ERR_HASH',
    'BOOT_ERR_TAG',
    'BOOT_ERR_DOWNGRADE',
    'BOOT_ERR_SKILL_FORMAT',
    'BOOT_ERR_CONFIG_FORMAT',
    'BOOT_ERR_NO_IMAGE',
    'BOOT_ERR_FLASH',
    'BOOT_ERR_ARG',
    'FWU_ERR_LOCKED',
    'FWU_ERR_SEQUENCE',
    'FWU_ERR_BLOCK_COUNTER',
    'FWU_ERR_OVERRUN',
    'FWU_ERR_TEST_PENDING',
    'FWU_ERR_RANGE',
    'ERR_IMAGE_KEY',
    'ERR_IMAGE_ARGS',
    'NODE_MAX',
    'DEFAULT_NODE',
    'CAN_ID_EMERGENCY',
    'CAN_ID_HOST_COMMAND',
    'CAN_ID_HOST_HEARTBEAT',
    'CAN_ID_STATUS',
    'CAN_ID_TELEM_POS',
    'CAN_ID_TELEM_FORCE',
    'UDS_REQUEST_BASE',
    'UDS_RESPONSE_BASE',
    'UDS_REQUEST_2_BASE',
    'UDS_RESPONSE_2_BASE',
    'DID_SW_VERSION',
    'DID_VERSIONS',
    'DID_GAINS_X',
    'DID_GAINS_Y',
    'DID_LIMITS_X',
    'DID_LIMITS_Y',
    'DID_COMM',
    'DID_OBJECT',
    'DID_SLOT_DIR',
    'DID_LAST_TRANSFER',
    'DID_DEVICE_STATE',
    'DID_STIFFNESS_MAX',
    'DID_FAULT_CAUSES',
    'DID_MOTION_KEY',
    'DID_AUTH_STATS',
    'DID_CONTACT_WAIT',
    'DID_BAND',
    'DID_FWU_STATUS',
    'RID_RUN_SKILL',
    'RID_RUN_SEQUENCE',
    'RID_SELF_TEST',
    'RID_CLEAR_FAULTS',
    'RID_ERASE_SLOT',
    'RID_MARK_TEST',
    'RID_CONFIRM',
    'SEC_LEVEL_WRITE',
    'SEC_LEVEL_FIRMWARE',
    'DOWNLOAD_ADDRESS',
    'NRC_GENERAL_REJECT',
    'NRC_SERVICE_NOT_SUPPORTED',
    'NRC_SUBFUNCTION_NOT_SUPPORTED',
    'NRC_INCORRECT_LENGTH',
    'NRC_RESPONSE_TOO_LONG',
    'NRC_BUSY_REPEAT_REQUEST',
    'NRC_CONDITIONS_NOT_CORRECT',
    'NRC_REQUEST_SEQUENCE_ERROR',
    'NRC_REQUEST_OUT_OF_RANGE',
    'NRC_SECURITY_ACCESS_DENIED',
    'NRC_INVALID_KEY',
    'NRC_EXCEEDED_ATTEMPTS',
    'NRC_DELAY_NOT_EXPIRED',
    'NRC_UPLOAD_DOWNLOAD_NOT_ACCEPTED',
    'NRC_TRANSFER_SUSPENDED',
    'NRC_PROGRAMMING_FAILURE',
    'NRC_WRONG_BLOCK_COUNTER',
    'NRC_RESPONSE_PENDING',
    'NRC_SUBFUNCTION_NOT_IN_SESSION',
    'NRC_SERVICE_NOT_IN_SESSION',
    'NRC_FW_HEADER',
    'NRC_FW_TARGET',
    'NRC_FW_TRUNCATED',
    'NRC_FW_HASH',
    'NRC_FW_TAG',
    'NRC_FW_DOWNGRADE',
    'NRC_FW_SKILL_FORMAT',
    'NRC_FW_CONFIG_FORMAT',
    'BOOT_STATUS_NRC',
]

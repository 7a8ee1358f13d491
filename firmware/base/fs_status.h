/* Status codes: Core: parameters, skill image, fixed point.
 * generated from firmware/base/codes.toml by tools/gen_codes.py; do not edit. */
#ifndef FS_STATUS_H
#define FS_STATUS_H

/** Core: parameters, skill image, fixed point (1xx-3xx). */
typedef enum {
    FS_OK = 0,

    /* 1xx: gain and parameter validation (dmp_params_from_gains, pfc_config_validate) */
    FS_ERR_NULL_ARG = 100,              /* a required pointer was NULL */
    FS_ERR_NOT_FINITE = 101,            /* a parameter is NaN or infinite */
    FS_ERR_MASS_NONPOSITIVE = 102,      /* m_d <= 0 */
    FS_ERR_KD_LE_MD = 103,              /* k_d <= m_d, so alpha <= 0 (unstable) */
    FS_ERR_BETA_NONPOSITIVE = 104,      /* derived beta <= 0 (unstable) */
    FS_ERR_PHASE_NOT_MONOTONE = 105,    /* beta > alpha/4: the phase overshoots */
    FS_ERR_STIFFNESS_NONPOSITIVE = 106, /* k <= 0 */
    FS_ERR_GAIN_NEGATIVE = 107,         /* a gain that must be >= 0 is negative */
    FS_ERR_DT_INVALID = 108,            /* dt <= 0 or not finite */
    FS_ERR_SCALE_INVALID = 109,         /* goal/time scale not finite, or time scale <= 0 */
    FS_ERR_LIMIT_INVALID = 110,         /* a controller limit (force_max, integral_max) is <= 0 */
    /* k_f*m_v/m_d >= 1: the force loop feeds back the object's inertia */
    FS_ERR_FORCE_GAIN_INERTIA = 112,

    /* 2xx: skill image parsing and validation (skill_parse) */
    FS_ERR_SKILL_TOO_SHORT = 200,       /* fewer bytes than the fixed header */
    FS_ERR_SKILL_MAGIC = 201,           /* magic is not "FSKL" */
    FS_ERR_SKILL_VERSION = 202,         /* unsupported format version */
    FS_ERR_SKILL_LENGTH = 203,          /* length field disagrees with the buffer or with N */
    FS_ERR_SKILL_CRC = 204,             /* CRC-32 mismatch */
    FS_ERR_SKILL_KERNELS = 205,         /* N == 0 or N > DMP_MAX_KERNELS */
    FS_ERR_SKILL_NOT_FINITE = 206,      /* a stored value is NaN or infinite */
    /* a value outside its physical range (dt, tau, T, widths) */
    FS_ERR_SKILL_RANGE = 207,
    FS_ERR_SKILL_CENTRES = 208,         /* centres not strictly increasing in [0, 1] */
    FS_ERR_SKILL_GAINS = 209,           /* stored alpha/beta/gamma disagree with the stored gains */
    FS_ERR_SKILL_UNSUPPORTED = 210,     /* a flag this firmware does not implement */
    FS_ERR_SKILL_HEADER_SIZE = 211,     /* header_size field is not the v1 header size */
    /* a parameter outside the device's documented range (skill_check.h) */
    FS_ERR_SKCHK_RANGE = 220,
    FS_ERR_SKCHK_STEP = 221,            /* dt/(tau*time_scale) too large for the DMP's Euler step */
    FS_ERR_SKCHK_NOT_FINITE = 222,      /* the rollout at goal scale 1 is not finite */
    /* the rollout at goal scale 1 peaks above the force limit */
    FS_ERR_SKCHK_PEAK = 223,
    FS_ERR_SKCHK_GOAL_SCALE = 224,      /* goal_scale * peak above the force limit: run refused */
    /* the y path at path scale 1 is not finite or leaves the device's y range (its extent from
     * the start above the y workspace's width), or a y parameter is outside the device's range */
    FS_ERR_SKCHK_PATH = 225,
    /* path_scale * path extent above the y workspace's width, or a path scale not finite or
     * negative: run refused */
    FS_ERR_SKCHK_PATH_SCALE = 226,
    /* the skill's nominal stiffness is above the device's stiffness limit (commit and run
     * refused) */
    FS_ERR_SKCHK_STIFFNESS = 227,
    /* format v4: a kind other than discrete (0) or periodic (1), the reserved field not 0, or a
     * discrete skill with periodic fields not 0 */
    FS_ERR_SKILL_KIND = 228,
    /* periodic skill: its duration (the period) is not 2*pi*tau */
    FS_ERR_SKILL_PERIOD = 229,
    FS_ERR_SKILL_AMPLITUDE = 230,       /* periodic skill: amplitude not > 0 */
    /* periodic skill: centres not strictly increasing in [0, 2*pi) */
    FS_ERR_SKILL_PHASES = 231,
    FS_ERR_SKILL_NO_PERIODIC = 232,     /* a periodic skill on a device build that cannot run one */
    /* format v4: the contact-wait fields out of range (a time constant above 10 s, or one
     * without a threshold) */
    FS_ERR_SKILL_CONTACT_WAIT = 233,
    /* format v5: the band's point count outside 2..128, its reserved fields not 0, or a lower
     * bound above the upper one */
    FS_ERR_SKILL_BAND = 234,

    /* 3xx: fixed-point conversion (firmware/fixed) */
    FS_ERR_FIXED_OVERFLOW = 300,        /* a value does not fit its fixed-point format */
    FS_ERR_FIXED_WINDOW = 301,          /* more kernels overlap than the fixed build evaluates */
    FS_ERR_FIXED_STEP = 302,            /* dt/tau too small or too large for Q1.31 */
    FS_ERR_FIXED_CONFIG = 303,          /* a controller gain/limit does not fit Q16.16 */
} fs_status_t;

#endif /* FS_STATUS_H */

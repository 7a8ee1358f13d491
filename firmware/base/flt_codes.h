/* Status codes: Safety: latched device faults; Safety configuration.
 * generated from firmware/base/codes.toml by tools/gen_codes.py; do not edit. */
#ifndef FLT_CODES_H
#define FLT_CODES_H

#include <stdint.h>

/** Safety: latched device faults (500-519). */
typedef enum {
    FLT_NONE = 0,
    FLT_HOST_SILENCE = 500,   /* no host heartbeat/command for wdg timeout (default 100 ms) */
    FLT_BUS_OFF = 501,        /* CAN controller reported bus-off */
    FLT_SENSOR_NAN = 502,     /* a position, velocity or force reading is NaN or infinite */
    FLT_SENSOR_RANGE = 503,   /* a reading outside the sensor's physical range */
    FLT_SENSOR_STUCK = 504,   /* non-zero force reading bit-identical for sen stuck_ticks */
    FLT_SENSOR_SPIKE = 505,   /* force reading changed by more than spike_N in one tick */
    FLT_ENCODER_JUMP = 506,   /* position changed by more than jump_m in one tick */
    FLT_FORCE_LIMIT = 507,    /* measured contact force above contact_force_max_N */
    FLT_SLEW_LIMIT = 508,     /* command request held at the slew limit for slew_fault_ticks */
    FLT_WORKSPACE = 509,      /* measured position outside the workspace */
    FLT_VELOCITY = 510,       /* |measured velocity| above vel_max_mps */
    FLT_TICK_OVERRUN = 511,   /* a control tick did not finish before the next one was due */
    FLT_SKILL_INVALID = 512,  /* the active skill failed validation or could not be loaded */
    FLT_CMD_NOT_FINITE = 513, /* the control law produced a NaN or infinite force request */
    FLT_STORAGE = 514,        /* flash error while the device was running (erase/program/read) */
    /* the contact force stayed outside the skill's demonstrated band for the run's band stop
     * time */
    FLT_BAND = 515,
} flt_code_t;

#define FLT_CODE_FIRST 500u
#define FLT_COUNT 16u /* codes FLT_CODE_FIRST .. FLT_CODE_FIRST + FLT_COUNT - 1 */

/** Bit of a code in a cause/latched mask (0 for FLT_NONE or an unknown code). */
#define FLT_BIT(code) \
    (((uint32_t)(code) >= FLT_CODE_FIRST && (uint32_t)(code) < FLT_CODE_FIRST + FLT_COUNT) \
         ? (1u << ((uint32_t)(code) - FLT_CODE_FIRST)) : 0u)

/** Safety configuration (520-529: saf_config_validate and the modules' *_config_validate). */
typedef enum {
    SAF_OK = 0,
    SAF_ERR_NULL_ARG = 520,    /* a required pointer was NULL */
    SAF_ERR_NOT_FINITE = 521,  /* a limit is NaN or infinite */
    SAF_ERR_NONPOSITIVE = 522, /* a limit that must be > 0 is <= 0 */
    SAF_ERR_WORKSPACE = 523,   /* workspace or sensor range with min >= max */
    SAF_ERR_TIMEOUT = 524,     /* host-silence timeout outside 20..500 ms */
    /* ramp longer than 50 ms, shorter than one tick, or the slew limit cannot reach zero from
     * force_max within the ramp */
    SAF_ERR_RAMP = 525,
    SAF_ERR_FORCE_MAX = 526,   /* force_max above the hardware ceiling LIM_FORCE_CEILING_N */
} saf_status_t;

#endif /* FLT_CODES_H */

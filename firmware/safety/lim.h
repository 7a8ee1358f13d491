/* Limits at the last stage before the actuator (docs/safety.md): |force| <= force_max_N, force slew per
 * tick, workspace and velocity. A pure function over explicit structs: whatever the request
 * (NaN, inf, huge), the output is finite, |out| <= force_max_N and |out - previous out| <=
 * slew_max_N, given a configuration that passed lim_config_validate.
 * Sign convention: a positive force pushes towards positive position (x: into the object). */
#ifndef LIM_H
#define LIM_H

#include <stdbool.h>
#include <stdint.h>
#include "flt_codes.h"
#include "fs_real.h"
#include "saf_real.h"

#define LIM_AXES SAF_AXES
#define LIM_FORCE_CEILING_N 200.0 /* no configuration may set force_max_N above this */

/** Limits of one axis. */
typedef struct {
    fs_real_t force_max_N; /* |command| <= this (default 50 N) */
    fs_real_t slew_max_N;  /* |command change| per tick <= this (default 2 N = 2 kN/s) */
    fs_real_t pos_min_m;   /* workspace; outside it force pushing further out is cut */
    fs_real_t pos_max_m;
    fs_real_t vel_max_mps;         /* above it, force along the velocity is cut (default 1 m/s) */
    fs_real_t contact_force_max_N; /* measured |contact force| above it latches FLT_FORCE_LIMIT */
} lim_axis_t;

/** Limits of the device. */
typedef struct {
    lim_axis_t axis[LIM_AXES];
    uint16_t slew_fault_ticks; /* FLT_SLEW_LIMIT when the slew limit binds persistently:
                                       leaky bucket +2 per binding tick, -1 per free tick,
                                       trips at 2*slew_fault_ticks, i.e. after this many ticks
                                       of continuous binding (default 50; 0 = never) */
} lim_config_t;

/** One axis's limits in the tick's units (lim_prepare): the force and slew bounds sanitised
 *  (NaN, inf or <= 0 give 0, so a corrupted configuration can only make the output smaller). */
typedef struct {
    saf_force_t force_max_N;
    saf_force_t slew_max_N;
    saf_pos_t pos_min_m;
    saf_pos_t pos_max_m;
    saf_vel_t vel_max_mps;
    saf_force_t contact_force_max_N;
} lim_bounds_t;

/** State: the last output (the slew reference), the slew-binding leaky bucket and the bounds
 *  of the configuration last prepared. */
typedef struct {
    saf_force_t out_N[LIM_AXES];
    uint16_t slew_run[LIM_AXES];
    lim_bounds_t b[LIM_AXES];
} lim_state_t;

/* Flags of what lim_apply did this tick (lim_result_t.flags). */
#define LIM_F_NOT_FINITE 0x01u /* a request was NaN/inf (treated as 0) */
#define LIM_F_FORCE 0x02u      /* a request was clamped to +-force_max_N */
#define LIM_F_SLEW 0x04u       /* the slew limit bound the output */
#define LIM_F_WORKSPACE 0x08u  /* outside the workspace: outward force cut */
#define LIM_F_VELOCITY 0x10u   /* over speed: force along the velocity cut */

/** What the limiter did and which fault causes it saw (FLT_BIT mask). */
typedef struct {
    uint32_t flags;
    uint32_t cause_mask; /* FLT_CMD_NOT_FINITE, FLT_WORKSPACE, FLT_VELOCITY, FLT_FORCE_LIMIT,
                              FLT_SLEW_LIMIT */
} lim_result_t;

/** Defaults: 50 N, 2 N/tick, workspace [-0.5, 0.5] m, 1 m/s, contact 60 N, slew fault 50 ticks. */
void lim_default_config(lim_config_t *cfg);

/** Validate: finite, positive, min < max, force_max <= LIM_FORCE_CEILING_N. */
saf_status_t lim_config_validate(const lim_config_t *cfg);

/** Zero the slew reference (actuator output assumed 0); the bounds are kept. */
void lim_reset(lim_state_t *st);

/** The bounds lim_apply uses, from cfg: call it once cfg is set and whenever it changes. */
void lim_prepare(const lim_config_t *cfg, lim_state_t *st);

/** Limit req_N into out_N (may alias) with st's prepared bounds (cfg: slew_fault_ticks). meas
 *  may be NULL (no workspace/velocity/contact check; non-finite measurements never gate the
 *  force here, sen_check reports them). */
lim_result_t lim_apply(const lim_config_t *cfg, lim_state_t *st, const saf_force_t req_N[LIM_AXES],
                       const saf_meas_t meas[LIM_AXES], saf_force_t out_N[LIM_AXES]);

#endif /* LIM_H */

/* Sensor plausibility: NaN/inf, out of range, stuck, spike, encoder jump.
 * Run once per tick on the raw measurements before they reach the control law. */
#ifndef SEN_H
#define SEN_H

#include <stdint.h>
#include "flt_codes.h"
#include "fs_real.h"
#include "saf_real.h"

/** Plausibility bounds of one axis. */
typedef struct {
    fs_real_t force_range_N; /* |force| above it: FLT_SENSOR_RANGE (default 200 N) */
    fs_real_t pos_min_m;     /* position outside [min, max]: FLT_SENSOR_RANGE (+-1 m) */
    fs_real_t pos_max_m;
    fs_real_t vel_range_mps; /* |velocity| above it: FLT_SENSOR_RANGE (default 10 m/s) */
    fs_real_t spike_N;       /* |force change| per tick above it: FLT_SENSOR_SPIKE (20 N) */
    fs_real_t jump_m;        /* |position change| per tick above it: FLT_ENCODER_JUMP (5 mm) */
    fs_real_t stuck_min_N;   /* stuck check only while |force| > this (default 0.5 N) */
    uint16_t stuck_ticks;    /* force bit-identical this many ticks: FLT_SENSOR_STUCK
                                 (default 500; 0 = off, e.g. for a noiseless simulated sensor) */
} sen_axis_t;

/** Plausibility bounds of the device. */
typedef struct {
    sen_axis_t axis[SAF_AXES];
} sen_config_t;

/** One axis's bounds in the tick's units (sen_prepare). */
typedef struct {
    saf_force_t force_range_N;
    saf_pos_t pos_min_m;
    saf_pos_t pos_max_m;
    saf_vel_t vel_range_mps;
    saf_force_t spike_N;
    saf_pos_t jump_m;
    saf_force_t stuck_min_N;
} sen_bounds_t;

/** Previous accepted reading, stuck counters and the bounds of the configuration last
 *  prepared. */
typedef struct {
    saf_meas_t prev[SAF_AXES];
    uint16_t same_count[SAF_AXES];
    uint8_t have_prev;
    uint8_t bounds_finite; /* every bound finite (sen_prepare): one test finds a reading usual */
    sen_bounds_t b[SAF_AXES];
} sen_state_t;

/** Defaults listed in sen_axis_t's comments. */
void sen_default_config(sen_config_t *cfg);

/** Validate: finite, positive, min < max. */
saf_status_t sen_config_validate(const sen_config_t *cfg);

/** Forget the previous reading (after power-up or a sensor re-init); the bounds are kept. */
void sen_reset(sen_state_t *st);

/** The bounds sen_check uses, from cfg: call it once cfg is set and whenever it changes. */
void sen_prepare(const sen_config_t *cfg, sen_state_t *st);

/** Check one tick's readings against st's prepared bounds (cfg: stuck_ticks); returns the
 *  FLT_BIT mask of causes present. Non-finite readings are not stored as the previous one. */
uint32_t sen_check(const sen_config_t *cfg, sen_state_t *st, const saf_meas_t meas[SAF_AXES]);

#endif /* SEN_H */

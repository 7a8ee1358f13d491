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

/** Previous accepted reading and stuck counters. */
typedef struct {
    saf_meas_t prev[SAF_AXES];
    uint16_t same_count[SAF_AXES];
    uint8_t have_prev;
} sen_state_t;

/** Defaults listed in sen_axis_t's comments. */
void sen_default_config(sen_config_t *cfg);

/** Validate: finite, positive, min < max. */
saf_status_t sen_config_validate(const sen_config_t *cfg);

/** Forget the previous reading (after power-up or a sensor re-init). */
void sen_reset(sen_state_t *st);

/** Check one tick's readings; returns the FLT_BIT mask of causes present. Non-finite readings
 *  are not stored as the previous reading. */
uint32_t sen_check(const sen_config_t *cfg, sen_state_t *st, const saf_meas_t meas[SAF_AXES]);

#endif /* SEN_H */

/* The fixed-point executor (fs_app_exec_fx: float32 with the DMP and the law in fixed point)
 * behind plain double arrays, for test_exec_fixed.c: its public header cannot be included in
 * the same file as the double executor's (the two builds of fs_exec.h define the same types). */
#ifndef EXEC_FIXED_SIDE_H
#define EXEC_FIXED_SIDE_H

#include <stddef.h>
#include <stdint.h>

/** A run of one skill as the application starts it (exec_config_default, the skill's gains on
 *  x, the default law's on y), open loop over recorded measurements. */
typedef struct {
    const uint8_t *image;
    uint32_t image_len;
    double goal_scale;
    double time_scale;
    double path_scale;
    double phase_stop_gain_per_N2;
    uint8_t use_model;
    double contact_threshold_N; /* the skill's contact wait set to this (0: the image's) */
    double contact_tau_s;
    double lost_from_s, lost_to_s; /* the float64 run's contact lost in [from, to) */
} exec_side_run_t;

/** One tick's measurements (x, y) and the executor's outputs. */
typedef struct {
    double pos_m[2];
    double vel_mps[2];
    double force_contact_N;
} exec_side_meas_t;

typedef struct {
    double force_cmd_N[2];
    double force_hat_N;
    double pos_ref_m;
    double y_ref_m;
    int status;
    uint8_t step, done;
} exec_side_out_t;

/** One step of a sequence (exec_step_t's fields) with its skill image; contact_threshold_N > 0
 *  sets the skill's contact wait. */
typedef struct {
    const uint8_t *image;
    uint32_t image_len;
    double goal_scale, time_scale, duration_s, path_scale, amplitude_scale;
    uint8_t end_policy, until_stopped;
    double contact_threshold_N, contact_tau_s;
} exec_side_step_t;

#define EXEC_SIDE_MAX_STEPS 4u

/** The band's check of the last exec_side_fixed_replay: ticks checked, ticks outside, the
 *  longest run outside, the first tick outside, the largest excursion (0.001 band widths). */
void exec_side_band(uint32_t out[5]);

/** A sequence run: its steps, the configuration's switches (the default object model when
 *  use_model), the y start, and a mutation of the integer executor's constants for the test's
 *  check of its own power (0: none). */
typedef struct {
    exec_side_step_t step[EXEC_SIDE_MAX_STEPS];
    uint8_t n_steps;
    uint8_t use_model;
    uint8_t surface_from_contact;
    double surface_m;
    double phase_stop_gain_per_N2;
    double y_hold_m;
    uint32_t saturate_at; /* > 0: the DMP's accumulators forced beyond range before this tick */
    int mutation;
    uint8_t via_wrapper; /* 1: run exec_tick (the float32 boundary over exec_tick_q) instead */
    uint8_t prepare;     /* 1: exec_prepare_next after each tick, as the application does */
} exec_side_seq_t;

/** The mutations exec_side_q_replay applies after exec_start (one wrong constant each). */
enum {
    EXEC_SIDE_MUT_NONE = 0,
    EXEC_SIDE_MUT_BLEND,   /* the blend's increment 1 % high */
    EXEC_SIDE_MUT_RELEASE, /* the release ramp's increment 1 % high */
    EXEC_SIDE_MUT_INV_K,   /* 1/k of step 0 1 % high */
    EXEC_SIDE_MUT_INV_M,   /* the object model's 1/m_v 1 % high */
    EXEC_SIDE_MUT_STOP,    /* the phase-stop gain 10 % high */
    EXEC_SIDE_MUT_CONTACT, /* the contact wait's gain of step 0 10 % high */
    EXEC_SIDE_MUT_CARRY,   /* step 1's starting force 10 mN high */
};

/** Start the fixed-point executor on seq (skills parsed in float32, converted as the device
 *  does) and run exec_tick_q over n ticks of meas (rounded to Q8.24 / Q16.16, NaN as INT32_MIN)
 *  into out; returns the status of the first failing set-up call (FS_OK = 0). */
int exec_side_q_replay(const exec_side_seq_t *seq, const exec_side_meas_t *meas,
                       exec_side_out_t *out, size_t n);

/** exec_contact_hold_ms of the last exec_side_q_replay's run. */
uint32_t exec_side_q_hold_ms(void);

/** Parse the image in float32, start the fixed-point executor (y held at y_hold_m) and run it
 *  over n ticks of meas into out; returns the status of the first failing call (FS_OK = 0). */
int exec_side_fixed_replay(const exec_side_run_t *run, double y_hold_m,
                           const exec_side_meas_t *meas, exec_side_out_t *out, size_t n);

#endif /* EXEC_FIXED_SIDE_H */

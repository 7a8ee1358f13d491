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
} exec_side_out_t;

/** Parse the image in float32, start the fixed-point executor (y held at y_hold_m) and run it
 *  over n ticks of meas into out; returns the status of the first failing call (FS_OK = 0). */
int exec_side_fixed_replay(const exec_side_run_t *run, double y_hold_m,
                           const exec_side_meas_t *meas, exec_side_out_t *out, size_t n);

#endif /* EXEC_FIXED_SIDE_H */

/* The executor's numeric layer, real (fs_control_exec: double; fs_control_exec_f32: float32):
 * every quantity of fs_exec.h's per-tick state is fs_real_t, the DMP and the control law are
 * the core's (dmp_step_xy, pfc_step), and exec_num_real_api.h's operations are the plain
 * arithmetic, inline. The build selects it unless FS_EXEC_NUM names another layer. */
#ifndef EXEC_NUM_REAL_H
#define EXEC_NUM_REAL_H

#include <stdint.h>
#include "dmp.h"
#include "fs_real.h"
#include "pfc.h"

/* the operations of this layer (fs_exec.h includes them at its end) */
#define EXEC_NUM_API "exec_num_real_api.h"
/* the native measurements and outputs of exec_tick_n: exec_tick's own */
#define EXEC_NUM_MEAS_N exec_meas_t
#define EXEC_NUM_OUT_N exec_out_t
#define exec_tick_n exec_tick

typedef fs_real_t exec_nf_t;     /* force, N */
typedef fs_real_t exec_nx_t;     /* x position, velocity, acceleration; y velocity */
typedef fs_real_t exec_ny_t;     /* y path, m */
typedef fs_real_t exec_nrate_t;  /* phase rate, 0..1 */
typedef fs_real_t exec_nsum_t;   /* the contact wait's hold (s) and deferred ticks */
typedef fs_real_t exec_nclock_t; /* time of a step, of the end policy, s */
typedef fs_real_t exec_nturn_t;  /* the band's normalised time */
typedef fs_real_t exec_nwidth_t; /* the band's largest excursion, band widths */
typedef fs_real_t exec_nmeas_pos_t;
typedef fs_real_t exec_nmeas_force_t;
typedef dmp_state_t exec_ndmp_t;
typedef pfc_axis_ref_t exec_nref_t;
typedef pfc_axis_meas_t exec_nlaw_meas_t;

/** The layer's part of exec_state_t: the running step's DMP run and the law's state, and the
 *  step's constants exec_begin_step derives (a turn's ticks, the band's scale). */
typedef struct {
    dmp_run_t run;
    pfc_state_t pfc;
    fs_real_t path_ramp_inv; /* dt over a turn's time */
    fs_real_t band_c0_N;     /* the running step's band scale: c0 + band_k*b */
    fs_real_t band_k;        /* goal_scale (discrete) or amplitude_scale (periodic) */
} exec_num_t;

/** The real executors run the skill's own model (exec_step_t has no other). */
typedef dmp_model_t exec_model_t;

/** The velocity estimator's layer state: none beyond exec_vel_t's. */
typedef struct {
    uint8_t unused;
} exec_vel_n_t;

#endif /* EXEC_NUM_REAL_H */

/* The executor's numeric layer, fixed point (fs_control_exec_fx: the Cortex-M3 image, no FPU):
 * the types of fs_exec.h's per-tick state in Q formats, the DMP and the control law of
 * firmware/fixed (dmpfx_step_xy, pfcfx_step). The build selects it (FS_EXEC_NUM names this
 * header); exec_num_fixed_api.h holds its operations. Its symbols carry an _fx suffix, so a test
 * links it beside the real executor.
 * Units: forces N Q.32 (int64), x positions and their derivatives m, m/s, m/s^2 Q.48, the y path
 * m Q.55 (the DMP accumulators' own resolution), its velocity Q.48 and acceleration Q.40, rates
 * and blends Q1.31; the law's references and measurements m, m/s Q8.24 and N Q16.16. The tick
 * (exec_tick_n, named exec_tick_q) runs without a floating-point operation: every constant is
 * derived by exec_start's slices (fs_exec_fixed.c), so neither the start tick nor a switch between
 * steps converts anything. */
#ifndef EXEC_NUM_FIXED_H
#define EXEC_NUM_FIXED_H

#ifndef FS_REAL_FLOAT
#error "the fixed-point executor is the float32 executor's fixed-point build (FS_REAL_FLOAT)"
#endif
#include <stdint.h>
#include <string.h>
#include "dmpfx.h"
#include "pfc.h"
#include "pfcfx.h"

#define exec_config_default exec_config_default_fx
#define exec_start exec_start_fx
#define exec_start_begin exec_start_begin_fx
#define exec_start_load exec_start_load_fx
#define exec_start_reset exec_start_reset_fx
#define exec_start_run exec_start_run_fx
#define exec_object_force exec_object_force_fx
#define exec_object_deformation exec_object_deformation_fx
#define exec_tick exec_tick_fx
#define exec_tick_n exec_tick_q_fx
#define exec_tick_q exec_tick_q_fx
#define exec_contact_hold_ms exec_contact_hold_ms_fx
#define exec_contact_rate exec_contact_rate_fx
#define exec_force_hat_N exec_force_hat_N_fx
#define exec_band_max_milli exec_band_max_milli_fx
#define exec_vel_init exec_vel_init_fx
#define exec_vel_update exec_vel_update_fx
#define exec_vel_update_q exec_vel_update_q_fx
#define exec_render_default exec_render_default_fx
#define exec_render_reset exec_render_reset_fx
#define exec_render_step exec_render_step_fx
#define exec_prep_parts exec_prep_parts_fx
#define exec_prep_run exec_prep_run_fx
#define exec_counts_edge exec_counts_edge_fx

/* the operations of this layer (fs_exec.h includes them at its end) */
#define EXEC_NUM_API "exec_num_fixed_api.h"

typedef int64_t exec_nf_t;      /* force, N Q.32 */
typedef int64_t exec_nx_t;      /* x position, velocity, acceleration; y velocity: Q.48 */
typedef int64_t exec_ny_t;      /* y path, m Q.55 */
typedef uint32_t exec_nrate_t;  /* phase rate, Q1.31 */
typedef uint64_t exec_nsum_t;   /* the contact wait's sums of (1 - rate), ticks Q.31 */
typedef uint32_t exec_nclock_t; /* ticks of a step, of the end policy */
typedef uint64_t exec_nturn_t;  /* the band's normalised time, Q.32 */
typedef uint32_t exec_nwidth_t; /* the band's largest excursion, band widths Q16.16 */
typedef int32_t
    exec_nmeas_pos_t; /* a measured position or velocity, Q8.24 (INT32_MIN: not finite) */
typedef int32_t exec_nmeas_force_t; /* a measured force or a command, N Q16.16 */
typedef dmpfx_state_t exec_ndmp_t;
typedef pfcfx_ref_t exec_nref_t;
typedef pfcfx_meas_t exec_nlaw_meas_t;

/** One step's constants, derived by exec_start_run from the step's skill and run. */
typedef struct {
    int64_t force0_q32;      /* f_dmp without the DMP's y: f0 (+ a periodic step's 2^s*g_e) */
    int64_t start_force_q32; /* the step's first force (the carry's reference) */
    int64_t path0_q55;       /* a periodic y path's s_p*g_y (0 otherwise) */
    int64_t contact_threshold_q32;
    fx_scale_t inv_k;          /* 1/k of the skill: N Q.32 -> m Q.48 */
    uint32_t ticks;            /* the step's length at dt (EXEC_TICKS_MAX: until stopped) */
    uint32_t ramp_inc_q32;     /* dt over a turn's time, rounded up (a y path's ramp-out) */
    uint32_t contact_gain_q31; /* dt/(contact_tau_s + dt) */
    uint8_t y_shift;           /* 23 - s: y_acc (Q.55 in units of 2^s N) -> N Q.32 */
    uint8_t contact_wait;      /* the skill's contact_threshold_N > 0 */
    int64_t band_c0_q32;       /* the band scaled as f_hat: c0 + k*b */
    int32_t band_k_q16;        /* k, Q16.16 */
} exec_step_q_t;

/** The run's constants from the configuration (exec_start's last slices). */
typedef struct {
    fx_scale_t inv_dt_x;       /* m Q.48 -> m/s Q.48 */
    fx_scale_t inv_dt_y;       /* m Q.55 -> m/s Q.48 */
    fx_scale_t inv_dt_yd;      /* m/s Q.48 -> m/s^2 Q.40 */
    fx_scale_t dt;             /* Q.48 -> Q.48 times dt */
    fx_scale_t d_v;            /* m/s Q.48 -> N Q.32 */
    fx_scale_t k1, k2;         /* m Q.48 -> N Q.32 */
    fx_scale_t inv_m;          /* N Q.32 -> m/s^2 Q.48 */
    fx_scale_t inv_k1, inv_k2; /* N Q.32 -> m Q.48 */
    fx_scale_t stop_gain;      /* N^2 Q.32 -> Q.24 */
    fx_scale_t hold_ms;        /* held ticks Q.31 -> ms (exec_contact_hold_ms) */
    int64_t layer_q48;
    int64_t f_layer_q32;      /* k1 * layer depth */
    uint32_t blend_inc_q32;   /* dt/EXEC_BLEND_S, rounded up */
    uint32_t release_inc_q32; /* dt/SKILL_RELEASE_TIME_S, rounded up */
    uint8_t phase_stop;
    uint8_t use_model; /* cfg->use_model: the reference integrates the object model */
} exec_cfg_q_t;

/** The layer's part of exec_state_t: each step's DMP run and starting state and the integer
 *  constants (exec_start), the law's configuration in fixed point and its state. */
typedef struct {
    exec_step_q_t step[EXEC_MAX_STEPS];
    exec_cfg_q_t c;
    dmpfx_run_t run[EXEC_MAX_STEPS];         /* each step's per-run constants */
    dmpfx_state_t dmp_start[EXEC_MAX_STEPS]; /* each step's starting DMP state */
    pfcfx_config_t pfc_cfg;                  /* cfg->pfc at exec_start */
    pfcfx_state_t pfc;
    uint8_t dmp_saturated; /* this tick's DMP step saturated */
    /* the object model's damping and spring forces at ref_pd = pre_pd, ref_p = pre_p (N Q.32),
     * computed after a tick's write for the next tick's reference (pre_ok: made this run) */
    uint8_t pre_ok;
    int64_t pre_p, pre_pd;
    int64_t pre_damp, pre_spring;
    /* the band's segment in use (band_seg: (step << 8) + point + 1, 0 none) and its two points'
     * bounds lo[i], lo[i+1], hi[i], hi[i+1] (N Q16.16): converted from the skill's floats only
     * when the run enters another segment (64 points over a skill: every ~100 ticks) */
    uint32_t band_seg;
    int32_t band_q[4];
} exec_num_t;

/** A step's fixed-point model (exec_step_t.model_fx), converted beforehand
 *  (dmpfx_from_model_bound: the device does it at the skill's commit). */
typedef dmpfx_model_t exec_model_t;

/** Measurements of one tick in the fixed-point build's units (INT32_MIN: not finite). */
typedef struct {
    int32_t pos_q24[PFC_AXES]; /* m, Q8.24 */
    int32_t vel_q24[PFC_AXES]; /* m/s, Q8.24 */
    int32_t force_contact_q16; /* N, Q16.16 */
} exec_meas_q_t;

/** Output of one integer tick (exec_out_t's fields in Q formats). */
typedef struct {
    int32_t force_cmd_q16[PFC_AXES]; /* N, Q16.16 */
    int32_t force_hat_q16;           /* f_hat, N, Q16.16 */
    int32_t pos_ref_q24, y_ref_q24;  /* m, Q8.24 */
    uint8_t step, done;
} exec_out_q_t;

/* the native measurements and outputs of exec_tick_n */
#define EXEC_NUM_MEAS_N exec_meas_q_t
#define EXEC_NUM_OUT_N exec_out_q_t

/** The velocity estimator's integer state (exec_vel_t.n). */
typedef struct {
    int32_t prev_q24;   /* the last position, m in Q8.24 */
    int32_t vel_q24;    /* the filtered velocity, m/s in Q8.24 */
    int32_t alpha_q30;  /* alpha in Q2.30 */
    int32_t inv_dt_q16; /* 1/dt in Q16.16 (1/s) */
    uint8_t not_finite; /* a non-finite sample was fed: the velocity is not finite from then */
} exec_vel_n_t;

#endif /* EXEC_NUM_FIXED_H */

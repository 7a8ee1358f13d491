/* Skill execution on the device: a sequence of up to EXEC_MAX_STEPS learned force
 * skills evaluated at 1 kHz, the position reference from the known object model, the parallel
 * force/position law for both axes, end policy (hold/release), and the rendering of the law's
 * force command on a real carriage (admittance: the same code renders m_d in TEACH).
 * Pure functions over explicit state structs: no heap, no I/O, bounded work per tick.
 *
 * Per tick (exec_tick), step k of the sequence:
 *   f_dmp  = dmp_step(skill_k, goal_scale_k, time_scale_k, coupling) = f0_k + y   (f0_k: the
 *            skill's starting force; goal_scale scales y, the part above f0_k)
 *   f_hat  = f_dmp + f_carry * blend(t)        (start and sequence continuity, see below)
 *   x_d, xd_d, xdd_d from f_hat: the object model m_v*pdd + d_v*pd + F(p) = f_hat integrated
 *            forward (semi-implicit Euler, unilateral p >= 0), x_d = surface + p;
 *            without a model x_d = surface + f_hat/k (k of the skill), xd_d by difference.
 *   p      = the skill's y DMP on the same phase (dmp_step_xy, path_scale of the step), a skill
 *            without one: p = 0; y_d = y_base + p, yd_d and ydd_d by differences of y_d
 *   f_cmd  = pfc_step(ref = {x_d, xd_d, xdd_d, f_hat}, {y_d, yd_d, ydd_d}); the caller gives
 *            the skill's controller gains (k_f = kkf/k, k_i = kki/k: skill_t.gains); y is
 *            position-controlled (its k_f = k_i = 0)
 * y_base is the y position at exec_start (the path is learned relative to its start); at a
 * switch between steps it advances by the finished step's p, so the path is continuous; after
 * the sequence y_d stays where the path ended.
 * Start: the first tick measures the contact force f_c; f_carry = f_c - f0 of the first skill, so
 * execution starts from the measured contact force without a jump and reaches the skill's own
 * profile after EXEC_BLEND_S. On a stiff object a surface error d acts as a force disturbance
 * k*d*k_p/(k_p + k*k_f) (3.4 N per 0.5 mm at 1e4 N/m): with surface_from_contact the surface is
 * taken from that first measurement instead (x - p(f_c); error sigma_f/k). Continuity between steps: the next skill's DMP starts from zero
 * state (its force starts at its f0); f_carry = last f_hat of the previous step - f0 of the next
 * is added and faded out with a raised cosine over EXEC_BLEND_S. The force is therefore
 * continuous at the switch (jump = one DMP step of the new skill).
 * A periodic step runs dmp_periodic_step (cycles from the stored cycle state, f_dmp = f0 +
 * goal_scale*g + e) for its duration or until stopped; its starting force (the carry's
 * reference) is its first value f0 + goal_scale*g + amplitude_scale*e0.
 * Contact wait (a skill with skill_t.contact_threshold_N > 0, docs/math.md section 6): each
 * tick the phase rate r follows dmp_contact_rate (to 0 while the last f_hat exceeds the
 * measured contact force by more than the threshold, to 1 otherwise) and every DMP state runs
 * at r (dmp_slowdown_at_rate beside phase stopping), so f_hat holds and resumes without a step;
 * the step lasts one tick more per tick of phase held; the hold sum (1 - r)*dt is counted.
 * End of the sequence: hold keeps the last f_hat; release ramps it linearly to 0 in
 * SKILL_RELEASE_TIME_S, then the sequence is done (f_hat stays 0). */
#ifndef FS_EXEC_H
#define FS_EXEC_H

#include <stdbool.h>
#include <stdint.h>
#include "dmp.h"
#include "fs_real.h"
#include "fs_status.h"
#include "pfc.h"
#include "skill.h"

/* Numeric layer of the DMP and the control law, chosen by the build like the core's:
 *   default         the core's dmp_step_xy/pfc_step in fs_real_t (fs_app_exec, fs_app_exec_f32)
 *   FS_EXEC_FIXED   their fixed-point build (firmware/fixed: dmpfx_step_xy, pfcfx_step) and an
 *                   integer tick around them (fs_app_exec_fx: the Cortex-M3 image, no FPU):
 *                   exec_tick_q runs the whole tick (references, blends, sequence, contact
 *                   wait, phase stopping, the law) without a floating-point operation on the
 *                   units of exec_q_t; exec_tick is its float32 boundary (measurements in,
 *                   commands and references out). A step names its skill's fixed-point model,
 *                   converted beforehand (dmpfx_from_model_bound: the device does it at the
 *                   skill's commit); exec_start derives every step's per-run constants, its
 *                   integer constants and starting state and converts the law's configuration,
 *                   so neither the start tick nor a switch between steps converts anything. Its
 *                   symbols carry an _fx suffix, so a test links it beside the real executor. */
#ifdef FS_EXEC_FIXED
#ifndef FS_REAL_FLOAT
#error "FS_EXEC_FIXED is the float32 executor's fixed-point build (FS_REAL_FLOAT)"
#endif
#include "dmpfx.h"
#include "pfcfx.h"
#define exec_config_default exec_config_default_fx
#define exec_start exec_start_fx
#define exec_start_begin exec_start_begin_fx
#define exec_start_run exec_start_run_fx
#define exec_object_force exec_object_force_fx
#define exec_object_deformation exec_object_deformation_fx
#define exec_tick exec_tick_fx
#define exec_tick_q exec_tick_q_fx
#define exec_contact_hold_ms exec_contact_hold_ms_fx
#define exec_band_max_milli exec_band_max_milli_fx
#define exec_vel_init exec_vel_init_fx
#define exec_vel_update exec_vel_update_fx
#define exec_vel_update_q exec_vel_update_q_fx
#define exec_render_default exec_render_default_fx
#define exec_render_reset exec_render_reset_fx
#define exec_render_step exec_render_step_fx
#endif

#define EXEC_MAX_STEPS 8u
/* Fade-out time of the previous step's force at a switch. 1 s spans a demonstration's ramp-up,
 * so the sum neither dips nor jumps; measured on the reuse experiment (8 seeds, deformation
 * difference 300 N/m @1.5x vs 200 N/m @1x): 0.5 s 8.9-11.8 %, 1.0 s 6.6-10.0 %, 1.5 s 5.9-10.0 %
 * (longer blends keep the new skill off its own profile for longer). */
#define EXEC_BLEND_S 1.0

/** One step of a sequence: which skill, how it is modulated, for how long, what happens after. */
typedef struct {
    const skill_t *skill;   /* parsed, validated skill (not owned) */
    fs_real_t goal_scale;   /* g -> goal_scale*g: scales the force */
    fs_real_t time_scale;   /* tau -> time_scale*tau: stretches the profile */
    fs_real_t duration_s;   /* how long the step runs; <= 0 means the skill's T*time_scale */
    skill_end_t end_policy; /* used after the last step: hold or release */
    fs_real_t path_scale;   /* the y path about its start (skills with a y DMP); >= 0 */
    /* a periodic skill (docs/math.md section 5): duration_s <= 0 runs one cycle (its period
     * times time_scale), until_stopped runs cycles until the run is stopped (the duration is
     * then ignored); amplitude_scale (>= 0) multiplies the stroke about the mean force, which
     * goal_scale scales */
    fs_real_t amplitude_scale;
    uint8_t until_stopped;
#ifdef FS_EXEC_FIXED
    const dmpfx_model_t *model_fx; /* the skill's DMP in fixed point (not owned, required) */
#endif
} exec_step_t;

/** Known object model for the position reference (docs/math.md): f = m_v*pdd + d_v*pd
 *  + F(p), F piecewise linear (k1 up to layer_depth_m, k2 beyond), p = x - surface_m >= 0. */
typedef struct {
    fs_real_t m_v_kg;
    fs_real_t d_v_Nspm;
    fs_real_t k1_Npm;
    fs_real_t k2_Npm;
    fs_real_t layer_depth_m;
    fs_real_t surface_m;
} exec_object_t;

/** Execution configuration: controller gains/limits, optional object model, phase stopping. */
typedef struct {
    pfc_config_t pfc;
    uint8_t use_model;                /* 1: invert the object model; 0: x_d = surface + f_hat/k */
    exec_object_t object;             /* used when use_model; surface_m is used in both cases */
    fs_real_t phase_stop_gain_per_N2; /* 0 disables phase stopping (dmp coupling) */
    uint8_t surface_from_contact;     /* 1: the surface is taken at the first tick from the measured
                                      * position and contact force, x - p(f) (the object model's
                                      * or f/k); 0: object.surface_m */
} exec_config_t;

/** Measurements of one tick (already delayed/filtered as the firmware sees them). */
typedef struct {
    fs_real_t pos_m[PFC_AXES];
    fs_real_t vel_mps[PFC_AXES];
    fs_real_t force_contact_N; /* x-axis tip force, pushing positive */
} exec_meas_t;

/** Output of one tick. */
typedef struct {
    fs_real_t force_cmd_N[PFC_AXES]; /* saturated law output ("m_d*xdd") per axis */
    fs_real_t force_hat_N;           /* reference force f_hat */
    fs_real_t pos_ref_m;             /* x_d */
    fs_real_t y_ref_m;               /* y_d */
    uint8_t step;                    /* index of the running step */
    uint8_t done;                    /* 1 once the sequence (and any release) has ended */
} exec_out_t;

#ifdef FS_EXEC_FIXED
/* The integer executor's units (exec_tick_q): forces N Q.32 (int64), x positions and their
 * derivatives m, m/s, m/s^2 Q.48, the y path m Q.55 (the DMP accumulators' own resolution), its
 * velocity Q.48 and acceleration Q.40, rates and blends Q1.31. */

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
    int64_t band_c0_q32;       /* the band scaled as f_hat: c0 + k*b (exec_state_t's band) */
    int32_t band_k_q16;        /* k, Q16.16 */
} exec_step_q_t;

/** The run's constants from the configuration (exec_start_begin). */
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
    uint8_t use_model;
    uint8_t surface_from_contact;
    uint8_t phase_stop;
} exec_cfg_q_t;

/** The integer executor's state (the fixed-point build's exec_state_t.q). */
typedef struct {
    exec_step_q_t step[EXEC_MAX_STEPS];
    exec_cfg_q_t c;
    int64_t f_hat_q32;
    int64_t f_carry_q32;
    int64_t f_end_q32;
    int64_t p_q48; /* reference deformation p_d and its rate (the object model) */
    int64_t pd_q48;
    int64_t prev_x_q48; /* model-free reference: the previous x_d */
    int64_t surface_q48;
    int64_t y_hold_q55;
    int64_t path_q55;
    int64_t y_ref_q55;
    int64_t y_ref_vel_q48;
    uint64_t hold_q31;  /* the contact wait's sum of (1 - rate), ticks Q.31 */
    uint64_t defer_q31; /* ticks held not yet added to the step's length, Q.31 */
    uint32_t end_tick;  /* ticks of the end policy */
    uint32_t contact_rate_q31;
    int64_t band_off_q32; /* the last tick's f_hat - f_dmp (the carry's share) */
    uint64_t band_s_q32;  /* the band's normalised time t/T, Q.32 */
} exec_q_t;
#endif

/** Execution state (sequence, DMP, reference model, controller integral). */
typedef struct {
    exec_step_t steps[EXEC_MAX_STEPS];
    uint8_t n_steps;
    uint8_t step;
    uint8_t ending; /* 1 after the last step's duration: end policy active */
    uint8_t done;
#ifdef FS_EXEC_FIXED
    dmpfx_run_t run[EXEC_MAX_STEPS];         /* each step's per-run constants */
    dmpfx_state_t dmp_start[EXEC_MAX_STEPS]; /* each step's starting DMP state */
    dmpfx_state_t dmp;
    pfcfx_config_t pfc_cfg; /* cfg->pfc at exec_start */
    pfcfx_state_t pfc;
    uint8_t dmp_saturated; /* this tick's DMP step saturated */
    exec_q_t q;            /* the integer tick's constants and state (exec_tick_q); of the fs_real_t
                 * fields below this build keeps y_hold_m (the start's) and, written by
                 * exec_tick, force_hat_N and contact_rate (the integer state's float view) */
#else
    dmp_state_t dmp;
    dmp_run_t run;
    pfc_state_t pfc;
#endif
    fs_real_t t_step_s;      /* time since the running step started */
    uint32_t step_ticks;     /* ticks of the running step (its duration at dt, set at its start) */
    uint32_t step_tick;      /* ticks of the running step done */
    fs_real_t t_end_s;       /* time since the end policy started */
    fs_real_t force_dmp_N;   /* last DMP output of the running step */
    fs_real_t force_hat_N;   /* last f_hat */
    fs_real_t force_carry_N; /* previous step's last f_hat, faded out over EXEC_BLEND_S */
    fs_real_t force_end_N;   /* f_hat when the end policy started */
    fs_real_t ref_p_m;       /* reference deformation p_d */
    fs_real_t ref_pd_mps;
    fs_real_t ref_pdd_mps2;
    fs_real_t ref_prev_pos_m; /* model-free reference: previous x_d (for xd_d) */
    fs_real_t y_hold_m;       /* y_base: the running step's path starts here */
    fs_real_t path_m;         /* p of the running step's y DMP */
    fs_real_t y_ref_m;        /* y_d = y_base + p */
    fs_real_t y_ref_vel_mps;  /* yd_d */
    uint8_t start_pending;    /* 1 until the first tick has measured the contact force */
    uint8_t path_ramp;        /* 1 while a periodic y path ramps in (its first turn) */
    uint8_t path_ramp_out;    /* 1: it ramps out over the step's last turn (a known length) */
    fs_real_t path_ramp_inv;  /* dt over a turn's time (the float executors' ramp-out) */
    uint8_t prepared;         /* parts exec_start_run derived (fixed build: 3 a step, 4 more) */
    fs_real_t surface_m;      /* the surface the reference is built on */
    /* the running skill's contact wait (skill_t.contact_threshold_N > 0) */
    fs_real_t contact_rate;   /* the phase rate, 0..1 (1 without a contact wait) */
    fs_real_t contact_hold_s; /* sum of (1 - rate)*dt: how long the phase held */
    fs_real_t contact_defer;  /* ticks held not yet added to the running step's length */
    uint16_t contact_losses;  /* losses of contact counted */
    uint8_t contact_lost;     /* contact lost at the last tick */
    /* the demonstrated band's check (a step whose skill has one, skill_t.band_n > 0): each tick
     * of the step before its end policy, the measured contact force less the carry's share of
     * f_hat against the band at the step's normalised time (advanced at the contact wait's
     * phase rate), scaled as f_hat (skill_band_at); counts in ticks since exec_start */
    fs_real_t band_s;            /* the float executors' normalised time t/T of the step */
    fs_real_t band_c0_N;         /* the running step's band scale: c0 + band_k*b */
    fs_real_t band_k;            /* goal_scale (discrete) or amplitude_scale (periodic) */
    uint32_t band_run_ticks;     /* ticks since exec_start */
    uint32_t band_checked_ticks; /* ticks checked against a band */
    uint32_t band_out_ticks;     /* ticks outside it */
    uint32_t band_streak_ticks;  /* consecutive ticks outside up to the last */
    uint32_t band_longest_ticks; /* the longest such run */
    uint32_t band_first_tick;    /* band_run_ticks at the first tick outside (0: none) */
    uint32_t band_max_q16;       /* the fixed-point build's largest excursion beyond the band,
                                  * band widths Q16.16 */
    fs_real_t band_max_widths;   /* the float executors' (band widths) */
    uint8_t band_outside;        /* outside at the last tick */
    uint8_t band_any;            /* a step of the run has a band (else no check runs) */
} exec_state_t;

/** Default configuration: pfc_default_config, 50 N limit, no model, no phase stopping. */
void exec_config_default(exec_config_t *cfg);

/** Load a sequence (1..EXEC_MAX_STEPS steps) and reset the state; y_hold_m is the y position the
 *  path starts from (held by skills without a y DMP). Validates skills (non-NULL), finite scales,
 *  time_scale > 0, path_scale >= 0 (a periodic step's amplitude_scale too) and the
 *  configuration; the fixed-point build also needs every step's model_fx (FS_ERR_NULL_ARG) and
 *  derives its constants (3xx codes: a scale or gain that does not fit its Q format). */
fs_status_t exec_start(const exec_config_t *cfg, exec_state_t *st, const exec_step_t *steps,
                       uint8_t n_steps, fs_real_t y_hold_m);

/** exec_start in slices, for a caller that bounds its work a tick: the checks, the sequence
 *  loaded and the law's configuration (exec_start_begin, the same codes), then each
 *  exec_start_run derives one of the three parts of a step's constants or, after them, one of
 *  the four of the integer tick's constants of the configuration (the fixed-point build; 3xx
 *  codes) or, once all are, starts the first step and sets *done. Nothing runs before *done. */
fs_status_t exec_start_begin(const exec_config_t *cfg, exec_state_t *st, const exec_step_t *steps,
                             uint8_t n_steps, fs_real_t y_hold_m);
fs_status_t exec_start_run(const exec_config_t *cfg, exec_state_t *st, bool *done);

/** Force of the object model at deformation p (0 for p <= 0). */
fs_real_t exec_object_force(const exec_object_t *obj, fs_real_t p_m);

/** Static deformation of the object model under force f (the inverse of exec_object_force;
 *  0 for f <= 0). */
fs_real_t exec_object_deformation(const exec_object_t *obj, fs_real_t force_N);

/** One 1 kHz tick. Returns FS_ERR_NOT_FINITE (commanding 0 N) when a measurement is not finite;
 *  the fixed-point build returns FS_ERR_FIXED_OVERFLOW in a tick whose DMP step saturated (the
 *  commands are computed from the saturated values). */
fs_status_t exec_tick(const exec_config_t *cfg, exec_state_t *st, const exec_meas_t *meas,
                      exec_out_t *out);

#ifdef FS_EXEC_FIXED
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

/** exec_tick in integers only (no floating-point operation: every constant, cfg's included,
 *  derived by exec_start, so cfg changed after it has no effect), the same codes. exec_tick of
 *  this build converts its measurements in, calls it, converts the outputs out and mirrors
 *  f_hat and the contact wait's rate into force_hat_N and contact_rate. */
fs_status_t exec_tick_q(const exec_config_t *cfg, exec_state_t *st, const exec_meas_q_t *meas,
                        exec_out_q_t *out);
#endif

/** The largest excursion beyond the band so far, in thousandths of a band width (0 without
 *  one; saturated at 65535). */
uint16_t exec_band_max_milli(const exec_state_t *st);

/** How long the phase of the execution held for contact (the contact wait's sum of
 *  (1 - rate)*dt), rounded to ms (0 without a contact wait). */
uint32_t exec_contact_hold_ms(const exec_state_t *st);

/* ---- Velocity estimation (encoder difference + first-order low-pass) ---- */

/** Velocity estimator state of one axis. */
typedef struct {
    fs_real_t prev_pos_m;
    fs_real_t vel_mps;
    fs_real_t alpha; /* low-pass coefficient dt/(dt + 1/(2 pi fc)) */
    uint8_t primed;
#ifdef FS_EXEC_FIXED
    int32_t prev_q24;   /* exec_vel_update_q: the last position, m in Q8.24 */
    int32_t vel_q24;    /* the filtered velocity, m/s in Q8.24 */
    int32_t alpha_q30;  /* alpha in Q2.30 */
    int32_t inv_dt_q16; /* 1/dt in Q16.16 (1/s) */
    uint8_t not_finite; /* a non-finite sample was fed: the velocity is not finite from then */
#endif
} exec_vel_t;

/** Initialise with a cut-off frequency (Hz) and the tick dt. */
void exec_vel_init(exec_vel_t *v, fs_real_t cutoff_Hz, fs_real_t dt_s);

/** Feed one encoder sample; returns the filtered velocity. */
fs_real_t exec_vel_update(exec_vel_t *v, fs_real_t pos_m, fs_real_t dt_s);

/** exec_vel_update inline (the same operations): the application's tick calls it per axis. */
static inline fs_real_t exec_vel_step(exec_vel_t *v, fs_real_t pos_m, fs_real_t dt_s)
{
    if (v->primed == 0u) {
        v->prev_pos_m = pos_m;
        v->primed = 1u;
        return v->vel_mps;
    }
    const fs_real_t raw = (pos_m - v->prev_pos_m) / dt_s;
    v->prev_pos_m = pos_m;
    v->vel_mps += v->alpha * (raw - v->vel_mps);
    return v->vel_mps;
}

#ifdef FS_EXEC_FIXED
/** exec_vel_update in integers, at the dt given to exec_vel_init: position and velocity in
 *  Q8.24 (m, m/s), INT32_MIN for a value that is not finite (a sample that was not finite
 *  makes every later velocity not finite, as NaN does in exec_vel_update). */
int32_t exec_vel_update_q(exec_vel_t *v, int32_t pos_q24);
#endif

/* ---- Rendering on a real carriage (admittance control) ---- */

/** Carriage model and inner loop gains used to render a desired acceleration. */
typedef struct {
    fs_real_t carriage_kg;   /* moving mass of the carriage */
    fs_real_t viscous_Nspm;  /* friction compensation, viscous part */
    fs_real_t coulomb_N;     /* friction compensation, Coulomb part */
    fs_real_t kp_Npm;        /* inner loop: virtual position - measured position */
    fs_real_t kd_Nspm;       /* inner loop: virtual velocity - measured velocity */
    fs_real_t ext_ff;        /* fraction of the measured external force fed forward, 0..1 */
    fs_real_t ext_cutoff_Hz; /* low-pass on that feedforward: the measured contact force
                                  * carries the object's inertia one sample late, and feeding it
                                  * back unfiltered oscillates at fs/4 (measured) */
    fs_real_t motor_max_N;   /* actuator limit */
} exec_render_cfg_t;

/** Virtual (admittance) state of one axis. */
typedef struct {
    fs_real_t pos_m;
    fs_real_t vel_mps;
    fs_real_t ext_lp_N; /* low-passed external force */
} exec_render_t;

/** Defaults for the realistic HIL carriage (2 kg, 5 Ns/m, 1 N, +-200 N). */
void exec_render_default(exec_render_cfg_t *cfg);

/** Start the virtual state at the measured position, at rest. */
void exec_render_reset(exec_render_t *r, fs_real_t pos_m);

/** Motor force that makes the carriage follow acc = force_total_N/m_d_kg (the admittance), given
 *  the measured external force on the carriage (operator - contact) and its measured motion. */
fs_real_t exec_render_step(const exec_render_cfg_t *cfg, exec_render_t *r, fs_real_t force_total_N,
                           fs_real_t m_d_kg, fs_real_t force_ext_meas_N, fs_real_t pos_m,
                           fs_real_t vel_mps, fs_real_t dt_s);

#endif /* FS_EXEC_H */

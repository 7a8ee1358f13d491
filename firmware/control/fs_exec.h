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
#include "hal.h"
#include "pfc.h"
#include "skill.h"
#include "skill_check.h"

#define EXEC_MAX_STEPS 8u

/* The executor's numeric layer, chosen by the build like the core's (fs_num.h): FS_EXEC_NUM
 * names its header (fs_control_exec_fx: "exec_num_fixed.h", the DMP and the law in fixed point
 * with an integer tick), otherwise exec_num_real.h (fs_real_t: the core's DMP and law). It gives
 * the per-tick state's types (exec_nf_t forces, exec_nx_t x positions, exec_ny_t the y path, ...),
 * exec_num_t (its DMP run, law and constants), exec_model_t (a step's model) and, at the end of
 * this header, its operations; the tick itself (fs_exec.c) is written once over them. */
#ifdef FS_EXEC_NUM
#include FS_EXEC_NUM
#else
#include "exec_num_real.h"
#endif
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
    /* the fixed-point build's model of the skill (not owned, required there: exec_model_t,
     * converted beforehand); the real executors run skill->dmp and ignore it */
    const exec_model_t *model_fx;
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


/** Execution state (sequence, DMP, reference model, controller integral), in the layer's types. */
typedef struct {
    exec_step_t steps[EXEC_MAX_STEPS];
    uint8_t n_steps;
    uint8_t step;
    uint8_t ending; /* 1 after the last step's duration: end policy active */
    uint8_t done;
    exec_ndmp_t dmp;      /* the running step's DMP state */
    exec_num_t n;         /* the layer's run, law and constants */
    uint32_t step_ticks;  /* ticks of the running step (its duration at dt, set at its start) */
    uint32_t step_tick;   /* ticks of the running step done */
    exec_nclock_t t_step; /* time (ticks) since the running step started */
    exec_nclock_t t_end;  /* time (ticks) since the end policy started */
    exec_nf_t f_dmp;      /* last DMP output of the running step (its start force at a switch) */
    exec_nf_t f_hat;      /* last f_hat */
    exec_nf_t f_carry;    /* previous step's last f_hat, faded out over EXEC_BLEND_S */
    exec_nf_t f_end;      /* f_hat when the end policy started */
    exec_nx_t ref_p;      /* reference deformation p_d, its rate and acceleration */
    exec_nx_t ref_pd;
    exec_nx_t ref_pdd;
    exec_nx_t ref_prev_pos; /* model-free reference: previous x_d (for xd_d) */
    exec_nx_t surface;      /* the surface the reference is built on */
    exec_ny_t y_hold;       /* y_base: the running step's path starts here */
    exec_ny_t path;         /* p of the running step's y DMP */
    exec_ny_t y_ref;        /* y_d = y_base + p */
    exec_nx_t y_ref_vel;    /* yd_d */
    fs_real_t y_start_m;    /* the y position exec_start was given */
    uint8_t start_pending;  /* 1 until the first tick has measured the contact force */
    uint8_t path_ramp;      /* 1 while a periodic y path ramps in (its first turn) */
    uint8_t path_ramp_out;  /* 1: it ramps out over the step's last turn (a known length) */
    uint8_t prepared;       /* parts of exec_start_run done (exec_prep_parts) */
    uint8_t prep_next;      /* 1 while a discrete step runs before its end policy: the next
                               tick steps its DMP (exec_prepare_next computes the blend) */
    /* the running skill's contact wait (skill_t.contact_threshold_N > 0) */
    exec_nrate_t contact_rate; /* the phase rate, 0..1 (1 without a contact wait) */
    exec_nsum_t contact_hold;  /* sum of (1 - rate) (times dt in the real layer) */
    exec_nsum_t contact_defer; /* ticks held not yet added to the running step's length */
    uint16_t contact_losses;   /* losses of contact counted */
    uint8_t contact_lost;      /* contact lost at the last tick */
    /* the demonstrated band's check (a step whose skill has one, skill_t.band_n > 0): each tick
     * of the step before its end policy, the measured contact force less the carry's share of
     * f_hat against the band at the step's normalised time (advanced at the contact wait's
     * phase rate), scaled as f_hat (skill_band_at); counts in ticks since exec_start */
    exec_nturn_t band_s;         /* normalised time t/T of the step */
    exec_nwidth_t band_max;      /* the largest excursion beyond the band (band widths) */
    uint32_t band_run_ticks;     /* ticks since exec_start */
    uint32_t band_checked_ticks; /* ticks checked against a band */
    uint32_t band_out_ticks;     /* ticks outside it */
    uint32_t band_streak_ticks;  /* consecutive ticks outside up to the last */
    uint32_t band_longest_ticks; /* the longest such run */
    uint32_t band_first_tick;    /* band_run_ticks at the first tick outside (0: none) */
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
 *  loaded and the law's configuration (exec_start_begin, the same codes; or its two halves in
 *  calls of their own: exec_start_load, the steps' checks and the sequence held, then
 *  exec_start_reset, the configuration's checks and the state's reset), then each
 *  exec_start_run derives one part of the steps' or the configuration's integer constants
 *  (exec_prep_parts of them: the fixed-point build; 3xx codes) or, once all are, starts the
 *  first step and sets *done. Nothing runs before *done. */
fs_status_t exec_start_begin(const exec_config_t *cfg, exec_state_t *st, const exec_step_t *steps,
                             uint8_t n_steps, fs_real_t y_hold_m);
/** exec_start_begin's first half: the steps and y_hold_m checked and held (nothing changed on a
 *  refusal). */
fs_status_t exec_start_load(exec_state_t *st, const exec_step_t *steps, uint8_t n_steps,
                            fs_real_t y_hold_m);
/** exec_start_begin's second half: cfg checked (a refusal leaves the held sequence unstarted),
 *  the state reset for the held sequence. */
fs_status_t exec_start_reset(const exec_config_t *cfg, exec_state_t *st);
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

/** The layer's native measurements and outputs (exec_tick's in the real layer; Q formats,
 *  exec_meas_q_t and exec_out_q_t, in the fixed-point one). */
typedef EXEC_NUM_MEAS_N exec_meas_n_t;
typedef EXEC_NUM_OUT_N exec_out_n_t;

/** exec_tick on the layer's native measurements and outputs (the real layer: exec_tick itself;
 *  the fixed-point one: in integers only, every constant derived by exec_start), the same codes.
 *  The fixed-point build's exec_tick converts its measurements in and calls it. */
fs_status_t exec_tick_n(const exec_config_t *cfg, exec_state_t *st, const exec_meas_n_t *meas,
                        exec_out_n_t *out);

/** The largest excursion beyond the band so far, in thousandths of a band width (0 without
 *  one; saturated at 65535). */
uint16_t exec_band_max_milli(const exec_state_t *st);

/** How long the phase of the execution held for contact (the contact wait's sum of
 *  (1 - rate)*dt), rounded to ms (0 without a contact wait). */
uint32_t exec_contact_hold_ms(const exec_state_t *st);

/** The contact wait's phase rate at the last tick, 0..1 (1 without a contact wait). */
fs_real_t exec_contact_rate(const exec_state_t *st);

/** The reference force f_hat of the last tick, N. */
fs_real_t exec_force_hat_N(const exec_state_t *st);

/* ---- Velocity estimation (encoder difference + first-order low-pass) ---- */

/** Velocity estimator state of one axis. */
typedef struct {
    fs_real_t prev_pos_m;
    fs_real_t vel_mps;
    fs_real_t alpha; /* low-pass coefficient dt/(dt + 1/(2 pi fc)) */
    uint8_t primed;
    exec_vel_n_t n; /* the layer's estimator (the fixed-point build's integer one) */
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

/* ---- Helpers of the executor and its layers' preparation ---- */

/* The most ticks of a step (46 days at 1 kHz): a periodic step run until stopped. */
#define EXEC_TICKS_MAX 4000000000u

/** t_s in ticks of dt_s, rounded (0 for t <= 0, EXEC_TICKS_MAX beyond 4e9). */
static inline uint32_t exec_ticks(fs_real_t t_s, fs_real_t dt_s)
{
    fs_real_t n = t_s / dt_s + FS_R(0.5);
    if (!(n > FS_R(0.0))) {
        return 0u;
    }
    if (n > FS_R(4.0e9)) {
        return EXEC_TICKS_MAX;
    }
    return (uint32_t)n;
}

/** The step's first force: f0, or a periodic step's f0 + goal_scale*g + amplitude_scale*e0. */
static inline fs_real_t exec_step_start_force(const exec_step_t *s)
{
    const dmp_model_t *m = &s->skill->dmp;
    if (m->periodic == 0u) {
        return m->force0_N;
    }
    return m->force0_N + s->goal_scale * m->goal_N + s->amplitude_scale * m->cycle_e0_N;
}

/** The step's length: duration_s, or (<= 0) the skill's T times time_scale. */
static inline fs_real_t exec_step_duration(const exec_step_t *s)
{
    if (s->duration_s > FS_R(0.0)) {
        return s->duration_s;
    }
    return s->skill->dmp.duration_s * s->time_scale;
}

/** The step's length in ticks of dt_s (EXEC_TICKS_MAX: a periodic step until stopped). */
static inline uint32_t exec_step_ticks(const exec_step_t *s, fs_real_t dt_s)
{
    return (s->skill->dmp.periodic != 0u && s->until_stopped != 0u)
               ? EXEC_TICKS_MAX
               : exec_ticks(exec_step_duration(s), dt_s);
}

/* A path a caller rarely takes (a telemetry count's edge case): out of its hot code. */
#if defined(__GNUC__)
#define EXEC_COLD __attribute__((cold))
#else
#define EXEC_COLD
#endif

/** A telemetry count's edge (the real layer's exec_*_counts): r = v / scale with |r| >= hi or
 *  NaN: clamped to lo..hi, NaN and inf 0, or rounded half away from zero (lo < r <= -hi). */
EXEC_COLD int32_t exec_counts_edge(fs_real_t v, fs_real_t r, int32_t lo, int32_t hi);

/* the layer's operations (fs_exec.c's tick is written over them) and its native API */
#include EXEC_NUM_API

/** The next exec_tick's DMP kernel blend computed now (dmp_prepare, dmpfx_prepare; in the
 *  fixed-point layer also the object model's forces) while a discrete step runs, nothing
 *  otherwise: called after a tick's output, the next tick gives the same result with that work
 *  already done. Inline: the application's tick calls it once. */
static inline void exec_prepare_next(exec_state_t *st)
{
    /* the state the next tick steps: the running step's (exec_reference_force); the fixed-point
     * layer also the object model's forces of the reference's present state */
    if (st->prep_next != 0u) {
        exec_num_dmp_prepare(st, &st->steps[st->step]);
        exec_num_model_prepare(st);
    }
}

#endif /* FS_EXEC_H */

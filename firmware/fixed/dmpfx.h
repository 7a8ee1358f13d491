/* The force DMP in fixed point (docs/cortex-m.md), for a Cortex-M3 without FPU:
 * the blend and the Euler step are firmware/core/dmp_tick.h (the same source as dmp_step)
 * compiled over the fixed numeric layer (fs_num.h, formats in fx.h); this module converts a
 * skill, derives the per-tick constants and wraps the step. A skill is parsed in double (skill_parse)
 * and converted once by dmpfx_from_model, which rejects values that do not fit (3xx codes).
 * docs/cortex-m.md describes the formats, bounds and measured accuracy. */
#ifndef DMPFX_H
#define DMPFX_H

#include <stdbool.h>
#include <stdint.h>
#include "dmp.h"
#include "fs_job.h"
#include "fx.h"

/* Most kernels that may be evaluated in one tick (the candidate window): bounded at conversion
 * so the tick has a fixed worst case. The default fit (sigma = half spacing) needs 6. */
#ifndef DMPFX_MAX_WINDOW
#define DMPFX_MAX_WINDOW 32u
#endif
/* Largest magnitude accepted for a Q8.24 quantity (the dimensionless weights; goal and the peaks
 * of h, y, z, I over the run in units of 2^s N): 64 = half the Q8.24 range, one bit of headroom for coupling
 * and disturbances. */
#define DMPFX_Q24_HEADROOM 64.0
/* The value scale 2^s is chosen so that the nominal run's peak of |h|, |y|, |z|, |I| times 2^-s
 * is at most this: goal scales up to 64/8 = 8 stay within the headroom. */
#define DMPFX_SCALE_TARGET 8.0
/* Range of the value-scale exponent s: 2^s in Q20.12 needs -12 <= s <= 18. */
#define DMPFX_SHIFT_MIN (-12)
#define DMPFX_SHIFT_MAX 18
/* Largest phase velocity v~ accepted (Q2.30 holds |v| < 2). */
#define DMPFX_V_MAX 1.9

/** A skill in fixed point (what dmpfx_from_model fills); the kernel fields have dmp_model_t's
 *  names (dmp_tick.h reads both). */
typedef struct {
    uint16_t n_kernels;
    int32_t centre[DMP_MAX_KERNELS];       /* Q2.30 */
    int32_t kernel_scale[DMP_MAX_KERNELS]; /* 1/sigma_i, Q13.19 */
    int32_t weight[DMP_MAX_KERNELS];       /* Q8.24 */
    int32_t env_lo[DMP_MAX_KERNELS];       /* Q2.30 suffix min of c_i - r sigma_i, r = sqrt(32) */
    int32_t env_hi[DMP_MAX_KERNELS];       /* Q2.30 prefix max of c_i + r sigma_i */
    int32_t out_scale_q12;                 /* 2^s: N per unit of y, z, I, h, g (Q20.12) */
    int32_t value_shift;                   /* s: values are stored as N * 2^-s */
    int32_t force0_q16;                    /* starting force f0, N, Q16.16 */
    /* scalars kept in double for dmpfx_run_init (run set-up, not the tick) */
    double dt_s;
    double tau_s;
    double alpha;
    double beta;
    double gamma;
    double goal_N;
    /* peaks of the nominal run (goal 1, time 1, no coupling), for dmpfx_run_init's check:
     * max |h|, |y|, |z|, |I| in Q8.24 units and max |v~| in Q2.30 units */
    double peak_q24;
    double peak_v_q30;
    /* the position DMP on y (has_y = 1): weights and values in m, Q8.24 without a scale (a
     * path of 0.1 m is 1.7e6 LSB) */
    uint8_t has_y;
    int32_t y_weight[DMP_MAX_KERNELS]; /* Q8.24 m */
    double beta_y;
    double goal_y_m;
    double peak_y_q24; /* max |h_y|, |p|, |z_p| of the nominal run (path scale 1) */
    /* the periodic DMP (periodic = 1, dmp_ptick.h): env_lo/env_hi in turns (Q2.30), kernel_scale
     * 2 sqrt(kappa_i) (Q13.19), sin/cos(c_i/2) in Q1.31 (+-1 held at +-INT32_MAX); amplitude r and the cycle state
     * (e0, z0, I0) in N kept in double for the run set-up; the nominal run is one cycle */
    uint8_t periodic;
    int32_t half_sin[DMP_MAX_KERNELS]; /* sin(c_i/2), Q1.31 */
    int32_t half_cos[DMP_MAX_KERNELS];
    double amplitude_N;
    double cycle0_N[3];
    double cycle_y0_m[2]; /* the y path's (q, z_q) at phi = 0 (has_y) */
} dmpfx_model_t;

/** Per-run constants: dt/tau_e * {1, alpha, alpha*beta, gamma} in Q1.31 and g_e in Q8.24. */
typedef struct {
    int32_t k1_q31;
    int32_t k_alpha_q31;
    int32_t k_alphabeta_q31;
    int32_t k_gamma_q31;
    int32_t goal_q24;
    /* the y DMP: dt/tau_e*alpha*beta_y, the scaled goal and the path scale (dmpfx_run_path) */
    int32_t k_alphabeta_y_q31;
    int32_t goal_y_q24;
    int32_t path_scale_q24;
    /* the periodic DMP: the phase increment (turns * 2^61 a step), s_a*r in Q8.24 (units of 2^s
     * N) and the amplitude scale s_a (dmpfx_run_periodic) */
    int64_t phase_inc;
    int32_t amplitude_q24;
    double amplitude_scale;
} dmpfx_run_t;

/** Fixed-point DMP state. Each state is kept as the exact 64-bit sum of its Euler increments
 *  (Q1.31 constant * Q8.24 or Q2.30 value = Q.55 / Q.61, i.e. the value << 31); products use the
 *  value rounded to Q8.24 / Q2.30 (dmpfx_view). Rounding every step instead drifts by up to
 *  0.5 LSB per tick while an increment is nearly constant (a force plateau): measured 0.13 %
 *  of max force on engrave_n50 at time scale 1.3 (docs/cortex-m.md). Each sum is kept within
 *  +-(2^30 - 1)*2^32 so its view fits int32. sat_events counts saturations (0 in a valid run:
 *  values never wrap). window: the last step's kernel window (a hint, as dmp_state_t's). */
typedef struct {
    uint16_t window[2];
    int64_t u_acc;
    int64_t v_acc;
    int64_t integral_y_acc;
    int64_t y_acc;
    int64_t z_acc;
    int64_t path_acc;   /* p of the y DMP, m */
    int64_t path_z_acc; /* z_p */
    int64_t u_comp_acc; /* the periodic phase sum's compensation: 0 (the sum is exact) */
    uint32_t sat_events;
    /* the kernel blend dmpfx_prepare computed ahead for the next step, at the phase view prep_u
     * (Q2.30) of model prep_model (NULL: none); the step takes it once */
    const void *prep_model;
    int32_t prep_u;
    int32_t prep_s;  /* S(u), Q8.24 */
    int32_t prep_sy; /* S_y(u), Q8.24 (has_y) */
} dmpfx_state_t;

/** A state's value in its working format (Q2.30 for u~, v~; Q8.24 for I, x, z). */
static inline int32_t dmpfx_view(int64_t acc)
{
    return fx_acc_view(acc);
}

/** Coupling: term_y added to tau*yd (Q8.24, in the model's units of 2^s N) and rate = 1/(1 + phase_slowdown) in Q1.31
 *  (unsigned, 1.0 = 2^31 means no slow-down). */
typedef struct {
    int32_t term_y_q24;
    uint32_t rate_q31;
} dmpfx_coupling_t;

/** Convert a validated double model (dmp_model_init done) into fixed point, then roll the
 *  nominal run (goal 1, time 1) out once in fixed point to measure the peaks of h, y, z, I and
 *  v~ (the system is linear in g with zero initial conditions, so a goal scale s scales them by
 *  |s| exactly; the time scale changes them only by O(dt/tau)). Cost: two rollouts, T/dt steps each.
 *  Errors: FS_ERR_FIXED_OVERFLOW (300) a value does not fit its format (1/sigma >= 4096, |w| or
 *  g beyond the value scale's range, f0 beyond Q16.16, a peak > 64 or |v~| > 1.9, or a saturation
 *  in the nominal run). The forces (g, y, z, I, h) are kept in N * 2^-s, s the smallest
 *  exponent that puts the nominal run's peak at or below DMPFX_SCALE_TARGET (an exact
 *  power-of-two scaling: the fixed-point accuracy does not depend on the force level or on k;
 *  it costs a second rollout at conversion),
 *  FS_ERR_FIXED_WINDOW (301) too many overlapping kernels, FS_ERR_FIXED_STEP, FS_ERR_NULL_ARG. */
fs_status_t dmpfx_from_model(const dmp_model_t *m, dmpfx_model_t *out);

/** dmpfx_from_model without its rollouts, O(N): for a conversion within a control tick (the
 *  fixed-point executor converts a skill when its step begins). The peaks are estimated instead
 *  of measured: of h, y, z, I as B = |g|*(1 + max|w_i|) in N (the measured nominal peak is at
 *  most 0.50 B on every skill of tests/vectors), of the y DMP as |g_y| + 1.9 max|w_y,i|, of v~
 *  as 1.01 sqrt(alpha beta)/e; the value scale 2^s puts B at or below DMPFX_SCALE_TARGET (one to
 *  five bits coarser than the measured scale, tests/firmware/fixed). A run beyond the estimate saturates (never
 *  wraps) and is counted in dmpfx_state_t.sat_events. Errors as dmpfx_from_model, the estimate
 *  checked where the measured peaks are. */
fs_status_t dmpfx_from_model_bound(const dmp_model_t *m, dmpfx_model_t *out);

/** dmpfx_from_model_bound in slices (dmpfx_bound_begin, then dmpfx_bound_run until it returns
 *  true), so a device converts a skill over several control ticks: the same checks in the same
 *  order and the same model. A unit is the force bound, the scale's choice, one kernel, the
 *  envelope passes, one window check, the scalars, or the peaks. m and *out must stay in place until it is done. */
typedef struct {
    const dmp_model_t *m;
    dmpfx_model_t *out;
    double bound_N; /* B of dmpfx_from_model_bound */
    uint32_t pos;   /* progress inside the stage */
    uint8_t stage;  /* internal */
    bool done;
    fs_status_t status; /* FS_OK while running or once converted; the refusal once done */
} dmpfx_conv_t;

/** Start a sliced conversion of m into *out (a NULL or kernel-count error ends it at once). */
void dmpfx_bound_begin(dmpfx_conv_t *c, const dmp_model_t *m, dmpfx_model_t *out);

/** At most max_units units of the conversion; true once done (then c->status). */
bool dmpfx_bound_run(dmpfx_conv_t *c, uint32_t max_units);

/** Per-tick constants for a goal and time scale; FS_ERR_SCALE_INVALID for a bad scale,
 *  FS_ERR_FIXED_STEP (302) if dt/tau_e is below 2^-24 or a constant is >= 0.5,
 *  FS_ERR_FIXED_OVERFLOW if |goal_scale| times the nominal peaks leaves the Q8.24 headroom. */
fs_status_t dmpfx_run_init(const dmpfx_model_t *m, double goal_scale, double time_scale,
                           dmpfx_run_t *run);

/** The force DMP's part of dmpfx_run_init (its checks and codes), leaving the periodic and y
 *  constants to dmpfx_run_periodic and dmpfx_run_path: a caller that sets those itself, each in
 *  its own slice. */
fs_status_t dmpfx_run_force(const dmpfx_model_t *m, double goal_scale, double time_scale,
                            dmpfx_run_t *run);

/** dmpfx_run_force in two slices (each a bounded piece of software double on the M3): the
 *  scales' checks and the step's rates, ... */
fs_status_t dmpfx_run_rates(const dmpfx_model_t *m, double goal_scale, double time_scale,
                            dmpfx_run_t *run);

/** ... then the phase's increment and the goal (FS_ERR_FIXED_OVERFLOW beyond the headroom). */
fs_status_t dmpfx_run_goal(const dmpfx_model_t *m, double goal_scale, double time_scale,
                           dmpfx_run_t *run);

/** The y DMP's constants in run (after dmpfx_run_init, which sets path scale 1): path scale
 *  finite and >= 0 (FS_ERR_SCALE_INVALID), |path_scale| times the nominal peaks within the
 *  Q8.24 headroom (FS_ERR_FIXED_OVERFLOW). A model without a y DMP: FS_OK, nothing to set. */
fs_status_t dmpfx_run_path(const dmpfx_model_t *m, double path_scale, dmpfx_run_t *run);

/** Zero initial conditions. */
void dmpfx_state_reset(dmpfx_state_t *s);

/** S(u) = sum psi_i w_i / sum psi_i in Q8.24 at phase u (Q2.30), window + cutoff 12 + e_min
 *  shift (dmp_tick_blend); *count (may be NULL) receives the number of kernels summed. */
int32_t dmpfx_blend(const dmpfx_model_t *m, int32_t u_q30, uint16_t *count);

/** One forward-Euler step (dmp_tick_step, all right-hand sides at the old state); coupling may
 *  be NULL. Returns f_hat = f0 + 2^s*y after the step in Q16.16 N. */
int32_t dmpfx_step(const dmpfx_model_t *m, const dmpfx_run_t *run, dmpfx_state_t *s,
                   const dmpfx_coupling_t *coupling);

/** The kernel blend of the next dmpfx_step / dmpfx_step_xy of m at the state's present phase,
 *  computed now (the state's window walked there): that step then takes it instead of
 *  computing it, with the same result. For work done after a tick's output rather than before
 *  it; a step at another phase or of another model computes its own. A discrete model only. */
void dmpfx_prepare(const dmpfx_model_t *m, dmpfx_state_t *s);

/** dmpfx_step and, with has_y, the y DMP's step on the same phase (each kernel activation
 *  computed once for both); *path_q24 (may be NULL) receives p after the step, Q8.24 m above
 *  the path's start (0 without a y DMP). Returns f_hat as dmpfx_step. */
int32_t dmpfx_step_xy(const dmpfx_model_t *m, const dmpfx_run_t *run, dmpfx_state_t *s,
                      const dmpfx_coupling_t *coupling, int32_t *path_q24);

/** The periodic DMP's amplitude scale s_a in run (after dmpfx_run_init, which sets 1): finite
 *  and >= 0 (FS_ERR_SCALE_INVALID), s_a times the nominal peaks within the Q8.24 headroom
 *  (FS_ERR_FIXED_OVERFLOW). A discrete model: FS_OK, nothing to set. */
fs_status_t dmpfx_run_periodic(const dmpfx_model_t *m, double amplitude_scale, dmpfx_run_t *run);

/** A periodic model's start: phase 0, (e, z, I) = s_a times the cycle state (run's s_a), the
 *  window found by search; with a y path (q, z_q) = s_p times its cycle state (the run's path
 *  scale: dmpfx_run_path before this). */
void dmpfx_periodic_reset(const dmpfx_model_t *m, const dmpfx_run_t *run, dmpfx_state_t *s);

/** S(x) of a periodic model at phase x in turns (Q2.30, [0, 1)), Q8.24; *count (may be NULL)
 *  the number of kernels summed. */
int32_t dmpfx_periodic_blend(const dmpfx_model_t *m, int32_t x_q30, uint16_t *count);

/** One step of a periodic model (dmp_ptick_step over the fixed layer); coupling may be NULL.
 *  Returns f_hat = f0 + 2^s*(g_e + e) after the step in Q16.16 N. */
int32_t dmpfx_periodic_step(const dmpfx_model_t *m, const dmpfx_run_t *run, dmpfx_state_t *s,
                            const dmpfx_coupling_t *coupling);

/** dmpfx_periodic_step and, for a model with has_y, the periodic y path's step on the same
 *  phase (each activation once for both; the run's path scale). *path_q24 (may be NULL)
 *  receives p = s_p*g_y + q after the step in Q8.24 m (0 without a y path). */
int32_t dmpfx_periodic_step_xy(const dmpfx_model_t *m, const dmpfx_run_t *run, dmpfx_state_t *s,
                               const dmpfx_coupling_t *coupling, int32_t *path_q24);

/** A skill's own rollout in fixed point (the device's output check, skill_check.h's step 2 on
 *  the model the fixed-point executor runs): goal, time, path and amplitude scale 1, no coupling,
 *  the skill's duration at the executor's dt, each step's |f_hat| (a periodic model: the bound
 *  |f0| + g + |e|) and |p| of the y DMP tracked in integers. A path above path_max_m (225) or a
 *  peak above force_max_N (223) refuses, as skchk_run does, and so does a saturation (300: the
 *  executor would saturate). Incremental: dmpfx_check_begin, then dmpfx_check_run with a step
 *  budget per call. */
typedef struct {
    const dmpfx_model_t *m;
    dmpfx_run_t run;
    dmpfx_state_t s;
    uint32_t steps_total;
    uint32_t steps_done;
    int32_t force_max_q16; /* force_max_N in Q16.16 (saturated) */
    int32_t path_max_q24;  /* path_max_m in Q8.24 (saturated) */
    int32_t base_q16;      /* a periodic model: |f0| + g in Q16.16 */
    int32_t goal_q16;      /* a periodic model: g in Q16.16 */
    int32_t peak_q16;      /* max |f_hat| so far */
    int32_t path_peak_q24; /* max |p| so far (0 without a y DMP) */
    fs_status_t status;    /* FS_OK while running or passed; 223/225/300 or a 3xx of the set-up */
    fs_job_t job;          /* the rest of the set-up, then the steps (dmpfx_check_run) */
    bool done;
} dmpfx_check_t;

/** Start the rollout check of m (a converted model) over duration_s at dt_s against the force
 *  limit force_max_N and the y range path_max_m. */
void dmpfx_check_begin(dmpfx_check_t *c, const dmpfx_model_t *m, float duration_s, float dt_s,
                       float force_max_N, float path_max_m);

/** dmpfx_check_run's first calls, the rest of the set-up (the goal; the periodic constants; the
 *  path's; the starting state), each without a step. */
#define DMPFX_CHECK_SET_UP_CALLS 4u

/** Advance by at most max_steps DMP steps (the first DMPFX_CHECK_SET_UP_CALLS calls: the rest of
 *  the set-up, no step); true once finished (then c->status). */
bool dmpfx_check_run(dmpfx_check_t *c, uint32_t max_steps);

/** The check's peak |f_hat| (N) so far. */
float dmpfx_check_peak_N(const dmpfx_check_t *c);

/** The check's path extent max |p| (m) so far. */
float dmpfx_check_path_m(const dmpfx_check_t *c);

#endif /* DMPFX_H */

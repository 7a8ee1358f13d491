/* The force DMP (the paper's eqs. 11-17 corrected): parameters from gains, the learned system
 * with its phase, and one forward-Euler step per tick. Pure functions over explicit structs: no
 * heap, no I/O, bounded work per step. See docs/math.md for the derivation. It runs in force
 * units: y = k*x - f0 (N above the starting force f0), g, z, I and h in N (the weights w_i are
 * dimensionless, h/(g*v~)):
 *
 *   tau*yd  = z - y - gamma*I + h + c_y       tau*zd = alpha*(beta*(g - y) - z)    tau*Id = y
 *   tau*vd~ = alpha*(beta*(1 - u~) - v~)      tau*ud~ = v~
 *   h = g*v~ * sum(psi_i*w_i)/sum(psi_i),     psi_i = exp(-(u~ - c_i)^2 / (2*sigma_i^2))
 *   f_hat = f0 + y
 * with tau -> tau*time_scale*(1 + phase_slowdown) and g -> g*goal_scale at run time. Nothing here
 * depends on the stiffness k: it enters only the execution reference and the controller gains
 * (dmp_gains_at_stiffness).
 * A skill may also hold the position DMP on y (paper eq. 9: the same law with k_f = k_i = 0), on
 * the same phase and kernels, with its own weights w_y (m), goal g_y (m) and beta_y:
 *   tau*pd = z_p - p + h_y      tau*z_pd = alpha*(beta_y*(s_p*g_y - p) - z_p)
 *   h_y = s_p*v~ * sum(psi_i*w_y_i)/sum(psi_i),   y_hat = y_start + p
 * s_p the path scale (the path scales about its start); dmp_step_xy advances both. */
#ifndef DMP_H
#define DMP_H

#include <stdbool.h>
#include <stdint.h>
#include "fs_real.h"
#include "fs_status.h"
#include "pfc.h"

#ifndef DMP_MAX_KERNELS
#define DMP_MAX_KERNELS 1024u
#endif

/* Kernels with (u~-c_i)^2/(2 sigma_i^2) above this are skipped. exp(-23) ~ 1e-10, so the
 * truncated sum equals the full sum within 1e-9 relative (4 sigma, exp(-8) = 3.4e-4, does not). */
#ifndef DMP_KERNEL_CUTOFF_EXP
#define DMP_KERNEL_CUTOFF_EXP 23.0
#endif

/* beta <= alpha/4 is checked with this relative tolerance: the default gains give beta = alpha/4
 * exactly in real numbers, and round-off must not turn that into a rejection. */
#define DMP_MONOTONE_REL_TOL 1e-9

/* The same tolerance in the core's own type: float cannot resolve 1e-9, so the float build
 * allows a few ulp (a skill accepted in double must stay accepted after rounding to float). */
#ifdef FS_REAL_FLOAT
#define DMP_MONOTONE_REL_TOL_REAL 1e-6f
#else
#define DMP_MONOTONE_REL_TOL_REAL DMP_MONOTONE_REL_TOL
#endif

/** DMP parameters derived from the gains (corrected eq. 14 in force units). */
typedef struct {
    fs_real_t alpha;
    fs_real_t beta;
    fs_real_t gamma;
} dmp_params_t;

/** Gains a skill is fitted with, independent of the stiffness k: the force gains are stored
 *  scaled, kkf = k*k_f (N/m) and kki = k*k_i (N/(m s)). Defaults 40, 400, 1170, 540, 4860. */
typedef struct {
    fs_real_t m_d_kg;
    fs_real_t k_d_Nspm;
    fs_real_t k_p_Npm;
    fs_real_t kkf_Npm;
    fs_real_t kki_Npms;
} dmp_gains_t;

/** The one derivation, in double (skill_parse checks stored float64 values with it):
 *  gain[] = {m_d, k_d, k_p, kkf, kki} -> abg[] = {alpha, beta, gamma}, alpha = k_d/m_d - 1,
 *  gamma = kki/(m_d*alpha), beta = (k_p + (kkf - kki/alpha))/(m_d*alpha) - 1. Checks, first
 *  failure reported: any input not finite (101); m_d <= 0 (102); a gain < 0 (107); k_d <= m_d
 *  (103); a derived value not finite (101); beta <= 0 (104: beta > 0 with alpha > 0 implies the
 *  closed loop is Routh-Hurwitz stable); beta > alpha/4*(1 + DMP_MONOTONE_REL_TOL) (105).
 *  abg[] is written only on success. */
fs_status_t dmp_derive_f64(const double gain[5], double abg[3]);

/** The parts of dmp_derive_f64 (one double division each: a bounded slice on a core without a
 *  double FPU). */
#define DMP_DERIVE_PARTS 4u

/** Part part (0 .. DMP_DERIVE_PARTS - 1, called in order) of dmp_derive_f64 into work, which
 *  holds alpha, beta, gamma after the last part succeeds; dmp_derive_f64's codes (100 also for
 *  a part out of range). */
fs_status_t dmp_derive_f64_part(const double gain[5], double work[3], uint32_t part);

/** dmp_derive_f64 in the core's type: NULL (100), then its checks, with the float build's
 *  tolerance DMP_MONOTONE_REL_TOL_REAL for beta <= alpha/4. On error *out is zeroed. */
fs_status_t dmp_params_from_gains(const dmp_gains_t *gains, dmp_params_t *out);

/** Controller gains on an object of nominal stiffness k: k_f = kkf/k, k_i = kki/k (m_d, k_d,
 *  k_p copied). NULL (100); k not finite (101) or <= 0 (106); a result not finite (101). */
fs_status_t dmp_gains_at_stiffness(const dmp_gains_t *gains, fs_real_t stiffness_Npm,
                                   pfc_axis_gains_t *out);

/** Goal trajectory in N, k*g'(t) = c/(alpha*beta), c = (k_p*(k*x_d) + kkf*f_d + kki*int_f_d)/m_d,
 *  the position reference given as the force k*x_d it stands for. */
fs_real_t dmp_goal(const dmp_params_t *p, const dmp_gains_t *gains, fs_real_t ref_force_N,
                   fs_real_t force_d_N, fs_real_t force_d_integral_Ns);

/** A learned force skill ready to evaluate (what skill_parse fills). Derived arrays are set by
 *  dmp_model_init; do not fill them by hand. */
typedef struct {
    uint16_t n_kernels;
    dmp_params_t p;
    fs_real_t dt_s;
    fs_real_t tau_s;
    fs_real_t goal_N;
    fs_real_t force0_N; /* starting force f0: f_hat = f0 + y */
    fs_real_t duration_s;
    fs_real_t centre[DMP_MAX_KERNELS];
    fs_real_t width[DMP_MAX_KERNELS]; /* sigma_i */
    fs_real_t weight[DMP_MAX_KERNELS];
    /* derived by dmp_model_init */
    fs_real_t kernel_scale[DMP_MAX_KERNELS]; /* 1/(2 sigma_i^2): e_i = (u~ - c_i)^2 * this */
    fs_real_t env_hi[DMP_MAX_KERNELS];       /* prefix max of c_i + r*sigma_i (non-decreasing) */
    fs_real_t env_lo[DMP_MAX_KERNELS];       /* suffix min of c_i - r*sigma_i (non-decreasing) */
    /* the position DMP on y (has_y = 1), on the same phase and kernels */
    uint8_t has_y;
    fs_real_t beta_y;                    /* k_p/(m_d*alpha) - 1 (gamma = 0) */
    fs_real_t goal_y_m;                  /* g_y: the DMP's goal, m above the path's start */
    fs_real_t y_start_m;                 /* where the demonstrated path started */
    fs_real_t y_weight[DMP_MAX_KERNELS]; /* m: h_y = v~*S_y */
    /* the periodic DMP (periodic = 1, docs/math.md section 5; with has_y the y path about its
     * mean goal_y_m, the same y_weight[] and beta_y, from its cycle state): centre[] holds the
     * angles c_i in [0, 2 pi), width[] the von Mises concentrations kappa_i, duration_s the
     * period 2 pi tau; derived: kernel_scale[] = 2 kappa_i, env_lo/env_hi in turns (of the
     * phase x = phi/(2 pi)), half_sin/half_cos = sin/cos(c_i/2) */
    uint8_t periodic;
    fs_real_t amplitude_N; /* r: h = s_a*r*S */
    fs_real_t cycle_e0_N;  /* (e, z, I) of the orbit at phi = 0 */
    fs_real_t cycle_z0_N;
    fs_real_t cycle_i0_N;
    fs_real_t cycle_q0_m; /* the y path's (q, z_q) at phi = 0 (q = p - g_y) */
    fs_real_t cycle_zq0_m;
    fs_real_t half_sin[DMP_MAX_KERNELS];
    fs_real_t half_cos[DMP_MAX_KERNELS];
} dmp_model_t;

/** Validate the model and fill the derived arrays (after centre/width/weight and scalars are set;
 *  periodic = 0 for the discrete DMP).
 *  Checks in skill-image order: NULL (100); 1 <= N <= DMP_MAX_KERNELS (205); every value finite
 *  (206); 0 < dt <= 0.1, tau > 0, 0 < T <= 3600, g > 0, sigma_i > 0 and 1/(2 sigma_i^2)
 *  finite (207); centres strictly increasing in [0, 1] (208); alpha > 0, beta > 0, gamma >= 0,
 *  beta <= alpha/4*(1 + DMP_MONOTONE_REL_TOL_REAL) (209). With has_y: goal_y, y_start and
 *  y_weight[] finite (206), 0 < beta_y <= alpha/4*(1 + tol) (209). A periodic model: its four
 *  scalars finite (206), r > 0 and kappa_i > 0 with 2 kappa_i finite (207), centres strictly
 *  increasing in [0, 2 pi) (208), and no y DMP (210). */
fs_status_t dmp_model_init(dmp_model_t *m);

/** dmp_model_init in slices (dmp_model_init_begin, then dmp_model_init_run until it returns
 *  true): the same checks in the same order and the same derived arrays, at most max_kernels
 *  kernels of one pass (or one of the scalar checks) per call; then it->status is
 *  dmp_model_init's result. */
typedef struct {
    uint8_t stage;      /* internal */
    uint16_t i;         /* the pass's next kernel */
    fs_real_t run;      /* the envelope's running max/min */
    fs_status_t status; /* FS_OK while running or once done and valid */
} dmp_init_t;

/** Start a sliced dmp_model_init. */
void dmp_model_init_begin(dmp_init_t *it);

/** At most max_kernels units of dmp_model_init of m; true once done (it->status). */
bool dmp_model_init_run(dmp_model_t *m, dmp_init_t *it, uint32_t max_kernels);

/** True if the next unit of dmp_model_init_run is a periodic kernel's reach (an arcsine and a
 *  square root: the derivation's dearest unit, ~2,500 instructions in software float). */
bool dmp_model_init_next_is_reach(const dmp_model_t *m, const dmp_init_t *it);

/** DMP state, DMP time: normalised phase u~, v~, the integral I of y, y = f_hat - f0 (N), z;
 *  window is the last step's kernel window [start, end) (a hint for the next: the result never
 *  depends on it). */
typedef struct {
    uint16_t window[2];
    fs_real_t u;
    fs_real_t v;
    fs_real_t integral_y;
    fs_real_t y_N;
    fs_real_t z;
    fs_real_t path_m; /* p: the y DMP's position above the path's start (0 without one) */
    fs_real_t path_z; /* z_p */
    fs_real_t u_comp; /* the periodic phase sum's compensation (dmp_ptick.h) */
    /* the kernel blend dmp_prepare computed ahead for the next step, at phase prep_u of model
     * prep_model (NULL: none); the step takes it once */
    const void *prep_model;
    fs_real_t prep_u;
    fs_real_t prep_s;  /* S(u) of the force weights */
    fs_real_t prep_sy; /* S_y(u) of the y weights (has_y) */
} dmp_state_t;

/** Run-time modulation: goal_scale multiplies g (and so f_hat), time_scale stretches tau. */
typedef struct {
    fs_real_t goal_scale;
    fs_real_t time_scale;
} dmp_run_t;

/** Coupling (optional): term_y (N) is added to tau*yd; phase_slowdown >= 0 multiplies tau by
 *  (1 + phase_slowdown) for every state, so the skill waits (e.g. for contact). */
typedef struct {
    fs_real_t term_y_N;
    fs_real_t phase_slowdown;
} dmp_coupling_t;

/** Validate run-time modulation: both scales finite, time_scale > 0 (109). goal_scale may be
 *  zero or negative (it scales the force linearly). */
fs_status_t dmp_run_validate(const dmp_run_t *run);

/** Zero initial conditions (y = 0: f_hat starts at f0). */
void dmp_state_reset(dmp_state_t *s);

/** Forcing term h at phase (u~, v~) and goal g, summing only kernels with
 *  e_i = (u~ - c_i)^2/(2 sigma_i^2) <= DMP_KERNEL_CUTOFF_EXP (found by binary search on the envelopes),
 *  psi_i = exp(-e_i) (dmp_tick.h); if none qualifies, the kernel with the smallest e_i
 *  alone (an O(N) scan that only happens when the phase is outside every kernel). */
fs_real_t dmp_forcing(const dmp_model_t *m, fs_real_t u, fs_real_t v, fs_real_t goal_N);

/** Forcing term h over all N kernels (reference for tests; not for the tick). */
fs_real_t dmp_forcing_full(const dmp_model_t *m, fs_real_t u, fs_real_t v, fs_real_t goal_N);

/** Number of kernels dmp_forcing sums at phase u~ (1 in the nearest-kernel fallback). */
uint16_t dmp_active_kernels(const dmp_model_t *m, fs_real_t u);

/** Phase slow-down for phase stopping: gain * err^2 (err = force tracking error, N); 0 if that is
 *  negative, +inf (phase frozen) if it is NaN. */
fs_real_t dmp_phase_stop_factor(fs_real_t force_err_N, fs_real_t gain_per_N2);

/** The contact wait's phase rate after one tick (docs/math.md, "A phase that waits for
 *  contact"): contact is lost while f_hat_N - f_contact_N > threshold_N (f_hat the last tick's
 *  reference), and the rate moves by gain = dt/(tau + dt) towards 0 while it is lost, towards 1
 *  otherwise (a NaN force counts as lost). */
fs_real_t dmp_contact_rate(fs_real_t rate, fs_real_t f_hat_N, fs_real_t f_contact_N,
                           fs_real_t threshold_N, fs_real_t gain);

/** The phase slow-down that also runs at rate (0..1) of the nominal: (1 + slowdown)/rate - 1,
 *  slowdown itself at rate >= 1, +inf (every state frozen) at rate <= 0 or NaN. */
fs_real_t dmp_slowdown_at_rate(fs_real_t slowdown, fs_real_t rate);

/** Advance the state by one step of dt_s (forward Euler, all right-hand sides at the old
 *  state, docs/math.md section 2; the step is dmp_tick.h, shared with dmpfx_step). run NULL means scales 1; coupling may be NULL (none); a
 *  phase_slowdown that is negative or NaN counts as 0, +inf freezes every state.
 *  Returns f_hat = f0 + y after the step. The caller validates run with dmp_run_validate. */
fs_real_t dmp_step(const dmp_model_t *m, dmp_state_t *s, const dmp_run_t *run,
                   const dmp_coupling_t *coupling);

/** dmp_step and, for a model with has_y, the y DMP's step on the same phase (the kernel
 *  activations computed once for both), path scale path_scale (not checked: finite, >= 0 is
 *  the caller's). *path_m (may be NULL) receives p after the step (m above the path's start,
 *  0 without a y DMP). Returns f_hat as dmp_step. */
fs_real_t dmp_step_xy(const dmp_model_t *m, dmp_state_t *s, const dmp_run_t *run,
                      const dmp_coupling_t *coupling, fs_real_t path_scale, fs_real_t *path_m);

/** The kernel blend of the next dmp_step / dmp_step_xy of m at the state's present phase,
 *  computed now (the state's window walked there): that step then takes it instead of
 *  computing it, with the same result. For work done after a tick's output rather than before
 *  it; a step at another phase or of another model computes its own. A discrete model only. */
void dmp_prepare(const dmp_model_t *m, dmp_state_t *s);

/** A periodic model's start (docs/math.md section 5): the phase at 0 turns, (e, z, I) = s_a
 *  times the stored cycle state, the kernel window found by search. s_a (the amplitude scale)
 *  is the caller's to validate (finite). */
void dmp_periodic_reset(const dmp_model_t *m, dmp_state_t *s, fs_real_t amplitude_scale);

/** S(x) of a periodic model at phase x in turns, 0 <= x < 1: the tick's blend (window, cutoff,
 *  nearest kernel); *count (may be NULL) the number of kernels summed. */
fs_real_t dmp_periodic_blend(const dmp_model_t *m, fs_real_t x_turns, uint16_t *count);

/** S(x) over all N kernels, psi_i = exp(-(e_i - e_min)) with e_i = kappa_i (1 - cos(2 pi x -
 *  c_i)) (the test reference; not for the tick). */
fs_real_t dmp_periodic_blend_full(const dmp_model_t *m, fs_real_t x_turns);

/** One step of a periodic model (dmp_ptick.h, forward Euler, every right-hand side at the old
 *  state): the phase advances dt/(2 pi tau_e) turns and wraps, tau_e = tau*time_scale*(1 +
 *  phase_slowdown); run NULL means scales 1, coupling may be NULL. Returns
 *  f_hat = f0 + goal_scale*g + e after the step. */
fs_real_t dmp_periodic_step(const dmp_model_t *m, dmp_state_t *s, const dmp_run_t *run,
                            fs_real_t amplitude_scale, const dmp_coupling_t *coupling);

/** dmp_periodic_step and, for a model with has_y, the periodic y path's step on the same phase
 *  (each activation once for both), path scale path_scale (finite, >= 0: the caller's); the
 *  path starts from path_scale times its cycle state (dmp_periodic_reset_xy). *path_m (may be
 *  NULL) receives p = path_scale*g_y + q after the step (m above the path at phi = 0; 0
 *  without a y path). Returns f_hat as dmp_periodic_step. */
fs_real_t dmp_periodic_step_xy(const dmp_model_t *m, dmp_state_t *s, const dmp_run_t *run,
                               fs_real_t amplitude_scale, const dmp_coupling_t *coupling,
                               fs_real_t path_scale, fs_real_t *path_m);

/** dmp_periodic_reset and the y path's state at path_scale times its cycle state (0 without
 *  a y path). */
void dmp_periodic_reset_xy(const dmp_model_t *m, dmp_state_t *s, fs_real_t amplitude_scale,
                           fs_real_t path_scale);

#endif /* DMP_H */

/* The force DMP (the paper's eqs. 11-17 corrected, docs/math.md): parameters from gains, the learned
 * system with its phase, and one forward-Euler step per tick. Pure functions over explicit
 * structs: no heap, no I/O, bounded work per step. See docs/math.md for the derivation.
 *
 *   tau*xd  = z - x - gamma*I + h + c_x       tau*zd = alpha*(beta*(g - x) - z)    tau*Id = x
 *   tau*vd~ = alpha*(beta*(1 - u~) - v~)      tau*ud~ = v~
 *   h = g*v~ * sum(psi_i*w_i)/sum(psi_i),     psi_i = exp(-(u~ - c_i)^2 / (2*sigma_i^2))
 *   f_hat = k*x
 * with tau -> tau*time_scale*(1 + phase_slowdown) and g -> g*goal_scale at run time. */
#ifndef DMP_H
#define DMP_H

#include <stdint.h>
#include "fs_real.h"
#include "fs_status.h"
#include "pfc.h"

#ifndef DMP_MAX_KERNELS
#define DMP_MAX_KERNELS 256u
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

/** DMP parameters derived from gains and nominal stiffness (corrected eq. 14). */
typedef struct {
    fs_real_t alpha;
    fs_real_t beta;
    fs_real_t gamma;
} dmp_params_t;

/** alpha = k_d/m_d - 1, gamma = k*k_i/(m_d*alpha), beta = (k_p + k*k_f - m_d*gamma)/(m_d*alpha) - 1
 *  (evaluated as (k_p + k*(k_f - k_i/alpha))/(m_d*alpha) - 1, the same in real numbers).
 *  Checks, first failure reported: NULL (100); any input not finite (101); m_d <= 0 (102);
 *  k <= 0 (106); k_d, k_p, k_f or k_i < 0 (107); k_d <= m_d (103); a derived value not finite (101);
 *  beta <= 0 (104); beta > alpha/4*(1 + DMP_MONOTONE_REL_TOL_REAL) (105).
 *  On error *out is zeroed (never NaN). */
fs_status_t dmp_params_from_gains(const pfc_axis_gains_t *gains, fs_real_t stiffness_Npm,
                                  dmp_params_t *out);

/** Goal trajectory g'(t) = c/(alpha*beta), c = (k_p*x_d + k_f*f_d + k_i*int_f_d)/m_d. */
fs_real_t dmp_goal_prime(const dmp_params_t *p, const pfc_axis_gains_t *gains, fs_real_t pos_d_m,
                         fs_real_t force_d_N, fs_real_t force_d_integral_Ns);

/** A learned force skill ready to evaluate (what skill_parse fills). Derived arrays are set by
 *  dmp_model_init; do not fill them by hand. */
typedef struct {
    uint16_t n_kernels;
    dmp_params_t p;
    fs_real_t dt_s;
    fs_real_t tau_s;
    fs_real_t goal_m;
    fs_real_t stiffness_Npm;
    fs_real_t duration_s;
    fs_real_t centre[DMP_MAX_KERNELS];
    fs_real_t width[DMP_MAX_KERNELS]; /* sigma_i */
    fs_real_t weight[DMP_MAX_KERNELS];
    /* derived by dmp_model_init */
    fs_real_t kernel_scale[DMP_MAX_KERNELS]; /* 1/(2 sigma_i^2): e_i = (u~ - c_i)^2 * this */
    fs_real_t env_hi[DMP_MAX_KERNELS];       /* prefix max of c_i + r*sigma_i (non-decreasing) */
    fs_real_t env_lo[DMP_MAX_KERNELS];       /* suffix min of c_i - r*sigma_i (non-decreasing) */
} dmp_model_t;

/** Validate the model and fill the derived arrays (after centre/width/weight and scalars are set).
 *  Checks in skill-image order: NULL (100); 1 <= N <= DMP_MAX_KERNELS (205); every value finite
 *  (206); 0 < dt <= 0.1, tau > 0, 0 < T <= 3600, k > 0, g > 0, sigma_i > 0 and 1/(2 sigma_i^2)
 *  finite (207); centres strictly increasing in [0, 1] (208); alpha > 0, beta > 0, gamma >= 0,
 *  beta <= alpha/4*(1 + DMP_MONOTONE_REL_TOL_REAL) (209). */
fs_status_t dmp_model_init(dmp_model_t *m);

/** DMP state, DMP time: normalised phase u~, v~, the position integral I, x, z. */
typedef struct {
    fs_real_t u;
    fs_real_t v;
    fs_real_t integral_x;
    fs_real_t x_m;
    fs_real_t z;
} dmp_state_t;

/** Run-time modulation: goal_scale multiplies g (and so f_hat), time_scale stretches tau. */
typedef struct {
    fs_real_t goal_scale;
    fs_real_t time_scale;
} dmp_run_t;

/** Coupling (optional): term_x is added to tau*xd; phase_slowdown >= 0 multiplies tau by
 *  (1 + phase_slowdown) for every state, so the skill waits (e.g. for contact). */
typedef struct {
    fs_real_t term_x;
    fs_real_t phase_slowdown;
} dmp_coupling_t;

/** Validate run-time modulation: both scales finite, time_scale > 0 (109). goal_scale may be
 *  zero or negative (it scales the force linearly). */
fs_status_t dmp_run_validate(const dmp_run_t *run);

/** Zero initial conditions. */
void dmp_state_reset(dmp_state_t *s);

/** Forcing term h at phase (u~, v~) and goal g, summing only kernels with
 *  e_i = (u~ - c_i)^2/(2 sigma_i^2) <= DMP_KERNEL_CUTOFF_EXP (found by binary search on the envelopes),
 *  psi_i = exp(-(e_i - e_min)) (dmp_tick.h); if none qualifies, the kernel with the smallest e_i
 *  alone (an O(N) scan that only happens when the phase is outside every kernel). */
fs_real_t dmp_forcing(const dmp_model_t *m, fs_real_t u, fs_real_t v, fs_real_t goal_m);

/** Forcing term h over all N kernels (reference for tests; not for the tick). */
fs_real_t dmp_forcing_full(const dmp_model_t *m, fs_real_t u, fs_real_t v, fs_real_t goal_m);

/** Number of kernels dmp_forcing sums at phase u~ (1 in the nearest-kernel fallback). */
uint16_t dmp_active_kernels(const dmp_model_t *m, fs_real_t u);

/** Phase slow-down for phase stopping: gain * err^2 (err = force tracking error, N); 0 if that is
 *  negative, +inf (phase frozen) if it is NaN. */
fs_real_t dmp_phase_stop_factor(fs_real_t force_err_N, fs_real_t gain_per_N2);

/** Advance the state by one step of dt_s (forward Euler, all right-hand sides at the old
 *  state, docs/math.md section 2; the step is dmp_tick.h, shared with dmpfx_step). run NULL means scales 1; coupling may be NULL (none); a
 *  phase_slowdown that is negative or NaN counts as 0, +inf freezes every state.
 *  Returns f_hat = k*x after the step. The caller validates run with dmp_run_validate. */
fs_real_t dmp_step(const dmp_model_t *m, dmp_state_t *s, const dmp_run_t *run,
                   const dmp_coupling_t *coupling);

#endif /* DMP_H */

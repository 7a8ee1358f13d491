/* The force DMP (SPEC 2, the paper's eqs. 11-17 corrected): parameters from gains, the learned
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

/** DMP parameters derived from gains and nominal stiffness (SPEC 2, corrected eq. 14). */
typedef struct {
    fs_real_t alpha;
    fs_real_t beta;
    fs_real_t gamma;
} dmp_params_t;

/** alpha = k_d/m_d - 1, gamma = k*k_i/(m_d*alpha), beta = (k_p + k*k_f - m_d*gamma)/(m_d*alpha) - 1;
 *  validates k_d > m_d, beta > 0, beta <= alpha/4; never writes NaN into *out. */
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
    fs_real_t width[DMP_MAX_KERNELS];          /* sigma_i */
    fs_real_t weight[DMP_MAX_KERNELS];
    /* derived by dmp_model_init */
    fs_real_t half_inv_var[DMP_MAX_KERNELS];   /* 1/(2 sigma_i^2) */
    fs_real_t env_hi[DMP_MAX_KERNELS];         /* prefix max of c_i + r*sigma_i (non-decreasing) */
    fs_real_t env_lo[DMP_MAX_KERNELS];         /* suffix min of c_i - r*sigma_i (non-decreasing) */
} dmp_model_t;

/** Fill derived arrays after centre/width/weight and scalars are set; validates ranges. */
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

/** Zero initial conditions. */
void dmp_state_reset(dmp_state_t *s);

/** Forcing term h at phase (u~, v~) and goal g, summing only kernels within the cutoff. */
fs_real_t dmp_forcing(const dmp_model_t *m, fs_real_t u, fs_real_t v, fs_real_t goal_m);

/** Forcing term h over all N kernels (reference for tests; not for the tick). */
fs_real_t dmp_forcing_full(const dmp_model_t *m, fs_real_t u, fs_real_t v, fs_real_t goal_m);

/** Number of kernels dmp_forcing evaluates at phase u~ (for tests and benchmarks). */
uint16_t dmp_active_kernels(const dmp_model_t *m, fs_real_t u);

/** Phase slow-down for phase stopping: gain * err^2 (err = force tracking error, N). */
fs_real_t dmp_phase_stop_factor(fs_real_t force_err_N, fs_real_t gain_per_N2);

/** Advance the state by one step of dt_s (forward Euler, all right-hand sides at the old
 *  state); coupling may be NULL. Returns f_hat = k*x after the step. */
fs_real_t dmp_step(const dmp_model_t *m, dmp_state_t *s, const dmp_run_t *run,
                   const dmp_coupling_t *coupling);

#endif /* DMP_H */

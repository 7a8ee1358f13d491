/* The force DMP: parameters from gains, model validation, the per-tick coefficients and the
 * public evaluation functions. The kernel blend and the Euler step are dmp_tick.h, shared with
 * the fixed-point build (dmpfx.c). docs/math.md sections 1-2 give the derivation and the exact
 * discrete algorithm. */
#include "dmp.h"

#include <stddef.h>

#include "fs_num.h"
#define DMP_TICK_MODEL dmp_model_t
#include "dmp_tick.h"

/* Kernel i is relevant at phase u iff |u - c_i| <= r_i, r_i = sqrt(2*cutoff)*sigma_i. The
 * envelopes use r_i widened by this factor, so the window found by binary search always contains
 * every kernel with e_i <= cutoff despite rounding; the e_i test itself decides. */
#define DMP_ENVELOPE_MARGIN FS_R(1.0001)

static int dmp_all_finite(const fs_real_t *a, uint16_t n)
{
    for (uint16_t i = 0u; i < n; i++) {
        if (!fs_isfinite(a[i])) {
            return 0;
        }
    }
    return 1;
}

static void dmp_params_zero(dmp_params_t *out)
{
    out->alpha = FS_R(0.0);
    out->beta = FS_R(0.0);
    out->gamma = FS_R(0.0);
}

fs_status_t dmp_params_from_gains(const pfc_axis_gains_t *gains, fs_real_t stiffness_Npm,
                                  dmp_params_t *out)
{
    if (gains == NULL || out == NULL) {
        return FS_ERR_NULL_ARG;
    }
    dmp_params_zero(out);
    const fs_real_t m_d = gains->m_d_kg;
    const fs_real_t k_d = gains->k_d_Nspm;
    const fs_real_t k_p = gains->k_p_Npm;
    const fs_real_t k_f = gains->k_f;
    const fs_real_t k_i = gains->k_i_per_s;
    const fs_real_t k = stiffness_Npm;
    if (!fs_isfinite(m_d) || !fs_isfinite(k_d) || !fs_isfinite(k_p) || !fs_isfinite(k_f) ||
        !fs_isfinite(k_i) || !fs_isfinite(k)) {
        return FS_ERR_NOT_FINITE;
    }
    if (!(m_d > FS_R(0.0))) {
        return FS_ERR_MASS_NONPOSITIVE;
    }
    if (!(k > FS_R(0.0))) {
        return FS_ERR_STIFFNESS_NONPOSITIVE;
    }
    if (k_d < FS_R(0.0) || k_p < FS_R(0.0) || k_f < FS_R(0.0) || k_i < FS_R(0.0)) {
        return FS_ERR_GAIN_NEGATIVE;
    }
    if (!(k_d > m_d)) {
        return FS_ERR_KD_LE_MD;
    }
    const fs_real_t alpha = k_d / m_d - FS_R(1.0);
    /* alpha can round to 0 when k_d exceeds m_d by less than an ulp: that is k_d <= m_d too. */
    if (!(alpha > FS_R(0.0))) {
        return FS_ERR_KD_LE_MD;
    }
    const fs_real_t gamma = k * k_i / (m_d * alpha);
    /* m_d*gamma = k*k_i/alpha: written this way the k terms cancel exactly for the default gains
     * (k_f = k_i/alpha), so beta = alpha/4 holds in floating point for every k. */
    const fs_real_t beta = (k_p + k * (k_f - k_i / alpha)) / (m_d * alpha) - FS_R(1.0);
    if (!fs_isfinite(alpha) || !fs_isfinite(gamma) || !fs_isfinite(beta)) {
        return FS_ERR_NOT_FINITE;
    }
    if (!(beta > FS_R(0.0))) {
        return FS_ERR_BETA_NONPOSITIVE;
    }
    if (beta > alpha / FS_R(4.0) * (FS_R(1.0) + DMP_MONOTONE_REL_TOL_REAL)) {
        return FS_ERR_PHASE_NOT_MONOTONE;
    }
    out->alpha = alpha;
    out->beta = beta;
    out->gamma = gamma;
    return FS_OK;
}

fs_real_t dmp_goal_prime(const dmp_params_t *p, const pfc_axis_gains_t *gains, fs_real_t pos_d_m,
                         fs_real_t force_d_N, fs_real_t force_d_integral_Ns)
{
    const fs_real_t c = (gains->k_p_Npm * pos_d_m + gains->k_f * force_d_N +
                         gains->k_i_per_s * force_d_integral_Ns) /
                        gains->m_d_kg;
    return c / (p->alpha * p->beta);
}

fs_status_t dmp_model_init(dmp_model_t *m)
{
    if (m == NULL) {
        return FS_ERR_NULL_ARG;
    }
    const uint16_t n = m->n_kernels;
    if (n == 0u || n > DMP_MAX_KERNELS) {
        return FS_ERR_SKILL_KERNELS;
    }
    if (!fs_isfinite(m->p.alpha) || !fs_isfinite(m->p.beta) || !fs_isfinite(m->p.gamma) ||
        !fs_isfinite(m->dt_s) || !fs_isfinite(m->tau_s) || !fs_isfinite(m->goal_m) ||
        !fs_isfinite(m->stiffness_Npm) || !fs_isfinite(m->duration_s) ||
        !dmp_all_finite(m->centre, n) || !dmp_all_finite(m->width, n) ||
        !dmp_all_finite(m->weight, n)) {
        return FS_ERR_SKILL_NOT_FINITE;
    }
    if (!(m->dt_s > FS_R(0.0)) || m->dt_s > FS_R(0.1) || !(m->tau_s > FS_R(0.0)) ||
        !(m->duration_s > FS_R(0.0)) || m->duration_s > FS_R(3600.0) ||
        !(m->stiffness_Npm > FS_R(0.0)) || !(m->goal_m > FS_R(0.0))) {
        return FS_ERR_SKILL_RANGE;
    }
    for (uint16_t i = 0u; i < n; i++) {
        const fs_real_t s = m->width[i];
        if (!(s > FS_R(0.0))) {
            return FS_ERR_SKILL_RANGE;
        }
        const fs_real_t hiv = FS_R(1.0) / (FS_R(2.0) * s * s);
        if (!fs_isfinite(hiv)) {
            return FS_ERR_SKILL_RANGE;
        }
    }
    for (uint16_t i = 0u; i < n; i++) {
        const fs_real_t c = m->centre[i];
        if (c < FS_R(0.0) || c > FS_R(1.0) || (i > 0u && !(c > m->centre[i - 1u]))) {
            return FS_ERR_SKILL_CENTRES;
        }
    }
    const fs_real_t alpha = m->p.alpha;
    const fs_real_t beta = m->p.beta;
    if (!(alpha > FS_R(0.0)) || !(beta > FS_R(0.0)) || m->p.gamma < FS_R(0.0) ||
        beta > alpha / FS_R(4.0) * (FS_R(1.0) + DMP_MONOTONE_REL_TOL_REAL)) {
        return FS_ERR_SKILL_GAINS;
    }

    const fs_real_t r_per_sigma = fs_sqrt(FS_R(2.0) * (fs_real_t)DMP_KERNEL_CUTOFF_EXP) *
                                  DMP_ENVELOPE_MARGIN;
    fs_real_t run_max = -FS_REAL_INF;
    for (uint16_t i = 0u; i < n; i++) {
        const fs_real_t s = m->width[i];
        m->kernel_scale[i] = FS_R(1.0) / (FS_R(2.0) * s * s);
        const fs_real_t hi = m->centre[i] + r_per_sigma * s;
        run_max = (hi > run_max) ? hi : run_max;
        m->env_hi[i] = run_max;
    }
    fs_real_t run_min = FS_REAL_INF;
    for (uint16_t j = n; j > 0u; j--) {
        const uint16_t i = (uint16_t)(j - 1u);
        const fs_real_t lo = m->centre[i] - r_per_sigma * m->width[i];
        run_min = (lo < run_min) ? lo : run_min;
        m->env_lo[i] = run_min;
    }
    return FS_OK;
}

fs_status_t dmp_run_validate(const dmp_run_t *run)
{
    if (run == NULL) {
        return FS_ERR_NULL_ARG;
    }
    if (!fs_isfinite(run->goal_scale) || !fs_isfinite(run->time_scale) ||
        !(run->time_scale > FS_R(0.0))) {
        return FS_ERR_SCALE_INVALID;
    }
    return FS_OK;
}

void dmp_state_reset(dmp_state_t *s)
{
    s->u = FS_R(0.0);
    s->v = FS_R(0.0);
    s->integral_x = FS_R(0.0);
    s->x_m = FS_R(0.0);
    s->z = FS_R(0.0);
}

/* S(u) over all N kernels with psi_i = exp(-(e_i - e_min)) (the test reference: the shift keeps
 * sum psi >= 1 however far u is from every centre). */
static fs_real_t dmp_blend_all(const dmp_model_t *m, fs_real_t u)
{
    fs_real_t e_min = FS_REAL_INF;
    for (uint16_t i = 0u; i < m->n_kernels; i++) {
        const fs_real_t e = fs_num_kernel_expo(u, m->centre[i], m->kernel_scale[i]);
        e_min = (e < e_min) ? e : e_min;
    }
    fs_real_t num = FS_R(0.0);
    fs_real_t den = FS_R(0.0);
    for (uint16_t i = 0u; i < m->n_kernels; i++) {
        const fs_real_t psi = fs_exp(
            -(fs_num_kernel_expo(u, m->centre[i], m->kernel_scale[i]) - e_min));
        num += psi * m->weight[i];
        den += psi;
    }
    return num / den;
}

fs_real_t dmp_forcing(const dmp_model_t *m, fs_real_t u, fs_real_t v, fs_real_t goal_m)
{
    return goal_m * v * dmp_tick_blend(m, u, NULL);
}

fs_real_t dmp_forcing_full(const dmp_model_t *m, fs_real_t u, fs_real_t v, fs_real_t goal_m)
{
    return goal_m * v * dmp_blend_all(m, u);
}

uint16_t dmp_active_kernels(const dmp_model_t *m, fs_real_t u)
{
    uint16_t count;
    (void)dmp_tick_blend(m, u, &count);
    return count;
}

fs_real_t dmp_phase_stop_factor(fs_real_t force_err_N, fs_real_t gain_per_N2)
{
    const fs_real_t r = gain_per_N2 * force_err_N * force_err_N;
    if (r != r) {
        return FS_REAL_INF;
    }
    return (r > FS_R(0.0)) ? r : FS_R(0.0);
}

fs_real_t dmp_step(const dmp_model_t *m, dmp_state_t *s, const dmp_run_t *run,
                   const dmp_coupling_t *coupling)
{
    const fs_real_t goal_scale = (run != NULL) ? run->goal_scale : FS_R(1.0);
    const fs_real_t time_scale = (run != NULL) ? run->time_scale : FS_R(1.0);
    fs_real_t slowdown = FS_R(0.0);
    fs_real_t term_x = FS_R(0.0);
    if (coupling != NULL) {
        term_x = coupling->term_x;
        slowdown = (coupling->phase_slowdown > FS_R(0.0)) ? coupling->phase_slowdown : FS_R(0.0);
    }
    const fs_real_t tau_e = m->tau_s * time_scale * (FS_R(1.0) + slowdown);
    const fs_real_t k = m->dt_s / tau_e;
    const fs_real_t k_alpha = k * m->p.alpha;
    const dmp_tick_coef_t c = {.k1 = k,
                               .k_alpha = k_alpha,
                               .k_alphabeta = k_alpha * m->p.beta,
                               .k_gamma = k * m->p.gamma,
                               .goal = m->goal_m * goal_scale,
                               .stiffness = m->stiffness_Npm,
                               .term_x = term_x};
    const dmp_tick_state_t st = {&s->u, &s->v, &s->integral_x, &s->x_m, &s->z};
    return dmp_tick_step(m, &c, &st, NULL);
}

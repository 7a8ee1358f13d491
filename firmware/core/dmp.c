/* The force DMP: parameters from gains, model validation, the per-tick coefficients and the
 * public evaluation functions. The kernel blend and the Euler step are dmp_tick.h, shared with
 * the fixed-point build (dmpfx.c). docs/math.md sections 1-2 give the derivation and the exact
 * discrete algorithm. */
#include "dmp.h"

#include <stddef.h>

#include "fs_num.h"
#define DMP_TICK_MODEL dmp_model_t
#include "dmp_tick.h"
#include "dmp_ptick.h"

#define DMP_TWO_PI FS_R(6.28318530717958647692)

/* Kernel i is relevant at phase u iff |u - c_i| <= r_i, r_i = sqrt(2*cutoff)*sigma_i. The
 * envelopes use r_i widened by this factor, so the window found by binary search always contains
 * every kernel with e_i <= cutoff despite rounding; the e_i test itself decides. */
#define DMP_ENVELOPE_MARGIN FS_R(1.0001)

static void dmp_params_zero(dmp_params_t *out)
{
    out->alpha = FS_R(0.0);
    out->beta = FS_R(0.0);
    out->gamma = FS_R(0.0);
}

/* Part part (DMP_DERIVE_PARTS in order, one double division each) of the derivation with the
 * beta <= alpha/4 tolerance as a parameter (double: DMP_MONOTONE_REL_TOL, the float core:
 * DMP_MONOTONE_REL_TOL_REAL) into w = {alpha, beta, gamma}: 0 the checks of the gains and
 * alpha, 1 gamma, 2 kki/alpha (kept in w[1]), 3 beta and its checks. */
static fs_status_t dmp_derive_part(const double gain[5], double monotone_rel_tol, double w[3],
                                   uint32_t part)
{
    const double m_d = gain[0];
    const double k_d = gain[1];
    const double k_p = gain[2];
    const double kkf = gain[3];
    const double kki = gain[4];
    switch (part) {
    case 0u: {
        for (uint32_t i = 0u; i < 5u; i++) {
            if (!isfinite(gain[i])) {
                return FS_ERR_NOT_FINITE;
            }
        }
        if (!(m_d > 0.0)) {
            return FS_ERR_MASS_NONPOSITIVE;
        }
        if (k_d < 0.0 || k_p < 0.0 || kkf < 0.0 || kki < 0.0) {
            return FS_ERR_GAIN_NEGATIVE;
        }
        if (!(k_d > m_d)) {
            return FS_ERR_KD_LE_MD;
        }
        const double alpha = k_d / m_d - 1.0;
        /* alpha can round to 0 when k_d exceeds m_d by less than an ulp: that is k_d <= m_d too. */
        if (!(alpha > 0.0)) {
            return FS_ERR_KD_LE_MD;
        }
        if (!isfinite(alpha)) {
            return FS_ERR_NOT_FINITE;
        }
        w[0] = alpha;
        return FS_OK;
    }
    case 1u: w[2] = kki / (m_d * w[0]); return FS_OK;
    case 2u: w[1] = kki / w[0]; return FS_OK;
    default: {
        const double alpha = w[0];
        const double gamma = w[2];
        /* m_d*gamma = kki/alpha: written this way the kkf and kki terms cancel exactly for the
         * default gains (kkf = kki/alpha), so beta = alpha/4 holds in floating point. */
        const double beta = (k_p + (kkf - w[1])) / (m_d * alpha) - 1.0;
        if (!isfinite(gamma) || !isfinite(beta)) {
            return FS_ERR_NOT_FINITE;
        }
        if (!(beta > 0.0)) {
            return FS_ERR_BETA_NONPOSITIVE;
        }
        if (beta > alpha / 4.0 * (1.0 + monotone_rel_tol)) {
            return FS_ERR_PHASE_NOT_MONOTONE;
        }
        w[1] = beta;
        return FS_OK;
    }
    }
}

/* The whole derivation: abg written only on success. */
static fs_status_t dmp_derive(const double gain[5], double monotone_rel_tol, double abg[3])
{
    double w[3] = {0.0, 0.0, 0.0};
    for (uint32_t part = 0u; part < DMP_DERIVE_PARTS; part++) {
        const fs_status_t st = dmp_derive_part(gain, monotone_rel_tol, w, part);
        if (st != FS_OK) {
            return st;
        }
    }
    abg[0] = w[0];
    abg[1] = w[1];
    abg[2] = w[2];
    return FS_OK;
}

fs_status_t dmp_derive_f64_part(const double gain[5], double work[3], uint32_t part)
{
    if (gain == NULL || work == NULL || part >= DMP_DERIVE_PARTS) {
        return FS_ERR_NULL_ARG;
    }
    return dmp_derive_part(gain, DMP_MONOTONE_REL_TOL, work, part);
}

fs_status_t dmp_derive_f64(const double gain[5], double abg[3])
{
    if (gain == NULL || abg == NULL) {
        return FS_ERR_NULL_ARG;
    }
    return dmp_derive(gain, DMP_MONOTONE_REL_TOL, abg);
}

fs_status_t dmp_params_from_gains(const dmp_gains_t *gains, dmp_params_t *out)
{
    if (gains == NULL || out == NULL) {
        return FS_ERR_NULL_ARG;
    }
    dmp_params_zero(out);
    const double gain[5] = {(double)gains->m_d_kg, (double)gains->k_d_Nspm, (double)gains->k_p_Npm,
                            (double)gains->kkf_Npm, (double)gains->kki_Npms};
    double abg[3];
    const fs_status_t st = dmp_derive(gain, (double)DMP_MONOTONE_REL_TOL_REAL, abg);
    if (st != FS_OK) {
        return st;
    }
    const fs_real_t alpha = (fs_real_t)abg[0];
    const fs_real_t beta = (fs_real_t)abg[1];
    const fs_real_t gamma = (fs_real_t)abg[2];
    if (!fs_isfinite(alpha) || !fs_isfinite(beta) || !fs_isfinite(gamma)) {
        return FS_ERR_NOT_FINITE;
    }
    out->alpha = alpha;
    out->beta = beta;
    out->gamma = gamma;
    return FS_OK;
}

fs_status_t dmp_gains_at_stiffness(const dmp_gains_t *gains, fs_real_t stiffness_Npm,
                                   pfc_axis_gains_t *out)
{
    if (gains == NULL || out == NULL) {
        return FS_ERR_NULL_ARG;
    }
    if (!fs_isfinite(stiffness_Npm)) {
        return FS_ERR_NOT_FINITE;
    }
    if (!(stiffness_Npm > FS_R(0.0))) {
        return FS_ERR_STIFFNESS_NONPOSITIVE;
    }
    out->m_d_kg = gains->m_d_kg;
    out->k_d_Nspm = gains->k_d_Nspm;
    out->k_p_Npm = gains->k_p_Npm;
    out->k_f = gains->kkf_Npm / stiffness_Npm;
    out->k_i_per_s = gains->kki_Npms / stiffness_Npm;
    if (!fs_isfinite(out->k_f) || !fs_isfinite(out->k_i_per_s)) {
        return FS_ERR_NOT_FINITE;
    }
    return FS_OK;
}

fs_real_t dmp_goal(const dmp_params_t *p, const dmp_gains_t *gains, fs_real_t ref_force_N,
                   fs_real_t force_d_N, fs_real_t force_d_integral_Ns)
{
    const fs_real_t c = (gains->k_p_Npm * ref_force_N + gains->kkf_Npm * force_d_N +
                         gains->kki_Npms * force_d_integral_Ns) /
                        gains->m_d_kg;
    return c / (p->alpha * p->beta);
}

/* The passes of dmp_model_init, in the order of its checks. */
enum {
    MI_HEAD,      /* kernel count, the scalars finite */
    MI_FINITE,    /* centre, width, weight finite, a kernel a unit */
    MI_RANGE,     /* dt, tau, T, g in range */
    MI_WIDTHS,    /* sigma > 0 and 1/(2 sigma^2) finite */
    MI_CENTRES,   /* centres increasing in [0, 1] */
    MI_GAINS,     /* alpha, beta, gamma; with the y DMP its scalars finite */
    MI_Y_WEIGHTS, /* the y weights finite */
    MI_Y_GAINS,   /* beta_y in range */
    MI_SINES,     /* a periodic model's half-angle sines (none in a discrete one) */
    MI_COSINES,   /* and cosines (none in a discrete one) */
    MI_ROOTS,     /* a periodic model's reach's square roots, kept in env_hi (none in a discrete) */
    MI_FORWARD,   /* kernel_scale and env_hi (prefix max) */
    MI_BACKWARD,  /* env_lo (suffix min), from the last kernel */
    MI_DONE
};

void dmp_model_init_begin(dmp_init_t *it)
{
    it->stage = MI_HEAD;
    it->i = 0u;
    it->run = FS_R(0.0);
    it->status = FS_OK;
}

/* The checks of one pass done once (head, ranges, gains, y gains). */
static fs_status_t dmp_init_once(const dmp_model_t *m, uint8_t stage)
{
    const fs_real_t alpha = m->p.alpha;
    const fs_real_t mono = alpha / FS_R(4.0) * (FS_R(1.0) + DMP_MONOTONE_REL_TOL_REAL);
    switch (stage) {
    case MI_HEAD:
        if (m->n_kernels == 0u || m->n_kernels > DMP_MAX_KERNELS) {
            return FS_ERR_SKILL_KERNELS;
        }
        return (!fs_isfinite(m->p.alpha) || !fs_isfinite(m->p.beta) || !fs_isfinite(m->p.gamma) ||
                !fs_isfinite(m->dt_s) || !fs_isfinite(m->tau_s) || !fs_isfinite(m->goal_N) ||
                !fs_isfinite(m->force0_N) || !fs_isfinite(m->duration_s) ||
                (m->periodic != 0u &&
                 (!fs_isfinite(m->amplitude_N) || !fs_isfinite(m->cycle_e0_N) ||
                  !fs_isfinite(m->cycle_z0_N) || !fs_isfinite(m->cycle_i0_N))))
                   ? FS_ERR_SKILL_NOT_FINITE
                   : FS_OK;
    case MI_RANGE:
        return (!(m->dt_s > FS_R(0.0)) || m->dt_s > FS_R(0.1) || !(m->tau_s > FS_R(0.0)) ||
                !(m->duration_s > FS_R(0.0)) || m->duration_s > FS_R(3600.0) ||
                !(m->goal_N > FS_R(0.0)) || (m->periodic != 0u && !(m->amplitude_N > FS_R(0.0))))
                   ? FS_ERR_SKILL_RANGE
                   : FS_OK;
    case MI_GAINS:
        if (!(alpha > FS_R(0.0)) || !(m->p.beta > FS_R(0.0)) || m->p.gamma < FS_R(0.0) ||
            m->p.beta > mono) {
            return FS_ERR_SKILL_GAINS;
        }
        return (m->has_y != 0u && (!fs_isfinite(m->beta_y) || !fs_isfinite(m->goal_y_m) ||
                                   !fs_isfinite(m->y_start_m) ||
                                   (m->periodic != 0u &&
                                    (!fs_isfinite(m->cycle_q0_m) || !fs_isfinite(m->cycle_zq0_m)))))
                   ? FS_ERR_SKILL_NOT_FINITE
                   : FS_OK;
    case MI_Y_GAINS:
        return (m->has_y != 0u && (!(m->beta_y > FS_R(0.0)) || m->beta_y > mono))
                   ? FS_ERR_SKILL_GAINS
                   : FS_OK;
    default: return FS_OK;
    }
}

/* A periodic kernel's reach in turns: the largest circular distance with kappa (1 - cos) <= the
 * cutoff, asin(sqrt(cutoff/(2 kappa)))/pi (half a turn when every phase is within), widened by
 * DMP_ENVELOPE_MARGIN; in two passes (in software float a square root costs as much as the
 * arcsine): the root (1 when every phase is within) ... */
static fs_real_t dmp_periodic_root(fs_real_t kappa)
{
    const fs_real_t q = (fs_real_t)DMP_KERNEL_CUTOFF_EXP / (FS_R(2.0) * kappa);
    return (q < FS_R(1.0)) ? fs_sqrt(q) : FS_R(1.0);
}

/* ... then the reach from it. */
static fs_real_t dmp_periodic_reach(fs_real_t root)
{
    if (!(root < FS_R(1.0))) {
        return FS_R(0.5);
    }
    const fs_real_t r = fs_asin(root) * (FS_R(2.0) / DMP_TWO_PI) * DMP_ENVELOPE_MARGIN;
    return (r < FS_R(0.5)) ? r : FS_R(0.5);
}

/* One kernel of a periodic model's per-kernel passes (the checks of widths and centres on the
 * circle, the derived arrays in turns). */
static void dmp_init_kernel_periodic(dmp_model_t *m, dmp_init_t *it, uint16_t i)
{
    const fs_real_t kappa = m->width[i];
    const fs_real_t x = m->centre[i] / DMP_TWO_PI;
    switch (it->stage) {
    case MI_WIDTHS:
        if (!(kappa > FS_R(0.0)) || !fs_isfinite(FS_R(2.0) * kappa)) {
            it->status = FS_ERR_SKILL_RANGE;
        }
        break;
    case MI_CENTRES: {
        const fs_real_t c = m->centre[i];
        if (c < FS_R(0.0) || !(c < DMP_TWO_PI) || (i > 0u && !(c > m->centre[i - 1u]))) {
            it->status = FS_ERR_SKILL_PHASES;
        }
        break;
    }
    case MI_SINES: /* a pass each: in software float a sine costs as much as a square root */
        m->half_sin[i] = fs_sin(FS_R(0.5) * m->centre[i]);
        break;
    case MI_COSINES: m->half_cos[i] = fs_cos(FS_R(0.5) * m->centre[i]); break;
    case MI_ROOTS: m->env_hi[i] = dmp_periodic_root(kappa); break;
    case MI_FORWARD: {
        m->kernel_scale[i] = FS_R(2.0) * kappa;
        const fs_real_t reach = dmp_periodic_reach(m->env_hi[i]);
        const fs_real_t hi = x + reach;
        it->run = (i == 0u || hi > it->run) ? hi : it->run;
        m->env_hi[i] = it->run;
        m->env_lo[i] = x - reach; /* the kernel's own low end, for the backward pass */
        break;
    }
    default: { /* MI_BACKWARD */
        const fs_real_t lo = m->env_lo[i];
        it->run = (i == m->n_kernels - 1u || lo < it->run) ? lo : it->run;
        m->env_lo[i] = it->run;
        break;
    }
    }
}

/* Kernel it->i of a per-kernel pass; true once the pass's last kernel is done. */
static bool dmp_init_kernel(dmp_model_t *m, dmp_init_t *it)
{
    const uint16_t n = m->n_kernels;
    const uint16_t i = (it->stage == MI_BACKWARD) ? (uint16_t)(n - 1u - it->i) : it->i;
    if (m->periodic != 0u && it->stage != MI_FINITE && it->stage != MI_Y_WEIGHTS) {
        dmp_init_kernel_periodic(m, it, i);
        it->i++;
        return it->i >= n;
    }
    const fs_real_t r_per_sigma = fs_sqrt(FS_R(2.0) * (fs_real_t)DMP_KERNEL_CUTOFF_EXP) *
                                  DMP_ENVELOPE_MARGIN;
    const fs_real_t s = m->width[i];
    switch (it->stage) {
    case MI_FINITE:
        if (!fs_isfinite(m->centre[i]) || !fs_isfinite(s) || !fs_isfinite(m->weight[i])) {
            it->status = FS_ERR_SKILL_NOT_FINITE;
        }
        break;
    case MI_WIDTHS:
        if (!(s > FS_R(0.0)) || !fs_isfinite(FS_R(1.0) / (FS_R(2.0) * s * s))) {
            it->status = FS_ERR_SKILL_RANGE;
        }
        break;
    case MI_CENTRES: {
        const fs_real_t c = m->centre[i];
        if (c < FS_R(0.0) || c > FS_R(1.0) || (i > 0u && !(c > m->centre[i - 1u]))) {
            it->status = FS_ERR_SKILL_CENTRES;
        }
        break;
    }
    case MI_SINES:
    case MI_COSINES:
    case MI_ROOTS: return true;
    case MI_Y_WEIGHTS:
        if (m->has_y == 0u) {
            return true;
        }
        if (!fs_isfinite(m->y_weight[i])) {
            it->status = FS_ERR_SKILL_NOT_FINITE;
        }
        break;
    case MI_FORWARD: {
        m->kernel_scale[i] = FS_R(1.0) / (FS_R(2.0) * s * s);
        const fs_real_t hi = m->centre[i] + r_per_sigma * s;
        it->run = (i == 0u || hi > it->run) ? hi : it->run;
        m->env_hi[i] = it->run;
        break;
    }
    default: { /* MI_BACKWARD */
        const fs_real_t lo = m->centre[i] - r_per_sigma * s;
        it->run = (i == n - 1u || lo < it->run) ? lo : it->run;
        m->env_lo[i] = it->run;
        break;
    }
    }
    it->i++;
    return it->i >= n;
}

bool dmp_model_init_run(dmp_model_t *m, dmp_init_t *it, uint32_t max_kernels)
{
    for (uint32_t k = 0u; k < max_kernels && it->stage != MI_DONE; k++) {
        bool pass_done = true;
        if (m == NULL) {
            it->status = FS_ERR_NULL_ARG;
        } else if (it->stage == MI_HEAD || it->stage == MI_RANGE || it->stage == MI_GAINS ||
                   it->stage == MI_Y_GAINS) {
            it->status = dmp_init_once(m, it->stage);
        } else {
            pass_done = dmp_init_kernel(m, it);
        }
        if (it->status != FS_OK) {
            it->stage = MI_DONE;
        } else if (pass_done) {
            it->stage++;
            it->i = 0u;
        }
    }
    return it->stage == MI_DONE;
}

bool dmp_model_init_next_is_reach(const dmp_model_t *m, const dmp_init_t *it)
{
    return m != NULL && it != NULL && m->periodic != 0u && it->stage == MI_FORWARD;
}

fs_status_t dmp_model_init(dmp_model_t *m)
{
    dmp_init_t it;
    dmp_model_init_begin(&it);
    while (!dmp_model_init_run(m, &it, UINT32_MAX)) {
    }
    return it.status;
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
    s->window[0] = 0u;
    s->window[1] = 0u;
    s->u = FS_R(0.0);
    s->v = FS_R(0.0);
    s->integral_y = FS_R(0.0);
    s->y_N = FS_R(0.0);
    s->z = FS_R(0.0);
    s->path_m = FS_R(0.0);
    s->path_z = FS_R(0.0);
    s->u_comp = FS_R(0.0);
    s->prep_model = NULL;
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

fs_real_t dmp_forcing(const dmp_model_t *m, fs_real_t u, fs_real_t v, fs_real_t goal_N)
{
    return goal_N * v *
           dmp_tick_blend(m, u, dmp_tick_window_start(m, u), dmp_tick_window_end(m, u), NULL);
}

fs_real_t dmp_forcing_full(const dmp_model_t *m, fs_real_t u, fs_real_t v, fs_real_t goal_N)
{
    return goal_N * v * dmp_blend_all(m, u);
}

uint16_t dmp_active_kernels(const dmp_model_t *m, fs_real_t u)
{
    uint16_t count;
    (void)dmp_tick_blend(m, u, dmp_tick_window_start(m, u), dmp_tick_window_end(m, u), &count);
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

fs_real_t dmp_contact_rate(fs_real_t rate, fs_real_t f_hat_N, fs_real_t f_contact_N,
                           fs_real_t threshold_N, fs_real_t gain)
{
    const int in_contact = (f_hat_N - f_contact_N <= threshold_N);
    const fs_real_t target = in_contact ? FS_R(1.0) : FS_R(0.0);
    return rate + gain * (target - rate);
}

fs_real_t dmp_slowdown_at_rate(fs_real_t slowdown, fs_real_t rate)
{
    if (rate >= FS_R(1.0)) {
        return slowdown;
    }
    if (!(rate > FS_R(0.0))) {
        return FS_REAL_INF;
    }
    return (FS_R(1.0) + slowdown) / rate - FS_R(1.0);
}

/* The force DMP's per-tick constants for a run and a coupling (both may be NULL); inline into
 * the steps: the constants stay in registers rather than going through a struct in memory. */
#if defined(__GNUC__)
__attribute__((always_inline))
#endif
static inline dmp_tick_coef_t
dmp_coef(const dmp_model_t *m, const dmp_run_t *run, const dmp_coupling_t *coupling)
{
    const fs_real_t goal_scale = (run != NULL) ? run->goal_scale : FS_R(1.0);
    const fs_real_t time_scale = (run != NULL) ? run->time_scale : FS_R(1.0);
    fs_real_t slowdown = FS_R(0.0);
    fs_real_t term_y = FS_R(0.0);
    if (coupling != NULL) {
        term_y = coupling->term_y_N;
        slowdown = (coupling->phase_slowdown > FS_R(0.0)) ? coupling->phase_slowdown : FS_R(0.0);
    }
    const fs_real_t tau_e = m->tau_s * time_scale * (FS_R(1.0) + slowdown);
    const fs_real_t k = m->dt_s / tau_e;
    const fs_real_t k_alpha = k * m->p.alpha;
    const dmp_tick_coef_t c = {.k1 = k,
                               .k_alpha = k_alpha,
                               .k_alphabeta = k_alpha * m->p.beta,
                               .k_gamma = k * m->p.gamma,
                               .goal = m->goal_N * goal_scale,
                               .out_scale = FS_R(1.0),
                               .term_y = term_y};
    return c;
}

/* The prepared blend pair if dmp_prepare made it for m at the state's phase (taken once). */
static inline bool dmp_take_prepared(const dmp_model_t *m, dmp_state_t *s)
{
    const bool hit = s->prep_model == (const void *)m && s->prep_u == s->u;
    s->prep_model = NULL;
    return hit;
}

void dmp_prepare(const dmp_model_t *m, dmp_state_t *s)
{
    const dmp_tick_state_t st = {s->window, &s->u, &s->v, &s->integral_y, &s->y_N, &s->z};
    /* the blend dmp_step (force only) or dmp_step_xy (with y) computes */
    if (m->has_y == 0u) {
        s->prep_s = dmp_tick_state_blend(m, &st);
    } else {
        s->prep_s = dmp_tick_state_blend2(m, &st, m->y_weight, &s->prep_sy);
    }
    s->prep_u = s->u;
    s->prep_model = m;
}

fs_real_t dmp_step(const dmp_model_t *m, dmp_state_t *s, const dmp_run_t *run,
                   const dmp_coupling_t *coupling)
{
    const dmp_tick_state_t st = {s->window, &s->u, &s->v, &s->integral_y, &s->y_N, &s->z};
    /* a blend prepared with y weights (dmp_tick_blend2) has the same S: the same operations */
    const fs_real_t s_blend = dmp_take_prepared(m, s) ? s->prep_s : dmp_tick_state_blend(m, &st);
    const dmp_tick_coef_t c = dmp_coef(m, run, coupling);
    return m->force0_N + dmp_tick_step(&c, &st, s_blend, NULL);
}

fs_real_t dmp_step_xy(const dmp_model_t *m, dmp_state_t *s, const dmp_run_t *run,
                      const dmp_coupling_t *coupling, fs_real_t path_scale, fs_real_t *path_m)
{
    if (m->has_y == 0u) { /* a force-only skill: dmp_step's code, p stays 0 */
        if (path_m != NULL) {
            *path_m = FS_R(0.0);
        }
        return dmp_step(m, s, run, coupling);
    }
    const dmp_tick_state_t st = {s->window, &s->u, &s->v, &s->integral_y, &s->y_N, &s->z};
    fs_real_t s_y = s->prep_sy;
    const fs_real_t s_blend = dmp_take_prepared(m, s)
                                  ? s->prep_s
                                  : dmp_tick_state_blend2(m, &st, m->y_weight, &s_y);
    const dmp_tick_coef_t c = dmp_coef(m, run, coupling);
    const dmp_tick_path_coef_t cp = {.k1 = c.k1,
                                     .k_alpha = c.k_alpha,
                                     .k_alphabeta = c.k_alpha * m->beta_y,
                                     .goal = m->goal_y_m * path_scale,
                                     .scale = path_scale};
    (void)dmp_tick_path_step(&cp, &s->path_m, &s->path_z, s->v, s_y, NULL);
    if (path_m != NULL) {
        *path_m = s->path_m;
    }
    return m->force0_N + dmp_tick_step(&c, &st, s_blend, NULL);
}

void dmp_periodic_reset(const dmp_model_t *m, dmp_state_t *s, fs_real_t amplitude_scale)
{
    dmp_state_reset(s);
    s->y_N = amplitude_scale * m->cycle_e0_N;
    s->z = amplitude_scale * m->cycle_z0_N;
    s->integral_y = amplitude_scale * m->cycle_i0_N;
    dmp_ptick_window_search(m, dmp_ptick_query(FS_R(0.0)), s->window);
}

void dmp_periodic_reset_xy(const dmp_model_t *m, dmp_state_t *s, fs_real_t amplitude_scale,
                           fs_real_t path_scale)
{
    dmp_periodic_reset(m, s, amplitude_scale);
    if (m->has_y != 0u) {
        s->path_m = path_scale * m->cycle_q0_m;
        s->path_z = path_scale * m->cycle_zq0_m;
    }
}

fs_real_t dmp_periodic_blend(const dmp_model_t *m, fs_real_t x_turns, uint16_t *count)
{
    uint16_t win[2];
    dmp_ptick_window_search(m, dmp_ptick_query(x_turns), win);
    return dmp_ptick_blend(m, x_turns, win[0], win[1], count);
}

fs_real_t dmp_periodic_blend_full(const dmp_model_t *m, fs_real_t x_turns)
{
    const fs_real_t phi = DMP_TWO_PI * x_turns;
    fs_real_t e_min = FS_REAL_INF;
    for (uint16_t i = 0u; i < m->n_kernels; i++) {
        const fs_real_t e = m->width[i] * (FS_R(1.0) - fs_cos(phi - m->centre[i]));
        e_min = (e < e_min) ? e : e_min;
    }
    fs_real_t num = FS_R(0.0);
    fs_real_t den = FS_R(0.0);
    for (uint16_t i = 0u; i < m->n_kernels; i++) {
        const fs_real_t e = m->width[i] * (FS_R(1.0) - fs_cos(phi - m->centre[i]));
        const fs_real_t psi = fs_exp(-(e - e_min));
        num += psi * m->weight[i];
        den += psi;
    }
    return num / den;
}

/* A periodic step's coefficients: the law's, its phase increment and the scaled amplitude. */
static inline dmp_ptick_coef_t dmp_pcoef(const dmp_model_t *m, const dmp_tick_coef_t *c,
                                         fs_real_t amplitude_scale)
{
    const dmp_ptick_coef_t pc = {.k1 = c->k1,
                                 .k_alpha = c->k_alpha,
                                 .k_alphabeta = c->k_alphabeta,
                                 .k_gamma = c->k_gamma,
                                 .phase_inc = fs_num_turn_inc(c->k1 / DMP_TWO_PI),
                                 .goal = c->goal,
                                 .amplitude = amplitude_scale * m->amplitude_N,
                                 .out_scale = FS_R(1.0),
                                 .term_y = c->term_y};
    return pc;
}

fs_real_t dmp_periodic_step(const dmp_model_t *m, dmp_state_t *s, const dmp_run_t *run,
                            fs_real_t amplitude_scale, const dmp_coupling_t *coupling)
{
    const dmp_ptick_state_t st = {s->window, &s->u, &s->u_comp, &s->y_N, &s->z, &s->integral_y};
    const fs_real_t s_blend = dmp_ptick_state_blend(m, &st);
    const dmp_tick_coef_t c = dmp_coef(m, run, coupling);
    const dmp_ptick_coef_t pc = dmp_pcoef(m, &c, amplitude_scale);
    return m->force0_N + dmp_ptick_step(m, &pc, &st, s_blend, NULL);
}

fs_real_t dmp_periodic_step_xy(const dmp_model_t *m, dmp_state_t *s, const dmp_run_t *run,
                               fs_real_t amplitude_scale, const dmp_coupling_t *coupling,
                               fs_real_t path_scale, fs_real_t *path_m)
{
    if (m->has_y == 0u) { /* a force-only skill: dmp_periodic_step's code */
        if (path_m != NULL) {
            *path_m = FS_R(0.0);
        }
        return dmp_periodic_step(m, s, run, amplitude_scale, coupling);
    }
    const dmp_ptick_state_t st = {s->window, &s->u, &s->u_comp, &s->y_N, &s->z, &s->integral_y};
    fs_real_t s_y = FS_R(0.0);
    const fs_real_t s_blend = dmp_ptick_state_blend2(m, &st, m->y_weight, &s_y);
    const dmp_tick_coef_t c = dmp_coef(m, run, coupling);
    const dmp_ptick_coef_t pc = dmp_pcoef(m, &c, amplitude_scale);
    const dmp_tick_path_coef_t cp = {.k1 = c.k1,
                                     .k_alpha = c.k_alpha,
                                     .k_alphabeta = c.k_alpha * m->beta_y,
                                     .goal = FS_R(0.0),
                                     .scale = path_scale};
    const fs_real_t q = dmp_ptick_path_step(&cp, &s->path_m, &s->path_z, s_y, NULL);
    if (path_m != NULL) {
        *path_m = path_scale * m->goal_y_m + q;
    }
    return m->force0_N + dmp_ptick_step(m, &pc, &st, s_blend, NULL);
}

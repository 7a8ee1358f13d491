/* Fixed-point force DMP: conversion with range validation, kernel blend and one Euler step.
 * Same discrete algorithm as firmware/core/dmp.c (docs/math.md section 2); formats in fx.h. */
#include "dmpfx.h"

#include <math.h>
#include <stddef.h>

/* sqrt(2*16): kernel i can pass the cutoff only if |u - c_i| <= DMPFX_R_CUT * sigma_i. The
 * envelopes are widened by 1e-4 so rounding never drops a kernel; the e_i test decides. */
#define DMPFX_R_CUT 5.656854249492381
#define DMPFX_ENVELOPE_MARGIN 1.0001
/* |u - c_i|/sigma_i >= 6 gives e_i > 16 and is skipped before squaring: in Q.49 that is a high
 * word >= 6 << 17. */
#define DMPFX_R_SKIP_HI ((uint32_t)6u << 17)

static int32_t dmpfx_env_clamp_q30(double v)
{
    const double lim = 2.0 - ldexp(1.0, -30);
    const double c = (v > lim) ? lim : ((v < -2.0) ? -2.0 : v);
    return (int32_t)floor(ldexp(c, 30) + 0.5);
}

/* Candidate window [lo, hi): lo = first i with env_hi[i] >= u, hi = first i with env_lo[i] > u
 * (both envelopes non-decreasing), as in dmp.c. */
static void dmpfx_window(const dmpfx_model_t *m, int32_t u, uint32_t *lo, uint32_t *hi)
{
    uint32_t a = 0u;
    uint32_t b = m->n_kernels;
    while (a < b) {
        const uint32_t mid = (a + b) >> 1;
        if (m->env_hi_q30[mid] < u) {
            a = mid + 1u;
        } else {
            b = mid;
        }
    }
    *lo = a;
    a = 0u;
    b = m->n_kernels;
    while (a < b) {
        const uint32_t mid = (a + b) >> 1;
        if (m->env_lo_q30[mid] <= u) {
            a = mid + 1u;
        } else {
            b = mid;
        }
    }
    *hi = a;
}

static fs_status_t dmpfx_measure_peaks(dmpfx_model_t *m, double duration_s);

fs_status_t dmpfx_from_model(const dmp_model_t *m, dmpfx_model_t *out)
{
    if (m == NULL || out == NULL) {
        return FS_ERR_NULL_ARG;
    }
    const uint16_t n = m->n_kernels;
    if (n == 0u || n > DMP_MAX_KERNELS) {
        return FS_ERR_SKILL_KERNELS;
    }
    out->n_kernels = n;
    const int32_t q24_lim = (int32_t)(DMPFX_Q24_HEADROOM * (double)FX_Q24_ONE);
    for (uint16_t i = 0u; i < n; i++) {
        const double c = (double)m->centre[i];
        const double s = (double)m->width[i];
        const double w = (double)m->weight[i];
        fs_status_t st = fx_from_double(c, 30u, INT32_MAX, &out->centre_q30[i]);
        if (st == FS_OK) {
            st = fx_from_double(1.0 / s, 19u, INT32_MAX, &out->inv_sigma_q19[i]);
        }
        if (st == FS_OK) {
            st = fx_from_double(w, 24u, q24_lim, &out->weight_q24[i]);
        }
        if (st != FS_OK) {
            return st;
        }
        const double r = DMPFX_R_CUT * DMPFX_ENVELOPE_MARGIN * s;
        out->env_hi_q30[i] = dmpfx_env_clamp_q30(c + r);
        out->env_lo_q30[i] = dmpfx_env_clamp_q30(c - r);
    }
    for (uint16_t i = 1u; i < n; i++) {
        if (out->env_hi_q30[i] < out->env_hi_q30[i - 1u]) {
            out->env_hi_q30[i] = out->env_hi_q30[i - 1u];
        }
    }
    for (uint16_t j = (uint16_t)(n - 1u); j > 0u; j--) {
        if (out->env_lo_q30[j - 1u] > out->env_lo_q30[j]) {
            out->env_lo_q30[j - 1u] = out->env_lo_q30[j];
        }
    }
    /* Largest candidate window: hi(u) only grows at u = env_lo[j], so the maximum of
     * hi(u) - lo(u) is attained at one of those phases. */
    for (uint16_t j = 0u; j < n; j++) {
        uint32_t lo;
        uint32_t hi;
        dmpfx_window(out, out->env_lo_q30[j], &lo, &hi);
        if (hi > lo && hi - lo > DMPFX_MAX_WINDOW) {
            return FS_ERR_FIXED_WINDOW;
        }
    }
    fs_status_t st = fx_from_double((double)m->stiffness_Npm, 12u, INT32_MAX, &out->stiffness_q12);
    if (st != FS_OK) {
        return st;
    }
    out->dt_s = (double)m->dt_s;
    out->tau_s = (double)m->tau_s;
    out->alpha = (double)m->p.alpha;
    out->beta = (double)m->p.beta;
    out->gamma = (double)m->p.gamma;
    out->goal_m = (double)m->goal_m;
    out->peak_q24 = 0.0;
    out->peak_v_q30 = 0.0;
    return dmpfx_measure_peaks(out, (double)m->duration_s);
}

fs_status_t dmpfx_run_init(const dmpfx_model_t *m, double goal_scale, double time_scale,
                           dmpfx_run_t *run)
{
    if (m == NULL || run == NULL) {
        return FS_ERR_NULL_ARG;
    }
    if (!isfinite(goal_scale) || !isfinite(time_scale) || !(time_scale > 0.0)) {
        return FS_ERR_SCALE_INVALID;
    }
    const double k = m->dt_s / (m->tau_s * time_scale);
    /* Below 2^-24 the phase increments lose more than 7 bits of Q1.31. Each constant < 0.5
     * keeps every 64-bit accumulator below 2^63 for any int32 state (and k*alpha >= 1 would
     * not be a stable Euler step anyway). */
    if (!(k >= ldexp(1.0, -24)) || !(k < 0.5) || !(k * m->alpha < 0.5) ||
        !(k * m->alpha * m->beta < 0.5) || !(k * m->gamma < 0.5)) {
        return FS_ERR_FIXED_STEP;
    }
    fs_status_t st = fx_from_double(k, 31u, INT32_MAX, &run->k1_q31);
    if (st == FS_OK) {
        st = fx_from_double(k * m->alpha, 31u, INT32_MAX, &run->k_alpha_q31);
    }
    if (st == FS_OK) {
        st = fx_from_double(k * m->alpha * m->beta, 31u, INT32_MAX, &run->k_alphabeta_q31);
    }
    if (st == FS_OK) {
        st = fx_from_double(k * m->gamma, 31u, INT32_MAX, &run->k_gamma_q31);
    }
    if (st != FS_OK) {
        return FS_ERR_FIXED_STEP;
    }
    const double g = m->goal_m * goal_scale;
    const double lim_q24 = DMPFX_Q24_HEADROOM * (double)FX_Q24_ONE;
    if (fabs(goal_scale) * m->peak_q24 > lim_q24) {
        return FS_ERR_FIXED_OVERFLOW;
    }
    return fx_from_double(g, 24u, (int32_t)lim_q24, &run->goal_q24);
}

void dmpfx_state_reset(dmpfx_state_t *s)
{
    s->u_acc = 0;
    s->v_acc = 0;
    s->integral_x_acc = 0;
    s->x_acc = 0;
    s->z_acc = 0;
    s->sat_events = 0u;
}

/* |u - c_i| / sigma_i in Q.49 (64-bit; |d| < 2^31, 1/sigma < 2^31). */
static int64_t dmpfx_r_abs_q49(const dmpfx_model_t *m, uint32_t i, int32_t u)
{
    const int64_t d = (int64_t)u - (int64_t)m->centre_q30[i];
    const int64_t r = (d < 0 ? -d : d) * (int64_t)m->inv_sigma_q19[i];
    return r;
}

/* Weight of the kernel with the smallest e_i = smallest |u - c_i|/sigma_i (first on ties). */
static int32_t dmpfx_nearest_weight(const dmpfx_model_t *m, int32_t u)
{
    uint32_t best = 0u;
    int64_t r_best = dmpfx_r_abs_q49(m, 0u, u);
    for (uint32_t i = 1u; i < m->n_kernels; i++) {
        const int64_t r = dmpfx_r_abs_q49(m, i, u);
        if (r < r_best) {
            r_best = r;
            best = i;
        }
    }
    return m->weight_q24[best];
}

int32_t dmpfx_blend(const dmpfx_model_t *m, int32_t u_q30, uint16_t *count)
{
    /* lo = first i with env_hi[i] >= u (binary search); the window then runs while
     * env_lo[i] <= u (env_lo is non-decreasing), as dmp.c's [lo, hi), at most
     * DMPFX_MAX_WINDOW kernels (guaranteed at conversion, enforced here). */
    uint32_t a = 0u;
    uint32_t b = m->n_kernels;
    while (a < b) {
        const uint32_t mid = (a + b) >> 1;
        if (m->env_hi_q30[mid] < u_q30) {
            a = mid + 1u;
        } else {
            b = mid;
        }
    }
    const uint32_t lo = a;
    uint32_t end = lo + DMPFX_MAX_WINDOW;
    end = (end < m->n_kernels) ? end : m->n_kernels;
    uint32_t e_q27[DMPFX_MAX_WINDOW];
    uint32_t idx[DMPFX_MAX_WINDOW];
    uint32_t n = 0u;
    uint32_t e_min = UINT32_MAX;
    for (uint32_t i = lo; i < end && m->env_lo_q30[i] <= u_q30; i++) {
        /* |u - c_i| exactly in uint32 (< 2^32 for any int32 pair; no signed overflow) */
        const uint32_t uu = (uint32_t)u_q30;
        const uint32_t cc = (uint32_t)m->centre_q30[i];
        const uint32_t ad = (u_q30 >= m->centre_q30[i]) ? uu - cc : cc - uu;
        /* r = |u - c_i|/sigma_i in Q.49 */
        const uint64_t r = (uint64_t)ad * (uint32_t)m->inv_sigma_q19[i];
        if ((uint32_t)(r >> 32) >= DMPFX_R_SKIP_HI) {
            continue;
        }
        const uint32_t r27 = (uint32_t)(r >> 22);                      /* Q.27, < 6*2^27 */
        const uint32_t e = (uint32_t)(((uint64_t)r27 * r27) >> 28);   /* r^2/2, Q5.27 */
        if (e > DMPFX_CUTOFF_Q27) {
            continue;
        }
        e_q27[n] = e;
        idx[n] = i;
        n++;
        e_min = (e < e_min) ? e : e_min;
    }
    if (count != NULL) {
        *count = (uint16_t)((n == 0u) ? 1u : n);
    }
    if (n == 0u) {
        return dmpfx_nearest_weight(m, u_q30);
    }
    /* psi in Q.30 (psi_Q31 / 2, so the product with w is one signed 32x32 multiply):
     * num = sum psi*w / 2^3 in Q.51 (< 32 * 2^60 / 8 = 2^62), den = sum psi in Q.30 >= 2^30. */
    int64_t num = 0;
    uint64_t den = 0u;
    for (uint32_t j = 0u; j < n; j++) {
        const int32_t psi = (int32_t)(fx_exp_neg_q27(e_q27[j] - e_min) >> 1);
        num += ((int64_t)m->weight_q24[idx[j]] * psi) >> 3;
        den += (uint32_t)psi;
    }
    /* S = num*2^3/den in Q.24. |S| <= max|w| <= 2^30, so the quotient fits; bring den to 32 bits
     * (it is >= 2^30, so it keeps >= 30 significant bits) and shift num to match. */
    const int neg = num < 0;
    const uint64_t mag = (uint64_t)(neg ? -num : num);
    uint64_t nn;
    uint32_t dd;
    if ((den >> 32) == 0u) {
        nn = mag << 3;
        dd = (uint32_t)den;
    } else {
        const unsigned s = 32u - (unsigned)__builtin_clz((uint32_t)(den >> 32)); /* 1..3 */
        dd = (uint32_t)(den >> s);
        nn = mag << (3u - s);
    }
    const uint32_t q = fx_udiv64_32_round(nn, dd);
    return neg ? -(int32_t)q : (int32_t)q;
}

/* Saturate and count: the states never wrap, and a run that saturates is visible. */
static int32_t dmpfx_sat(int64_t v, uint32_t *events)
{
    const int32_t r = fx_sat32(v);
    if ((int64_t)r != v) {
        (*events)++;
    }
    return r;
}

/* Saturating 32-bit add/sub that count saturations. */
static int32_t dmpfx_add(int32_t a, int32_t b, uint32_t *events)
{
    int32_t r;
    if (__builtin_add_overflow(a, b, &r)) {
        (*events)++;
        return (a < 0) ? INT32_MIN : INT32_MAX;
    }
    return r;
}

static int32_t dmpfx_sub(int32_t a, int32_t b, uint32_t *events)
{
    int32_t r;
    if (__builtin_sub_overflow(a, b, &r)) {
        (*events)++;
        return (a < 0) ? INT32_MIN : INT32_MAX;
    }
    return r;
}

/* acc + inc with acc kept within +-(2^30 - 1)*2^32 (its view, acc/2^31 rounded, then fits
 * int32 with a margin of 2): the bound is checked on the high word only. |acc| < 2^62 and
 * |inc| < 2^62 (constants < 0.5), so the sum cannot overflow int64. */
#define DMPFX_ACC_HI_MAX 0x3FFFFFFF
static int64_t dmpfx_acc_add(int64_t acc, int64_t inc, uint32_t *events)
{
    const int64_t r = acc + inc;
    const int32_t hi = (int32_t)(r >> 32);
    if (hi >= DMPFX_ACC_HI_MAX) {
        (*events)++;
        return (int64_t)DMPFX_ACC_HI_MAX * 4294967296;
    }
    if (hi < -DMPFX_ACC_HI_MAX) {
        (*events)++;
        return -(int64_t)DMPFX_ACC_HI_MAX * 4294967296;
    }
    return r;
}

static int32_t dmpfx_scale_q31(int32_t k_q31, uint32_t rate_q31)
{
    return (int32_t)(((uint64_t)(uint32_t)k_q31 * rate_q31 + (1u << 30)) >> 31);
}

int32_t dmpfx_step(const dmpfx_model_t *m, const dmpfx_run_t *run, dmpfx_state_t *s,
                   const dmpfx_coupling_t *coupling)
{
    int32_t k1 = run->k1_q31;
    int32_t ka = run->k_alpha_q31;
    int32_t kab = run->k_alphabeta_q31;
    int32_t kg = run->k_gamma_q31;
    int32_t term_x = 0;
    if (coupling != NULL) {
        term_x = coupling->term_x_q24;
        const uint32_t rate = (coupling->rate_q31 > FX_Q31_ONE_U) ? FX_Q31_ONE_U : coupling->rate_q31;
        if (rate != FX_Q31_ONE_U) {
            k1 = dmpfx_scale_q31(k1, rate);
            ka = dmpfx_scale_q31(ka, rate);
            kab = dmpfx_scale_q31(kab, rate);
            kg = dmpfx_scale_q31(kg, rate);
        }
    }
    const int32_t g = run->goal_q24;
    const int32_t u = dmpfx_view(s->u_acc);
    const int32_t v = dmpfx_view(s->v_acc);
    const int32_t i_x = dmpfx_view(s->integral_x_acc);
    const int32_t x = dmpfx_view(s->x_acc);
    const int32_t z = dmpfx_view(s->z_acc);
    uint32_t ev = s->sat_events;

    const int32_t sw = dmpfx_blend(m, u, NULL);
    const int32_t gv = dmpfx_sat(fx_rshift_round((int64_t)g * v, 30u), &ev);
    const int32_t h = dmpfx_sat(fx_rshift_round((int64_t)gv * sw, 24u), &ev);

    /* Increments in Q.55 (x, z, I) and Q.61 (u, v): Q1.31 constants times the views, exact. */
    const int32_t sx = dmpfx_add(dmpfx_add(dmpfx_sub(z, x, &ev), h, &ev), term_x, &ev);
    const int32_t gx = dmpfx_sub(g, x, &ev);
    const int32_t one_u = dmpfx_sub(FX_Q30_ONE, u, &ev);
    s->x_acc = dmpfx_acc_add(s->x_acc, (int64_t)k1 * sx - (int64_t)kg * i_x, &ev);
    s->z_acc = dmpfx_acc_add(s->z_acc, (int64_t)kab * gx - (int64_t)ka * z, &ev);
    s->integral_x_acc = dmpfx_acc_add(s->integral_x_acc, (int64_t)k1 * x, &ev);
    s->v_acc = dmpfx_acc_add(s->v_acc, (int64_t)kab * one_u - (int64_t)ka * v, &ev);
    s->u_acc = dmpfx_acc_add(s->u_acc, (int64_t)k1 * v, &ev);
    const int32_t x_new = dmpfx_view(s->x_acc);
    const int32_t f = dmpfx_sat(fx_rshift_round((int64_t)m->stiffness_q12 * x_new, 20u), &ev);
    s->sat_events = ev;
    return f;
}

static double dmpfx_absd(int32_t v)
{
    return fabs((double)v);
}

/* The nominal run (goal 1, time 1), T/dt steps: peaks of h, x, z, I (Q8.24 units) and v~ (Q2.30
 * units) into the model; any saturation, a peak above the headroom or |v~| > DMPFX_V_MAX -> 300.
 * The phase variable checks alpha, beta as the run will see them (v~ peaks at sqrt(alpha beta)/e
 * for the critically damped phase: 1.66 for the default gains). */
static fs_status_t dmpfx_measure_peaks(dmpfx_model_t *m, double duration_s)
{
    m->peak_q24 = 0.0;
    m->peak_v_q30 = 0.0;
    dmpfx_run_t run;
    const fs_status_t st = dmpfx_run_init(m, 1.0, 1.0, &run);
    if (st != FS_OK) {
        return st;
    }
    dmpfx_state_t s;
    dmpfx_state_reset(&s);
    const long rows = lround(duration_s / m->dt_s);
    double peak = 0.0;
    double peak_v = 0.0;
    for (long n = 0; n < rows; n++) {
        const int32_t u = dmpfx_view(s.u_acc);
        const int32_t v = dmpfx_view(s.v_acc);
        const int32_t sw = dmpfx_blend(m, u, NULL);
        const double h = (double)run.goal_q24 * ldexp((double)v, -30) * ldexp((double)sw, -24);
        (void)dmpfx_step(m, &run, &s, NULL);
        peak = fmax(peak, fmax(fabs(h), fmax(dmpfx_absd(dmpfx_view(s.x_acc)),
                                             fmax(dmpfx_absd(dmpfx_view(s.z_acc)),
                                                  dmpfx_absd(dmpfx_view(s.integral_x_acc))))));
        peak_v = fmax(peak_v, dmpfx_absd(dmpfx_view(s.v_acc)));
    }
    m->peak_q24 = fmax(peak, dmpfx_absd(run.goal_q24));
    m->peak_v_q30 = peak_v;
    if (s.sat_events != 0u || m->peak_q24 > DMPFX_Q24_HEADROOM * (double)FX_Q24_ONE ||
        peak_v > DMPFX_V_MAX * (double)FX_Q30_ONE) {
        return FS_ERR_FIXED_OVERFLOW;
    }
    return FS_OK;
}

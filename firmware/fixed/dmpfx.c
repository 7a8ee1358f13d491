/* Fixed-point force DMP: conversion with range validation and the per-run constants; the
 * kernel blend and the Euler step are firmware/core/dmp_tick.h over the fixed numeric layer,
 * the same source as dmp_step (docs/math.md section 2); formats in fx.h and fs_num.h. */
#include "dmpfx.h"

#include <math.h>
#include <stddef.h>

#include "fs_num.h"
#define DMP_TICK_MODEL dmpfx_model_t
#include "dmp_tick.h"

/* sqrt(2*16): kernel i can pass the cutoff only if |u - c_i| <= DMPFX_R_CUT * sigma_i. The
 * envelopes are widened by 1e-4 so rounding never drops a kernel; the e_i test decides. */
#define DMPFX_R_CUT 5.656854249492381
#define DMPFX_ENVELOPE_MARGIN 1.0001

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
    *lo = dmp_tick_window_start(m, u);
    uint32_t a = 0u;
    uint32_t b = m->n_kernels;
    while (a < b) {
        const uint32_t mid = (a + b) >> 1;
        if (m->env_lo[mid] <= u) {
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
        fs_status_t st = fx_from_double(c, 30u, INT32_MAX, &out->centre[i]);
        if (st == FS_OK) {
            st = fx_from_double(1.0 / s, 19u, INT32_MAX, &out->kernel_scale[i]);
        }
        if (st == FS_OK) {
            st = fx_from_double(w, 24u, q24_lim, &out->weight[i]);
        }
        if (st != FS_OK) {
            return st;
        }
        const double r = DMPFX_R_CUT * DMPFX_ENVELOPE_MARGIN * s;
        out->env_hi[i] = dmpfx_env_clamp_q30(c + r);
        out->env_lo[i] = dmpfx_env_clamp_q30(c - r);
    }
    for (uint16_t i = 1u; i < n; i++) {
        if (out->env_hi[i] < out->env_hi[i - 1u]) {
            out->env_hi[i] = out->env_hi[i - 1u];
        }
    }
    for (uint16_t j = (uint16_t)(n - 1u); j > 0u; j--) {
        if (out->env_lo[j - 1u] > out->env_lo[j]) {
            out->env_lo[j - 1u] = out->env_lo[j];
        }
    }
    /* Largest candidate window: hi(u) only grows at u = env_lo[j], so the maximum of
     * hi(u) - lo(u) is attained at one of those phases. */
    for (uint16_t j = 0u; j < n; j++) {
        uint32_t lo;
        uint32_t hi;
        dmpfx_window(out, out->env_lo[j], &lo, &hi);
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

int32_t dmpfx_blend(const dmpfx_model_t *m, int32_t u_q30, uint16_t *count)
{
    return dmp_tick_blend(m, u_q30, count);
}

static int32_t dmpfx_scale_q31(int32_t k_q31, uint32_t rate_q31)
{
    return (int32_t)(((uint64_t)(uint32_t)k_q31 * rate_q31 + (1u << 30)) >> 31);
}

int32_t dmpfx_step(const dmpfx_model_t *m, const dmpfx_run_t *run, dmpfx_state_t *s,
                   const dmpfx_coupling_t *coupling)
{
    dmp_tick_coef_t c = {.k1 = run->k1_q31,
                         .k_alpha = run->k_alpha_q31,
                         .k_alphabeta = run->k_alphabeta_q31,
                         .k_gamma = run->k_gamma_q31,
                         .goal = run->goal_q24,
                         .stiffness = m->stiffness_q12,
                         .term_x = 0};
    if (coupling != NULL) {
        c.term_x = coupling->term_x_q24;
        const uint32_t rate = (coupling->rate_q31 > FX_Q31_ONE_U) ? FX_Q31_ONE_U
                                                                  : coupling->rate_q31;
        if (rate != FX_Q31_ONE_U) {
            c.k1 = dmpfx_scale_q31(c.k1, rate);
            c.k_alpha = dmpfx_scale_q31(c.k_alpha, rate);
            c.k_alphabeta = dmpfx_scale_q31(c.k_alphabeta, rate);
            c.k_gamma = dmpfx_scale_q31(c.k_gamma, rate);
        }
    }
    const dmp_tick_state_t st = {&s->u_acc, &s->v_acc, &s->integral_x_acc, &s->x_acc, &s->z_acc};
    return dmp_tick_step(m, &c, &st, &s->sat_events);
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

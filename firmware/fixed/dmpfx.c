/* Fixed-point force DMP: conversion with range validation and the per-run constants; the
 * kernel blend and the Euler step are firmware/core/dmp_tick.h over the fixed numeric layer,
 * the same source as dmp_step (docs/math.md section 2); formats in fx.h and fs_num.h. */
#include "dmpfx.h"

#include <math.h>
#include <stddef.h>
#include <string.h>

#include "fs_job.h"
#include "fs_num.h"
#define DMP_TICK_MODEL dmpfx_model_t
#include "dmp_tick.h"
#include "dmp_ptick.h"

#define DMPFX_TWO_PI 6.283185307179586

/* sqrt(2 * FS_NUM_CUTOFF_E): kernel i can pass the cutoff only if |u - c_i| <= DMPFX_R_CUT * sigma_i. The
 * envelopes are widened by 1e-4 so rounding never drops a kernel; the e_i test decides. */
#define DMPFX_R_CUT 4.898979485566356
#define DMPFX_ENVELOPE_MARGIN 1.0001
/* 1/e, and the bound on |v~| the estimate of the y DMP's forcing uses (|h_y| = |v~ S_y|) */
#define DMPFX_INV_E 0.36787944117144233
#define DMPFX_V_PEAK_BOUND 1.9

/* A skill value (fs_real_t) in a Q format with frac fraction bits, |result| <= limit, else
 * FS_ERR_FIXED_OVERFLOW (also for a value that is not finite). The float build converts from the
 * float's bits (fx_from_float: no software-float call); the double build rounds half up. */
static fs_status_t dmpfx_q(fs_real_t v, unsigned frac, int32_t limit, int32_t *out)
{
#ifdef FS_REAL_FLOAT
    uint32_t b;
    memcpy(&b, &v, sizeof b);
    const int32_t x = fx_from_float(v, frac);
    if ((b & 0x7F800000u) == 0x7F800000u || x == INT32_MAX || x == INT32_MIN || x > limit ||
        x < -limit) {
        return FS_ERR_FIXED_OVERFLOW;
    }
    *out = x;
    return FS_OK;
#else
    return fx_from_double(v, frac, limit, out);
#endif
}

/* An envelope in Q2.30, clamped to its range [-2, 2) */
static int32_t dmpfx_env_clamp_q30(fs_real_t v)
{
#ifdef FS_REAL_FLOAT
    return fx_from_float(v, 30u); /* saturates to the range */
#else
    const double lim = 2.0 - ldexp(1.0, -30);
    const double c = (v > lim) ? lim : ((v < -2.0) ? -2.0 : v);
    return (int32_t)floor(ldexp(c, 30) + 0.5);
#endif
}

/* Candidate window [lo, hi): lo = first i with env_hi[i] >= u, hi = first i with env_lo[i] > u
 * (both envelopes non-decreasing), as in dmp.c. */
static void dmpfx_window(const dmpfx_model_t *m, int32_t u, uint32_t *lo, uint32_t *hi)
{
    *lo = dmp_tick_window_start(m, u);
    *hi = dmp_tick_window_end(m, u);
}

static fs_status_t dmpfx_measure_peaks(dmpfx_model_t *m, double duration_s);

/* The smallest s in [DMPFX_SHIFT_MIN, DMPFX_SHIFT_MAX] with magnitude*2^-s <= DMPFX_SCALE_TARGET
 * (DMPFX_SHIFT_MAX + 1 if none: refused by dmpfx_convert). */
static int32_t dmpfx_choose_shift(double magnitude)
{
    int32_t s = DMPFX_SHIFT_MIN;
    while (s <= DMPFX_SHIFT_MAX && !(magnitude <= ldexp(DMPFX_SCALE_TARGET, s))) {
        s++;
    }
    return s;
}

static fs_status_t dmpfx_convert(const dmp_model_t *m, int32_t shift, dmpfx_model_t *out);

/* max |w_i| of a weight set */
static double dmpfx_w_max(const fs_real_t *w, uint16_t n)
{
    fs_real_t w_max = FS_R(0.0);
    for (uint16_t i = 0u; i < n; i++) {
        const fs_real_t a = fs_fabs(w[i]);
        w_max = (a > w_max) ? a : w_max;
    }
    return (double)w_max;
}

/* B = |g|*(1 + max|w_i|) in N: |h| <= 1.9*|g|*max|w_i|, and y, z, I follow g and h. A periodic
 * model: |g| + DMPFX_PERIODIC_BOUND*r*(1 + max|w_i|) (h = r*S, |S| <= max|w_i|; e, z, I follow
 * h through the same stable filter, and the output is g + e). */
#define DMPFX_PERIODIC_BOUND 4.0
static double dmpfx_bound_N(const dmp_model_t *m)
{
    const double w = dmpfx_w_max(m->weight, m->n_kernels);
    if (m->periodic != 0u) {
        return fabs((double)m->goal_N) + DMPFX_PERIODIC_BOUND * (double)m->amplitude_N * (1.0 + w);
    }
    return fabs((double)m->goal_N) * (1.0 + w);
}

static fs_status_t dmpfx_check_args(const dmp_model_t *m, const dmpfx_model_t *out)
{
    if (m == NULL || out == NULL) {
        return FS_ERR_NULL_ARG;
    }
    return (m->n_kernels == 0u || m->n_kernels > DMP_MAX_KERNELS) ? FS_ERR_SKILL_KERNELS : FS_OK;
}

fs_status_t dmpfx_from_model(const dmp_model_t *m, dmpfx_model_t *out)
{
    const fs_status_t sa = dmpfx_check_args(m, out);
    if (sa != FS_OK) {
        return sa;
    }
    /* Two passes: first at a scale that keeps B <= 2 (the nominal run stays far below the
     * headroom of 64), to measure its peak in N; then at the scale that puts that peak at
     * DMPFX_SCALE_TARGET (the headroom above it is what goal scales up to
     * 64/DMPFX_SCALE_TARGET use), measured again. */
    const double bound_N = dmpfx_bound_N(m) * 0.5 * DMPFX_SCALE_TARGET;
    const int32_t s1 = dmpfx_choose_shift(bound_N);
    fs_status_t st = dmpfx_convert(m, s1, out);
    if (st == FS_OK) {
        st = dmpfx_measure_peaks(out, (double)m->duration_s);
    }
    if (st != FS_OK) {
        return st;
    }
    const double peak_N = ldexp(out->peak_q24 / (double)FX_Q24_ONE, s1);
    const int32_t s2 = dmpfx_choose_shift(peak_N);
    if (s2 == s1) {
        return FS_OK;
    }
    st = dmpfx_convert(m, s2, out);
    return (st == FS_OK) ? dmpfx_measure_peaks(out, (double)m->duration_s) : st;
}

fs_status_t dmpfx_from_model_bound(const dmp_model_t *m, dmpfx_model_t *out)
{
    dmpfx_conv_t c;
    dmpfx_bound_begin(&c, m, out);
    while (!dmpfx_bound_run(&c, UINT32_MAX)) {
    }
    return c.status;
}

/* A periodic kernel's reach in turns at the fixed cutoff 12: asin(y)/pi, y = sqrt(12/(2 kappa)),
 * bounded above by (y + (pi/2 - 1) y^3)/pi ((asin(y) - y)/y^3 rises from 1/6 to pi/2 - 1 on
 * [0, 1]: 3 % wider than exact at the fit's kappa, no asin), widened by the envelope margin, at
 * most half a turn. In the model's type: one software-float sqrt a kernel on the M3, no double
 * (the executor converts when a step begins, within a tick). */
static fs_real_t dmpfx_periodic_reach(fs_real_t kappa)
{
    const fs_real_t q = FS_R(12.0) / (FS_R(2.0) * kappa);
    if (!(q < FS_R(1.0))) {
        return FS_R(0.5);
    }
    const fs_real_t y = fs_sqrt(q);
    const fs_real_t r = (y + FS_R(0.5707963267948966) * y * y * y) * FS_R(0.3183098861837907) *
                        (fs_real_t)DMPFX_ENVELOPE_MARGIN;
    return (r < FS_R(0.5)) ? r : FS_R(0.5);
}

/* A value in [-1, 1] from Q2.30 to Q1.31, +-1 held at +-(1 - 2^-31) (fs_num_vm_dist's format). */
static int32_t dmpfx_q31_unit(int32_t q30)
{
    if (q30 >= FX_Q30_ONE) {
        return INT32_MAX;
    }
    if (q30 <= -FX_Q30_ONE) {
        return -INT32_MAX;
    }
    return q30 * 2;
}

/* Periodic kernel i in fixed point: its turn, 2 sqrt(kappa), the half-angle sine and cosine
 * (the model's, derived at load) and its envelopes in turns (before the prefix/suffix passes). */
static fs_status_t dmpfx_kernel_periodic(const dmp_model_t *m, uint16_t i, dmpfx_model_t *out)
{
    const int32_t q24_lim = (int32_t)(DMPFX_Q24_HEADROOM * (double)FX_Q24_ONE);
    const fs_real_t x = m->centre[i] * FS_R(0.15915494309189535); /* 1/(2 pi) */
    const fs_real_t kappa = m->width[i];
    fs_status_t st = dmpfx_q(x, 30u, INT32_MAX, &out->centre[i]);
    if (st == FS_OK) {
        st = dmpfx_q(FS_R(2.0) * fs_sqrt(kappa), 19u, INT32_MAX, &out->kernel_scale[i]);
    }
    if (st == FS_OK) {
        st = dmpfx_q(m->weight[i], 24u, q24_lim, &out->weight[i]);
    }
    if (st == FS_OK && m->has_y != 0u) {
        st = dmpfx_q(m->y_weight[i], 24u, q24_lim, &out->y_weight[i]);
    }
    if (st == FS_OK) {
        st = dmpfx_q(m->half_sin[i], 30u, INT32_MAX, &out->half_sin[i]);
    }
    if (st == FS_OK) {
        st = dmpfx_q(m->half_cos[i], 30u, INT32_MAX, &out->half_cos[i]);
    }
    out->half_sin[i] = dmpfx_q31_unit(out->half_sin[i]);
    out->half_cos[i] = dmpfx_q31_unit(out->half_cos[i]);
    if (st != FS_OK) {
        return st;
    }
    const fs_real_t r = dmpfx_periodic_reach(kappa);
    out->env_hi[i] = dmpfx_env_clamp_q30(x + r);
    out->env_lo[i] = dmpfx_env_clamp_q30(x - r);
    return FS_OK;
}

/* Discrete kernel i in fixed point: centre, 1/sigma, the weights and its envelopes c +- r sigma
 * (before the prefix/suffix passes). In the model's own type: software float on a core without
 * FPU, no double. */
static fs_status_t dmpfx_kernel_discrete(const dmp_model_t *m, uint16_t i, dmpfx_model_t *out)
{
    const int32_t q24_lim = (int32_t)(DMPFX_Q24_HEADROOM * (double)FX_Q24_ONE);
    const fs_real_t r_env = (fs_real_t)(DMPFX_R_CUT * DMPFX_ENVELOPE_MARGIN);
    const fs_real_t c = m->centre[i];
    const fs_real_t s = m->width[i];
    fs_status_t st = dmpfx_q(c, 30u, INT32_MAX, &out->centre[i]);
    if (st == FS_OK) {
        st = dmpfx_q(FS_R(1.0) / s, 19u, INT32_MAX, &out->kernel_scale[i]);
    }
    if (st == FS_OK) {
        st = dmpfx_q(m->weight[i], 24u, q24_lim, &out->weight[i]);
    }
    if (st == FS_OK && m->has_y != 0u) {
        st = dmpfx_q(m->y_weight[i], 24u, q24_lim, &out->y_weight[i]);
    }
    if (st != FS_OK) {
        return st;
    }
    const fs_real_t r = r_env * s;
    out->env_hi[i] = dmpfx_env_clamp_q30(c + r);
    out->env_lo[i] = dmpfx_env_clamp_q30(c - r);
    return FS_OK;
}

/* The envelopes made monotone: env_hi a prefix max, env_lo a suffix min (integers only). */
static void dmpfx_envelopes(dmpfx_model_t *out)
{
    const uint16_t n = out->n_kernels;
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
}

/* The phases where the candidate window is checked: the window's end grows only at the (virtual,
 * for a periodic model) lower envelopes, so its largest size is at one of them (a periodic
 * model: or at the query range's start). */
static uint32_t dmpfx_window_checks(const dmpfx_model_t *out)
{
    return (out->periodic != 0u) ? 2u * (uint32_t)out->n_kernels + 1u : out->n_kernels;
}

/* The window at check phase j within DMPFX_MAX_WINDOW kernels, else FS_ERR_FIXED_WINDOW. */
static fs_status_t dmpfx_window_check(const dmpfx_model_t *out, uint32_t j)
{
    const uint32_t n = out->n_kernels;
    if (out->periodic != 0u) {
        const int32_t q_lo = FX_Q30_ONE >> 1;
        const int32_t q_hi = FX_Q30_ONE + q_lo - 1;
        int32_t q = (j == 2u * n) ? q_lo : dmp_ptick_lo(out, j);
        q = (q < q_lo) ? q_lo : ((q > q_hi) ? q_hi : q);
        uint16_t win[2];
        dmp_ptick_window_search(out, q, win);
        return (win[1] > win[0] && (uint32_t)(win[1] - win[0]) > DMPFX_MAX_WINDOW &&
                n > DMPFX_MAX_WINDOW)
                   ? FS_ERR_FIXED_WINDOW
                   : FS_OK;
    }
    uint32_t lo;
    uint32_t hi;
    dmpfx_window(out, out->env_lo[j], &lo, &hi);
    return (hi > lo && hi - lo > DMPFX_MAX_WINDOW) ? FS_ERR_FIXED_WINDOW : FS_OK;
}

/* The conversion's scalars before the kernels (FS_ERR_FIXED_OVERFLOW for a shift out of range). */
static fs_status_t dmpfx_convert_head(const dmp_model_t *m, int32_t shift, dmpfx_model_t *out)
{
    if (shift > DMPFX_SHIFT_MAX) {
        return FS_ERR_FIXED_OVERFLOW;
    }
    out->n_kernels = m->n_kernels;
    out->value_shift = shift;
    out->periodic = m->periodic;
    out->amplitude_N = (double)m->amplitude_N;
    out->cycle0_N[0] = (double)m->cycle_e0_N;
    out->cycle0_N[1] = (double)m->cycle_z0_N;
    out->cycle0_N[2] = (double)m->cycle_i0_N;
    out->cycle_y0_m[0] = (double)m->cycle_q0_m;
    out->cycle_y0_m[1] = (double)m->cycle_zq0_m;
    return FS_OK;
}

/* The conversion's scalars after the kernels: the value scale, f0 and the run set-up's doubles;
 * the peaks cleared. */
static fs_status_t dmpfx_convert_tail(const dmp_model_t *m, dmpfx_model_t *out)
{
    fs_status_t st = fx_from_double(ldexp(1.0, out->value_shift), 12u, INT32_MAX,
                                    &out->out_scale_q12);
    if (st == FS_OK) {
        st = fx_from_double((double)m->force0_N, 16u, INT32_MAX, &out->force0_q16);
    }
    if (st != FS_OK) {
        return st;
    }
    out->dt_s = (double)m->dt_s;
    out->tau_s = (double)m->tau_s;
    out->alpha = (double)m->p.alpha;
    out->beta = (double)m->p.beta;
    out->gamma = (double)m->p.gamma;
    out->goal_N = (double)m->goal_N;
    out->has_y = m->has_y;
    out->beta_y = (double)m->beta_y;
    out->goal_y_m = (double)m->goal_y_m;
    out->peak_y_q24 = 0.0;
    out->peak_q24 = 0.0;
    out->peak_v_q30 = 0.0;
    return FS_OK;
}

/* The whole conversion at value shift s, in one call (dmpfx_from_model's passes). */
static fs_status_t dmpfx_convert(const dmp_model_t *m, int32_t shift, dmpfx_model_t *out)
{
    fs_status_t st = dmpfx_convert_head(m, shift, out);
    for (uint16_t i = 0u; st == FS_OK && i < m->n_kernels; i++) {
        st = (m->periodic != 0u) ? dmpfx_kernel_periodic(m, i, out)
                                 : dmpfx_kernel_discrete(m, i, out);
    }
    if (st != FS_OK) {
        return st;
    }
    dmpfx_envelopes(out);
    const uint32_t checks = dmpfx_window_checks(out);
    for (uint32_t j = 0u; st == FS_OK && j < checks; j++) {
        st = dmpfx_window_check(out, j);
    }
    return (st == FS_OK) ? dmpfx_convert_tail(m, out) : st;
}

/* The estimated peaks of dmpfx_from_model_bound (see dmpfx.h) and their check. */
static fs_status_t dmpfx_bound_peaks(const dmp_model_t *m, double bound_N, dmpfx_model_t *out)
{
    const double lim_q24 = DMPFX_Q24_HEADROOM * (double)FX_Q24_ONE;
    out->peak_q24 = ldexp(bound_N, 24 - out->value_shift);
    out->peak_y_q24 = 0.0;
    if (m->has_y != 0u) {
        out->peak_y_q24 = ldexp(fabs((double)m->goal_y_m) +
                                    DMPFX_V_PEAK_BOUND * dmpfx_w_max(m->y_weight, m->n_kernels),
                                24);
    }
    /* v~ of the phase system peaks at sqrt(alpha beta)/e when critically damped (beta =
     * alpha/4), lower when overdamped; the Euler steps overshoot that by 0.2 % on the vectors
     * (a periodic model has no v~) */
    out->peak_v_q30 = (m->periodic != 0u)
                          ? 0.0
                          : ldexp(sqrt(out->alpha * out->beta) * DMPFX_INV_E * 1.01, 30);
    if (out->peak_q24 > lim_q24 || out->peak_y_q24 > lim_q24 ||
        out->peak_v_q30 > DMPFX_V_MAX * (double)FX_Q30_ONE) {
        return FS_ERR_FIXED_OVERFLOW;
    }
    return FS_OK;
}

/* The stages of the sliced conversion (dmpfx_conv_t.stage). */
enum {
    DMPFX_CONV_BOUND = 0, /* the force bound (software double on the M3: a unit of its own) */
    DMPFX_CONV_HEAD,
    DMPFX_CONV_KERNELS,
    DMPFX_CONV_ENVELOPES,
    DMPFX_CONV_WINDOWS,
    DMPFX_CONV_TAIL,
    DMPFX_CONV_PEAKS
};

void dmpfx_bound_begin(dmpfx_conv_t *c, const dmp_model_t *m, dmpfx_model_t *out)
{
    c->m = m;
    c->out = out;
    c->bound_N = 0.0;
    c->pos = 0u;
    c->stage = DMPFX_CONV_BOUND;
    c->status = dmpfx_check_args(m, out);
    c->done = c->status != FS_OK;
}

/* One unit of the sliced conversion: its status (FS_OK while it goes on). */
static fs_status_t dmpfx_bound_unit(dmpfx_conv_t *c)
{
    const dmp_model_t *m = c->m;
    dmpfx_model_t *out = c->out;
    fs_status_t st = FS_OK;
    switch (c->stage) {
    case DMPFX_CONV_BOUND:
        c->bound_N = dmpfx_bound_N(m);
        c->stage = DMPFX_CONV_HEAD;
        break;
    case DMPFX_CONV_HEAD:
        st = dmpfx_convert_head(m, dmpfx_choose_shift(c->bound_N), out);
        c->stage = DMPFX_CONV_KERNELS;
        break;
    case DMPFX_CONV_KERNELS:
        st = (m->periodic != 0u) ? dmpfx_kernel_periodic(m, (uint16_t)c->pos, out)
                                 : dmpfx_kernel_discrete(m, (uint16_t)c->pos, out);
        if (++c->pos >= m->n_kernels) {
            c->stage = DMPFX_CONV_ENVELOPES;
        }
        break;
    case DMPFX_CONV_ENVELOPES:
        dmpfx_envelopes(out);
        c->pos = 0u;
        c->stage = DMPFX_CONV_WINDOWS;
        break;
    case DMPFX_CONV_WINDOWS:
        st = dmpfx_window_check(out, c->pos);
        if (++c->pos >= dmpfx_window_checks(out)) {
            c->stage = DMPFX_CONV_TAIL;
        }
        break;
    case DMPFX_CONV_TAIL:
        st = dmpfx_convert_tail(m, out);
        c->stage = DMPFX_CONV_PEAKS;
        break;
    default:
        st = dmpfx_bound_peaks(m, c->bound_N, out);
        c->done = true;
        break;
    }
    return st;
}

bool dmpfx_bound_run(dmpfx_conv_t *c, uint32_t max_units)
{
    for (uint32_t u = 0u; u < max_units && !c->done; u++) {
        c->status = dmpfx_bound_unit(c);
        if (c->status != FS_OK) {
            c->done = true;
        }
    }
    return c->done;
}

fs_status_t dmpfx_run_init(const dmpfx_model_t *m, double goal_scale, double time_scale,
                           dmpfx_run_t *run)
{
    fs_status_t st = dmpfx_run_force(m, goal_scale, time_scale, run);
    if (st == FS_OK) {
        st = dmpfx_run_periodic(m, 1.0, run);
    }
    return (st == FS_OK) ? dmpfx_run_path(m, 1.0, run) : st;
}

fs_status_t dmpfx_run_force(const dmpfx_model_t *m, double goal_scale, double time_scale,
                            dmpfx_run_t *run)
{
    const fs_status_t st = dmpfx_run_rates(m, goal_scale, time_scale, run);
    return (st == FS_OK) ? dmpfx_run_goal(m, goal_scale, time_scale, run) : st;
}

/* The arguments of dmpfx_run_rates and dmpfx_run_goal: present, finite, time scale > 0. */
static fs_status_t dmpfx_run_args(const dmpfx_model_t *m, double goal_scale, double time_scale,
                                  const dmpfx_run_t *run)
{
    if (m == NULL || run == NULL) {
        return FS_ERR_NULL_ARG;
    }
    if (!isfinite(goal_scale) || !isfinite(time_scale) || !(time_scale > 0.0)) {
        return FS_ERR_SCALE_INVALID;
    }
    return FS_OK;
}

/* A rate in [0, 0.5) in Q1.31, rounded half up: fx_from_double(v, 31, ...)'s value without its
 * checks (the range is the caller's). v * 2^32 is exact and below 2^31; floor(x / 2 + 1/2) of
 * x = v * 2^32 is (floor(x) + 1) >> 1. In software double a product and a conversion. */
static int32_t dmpfx_q31_rate(double v)
{
    return (int32_t)(((uint32_t)(v * 4294967296.0) + 1u) >> 1);
}

fs_status_t dmpfx_run_rates(const dmpfx_model_t *m, double goal_scale, double time_scale,
                            dmpfx_run_t *run)
{
    const fs_status_t args = dmpfx_run_args(m, goal_scale, time_scale, run);
    if (args != FS_OK) {
        return args;
    }
    /* each product once: software double on the M3 (the run start's dearest part) */
    const double k = m->dt_s / (m->tau_s * time_scale);
    const double k_alpha = k * m->alpha;
    const double k_alphabeta = k_alpha * m->beta;
    const double k_gamma = k * m->gamma;
    /* Below 2^-24 the phase increments lose more than 7 bits of Q1.31. Each constant < 0.5
     * keeps every 64-bit accumulator below 2^63 for any int32 state (and k*alpha >= 1 would
     * not be a stable Euler step anyway); none negative (dmpfx_q31_rate's range). */
    if (!(k >= 0x1p-24) || !(k < 0.5) || !(k_alpha >= 0.0 && k_alpha < 0.5) ||
        !(k_alphabeta >= 0.0 && k_alphabeta < 0.5) || !(k_gamma >= 0.0 && k_gamma < 0.5)) {
        return FS_ERR_FIXED_STEP;
    }
    run->k1_q31 = dmpfx_q31_rate(k);
    run->k_alpha_q31 = dmpfx_q31_rate(k_alpha);
    run->k_alphabeta_q31 = dmpfx_q31_rate(k_alphabeta);
    run->k_gamma_q31 = dmpfx_q31_rate(k_gamma);
    return FS_OK;
}

fs_status_t dmpfx_run_goal(const dmpfx_model_t *m, double goal_scale, double time_scale,
                           dmpfx_run_t *run)
{
    const fs_status_t args = dmpfx_run_args(m, goal_scale, time_scale, run);
    if (args != FS_OK) {
        return args;
    }
    run->k_alphabeta_y_q31 = 0;
    run->goal_y_q24 = 0;
    run->path_scale_q24 = 0;
    run->phase_inc = fs_num_turn_inc(m->dt_s / (m->tau_s * time_scale) / DMPFX_TWO_PI);
    run->amplitude_q24 = 0;
    run->amplitude_scale = 1.0;
    const double g = ldexp(m->goal_N * goal_scale, -m->value_shift);
    const double lim_q24 = DMPFX_Q24_HEADROOM * (double)FX_Q24_ONE;
    if (fabs(goal_scale) * m->peak_q24 > lim_q24) {
        return FS_ERR_FIXED_OVERFLOW;
    }
    return fx_from_double(g, 24u, (int32_t)lim_q24, &run->goal_q24);
}

fs_status_t dmpfx_run_periodic(const dmpfx_model_t *m, double amplitude_scale, dmpfx_run_t *run)
{
    if (m == NULL || run == NULL) {
        return FS_ERR_NULL_ARG;
    }
    if (!isfinite(amplitude_scale) || amplitude_scale < 0.0) {
        return FS_ERR_SCALE_INVALID;
    }
    if (m->periodic == 0u) {
        return FS_OK;
    }
    /* the nominal peaks are of goal 1 and amplitude 1: e, z, I, h scale with s_a, the output
     * g + e with both (bounded by the sum of the two) */
    const double lim_q24 = DMPFX_Q24_HEADROOM * (double)FX_Q24_ONE;
    if ((amplitude_scale + 1.0) * m->peak_q24 > lim_q24) {
        return FS_ERR_FIXED_OVERFLOW;
    }
    run->amplitude_scale = amplitude_scale;
    return fx_from_double(ldexp(m->amplitude_N * amplitude_scale, -m->value_shift), 24u,
                          (int32_t)lim_q24, &run->amplitude_q24);
}

fs_status_t dmpfx_run_path(const dmpfx_model_t *m, double path_scale, dmpfx_run_t *run)
{
    if (m == NULL || run == NULL) {
        return FS_ERR_NULL_ARG;
    }
    if (!isfinite(path_scale) || path_scale < 0.0) {
        return FS_ERR_SCALE_INVALID;
    }
    if (m->has_y == 0u) {
        return FS_OK;
    }
    const double lim_q24 = DMPFX_Q24_HEADROOM * (double)FX_Q24_ONE;
    if (path_scale * m->peak_y_q24 > lim_q24) {
        return FS_ERR_FIXED_OVERFLOW;
    }
    /* k*alpha*beta_y from the run's k*alpha (Q1.31): beta_y <= alpha/4 keeps it below 0.5
     * wherever k*alpha is */
    const double k_alpha = (double)run->k_alpha_q31 / 2147483648.0;
    if (!(k_alpha * m->beta_y < 0.5)) {
        return FS_ERR_FIXED_STEP;
    }
    fs_status_t st = fx_from_double(k_alpha * m->beta_y, 31u, INT32_MAX, &run->k_alphabeta_y_q31);
    if (st == FS_OK) {
        st = fx_from_double(m->goal_y_m * path_scale, 24u, (int32_t)lim_q24, &run->goal_y_q24);
    }
    if (st == FS_OK) {
        st = fx_from_double(path_scale, 24u, (int32_t)lim_q24, &run->path_scale_q24);
    }
    return st;
}

void dmpfx_state_reset(dmpfx_state_t *s)
{
    s->window[0] = 0u;
    s->window[1] = 0u;
    s->u_acc = 0;
    s->v_acc = 0;
    s->integral_y_acc = 0;
    s->y_acc = 0;
    s->z_acc = 0;
    s->path_acc = 0;
    s->path_z_acc = 0;
    s->u_comp_acc = 0;
    s->sat_events = 0u;
    s->prep_model = NULL;
}

int32_t dmpfx_blend(const dmpfx_model_t *m, int32_t u_q30, uint16_t *count)
{
    return dmp_tick_blend(m, u_q30, dmp_tick_window_start(m, u_q30), dmp_tick_window_end(m, u_q30),
                          count);
}

static int32_t dmpfx_scale_q31(int32_t k_q31, uint32_t rate_q31)
{
    return (int32_t)(((uint64_t)(uint32_t)k_q31 * rate_q31 + (1u << 30)) >> 31);
}

/* The force DMP's constants of one step (the run's, slowed down by the coupling's rate). */
static dmp_tick_coef_t dmpfx_coef(const dmpfx_model_t *m, const dmpfx_run_t *run,
                                  const dmpfx_coupling_t *coupling, int32_t *k_ab_y)
{
    dmp_tick_coef_t c = {.k1 = run->k1_q31,
                         .k_alpha = run->k_alpha_q31,
                         .k_alphabeta = run->k_alphabeta_q31,
                         .k_gamma = run->k_gamma_q31,
                         .goal = run->goal_q24,
                         .out_scale = m->out_scale_q12,
                         .term_y = 0};
    *k_ab_y = run->k_alphabeta_y_q31;
    if (coupling != NULL) {
        c.term_y = coupling->term_y_q24;
        const uint32_t rate = (coupling->rate_q31 > FX_Q31_ONE_U) ? FX_Q31_ONE_U
                                                                  : coupling->rate_q31;
        if (rate != FX_Q31_ONE_U) {
            c.k1 = dmpfx_scale_q31(c.k1, rate);
            c.k_alpha = dmpfx_scale_q31(c.k_alpha, rate);
            c.k_alphabeta = dmpfx_scale_q31(c.k_alphabeta, rate);
            c.k_gamma = dmpfx_scale_q31(c.k_gamma, rate);
            *k_ab_y = dmpfx_scale_q31(*k_ab_y, rate);
        }
    }
    return c;
}

/* The prepared blend pair if dmpfx_prepare made it for m at the state's phase (taken once). */
static inline bool dmpfx_take_prepared(const dmpfx_model_t *m, dmpfx_state_t *s)
{
    const bool hit = s->prep_model == (const void *)m && s->prep_u == dmpfx_view(s->u_acc);
    s->prep_model = NULL;
    return hit;
}

void dmpfx_prepare(const dmpfx_model_t *m, dmpfx_state_t *s)
{
    const dmp_tick_state_t st = {s->window,          &s->u_acc, &s->v_acc,
                                 &s->integral_y_acc, &s->y_acc, &s->z_acc};
    /* the blend dmpfx_step (force only) or dmpfx_step_xy (with y) computes */
    if (m->has_y == 0u) {
        s->prep_s = dmp_tick_state_blend(m, &st);
    } else {
        s->prep_s = dmp_tick_state_blend2(m, &st, m->y_weight, &s->prep_sy);
    }
    s->prep_u = dmpfx_view(s->u_acc);
    s->prep_model = m;
}

int32_t dmpfx_step_xy(const dmpfx_model_t *m, const dmpfx_run_t *run, dmpfx_state_t *s,
                      const dmpfx_coupling_t *coupling, int32_t *path_q24)
{
    if (m->has_y == 0u) { /* a force-only skill: dmpfx_step's code, p stays 0 */
        if (path_q24 != NULL) {
            *path_q24 = 0;
        }
        return dmpfx_step(m, run, s, coupling);
    }
    int32_t k_ab_y;
    const dmp_tick_coef_t c = dmpfx_coef(m, run, coupling, &k_ab_y);
    const dmp_tick_state_t st = {s->window,          &s->u_acc, &s->v_acc,
                                 &s->integral_y_acc, &s->y_acc, &s->z_acc};
    int32_t s_y = s->prep_sy;
    const int32_t s_x = dmpfx_take_prepared(m, s)
                            ? s->prep_s
                            : dmp_tick_state_blend2(m, &st, m->y_weight, &s_y);
    const dmp_tick_path_coef_t cp = {.k1 = c.k1,
                                     .k_alpha = c.k_alpha,
                                     .k_alphabeta = k_ab_y,
                                     .goal = run->goal_y_q24,
                                     .scale = run->path_scale_q24};
    (void)dmp_tick_path_step(&cp, &s->path_acc, &s->path_z_acc, dmpfx_view(s->v_acc), s_y,
                             &s->sat_events);
    if (path_q24 != NULL) {
        *path_q24 = dmpfx_view(s->path_acc);
    }
    const int32_t f = dmp_tick_step(&c, &st, s_x, &s->sat_events);
    return fx_add_sat(m->force0_q16, f);
}

int32_t dmpfx_step(const dmpfx_model_t *m, const dmpfx_run_t *run, dmpfx_state_t *s,
                   const dmpfx_coupling_t *coupling)
{
    int32_t k_ab_y;
    const dmp_tick_coef_t c = dmpfx_coef(m, run, coupling, &k_ab_y);
    const dmp_tick_state_t st = {s->window,          &s->u_acc, &s->v_acc,
                                 &s->integral_y_acc, &s->y_acc, &s->z_acc};
    const int32_t s_x = (dmpfx_take_prepared(m, s) && m->has_y == 0u)
                            ? s->prep_s
                            : dmp_tick_state_blend(m, &st);
    const int32_t f = dmp_tick_step(&c, &st, s_x, &s->sat_events);
    return fx_add_sat(m->force0_q16, f);
}

static double dmpfx_absd(int32_t v)
{
    return fabs((double)v);
}

/* The nominal run (goal 1, time 1), T/dt steps: peaks of h, y, z, I (Q8.24 units) and v~ (Q2.30
 * units) into the model; any saturation, a peak above the headroom or |v~| > DMPFX_V_MAX -> 300.
 * The phase variable checks alpha, beta as the run will see them (v~ peaks at sqrt(alpha beta)/e
 * for the critically damped phase: 1.66 for the default gains). */
static fs_status_t dmpfx_measure_peaks_periodic(dmpfx_model_t *m, double duration_s);

static fs_status_t dmpfx_measure_peaks(dmpfx_model_t *m, double duration_s)
{
    if (m->periodic != 0u) {
        return dmpfx_measure_peaks_periodic(m, duration_s);
    }
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
    double peak_y = 0.0;
    for (long n = 0; n < rows; n++) {
        const int32_t u = dmpfx_view(s.u_acc);
        const int32_t v = dmpfx_view(s.v_acc);
        const int32_t sw = dmpfx_blend(m, u, NULL);
        const double h = (double)run.goal_q24 * ldexp((double)v, -30) * ldexp((double)sw, -24);
        int32_t sy = 0;
        if (m->has_y != 0u) {
            (void)dmp_tick_blend2(m, u, dmp_tick_window_start(m, u), dmp_tick_window_end(m, u),
                                  NULL, m->y_weight, &sy);
        }
        const double h_y = (double)run.path_scale_q24 * ldexp((double)v, -30) *
                           ldexp((double)sy, -24);
        (void)dmpfx_step_xy(m, &run, &s, NULL, NULL);
        peak_y = fmax(peak_y, fmax(fabs(h_y), fmax(dmpfx_absd(dmpfx_view(s.path_acc)),
                                                   dmpfx_absd(dmpfx_view(s.path_z_acc)))));
        peak = fmax(peak, fmax(fabs(h), fmax(dmpfx_absd(dmpfx_view(s.y_acc)),
                                             fmax(dmpfx_absd(dmpfx_view(s.z_acc)),
                                                  dmpfx_absd(dmpfx_view(s.integral_y_acc))))));
        peak_v = fmax(peak_v, dmpfx_absd(dmpfx_view(s.v_acc)));
    }
    m->peak_q24 = fmax(peak, dmpfx_absd(run.goal_q24));
    m->peak_v_q30 = peak_v;
    m->peak_y_q24 = fmax(peak_y, dmpfx_absd(run.goal_y_q24));
    if (s.sat_events != 0u || m->peak_q24 > DMPFX_Q24_HEADROOM * (double)FX_Q24_ONE ||
        m->peak_y_q24 > DMPFX_Q24_HEADROOM * (double)FX_Q24_ONE ||
        peak_v > DMPFX_V_MAX * (double)FX_Q30_ONE) {
        return FS_ERR_FIXED_OVERFLOW;
    }
    return FS_OK;
}

void dmpfx_periodic_reset(const dmpfx_model_t *m, const dmpfx_run_t *run, dmpfx_state_t *s)
{
    dmpfx_state_reset(s);
    /* s_a times the cycle state, in the accumulators' units (Q8.24 * 2^31, times 2^-s) */
    const int exp2 = 55 - (int)m->value_shift;
    s->y_acc = (int64_t)llround(ldexp(run->amplitude_scale * m->cycle0_N[0], exp2));
    s->z_acc = (int64_t)llround(ldexp(run->amplitude_scale * m->cycle0_N[1], exp2));
    s->integral_y_acc = (int64_t)llround(ldexp(run->amplitude_scale * m->cycle0_N[2], exp2));
    if (m->has_y != 0u) { /* s_p times the path's cycle state, Q8.24 m * 2^31 */
        const double s_p = ldexp((double)run->path_scale_q24, -24);
        s->path_acc = (int64_t)llround(ldexp(s_p * m->cycle_y0_m[0], 55));
        s->path_z_acc = (int64_t)llround(ldexp(s_p * m->cycle_y0_m[1], 55));
    }
    dmp_ptick_window_search(m, dmp_ptick_query(0), s->window);
}

int32_t dmpfx_periodic_blend(const dmpfx_model_t *m, int32_t x_q30, uint16_t *count)
{
    uint16_t win[2];
    dmp_ptick_window_search(m, dmp_ptick_query(x_q30), win);
    return dmp_ptick_blend(m, x_q30, win[0], win[1], count);
}

/* The periodic step's constants: the force DMP's of the run (slowed by the coupling's rate,
 * the phase increment too) and k*alpha*beta_y of the y path in *k_ab_y. */
static dmp_ptick_coef_t dmpfx_pcoef(const dmpfx_model_t *m, const dmpfx_run_t *run,
                                    const dmpfx_coupling_t *coupling, int32_t *k_ab_y)
{
    const dmp_tick_coef_t c = dmpfx_coef(m, run, coupling, k_ab_y);
    int64_t phase_inc = run->phase_inc;
    if (coupling != NULL && coupling->rate_q31 < FX_Q31_ONE_U) {
        /* inc * rate / 2^31 in two halves (inc < 2^59: hi < 2^28, each product < 2^62) */
        const uint64_t inc = (uint64_t)phase_inc;
        const uint64_t r = coupling->rate_q31;
        phase_inc = (int64_t)((inc >> 31) * r + (((inc & 0x7FFFFFFFu) * r) >> 31));
    }
    const dmp_ptick_coef_t pc = {.k1 = c.k1,
                                 .k_alpha = c.k_alpha,
                                 .k_alphabeta = c.k_alphabeta,
                                 .k_gamma = c.k_gamma,
                                 .phase_inc = phase_inc,
                                 .goal = c.goal,
                                 .amplitude = run->amplitude_q24,
                                 .out_scale = c.out_scale,
                                 .term_y = c.term_y};
    return pc;
}

int32_t dmpfx_periodic_step(const dmpfx_model_t *m, const dmpfx_run_t *run, dmpfx_state_t *s,
                            const dmpfx_coupling_t *coupling)
{
    int32_t k_ab_y;
    const dmp_ptick_coef_t pc = dmpfx_pcoef(m, run, coupling, &k_ab_y);
    const dmp_ptick_state_t st = {s->window, &s->u_acc, &s->u_comp_acc,
                                  &s->y_acc, &s->z_acc, &s->integral_y_acc};
    const int32_t s_blend = dmp_ptick_state_blend(m, &st);
    const int32_t f = dmp_ptick_step(m, &pc, &st, s_blend, &s->sat_events);
    return fx_add_sat(m->force0_q16, f);
}

int32_t dmpfx_periodic_step_xy(const dmpfx_model_t *m, const dmpfx_run_t *run, dmpfx_state_t *s,
                               const dmpfx_coupling_t *coupling, int32_t *path_q24)
{
    if (m->has_y == 0u) { /* a force-only skill: dmpfx_periodic_step's code */
        if (path_q24 != NULL) {
            *path_q24 = 0;
        }
        return dmpfx_periodic_step(m, run, s, coupling);
    }
    int32_t k_ab_y;
    const dmp_ptick_coef_t pc = dmpfx_pcoef(m, run, coupling, &k_ab_y);
    const dmp_ptick_state_t st = {s->window, &s->u_acc, &s->u_comp_acc,
                                  &s->y_acc, &s->z_acc, &s->integral_y_acc};
    int32_t s_y = 0;
    const int32_t s_blend = dmp_ptick_state_blend2(m, &st, m->y_weight, &s_y);
    const dmp_tick_path_coef_t cp = {.k1 = pc.k1,
                                     .k_alpha = pc.k_alpha,
                                     .k_alphabeta = k_ab_y,
                                     .goal = 0,
                                     .scale = run->path_scale_q24};
    const int32_t q = dmp_ptick_path_step(&cp, &s->path_acc, &s->path_z_acc, s_y, &s->sat_events);
    if (path_q24 != NULL) {
        *path_q24 = fx_add_sat(run->goal_y_q24, q);
    }
    const int32_t f = dmp_ptick_step(m, &pc, &st, s_blend, &s->sat_events);
    return fx_add_sat(m->force0_q16, f);
}

/* The periodic nominal run (goal 1, amplitude 1, time 1): one cycle from the cycle state, the
 * peaks of h, e, z, I and g + e (Q8.24 units); a saturation or a peak above the headroom -> 300. */
static fs_status_t dmpfx_measure_peaks_periodic(dmpfx_model_t *m, double duration_s)
{
    m->peak_q24 = 0.0;
    m->peak_v_q30 = 0.0;
    m->peak_y_q24 = 0.0;
    dmpfx_run_t run;
    const fs_status_t st = dmpfx_run_init(m, 1.0, 1.0, &run);
    if (st != FS_OK) {
        return st;
    }
    dmpfx_state_t s;
    dmpfx_periodic_reset(m, &run, &s);
    const long rows = lround(duration_s / m->dt_s);
    double peak = fmax(dmpfx_absd(run.goal_q24), dmpfx_absd(dmpfx_view(s.y_acc)));
    double peak_y = dmpfx_absd(run.goal_y_q24);
    for (long n = 0; n < rows; n++) {
        const int32_t sw = dmpfx_periodic_blend(m, dmpfx_view(s.u_acc), NULL);
        const double h = (double)run.amplitude_q24 * ldexp((double)sw, -24);
        int32_t p = 0;
        (void)dmpfx_periodic_step_xy(m, &run, &s, NULL, &p);
        peak_y = fmax(peak_y, fmax(dmpfx_absd(p), fmax(dmpfx_absd(dmpfx_view(s.path_acc)),
                                                       dmpfx_absd(dmpfx_view(s.path_z_acc)))));
        const int32_t e = dmpfx_view(s.y_acc);
        peak = fmax(peak, fmax(fabs(h), fmax(dmpfx_absd(e), dmpfx_absd(run.goal_q24 + e))));
        peak = fmax(
            peak, fmax(dmpfx_absd(dmpfx_view(s.z_acc)), dmpfx_absd(dmpfx_view(s.integral_y_acc))));
    }
    m->peak_q24 = peak;
    m->peak_y_q24 = peak_y;
    if (s.sat_events != 0u || m->peak_q24 > DMPFX_Q24_HEADROOM * (double)FX_Q24_ONE ||
        m->peak_y_q24 > DMPFX_Q24_HEADROOM * (double)FX_Q24_ONE) {
        return FS_ERR_FIXED_OVERFLOW;
    }
    return FS_OK;
}

/* |v| of a Q value, saturated (|INT32_MIN| -> INT32_MAX) */
static int32_t dmpfx_abs_sat(int32_t v)
{
    return (v < 0) ? ((v == INT32_MIN) ? INT32_MAX : -v) : v;
}

void dmpfx_check_begin(dmpfx_check_t *c, const dmpfx_model_t *m, float duration_s, float dt_s,
                       float force_max_N, float path_max_m)
{
    c->m = m;
    c->steps_done = 0u;
    c->peak_q16 = 0;
    c->path_peak_q24 = 0;
    c->force_max_q16 = fx_from_float(force_max_N, 16u);
    c->path_max_q24 = fx_from_float(path_max_m, 24u);
    const float n = duration_s / dt_s + 0.5f;
    c->steps_total = (n > 0.0f && n < 4.0e9f) ? (uint32_t)n : 0u;
    c->status = dmpfx_run_rates(m, 1.0, 1.0, &c->run);
    fs_job_reset(&c->job); /* the rest of the set-up: dmpfx_check_run's first calls */
    c->done = c->status != FS_OK || c->steps_total == 0u;
}

/* One step of the check: |f_hat| of this step (a periodic model: |f0| + g + |e|); *path_q24 |p|. */
static int32_t dmpfx_check_step(dmpfx_check_t *c, int32_t *path_q24)
{
    const dmpfx_model_t *m = c->m;
    if (m->periodic != 0u) {
        const int32_t f = dmpfx_periodic_step(m, &c->run, &c->s, NULL);
        const int32_t e = fx_sub_sat(fx_sub_sat(f, m->force0_q16), c->goal_q16);
        *path_q24 = 0;
        return fx_add_sat(c->base_q16, dmpfx_abs_sat(e));
    }
    int32_t p = 0;
    const int32_t f = dmpfx_step_xy(m, &c->run, &c->s, NULL, &p);
    *path_q24 = dmpfx_abs_sat(p);
    return dmpfx_abs_sat(f);
}

/* max_steps steps of the check, its peaks and verdict. */
static void dmpfx_check_steps(dmpfx_check_t *c, uint32_t max_steps)
{
    for (uint32_t i = 0u; i < max_steps && c->status == FS_OK && c->steps_done < c->steps_total;
         i++) {
        int32_t p = 0;
        const int32_t a = dmpfx_check_step(c, &p);
        c->path_peak_q24 = (p > c->path_peak_q24) ? p : c->path_peak_q24;
        c->peak_q16 = (a > c->peak_q16) ? a : c->peak_q16;
        if (c->s.sat_events != 0u) {
            c->status = FS_ERR_FIXED_OVERFLOW;
        } else if (c->path_peak_q24 > c->path_max_q24) {
            c->status = FS_ERR_SKCHK_PATH;
        } else if (c->peak_q16 > c->force_max_q16) {
            c->status = FS_ERR_SKCHK_PEAK;
        }
        c->steps_done++;
    }
}

/* The check as a job (fs_job.h): the rest of the set-up a call each (bounded software double on
 * the M3: the goal, the periodic constants, the path's, the starting state), then max_steps DMP
 * steps a call. */
static fs_job_status_t dmpfx_check_job(dmpfx_check_t *c, uint32_t max_steps)
{
    fs_job_t *j = &c->job;
    const dmpfx_model_t *m = c->m;
    FS_JOB_BEGIN(j);
    c->status = dmpfx_run_goal(m, 1.0, 1.0, &c->run);
    FS_JOB_YIELD(j);
    if (c->status == FS_OK) {
        c->status = dmpfx_run_periodic(m, 1.0, &c->run);
    }
    FS_JOB_YIELD(j);
    if (c->status == FS_OK) {
        c->status = dmpfx_run_path(m, 1.0, &c->run);
    }
    FS_JOB_YIELD(j);
    if (c->status != FS_OK) {
        FS_JOB_EXIT(j);
    }
    /* g in Q16.16: the goal (Q8.24, units of 2^s N) times 2^s (Q20.12) */
    c->goal_q16 = (int32_t)(((int64_t)c->run.goal_q24 * m->out_scale_q12) >> 20);
    c->base_q16 = fx_add_sat(dmpfx_abs_sat(m->force0_q16), dmpfx_abs_sat(c->goal_q16));
    if (m->periodic != 0u) {
        dmpfx_periodic_reset(m, &c->run, &c->s);
    } else {
        dmpfx_state_reset(&c->s);
    }
    while (c->status == FS_OK && c->steps_done < c->steps_total) {
        FS_JOB_YIELD(j);
        dmpfx_check_steps(c, max_steps);
    }
    FS_JOB_END(j);
}

bool dmpfx_check_run(dmpfx_check_t *c, uint32_t max_steps)
{
    if (!c->done) {
        c->done = dmpfx_check_job(c, max_steps) == FS_JOB_DONE;
    }
    return c->done;
}

float dmpfx_check_peak_N(const dmpfx_check_t *c)
{
    return fx_to_float(c->peak_q16, 16u);
}

float dmpfx_check_path_m(const dmpfx_check_t *c)
{
    return fx_to_float(c->path_peak_q24, 24u);
}

/* The DMP's per-tick algorithm, written once over the numeric layer (fs_num.h) and compiled
 * three ways: by dmp.c into fs_core (double) and fs_core_f32 (float32), and by
 * firmware/fixed/dmpfx.c into fs_fixed (fixed point). docs/math.md section 2 is the algorithm:
 *   kernel window   binary search on the envelopes, at most FS_NUM_MAX_WINDOW kernels
 *   kernel blend    two passes: e_min over the kernels with e_i = (u - c_i)^2/(2 sigma_i^2) <= cutoff,
 *                   then S = sum psi_i w_i / sum psi_i with psi_i = exp(-(e_i - e_min));
 *                   no kernel within the cutoff -> the nearest kernel's weight
 *   Euler step      all right-hand sides at the old state, in coefficient form
 *                   x += k1*(z - x + h + term_x) - k_gamma*I     z += k_ab*(g - x) - k_a*z
 *                   I += k1*x    v += k_ab*(1 - u) - k_a*v       u += k1*v     f = k*x
 * The including file includes its public header, fs_num.h, then defines DMP_TICK_MODEL (its
 * model type, with fields n_kernels, centre[], kernel_scale[], weight[], env_lo[], env_hi[] in
 * the layer's types) and includes this file once. Building the coefficients from the run
 * (scales, slow-down) is the caller's: dmp_step (real) and dmpfx_step (fixed). */
#ifndef DMP_TICK_H
#define DMP_TICK_H

#include <stdint.h>

#ifndef DMP_TICK_MODEL
#error "define DMP_TICK_MODEL (the model type) before including dmp_tick.h"
#endif

/** Per-tick constants of one Euler step: dt/tau_e*{1, alpha, alpha*beta, gamma}, g_e, k and
 *  the coupling term added to tau*xd. */
typedef struct {
    fs_coef_t k1;
    fs_coef_t k_alpha;
    fs_coef_t k_alphabeta;
    fs_coef_t k_gamma;
    fs_val_t goal;
    fs_stiff_t stiffness;
    fs_val_t term_x;
} dmp_tick_coef_t;

/** The DMP state as the step sees it: the layer's accumulators (fs_acc_t) of u~, v~, I, x, z. */
typedef struct {
    fs_acc_t *u;
    fs_acc_t *v;
    fs_acc_t *integral_x;
    fs_acc_t *x;
    fs_acc_t *z;
} dmp_tick_state_t;

/** First kernel whose cutoff interval can reach u: the first i with env_hi[i] >= u (env_hi is
 *  non-decreasing, every earlier kernel ends before u). */
static inline uint32_t dmp_tick_window_start(const DMP_TICK_MODEL *m, fs_phase_t u)
{
    uint32_t a = 0u;
    uint32_t b = m->n_kernels;
    while (a < b) {
        const uint32_t mid = (a + b) >> 1;
        if (m->env_hi[mid] < u) {
            a = mid + 1u;
        } else {
            b = mid;
        }
    }
    return a;
}

/** Weight of the kernel with the smallest e_i (the first on ties): the fallback when no kernel
 *  is within the cutoff (an O(N) scan, only when u is outside every kernel). */
static inline fs_val_t dmp_tick_nearest_weight(const DMP_TICK_MODEL *m, fs_phase_t u)
{
    uint32_t best = 0u;
    fs_kdist_t r_best = fs_num_kernel_dist(u, m->centre[0], m->kernel_scale[0]);
    for (uint32_t i = 1u; i < m->n_kernels; i++) {
        const fs_kdist_t r = fs_num_kernel_dist(u, m->centre[i], m->kernel_scale[i]);
        if (r < r_best) {
            r_best = r;
            best = i;
        }
    }
    return m->weight[best];
}

/** S(u) = sum psi_i w_i / sum psi_i over the kernels with e_i <= FS_NUM_CUTOFF, psi_i =
 *  exp(-(e_i - e_min)) (the shift keeps sum psi >= 1: no underflow in float, full resolution
 *  in fixed). The window runs from dmp_tick_window_start while env_lo[i] <= u (env_lo is
 *  non-decreasing). *count (may be NULL) receives the number summed (1 in the fallback). */
static inline fs_val_t dmp_tick_blend(const DMP_TICK_MODEL *m, fs_phase_t u, uint16_t *count)
{
    const uint32_t lo = dmp_tick_window_start(m, u);
    uint32_t end = lo + FS_NUM_MAX_WINDOW;
    end = (end < m->n_kernels) ? end : m->n_kernels;
    /* pass 1: e_min, the number within the cutoff and the end of the window */
    fs_expo_t e_min = FS_NUM_EXPO_INF;
    uint32_t n = 0u;
    uint32_t hi = lo;
    for (; hi < end && m->env_lo[hi] <= u; hi++) {
        const fs_expo_t e = fs_num_kernel_expo(u, m->centre[hi], m->kernel_scale[hi]);
        if (e <= FS_NUM_CUTOFF) {
            n++;
            e_min = (e < e_min) ? e : e_min;
        }
    }
    if (count != NULL) {
        *count = (uint16_t)((n == 0u) ? 1u : n);
    }
    if (n == 0u) {
        return dmp_tick_nearest_weight(m, u);
    }
    /* pass 2: the shifted activations */
    fs_bnum_t num = 0;
    fs_bden_t den = 0;
    for (uint32_t i = lo; i < hi; i++) {
        const fs_expo_t e = fs_num_kernel_expo(u, m->centre[i], m->kernel_scale[i]);
        if (e <= FS_NUM_CUTOFF) {
            fs_num_blend_acc(&num, &den, fs_num_exp_neg(e - e_min), m->weight[i]);
        }
    }
    return fs_num_blend_div(num, den);
}

/** One forward-Euler step (every right-hand side at the old state) with constants c; the
 *  layer's saturations are counted in *ev. Returns f_hat = k*x after the step. */
static inline fs_force_t dmp_tick_step(const DMP_TICK_MODEL *m, const dmp_tick_coef_t *c,
                                       const dmp_tick_state_t *s, uint32_t *ev)
{
    const fs_phase_t u = fs_num_view(*s->u);
    const fs_phase_t v = fs_num_view(*s->v);
    const fs_val_t i_x = fs_num_view(*s->integral_x);
    const fs_val_t x = fs_num_view(*s->x);
    const fs_val_t z = fs_num_view(*s->z);

    const fs_val_t h = fs_num_mul_vv(fs_num_mul_vp(c->goal, v, ev), dmp_tick_blend(m, u, NULL), ev);
    const fs_val_t sx = fs_num_add_ev(fs_num_add_ev(fs_num_sub_ev(z, x, ev), h, ev), c->term_x, ev);
    const fs_val_t gx = fs_num_sub_ev(c->goal, x, ev);
    const fs_phase_t one_u = fs_num_sub_ev(FS_NUM_PHASE_ONE, u, ev);
    *s->x = fs_num_acc_mac2(*s->x, c->k1, sx, c->k_gamma, i_x, ev);
    *s->z = fs_num_acc_mac2(*s->z, c->k_alphabeta, gx, c->k_alpha, z, ev);
    *s->integral_x = fs_num_acc_mac1(*s->integral_x, c->k1, x, ev);
    *s->v = fs_num_acc_mac2(*s->v, c->k_alphabeta, one_u, c->k_alpha, v, ev);
    *s->u = fs_num_acc_mac1(*s->u, c->k1, v, ev);
    return fs_num_force(c->stiffness, fs_num_view(*s->x), ev);
}

#endif /* DMP_TICK_H */

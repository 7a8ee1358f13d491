/* The DMP's per-tick algorithm, written once over the numeric layer (fs_num.h) and compiled
 * three ways: by dmp.c into fs_core (double) and fs_core_f32 (float32), and by
 * firmware/fixed/dmpfx.c into fs_fixed (fixed point). docs/math.md section 2 is the algorithm:
 *   kernel window   [first i with env_hi[i] >= u, first i with env_lo[i] > u), both ends walked
 *                   from the previous tick's (the phase is monotone: an end moves every few
 *                   ticks; any previous window gives the same one), at most FS_NUM_MAX_WINDOW
 *   kernel blend    S = sum psi_i w_i / sum psi_i over the kernels with e_i = (u - c_i)^2/(2 sigma_i^2)
 *                   <= cutoff; real layer: one pass, psi_i = exp(-e_i) (>= exp(-cutoff), a normal
 *                   number); fixed layer: e_i stored in one pass, then psi_i = exp(-(e_i - e_min))
 *                   (the shift keeps sum psi >= 1.0 in Q.27: full resolution);
 *                   no kernel within the cutoff -> the nearest kernel's weight
 *   Euler step      all right-hand sides at the old state, in coefficient form
 *                   y += k1*(z - y + h + term_y) - k_gamma*I     z += k_ab*(g - y) - k_a*z
 *                   I += k1*y    v += k_ab*(1 - u) - k_a*v       u += k1*v     f = out_scale*y
 * y, z, I, h, g are in force units (N above the starting force; the weights are dimensionless);
 * the real layer's out_scale is 1, the fixed layer keeps them times 2^-s in Q8.24 and
 * out_scale = 2^s, a per-skill power of two. 
 * The including file includes its public header, fs_num.h, then defines DMP_TICK_MODEL (its
 * model type, with fields n_kernels, centre[], kernel_scale[], weight[], env_lo[], env_hi[] in
 * the layer's types) and includes this file once. The window of the last step is kept in the
 * caller's state (dmp_tick_state_t.window). Building the coefficients from the run
 * (scales, slow-down) is the caller's: dmp_step (real) and dmpfx_step (fixed). */
#ifndef DMP_TICK_H
#define DMP_TICK_H

#include <stdint.h>

#ifndef DMP_TICK_MODEL
#error "define DMP_TICK_MODEL (the model type) before including dmp_tick.h"
#endif

/* 1: psi_i = exp(-(e_i - e_min)), the exponents stored for a second pass (fixed point, where
 * exp(-12) would be 824 LSB of Q.27); 0: psi_i = exp(-e_i) in one pass (float and double, where
 * exp(-cutoff) is a normal number and the shift only changes round-off). */
#ifndef DMP_TICK_BLEND_SHIFT
#ifdef FS_NUMERIC_FIXED
#define DMP_TICK_BLEND_SHIFT 1
#else
#define DMP_TICK_BLEND_SHIFT 0
#endif
#endif

/** Per-tick constants of one Euler step: dt/tau_e*{1, alpha, alpha*beta, gamma}, g_e, the
 *  output scale (N per unit of y) and the coupling term added to tau*yd. */
typedef struct {
    fs_coef_t k1;
    fs_coef_t k_alpha;
    fs_coef_t k_alphabeta;
    fs_coef_t k_gamma;
    fs_val_t goal;
    fs_stiff_t out_scale;
    fs_val_t term_y;
} dmp_tick_coef_t;

/** The DMP state as the step sees it: the layer's accumulators (fs_acc_t) of u~, v~, I, y, z,
 *  and the kernel window [start, end) of the last step (a hint: any value gives the same result). */
typedef struct {
    uint16_t *window;
    fs_acc_t *u;
    fs_acc_t *v;
    fs_acc_t *integral_y;
    fs_acc_t *y;
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

/** Index of the kernel with the smallest e_i (the first on ties): the fallback when no kernel
 *  is within the cutoff (an O(N) scan, only when u is outside every kernel). */
static inline uint32_t dmp_tick_nearest(const DMP_TICK_MODEL *m, fs_phase_t u)
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
    return best;
}

/** End of the kernel window at u: the first i with env_lo[i] > u (env_lo is non-decreasing,
 *  every later kernel starts after u), by binary search. */
static inline uint32_t dmp_tick_window_end(const DMP_TICK_MODEL *m, fs_phase_t u)
{
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
    return a;
}

/** The window at u, walked from win (the previous step's window) and stored back into it: the
 *  start is dmp_tick_window_start's for any hint, the end dmp_tick_window_end's or later (a later
 *  end holds only kernels beyond the cutoff: the blend is the same). A monotone phase moves each
 *  end by one kernel every few ticks; a hint on the wrong side costs a longer walk. */
static inline void dmp_tick_window_walk(const DMP_TICK_MODEL *m, fs_phase_t u, uint16_t win[2])
{
    const uint32_t n = m->n_kernels;
    uint32_t lo = (win[0] < n) ? win[0] : n;
    uint32_t hi = (win[1] < n) ? win[1] : n;
    while (lo > 0u && m->env_hi[lo - 1u] >= u) {
        lo--;
    }
    while (lo < n && m->env_hi[lo] < u) {
        lo++;
    }
    /* an end past the first env_lo[i] > u only adds kernels beyond the cutoff (skipped by the
     * e_i test), so the end is walked forward only */
    while (hi < n && m->env_lo[hi] <= u) {
        hi++;
    }
    win[0] = (uint16_t)lo;
    win[1] = (uint16_t)hi;
}

/** S(u) = sum psi_i w_i / sum psi_i over the kernels with e_i <= FS_NUM_CUTOFF in the window
 *  [lo, hi) (dmp_tick_window_*; empty when hi <= lo), at most FS_NUM_MAX_WINDOW kernels from lo;
 *  psi_i as DMP_TICK_BLEND_SHIFT says. *count (may be NULL) receives the number summed (1 in
 *  the nearest-kernel fallback). With w_y non-NULL, *s_y receives the same blend of the second
 *  weight set w_y (the y DMP's) from the same activations: each psi_i is computed once. */
/* long: the counted hot path, one inline body without calls (docs/cortex-m.md) */
static inline fs_val_t dmp_tick_blend2(const DMP_TICK_MODEL *m, fs_phase_t u, uint32_t lo,
                                       uint32_t hi, uint16_t *count, const fs_val_t *w_y,
                                       fs_val_t *s_y)
{
    const uint32_t end = (hi > lo + FS_NUM_MAX_WINDOW) ? lo + FS_NUM_MAX_WINDOW : hi;
    fs_bnum_t num = 0;
    fs_bnum_t num_y = 0;
    fs_bden_t den = 0;
    uint32_t n = 0u;
#if DMP_TICK_BLEND_SHIFT
    /* pass 1: every exponent of the window once, e_min and the number within the cutoff */
    fs_expo_t e[FS_NUM_MAX_WINDOW];
    fs_expo_t e_min = FS_NUM_EXPO_INF;
    for (uint32_t i = lo; i < end; i++) {
        const fs_expo_t ei = fs_num_kernel_expo(u, m->centre[i], m->kernel_scale[i]);
        e[i - lo] = ei;
        if (ei <= FS_NUM_CUTOFF) {
            n++;
            e_min = (ei < e_min) ? ei : e_min;
        }
    }
    /* pass 2: the shifted activations of the stored exponents (one loop per case: no test of
     * w_y per kernel) */
    if (n != 0u && w_y == NULL) {
        for (uint32_t i = lo; i < end; i++) {
            if (e[i - lo] <= FS_NUM_CUTOFF) {
                fs_num_blend_acc(&num, &den, fs_num_exp_neg(e[i - lo] - e_min), m->weight[i]);
            }
        }
    } else if (n != 0u) {
        for (uint32_t i = lo; i < end; i++) {
            if (e[i - lo] <= FS_NUM_CUTOFF) {
                const fs_act_t psi = fs_num_exp_neg(e[i - lo] - e_min);
                fs_num_blend_acc(&num, &den, psi, m->weight[i]);
                fs_num_blend_acc_num(&num_y, psi, w_y[i]);
            }
        }
    }
#else
    /* psi_i >= exp(-cutoff) > 0: den > 0 tells that a kernel was summed (n only for *count);
     * one loop per case: no test of w_y per kernel */
    if (w_y == NULL) {
        for (uint32_t i = lo; i < end; i++) {
            const fs_expo_t ei = fs_num_kernel_expo(u, m->centre[i], m->kernel_scale[i]);
            if (ei <= FS_NUM_CUTOFF) {
                if (count != NULL) {
                    n++;
                }
                fs_num_blend_acc(&num, &den, fs_num_exp_neg(ei), m->weight[i]);
            }
        }
    } else {
        for (uint32_t i = lo; i < end; i++) {
            const fs_expo_t ei = fs_num_kernel_expo(u, m->centre[i], m->kernel_scale[i]);
            if (ei <= FS_NUM_CUTOFF) {
                if (count != NULL) {
                    n++;
                }
                const fs_act_t psi = fs_num_exp_neg(ei);
                fs_num_blend_acc(&num, &den, psi, m->weight[i]);
                fs_num_blend_acc_num(&num_y, psi, w_y[i]);
            }
        }
    }
    n = (den > FS_NUM_ZERO) ? ((n == 0u) ? 1u : n) : 0u;
#endif
    if (count != NULL) {
        *count = (uint16_t)((n == 0u) ? 1u : n);
    }
    if (n == 0u) {
        const uint32_t best = dmp_tick_nearest(m, u);
        if (w_y != NULL) {
            *s_y = w_y[best];
        }
        return m->weight[best];
    }
#ifdef FS_NUMERIC_FIXED
    /* one reciprocal of den for both quotients */
    if (w_y != NULL) {
        return fs_num_blend_div2(num, num_y, den, s_y);
    }
#else
    if (w_y != NULL) {
        *s_y = fs_num_blend_div(num_y, den);
    }
#endif
    return fs_num_blend_div(num, den);
}

/** dmp_tick_blend2 of the force weights alone. */
static inline fs_val_t dmp_tick_blend(const DMP_TICK_MODEL *m, fs_phase_t u, uint32_t lo,
                                      uint32_t hi, uint16_t *count)
{
    return dmp_tick_blend2(m, u, lo, hi, count, NULL, NULL);
}

/** The blend S at the state's phase, the state's window walked there first. Callers take it
 *  before building the step's constants: fewer values live across the exp calls. */
static inline fs_val_t dmp_tick_state_blend(const DMP_TICK_MODEL *m, const dmp_tick_state_t *s)
{
    const fs_phase_t u = fs_num_view(*s->u);
    dmp_tick_window_walk(m, u, s->window);
    return dmp_tick_blend(m, u, s->window[0], s->window[1], NULL);
}

/** One forward-Euler step (every right-hand side at the old state) with constants c and the
 *  blend s_blend = dmp_tick_state_blend of the same state; the layer's saturations are counted
 *  in *ev. Returns out_scale*y after the step (N above f0). */
static inline fs_force_t dmp_tick_step(const dmp_tick_coef_t *c, const dmp_tick_state_t *s,
                                       fs_val_t s_blend, uint32_t *ev)
{
    const fs_phase_t u = fs_num_view(*s->u);
    const fs_phase_t v = fs_num_view(*s->v);
    const fs_val_t i_y = fs_num_view(*s->integral_y);
    const fs_val_t y = fs_num_view(*s->y);
    const fs_val_t z = fs_num_view(*s->z);

    const fs_val_t h = fs_num_mul_vv(fs_num_mul_vp(c->goal, v, ev), s_blend, ev);
    const fs_val_t sy = fs_num_add_ev(fs_num_add_ev(fs_num_sub_ev(z, y, ev), h, ev), c->term_y, ev);
    const fs_val_t gy = fs_num_sub_ev(c->goal, y, ev);
    const fs_phase_t one_u = fs_num_sub_ev(FS_NUM_PHASE_ONE, u, ev);
    *s->y = fs_num_acc_mac2(*s->y, c->k1, sy, c->k_gamma, i_y, ev);
    *s->z = fs_num_acc_mac2(*s->z, c->k_alphabeta, gy, c->k_alpha, z, ev);
    *s->integral_y = fs_num_acc_mac1(*s->integral_y, c->k1, y, ev);
    *s->v = fs_num_acc_mac2(*s->v, c->k_alphabeta, one_u, c->k_alpha, v, ev);
    *s->u = fs_num_acc_mac1(*s->u, c->k1, v, ev);
    return fs_num_force(c->out_scale, fs_num_view(*s->y), ev);
}

/** The blend pair (S, S_y) at the state's phase, the state's window walked there first; *s_y
 *  is the blend of w_y (the y DMP's weights) over the same activations. */
static inline fs_val_t dmp_tick_state_blend2(const DMP_TICK_MODEL *m, const dmp_tick_state_t *s,
                                             const fs_val_t *w_y, fs_val_t *s_y)
{
    const fs_phase_t u = fs_num_view(*s->u);
    dmp_tick_window_walk(m, u, s->window);
    return dmp_tick_blend2(m, u, s->window[0], s->window[1], NULL, w_y, s_y);
}

/** Per-tick constants of the position DMP on y (paper eq. 9: the law with k_f = k_i = 0, so
 *  gamma = 0): dt/tau_e*{1, alpha, alpha*beta_y} (the phase's k1 and k_alpha), the scaled goal
 *  path_scale*g_y and the path scale itself (h_y = path_scale*v~*S_y). */
typedef struct {
    fs_coef_t k1;
    fs_coef_t k_alpha;
    fs_coef_t k_alphabeta;
    fs_val_t goal;
    fs_val_t scale;
} dmp_tick_path_coef_t;

/** One forward-Euler step of the y DMP, every right-hand side at the old state:
 *    h = scale*v*S_y     p += k1*(z_p - p + h)     z_p += k_ab*(goal - p) - k_a*z_p
 *  v is the phase velocity of the same step before it advances (take it before dmp_tick_step).
 *  Returns p after the step (m above the path's start). */
static inline fs_val_t dmp_tick_path_step(const dmp_tick_path_coef_t *c, fs_acc_t *p, fs_acc_t *z_p,
                                          fs_phase_t v, fs_val_t s_y, uint32_t *ev)
{
    const fs_val_t pv = fs_num_view(*p);
    const fs_val_t zv = fs_num_view(*z_p);
    const fs_val_t h = fs_num_mul_vv(fs_num_mul_vp(c->scale, v, ev), s_y, ev);
    const fs_val_t sp = fs_num_add_ev(fs_num_sub_ev(zv, pv, ev), h, ev);
    const fs_val_t gp = fs_num_sub_ev(c->goal, pv, ev);
    *p = fs_num_acc_mac1(*p, c->k1, sp, ev);
    *z_p = fs_num_acc_mac2(*z_p, c->k_alphabeta, gp, c->k_alpha, zv, ev);
    return fs_num_view(*p);
}

#endif /* DMP_TICK_H */

/* The periodic DMP's per-tick algorithm (docs/math.md section 5), written once over the numeric
 * layer (fs_num.h) like dmp_tick.h and compiled the same three ways (dmp.c: double and float32,
 * firmware/fixed/dmpfx.c: fixed point). The phase is kept in turns, x = phi/(2 pi) in [0, 1):
 *   kernel exponent  e_i = kappa_i (1 - cos(phi - c_i)) = 2 kappa_i d_i^2,
 *                    d_i = sin(pi (x - c_i/(2 pi))) = sin(pi x) cos(c_i/2) - cos(pi x) sin(c_i/2)
 *                    (one sine and cosine a tick, two products a kernel); the layer's
 *                    fs_num_kernel_expo(d_i, 0, s_i) with s_i = 2 kappa_i (real) or
 *                    2 sqrt(kappa_i) (fixed, where e = (|d| s)^2/2)
 *   kernel window    the kernels on a circle: virtual kernels j = 0..2N-1 (j mod N, the second
 *                    copy one turn later) with envelopes env_lo/env_hi in turns, queried at
 *                    q = x + 1 for x < 1/2, x otherwise (q in [1/2, 3/2): every kernel within
 *                    reach, <= 1/2 turn, has one copy there, and q is continuous where the
 *                    phase wraps); at most N kernels are summed from the window's start; walked
 *                    from the last tick's window, shifted back by N where q jumps (x = 1/2)
 *   kernel blend     dmp_tick.h's rules: cutoff, e_min shift in fixed point, nearest kernel
 *                    when none is within the cutoff
 *   Euler step       all right-hand sides at the old state, a = dt/tau_e
 *                    e += a*(z - e + h + term_y) - a*gamma*I    h = s_a*r*S(x)
 *                    z += a*alpha*beta*(0 - e) - a*alpha*z      I += a*e
 *                    x += a/(2 pi) (compensated sum), minus one turn once it reaches one
 *                    f = out_scale*(g + e)
 * The including file defines DMP_TICK_MODEL (with dmp_tick.h's kernel fields and half_sin[],
 * half_cos[]) and includes dmp_tick.h first. */
#ifndef DMP_PTICK_H
#define DMP_PTICK_H

#include <stdint.h>

#ifndef DMP_TICK_H
#error "include dmp_tick.h before dmp_ptick.h"
#endif

/** Per-tick constants of one periodic step: a*{1, alpha, alpha*beta, gamma} (a = dt/tau_e),
 *  the phase increment in the accumulator's units (a/(2 pi) turns), the goal g_e (mean force),
 *  the forcing's amplitude s_a*r, the output scale and the coupling term. */
typedef struct {
    fs_coef_t k1;
    fs_coef_t k_alpha;
    fs_coef_t k_alphabeta;
    fs_coef_t k_gamma;
    fs_acc_t phase_inc;
    fs_val_t goal;
    fs_val_t amplitude;
    fs_stiff_t out_scale;
    fs_val_t term_y;
} dmp_ptick_coef_t;

/** The periodic state as the step sees it: the phase in turns, e, z, I, the virtual window. */
typedef struct {
    uint16_t *window;
    fs_acc_t *x;
    fs_acc_t *x_comp; /* the phase sum's compensation (Kahan): 0 where the sum is exact */
    fs_acc_t *e;
    fs_acc_t *z;
    fs_acc_t *integral;
} dmp_ptick_state_t;

/** Virtual kernel j's upper envelope (prefix max over the two copies). */
static inline fs_phase_t dmp_ptick_hi(const DMP_TICK_MODEL *m, uint32_t j)
{
    const uint32_t n = m->n_kernels;
    if (j < n) {
        return m->env_hi[j];
    }
    const fs_phase_t a = m->env_hi[n - 1u];
    const fs_phase_t b = fs_num_add(m->env_hi[j - n], FS_NUM_PHASE_ONE);
    return (b > a) ? b : a;
}

/** Virtual kernel j's lower envelope (suffix min over the two copies). */
static inline fs_phase_t dmp_ptick_lo(const DMP_TICK_MODEL *m, uint32_t j)
{
    const uint32_t n = m->n_kernels;
    if (j >= n) {
        return fs_num_add(m->env_lo[j - n], FS_NUM_PHASE_ONE);
    }
    const fs_phase_t a = m->env_lo[j];
    const fs_phase_t b = fs_num_add(m->env_lo[0], FS_NUM_PHASE_ONE);
    return (b < a) ? b : a;
}

/** The virtual window at query q (dmp_ptick_query) by binary search: [first j with hi(j) >= q, first j
 *  with lo(j) > q), both envelopes non-decreasing in j. */
static inline void dmp_ptick_window_search(const DMP_TICK_MODEL *m, fs_phase_t q, uint16_t win[2])
{
    uint32_t a = 0u;
    uint32_t b = 2u * (uint32_t)m->n_kernels;
    while (a < b) {
        const uint32_t mid = (a + b) >> 1;
        if (dmp_ptick_hi(m, mid) < q) {
            a = mid + 1u;
        } else {
            b = mid;
        }
    }
    win[0] = (uint16_t)a;
    a = 0u;
    b = 2u * (uint32_t)m->n_kernels;
    while (a < b) {
        const uint32_t mid = (a + b) >> 1;
        if (dmp_ptick_lo(m, mid) <= q) {
            a = mid + 1u;
        } else {
            b = mid;
        }
    }
    win[1] = (uint16_t)a;
}

/** The window at query q walked from win (the last tick's, in virtual indices): the start is the
 *  search's for any hint, the end the search's or later (later only adds kernels beyond the
 *  cutoff, and at most N kernels are summed from the start: none twice). */
static inline void dmp_ptick_window_walk(const DMP_TICK_MODEL *m, fs_phase_t q, uint16_t win[2])
{
    const uint32_t n2 = 2u * (uint32_t)m->n_kernels;
    uint32_t lo = (win[0] < n2) ? win[0] : n2;
    uint32_t hi = (win[1] < n2) ? win[1] : n2;
    while (lo > 0u && dmp_ptick_hi(m, lo - 1u) >= q) {
        lo--;
    }
    while (lo < n2 && dmp_ptick_hi(m, lo) < q) {
        lo++;
    }
    while (hi < n2 && dmp_ptick_lo(m, hi) <= q) {
        hi++;
    }
    win[0] = (uint16_t)lo;
    win[1] = (uint16_t)hi;
}

/** The window's query point of phase x (turns, [0, 1)): x + 1 below half a turn, else x. */
static inline fs_phase_t dmp_ptick_query(fs_phase_t x)
{
    return (x < FS_NUM_PHASE_ONE / 2) ? fs_num_add(x, FS_NUM_PHASE_ONE) : x;
}

/** Kernel i's distance d_i at the phase whose half-angle sine and cosine are sh, ch. */
static inline fs_phase_t dmp_ptick_dist(const DMP_TICK_MODEL *m, uint32_t i, fs_phase_t sh,
                                        fs_phase_t ch)
{
    return fs_num_vm_dist(sh, ch, m->half_sin[i], m->half_cos[i]);
}

/** The kernel with the smallest e_i (the first on ties), an O(N) scan: the fallback when no
 *  kernel is within the cutoff. */
static inline uint32_t dmp_ptick_nearest(const DMP_TICK_MODEL *m, fs_phase_t sh, fs_phase_t ch)
{
    uint32_t best = 0u;
    fs_kdist_t r_best = fs_num_kernel_dist(dmp_ptick_dist(m, 0u, sh, ch), 0, m->kernel_scale[0]);
    for (uint32_t i = 1u; i < m->n_kernels; i++) {
        const fs_kdist_t r = fs_num_kernel_dist(dmp_ptick_dist(m, i, sh, ch), 0,
                                                m->kernel_scale[i]);
        if (r < r_best) {
            r_best = r;
            best = i;
        }
    }
    return best;
}

/** The virtual window [lo, end) (end <= lo + N) as two runs of real kernel indices in j order,
 *  [run[0], run[1]) then [run[2], run[3]) (either may be empty): no index test per kernel. */
static inline void dmp_ptick_runs(uint32_t n_k, uint32_t lo, uint32_t end, uint32_t run[4])
{
    const uint32_t b1 = (end < n_k) ? end : n_k;
    run[0] = (lo < b1) ? lo : b1;
    run[1] = b1;
    run[2] = ((lo > n_k) ? lo : n_k) - n_k;
    run[3] = (end > n_k) ? end - n_k : 0u;
}

/** S(x) over the virtual window [lo, hi) (at most min(N, FS_NUM_MAX_WINDOW) kernels from lo),
 *  the kernels with e_i <= FS_NUM_CUTOFF, psi_i as DMP_TICK_BLEND_SHIFT says; *count (may be
 *  NULL) the number summed (1 in the nearest-kernel fallback). With w_y non-NULL, *s_y
 *  receives the same blend of w_y (the y path's weights) from the same activations. */
/* long: the counted hot path, one inline body without calls (docs/cortex-m.md) */
static inline fs_val_t dmp_ptick_blend2(const DMP_TICK_MODEL *m, fs_phase_t x, uint32_t lo,
                                        uint32_t hi, uint16_t *count, const fs_val_t *w_y,
                                        fs_val_t *s_y)
{
    const uint32_t n_k = m->n_kernels;
    const uint32_t cap = (n_k < FS_NUM_MAX_WINDOW) ? n_k : FS_NUM_MAX_WINDOW;
    const uint32_t end = (hi > lo + cap) ? lo + cap : hi;
    uint32_t run[4];
    dmp_ptick_runs(n_k, lo, end, run);
    fs_phase_t sh;
    fs_phase_t ch;
    fs_num_sincos_pi(x, &sh, &ch);
    fs_bnum_t num = 0;
    fs_bnum_t num_y = 0;
    fs_bden_t den = 0;
    uint32_t n = 0u;
#if DMP_TICK_BLEND_SHIFT
    fs_expo_t e[FS_NUM_MAX_WINDOW];
    fs_expo_t e_min = FS_NUM_EXPO_INF;
    uint32_t k = 0u;
    for (uint32_t r = 0u; r < 4u; r += 2u) {
        for (uint32_t i = run[r]; i < run[r + 1u]; i++) {
            const fs_expo_t ei = fs_num_kernel_expo(dmp_ptick_dist(m, i, sh, ch), 0,
                                                    m->kernel_scale[i]);
            e[k++] = ei;
            if (ei <= FS_NUM_CUTOFF) {
                n++;
                e_min = (ei < e_min) ? ei : e_min;
            }
        }
    }
    /* one loop per case: no test of w_y per kernel */
    k = 0u;
    if (n != 0u && w_y == NULL) {
        for (uint32_t r = 0u; r < 4u; r += 2u) {
            for (uint32_t i = run[r]; i < run[r + 1u]; i++, k++) {
                if (e[k] <= FS_NUM_CUTOFF) {
                    fs_num_blend_acc(&num, &den, fs_num_exp_neg(e[k] - e_min), m->weight[i]);
                }
            }
        }
    } else if (n != 0u) {
        for (uint32_t r = 0u; r < 4u; r += 2u) {
            for (uint32_t i = run[r]; i < run[r + 1u]; i++, k++) {
                if (e[k] <= FS_NUM_CUTOFF) {
                    const fs_act_t psi = fs_num_exp_neg(e[k] - e_min);
                    fs_num_blend_acc(&num, &den, psi, m->weight[i]);
                    fs_num_blend_acc_num(&num_y, psi, w_y[i]);
                }
            }
        }
    }
#else
    /* one loop per case: no test of w_y per kernel */
    if (w_y == NULL) {
        for (uint32_t r = 0u; r < 4u; r += 2u) {
            for (uint32_t i = run[r]; i < run[r + 1u]; i++) {
                const fs_expo_t ei = fs_num_kernel_expo(dmp_ptick_dist(m, i, sh, ch), 0,
                                                        m->kernel_scale[i]);
                if (ei <= FS_NUM_CUTOFF) {
                    n++;
                    fs_num_blend_acc(&num, &den, fs_num_exp_neg(ei), m->weight[i]);
                }
            }
        }
    } else {
        for (uint32_t r = 0u; r < 4u; r += 2u) {
            for (uint32_t i = run[r]; i < run[r + 1u]; i++) {
                const fs_expo_t ei = fs_num_kernel_expo(dmp_ptick_dist(m, i, sh, ch), 0,
                                                        m->kernel_scale[i]);
                if (ei <= FS_NUM_CUTOFF) {
                    n++;
                    const fs_act_t psi = fs_num_exp_neg(ei);
                    fs_num_blend_acc(&num, &den, psi, m->weight[i]);
                    fs_num_blend_acc_num(&num_y, psi, w_y[i]);
                }
            }
        }
    }
#endif
    if (count != NULL) {
        *count = (uint16_t)((n == 0u) ? 1u : n);
    }
    if (n == 0u) {
        const uint32_t best = dmp_ptick_nearest(m, sh, ch);
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

/** dmp_ptick_blend2 of the force weights alone. */
static inline fs_val_t dmp_ptick_blend(const DMP_TICK_MODEL *m, fs_phase_t x, uint32_t lo,
                                       uint32_t hi, uint16_t *count)
{
    return dmp_ptick_blend2(m, x, lo, hi, count, NULL, NULL);
}

/** The blend at the state's phase, the state's window walked there first. */
static inline fs_val_t dmp_ptick_state_blend(const DMP_TICK_MODEL *m, const dmp_ptick_state_t *s)
{
    const fs_phase_t x = fs_num_view(*s->x);
    dmp_ptick_window_walk(m, dmp_ptick_query(x), s->window);
    return dmp_ptick_blend(m, x, s->window[0], s->window[1], NULL);
}

/** The blend pair (S, S_y) at the state's phase, the state's window walked there first; *s_y
 *  the blend of w_y (the y path's weights) over the same activations. */
static inline fs_val_t dmp_ptick_state_blend2(const DMP_TICK_MODEL *m, const dmp_ptick_state_t *s,
                                              const fs_val_t *w_y, fs_val_t *s_y)
{
    const fs_phase_t x = fs_num_view(*s->x);
    dmp_ptick_window_walk(m, dmp_ptick_query(x), s->window);
    return dmp_ptick_blend2(m, x, s->window[0], s->window[1], NULL, w_y, s_y);
}

/** One step of the periodic y path about its mean (the law with gamma = 0, every right-hand side
 *  at the old state; c: dmp_tick_path_coef_t with goal unused, scale the path scale s_p):
 *    h = scale*S_y     q += k1*(z_q - q + h)     z_q += k_ab*(0 - q) - k_a*z_q
 *  Returns q after the step (m from the path's mean). */
static inline fs_val_t dmp_ptick_path_step(const dmp_tick_path_coef_t *c, fs_acc_t *q,
                                           fs_acc_t *z_q, fs_val_t s_y, uint32_t *ev)
{
    const fs_val_t qv = fs_num_view(*q);
    const fs_val_t zv = fs_num_view(*z_q);
    const fs_val_t h = fs_num_mul_vv(c->scale, s_y, ev);
    const fs_val_t sq = fs_num_add_ev(fs_num_sub_ev(zv, qv, ev), h, ev);
    *q = fs_num_acc_mac1(*q, c->k1, sq, ev);
    *z_q = fs_num_acc_mac2(*z_q, c->k_alphabeta, fs_num_sub_ev(FS_NUM_ZERO, qv, ev), c->k_alpha, zv,
                           ev);
    return fs_num_view(*q);
}

/** One forward-Euler step with constants c and s_blend = dmp_ptick_state_blend of the same
 *  state (saturations counted in *ev); the phase wraps by one turn once it reaches one, and the
 *  window with it. Returns out_scale*(g + e) after the step (N above f0). */
static inline fs_force_t dmp_ptick_step(const DMP_TICK_MODEL *m, const dmp_ptick_coef_t *c,
                                        const dmp_ptick_state_t *s, fs_val_t s_blend, uint32_t *ev)
{
    const fs_val_t e = fs_num_view(*s->e);
    const fs_val_t z = fs_num_view(*s->z);
    const fs_val_t i_e = fs_num_view(*s->integral);
    const fs_val_t h = fs_num_mul_vv(c->amplitude, s_blend, ev);
    const fs_val_t se = fs_num_add_ev(fs_num_add_ev(fs_num_sub_ev(z, e, ev), h, ev), c->term_y, ev);
    *s->e = fs_num_acc_mac2(*s->e, c->k1, se, c->k_gamma, i_e, ev);
    *s->z = fs_num_acc_mac2(*s->z, c->k_alphabeta, fs_num_sub_ev(FS_NUM_ZERO, e, ev), c->k_alpha, z,
                            ev);
    *s->integral = fs_num_acc_mac1(*s->integral, c->k1, e, ev);
    const int below_half = *s->x < FS_NUM_TURN / 2;
    /* compensated sum: float32 rounding of x + inc would otherwise drift the phase by up to
     * 3e-8 turn a step (0.34 ms in 60 s of 0.5 s cycles); integer sums leave comp at 0 */
    const fs_acc_t inc = c->phase_inc - *s->x_comp;
    const fs_acc_t sum = *s->x + inc;
    *s->x_comp = (sum - *s->x) - inc;
    *s->x = sum;
    if (*s->x >= FS_NUM_TURN) {
        *s->x -= FS_NUM_TURN;
    }
    if (below_half && *s->x >= FS_NUM_TURN / 2) { /* the query jumps back one turn */
        const uint32_t n = m->n_kernels;
        const uint32_t w0 = s->window[0];
        const uint32_t w1 = s->window[1];
        s->window[0] = (uint16_t)((w0 > n) ? w0 - n : 0u);
        s->window[1] = (uint16_t)((w1 > n) ? w1 - n : 0u);
    }
    return fs_num_force(c->out_scale, fs_num_add_ev(c->goal, fs_num_view(*s->e), ev), ev);
}

#endif /* DMP_PTICK_H */

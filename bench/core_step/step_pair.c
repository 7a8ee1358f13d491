/* One real type's half of the side-by-side step benchmark (see step_pair.h). The minimal step
 * is what one would write from docs/math.md section 2 with no shared code: per-kernel reach
 * r_i = sqrt(2 cutoff) sigma_i, a window [lo, hi) kept from the previous step and only moved
 * forward (the phase only grows), one pass over it with psi_i = exp(-e_i) for e_i <= cutoff, the
 * forward-Euler step in the same coefficient form. Same kernels, cutoff and exp as the core. */
#define _POSIX_C_SOURCE 199309L
#include <math.h>
#include <stddef.h>
#include <string.h>
#include <time.h>

#include "skill.h"
#include "step_pair.h"

#ifndef STEP_PAIR_FN
#error "define STEP_PAIR_FN"
#endif

typedef fs_real_t real;

typedef struct {
    uint16_t n;
    real c[DMP_MAX_KERNELS];
    real s[DMP_MAX_KERNELS];      /* 1/(2 sigma^2) */
    real w[DMP_MAX_KERNELS];
    real reach_lo[DMP_MAX_KERNELS];
    real reach_hi[DMP_MAX_KERNELS];
    real k1, ka, kab, kg, g, f0; /* f0: the starting force, N */
} min_model_t;

typedef struct {
    real u, v, i_x, x, z;
    uint32_t lo;
    uint32_t hi;
} min_state_t;

static skill_t g_skill;           /* static: ~12 KB in double */
static min_model_t g_min;

/* Per-kernel reach [c_i - r_i, c_i + r_i] made monotone (running max of the upper ends, running
 * min of the lower ends from the right), so a window [lo, hi) can only move forward. */
static void min_build(const dmp_model_t *m, min_model_t *q)
{
    const real r = (real)sqrt(2.0 * (double)DMP_KERNEL_CUTOFF_EXP) * FS_R(1.0001);
    q->n = m->n_kernels;
    for (uint16_t i = 0u; i < q->n; i++) {
        q->c[i] = m->centre[i];
        q->s[i] = FS_R(1.0) / (FS_R(2.0) * m->width[i] * m->width[i]);
        q->w[i] = m->weight[i];
        q->reach_lo[i] = m->centre[i] - r * m->width[i];
        q->reach_hi[i] = m->centre[i] + r * m->width[i];
        if (i > 0u && q->reach_hi[i] < q->reach_hi[i - 1u]) {
            q->reach_hi[i] = q->reach_hi[i - 1u];
        }
    }
    for (uint32_t i = (uint32_t)q->n - 1u; i > 0u; i--) {
        if (q->reach_lo[i - 1u] > q->reach_lo[i]) {
            q->reach_lo[i - 1u] = q->reach_lo[i];
        }
    }
    const real k1 = m->dt_s / m->tau_s;
    q->k1 = k1;
    q->ka = k1 * m->p.alpha;
    q->kab = q->ka * m->p.beta;
    q->kg = k1 * m->p.gamma;
    q->g = m->goal_N;
    q->f0 = m->force0_N;
}

static real min_step(const min_model_t *q, min_state_t *st)
{
    const real u = st->u;
    const real cut = (real)DMP_KERNEL_CUTOFF_EXP;
    while (st->lo < q->n && q->reach_hi[st->lo] < u) {
        st->lo++;
    }
    while (st->hi < q->n && q->reach_lo[st->hi] <= u) {
        st->hi++;
    }
    real num = FS_R(0.0);
    real den = FS_R(0.0);
    for (uint32_t i = st->lo; i < st->hi; i++) {
        const real d = u - q->c[i];
        const real e = d * d * q->s[i];
        if (e <= cut) {
            const real psi = fs_exp(-e);
            num += psi * q->w[i];
            den += psi;
        }
    }
    real blend;
    if (den > FS_R(0.0)) {
        blend = num / den;
    } else {                      /* outside every kernel: the nearest one */
        uint32_t best = 0u;
        for (uint32_t i = 1u; i < q->n; i++) {
            if (fabs((double)(u - q->c[i])) * sqrt((double)q->s[i]) <
                fabs((double)(u - q->c[best])) * sqrt((double)q->s[best])) {
                best = i;
            }
        }
        blend = q->w[best];
    }
    const real h = q->g * st->v * blend;
    const real x = st->x;
    const real z = st->z;
    const real v = st->v;
    st->x = x + (q->k1 * (z - x + h + FS_R(0.0)) - q->kg * st->i_x);
    st->z = z + (q->kab * (q->g - x) - q->ka * z);
    st->i_x = st->i_x + q->k1 * x;
    st->v = v + (q->kab * (FS_R(1.0) - u) - q->ka * v);
    st->u = u + q->k1 * v;
    return q->f0 + st->x; /* force units: the state is N above the starting force */
}

static double now_ns(void)
{
    struct timespec ts;
    (void)clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e9 + (double)ts.tv_nsec;
}

static double median_of(double *v, uint32_t n)
{
    for (uint32_t i = 1u; i < n; i++) {
        const double x = v[i];
        uint32_t j = i;
        while (j > 0u && v[j - 1u] > x) {
            v[j] = v[j - 1u];
            j--;
        }
        v[j] = x;
    }
    return (n % 2u) ? v[n / 2u] : 0.5 * (v[n / 2u - 1u] + v[n / 2u]);
}

static real ours_rollout(const dmp_model_t *m, uint32_t n_steps)
{
    dmp_state_t s;
    const dmp_run_t run = {FS_R(1.0), FS_R(1.0)};
    dmp_state_reset(&s);
    real sum = FS_R(0.0);
    for (uint32_t i = 0u; i < n_steps; i++) {
        sum += dmp_step(m, &s, &run, NULL);
    }
    return sum;
}

static real min_rollout(const min_model_t *q, uint32_t n_steps)
{
    min_state_t s;
    memset(&s, 0, sizeof s);
    real sum = FS_R(0.0);
    for (uint32_t i = 0u; i < n_steps; i++) {
        sum += min_step(q, &s);
    }
    return sum;
}

void STEP_PAIR_FN(const uint8_t *img, uint32_t len, uint32_t reps, step_pair_result_t *out)
{
    static double t_ours[STEP_PAIR_MAX_REPS];
    static double t_min[STEP_PAIR_MAX_REPS];
    memset(out, 0, sizeof *out);
    const fs_status_t st = skill_parse(img, len, &g_skill);
    if (st != FS_OK) {
        out->status = (int)st;
        return;
    }
    const dmp_model_t *m = &g_skill.dmp;
    min_build(m, &g_min);
    out->n_kernels = m->n_kernels;
    out->n_steps = (uint32_t)lround((double)m->duration_s / (double)m->dt_s);
    reps = (reps > STEP_PAIR_MAX_REPS) ? STEP_PAIR_MAX_REPS : ((reps == 0u) ? 1u : reps);
    out->reps = reps;

    /* the outputs, step by step */
    dmp_state_t so;
    min_state_t sm;
    const dmp_run_t run = {FS_R(1.0), FS_R(1.0)};
    dmp_state_reset(&so);
    memset(&sm, 0, sizeof sm);
    double peak = 0.0;
    double diff = 0.0;
    for (uint32_t i = 0u; i < out->n_steps; i++) {
        const double a = (double)dmp_step(m, &so, &run, NULL);
        const double b = (double)min_step(&g_min, &sm);
        peak = fmax(peak, fabs(a));
        diff = fmax(diff, fabs(a - b));
        out->checksum += a;
    }
    out->max_rel_diff = (peak > 0.0) ? diff / peak : diff;

    /* interleaved timing: machine load hits both alike */
    volatile real sink = FS_R(0.0);
    for (uint32_t r = 0u; r < reps; r++) {
        double t0 = now_ns();
        sink += ours_rollout(m, out->n_steps);
        double t1 = now_ns();
        t_ours[r] = (t1 - t0) / (double)out->n_steps;
        t0 = now_ns();
        sink += min_rollout(&g_min, out->n_steps);
        t1 = now_ns();
        t_min[r] = (t1 - t0) / (double)out->n_steps;
    }
    (void)sink;
    out->ours_ns = median_of(t_ours, reps);
    out->minimal_ns = median_of(t_min, reps);
}

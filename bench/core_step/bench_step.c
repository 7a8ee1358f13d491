/* One half of the dmp_step benchmark, compiled twice: against the double core (defines
 * BENCH_ENTRY bench_core_step_double) and the float core (FS_REAL_FLOAT, BENCH_ENTRY
 * bench_core_step_float). Builds a realistic skill (default gains, force units, T = 17 s,
 * centres uniform in time through the discrete phase, sigma = half the gap, smooth weights) and
 * times full 17 000-step rollouts. */
#define _POSIX_C_SOURCE 199309L
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <time.h>

#include "bench_core_step.h"
#include "dmp.h"

#define DT_S 0.001
#define T_S 17.0

static dmp_model_t model;

static double phase_at(double alpha, double beta, double tau, long n)
{
    double u = 0.0, v = 0.0;
    const double k = DT_S / tau;
    for (long i = 0; i < n; i++) {
        const double v_next = v + k * alpha * (beta * (1.0 - u) - v);
        u += k * v;
        v = v_next;
    }
    return u;
}

static int build_model(uint16_t n)
{
    const double alpha = 9.0, beta = 2.25;
    const long steps = lround(T_S / DT_S);
    double lo = 0.01 * T_S, hi = 10.0 * T_S;
    for (int it = 0; it < 100; it++) {
        const double mid = 0.5 * (lo + hi);
        if (phase_at(alpha, beta, mid, steps) > 0.99) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    const double tau = 0.5 * (lo + hi);
    double c[DMP_MAX_KERNELS];
    for (uint16_t i = 0; i < n; i++) {
        const double pos = (double)steps * (double)i / (double)(n - 1);
        const long j = (long)floor(pos) >= steps ? steps - 1 : (long)floor(pos);
        const double u0 = phase_at(alpha, beta, tau, j);
        const double u1 = phase_at(alpha, beta, tau, j + 1);
        c[i] = u0 + (pos - (double)j) * (u1 - u0);
    }
    model.n_kernels = n;
    model.p.alpha = (fs_real_t)alpha;
    model.p.beta = (fs_real_t)beta;
    model.p.gamma = (fs_real_t)(4860.0 / (40.0 * alpha));
    model.dt_s = (fs_real_t)DT_S;
    model.tau_s = (fs_real_t)tau;
    model.goal_N = (fs_real_t)5.0;
    model.force0_N = (fs_real_t)0.0;
    model.duration_s = (fs_real_t)T_S;
    for (uint16_t i = 0; i < n; i++) {
        const double s = (double)i / (double)(n - 1);
        model.centre[i] = (fs_real_t)c[i];
        model.width[i] = (fs_real_t)(0.5 * ((i + 1 < n) ? c[i + 1] - c[i] : c[i] - c[i - 1]));
        model.weight[i] = (fs_real_t)(40.0 * sin(3.0 * s) + 15.0 * cos(11.0 * s) - 5.0);
    }
    return dmp_model_init(&model) == FS_OK;
}

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

double BENCH_ENTRY(uint16_t n_kernels, int runs, double *f_sink)
{
    if (!build_model(n_kernels) || runs > 64) {
        return -1.0;
    }
    const long steps = lround(T_S / DT_S);
    double ns[64];
    const dmp_run_t run = {(fs_real_t)1.0, (fs_real_t)1.0};
    for (int r = 0; r < runs; r++) {
        dmp_state_t s;
        dmp_state_reset(&s);
        fs_real_t acc = (fs_real_t)0.0;
        const double t0 = now_s();
        for (long i = 0; i < steps; i++) {
            acc += dmp_step(&model, &s, &run, NULL);
        }
        const double t1 = now_s();
        *f_sink += (double)acc;
        ns[r] = (t1 - t0) * 1e9 / (double)steps;
    }
    /* median (insertion sort, runs is small) */
    for (int i = 1; i < runs; i++) {
        const double x = ns[i];
        int j = i - 1;
        while (j >= 0 && ns[j] > x) {
            ns[j + 1] = ns[j];
            j--;
        }
        ns[j + 1] = x;
    }
    return ns[runs / 2];
}

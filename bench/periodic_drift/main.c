/* bench_periodic_drift SKILL [SECONDS]: cycles of a periodic skill for SECONDS (default 60) in
 * float32 (the M4F image's core) and in fixed point (the M3 image's, converted with the measured
 * peaks and as the executor converts) against the float64 core, all at scales 1 from the stored
 * cycle state. Prints per build the largest |f - f_64| in % of max |f_64|, the same over the last
 * cycle only (drift shows as growth), and the phase difference after the last step in turns and
 * in ms of the period. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "dmpfx.h"
#include "f32_side.h"
#include "skill.h"

#define MAX_ROWS 3600000L

static uint8_t image[SKILL_IMAGE_MAX];
static skill_t skill;
static dmpfx_model_t fxm;
static double f64[MAX_ROWS + 1];
static double other[MAX_ROWS + 1];

static void report(const char *build, long rows, long last, double x_64, double x_b, double period)
{
    double e = 0.0, e_last = 0.0, m = 0.0;
    for (long n = 0; n <= rows; n++) {
        const double d = fabs(other[n] - f64[n]);
        e = fmax(e, d);
        e_last = (n >= rows - last) ? fmax(e_last, d) : e_last;
        m = fmax(m, fabs(f64[n]));
    }
    double dx = x_b - x_64;
    dx -= round(dx); /* the phases compared on the circle */
    printf("%-24s max |f - f64| %.5f %% of max force, last cycle %.5f %%; phase %+.3g turns "
           "(%+.4f ms)\n",
           build, 100.0 * e / m, 100.0 * e_last / m, dx, 1e3 * dx * period);
}

static int fixed_rollout(const char *build, long rows, long last, double x_64, double period)
{
    dmpfx_run_t run;
    if (dmpfx_run_init(&fxm, 1.0, 1.0, &run) != FS_OK) {
        printf("%s: run refused\n", build);
        return 1;
    }
    dmpfx_state_t s;
    dmpfx_periodic_reset(&fxm, &run, &s);
    other[0] = fx_to_double(fxm.force0_q16, 16u) +
               ldexp((double)run.goal_q24 + (double)dmpfx_view(s.y_acc), fxm.value_shift - 24);
    for (long n = 1; n <= rows; n++) {
        other[n] = fx_to_double(dmpfx_periodic_step(&fxm, &run, &s, NULL), 16u);
    }
    report(build, rows, last, x_64, ldexp((double)s.u_acc, -61), period);
    if (s.sat_events != 0u) {
        printf("%s: %u saturations\n", build, (unsigned)s.sat_events);
        return 1;
    }
    return 0;
}

int main(int argc, char **argv)
{
    if (argc < 2 || argc > 3) {
        fprintf(stderr, "usage: bench_periodic_drift SKILL [SECONDS]\n");
        return 2;
    }
    const double seconds = (argc == 3) ? atof(argv[2]) : 60.0;
    FILE *f = fopen(argv[1], "rb");
    if (f == NULL) {
        fprintf(stderr, "cannot read %s\n", argv[1]);
        return 2;
    }
    const size_t len = fread(image, 1, sizeof image, f);
    fclose(f);
    if (skill_parse(image, (uint32_t)len, &skill) != FS_OK || skill.dmp.periodic == 0u) {
        fprintf(stderr, "%s: not a periodic skill\n", argv[1]);
        return 2;
    }
    const double dt = skill.dmp.dt_s;
    const double period = skill.dmp.duration_s;
    const long rows = lround(seconds / dt);
    const long last = lround(period / dt);
    if (!(seconds > 0.0) || rows > MAX_ROWS) {
        fprintf(stderr, "SECONDS must be in (0, %g]\n", (double)MAX_ROWS * dt);
        return 2;
    }
    dmp_state_t s;
    dmp_periodic_reset(&skill.dmp, &s, 1.0);
    f64[0] = skill.dmp.force0_N + skill.dmp.goal_N + s.y_N;
    for (long n = 1; n <= rows; n++) {
        f64[n] = dmp_periodic_step(&skill.dmp, &s, NULL, 1.0, NULL);
    }
    const double x_64 = s.u;
    printf("%s: N = %u, period %.4f s, %.0f s = %.1f cycles, %ld steps\n", argv[1],
           (unsigned)skill.dmp.n_kernels, period, seconds, seconds / period, rows);
    double x_32 = 0.0;
    int rc = 0;
    if (pd_f32_rollout(image, (uint32_t)len, rows, other, &x_32) != 0) {
        printf("float32: refused\n");
        rc = 1;
    } else {
        report("float32", rows, last, x_64, x_32, period);
    }
    if (dmpfx_from_model(&skill.dmp, &fxm) != FS_OK) {
        printf("fixed: conversion refused\n");
        return 1;
    }
    rc |= fixed_rollout("fixed (measured peaks)", rows, last, x_64, period);
    if (dmpfx_from_model_bound(&skill.dmp, &fxm) != FS_OK) {
        printf("fixed (executor): conversion refused\n");
        return 1;
    }
    rc |= fixed_rollout("fixed (executor)", rows, last, x_64, period);
    return rc;
}

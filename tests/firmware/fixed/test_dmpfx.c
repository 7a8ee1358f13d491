/* Fixed-point DMP against the float64 core: every golden vector of tests/vectors/manifest.txt
 * (pressing and engraving skills, N = 10/50/100, goal 1x and 1.5x, time 1x and 1.3x) and a long
 * 17 s skill; the kernel blend against the double blend; rejection of skills that do not fit
 * (3xx codes); coupling (phase slow-down, additive term) against the double core; the
 * executor's conversion without rollout (dmpfx_from_model_bound) on the same skills; the
 * periodic DMP (manifest_periodic.txt) against the float64 core and the Python rollout, its
 * sine polynomial and its blend; the device's commit on those skills: the conversion in slices
 * (one unit a call gives the one-call model byte for byte) and the output check's rollout in
 * fixed point (dmpfx_check) against the float64 skill check (skchk_skill). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core_test_util.h"
#include "dmpfx.h"
#include "fs_num_fixed.h"
#include "skill.h"
#include "skill_check.h"
#include "vectors_io.h"

#ifndef FS_VECTORS_DIR
#error "FS_VECTORS_DIR must point at tests/vectors"
#endif

/* Fixed-point rollout within 0.1 % of max force of float64 (docs/cortex-m.md); asserted at the aim, 0.02 %. */
#define FIXED_TOL_REL 2e-4
#define MAX_ROWS 40000

static skill_t skill;
static dmpfx_model_t fxm;
static uint8_t image[SKILL_IMAGE_MAX];
static double f_ref[MAX_ROWS + 1];
static double f_fx[MAX_ROWS + 1];

/* A golden skill of tests/vectors into skill (float64 core) and fxm (fixed point). */
static void load_fixed(const char *name)
{
    const uint32_t len = tv_read(name, image, sizeof(image));
    assert_true(len > 0u);
    assert_int_equal(skill_parse(image, len, &skill), FS_OK);
    assert_int_equal(dmpfx_from_model(&skill.dmp, &fxm), FS_OK);
}

/* Fixed rollout rows n = 0..rows (row 0 is f0), f in N. Returns the saturation count. */
static uint32_t rollout_fx(const dmpfx_model_t *m, double goal_scale, double time_scale, long rows,
                           double *out)
{
    dmpfx_run_t run;
    assert_int_equal(dmpfx_run_init(m, goal_scale, time_scale, &run), FS_OK);
    dmpfx_state_t s;
    dmpfx_state_reset(&s);
    out[0] = fx_to_double(m->force0_q16, 16u);
    for (long i = 1; i <= rows; i++) {
        out[i] = fx_to_double(dmpfx_step(m, &run, &s, NULL), 16u);
    }
    return s.sat_events;
}

static void rollout_double(const dmp_model_t *m, double goal_scale, double time_scale, long rows,
                           double *out)
{
    const dmp_run_t run = {goal_scale, time_scale};
    dmp_state_t s;
    dmp_state_reset(&s);
    out[0] = (double)m->force0_N;
    for (long i = 1; i <= rows; i++) {
        out[i] = dmp_step(m, &s, &run, NULL);
    }
}

static double rel_err(const double *a, const double *b, long rows)
{
    double e = 0.0;
    double m = 0.0;
    for (long i = 0; i <= rows; i++) {
        e = fmax(e, fabs(a[i] - b[i]));
        m = fmax(m, fabs(b[i]));
    }
    return e / m;
}

static void test_golden_vectors(void **state)
{
    (void)state;
    char mpath[512];
    snprintf(mpath, sizeof(mpath), "%s/manifest.txt", FS_VECTORS_DIR);
    FILE *mf = fopen(mpath, "r");
    assert_non_null(mf);
    char sk[256];
    char csv[256];
    double gs;
    double ts;
    int lines = 0;
    double worst = 0.0;
    while (fscanf(mf, "%255s %lf %lf %255s", sk, &gs, &ts, csv) == 4) {
        load_fixed(sk);
        const long rows = lround(skill.dmp.duration_s * ts / skill.dmp.dt_s);
        assert_true(rows <= MAX_ROWS);
        assert_int_equal(rollout_fx(&fxm, gs, ts, rows, f_fx), 0u);
        /* reference 1: the C double core; reference 2: the Python rollout in the CSV */
        rollout_double(&skill.dmp, gs, ts, rows, f_ref);
        const double e_core = rel_err(f_fx, f_ref, rows);
        char cpath[512];
        snprintf(cpath, sizeof(cpath), "%s/%s", FS_VECTORS_DIR, csv);
        FILE *cf = fopen(cpath, "r");
        assert_non_null(cf);
        char line[128];
        assert_non_null(fgets(line, sizeof(line), cf)); /* header t,f_hat */
        long n = 0;
        double t;
        double f;
        while (fscanf(cf, "%lf,%lf", &t, &f) == 2) {
            assert_true(n <= rows);
            f_ref[n++] = f;
        }
        fclose(cf);
        assert_int_equal(n, rows + 1);
        const double e_py = rel_err(f_fx, f_ref, rows);
        printf("fixed vs float64  %-34s g=%-3g t=%-3g  core %.4f %%  python %.4f %%\n", sk, gs, ts,
               100.0 * e_core, 100.0 * e_py);
        assert_true(e_core <= FIXED_TOL_REL);
        assert_true(e_py <= FIXED_TOL_REL);
        worst = fmax(worst, fmax(e_core, e_py));
        lines++;
    }
    fclose(mf);
    assert_true(lines >= 10);
    printf("fixed vs float64: worst over %d golden vectors %.4f %% of max force\n", lines,
           100.0 * worst);
}

static double y_ref[MAX_ROWS + 1];
static double y_fx[MAX_ROWS + 1];

/* The skills with a y DMP (manifest_y.txt): dmpfx_step_xy against the Python rollout of both
 * halves (force and y_hat = y_start + p), the same tolerance relative to max|f| and max|p|. */
static void test_golden_vectors_y(void **state)
{
    (void)state;
    char mpath[512];
    snprintf(mpath, sizeof(mpath), "%s/manifest_y.txt", FS_VECTORS_DIR);
    FILE *mf = fopen(mpath, "r");
    assert_non_null(mf);
    char sk[256];
    char csv[256];
    double gs;
    double ts;
    double ps;
    int lines = 0;
    while (fscanf(mf, "%255s %lf %lf %lf %255s", sk, &gs, &ts, &ps, csv) == 5) {
        load_fixed(sk);
        assert_int_equal(skill.dmp.has_y, 1u);
        const long rows = lround(skill.dmp.duration_s * ts / skill.dmp.dt_s);
        assert_true(rows <= MAX_ROWS);
        dmpfx_run_t run;
        assert_int_equal(dmpfx_run_init(&fxm, gs, ts, &run), FS_OK);
        assert_int_equal(dmpfx_run_path(&fxm, ps, &run), FS_OK);
        dmpfx_state_t s;
        dmpfx_state_reset(&s);
        const double y0 = (double)skill.dmp.y_start_m;
        f_fx[0] = fx_to_double(fxm.force0_q16, 16u);
        y_fx[0] = y0;
        for (long i = 1; i <= rows; i++) {
            int32_t p = 0;
            f_fx[i] = fx_to_double(dmpfx_step_xy(&fxm, &run, &s, NULL, &p), 16u);
            y_fx[i] = y0 + fx_to_double(p, 24u);
        }
        assert_int_equal(s.sat_events, 0u);
        char cpath[512];
        snprintf(cpath, sizeof(cpath), "%s/%s", FS_VECTORS_DIR, csv);
        FILE *cf = fopen(cpath, "r");
        assert_non_null(cf);
        char line[128];
        assert_non_null(fgets(line, sizeof(line), cf)); /* header t,f_hat,y_hat */
        long n = 0;
        double t;
        double f;
        double y;
        while (fscanf(cf, "%lf,%lf,%lf", &t, &f, &y) == 3) {
            assert_true(n <= rows);
            f_ref[n] = f;
            y_ref[n++] = y;
        }
        fclose(cf);
        assert_int_equal(n, rows + 1);
        double e_y = 0.0;
        double p_max = 0.0;
        for (long i = 0; i <= rows; i++) {
            e_y = fmax(e_y, fabs(y_fx[i] - y_ref[i]));
            p_max = fmax(p_max, fabs(y_ref[i] - y0));
        }
        const double e_f = rel_err(f_fx, f_ref, rows);
        printf(
            "fixed vs python  %-28s g=%-3g t=%-3g p=%-3g  force %.4f %%  path %.4f %% (%.3g um)\n",
            sk, gs, ts, ps, 100.0 * e_f, 100.0 * e_y / p_max, 1e6 * e_y);
        assert_true(e_f <= FIXED_TOL_REL);
        assert_true(e_y / p_max <= FIXED_TOL_REL);
        lines++;
    }
    fclose(mf);
    assert_true(lines >= 3);
}

/* dmpfx_from_model_bound (no rollout, the executor's conversion) on every skill of both
 * manifests and the long synthetic ones: its estimates are at or above the peaks
 * dmpfx_from_model measures (h, y, z, I; the y DMP; v~), and its rollout agrees with the
 * float64 core within the same tolerance, without a saturation. */
static void check_bound(const dmp_model_t *m, const char *name, double gs, double ts)
{
    static dmpfx_model_t bm;
    assert_int_equal(dmpfx_from_model(m, &fxm), FS_OK);
    assert_int_equal(dmpfx_from_model_bound(m, &bm), FS_OK);
    /* the estimate in N against the measured peak in N (the scales differ) */
    assert_true(ldexp(bm.peak_q24, bm.value_shift) >= ldexp(fxm.peak_q24, fxm.value_shift));
    assert_true(bm.value_shift >= fxm.value_shift);
    assert_true(bm.peak_y_q24 >= fxm.peak_y_q24);
    assert_true(bm.peak_v_q30 >= fxm.peak_v_q30);
    const long rows = lround((double)m->duration_s * ts / (double)m->dt_s);
    assert_true(rows <= MAX_ROWS);
    assert_int_equal(rollout_fx(&bm, gs, ts, rows, f_fx), 0u);
    rollout_double(m, gs, ts, rows, f_ref);
    const double e = rel_err(f_fx, f_ref, rows);
    printf("bound conversion  %-34s g=%-3g t=%-3g  s=%d (measured %d)  %.4f %%\n", name, gs, ts,
           (int)bm.value_shift, (int)fxm.value_shift, 100.0 * e);
    assert_true(e <= FIXED_TOL_REL);
}

/* A manifest of tests/vectors, open for reading. */
static FILE *open_manifest(const char *name)
{
    char mpath[512];
    snprintf(mpath, sizeof(mpath), "%s/%s", FS_VECTORS_DIR, name);
    FILE *mf = fopen(mpath, "r");
    assert_non_null(mf);
    return mf;
}

static void test_bound_conversion(void **state)
{
    (void)state;
    const char *manifests[] = {"manifest.txt", "manifest_y.txt"};
    int lines = 0;
    for (size_t k = 0; k < 2u; k++) {
        FILE *mf = open_manifest(manifests[k]);
        char line[600];
        while (fgets(line, sizeof(line), mf) != NULL) {
            char sk[256];
            double gs;
            double ts;
            if (sscanf(line, "%255s %lf %lf", sk, &gs, &ts) != 3) {
                continue;
            }
            load_fixed(sk);
            check_bound(&skill.dmp, sk, gs, ts);
            lines++;
        }
        fclose(mf);
    }
    assert_true(lines >= 13);
    static tu_skill_desc_t d;
    static dmp_model_t m;
    tu_default_desc(&d, 50, 2000.0, 17.0);
    assert_int_equal(tu_model_from_desc(&d, &m), FS_OK);
    check_bound(&m, "synthetic 17 s N=50 k=2000", 1.5, 1.0);
}

/* A long (17 s) synthetic skill with the default fit's kernel layout, goal 1x and 1.5x. */
/* One skill of the commit's path: the sliced conversion, one unit a call, equals
 * dmpfx_from_model_bound byte for byte in N + checks + 3 units; the fixed-point output check's
 * peak |f_hat| and path extent agree with the float64 check's within FIXED_TOL_REL of the peak
 * (plus one LSB). Returns the peak's relative difference. */
static double check_commit_path(const char *name)
{
    static dmpfx_model_t one;
    static dmpfx_model_t sliced;
    const uint32_t len = tv_read(name, image, sizeof(image));
    assert_true(len > 0u);
    assert_int_equal(skill_parse(image, len, &skill), FS_OK);
    memset(&one, 0, sizeof one);
    memset(&sliced, 0, sizeof sliced);
    assert_int_equal(dmpfx_from_model_bound(&skill.dmp, &one), FS_OK);
    dmpfx_conv_t c;
    dmpfx_bound_begin(&c, &skill.dmp, &sliced);
    uint32_t units = 0u;
    while (!dmpfx_bound_run(&c, 1u)) {
        units++;
    }
    units++;
    assert_int_equal(c.status, FS_OK);
    assert_memory_equal(&one, &sliced, sizeof one);
    const uint32_t n = skill.dmp.n_kernels;
    assert_int_equal(units, n + ((skill.dmp.periodic != 0u) ? 2u * n + 1u : n) + 5u);

    fs_real_t peak_ref = 0.0;
    assert_int_equal(skchk_skill(&skill, 0.001, 1e30, &peak_ref), FS_OK);
    skchk_t ref;
    skchk_begin(&ref, &skill, 0.001, 1e30);
    ref.path_max_m = 1e30;
    while (!skchk_run(&ref, UINT32_MAX)) {
    }
    dmpfx_check_t fc;
    dmpfx_check_begin(&fc, &sliced, (float)skill.dmp.duration_s, 0.001f, 1e30f, 1e30f);
    uint32_t calls = 0u;
    while (!dmpfx_check_run(&fc, 3u)) {
        calls++;
    }
    assert_int_equal(fc.status, FS_OK);
    assert_int_equal(fc.steps_done, ref.steps_total);
    const double peak = (double)dmpfx_check_peak_N(&fc);
    const double path = (double)dmpfx_check_path_m(&fc);
    const double e_peak = fabs(peak - (double)peak_ref) / (double)peak_ref;
    printf("commit check  %-32s N=%3u units=%4u  peak %.5f N (float64 %.5f N, %.4f %%)  path "
           "%.6f m (float64 %.6f m)\n",
           name, (unsigned)n, (unsigned)units, peak, (double)peak_ref, 100.0 * e_peak, path,
           (double)ref.path_peak_m);
    assert_true(fabs(peak - (double)peak_ref) <= FIXED_TOL_REL * (double)peak_ref + 0x1p-16);
    assert_true(fabs(path - (double)ref.path_peak_m) <=
                FIXED_TOL_REL * (double)ref.path_peak_m + 0x1p-24);
    /* the limits refuse as the float64 check does: a peak above the limit (223), a path above
     * the y range (225) */
    dmpfx_check_begin(&fc, &sliced, (float)skill.dmp.duration_s, 0.001f,
                      (float)(0.9 * (double)peak_ref), 1e30f);
    while (!dmpfx_check_run(&fc, UINT32_MAX)) {
    }
    assert_int_equal(fc.status, FS_ERR_SKCHK_PEAK);
    if (ref.path_peak_m > 0.0) {
        dmpfx_check_begin(&fc, &sliced, (float)skill.dmp.duration_s, 0.001f, 1e30f,
                          (float)(0.9 * (double)ref.path_peak_m));
        while (!dmpfx_check_run(&fc, UINT32_MAX)) {
        }
        assert_int_equal(fc.status, FS_ERR_SKCHK_PATH);
    }
    return e_peak;
}

static void test_commit_path(void **state)
{
    (void)state;
    const char *manifests[] = {"manifest.txt", "manifest_y.txt", "manifest_periodic.txt"};
    int lines = 0;
    double worst = 0.0;
    for (size_t k = 0; k < 3u; k++) {
        FILE *mf = open_manifest(manifests[k]);
        char line[600];
        char last[256] = "";
        while (fgets(line, sizeof(line), mf) != NULL) {
            char sk[256];
            if (sscanf(line, "%255s", sk) != 1 || strcmp(sk, last) == 0) {
                continue;
            }
            snprintf(last, sizeof(last), "%s", sk);
            worst = fmax(worst, check_commit_path(sk));
            lines++;
        }
        fclose(mf);
    }
    printf("commit check: %d skills, worst peak difference %.4f %% (bound %.2f %%)\n", lines,
           100.0 * worst, 100.0 * FIXED_TOL_REL);
    assert_true(lines >= 10);
}

static void test_long_skill(void **state)
{
    (void)state;
    static tu_skill_desc_t d;
    static dmp_model_t m;
    const double ks[] = {100.0, 280.0, 2000.0};
    for (size_t k = 0; k < sizeof(ks) / sizeof(ks[0]); k++) {
        tu_default_desc(&d, 50, ks[k], 17.0);
        assert_int_equal(tu_model_from_desc(&d, &m), FS_OK);
        assert_int_equal(dmpfx_from_model(&m, &fxm), FS_OK);
        const double gss[] = {1.0, 1.5};
        for (size_t g = 0; g < 2; g++) {
            const long rows = 17000;
            assert_int_equal(rollout_fx(&fxm, gss[g], 1.0, rows, f_fx), 0u);
            rollout_double(&m, gss[g], 1.0, rows, f_ref);
            const double e = rel_err(f_fx, f_ref, rows);
            printf("fixed vs float64  synthetic 17 s N=50 k=%-6g g=%g  %.4f %%\n", ks[k], gss[g],
                   100.0 * e);
            assert_true(e <= FIXED_TOL_REL);
        }
    }
}

/* S(u) in fixed point against the double blend (h = g v S with g = v = 1). Inside the kernel
 * span [0, c_N] the cutoff (16 here, 23 in the float core) drops only kernels with relative
 * activation <= exp(-16 + e_min), e_min < 2: agreement to the exp table's accuracy. Beyond c_N
 * (the phase after the skill, where v~ -> 0 and h with it) e_min grows and the cut kernels
 * weigh more: asserted looser there. */
static void test_blend(void **state)
{
    (void)state;
    load_fixed("engrave_n50_ridge_release.skill");
    double wmax = 0.0;
    for (uint16_t i = 0; i < skill.dmp.n_kernels; i++) {
        wmax = fmax(wmax, fabs(skill.dmp.weight[i]));
    }
    const double c_last = skill.dmp.centre[skill.dmp.n_kernels - 1u];
    double worst_in = 0.0;
    double worst_out = 0.0;
    uint16_t most = 0;
    for (int k = 0; k <= 20000; k++) {
        const double u = 1.05 * k / 20000.0;
        int32_t u_q30;
        assert_int_equal(fx_from_double(u, 30u, INT32_MAX, &u_q30), FS_OK);
        uint16_t cnt = 0;
        const double s_fx = fx_to_double(dmpfx_blend(&fxm, u_q30, &cnt), 24u);
        const double s_d = dmp_forcing(&skill.dmp, fx_to_double(u_q30, 30u), 1.0, 1.0);
        if (u <= c_last) {
            worst_in = fmax(worst_in, fabs(s_fx - s_d));
        } else {
            worst_out = fmax(worst_out, fabs(s_fx - s_d));
        }
        most = (cnt > most) ? cnt : most;
    }
    printf("blend: max |S_fx - S_double| / max|w| = %.2e in [0, c_N], %.2e beyond; at most %u "
           "kernels per tick\n",
           worst_in / wmax, worst_out / wmax, most);
    assert_true(worst_in <= 2e-6 * wmax);
    assert_true(worst_out <= 2e-4 * wmax); /* 7.9e-5: the last kernels sit closer together */
    assert_true(most <= 10u);              /* 9: kernels denser where the force bends */
}

/* dmpfx_prepare and dmp_prepare between steps (the blend computed after a tick's write for the
 * next) leave every step's output and state bit for bit as without them, with and without a y
 * DMP and with a coupling that slows the phase; a prepared blend is taken once, and not by a
 * step at another phase. */
static void test_prepare_same(void **state)
{
    (void)state;
    static const char *const names[] = {"engrave_n50_ridge_release.skill",
                                        "wipe_n50_ridge_release.skill"};
    for (unsigned k = 0u; k < sizeof names / sizeof names[0]; k++) {
        load_fixed(names[k]);
        dmpfx_run_t run;
        assert_int_equal(dmpfx_run_init(&fxm, 1.2, 1.1, &run), FS_OK);
        assert_int_equal(dmpfx_run_path(&fxm, 1.0, &run), FS_OK);
        dmpfx_state_t a;
        dmpfx_state_t b;
        dmpfx_state_reset(&a);
        dmpfx_state_reset(&b);
        const long rows = lround(skill.dmp.duration_s / skill.dmp.dt_s);
        for (long i = 0; i < rows; i++) {
            /* a slowed phase over some ticks: the coupling changes the step, not the blend */
            const dmpfx_coupling_t c = {0, (i % 7 == 3) ? 0x40000000u : FX_Q31_ONE_U};
            int32_t pa = 0;
            int32_t pb = 0;
            const int32_t fa = dmpfx_step_xy(&fxm, &run, &a, &c, &pa);
            dmpfx_prepare(&fxm, &b);
            const int32_t fb = dmpfx_step_xy(&fxm, &run, &b, &c, &pb);
            assert_int_equal(fa, fb);
            assert_int_equal(pa, pb);
            assert_true(a.u_acc == b.u_acc && a.v_acc == b.v_acc && a.y_acc == b.y_acc &&
                        a.z_acc == b.z_acc && a.integral_y_acc == b.integral_y_acc &&
                        a.path_acc == b.path_acc && a.path_z_acc == b.path_z_acc);
            assert_int_equal(a.sat_events, b.sat_events);
            assert_null(b.prep_model); /* taken */
        }
    }
    /* the real core's dmp_prepare (the float64 build here, the M4F's float32 the same code) */
    for (unsigned k = 0u; k < sizeof names / sizeof names[0]; k++) {
        load_fixed(names[k]);
        const dmp_run_t run = {FS_R(1.2), FS_R(1.1)};
        const dmp_coupling_t cpl = {FS_R(0.0), FS_R(0.25)};
        dmp_state_t a;
        dmp_state_t b;
        dmp_state_reset(&a);
        dmp_state_reset(&b);
        const long rows = lround(skill.dmp.duration_s / skill.dmp.dt_s);
        for (long i = 0; i < rows; i++) {
            const dmp_coupling_t *c = (i % 7 == 3) ? &cpl : NULL;
            fs_real_t pa = FS_R(0.0);
            fs_real_t pb = FS_R(0.0);
            const fs_real_t fa = dmp_step_xy(&skill.dmp, &a, &run, c, FS_R(1.0), &pa);
            dmp_prepare(&skill.dmp, &b);
            const fs_real_t fb = (skill.dmp.has_y == 0u)
                                     ? dmp_step(&skill.dmp, &b, &run, c)
                                     : dmp_step_xy(&skill.dmp, &b, &run, c, FS_R(1.0), &pb);
            assert_memory_equal(&fa, &fb, sizeof fa);
            if (skill.dmp.has_y != 0u) {
                assert_memory_equal(&pa, &pb, sizeof pa);
            }
            assert_true(a.u == b.u && a.v == b.v && a.y_N == b.y_N && a.z == b.z &&
                        a.integral_y == b.integral_y && a.path_m == b.path_m);
            assert_null(b.prep_model);
        }
    }
    /* prepared at one phase, stepped at another: the step computes its own blend */
    load_fixed("engrave_n50_ridge_release.skill");
    dmpfx_run_t run;
    assert_int_equal(dmpfx_run_init(&fxm, 1.0, 1.0, &run), FS_OK);
    dmpfx_state_t a;
    dmpfx_state_t b;
    dmpfx_state_reset(&a);
    for (int i = 0; i < 400; i++) {
        (void)dmpfx_step(&fxm, &run, &a, NULL);
    }
    b = a;
    dmpfx_prepare(&fxm, &b); /* at the phase before the next step */
    (void)dmpfx_step(&fxm, &run, &a, NULL);
    assert_true(dmpfx_view(a.u_acc) != b.prep_u);
    dmpfx_state_t c = a;
    c.prep_model = b.prep_model;
    c.prep_u = b.prep_u;
    c.prep_s = b.prep_s + 12345; /* a blend of another phase, never to be taken */
    assert_int_equal(dmpfx_step(&fxm, &run, &c, NULL), dmpfx_step(&fxm, &run, &a, NULL));
}

/* A periodic model's reach pass (an arcsine and a square root a kernel) counts
 * SKILL_PARSE_REACH_UNITS (2) parse units: parsed two units a call, each call that starts in it does
 * one unit's kernels (two units would do twice as many), and the result is skill_parse's. */
static void test_parse_reach_units(void **state)
{
    (void)state;
    static skill_t sliced;
    const uint32_t len = tv_read("periodic_n20_ridge.skill", image, sizeof(image));
    assert_true(len > 0u);
    memset(&skill, 0, sizeof skill);
    assert_int_equal(skill_parse(image, len, &skill), FS_OK);
    memset(&sliced, 0, sizeof sliced);
    skill_parser_t p;
    skill_parse_begin(&p, image, len, &sliced);
    uint32_t reach_calls = 0u;
    bool done = false;
    while (!done) {
        reach_calls += dmp_model_init_next_is_reach(&sliced.dmp, &p.init) ? 1u : 0u;
        done = skill_parse_run(&p, 2u);
    }
    assert_int_equal(p.status, FS_OK);
    assert_memory_equal(&skill, &sliced, sizeof skill);
    const uint32_t k = SKILL_PARSE_INIT_PERIODIC_KERNELS;
    assert_int_equal(reach_calls, (skill.dmp.n_kernels + k - 1u) / k);
}

static void test_rejects(void **state)
{
    (void)state;
    static tu_skill_desc_t d;
    static dmp_model_t m;
    dmpfx_run_t run;
    /* a (dimensionless) weight that does not fit the Q8.24 headroom */
    tu_default_desc(&d, 50, 280.0, 2.0);
    d.weight[17] = 200.0;
    assert_int_equal(tu_model_from_desc(&d, &m), FS_OK);
    assert_int_equal(dmpfx_from_model(&m, &fxm), FS_ERR_FIXED_OVERFLOW);
    /* a goal beyond the largest value scale (64 * 2^18 N) */
    tu_default_desc(&d, 50, 280.0, 2.0);
    d.goal_N = 1.0e8;
    assert_int_equal(tu_model_from_desc(&d, &m), FS_OK);
    assert_int_equal(dmpfx_from_model(&m, &fxm), FS_ERR_FIXED_OVERFLOW);
    /* a starting force beyond Q16.16 */
    tu_default_desc(&d, 50, 280.0, 2.0);
    d.force0_N = 1.0e5;
    assert_int_equal(tu_model_from_desc(&d, &m), FS_OK);
    assert_int_equal(dmpfx_from_model(&m, &fxm), FS_ERR_FIXED_OVERFLOW);
    /* small and large forces are scaled by a power of two: both convert */
    tu_default_desc(&d, 50, 280.0, 2.0);
    d.goal_N = 0.05;
    assert_int_equal(tu_model_from_desc(&d, &m), FS_OK);
    assert_int_equal(dmpfx_from_model(&m, &fxm), FS_OK);
    assert_true(fxm.value_shift < 0);
    d.goal_N = 5.0e3;
    assert_int_equal(tu_model_from_desc(&d, &m), FS_OK);
    assert_int_equal(dmpfx_from_model(&m, &fxm), FS_OK);
    assert_true(fxm.value_shift > 10);
    /* accepted at 1x, refused at a goal scale that would overflow */
    tu_default_desc(&d, 50, 280.0, 2.0);
    assert_int_equal(tu_model_from_desc(&d, &m), FS_OK);
    assert_int_equal(dmpfx_from_model(&m, &fxm), FS_OK);
    assert_int_equal(dmpfx_run_init(&fxm, 1.5, 1.0, &run), FS_OK);
    assert_int_equal(dmpfx_run_init(&fxm, 1000.0, 1.0, &run), FS_ERR_FIXED_OVERFLOW);
    assert_int_equal(dmpfx_run_init(&fxm, 1.0, 0.0, &run), FS_ERR_SCALE_INVALID);
    assert_int_equal(dmpfx_run_init(&fxm, NAN, 1.0, &run), FS_ERR_SCALE_INVALID);
    /* the stiffness is not part of the DMP: 1e7 N/m converts like any other */
    tu_default_desc(&d, 50, 1.0e7, 2.0);
    assert_int_equal(tu_model_from_desc(&d, &m), FS_OK);
    assert_int_equal(dmpfx_from_model(&m, &fxm), FS_OK);
    /* kernels narrower than Q13.19 can hold (1/sigma >= 4096) */
    tu_default_desc(&d, 50, 280.0, 2.0);
    d.width[30] = 1.0e-4;
    assert_int_equal(tu_model_from_desc(&d, &m), FS_OK);
    assert_int_equal(dmpfx_from_model(&m, &fxm), FS_ERR_FIXED_OVERFLOW);
    /* kernels so wide that all 50 overlap: the per-tick window would be unbounded */
    tu_default_desc(&d, 50, 280.0, 2.0);
    for (int i = 0; i < 50; i++) {
        d.width[i] = 0.5;
    }
    assert_int_equal(tu_model_from_desc(&d, &m), FS_OK);
    assert_int_equal(dmpfx_from_model(&m, &fxm), FS_ERR_FIXED_WINDOW);
    /* a skill so long that dt/tau is below 2^-24 */
    tu_default_desc(&d, 50, 280.0, 3000.0);
    assert_int_equal(tu_model_from_desc(&d, &m), FS_OK);
    assert_int_equal(dmpfx_from_model(&m, &fxm), FS_OK);
    assert_int_equal(dmpfx_run_init(&fxm, 1.0, 1.0e4, &run), FS_ERR_FIXED_STEP);
    assert_int_equal(dmpfx_from_model(NULL, &fxm), FS_ERR_NULL_ARG);
}

/* Coupling: constant phase slow-down and additive term, against the double core. */
static void test_coupling(void **state)
{
    (void)state;
    load_fixed("press_n50_ridge_release.skill");
    dmpfx_run_t run;
    assert_int_equal(dmpfx_run_init(&fxm, 1.0, 1.0, &run), FS_OK);
    const double slow = 0.6;
    const double term = 0.4; /* N */
    dmpfx_coupling_t cfx;
    assert_int_equal(fx_from_double(ldexp(term, -fxm.value_shift), 24u, INT32_MAX, &cfx.term_y_q24),
                     FS_OK);
    cfx.rate_q31 = (uint32_t)floor(ldexp(1.0 / (1.0 + slow), 31) + 0.5);
    const dmp_coupling_t cd = {term, slow};
    const dmp_run_t rd = {1.0, 1.0};
    dmpfx_state_t sf;
    dmp_state_t sd;
    dmpfx_state_reset(&sf);
    dmp_state_reset(&sd);
    const long rows = 2500;
    f_fx[0] = 0.0;
    f_ref[0] = 0.0;
    for (long i = 1; i <= rows; i++) {
        f_fx[i] = fx_to_double(dmpfx_step(&fxm, &run, &sf, &cfx), 16u);
        f_ref[i] = dmp_step(&skill.dmp, &sd, &rd, &cd);
    }
    const double e = rel_err(f_fx, f_ref, rows);
    printf("coupling (slow-down %.1f, term %.3f): fixed vs float64 %.4f %%\n", slow, term,
           100.0 * e);
    assert_true(e <= FIXED_TOL_REL);
    assert_true(fabs(fx_to_double(dmpfx_view(sf.u_acc), 30u) - sd.u) < 1e-5);
}

/* Forced far outside the validated range (bypassing dmpfx_run_init): every state saturates,
 * nothing wraps (UBSan would abort on signed overflow), and the saturations are counted. */
static void test_saturation_never_wraps(void **state)
{
    (void)state;
    load_fixed("press_n50_ridge_release.skill");
    dmpfx_run_t run;
    assert_int_equal(dmpfx_run_init(&fxm, 1.0, 1.0, &run), FS_OK);
    const int32_t goals[] = {INT32_MAX, INT32_MIN};
    for (size_t k = 0; k < 2; k++) {
        run.goal_q24 = goals[k];
        run.k1_q31 = run.k_alpha_q31 = run.k_alphabeta_q31 = run.k_gamma_q31 = INT32_MAX / 2;
        dmpfx_state_t s;
        dmpfx_state_reset(&s);
        int32_t x_abs_max = 0;
        for (int i = 0; i < 5000; i++) {
            (void)dmpfx_step(&fxm, &run, &s, NULL);
            const int64_t accs[] = {s.u_acc, s.v_acc, s.integral_y_acc, s.y_acc, s.z_acc};
            for (size_t j = 0; j < 5; j++) {
                const int32_t a = fx_abs_sat(dmpfx_view(accs[j]));
                x_abs_max = (a > x_abs_max) ? a : x_abs_max;
            }
        }
        printf("forced saturation (g = %s): %u events, max |state| %d LSB\n",
               k == 0 ? "max" : "min", s.sat_events, x_abs_max);
        assert_true(s.sat_events > 0u);
        /* the accumulators are clamped to +-(2^30 - 1)*2^32: the views reach the rail, never wrap */
        assert_true(x_abs_max >= INT32_MAX - 2);
        assert_true(x_abs_max <= INT32_MAX - 1);
    }
}

/* Periodic rollout rows n = 0..rows in N, fixed point (by_bound: the executor's conversion) and
 * the float64 core; returns the fixed run's saturation count. */
static uint32_t rollout_periodic_fx(const dmpfx_model_t *m, const double sc[3], long rows,
                                    double *out)
{
    dmpfx_run_t run;
    assert_int_equal(dmpfx_run_init(m, sc[0], sc[2], &run), FS_OK);
    assert_int_equal(dmpfx_run_periodic(m, sc[1], &run), FS_OK);
    dmpfx_state_t s;
    dmpfx_periodic_reset(m, &run, &s);
    out[0] = fx_to_double(m->force0_q16, 16u) +
             ldexp((double)run.goal_q24 + (double)dmpfx_view(s.y_acc), m->value_shift - 24);
    for (long i = 1; i <= rows; i++) {
        out[i] = fx_to_double(dmpfx_periodic_step(m, &run, &s, NULL), 16u);
    }
    return s.sat_events;
}

static void rollout_periodic_double(const dmp_model_t *m, const double sc[3], long rows,
                                    double *out)
{
    const dmp_run_t run = {sc[0], sc[2]};
    dmp_state_t s;
    dmp_periodic_reset(m, &s, sc[1]);
    out[0] = m->force0_N + sc[0] * m->goal_N + s.y_N;
    for (long i = 1; i <= rows; i++) {
        out[i] = dmp_periodic_step(m, &s, &run, sc[1], NULL);
    }
}

static void test_golden_periodic(void **state)
{
    (void)state;
    char mpath[512];
    snprintf(mpath, sizeof(mpath), "%s/manifest_periodic.txt", FS_VECTORS_DIR);
    FILE *mf = fopen(mpath, "r");
    assert_non_null(mf);
    char sk[256];
    char csv[256];
    double sc[3];
    double cycles;
    int lines = 0;
    double worst = 0.0;
    static dmpfx_model_t fxb;
    while (fscanf(mf, "%255s %lf %lf %lf %lf %255s", sk, &sc[0], &sc[1], &sc[2], &cycles, csv) ==
           6) {
        load_fixed(sk);
        assert_int_equal(fxm.periodic, 1u);
        assert_int_equal(dmpfx_from_model_bound(&skill.dmp, &fxb), FS_OK);
        const long rows = lround(cycles * skill.dmp.duration_s * sc[2] / skill.dmp.dt_s);
        assert_true(rows <= MAX_ROWS);
        rollout_periodic_double(&skill.dmp, sc, rows, f_ref);
        assert_int_equal(rollout_periodic_fx(&fxm, sc, rows, f_fx), 0u);
        const double e_core = rel_err(f_fx, f_ref, rows);
        assert_int_equal(rollout_periodic_fx(&fxb, sc, rows, f_fx), 0u);
        const double e_bound = rel_err(f_fx, f_ref, rows);
        char cpath[512];
        snprintf(cpath, sizeof(cpath), "%s/%s", FS_VECTORS_DIR, csv);
        FILE *cf = fopen(cpath, "r");
        assert_non_null(cf);
        char line[128];
        assert_non_null(fgets(line, sizeof(line), cf));
        long n = 0;
        double t;
        double f;
        while (fscanf(cf, "%lf,%lf", &t, &f) == 2) {
            assert_true(n <= rows);
            f_ref[n++] = f;
        }
        fclose(cf);
        assert_int_equal(n, rows + 1);
        (void)rollout_periodic_fx(&fxm, sc, rows, f_fx);
        const double e_py = rel_err(f_fx, f_ref, rows);
        printf("fixed vs float64 periodic %-26s g=%-3g a=%-3g t=%-3g c=%-3g core %.4f %% python "
               "%.4f %% (bound conversion s=%d vs %d: %.4f %%, peak %.2f of the bound's)\n",
               sk, sc[0], sc[1], sc[2], cycles, 100.0 * e_core, 100.0 * e_py, fxb.value_shift,
               fxm.value_shift, 100.0 * e_bound,
               ldexp(fxm.peak_q24, fxm.value_shift) / ldexp(fxb.peak_q24, fxb.value_shift));
        assert_true(e_core <= FIXED_TOL_REL && e_py <= FIXED_TOL_REL && e_bound <= FIXED_TOL_REL);
        assert_true(ldexp(fxm.peak_q24, fxm.value_shift) <= ldexp(fxb.peak_q24, fxb.value_shift));
        worst = fmax(worst, fmax(e_core, fmax(e_py, e_bound)));
        lines++;
    }
    fclose(mf);
    assert_true(lines >= 5);
    printf("fixed vs float64 periodic: worst over %d golden vectors %.4f %% of max force\n", lines,
           100.0 * worst);
}

/* One periodic rollout with the y path (scales goal, amplitude, time, path in sc) in fixed
 * point: f_hat into f, y_hat = y_start + p into y; returns the saturation count. */
static uint32_t rollout_periodic_y_fx(const dmpfx_model_t *m, const double sc[4], long rows,
                                      double *f, double *y)
{
    dmpfx_run_t run;
    assert_int_equal(dmpfx_run_init(m, sc[0], sc[2], &run), FS_OK);
    assert_int_equal(dmpfx_run_periodic(m, sc[1], &run), FS_OK);
    assert_int_equal(dmpfx_run_path(m, sc[3], &run), FS_OK);
    dmpfx_state_t s;
    dmpfx_periodic_reset(m, &run, &s);
    const double y0 = (double)skill.dmp.y_start_m;
    f[0] = fx_to_double(m->force0_q16, 16u) +
           ldexp((double)run.goal_q24 + (double)dmpfx_view(s.y_acc), m->value_shift - 24);
    y[0] = y0 + ldexp((double)run.goal_y_q24 + (double)dmpfx_view(s.path_acc), -24);
    for (long i = 1; i <= rows; i++) {
        int32_t p = 0;
        f[i] = fx_to_double(dmpfx_periodic_step_xy(m, &run, &s, NULL, &p), 16u);
        y[i] = y0 + fx_to_double(p, 24u);
    }
    return s.sat_events;
}

/* The same rollout in the float64 core (dmp_periodic_step_xy). */
static void rollout_periodic_y_double(const dmp_model_t *m, const double sc[4], long rows,
                                      double *f, double *y)
{
    const dmp_run_t run = {sc[0], sc[2]};
    dmp_state_t s;
    dmp_periodic_reset_xy(m, &s, sc[1], sc[3]);
    f[0] = m->force0_N + sc[0] * m->goal_N + s.y_N;
    y[0] = m->y_start_m + sc[3] * m->goal_y_m + s.path_m;
    for (long i = 1; i <= rows; i++) {
        double p = 0.0;
        f[i] = dmp_periodic_step_xy(m, &s, &run, sc[1], NULL, sc[3], &p);
        y[i] = m->y_start_m + p;
    }
}

/* max |a - b| over rows 0..rows relative to max |b - y0| (the path's extent). */
static double path_err(const double *a, const double *b, long rows, double y0)
{
    double e = 0.0;
    double p_max = 0.0;
    for (long i = 0; i <= rows; i++) {
        e = fmax(e, fabs(a[i] - b[i]));
        p_max = fmax(p_max, fabs(b[i] - y0));
    }
    return e / p_max;
}

static double f_py[MAX_ROWS + 1];
static double y_py[MAX_ROWS + 1];

/* The periodic skills with the y path (manifest_periodic_y.txt): dmpfx_periodic_step_xy against
 * the float64 core and the Python rollout, force and path, the discrete y path's tolerance. */
static void test_golden_periodic_y(void **state)
{
    (void)state;
    FILE *mf = open_manifest("manifest_periodic_y.txt");
    char sk[256];
    char csv[256];
    double sc[4];
    double cycles;
    int lines = 0;
    while (fscanf(mf, "%255s %lf %lf %lf %lf %lf %255s", sk, &sc[0], &sc[1], &sc[2], &cycles,
                  &sc[3], csv) == 7) {
        load_fixed(sk);
        assert_int_equal(fxm.periodic, 1u);
        assert_int_equal(fxm.has_y, 1u);
        const long rows = lround(cycles * skill.dmp.duration_s * sc[2] / skill.dmp.dt_s);
        assert_true(rows <= MAX_ROWS);
        rollout_periodic_y_double(&skill.dmp, sc, rows, f_ref, y_ref);
        assert_int_equal(rollout_periodic_y_fx(&fxm, sc, rows, f_fx, y_fx), 0u);
        const double y0 = (double)skill.dmp.y_start_m;
        const double ef_core = rel_err(f_fx, f_ref, rows);
        const double ey_core = path_err(y_fx, y_ref, rows, y0);
        char cpath[512];
        snprintf(cpath, sizeof(cpath), "%s/%s", FS_VECTORS_DIR, csv);
        FILE *cf = fopen(cpath, "r");
        assert_non_null(cf);
        char line[128];
        assert_non_null(fgets(line, sizeof(line), cf)); /* t,f_hat,y_hat */
        long n = 0;
        double t;
        double f;
        double y;
        while (fscanf(cf, "%lf,%lf,%lf", &t, &f, &y) == 3) {
            assert_true(n <= rows);
            f_py[n] = f;
            y_py[n++] = y;
        }
        fclose(cf);
        assert_int_equal(n, rows + 1);
        const double ef_py = rel_err(f_fx, f_py, rows);
        const double ey_py = path_err(y_fx, y_py, rows, y0);
        printf("fixed periodic y %-24s g=%-3g a=%-3g t=%-3g c=%-3g p=%-3g vs float64 force %.5f %% "
               "path %.5f %%, vs python force %.5f %% path %.5f %%\n",
               sk, sc[0], sc[1], sc[2], cycles, sc[3], 100.0 * ef_core, 100.0 * ey_core,
               100.0 * ef_py, 100.0 * ey_py);
        assert_true(ef_core <= FIXED_TOL_REL && ey_core <= FIXED_TOL_REL);
        assert_true(ef_py <= FIXED_TOL_REL && ey_py <= FIXED_TOL_REL);
        lines++;
    }
    fclose(mf);
    assert_true(lines >= 3);
}

/* The fixed blend against the double one at 2000 phases of a cycle, every periodic skill. */
static void test_periodic_blend(void **state)
{
    (void)state;
    static const char *const names[] = {"periodic_n20_ridge.skill", "periodic_n50_lwr.skill",
                                        "periodic_n50_ridge.skill"};
    for (size_t k = 0u; k < sizeof(names) / sizeof(names[0]); k++) {
        load_fixed(names[k]);
        double e = 0.0;
        double w = 0.0;
        for (int i = 0; i < 2000; i++) {
            const double x = (double)i / 2000.0;
            const double s_d = dmp_periodic_blend_full(&skill.dmp, x);
            const int32_t x_q = (int32_t)lround(ldexp(x, 30));
            const double s_f = ldexp((double)dmpfx_periodic_blend(&fxm, x_q, NULL), -24);
            e = fmax(e, fabs(s_f - dmp_periodic_blend_full(&skill.dmp, ldexp((double)x_q, -30))));
            w = fmax(w, fabs(s_d));
        }
        printf("periodic blend %s: fixed vs full double %.3g of max|S|\n", names[k], e / w);
        assert_true(e / w <= 1e-5);
    }
}

/* The blend's quotient by a reciprocal (fs_num_blend_div, fs_num_blend_div2) against the exact
 * num/den over dens across [2^27 - 1, 2^32) and quotients up to +-2^30 (|w| <= 64): within
 * 2e-9 of |S| + 1 LSB; and the activation table's pairs against fx_exp2_table. */
static void test_blend_div(void **state)
{
    (void)state;
    double worst = 0.0;
    uint64_t lcg = 12345u;
    for (int i = 0; i < 200000; i++) {
        lcg = lcg * 6364136223846793005u + 1442695040888963407u;
        const uint32_t den = (uint32_t)((1u << 27) - 1u) +
                             (uint32_t)((lcg >> 16) % (0xFFFFFFFFu - ((1u << 27) - 1u)));
        lcg = lcg * 6364136223846793005u + 1442695040888963407u;
        const double s = ((double)(lcg >> 11) / 9007199254740992.0 * 2.0 - 1.0) * 1073741823.0;
        const int64_t num = (int64_t)llround(s * (double)den);
        const double exact = (double)num / (double)den;
        fs_val_t s_y;
        const fs_val_t q = fs_num_blend_div2(num, -num, den, &s_y);
        assert_int_equal(q, fs_num_blend_div(num, den));
        assert_int_equal(s_y, fs_num_blend_div(-num, den));
        worst = fmax(worst, (fabs((double)q - exact) - 1.0) / fmax(fabs(exact), 1.0));
    }
    printf("blend quotient by reciprocal: worst %.3g of |S| beyond 1 LSB\n", worst);
    assert_true(worst <= 2e-9);
    for (uint32_t k = 1u; k < (1u << FX_EXP_TABLE_BITS); k++) {
        assert_int_equal(fx_exp2_pairs[2u * k], fx_exp2_table[k]);
        assert_int_equal(fx_exp2_pairs[2u * k + 1u], fx_exp2_table[k] - fx_exp2_table[k + 1u]);
    }
    assert_int_equal(fx_exp2_pairs[0], fx_exp2_table[0] - 16u);
    assert_int_equal(fx_exp2_pairs[1], fx_exp2_table[0] - fx_exp2_table[1]);
}

/* The fixed layer's sin(pi x) and cos(pi x) (Q1.31) over [0, 1] (10^5 + 1 phases) against libm. */
static void test_sincos_pi(void **state)
{
    (void)state;
    double e = 0.0;
    for (int i = 0; i <= 100000; i++) {
        const int32_t x = (int32_t)lround(ldexp((double)i / 100000.0, 30));
        int32_t sq;
        int32_t cq;
        fs_num_sincos_pi(x, &sq, &cq);
        const double xd = ldexp((double)x, -30);
        e = fmax(e, fabs(ldexp((double)sq, -31) - sin(3.141592653589793 * xd)));
        e = fmax(e, fabs(ldexp((double)cq, -31) - cos(3.141592653589793 * xd)));
    }
    printf("fixed sin/cos(pi x): max error %.3g\n", e);
    assert_true(e <= 5e-9);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_golden_vectors),
        cmocka_unit_test(test_golden_vectors_y),
        cmocka_unit_test(test_golden_periodic),
        cmocka_unit_test(test_golden_periodic_y),
        cmocka_unit_test(test_periodic_blend),
        cmocka_unit_test(test_sincos_pi),
        cmocka_unit_test(test_blend_div),
        cmocka_unit_test(test_long_skill),
        cmocka_unit_test(test_bound_conversion),
        cmocka_unit_test(test_commit_path),
        cmocka_unit_test(test_blend),
        cmocka_unit_test(test_prepare_same),
        cmocka_unit_test(test_parse_reach_units),
        cmocka_unit_test(test_rejects),
        cmocka_unit_test(test_coupling),
        cmocka_unit_test(test_saturation_never_wraps),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

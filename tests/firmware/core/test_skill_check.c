/* Device-side skill validation (skill_check.h): the peak of the skill's own rollout equals the
 * maximum of the Python reference rollout (tests/vectors/NAME_g1_t1.csv, written by
 * host/forceskill with numpy, independent of this code); hostile but well-formed skills are
 * refused with their 22x code; the incremental check gives the one-shot result whatever the
 * budget per call; the run-time goal-scale rule is exact at the limit. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "skill_check.h"

#ifdef FS_REAL_FLOAT
#define PEAK_REL_TOL 1e-4
#else
#define PEAK_REL_TOL 1e-9
#endif

static uint8_t image[16384];
static skill_t skill;

static void load_skill(const char *name)
{
    char path[512];
    snprintf(path, sizeof path, "%s/%s.skill", FS_VECTORS_DIR, name);
    FILE *f = fopen(path, "rb");
    assert_non_null(f);
    const size_t n = fread(image, 1, sizeof image, f);
    fclose(f);
    assert_int_equal(skill_parse(image, (uint32_t)n, &skill), FS_OK);
}

/* max |f_hat| of the reference rollout over the skill's duration */
static double reference_peak(const char *name, double duration_s)
{
    char path[512];
    snprintf(path, sizeof path, "%s/%s_g1_t1.csv", FS_VECTORS_DIR, name);
    FILE *f = fopen(path, "r");
    assert_non_null(f);
    char line[256];
    assert_non_null(fgets(line, sizeof line, f)); /* header */
    double peak = 0.0;
    while (fgets(line, sizeof line, f) != NULL) {
        double t = 0.0, v = 0.0;
        assert_int_equal(sscanf(line, "%lf,%lf", &t, &v), 2);
        if (t <= duration_s + 1e-9 && fabs(v) > peak) {
            peak = fabs(v);
        }
    }
    fclose(f);
    return peak;
}

static void test_peak_matches_reference(void **state)
{
    (void)state;
    static const char *names[] = {"press_n50_lwr_hold", "engrave_n50_ridge_release",
                                  "press_n100_ridge_hold", "engrave_n10_lwr_hold"};
    for (unsigned i = 0; i < sizeof names / sizeof names[0]; i++) {
        load_skill(names[i]);
        fs_real_t peak = FS_R(0.0);
        assert_int_equal(skchk_skill(&skill, FS_R(0.001), FS_R(50.0), &peak), FS_OK);
        const double ref = reference_peak(names[i], (double)skill.dmp.duration_s);
        print_message("%s: peak %.9f N, reference %.9f N\n", names[i], (double)peak, ref);
        assert_true(ref > 1.0);
        assert_true(fabs((double)peak - ref) <= PEAK_REL_TOL * ref);
        /* a limit just below the peak refuses it */
        assert_int_equal(skchk_skill(&skill, FS_R(0.001), peak * FS_R(0.999), NULL),
                         FS_ERR_SKCHK_PEAK);
    }
}

/* skchk_params gives code, and so does its sliced form at one unit a call (the scalars, then
 * SKCHK_PARAMS_KERNELS_PER_UNIT kernels a unit, the y part, the step rule). */
static void expect_params(const skill_t *s, fs_status_t code)
{
    assert_int_equal(skchk_params(s), code);
    skchk_params_t c;
    skchk_params_begin(&c, s);
    uint32_t units = 1u;
    while (!skchk_params_run(&c, 1u)) {
        units++;
    }
    assert_int_equal(c.status, code);
    if (code == FS_OK) {
        const uint32_t per = (s->dmp.n_kernels + SKCHK_PARAMS_KERNELS_PER_UNIT - 1u) /
                             SKCHK_PARAMS_KERNELS_PER_UNIT;
        assert_int_equal(units, 2u + per * ((s->dmp.has_y != 0u) ? 2u : 1u) +
                                    ((s->dmp.has_y != 0u) ? 1u : 0u));
    }
}

static void test_hostile_skills_refused(void **state)
{
    (void)state;
    load_skill("press_n50_lwr_hold");
    const skill_t good = skill;
    skill.dmp.weight[3] *= FS_R(1e30);
    expect_params(&skill, FS_ERR_SKCHK_RANGE);
    skill = good;
    skill.dmp.goal_N = FS_R(1e30);
    expect_params(&skill, FS_ERR_SKCHK_RANGE);
    skill = good;
    skill.dmp.tau_s = FS_R(1e-9);
    expect_params(&skill, FS_ERR_SKCHK_RANGE);
    skill = good;
    skill.dmp.tau_s = FS_R(0.005); /* in range, but dt*rate/tau = 2.5 */
    expect_params(&skill, FS_ERR_SKCHK_STEP);
    skill = good;
    skill.dmp.duration_s = FS_R(601.0);
    expect_params(&skill, FS_ERR_SKCHK_RANGE);
    skill = good;
    skill.dmp.width[0] = FS_R(1e-7);
    expect_params(&skill, FS_ERR_SKCHK_RANGE);
    skill = good;
    skill.dmp.width[skill.dmp.n_kernels - 1u] = FS_R(2.0); /* the last kernel's unit */
    expect_params(&skill, FS_ERR_SKCHK_RANGE);
    /* in range, but weights x100: the rollout peaks far above 50 N */
    skill = good;
    for (uint16_t i = 0; i < skill.dmp.n_kernels; i++) {
        skill.dmp.weight[i] *= FS_R(100.0);
    }
    expect_params(&skill, FS_OK);
    assert_int_equal(skchk_skill(&skill, FS_R(0.001), FS_R(50.0), NULL), FS_ERR_SKCHK_PEAK);
    assert_int_equal(skchk_params(NULL), FS_ERR_NULL_ARG);
}

static void test_incremental_equals_one_shot(void **state)
{
    (void)state;
    load_skill("engrave_n50_ridge_release");
    fs_real_t one = FS_R(0.0);
    assert_int_equal(skchk_skill(&skill, FS_R(0.001), FS_R(50.0), &one), FS_OK);
    static const uint32_t budgets[] = {1u, 7u, 100u, 5000u};
    for (unsigned b = 0; b < 4u; b++) {
        skchk_t c;
        skchk_begin(&c, &skill, FS_R(0.001), FS_R(50.0));
        unsigned calls = 0u;
        while (!skchk_run(&c, budgets[b])) {
            calls++;
        }
        assert_int_equal(c.status, FS_OK);
        assert_int_equal(c.steps_done, 2000u); /* T = 2 s at 1 ms */
        assert_true(c.peak_N == one);
        assert_int_equal(calls + 1u, (2000u + budgets[b] - 1u) / budgets[b]);
    }
}

static void test_run_scales(void **state)
{
    (void)state;
    load_skill("press_n50_lwr_hold");
    fs_real_t peak = FS_R(0.0);
    assert_int_equal(skchk_skill(&skill, FS_R(0.001), FS_R(50.0), &peak), FS_OK);
    const fs_real_t g_max = FS_R(50.0) / peak;
    assert_int_equal(
        skchk_run_scales(&skill, peak, g_max * FS_R(0.999), FS_R(1.0), FS_R(0.001), FS_R(50.0)),
        FS_OK);
    assert_int_equal(
        skchk_run_scales(&skill, peak, g_max * FS_R(1.001), FS_R(1.0), FS_R(0.001), FS_R(50.0)),
        FS_ERR_SKCHK_GOAL_SCALE);
    assert_int_equal(skchk_run_scales(&skill, peak, FS_R(50.0), FS_R(1.0), FS_R(0.001), FS_R(50.0)),
                     FS_ERR_SKCHK_GOAL_SCALE);
    /* the goal-scaled rollout really peaks at goal_scale * peak (f_hat linear in the goal) */
    dmp_state_t s;
    dmp_state_reset(&s);
    const dmp_run_t run = {FS_R(1.5), FS_R(1.0)};
    fs_real_t p15 = FS_R(0.0);
    for (unsigned k = 0; k < 1500u; k++) {
        const fs_real_t f = fs_fabs(dmp_step(&skill.dmp, &s, &run, NULL));
        p15 = f > p15 ? f : p15;
    }
    assert_true(fabs((double)p15 - 1.5 * (double)peak) <= PEAK_REL_TOL * 10.0 * (double)p15);
    /* a time scale that makes the Euler step too coarse */
    assert_int_equal(
        skchk_run_scales(&skill, peak, FS_R(1.0), FS_R(0.002), FS_R(0.001), FS_R(50.0)),
        FS_ERR_SKCHK_STEP);
    assert_int_equal(skchk_run_scales(&skill, peak, FS_R(1.0), FS_R(0.0), FS_R(0.001), FS_R(50.0)),
                     FS_ERR_SCALE_INVALID);
}

/* The y half: the path extent of the check equals max|y_hat - y_start| of the Python rollout
 * (wipe_n50_ridge_release_g1_t1_p1.csv); a y range below it refuses the skill (225); the run's
 * path scale is refused beyond the range (226); a y weight beyond the device's range: 225. */
static void test_y_path(void **state)
{
    (void)state;
    load_skill("wipe_n50_ridge_release");
    assert_int_equal(skill.dmp.has_y, 1u);
    char path[512];
    snprintf(path, sizeof path, "%s/wipe_n50_ridge_release_g1_t1_p1.csv", FS_VECTORS_DIR);
    FILE *f = fopen(path, "r");
    assert_non_null(f);
    char line[256];
    assert_non_null(fgets(line, sizeof line, f));
    double ext = 0.0;
    const double y0 = (double)skill.dmp.y_start_m;
    while (fgets(line, sizeof line, f) != NULL) {
        double t = 0.0, v = 0.0, y = 0.0;
        assert_int_equal(sscanf(line, "%lf,%lf,%lf", &t, &v, &y), 3);
        ext = fmax(ext, fabs(y - y0));
    }
    fclose(f);
    skchk_t c;
    expect_params(&skill, FS_OK);
    skchk_begin(&c, &skill, FS_R(0.001), FS_R(50.0));
    while (!skchk_run(&c, 100u)) {
    }
    assert_int_equal(c.status, FS_OK);
    printf("path extent %.9f m, reference %.9f m\n", (double)c.path_peak_m, ext);
    assert_true(fabs((double)c.path_peak_m - ext) <= PEAK_REL_TOL * ext);
    skchk_begin(&c, &skill, FS_R(0.001), FS_R(50.0));
    c.path_max_m = (fs_real_t)(0.5 * ext);
    while (!skchk_run(&c, 100u)) {
    }
    assert_int_equal(c.status, FS_ERR_SKCHK_PATH);
    const fs_real_t pk = (fs_real_t)ext;
    assert_int_equal(skchk_run_path(&skill, pk, FS_R(2.0), (fs_real_t)(2.0 * ext * 1.001)), FS_OK);
    assert_int_equal(skchk_run_path(&skill, pk, FS_R(2.0), (fs_real_t)(1.99 * ext)),
                     FS_ERR_SKCHK_PATH_SCALE);
    assert_int_equal(skchk_run_path(&skill, pk, FS_R(-1.0), FS_R(1.0)), FS_ERR_SKCHK_PATH_SCALE);
    skill.dmp.y_weight[3] = (fs_real_t)(2.0 * SKCHK_WEIGHT_MAX);
    expect_params(&skill, FS_ERR_SKCHK_PATH);
}

static void test_stiffness_limit(void **state)
{
    (void)state;
    load_skill("press_n50_lwr_hold");
    const fs_real_t k = skill.stiffness_Npm;
    assert_true(k > FS_R(0.0));
    assert_int_equal(skchk_stiffness(&skill, k), FS_OK); /* at the limit: accepted */
    assert_int_equal(skchk_stiffness(&skill, k * FS_R(10.0)), FS_OK);
    assert_int_equal(skchk_stiffness(&skill, k * FS_R(0.999)), FS_ERR_SKCHK_STIFFNESS);
    assert_int_equal(skchk_stiffness(NULL, k), FS_ERR_NULL_ARG);
}

/* A periodic skill: the check rolls one cycle out from the cycle state; its bound |f0| + g +
 * max|e| is at or above the Python rollout's peak over a cycle and equals it exactly when the
 * deviation's extreme is a maximum (|f0| + g + max e); the run-time check scales it by the
 * larger of the goal and amplitude scales. */
static void test_periodic_cycle(void **state)
{
    (void)state;
    load_skill("periodic_n50_ridge");
    assert_int_equal(skill.dmp.periodic, 1u);
    fs_real_t peak = FS_R(0.0);
    assert_int_equal(skchk_skill(&skill, FS_R(0.001), FS_R(50.0), &peak), FS_OK);
    char path[512];
    snprintf(path, sizeof path, "%s/periodic_n50_ridge_g1_a1_t1_c2.csv", FS_VECTORS_DIR);
    FILE *f = fopen(path, "r");
    assert_non_null(f);
    char line[256];
    assert_non_null(fgets(line, sizeof line, f));
    double f_max = 0.0, e_max = 0.0;
    const double g = (double)skill.dmp.goal_N;
    while (fgets(line, sizeof line, f) != NULL) {
        double t = 0.0, v = 0.0;
        assert_int_equal(sscanf(line, "%lf,%lf", &t, &v), 2);
        f_max = fmax(f_max, fabs(v));
        e_max = fmax(e_max, fabs(v - g));
    }
    fclose(f);
    print_message("periodic: bound %.6f N, rollout peak %.6f N, g + max|e| %.6f N\n", (double)peak,
                  f_max, g + e_max);
    assert_true((double)peak >= f_max * (1.0 - 1e-6));
    assert_true(fabs((double)peak - (g + e_max)) <= 1e-4 * (g + e_max));
    const fs_real_t lim = peak * FS_R(1.5);
    assert_int_equal(
        skchk_run_scales_periodic(&skill, peak, FS_R(1.4), FS_R(1.0), FS_R(1.0), FS_R(0.001), lim),
        FS_OK);
    assert_int_equal(
        skchk_run_scales_periodic(&skill, peak, FS_R(1.0), FS_R(1.6), FS_R(1.0), FS_R(0.001), lim),
        FS_ERR_SKCHK_GOAL_SCALE);
    assert_int_equal(
        skchk_run_scales_periodic(&skill, peak, FS_R(1.0), FS_R(-1.0), FS_R(1.0), FS_R(0.001), lim),
        FS_ERR_SCALE_INVALID);
    assert_int_equal(skchk_skill(&skill, FS_R(0.001), peak * FS_R(0.999), NULL), FS_ERR_SKCHK_PEAK);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_peak_matches_reference),
        cmocka_unit_test(test_hostile_skills_refused),
        cmocka_unit_test(test_incremental_equals_one_shot),
        cmocka_unit_test(test_run_scales),
        cmocka_unit_test(test_y_path),
        cmocka_unit_test(test_stiffness_limit),
        cmocka_unit_test(test_periodic_cycle),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

/* dmp_params_from_gains: default gains and every validation code (built double and float). */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "dmp.h"

static pfc_axis_gains_t default_gains(void)
{
    pfc_config_t cfg;
    pfc_default_config(&cfg);
    return cfg.gains[0];
}

static void assert_rel(double got, double want, double rel)
{
    const double err = fabs(got - want);
    if (!(err <= rel * fabs(want))) {
        fail_msg("got %.17g want %.17g (rel err %.3g > %.3g)", got, want, err / fabs(want), rel);
    }
}

/* Defaults: alpha 9, beta 2.25 = alpha/4 for every k, gamma = k*27/(40*9) = 0.075*k. */
static void test_defaults(void **state)
{
    (void)state;
    const pfc_axis_gains_t g = default_gains();
    const double ks[] = {1.0, 100.0, 180.0, 280.0, 500.0, 600.0, 1e4, 1e6};
#ifdef FS_REAL_FLOAT
    const double rel = 1e-6;
#else
    const double rel = 1e-14;
#endif
    for (size_t i = 0; i < sizeof(ks) / sizeof(ks[0]); i++) {
        dmp_params_t p;
        assert_int_equal(dmp_params_from_gains(&g, (fs_real_t)ks[i], &p), FS_OK);
        assert_true((double)p.alpha == 9.0);
        assert_true((double)p.beta == 2.25); /* exact: the k terms cancel (see dmp.c) */
        assert_rel((double)p.gamma, 0.075 * ks[i], rel);
    }
}

typedef struct {
    const char *what;
    pfc_axis_gains_t g;
    double k;
    fs_status_t want;
} bad_case_t;

static void assert_no_nan(const dmp_params_t *p)
{
    assert_true(!isnan((double)p->alpha));
    assert_true(!isnan((double)p->beta));
    assert_true(!isnan((double)p->gamma));
}

static void test_invalid_inputs(void **state)
{
    (void)state;
    const pfc_axis_gains_t d = default_gains();
    const fs_real_t nan_r = (fs_real_t)NAN;
    const fs_real_t inf_r = (fs_real_t)INFINITY;
    bad_case_t cases[] = {
        {"m_d NaN", d, 100.0, FS_ERR_NOT_FINITE},
        {"k_i inf", d, 100.0, FS_ERR_NOT_FINITE},
        {"k NaN", d, NAN, FS_ERR_NOT_FINITE},
        {"m_d 0", d, 100.0, FS_ERR_MASS_NONPOSITIVE},
        {"m_d < 0", d, 100.0, FS_ERR_MASS_NONPOSITIVE},
        {"k 0", d, 0.0, FS_ERR_STIFFNESS_NONPOSITIVE},
        {"k < 0", d, -5.0, FS_ERR_STIFFNESS_NONPOSITIVE},
        {"k_p < 0", d, 100.0, FS_ERR_GAIN_NEGATIVE},
        {"k_f < 0", d, 100.0, FS_ERR_GAIN_NEGATIVE},
        {"k_d < 0", d, 100.0, FS_ERR_GAIN_NEGATIVE},
        {"k_d == m_d", d, 100.0, FS_ERR_KD_LE_MD},
        {"k_d < m_d", d, 100.0, FS_ERR_KD_LE_MD},
        {"beta < 0 (k_p tiny, k_f 0)", d, 100.0, FS_ERR_BETA_NONPOSITIVE},
        {"beta == 0", d, 100.0, FS_ERR_BETA_NONPOSITIVE},
        {"beta > alpha/4 (k_p large)", d, 100.0, FS_ERR_PHASE_NOT_MONOTONE},
        {"beta > alpha/4 (k_f large, k large)", d, 1000.0, FS_ERR_PHASE_NOT_MONOTONE},
        {"alpha overflows", d, 100.0, FS_ERR_NOT_FINITE},
    };
    cases[0].g.m_d_kg = nan_r;
    cases[1].g.k_i_per_s = inf_r;
    cases[3].g.m_d_kg = FS_R(0.0);
    cases[4].g.m_d_kg = FS_R(-1.0);
    cases[7].g.k_p_Npm = FS_R(-1.0);
    cases[8].g.k_f = FS_R(-0.5);
    cases[9].g.k_d_Nspm = FS_R(-400.0);
    cases[10].g.k_d_Nspm = FS_R(40.0);
    cases[11].g.k_d_Nspm = FS_R(20.0);
    cases[12].g.k_p_Npm = FS_R(10.0);
    cases[12].g.k_f = FS_R(0.0);
    cases[12].g.k_i_per_s = FS_R(0.0);
    /* beta = k_p/(m_d*alpha) - 1 = 0 exactly with k_f = k_i = 0, k_p = m_d*alpha = 360 */
    cases[13].g.k_p_Npm = FS_R(360.0);
    cases[13].g.k_f = FS_R(0.0);
    cases[13].g.k_i_per_s = FS_R(0.0);
    cases[14].g.k_p_Npm = FS_R(1200.0);
    cases[15].g.k_f = FS_R(3.01);
    /* k_d/m_d overflows: m_d tiny, k_d huge (both finite). */
#ifdef FS_REAL_FLOAT
    cases[16].g.m_d_kg = FS_R(1e-30);
    cases[16].g.k_d_Nspm = FS_R(1e30);
#else
    cases[16].g.m_d_kg = 1e-300;
    cases[16].g.k_d_Nspm = 1e300;
#endif
    for (size_t i = 0; i < sizeof(cases) / sizeof(cases[0]); i++) {
        dmp_params_t p = {(fs_real_t)NAN, (fs_real_t)NAN, (fs_real_t)NAN};
        const fs_status_t st = dmp_params_from_gains(&cases[i].g, (fs_real_t)cases[i].k, &p);
        if (st != cases[i].want) {
            fail_msg("%s: got %d want %d", cases[i].what, (int)st, (int)cases[i].want);
        }
        assert_no_nan(&p);
    }
    dmp_params_t p;
    assert_int_equal(dmp_params_from_gains(NULL, FS_R(100.0), &p), FS_ERR_NULL_ARG);
    assert_int_equal(dmp_params_from_gains(&d, FS_R(100.0), NULL), FS_ERR_NULL_ARG);
}

/* Just inside the monotone bound is accepted; the relative tolerance only absorbs round-off. */
static void test_monotone_boundary(void **state)
{
    (void)state;
    pfc_axis_gains_t g = default_gains();
    g.k_f = FS_R(0.0);
    g.k_i_per_s = FS_R(0.0);
    /* beta = k_p/360 - 1 = 2.25 exactly at k_p = 1170; 1170.5 gives beta = alpha/4 + 1.4e-3. */
    dmp_params_t p;
    g.k_p_Npm = FS_R(1170.0);
    assert_int_equal(dmp_params_from_gains(&g, FS_R(100.0), &p), FS_OK);
    g.k_p_Npm = FS_R(1170.5);
    assert_int_equal(dmp_params_from_gains(&g, FS_R(100.0), &p), FS_ERR_PHASE_NOT_MONOTONE);
    g.k_p_Npm = FS_R(1169.5);
    assert_int_equal(dmp_params_from_gains(&g, FS_R(100.0), &p), FS_OK);
}

/* g' = c/(alpha*beta), c = (k_p*x_d + k_f*f_d + k_i*int f_d)/m_d. */
static void test_goal_prime(void **state)
{
    (void)state;
    const pfc_axis_gains_t g = default_gains();
    dmp_params_t p;
    assert_int_equal(dmp_params_from_gains(&g, FS_R(280.0), &p), FS_OK);
    const double want = (1170.0 * 0.02 + 3.0 * 5.0 + 27.0 * 7.5) / 40.0 / (9.0 * 2.25);
    const fs_real_t got = dmp_goal_prime(&p, &g, FS_R(0.02), FS_R(5.0), FS_R(7.5));
#ifdef FS_REAL_FLOAT
    assert_rel((double)got, want, 1e-6);
#else
    assert_rel(got, want, 1e-15);
#endif
}

/* dmp_run_validate: scales finite, time scale > 0. */
static void test_run_validate(void **state)
{
    (void)state;
    dmp_run_t r = {FS_R(1.0), FS_R(1.0)};
    assert_int_equal(dmp_run_validate(&r), FS_OK);
    r.goal_scale = FS_R(-0.5);
    assert_int_equal(dmp_run_validate(&r), FS_OK);
    r.time_scale = FS_R(0.0);
    assert_int_equal(dmp_run_validate(&r), FS_ERR_SCALE_INVALID);
    r.time_scale = (fs_real_t)NAN;
    assert_int_equal(dmp_run_validate(&r), FS_ERR_SCALE_INVALID);
    r.time_scale = FS_R(2.0);
    r.goal_scale = (fs_real_t)INFINITY;
    assert_int_equal(dmp_run_validate(&r), FS_ERR_SCALE_INVALID);
    assert_int_equal(dmp_run_validate(NULL), FS_ERR_NULL_ARG);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_defaults),
        cmocka_unit_test(test_invalid_inputs),
        cmocka_unit_test(test_monotone_boundary),
        cmocka_unit_test(test_goal_prime),
        cmocka_unit_test(test_run_validate),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

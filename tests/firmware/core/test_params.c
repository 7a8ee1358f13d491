/* dmp_params_from_gains, dmp_gains_at_stiffness, dmp_goal: defaults and every validation code
 * (built double and float). */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "dmp.h"

static dmp_gains_t default_gains(void)
{
    const dmp_gains_t g = {FS_R(40.0), FS_R(400.0), FS_R(1170.0), FS_R(540.0), FS_R(4860.0)};
    return g;
}

static void assert_rel(double got, double want, double rel)
{
    const double err = fabs(got - want);
    if (!(err <= rel * fabs(want))) {
        fail_msg("got %.17g want %.17g (rel err %.3g > %.3g)", got, want, err / fabs(want), rel);
    }
}

/* Defaults: alpha 9, beta 2.25 = alpha/4, gamma = 4860/(40*9) = 13.5, whatever the stiffness;
 * the controller's k_f = 540/k, k_i = 4860/k (3 and 27 at 180 N/m). */
static void test_defaults(void **state)
{
    (void)state;
    const dmp_gains_t g = default_gains();
    dmp_params_t p;
    assert_int_equal(dmp_params_from_gains(&g, &p), FS_OK);
    assert_true((double)p.alpha == 9.0);
    assert_true((double)p.beta == 2.25); /* exact: the kkf and kki terms cancel (see dmp.c) */
    assert_true((double)p.gamma == 13.5);
    const double ks[] = {10.0, 100.0, 180.0, 1e4, 1e6, 1e7};
#ifdef FS_REAL_FLOAT
    const double rel = 1e-6;
#else
    const double rel = 1e-15;
#endif
    for (size_t i = 0; i < sizeof(ks) / sizeof(ks[0]); i++) {
        pfc_axis_gains_t at;
        assert_int_equal(dmp_gains_at_stiffness(&g, (fs_real_t)ks[i], &at), FS_OK);
        assert_rel((double)at.k_f, 540.0 / ks[i], rel);
        assert_rel((double)at.k_i_per_s, 4860.0 / ks[i], rel);
        assert_true(at.m_d_kg == g.m_d_kg && at.k_d_Nspm == g.k_d_Nspm && at.k_p_Npm == g.k_p_Npm);
    }
    pfc_axis_gains_t at;
    assert_int_equal(dmp_gains_at_stiffness(&g, FS_R(0.0), &at), FS_ERR_STIFFNESS_NONPOSITIVE);
    assert_int_equal(dmp_gains_at_stiffness(&g, (fs_real_t)NAN, &at), FS_ERR_NOT_FINITE);
    assert_int_equal(dmp_gains_at_stiffness(NULL, FS_R(1.0), &at), FS_ERR_NULL_ARG);
}

typedef struct {
    const char *what;
    dmp_gains_t g;
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
    const dmp_gains_t d = default_gains();
    const fs_real_t nan_r = (fs_real_t)NAN;
    const fs_real_t inf_r = (fs_real_t)INFINITY;
    bad_case_t cases[] = {
        {"m_d NaN", d, FS_ERR_NOT_FINITE},
        {"kki inf", d, FS_ERR_NOT_FINITE},
        {"m_d 0", d, FS_ERR_MASS_NONPOSITIVE},
        {"m_d < 0", d, FS_ERR_MASS_NONPOSITIVE},
        {"k_p < 0", d, FS_ERR_GAIN_NEGATIVE},
        {"kkf < 0", d, FS_ERR_GAIN_NEGATIVE},
        {"k_d < 0", d, FS_ERR_GAIN_NEGATIVE},
        {"k_d == m_d", d, FS_ERR_KD_LE_MD},
        {"k_d < m_d", d, FS_ERR_KD_LE_MD},
        {"beta < 0 (k_p tiny, kkf 0)", d, FS_ERR_BETA_NONPOSITIVE},
        {"beta == 0", d, FS_ERR_BETA_NONPOSITIVE},
        {"beta > alpha/4 (k_p large)", d, FS_ERR_PHASE_NOT_MONOTONE},
        {"beta > alpha/4 (kkf large)", d, FS_ERR_PHASE_NOT_MONOTONE},
        {"alpha overflows", d, FS_ERR_NOT_FINITE},
    };
    cases[0].g.m_d_kg = nan_r;
    cases[1].g.kki_Npms = inf_r;
    cases[2].g.m_d_kg = FS_R(0.0);
    cases[3].g.m_d_kg = FS_R(-1.0);
    cases[4].g.k_p_Npm = FS_R(-1.0);
    cases[5].g.kkf_Npm = FS_R(-0.5);
    cases[6].g.k_d_Nspm = FS_R(-400.0);
    cases[7].g.k_d_Nspm = FS_R(40.0);
    cases[8].g.k_d_Nspm = FS_R(20.0);
    cases[9].g.k_p_Npm = FS_R(10.0);
    cases[9].g.kkf_Npm = FS_R(0.0);
    cases[9].g.kki_Npms = FS_R(0.0);
    /* beta = k_p/(m_d*alpha) - 1 = 0 exactly with kkf = kki = 0, k_p = m_d*alpha = 360 */
    cases[10].g.k_p_Npm = FS_R(360.0);
    cases[10].g.kkf_Npm = FS_R(0.0);
    cases[10].g.kki_Npms = FS_R(0.0);
    cases[11].g.k_p_Npm = FS_R(1200.0);
    cases[12].g.kkf_Npm = FS_R(541.0);
    /* k_d/m_d overflows: m_d tiny, k_d huge (both finite). The float core derives in double:
     * there alpha = 1e40 is finite and valid (k_p keeps 0 < beta <= alpha/4), and only its
     * conversion to float overflows. */
#ifdef FS_REAL_FLOAT
    cases[13].g.m_d_kg = FS_R(1e-20);
    cases[13].g.k_d_Nspm = FS_R(1e20);
    cases[13].g.k_p_Npm = FS_R(1e30);
#else
    cases[13].g.m_d_kg = 1e-300;
    cases[13].g.k_d_Nspm = 1e300;
#endif
    for (size_t i = 0; i < sizeof(cases) / sizeof(cases[0]); i++) {
        dmp_params_t p = {(fs_real_t)NAN, (fs_real_t)NAN, (fs_real_t)NAN};
        const fs_status_t st = dmp_params_from_gains(&cases[i].g, &p);
        if (st != cases[i].want) {
            fail_msg("%s: got %d want %d", cases[i].what, (int)st, (int)cases[i].want);
        }
        assert_no_nan(&p);
    }
    dmp_params_t p;
    assert_int_equal(dmp_params_from_gains(NULL, &p), FS_ERR_NULL_ARG);
    assert_int_equal(dmp_params_from_gains(&d, NULL), FS_ERR_NULL_ARG);
    double abg[3];
    assert_int_equal(dmp_derive_f64(NULL, abg), FS_ERR_NULL_ARG);
}

/* Just inside the monotone bound is accepted; the relative tolerance only absorbs round-off. */
static void test_monotone_boundary(void **state)
{
    (void)state;
    dmp_gains_t g = default_gains();
    g.kkf_Npm = FS_R(0.0);
    g.kki_Npms = FS_R(0.0);
    /* beta = k_p/360 - 1 = 2.25 exactly at k_p = 1170; 1170.5 gives beta = alpha/4 + 1.4e-3. */
    dmp_params_t p;
    g.k_p_Npm = FS_R(1170.0);
    assert_int_equal(dmp_params_from_gains(&g, &p), FS_OK);
    g.k_p_Npm = FS_R(1170.5);
    assert_int_equal(dmp_params_from_gains(&g, &p), FS_ERR_PHASE_NOT_MONOTONE);
    g.k_p_Npm = FS_R(1169.5);
    assert_int_equal(dmp_params_from_gains(&g, &p), FS_OK);
}

/* g = c/(alpha*beta), c = (k_p*(k*x_d) + kkf*f_d + kki*int f_d)/m_d. */
static void test_goal(void **state)
{
    (void)state;
    const dmp_gains_t g = default_gains();
    dmp_params_t p;
    assert_int_equal(dmp_params_from_gains(&g, &p), FS_OK);
    const double want = (1170.0 * 5.6 + 540.0 * 5.0 + 4860.0 * 7.5) / 40.0 / (9.0 * 2.25);
    const fs_real_t got = dmp_goal(&p, &g, FS_R(5.6), FS_R(5.0), FS_R(7.5));
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
        cmocka_unit_test(test_goal),
        cmocka_unit_test(test_run_validate),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

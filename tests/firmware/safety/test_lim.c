/* Limits at the last stage (lim_apply), property tests with a fixed seed:
 *  1. 10^6 random requests, including NaN, +-inf, huge, denormal, and random measurements:
 *     output finite, |out| <= force_max, |out - previous| <= slew (within one rounding).
 *  2. random and hostile skills and goal scales through the real chain dmp_step -> pfc_step
 *     (with its own saturation disabled) -> lim_apply: same properties over 10^6 ticks.
 *  3. workspace, velocity, contact-force and slew-fault behaviour, configuration validation.
 * Built against fs_safety (double) and fs_safety_f32 (float). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include <float.h>
#include <cmocka.h>

#include "dmp.h"
#include "lim.h"
#include "pfc.h"
#include "vectors_io.h"
#include "skill.h"

#ifdef FS_REAL_FLOAT
#define REL_EPS (4.0 * (double)FLT_EPSILON)
#else
#define REL_EPS (4.0 * DBL_EPSILON)
#endif

static uint64_t g_rng = 0x9E3779B97F4A7C15ull;

static uint64_t next_u64(void)
{
    /* xorshift64* */
    g_rng ^= g_rng >> 12;
    g_rng ^= g_rng << 25;
    g_rng ^= g_rng >> 27;
    return g_rng * 0x2545F4914F6CDD1Dull;
}

static double uniform(double lo, double hi)
{
    return lo + (hi - lo) * ((double)(next_u64() >> 11) * (1.0 / 9007199254740992.0));
}

/* A hostile value: NaN, +-inf, huge, tiny, denormal, exactly the limit, or ordinary. */
static double hostile(double scale)
{
    switch (next_u64() % 12u) {
    case 0: return NAN;
    case 1: return INFINITY;
    case 2: return -INFINITY;
    case 3: return (next_u64() & 1u) ? DBL_MAX : -DBL_MAX;
    case 4: return uniform(-1e300, 1e300);
    case 5: return (next_u64() & 1u) ? 4.9e-324 : -4.9e-324;
    case 6: return (next_u64() & 1u) ? 50.0 : -50.0;
    case 7: return uniform(-1e6, 1e6);
    default: return uniform(-2.0 * scale, 2.0 * scale);
    }
}

typedef struct {
    uint64_t n;
    double worst_abs_N;
    double worst_slew_N;
    uint64_t nonfinite;
} stats_t;

static void check_out(const lim_config_t *cfg, const fs_real_t prev[LIM_AXES],
                      const fs_real_t out[LIM_AXES], stats_t *st)
{
    for (uint32_t i = 0; i < LIM_AXES; i++) {
        const double o = (double)out[i];
        const double fmax = (double)cfg->axis[i].force_max_N;
        const double slew = (double)cfg->axis[i].slew_max_N;
        if (!isfinite(o)) {
            st->nonfinite++;
        }
        assert_true(isfinite(o));
        assert_true(fabs(o) <= fmax);
        const double d = fabs(o - (double)prev[i]);
        assert_true(d <= slew * (1.0 + REL_EPS) + fmax * REL_EPS);
        if (fabs(o) > st->worst_abs_N) {
            st->worst_abs_N = fabs(o);
        }
        if (d > st->worst_slew_N) {
            st->worst_slew_N = d;
        }
    }
    st->n++;
}

static void test_random_hostile_requests(void **state)
{
    (void)state;
    stats_t s = {0, 0.0, 0.0, 0};
    lim_config_t cfg;
    for (uint32_t c = 0; c < 1000u; c++) {
        lim_default_config(&cfg);
        /* random valid configurations too */
        for (uint32_t i = 0; i < LIM_AXES; i++) {
            cfg.axis[i].force_max_N = (fs_real_t)uniform(0.5, 200.0);
            cfg.axis[i].slew_max_N = (fs_real_t)uniform(0.01, 20.0);
        }
        assert_int_equal(lim_config_validate(&cfg), SAF_OK);
        lim_state_t st;
        lim_reset(&st);
        lim_prepare(&cfg, &st);
        for (uint32_t k = 0; k < 1000u; k++) {
            fs_real_t req[LIM_AXES], out[LIM_AXES], prev[LIM_AXES];
            saf_meas_t meas[LIM_AXES];
            for (uint32_t i = 0; i < LIM_AXES; i++) {
                req[i] = (fs_real_t)hostile(100.0);
                meas[i].pos_m = (fs_real_t)hostile(0.5);
                meas[i].vel_mps = (fs_real_t)hostile(1.0);
                meas[i].force_N = (fs_real_t)hostile(60.0);
                prev[i] = st.out_N[i];
            }
            (void)lim_apply(&cfg, &st, req, (k & 1u) ? meas : NULL, out);
            check_out(&cfg, prev, out, &s);
        }
    }
    printf(
        "lim property: %llu cases, worst |out| / F_max ok, worst |slew| %.6g N, non-finite %llu\n",
        (unsigned long long)s.n, s.worst_slew_N, (unsigned long long)s.nonfinite);
    assert_int_equal(s.n, 1000000u);
}

static void test_hostile_skills_and_goal_scales(void **state)
{
    (void)state;
    static const char *vectors[] = {"press_n50_lwr_hold.skill", "engrave_n100_ridge_hold.skill",
                                    "press_n10_ridge_release.skill", "engrave_n10_lwr_hold.skill"};
    static uint8_t img[8192];
    skill_t *base = malloc(sizeof *base);
    dmp_model_t *m = malloc(sizeof *m);
    assert_non_null(base);
    assert_non_null(m);
    lim_config_t lcfg;
    lim_default_config(&lcfg);
    pfc_config_t pcfg;
    pfc_default_config(&pcfg);
    /* a misconfigured controller: its own saturation is effectively off, lim is the only guard */
    for (uint32_t i = 0; i < SAF_AXES; i++) {
        pcfg.limits[i].force_max_N = (fs_real_t)1e30;
        pcfg.limits[i].integral_max_Ns = (fs_real_t)1e30;
    }
    stats_t s = {0, 0.0, 0.0, 0};
    uint32_t n_skills = 0;
    while (s.n < 1000000u) {
        const uint32_t len = tv_read(vectors[n_skills % 4u], img, sizeof img);
        assert_true(len > 0u);
        assert_int_equal(skill_parse(img, len, base), FS_OK);
        *m = base->dmp;
        /* hostile skill: weights scaled by up to 1e+-300, some NaN/inf (as if validation had
         * been bypassed); then the derived arrays recomputed where possible */
        const uint32_t mode = (uint32_t)(next_u64() % 4u);
        for (uint32_t i = 0; i < m->n_kernels; i++) {
            if (mode == 1u) {
                m->weight[i] = (fs_real_t)((double)m->weight[i] * pow(10.0, uniform(-30.0, 30.0)));
            } else if (mode == 2u) {
                m->weight[i] = (fs_real_t)hostile(1e4);
            } else if (mode == 3u) {
                m->weight[i] = (fs_real_t)uniform(-1e3, 1e3);
            }
        }
        dmp_run_t run;
        run.goal_scale = (fs_real_t)((next_u64() % 3u == 0u) ? hostile(3.0) : uniform(-3.0, 3.0));
        run.time_scale = (fs_real_t)uniform(0.2, 3.0);
        dmp_state_t ds;
        dmp_state_reset(&ds);
        pfc_state_t ps;
        pfc_reset(&ps);
        lim_state_t ls;
        lim_reset(&ls);
        lim_prepare(&lcfg, &ls);
        fs_real_t plant_x = FS_R(0.0), plant_v = FS_R(0.0);
        const fs_real_t k_env = (fs_real_t)uniform(100.0, 5000.0);
        for (uint32_t k = 0; k < 2000u && s.n < 1000000u; k++) {
            const fs_real_t f_hat = dmp_step(m, &ds, &run, NULL);
            pfc_axis_ref_t ref[SAF_AXES] = {
                {ds.y_N / base->stiffness_Npm, FS_R(0.0), FS_R(0.0), f_hat},
                {FS_R(0.0), FS_R(0.0), FS_R(0.0), FS_R(0.0)}};
            saf_meas_t meas[SAF_AXES] = {{plant_x, plant_v, k_env * plant_x},
                                         {FS_R(0.0), FS_R(0.0), FS_R(0.0)}};
            pfc_axis_meas_t pfc_meas[SAF_AXES] = {{plant_x, plant_v, k_env * plant_x},
                                                  {FS_R(0.0), FS_R(0.0), FS_R(0.0)}};
            fs_real_t req[SAF_AXES], out[SAF_AXES], prev[SAF_AXES];
            pfc_step(&pcfg, &ps, ref, pfc_meas, req);
            prev[0] = ls.out_N[0];
            prev[1] = ls.out_N[1];
            (void)lim_apply(&lcfg, &ls, req, meas, out);
            check_out(&lcfg, prev, out, &s);
            /* a 1 kg mass on a spring, driven by the limited force (semi-implicit Euler) */
            const fs_real_t acc = out[0] - k_env * plant_x;
            plant_v += acc * FS_R(0.001);
            plant_x += plant_v * FS_R(0.001);
        }
        n_skills++;
    }
    printf("hostile skills/goal scales: %u rollouts, %llu ticks, worst |F| %.6g N (limit %.6g), "
           "worst slew %.6g N/tick, non-finite outputs %llu\n",
           n_skills, (unsigned long long)s.n, s.worst_abs_N, (double)lcfg.axis[0].force_max_N,
           s.worst_slew_N, (unsigned long long)s.nonfinite);
    free(base);
    free(m);
}

static void test_workspace_velocity_contact(void **state)
{
    (void)state;
    lim_config_t cfg;
    lim_default_config(&cfg);
    cfg.axis[0].slew_max_N = FS_R(100.0); /* no slew effect in this test */
    cfg.axis[1].slew_max_N = FS_R(100.0);
    lim_state_t st;
    lim_reset(&st);
    lim_prepare(&cfg, &st);
    fs_real_t req[2] = {FS_R(30.0), FS_R(-30.0)}, out[2];
    saf_meas_t in_ws[2] = {{FS_R(0.1), FS_R(0.0), FS_R(5.0)}, {FS_R(0.0), FS_R(0.0), FS_R(0.0)}};
    lim_result_t r = lim_apply(&cfg, &st, req, in_ws, out);
    assert_int_equal(r.cause_mask, 0);
    assert_true(out[0] == FS_R(30.0) && out[1] == FS_R(-30.0));
    /* x beyond pos_max: outward (+) force cut, inward allowed */
    saf_meas_t out_ws[2] = {{FS_R(0.6), FS_R(0.0), FS_R(5.0)}, {FS_R(-0.6), FS_R(0.0), FS_R(0.0)}};
    r = lim_apply(&cfg, &st, req, out_ws, out);
    assert_true(r.cause_mask & FLT_BIT(FLT_WORKSPACE));
    assert_true(r.flags & LIM_F_WORKSPACE);
    assert_true(out[0] == FS_R(0.0) && out[1] == FS_R(0.0));
    fs_real_t inward[2] = {FS_R(-10.0), FS_R(10.0)};
    r = lim_apply(&cfg, &st, inward, out_ws, out);
    assert_true(out[0] == FS_R(-10.0) && out[1] == FS_R(10.0));
    /* over speed: force along the velocity cut, against it allowed */
    saf_meas_t fast[2] = {{FS_R(0.0), FS_R(2.0), FS_R(0.0)}, {FS_R(0.0), FS_R(-2.0), FS_R(0.0)}};
    r = lim_apply(&cfg, &st, req, fast, out);
    assert_true(r.cause_mask & FLT_BIT(FLT_VELOCITY));
    assert_true(out[0] == FS_R(0.0) && out[1] == FS_R(0.0));
    fs_real_t brake[2] = {FS_R(-5.0), FS_R(5.0)};
    r = lim_apply(&cfg, &st, brake, fast, out);
    assert_true(out[0] == FS_R(-5.0) && out[1] == FS_R(5.0));
    /* contact force above its limit is a fault cause (the command is not what exceeded) */
    saf_meas_t hard[2] = {{FS_R(0.0), FS_R(0.0), FS_R(61.0)}, {FS_R(0.0), FS_R(0.0), FS_R(0.0)}};
    r = lim_apply(&cfg, &st, req, hard, out);
    assert_true(r.cause_mask & FLT_BIT(FLT_FORCE_LIMIT));
    /* NaN request */
    fs_real_t nan_req[2] = {(fs_real_t)NAN, FS_R(0.0)};
    r = lim_apply(&cfg, &st, nan_req, in_ws, out);
    assert_true(r.cause_mask & FLT_BIT(FLT_CMD_NOT_FINITE));
    assert_true(out[0] == FS_R(0.0));
}

static void test_slew_and_slew_fault(void **state)
{
    (void)state;
    lim_config_t cfg;
    lim_default_config(&cfg);
    lim_state_t st;
    lim_reset(&st);
    lim_prepare(&cfg, &st);
    fs_real_t req[2] = {FS_R(50.0), FS_R(0.0)}, out[2];
    /* a step of 50 N is reached in 25 ticks of 2 N */
    for (uint32_t k = 1; k <= 25; k++) {
        const lim_result_t r = lim_apply(&cfg, &st, req, NULL, out);
        assert_true(fabs((double)out[0] - 2.0 * k) < 1e-4);
        assert_int_equal(r.cause_mask, 0);
    }
    /* that step (25 binding ticks) is normal and did not trip the fault; keep going */
    for (uint32_t k = 0; k < 100; k++) {
        const lim_result_t r = lim_apply(&cfg, &st, req, NULL, out);
        assert_int_equal(r.cause_mask, 0);
    }
    /* continuous binding: a slow slew limit and a far request trip after slew_fault_ticks */
    cfg.axis[0].slew_max_N = FS_R(0.1);
    lim_prepare(&cfg, &st);
    req[0] = FS_R(-50.0);
    uint32_t first = 0;
    for (uint32_t k = 1; k <= 200 && first == 0; k++) {
        const lim_result_t r = lim_apply(&cfg, &st, req, NULL, out);
        if (r.cause_mask & FLT_BIT(FLT_SLEW_LIMIT)) {
            first = k;
        }
    }
    assert_int_equal(first, cfg.slew_fault_ticks);
    /* an unstable controller oscillating +-50 N every tick trips within 4*slew_fault_ticks */
    lim_default_config(&cfg);
    lim_reset(&st);
    lim_prepare(&cfg, &st);
    first = 0;
    for (uint32_t k = 1; k <= 1000 && first == 0; k++) {
        req[0] = (k & 1u) ? FS_R(-50.0) : FS_R(50.0);
        const lim_result_t r = lim_apply(&cfg, &st, req, NULL, out);
        if (r.cause_mask & FLT_BIT(FLT_SLEW_LIMIT)) {
            first = k;
        }
    }
    assert_true(first >= cfg.slew_fault_ticks && first <= 4u * cfg.slew_fault_ticks + 2u);
    printf("slew fault: continuous binding after %u ticks, +-50 N oscillation after %u ticks\n",
           (unsigned)cfg.slew_fault_ticks, (unsigned)first);
}

static void test_config_validation(void **state)
{
    (void)state;
    lim_config_t c;
    lim_default_config(&c);
    assert_int_equal(lim_config_validate(&c), SAF_OK);
    assert_true((double)c.axis[0].force_max_N == 50.0);
    c.axis[1].force_max_N = (fs_real_t)NAN;
    assert_int_equal(lim_config_validate(&c), SAF_ERR_NOT_FINITE);
    lim_default_config(&c);
    c.axis[0].slew_max_N = FS_R(0.0);
    assert_int_equal(lim_config_validate(&c), SAF_ERR_NONPOSITIVE);
    lim_default_config(&c);
    c.axis[0].pos_min_m = FS_R(1.0);
    assert_int_equal(lim_config_validate(&c), SAF_ERR_WORKSPACE);
    lim_default_config(&c);
    c.axis[0].force_max_N = FS_R(500.0);
    assert_int_equal(lim_config_validate(&c), SAF_ERR_FORCE_MAX);
    assert_int_equal(lim_config_validate(NULL), SAF_ERR_NULL_ARG);
    /* even an invalid configuration can only shrink the output, never make it non-finite */
    lim_default_config(&c);
    c.axis[0].force_max_N = (fs_real_t)NAN;
    c.axis[1].slew_max_N = (fs_real_t)-INFINITY;
    lim_state_t st;
    lim_reset(&st);
    lim_prepare(&c, &st);
    fs_real_t req[2] = {FS_R(10.0), FS_R(10.0)}, out[2];
    (void)lim_apply(&c, &st, req, NULL, out);
    assert_true(out[0] == FS_R(0.0) && out[1] == FS_R(0.0));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_random_hostile_requests),
        cmocka_unit_test(test_hostile_skills_and_goal_scales),
        cmocka_unit_test(test_workspace_velocity_contact),
        cmocka_unit_test(test_slew_and_slew_fault),
        cmocka_unit_test(test_config_validation),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

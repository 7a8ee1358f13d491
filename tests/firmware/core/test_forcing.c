/* Truncated kernel evaluation (dmp_forcing) equals the full sum (dmp_forcing_full) within 1e-9
 * relative, on realistic kernel layouts (centres uniform in time mapped through the discrete
 * phase, sigma_i = half the gap), for N = 10, 50, 100, 200; the binary-search window never drops
 * a kernel within the cutoff; the number of kernels summed per tick is small and bounded. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <cmocka.h>

#include "core_test_util.h"
#include "dmp.h"

#define SWEEP_POINTS 100000
/* Kernels summed per tick, for every N tested: with sigma_i = half the gap the cutoff is
 * |u - c_i| <= sqrt(46)*sigma_i = 3.4 gaps, so about 7 neighbours qualify; where gaps grow fast
 * (N = 10, early phase) kernels further right reach back: 9 measured. */
#define ACTIVE_BOUND 9u

static tu_skill_desc_t desc;
static dmp_model_t model;

static void sweep(uint16_t n, int random_weights)
{
    tu_default_desc(&desc, n, 280.0, 17.0);
    if (random_weights) {
        uint64_t rng = 12345u + n;
        for (uint16_t i = 0; i < n; i++) {
            desc.weight[i] = tu_uniform(&rng, -100.0, 100.0);
        }
    }
    assert_int_equal(tu_model_from_desc(&desc, &model), FS_OK);
    double w_max = 0.0;
    for (uint16_t i = 0; i < n; i++) {
        w_max = fmax(w_max, fabs(desc.weight[i]));
    }
    const double u_end = desc.centre[n - 1];
    double err_max = 0.0;
    uint16_t active_max = 0;
    for (long j = 0; j <= SWEEP_POINTS; j++) {
        const double u = u_end * (double)j / SWEEP_POINTS;
        const double v = 0.37, g = 0.05;
        const double h_t = dmp_forcing(&model, u, v, g);
        const double h_f = dmp_forcing_full(&model, u, v, g);
        err_max = fmax(err_max, fabs(h_t - h_f) / (g * v * w_max));
        /* brute-force count of kernels with e_i <= cutoff: the window must hold all of them */
        uint16_t brute = 0;
        for (uint16_t i = 0; i < n; i++) {
            const double d = u - model.centre[i];
            if (d * d * model.kernel_scale[i] <= DMP_KERNEL_CUTOFF_EXP) {
                brute++;
            }
        }
        const uint16_t active = dmp_active_kernels(&model, u);
        if (active != brute) {
            fail_msg("N=%u u=%.9f: window summed %u kernels, %u within cutoff", n, u, active, brute);
        }
        active_max = (active > active_max) ? active : active_max;
    }
    printf("N=%3u %s weights: max |h_trunc - h_full|/(g*v*max|w|) = %.3g, active kernels max %u\n",
           n, random_weights ? "random" : "smooth", err_max, active_max);
    assert_true(err_max <= 1e-9);
    assert_true(active_max <= ACTIVE_BOUND);
}

static void test_truncation_n10(void **state)
{
    (void)state;
    sweep(10, 0);
    sweep(10, 1);
}

static void test_truncation_n50(void **state)
{
    (void)state;
    sweep(50, 0);
    sweep(50, 1);
}

static void test_truncation_n100(void **state)
{
    (void)state;
    sweep(100, 0);
    sweep(100, 1);
}

static void test_truncation_n200(void **state)
{
    (void)state;
    sweep(200, 0);
    sweep(200, 1);
}

/* Past every kernel's cutoff (u -> 1 after the last centre) the kernel with the smallest e_i is
 * used alone. */
static void test_nearest_fallback(void **state)
{
    (void)state;
    tu_default_desc(&desc, 200, 280.0, 17.0);
    assert_int_equal(tu_model_from_desc(&desc, &model), FS_OK);
    const double u = 0.9995;
    uint16_t best = 0;
    double e_best = INFINITY;
    for (uint16_t i = 0; i < 200; i++) {
        const double d = u - model.centre[i];
        const double e = d * d * model.kernel_scale[i];
        assert_true(e > DMP_KERNEL_CUTOFF_EXP);
        if (e < e_best) {
            e_best = e;
            best = i;
        }
    }
    assert_int_equal(dmp_active_kernels(&model, u), 1);
    assert_true(dmp_forcing(&model, u, 1.0, 1.0) == model.weight[best]);
}

/* dmp_model_init refuses what the skill image refuses, with the same codes. */
static void test_model_init_codes(void **state)
{
    (void)state;
    tu_default_desc(&desc, 10, 280.0, 5.0);
    assert_int_equal(tu_model_from_desc(&desc, &model), FS_OK);
    tu_skill_desc_t d;
    d = desc; d.n_kernels = 0;
    assert_int_equal(tu_model_from_desc(&d, &model), FS_ERR_SKILL_KERNELS);
    d = desc; d.weight[3] = NAN;
    assert_int_equal(tu_model_from_desc(&d, &model), FS_ERR_SKILL_NOT_FINITE);
    d = desc; d.dt_s = 0.0;
    assert_int_equal(tu_model_from_desc(&d, &model), FS_ERR_SKILL_RANGE);
    d = desc; d.width[9] = 0.0;
    assert_int_equal(tu_model_from_desc(&d, &model), FS_ERR_SKILL_RANGE);
    d = desc; d.width[2] = 1e-200; /* 1/(2 sigma^2) overflows */
    assert_int_equal(tu_model_from_desc(&d, &model), FS_ERR_SKILL_RANGE);
    d = desc; d.centre[4] = d.centre[3];
    assert_int_equal(tu_model_from_desc(&d, &model), FS_ERR_SKILL_CENTRES);
    d = desc; d.beta = d.alpha / 4.0 * 1.001;
    assert_int_equal(tu_model_from_desc(&d, &model), FS_ERR_SKILL_GAINS);
    assert_int_equal(dmp_model_init(NULL), FS_ERR_NULL_ARG);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_truncation_n10),
        cmocka_unit_test(test_truncation_n50),
        cmocka_unit_test(test_truncation_n100),
        cmocka_unit_test(test_truncation_n200),
        cmocka_unit_test(test_nearest_fallback),
        cmocka_unit_test(test_model_init_codes),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

/* The Cortex-M4F table expf (firmware/ports/mps2/cm_expf.c) on the host against exp() in
 * double: relative error over the DMP's argument range [-23, 0] and the whole finite range,
 * subnormal results, special values. The error is the table interpolation (9.2e-7) plus the
 * float32 rounding of x*log2(e) (6e-8 relative of |x|*1.44 octaves: 2e-6 at x = -23, 7e-6
 * at |x| = 88): bounds 3e-6 on [-23, 0] and 6e-6 on the rest. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <float.h>
#include <math.h>
#include <stdio.h>

#include "cm_expf.h"

static double rel_err(float x)
{
    const double ref = exp((double)x);
    return fabs((double)cm_expf(x) - ref) / ref;
}

static void test_dmp_range(void **state)
{
    (void)state;
    double worst = 0.0;
    for (int i = 0; i <= 2000000; i++) {
        const float x = (float)(-23.0 * i / 2000000.0);
        worst = fmax(worst, rel_err(x));
    }
    printf("cm_expf on [-23, 0]: max relative error %.3g\n", worst);
    assert_true(worst <= 3e-6);
}

static void test_full_range(void **state)
{
    (void)state;
    double worst = 0.0;
    for (int i = 0; i <= 1000000; i++) {
        const float x = (float)(-87.0 + 175.0 * i / 1000000.0);
        if (x < 88.7f) {
            worst = fmax(worst, rel_err(x));
        }
    }
    printf("cm_expf on [-87, 88.7]: max relative error %.3g\n", worst);
    assert_true(worst <= 6e-6);
    /* subnormal results: absolute error within a few subnormal steps */
    for (float x = -103.9f; x < -87.4f; x += 0.37f) {
        const double ref = exp((double)x);
        assert_true(fabs((double)cm_expf(x) - ref) <= 6e-6 * ref + 4.0 * 1.4e-45);
    }
}

static void test_special(void **state)
{
    (void)state;
    assert_true(isnan(cm_expf(NAN)));
    assert_true(isinf(cm_expf(INFINITY)) && cm_expf(INFINITY) > 0.0f);
    assert_true(cm_expf(-INFINITY) == 0.0f);
    assert_true(isinf(cm_expf(89.0f)));
    assert_true(cm_expf(-104.0f) == 0.0f);
    assert_true(cm_expf(0.0f) == 1.0f);
    assert_true(cm_expf(-0.0f) == 1.0f);
    assert_true(cm_expf(88.7f) < INFINITY && cm_expf(88.7f) > 1e38f);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_dmp_range),
        cmocka_unit_test(test_full_range),
        cmocka_unit_test(test_special),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

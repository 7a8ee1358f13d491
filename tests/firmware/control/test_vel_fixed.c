/* The velocity estimator in integers (exec_vel_update_q, the fixed-point build) against the
 * filter written here in double: (pos - prev)/dt low-passed by alpha = dt/(dt + 1/(2 pi fc)), on
 * a sine sweep with encoder noise, steps and a long ramp; the largest difference is printed and
 * bound to 2e-5 m/s (the Q8.24 position's LSB over dt is 6e-5 m/s per sample, low-passed). A
 * non-finite sample makes every later velocity not finite, and the first sample only primes. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <cmocka.h>

#include "fs_exec.h"

static int32_t q24(double v)
{
    return (int32_t)llround(v * 16777216.0);
}

static void test_matches_the_double_filter(void **state)
{
    (void)state;
    const double dt = 0.001, fc = 80.0;
    const double alpha = dt / (dt + 1.0 / (2.0 * 3.14159265358979323846 * fc));
    exec_vel_t v;
    exec_vel_init(&v, (fs_real_t)fc, (fs_real_t)dt);
    double prev = 0.0, vel = 0.0, worst = 0.0;
    uint32_t seed = 12345u;
    for (int i = 0; i < 20000; i++) {
        seed = seed * 1664525u + 1013904223u;
        const double t = i * dt;
        double pos = 0.02 * sin(2.0 * 3.14159265358979323846 * (0.5 + 2.0 * t) * t) +
                     1e-6 * ((double)(seed >> 8) / 16777216.0 - 0.5);
        if (i > 12000) {
            pos = 0.05 + 0.3 * (t - 12.0); /* a ramp at 0.3 m/s */
        }
        if (i == 9000) {
            pos += 0.004; /* a step */
        }
        const int32_t pq = q24(pos);
        const double posq = pq / 16777216.0; /* the reference sees the same quantised sample */
        const int32_t got = exec_vel_update_q(&v, pq);
        if (i == 0) {
            prev = posq;
            assert_int_equal(got, 0);
            continue;
        }
        vel += alpha * ((posq - prev) / dt - vel);
        prev = posq;
        const double d = fabs(got / 16777216.0 - vel);
        worst = (d > worst) ? d : worst;
    }
    printf("exec_vel_update_q vs double: max |difference| %.3g m/s (bound 2e-5)\n", worst);
    assert_true(worst < 2e-5);
}

static void test_not_finite_is_sticky(void **state)
{
    (void)state;
    exec_vel_t v;
    exec_vel_init(&v, 80.0f, 0.001f);
    (void)exec_vel_update_q(&v, q24(0.01));
    assert_int_not_equal(exec_vel_update_q(&v, q24(0.0101)), INT32_MIN);
    assert_int_equal(exec_vel_update_q(&v, INT32_MIN), INT32_MIN);
    assert_int_equal(exec_vel_update_q(&v, q24(0.0102)), INT32_MIN);
    exec_vel_init(&v, 80.0f, 0.001f);
    (void)exec_vel_update_q(&v, q24(0.01));
    assert_int_not_equal(exec_vel_update_q(&v, q24(0.0101)), INT32_MIN);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_matches_the_double_filter),
        cmocka_unit_test(test_not_finite_is_sticky),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

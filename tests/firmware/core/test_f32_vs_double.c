/* The float32 core (Cortex-M4F build) against the double core on the same skill images: realistic
 * 17 s skills, N = 10..200, with goal and time scaling, within 1e-4 of max force (the golden-vector
 * tolerance for float). Both cores live in this executable: fs_core_f32's symbols carry an _f32
 * suffix (fs_real.h). */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <cmocka.h>

#include "core_test_util.h"
#include "f32_side.h"
#include "skill.h"

#define CAP_ROWS 30000L

static tu_skill_desc_t desc;
static uint8_t img[SKILL_HEADER_SIZE + 24 * 256 + 4];
static skill_t sk;
static double fd[CAP_ROWS], ff[CAP_ROWS];

static void test_float_tracks_double(void **state)
{
    (void)state;
    const uint16_t ns[] = {10, 50, 100, 200};
    const double scales[][2] = {{1.0, 1.0}, {1.5, 1.0}, {1.0, 1.3}};
    double worst = 0.0;
    for (size_t i = 0; i < 4; i++) {
        tu_default_desc(&desc, ns[i], 280.0, 17.0);
        const uint32_t len = tu_write_image(&desc, img, sizeof(img));
        assert_int_equal(skill_parse(img, len, &sk), FS_OK);
        for (size_t j = 0; j < 3; j++) {
            const dmp_run_t run = {scales[j][0], scales[j][1]};
            const long rows = lround(17.0 * scales[j][1] / 0.001) + 1;
            assert_true(rows <= CAP_ROWS);
            dmp_state_t s;
            dmp_state_reset(&s);
            fd[0] = sk.dmp.force0_N;
            for (long r = 1; r < rows; r++) {
                fd[r] = dmp_step(&sk.dmp, &s, &run, NULL);
            }
            const long got = f32_parse_rollout(img, len, scales[j][0], scales[j][1], ff, CAP_ROWS);
            assert_int_equal(got, rows);
            double e = 0.0, m = 0.0;
            for (long r = 0; r < rows; r++) {
                e = fmax(e, fabs(ff[r] - fd[r]));
                m = fmax(m, fabs(fd[r]));
            }
            printf("N=%3u gs=%.1f ts=%.1f: float vs double max err %.3g of max|f| (%.2f N)\n",
                   ns[i], scales[j][0], scales[j][1], e / m, m);
            worst = fmax(worst, e / m);
        }
    }
    printf("float32 core vs double core, 17 s skills: worst %.3g of max|f|\n", worst);
    assert_true(worst <= 1e-4);
}

/* The float core's inline kernel activation against libm's double exp over [0, cutoff]: within
 * 2e-6 relative (polynomial 3.1e-7 in float32, plus the float32 rounding of e*log2(e), at most
 * cutoff*log2(e)*6e-8 octave: 1.4e-6 at 23), exact at 0, decreasing. */
static void test_kernel_exp_accuracy(void **state)
{
    (void)state;
    const double cut = f32_kernel_cutoff();
    double worst = 0.0, prev = 2.0;
    int monotone = 1;
    for (long i = 0; i <= 200000; i++) {
        const double e = (double)(float)(cut * (double)i / 200000.0);
        const double got = f32_exp_neg(e);
        worst = fmax(worst, fabs(got / exp(-e) - 1.0));
        monotone = monotone && got <= prev;
        prev = got;
    }
    printf("fs_num_exp_neg (float32) over [0, %.0f]: worst relative error %.3g\n", cut, worst);
    assert_true(f32_exp_neg(0.0) == 1.0);
    assert_true(worst <= 2e-6);
    assert_true(monotone);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_float_tracks_double),
        cmocka_unit_test(test_kernel_exp_accuracy),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

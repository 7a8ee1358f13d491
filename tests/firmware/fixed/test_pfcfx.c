/* Fixed-point control law against pfc_step (double): random references and measurements over
 * long runs (integral, saturation and anti-windup included), and configuration limits. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <string.h>

#include <math.h>
#include <stdio.h>

#include "core_test_util.h"
#include "pfcfx.h"

static int32_t q(double v, unsigned frac)
{
    int32_t out = 0;
    assert_int_equal(fx_from_double(v, frac, INT32_MAX, &out), FS_OK);
    return out;
}

static void test_against_double(void **state)
{
    (void)state;
    pfc_config_t cfg;
    pfc_default_config(&cfg);
    pfcfx_config_t fcfg;
    assert_int_equal(pfcfx_from_config(&cfg, &fcfg), FS_OK);
    /* the conversion alone (a caller that validated the configuration) gives the same */
    pfcfx_config_t vcfg;
    memset(&vcfg, 0, sizeof vcfg);
    assert_int_equal(pfcfx_from_valid_config(&cfg, &vcfg), FS_OK);
    assert_memory_equal(&vcfg, &fcfg, sizeof vcfg);
    pfc_state_t sd;
    pfcfx_state_t sf;
    pfc_reset(&sd);
    pfcfx_reset(&sf);
    uint64_t rng = 12345u;
    double worst_cmd = 0.0;
    double worst_int = 0.0;
    int saturated = 0;
    int held = 0;
    for (int step = 0; step < 200000; step++) {
        /* slowly varying references with occasional large force errors (saturation) */
        const double t = step * 0.001;
        pfc_axis_ref_t rd[PFC_AXES];
        pfc_axis_meas_t md[PFC_AXES];
        pfcfx_ref_t rf[PFC_AXES];
        pfcfx_meas_t mf[PFC_AXES];
        for (uint32_t a = 0; a < PFC_AXES; a++) {
            const double big = (step / 5000) % 3 == 2 ? 8.0 : 1.0;
            rd[a].pos_m = 0.01 * sin(0.7 * t + a) + tu_uniform(&rng, -1e-4, 1e-4);
            rd[a].vel_mps = 0.007 * cos(0.7 * t + a);
            rd[a].acc_mps2 = tu_uniform(&rng, -0.05, 0.05);
            rd[a].force_N = big * (5.0 + 4.0 * sin(0.3 * t));
            md[a].pos_m = rd[a].pos_m + tu_uniform(&rng, -2e-3, 2e-3);
            md[a].vel_mps = rd[a].vel_mps + tu_uniform(&rng, -0.01, 0.01);
            md[a].force_N = 5.0 + 4.0 * sin(0.3 * t) + tu_uniform(&rng, -0.6, 0.5);
            /* quantise the double inputs exactly like the fixed ones, so only the law differs */
            rf[a].pos_m = q(rd[a].pos_m, 24u);
            rf[a].vel_mps = q(rd[a].vel_mps, 24u);
            rf[a].acc_mps2 = q(rd[a].acc_mps2, 24u);
            rf[a].force_N = q(rd[a].force_N, 16u);
            mf[a].pos_m = q(md[a].pos_m, 24u);
            mf[a].vel_mps = q(md[a].vel_mps, 24u);
            mf[a].force_N = q(md[a].force_N, 16u);
            rd[a].pos_m = fx_to_double(rf[a].pos_m, 24u);
            rd[a].vel_mps = fx_to_double(rf[a].vel_mps, 24u);
            rd[a].acc_mps2 = fx_to_double(rf[a].acc_mps2, 24u);
            rd[a].force_N = fx_to_double(rf[a].force_N, 16u);
            md[a].pos_m = fx_to_double(mf[a].pos_m, 24u);
            md[a].vel_mps = fx_to_double(mf[a].vel_mps, 24u);
            md[a].force_N = fx_to_double(mf[a].force_N, 16u);
        }
        double cd[PFC_AXES];
        int32_t cf[PFC_AXES];
        const double i_before = sd.force_err_integral_Ns[0];
        pfc_step(&cfg, &sd, rd, md, cd);
        pfcfx_step(&fcfg, &sf, rf, mf, cf);
        if (fabs(cd[0]) >= cfg.limits[0].force_max_N) {
            saturated++;
            held += (sd.force_err_integral_Ns[0] == i_before);
        }
        for (uint32_t a = 0; a < PFC_AXES; a++) {
            worst_cmd = fmax(worst_cmd, fabs(fx_to_double(cf[a], 16u) - cd[a]));
            worst_int = fmax(worst_int, fabs(fx_to_double(sf.force_err_integral_Ns[a], 24u) -
                                             sd.force_err_integral_Ns[a]));
        }
    }
    printf("pfcfx vs pfc_step (double), 200 s: max |cmd diff| = %.3g N, max |integral diff| = "
           "%.3g N*s; %d saturated ticks, %d with the integral held\n",
           worst_cmd, worst_int, saturated, held);
    assert_true(saturated > 1000);
    assert_true(held > 0);
    /* 50 N full scale: 1e-3 N = 0.002 % of full scale (a few Q16.16 LSB of rounding) */
    assert_true(worst_cmd <= 1e-3);
    assert_true(worst_int <= 1e-5);
}

static void test_config_limits(void **state)
{
    (void)state;
    pfc_config_t cfg;
    pfcfx_config_t fcfg;
    pfc_default_config(&cfg);
    cfg.gains[0].k_p_Npm = 40000.0; /* > 32767 does not fit Q16.16 */
    assert_int_equal(pfcfx_from_config(&cfg, &fcfg), FS_ERR_FIXED_CONFIG);
    pfc_default_config(&cfg);
    cfg.limits[1].integral_max_Ns = 200.0; /* > 127 does not fit Q8.24 */
    assert_int_equal(pfcfx_from_config(&cfg, &fcfg), FS_ERR_FIXED_CONFIG);
    pfc_default_config(&cfg);
    cfg.gains[0].m_d_kg = -1.0; /* the double validation runs first */
    assert_int_equal(pfcfx_from_config(&cfg, &fcfg), FS_ERR_MASS_NONPOSITIVE);
    assert_int_equal(pfcfx_from_config(NULL, &fcfg), FS_ERR_NULL_ARG);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_against_double),
        cmocka_unit_test(test_config_limits),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

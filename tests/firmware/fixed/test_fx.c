/* fx_ helpers at boundary values against a double reference: exact rounding (0 LSB) for the
 * arithmetic helpers, the documented table bound for exp, saturation instead of wrap-around.
 * Built under ASan+UBSan in Debug, so a signed overflow anywhere here fails the test. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>

#include "fx.h"

static const int32_t k_edges[] = {INT32_MIN, INT32_MIN + 1, -(1 << 30), -(1 << 24), -65537, -2,
                                  -1, 0, 1, 2, 65537, 1 << 24, 1 << 30, INT32_MAX - 1, INT32_MAX,
                                  123456789, -987654321};
#define N_EDGES (sizeof(k_edges) / sizeof(k_edges[0]))

static uint64_t rng_state = 0x9E3779B97F4A7C15ull;
static uint64_t rng_next(void)
{
    rng_state ^= rng_state >> 12;
    rng_state ^= rng_state << 25;
    rng_state ^= rng_state >> 27;
    return rng_state * 2685821657736338717ull;
}

/* Reference: clamp(floor(x + 0.5)) in long double (64-bit mantissa: exact for these sizes). */
static int32_t ref_round_sat(long double x)
{
    const long double r = floorl(x + 0.5L);
    if (r > (long double)INT32_MAX) {
        return INT32_MAX;
    }
    if (r < (long double)INT32_MIN) {
        return INT32_MIN;
    }
    return (int32_t)r;
}

static void test_sat_add_sub(void **state)
{
    (void)state;
    for (size_t i = 0; i < N_EDGES; i++) {
        for (size_t j = 0; j < N_EDGES; j++) {
            const int32_t a = k_edges[i];
            const int32_t b = k_edges[j];
            assert_int_equal(fx_add_sat(a, b), ref_round_sat((long double)a + (long double)b));
            assert_int_equal(fx_sub_sat(a, b), ref_round_sat((long double)a - (long double)b));
        }
    }
    const int32_t ks[] = {0, 1, -1, 16, 64, 1000, -1000, INT32_MAX, INT32_MIN};
    for (size_t i = 0; i < N_EDGES; i++) {
        for (size_t j = 0; j < sizeof(ks) / sizeof(ks[0]); j++) {
            assert_int_equal(fx_mul_int_sat(k_edges[i], ks[j]),
                             ref_round_sat((long double)k_edges[i] * (long double)ks[j]));
        }
    }
    assert_int_equal(fx_sat32((int64_t)INT32_MAX + 1), INT32_MAX);
    assert_int_equal(fx_sat32((int64_t)INT32_MIN - 1), INT32_MIN);
    assert_int_equal(fx_sat32(INT64_MAX), INT32_MAX);
    assert_int_equal(fx_sat32(INT64_MIN), INT32_MIN);
    assert_int_equal(fx_abs_sat(INT32_MIN), INT32_MAX);
    assert_int_equal(fx_abs_sat(-5), 5);
    assert_int_equal(fx_clamp_sym(100, 7), 7);
    assert_int_equal(fx_clamp_sym(-100, 7), -7);
    assert_int_equal(fx_clamp_sym(INT32_MIN, INT32_MAX), -INT32_MAX);
}

/* fx_sat32 and fx_clamp61 (a fast path on the high word, then the compares) against the plain
 * compares: every value within a few LSB of each bound and of 2^k, and 200,000 random words. */
static void test_sat_fast_paths(void **state)
{
    (void)state;
    const int64_t s61 = ((int64_t)1 << 61) - 1;
    int64_t probe[1024];
    size_t n = 0;
    for (int k = 0; k <= 62; k++) {
        for (int64_t d = -3; d <= 3; d++) {
            const int64_t p = ((int64_t)1 << k) + d;
            probe[n++] = p;
            probe[n++] = -p;
        }
    }
    probe[n++] = INT64_MAX;
    probe[n++] = INT64_MIN;
    probe[n++] = INT64_MIN + 1;
    for (size_t r = 0; r < 200000u + n; r++) {
        const int64_t v = (r < n) ? probe[r] : (int64_t)rng_next() >> (rng_next() % 40u);
        const int32_t sat = (v > INT32_MAX) ? INT32_MAX : (v < INT32_MIN) ? INT32_MIN : (int32_t)v;
        const int64_t c61 = (v > s61) ? s61 : (v < -s61) ? -s61 : v;
        assert_int_equal(fx_sat32(v), sat);
        assert_true(fx_clamp61(v) == c61);
    }
}

/* fx_rshift_round_var (in 32-bit words) against fx_rshift_round: every shift 0..62, values near
 * 0, near each 2^j and half-way points, and 200,000 random ones below 2^62. */
static void test_rshift_round_var(void **state)
{
    (void)state;
    for (unsigned k = 0u; k <= 62u; k++) {
        for (int r = 0; r < 4000; r++) {
            int64_t t;
            if (r < 64 && k <= 59u) { /* |t| < 2^62 */
                const int64_t p = (k > 0u) ? ((int64_t)1 << (k - 1u)) : 0;
                t = p * (r / 8 - 4) + (r % 8 - 4);
            } else {
                t = (int64_t)(rng_next() >> (2u + rng_next() % 62u)) * ((rng_next() & 1u) ? 1 : -1);
            }
            const int64_t ref = (k == 0u) ? t : fx_rshift_round(t, k);
            assert_true(fx_rshift_round_var(t, k) == ref);
        }
    }
}

static void test_mul_round_exact(void **state)
{
    (void)state;
    const unsigned shifts[] = {1u, 16u, 19u, 20u, 23u, 24u, 30u, 31u};
    for (size_t s = 0; s < sizeof(shifts) / sizeof(shifts[0]); s++) {
        for (size_t i = 0; i < N_EDGES; i++) {
            for (size_t j = 0; j < N_EDGES; j++) {
                const int32_t a = k_edges[i];
                const int32_t b = k_edges[j];
                const long double ref = ldexpl((long double)a * (long double)b, -(int)shifts[s]);
                assert_int_equal(fx_mul_sat(a, b, shifts[s]), ref_round_sat(ref));
            }
        }
        for (int k = 0; k < 20000; k++) {
            const int32_t a = (int32_t)(uint32_t)rng_next();
            const int32_t b = (int32_t)(uint32_t)rng_next();
            const long double ref = ldexpl((long double)a * (long double)b, -(int)shifts[s]);
            assert_int_equal(fx_mul_sat(a, b, shifts[s]), ref_round_sat(ref));
        }
    }
    /* rshift_round: half rounds up, negative values floor(x + 0.5) too */
    assert_int_equal(fx_rshift_round(3, 1u), 2);
    assert_int_equal(fx_rshift_round(-3, 1u), -1);
    assert_int_equal(fx_rshift_round(-5, 2u), -1);
    assert_int_equal(fx_rshift_round(((int64_t)1 << 62) - 1, 31u), (int64_t)1 << 31);
}

/* exp(-a) by table: error <= (ln2/256)^2/8 relative (linear interpolation of 2^-f) plus the
 * rounding of the table entries, interpolation product and final shift (<= 2 LSB). */
static void test_exp_table(void **state)
{
    (void)state;
    const double interp_rel = pow(log(2.0) / 256.0, 2.0) / 8.0;
    double worst_lsb = 0.0;
    double worst_rel = 0.0;
    uint32_t prev = UINT32_MAX;
    const uint32_t max = FX_EXP_ARG_MAX_Q27;
    for (uint64_t a = 0; a <= max; a += 4099u) {
        const uint32_t got = fx_exp_neg_q27((uint32_t)a);
        const double ref = ldexp(exp(-ldexp((double)a, -27)), 31);
        const double err = fabs((double)got - ref);
        assert_true(err <= interp_rel * ref + 2.0);
        worst_lsb = fmax(worst_lsb, err);
        worst_rel = fmax(worst_rel, err / ref);
        assert_true(got <= prev); /* monotone non-increasing */
        prev = got;
    }
    const uint32_t edges[] = {0u, 1u, 2u, (1u << 27) - 1u, 1u << 27, max - 1u, max};
    for (size_t i = 0; i < sizeof(edges) / sizeof(edges[0]); i++) {
        const double ref = ldexp(exp(-ldexp((double)edges[i], -27)), 31);
        const double got = (double)fx_exp_neg_q27(edges[i]);
        assert_true(fabs(got - ref) <= interp_rel * ref + 2.0);
    }
    assert_int_equal(fx_exp_neg_q27(0u), FX_Q31_ONE_U);
    /* clipped at 16: larger arguments give exp(-16), never wrap to large values */
    assert_int_equal(fx_exp_neg_q27(max + 1u), fx_exp_neg_q27(max));
    assert_int_equal(fx_exp_neg_q27(UINT32_MAX), fx_exp_neg_q27(max));
    print_message("fx_exp_neg_q27: worst %.1f LSB, %.2e relative (bound %.2e)\n", worst_lsb,
                  worst_rel, interp_rel);
}

static void test_udiv(void **state)
{
    (void)state;
    const uint32_t ds[] = {1u,          2u,          3u,          0xFFFFu,     0x10000u,   0x10001u,
                           0x7FFFFFFFu, 0x80000000u, 0x80000001u, 0xFFFFFFFEu, 0xFFFFFFFFu};
    for (size_t i = 0; i < sizeof(ds) / sizeof(ds[0]); i++) {
        const uint32_t d = ds[i];
        /* largest n with the quotient in 32 bits after rounding: d*2^32 - d/2 - 1 */
        const uint64_t nmax = (uint64_t)d * 0xFFFFFFFFull + (uint64_t)(d - 1u) - (d >> 1);
        const uint64_t ns[] = {0u, 1u, d, (uint64_t)d * 2u + 1u, nmax / 2u, nmax};
        for (size_t j = 0; j < sizeof(ns) / sizeof(ns[0]); j++) {
            const uint64_t n = ns[j];
            const uint64_t ref = (n + (d >> 1)) / d;
            assert_int_equal(fx_udiv64_32_round(n, d), (uint32_t)ref);
        }
    }
    for (int k = 0; k < 200000; k++) {
        uint32_t d = (uint32_t)rng_next() >> (rng_next() % 31u);
        d = (d == 0u) ? 1u : d;
        const uint64_t n = rng_next() % ((uint64_t)d << 31); /* quotient < 2^31 */
        const uint64_t ref = (n + (d >> 1)) / d;
        assert_int_equal(fx_udiv64_32_round(n, d), (uint32_t)ref);
    }
}

/* fx_mul64_u32 against the exact 128-bit product rounded half up: within 1 LSB (it floors the
 * low 31 bits before rounding); fx_scale_apply of factors from 1e-9 to 1e9 between formats
 * against long double: within 1 LSB of the output (2^post when it shifts left). */
static void test_mul64_scale(void **state)
{
    (void)state;
    for (int k = 0; k < 200000; k++) {
        const int64_t a = (int64_t)(rng_next() >> 3) * ((rng_next() & 1u) ? 1 : -1);
        const uint32_t m = (uint32_t)rng_next();
        const unsigned sh = 31u + (unsigned)(rng_next() % 63u);
        const __int128 p = (__int128)a * m;
        const __int128 ref = (p + ((__int128)1 << (sh - 1u))) >> sh;
        const __int128 d = (__int128)fx_mul64_u32(a, m, sh) - ref;
        assert_true(d >= -1 && d <= 1);
    }
    const double vs[] = {1e-9, 3.7e-6, 0.001, 0.05, 1.0, 3.0, 280.0, 1000.0, 1e4, 7.3e6, 1e9};
    const int32_t fmt[][2] = {{32, 48}, {48, 32}, {55, 48}, {48, 40}, {48, 48}, {32, 24}};
    for (size_t i = 0; i < sizeof vs / sizeof vs[0]; i++) {
        for (size_t j = 0; j < sizeof fmt / sizeof fmt[0]; j++) {
            fx_scale_t c;
            const fs_status_t rc = fx_scale_from_double(vs[i], fmt[j][0], fmt[j][1], &c);
            const long double f = ldexpl((long double)vs[i], fmt[j][1] - fmt[j][0]);
            if (f >= ldexpl(1.0L, 61)) {
                assert_int_equal(rc, FS_ERR_FIXED_OVERFLOW);
                continue;
            }
            assert_int_equal(rc, FS_OK);
            for (int k = 0; k < 2000; k++) {
                const int64_t a = (int64_t)(rng_next() >> (3u + rng_next() % 58u)) *
                                  ((rng_next() & 1u) ? 1 : -1);
                const long double exact = (long double)a * f;
                if (fabsl(exact) >= ldexpl(1.0L, 60)) {
                    continue;
                }
                const long double err = fabsl((long double)fx_scale_apply(a, c) - exact);
                /* the mantissa's rounding (2^-32 relative) + 1 LSB of the output */
                assert_true(err <= fabsl(exact) * ldexpl(1.0L, -31) + ldexpl(1.0L, c.post) + 1.0L);
            }
        }
    }
    fx_scale_t c;
    assert_int_equal(fx_scale_from_double(-1.0, 0, 0, &c), FS_ERR_FIXED_OVERFLOW);
    assert_int_equal(fx_scale_from_double(NAN, 0, 0, &c), FS_ERR_FIXED_OVERFLOW);
    assert_int_equal(fx_scale_from_double(0.0, 0, 0, &c), FS_OK);
    assert_true(fx_scale_apply(123456789, c) == 0);
    /* saturation at +-FX_S61_MAX, never wrap */
    assert_int_equal(fx_scale_from_double(1e6, 0, 0, &c), FS_OK);
    assert_true(fx_scale_apply(INT64_MAX, c) == FX_S61_MAX);
    assert_true(fx_scale_apply(INT64_MIN, c) == -FX_S61_MAX);
}

static void test_from_double(void **state)
{
    (void)state;
    int32_t out = 0;
    assert_int_equal(fx_from_double(1.0, 24u, INT32_MAX, &out), FS_OK);
    assert_int_equal(out, FX_Q24_ONE);
    assert_int_equal(fx_from_double(-0.5, 31u, INT32_MAX, &out), FS_OK);
    assert_int_equal(out, -(1 << 30));
    assert_int_equal(fx_from_double(1.0, 31u, INT32_MAX, &out), FS_ERR_FIXED_OVERFLOW);
    assert_int_equal(fx_from_double(128.0, 24u, INT32_MAX, &out), FS_ERR_FIXED_OVERFLOW);
    assert_int_equal(fx_from_double(127.99999994, 24u, INT32_MAX, &out), FS_OK);
    assert_int_equal(out, INT32_MAX);
    assert_int_equal(fx_from_double(-128.0, 24u, INT32_MAX, &out), FS_ERR_FIXED_OVERFLOW);
    assert_int_equal(fx_from_double(NAN, 24u, INT32_MAX, &out), FS_ERR_FIXED_OVERFLOW);
    assert_int_equal(fx_from_double(INFINITY, 24u, INT32_MAX, &out), FS_ERR_FIXED_OVERFLOW);
    assert_int_equal(fx_from_double(65.0, 24u, 64 << 24, &out), FS_ERR_FIXED_OVERFLOW);
    /* round to nearest: within 1/2 LSB */
    assert_int_equal(fx_from_double(0.1, 24u, INT32_MAX, &out), FS_OK);
    assert_true(fabs(fx_to_double(out, 24u) - 0.1) <= ldexp(0.5, -24));
}

/* Float32 <-> fixed by bits against the double reference: round to nearest (the exact value
 * floor(v*2^q + 0.5) for v >= 0), saturation, NaN, subnormals; back to float exactly rounded. */
static void test_float_conversions(void **state)
{
    (void)state;
    assert_int_equal(fx_from_float(1.0f, 24u), FX_Q24_ONE);
    assert_int_equal(fx_from_float(-0.5f, 31u), -(1 << 30));
    assert_int_equal(fx_from_float(1.0f, 31u), INT32_MAX);
    assert_int_equal(fx_from_float(-1.0f, 31u), INT32_MIN);
    assert_int_equal(fx_from_float(200.0f, 24u), INT32_MAX);
    assert_int_equal(fx_from_float(-INFINITY, 16u), INT32_MIN);
    assert_int_equal(fx_from_float(INFINITY, 16u), INT32_MAX);
    assert_int_equal(fx_from_float(NAN, 16u), 0);
    assert_int_equal(fx_from_float(1e-40f, 31u), 0);
    assert_int_equal(fx_from_float(0.0f, 24u), 0);
    assert_true(fx_to_float(0, 24u) == 0.0f);
    assert_true(fx_acc_to_float(0, -55) == 0.0f);
    for (int i = 0; i < 200000; i++) {
        const unsigned q = (unsigned)(rng_next() % 32u);
        const double mag = ldexp((double)(rng_next() % 1000000u) / 1e6,
                                 (int)(rng_next() % 40u) - 32);
        const float v = (float)((rng_next() & 1u) ? -mag : mag);
        const double scaled = ldexp((double)v, (int)q);
        if (fabs(scaled) < 2147483647.0) {
            /* ties away from zero: floor(|x| + 0.5) with the sign of x */
            const double ref = copysign(floor(fabs(scaled) + 0.5), scaled);
            assert_true((double)fx_from_float(v, q) == ref);
        }
        const int32_t x = (int32_t)(uint32_t)rng_next();
        assert_true(fx_to_float(x, q) == (float)ldexp((double)x, -(int)q) ||
                    fabs((double)fx_to_float(x, q) - ldexp((double)x, -(int)q)) <=
                        0.5 * ldexp(fabs((double)x), -(int)q) * 0x1p-23);
        const int64_t acc = (int64_t)(((uint64_t)rng_next() << 32) | rng_next()) >>
                            (rng_next() % 40u);
        const double a_ref = ldexp((double)acc, -55);
        assert_true(fabs((double)fx_acc_to_float(acc, -55) - a_ref) <= fabs(a_ref) * 0x1p-24);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_sat_add_sub),
        cmocka_unit_test(test_sat_fast_paths),
        cmocka_unit_test(test_rshift_round_var),
        cmocka_unit_test(test_mul_round_exact),
        cmocka_unit_test(test_exp_table),
        cmocka_unit_test(test_udiv),
        cmocka_unit_test(test_mul64_scale),
        cmocka_unit_test(test_from_double),
        cmocka_unit_test(test_float_conversions),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

/* Skill image v2 parsing (docs/skill_format.md): CRC-32 against the standard check value, a
 * valid image round trip, and one or more images for every rejection code, including the check
 * order. Images are built here with a small byte writer (core_test_util.c). Built double and float. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <cmocka.h>

#include "core_test_util.h"
#include "skill.h"

#define H SKILL_HEADER_SIZE_V2
#define CAP (H + 24u * 1100u + 4u)

static tu_skill_desc_t desc;
static uint8_t img[CAP];
static skill_t sk;

/* Offsets of header f64 fields (docs/skill_format.md). */
enum {
    O_DT = 16,
    O_TAU = 24,
    O_ALPHA = 32,
    O_BETA = 40,
    O_GAMMA = 48,
    O_K = 56,
    O_G = 64,
    O_T = 72,
    O_MD = 80,
    O_KD = 88,
    O_KP = 96,
    O_KKF = 104,
    O_KKI = 112,
    O_SURF = 120,
    O_F0 = 128
};

static uint32_t valid_image(uint16_t n)
{
    tu_default_desc(&desc, n, 280.0, 8.0);
    desc.flags = 1;
    const uint32_t len = tu_write_image(&desc, img, CAP);
    assert_int_equal(len, skill_image_size(n));
    return len;
}

static skill_t sk_sliced;

/* skill_parse, and the same image parsed one unit per call (skill_parse_run): the same status
 * and, when valid, the same skill byte for byte and the image's CRC. */
static void expect(const char *what, uint32_t len, fs_status_t want)
{
    memset(&sk, 0, sizeof sk);
    memset(&sk_sliced, 0, sizeof sk_sliced);
    const fs_status_t got = skill_parse(img, len, &sk);
    if (got != want) {
        fail_msg("%s: skill_parse returned %d, expected %d", what, (int)got, (int)want);
    }
    skill_parser_t p;
    skill_parse_begin(&p, img, len, &sk_sliced);
    uint32_t calls = 1u;
    while (!skill_parse_run(&p, 1u)) {
        calls++;
    }
    if (p.status != want) {
        fail_msg("%s: sliced parse returned %d, expected %d", what, (int)p.status, (int)want);
    }
    if (want == FS_OK) {
        assert_memory_equal(&sk, &sk_sliced, sizeof sk);
        assert_true(calls > 3u * sk.dmp.n_kernels); /* widths, centres, values: a unit a kernel */
        uint32_t stored;
        memcpy(&stored, &img[len - 4u], 4);
        assert_int_equal(p.crc, stored);
    }
}

/* Patch a header f64, fix the CRC, expect a code. */
static void expect_f64(const char *what, uint32_t off, double v, fs_status_t want)
{
    const uint32_t len = valid_image(10);
    tu_put_f64(img, off, v);
    tu_fix_crc(img, len);
    expect(what, len, want);
}

static void test_crc32_check_value(void **state)
{
    (void)state;
    const uint8_t check[] = "123456789";
    assert_int_equal(skill_crc32(0u, check, 9u), 0xCBF43926u);
    assert_int_equal(skill_crc32(0u, check, 0u), 0u);
    /* continuation: crc(a||b) = crc(crc(a), b) */
    assert_int_equal(skill_crc32(skill_crc32(0u, check, 4u), check + 4, 5u), 0xCBF43926u);
    const uint8_t zeros[32] = {0};
    assert_int_equal(skill_crc32(0u, zeros, 32u), 0x190A55ADu);
}

static void test_image_size(void **state)
{
    (void)state;
    assert_int_equal(skill_image_size(1), 164u);
    assert_int_equal(skill_image_size(50), 136u + 1200u + 4u);
    assert_int_equal(skill_image_size(1024), 136u + 24576u + 4u);
    assert_int_equal(skill_image_size(256), 136u + 6144u + 4u);
}

static void test_valid_round_trip(void **state)
{
    (void)state;
    const uint16_t ns[] = {1, 2, 50, 256, 1024};
    for (size_t k = 0; k < 5; k++) {
        const uint16_t n = ns[k];
        const uint32_t len = valid_image(n);
        expect("valid image, whole and sliced", len, FS_OK);
        const dmp_model_t *m = &sk.dmp;
        assert_int_equal(m->n_kernels, n);
        assert_true(m->dt_s == (fs_real_t)desc.dt_s);
        assert_true(m->tau_s == (fs_real_t)desc.tau_s);
        assert_true(m->p.alpha == (fs_real_t)desc.alpha);
        assert_true(m->p.beta == (fs_real_t)desc.beta);
        assert_true(m->p.gamma == (fs_real_t)desc.gamma);
        assert_true(sk.stiffness_Npm == (fs_real_t)desc.stiffness_Npm);
        assert_true(m->goal_N == (fs_real_t)desc.goal_N);
        assert_true(m->force0_N == (fs_real_t)desc.force0_N);
        assert_true(m->duration_s == (fs_real_t)desc.duration_s);
        assert_true(sk.gains.m_d_kg == (fs_real_t)desc.m_d);
        assert_true(sk.gains.k_d_Nspm == (fs_real_t)desc.k_d);
        assert_true(sk.gains.k_p_Npm == (fs_real_t)desc.k_p);
        assert_true(sk.fit_gains.kkf_Npm == (fs_real_t)desc.kkf);
        assert_true(sk.fit_gains.kki_Npms == (fs_real_t)desc.kki);
        /* controller gains at the nominal k */
        assert_true(fabs((double)sk.gains.k_f - desc.kkf / desc.stiffness_Npm) <=
                    1e-6 * desc.kkf / desc.stiffness_Npm);
        assert_true(fabs((double)sk.gains.k_i_per_s - desc.kki / desc.stiffness_Npm) <=
                    1e-6 * desc.kki / desc.stiffness_Npm);
        assert_true(sk.surface_m == (fs_real_t)desc.surface_m);
        assert_int_equal(sk.end_policy, SKILL_END_RELEASE);
        for (uint16_t i = 0; i < n; i++) {
            assert_true(m->centre[i] == (fs_real_t)desc.centre[i]);
            assert_true(m->width[i] == (fs_real_t)desc.width[i]);
            assert_true(m->weight[i] == (fs_real_t)desc.weight[i]);
            /* dmp_model_init ran */
            assert_true(m->kernel_scale[i] > FS_R(0.0));
        }
    }
    /* hold policy */
    uint32_t len = valid_image(5);
    tu_put_u16(img, 14, 0);
    tu_fix_crc(img, len);
    assert_int_equal(skill_parse(img, len, &sk), FS_OK);
    assert_int_equal(sk.end_policy, SKILL_END_HOLD);
    /* beta exactly alpha/4 (the default gains) and a stored beta 1e-10 relative above the
     * derived value are both accepted */
    len = valid_image(5);
    tu_put_f64(img, O_BETA, desc.beta * (1.0 + 1e-10));
    tu_fix_crc(img, len);
    assert_int_equal(skill_parse(img, len, &sk), FS_OK);
}

static void test_reject_structure(void **state)
{
    (void)state;
    uint32_t len = valid_image(10);
    expect("empty", 0, FS_ERR_SKILL_TOO_SHORT);
    expect("5 bytes", 5, FS_ERR_SKILL_TOO_SHORT);
    expect("135 bytes", H - 1u, FS_ERR_SKILL_TOO_SHORT);
    assert_int_equal(skill_parse(NULL, len, &sk), FS_ERR_NULL_ARG);
    assert_int_equal(skill_parse(img, len, NULL), FS_ERR_NULL_ARG);

    len = valid_image(10);
    img[0] = 'X';
    tu_fix_crc(img, len);
    expect("magic", len, FS_ERR_SKILL_MAGIC);

    len = valid_image(10);
    tu_put_u16(img, 4, 1);
    tu_fix_crc(img, len);
    expect("version 1 (metres, k-dependent gains)", len, FS_ERR_SKILL_VERSION);
    expect("version 1, a v1-sized buffer", H - 8u, FS_ERR_SKILL_VERSION);
    tu_put_u16(img, 4, 6);
    tu_fix_crc(img, len);
    expect("version 6", len, FS_ERR_SKILL_VERSION);
    tu_put_u16(img, 4, 3);
    tu_fix_crc(img, len);
    expect("version 3 with the v2 header size", len, FS_ERR_SKILL_HEADER_SIZE);
    tu_put_u16(img, 4, 0);
    tu_fix_crc(img, len);
    expect("version 0", len, FS_ERR_SKILL_VERSION);

    len = valid_image(10);
    tu_put_u16(img, 6, 64);
    tu_fix_crc(img, len);
    expect("header_size", len, FS_ERR_SKILL_HEADER_SIZE);

    len = valid_image(10);
    expect("buffer shorter than total_length", len - 1, FS_ERR_SKILL_LENGTH);
    expect("header only", H, FS_ERR_SKILL_LENGTH);
    expect("buffer longer than total_length", len + 8, FS_ERR_SKILL_LENGTH);
    tu_put_u32(img, 8, len + 24);
    tu_fix_crc(img, len);
    expect("total_length field wrong", len, FS_ERR_SKILL_LENGTH);
    len = valid_image(10);
    tu_put_u16(img, 12, 11);
    tu_fix_crc(img, len);
    expect("N disagrees with total_length", len, FS_ERR_SKILL_LENGTH);

    len = valid_image(10);
    img[H + 16 * 10 + 3] ^= 0x40u; /* a weight bit */
    expect("CRC (payload flipped)", len, FS_ERR_SKILL_CRC);
    len = valid_image(10);
    img[len - 1] ^= 0x01u;
    expect("CRC (stored CRC flipped)", len, FS_ERR_SKILL_CRC);

    /* N = 0 with a consistent length and CRC */
    len = valid_image(1);
    tu_put_u16(img, 12, 0);
    tu_put_u32(img, 8, H + 4u);
    len = H + 4u;
    tu_fix_crc(img, len);
    expect("N = 0", len, FS_ERR_SKILL_KERNELS);
    /* N = DMP_MAX_KERNELS + 1 with a consistent length and CRC */
    tu_default_desc(&desc, DMP_MAX_KERNELS, 280.0, 8.0);
    desc.n_kernels = DMP_MAX_KERNELS;
    len = tu_write_image(&desc, img, CAP);
    {
        /* grow by one kernel by hand */
        static uint8_t big[CAP];
        const uint32_t m = DMP_MAX_KERNELS, n = m + 1u, blen = H + 24 * n + 4;
        memcpy(big, img, H);
        for (uint32_t i = 0; i < n; i++) {
            const uint32_t src = (i < m) ? i : m - 1u;
            tu_put_f64(big, H + 8 * i, (double)i / (double)(n + 10u));
            memcpy(big + H + 8 * n + 8 * i, img + H + 8 * m + 8 * src, 8);
            memcpy(big + H + 16 * n + 8 * i, img + H + 16 * m + 8 * src, 8);
        }
        tu_put_u16(big, 12, (uint16_t)n);
        tu_put_u32(big, 8, blen);
        tu_fix_crc(big, blen);
        const fs_status_t st = skill_parse(big, blen, &sk);
        assert_int_equal(st, FS_ERR_SKILL_KERNELS);
    }
}

static void test_reject_values(void **state)
{
    (void)state;
    /* 206: every f64 field must be finite, including ones no range check looks at */
    expect_f64("dt NaN", O_DT, NAN, FS_ERR_SKILL_NOT_FINITE);
    expect_f64("surface NaN", O_SURF, NAN, FS_ERR_SKILL_NOT_FINITE);
    expect_f64("kki inf", O_KKI, INFINITY, FS_ERR_SKILL_NOT_FINITE);
    expect_f64("f0 NaN", O_F0, NAN, FS_ERR_SKILL_NOT_FINITE);
    expect_f64("f0 -0.8 N (a sensor bias) accepted", O_F0, -0.8, FS_OK);
    expect_f64("f0 3 N (in contact) accepted", O_F0, 3.0, FS_OK);
    expect_f64("gamma -inf", O_GAMMA, -INFINITY, FS_ERR_SKILL_NOT_FINITE);
    expect_f64("centre NaN", H, NAN, FS_ERR_SKILL_NOT_FINITE);
    expect_f64("width inf", H + 8 * 10 + 8 * 9, INFINITY, FS_ERR_SKILL_NOT_FINITE);
    expect_f64("weight NaN", H + 16 * 10 + 8 * 9, NAN, FS_ERR_SKILL_NOT_FINITE);
    /* 207 */
    expect_f64("dt 0", O_DT, 0.0, FS_ERR_SKILL_RANGE);
    expect_f64("dt > 0.1", O_DT, 0.2, FS_ERR_SKILL_RANGE);
    expect_f64("tau 0", O_TAU, 0.0, FS_ERR_SKILL_RANGE);
    expect_f64("tau < 0", O_TAU, -1.0, FS_ERR_SKILL_RANGE);
    expect_f64("T 0", O_T, 0.0, FS_ERR_SKILL_RANGE);
    expect_f64("T > 3600", O_T, 3600.5, FS_ERR_SKILL_RANGE);
    expect_f64("k 0", O_K, 0.0, FS_ERR_SKILL_RANGE);
    expect_f64("g 0", O_G, 0.0, FS_ERR_SKILL_RANGE);
    expect_f64("g < 0", O_G, -0.01, FS_ERR_SKILL_RANGE);
    expect_f64("sigma 0", H + 8 * 10 + 8 * 4, 0.0, FS_ERR_SKILL_RANGE);
    expect_f64("sigma < 0", H + 8 * 10, -0.01, FS_ERR_SKILL_RANGE);
    /* boundary values accepted */
    expect_f64("dt 0.1", O_DT, 0.1, FS_OK);
    expect_f64("T 3600", O_T, 3600.0, FS_OK);
    /* 208 */
    expect_f64("centre < 0", H, -1e-9, FS_ERR_SKILL_CENTRES);
    expect_f64("centre > 1", H + 8 * 9, 1.0 + 1e-9, FS_ERR_SKILL_CENTRES);
    {
        const uint32_t len = valid_image(10);
        tu_put_f64(img, H + 8 * 5, desc.centre[4]);
        tu_fix_crc(img, len);
        expect("centres equal", len, FS_ERR_SKILL_CENTRES);
        tu_put_f64(img, H + 8 * 5, desc.centre[4] - 1e-6);
        tu_fix_crc(img, len);
        expect("centres decreasing", len, FS_ERR_SKILL_CENTRES);
    }
    /* 209 */
    const uint32_t len10 = valid_image(10);
    (void)len10;
    expect_f64("alpha off by 1e-8 rel", O_ALPHA, desc.alpha * (1.0 + 1e-8), FS_ERR_SKILL_GAINS);
    expect_f64("beta off by 1e-8 rel", O_BETA, desc.beta * (1.0 - 1e-8), FS_ERR_SKILL_GAINS);
    expect_f64("gamma off", O_GAMMA, desc.gamma * 1.01, FS_ERR_SKILL_GAINS);
    expect_f64("k changed: the DMP does not depend on it", O_K, 1e7, FS_OK);
    expect_f64("k_d <= m_d", O_KD, 40.0, FS_ERR_SKILL_GAINS);
    expect_f64("m_d <= 0", O_MD, 0.0, FS_ERR_SKILL_GAINS);
    expect_f64("kkf < 0", O_KKF, -1.0, FS_ERR_SKILL_GAINS);
    {
        /* consistent alpha/beta/gamma but beta > alpha/4: k_p raised */
        uint32_t len = valid_image(10);
        const double k_p = 1300.0;
        const double beta = (k_p + (desc.kkf - desc.kki / desc.alpha)) / (desc.m_d * desc.alpha) -
                            1.0;
        assert_true(beta > desc.alpha / 4.0);
        tu_put_f64(img, O_KP, k_p);
        tu_put_f64(img, O_BETA, beta);
        tu_fix_crc(img, len);
        expect("beta > alpha/4", len, FS_ERR_SKILL_GAINS);
        /* beta <= 0 with consistent values: k_p = 0, kkf = 0 */
        len = valid_image(10);
        tu_put_f64(img, O_KP, 0.0);
        tu_put_f64(img, O_KKF, 0.0);
        tu_put_f64(img, O_KKI, 0.0);
        tu_put_f64(img, O_GAMMA, 0.0);
        tu_put_f64(img, O_BETA, -1.0);
        tu_fix_crc(img, len);
        expect("beta <= 0", len, FS_ERR_SKILL_GAINS);
    }
    /* 210 */
    {
        uint32_t len = valid_image(10);
        tu_put_u16(img, 14, 0x0002);
        tu_fix_crc(img, len);
        expect("y-axis flag (reserved)", len, FS_ERR_SKILL_UNSUPPORTED);
        tu_put_u16(img, 14, 0x8001);
        tu_fix_crc(img, len);
        expect("unknown flag bit 15", len, FS_ERR_SKILL_UNSUPPORTED);
    }
}

/* First failure wins, in the documented order. */
static void test_check_order(void **state)
{
    (void)state;
    uint32_t len = valid_image(10);
    img[0] = 'X';
    tu_put_u16(img, 4, 9);
    expect("magic before version", len, FS_ERR_SKILL_MAGIC);
    len = valid_image(10);
    tu_put_u16(img, 4, 9);
    tu_put_u16(img, 6, 1);
    expect("version before header_size", len, FS_ERR_SKILL_VERSION);
    len = valid_image(10);
    tu_put_u16(img, 6, 1);
    tu_put_u32(img, 8, 7);
    expect("header_size before length", len, FS_ERR_SKILL_HEADER_SIZE);
    len = valid_image(10);
    img[200] ^= 1u;
    expect("length before CRC", len - 4, FS_ERR_SKILL_LENGTH);
    len = valid_image(10);
    tu_put_f64(img, O_DT, NAN);
    expect("CRC before finiteness", len, FS_ERR_SKILL_CRC);
    len = valid_image(10);
    tu_put_f64(img, O_DT, 0.0);
    tu_put_f64(img, O_SURF, NAN);
    tu_fix_crc(img, len);
    expect("finiteness before range", len, FS_ERR_SKILL_NOT_FINITE);
    len = valid_image(10);
    tu_put_f64(img, O_DT, 0.0);
    tu_put_f64(img, H, 2.0);
    tu_fix_crc(img, len);
    expect("range before centres", len, FS_ERR_SKILL_RANGE);
    len = valid_image(10);
    tu_put_f64(img, H, 2.0);
    tu_put_f64(img, O_ALPHA, 1.0);
    tu_fix_crc(img, len);
    expect("centres before gains", len, FS_ERR_SKILL_CENTRES);
    len = valid_image(10);
    tu_put_f64(img, O_ALPHA, 1.0);
    tu_put_u16(img, 14, 0x00F0);
    tu_fix_crc(img, len);
    expect("gains before flags", len, FS_ERR_SKILL_GAINS);
}

#ifdef FS_REAL_FLOAT
/* Valid in double but outside the float core: refused by the float build only. */
static void test_float_range(void **state)
{
    (void)state;
    expect_f64("weight 1e300 (float)", H + 16 * 10, 1e300, FS_ERR_SKILL_RANGE);
    expect_f64("sigma 1e-30 (float: 1/(2 sigma^2) overflows)", H + 8 * 10, 1e-30,
               FS_ERR_SKILL_RANGE);
}
#else
static void test_double_accepts_extremes(void **state)
{
    (void)state;
    expect_f64("weight 1e300 (double)", H + 16 * 10, 1e300, FS_OK);
}
#endif

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_crc32_check_value), cmocka_unit_test(test_image_size),
        cmocka_unit_test(test_valid_round_trip),  cmocka_unit_test(test_reject_structure),
        cmocka_unit_test(test_reject_values),     cmocka_unit_test(test_check_order),
#ifdef FS_REAL_FLOAT
        cmocka_unit_test(test_float_range),
#else
        cmocka_unit_test(test_double_accepts_extremes),
#endif
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

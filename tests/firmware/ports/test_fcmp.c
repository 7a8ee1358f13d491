/* The images' integer compares of binary32/binary64 bit patterns (firmware/ports/mps2/cm_fcmp.h)
 * against the host's hardware compares (IEEE 754, SSE): every pair of a set of edge values
 * (signed zeros, subnormals, the smallest and largest normals, neighbours, infinities, quiet and
 * signalling NaNs with payloads) and millions of random pairs, random bit patterns and
 * neighbours one ulp apart. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "cm_fcmp.h"

static float f32_of(uint32_t b)
{
    float v;
    memcpy(&v, &b, sizeof v);
    return v;
}

static double f64_of(uint64_t b)
{
    double v;
    memcpy(&v, &b, sizeof v);
    return v;
}

static uint64_t g_rng = 0x9E3779B97F4A7C15ull;

static uint64_t rng64(void)
{
    /* xorshift64*: a fixed seed, the same pairs every run */
    g_rng ^= g_rng >> 12;
    g_rng ^= g_rng << 25;
    g_rng ^= g_rng >> 27;
    return g_rng * 0x2545F4914F6CDD1Dull;
}

static unsigned g_fails;

static void check32(uint32_t a, uint32_t b)
{
    const float x = f32_of(a);
    const float y = f32_of(b);
    const int want[6] = {x == y, x<y, x <= y, x> y, x >= y, x != x || y != y};
    const int got[6] = {cm_f32_eq(a, b), cm_f32_lt(a, b), cm_f32_le(a, b),
                        cm_f32_lt(b, a), cm_f32_le(b, a), cm_f32_un(a, b)};
    for (int i = 0; i < 6; i++) {
        if (want[i] != got[i] && g_fails++ < 10u) {
            print_error("binary32 %08x %08x op %d: want %d got %d\n", a, b, i, want[i], got[i]);
        }
    }
}

static void check64(uint64_t a, uint64_t b)
{
    const double x = f64_of(a);
    const double y = f64_of(b);
    const int want[6] = {x == y, x<y, x <= y, x> y, x >= y, x != x || y != y};
    const int got[6] = {cm_f64_eq(a, b), cm_f64_lt(a, b), cm_f64_le(a, b),
                        cm_f64_lt(b, a), cm_f64_le(b, a), cm_f64_un(a, b)};
    for (int i = 0; i < 6; i++) {
        if (want[i] != got[i] && g_fails++ < 10u) {
            print_error("binary64 %016llx %016llx op %d: want %d got %d\n", (unsigned long long)a,
                        (unsigned long long)b, i, want[i], got[i]);
        }
    }
}

static const uint32_t EDGE32[] = {
    0x00000000u, 0x00000001u, 0x00000002u, 0x007FFFFFu, 0x00800000u, 0x00800001u,
    0x3F7FFFFFu, 0x3F800000u, 0x3F800001u, 0x7F7FFFFEu, 0x7F7FFFFFu, 0x7F800000u,
    0x7F800001u, 0x7FBFFFFFu, 0x7FC00000u, 0x7FFFFFFFu,
};

static const uint64_t EDGE64[] = {
    0x0000000000000000ull, 0x0000000000000001ull,
    0x000FFFFFFFFFFFFFull, 0x0010000000000000ull,
    0x0010000000000001ull, 0x3FEFFFFFFFFFFFFFull,
    0x3FF0000000000000ull, 0x3FF0000000000001ull,
    0x3FF0000100000000ull, 0x3FF0000000000000ull ^ 0x0000000100000000ull,
    0x7FEFFFFFFFFFFFFFull, 0x7FF0000000000000ull,
    0x7FF0000000000001ull, 0x7FF7FFFFFFFFFFFFull,
    0x7FF8000000000000ull, 0x7FFFFFFFFFFFFFFFull,
};

static void test_edges(void **state)
{
    (void)state;
    g_fails = 0u;
    const size_t n32 = sizeof EDGE32 / sizeof EDGE32[0];
    for (size_t i = 0; i < 2u * n32; i++) {
        const uint32_t a = EDGE32[i % n32] | ((i >= n32) ? 0x80000000u : 0u);
        for (size_t j = 0; j < 2u * n32; j++) {
            check32(a, EDGE32[j % n32] | ((j >= n32) ? 0x80000000u : 0u));
        }
    }
    const size_t n64 = sizeof EDGE64 / sizeof EDGE64[0];
    for (size_t i = 0; i < 2u * n64; i++) {
        const uint64_t a = EDGE64[i % n64] | ((i >= n64) ? 0x8000000000000000ull : 0u);
        for (size_t j = 0; j < 2u * n64; j++) {
            check64(a, EDGE64[j % n64] | ((j >= n64) ? 0x8000000000000000ull : 0u));
        }
    }
    assert_int_equal(g_fails, 0u);
}

static void test_random_pairs(void **state)
{
    (void)state;
    g_fails = 0u;
    for (uint32_t i = 0u; i < 1000000u; i++) {
        const uint64_t r = rng64();
        const uint32_t a = (uint32_t)r;
        const uint32_t b = (uint32_t)(r >> 32);
        check32(a, b);
        /* the same value, its neighbours one ulp each way and its negation */
        check32(a, a);
        check32(a, a + 1u);
        check32(a + 1u, a);
        check32(a, a ^ 0x80000000u);
        const uint64_t c = rng64();
        const uint64_t d = rng64();
        check64(c, d);
        check64(c, c);
        check64(c, c + 1u);
        check64(c + 1u, c);
        check64(c, c ^ 0x8000000000000000ull);
        /* same sign and exponent, random fractions: the close calls */
        check32(a, (a & 0xFF800000u) | (b & 0x007FFFFFu));
        check64(c, (c & 0xFFF0000000000000ull) | (d & 0x000FFFFFFFFFFFFFull));
    }
    assert_int_equal(g_fails, 0u);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_edges),
        cmocka_unit_test(test_random_pairs),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

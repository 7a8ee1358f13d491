/* Saturating Q-format arithmetic for the fixed-point build (docs/cortex-m.md): the
 * helpers of the fixed half of the numeric layer (fs_num_fixed.h, fs_num.h).
 * Every helper works on int32 values with 64-bit intermediates; results that do not fit are
 * saturated to the int32 range, never wrapped, and no helper has signed-overflow UB.
 * Right shifts of negative values rely on arithmetic shift (GCC and Clang define it).
 * Rounding: round half up (floor(x + 0.5)) wherever precision is dropped.
 * Formats used (Qm.n = m integer bits incl. sign, n fraction bits):
 *   phase u~, v~, centres c_i    Q2.30      1/sigma_i        Q13.19
 *   kernel exponent e_i          Q5.27 (unsigned, clipped at 16)
 *   kernel activation psi_i      Q1.31 (unsigned, 1.0 = 2^31)
 *   w_i, x, z, I, h, g           Q8.24      per-tick constants  Q1.31
 *   forces                       Q16.16 N   DMP output scale    Q20.12 */
#ifndef FX_H
#define FX_H

#include <stdint.h>
#include "fs_status.h"

/* 3xx codes (FS_ERR_FIXED_*) are in fs_status.h with the other numbered codes. */

#define FX_Q30_ONE ((int32_t)1 << 30)
#define FX_Q31_ONE_U ((uint32_t)1u << 31)
#define FX_Q24_ONE ((int32_t)1 << 24)
#define FX_Q16_ONE ((int32_t)1 << 16)
/* exp argument clip: 16 in Q5.27 = 2^31 (unsigned). */
#define FX_EXP_ARG_MAX_Q27 ((uint32_t)16u << 27)
/* Table resolution of 2^-f, f in [0, 1): 2^FX_EXP_TABLE_BITS intervals, linear interpolation.
 * Interpolation error <= (ln2 * 2^-bits)^2 / 8 relative = 9.2e-7 for 8 bits. */
#define FX_EXP_TABLE_BITS 8u

/** Clamp a 64-bit value into int32 (saturation, never wrap). */
static inline int32_t fx_sat32(int64_t v)
{
    /* in range iff the high word is the low word's sign extension: one 32-bit compare */
    if ((int32_t)((uint64_t)v >> 32) == ((int32_t)(uint32_t)v >> 31)) {
        return (int32_t)v;
    }
    if (v > (int64_t)INT32_MAX) {
        return INT32_MAX;
    }
    if (v < (int64_t)INT32_MIN) {
        return INT32_MIN;
    }
    return (int32_t)v;
}

/** Saturating a + b (overflow detected by the compiler builtin: adds + bvs on ARM). */
static inline int32_t fx_add_sat(int32_t a, int32_t b)
{
    int32_t r;
    if (__builtin_add_overflow(a, b, &r)) {
        return (a < 0) ? INT32_MIN : INT32_MAX;
    }
    return r;
}

/** Saturating a - b. */
static inline int32_t fx_sub_sat(int32_t a, int32_t b)
{
    int32_t r;
    if (__builtin_sub_overflow(a, b, &r)) {
        return (a < 0) ? INT32_MIN : INT32_MAX;
    }
    return r;
}

/** Saturating a * k for an integer k (e.g. a unit scale or 1/dt). */
static inline int32_t fx_mul_int_sat(int32_t a, int32_t k)
{
    int32_t r;
    if (__builtin_mul_overflow(a, k, &r)) {
        return ((a < 0) != (k < 0)) ? INT32_MIN : INT32_MAX;
    }
    return r;
}

/** v / 2^s rounded half up, 1 <= s <= 62, |v| < 2^62 (no overflow in the rounding add). */
static inline int64_t fx_rshift_round(int64_t v, unsigned s)
{
    return (v + ((int64_t)1 << (s - 1u))) >> s;
}

/** Saturating product a*b / 2^s rounded half up (1 <= s <= 62): e.g. Q1.31 * Q8.24 with s = 31
 *  gives Q8.24. */
static inline int32_t fx_mul_sat(int32_t a, int32_t b, unsigned s)
{
    return fx_sat32(fx_rshift_round((int64_t)a * (int64_t)b, s));
}

/** Absolute value saturated: |INT32_MIN| -> INT32_MAX. */
static inline int32_t fx_abs_sat(int32_t a)
{
    return (a == INT32_MIN) ? INT32_MAX : ((a < 0) ? -a : a);
}

/** Clamp a to [-lim, lim] (lim >= 0). */
static inline int32_t fx_clamp_sym(int32_t a, int32_t lim)
{
    if (a > lim) {
        return lim;
    }
    if (a < -lim) {
        return -lim;
    }
    return a;
}

/* A DMP state accumulator (value * 2^31, the exact sum of its Euler increments) is kept within
 * +-(2^30 - 1)*2^32, so its view fits int32 with a margin of 2; the bound is checked on the high
 * word only. */
#define FX_ACC_HI_MAX 0x3FFFFFFF

/** A state accumulator's value in its working format (acc / 2^31 rounded: Q8.24 or Q2.30). */
static inline int32_t fx_acc_view(int64_t acc)
{
    return (int32_t)fx_rshift_round(acc, 31u);
}

/** r held within +-FX_ACC_HI_MAX*2^32, counting a saturation in *events: the in-range case by
 *  one unsigned compare of the high word. */
static inline int64_t fx_acc_hold(int64_t r, uint32_t *events)
{
    const int32_t hi = (int32_t)(r >> 32);
    if ((uint32_t)hi + (uint32_t)FX_ACC_HI_MAX < 2u * (uint32_t)FX_ACC_HI_MAX) {
        return r;
    }
    (*events)++;
    return (hi >= 0) ? (int64_t)FX_ACC_HI_MAX * 4294967296 : -(int64_t)FX_ACC_HI_MAX * 4294967296;
}

/** acc + inc held within +-FX_ACC_HI_MAX*2^32, counting a saturation in *events; needs
 *  |acc|, |inc| < 2^62 (Euler constants < 0.5), so the sum cannot overflow int64. */
static inline int64_t fx_acc_add(int64_t acc, int64_t inc, uint32_t *events)
{
    return fx_acc_hold(acc + inc, events);
}

/* Bound of the 64-bit values fx_scale_apply takes and returns: |v| <= FX_S61_MAX. */
#define FX_S61_MAX (((int64_t)1 << 61) - 1)

/** v clamped to +-FX_S61_MAX. */
static inline int64_t fx_clamp61(int64_t v)
{
    /* the common case by the high word alone: |high word| < 2^29 is within +-FX_S61_MAX */
    if ((uint32_t)((uint64_t)v >> 32) + 0x1FFFFFFFu <= 0x3FFFFFFEu) {
        return v;
    }
    return (v > FX_S61_MAX) ? FX_S61_MAX : ((v < -FX_S61_MAX) ? -FX_S61_MAX : v);
}

/** fx_rshift_round(t, k) for a shift known only at run time, 0 <= k <= 62, |t| < 2^62: in 32-bit
 *  words, the rounding bit added to the word it falls in (a generic 64-bit shift by a variable
 *  costs twice as many instructions on a 32-bit core). */
static inline int64_t fx_rshift_round_var(int64_t t, unsigned k)
{
    if (k == 0u) {
        return t;
    }
    const uint32_t tl = (uint32_t)(uint64_t)t;
    int32_t th = (int32_t)((uint64_t)t >> 32);
    if (k > 32u) { /* 2^(k-1) is in the high word, which alone holds the result */
        return (int64_t)((th + (int32_t)(1u << (k - 33u))) >> (k - 32u));
    }
    const uint32_t nl = tl + (1u << (k - 1u));
    th += (nl < tl) ? 1 : 0;
    if (k == 32u) {
        return (int64_t)th;
    }
    const uint32_t lo = (nl >> k) | ((uint32_t)th << (32u - k));
    return (int64_t)(((uint64_t)(uint32_t)(th >> k) << 32) | lo);
}

/** a*m / 2^s for |a| <= FX_S61_MAX, 31 <= s <= 93: the 96-bit product from 32x32 parts, floored
 *  to 2^-31 and then rounded half up (error < 1 LSB + 2^-31 of it); |result| < 2^62. */
static inline int64_t fx_mul64_u32(int64_t a, uint32_t m, unsigned s)
{
    const int64_t hi = (a >> 32) * (int64_t)m;               /* |a >> 32| < 2^29: < 2^61 */
    const uint64_t lo = (uint64_t)(uint32_t)(uint64_t)a * m; /* < 2^64 */
    const int64_t t = hi * 2 + (int64_t)(lo >> 31);          /* floor(a*m / 2^31) */
    return fx_rshift_round_var(t, s - 31u);
}

/** A non-negative constant factor c ~ mant * 2^(post - shift) between two fixed-point formats
 *  (fx_scale_from_double), applied per tick by fx_scale_apply in integers. */
typedef struct {
    uint32_t mant;
    uint8_t shift; /* 31..93 */
    uint8_t post;  /* left shift after the product (c >= 2^32 with shift 31) */
} fx_scale_t;

/** round(a*c) in the output format, |a| clamped to FX_S61_MAX first, the result held within
 *  +-FX_S61_MAX (saturated). */
static inline int64_t fx_scale_apply(int64_t a, fx_scale_t c)
{
    const int64_t r = fx_mul64_u32(fx_clamp61(a), c.mant, c.shift);
    if (c.post == 0u) {
        return fx_clamp61(r);
    }
    const unsigned p = c.post;
    if (p <= 29u) { /* the common case by the high word alone: |high word| < 2^(29 - p) */
        const uint32_t h = 1u << (29u - p);
        if ((uint32_t)((uint64_t)r >> 32) + (h - 1u) <= 2u * h - 2u) {
            return (int64_t)((uint64_t)r << p);
        }
    }
    const int64_t lim = FX_S61_MAX >> c.post;
    return (r > lim) ? FX_S61_MAX : ((r < -lim) ? -FX_S61_MAX : r * ((int64_t)1 << c.post));
}

/** The factor v * 2^(out_frac - in_frac) (v finite, >= 0) as an fx_scale_t with a 32-bit
 *  mantissa; FS_ERR_FIXED_OVERFLOW if v is negative, not finite or the factor >= 2^61. Set-up
 *  code (double), not the tick. */
fs_status_t fx_scale_from_double(double v, int32_t in_frac, int32_t out_frac, fx_scale_t *out);

/** 2^(-k/2^FX_EXP_TABLE_BITS) in Q1.31 (unsigned), k = 0..2^FX_EXP_TABLE_BITS (fx.c). */
extern const uint32_t fx_exp2_table[(1u << FX_EXP_TABLE_BITS) + 1u];

/** The table of fx_exp2_table as pairs {t_k, t_k - t_(k+1)}, k = 0..255, t_0 = 2^31 - 16 (fx.c):
 *  one 64-bit load a lookup. */
extern const uint32_t fx_exp2_pairs[2u << FX_EXP_TABLE_BITS];

/* log2(e) in Q1.31 (unsigned): round(1.4426950408889634 * 2^31). */
#define FX_LOG2E_Q31 3098164009u

/** exp(-a) for a in Q5.27, 0 <= a <= 16 (FX_EXP_ARG_MAX_Q27; the caller guarantees it), result
 *  Q1.31 unsigned in [0, 2^31]. 2^-(a*log2 e): integer part by shift, fraction by a 257-entry
 *  table of 2^-k/256 with linear interpolation. Error <= 9.3e-7 relative + 2 LSB
 *  (tests/firmware/fixed). Inline: it is the inner loop of the kernel blend. */
static inline uint32_t fx_exp_neg_q27_le16(uint32_t a)
{
    /* y = a*log2(e) in Q.58, < 23.09 * 2^58 < 2^63: exact product, no rounding of the exponent */
    const uint64_t y = (uint64_t)a * FX_LOG2E_Q31;
    const uint32_t n = (uint32_t)(y >> 58); /* integer part, 0..23 */
    const uint32_t f = (uint32_t)(y >> 26); /* fraction, Q.32 */
    const uint32_t frac_bits = 32u - FX_EXP_TABLE_BITS;
    const uint32_t k = f >> frac_bits;
    const uint32_t r = f & ((1u << frac_bits) - 1u);
    const uint32_t t0 = fx_exp2_table[k];
    const uint32_t t1 = fx_exp2_table[k + 1u];
    /* t0 - t1 < 2^23 and r < 2^24: the product needs 47 bits */
    const uint32_t drop = (uint32_t)(((uint64_t)(t0 - t1) * r + (1u << (frac_bits - 1u))) >>
                                     frac_bits);
    const uint32_t m = t0 - drop;
    if (n == 0u) {
        return m;
    }
    return (m + (1u << (n - 1u))) >> n;
}

/** fx_exp_neg_q27_le16 of any Q5.27 argument, values above 16 clipped to 16. */
static inline uint32_t fx_exp_neg_q27(uint32_t a_q27)
{
    return fx_exp_neg_q27_le16((a_q27 > FX_EXP_ARG_MAX_Q27) ? FX_EXP_ARG_MAX_Q27 : a_q27);
}

/** Unsigned 64/32 division rounded to nearest, n / d, for d > 0 and n < d * 2^32 - d/2 (the
 *  quotient fits 32 bits). Uses only 32-bit divides (Hacker's Delight divlu): no libgcc call. */
uint32_t fx_udiv64_32_round(uint64_t n, uint32_t d);

/** Double -> fixed with frac_bits fraction bits, rounded to nearest; FS_ERR_FIXED_OVERFLOW if
 *  |v| * 2^frac_bits does not fit [-limit, limit] (limit <= INT32_MAX) or v is not finite. */
fs_status_t fx_from_double(double v, unsigned frac_bits, int32_t limit, int32_t *out);

/** Fixed -> double (exact). */
double fx_to_double(int64_t v, unsigned frac_bits);

/** Float32 -> fixed with frac_bits (0..31) fraction bits, rounded to nearest (ties away from 0),
 *  saturated to the int32 range, NaN -> 0: integer operations on the float's bits only (no
 *  software-float call on a core without FPU: the fixed executor's per-tick boundary). */
int32_t fx_from_float(float v, unsigned frac_bits);

/** Fixed with frac_bits (0..31) fraction bits -> the nearest float32 (ties up), from the bits. */
float fx_to_float(int32_t v, unsigned frac_bits);

/** acc * 2^exp2 as the nearest float32 (ties up), from the bits: a DMP state accumulator at its
 *  full resolution (the exact sum of the Euler increments, Q.55 for a Q8.24 state: exp2 = -55),
 *  where the Q8.24 view would quantise. Results below 2^-126 are 0, above float range +-inf. */
float fx_acc_to_float(int64_t acc, int32_t exp2);

#endif /* FX_H */

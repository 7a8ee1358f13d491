/* The fixed-point half of the numeric layer (fs_num.h), over the Q-format helpers of fx.h:
 * int32 values in the formats listed in fs_num.h, 64-bit exact intermediates, rounding half up,
 * saturation (never wrap). The _ev operations and the DMP state updates count every saturation
 * in *ev (0 in a validated run). Selected by FS_NUMERIC_FIXED (fs_fixed); fs_num.h documents
 * each operation, the comments here give the formats. */
#ifndef FS_NUM_FIXED_H
#define FS_NUM_FIXED_H

#include <stdint.h>
#include <math.h>
#include "fx.h"

typedef int32_t fs_phase_t;  /* Q2.30 */
typedef int32_t fs_kscale_t; /* Q13.19 1/sigma */
typedef uint32_t fs_expo_t;  /* base 2: e*log2(e) in Q6.26 unsigned */
typedef uint64_t fs_kdist_t; /* Q.49 unsigned */
typedef int32_t fs_act_t;    /* Q.27, in [0, 2^27) */
typedef int64_t fs_bnum_t;   /* Q.51 */
typedef uint32_t fs_bden_t;  /* Q.27 */
typedef int32_t fs_val_t;    /* Q8.24 */
typedef int32_t fs_coef_t;   /* Q1.31, in [0, 0.5) for the DMP */
typedef int64_t fs_acc_t;    /* value * 2^31 */
typedef int32_t fs_force_t;  /* Q16.16 N */
typedef int32_t fs_gain_t;   /* Q16.16 */
typedef int32_t fs_stiff_t;  /* Q20.12: the DMP output scale 2^s (N per unit of y) */
typedef int64_t fs_wide_t;   /* Q.32 N */

#define FS_NUM_ZERO 0
#define FS_NUM_PHASE_ONE FX_Q30_ONE
/* Kernels with e_i above 12 are skipped: exp(-12) = 6.1e-6 of the largest activation (the blend
 * within 8e-7 of max|w| of the double one on the golden skills, tests/firmware/fixed; the real
 * layer uses DMP_KERNEL_CUTOFF_EXP, 23 or the port's 16). 16 would sum two more kernels a tick at
 * N = 50 on the M3 for a blend within 3e-8. */
#define FS_NUM_CUTOFF_E 12u
/* in base 2, as the exponents: 17.375 in Q6.26, just above 12 log2(e) = 17.312 (an immediate
 * operand, 0x8B << 23: no register or literal load in the blend's loops). The cutoff itself is
 * FS_NUM_R_SKIP_HI's (r < sqrt(24), e < 12): this bound only tells a summed kernel from
 * FS_NUM_EXPO_INF. */
#define FS_NUM_CUTOFF 0x45800000u
#define FS_NUM_EXPO_INF UINT32_MAX
/* Most kernels one blend looks at: DMPFX_MAX_WINDOW (dmpfx.h, checked at conversion). */
#define FS_NUM_MAX_WINDOW DMPFX_MAX_WINDOW
/* |u - c_i|/sigma_i > sqrt(2 * 12) (e_i > 12) is skipped before squaring: in Q.49 a high word
 * >= 642,120 (sqrt(24) * 2^17 = 642,119.04), and below it r fits uint32 in Q3.29. */
#define FS_NUM_R_SKIP_HI 642120u

static inline fs_val_t fs_num_view(fs_acc_t acc)
{
    return fx_acc_view(acc);
}

/* A saturated operand (fs_num_add_ev & co.) as an opaque 32-bit register value: GCC otherwise
 * widens it on each path of the saturation and the product k*a becomes a 64x64 multiply (mul,
 * mla, umull) instead of one smlal. */
static inline int32_t fs_num_opaque(int32_t a)
{
#if defined(__GNUC__) && defined(__arm__)
    __asm__("" : "+r"(a));
#endif
    return a;
}

static inline fs_acc_t fs_num_acc_mac1(fs_acc_t acc, fs_coef_t k, fs_val_t a, uint32_t *ev)
{
    return fx_acc_add(acc, (int64_t)k * fs_num_opaque(a), ev);
}

static inline fs_acc_t fs_num_acc_mac2(fs_acc_t acc, fs_coef_t ka, fs_val_t a, fs_coef_t kb,
                                       fs_val_t b, uint32_t *ev)
{
    /* two multiply-accumulates (kb < 2^31: -kb fits); |acc| < 2^62 and each product < 2^61 */
    return fx_acc_hold(acc + (int64_t)ka * fs_num_opaque(a) + (int64_t)(-kb) * fs_num_opaque(b),
                       ev);
}

/* The result of a 32-bit add/sub whose overflow flag is ovf: r, or saturated toward a's sign
 * (the overflowing direction for a + b and a - b alike) and counted. */
static inline fs_val_t fs_num_ovf_ev(int ovf, int32_t r, int32_t a, uint32_t *ev)
{
    if (ovf) {
        (*ev)++;
        return (a < 0) ? INT32_MIN : INT32_MAX;
    }
    return r;
}

static inline fs_val_t fs_num_add_ev(fs_val_t a, fs_val_t b, uint32_t *ev)
{
    int32_t r;
    const int ovf = __builtin_add_overflow(a, b, &r);
    return fs_num_ovf_ev(ovf, r, a, ev);
}

static inline fs_val_t fs_num_sub_ev(fs_val_t a, fs_val_t b, uint32_t *ev)
{
    int32_t r;
    const int ovf = __builtin_sub_overflow(a, b, &r);
    return fs_num_ovf_ev(ovf, r, a, ev);
}

static inline fs_val_t fs_num_add(fs_val_t a, fs_val_t b)
{
    return fx_add_sat(a, b);
}
static inline fs_val_t fs_num_sub(fs_val_t a, fs_val_t b)
{
    return fx_sub_sat(a, b);
}

/* Saturate a 64-bit value into int32 and count. */
static inline int32_t fs_num_sat_ev(int64_t v, uint32_t *ev)
{
    const int32_t r = fx_sat32(v);
    if ((int64_t)r != v) {
        (*ev)++;
    }
    return r;
}

/* Q8.24 * Q2.30 -> Q8.24 */
static inline fs_val_t fs_num_mul_vp(fs_val_t a, fs_phase_t p, uint32_t *ev)
{
    return fs_num_sat_ev(fx_rshift_round((int64_t)a * fs_num_opaque(p), 30u), ev);
}

/* Q8.24 * Q8.24 -> Q8.24 */
static inline fs_val_t fs_num_mul_vv(fs_val_t a, fs_val_t b, uint32_t *ev)
{
    return fs_num_sat_ev(fx_rshift_round((int64_t)fs_num_opaque(a) * fs_num_opaque(b), 24u), ev);
}

/* Q20.12 scale * Q8.24 y -> Q16.16 N */
static inline fs_force_t fs_num_force(fs_stiff_t k, fs_val_t x, uint32_t *ev)
{
    return fs_num_sat_ev(fx_rshift_round((int64_t)k * fs_num_opaque(x), 20u), ev);
}

/* r = |u - c| s in Q.49 (s = 1/sigma): |u - c| exactly in uint32 (< 2^32 for any int32 pair),
 * s < 2^31. */
static inline fs_kdist_t fs_num_kernel_dist(fs_phase_t u, fs_phase_t c, fs_kscale_t s)
{
    const uint32_t ad = (u >= c) ? (uint32_t)u - (uint32_t)c : (uint32_t)c - (uint32_t)u;
    return (uint64_t)ad * (uint32_t)s;
}

/* The exponent in base 2, e log2(e) = r^2 log2(e)/2, in Q6.26 (floor; r truncated to Q3.29
 * first): the high word of r times the high word of r log2(e), so the activation needs no
 * multiply by log2(e); FS_NUM_EXPO_INF when r >= sqrt(24). */
static inline fs_expo_t fs_num_kernel_expo(fs_phase_t u, fs_phase_t c, fs_kscale_t s)
{
    const uint64_t r = fs_num_kernel_dist(u, c, s);
    if ((uint32_t)(r >> 32) >= FS_NUM_R_SKIP_HI) {
        return FS_NUM_EXPO_INF;
    }
    const uint32_t r29 = (uint32_t)(r >> 20);
    const uint32_t r_l = (uint32_t)(((uint64_t)r29 * FX_LOG2E_Q31) >> 32); /* r log2(e)/2, Q.29 */
    return (uint32_t)(((uint64_t)r29 * r_l) >> 32);
}

/* exp(-e) = 2^-y in Q.27 for a base-2 exponent y (fs_num_kernel_expo's, Q6.26) below 32: its
 * fraction interpolated in fx_exp2_pairs by the high word of one product, the integer part by
 * a plain shift (error within the table's 9.2e-7 relative). The blend calls it with y - y_min of
 * a kernel within the cutoff. Below 2^27 (t_0's clip): 32 activations sum within uint32. */
static inline fs_act_t fs_num_exp_neg(fs_expo_t y)
{
    const uint32_t *t = &fx_exp2_pairs[2u * ((y >> 18) & 0xFFu)];
    const uint32_t m = t[0] - (uint32_t)(((uint64_t)t[1] * (y << 14)) >> 32);
    /* m < 2^31: an arithmetic shift of it as int32, so the products psi*w are signed
     * multiply-accumulates (smlal; a shift known to clear the sign gives umull + mla) */
    return (int32_t)m >> ((y >> 26) + 4u);
}

/* The numerator part of fs_num_blend_acc, for either weight set (the force DMP's, and the y
 * DMP's over the same activations): num += w * psi in Q.51 (< 32 * 2^58 over a window), one
 * multiply-accumulate. */
static inline void fs_num_blend_acc_num(fs_bnum_t *num, fs_act_t psi, fs_val_t w)
{
    *num += (int64_t)w * psi;
}

/* num as fs_num_blend_acc_num, den += psi (Q.27, < 2^32 over a window of 32). */
static inline void fs_num_blend_acc(fs_bnum_t *num, fs_bden_t *den, fs_act_t psi, fs_val_t w)
{
    fs_num_blend_acc_num(num, psi, w);
    *den += (uint32_t)psi;
}

/* ~2^62/d for d in [2^31, 2^32), in (2^30, 2^31): a 16-bit estimate by one 32-bit divide (by
 * d's 16 leading bits plus one: low, never 2^31) and one Newton step (relative error within
 * 1.8e-9): a quotient by two multiplies instead of a 64/32 division. */
static inline int32_t fs_num_recip_q62(uint32_t d)
{
    const uint32_t r0 = (0xFFFFFFFFu / ((d >> 16) + 1u)) << 14;
    const int32_t eps = (int32_t)((1u << 30) - (uint32_t)(((uint64_t)d * r0) >> 32));
    return (int32_t)r0 + (int32_t)(((int64_t)(int32_t)r0 * (eps * 4)) >> 32);
}

/* num * r / 2^(32 + sh) for a reciprocal r of fs_num_recip_q62, 0 < sh < 32, the result
 * fitting int32 (floor): the high words of the 96-bit product, one 32-bit funnel shift. */
static inline int32_t fs_num_mul_recip(int64_t num, int32_t r, unsigned sh)
{
    const int64_t t = (int64_t)(int32_t)((uint64_t)num >> 32) * r +
                      (int64_t)(((uint64_t)(uint32_t)(uint64_t)num * (uint32_t)r) >> 32);
    return (int32_t)(((uint32_t)(uint64_t)t >> sh) | ((uint32_t)((uint64_t)t >> 32) << (32u - sh)));
}

/* den (Q.27, >= 2^27 - 1) brought to [2^31, 2^32) as d; *sh the shift of fs_num_mul_recip that
 * turns a Q.51 num times d's reciprocal into num / den in Q8.24. */
static inline uint32_t fs_num_blend_norm(fs_bden_t den, unsigned *sh)
{
    const unsigned c = (unsigned)__builtin_clz(den); /* 0..5 */
    *sh = 30u - c;
    return den << c;
}

/* S = num / den in Q8.24 rounded half up, den >= 2^27 - 1 (the e_min kernel's psi): |S| <= max
 * |w_i|, so the quotient fits. By den's reciprocal (error < 2^-28 of |S|). */
static inline fs_val_t fs_num_blend_div(fs_bnum_t num, fs_bden_t den)
{
    unsigned sh;
    const int32_t r = fs_num_recip_q62(fs_num_blend_norm(den, &sh));
    return fs_num_mul_recip(num + (int64_t)(den >> 1), r, sh);
}

/* S = num/den as fs_num_blend_div, and *s_y = num_y/den: one reciprocal for both. */
static inline fs_val_t fs_num_blend_div2(fs_bnum_t num, fs_bnum_t num_y, fs_bden_t den,
                                         fs_val_t *s_y)
{
    unsigned sh;
    const int32_t r = fs_num_recip_q62(fs_num_blend_norm(den, &sh));
    const int64_t half = (int64_t)(den >> 1);
    *s_y = fs_num_mul_recip(num_y + half, r, sh);
    return fs_num_mul_recip(num + half, r, sh);
}

/* Q16.16 gain * Q8.24 -> Q.32 (N); < 2^54 for int32 operands. */
static inline fs_wide_t fs_num_gain_val(fs_gain_t g, fs_val_t v)
{
    return ((int64_t)g * fs_num_opaque(v)) >> 8;
}
/* Q16.16 gain * Q16.16 N -> Q.32 (N); < 2^62. */
static inline fs_wide_t fs_num_gain_force(fs_gain_t g, fs_force_t f)
{
    return (int64_t)g * fs_num_opaque(f);
}
/* Q.32 -> Q16.16 N, rounded, saturated. */
static inline fs_force_t fs_num_wide_force(fs_wide_t w)
{
    return fx_sat32(fx_rshift_round(w, 16u));
}
/* Q1.31 s * Q16.16 N -> Q8.24 N*s */
static inline fs_val_t fs_num_dt_force(fs_coef_t dt, fs_force_t f)
{
    return fx_sat32(fx_rshift_round((int64_t)dt * fs_num_opaque(f), 23u));
}
static inline int fs_num_is_nan(fs_wide_t w)
{
    (void)w;
    return 0;
}
static inline int32_t fs_num_clamp(int32_t v, int32_t lim)
{
    return fx_clamp_sym(v, lim);
}

/* The high word of a * b (unsigned): free on a 32-bit core. */
static inline uint32_t fs_num_umulhi(uint32_t a, uint32_t b)
{
    return (uint32_t)(((uint64_t)a * b) >> 32);
}

/* sin(pi t) in Q1.31 (saturated to +-INT32_MAX) for t in Q2.30, |t| <= 1/2: |t| P(4 t^2),
 * P(v) = c0 - v (c1 - v (c2 - v (c3 - v (c4 - v c5)))) a degree-5 minimax fit (weighted least
 * squares to equal ripple) with every c_k > 0 and every partial sum positive, so each Horner
 * step is one unsigned high-word product and a subtraction: v = 4 t^2 in Q.32 (|t| held below
 * 1/2 by 2^-30 so v < 2^32), c0 in Q2.30, c1..c5 in Q1.31 (max error 9.1e-10 over [0, 1] for
 * sin and cos, test_sincos_pi in tests/firmware/fixed/test_dmpfx.c). */
static inline int32_t fs_num_sinpi_half(int32_t t)
{
    const uint32_t sgn = (uint32_t)(t >> 31);
    uint32_t a = ((uint32_t)t ^ sgn) - sgn;
    a = (a < (1u << 29)) ? a : (1u << 29) - 1u;
    const uint32_t v = (uint32_t)(((uint64_t)a * a) >> 26);
    uint32_t q = 688128u - fs_num_umulhi(14681u, v);
    q = 20107406u - fs_num_umulhi(q, v);
    q = 342277056u - fs_num_umulhi(q, v);
    q = 2774394652u - fs_num_umulhi(q, v);
    const uint32_t p = 3373259426u - (fs_num_umulhi(q, v) >> 1);
    uint32_t r = fs_num_umulhi(a << 3, p); /* |t| in Q.33 times P in Q2.30: Q1.31 */
    r = (r < FX_Q31_ONE_U) ? r : (uint32_t)INT32_MAX;
    return (int32_t)((r ^ sgn) - sgn);
}

/* sin(pi x), cos(pi x) in Q1.31 (fs_num_vm_dist's operands) for a phase x in turns, Q2.30 in
 * [0, 1] */
static inline void fs_num_sincos_pi(fs_phase_t x, fs_phase_t *s, fs_phase_t *c)
{
    const int32_t half = FX_Q30_ONE >> 1;
    *s = fs_num_sinpi_half((x <= half) ? x : FX_Q30_ONE - x);
    *c = fs_num_sinpi_half(half - x);
}

/* d = sh*hc - ch*hs in Q2.30 (floor) from Q1.31 operands (each |.| <= 1 - 2^-31: the difference
 * fits): the high word of one multiply and one multiply-accumulate (-ch is loop-invariant). */
static inline fs_phase_t fs_num_vm_dist(fs_phase_t sh, fs_phase_t ch, fs_phase_t hs, fs_phase_t hc)
{
    return (int32_t)(((int64_t)sh * hc + (int64_t)(-ch) * hs) >> 32);
}

/* The periodic phase's accumulator (value * 2^31, a Q2.30 view): one turn, and the exact
 * increment of a rate in turns per step (rounded to 2^-61 turn: no drift over any run). */
#define FS_NUM_TURN ((int64_t)FX_Q30_ONE << 31)
static inline fs_acc_t fs_num_turn_inc(double turns_per_step)
{
    return (int64_t)llround(ldexp(turns_per_step, 61));
}

#endif /* FS_NUM_FIXED_H */

/* The real half of the numeric layer (fs_num.h): every quantity is fs_real_t (double, or
 * float32 with FS_REAL_FLOAT) and every operation is the plain arithmetic, inline, so the shared
 * per-tick code costs nothing over writing it in fs_real_t directly. Saturation counters (ev)
 * are ignored: real arithmetic does not saturate. The kernel scale is s_i = 1/(2 sigma_i^2) and
 * e_i = d*d*s_i (two multiplies; the fixed layer's (|d|/sigma)^2/2 costs one more here).
 * fs_num.h documents each operation. */
#ifndef FS_NUM_REAL_H
#define FS_NUM_REAL_H

#include <stdint.h>
#include "fs_real.h"

typedef fs_real_t fs_phase_t;
typedef fs_real_t fs_kscale_t;
typedef fs_real_t fs_expo_t;
typedef fs_real_t fs_kdist_t;
typedef fs_real_t fs_act_t;
typedef fs_real_t fs_bnum_t;
typedef fs_real_t fs_bden_t;
typedef fs_real_t fs_val_t;
typedef fs_real_t fs_coef_t;
typedef fs_real_t fs_acc_t;
typedef fs_real_t fs_force_t;
typedef fs_real_t fs_gain_t;
typedef fs_real_t fs_stiff_t;
typedef fs_real_t fs_wide_t;

#define FS_NUM_ZERO FS_R(0.0)
#define FS_NUM_PHASE_ONE FS_R(1.0)
#define FS_NUM_CUTOFF ((fs_real_t)DMP_KERNEL_CUTOFF_EXP)
#define FS_NUM_EXPO_INF FS_REAL_INF
#define FS_NUM_MAX_WINDOW DMP_MAX_KERNELS

static inline fs_val_t fs_num_view(fs_acc_t acc)
{
    return acc;
}

static inline fs_acc_t fs_num_acc_mac1(fs_acc_t acc, fs_coef_t k, fs_val_t a, uint32_t *ev)
{
    (void)ev;
    return acc + k * a;
}

static inline fs_acc_t fs_num_acc_mac2(fs_acc_t acc, fs_coef_t ka, fs_val_t a, fs_coef_t kb,
                                       fs_val_t b, uint32_t *ev)
{
    (void)ev;
    return acc + (ka * a - kb * b);
}

static inline fs_val_t fs_num_add_ev(fs_val_t a, fs_val_t b, uint32_t *ev)
{
    (void)ev;
    return a + b;
}

static inline fs_val_t fs_num_sub_ev(fs_val_t a, fs_val_t b, uint32_t *ev)
{
    (void)ev;
    return a - b;
}

static inline fs_val_t fs_num_add(fs_val_t a, fs_val_t b)
{
    return a + b;
}
static inline fs_val_t fs_num_sub(fs_val_t a, fs_val_t b)
{
    return a - b;
}

static inline fs_val_t fs_num_mul_vp(fs_val_t a, fs_phase_t p, uint32_t *ev)
{
    (void)ev;
    return a * p;
}

static inline fs_val_t fs_num_mul_vv(fs_val_t a, fs_val_t b, uint32_t *ev)
{
    (void)ev;
    return a * b;
}

static inline fs_force_t fs_num_force(fs_stiff_t k, fs_val_t x, uint32_t *ev)
{
    (void)ev;
    return k * x;
}

static inline fs_expo_t fs_num_kernel_expo(fs_phase_t u, fs_phase_t c, fs_kscale_t s)
{
    const fs_real_t d = u - c;
    return d * d * s;
}

static inline fs_kdist_t fs_num_kernel_dist(fs_phase_t u, fs_phase_t c, fs_kscale_t s)
{
    return fs_num_kernel_expo(u, c, s);
}

#ifdef FS_REAL_FLOAT
#ifdef DMP_KERNEL_CUTOFF_EXP
_Static_assert((int)(DMP_KERNEL_CUTOFF_EXP) < 64, "fs_num_exp_neg: e*log2(e) must stay < 126");
#endif
/* exp(-e) = 2^-(n + f), n = floor(e log2 e), f in [0, 1): 2^-f by a degree-5 polynomial
 * (relative error 8.4e-8 on [0, 1], 2.7e-7 evaluated in float32), 2^-n by the exponent bits.
 * Only for a kernel exponent 0 <= e <= FS_NUM_CUTOFF (the blend's one caller tests e first):
 * no call, no special values (the library expf handles NaN, inf and underflow; ~37
 * instructions a call on the M4F against ~18 inline). */
static inline fs_act_t fs_num_exp_neg(fs_expo_t e)
{
    const float y = e * 1.44269504f; /* e log2(e) */
    const int32_t n = (int32_t)y;    /* floor: y >= 0 */
    const float f = y - (float)n;
    float p = -9.44899977e-04f;
    p = p * f + 9.20579955e-03f;
    p = p * f - 5.52973598e-02f;
    p = p * f + 2.40180150e-01f;
    p = p * f - 6.93143725e-01f;
    p = p * f + 1.0f; /* exp(-0) = 1 exactly */
    const union {
        uint32_t u;
        float f;
    } scale = {.u = (uint32_t)(127 - n) << 23};
    return p * scale.f;
}
#else
static inline fs_act_t fs_num_exp_neg(fs_expo_t e)
{
    return fs_exp(-e);
}
#endif

static inline void fs_num_blend_acc(fs_bnum_t *num, fs_bden_t *den, fs_act_t psi, fs_val_t w)
{
    *num += psi * w;
    *den += psi;
}

static inline void fs_num_blend_acc_num(fs_bnum_t *num, fs_act_t psi, fs_val_t w)
{
    *num += psi * w;
}

static inline fs_val_t fs_num_blend_div(fs_bnum_t num, fs_bden_t den)
{
    return num / den;
}

static inline fs_wide_t fs_num_gain_val(fs_gain_t g, fs_val_t v)
{
    return g * v;
}
static inline fs_wide_t fs_num_gain_force(fs_gain_t g, fs_force_t f)
{
    return g * f;
}
static inline fs_force_t fs_num_wide_force(fs_wide_t w)
{
    return w;
}
static inline fs_val_t fs_num_dt_force(fs_coef_t dt, fs_force_t f)
{
    return dt * f;
}
static inline int fs_num_is_nan(fs_wide_t w)
{
    return w != w;
}

static inline fs_real_t fs_num_clamp(fs_real_t v, fs_real_t lim)
{
    if (v > lim) {
        return lim;
    }
    if (v < -lim) {
        return -lim;
    }
    return v;
}

/* The periodic DMP's kernel distance (dmp_ptick.h): sin(pi x) and cos(pi x) of a phase x in
 * turns, 0 <= x <= 1 (the half angle of phi = 2 pi x), and d_i = sin(pi (x - c_i)) from them and
 * the kernel's half-angle sine and cosine. Double: the library's sin and cos; float: odd Taylor
 * polynomials of sin(pi t), |t| <= 1/2, to t^11 (truncation 5.7e-8, near float's resolution),
 * no library call. */
#define FS_NUM_PI 3.14159265358979323846
#ifdef FS_REAL_FLOAT
static inline float fs_num_sinpi_half(float t)
{
    const float t2 = t * t;
    float p = -7.37043094571435e-03f;
    p = p * t2 + 8.21458866111282e-02f;
    p = p * t2 - 5.99264529320792e-01f;
    p = p * t2 + 2.55016403987734e+00f;
    p = p * t2 - 5.16771278004997e+00f;
    p = p * t2 + 3.14159265358979e+00f;
    return p * t;
}

static inline void fs_num_sincos_pi(fs_phase_t x, fs_phase_t *s, fs_phase_t *c)
{
    *s = fs_num_sinpi_half((x <= 0.5f) ? x : 1.0f - x);
    *c = fs_num_sinpi_half(0.5f - x);
}
#else
static inline void fs_num_sincos_pi(fs_phase_t x, fs_phase_t *s, fs_phase_t *c)
{
    *s = sin(FS_NUM_PI * x);
    *c = cos(FS_NUM_PI * x);
}
#endif

static inline fs_phase_t fs_num_vm_dist(fs_phase_t sh, fs_phase_t ch, fs_phase_t hs, fs_phase_t hc)
{
    return sh * hc - ch * hs;
}

/* The periodic phase's accumulator: one turn, and the increment of a per-step rate in turns. */
#define FS_NUM_TURN FS_R(1.0)
static inline fs_acc_t fs_num_turn_inc(fs_real_t turns_per_step)
{
    return turns_per_step;
}

#endif /* FS_NUM_REAL_H */

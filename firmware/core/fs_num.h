/* The numeric layer: the types and operations the per-tick algorithms of the DMP (dmp_tick.h)
 * and of the control law (pfc_tick.h) are written in, so each is written once and compiled
 * three ways. The build selects the layer; the core names no other layer:
 *   FS_NUM_LAYER="header.h"   -> that header, plugged in by the library that compiles the tick
 *                                code over it (fs_fixed: "fs_num_fixed.h", Q formats over fx.h,
 *                                with FS_NUMERIC_FIXED for the few fixed-only branches)
 *   otherwise                 -> fs_num_real.h  (fs_real_t: double, or float32 with FS_REAL_FLOAT)
 * Types, one per quantity (real layer: all fs_real_t; fixed layer: the format given):
 *   fs_phase_t  phase u~, v~, centres c_i, envelopes      Q2.30
 *   fs_kscale_t kernel scale s_i: real 1/(2 sigma_i^2), fixed 1/sigma_i  Q13.19
 *   fs_expo_t   kernel exponent e_i = (u - c_i)^2/(2 sigma_i^2)  fixed: in base 2, e_i log2(e),
 *               Q6.26 unsigned (far: > cutoff)
 *   fs_kdist_t  nearest-kernel key, monotone in e_i        Q.49 unsigned |u - c_i| s_i
 *   fs_act_t    kernel activation psi_i = exp(-e)          Q.27 (below 2^27)
 *   fs_bnum_t, fs_bden_t  blend sums sum psi w, sum psi   int64 Q.51, uint32 Q.27
 *   fs_val_t    DMP y, z, I, h, g, term_y (force units, times 2^-s in fixed point), w_i,
 *               positions, velocities, accelerations, force integral        Q8.24
 *   fs_coef_t   Euler coefficients dt/tau_e*{1, alpha, alpha*beta, gamma}, control dt  Q1.31
 *   fs_acc_t    a DMP state: exact sum of its Euler increments (value * 2^31)  int64
 *   fs_force_t  forces (N)                                 Q16.16
 *   fs_gain_t   control gains                              Q16.16
 *   fs_stiff_t  DMP output scale (N per unit of y: 1, or 2^s) Q20.12
 *   fs_wide_t   sum of control-law terms (N)               int64 Q.32
 * Operations (trivial inline functions over fs_real_t in the real layer; in the fixed layer
 * rounding half up, saturation and not wrapping; the _ev variants count saturations in *ev):
 *   fs_num_view(acc)                  a state's value (fs_val_t / fs_phase_t)
 *   fs_num_acc_mac1(acc, k, a, ev)    acc + k*a           (state update, one term)
 *   fs_num_acc_mac2(acc, ka, a, kb, b, ev)  acc + ka*a - kb*b
 *   fs_num_add_ev / fs_num_sub_ev     saturating a +- b, counted
 *   fs_num_sub / fs_num_add           saturating a +- b (control law)
 *   fs_num_mul_vp(val, phase, ev)     val * phase -> val    fs_num_mul_vv(val, val, ev) -> val
 *   fs_num_force(scale, y, ev)        scale * y -> force
 *   fs_num_kernel_expo(u, c, s)       e_i: real d*d*s, fixed (|d| s)^2/2 (d = u - c)
 *   fs_num_kernel_dist(u, c, s)       a key monotone in e_i (nearest-kernel fallback)
 *   fs_num_exp_neg(e)                 exp(-e) for e >= 0 -> activation
 *   fs_num_blend_acc(&num, &den, psi, w)  fs_num_blend_div(num, den) -> S = num/den (val)
 *   fs_num_blend_div2(num, num_y, den, &s_y)  fixed only: both quotients by one reciprocal
 *   fs_num_gain_val(g, v), fs_num_gain_force(g, f) -> wide   fs_num_wide_force(w) -> force
 *   fs_num_dt_force(dt, f) -> val     fs_num_clamp(a, lim)  fs_num_is_nan(w)
 * Constants: FS_NUM_ZERO, FS_NUM_PHASE_ONE, FS_NUM_CUTOFF (kernel exponent cutoff),
 * FS_NUM_EXPO_INF, FS_NUM_MAX_WINDOW (most kernels one blend looks at).
 * Only implementation files include this header (after their public headers): the public
 * headers of the double, float and fixed builds stay includable together in one file. */
#ifndef FS_NUM_H
#define FS_NUM_H

#if defined(FS_NUM_LAYER)
#include FS_NUM_LAYER
#elif defined(FS_NUMERIC_FIXED)
#error "FS_NUMERIC_FIXED needs FS_NUM_LAYER, the header of the numeric layer it plugs in"
#else
#include "fs_num_real.h"
#endif

#endif /* FS_NUM_H */

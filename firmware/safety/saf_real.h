/* The safety modules are built three ways: fs_safety (double), fs_safety_f32 (float,
 * FS_REAL_FLOAT) and fs_safety_fx (SAF_FIXED over the float core: the per-tick values in
 * integers, for a core without FPU). The configuration is in fs_real_t in every build (the
 * device reads and writes it in physical units); the tick works on the values below and on the
 * bounds saf_prepare derived from the configuration. Under FS_REAL_FLOAT the external symbols
 * get an _f32 suffix, under SAF_FIXED an _fx suffix, so the libraries link into one host
 * executable. */
#ifndef SAF_REAL_H
#define SAF_REAL_H

#include <stdbool.h>
#include <stdint.h>
#include "fs_real.h"

#define SAF_AXES 2u

#ifdef SAF_FIXED
#ifndef FS_REAL_FLOAT
#error "SAF_FIXED is built over the float core (FS_REAL_FLOAT)"
#endif
typedef int32_t saf_force_t;     /* N, Q16.16 */
typedef int32_t saf_pos_t;       /* m and m/s, Q8.24 */
#define SAF_NOT_FINITE INT32_MIN /* a value that was NaN or infinite where it was converted */
#define SAF_FORCE_FRAC 16
#define SAF_POS_FRAC 24
/* a constant in the tick's units (folded by the compiler: no arithmetic in the tick) */
#define SAF_FORCE_C(x) ((saf_force_t)((x)*65536.0 + 0.5))
#else
typedef fs_real_t saf_force_t;
typedef fs_real_t saf_pos_t;
#define SAF_FORCE_C(x) ((saf_force_t)(x))
#endif
typedef saf_pos_t saf_vel_t;

/** One axis's measurement as the safety layer checks it (the application fills it from the
 *  sensors; the safety layer depends on no control-law type). */
typedef struct {
    saf_pos_t pos_m;
    saf_vel_t vel_mps;
    saf_force_t force_N;
} saf_meas_t;

#ifdef SAF_FIXED
#include "saf_fx_names.h" /* generated from lim.h, sen.h, wdg.h, saf.h */

static inline bool saf_finite(int32_t x)
{
    return x != SAF_NOT_FINITE;
}

/** True if x's comparisons with a bound mean what they say (floating point: always, a NaN
 *  compares false by itself; integers: x is not SAF_NOT_FINITE). */
static inline bool saf_comparable(int32_t x)
{
    return x != SAF_NOT_FINITE;
}

/** True if x is finite and |x| <= b. */
static inline bool saf_within(int32_t x, int32_t b)
{
    return x != SAF_NOT_FINITE && ((x < 0) ? -x : x) <= b;
}

/** True if x is finite and lo <= x <= hi. */
static inline bool saf_inside(int32_t x, int32_t lo, int32_t hi)
{
    return x != SAF_NOT_FINITE && x >= lo && x <= hi;
}

static inline int32_t saf_sat(int64_t x)
{
    return (x > INT32_MAX) ? INT32_MAX : ((x <= INT32_MIN) ? INT32_MIN + 1 : (int32_t)x);
}

/** |x| (x finite: never SAF_NOT_FINITE). */
static inline int32_t saf_abs(int32_t x)
{
    return (x < 0) ? -x : x;
}

/** |a - b|, saturated. */
static inline int32_t saf_absdiff(int32_t a, int32_t b)
{
    const int64_t d = (int64_t)a - (int64_t)b;
    return saf_sat((d < 0) ? -d : d);
}

/** a + b, saturated (a, b finite). */
static inline int32_t saf_add(int32_t a, int32_t b)
{
    return saf_sat((int64_t)a + (int64_t)b);
}

/** a - b, saturated (a, b finite). */
static inline int32_t saf_sub(int32_t a, int32_t b)
{
    return saf_sat((int64_t)a - (int64_t)b);
}

/** A configuration value in the tick's units (frac fraction bits): rounded, saturated; NaN 0
 *  (configuration time: the float arithmetic here never runs in the tick). */
static inline int32_t saf_from_real(fs_real_t v, int frac)
{
    if (v != v) {
        return 0;
    }
    const fs_real_t s = v * (fs_real_t)(1u << frac);
    if (s >= FS_R(2147483520.0)) {
        return INT32_MAX;
    }
    if (s <= FS_R(-2147483520.0)) {
        return INT32_MIN + 1;
    }
    return (int32_t)((s < FS_R(0.0)) ? s - FS_R(0.5) : s + FS_R(0.5));
}
#define SAF_FORCE_OF(v) saf_from_real((v), SAF_FORCE_FRAC)
#define SAF_POS_OF(v) saf_from_real((v), SAF_POS_FRAC)
#else
#ifdef FS_REAL_FLOAT
#include "saf_f32_names.h" /* generated from lim.h, sen.h, wdg.h, saf.h */
#endif

static inline bool saf_finite(fs_real_t x)
{
    return fs_isfinite(x);
}

static inline bool saf_comparable(fs_real_t x)
{
    (void)x;
    return true;
}

/** True if x is finite and |x| <= b (b finite: one compare, NaN and inf fail it). */
static inline bool saf_within(fs_real_t x, fs_real_t b)
{
    return fs_fabs(x) <= b;
}

/** True if x is finite and lo <= x <= hi (lo, hi finite). */
static inline bool saf_inside(fs_real_t x, fs_real_t lo, fs_real_t hi)
{
    return x >= lo && x <= hi;
}

static inline fs_real_t saf_abs(fs_real_t x)
{
    return fs_fabs(x);
}

static inline fs_real_t saf_absdiff(fs_real_t a, fs_real_t b)
{
    return fs_fabs(a - b);
}

static inline fs_real_t saf_add(fs_real_t a, fs_real_t b)
{
    return a + b;
}

static inline fs_real_t saf_sub(fs_real_t a, fs_real_t b)
{
    return a - b;
}
#define SAF_FORCE_OF(v) (v)
#define SAF_POS_OF(v) (v)
#endif

#endif /* SAF_REAL_H */

/* The scalar type of the floating-point core, chosen at build time:
 * FS_REAL_FLOAT defined -> float32 (Cortex-M4F, the "float" build), otherwise double (host
 * reference). Parsing, validation and parameter derivation are written in fs_real_t; the
 * per-tick DMP and control law (dmp_tick.h, pfc_tick.h) are written over the numeric layer
 * fs_num.h, whose real half (fs_num_real.h) is fs_real_t and whose fixed-point half
 * (firmware/fixed/fs_num_fixed.h, FS_NUMERIC_FIXED) compiles the same tick code in Q formats. */
#ifndef FS_REAL_H
#define FS_REAL_H

#include <math.h>

#ifdef FS_REAL_FLOAT
/* The float core's external symbols carry an _f32 suffix, so fs_core and fs_core_f32 can be
 * linked into one host executable (tests and benchmarks that compare them). Source code keeps
 * the plain names: the macros of fs_f32_names.h (generated from the headers by
 * tools/gen_f32_names.py) rename them wherever the float headers are included. */
#include "fs_f32_names.h"

typedef float fs_real_t;
#define FS_R(x) ((fs_real_t)(x##f))
#ifndef fs_exp /* a port may supply a faster exp (e.g. -Dfs_exp=cm_expf) */
#define fs_exp expf
#endif
#define fs_sqrt sqrtf
#define fs_sin sinf
#define fs_cos cosf
#define fs_asin asinf
#define fs_fabs fabsf
#if defined(__arm__) && !defined(__ARM_FP)
/* A core without an FPU (the Cortex-M3): isfinite would be two software compares; the test of
 * the exponent field is the same and takes three instructions. */
#include <stdint.h>
#include <string.h>
static inline int fs_isfinite_f32_bits(float x)
{
    uint32_t b;
    memcpy(&b, &x, sizeof b);
    return (b & 0x7F800000u) != 0x7F800000u;
}
#define fs_isfinite(x) fs_isfinite_f32_bits(x)
#else
#define fs_isfinite(x) isfinite(x)
#endif
#define FS_REAL_INF HUGE_VALF
#else
typedef double fs_real_t;
#define FS_R(x) ((fs_real_t)(x))
#ifndef fs_exp
#define fs_exp exp
#endif
#define fs_sqrt sqrt
#define fs_sin sin
#define fs_cos cos
#define fs_asin asin
#define fs_fabs fabs
#define fs_isfinite(x) isfinite(x)
#define FS_REAL_INF HUGE_VAL
#endif

#endif /* FS_REAL_H */

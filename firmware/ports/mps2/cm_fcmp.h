/* IEEE 754 comparisons for the images' software floating point: binary32 on the Cortex-M3 (no
 * FPU) and binary64 on both images. libgcc's __aeabi_fcmp and __aeabi_dcmp helpers go through
 * its flag-setting compare (about 32 instructions a binary32 compare on the M3, ~30 a binary64
 * one); these compare the bit patterns as integers, sign and magnitude mapped to two's-complement
 * order, with the same results: every ordered compare is false when an operand is NaN, -0 equals
 * +0, "un" is true when an operand is NaN. The images link them in place of libgcc's with
 * -Wl,--wrap (CMakeLists.txt), so every compiled compare calls them. Portable C: the host test
 * (tests/firmware/ports/test_fcmp.c) checks them against the host's hardware compares. */
#ifndef CM_FCMP_H
#define CM_FCMP_H

#include <stdint.h>

static inline int cm_f32_nan(uint32_t b)
{
    return (b & 0x7FFFFFFFu) > 0x7F800000u;
}

/* The order key: the bits of a non-negative value, minus the magnitude of a negative one. */
static inline int32_t cm_f32_key(uint32_t b)
{
    return ((b & 0x80000000u) != 0u) ? (int32_t)(0x80000000u - b) : (int32_t)b;
}

static inline int cm_f32_un(uint32_t a, uint32_t b)
{
    return cm_f32_nan(a) || cm_f32_nan(b);
}
static inline int cm_f32_eq(uint32_t a, uint32_t b)
{
    return !cm_f32_un(a, b) && cm_f32_key(a) == cm_f32_key(b);
}
static inline int cm_f32_lt(uint32_t a, uint32_t b)
{
    return !cm_f32_un(a, b) && cm_f32_key(a) < cm_f32_key(b);
}
static inline int cm_f32_le(uint32_t a, uint32_t b)
{
    return !cm_f32_un(a, b) && cm_f32_key(a) <= cm_f32_key(b);
}

static inline int cm_f64_nan(uint64_t b)
{
    return (b & 0x7FFFFFFFFFFFFFFFull) > 0x7FF0000000000000ull;
}

static inline int64_t cm_f64_key(uint64_t b)
{
    return ((b & 0x8000000000000000ull) != 0u) ? (int64_t)(0x8000000000000000ull - b) : (int64_t)b;
}

static inline int cm_f64_un(uint64_t a, uint64_t b)
{
    return cm_f64_nan(a) || cm_f64_nan(b);
}
static inline int cm_f64_eq(uint64_t a, uint64_t b)
{
    return !cm_f64_un(a, b) && cm_f64_key(a) == cm_f64_key(b);
}
static inline int cm_f64_lt(uint64_t a, uint64_t b)
{
    return !cm_f64_un(a, b) && cm_f64_key(a) < cm_f64_key(b);
}
static inline int cm_f64_le(uint64_t a, uint64_t b)
{
    return !cm_f64_un(a, b) && cm_f64_key(a) <= cm_f64_key(b);
}

/* The run-time ABI's compare helpers (1 if the relation holds, else 0), as linked by --wrap.
 * They take the base procedure call standard (arguments in core registers) on a hard-float image
 * too, as the run-time ABI requires of every __aeabi_ helper. */
#if defined(__arm__)
#define CM_AEABI __attribute__((pcs("aapcs")))
#else
#define CM_AEABI
#endif
CM_AEABI int __wrap___aeabi_fcmpeq(float a, float b);
CM_AEABI int __wrap___aeabi_fcmplt(float a, float b);
CM_AEABI int __wrap___aeabi_fcmple(float a, float b);
CM_AEABI int __wrap___aeabi_fcmpgt(float a, float b);
CM_AEABI int __wrap___aeabi_fcmpge(float a, float b);
CM_AEABI int __wrap___aeabi_fcmpun(float a, float b);
CM_AEABI int __wrap___aeabi_dcmpeq(double a, double b);
CM_AEABI int __wrap___aeabi_dcmplt(double a, double b);
CM_AEABI int __wrap___aeabi_dcmple(double a, double b);
CM_AEABI int __wrap___aeabi_dcmpgt(double a, double b);
CM_AEABI int __wrap___aeabi_dcmpge(double a, double b);
CM_AEABI int __wrap___aeabi_dcmpun(double a, double b);

#endif /* CM_FCMP_H */

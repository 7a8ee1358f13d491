/* The run-time ABI's compare helpers over cm_fcmp.h's integer compares. */
#include "cm_fcmp.h"

#include <string.h>

static uint32_t bits32(float v)
{
    uint32_t b;
    memcpy(&b, &v, sizeof b);
    return b;
}

static uint64_t bits64(double v)
{
    uint64_t b;
    memcpy(&b, &v, sizeof b);
    return b;
}

CM_AEABI int __wrap___aeabi_fcmpeq(float a, float b)
{
    return cm_f32_eq(bits32(a), bits32(b));
}
CM_AEABI int __wrap___aeabi_fcmplt(float a, float b)
{
    return cm_f32_lt(bits32(a), bits32(b));
}
CM_AEABI int __wrap___aeabi_fcmple(float a, float b)
{
    return cm_f32_le(bits32(a), bits32(b));
}
CM_AEABI int __wrap___aeabi_fcmpgt(float a, float b)
{
    return cm_f32_lt(bits32(b), bits32(a));
}
CM_AEABI int __wrap___aeabi_fcmpge(float a, float b)
{
    return cm_f32_le(bits32(b), bits32(a));
}
CM_AEABI int __wrap___aeabi_fcmpun(float a, float b)
{
    return cm_f32_un(bits32(a), bits32(b));
}

CM_AEABI int __wrap___aeabi_dcmpeq(double a, double b)
{
    return cm_f64_eq(bits64(a), bits64(b));
}
CM_AEABI int __wrap___aeabi_dcmplt(double a, double b)
{
    return cm_f64_lt(bits64(a), bits64(b));
}
CM_AEABI int __wrap___aeabi_dcmple(double a, double b)
{
    return cm_f64_le(bits64(a), bits64(b));
}
CM_AEABI int __wrap___aeabi_dcmpgt(double a, double b)
{
    return cm_f64_lt(bits64(b), bits64(a));
}
CM_AEABI int __wrap___aeabi_dcmpge(double a, double b)
{
    return cm_f64_le(bits64(b), bits64(a));
}
CM_AEABI int __wrap___aeabi_dcmpun(double a, double b)
{
    return cm_f64_un(bits64(a), bits64(b));
}

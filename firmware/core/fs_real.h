/* The scalar type of the floating-point core, chosen at build time:
 * FS_REAL_FLOAT defined -> float32 (Cortex-M4F, the "float" build), otherwise double (host
 * reference). The fixed-point build has its own types (fx_*.h, issue 5). */
#ifndef FS_REAL_H
#define FS_REAL_H

#include <math.h>

#ifdef FS_REAL_FLOAT
typedef float fs_real_t;
#define FS_R(x) ((fs_real_t)(x##f))
#define fs_exp expf
#define fs_sqrt sqrtf
#define fs_fabs fabsf
#define fs_isfinite(x) isfinite(x)
#else
typedef double fs_real_t;
#define FS_R(x) ((fs_real_t)(x))
#define fs_exp exp
#define fs_sqrt sqrt
#define fs_fabs fabs
#define fs_isfinite(x) isfinite(x)
#endif

#endif /* FS_REAL_H */

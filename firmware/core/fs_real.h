/* The scalar type of the floating-point core, chosen at build time:
 * FS_REAL_FLOAT defined -> float32 (Cortex-M4F, the "float" build), otherwise double (host
 * reference). Parsing, validation and parameter derivation are written in fs_real_t; the
 * per-tick DMP and control law (dmp_tick.h, pfc_tick.h) are written over the numeric layer
 * fs_num.h, whose real half (fs_num_real.h) is fs_real_t and whose fixed-point half
 * (firmware/fixed/fs_num_fixed.h, FS_NUMERIC_FIXED) compiles the same tick code in Q formats
 * (issue 5). */
#ifndef FS_REAL_H
#define FS_REAL_H

#include <math.h>

#ifdef FS_REAL_FLOAT
/* The float core's external symbols carry an _f32 suffix, so fs_core and fs_core_f32 can be
 * linked into one host executable (tests and benchmarks that compare them). Source code keeps
 * the plain names: these macros rename them wherever the float headers are included. */
#define dmp_params_from_gains dmp_params_from_gains_f32
#define dmp_derive_f64 dmp_derive_f64_f32
#define dmp_gains_at_stiffness dmp_gains_at_stiffness_f32
#define dmp_goal dmp_goal_f32
#define dmp_model_init dmp_model_init_f32
#define dmp_run_validate dmp_run_validate_f32
#define dmp_state_reset dmp_state_reset_f32
#define dmp_forcing dmp_forcing_f32
#define dmp_forcing_full dmp_forcing_full_f32
#define dmp_active_kernels dmp_active_kernels_f32
#define dmp_phase_stop_factor dmp_phase_stop_factor_f32
#define dmp_step dmp_step_f32
#define pfc_default_config pfc_default_config_f32
#define pfc_config_validate pfc_config_validate_f32
#define pfc_reset pfc_reset_f32
#define pfc_step pfc_step_f32
#define skill_image_size skill_image_size_f32
#define skill_crc32 skill_crc32_f32
#define skill_parse skill_parse_f32

typedef float fs_real_t;
#define FS_R(x) ((fs_real_t)(x##f))
#ifndef fs_exp /* a port may supply a faster exp (e.g. -Dfs_exp=cm_expf) */
#define fs_exp expf
#endif
#define fs_sqrt sqrtf
#define fs_fabs fabsf
#define fs_isfinite(x) isfinite(x)
#define FS_REAL_INF HUGE_VALF
#else
typedef double fs_real_t;
#define FS_R(x) ((fs_real_t)(x))
#ifndef fs_exp
#define fs_exp exp
#endif
#define fs_sqrt sqrt
#define fs_fabs fabs
#define fs_isfinite(x) isfinite(x)
#define FS_REAL_INF HUGE_VAL
#endif

#endif /* FS_REAL_H */

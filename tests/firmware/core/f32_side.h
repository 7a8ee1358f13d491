/* The float32 half of test_f32_vs_double: compiled with FS_REAL_FLOAT and linked to fs_core_f32,
 * exchanging only plain bytes and doubles with the double half. */
#ifndef F32_SIDE_H
#define F32_SIDE_H

#include <stdint.h>

/** Parse a skill image with the float core and roll it out: rows n = 0..round(T*ts/dt) into
 *  out[] (row 0 is 0). Returns the number of rows, or -(status) if parsing fails, or 0 if cap is
 *  too small. */
long f32_parse_rollout(const uint8_t *image, uint32_t len, double goal_scale, double time_scale,
                       double *out, long cap);

/** The float core's kernel activation fs_num_exp_neg(e) (exp(-e) for 0 <= e <= the cutoff). */
double f32_exp_neg(double e);

/** The float core's kernel cutoff (DMP_KERNEL_CUTOFF_EXP as its build sets it). */
double f32_kernel_cutoff(void);

#endif

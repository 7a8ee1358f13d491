/* bench_periodic_drift's float32 rollout (f32_side.c). */
#ifndef PD_F32_SIDE_H
#define PD_F32_SIDE_H

#include <stdint.h>

/** Parse img with the float32 core and roll its periodic skill out rows steps at scales 1 into
 *  f[0..rows] (N); *x_end the phase in turns after the last step. -1 if it is not a periodic
 *  skill the float core parses. */
int pd_f32_rollout(const uint8_t *img, uint32_t len, long rows, double *f, double *x_end);

#endif /* PD_F32_SIDE_H */

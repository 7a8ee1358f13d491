/* Table-based expf for the Cortex-M4F image (see cm_expf.c for method and accuracy). */
#ifndef CM_EXPF_H
#define CM_EXPF_H

/** e^x in float32 by a 2^(k/256) table + linear interpolation; <= 3e-6 relative on [-23, 0]. */
float cm_expf(float x);

#endif /* CM_EXPF_H */

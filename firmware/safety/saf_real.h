/* The safety modules that compute in fs_real_t are built twice, like the core: fs_safety
 * (double) and fs_safety_f32 (float, FS_REAL_FLOAT). Under FS_REAL_FLOAT their external
 * symbols get an _f32 suffix so both libraries can be linked into one host executable. */
#ifndef SAF_REAL_H
#define SAF_REAL_H

#include "fs_real.h"

#define SAF_AXES 2u

/** One axis's measurement as the safety layer checks it (the application fills it from the
 *  sensors; the safety layer depends on no control-law type). */
typedef struct {
    fs_real_t pos_m;
    fs_real_t vel_mps;
    fs_real_t force_N;
} saf_meas_t;

#ifdef FS_REAL_FLOAT
#include "saf_f32_names.h" /* generated from lim.h, sen.h, wdg.h, saf.h */
#endif

#endif /* SAF_REAL_H */

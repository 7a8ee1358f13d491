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
#define lim_default_config lim_default_config_f32
#define lim_config_validate lim_config_validate_f32
#define lim_reset lim_reset_f32
#define lim_apply lim_apply_f32
#define sen_default_config sen_default_config_f32
#define sen_config_validate sen_config_validate_f32
#define sen_reset sen_reset_f32
#define sen_check sen_check_f32
#define wdg_default_config wdg_default_config_f32
#define wdg_config_validate wdg_config_validate_f32
#define wdg_init wdg_init_f32
#define wdg_kick wdg_kick_f32
#define wdg_disarm wdg_disarm_f32
#define wdg_expired wdg_expired_f32
#define wdg_ramp_ticks wdg_ramp_ticks_f32
#define wdg_ramp_start wdg_ramp_start_f32
#define wdg_ramp_step wdg_ramp_step_f32
#define saf_default_config saf_default_config_f32
#define saf_config_validate saf_config_validate_f32
#define saf_init saf_init_f32
#define saf_step saf_step_f32
#define saf_clear_request saf_clear_request_f32
#endif

#endif /* SAF_REAL_H */

/* The _f32 names of the float32 build of lim.h, sen.h, wdg.h, saf.h
 * (FS_REAL_FLOAT): generated from their declarations by tools/gen_f32_names.py;
 * do not edit. */
#ifndef SAF_F32_NAMES_H
#define SAF_F32_NAMES_H

#define lim_default_config lim_default_config_f32
#define lim_config_validate lim_config_validate_f32
#define lim_reset lim_reset_f32
#define lim_prepare lim_prepare_f32
#define lim_apply lim_apply_f32
#define sen_default_config sen_default_config_f32
#define sen_config_validate sen_config_validate_f32
#define sen_reset sen_reset_f32
#define sen_prepare sen_prepare_f32
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
#define saf_prepare saf_prepare_f32
#define saf_step saf_step_f32
#define saf_clear_request saf_clear_request_f32

#endif /* SAF_F32_NAMES_H */

/* The _fx names of the integer build of lim.h, sen.h, wdg.h, saf.h
 * (SAF_FIXED): generated from their declarations by tools/gen_f32_names.py;
 * do not edit. */
#ifndef SAF_FX_NAMES_H
#define SAF_FX_NAMES_H

#define lim_default_config lim_default_config_fx
#define lim_config_validate lim_config_validate_fx
#define lim_reset lim_reset_fx
#define lim_prepare lim_prepare_fx
#define lim_apply lim_apply_fx
#define sen_default_config sen_default_config_fx
#define sen_config_validate sen_config_validate_fx
#define sen_reset sen_reset_fx
#define sen_prepare sen_prepare_fx
#define sen_check sen_check_fx
#define wdg_default_config wdg_default_config_fx
#define wdg_config_validate wdg_config_validate_fx
#define wdg_init wdg_init_fx
#define wdg_kick wdg_kick_fx
#define wdg_disarm wdg_disarm_fx
#define wdg_expired wdg_expired_fx
#define wdg_ramp_ticks wdg_ramp_ticks_fx
#define wdg_ramp_start wdg_ramp_start_fx
#define wdg_ramp_step wdg_ramp_step_fx
#define saf_default_config saf_default_config_fx
#define saf_config_validate saf_config_validate_fx
#define saf_init saf_init_fx
#define saf_prepare saf_prepare_fx
#define saf_step saf_step_fx
#define saf_clear_request saf_clear_request_fx

#endif /* SAF_FX_NAMES_H */

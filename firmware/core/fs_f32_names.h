/* The _f32 names of the float32 build of dmp.h, pfc.h, skill.h, skill_check.h
 * (FS_REAL_FLOAT): generated from their declarations by tools/gen_f32_names.py;
 * do not edit. */
#ifndef FS_F32_NAMES_H
#define FS_F32_NAMES_H

#define dmp_derive_f64 dmp_derive_f64_f32
#define dmp_derive_f64_part dmp_derive_f64_part_f32
#define dmp_params_from_gains dmp_params_from_gains_f32
#define dmp_gains_at_stiffness dmp_gains_at_stiffness_f32
#define dmp_goal dmp_goal_f32
#define dmp_model_init dmp_model_init_f32
#define dmp_model_init_begin dmp_model_init_begin_f32
#define dmp_model_init_run dmp_model_init_run_f32
#define dmp_model_init_next_is_reach dmp_model_init_next_is_reach_f32
#define dmp_run_validate dmp_run_validate_f32
#define dmp_state_reset dmp_state_reset_f32
#define dmp_forcing dmp_forcing_f32
#define dmp_forcing_full dmp_forcing_full_f32
#define dmp_active_kernels dmp_active_kernels_f32
#define dmp_phase_stop_factor dmp_phase_stop_factor_f32
#define dmp_contact_rate dmp_contact_rate_f32
#define dmp_slowdown_at_rate dmp_slowdown_at_rate_f32
#define dmp_step dmp_step_f32
#define dmp_step_xy dmp_step_xy_f32
#define dmp_prepare dmp_prepare_f32
#define dmp_periodic_reset dmp_periodic_reset_f32
#define dmp_periodic_blend dmp_periodic_blend_f32
#define dmp_periodic_blend_full dmp_periodic_blend_full_f32
#define dmp_periodic_step dmp_periodic_step_f32
#define dmp_periodic_step_xy dmp_periodic_step_xy_f32
#define dmp_periodic_reset_xy dmp_periodic_reset_xy_f32
#define pfc_default_config pfc_default_config_f32
#define pfc_config_validate pfc_config_validate_f32
#define pfc_reset pfc_reset_f32
#define pfc_step pfc_step_f32
#define skill_image_size skill_image_size_f32
#define skill_image_size_v skill_image_size_v_f32
#define skill_image_size_band skill_image_size_band_f32
#define skill_crc32 skill_crc32_f32
#define skill_band_at skill_band_at_f32
#define skill_parse_begin skill_parse_begin_f32
#define skill_parse_run skill_parse_run_f32
#define skill_parse skill_parse_f32
#define skchk_params skchk_params_f32
#define skchk_params_begin skchk_params_begin_f32
#define skchk_params_run skchk_params_run_f32
#define skchk_begin skchk_begin_f32
#define skchk_run skchk_run_f32
#define skchk_skill skchk_skill_f32
#define skchk_run_path skchk_run_path_f32
#define skchk_run_scales skchk_run_scales_f32
#define skchk_run_scales_periodic skchk_run_scales_periodic_f32
#define skchk_stiffness skchk_stiffness_f32

#endif /* FS_F32_NAMES_H */

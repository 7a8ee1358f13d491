/* Parallel force/position law (paper eqs. 2-5, firmware/core/pfc.h) in fixed point for the
 * Cortex-M3 build: the tick is pfc_tick.h compiled over the fixed numeric layer (fs_num.h), the
 * same source as pfc_step. The types have pfc.h's field names (units) in these formats: gains
 * Q16.16 (kg, N*s/m, N/m, 1, 1/s), positions/velocities/accelerations Q8.24 (m, m/s, m/s^2),
 * forces Q16.16 N, force integral Q8.24 N*s, dt Q1.31 s. */
#ifndef PFCFX_H
#define PFCFX_H

#include <stdint.h>
#include "fx.h"
#include "pfc.h"

/** Gains of one axis (field names as pfc_axis_gains_t), Q16.16. */
typedef struct {
    int32_t m_d_kg;
    int32_t k_d_Nspm;
    int32_t k_p_Npm;
    int32_t k_f;
    int32_t k_i_per_s;
} pfcfx_axis_gains_t;

/** Output saturation (Q16.16 N) and anti-windup bound (Q8.24 N*s) of one axis. */
typedef struct {
    int32_t force_max_N;
    int32_t integral_max_Ns;
} pfcfx_axis_limits_t;

/** Complete fixed-point controller configuration; dt in Q1.31 s. */
typedef struct {
    pfcfx_axis_gains_t gains[PFC_AXES];
    pfcfx_axis_limits_t limits[PFC_AXES];
    int32_t dt_s;
} pfcfx_config_t;

/** Force-error integral per axis, Q8.24 N*s. */
typedef struct {
    int32_t force_err_integral_Ns[PFC_AXES];
} pfcfx_state_t;

/** Reference of one axis: Q8.24 m, m/s, m/s^2; Q16.16 N. */
typedef struct {
    int32_t pos_m;
    int32_t vel_mps;
    int32_t acc_mps2;
    int32_t force_N;
} pfcfx_ref_t;

/** Measurement of one axis: Q8.24 m, m/s; Q16.16 N. */
typedef struct {
    int32_t pos_m;
    int32_t vel_mps;
    int32_t force_N;
} pfcfx_meas_t;

/** Convert a validated double configuration; FS_ERR_FIXED_CONFIG (303) if a gain or limit
 *  does not fit (gains and force_max < 32768, integral_max < 128, dt < 1 s). */
fs_status_t pfcfx_from_config(const pfc_config_t *cfg, pfcfx_config_t *out);

/** pfcfx_from_config of a configuration pfc_config_validate already passed (non-NULL
 *  arguments): the conversion alone, for a caller that validated it (exec_start). */
fs_status_t pfcfx_from_valid_config(const pfc_config_t *cfg, pfcfx_config_t *out);

/** Zero the integral state. */
void pfcfx_reset(pfcfx_state_t *st);

/** One control tick (pfc_tick.h, the same code as pfc_step): saturated force command per axis
 *  (Q16.16 N) into force_cmd_q16[2]. */
void pfcfx_step(const pfcfx_config_t *cfg, pfcfx_state_t *st, const pfcfx_ref_t ref[PFC_AXES],
                const pfcfx_meas_t meas[PFC_AXES], int32_t force_cmd_q16[PFC_AXES]);

#endif /* PFCFX_H */

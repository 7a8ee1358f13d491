/* Parallel force/position control law (paper eqs. 2-5), 2 DOF with diagonal gains.
 * Per axis:  f_cmd = m_d*xdd_d + k_d*(xd_d - xd) + k_p*(x_d - x) + k_f*(f_d - f) + k_i*I_f,
 *            I_f = integral(f_d - f) dt  (anti-windup: clamped, and frozen while the output
 *            saturates in the direction that would grow it).
 * f_cmd is the total force command "m_d*xdd" of the paper; it is saturated to +-force_max_N.
 * Axis 0 is x (constrained, into the object), axis 1 is y (unconstrained: k_f = k_i = 0). */
#ifndef PFC_H
#define PFC_H

#include <stdint.h>
#include "fs_real.h"
#include "fs_status.h"

#define PFC_AXES 2u

/** Gains of one axis. Units: m_d kg, k_d N*s/m, k_p N/m, k_f dimensionless, k_i 1/s. */
typedef struct {
    fs_real_t m_d_kg;
    fs_real_t k_d_Nspm;
    fs_real_t k_p_Npm;
    fs_real_t k_f;
    fs_real_t k_i_per_s;
} pfc_axis_gains_t;

/** Output saturation and anti-windup bound of one axis. */
typedef struct {
    fs_real_t force_max_N;     /* |f_cmd| <= force_max_N */
    fs_real_t integral_max_Ns; /* |I_f| <= integral_max_Ns */
} pfc_axis_limits_t;

/** Complete controller configuration (both axes). */
typedef struct {
    pfc_axis_gains_t gains[PFC_AXES];
    pfc_axis_limits_t limits[PFC_AXES];
    fs_real_t dt_s;
} pfc_config_t;

/** Controller state: the force-error integral per axis. */
typedef struct {
    fs_real_t force_err_integral_Ns[PFC_AXES];
} pfc_state_t;

/** Reference of one axis: desired position/velocity/acceleration and contact force. */
typedef struct {
    fs_real_t pos_m;
    fs_real_t vel_mps;
    fs_real_t acc_mps2;
    fs_real_t force_N;
} pfc_axis_ref_t;

/** Measurement of one axis: position, velocity and contact force. */
typedef struct {
    fs_real_t pos_m;
    fs_real_t vel_mps;
    fs_real_t force_N;
} pfc_axis_meas_t;

/** Default gains: m_d 40, k_d 400, k_p 1170, k_i 27, k_f 3 (x); y has k_f = k_i = 0.
 *  force_max 50 N, x integral_max = 4*force_max/k_i (7.4 Ns), dt 1 ms. */
void pfc_default_config(pfc_config_t *cfg);

/** Validate a configuration, per axis then dt: NULL (100), not finite (101), m_d <= 0 (102),
 *  a gain < 0 (107), k_d <= m_d (103), a limit <= 0 (110); dt not finite or <= 0 (108). */
fs_status_t pfc_config_validate(const pfc_config_t *cfg);

/** Zero the integral state. */
void pfc_reset(pfc_state_t *st);

/** One control tick: compute the saturated commanded force per axis into force_cmd_N[2]
 *  (output from the integral of the previous tick, then the integral advances by dt*(f_d - f));
 *  an axis whose command evaluates to NaN gets 0 and its integral is left unchanged. */
void pfc_step(const pfc_config_t *cfg, pfc_state_t *st, const pfc_axis_ref_t ref[PFC_AXES],
              const pfc_axis_meas_t meas[PFC_AXES], fs_real_t force_cmd_N[PFC_AXES]);

#endif /* PFC_H */

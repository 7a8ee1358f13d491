/* Parallel force/position control law (paper eqs. 2-5), 2 DOF, diagonal gains, with output
 * saturation and anti-windup on the force integral. See pfc.h. The tick itself is pfc_tick.h,
 * shared with the fixed-point build (pfcfx.c); configuration and validation are here. */
#include "pfc.h"

#include <stddef.h>

#include "fs_num.h"
#include "fs_wire_const.h"
#define PFC_TICK_CONFIG pfc_config_t
#define PFC_TICK_STATE pfc_state_t
#define PFC_TICK_REF pfc_axis_ref_t
#define PFC_TICK_MEAS pfc_axis_meas_t
#include "pfc_tick.h"

/* Default output limit: |force| <= F_max = 50 N (docs/safety.md). */
#define PFC_DEFAULT_FORCE_MAX_N ((fs_real_t)FS_FORCE_LIMIT_N)
/* Default integral clamp, as a multiple of F_max/k_i (see pfc_default_config). */
#define PFC_DEFAULT_INTEGRAL_FORCE_RATIO FS_R(4.0)
/* Unconstrained axis (k_i = 0): the integral is never used; its bound only has to be > 0.
 * One second of full-scale force error. */
#define PFC_DEFAULT_Y_INTEGRAL_MAX_NS FS_R(50.0)

void pfc_default_config(pfc_config_t *cfg)
{
    /* Default gains: alpha = k_d/m_d - 1 = 9, k_f = k_i/alpha = 3, beta = alpha/4. */
    const pfc_axis_gains_t x = {FS_R(40.0), FS_R(400.0), FS_R(1170.0), FS_R(3.0), FS_R(27.0)};
    const pfc_axis_gains_t y = {FS_R(40.0), FS_R(400.0), FS_R(1170.0), FS_R(0.0), FS_R(0.0)};
    cfg->gains[0] = x;
    cfg->gains[1] = y;
    /* x: conditional integration (pfc_step) is the anti-windup; this clamp is the backstop.
     * At equilibrium on an object the integral balances the position term,
     * k_i*I_f = k_p*(x - x_d), so it must cover a position reference that is off because the
     * object is softer than the skill's nominal k: reusing a 280 N/m skill at 20 N on a 100 N/m
     * object needs k_i*I_f = 1170*20*(1/100 - 1/280) = 150 N. |k_i*I_f| <= 4*F_max = 200 N
     * covers that (I_f <= 7.4 Ns with the default k_i). */
    cfg->limits[0].force_max_N = PFC_DEFAULT_FORCE_MAX_N;
    cfg->limits[0].integral_max_Ns = PFC_DEFAULT_INTEGRAL_FORCE_RATIO * PFC_DEFAULT_FORCE_MAX_N /
                                     x.k_i_per_s;
    cfg->limits[1].force_max_N = PFC_DEFAULT_FORCE_MAX_N;
    cfg->limits[1].integral_max_Ns = PFC_DEFAULT_Y_INTEGRAL_MAX_NS;
    cfg->dt_s = (fs_real_t)FS_TICK_S;
}

fs_status_t pfc_config_validate(const pfc_config_t *cfg)
{
    if (cfg == NULL) {
        return FS_ERR_NULL_ARG;
    }
    for (uint32_t a = 0u; a < PFC_AXES; a++) {
        const pfc_axis_gains_t *g = &cfg->gains[a];
        const pfc_axis_limits_t *l = &cfg->limits[a];
        if (!fs_isfinite(g->m_d_kg) || !fs_isfinite(g->k_d_Nspm) || !fs_isfinite(g->k_p_Npm) ||
            !fs_isfinite(g->k_f) || !fs_isfinite(g->k_i_per_s) || !fs_isfinite(l->force_max_N) ||
            !fs_isfinite(l->integral_max_Ns)) {
            return FS_ERR_NOT_FINITE;
        }
        if (!(g->m_d_kg > FS_R(0.0))) {
            return FS_ERR_MASS_NONPOSITIVE;
        }
        if (g->k_d_Nspm < FS_R(0.0) || g->k_p_Npm < FS_R(0.0) || g->k_f < FS_R(0.0) ||
            g->k_i_per_s < FS_R(0.0)) {
            return FS_ERR_GAIN_NEGATIVE;
        }
        if (!(g->k_d_Nspm > g->m_d_kg)) {
            return FS_ERR_KD_LE_MD;
        }
        if (!(l->force_max_N > FS_R(0.0)) || !(l->integral_max_Ns > FS_R(0.0))) {
            return FS_ERR_LIMIT_INVALID;
        }
    }
    if (!fs_isfinite(cfg->dt_s) || !(cfg->dt_s > FS_R(0.0))) {
        return FS_ERR_DT_INVALID;
    }
    return FS_OK;
}

void pfc_reset(pfc_state_t *st)
{
    for (uint32_t a = 0u; a < PFC_AXES; a++) {
        st->force_err_integral_Ns[a] = FS_R(0.0);
    }
}

void pfc_step(const pfc_config_t *cfg, pfc_state_t *st, const pfc_axis_ref_t ref[PFC_AXES],
              const pfc_axis_meas_t meas[PFC_AXES], fs_real_t force_cmd_N[PFC_AXES])
{
    pfc_tick_step(cfg, st, ref, meas, force_cmd_N);
}

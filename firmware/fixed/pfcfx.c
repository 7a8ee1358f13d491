/* Fixed-point parallel force/position law; mirrors firmware/core/pfc.c line by line. */
#include "pfcfx.h"

#include <stddef.h>

static fs_status_t pfcfx_q(double v, unsigned frac, int32_t *out)
{
    return (fx_from_double(v, frac, INT32_MAX, out) == FS_OK) ? FS_OK : FS_ERR_FIXED_CONFIG;
}

fs_status_t pfcfx_from_config(const pfc_config_t *cfg, pfcfx_config_t *out)
{
    if (cfg == NULL || out == NULL) {
        return FS_ERR_NULL_ARG;
    }
    const fs_status_t v = pfc_config_validate(cfg);
    if (v != FS_OK) {
        return v;
    }
    for (uint32_t a = 0u; a < PFC_AXES; a++) {
        const pfc_axis_gains_t *g = &cfg->gains[a];
        const pfc_axis_limits_t *l = &cfg->limits[a];
        pfcfx_axis_t *o = &out->axis[a];
        fs_status_t st = pfcfx_q((double)g->m_d_kg, 16u, &o->m_d_q16);
        st = (st == FS_OK) ? pfcfx_q((double)g->k_d_Nspm, 16u, &o->k_d_q16) : st;
        st = (st == FS_OK) ? pfcfx_q((double)g->k_p_Npm, 16u, &o->k_p_q16) : st;
        st = (st == FS_OK) ? pfcfx_q((double)g->k_f, 16u, &o->k_f_q16) : st;
        st = (st == FS_OK) ? pfcfx_q((double)g->k_i_per_s, 16u, &o->k_i_q16) : st;
        st = (st == FS_OK) ? pfcfx_q((double)l->force_max_N, 16u, &o->force_max_q16) : st;
        st = (st == FS_OK) ? pfcfx_q((double)l->integral_max_Ns, 24u, &o->integral_max_q24) : st;
        if (st != FS_OK) {
            return st;
        }
    }
    return pfcfx_q((double)cfg->dt_s, 31u, &out->dt_q31);
}

void pfcfx_reset(pfcfx_state_t *st)
{
    for (uint32_t a = 0u; a < PFC_AXES; a++) {
        st->force_err_integral_q24[a] = 0;
    }
}

void pfcfx_step(const pfcfx_config_t *cfg, pfcfx_state_t *st, const pfcfx_ref_t ref[PFC_AXES],
                const pfcfx_meas_t meas[PFC_AXES], int32_t force_cmd_q16[PFC_AXES])
{
    for (uint32_t a = 0u; a < PFC_AXES; a++) {
        const pfcfx_axis_t *g = &cfg->axis[a];
        const int32_t err_q16 = fx_sub_sat(ref[a].force_q16, meas[a].force_q16);
        const int32_t i_f = st->force_err_integral_q24[a];
        /* Every term in Q.32 (N): Q16.16 gain * Q8.24 quantity / 2^8; Q16.16 * Q16.16 as is.
         * The k_f term is < 2^62, the others < 2^54, so the 64-bit sum cannot overflow. */
        const int32_t dv = fx_sub_sat(ref[a].vel_q24, meas[a].vel_q24);
        const int32_t dx = fx_sub_sat(ref[a].pos_q24, meas[a].pos_q24);
        const int64_t sum = (((int64_t)g->m_d_q16 * ref[a].acc_q24) >> 8) +
                            (((int64_t)g->k_d_q16 * dv) >> 8) +
                            (((int64_t)g->k_p_q16 * dx) >> 8) + ((int64_t)g->k_f_q16 * err_q16) +
                            (((int64_t)g->k_i_q16 * i_f) >> 8);
        const int32_t unsat = fx_sat32(fx_rshift_round(sum, 16u));
        force_cmd_q16[a] = fx_clamp_sym(unsat, g->force_max_q16);
        /* Conditional integration, as pfc_step: hold while saturated in the growing direction. */
        const int windup = (unsat > g->force_max_q16 && err_q16 > 0) ||
                           (unsat < -g->force_max_q16 && err_q16 < 0);
        if (g->k_i_q16 > 0 && !windup) {
            const int32_t inc = fx_sat32(fx_rshift_round((int64_t)cfg->dt_q31 * err_q16, 23u));
            st->force_err_integral_q24[a] =
                fx_clamp_sym(fx_add_sat(i_f, inc), g->integral_max_q24);
        }
    }
}

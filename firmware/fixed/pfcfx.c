/* Fixed-point parallel force/position law: conversion of a double configuration here, the tick
 * is firmware/core/pfc_tick.h over the fixed numeric layer (the same source as pfc_step). */
#include "pfcfx.h"

#include <stddef.h>

#include "fs_num.h"
#define PFC_TICK_CONFIG pfcfx_config_t
#define PFC_TICK_STATE pfcfx_state_t
#define PFC_TICK_REF pfcfx_ref_t
#define PFC_TICK_MEAS pfcfx_meas_t
#include "pfc_tick.h"

#include <string.h>

/* A configuration value in a Q format, FS_ERR_FIXED_CONFIG if it does not fit (or is not
 * finite). The float build converts from the float's bits (fx_from_float: no software-float
 * call on a core without FPU, where exec_start runs in a control tick); the double build rounds
 * half up. */
static fs_status_t pfcfx_q(fs_real_t v, unsigned frac, int32_t *out)
{
#ifdef FS_REAL_FLOAT
    uint32_t b;
    memcpy(&b, &v, sizeof b);
    const int32_t x = fx_from_float(v, frac);
    if ((b & 0x7F800000u) == 0x7F800000u || x == INT32_MAX || x == INT32_MIN) {
        return FS_ERR_FIXED_CONFIG;
    }
    *out = x;
    return FS_OK;
#else
    return (fx_from_double(v, frac, INT32_MAX, out) == FS_OK) ? FS_OK : FS_ERR_FIXED_CONFIG;
#endif
}

fs_status_t pfcfx_from_config(const pfc_config_t *cfg, pfcfx_config_t *out)
{
    if (cfg == NULL || out == NULL) {
        return FS_ERR_NULL_ARG;
    }
    const fs_status_t v = pfc_config_validate(cfg);
    return (v == FS_OK) ? pfcfx_from_valid_config(cfg, out) : v;
}

fs_status_t pfcfx_from_valid_config(const pfc_config_t *cfg, pfcfx_config_t *out)
{
    for (uint32_t a = 0u; a < PFC_AXES; a++) {
        const pfc_axis_gains_t *g = &cfg->gains[a];
        const pfc_axis_limits_t *l = &cfg->limits[a];
        pfcfx_axis_gains_t *o = &out->gains[a];
        pfcfx_axis_limits_t *ol = &out->limits[a];
        fs_status_t st = pfcfx_q(g->m_d_kg, 16u, &o->m_d_kg);
        st = (st == FS_OK) ? pfcfx_q(g->k_d_Nspm, 16u, &o->k_d_Nspm) : st;
        st = (st == FS_OK) ? pfcfx_q(g->k_p_Npm, 16u, &o->k_p_Npm) : st;
        st = (st == FS_OK) ? pfcfx_q(g->k_f, 16u, &o->k_f) : st;
        st = (st == FS_OK) ? pfcfx_q(g->k_i_per_s, 16u, &o->k_i_per_s) : st;
        st = (st == FS_OK) ? pfcfx_q(l->force_max_N, 16u, &ol->force_max_N) : st;
        st = (st == FS_OK) ? pfcfx_q(l->integral_max_Ns, 24u, &ol->integral_max_Ns) : st;
        if (st != FS_OK) {
            return st;
        }
    }
    return pfcfx_q(cfg->dt_s, 31u, &out->dt_s);
}

void pfcfx_reset(pfcfx_state_t *st)
{
    for (uint32_t a = 0u; a < PFC_AXES; a++) {
        st->force_err_integral_Ns[a] = 0;
    }
}

void pfcfx_step(const pfcfx_config_t *cfg, pfcfx_state_t *st, const pfcfx_ref_t ref[PFC_AXES],
                const pfcfx_meas_t meas[PFC_AXES], int32_t force_cmd_q16[PFC_AXES])
{
    pfc_tick_step(cfg, st, ref, meas, force_cmd_q16);
}

/* Limits at the last stage before the actuator: see lim.h. */
#include "lim.h"

#include <stdbool.h>
#include <stddef.h>

#include "fs_wire_const.h"
#include "saf_tick.h"

void lim_default_config(lim_config_t *cfg)
{
    if (cfg == NULL) {
        return;
    }
    for (uint32_t i = 0u; i < LIM_AXES; i++) {
        cfg->axis[i].force_max_N = (fs_real_t)FS_FORCE_LIMIT_N;
        cfg->axis[i].slew_max_N = FS_R(2.0);
        cfg->axis[i].pos_min_m = FS_R(-0.5);
        cfg->axis[i].pos_max_m = FS_R(0.5);
        cfg->axis[i].vel_max_mps = FS_R(1.0);
        cfg->axis[i].contact_force_max_N = FS_R(60.0);
    }
    cfg->slew_fault_ticks = 50u;
}

saf_status_t lim_config_validate(const lim_config_t *cfg)
{
    if (cfg == NULL) {
        return SAF_ERR_NULL_ARG;
    }
    for (uint32_t i = 0u; i < LIM_AXES; i++) {
        const lim_axis_t *a = &cfg->axis[i];
        const fs_real_t v[6] = {a->force_max_N, a->slew_max_N,  a->pos_min_m,
                                a->pos_max_m,   a->vel_max_mps, a->contact_force_max_N};
        for (uint32_t j = 0u; j < 6u; j++) {
            if (!fs_isfinite(v[j])) {
                return SAF_ERR_NOT_FINITE;
            }
        }
        if (!(a->force_max_N > FS_R(0.0)) || !(a->slew_max_N > FS_R(0.0)) ||
            !(a->vel_max_mps > FS_R(0.0)) || !(a->contact_force_max_N > FS_R(0.0))) {
            return SAF_ERR_NONPOSITIVE;
        }
        if (!(a->pos_min_m < a->pos_max_m)) {
            return SAF_ERR_WORKSPACE;
        }
        if (a->force_max_N > (fs_real_t)LIM_FORCE_CEILING_N) {
            return SAF_ERR_FORCE_MAX;
        }
    }
    return SAF_OK;
}

void lim_reset(lim_state_t *st)
{
    if (st == NULL) {
        return;
    }
    for (uint32_t i = 0u; i < LIM_AXES; i++) {
        st->out_N[i] = SAF_FORCE_C(0.0);
        st->slew_run[i] = 0u;
    }
}

/* A usable positive bound from a configuration value: NaN, inf or <= 0 give 0, so a corrupted
 * configuration can only make the output smaller, never non-finite. */
static fs_real_t safe_bound(fs_real_t b)
{
    return (fs_isfinite(b) && b > FS_R(0.0)) ? b : FS_R(0.0);
}

void lim_prepare(const lim_config_t *cfg, lim_state_t *st)
{
    if (cfg == NULL || st == NULL) {
        return;
    }
    for (uint32_t i = 0u; i < LIM_AXES; i++) {
        const lim_axis_t *a = &cfg->axis[i];
        lim_bounds_t *b = &st->b[i];
        b->force_max_N = SAF_FORCE_OF(safe_bound(a->force_max_N));
        b->slew_max_N = SAF_FORCE_OF(safe_bound(a->slew_max_N));
        b->pos_min_m = SAF_POS_OF(a->pos_min_m);
        b->pos_max_m = SAF_POS_OF(a->pos_max_m);
        b->vel_max_mps = SAF_POS_OF(a->vel_max_mps);
        b->contact_force_max_N = SAF_FORCE_OF(a->contact_force_max_N);
    }
}

lim_result_t lim_apply(const lim_config_t *cfg, lim_state_t *st, const saf_force_t req_N[LIM_AXES],
                       const saf_meas_t meas[LIM_AXES], saf_force_t out_N[LIM_AXES])
{
    lim_result_t r = {0u, 0u};
    if (out_N == NULL) {
        return r;
    }
    if (cfg == NULL || st == NULL || req_N == NULL) {
        for (uint32_t i = 0u; i < LIM_AXES; i++) {
            out_N[i] = SAF_FORCE_C(0.0);
        }
        return r;
    }
    for (uint32_t i = 0u; i < LIM_AXES; i++) {
        out_N[i] = lim_apply_axis(cfg, st, i, req_N[i], (meas != NULL) ? &meas[i] : NULL, false,
                                  &r);
    }
    return r;
}

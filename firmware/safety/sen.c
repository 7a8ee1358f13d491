/* Sensor plausibility: see sen.h. */
#include "sen.h"

#include <stdbool.h>
#include <stddef.h>
#include <string.h>

#include "saf_tick.h"

void sen_default_config(sen_config_t *cfg)
{
    if (cfg == NULL) {
        return;
    }
    for (uint32_t i = 0u; i < SAF_AXES; i++) {
        cfg->axis[i].force_range_N = FS_R(200.0);
        cfg->axis[i].pos_min_m = FS_R(-1.0);
        cfg->axis[i].pos_max_m = FS_R(1.0);
        cfg->axis[i].vel_range_mps = FS_R(10.0);
        cfg->axis[i].spike_N = FS_R(20.0);
        cfg->axis[i].jump_m = FS_R(0.005);
        cfg->axis[i].stuck_min_N = FS_R(0.5);
        cfg->axis[i].stuck_ticks = 500u;
    }
}

saf_status_t sen_config_validate(const sen_config_t *cfg)
{
    if (cfg == NULL) {
        return SAF_ERR_NULL_ARG;
    }
    for (uint32_t i = 0u; i < SAF_AXES; i++) {
        const sen_axis_t *a = &cfg->axis[i];
        const fs_real_t v[7] = {a->force_range_N, a->pos_min_m, a->pos_max_m,  a->vel_range_mps,
                                a->spike_N,       a->jump_m,    a->stuck_min_N};
        for (uint32_t j = 0u; j < 7u; j++) {
            if (!fs_isfinite(v[j])) {
                return SAF_ERR_NOT_FINITE;
            }
        }
        if (!(a->force_range_N > FS_R(0.0)) || !(a->vel_range_mps > FS_R(0.0)) ||
            !(a->spike_N > FS_R(0.0)) || !(a->jump_m > FS_R(0.0)) ||
            !(a->stuck_min_N >= FS_R(0.0))) {
            return SAF_ERR_NONPOSITIVE;
        }
        if (!(a->pos_min_m < a->pos_max_m)) {
            return SAF_ERR_WORKSPACE;
        }
    }
    return SAF_OK;
}

void sen_reset(sen_state_t *st)
{
    if (st == NULL) {
        return;
    }
    for (uint32_t i = 0u; i < SAF_AXES; i++) {
        st->prev[i].pos_m = (saf_pos_t)0;
        st->prev[i].vel_mps = (saf_vel_t)0;
        st->prev[i].force_N = SAF_FORCE_C(0.0);
        st->same_count[i] = 0u;
    }
    st->have_prev = 0u;
}

void sen_prepare(const sen_config_t *cfg, sen_state_t *st)
{
    if (cfg == NULL || st == NULL) {
        return;
    }
    bool finite = true;
    for (uint32_t i = 0u; i < SAF_AXES; i++) {
        const sen_axis_t *a = &cfg->axis[i];
        finite = finite && fs_isfinite(a->force_range_N) && fs_isfinite(a->vel_range_mps) &&
                 fs_isfinite(a->pos_min_m) && fs_isfinite(a->pos_max_m);
        sen_bounds_t *b = &st->b[i];
        b->force_range_N = SAF_FORCE_OF(a->force_range_N);
        b->pos_min_m = SAF_POS_OF(a->pos_min_m);
        b->pos_max_m = SAF_POS_OF(a->pos_max_m);
        b->vel_range_mps = SAF_POS_OF(a->vel_range_mps);
        b->spike_N = SAF_FORCE_OF(a->spike_N);
        b->jump_m = SAF_POS_OF(a->jump_m);
        b->stuck_min_N = SAF_FORCE_OF(a->stuck_min_N);
    }
    st->bounds_finite = finite ? 1u : 0u;
}

uint32_t sen_check(const sen_config_t *cfg, sen_state_t *st, const saf_meas_t meas[SAF_AXES])
{
    if (cfg == NULL || st == NULL || meas == NULL) {
        return FLT_BIT(FLT_SENSOR_NAN);
    }
    return sen_check_tick(cfg, st, meas, false, false);
}

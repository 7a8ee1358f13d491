/* Limits at the last stage before the actuator: see lim.h. */
#include "lim.h"

#include <stdbool.h>
#include <stddef.h>

#include "fs_wire_const.h"

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

static saf_force_t clamp_sym(saf_force_t x, saf_force_t b)
{
    if (x > b) {
        return b;
    }
    if (x < -b) {
        return -b;
    }
    return x;
}

/* The measurement gates of one axis: outside the workspace or above the velocity limit, a
 * request pushing further out is zeroed; the contact force is checked. Returns the target. */
static saf_force_t gate_by_measurement(const lim_bounds_t *a, const saf_meas_t *m,
                                       saf_force_t target, lim_result_t *r)
{
    const saf_pos_t pos = m->pos_m;
    const saf_vel_t vel = m->vel_mps;
    const saf_force_t f = m->force_N;
    const saf_force_t zero = SAF_FORCE_C(0.0);
    /* A non-finite reading never gates here (sen_check latches FLT_SENSOR_NAN and the stop
     * ramp takes over): in floating point its comparisons are false, in integers it is tested */
    if (saf_comparable(pos) && (pos > a->pos_max_m || pos < a->pos_min_m)) {
        r->cause_mask |= FLT_BIT(FLT_WORKSPACE);
        if ((pos > a->pos_max_m && target > zero) || (pos < a->pos_min_m && target < zero)) {
            r->flags |= LIM_F_WORKSPACE;
            target = zero;
        }
    }
    if (saf_comparable(vel) && saf_abs(vel) > a->vel_max_mps) {
        r->cause_mask |= FLT_BIT(FLT_VELOCITY);
        if ((vel > (saf_vel_t)0 && target > zero) || (vel < (saf_vel_t)0 && target < zero)) {
            r->flags |= LIM_F_VELOCITY;
            target = zero;
        }
    }
    if (saf_comparable(f) && saf_abs(f) > a->contact_force_max_N) {
        r->cause_mask |= FLT_BIT(FLT_FORCE_LIMIT);
    }
    return target;
}

/* The slew limit of axis i toward target, its leaky bucket and the force clamp; returns the
 * output (also kept as the axis's last output). */
static saf_force_t slew_step(const lim_config_t *cfg, lim_state_t *st, uint32_t i,
                             saf_force_t target, saf_force_t fmax, saf_force_t slew,
                             lim_result_t *r)
{
    /* Slew relative to the last output (sanitised: it is this module's own state, but a
     * corrupted value must not propagate). */
    saf_force_t prev = st->out_N[i];
    if (!saf_within(prev, fmax)) { /* fmax is finite: the usual value costs one test */
        if (!saf_finite(prev)) {
            prev = SAF_FORCE_C(0.0);
        }
        prev = clamp_sym(prev, fmax);
    }
    saf_force_t out = target;
    const saf_force_t step = saf_sub(target, prev);
    bool binds = true;
    if (step > slew) {
        out = saf_add(prev, slew);
    } else if (step < -slew) {
        out = saf_sub(prev, slew);
    } else {
        binds = false;
    }
    if (binds) {
        r->flags |= LIM_F_SLEW;
        out = clamp_sym(out, fmax); /* else out is the target, within fmax already */
    }
    /* Leaky bucket: +2 when the slew limit binds on this axis, -1 otherwise. Binding every tick
     * trips after slew_fault_ticks; an oscillation binding every other tick after about
     * 4*slew_fault_ticks; a single large step (e.g. 0 -> 50 N, 25 ticks) never. */
    if (binds) {
        st->slew_run[i] = (uint16_t)((st->slew_run[i] <= UINT16_MAX - 2u) ? st->slew_run[i] + 2u
                                                                          : UINT16_MAX);
    } else if (st->slew_run[i] > 0u) {
        st->slew_run[i]--;
    }
    if (cfg->slew_fault_ticks != 0u &&
        (uint32_t)st->slew_run[i] >= 2u * (uint32_t)cfg->slew_fault_ticks) {
        r->cause_mask |= FLT_BIT(FLT_SLEW_LIMIT);
    }
    st->out_N[i] = out;
    return out;
}

/* A request that is not finite (0) or beyond fmax (clamped), its flags and cause. */
static saf_force_t limit_request(saf_force_t target, saf_force_t fmax, lim_result_t *r)
{
    if (!saf_finite(target)) {
        r->flags |= LIM_F_NOT_FINITE;
        r->cause_mask |= FLT_BIT(FLT_CMD_NOT_FINITE);
        return SAF_FORCE_C(0.0);
    }
    if (saf_abs(target) > fmax) {
        r->flags |= LIM_F_FORCE;
        return clamp_sym(target, fmax);
    }
    return target;
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
        const lim_bounds_t *a = &st->b[i];
        const saf_force_t fmax = a->force_max_N;
        saf_force_t target = req_N[i];
        if (!saf_within(target, fmax)) { /* fmax is finite: the usual request costs one test */
            target = limit_request(target, fmax, &r);
        }
        if (meas != NULL) {
            target = gate_by_measurement(a, &meas[i], target, &r);
        }
        out_N[i] = slew_step(cfg, st, i, target, fmax, a->slew_max_N, &r);
    }
    return r;
}

/* The tick's checks of the safety layer as inline functions (private to firmware/safety):
 * sen_check and lim_apply are these behind their argument checks, and saf_step runs them inline,
 * so the supervisor's tick is one function with its two axes written out. */
#ifndef SAF_TICK_H
#define SAF_TICK_H

#include <stdbool.h>
#include <stdint.h>
#include <string.h>

#include "lim.h"
#include "sen.h"
#include "wdg.h"

_Static_assert(SAF_AXES == 2u, "the tick's checks are written out for two axes");

/* inline whatever the compiler's size estimate: each runs once or twice a tick; the usual
 * outcome of a test laid out as the straight path (SAF_USUAL: a hint, no other effect) */
#if defined(__GNUC__)
#define SAF_TICK_INLINE static inline __attribute__((always_inline))
#define SAF_USUAL(x, v) __builtin_expect((x), (v))
#else
#define SAF_TICK_INLINE static inline
#define SAF_USUAL(x, v) (x)
#endif

/* ---------------------------------------------------------------- sensor plausibility */

/* A reading finite and within its range bounds (finite bounds): its finite and range checks
 * find nothing, in one pass of four compares. */
static inline bool sen_usual_reading(const sen_bounds_t *a, const saf_meas_t *m)
{
    return saf_within(m->force_N, a->force_range_N) && saf_within(m->vel_mps, a->vel_range_mps) &&
           saf_inside(m->pos_m, a->pos_min_m, a->pos_max_m);
}

/* Two readings with the same bit pattern (a word compare: -0.0/+0.0 differ, NaN equals itself;
 * in integers the converted values, which a reading frozen at the ADC freezes too). */
static inline bool sen_same_bits(const saf_force_t *a, const saf_force_t *b)
{
#if defined(FS_REAL_FLOAT) || defined(SAF_FIXED)
    uint32_t x, y;
#else
    uint64_t x, y;
#endif
    _Static_assert(sizeof x == sizeof *a, "saf_force_t is 4 or 8 bytes");
    memcpy(&x, a, sizeof x);
    memcpy(&y, b, sizeof y);
    return x == y;
}

/* Axis i of sen_check: its causes; *finite cleared if a reading is not finite (then neither
 * the checks against the previous reading nor its storing run). usual: the reading is known
 * finite and within its range bounds (the supervisor's test, lim_reading_inside). */
SAF_TICK_INLINE uint32_t sen_check_axis(const sen_config_t *cfg, sen_state_t *st, uint32_t i,
                                        const saf_meas_t *m, bool bounds_finite, bool usual,
                                        bool *finite)
{
    const sen_axis_t *c = &cfg->axis[i];
    const sen_bounds_t *a = &st->b[i];
    uint32_t cause = 0u;
    if (usual || (bounds_finite && sen_usual_reading(a, m))) {
        /* finite and in range */
    } else if (!saf_finite(m->pos_m) || !saf_finite(m->vel_mps) || !saf_finite(m->force_N)) {
        *finite = false;
        return FLT_BIT(FLT_SENSOR_NAN);
    } else if (saf_abs(m->force_N) > a->force_range_N || m->pos_m < a->pos_min_m ||
               m->pos_m > a->pos_max_m || saf_abs(m->vel_mps) > a->vel_range_mps) {
        cause |= FLT_BIT(FLT_SENSOR_RANGE);
    }
    if (SAF_USUAL(st->have_prev != 0u, 1)) {
        const saf_meas_t *p = &st->prev[i];
        if (saf_absdiff(m->force_N, p->force_N) > a->spike_N) {
            cause |= FLT_BIT(FLT_SENSOR_SPIKE);
        }
        if (saf_absdiff(m->pos_m, p->pos_m) > a->jump_m) {
            cause |= FLT_BIT(FLT_ENCODER_JUMP);
        }
        /* Stuck: bit-identical non-zero force. Compare the bytes, so -0.0/+0.0 and rounding
         * cannot hide a frozen ADC word. */
        if (c->stuck_ticks != 0u && saf_abs(m->force_N) > a->stuck_min_N &&
            sen_same_bits(&m->force_N, &p->force_N)) {
            if (st->same_count[i] < UINT16_MAX) {
                st->same_count[i]++;
            }
        } else {
            st->same_count[i] = 0u;
        }
        /* same_count counts repeats: stuck_ticks identical readings = stuck_ticks - 1 */
        if (c->stuck_ticks != 0u && (uint32_t)st->same_count[i] + 1u >= c->stuck_ticks) {
            cause |= FLT_BIT(FLT_SENSOR_STUCK);
        }
    }
    return cause;
}

/* sen_check with its arguments valid; usual0/1: as sen_check_axis's usual for each axis. */
SAF_TICK_INLINE uint32_t sen_check_tick(const sen_config_t *cfg, sen_state_t *st,
                                        const saf_meas_t meas[SAF_AXES], bool usual0, bool usual1)
{
    bool finite = true;
    const bool bounds_finite = st->bounds_finite != 0u;
    uint32_t cause = sen_check_axis(cfg, st, 0u, &meas[0], bounds_finite, usual0, &finite);
    cause |= sen_check_axis(cfg, st, 1u, &meas[1], bounds_finite, usual1, &finite);
    if (SAF_USUAL(finite, 1)) {
        st->prev[0] = meas[0];
        st->prev[1] = meas[1];
        st->have_prev = 1u;
    }
    return cause;
}

/* ---------------------------------------------------------------- limits */

static inline saf_force_t lim_clamp_sym(saf_force_t x, saf_force_t b)
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
SAF_TICK_INLINE saf_force_t lim_gate_by_measurement(const lim_bounds_t *a, const saf_meas_t *m,
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
SAF_TICK_INLINE saf_force_t lim_slew_step(const lim_config_t *cfg, lim_state_t *st, uint32_t i,
                                          saf_force_t target, saf_force_t fmax, saf_force_t slew,
                                          lim_result_t *r)
{
    /* Slew relative to the last output (sanitised: it is this module's own state, but a
     * corrupted value must not propagate). */
    saf_force_t prev = st->out_N[i];
    if (SAF_USUAL(!saf_within(prev, fmax), 0)) { /* fmax finite: the usual value, one test */
        if (!saf_finite(prev)) {
            prev = SAF_FORCE_C(0.0);
        }
        prev = lim_clamp_sym(prev, fmax);
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
        out = lim_clamp_sym(out, fmax); /* else out is the target, within fmax already */
    }
    /* Leaky bucket: +2 when the slew limit binds on this axis, -1 otherwise. Binding every tick
     * trips after slew_fault_ticks; an oscillation binding every other tick after about
     * 4*slew_fault_ticks; a single large step (e.g. 0 -> 50 N, 25 ticks) never. */
    /* an empty bucket that stays empty cannot trip */
    if (SAF_USUAL(binds || st->slew_run[i] > 0u, 0)) {
        if (binds) {
            st->slew_run[i] = (uint16_t)((st->slew_run[i] <= UINT16_MAX - 2u) ? st->slew_run[i] + 2u
                                                                              : UINT16_MAX);
        } else {
            st->slew_run[i]--;
        }
        if (cfg->slew_fault_ticks != 0u &&
            (uint32_t)st->slew_run[i] >= 2u * (uint32_t)cfg->slew_fault_ticks) {
            r->cause_mask |= FLT_BIT(FLT_SLEW_LIMIT);
        }
    }
    st->out_N[i] = out;
    return out;
}

/* A request that is not finite (0) or beyond fmax (clamped), its flags and cause. */
static inline saf_force_t lim_limit_request(saf_force_t target, saf_force_t fmax, lim_result_t *r)
{
    if (!saf_finite(target)) {
        r->flags |= LIM_F_NOT_FINITE;
        r->cause_mask |= FLT_BIT(FLT_CMD_NOT_FINITE);
        return SAF_FORCE_C(0.0);
    }
    if (saf_abs(target) > fmax) {
        r->flags |= LIM_F_FORCE;
        return lim_clamp_sym(target, fmax);
    }
    return target;
}

/* A reading inside the axis's workspace, velocity and contact force bounds (finite): the
 * measurement gates find nothing. */
static inline bool lim_reading_inside(const lim_bounds_t *a, const saf_meas_t *m)
{
    return saf_inside(m->pos_m, a->pos_min_m, a->pos_max_m) &&
           saf_within(m->vel_mps, a->vel_max_mps) && saf_within(m->force_N, a->contact_force_max_N);
}

/* Axis i of lim_apply (meas may be NULL): the limited request. inside: the reading is known
 * inside the axis's bounds (lim_reading_inside): no gate to run. */
SAF_TICK_INLINE saf_force_t lim_apply_axis(const lim_config_t *cfg, lim_state_t *st, uint32_t i,
                                           saf_force_t req, const saf_meas_t *meas, bool inside,
                                           lim_result_t *r)
{
    const lim_bounds_t *a = &st->b[i];
    const saf_force_t fmax = a->force_max_N;
    saf_force_t target = req;
    if (SAF_USUAL(!saf_within(target, fmax), 0)) { /* fmax finite: the usual request, one test */
        target = lim_limit_request(target, fmax, r);
    }
    if (SAF_USUAL(meas != NULL && !inside, 0)) {
        target = lim_gate_by_measurement(a, meas, target, r);
    }
    return lim_slew_step(cfg, st, i, target, fmax, a->slew_max_N, r);
}

/* ---------------------------------------------------------------- watchdog */

/* wdg_expired with its arguments valid. */
static inline bool wdg_expired_tick(const wdg_config_t *cfg, const wdg_state_t *st, uint32_t now_ms)
{
    return st->armed != 0u && (uint32_t)(now_ms - st->last_host_ms) >= (uint32_t)cfg->timeout_ms;
}

#endif /* SAF_TICK_H */

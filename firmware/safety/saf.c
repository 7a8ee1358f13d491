/* Safety supervisor: see saf.h. */
#include "saf.h"

#include <stddef.h>
#include <string.h>

#include "saf_tick.h"

void saf_default_config(saf_config_t *cfg)
{
    if (cfg == NULL) {
        return;
    }
    lim_default_config(&cfg->lim);
    sen_default_config(&cfg->sen);
    wdg_default_config(&cfg->wdg);
}

saf_status_t saf_config_validate(const saf_config_t *cfg)
{
    if (cfg == NULL) {
        return SAF_ERR_NULL_ARG;
    }
    saf_status_t s = lim_config_validate(&cfg->lim);
    if (s != SAF_OK) {
        return s;
    }
    s = sen_config_validate(&cfg->sen);
    if (s != SAF_OK) {
        return s;
    }
    s = wdg_config_validate(&cfg->wdg);
    if (s != SAF_OK) {
        return s;
    }
    /* The stop ramp must not be slower than the slew limit allows in the other direction: a
     * restart after a clear climbs at slew_max, and the ramp from force_max takes
     * force_max/n per tick; both are bounded by slew_max so the actuator never sees a step
     * larger than the configured slew. */
    const fs_real_t n = (fs_real_t)wdg_ramp_ticks(&cfg->wdg);
    for (uint32_t i = 0u; i < LIM_AXES; i++) {
        if (cfg->lim.axis[i].slew_max_N * n < cfg->lim.axis[i].force_max_N) {
            return SAF_ERR_RAMP;
        }
    }
    return SAF_OK;
}

void saf_init(saf_state_t *st)
{
    if (st == NULL) {
        return;
    }
    flt_init(&st->flt);
    lim_reset(&st->lim);
    sen_reset(&st->sen);
    memset(st->lim.b, 0, sizeof st->lim.b);
    memset(st->sen.b, 0, sizeof st->sen.b);
    st->sen.bounds_finite = 0u;
    wdg_init(&st->wdg);
    st->ramp.active = 0u;
    st->ramp.k = 0u;
    st->ramp.n_ticks = 1u;
    for (uint32_t i = 0u; i < SAF_AXES; i++) {
        st->ramp.from_N[i] = SAF_FORCE_C(0.0);
        st->ramp.out_N[i] = SAF_FORCE_C(0.0);
        st->last_cmd_N[i] = SAF_FORCE_C(0.0);
    }
    st->cause_mask = 0u;
    st->actuator_enabled = true;
    st->hold_zero = false;
    st->bounds_nested = false;
}

void saf_prepare(const saf_config_t *cfg, saf_state_t *st)
{
    if (cfg == NULL || st == NULL) {
        return;
    }
    lim_prepare(&cfg->lim, &st->lim);
    sen_prepare(&cfg->sen, &st->sen);
    /* every limiter bound within the sensor checks' finite ranges (a NaN bound fails) */
    bool nested = st->sen.bounds_finite != 0u;
    for (uint32_t i = 0u; i < SAF_AXES; i++) {
        const lim_bounds_t *l = &st->lim.b[i];
        const sen_bounds_t *s = &st->sen.b[i];
        nested = nested && s->pos_min_m <= l->pos_min_m && l->pos_max_m <= s->pos_max_m &&
                 l->vel_max_mps <= s->vel_range_mps && l->contact_force_max_N <= s->force_range_N;
    }
    st->bounds_nested = nested;
}

/* Every cause bit, lowest first (the order of the codes); a tick without a cause costs one test. */
static void latch_causes(flt_state_t *flt, uint32_t cause, uint32_t tick)
{
    uint32_t rest = cause & ((1u << FLT_COUNT) - 1u);
    for (uint32_t i = 0u; rest != 0u; i++, rest >>= 1) {
        if ((rest & 1u) != 0u) {
            (void)flt_raise(flt, (flt_code_t)(FLT_CODE_FIRST + i), tick);
        }
    }
}

/* No configuration, state or input: zero force, actuator off, stopping. */
static void fail_safe(saf_output_t *out)
{
    for (uint32_t i = 0u; i < SAF_AXES; i++) {
        out->force_cmd_N[i] = SAF_FORCE_C(0.0);
    }
    out->actuator_enable = false;
    out->stopping = true;
    out->fault_code = 0u;
    out->cause_mask = 0u;
    out->lim_flags = 0u;
}

/* The causes seen in this tick's inputs: host watchdog, the application's (bus-off, overrun,
 * skill, storage, band) and the sensor checks (the limiter's causes come later); inside0/1: axis
 * 0/1's reading inside the limiter's bounds, nested in the sensor ranges (its range tests are
 * passed). */
static uint32_t input_causes(const saf_config_t *cfg, saf_state_t *st, const saf_input_t *in,
                             bool inside0, bool inside1)
{
    uint32_t cause = 0u;
    if (in->host_frame) { /* silence measured from the frame's arrival, not its check */
        wdg_kick(&st->wdg, in->now_ms - in->host_frame_age_ms);
    }
    if (wdg_expired_tick(&cfg->wdg, &st->wdg, in->now_ms)) {
        cause |= FLT_BIT(FLT_HOST_SILENCE);
    }
    cause |= in->causes & SAF_INPUT_CAUSES; /* bus-off, overrun, skill, storage, band */
    return cause | sen_check_tick(&cfg->sen, &st->sen, in->meas, inside0, inside1);
}

/* The request the limiter sees: zero while stopping, and after a clear until the request has
 * come back to (near) zero once (hold_zero). */
static void gate_request(saf_state_t *st, const saf_input_t *in, bool stopping,
                         saf_force_t req[SAF_AXES])
{
    bool pass = !stopping;
    if (st->hold_zero) { /* the request's magnitude matters only while holding zero */
        bool req_zero = true;
        for (uint32_t i = 0u; i < SAF_AXES; i++) {
            const saf_force_t r = in->force_req_N[i];
            if (!(r <= SAF_FORCE_C(SAF_REARM_N) && r >= -SAF_FORCE_C(SAF_REARM_N))) {
                req_zero = false;
            }
        }
        if (req_zero) {
            st->hold_zero = false;
        } else {
            pass = false;
        }
    }
    for (uint32_t i = 0u; i < SAF_AXES; i++) {
        req[i] = pass ? in->force_req_N[i] : SAF_FORCE_C(0.0);
    }
}

/* A latched fault: the ramp to zero from the last command, then the actuator off; the
 * limiter's slew reference follows what the actuator really got. */
static void stop_command(const saf_config_t *cfg, saf_state_t *st, saf_force_t cmd[SAF_AXES])
{
    if (st->actuator_enabled) {
        if (st->ramp.active == 0u) {
            wdg_ramp_start(&st->ramp, &cfg->wdg, st->last_cmd_N);
        }
        if (wdg_ramp_step(&st->ramp, cmd)) {
            st->actuator_enabled = false;
        }
    } else {
        for (uint32_t i = 0u; i < SAF_AXES; i++) {
            cmd[i] = SAF_FORCE_C(0.0);
        }
    }
    for (uint32_t i = 0u; i < SAF_AXES; i++) {
        st->lim.out_N[i] = cmd[i];
    }
}

void saf_step(const saf_config_t *cfg, saf_state_t *st, const saf_input_t *in, saf_output_t *out)
{
    if (out == NULL) {
        return;
    }
    if (cfg == NULL || st == NULL || in == NULL) {
        fail_safe(out);
        return;
    }
    /* a reading inside the limiter's bounds, when these lie within the sensor checks' ranges
     * (saf_prepare), passes both modules' range tests by one test of its own */
    const bool inside0 = st->bounds_nested && lim_reading_inside(&st->lim.b[0], &in->meas[0]);
    const bool inside1 = st->bounds_nested && lim_reading_inside(&st->lim.b[1], &in->meas[1]);
    uint32_t cause = input_causes(cfg, st, in, inside0, inside1);
    /* While stopping (a fault latched or a cause seen this tick) the request is ignored: the
     * limiter still runs for its measurement checks (workspace, velocity, contact force), but
     * sees a zero request, and its slew-binding bucket is not charged by the ramp. */
    const bool stopping = flt_active(&st->flt) || cause != 0u;
    saf_force_t req[SAF_AXES];
    gate_request(st, in, stopping, req);
    /* lim_apply's two axes, into the command a latched fault replaces */
    lim_result_t lr = {0u, 0u};
    saf_force_t cmd[SAF_AXES];
    cmd[0] = lim_apply_axis(&cfg->lim, &st->lim, 0u, req[0], &in->meas[0], inside0, &lr);
    cmd[1] = lim_apply_axis(&cfg->lim, &st->lim, 1u, req[1], &in->meas[1], inside1, &lr);
    if (SAF_USUAL(stopping, 0)) {
        for (uint32_t i = 0u; i < LIM_AXES; i++) {
            st->lim.slew_run[i] = 0u;
        }
        cause |= lr.cause_mask & ~FLT_BIT(FLT_SLEW_LIMIT);
    } else {
        cause |= lr.cause_mask;
    }
    st->cause_mask = cause;
    latch_causes(&st->flt, cause, in->tick);

    const bool latched = flt_active(&st->flt); /* the stop command latches nothing */
    if (SAF_USUAL(latched, 0)) {
        stop_command(cfg, st, cmd);
    }
    for (uint32_t i = 0u; i < SAF_AXES; i++) {
        st->last_cmd_N[i] = cmd[i];
        out->force_cmd_N[i] = cmd[i];
    }
    out->actuator_enable = st->actuator_enabled;
    out->stopping = latched;
    out->fault_code = flt_active_code(&st->flt);
    out->cause_mask = cause;
    out->lim_flags = lr.flags;
}

flt_code_t saf_clear_request(const saf_config_t *cfg, saf_state_t *st, uint32_t now_ms)
{
    if (cfg == NULL || st == NULL) {
        return FLT_NONE;
    }
    wdg_kick(&st->wdg, now_ms);
    uint32_t present = st->cause_mask & ~FLT_BIT(FLT_HOST_SILENCE);
    if (wdg_expired(&cfg->wdg, &st->wdg, now_ms)) {
        present |= FLT_BIT(FLT_HOST_SILENCE);
    }
    const bool was_active = flt_active(&st->flt);
    const flt_code_t r = flt_clear_request(&st->flt, present);
    if (r == FLT_NONE && was_active) {
        /* The limiter keeps its slew reference (the last output), so leaving a half-done ramp
         * steps down at most slew_max per tick, never jumps. */
        for (uint32_t i = 0u; i < LIM_AXES; i++) {
            st->lim.out_N[i] = st->last_cmd_N[i];
            st->lim.slew_run[i] = 0u;
        }
        st->ramp.active = 0u;
        st->ramp.k = 0u;
        st->actuator_enabled = true;
        st->hold_zero = true;
        st->cause_mask = present;
    }
    return r;
}

/* Host-silence watchdog and safe-stop ramp: see wdg.h. */
#include "wdg.h"

#include <stddef.h>

#include "saf_tick.h"

void wdg_default_config(wdg_config_t *cfg)
{
    if (cfg == NULL) {
        return;
    }
    cfg->timeout_ms = (uint16_t)WDG_TIMEOUT_DEFAULT_MS;
    cfg->ramp_ms = (uint16_t)WDG_RAMP_DEFAULT_MS;
    cfg->tick_us = 1000u;
}

saf_status_t wdg_config_validate(const wdg_config_t *cfg)
{
    if (cfg == NULL) {
        return SAF_ERR_NULL_ARG;
    }
    if (cfg->timeout_ms < WDG_TIMEOUT_MIN_MS || cfg->timeout_ms > WDG_TIMEOUT_MAX_MS) {
        return SAF_ERR_TIMEOUT;
    }
    if (cfg->tick_us == 0u) {
        return SAF_ERR_NONPOSITIVE;
    }
    if (cfg->ramp_ms > WDG_RAMP_MAX_MS || (uint32_t)cfg->ramp_ms * 1000u < cfg->tick_us) {
        return SAF_ERR_RAMP;
    }
    return SAF_OK;
}

void wdg_init(wdg_state_t *st)
{
    if (st == NULL) {
        return;
    }
    st->last_host_ms = 0u;
    st->armed = 0u;
}

void wdg_kick(wdg_state_t *st, uint32_t now_ms)
{
    if (st == NULL) {
        return;
    }
    st->last_host_ms = now_ms;
    st->armed = 1u;
}

void wdg_disarm(wdg_state_t *st)
{
    if (st != NULL) {
        st->armed = 0u;
    }
}

bool wdg_expired(const wdg_config_t *cfg, const wdg_state_t *st, uint32_t now_ms)
{
    if (cfg == NULL || st == NULL) {
        return false;
    }
    return wdg_expired_tick(cfg, st, now_ms);
}

uint16_t wdg_ramp_ticks(const wdg_config_t *cfg)
{
    if (cfg == NULL || cfg->tick_us == 0u) {
        return 1u;
    }
    uint32_t n = ((uint32_t)cfg->ramp_ms * 1000u + cfg->tick_us - 1u) / cfg->tick_us;
    if (n == 0u) {
        n = 1u;
    }
    if (n > UINT16_MAX) {
        n = UINT16_MAX;
    }
    return (uint16_t)n;
}

void wdg_ramp_start(wdg_ramp_t *r, const wdg_config_t *cfg, const saf_force_t from_N[SAF_AXES])
{
    if (r == NULL) {
        return;
    }
    r->n_ticks = wdg_ramp_ticks(cfg);
    r->k = 0u;
    r->active = 1u;
    for (uint32_t i = 0u; i < SAF_AXES; i++) {
        const saf_force_t f = (from_N != NULL) ? from_N[i] : SAF_FORCE_C(0.0);
        r->from_N[i] = saf_finite(f) ? f : SAF_FORCE_C(0.0);
        r->out_N[i] = r->from_N[i];
    }
}

bool wdg_ramp_step(wdg_ramp_t *r, saf_force_t out_N[SAF_AXES])
{
    if (r == NULL || r->active == 0u || r->k >= r->n_ticks) {
        for (uint32_t i = 0u; i < SAF_AXES; i++) {
            if (r != NULL) {
                r->out_N[i] = SAF_FORCE_C(0.0);
            }
            if (out_N != NULL) {
                out_N[i] = SAF_FORCE_C(0.0);
            }
        }
        return true;
    }
    r->k++;
    const uint16_t left = (uint16_t)(r->n_ticks - r->k);
    for (uint32_t i = 0u; i < SAF_AXES; i++) {
        /* from * (n-k) / n: exactly linear, exactly 0 at k = n, and non-increasing in magnitude
         * because each rounded operation is monotone in k (integers: truncated toward 0). */
#ifdef SAF_FIXED
        const saf_force_t f = (saf_force_t)(((int64_t)r->from_N[i] * (int64_t)left) /
                                            (int64_t)r->n_ticks);
#else
        const saf_force_t f = (left == 0u) ? FS_R(0.0)
                                           : r->from_N[i] * (fs_real_t)left / (fs_real_t)r->n_ticks;
#endif
        r->out_N[i] = f;
        if (out_N != NULL) {
            out_N[i] = f;
        }
    }
    return left == 0u;
}

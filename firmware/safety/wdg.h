/* Host-silence watchdog and the safe-stop ramp (docs/safety.md).
 * Watchdog: armed by the first host frame; expires when no host frame was seen for timeout_ms
 * (default 100, configurable 20..500). With frames taken at the next 1 ms tick, the fault is
 * detected at most timeout + 1 tick after the last frame really arrived.
 * Ramp: from the force being commanded when the stop starts, linearly to exactly zero in
 * ramp_ms (default 40, at most 50); |force| is non-increasing every tick; then the actuator is
 * disabled. */
#ifndef WDG_H
#define WDG_H

#include <stdbool.h>
#include <stdint.h>
#include "flt_codes.h"
#include "fs_real.h"
#include "saf_real.h"

#define WDG_TIMEOUT_MIN_MS 20u
#define WDG_TIMEOUT_MAX_MS 500u
#define WDG_TIMEOUT_DEFAULT_MS 100u
#define WDG_RAMP_MAX_MS 50u
#define WDG_RAMP_DEFAULT_MS 40u

/** Watchdog and ramp configuration. */
typedef struct {
    uint16_t timeout_ms; /* host silence that latches FLT_HOST_SILENCE */
    uint16_t ramp_ms;    /* safe-stop ramp duration, 1..50 ms (>= one tick) */
    uint16_t tick_us;    /* control period (1000 at 1 kHz) */
} wdg_config_t;

/** Watchdog state. */
typedef struct {
    uint32_t last_host_ms; /* time of the last host frame */
    uint8_t armed;         /* a host frame has been seen since init/disarm */
} wdg_state_t;

/** Safe-stop ramp state. */
typedef struct {
    saf_force_t from_N[SAF_AXES];
    saf_force_t out_N[SAF_AXES];
    uint16_t n_ticks; /* ramp length in ticks */
    uint16_t k;       /* ticks done */
    uint8_t active;
} wdg_ramp_t;

/** Defaults: 100 ms, 40 ms ramp, 1000 us tick. */
void wdg_default_config(wdg_config_t *cfg);

/** Validate: timeout 20..500 ms, 1 tick <= ramp <= 50 ms, tick_us > 0. */
saf_status_t wdg_config_validate(const wdg_config_t *cfg);

/** Disarmed watchdog (no host seen yet). */
void wdg_init(wdg_state_t *st);

/** A host frame arrived (processed at now_ms): restart the silence timer and arm. */
void wdg_kick(wdg_state_t *st, uint32_t now_ms);

/** Disarm until the next host frame (e.g. after a deliberate disconnect in IDLE). */
void wdg_disarm(wdg_state_t *st);

/** True if armed and now_ms - last host frame >= timeout_ms (wrap-safe). */
bool wdg_expired(const wdg_config_t *cfg, const wdg_state_t *st, uint32_t now_ms);

/** Number of ticks of the ramp: ceil(ramp_ms*1000/tick_us), at least 1. */
uint16_t wdg_ramp_ticks(const wdg_config_t *cfg);

/** Start a ramp from from_N (non-finite values start from 0). */
void wdg_ramp_start(wdg_ramp_t *r, const wdg_config_t *cfg, const saf_force_t from_N[SAF_AXES]);

/** One tick of the ramp into out_N; returns true once the output is exactly zero (the actuator
 *  may then be disabled). Calling it on an inactive ramp outputs zero. */
bool wdg_ramp_step(wdg_ramp_t *r, saf_force_t out_N[SAF_AXES]);

#endif /* WDG_H */

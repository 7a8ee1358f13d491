/* Safety supervisor: the one call the application makes every control tick, after the control
 * law and before the actuator. It runs the sensor checks, the host-silence watchdog and the
 * limits, latches faults (flt_*), and while any fault is latched replaces the command by the
 * safe-stop ramp (wdg_ramp_*), then disables the actuator. It never resumes by itself: after
 * saf_clear_request succeeds the output is zero until the application sends new requests.
 *
 * Per tick (1 kHz):
 *   at start and whenever cfg changes: saf_prepare(&cfg, &st);
 *   saf_input_t in = {tick, now_ms, host_frame, age, causes, meas, force_req_N};
 *   saf_step(&cfg, &st, &in, &out);
 *   actuator_write(out.force_cmd_N, out.actuator_enable);   status frame: out.fault_code
 *   while (flt_emcy_peek(&st.flt, &e) && the emergency frame with e was sent)
 *       flt_emcy_pop(&st.flt, &e);      (unsent frames wait in the queue, e.g. bus-off)   */
#ifndef SAF_H
#define SAF_H

#include <stdbool.h>
#include <stdint.h>
#include "flt.h"
#include "lim.h"
#include "sen.h"
#include "wdg.h"

/** Complete safety configuration (limits, sensor plausibility, watchdog/ramp). */
typedef struct {
    lim_config_t lim;
    sen_config_t sen;
    wdg_config_t wdg;
} saf_config_t;

/** The causes an application reports in saf_input_t.causes. */
#define SAF_INPUT_CAUSES                                                             \
    (FLT_BIT(FLT_BUS_OFF) | FLT_BIT(FLT_TICK_OVERRUN) | FLT_BIT(FLT_SKILL_INVALID) | \
     FLT_BIT(FLT_STORAGE) | FLT_BIT(FLT_BAND))

/** Inputs of one tick. Event flags are levels for this tick ("present now"). */
typedef struct {
    uint32_t tick;              /* control tick counter */
    uint32_t now_ms;            /* time of this tick, ms */
    bool host_frame;            /* a host command/heartbeat was accepted since last tick */
    uint32_t host_frame_age_ms; /* ms since the newest of them arrived (0: this tick) */
    /* the causes the application sees this tick, FLT_BIT of each (SAF_INPUT_CAUSES, others
     * ignored): FLT_BUS_OFF the CAN controller is bus-off, FLT_TICK_OVERRUN the previous tick
     * overran its period, FLT_SKILL_INVALID the active skill is invalid, FLT_STORAGE a flash
     * operation failed, FLT_BAND outside the skill's band for the run's stop time */
    uint32_t causes;
    saf_meas_t meas[SAF_AXES];         /* raw measurements of this tick */
    saf_force_t force_req_N[SAF_AXES]; /* the control law's request (any value) */
} saf_input_t;

/** Outputs of one tick. */
typedef struct {
    saf_force_t force_cmd_N[SAF_AXES]; /* to the actuator: always finite, within the limits */
    bool actuator_enable;              /* false once the stop ramp has reached zero */
    bool stopping;                     /* a fault is latched (ramping or disabled) */
    uint16_t fault_code;               /* status frame: first latched fault, 0 if none */
    uint32_t cause_mask;               /* FLT_BIT of every cause present this tick */
    uint32_t lim_flags;                /* LIM_F_* of this tick */
} saf_output_t;

/** Supervisor state. */
typedef struct {
    flt_state_t flt;
    lim_state_t lim;
    sen_state_t sen;
    wdg_state_t wdg;
    wdg_ramp_t ramp;
    uint32_t cause_mask; /* causes seen at the last saf_step (for clearing) */
    saf_force_t last_cmd_N[SAF_AXES];
    bool actuator_enabled;
    bool hold_zero;     /* after a clear: output 0 until a zero request is seen */
    bool bounds_nested; /* saf_prepare: every limiter bound within the sensor checks' finite
                           ranges, so a reading inside the first passes the second */
} saf_state_t;

#define SAF_REARM_N 0.01 /* |request| at or below this re-arms the output after a clear */

/** Defaults of lim, sen and wdg. */
void saf_default_config(saf_config_t *cfg);

/** Validate everything, including that the slew limit lets the ramp reach zero from
 *  force_max_N within ramp_ms (slew_max_N * ramp ticks >= force_max_N). */
saf_status_t saf_config_validate(const saf_config_t *cfg);

/** Power-up state: no faults, actuator enabled with zero force, watchdog disarmed; no bounds
 *  prepared (every limit 0: zero force until saf_prepare). */
void saf_init(saf_state_t *st);

/** The limits' and sensor checks' bounds of cfg in the tick's units (lim_prepare,
 *  sen_prepare): call it after saf_init and whenever cfg changes. */
void saf_prepare(const saf_config_t *cfg, saf_state_t *st);

/** One control tick (see the file comment). cfg must have passed saf_config_validate. */
void saf_step(const saf_config_t *cfg, saf_state_t *st, const saf_input_t *in, saf_output_t *out);

/** Host asks to clear faults at now_ms (the request is itself a host frame: it kicks the
 *  watchdog). Refused, returning the lowest latched code whose cause is present (host silence
 *  re-evaluated now, the other causes as seen at the last saf_step), or clears all (FLT_NONE).
 *  After a clear the output stays zero until a tick whose request is zero on every axis
 *  (|req| <= SAF_REARM_N): a skill cannot resume by itself. */
flt_code_t saf_clear_request(const saf_config_t *cfg, saf_state_t *st, uint32_t now_ms);

#endif /* SAF_H */

/* The device state's one place of change (see app_internal.h): app_sm_next's table and the
 * entry actions of each state, and the clearing of latched faults. */
#include "app_internal.h"

bool app_event(app_t *app, app_event_t ev)
{
    const app_state_t next = app_sm_next(app->state, ev);
    if (next == app->state) {
        return false;
    }
    app->state = next;
    switch (next) {
    case APP_TEACH:
    case APP_EXECUTE:
        if (next == APP_TEACH) {
            app->ctl.teach_ticks = 0u;
        }
        /* the host must keep its heartbeat from now on: silence in TEACH/EXECUTE stops safely */
        wdg_kick(&app->saf.wdg, app->now_ms);
        for (unsigned a = 0; a < PFC_AXES; a++) {
            exec_render_reset(&app->ctl.rend[a], app->sens.pos_m[a]);
        }
        break;
    case APP_IDLE:
    case APP_FAULT:
        if (app_run_starting(app)) { /* stopped or faulted before its first step */
            fs_job_reset(&app->ctl.start);
            app->ctl.run_start_nrc = UDS_NRC_CONDITIONS_NOT_CORRECT;
        }
        if (next == APP_IDLE) {
            app->ctl.seq_step = 0u;
            app->ctl.exec_done = false;
        } else { /* the telemetry keeps its rate through the stop ramp and a little after */
            app->fault_fast_until_ms = app->now_ms + (uint32_t)app->saf_cfg.wdg.ramp_ms +
                                       APP_FAULT_TELEMETRY_TAIL_MS;
        }
        app->force_hat = 0;
        wdg_disarm(&app->saf.wdg); /* host silence matters only while the device acts */
        break;
    case APP_BOOT:
    default: break;
    }
    return true;
}

flt_code_t app_clear_faults(app_t *app)
{
    const flt_code_t r = saf_clear_request(&app->saf_cfg, &app->saf, app->now_ms);
    if (r == FLT_NONE) {
        /* the tick's safety output (its status frame, DIDs) says so at once: the clear comes
         * after the tick's safety step */
        app->saf_out.fault_code = 0u;
        app->saf_out.stopping = false;
        (void)app_event(app, APP_EV_CLEARED);
    } else {
        /* the request counts as a host frame (it arms the watchdog); in FAULT silence does not
         * matter, so disarm it again */
        wdg_disarm(&app->saf.wdg);
    }
    return r;
}

/* The end of every command sent before now: what waits for its MAC check is dropped and the next
 * command needs a heartbeat after this (a stop, a UDS fault clear or run stop, a new key). */
void app_commands_void(app_t *app)
{
    app->bus.host_seen = false;
    app->auth.macq.count = 0u; /* what waits for its check arrived before: it never acts */
    secoc_verify_abandon(&app->auth.mac_job);
}

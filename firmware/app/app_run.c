/* The one motion path of the device (see app_internal.h): every start, from a HostCommand frame
 * or a RUN_SKILL / RUN_SEQUENCE routine, is an app_run_request_t that goes through
 * app_run_authorize, then the same checks, then EXECUTE. */
#include "app_internal.h"

uint8_t app_run_authorize(const app_t *app, const app_run_request_t *req)
{
    /* A HostCommand reached here only after its MAC and freshness were verified on receipt
     * (host_frame_accepted, secoc.h). A routine start needs the unlocked host session: level 1,
     * the level that also keys the motion MAC. */
    if (req->source == APP_RUN_FROM_ROUTINE &&
        app->diag.uds.unlocked_level != UDS_SEC_LEVEL_WRITE) {
        return UDS_NRC_SECURITY_ACCESS_DENIED;
    }
    return UDS_NRC_OK;
}

/* One step's checks, before any motion: a valid slot, finite scales (time > 0), a stiffness the
 * device tracks, the skill's peak times the goal scale within the force limit, the y path within
 * the y workspace; the step filled in. A UDS NRC; the check's code in last_run_status. */
static uint8_t run_check_step(app_t *app, const app_run_step_t *rs, uint8_t end, exec_step_t *out)
{
    const uint8_t s = rs->slot;
    const skill_t *sk = slots_skill(&app->slots, s);
    if (sk == NULL) {
        return UDS_NRC_REQUEST_OUT_OF_RANGE;
    }
    if (!(rs->goal_scale >= FS_R(0.0)) || !(rs->time_scale > FS_R(0.0)) ||
        !fs_isfinite(rs->goal_scale) || !fs_isfinite(rs->time_scale)) {
        return UDS_NRC_REQUEST_OUT_OF_RANGE;
    }
    fs_status_t sc = skchk_stiffness(sk, app->cfg.stiffness_max_Npm);
    if (sc != FS_OK) {
        app->ctl.last_run_status = (uint16_t)sc;
        return UDS_NRC_REQUEST_OUT_OF_RANGE;
    }
    sc = (sk->dmp.periodic != 0u)
             ? skchk_run_scales_periodic(sk, app->slots.peak_N[s - 1u], rs->goal_scale,
                                         rs->amplitude_scale, rs->time_scale, APP_TICK_S,
                                         app->cfg.saf.lim.axis[0].force_max_N)
             : skchk_run_scales(sk, app->slots.peak_N[s - 1u], rs->goal_scale, rs->time_scale,
                                APP_TICK_S, app->cfg.saf.lim.axis[0].force_max_N);
    app->ctl.last_run_status = (uint16_t)sc;
    if (sc != FS_OK) {
        return UDS_NRC_REQUEST_OUT_OF_RANGE;
    }
    const lim_axis_t *ya = &app->cfg.saf.lim.axis[1];
    sc = skchk_run_path(sk, app->slots.path_m[s - 1u], rs->path_scale,
                        ya->pos_max_m - ya->pos_min_m);
    app->ctl.last_run_status = (uint16_t)sc;
    if (sc != FS_OK) {
        return UDS_NRC_REQUEST_OUT_OF_RANGE;
    }
    out->path_scale = rs->path_scale;
    out->skill = sk;
    out->model_fx = slots_model(&app->slots, s); /* the fixed-point one: converted at the commit */
    out->goal_scale = rs->goal_scale;
    out->time_scale = rs->time_scale;
    out->duration_s = rs->duration_s;
    out->amplitude_scale = rs->amplitude_scale;
    out->until_stopped = (sk->dmp.periodic != 0u && rs->duration_s <= FS_R(0.0) && rs->cycles == 0u)
                             ? 1u
                             : 0u;
    if (sk->dmp.periodic != 0u && rs->duration_s <= FS_R(0.0) && rs->cycles > 1u) {
        out->duration_s = (fs_real_t)rs->cycles * sk->dmp.duration_s * rs->time_scale;
    }
    out->end_policy = (end == 0u) ? sk->end_policy
                                  : (end == 1u ? SKILL_END_HOLD : SKILL_END_RELEASE);
    return UDS_NRC_OK;
}

/* A run's start: the configuration's checks and the executor's reset (exec_start_reset), the
 * steps' integer constants a part a call (exec_start_run: the fixed-point build's, none in the
 * float one), then the first step's start; run_start_nrc its answer (the code in
 * last_run_status: a configuration refused, a scale beyond the fixed-point formats). */
static fs_job_status_t start_job(app_t *app)
{
    fs_job_t *j = &app->ctl.start;
    FS_JOB_BEGIN(j);
    FS_JOB_YIELD(j); /* accepted in this tick: the slices from the next, before the bus's */
    const fs_status_t begun = exec_start_reset(&app->ctl.exec_run_cfg, &app->ctl.exec);
    if (begun != FS_OK) {
        app->ctl.last_run_status = (uint16_t)begun;
        app->ctl.run_start_nrc = UDS_NRC_REQUEST_OUT_OF_RANGE;
        FS_JOB_EXIT(j);
    }
    if (exec_prep_parts(app->ctl.exec.n_steps) != 0u) {
        FS_JOB_YIELD(j); /* the constants' parts (the fixed-point build) from the next tick */
    }
    for (;;) {
        bool done = false;
        const fs_status_t rc = exec_start_run(&app->ctl.exec_run_cfg, &app->ctl.exec, &done);
        if (rc != FS_OK) {
            app->ctl.last_run_status = (uint16_t)rc;
            app->ctl.run_start_nrc = UDS_NRC_REQUEST_OUT_OF_RANGE;
            FS_JOB_EXIT(j);
        }
        if (done) {
            break;
        }
        FS_JOB_YIELD(j);
    }
    app->ctl.run_start_nrc = UDS_NRC_OK;
    FS_JOB_END(j);
}

uint8_t app_run_start(app_t *app, const app_run_request_t *req)
{
    const uint8_t auth = app_run_authorize(app, req);
    if (auth != UDS_NRC_OK) {
        return auth;
    }
    if (req->n_steps == 0u || req->n_steps > EXEC_MAX_STEPS || req->end > 2u) {
        return UDS_NRC_REQUEST_OUT_OF_RANGE;
    }
    if (app->state != APP_IDLE || slots_committing(&app->slots)) {
        return UDS_NRC_CONDITIONS_NOT_CORRECT; /* a download's commit runs: its end decides */
    }
    exec_step_t steps[EXEC_MAX_STEPS];
    for (uint8_t i = 0; i < req->n_steps; i++) {
        const uint8_t nrc = run_check_step(app, &req->step[i], req->end, &steps[i]);
        if (nrc != UDS_NRC_OK) {
            return nrc;
        }
    }
    /* execution uses the gains the (first) skill was fitted with; the y axis keeps the device's */
    app->ctl.exec_run_cfg = app->cfg.exec;
    app->ctl.exec_run_cfg.pfc.gains[0] = steps[0].skill->gains;
    app->ctl.exec_run_cfg.pfc.gains[1] = app->cfg.gains[1];
    app->ctl.exec_run_cfg.pfc.gains[1].m_d_kg = steps[0].skill->gains.m_d_kg;
    for (unsigned a = 0; a < PFC_AXES; a++) {
        app->ctl.exec_run_cfg.pfc.limits[a].force_max_N = app->cfg.saf.lim.axis[a].force_max_N;
    }
    app->ctl.exec_run_cfg.pfc.dt_s = APP_TICK_S;
    /* the steps held; the configuration's checks and the state's reset are the start job's */
    const fs_status_t rc = exec_start_load(&app->ctl.exec, steps, req->n_steps, app->sens.pos_m[1]);
    if (rc != FS_OK) {
        app->ctl.last_run_status = (uint16_t)rc;
        return UDS_NRC_REQUEST_OUT_OF_RANGE;
    }
    app->ctl.active_slot = req->step[0].slot;
    app->ctl.band_stop_ms = req->band_stop_ms;
    app->ctl.seq_step = 0u;
    app->ctl.exec_done = false;
    /* the steps' constants and the first step's start follow a slice a tick (app_run_start_step) */
    app->ctl.run_start_nrc = UDS_NRC_RESPONSE_PENDING;
    fs_job_reset(&app->ctl.start);
    (void)start_job(app);
    (void)app_event(app, APP_EV_EXECUTE);
    return UDS_NRC_OK;
}

void app_run_start_step(app_t *app)
{
    if (start_job(app) == FS_JOB_DONE && app->ctl.run_start_nrc != UDS_NRC_OK) {
        (void)app_event(app, APP_EV_STOP); /* a scale beyond the fixed-point formats: no run */
    }
}

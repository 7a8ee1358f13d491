/* UDS device hooks of the application (see uds.h for the server, docs/protocol.md for the
 * identifiers): data identifiers, routines, SecurityAccess via sec_access, skill download into a
 * slot and upload through the skill store (slots.h: the old skill kept on any failure), the
 * firmware download through fwu_uds. */
#include <string.h>

#include "app_internal.h"
#include "fwu_uds.h"

/* A hook's answer nrc; answered 0x78, the long work it began goes on through next (resume). */
static uint8_t pend(app_t *app, uint8_t nrc, uint8_t (*next)(app_t *app))
{
    app->diag.pending = (nrc == UDS_NRC_RESPONSE_PENDING) ? next : NULL;
    return nrc;
}

/* The motion key's derivation, a slice a call. */
static uint8_t motion_key_slice(app_t *app)
{
    return app_motion_key_run(app, APP_SEC_ROUNDS_PER_TICK);
}

/* A run's start: its slices run in the control tick (app_run.c); the answer once they are done. */
static uint8_t run_start_answer(app_t *app)
{
    return app->ctl.run_start_nrc;
}

/* Data identifiers (DID_*, fs_uds_ids.h) and routine records: the generated codecs of
 * wire.toml (fs_wire.h). Each DID function packs into buf (cap bytes) and returns the length,
 * 0 for another DID. */

/* The identity DIDs (software version, format versions). */
static uint16_t did_identity(uint16_t did, uint8_t *buf, uint16_t cap)
{
    switch (did) {
    case DID_SW_VERSION: {
        const uint16_t n = (uint16_t)strlen(APP_SW_VERSION);
        memcpy(buf, APP_SW_VERSION, n);
        return n;
    }
    case DID_VERSIONS: {
        const fs_wire_versions_t v = {APP_PROTO_VERSION_MAJOR, APP_PROTO_VERSION_MINOR,
                                      SKILL_FORMAT_VERSION, DMP_MAX_KERNELS, APP_N_SLOTS};
        return fs_wire_versions_pack(&v, buf, cap);
    }
    default: return 0u;
    }
}

/* The configuration DIDs (gains, limits, communication, object). */
static uint16_t did_config(const app_t *app, uint16_t did, uint8_t *buf, uint16_t cap)
{
    switch (did) {
    case DID_GAINS_X:
    case DID_GAINS_Y: {
        const pfc_axis_gains_t *g = &app->cfg.gains[did - DID_GAINS_X];
        const fs_wire_gains_t v = {(float)g->m_d_kg, (float)g->k_d_Nspm, (float)g->k_p_Npm,
                                   (float)g->k_f, (float)g->k_i_per_s};
        return fs_wire_gains_pack(&v, buf, cap);
    }
    case DID_LIMITS_X:
    case DID_LIMITS_Y: {
        const lim_axis_t *l = &app->saf_cfg.lim.axis[did - DID_LIMITS_X];
        const fs_wire_limits_t v = {(float)l->force_max_N, (float)l->slew_max_N,
                                    (float)l->pos_min_m,   (float)l->pos_max_m,
                                    (float)l->vel_max_mps, (float)l->contact_force_max_N};
        return fs_wire_limits_pack(&v, buf, cap);
    }
    case DID_COMM: {
        const fs_wire_comm_t v = {app->cfg.telemetry_period_ms, app->saf_cfg.wdg.timeout_ms};
        return fs_wire_comm_pack(&v, buf, cap);
    }
    case DID_OBJECT: {
        const exec_object_t *o = &app->cfg.exec.object;
        const fs_wire_object_t v = {
            app->cfg.exec.use_model, (float)o->m_v_kg,        (float)o->d_v_Nspm, (float)o->k1_Npm,
            (float)o->k2_Npm,        (float)o->layer_depth_m, (float)o->surface_m};
        return fs_wire_object_pack(&v, buf, cap);
    }
    default: return 0u;
    }
}

/* The slot directory: the count, then per slot valid, length, CRC, kernels, T, end policy. */
static uint16_t did_slot_dir(const app_t *app, uint8_t *buf, uint16_t cap)
{
    fs_wire_slot_dir_t v;
    memset(&v, 0, sizeof(v));
    v.count = APP_N_SLOTS;
    v.n_entries = APP_N_SLOTS;
    for (uint16_t s = 0; s < APP_N_SLOTS; s++) {
        fs_wire_slot_entry_t *e = &v.entries[s];
        const skill_t *sk = slots_skill(&app->slots, s + 1u);
        if (sk != NULL) {
            e->valid = 1u;
            e->length = app->slots.len[s];
            e->crc32 = app->slots.crc[s]; /* the image's own CRC-32 field */
            e->n_kernels = sk->dmp.n_kernels;
            e->duration_s = (float)sk->dmp.duration_s;
            e->end = (uint8_t)sk->end_policy;
        }
    }
    return fs_wire_slot_dir_pack(&v, buf, cap);
}

/* The status DIDs (slots, last transfer, device state, fault causes). */
static uint16_t did_status(const app_t *app, uint16_t did, uint8_t *buf, uint16_t cap)
{
    switch (did) {
    case DID_SLOT_DIR: return did_slot_dir(app, buf, cap);
    case DID_LAST_TRANSFER: {
        const fs_wire_last_transfer_t v = {app->slots.last_transfer_status};
        return fs_wire_last_transfer_pack(&v, buf, cap);
    }
    case DID_DEVICE_STATE: {
        const fs_wire_device_state_t v = {(uint8_t)app->state, app->saf_out.fault_code,
                                          app->ctl.active_slot, app->ctl.seq_step, app->tick};
        return fs_wire_device_state_pack(&v, buf, cap);
    }
    case DID_CONTACT_WAIT: {
        const fs_wire_contact_wait_t v = {
            exec_contact_hold_ms(&app->ctl.exec), app->ctl.exec.contact_losses,
            FS_WIRE_CONTACT_WAIT_RATE_COUNT(fs_real_t, exec_contact_rate(&app->ctl.exec))};
        return fs_wire_contact_wait_pack(&v, buf, cap);
    }
    case DID_BAND: {
        const exec_state_t *e = &app->ctl.exec;
        const fs_wire_band_t v = {e->band_checked_ticks,  e->band_out_ticks,  e->band_longest_ticks,
                                  exec_band_max_milli(e), e->band_first_tick, e->band_outside,
                                  app->ctl.band_stop_ms};
        return fs_wire_band_pack(&v, buf, cap);
    }
    case DID_STIFFNESS_MAX: {
        const fs_wire_stiffness_max_t v = {(float)app->cfg.stiffness_max_Npm};
        return fs_wire_stiffness_max_pack(&v, buf, cap);
    }
    case DID_FAULT_CAUSES: { /* what blocks a clear: the causes still present at the last tick */
        const fs_wire_fault_causes_t v = {app->saf.flt.latched_mask, app->saf.cause_mask};
        return fs_wire_fault_causes_pack(&v, buf, cap);
    }
    case DID_MOTION_KEY: {
        fs_wire_motion_key_t v = {{0u},
                                  app->auth.secoc.keyed ? 1u : 0u,
                                  app->auth.secoc.keyed ? app->sec.motion.confirm : 0u};
        memcpy(v.nonce, app->sec.motion.dev_nonce, sizeof(v.nonce));
        return fs_wire_motion_key_pack(&v, buf, cap);
    }
    case DID_AUTH_STATS: {
        const secoc_t *a = &app->auth.secoc;
        const fs_wire_auth_stats_t v = {a->accepted,
                                        a->bad_mac,
                                        a->replayed,
                                        a->no_key,
                                        a->revoked,
                                        a->last_refusal,
                                        a->keyed ? 1u : 0u,
                                        a->fv[SECOC_CH_COMMAND],
                                        a->fv[SECOC_CH_HEARTBEAT],
                                        app->diag.uds_foreign};
        return fs_wire_auth_stats_pack(&v, buf, cap);
    }
    default: return 0u;
    }
}

/* The NRC of a refused unpack: the length (0x13) or a field's range (0x31). */
static uint8_t wire_nrc(proto_status_t st)
{
    return st == PROTO_ERR_WIRE_LENGTH ? UDS_NRC_INCORRECT_LENGTH : UDS_NRC_REQUEST_OUT_OF_RANGE;
}

static uint8_t read_did(void *ctx, uint16_t did, uint8_t *out, uint16_t cap, uint16_t *len)
{
    app_t *app = ctx;
    uint8_t buf[FS_WIRE_SLOT_DIR_LEN_MAX]; /* the longest DID */
    if (did == FWU_DID_STATUS) {
        return fwu_uds_read_did(&app->fw.fwu, out, cap, len);
    }
    const uint16_t bc = (uint16_t)sizeof(buf);
    uint16_t n = did_identity(did, buf, bc);
    n = n != 0u ? n : did_config(app, did, buf, bc);
    n = n != 0u ? n : did_status(app, did, buf, bc);
    if (n == 0u) {
        return UDS_NRC_REQUEST_OUT_OF_RANGE;
    }
    if (n > cap) {
        return UDS_NRC_RESPONSE_TOO_LONG;
    }
    memcpy(out, buf, n);
    *len = n;
    return UDS_NRC_OK;
}

/* DID_GAINS_X/Y: m_d, k_d, k_p, k_f, k_i (float32), accepted when the gains validate. */
static uint8_t write_gains(app_t *app, uint16_t did, const uint8_t *d, uint16_t len)
{
    fs_wire_gains_t v;
    const proto_status_t st = fs_wire_gains_unpack(&v, d, len);
    if (st != PROTO_OK) {
        return wire_nrc(st);
    }
    pfc_config_t pc;
    pfc_default_config(&pc);
    pc.gains[0] = app->cfg.gains[0];
    pc.gains[1] = app->cfg.gains[1];
    pfc_axis_gains_t *g = &pc.gains[did - DID_GAINS_X];
    g->m_d_kg = (fs_real_t)v.m_d_kg;
    g->k_d_Nspm = (fs_real_t)v.k_d_Nspm;
    g->k_p_Npm = (fs_real_t)v.k_p_Npm;
    g->k_f = (fs_real_t)v.k_f;
    g->k_i_per_s = (fs_real_t)v.k_i_per_s;
    if (pfc_config_validate(&pc) != FS_OK) {
        return UDS_NRC_REQUEST_OUT_OF_RANGE;
    }
    app->cfg.gains[did - DID_GAINS_X] = *g;
    return UDS_NRC_OK;
}

/* A changed safety configuration takes effect when it validates; refused, nothing changes. */
static uint8_t apply_saf(app_t *app, const saf_config_t *sc)
{
    if (saf_config_validate(sc) != SAF_OK) {
        return UDS_NRC_REQUEST_OUT_OF_RANGE;
    }
    app->saf_cfg = *sc;
    app->cfg.saf = *sc;
    saf_prepare(&app->saf_cfg, &app->saf); /* the tick's bounds follow from this tick on */
    return UDS_NRC_OK;
}

/* DID_LIMITS_X/Y: six float32 limits, accepted when the safety configuration validates. */
static uint8_t write_limits(app_t *app, uint16_t did, const uint8_t *d, uint16_t len)
{
    fs_wire_limits_t v;
    const proto_status_t st = fs_wire_limits_unpack(&v, d, len); /* finite */
    if (st != PROTO_OK) {
        return wire_nrc(st);
    }
    saf_config_t sc = app->saf_cfg;
    lim_axis_t *l = &sc.lim.axis[did - DID_LIMITS_X];
    l->force_max_N = (fs_real_t)v.force_max_N;
    l->slew_max_N = (fs_real_t)v.slew_max_N;
    l->pos_min_m = (fs_real_t)v.pos_min_m;
    l->pos_max_m = (fs_real_t)v.pos_max_m;
    l->vel_max_mps = (fs_real_t)v.vel_max_mps;
    l->contact_force_max_N = (fs_real_t)v.contact_force_max_N;
    return apply_saf(app, &sc);
}

/* DID_COMM: telemetry period (ms, > 0) and host timeout (ms, the watchdog's range). */
static uint8_t write_comm(app_t *app, const uint8_t *d, uint16_t len)
{
    fs_wire_comm_t v;
    const proto_status_t st = fs_wire_comm_unpack(&v, d, len);
    if (st != PROTO_OK) {
        return wire_nrc(st);
    }
    saf_config_t sc = app->saf_cfg;
    sc.wdg.timeout_ms = v.host_timeout_ms;
    const uint8_t nrc = apply_saf(app, &sc);
    if (nrc == UDS_NRC_OK) {
        app->cfg.telemetry_period_ms = v.telemetry_period_ms;
    }
    return nrc;
}

/* DID_STIFFNESS_MAX: the highest nominal skill stiffness accepted, finite in
 * (0, FS_STIFFNESS_CEILING_NPM] N/m (the record's range). */
static uint8_t write_stiffness_max(app_t *app, const uint8_t *d, uint16_t len)
{
    fs_wire_stiffness_max_t v;
    const proto_status_t st = fs_wire_stiffness_max_unpack(&v, d, len);
    if (st != PROTO_OK) {
        return wire_nrc(st);
    }
    app->cfg.stiffness_max_Npm = (fs_real_t)v.stiffness_max_Npm;
    return UDS_NRC_OK;
}

/* DID_OBJECT: use the model (0/1), then m_v, d_v, k1, k2, layer depth, surface (float32; the
 * record's ranges). */
static uint8_t write_object(app_t *app, const uint8_t *d, uint16_t len)
{
    fs_wire_object_t v;
    const proto_status_t st = fs_wire_object_unpack(&v, d, len);
    if (st != PROTO_OK) {
        return wire_nrc(st);
    }
    exec_object_t *o = &app->cfg.exec.object;
    app->cfg.exec.use_model = v.use_model;
    o->m_v_kg = (fs_real_t)v.m_v_kg;
    o->d_v_Nspm = (fs_real_t)v.d_v_Nspm;
    o->k1_Npm = (fs_real_t)v.k1_Npm;
    o->k2_Npm = (fs_real_t)v.k2_Npm;
    o->layer_depth_m = (fs_real_t)v.layer_depth_m;
    o->surface_m = (fs_real_t)v.surface_m;
    return UDS_NRC_OK;
}

static uint8_t write_did(void *ctx, uint16_t did, const uint8_t *d, uint16_t len)
{
    app_t *app = ctx;
    if (app->diag.uds.unlocked_level != UDS_SEC_LEVEL_WRITE) {
        return UDS_NRC_SECURITY_ACCESS_DENIED; /* settings: level 1 (not the firmware level) */
    }
    if (did == DID_MOTION_KEY) {
        /* also in FAULT: a host resynchronises to clear it; answered 0x78, derived in slices */
        fs_wire_motion_key_write_t w;
        if (fs_wire_motion_key_write_unpack(&w, d, len) != PROTO_OK) {
            return UDS_NRC_INCORRECT_LENGTH;
        }
        return pend(app, app_motion_key_begin(app, d, len), motion_key_slice);
    }
    if (app->state != APP_IDLE) {
        return UDS_NRC_CONDITIONS_NOT_CORRECT; /* configuration changes only while idle */
    }
    switch (did) {
    case DID_GAINS_X:
    case DID_GAINS_Y: return write_gains(app, did, d, len);
    case DID_LIMITS_X:
    case DID_LIMITS_Y: return write_limits(app, did, d, len);
    case DID_COMM: return write_comm(app, d, len);
    case DID_OBJECT: return write_object(app, d, len);
    case DID_STIFFNESS_MAX: return write_stiffness_max(app, d, len);
    default: return UDS_NRC_REQUEST_OUT_OF_RANGE; /* read-only or unknown */
    }
}

/* ---------------------------------------------------------------- routines */

/* A RUN_SKILL start (slot, goal and time scale, end policy [, path scale]) or a RUN_SEQUENCE start
 * (end policy, then per step: slot, goal and time scale, duration) as a run request; a UDS NRC
 * (0x13 length, 0x31 a field's range). */
/* One discrete step of a RUN_SKILL start: its slot and scales (counts of FS_WIRE_SCALE), the
 * skill's own duration, one cycle, amplitude scale 1. */
static void run_single_step(app_run_step_t *s, uint8_t slot, uint16_t goal, uint16_t time,
                            uint16_t path)
{
    s->slot = slot;
    s->goal_scale = FS_WIRE_REAL(fs_real_t, goal);
    s->time_scale = FS_WIRE_REAL(fs_real_t, time);
    s->duration_s = FS_R(0.0);
    s->path_scale = FS_WIRE_REAL(fs_real_t, path);
    s->cycles = 1u;
    s->amplitude_scale = FS_R(1.0);
}

static uint8_t run_from_routine(uint16_t rid, const uint8_t *d, uint16_t len,
                                app_run_request_t *req)
{
    memset(req, 0, sizeof(*req));
    req->source = APP_RUN_FROM_ROUTINE;
    if (rid == UDS_RID_RUN_SKILL && len >= FS_WIRE_RUN_PERIODIC_LEN_MIN) {
        fs_wire_run_periodic_t r;
        const proto_status_t st = fs_wire_run_periodic_unpack(&r, d, len);
        if (st != PROTO_OK) {
            return wire_nrc(st);
        }
        req->n_steps = 1u;
        req->end = r.end;
        req->step[0].slot = r.slot;
        req->step[0].goal_scale = FS_WIRE_REAL(fs_real_t, r.goal_scale);
        req->step[0].time_scale = FS_WIRE_REAL(fs_real_t, r.time_scale);
        req->step[0].path_scale = FS_WIRE_REAL(fs_real_t, r.path_scale);
        req->step[0].cycles = r.cycles;
        req->step[0].amplitude_scale = FS_WIRE_REAL(fs_real_t, r.amplitude_scale);
        req->band_stop_ms = r.band_stop_ms;
        return UDS_NRC_OK;
    }
    if (rid == UDS_RID_RUN_SKILL && len == FS_WIRE_RUN_SKILL_BAND_LEN) {
        fs_wire_run_skill_band_t r;
        const proto_status_t st = fs_wire_run_skill_band_unpack(&r, d, len);
        if (st != PROTO_OK) {
            return wire_nrc(st);
        }
        req->n_steps = 1u;
        req->end = r.end;
        req->band_stop_ms = r.band_stop_ms;
        run_single_step(&req->step[0], r.slot, r.goal_scale, r.time_scale, r.path_scale);
        return UDS_NRC_OK;
    }
    if (rid == UDS_RID_RUN_SKILL) {
        fs_wire_run_skill_t r;
        const proto_status_t st = fs_wire_run_skill_unpack(&r, d, len);
        if (st != PROTO_OK) {
            return wire_nrc(st);
        }
        req->n_steps = 1u;
        req->end = r.end;
        run_single_step(&req->step[0], r.slot, r.goal_scale, r.time_scale,
                        r.path_scale); /* absent: 1 */
        return UDS_NRC_OK;
    }
    fs_wire_run_sequence_t r;
    const proto_status_t st = fs_wire_run_sequence_unpack(&r, d, len);
    if (st != PROTO_OK) {
        return wire_nrc(st);
    }
    req->n_steps = r.n_steps;
    req->end = r.end;
    for (uint8_t i = 0; i < r.n_steps; i++) {
        app_run_step_t *s = &req->step[i];
        s->slot = r.steps[i].slot;
        s->goal_scale = FS_WIRE_REAL(fs_real_t, r.steps[i].goal_scale);
        s->time_scale = FS_WIRE_REAL(fs_real_t, r.steps[i].time_scale);
        s->duration_s = FS_WIRE_REAL(fs_real_t, r.steps[i].duration_s);
        s->path_scale = FS_R(1.0);
        s->amplitude_scale = FS_R(1.0);
        s->cycles = 1u; /* a periodic step: duration 0 is one cycle */
    }
    return UDS_NRC_OK;
}

/* RUN_SKILL / RUN_SEQUENCE: start, stop, or the results (state, step, done, fault code). */
static uint8_t routine_run(app_t *app, uint8_t sub, uint16_t rid, const uint8_t *d, uint16_t len,
                           uint8_t *out, uint16_t cap, uint16_t *out_len)
{
    if (sub == UDS_ROUTINE_START) {
        app_run_request_t req;
        const uint8_t nrc = run_from_routine(rid, d, len, &req);
        const uint8_t started = (nrc != UDS_NRC_OK) ? nrc : app_run_start(app, &req);
        /* answered once the start's slices are done (resume): its 3xx refusal comes then */
        return (started == UDS_NRC_OK && app_run_starting(app))
                   ? pend(app, UDS_NRC_RESPONSE_PENDING, run_start_answer)
                   : started;
    }
    if (sub == UDS_ROUTINE_STOP) {
        if (app->state != APP_EXECUTE) {
            return UDS_NRC_REQUEST_SEQUENCE_ERROR;
        }
        (void)app_event(app, APP_EV_STOP);
        app_commands_void(app); /* a command withheld before the stop never acts after it */
        return UDS_NRC_OK;
    }
    const fs_wire_run_results_t v = {(uint8_t)app->state, app->ctl.seq_step,
                                     app->ctl.exec_done ? 1u : 0u, app->saf_out.fault_code};
    *out_len = fs_wire_run_results_pack(&v, out, cap);
    return *out_len != 0u ? UDS_NRC_OK : UDS_NRC_RESPONSE_TOO_LONG;
}

/* SELF_TEST: the configurations, the skill storage and the sensors; out = pass/fail, code. */
static uint8_t routine_self_test(const app_t *app, uint8_t sub, uint8_t *out, uint16_t cap,
                                 uint16_t *out_len)
{
    if (sub == UDS_ROUTINE_STOP) {
        return UDS_NRC_SUBFUNCTION_NOT_SUPPORTED;
    }
    uint16_t code = 0u;
    pfc_config_t pc;
    pfc_default_config(&pc);
    pc.gains[0] = app->cfg.gains[0];
    pc.gains[1] = app->cfg.gains[1];
    if (saf_config_validate(&app->saf_cfg) != SAF_OK) {
        code = 1u;
    } else if (pfc_config_validate(&pc) != FS_OK) {
        code = (uint16_t)pfc_config_validate(&pc);
    } else if (!app->slots.nvm_ok) {
        code = NVM_ERR_GEOMETRY;
    } else if (!fs_isfinite(app->sens.pos_m[0]) || !fs_isfinite(app->sens.pos_m[1]) ||
               !fs_isfinite(app->sens.force_contact_N[0])) {
        code = FLT_SENSOR_NAN;
    }
    const fs_wire_self_test_t v = {(uint8_t)(code == 0u ? 0u : 1u), code};
    *out_len = fs_wire_self_test_pack(&v, out, cap);
    return *out_len != 0u ? UDS_NRC_OK : UDS_NRC_RESPONSE_TOO_LONG;
}

/* CLEAR_FAULTS: accepted in FAULT once no cause persists. */
static uint8_t routine_clear_faults(app_t *app, uint8_t sub)
{
    if (sub != UDS_ROUTINE_START) {
        return UDS_NRC_SUBFUNCTION_NOT_SUPPORTED;
    }
    if (app->state != APP_FAULT) {
        return UDS_NRC_REQUEST_SEQUENCE_ERROR;
    }
    app_commands_void(app); /* a command withheld before the fault never acts after the clear */
    if (app_clear_faults(app) != FLT_NONE) {
        return UDS_NRC_CONDITIONS_NOT_CORRECT; /* a cause persists */
    }
    return UDS_NRC_OK;
}

/* ERASE_SLOT (slot 1..APP_N_SLOTS): write level unlocked, only while idle. */
static uint8_t routine_erase_slot(app_t *app, uint8_t sub, const uint8_t *d, uint16_t len)
{
    if (sub != UDS_ROUTINE_START) {
        return UDS_NRC_SUBFUNCTION_NOT_SUPPORTED;
    }
    fs_wire_erase_slot_t v;
    const proto_status_t st = fs_wire_erase_slot_unpack(&v, d, len); /* slot 1..FS_SLOT_COUNT */
    if (st != PROTO_OK) {
        return wire_nrc(st);
    }
    if (app->diag.uds.unlocked_level != UDS_SEC_LEVEL_WRITE) {
        return UDS_NRC_SECURITY_ACCESS_DENIED;
    }
    if (app->state != APP_IDLE) {
        return UDS_NRC_CONDITIONS_NOT_CORRECT; /* slots change only while idle */
    }
    return slots_erase(&app->slots, v.slot);
}

static uint8_t routine(void *ctx, uint8_t sub, uint16_t rid, const uint8_t *d, uint16_t len,
                       uint8_t *out, uint16_t cap, uint16_t *out_len)
{
    app_t *app = ctx;
    if (fwu_uds_owns_rid(rid)) {
        if (rid == FWU_RID_CONFIRM && fwu_uds_authorised(&app->diag.uds) && !app->fw.self_test_ok) {
            *out_len = 0u;
            return UDS_NRC_CONDITIONS_NOT_CORRECT; /* only an image that passed its self-test */
        }
        return fwu_uds_routine(&app->fw.fwu, &app->diag.uds, sub, rid, d, len, out, cap, out_len);
    }
    *out_len = 0u;
    if (cap < 8u) {
        return UDS_NRC_RESPONSE_TOO_LONG;
    }
    switch (rid) {
    case UDS_RID_RUN_SKILL:
    case UDS_RID_RUN_SEQUENCE: return routine_run(app, sub, rid, d, len, out, cap, out_len);
    case UDS_RID_SELF_TEST: return routine_self_test(app, sub, out, cap, out_len);
    case UDS_RID_CLEAR_FAULTS: return routine_clear_faults(app, sub);
    case UDS_RID_ERASE_SLOT: return routine_erase_slot(app, sub, d, len);
    default: return UDS_NRC_REQUEST_OUT_OF_RANGE;
    }
}

/* ---------------------------------------------------------------- session, reset, security */

static uint8_t session_allowed(void *ctx, uint8_t session)
{
    app_t *app = ctx;
    if (session == UDS_SESSION_PROGRAMMING && app->state != APP_IDLE) {
        return UDS_NRC_CONDITIONS_NOT_CORRECT;
    }
    return UDS_NRC_OK;
}

static uint8_t ecu_reset(void *ctx, uint8_t type)
{
    app_t *app = ctx;
    (void)type;
    return (app->state == APP_TEACH || app->state == APP_EXECUTE) ? UDS_NRC_CONDITIONS_NOT_CORRECT
                                                                  : UDS_NRC_OK;
}

static void reset_now(void *ctx, uint8_t type)
{
    (void)ctx;
    hal_request_reset(type);
}

static uint8_t security_seed(void *ctx, uint8_t level, uint8_t *seed, uint16_t cap, uint16_t *len)
{
    app_t *app = ctx;
    const sec_config_t *cfg = app_sec_config(app, level);
    if (cfg == NULL) {
        return UDS_NRC_SUBFUNCTION_NOT_SUPPORTED;
    }
    if (cap < SEC_SEED_LEN) {
        return UDS_NRC_RESPONSE_TOO_LONG;
    }
    /* the state is shared by the levels: a seed of another level is never "already unlocked"
     * (a locked state is left as it is: other testers' seeds stay theirs) */
    if (app->diag.uds.unlocked_level != level && sec_is_unlocked(&app->sec.access)) {
        sec_lock(&app->sec.access);
    }
    const sec_nrc_t nrc = sec_request_seed(cfg, &app->sec.access, app->diag.uds.tester, app->now_ms,
                                           seed);
    app_sec_persist(app); /* a lockout that ended clears the stored counter */
    if (nrc != SEC_NRC_NONE) {
        return (uint8_t)nrc;
    }
    *len = SEC_SEED_LEN;
    return UDS_NRC_OK;
}

static uint8_t security_key(void *ctx, uint8_t level, const uint8_t *key, uint16_t len)
{
    app_t *app = ctx; /* answered 0x78, checked in slices */
    return pend(app, app_sec_key_check_begin(app, level, key, len), app_sec_key_check_run);
}

/* The long work a request answered 0x78 began, a slice a call: the continuation its hook left
 * (pend); the server knows the request, the application which work it began. */
static uint8_t resume(void *ctx, uint8_t sid, uint16_t arg)
{
    (void)sid;
    (void)arg;
    app_t *app = ctx;
    return app->diag.pending != NULL ? app->diag.pending(app) : UDS_NRC_CONDITIONS_NOT_CORRECT;
}

/* ---------------------------------------------------------------- transfers */

static uint8_t download_begin(void *ctx, uint32_t addr, uint32_t size)
{
    app_t *app = ctx;
    app->fw.xfer = addr == FWU_DOWNLOAD_ADDRESS;
    if (app->fw.xfer) {
        if (!fwu_uds_authorised(&app->diag.uds)) {
            return UDS_NRC_SECURITY_ACCESS_DENIED; /* firmware: level 3 only */
        }
        return app->state == APP_IDLE ? fwu_uds_download_begin(&app->fw.fwu, &app->diag.uds, size)
                                      : UDS_NRC_CONDITIONS_NOT_CORRECT;
    }
    if (addr < 1u || addr > APP_N_SLOTS || size < SKILL_HEADER_SIZE_V2 + SKILL_CRC_SIZE ||
        size > APP_IMAGE_MAX) {
        return UDS_NRC_REQUEST_OUT_OF_RANGE;
    }
    if (app->diag.uds.unlocked_level != UDS_SEC_LEVEL_WRITE) {
        return UDS_NRC_SECURITY_ACCESS_DENIED;
    }
    if (app->state != APP_IDLE) {
        return UDS_NRC_CONDITIONS_NOT_CORRECT; /* slots change only while idle */
    }
    return slots_download_begin(&app->slots, addr, size);
}

static uint8_t download_data(void *ctx, uint32_t offset, const uint8_t *d, uint16_t len)
{
    app_t *app = ctx;
    if (app->fw.xfer) {
        return fwu_uds_download_data(&app->fw.fwu, &app->diag.uds, offset, d, len);
    }
    return slots_download_data(&app->slots, offset, d, len);
}

static uint8_t download_end(void *ctx, uint32_t *crc_out)
{
    app_t *app = ctx;
    if (app->fw.xfer) {
        return fwu_uds_download_end(&app->fw.fwu, &app->diag.uds, crc_out);
    }
    if (app->state != APP_IDLE || app->diag.uds.unlocked_level != UDS_SEC_LEVEL_WRITE) {
        /* a skill started (or security dropped) since RequestDownload: commit refused, the slot
         * keeps what it holds; nothing changes while a skill runs */
        slots_refuse_commit(&app->slots);
        return app->state != APP_IDLE ? UDS_NRC_CONDITIONS_NOT_CORRECT
                                      : UDS_NRC_SECURITY_ACCESS_DENIED;
    }
    const lim_axis_t *ya = &app->cfg.saf.lim.axis[1];
    const slots_limits_t lim = {APP_TICK_S, app->cfg.stiffness_max_Npm,
                                app->cfg.saf.lim.axis[0].force_max_N,
                                ya->pos_max_m - ya->pos_min_m};
    return slots_commit_step(&app->slots, &lim, crc_out);
}

static void transfer_abort(void *ctx)
{
    app_t *app = ctx;
    if (app->fw.xfer) {
        fwu_abort(&app->fw.fwu);
    }
    slots_abort(&app->slots);
}

static uint8_t upload_begin(void *ctx, uint32_t addr, uint32_t size)
{
    app_t *app = ctx;
    return slots_upload_begin(&app->slots, addr, size);
}

static uint8_t upload_data(void *ctx, uint32_t offset, uint8_t *out, uint16_t len)
{
    const app_t *app = ctx;
    return slots_upload_data(&app->slots, offset, out, len);
}

void app_uds_bind(app_t *app, uds_app_t *out)
{
    memset(out, 0, sizeof(*out));
    out->ctx = app;
    out->read_did = read_did;
    out->write_did = write_did;
    out->routine = routine;
    out->session_allowed = session_allowed;
    out->ecu_reset = ecu_reset;
    out->reset_now = reset_now;
    out->security_seed = security_seed;
    out->security_key = security_key;
    out->resume = resume;
    out->download_begin = download_begin;
    out->download_data = download_data;
    out->download_end = download_end;
    out->transfer_abort = transfer_abort;
    out->upload_begin = upload_begin;
    out->upload_data = upload_data;
}

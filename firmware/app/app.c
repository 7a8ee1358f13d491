/* Device application: state machine, 1 kHz tick, cyclic frames (see app.h). */
#include "app_internal.h"

#include <string.h>

#include "fs_dbc.h"
#include "proto_ids.h"

#ifndef APP_FW_TARGET_ID
/* the firmware images this device accepts (BOOT_TARGET_*): a port's build defines its own */
#define APP_FW_TARGET_ID FS_TARGET_HOST
#endif

_Static_assert(SAF_AXES == PFC_AXES && SAF_AXES == HAL_AXES,
               "safety, control law and HAL axes differ");
_Static_assert(PFC_AXES == 2u, "the tick writes its two axes out");

/* ---------------------------------------------------------------- configuration */

void app_config_default(app_config_t *cfg)
{
    memset(cfg, 0, sizeof(*cfg));
    cfg->node = PROTO_DEFAULT_NODE;
    cfg->render_carriage = 0u;
    pfc_config_t pfc;
    pfc_default_config(&pfc);
    cfg->gains[0] = pfc.gains[0];
    cfg->gains[1] = pfc.gains[1];
    exec_config_default(&cfg->exec);
    exec_render_default(&cfg->render);
    saf_default_config(&cfg->saf);
    cfg->vel_cutoff_Hz = FS_R(50.0);
    cfg->telemetry_period_ms = 1u;
    cfg->stiffness_max_Npm = app_stiffness_max_default_Npm(cfg->render_carriage);
    cfg->uds_tx_dl = CAN_CLASSIC_MAX_LEN;
}

fs_real_t app_stiffness_max_default_Npm(uint8_t render_carriage)
{
    return (fs_real_t)(render_carriage != 0u ? FS_STIFFNESS_MAX_RENDERED_NPM
                                             : FS_STIFFNESS_MAX_NPM);
}

/* ---------------------------------------------------------------- CAN helpers */

/* Queue a frame; bulk frames (telemetry, UDS) leave APP_TX_RESERVE places for safety frames. */
static bool app_send(app_t *app, const can_frame_t *f, bool bulk)
{
    if (!(bulk ? hal_can_send_bulk(f, APP_TX_RESERVE) : hal_can_send(f))) {
        app->bus.tx_dropped++;
        return false;
    }
    return true;
}

static bool tp_send(void *ctx, const can_frame_t *f)
{
    app_t *app = ctx;
    if (app->diag.tp_frames >= APP_TP_FRAMES_PER_TICK || !hal_can_send_bulk(f, APP_TX_RESERVE)) {
        return false; /* refused: ISO-TP retries */
    }
    app->diag.tp_frames++;
    return true;
}

static void send_status(app_t *app)
{
    struct fs_dbc_device_status_t s;
    memset(&s, 0, sizeof(s));
    s.state = (uint8_t)app->state;
    s.slot = (uint8_t)(app->state == APP_EXECUTE ? app->ctl.active_slot : 0u);
    s.fault_code = app->saf_out.fault_code;
    s.tick = app->tick & 0xFFFFFFu;
    s.actuator_enabled = app->actuator_enabled ? 1u : 0u;
    s.host_alive = (app->saf.wdg.armed != 0u) ? 1u : 0u;
    s.sequence_step = (uint8_t)(app->ctl.seq_step & 0x3u);
    can_frame_t f;
    memset(&f, 0, sizeof(f));
    f.id = PROTO_ID_STATUS(app->cfg.node);
    (void)fs_dbc_device_status_pack(f.data, &s, sizeof(f.data));
    e2e_protect(&f, app->bus.tx_counter_status++);
    (void)app_send(app, &f, false);
}

/* True if the controller took the frame. Not counted in tx_dropped: an emergency frame that
 * could not leave stays queued (app_tick) and is sent again. */
static bool send_emergency(app_t *app, const flt_emcy_t *e)
{
    struct fs_dbc_emergency_t m;
    memset(&m, 0, sizeof(m));
    m.fault_code = e->code;
    m.state = (uint8_t)app->state;
    m.n_latched = (uint8_t)(e->n_latched > 15u ? 15u : e->n_latched);
    m.tick = e->tick & 0xFFFFFFu;
    can_frame_t f;
    memset(&f, 0, sizeof(f));
    f.id = PROTO_ID_EMERGENCY(app->cfg.node);
    (void)fs_dbc_emergency_pack(f.data, &m, sizeof(f.data));
    e2e_protect(&f, app->bus.tx_counter_emcy);
    if (!hal_can_send(&f)) {
        return false;
    }
    app->bus.tx_counter_emcy++;
    return true;
}

static void send_telemetry(app_t *app)
{
    /* every count before the first call: the conversions' constants stay in registers */
    struct fs_dbc_telemetry_position_t p;
    struct fs_dbc_telemetry_force_t q;
    const exec_counts_k_t k = exec_counts_k();
    const exec_sample_t *sa = &app->ctl.sample;
    p.pos_x = exec_pos_counts(k, exec_sample_pos(sa, &app->sens, 0u));
    p.pos_y = exec_pos_y_counts(k, exec_sample_pos(sa, &app->sens, 1u));
    q.force_contact = exec_force_counts(k, exec_sample_force(sa, &app->sens, 0u));
    q.force_cmd = exec_force_counts(k, app->saf_out.force_cmd_N[0]);
    q.force_ref = exec_force_counts(k, app->force_hat);
    q.force_operator = exec_force_counts_real(k, app->sens.force_operator_N[0]);
    /* bit 47: the band's check */
    p.band_outside = (app->state == APP_EXECUTE) ? app->ctl.exec.band_outside : 0u;
    p.tick = (uint16_t)(app->tick & 0xFFFFu);
    can_frame_t f; /* id, length and flags; the pack functions write every data byte */
    f.id = PROTO_ID_TELEM_POS(app->cfg.node);
    f.len = FS_DBC_TELEMETRY_POSITION_LENGTH;
    f.flags = 0u;
    (void)fs_dbc_telemetry_position_pack(f.data, &p, sizeof(f.data));
    (void)app_send(app, &f, true);
    f.id = PROTO_ID_TELEM_FORCE(app->cfg.node);
    f.len = FS_DBC_TELEMETRY_FORCE_LENGTH;
    (void)fs_dbc_telemetry_force_pack(f.data, &q, sizeof(f.data));
    (void)app_send(app, &f, true);
}

/* A HostCommand EXECUTE as a run request: one step, its slot, goal and time scale (counts of the
 * DBC's factor, FS_WIRE_SCALE), the skill's own duration, path scale 1. */
static void run_from_command(const struct fs_dbc_host_command_t *c, uint16_t time_scale,
                             uint8_t end, app_run_request_t *req)
{
    memset(req, 0, sizeof(*req));
    req->source = APP_RUN_FROM_COMMAND;
    req->n_steps = 1u;
    req->end = end;
    req->step[0].slot = c->slot;
    req->step[0].goal_scale = FS_WIRE_REAL(fs_real_t, c->goal_scale);
    req->step[0].time_scale = FS_WIRE_REAL(fs_real_t, time_scale);
    req->step[0].duration_s = FS_R(0.0);
    req->step[0].path_scale = FS_R(1.0);
    req->step[0].amplitude_scale = FS_R(1.0);
    req->step[0].cycles = 1u;
}

/* An authenticated command acted on (its MAC, freshness and arrival checked). */
static void handle_command(app_t *app, const struct fs_dbc_host_command_t *c)
{
    switch ((app_cmd_mode_t)c->mode) {
    case APP_CMD_TEACH: (void)app_event(app, APP_EV_TEACH); break;
    case APP_CMD_RUN_OPTIONS:
        app->auth.run_opts_fv = app->auth.secoc.fv[SECOC_CH_COMMAND];
        app->auth.run_opts_time = c->time_scale;
        app->auth.run_opts_end = c->end_policy;
        break;
    case APP_CMD_EXECUTE: {
        /* its options are the RUN_OPTIONS frame of the freshness value just before */
        if (app->auth.run_opts_fv == 0u ||
            app->auth.run_opts_fv + 1u != app->auth.secoc.fv[SECOC_CH_COMMAND]) {
            app->auth.secoc.last_refusal = (uint16_t)SEC_ERR_EXECUTE_OPTIONS;
            break;
        }
        app_run_request_t req;
        run_from_command(c, app->auth.run_opts_time, app->auth.run_opts_end, &req);
        (void)app_run_start(app,
                            &req); /* a refused command is ignored: the status frame shows it */
        break;
    }
    case APP_CMD_CLEAR_FAULT:
        if (app->state == APP_FAULT) {
            (void)app_clear_faults(app);
        }
        break;
    case APP_CMD_IDLE: /* acted on at receipt (host_frame_take) */
    case APP_CMD_NONE:
    default: break;
    }
}

/* An authenticated heartbeat: the telemetry period, and the command freshness it carries voids
 * every command the host sent before it that has not arrived yet. */
static void handle_heartbeat(app_t *app, const can_frame_t *f)
{
    struct fs_dbc_host_heartbeat_t h;
    if (fs_dbc_host_heartbeat_unpack(&h, f->data, f->len) != 0) {
        return;
    }
    if (h.telemetry_period != 0u) {
        app->bus.host_period_ms = h.telemetry_period;
    }
    secoc_raise_floor(&app->auth.secoc, SECOC_CH_COMMAND, h.command_freshness);
}

/* A host frame whose MAC and freshness were verified, arrived at arrival_ms: a heartbeat always
 * counts (the silence watchdog measures from its arrival); a command only if it arrived within
 * APP_CMD_FRESH_MS of the previous frame acted on (a withheld frame never acts late). */
static void host_frame_accepted(app_t *app, const can_frame_t *f, secoc_channel_t ch,
                                uint32_t arrival_ms)
{
    if (ch == SECOC_CH_COMMAND) {
        struct fs_dbc_host_command_t c;
        if (fs_dbc_host_command_unpack(&c, f->data, f->len) != 0) {
            return;
        }
        if (!app->bus.host_seen ||
            (uint32_t)(arrival_ms - app->bus.host_seen_ms) > APP_CMD_FRESH_MS) {
            app->bus.stale_commands++;
            app->auth.secoc.last_refusal = (uint16_t)SEC_ERR_STALE;
            return;
        }
        app->bus.host_seen_ms = arrival_ms;
        app->bus.host_frame = true;
        app->bus.host_frame_ms = arrival_ms;
        handle_command(app, &c);
        return;
    }
    app->bus.host_seen = true;
    app->bus.host_seen_ms = arrival_ms;
    app->bus.host_frame = true;
    app->bus.host_frame_ms = arrival_ms;
    handle_heartbeat(app, f);
}

/* The verification in flight with this tick's AES rounds; its frame acted on once accepted. */
static void mac_job_step(app_t *app, uint32_t *rounds)
{
    app->auth.mac_ran = true;
    if ((*rounds == 0u && secoc_verify_busy(&app->auth.mac_job)) || /* a start took the share */
        !secoc_verify_run(&app->auth.secoc, &app->auth.mac_job, rounds)) {
        return;
    }
    if (app->auth.mac_job.status == SEC_OK) {
        host_frame_accepted(app, &app->auth.mac_job.f, (secoc_channel_t)app->auth.mac_job.ch,
                            app->auth.mac_job_arrival_ms);
    }
}

/* The oldest waiting frame that is not stale into the verification (stale ones dropped,
 * counted); false if none waits. */
static bool mac_job_next(app_t *app)
{
    app_mac_queue_t *q = &app->auth.macq;
    while (q->count != 0u) {
        const uint8_t i = q->head;
        q->head = (uint8_t)((q->head + 1u) % APP_MAC_QUEUE_LEN);
        q->count--;
        if ((uint32_t)(app->now_ms - q->arrival_ms[i]) > APP_MAC_STALE_MS) {
            app->auth.mac_dropped++;
            continue;
        }
        const secoc_channel_t ch = (secoc_channel_t)q->ch[i];
        can_frame_t f;
        f.id = (ch == SECOC_CH_COMMAND) ? PROTO_ID_HOST_COMMAND(app->cfg.node)
                                        : PROTO_ID_HOST_HEARTBEAT(app->cfg.node);
        f.len = E2E_FRAME_LEN;
        f.flags = 0u;
        memcpy(f.data, q->data[i], E2E_FRAME_LEN);
        if (q->count == 0u) {
            secoc_verify_begin(&app->auth.secoc, &app->auth.mac_job, &f, ch);
        } else { /* more frames wait: a forged one costs one encryption, not two */
            secoc_verify_begin_fast(&app->auth.secoc, &app->auth.mac_job, &f, ch);
        }
        app->auth.mac_job_arrival_ms = q->arrival_ms[i];
        return true;
    }
    return false;
}

/* A host frame to verify, queued with its arrival time; a full queue drops its oldest. */
static void mac_queue_push(app_t *app, const can_frame_t *f, secoc_channel_t ch)
{
    app_mac_queue_t *q = &app->auth.macq;
    if (q->count == APP_MAC_QUEUE_LEN) {
        q->head = (uint8_t)((q->head + 1u) % APP_MAC_QUEUE_LEN);
        q->count--;
        app->auth.mac_dropped++;
    }
    const uint8_t i = (uint8_t)((q->head + q->count) % APP_MAC_QUEUE_LEN);
    memcpy(q->data[i], f->data, E2E_FRAME_LEN);
    q->arrival_ms[i] = app->now_ms;
    q->ch[i] = (uint8_t)ch;
    q->count++;
}

/* True if the UDS server has sliced work or a complete request waiting (uds_service's share). */
static bool uds_work_waiting(const app_t *app)
{
    _Static_assert(APP_TESTERS == 2u, "two testers");
    return app->diag.uds.pending_sid != 0u || isotp_rx_ready(&app->diag.tp[0]) ||
           isotp_rx_ready(&app->diag.tp[1]);
}

/* One received frame: to its ISO-TP link, or a host frame: a wrong length or CRC refused, a stop
 * acted on at once (from any node: the safe direction is never blocked by what came before it),
 * anything else queued for its MAC check. Nothing about a host frame is recorded before its MAC
 * is verified. */
static void can_take(app_t *app, const can_frame_t *f)
{
    const uint32_t node = app->cfg.node;
    secoc_channel_t ch;
    if (f->id == PROTO_ID_HOST_COMMAND(node)) {
        ch = SECOC_CH_COMMAND;
    } else if (f->id == PROTO_ID_HOST_HEARTBEAT(node)) {
        ch = SECOC_CH_HEARTBEAT;
    } else {
        if (f->id == PROTO_ID_UDS_REQUEST(node)) {
            isotp_on_frame(&app->diag.tp[0], f, app->now_us);
        } else if (f->id == PROTO_ID_UDS_REQUEST_2(node)) {
            isotp_on_frame(&app->diag.tp[1], f, app->now_us);
        }
        return;
    }
    if (!e2e_frame_ok(f)) {
        app->bus.e2e_errors++;
        return;
    }
    if (ch == SECOC_CH_COMMAND && (f->data[0] & 0x0Fu) == (uint8_t)APP_CMD_IDLE) {
        (void)app_event(app, APP_EV_STOP);
        app_commands_void(app);
        return;
    }
    mac_queue_push(app, f, ch);
}

/* The CAN frames of this tick: every frame received (up to APP_RX_FRAMES_PER_TICK, more than the
 * bus carries in a tick), stamped with this tick's time; then the MAC checks, oldest first, within
 * APP_MAC_ROUNDS_PER_TICK AES rounds (a start counting APP_MAC_BEGIN_ROUNDS) and
 * APP_MAC_FRAMES_PER_TICK starts. A new verification and
 * the UDS server's work never share a tick: one in flight goes on, a new one waits a tick while
 * the server has work (uds_service then leaves its share to the next tick). */
static void can_receive(app_t *app)
{
    app->auth.mac_ran = false;
    can_frame_t f;
    for (unsigned i = 0u; i < APP_RX_FRAMES_PER_TICK && hal_can_receive(&f); i++) {
        can_take(app, &f);
    }
    if (!secoc_verify_busy(&app->auth.mac_job) && app->auth.macq.count == 0u) {
        return; /* the usual tick: nothing to verify */
    }
    uint32_t rounds = APP_MAC_ROUNDS_PER_TICK;
    if (secoc_verify_busy(&app->auth.mac_job)) {
        mac_job_step(app, &rounds);
    } else if (uds_work_waiting(app)) {
        return;
    }
    for (unsigned started = 0u;
         started < APP_MAC_FRAMES_PER_TICK && rounds >= APP_MAC_BEGIN_ROUNDS &&
         !secoc_verify_busy(&app->auth.mac_job) && mac_job_next(app);
         started++) {
        rounds -= APP_MAC_BEGIN_ROUNDS;
        mac_job_step(app, &rounds);
    }
}

/* True if a request of service sid from tester t is a write in a session another tester
 * unlocked: session, reset, SecurityAccess, DID writes, routines, transfers (reads and
 * TesterPresent stay open). */
static bool foreign_write(const app_t *app, uint8_t t, uint8_t sid)
{
    if (app->diag.uds_owner == 0u || app->diag.uds_owner == t + 1u) {
        return false;
    }
    switch (sid) {
    case UDS_SID_DSC:
    case UDS_SID_ECU_RESET:
    case UDS_SID_SECURITY:
    case UDS_SID_WDBI:
    case UDS_SID_ROUTINE:
    case UDS_SID_REQ_DOWNLOAD:
    case UDS_SID_REQ_UPLOAD:
    case UDS_SID_TRANSFER_DATA:
    case UDS_SID_TRANSFER_EXIT: return true;
    default: return false;
    }
}

/* The ISO-TP frame share of a tick that verified a frame's MAC or did the server's work: at most
 * APP_TP_FRAMES_BUSY_TICK frames (APP_TP_FRAMES_EXEC_BUSY_TICK while a skill runs), the answer's
 * first frame included (set before it is queued). */
static void tp_busy_share(app_t *app)
{
    const uint32_t busy_frames = (app->state == APP_EXECUTE) ? APP_TP_FRAMES_EXEC_BUSY_TICK
                                                             : APP_TP_FRAMES_BUSY_TICK;
    if (app->diag.tp_frames < APP_TP_FRAMES_PER_TICK - busy_frames) {
        app->diag.tp_frames = APP_TP_FRAMES_PER_TICK - busy_frames;
    }
}

/* An answer of n bytes built in link tp's buffer: sent within the tick's busy frame share, or
 * queued for the next tick's poll when none is left (no frame built only to be refused). */
static void tp_answer(app_t *app, isotp_link_t *tp, const uint8_t *resp, uint16_t n)
{
    tp_busy_share(app);
    if (app->diag.tp_frames >= APP_TP_FRAMES_PER_TICK) {
        (void)isotp_queue(tp, resp, n);
    } else {
        (void)isotp_send(tp, resp, n, app->now_us);
    }
}

/* True if a request is a SecurityAccess sendKey of tester t whose reception began before that
 * tester was last sent a seed (a key can only answer a seed it has seen). */
static bool key_before_seed(const app_t *app, uint8_t t, const uint8_t *req, uint16_t len)
{
    if (req[0] != UDS_SID_SECURITY || len < 2u) {
        return false;
    }
    const uint8_t sub = (uint8_t)(req[1] & 0x7Fu);
    return sub != 0u && (sub & 1u) == 0u &&
           app->diag.tp[t].rx_start_us <= app->diag.seed_sent_us[t];
}

/* A negative answer built by the device itself, the server untouched. */
static uint16_t refuse_request(app_t *app, const uint8_t *req, uint8_t *resp, uint8_t nrc,
                               sec_status_t why)
{
    resp[0] = UDS_NEGATIVE_RESPONSE;
    resp[1] = req[0];
    resp[2] = nrc;
    app->auth.secoc.last_refusal = (uint16_t)why;
    return 3u;
}

/* Serve one request of tester t (its link has one and is free to answer); a foreign write is
 * refused here (0x33, code 558 as the last refusal, counted), and a key whose reception began
 * before its tester's seed was sent (0x24, 560); the rest goes to the server, which keeps each
 * tester's seed apart (uds_server_t.tester). */
static void uds_serve(app_t *app, uint8_t t, const uint8_t *req, uint16_t len)
{
    isotp_link_t *tp = &app->diag.tp[t];
    uint8_t *resp = isotp_tx_buffer(tp); /* the link is free: the answer is built in place */
    uint16_t n;
    if (foreign_write(app, t, req[0])) {
        n = refuse_request(app, req, resp, UDS_NRC_SECURITY_ACCESS_DENIED, SEC_ERR_SESSION_OWNER);
        app->diag.uds_foreign++;
    } else if (key_before_seed(app, t, req, len)) {
        n = refuse_request(app, req, resp, UDS_NRC_REQUEST_SEQUENCE_ERROR, SEC_ERR_KEY_SEQUENCE);
    } else {
        if (app->diag.uds.pending_sid == 0u) {
            app->diag.uds_from = t; /* the answer to a pending request goes to its own tester */
        }
        app->diag.uds.tester = t;
        n = uds_server_handle(&app->diag.uds, req, len, resp, ISOTP_MAX_PAYLOAD, app->now_ms);
        app->diag.reset_since_ms = app->now_ms; /* used only if this was an accepted ECUReset */
        if (req[0] == UDS_SID_SECURITY && n > 2u && resp[0] == UDS_SID_SECURITY + 0x40u) {
            app->diag.seed_sent_us[t] = app->now_us; /* a seed (a key's answer is 2 bytes) */
        }
    }
    if (app->diag.uds.pending_sid == UDS_SID_TRANSFER_DATA && app->diag.tp_held == 0u) {
        app->diag.tp_held = (uint8_t)(t +
                                      1u); /* the block is taken in slices from the link's buffer */
    } else {
        isotp_rx_release(tp);
    }
    if (n != 0u) {
        tp_answer(app, tp, resp, n);
    }
}

/* The link buffer held for a TransferData block given back once its slices are done. */
static void uds_release_held(app_t *app)
{
    if (app->diag.tp_held != 0u && app->diag.uds.pending_sid != UDS_SID_TRANSFER_DATA) {
        isotp_rx_release(&app->diag.tp[app->diag.tp_held - 1u]);
        app->diag.tp_held = 0u;
    }
}

static bool any_tx_busy(const app_t *app)
{
    for (unsigned t = 0; t < APP_TESTERS; t++) {
        if (isotp_tx_busy(&app->diag.tp[t])) {
            return true;
        }
    }
    return false;
}

/* The pending request's next slice, its response queued once it completes. */
static void uds_resume_step(app_t *app, isotp_link_t *own)
{
    uint8_t *resp = isotp_tx_buffer(own); /* the link is free: the answer is built in place */
    const uint16_t n = uds_server_resume(&app->diag.uds, resp, ISOTP_MAX_PAYLOAD, app->now_ms);
    if (n != 0u) {
        tp_answer(app, own, resp, n);
    }
}

/* One new request from either tester in turn; true if one was served. */
static bool uds_serve_next(app_t *app)
{
    for (unsigned k = 0; k < APP_TESTERS; k++) {
        const uint8_t t = (uint8_t)((app->diag.uds_next + k) % APP_TESTERS);
        const uint8_t *req = NULL;
        const uint16_t len = isotp_rx_peek(&app->diag.tp[t], &req);
        if (len != 0u && !isotp_tx_busy(&app->diag.tp[t]) && app->diag.tp_held != t + 1u) {
            uds_serve(app, t, req, len);
            app->diag.uds_next = (uint8_t)((t + 1u) % APP_TESTERS);
            return true;
        }
    }
    return false;
}

/* The server's work of this tick: a pending request's next slice or one new request, never both
 * (each is a tick's share of work); while both wait they take turns. True if it did any. */
static bool uds_work(app_t *app)
{
    isotp_link_t *own = &app->diag.tp[app->diag.uds_from];
    const bool resume = app->diag.uds.pending_sid != 0u && !isotp_tx_busy(own);
    if (resume && !app->diag.uds_request_turn) {
        uds_resume_step(app, own);
        app->diag.uds_request_turn = true; /* a request waiting meanwhile goes next tick */
        return true;
    }
    app->diag.uds_request_turn = false;
    if (uds_serve_next(app)) {
        return true;
    }
    if (resume) { /* no request waited: the slice runs in this tick after all */
        uds_resume_step(app, own);
        app->diag.uds_request_turn = true;
        return true;
    }
    return false;
}

/* True if both links are idle and the server has no request pending, held or resetting: the
 * tick's request scan and the links' polls have nothing to do (the usual tick, one test). */
static bool uds_all_idle(const app_t *app)
{
    _Static_assert(APP_TESTERS == 2u, "two testers");
    return (app->diag.uds.pending_sid | app->diag.uds.pending_reset | app->diag.tp_held) == 0u &&
           isotp_idle(&app->diag.tp[0]) && isotp_idle(&app->diag.tp[1]);
}

/* The session's share of every tick: its timeout, then its owner (the server may have locked). */
static inline void uds_session_step(app_t *app)
{
    if (uds_server_session_expired(&app->diag.uds, app->now_ms)) {
        uds_server_poll(&app->diag.uds, app->now_ms);
    }
    if (app->diag.uds.unlocked_level == 0u) {
        app->diag.uds_owner = 0u;
        if (sec_is_unlocked(&app->sec.access)) {
            sec_lock(&app->sec.access); /* the server locked (session change, S3 timeout, reset) */
        }
    } else if (app->diag.uds_owner == 0u) {
        app->diag.uds_owner = (uint8_t)(app->diag.uds_from +
                                        1u); /* the tester whose sendKey unlocked */
    }
}

/* One UDS request a tick, from either tester in turn; the session belongs to the tester that
 * unlocked it (uds_owner) until it locks again. */
static void uds_service(app_t *app)
{
    if (uds_all_idle(app)) {
        /* nothing held to release, no link to poll: the frame share and the session alone */
        if (app->auth.mac_ran) {
            tp_busy_share(app);
        } else {
            app->diag.uds_request_turn = false; /* as uds_work when nothing waits */
        }
        uds_session_step(app);
        return;
    }
    uds_release_held(app);
    if (app->diag.uds.pending_reset != 0u) {
        /* ECUReset accepted (ISO 14229-1): its positive response leaves the bus first, then the
         * reset (at the first tick that finds the transport and the CAN queue empty; bounded by
         * APP_RESET_TX_WAIT_MS, e.g. bus-off). No request is served meanwhile. */
        if ((!any_tx_busy(app) && hal_can_tx_idle()) ||
            (uint32_t)(app->now_ms - app->diag.reset_since_ms) >= APP_RESET_TX_WAIT_MS) {
            uds_server_after_response(&app->diag.uds);
        }
        for (unsigned t = 0; t < APP_TESTERS; t++) {
            isotp_poll(&app->diag.tp[t], app->now_us);
        }
        return;
    }
    /* a tick that verified a frame's MAC leaves the server's work to the next tick; one with
     * either queues a busy tick's ISO-TP frames */
    if (app->auth.mac_ran || uds_work(app)) {
        tp_busy_share(app);
    }
    /* the session, the held buffer given back, then the links' timers and frames */
    uds_session_step(app);
    uds_release_held(app);
    if (app->diag.tp_frames < APP_TP_FRAMES_PER_TICK) {
        /* a tick without a frame share left polls nothing: its frames would be built to be
         * refused (the links' timeouts are checked a tick later) */
        for (unsigned t = 0; t < APP_TESTERS; t++) {
            isotp_poll(&app->diag.tp[t], app->now_us);
        }
    }
}

/* ---------------------------------------------------------------- init and tick */

void app_init(app_t *app, const app_config_t *cfg)
{
    memset(app, 0, sizeof(*app));
    app->cfg = *cfg;
    app->state = APP_BOOT;
    app->now_us = hal_time_us_ms(&app->now_ms);
    secoc_init(&app->auth.secoc); /* no motion key until a host session establishes one */

    isotp_config_t tpc;
    isotp_config_default(&tpc, PROTO_ID_UDS_RESPONSE(cfg->node), PROTO_ID_UDS_REQUEST(cfg->node));
    tpc.tx_dl = cfg->uds_tx_dl; /* isotp_init takes anything but 64 as classic */
    tpc.brs = cfg->uds_brs;
    isotp_init(&app->diag.tp[0], &tpc, tp_send, app);
    isotp_config_default(&tpc, PROTO_ID_UDS_RESPONSE_2(cfg->node),
                         PROTO_ID_UDS_REQUEST_2(cfg->node));
    tpc.tx_dl = cfg->uds_tx_dl;
    tpc.brs = cfg->uds_brs;
    isotp_init(&app->diag.tp[1], &tpc, tp_send, app);
    uds_app_t hooks;
    app_uds_bind(app, &hooks);
    uds_server_init(&app->diag.uds, &hooks);

    app_sec_setup(app);

    slots_init(&app->slots, hal_flash());

    app_fw_init(&app->fw, APP_FW_TARGET_ID, slots_any(&app->slots)); /* firmware update */

    app->saf_cfg = cfg->saf;
    saf_init(&app->saf);
    saf_prepare(&app->saf_cfg, &app->saf);
    for (unsigned a = 0; a < PFC_AXES; a++) {
        exec_vel_init(&app->ctl.vel[a], cfg->vel_cutoff_Hz, APP_TICK_S);
    }
    hal_actuator_enable(false);
    app->next_tick_us = app->now_us + APP_TICK_US;
}

bool app_poll(app_t *app)
{
    const uint64_t now = hal_time_us();
    if (now < app->next_tick_us) {
        return false;
    }
    const bool late = now >= app->next_tick_us + APP_TICK_US;
    app->next_tick_us = late ? now + APP_TICK_US : app->next_tick_us + APP_TICK_US;
    app_tick(app, late);
    return true;
}

/* One executor tick: its commands into force_req (the integer build: the tick sample's request
 * unless the drive is rendered), its status as the app keeps it; returns 1 once the run has
 * ended. */
static uint8_t control_execute(app_t *app, fs_real_t dt)
{
    /* non-finite measurement: 0 N, the sensor checks latch the fault. A saturated DMP step
     * (the fixed-point build: the skill at this scale left its Q formats, 300) stops the run:
     * counted, kept as the run status, and latched as skill invalid in this tick */
    exec_out_n_t out;
    const fs_status_t rc = exec_tick_sample(&app->ctl.exec_run_cfg, &app->ctl.exec,
                                            &app->ctl.sample, &app->sens, app->vel_mps, &out);
    app->force_hat = exec_out_force_hat(&out);
    if (app->cfg.render_carriage == 0u) {
        exec_sample_request(&app->ctl.sample, &out); /* the integer build's request */
    }
    if (rc == FS_ERR_FIXED_OVERFLOW) {
        app->ctl.exec_saturated_ticks++;
        app->ctl.last_run_status = (uint16_t)FS_ERR_FIXED_OVERFLOW;
        app->ctl.causes |= FLT_BIT(FLT_SKILL_INVALID); /* latched in this tick */
    }
    app->ctl.seq_step = out.step;
    /* the band's stop: outside it for the run's band stop time (1 ms a tick) */
    if (app->ctl.band_stop_ms != 0u && app->ctl.exec.band_streak_ticks >= app->ctl.band_stop_ms) {
        app->ctl.causes |= FLT_BIT(FLT_BAND);
    }
    if (app->cfg.render_carriage != 0u) {
        const fs_real_t m_d = app->ctl.exec_run_cfg.pfc.gains[0].m_d_kg;
        app->force_req_N[0] = exec_render_step(
            &app->cfg.render, &app->ctl.rend[0], exec_out_cmd_real(&out, 0u), m_d,
            -app->sens.force_contact_N[0], app->sens.pos_m[0], app->vel_mps[0], dt);
        app->force_req_N[1] = exec_render_step(&app->cfg.render, &app->ctl.rend[1],
                                               exec_out_cmd_real(&out, 1u), m_d, FS_R(0.0),
                                               app->sens.pos_m[1], app->vel_mps[1], dt);
    } else {
        app->force_req_N[0] = exec_out_cmd_req(&out, 0u);
        app->force_req_N[1] = exec_out_cmd_req(&out, 1u);
    }
    return out.done;
}

static void control(app_t *app)
{
    const fs_real_t dt = APP_TICK_S;
    /* a run's start goes a slice a tick after the actuator's write (app_tick): no force yet, as
     * in IDLE; the first step starts from the sample after the last slice */
    if (app->state == APP_EXECUTE && !app_run_starting(app)) {
        const uint8_t done = control_execute(app, dt); /* sets force_req_N */
        if (done != 0u) {
            app->ctl.exec_done = true;
            (void)app_event(app, APP_EV_STOP); /* release finished: back to IDLE */
            app->force_req_N[0] = FS_R(0.0);
            app->force_req_N[1] = FS_R(0.0);
            exec_sample_request_clear(&app->ctl.sample);
        }
        return;
    }
    app->force_req_N[0] = FS_R(0.0);
    app->force_req_N[1] = FS_R(0.0);
    if (app->state == APP_TEACH) {
        app->ctl.teach_ticks++;
        if (app->cfg.render_carriage != 0u) {
            /* render the handle m_d: the carriage follows (operator - contact)/m_d */
            const fs_real_t tot_x = app->sens.force_operator_N[0] - app->sens.force_contact_N[0];
            const fs_real_t tot_y = app->sens.force_operator_N[1];
            app->force_req_N[0] = exec_render_step(&app->cfg.render, &app->ctl.rend[0], tot_x,
                                                   app->cfg.gains[0].m_d_kg, tot_x,
                                                   app->sens.pos_m[0], app->vel_mps[0], dt);
            app->force_req_N[1] = exec_render_step(&app->cfg.render, &app->ctl.rend[1], tot_y,
                                                   app->cfg.gains[1].m_d_kg, tot_y,
                                                   app->sens.pos_m[1], app->vel_mps[1], dt);
        }
        /* ideal (dynamics-compensated) drive: the device is m_d with zero command */
    }
}

/* The safety layer's step over this tick's measurement and request; a stop latches the fault
 * and the command it leaves is what the actuator gets. */
static void supervise(app_t *app, bool overrun)
{
    saf_input_t in; /* every field set: no memset in the tick */
    in.tick = app->tick;
    in.now_ms = app->now_ms;
    in.host_frame = app->bus.host_frame && (app->state == APP_TEACH || app->state == APP_EXECUTE);
    in.host_frame_age_ms = app->now_ms - app->bus.host_frame_ms;
    /* the tick's own causes (a saturated step, the band's stop: control_execute) and the bus's */
    in.causes = app->ctl.causes | (hal_can_bus_off() ? FLT_BIT(FLT_BUS_OFF) : 0u) |
                (overrun ? FLT_BIT(FLT_TICK_OVERRUN) : 0u);
    app->ctl.causes = 0u;
    const exec_sample_t *sa = &app->ctl.sample;
    for (unsigned a = 0; a < PFC_AXES; a++) {
        in.meas[a].pos_m = exec_sample_pos(sa, &app->sens, a);
        in.meas[a].vel_mps = exec_sample_vel(sa, app->vel_mps, a);
        in.meas[a].force_N = exec_sample_force(sa, &app->sens, a);
        in.force_req_N[a] = exec_sample_req(sa, app->force_req_N[a], a);
    }
    saf_step(&app->saf_cfg, &app->saf, &in, &app->saf_out);
    if (app->saf_out.stopping) {
        (void)app_event(app, APP_EV_FAULT); /* latched; a skill never resumes by itself */
    }
    app->force_out_N[0] = exec_force_real(app->saf_out.force_cmd_N[0]);
    app->force_out_N[1] = exec_force_real(app->saf_out.force_cmd_N[1]);
}

static uint32_t telemetry_period(app_t *app);

/* The tick's cyclic frames: pending emergencies, then status and telemetry on their periods. */
static void transmit(app_t *app)
{
    /* Emergency frames leave in the tick that latched the fault; one that cannot leave (bus-off,
     * transmit queue full) stays queued and goes out once the controller takes frames again, so
     * the host learns every fault code from its own frame. */
    if (flt_emcy_pending(&app->saf.flt)) {
        flt_emcy_t e;
        while (!hal_can_bus_off() && flt_emcy_peek(&app->saf.flt, &e) && send_emergency(app, &e)) {
            (void)flt_emcy_pop(&app->saf.flt, &e);
        }
    }
    if (app->tick % APP_STATUS_PERIOD_MS == 0u) {
        send_status(app);
    }
    const uint32_t period = telemetry_period(app);
    if (period <= 1u || app->tick % period == 0u) { /* 1 ms, the usual period: no division */
        send_telemetry(app);
    }
}

void app_tick(app_t *app, bool overrun)
{
    app->now_us = hal_time_us_ms(&app->now_ms);
    app->tick++;
    app->overrun = overrun;

    /* The control path first: sensors, control, the safety layer and the actuator's write, so
     * the force loop's delay is the same whatever the bus carries. What arrived meanwhile
     * (commands, UDS requests, keys) is taken after the write and acts from the next tick's
     * sample: a stop reaches the actuator at most two periods after its arrival. */
    hal_sensors_read(&app->sens);
    exec_sample_read(&app->ctl.sample, &app->sens, app->ctl.vel, app->vel_mps,
                     app->cfg.render_carriage != 0u, APP_TICK_S);
    if (app->state == APP_BOOT) {
        app->fw.self_test_ok = app_fw_self_test_and_confirm(app);
        if (!app->fw.self_test_ok) {
            /* unconfirmed: the port resets after this tick and the bootloader reverts. Nothing
             * from the bus is served meanwhile (no node can confirm this image for it). */
            hal_request_reset(1u);
            hal_actuator_enable(false);
            return;
        }
        (void)app_event(app, APP_EV_BOOTED);
    }
    control(app);
    supervise(app, overrun); /* the host frames of the last tick's receive kick the watchdog */
    const bool enable = app->saf_out.actuator_enable && app->state != APP_BOOT;
    if (enable != app->actuator_enabled) {
        hal_actuator_enable(enable);
        app->actuator_enabled = enable;
    }
    hal_actuator_force(app->force_out_N);

    /* then a run's start slice (a start this tick's bus accepts has its first in the next), the
     * bus (the frames that arrived, the UDS server) and the long work's slices */
    if (app_run_starting(app)) {
        app_run_start_step(app);
    }
    app->bus.host_frame = false;
    /* while a skill runs ISO-TP queues at most APP_TP_FRAMES_EXEC_TICK frames a tick */
    app->diag.tp_frames = app->state == APP_EXECUTE
                              ? APP_TP_FRAMES_PER_TICK - APP_TP_FRAMES_EXEC_TICK
                              : 0u;
    can_receive(app);
    uds_service(app);
    if (app_sec_store_pending(app)) {
        app_sec_store_step(app);
    }
    transmit(app);
    /* the next step's kernel blend, after the write (off the sensor-to-actuator path) and after
     * the bus (a run it stopped prepares nothing; one it started steps from a fresh state) */
    if (app->state == APP_EXECUTE && !app_run_starting(app)) {
        exec_prepare_next(&app->ctl.exec);
    }
}

/* The telemetry's period this tick: the host's (or the configured one) while the device acts, and
 * in FAULT through the stop ramp and while a host keeps sending (its frames extend it by the
 * host-silence timeout); IDLE's slow period otherwise, so a device left in FAULT by a silent host
 * does not keep the bus busy. */
static uint32_t telemetry_period(app_t *app)
{
    bool fast = app->state == APP_TEACH || app->state == APP_EXECUTE;
    if (app->state == APP_FAULT) {
        if (app->bus.host_frame) {
            const uint32_t until = app->now_ms + (uint32_t)app->saf_cfg.wdg.timeout_ms;
            if ((int32_t)(until - app->fault_fast_until_ms) > 0) {
                app->fault_fast_until_ms = until;
            }
        }
        fast = (int32_t)(app->fault_fast_until_ms - app->now_ms) > 0;
    }
    if (!fast) {
        return APP_IDLE_TELEMETRY_PERIOD_MS;
    }
    return (app->bus.host_period_ms != 0u) ? app->bus.host_period_ms : app->cfg.telemetry_period_ms;
}

bool app_fw_self_test_and_confirm(app_t *app)
{
    /* a new image's self-test: its safety configuration valid and its storage readable */
    return app_fw_self_test(&app->fw, saf_config_validate(&app->saf_cfg) == SAF_OK,
                            app->slots.nvm_ok);
}

app_state_t app_state(const app_t *app)
{
    return app->state;
}

uint16_t app_fault_code(const app_t *app)
{
    return app->saf_out.fault_code;
}

uint32_t app_tick_count(const app_t *app)
{
    return app->tick;
}

fs_real_t app_force_ref_N(const app_t *app)
{
    return exec_force_real(app->force_hat);
}

const skill_t *app_slot_skill(const app_t *app, uint8_t slot)
{
    return slots_skill(&app->slots, slot);
}

uint32_t app_slot_crc(const app_t *app, uint8_t slot)
{
    return slots_skill(&app->slots, slot) != NULL ? app->slots.crc[slot - 1u] : 0u;
}

const boot_t *app_boot(const app_t *app)
{
    return &app->fw.boot;
}

const boot_config_t *app_boot_config(const app_t *app)
{
    return &app->fw.boot_cfg;
}

uint16_t app_last_run_status(const app_t *app)
{
    return app->ctl.last_run_status;
}

const uint32_t *app_tx_dropped(const app_t *app)
{
    return &app->bus.tx_dropped;
}

const uint8_t *app_motion_nonce(const app_t *app)
{
    return app->sec.motion.dev_nonce;
}

bool app_transfer_busy(const app_t *app)
{
    return app->diag.uds.xfer != UDS_XFER_NONE || app->diag.uds.pending_sid != 0u;
}

bool app_transfer_is_firmware(const app_t *app)
{
    return app->fw.xfer;
}

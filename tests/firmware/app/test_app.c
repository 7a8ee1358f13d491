/* The device application through its CAN interface only (host port, simulator backend): boot to
 * IDLE, E2E-checked commands, TEACH, host silence (default 100 ms) -> FAULT with an emergency
 * frame and the force ramped to zero within 50 ms, no auto-resume, guarded clearing; UDS over
 * ISO-TP: skill download into a slot (golden vector), corrupted and interrupted downloads keep
 * the old skill, refusals while executing; ECUReset answered before the device restarts. */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <cmocka.h>

#include "app_internal.h"
#include "fs_dbc.h"
#include "hal_host.h"
#include "vectors_io.h"

static app_t app;
static app_config_t cfg;
static uint64_t t_us;
static secoc_t host; /* the test host's session: motion key and freshness values */

/* The host session with the device (as the DID 0x0302 write, then the host's derivation). */
static void host_session(void)
{
    static const uint8_t nonce[SECOC_NONCE_LEN] = "test host nonce";
    assert_int_equal(app_motion_key(&app, nonce, SECOC_NONCE_LEN), 0);
    uint8_t len = 0u;
    const uint8_t *secret = hal_device_secret(UDS_SEC_LEVEL_WRITE, &len);
    secoc_start_session(&host, secret, len, app.sec.motion.dev_nonce, nonce);
}

/* MAC, freshness and E2E of a packed host frame, sent to the device (lost while it is bus-off:
 * the host's freshness value advances all the same). */
static void deliver_authentic(can_frame_t *f, secoc_channel_t ch)
{
    const uint32_t fv = secoc_protect(&host, f, ch);
    e2e_protect(f, (uint8_t)(fv & E2E_COUNTER_MASK));
    (void)hal_sim_can_deliver(f);
}

/* frames the device sent, collected per tick */
#define OUTCAP 4096u
static can_frame_t out[OUTCAP];
static unsigned n_out;

static void tick(void)
{
    t_us += 1000u;
    hal_host_set_time_us(t_us);
    app_tick(&app, false);
    can_frame_t f;
    while (hal_sim_can_tx_peek(&f)) {
        if (n_out < OUTCAP) {
            out[n_out++] = f;
        }
        hal_sim_can_tx_pop();
    }
}

static void ticks(unsigned n)
{
    for (unsigned i = 0; i < n; i++) {
        tick();
    }
}

static void send_command(uint8_t mode, uint8_t slot)
{
    struct fs_dbc_host_command_t c;
    can_frame_t f = {.id = PROTO_ID_HOST_COMMAND(0), .len = 8};
    if (mode == APP_CMD_EXECUTE) { /* its time scale and end policy first */
        memset(&c, 0, sizeof(c));
        c.mode = APP_CMD_RUN_OPTIONS;
        c.time_scale = 1000u;
        (void)fs_dbc_host_command_pack(f.data, &c, 8);
        deliver_authentic(&f, SECOC_CH_COMMAND);
    }
    memset(&c, 0, sizeof(c));
    c.mode = mode;
    c.slot = slot;
    c.goal_scale = 1000u;
    (void)fs_dbc_host_command_pack(f.data, &c, 8);
    deliver_authentic(&f, SECOC_CH_COMMAND);
}

/* A heartbeat as the host sends it: the low byte of its last command's freshness value in it. */
static void send_heartbeat(void)
{
    can_frame_t f = {.id = PROTO_ID_HOST_HEARTBEAT(0), .len = 8};
    struct fs_dbc_host_heartbeat_t h = {0};
    h.command_freshness = (uint8_t)host.fv[SECOC_CH_COMMAND];
    (void)fs_dbc_host_heartbeat_pack(f.data, &h, 8);
    deliver_authentic(&f, SECOC_CH_HEARTBEAT);
}

static struct fs_dbc_device_status_t last_status(void)
{
    struct fs_dbc_device_status_t s;
    memset(&s, 0xFF, sizeof(s));
    for (unsigned i = n_out; i-- > 0;) {
        if (out[i].id == PROTO_ID_STATUS(0)) {
            e2e_rx_t rx;
            e2e_rx_reset(&rx);
            assert_int_equal(e2e_check(&rx, &out[i]), PROTO_OK);
            assert_int_equal(fs_dbc_device_status_unpack(&s, out[i].data, 8), 0);
            break;
        }
    }
    return s;
}

/* A minimal ISO-TP/UDS tester over the sim queues (the isotp module acting as the tester side;
 * can-isotp/udsoncan play this role in tests/can). */
static isotp_link_t tester;
static bool tester_send(void *ctx, const can_frame_t *f)
{
    (void)ctx;
    return hal_sim_can_deliver(f);
}

static int setup(void **state)
{
    (void)state;
    hal_host_init();
    hal_host_flash_erase();
    hal_sim_can_reset();
    t_us = 0u;
    n_out = 0u;
    hal_sensors_t s;
    memset(&s, 0, sizeof(s));
    s.pos_m[0] = 0.001;
    hal_host_set_sensors(&s);
    app_config_default(&cfg);
    hal_host_set_time_us(0u);
    app_init(&app, &cfg);
    host_session();
    isotp_config_t c;
    isotp_config_default(&c, PROTO_ID_UDS_REQUEST(0), PROTO_ID_UDS_RESPONSE(0));
    isotp_init(&tester, &c, tester_send, NULL);
    return 0;
}


static uint16_t uds(const uint8_t *req, uint16_t len, uint8_t *resp, uint16_t cap)
{
    assert_int_equal(isotp_send(&tester, req, len, t_us), PROTO_OK);
    for (unsigned k = 0; k < 2000u; k++) {
        isotp_poll(&tester, t_us);
        unsigned before = n_out;
        tick();
        for (unsigned i = before; i < n_out; i++) {
            isotp_on_frame(&tester, &out[i], t_us);
        }
        const uint8_t *r = NULL;
        const uint16_t n = isotp_rx_peek(&tester, &r);
        if (n != 0u) {
            if (n >= 3u && r[0] == 0x7F && r[2] == 0x78) { /* response pending: keep waiting */
                isotp_rx_release(&tester);
                continue;
            }
            assert_true(n <= cap);
            memcpy(resp, r, n);
            isotp_rx_release(&tester);
            return n;
        }
    }
    fail_msg("no UDS response");
    return 0;
}

/* SecurityAccess at level with the secret of key_level (the port's secret of that level):
 * returns 0 when unlocked, else the NRC of the key. */
static uint8_t unlock_with(uint8_t session, uint8_t level, uint8_t key_level)
{
    uint8_t r[64];
    const uint8_t dsc[2] = {0x10, session};
    assert_int_equal(uds(dsc, 2, r, sizeof(r)), 6);
    ticks(1100); /* SecurityAccess boot delay (1 s) */
    const uint8_t seed_req[2] = {0x27, level};
    assert_int_equal(uds(seed_req, 2, r, sizeof(r)), 2 + SEC_SEED_LEN);
    uint8_t key[2 + SEC_KEY_LEN] = {0x27, (uint8_t)(level + 1u)};
    /* HMAC-SHA256 (checked against RFC 4231 vectors in the security tests), secret of the port */
    sec_compute_key(app_sec_config(&app, key_level), &r[2], &key[2]);
    (void)uds(key, sizeof(key), r, sizeof(r));
    return r[0] == 0x67 ? 0u : r[2];
}

static void unlock(uint8_t session)
{
    assert_int_equal(unlock_with(session, 0x01, 0x01), 0);
}

static uint8_t image_a[APP_IMAGE_MAX], image_b[APP_IMAGE_MAX];
static uint32_t len_a, len_b;

/* A golden image of tests/vectors into buf (APP_IMAGE_MAX bytes); its length. */
static uint32_t load(const char *name, uint8_t *buf)
{
    const uint32_t n = tv_read(name, buf, APP_IMAGE_MAX);
    assert_true(n > 0u);
    return n;
}

static uint8_t download(uint8_t slot, const uint8_t *img, uint32_t len, uint32_t stop_after)
{
    uint8_t r[64];
    uint8_t rd[7] = {0x34, 0x00, 0x21, slot, (uint8_t)(len >> 8), (uint8_t)len};
    uint16_t n = uds(rd, 6, r, sizeof(r));
    if (r[0] == 0x7F) {
        return r[2];
    }
    assert_int_equal(n, 4);
    static uint8_t td[4096];
    td[0] = 0x36;
    td[1] = 0x01;
    const uint32_t send = stop_after < len ? stop_after : len;
    memcpy(&td[2], img, send);
    n = uds(td, (uint16_t)(send + 2u), r, sizeof(r));
    if (r[0] == 0x7F) {
        return r[2];
    }
    if (stop_after < len) {
        return 0xFF; /* the tester goes away here */
    }
    const uint8_t exit_req[1] = {0x37};
    n = uds(exit_req, 1, r, sizeof(r));
    return r[0] == 0x7F ? r[2] : 0x00;
}

static void test_boot_status_and_e2e(void **state)
{
    (void)state;
    ticks(20);
    struct fs_dbc_device_status_t s = last_status();
    assert_int_equal(s.state, APP_IDLE);
    assert_int_equal(s.fault_code, 0);
    unsigned n_status = 0;
    for (unsigned i = 0; i < n_out; i++) {
        n_status += out[i].id == PROTO_ID_STATUS(0);
    }
    assert_int_equal(n_status, 2); /* every 10 ms */
    /* a command with a bad CRC is ignored */
    struct fs_dbc_host_command_t c = {.mode = APP_CMD_TEACH};
    can_frame_t f = {.id = PROTO_ID_HOST_COMMAND(0), .len = 8};
    (void)fs_dbc_host_command_pack(f.data, &c, 8);
    e2e_protect(&f, 3);
    f.data[7] ^= 0x5A;
    assert_true(hal_sim_can_deliver(&f));
    ticks(20);
    assert_int_equal(last_status().state, APP_IDLE);
    assert_int_equal(app.bus.e2e_errors, 1);
}

static void test_host_silence_faults_and_ramps(void **state)
{
    (void)state;
    ticks(5);
    send_heartbeat();
    send_command(APP_CMD_TEACH, 0);
    for (unsigned i = 0; i < 50; i++) {
        if (i % 10 == 0) {
            send_heartbeat();
        }
        tick();
    }
    assert_int_equal(app.state, APP_TEACH);
    /* silence: the last heartbeat was at tick 40 of the loop above */
    unsigned fault_tick = 0;
    for (unsigned i = 0; i < 200 && fault_tick == 0; i++) {
        tick();
        if (app.state == APP_FAULT) {
            fault_tick = i + 1u + 10u; /* ms since the last heartbeat */
        }
    }
    assert_int_equal(app.saf_out.fault_code, FLT_HOST_SILENCE);
    assert_true(fault_tick >= WDG_TIMEOUT_DEFAULT_MS && fault_tick <= WDG_TIMEOUT_DEFAULT_MS + 2u);
    /* an emergency frame with the code */
    bool emcy = false;
    for (unsigned i = 0; i < n_out; i++) {
        if (out[i].id == PROTO_ID_EMERGENCY(0)) {
            struct fs_dbc_emergency_t e;
            assert_int_equal(fs_dbc_emergency_unpack(&e, out[i].data, 8), 0);
            assert_int_equal(e.fault_code, FLT_HOST_SILENCE);
            emcy = true;
        }
    }
    assert_true(emcy);
    ticks(60);
    bool en = true;
    fs_real_t f[2];
    hal_host_get_actuator(&en, f);
    assert_false(en); /* ramped and disabled within 50 ms */
    /* stays in FAULT; a TEACH command is ignored; clearing (with the host back) goes to IDLE */
    send_command(APP_CMD_TEACH, 0);
    ticks(10);
    assert_int_equal(app.state, APP_FAULT);
    send_heartbeat();
    send_command(APP_CMD_CLEAR_FAULT, 0);
    ticks(10);
    assert_int_equal(app.state, APP_IDLE);
    assert_int_equal(last_status().fault_code, 0);
}

/* Bus-off: BUS_OFF latches in the same tick; its emergency frame cannot leave while the controller
 * is off the bus, stays queued, and is the first frame sent after recovery (E2E counter intact). */
static void test_bus_off_emergency_sent_after_recovery(void **state)
{
    (void)state;
    ticks(5);
    send_heartbeat();
    tick();
    hal_sim_can_set_bus_off(true);
    tick();
    assert_int_equal(app.state, APP_FAULT);
    assert_int_equal(app.saf_out.fault_code, FLT_BUS_OFF);
    for (unsigned i = 0; i < 30; i++) {
        if (i % 10 == 0) {
            send_heartbeat();
        }
        tick();
    }
    const unsigned before = n_out;
    hal_sim_can_set_bus_off(false);
    tick();
    /* the heartbeats lost meanwhile are within the freshness window: the next one is taken */
    const uint32_t accepted = app.auth.secoc.accepted;
    send_heartbeat();
    assert_true(n_out > before);
    assert_int_equal(out[before].id, PROTO_ID_EMERGENCY(0));
    e2e_rx_t rx;
    e2e_rx_reset(&rx);
    assert_int_equal(e2e_check(&rx, &out[before]), PROTO_OK);
    struct fs_dbc_emergency_t e;
    assert_int_equal(fs_dbc_emergency_unpack(&e, out[before].data, 8), 0);
    assert_int_equal(e.fault_code, FLT_BUS_OFF);
    unsigned n_emcy = 0;
    for (unsigned i = 0; i < n_out; i++) {
        n_emcy += out[i].id == PROTO_ID_EMERGENCY(0) ? 1u : 0u;
    }
    assert_int_equal(n_emcy, 1); /* once, not repeated */
    ticks(20);
    for (unsigned i = before + 1u; i < n_out; i++) {
        assert_int_not_equal(out[i].id, PROTO_ID_EMERGENCY(0));
    }
    assert_int_equal(app.auth.secoc.accepted, accepted + 1u);
}

/* RequestDownload and one TransferData of img into slot, no RequestTransferExit yet. */
static void download_data_only(uint8_t slot, const uint8_t *img, uint32_t len)
{
    uint8_t r[64];
    const uint8_t rd[6] = {0x34, 0x00, 0x21, slot, (uint8_t)(len >> 8), (uint8_t)len};
    assert_int_equal(uds(rd, 6, r, sizeof(r)), 4);
    static uint8_t td[4096];
    td[0] = 0x36;
    td[1] = 0x01;
    memcpy(&td[2], img, len);
    assert_int_equal(uds(td, (uint16_t)(len + 2u), r, sizeof(r)), 2);
}

static void test_download_corrupt_interrupted(void **state)
{
    (void)state;
    len_a = load("press_n50_ridge_release.skill", image_a);
    len_b = load("press_n10_ridge_release.skill", image_b);
    unlock(UDS_SESSION_PROGRAMMING);
    assert_int_equal(download(1, image_a, len_a, UINT32_MAX), 0x00);
    assert_true(app.slots.valid[0]);
    assert_int_equal(app.slots.skill[0].dmp.n_kernels, 50);
    /* corrupted: one flipped byte -> CRC fails at exit, slot 1 keeps the N = 50 skill */
    static uint8_t bad[APP_IMAGE_MAX];
    memcpy(bad, image_b, len_b);
    bad[150] ^= 0x10;
    assert_int_equal(download(1, bad, len_b, UINT32_MAX), UDS_NRC_PROGRAMMING_FAILURE);
    assert_int_equal(app.slots.last_transfer_status, FS_ERR_SKILL_CRC);
    assert_int_equal(app.slots.skill[0].dmp.n_kernels, 50);
    /* interrupted: half of the data, then the tester leaves (S3 timeout) */
    assert_int_equal(download(1, image_b, len_b, len_b / 2u), 0xFF);
    ticks(UDS_S3_MS + 10u);
    assert_int_equal(app.diag.uds.session, UDS_SESSION_DEFAULT);
    assert_int_equal(app.slots.last_transfer_status, 0xFFFEu);
    /* after a reboot (flash kept) slot 1 still holds the N = 50 skill */
    app_init(&app, &cfg);
    ticks(2);
    assert_true(app.slots.valid[0]);
    assert_int_equal(app.slots.skill[0].dmp.n_kernels, 50);
    assert_int_equal(app.slots.len[0], len_a);
}

static void test_execute_and_refusals(void **state)
{
    (void)state;
    len_a = load("press_n10_ridge_release.skill", image_a);
    unlock(UDS_SESSION_PROGRAMMING);
    assert_int_equal(download(2, image_a, len_a, UINT32_MAX), 0x00);
    uint8_t r[64];
    unlock(UDS_SESSION_EXTENDED); /* a run is started by the unlocked host session */
    /* empty slot -> out of range; valid slot -> EXECUTE */
    const uint8_t run_empty[10] = {0x31, 0x01, 0x02, 0x01, 5, 0x03, 0xE8, 0x03, 0xE8, 0};
    assert_int_equal(uds(run_empty, 10, r, sizeof(r)), 3);
    assert_int_equal(r[2], UDS_NRC_REQUEST_OUT_OF_RANGE);
    send_heartbeat();
    const uint8_t run2[10] = {0x31, 0x01, 0x02, 0x01, 2, 0x03, 0xE8, 0x03, 0xE8, 0};
    assert_int_equal(uds(run2, 10, r, sizeof(r)), 4);
    assert_int_equal(app.state, APP_EXECUTE);
    /* while executing: programming session and configuration writes refused (0x22) */
    send_heartbeat();
    const uint8_t prog[2] = {0x10, 0x02};
    assert_int_equal(uds(prog, 2, r, sizeof(r)), 3);
    assert_int_equal(r[2], UDS_NRC_CONDITIONS_NOT_CORRECT);
    /* stop -> IDLE; stop again -> sequence error */
    send_heartbeat();
    const uint8_t stop[4] = {0x31, 0x02, 0x02, 0x01};
    assert_int_equal(uds(stop, 4, r, sizeof(r)), 4);
    assert_int_equal(app.state, APP_IDLE);
    assert_int_equal(uds(stop, 4, r, sizeof(r)), 3);
    assert_int_equal(r[2], UDS_NRC_REQUEST_SEQUENCE_ERROR);
    /* unknown DID and routine */
    const uint8_t rd[3] = {0x22, 0x12, 0x34};
    assert_int_equal(uds(rd, 3, r, sizeof(r)), 3);
    assert_int_equal(r[2], UDS_NRC_REQUEST_OUT_OF_RANGE);
    const uint8_t ver[3] = {0x22, 0xF1, 0x89};
    const uint16_t n = uds(ver, 3, r, sizeof(r));
    assert_int_equal(n, 3u + strlen(APP_SW_VERSION));
    assert_memory_equal(&r[3], APP_SW_VERSION, strlen(APP_SW_VERSION));
}

/* One tick of a port that restarts the firmware when it asks (as hil_sim serve does: flash kept,
 * CAN queues cleared, so frames still queued at the reset are lost with it), then the bus takes
 * what the device queued. True if the device restarted in this tick. */
static bool tick_port(void)
{
    t_us += 1000u;
    hal_host_set_time_us(t_us);
    app_tick(&app, false);
    uint8_t type = 0u;
    const bool restarted = hal_host_take_reset(&type);
    if (restarted) {
        hal_sim_can_reset();
        app_init(&app, &cfg);
    }
    can_frame_t f;
    while (hal_sim_can_tx_peek(&f)) {
        if (n_out < OUTCAP) {
            out[n_out++] = f;
        }
        hal_sim_can_tx_pop();
    }
    return restarted;
}

/* ECUReset request; returns the response length (0: none) and the ticks at which the response
 * reached the bus and the device restarted (UINT32_MAX: never, within 500 ticks). */
static uint16_t ecu_reset(uint8_t sub, uint8_t *resp, uint32_t *t_resp, uint32_t *t_reset)
{
    const uint8_t req[2] = {0x11, sub};
    assert_int_equal(isotp_send(&tester, req, 2, t_us), PROTO_OK);
    uint16_t n = 0u;
    *t_resp = *t_reset = UINT32_MAX;
    for (uint32_t k = 0; k < 500u && (*t_reset == UINT32_MAX || k < *t_reset + 20u); k++) {
        isotp_poll(&tester, t_us);
        const unsigned before = n_out;
        if (tick_port() && *t_reset == UINT32_MAX) {
            *t_reset = k;
        }
        for (unsigned i = before; i < n_out; i++) {
            isotp_on_frame(&tester, &out[i], t_us);
        }
        const uint8_t *r = NULL;
        const uint16_t m = isotp_rx_peek(&tester, &r);
        if (m != 0u) {
            assert_int_equal(n, 0u); /* one response only */
            n = m;
            memcpy(resp, r, m < 8u ? m : 8u);
            *t_resp = k;
            isotp_rx_release(&tester);
        }
    }
    return n;
}

static void test_ecu_reset_responds_then_resets(void **state)
{
    (void)state;
    len_a = load("press_n10_ridge_release.skill", image_a);
    unlock(UDS_SESSION_PROGRAMMING);
    assert_int_equal(download(1, image_a, len_a, UINT32_MAX), 0x00);
    /* hard reset: the positive response 51 01 reaches the bus, then the device restarts at the
     * next tick (ISO 14229-1: response before reset), in the default session, skill kept */
    uint8_t r[8];
    uint32_t t_resp = 0u, t_reset = 0u;
    assert_int_equal(ecu_reset(0x01, r, &t_resp, &t_reset), 2);
    assert_int_equal(r[0], 0x51);
    assert_int_equal(r[1], 0x01);
    assert_int_not_equal(t_reset, UINT32_MAX);
    assert_true(t_resp < t_reset);
    assert_true(t_reset - t_resp <= 2u);
    assert_int_equal(app.diag.uds.session, UDS_SESSION_DEFAULT);
    assert_true(app.slots.valid[0]);
    assert_int_equal(app.slots.len[0], len_a);
    ticks(2);
    assert_int_equal(app.state, APP_IDLE);
    assert_false(app.auth.secoc.keyed); /* the motion key does not survive a reset */
    /* soft reset with the positive response suppressed (bit 7): no answer, reset all the same */
    assert_int_equal(ecu_reset(0x83, r, &t_resp, &t_reset), 0);
    assert_int_not_equal(t_reset, UINT32_MAX);
    assert_true(t_reset <= 2u);
    /* refused while executing: 7F 11 22 and no reset */
    host_session(); /* the host's new session after the reset */
    unlock(UDS_SESSION_PROGRAMMING);
    uint8_t rr[64];
    unlock(UDS_SESSION_EXTENDED);
    send_heartbeat();
    const uint8_t run1[10] = {0x31, 0x01, 0x02, 0x01, 1, 0x03, 0xE8, 0x03, 0xE8, 0};
    assert_int_equal(uds(run1, 10, rr, sizeof(rr)), 4);
    assert_int_equal(app.state, APP_EXECUTE);
    send_heartbeat();
    assert_int_equal(ecu_reset(0x01, r, &t_resp, &t_reset), 3);
    assert_int_equal(r[0], 0x7F);
    assert_int_equal(r[2], UDS_NRC_CONDITIONS_NOT_CORRECT);
    assert_int_equal(t_reset, UINT32_MAX);
}


/* ---- SecurityAccess levels, firmware confirm, slot changes only while idle ---- */

static uint8_t nrc_of(const uint8_t *req, uint16_t len)
{
    uint8_t r[64];
    (void)uds(req, len, r, sizeof(r));
    return r[0] == 0x7F ? r[2] : 0x00;
}

/* 0x0F02 (confirm firmware) and 0x0F01 need level 3 in the programming session: refused with
 * securityAccessDenied in the default session and with level 1; the level-3 secret differs from
 * the level-1 secret; settings and slots need level 1, not level 3. */
static void test_security_levels_and_confirm(void **state)
{
    (void)state;
    ticks(5);
    const uint8_t confirm[4] = {0x31, 0x01, 0x0F, 0x02};
    const uint8_t mark[5] = {0x31, 0x01, 0x0F, 0x01, 0x00};
    assert_int_equal(nrc_of(confirm, 4), UDS_NRC_SECURITY_ACCESS_DENIED); /* default session */
    unlock(UDS_SESSION_PROGRAMMING);
    assert_int_equal(nrc_of(confirm, 4), UDS_NRC_SECURITY_ACCESS_DENIED); /* level 1 only */
    assert_int_equal(nrc_of(mark, 5), UDS_NRC_SECURITY_ACCESS_DENIED);
    /* level 3 with the level-1 secret: invalid key */
    assert_int_equal(unlock_with(UDS_SESSION_PROGRAMMING, 0x03, 0x01), UDS_NRC_INVALID_KEY);
    assert_memory_not_equal(app_sec_config(&app, 1)->secret, app_sec_config(&app, 3)->secret,
                            app_sec_config(&app, 1)->secret_len);
    /* level 3 with its own secret: firmware routines allowed, settings and slots are not */
    assert_int_equal(unlock_with(UDS_SESSION_PROGRAMMING, 0x03, 0x03), 0);
    assert_int_equal(nrc_of(confirm, 4), 0x00); /* not on test: nothing to confirm, ok */
    const uint8_t wr[23] = {0x2E, 0x01, 0x00};
    assert_int_equal(nrc_of(wr, 23), UDS_NRC_SECURITY_ACCESS_DENIED);
    const uint8_t erase[5] = {0x31, 0x01, 0xFF, 0x00, 1};
    assert_int_equal(nrc_of(erase, 5), UDS_NRC_SECURITY_ACCESS_DENIED);
    len_a = load("press_n10_ridge_release.skill", image_a);
    assert_int_equal(download(1, image_a, len_a, UINT32_MAX), UDS_NRC_SECURITY_ACCESS_DENIED);
    assert_false(app.slots.valid[0]);
    /* level 3 needs the programming session */
    uint8_t r[64];
    const uint8_t ext[2] = {0x10, 0x03};
    assert_int_equal(uds(ext, 2, r, sizeof(r)), 6);
    const uint8_t seed3[2] = {0x27, 0x03};
    assert_int_equal(nrc_of(seed3, 2), UDS_NRC_SUBFUNCTION_NOT_IN_SESSION);
}

/* A new image on its test boot whose self-test fails serves nothing from the bus in its boot
 * tick (a confirm request from another node goes unanswered) and asks for the reset that makes
 * the bootloader revert; it never reaches IDLE. */
static void test_failing_test_image_serves_nothing(void **state)
{
    (void)state;
    app.fw.boot.test_boot = 1u; /* on test ... */
    app.slots.nvm_ok = false;   /* ... and its self-test fails (storage unreadable) */
    uint8_t type = 0u;
    (void)hal_host_take_reset(&type);
    const uint8_t confirm[4] = {0x31, 0x01, 0x0F, 0x02};
    assert_int_equal(isotp_send(&tester, confirm, 4, t_us), PROTO_OK);
    isotp_poll(&tester, t_us);
    const unsigned before = n_out;
    tick();
    assert_int_equal(app.state, APP_BOOT);
    assert_true(hal_host_take_reset(&type));
    for (unsigned i = before; i < n_out; i++) {
        assert_int_not_equal(out[i].id, PROTO_ID_UDS_RESPONSE(0));
    }
    assert_int_equal(app.fw.boot.test_boot, 1u); /* not confirmed */
}

static uint8_t wrong_key(void)
{
    uint8_t r[64];
    const uint8_t seed_req[2] = {0x27, 0x01};
    (void)uds(seed_req, 2, r, sizeof(r));
    if (r[0] == 0x7F) {
        return r[2];
    }
    uint8_t key[2 + SEC_KEY_LEN] = {0x27, 0x02};
    memset(&key[2], 0xA5, SEC_KEY_LEN);
    (void)uds(key, sizeof(key), r, sizeof(r));
    return r[0] == 0x7F ? r[2] : 0x00;
}

static uint16_t ecu_reset(uint8_t sub, uint8_t *resp, uint32_t *t_resp, uint32_t *t_reset);

/* n ms with TesterPresent every second (the session stays) */
static void ticks_present(unsigned n)
{
    uint8_t r[8];
    const uint8_t tp[2] = {0x3E, 0x00};
    for (unsigned i = 0; i < n; i += 1000u) {
        assert_int_equal(uds(tp, 2, r, sizeof(r)), 2);
        ticks(n - i < 1000u ? n - i : 1000u);
    }
}

/* The wrong-key counter and its lockout survive ECUReset and power-up: a node that resets the
 * device after every wrong key gets 3 guesses, then waits the full lockout (10 s) again after
 * every reset; a guesser that resets in a loop gets at most 3 wrong keys per 12 s. */
static void test_wrong_key_counter_survives_reset(void **state)
{
    (void)state;
    uint8_t r[64];
    const uint8_t prog[2] = {0x10, 0x02};
    assert_int_equal(uds(prog, 2, r, sizeof(r)), 6);
    ticks(1100);
    assert_int_equal(wrong_key(), UDS_NRC_INVALID_KEY);
    uint32_t t_resp = 0u, t_reset = 0u;
    assert_int_equal(ecu_reset(0x01, r, &t_resp, &t_reset), 2);
    assert_int_equal(uds(prog, 2, r, sizeof(r)), 6);
    ticks(1100); /* delay after a wrong key, from power-up */
    assert_int_equal(wrong_key(), UDS_NRC_INVALID_KEY);
    assert_int_equal(ecu_reset(0x01, r, &t_resp, &t_reset), 2);
    assert_int_equal(uds(prog, 2, r, sizeof(r)), 6);
    ticks(1100);
    assert_int_equal(wrong_key(), UDS_NRC_EXCEEDED_ATTEMPTS); /* the third, across two resets */
    /* power-up (flash kept): the lockout runs again from power-up */
    hal_sim_can_reset();
    app_init(&app, &cfg);
    assert_int_equal(uds(prog, 2, r, sizeof(r)), 6);
    ticks_present(9000);
    assert_int_equal(wrong_key(), UDS_NRC_DELAY_NOT_EXPIRED);
    ticks_present(1100);
    assert_int_equal(wrong_key(), UDS_NRC_INVALID_KEY); /* lockout over: counter 1 */

    /* a guesser that resets after every attempt, 12 s of simulated time */
    hal_host_flash_erase();
    hal_sim_can_reset();
    app_init(&app, &cfg);
    const uint64_t t_end = t_us + 12000000u;
    unsigned guesses = 0u;
    while (t_us < t_end) {
        assert_int_equal(uds(prog, 2, r, sizeof(r)), 6);
        uint8_t nrc = wrong_key();
        while (nrc == UDS_NRC_DELAY_NOT_EXPIRED && t_us < t_end) {
            ticks(100); /* asks again until the delay is over */
            nrc = wrong_key();
        }
        guesses += (nrc == UDS_NRC_INVALID_KEY || nrc == UDS_NRC_EXCEEDED_ATTEMPTS) ? 1u : 0u;
        assert_int_equal(ecu_reset(0x01, r, &t_resp, &t_reset), 2);
    }
    print_message("wrong keys in 12 s with a reset after each: %u\n", guesses);
    assert_true(guesses <= 3u);
}

/* A slot's content cannot change while a skill executes: a download announced and sent in IDLE
 * whose RequestTransferExit comes after a run started is refused with 0x22 and the slot keeps
 * the running skill; RequestDownload and erase are refused with 0x22 too. */
static void test_commit_refused_while_executing(void **state)
{
    (void)state;
    len_a = load("press_n10_ridge_release.skill", image_a);
    len_b = load("press_n50_ridge_release.skill", image_b);
    unlock(UDS_SESSION_PROGRAMMING);
    assert_int_equal(download(2, image_a, len_a, UINT32_MAX), 0x00);
    const uint8_t rd[6] = {0x34, 0x00, 0x21, 2, (uint8_t)(len_b >> 8), (uint8_t)len_b};
    download_data_only(2, image_b, len_b);
    send_heartbeat();
    const uint8_t run2[10] = {0x31, 0x01, 0x02, 0x01, 2, 0x03, 0xE8, 0x03, 0xE8, 0};
    assert_int_equal(nrc_of(run2, 10), 0x00);
    assert_int_equal(app.state, APP_EXECUTE);
    send_heartbeat();
    const uint8_t exit_req[1] = {0x37};
    assert_int_equal(nrc_of(exit_req, 1), UDS_NRC_CONDITIONS_NOT_CORRECT);
    assert_int_equal(app.slots.skill[1].dmp.n_kernels, 10);
    assert_int_equal(app.slots.len[1], len_a);
    send_heartbeat();
    assert_int_equal(nrc_of(rd, 6), UDS_NRC_CONDITIONS_NOT_CORRECT);
    send_heartbeat();
    const uint8_t erase[5] = {0x31, 0x01, 0xFF, 0x00, 2};
    assert_int_equal(nrc_of(erase, 5), UDS_NRC_CONDITIONS_NOT_CORRECT);
    assert_true(app.slots.valid[1]);
    /* the stored record is the running one too */
    uint32_t len = 0u;
    assert_int_equal(nvm_read(&app.slots.nvm, 1u, app.slots.image, sizeof(app.slots.image), &len),
                     NVM_OK);
    assert_int_equal(len, len_a);
    assert_memory_equal(app.slots.image, image_a, len_a);
}


/* The device validates a skill before committing it: weights x100 (in range) make the rollout at
 * goal 1 peak far above 50 N -> RequestTransferExit refused (0x72), DID 0x0201 = 223, slot
 * unchanged; tau 1e-9 -> 220. Run: a goal scale that takes the peak above the force limit is
 * refused (0x31) before any motion, one just below it starts. */
static void test_skill_validated_before_commit_and_run(void **state)
{
    (void)state;
    len_a = load("press_n50_lwr_hold.skill", image_a);
    unlock(UDS_SESSION_PROGRAMMING);
    uint8_t r[64];
    download_data_only(1, image_a, len_a);
    const uint32_t t0 = app.tick;
    const uint8_t exit_req[1] = {0x37};
    assert_int_equal(uds(exit_req, 1, r, sizeof(r)), 5); /* after 0x78, the CRC */
    print_message("commit of a 1.5 s skill (N = 50): %u ticks from RequestTransferExit to its "
                  "answer\n",
                  (unsigned)(app.tick - t0));
    /* one stage after the other, each bounded per tick: the parse (v2, N = 50: CRC 42 units of
     * 32 bytes, finiteness 42 of 4 fields, widths, centres and values 50 each, 5 header stages,
     * the model's derivation 32 units of 8 (4 scalar checks and 5 passes of 50 kernels, the y
     * weights' one step): 271 units), the parameters (1 tick), the rollout (1,500 steps), the
     * flash write (1,340 bytes: CRC 21 slices of 64, erase 1, program 1 + 6 pieces of 256,
     * read-back 1 + 6, commit 1, scan of the new copy 1 + 21 slices and of the empty one 1: 60
     * units) */
    const uint32_t parse_ticks = (271u + SLOTS_PARSE_UNITS_PER_TICK - 1u) /
                                 SLOTS_PARSE_UNITS_PER_TICK;
    const uint32_t check_ticks = (1500u + SLOTS_CHECK_STEPS_PER_TICK - 1u) /
                                 SLOTS_CHECK_STEPS_PER_TICK;
    const uint32_t write_ticks = (60u + SLOTS_FLASH_UNITS_PER_TICK - 1u) /
                                 SLOTS_FLASH_UNITS_PER_TICK;
    assert_int_equal(len_a, 1340u);
    /* then the cache: the checked skill copied in SLOTS_SWAP_BYTES_PER_TICK pieces */
    const uint32_t swap_ticks = ((uint32_t)sizeof(skill_t) + SLOTS_SWAP_BYTES_PER_TICK - 1u) /
                                SLOTS_SWAP_BYTES_PER_TICK;
    /* and the set-up of each of the five stages (parse, parameters, rollout, write, cache) a
     * tick of its own */
    assert_int_equal(app.tick - t0, 5u + parse_ticks + 1u + check_ticks + write_ticks + swap_ticks);
    const fs_real_t peak = app.slots.peak_N[0];
    assert_true(peak > FS_R(4.8) && peak < FS_R(4.9)); /* the reference rollout: 4.842 N */
    /* weights x100, CRC recomputed: a well-formed image whose output exceeds the limit */
    memcpy(image_b, image_a, len_a);
    const uint16_t n = app.slots.skill[0].dmp.n_kernels;
    for (uint16_t i = 0; i < n; i++) {
        double w;
        memcpy(&w, &image_b[SKILL_HEADER_SIZE_V2 + 16u * n + 8u * i], 8);
        w *= 100.0;
        memcpy(&image_b[SKILL_HEADER_SIZE_V2 + 16u * n + 8u * i], &w, 8);
    }
    uint32_t crc = skill_crc32(0u, image_b, len_a - 4u);
    memcpy(&image_b[len_a - 4u], &crc, 4);
    assert_int_equal(download(1, image_b, len_a, UINT32_MAX), UDS_NRC_PROGRAMMING_FAILURE);
    assert_int_equal(app.slots.last_transfer_status, FS_ERR_SKCHK_PEAK);
    assert_true(app.slots.peak_N[0] == peak);
    uint32_t len = 0u;
    assert_int_equal(nvm_read(&app.slots.nvm, 0u, app.slots.image, sizeof(app.slots.image), &len),
                     NVM_OK);
    assert_memory_equal(app.slots.image, image_a, len_a);
    /* tau = 1e-9 (header offset of tau: 24): parameter range */
    memcpy(image_b, image_a, len_a);
    const double tau = 1e-9;
    memcpy(&image_b[24], &tau, 8);
    crc = skill_crc32(0u, image_b, len_a - 4u);
    memcpy(&image_b[len_a - 4u], &crc, 4);
    assert_int_equal(download(2, image_b, len_a, UINT32_MAX), UDS_NRC_PROGRAMMING_FAILURE);
    assert_true(app.slots.last_transfer_status == FS_ERR_SKCHK_RANGE ||
                app.slots.last_transfer_status == FS_ERR_SKILL_GAINS);
    assert_false(app.slots.valid[1]);
    /* run: goal scale 10.4 x 4.84 N > 50 N refused before any motion; 10.2 starts */
    send_heartbeat();
    const uint16_t g_over = (uint16_t)(50.0 / (double)peak * 1000.0 * 1.005);
    const uint16_t g_under = (uint16_t)(50.0 / (double)peak * 1000.0 * 0.995);
    uint8_t run[10] = {0x31, 0x01, 0x02, 0x01, 1, (uint8_t)(g_over >> 8), (uint8_t)g_over,
                       0x03, 0xE8, 0};
    assert_int_equal(uds(run, 10, r, sizeof(r)), 3);
    assert_int_equal(r[2], UDS_NRC_REQUEST_OUT_OF_RANGE);
    assert_int_equal(app.ctl.last_run_status, FS_ERR_SKCHK_GOAL_SCALE);
    assert_int_equal(app.state, APP_IDLE);
    assert_true(app.force_out_N[0] == FS_R(0.0) && app_force_ref_N(&app) == FS_R(0.0));
    send_heartbeat();
    run[5] = (uint8_t)(g_under >> 8);
    run[6] = (uint8_t)g_under;
    assert_int_equal(uds(run, 10, r, sizeof(r)), 4);
    assert_int_equal(app.state, APP_EXECUTE);
}

/* A read-back (RequestUpload) reads the slot's record and checks its CRC in slices: the device
 * answers 0x78 at once, serves nothing else meanwhile (0x21), and answers positively after
 * 1 + ceil(len / NVM_READ_CHUNK) units (SLOTS_READ_UNITS_PER_TICK a tick); the data read back is
 * the image downloaded. A size other than the stored one is refused (0x31) once the read ends. */
static void test_read_back_in_slices(void **state)
{
    (void)state;
    len_a = load("press_n50_lwr_hold.skill", image_a);
    unlock(UDS_SESSION_PROGRAMMING);
    assert_int_equal(download(1, image_a, len_a, UINT32_MAX), 0x00);
    const uint8_t ru[6] = {0x35, 0x00, 0x21, 1, (uint8_t)(len_a >> 8), (uint8_t)len_a};
    assert_int_equal(isotp_send(&tester, ru, 6, t_us), PROTO_OK);
    const uint32_t t0 = app.tick;
    bool pending = false, busy = false;
    uint8_t r[64];
    uint16_t n = 0u;
    for (unsigned k = 0; k < 2000u && n == 0u; k++) {
        isotp_poll(&tester, t_us);
        const unsigned before = n_out;
        tick();
        for (unsigned i = before; i < n_out; i++) {
            isotp_on_frame(&tester, &out[i], t_us);
        }
        const uint8_t *rx = NULL;
        const uint16_t m = isotp_rx_peek(&tester, &rx);
        if (m >= 3u && rx[0] == 0x7F && rx[1] == 0x35 && rx[2] == 0x78) {
            pending = true;
            isotp_rx_release(&tester);
            if (!busy) { /* another request while the read runs */
                const uint8_t tp[2] = {0x3E, 0x00};
                assert_int_equal(isotp_send(&tester, tp, 2, t_us), PROTO_OK);
            }
        } else if (m >= 3u && rx[0] == 0x7F && rx[1] == 0x3E) {
            busy = rx[2] == UDS_NRC_BUSY_REPEAT_REQUEST;
            isotp_rx_release(&tester);
        } else if (m != 0u) {
            assert_true(m <= sizeof(r));
            memcpy(r, rx, m);
            n = m;
            isotp_rx_release(&tester);
        }
    }
    assert_true(pending);
    assert_true(busy);
    assert_int_equal(n, 4);
    assert_int_equal(r[0], 0x75);
    const uint32_t units = 1u + (len_a + NVM_READ_CHUNK - 1u) / NVM_READ_CHUNK;
    const uint32_t want = (units + SLOTS_READ_UNITS_PER_TICK - 1u) / SLOTS_READ_UNITS_PER_TICK;
    print_message("read-back of %u bytes: answered after %u ticks (%u units)\n", (unsigned)len_a,
                  (unsigned)(app.tick - t0), (unsigned)units);
    assert_true(app.tick - t0 >= want);
    assert_true(app.tick - t0 <= want + 2u);
    static uint8_t back[4096];
    uint32_t got = 0u;
    for (uint8_t c = 1u; got < len_a; c++) {
        static uint8_t rr[4096];
        const uint8_t td[2] = {0x36, c};
        const uint16_t m = uds(td, 2, rr, sizeof(rr));
        assert_true(m > 2u && rr[0] == 0x76);
        memcpy(&back[got], &rr[2], m - 2u);
        got += m - 2u;
    }
    assert_int_equal(got, len_a);
    assert_memory_equal(back, image_a, len_a);
    const uint8_t exit_req[1] = {0x37};
    assert_int_equal(uds(exit_req, 1, r, sizeof(r)), 1);
    const uint8_t wrong[6] = {
        0x35, 0x00, 0x21, 1, (uint8_t)((len_a + 1u) >> 8), (uint8_t)(len_a + 1u)};
    assert_int_equal(nrc_of(wrong, 6), UDS_NRC_REQUEST_OUT_OF_RANGE);
    const uint8_t empty[6] = {0x35, 0x00, 0x21, 3, 0x01, 0x00};
    assert_int_equal(nrc_of(empty, 6), UDS_NRC_UPLOAD_DOWNLOAD_NOT_ACCEPTED);
}

/* While a download's commit runs (0x78 sent), a start is refused (the HostCommand frame and the
 * UDS routine alike: the UDS server answers busy) and the slot keeps its old skill; the commit
 * then completes and the new skill starts. */
static void test_start_refused_during_commit(void **state)
{
    (void)state;
    len_a = load("press_n10_ridge_release.skill", image_a);
    len_b = load("press_n50_ridge_release.skill", image_b);
    unlock(UDS_SESSION_PROGRAMMING);
    assert_int_equal(download(1, image_a, len_a, UINT32_MAX), 0x00);
    download_data_only(1, image_b, len_b);
    const uint8_t exit_req[1] = {0x37};
    assert_int_equal(isotp_send(&tester, exit_req, 1, t_us), PROTO_OK);
    isotp_poll(&tester, t_us);
    ticks(5);
    assert_true(slots_committing(&app.slots));
    send_heartbeat();
    send_command(APP_CMD_EXECUTE, 1);
    ticks(2);
    assert_int_equal(app.state, APP_IDLE);                  /* refused: the commit runs */
    assert_int_equal(app.slots.skill[0].dmp.n_kernels, 10); /* not yet replaced */
    assert_true(slots_committing(&app.slots));
    for (unsigned k = 0; k < 2000u && slots_committing(&app.slots);
         k++) { /* the commit completes */
        tick();
    }
    assert_false(slots_committing(&app.slots));
    assert_int_equal(app.slots.last_transfer_status, 0u);
    assert_int_equal(app.slots.skill[0].dmp.n_kernels, 50);
    send_heartbeat();
    send_command(APP_CMD_EXECUTE, 1);
    ticks(3); /* one MAC a tick: heartbeat, RUN_OPTIONS, EXECUTE */
    assert_int_equal(app.state, APP_EXECUTE);
}

/* A forged frame on the host's id, its CRC valid and its MAC not (what any node can send). */
static void deliver_forged(uint32_t id, uint8_t mode, uint32_t fv)
{
    can_frame_t f = {.id = id, .len = 8};
    memset(f.data, 0, 8);
    f.data[0] = mode;
    f.data[SECOC_MAC_OFFSET] = 0x5Au;
    f.data[SECOC_FV_BYTE] = (uint8_t)fv;
    e2e_protect(&f, (uint8_t)(fv & E2E_COUNTER_MASK));
    (void)hal_sim_can_deliver(&f);
}

/* The host build verifies every frame of a tick in that tick, oldest first: three authentic
 * heartbeats and a forged one are all judged in the tick they arrived. */
static void test_every_mac_in_its_tick(void **state)
{
    (void)state;
    ticks(5);
    const uint32_t acc0 = app.auth.secoc.accepted, bad0 = app.auth.secoc.bad_mac;
    for (int i = 0; i < 3; i++) {
        send_heartbeat();
    }
    deliver_forged(PROTO_ID_HOST_HEARTBEAT(0), 0u, host.fv[SECOC_CH_HEARTBEAT] + 1u);
    tick();
    assert_int_equal(app.auth.secoc.accepted, acc0 + 3u);
    assert_int_equal(app.auth.secoc.bad_mac, bad0 + 1u);
    assert_int_equal(app.auth.macq.count, 0u);
}

/* A stop is never blocked: a forged command carrying the counter the host's stop will carry
 * (which once moved the E2E counter before its MAC was checked) changes nothing, and the host's
 * IDLE stops the run in the tick it arrives. Positive control: the same path with no forged frame
 * in between runs and stops alike. */
static void test_forged_counter_never_blocks_a_stop(void **state)
{
    (void)state;
    for (int forge = 0; forge < 2; forge++) {
        send_heartbeat();
        send_command(APP_CMD_TEACH, 0);
        tick();
        assert_int_equal(app.state, APP_TEACH);
        const uint32_t next = host.fv[SECOC_CH_COMMAND] + 1u;
        if (forge != 0) {
            deliver_forged(PROTO_ID_HOST_COMMAND(0), APP_CMD_NONE, next);
            tick();
            assert_int_equal(app.state, APP_TEACH); /* refused: nothing recorded */
        }
        send_command(APP_CMD_IDLE, 0);
        tick();
        assert_int_equal(app.state, APP_IDLE);
        send_heartbeat();
        tick();
    }
    /* any node's IDLE, its MAC and counter anything, stops too */
    send_command(APP_CMD_TEACH, 0);
    tick();
    assert_int_equal(app.state, APP_TEACH);
    deliver_forged(PROTO_ID_HOST_COMMAND(0), APP_CMD_IDLE, 0u);
    tick();
    assert_int_equal(app.state, APP_IDLE);
}

/* A command withheld from the bus never acts late: after a heartbeat that carries a newer command
 * freshness (it is refused as a replay), or more than APP_CMD_FRESH_MS after the host's previous
 * frame, or after a UDS run stop or fault clear with no heartbeat between (refused as stale).
 * Positive control: the same frames delivered on time run the skill. */
static void test_withheld_command_never_acts_late(void **state)
{
    (void)state;
    len_a = load("press_n10_ridge_release.skill", image_a);
    unlock(UDS_SESSION_PROGRAMMING);
    assert_int_equal(download(1, image_a, len_a, UINT32_MAX), 0x00);
    send_heartbeat();
    tick();
    /* the pair on time: runs (positive control) */
    send_command(APP_CMD_EXECUTE, 1);
    tick();
    assert_int_equal(app.state, APP_EXECUTE);
    send_command(APP_CMD_IDLE, 0);
    send_heartbeat();
    tick();
    assert_int_equal(app.state, APP_IDLE);
    /* the pair withheld, a heartbeat after it: refused when delivered */
    can_frame_t held[2];
    const uint32_t hb_before = host.fv[SECOC_CH_HEARTBEAT];
    for (int i = 0; i < 2; i++) {
        struct fs_dbc_host_command_t c = {0};
        c.mode = i == 0 ? APP_CMD_RUN_OPTIONS : APP_CMD_EXECUTE;
        c.slot = 1u;
        c.goal_scale = 1000u;
        c.time_scale = 1000u;
        held[i] = (can_frame_t){.id = PROTO_ID_HOST_COMMAND(0), .len = 8};
        (void)fs_dbc_host_command_pack(held[i].data, &c, 8);
        const uint32_t fv = secoc_protect(&host, &held[i], SECOC_CH_COMMAND);
        e2e_protect(&held[i], (uint8_t)(fv & E2E_COUNTER_MASK));
    }
    send_heartbeat();
    tick();
    assert_int_equal(host.fv[SECOC_CH_HEARTBEAT], hb_before + 1u);
    const uint32_t replayed0 = app.auth.secoc.replayed;
    for (int i = 0; i < 2; i++) { /* one a tick: each alone takes the replay check */
        (void)hal_sim_can_deliver(&held[i]);
        tick();
    }
    assert_int_equal(app.state, APP_IDLE);
    assert_int_equal(app.auth.secoc.replayed, replayed0 + 2u);
    /* a fresh pair, the host silent for longer than the bound: stale */
    ticks(APP_CMD_FRESH_MS + 1u);
    const uint32_t stale0 = app.bus.stale_commands;
    send_command(APP_CMD_EXECUTE, 1);
    tick();
    assert_int_equal(app.state, APP_IDLE);
    assert_int_equal(app.bus.stale_commands, stale0 + 2u);
    /* a heartbeat, then a pair: runs again (the same path acts when it should) */
    send_heartbeat();
    send_command(APP_CMD_EXECUTE, 1);
    tick();
    assert_int_equal(app.state, APP_EXECUTE);
    send_command(APP_CMD_IDLE, 0);
    tick();
    assert_int_equal(app.state, APP_IDLE);
}

static void test_scheduler_overrun(void **state)
{
    (void)state;
    /* on time: one tick per millisecond boundary */
    unsigned ran = 0;
    for (uint64_t t = 100u; t <= 20000u; t += 100u) {
        hal_host_set_time_us(t);
        ran += app_poll(&app) ? 1u : 0u;
    }
    assert_int_equal(ran, 20);
    assert_int_equal(app.state, APP_IDLE);
    /* a tick that starts 2.5 ms late: overrun latched */
    hal_host_set_time_us(22500u);
    assert_true(app_poll(&app));
    hal_host_set_time_us(23500u);
    assert_true(app_poll(&app));
    assert_int_equal(app.state, APP_FAULT);
    assert_int_equal(app.saf_out.fault_code, FLT_TICK_OVERRUN);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(test_boot_status_and_e2e, setup),
        cmocka_unit_test_setup(test_host_silence_faults_and_ramps, setup),
        cmocka_unit_test_setup(test_bus_off_emergency_sent_after_recovery, setup),
        cmocka_unit_test_setup(test_download_corrupt_interrupted, setup),
        cmocka_unit_test_setup(test_execute_and_refusals, setup),
        cmocka_unit_test_setup(test_ecu_reset_responds_then_resets, setup),
        cmocka_unit_test_setup(test_every_mac_in_its_tick, setup),
        cmocka_unit_test_setup(test_forged_counter_never_blocks_a_stop, setup),
        cmocka_unit_test_setup(test_withheld_command_never_acts_late, setup),
        cmocka_unit_test_setup(test_scheduler_overrun, setup),
        cmocka_unit_test_setup(test_security_levels_and_confirm, setup),
        cmocka_unit_test_setup(test_failing_test_image_serves_nothing, setup),
        cmocka_unit_test_setup(test_wrong_key_counter_survives_reset, setup),
        cmocka_unit_test_setup(test_commit_refused_while_executing, setup),
        cmocka_unit_test_setup(test_skill_validated_before_commit_and_run, setup),
        cmocka_unit_test_setup(test_start_refused_during_commit, setup),
        cmocka_unit_test_setup(test_read_back_in_slices, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

/* libFuzzer harness: the whole device application (firmware/app with the real UDS server,
 * ISO-TP, SecurityAccess, storage, firmware update receiver, bootloader logic and the host port
 * of the HAL) driven through app_tick by arbitrary timed sequences of:
 *   raw CAN frames to any of the device's identifiers, E2E-valid host commands and heartbeats,
 *   UDS requests through a tester ISO-TP link, authenticated SecurityAccess (either level, with
 *   the port's secrets), skill downloads (a golden image with fuzzed byte changes, completed or
 *   cut short), firmware downloads (fuzz bytes; or a golden image marked for a test boot and
 *   reset into, its self-test passing or failing), sensor values (NaN included), bus-off,
 *   ECUReset / power-up, and time advancing; a host session (the motion key), authentic host
 *   commands and heartbeats (MAC and freshness of that session), replays of the last authentic
 *   frame, and E2E-valid frames without a valid MAC.
 * Invariants checked after every tick:
 *   1. the commanded force is finite and within the configured force limit on both axes;
 *   2. a slot changes only by a complete, authenticated (level 1), validated transfer while the
 *      device was idle (or an authenticated erase while idle): storage and the slot cache agree,
 *      the new skill parses and passes skill_check against the force limit;
 *   3. state transitions are legal (BOOT -> IDLE; IDLE -> TEACH | EXECUTE | FAULT; TEACH and
 *      EXECUTE -> IDLE | FAULT; FAULT -> IDLE, at most one per stage of a tick, never back to
 *      BOOT), FAULT is left only with its code cleared, and EXECUTE starts only with goal
 *      scales whose peak is within the force limit;
 *   4. a firmware image on test is confirmed only after its own self-test passed;
 *   5. motion starts (IDLE -> TEACH | EXECUTE) only within two ticks of an authentic fresh
 *      HostCommand (a frame beyond the tick's MAC budget is verified the tick after) or during a
 *      UDS request (the run routines); the device accepts no more authenticated frames than the
 *      harness sent authentic ones (no forged or replayed frame is ever accepted);
 *   6. a host IDLE stops within one tick, whatever else is on the bus: any frames before and
 *      after it in that tick (forged, authentic, replayed), its own counter, freshness and MAC
 *      any bytes.
 * A violated invariant aborts (libFuzzer reports it as a crash). */
#include <math.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app_internal.h"
#include "fs_dbc.h"
#include "hal_host.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerInitialize(int *argc, char ***argv);

#define MAX_TICKS 20000u  /* simulated ms per input */
#define MAX_UDS_WAIT 400u /* ticks to wait for one UDS answer */

static app_t app;
static app_config_t cfg;
static isotp_link_t tester;
static uint64_t t_us;
static uint32_t n_ticks;
static uint8_t cmd_counter, hb_counter;
static uint8_t golden[APP_IMAGE_MAX];
static uint32_t golden_len;
static uint8_t golden_fw[4096]; /* a firmware image tagged with the port's development key */
static uint32_t golden_fw_len;
static bool fail_self_test; /* the next image started fails its self-test */
static uint8_t img[APP_IMAGE_MAX];
static uint8_t resp[ISOTP_MAX_PAYLOAD];
static uint16_t resp_len;

/* the slots as the previous tick left them */
static bool prev_valid[APP_N_SLOTS];
static uint32_t prev_crc[APP_N_SLOTS], prev_len[APP_N_SLOTS];
static app_state_t prev_state;
static uint8_t prev_test_boot;
/* the harness's host session: its key and freshness values, the last authentic frame */
static secoc_t fz_host;
static bool fz_keyed;
static can_frame_t fz_last;
static bool fz_have_last;
static uint32_t fz_authentic;   /* authentic frames delivered since power-up */
static unsigned fz_start_ticks; /* ticks left in which a motion start is allowed */
static bool fz_in_uds;          /* a UDS request is being answered */
/* FS_FUZZ_TRACE set: one line per input (what it reached), for checking the seeds */
static bool trace;
static unsigned seen_states, commits;

#define CHECK(cond)                                                                        \
    do {                                                                                   \
        if (!(cond)) {                                                                     \
            fprintf(stderr, "invariant violated at tick %u: %s (%s:%d)\n", n_ticks, #cond, \
                    __FILE__, __LINE__);                                                   \
            abort();                                                                       \
        }                                                                                  \
    } while (0)

static bool tester_send(void *ctx, const can_frame_t *f)
{
    (void)ctx;
    return hal_sim_can_deliver(f);
}

static void snapshot(void)
{
    for (unsigned s = 0; s < APP_N_SLOTS; s++) {
        prev_valid[s] = app.slots.valid[s];
        prev_crc[s] = app.slots.crc[s];
        prev_len[s] = app.slots.len[s];
    }
    prev_state = app.state;
    prev_test_boot = app.fw.boot.test_boot;
}

/* One transition of the state machine (docs/safety.md). */
static bool edge(app_state_t from, app_state_t to)
{
    switch (from) {
    case APP_BOOT: return to == APP_IDLE;
    case APP_IDLE: return to == APP_TEACH || to == APP_EXECUTE || to == APP_FAULT;
    case APP_TEACH:
    case APP_EXECUTE: return to == APP_IDLE || to == APP_FAULT;
    case APP_FAULT: return to == APP_IDLE;
    default: return false;
    }
}

/* Legal within one tick: a path of at most 4 transitions (boot, a host command, a UDS request,
 * the safety supervisor can each act once per tick), never back to BOOT. */
static bool legal(app_state_t from, app_state_t to)
{
    unsigned reach = 1u << from;
    for (unsigned k = 0; k < 4u; k++) {
        unsigned next = reach;
        for (unsigned a = 0; a <= APP_FAULT; a++) {
            for (unsigned b = 0; b <= APP_FAULT; b++) {
                if ((reach & (1u << a)) != 0u && edge((app_state_t)a, (app_state_t)b)) {
                    next |= 1u << b;
                }
            }
        }
        reach = next;
    }
    return (reach & (1u << to)) != 0u;
}

static void check_invariants(void)
{
    const fs_real_t fmax[2] = {app.saf_cfg.lim.axis[0].force_max_N,
                               app.saf_cfg.lim.axis[1].force_max_N};
    bool en = false;
    fs_real_t act[2];
    hal_host_get_actuator(&en, act);
    for (unsigned a = 0; a < 2u; a++) {
        CHECK(isfinite(app.force_out_N[a]) && fabs(app.force_out_N[a]) <= fmax[a] + 1e-9);
        CHECK(isfinite(act[a]) && fabs(act[a]) <= fmax[a] + 1e-9);
    }
    CHECK(legal(prev_state, app.state));
    if (prev_state == APP_FAULT && app.state != APP_FAULT) {
        CHECK(app.saf_out.fault_code == 0u); /* left FAULT only by clearing it */
    }
    if (app.state == APP_EXECUTE && prev_state != APP_EXECUTE) {
        for (unsigned i = 0; i < app.ctl.exec.n_steps; i++) {
            const exec_step_t *st = &app.ctl.exec.steps[i];
            const long s = st->skill - app.slots.skill;
            CHECK(s >= 0 && s < (long)APP_N_SLOTS && app.slots.valid[s]);
            CHECK(st->goal_scale * app.slots.peak_N[s] <= fmax[0] * (1.0 + 1e-9));
        }
    }
    for (unsigned s = 0; s < APP_N_SLOTS; s++) {
        const bool changed = app.slots.valid[s] != prev_valid[s] ||
                             (app.slots.valid[s] &&
                              (app.slots.crc[s] != prev_crc[s] || app.slots.len[s] != prev_len[s]));
        if (!changed) {
            continue;
        }
        CHECK(prev_state == APP_IDLE);
        CHECK(app.diag.uds.unlocked_level == UDS_SEC_LEVEL_WRITE);
        uint32_t len = 0u;
        const nvm_status_t ns = nvm_read(&app.slots.nvm, (uint16_t)s, img, sizeof img, &len);
        if (!app.slots.valid[s]) {
            CHECK(ns != NVM_OK); /* erased */
            continue;
        }
        CHECK(ns == NVM_OK && len == app.slots.len[s]);
        static skill_t sk;
        CHECK(skill_parse(img, len, &sk) == FS_OK);
        fs_real_t peak = 0.0;
        CHECK(skchk_skill(&sk, 0.001, fmax[0], &peak) == FS_OK);
        CHECK(peak == app.slots.peak_N[s]);
        CHECK(app.slots.last_transfer_status == 0u);
        commits++;
    }
    if (prev_state == APP_IDLE && (app.state == APP_TEACH || app.state == APP_EXECUTE)) {
        CHECK(fz_start_ticks > 0u || fz_in_uds);
    }
    CHECK(app.auth.secoc.accepted <= fz_authentic);
    seen_states |= 1u << app.state;
    if (prev_test_boot != 0u && app.fw.boot.test_boot == 0u) {
        CHECK(app.fw.self_test_ok);
    }
}

static void power_up(void)
{
    hal_sim_can_reset();
    hal_host_set_time_us(t_us);
    app_init(&app, &cfg);
    fz_keyed = false; /* the device forgot the motion key */
    fz_authentic = 0u;
    if (fail_self_test) {
        app.slots.nvm_ok = false; /* storage unreadable: self-test fails */
        fail_self_test = false;
    }
    snapshot();
    prev_state = APP_BOOT;
}

static void tick(void)
{
    t_us += 1000u;
    n_ticks++;
    hal_host_set_time_us(t_us);
    snapshot();
    app_tick(&app, false);
    check_invariants();
    if (fz_start_ticks > 0u) {
        fz_start_ticks--;
    }
    uint8_t type = 0u;
    if (hal_host_take_reset(&type)) {
        power_up(); /* the port restarts; flash kept */
    }
    can_frame_t f;
    while (hal_sim_can_tx_peek(&f)) {
        hal_sim_can_tx_pop();
        isotp_on_frame(&tester, &f, t_us);
    }
    isotp_poll(&tester, t_us);
}

/* Send a UDS request through the tester and tick until its final answer (resp/resp_len) or
 * MAX_UDS_WAIT ticks; false if no answer. */
static bool uds(const uint8_t *req, uint16_t len)
{
    resp_len = 0u;
    if (isotp_tx_busy(&tester) || isotp_send(&tester, req, len, t_us) != PROTO_OK) {
        return false;
    }
    for (unsigned k = 0; k < MAX_UDS_WAIT && n_ticks < MAX_TICKS; k++) {
        fz_in_uds = true;
        tick();
        fz_in_uds = false;
        const uint8_t *r = NULL;
        const uint16_t n = isotp_rx_peek(&tester, &r);
        if (n != 0u) {
            const bool pending = n >= 3u && r[0] == 0x7Fu && r[2] == UDS_NRC_RESPONSE_PENDING;
            if (!pending) {
                memcpy(resp, r, n);
                resp_len = n;
            }
            isotp_rx_release(&tester);
            if (!pending) {
                return true;
            }
        }
    }
    return false;
}

static void unlock(uint8_t session, uint8_t level, bool right_key)
{
    const uint8_t dsc[2] = {0x10u, session};
    (void)uds(dsc, 2u);
    const uint8_t seed[2] = {0x27u, level};
    if (!uds(seed, 2u) || resp_len != 2u + SEC_SEED_LEN || resp[0] != 0x67u) {
        return;
    }
    uint8_t key[2u + SEC_KEY_LEN] = {0x27u, (uint8_t)(level + 1u)};
    const sec_config_t *c = app_sec_config(&app, level);
    if (c == NULL) {
        return;
    }
    sec_compute_key(c, &resp[2], &key[2]);
    if (!right_key) {
        key[2] ^= 0x01u;
    }
    (void)uds(key, (uint16_t)sizeof key);
}

/* RequestDownload to addr, TransferData in blocks of blk, RequestTransferExit unless cut. */
static void download(uint32_t addr, const uint8_t *d, uint32_t len, uint32_t blk, bool cut)
{
    uint8_t rd[UDS_REQ_DOWNLOAD_LEN];
    if (!uds(rd, uds_request_download(rd, addr, len)) || resp[0] != 0x74u) {
        return;
    }
    static uint8_t td[UDS_MAX_BLOCK_LENGTH];
    uint8_t counter = 1u;
    const uint32_t send = cut ? len / 2u : len;
    for (uint32_t off = 0u; off < send; off += blk) {
        const uint32_t n = (send - off < blk) ? send - off : blk;
        td[0] = 0x36u;
        td[1] = counter++;
        memcpy(&td[2], &d[off], n);
        if (!uds(td, (uint16_t)(n + 2u)) || resp[0] != 0x76u) {
            return;
        }
    }
    if (!cut) {
        const uint8_t ex[1] = {0x37u};
        (void)uds(ex, 1u);
    }
}

static void send_safety(uint32_t id, uint8_t *counter, const uint8_t *payload)
{
    can_frame_t f = {.id = id, .len = 8u};
    memcpy(f.data, payload, 8u);
    e2e_protect(&f, ++(*counter));
    (void)hal_sim_can_deliver(&f);
}

/* An authentic host frame of the harness's session (MAC, freshness, E2E), delivered. */
static void send_authentic(uint32_t id, secoc_channel_t ch, const uint8_t *payload)
{
    can_frame_t f = {.id = id, .len = 8u};
    memcpy(f.data, payload, 8u);
    const uint32_t fv = secoc_protect(&fz_host, &f, ch);
    e2e_protect(&f, (uint8_t)(fv & E2E_COUNTER_MASK));
    if (hal_sim_can_deliver(&f)) {
        fz_authentic++;
    }
    fz_last = f;
    fz_have_last = true;
}

/* A HostCommand payload from 6 fuzz bytes (mode, slot, goal, time scale, end policy). */
static void command_payload(const uint8_t *p, uint8_t payload[8])
{
    struct fs_dbc_host_command_t c;
    memset(&c, 0, sizeof c);
    c.mode = (uint8_t)(p[0] % 6u);
    c.slot = (uint8_t)(p[1] % 10u);
    c.goal_scale = (uint16_t)(p[2] | (p[3] << 8));
    c.time_scale = (uint16_t)(p[4] | (p[5] << 8));
    c.end_policy = (uint8_t)(p[1] >> 6);
    memset(payload, 0, 8u);
    (void)fs_dbc_host_command_pack(payload, &c, 8u);
}

static float get_f32(const uint8_t *p)
{
    float v;
    memcpy(&v, p, sizeof v);
    return v;
}

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    trace = getenv("FS_FUZZ_TRACE") != NULL;
    FILE *f = fopen(FS_FUZZ_GOLDEN, "rb");
    if (f != NULL) {
        golden_len = (uint32_t)fread(golden, 1, sizeof golden, f);
        fclose(f);
    }
    f = fopen(FS_FUZZ_GOLDEN_FW, "rb");
    if (f != NULL) {
        golden_fw_len = (uint32_t)fread(golden_fw, 1, sizeof golden_fw, f);
        fclose(f);
    }
    return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    hal_host_init();
    hal_host_flash_erase();
    t_us = 0u;
    n_ticks = 0u;
    cmd_counter = hb_counter = 0u;
    fail_self_test = false;
    fz_keyed = false;
    fz_have_last = false;
    fz_start_ticks = 0u;
    fz_in_uds = false;
    seen_states = 0u;
    commits = 0u;
    app_config_default(&cfg);
    power_up();
    isotp_config_t tc;
    isotp_config_default(&tc, PROTO_ID_UDS_REQUEST(0), PROTO_ID_UDS_RESPONSE(0));
    isotp_init(&tester, &tc, tester_send, NULL);
    hal_sensors_t sens;
    memset(&sens, 0, sizeof sens);
    sens.pos_m[0] = 0.001;
    hal_host_set_sensors(&sens);

    size_t i = 0u;
    while (i < size && n_ticks < MAX_TICKS) {
        const uint8_t op = data[i++];
        const size_t left = size - i;
        const uint8_t *p = &data[i];
        switch (op % 18u) {
        case 0: { /* time passes */
            const unsigned n = left > 0u ? 1u + p[0] : 1u;
            i += left > 0u ? 1u : 0u;
            for (unsigned k = 0; k < n && n_ticks < MAX_TICKS; k++) {
                tick();
            }
            break;
        }
        case 1: { /* raw frame to one of the device's ids */
            if (left < 10u) {
                i = size;
                break;
            }
            static const uint32_t ids[6] = {0x100u, 0x110u, 0x600u, 0x080u, 0x180u, 0x7FFu};
            can_frame_t f = {.id = ids[p[0] % 6u], .len = (uint8_t)(p[1] % 9u)};
            memcpy(f.data, &p[2], 8u);
            (void)hal_sim_can_deliver(&f);
            i += 10u;
            tick();
            break;
        }
        case 2: { /* E2E-valid host command */
            if (left < 6u) {
                i = size;
                break;
            }
            uint8_t payload[8];
            command_payload(p, payload); /* no MAC: refused unless a stop */
            send_safety(PROTO_ID_HOST_COMMAND(0), &cmd_counter, payload);
            i += 6u;
            tick();
            break;
        }
        case 3: { /* heartbeat */
            uint8_t payload[8] = {0};
            payload[0] = left > 0u ? p[0] : 0u;
            i += left > 0u ? 1u : 0u;
            send_safety(PROTO_ID_HOST_HEARTBEAT(0), &hb_counter, payload);
            tick();
            break;
        }
        case 4: { /* arbitrary UDS request */
            if (left < 1u) {
                break;
            }
            uint16_t n = (uint16_t)(p[0] + 1u);
            if (n > left - 1u) {
                n = (uint16_t)(left - 1u);
            }
            if (n > 0u) {
                (void)uds(&p[1], n);
            }
            i += 1u + n;
            break;
        }
        case 5: /* authenticated SecurityAccess */
            if (left >= 1u) {
                unlock((p[0] & 1u) ? UDS_SESSION_PROGRAMMING : UDS_SESSION_EXTENDED,
                       (p[0] & 2u) ? UDS_SEC_LEVEL_FIRMWARE : UDS_SEC_LEVEL_WRITE,
                       (p[0] & 4u) == 0u);
                i += 1u;
            }
            break;
        case 6: { /* skill download: golden, byte changes */
            if (left < 4u || golden_len == 0u) {
                i = size;
                break;
            }
            memcpy(img, golden, golden_len);
            const unsigned n_mut = p[1] % 4u;
            for (unsigned k = 0; k < n_mut && 4u + 2u * k + 1u < left; k++) {
                img[p[4u + 2u * k] % golden_len] ^= p[5u + 2u * k];
            }
            if ((p[2] & 1u) != 0u) { /* keep the CRC right */
                const uint32_t crc = skill_crc32(0u, img, golden_len - SKILL_CRC_SIZE);
                memcpy(&img[golden_len - SKILL_CRC_SIZE], &crc, 4u);
            }
            download(1u + p[0] % 9u, img, golden_len, 8u + p[3], (p[2] & 2u) != 0u);
            i += 4u + 2u * n_mut;
            break;
        }
        case 7: { /* firmware download of fuzz bytes */
            if (left < 2u) {
                i = size;
                break;
            }
            const uint32_t n = (uint32_t)(left - 1u) < 2048u ? (uint32_t)(left - 1u) : 2048u;
            download(FWU_DOWNLOAD_ADDRESS, &p[1], n, 256u, (p[0] & 1u) != 0u);
            i += 1u + n;
            break;
        }
        case 8: { /* sensors */
            if (left < 12u) {
                i = size;
                break;
            }
            sens.pos_m[0] = get_f32(&p[0]);
            sens.force_contact_N[0] = get_f32(&p[4]);
            sens.force_operator_N[0] = get_f32(&p[8]);
            hal_host_set_sensors(&sens);
            i += 12u;
            tick();
            break;
        }
        case 9: /* bus-off for a while */
            hal_sim_can_set_bus_off(true);
            tick();
            tick();
            hal_sim_can_set_bus_off(false);
            break;
        case 10: /* power cycle (flash kept) */ power_up(); break;
        case 11: { /* firmware update: level 3, golden image,
                                                          mark test, ECUReset into it */
            if (left < 1u || golden_fw_len == 0u) {
                i = size;
                break;
            }
            for (unsigned k = 0; k < 15u && n_ticks < MAX_TICKS; k++) {
                unlock(UDS_SESSION_PROGRAMMING, UDS_SEC_LEVEL_FIRMWARE, true);
                if (app.diag.uds.unlocked_level == UDS_SEC_LEVEL_FIRMWARE) {
                    break;
                }
                for (unsigned w = 0; w < 100u && n_ticks < MAX_TICKS; w++) {
                    tick(); /* power-up delay or lockout */
                }
            }
            download(FWU_DOWNLOAD_ADDRESS, golden_fw, golden_fw_len, 64u + p[0], false);
            const uint8_t mark[5] = {0x31u, 0x01u, 0x0Fu, 0x01u, (uint8_t)(p[0] & 1u)};
            (void)uds(mark, 5u);
            fail_self_test = (p[0] & 2u) != 0u;
            const uint8_t reset[2] = {0x11u, 0x01u};
            (void)uds(reset, 2u);
            for (unsigned w = 0; w < 5u && fail_self_test && n_ticks < MAX_TICKS; w++) {
                tick(); /* the reset follows its response */
            }
            fail_self_test = false;
            i += 1u;
            break;
        }
        case 13: { /* host session: the motion key */
            static const uint8_t nonce[SECOC_NONCE_LEN] = "fuzz host nonce";
            if (app_motion_key(&app, nonce, SECOC_NONCE_LEN) == 0u) {
                uint8_t len = 0u;
                const uint8_t *secret = hal_device_secret(UDS_SEC_LEVEL_WRITE, &len);
                secoc_start_session(&fz_host, secret, len, app.sec.motion.dev_nonce, nonce);
                fz_keyed = true;
            }
            tick();
            break;
        }
        case 14: { /* authentic host command */
            if (left < 6u) {
                i = size;
                break;
            }
            if (fz_keyed) {
                uint8_t payload[8];
                command_payload(p, payload);
                send_authentic(PROTO_ID_HOST_COMMAND(0), SECOC_CH_COMMAND, payload);
                fz_start_ticks = 2u;
            }
            i += 6u;
            tick();
            break;
        }
        case 15: { /* authentic heartbeat */
            uint8_t payload[8] = {0};
            payload[0] = left > 0u ? p[0] : 0u;
            payload[1] = (uint8_t)fz_host.fv[SECOC_CH_COMMAND]; /* the last command sent */
            i += left > 0u ? 1u : 0u;
            if (fz_keyed) {
                send_authentic(PROTO_ID_HOST_HEARTBEAT(0), SECOC_CH_HEARTBEAT, payload);
            }
            tick();
            break;
        }
        case 17: { /* a stop among other frames: IDLE with any MAC, counter and freshness */
            if (left < 4u) {
                i = size;
                break;
            }
            const unsigned before = p[0] % 4u, after = p[1] % 4u;
            for (unsigned k = 0; k < before + after + 1u; k++) {
                can_frame_t f = {.id = PROTO_ID_HOST_COMMAND(0), .len = 8u};
                memset(f.data, 0, 8u);
                if (k == before) { /* the stop */
                    f.data[0] = APP_CMD_IDLE;
                    f.data[SECOC_MAC_OFFSET] = p[2];
                    f.data[SECOC_FV_BYTE] = p[3];
                    e2e_protect(&f, p[3]);
                    (void)hal_sim_can_deliver(&f);
                } else if ((k & 1u) != 0u && fz_have_last) {
                    (void)hal_sim_can_deliver(&fz_last); /* a replay */
                } else {
                    f.data[0] = (uint8_t)((p[2] + k) % 6u); /* any mode, forged */
                    f.data[SECOC_FV_BYTE] = (uint8_t)(p[3] + k);
                    e2e_protect(&f, (uint8_t)(p[3] + k));
                    (void)hal_sim_can_deliver(&f);
                }
            }
            i += 4u;
            tick();
            CHECK(app.state != APP_TEACH && app.state != APP_EXECUTE);
            break;
        }
        case 16: /* replay of the last authentic frame */
            if (fz_have_last) {
                (void)hal_sim_can_deliver(&fz_last);
            }
            tick();
            break;
        default: { /* run a skill through UDS */
            if (left < 5u) {
                i = size;
                break;
            }
            const uint8_t run[10] = {0x31u, 0x01u, 0x02u, 0x01u, p[0], p[1], p[2], p[3], p[4], 0u};
            (void)uds(run, 10u);
            i += 5u;
            break;
        }
        }
    }
    if (trace) {
        fprintf(stderr,
                "fuzz_app: %u ticks, states seen 0x%02X (bit = state), %u slot changes, "
                "last transfer %u, last run %u, firmware %08X on test %u, reverted %u\n",
                n_ticks, seen_states, commits, app.slots.last_transfer_status,
                app.ctl.last_run_status, (unsigned)app.fw.boot.running.fw_version,
                app.fw.boot.test_boot, app.fw.boot.path == BOOT_PATH_REVERTED ? 1u : 0u);
    }
    return 0;
}

/* The device application on the host port's SocketCAN backend (hal_can_socketcan.c), the bus a
 * socket pair carrying struct can_frame (pair_ops.h): status frames reach the bus, authenticated
 * host frames (motion session, MAC and freshness, E2E) reach the application, and the fault table's bus-off row holds as on the simulator's
 * bus: BUS_OFF (501) latches in the tick the driver reads the error frame, the actuator is ramped
 * off, nothing is transmitted while bus-off, the restart is requested, and the emergency frame is
 * the first frame on the bus after recovery, once, with the fault still latched. */
#define _GNU_SOURCE
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <cmocka.h>

#include <errno.h>

#include "app_internal.h"
#include "cansock.h"
#include "fs_dbc.h"
#include "hal_host.h"
#include "pair_ops.h"

static app_t *app; /* app_device() */
static app_config_t cfg;
static uint64_t t_us;
static secoc_t host; /* the test host's motion session (as tests/firmware/app/test_app.c) */

/* The host session with the device (the DID 0x0302 write, then the host's derivation). */
static void host_session(void)
{
    static const uint8_t nonce[SECOC_NONCE_LEN] = "test host nonce";
    assert_int_equal(app_motion_key(app, nonce, SECOC_NONCE_LEN), 0);
    uint8_t len = 0u;
    const uint8_t *secret = hal_device_secret(UDS_SEC_LEVEL_WRITE, &len);
    secoc_start_session(&host, secret, len, app_motion_nonce(app), nonce);
}

static int setup(void **state)
{
    (void)state;
    pair_reset();
    char err[160];
    assert_int_equal(hal_socketcan_open_with(&pair_ops, "can0", 0u, err, sizeof(err)), 0);
    hal_host_init();
    hal_host_flash_erase();
    t_us = 0u;
    hal_sensors_t s;
    memset(&s, 0, sizeof(s));
    s.pos_m[0] = 0.001;
    s.force_operator_N[0] = 4.0; /* an operator pressing in TEACH */
    hal_host_set_sensors(&s);
    app_config_default(&cfg);
    cfg.render_carriage = 1u; /* TEACH commands a force: the rendering */
    hal_host_set_time_us(0u);
    app = app_device();
    app_init(app, &cfg);
    host_session();
    return 0;
}

static int teardown(void **state)
{
    (void)state;
    hal_socketcan_close();
    pair_reset();
    return 0;
}

static void tick(void)
{
    t_us += 1000u;
    hal_host_set_time_us(t_us);
    app_tick(app, false);
}

static void put_frame(const can_frame_t *f)
{
    pair_put(f->id, f->len, f->data);
}

static void heartbeat(void)
{
    can_frame_t f = {.id = PROTO_ID_HOST_HEARTBEAT(0), .len = 8};
    f.data[1] = (uint8_t)host.fv[SECOC_CH_COMMAND]; /* CommandFreshness: the last command sent */
    const uint32_t fv = secoc_protect(&host, &f, SECOC_CH_HEARTBEAT);
    e2e_protect(&f, (uint8_t)(fv & E2E_COUNTER_MASK));
    put_frame(&f);
}

static void command(uint8_t mode)
{
    struct fs_dbc_host_command_t c;
    memset(&c, 0, sizeof(c));
    c.mode = mode;
    c.goal_scale = 1000u;
    c.time_scale = 1000u;
    can_frame_t f = {.id = PROTO_ID_HOST_COMMAND(0), .len = 8};
    (void)fs_dbc_host_command_pack(f.data, &c, 8);
    const uint32_t fv = secoc_protect(&host, &f, SECOC_CH_COMMAND);
    e2e_protect(&f, (uint8_t)(fv & E2E_COUNTER_MASK));
    put_frame(&f);
}

/* Frames the device put on the bus since the last call. */
static unsigned drain(can_frame_t *out, unsigned cap)
{
    unsigned n = 0u;
    struct can_frame lf;
    while (pair_take(&lf)) {
        if (n < cap) {
            assert_int_equal(cansock_from_linux(&lf, &out[n]), CANSOCK_RX_DATA);
            n++;
        }
    }
    return n;
}

static void test_status_out_commands_in(void **state)
{
    (void)state;
    for (unsigned i = 0; i < 20; i++) {
        tick();
    }
    can_frame_t out[64];
    const unsigned n = drain(out, 64);
    unsigned n_status = 0u;
    for (unsigned i = 0; i < n; i++) {
        if (out[i].id == PROTO_ID_STATUS(0)) {
            e2e_rx_t rx;
            e2e_rx_reset(&rx);
            assert_int_equal(e2e_check(&rx, &out[i]), PROTO_OK);
            n_status++;
        }
    }
    assert_int_equal(n_status, 2); /* every 10 ms */
    assert_int_equal(app_state(app), APP_IDLE);
    heartbeat(); /* a command needs a heartbeat before it (APP_CMD_FRESH_MS) */
    command(APP_CMD_TEACH);
    for (unsigned i = 0; i < 5; i++) {
        tick();
    }
    assert_int_equal(app_state(app), APP_TEACH);
    assert_true(drain(out, 64) > 0u);
    assert_true(hal_can_tx_idle()); /* the bus took every frame */
}

static void test_bus_off_row(void **state)
{
    (void)state;
    for (unsigned i = 0; i < 5; i++) {
        tick();
    }
    heartbeat();
    command(APP_CMD_TEACH);
    for (unsigned i = 0; i < 60; i++) {
        if (i % 10 == 0) {
            heartbeat();
        }
        tick();
    }
    assert_int_equal(app_state(app), APP_TEACH);
    bool en = false;
    fs_real_t f_N[2];
    hal_host_get_actuator(&en, f_N);
    assert_true(en && f_N[0] != 0.0); /* the device renders the operator's push */
    can_frame_t out[256];
    (void)drain(out, 256);

    /* bus-off, read in this tick's receive (after the actuator's write): 501 latched by the next
     * tick's safety step, before its actuator write */
    pair_put(CAN_ERR_FLAG | CAN_ERR_BUSOFF, CAN_ERR_DLC, NULL);
    tick();
    assert_true(hal_can_bus_off());
    const uint64_t off_us = t_us;
    assert_int_equal(app_state(app), APP_TEACH);
    tick();
    assert_int_equal(app_state(app), APP_FAULT);
    assert_int_equal(app_fault_code(app), FLT_BUS_OFF);
    pair_ctl.restart_result = -EPERM; /* first restart refused, the second works */
    bool restarted = false;
    for (unsigned i = 0; i < 200 && !restarted; i++) {
        if (i % 10 == 0) {
            heartbeat();
        }
        tick();
        if (pair_ctl.restart_calls == 1u) {
            pair_ctl.restart_result = 0;
        }
        if (i == 49u) {
            hal_host_get_actuator(&en, f_N);
            assert_false(en);                     /* ramped to zero and off within 50 ms */
            assert_int_equal(drain(out, 256), 0); /* nothing transmitted while bus-off */
        }
        restarted = !hal_can_bus_off();
    }
    assert_true(restarted);
    assert_int_equal(pair_ctl.restart_calls, 2);
    assert_int_equal(t_us - off_us, 2u * CANSOCK_RESTART_MS * 1000u);
    tick();
    const unsigned n = drain(out, 256);
    assert_true(n >= 1u);
    assert_int_equal(out[0].id, PROTO_ID_EMERGENCY(0));
    e2e_rx_t rx;
    e2e_rx_reset(&rx);
    assert_int_equal(e2e_check(&rx, &out[0]), PROTO_OK);
    struct fs_dbc_emergency_t e;
    assert_int_equal(fs_dbc_emergency_unpack(&e, out[0].data, 8), 0);
    assert_int_equal(e.fault_code, FLT_BUS_OFF);
    /* latched: no resume after the bus came back, the emergency not repeated */
    for (unsigned i = 0; i < 100; i++) {
        if (i % 10 == 0) {
            heartbeat();
        }
        tick();
    }
    assert_int_equal(app_state(app), APP_FAULT);
    hal_host_get_actuator(&en, f_N);
    assert_false(en);
    const unsigned m = drain(out, 256);
    for (unsigned i = 0; i < m; i++) {
        assert_int_not_equal(out[i].id, PROTO_ID_EMERGENCY(0));
    }
    const cansock_t *d = hal_socketcan_driver();
    assert_int_equal(d->st.bus_offs, 1);
    assert_int_equal(d->st.restart_failures, 1);
    assert_true(d->st.tx_bus_off > 0u);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_status_out_commands_in, setup, teardown),
        cmocka_unit_test_setup_teardown(test_bus_off_row, setup, teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

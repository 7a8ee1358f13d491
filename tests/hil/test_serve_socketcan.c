/* `hil_sim serve --socketcan`'s run loop and bridge (hil_sim/bus/serve_socketcan.c) with the
 * device application on the host port's queues, the interface a socket pair carrying struct
 * can_frame (tests/firmware/ports/host/pair_ops.h): a refused bit rate does not stop the run; a
 * full interface queue (ENOBUFS) loses no frame, they leave later in order; bus-off latches
 * fault 501 in the tick the error frame is read, nothing is sent while off, and after the restart
 * the emergency frame is the first frame on the bus; a burst larger than the device's receive
 * FIFO waits in the socket and is not lost. */
#define _GNU_SOURCE
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <cmocka.h>

#include <errno.h>

#include "app_config.h"
#include "proto_ids.h"
#include "fs_dbc.h"
#include "hal_host.h"
#include "pair_ops.h"
#include "serve_socketcan.h"

#define RUN_TICKS 600u
#define ENOBUFS_TICK 50u  /* the interface refuses 30 writes from here */
#define BUS_OFF_TICK 200u /* the bus-off error frame goes on the bus after this tick */

static app_t *app; /* app_device() */
static app_config_t cfg;
static uint32_t k; /* ticks run */
static uint32_t fault_tick;
static uint32_t dropped_before_off;
static can_frame_t seen[4096];
static uint32_t seen_tick[4096];
static unsigned n_seen;

static void device_tick(void *ctx)
{
    (void)ctx;
    hal_host_set_time_us((uint64_t)k * 1000u);
    app_tick(app, false);
    if (app_state(app) == APP_FAULT && fault_tick == 0u) {
        fault_tick = k;
    }
    struct can_frame lf;
    while (pair_take(&lf) && n_seen < 4096u) {
        assert_int_equal(cansock_from_linux(&lf, &seen[n_seen]), CANSOCK_RX_DATA);
        seen_tick[n_seen++] = k;
    }
    if (k == ENOBUFS_TICK) {
        pair_ctl.write_fail_count = 30u;
        pair_ctl.write_fail_errno = ENOBUFS;
    }
    if (k == BUS_OFF_TICK) {
        dropped_before_off = *app_tx_dropped(app);
        pair_put(CAN_ERR_FLAG | CAN_ERR_BUSOFF, CAN_ERR_DLC, NULL);
    }
    k++;
}

static void test_run_over_socket_pair(void **state)
{
    (void)state;
    pair_reset();
    pair_ctl.bitrate_bps = 500000u;
    pair_ctl.set_result = -EPERM; /* no CAP_NET_ADMIN: refused, run goes on */
    hal_host_init();
    hal_host_flash_erase();
    hal_sim_can_reset();
    app_config_default(&cfg);
    hal_host_set_time_us(0u);
    app = app_device();
    app_init(app, &cfg);
    volatile sig_atomic_t stop = 0;
    const serve_socketcan_cfg_t sc = {.ifname = "can0",
                                      .ops = &pair_ops,
                                      .bitrate_bps = 250000u,
                                      .speed = 20.0,
                                      .end_ns = (uint64_t)RUN_TICKS * 1000000u,
                                      .node = 0u,
                                      .scenario = NULL,
                                      .tick = device_tick,
                                      .ctx = NULL,
                                      .device_tx_dropped = app_tx_dropped(app),
                                      .stop = &stop};
    assert_int_equal(serve_socketcan_run(&sc), 0);
    assert_int_equal(k, RUN_TICKS);
    assert_int_equal(pair_ctl.set_calls, 1);
    assert_int_equal(pair_ctl.bitrate_bps, 500000u);

    /* every status frame before the bus-off reached the bus, E2E counters without a gap, though
     * the interface refused 30 writes */
    unsigned n_status = 0u;
    uint8_t last = 0u;
    unsigned same_tick = 0u, most_in_one_tick = 0u;
    for (unsigned i = 0; i < n_seen && seen_tick[i] <= BUS_OFF_TICK; i++) {
        if (seen[i].id != PROTO_ID_STATUS(0)) {
            continue;
        }
        const uint8_t ctr = (uint8_t)(seen[i].data[6] & 0x0Fu);
        if (n_status > 0u) {
            assert_int_equal(ctr, (uint8_t)((last + 1u) & 0x0Fu));
        }
        same_tick = (i > 0u && n_status > 0u && seen_tick[i] == seen_tick[i - 1u]) ? same_tick + 1u
                                                                                   : 1u;
        most_in_one_tick = same_tick > most_in_one_tick ? same_tick : most_in_one_tick;
        last = ctr;
        n_status++;
    }
    assert_int_equal(n_status, BUS_OFF_TICK / 10u); /* ticks 0, 10, ..., 190 */
    assert_int_equal(dropped_before_off, 0u);
    assert_int_equal(pair_ctl.write_fail_count, 0u);
    /* held while refused (ticks 50..80), then written together: status of 50, 60, 70 */
    assert_true(most_in_one_tick >= 3u);

    /* bus-off: read before tick BUS_OFF_TICK + 1, latched in that tick */
    assert_int_equal(fault_tick, BUS_OFF_TICK + 1u);
    assert_int_equal(app_fault_code(app), FLT_BUS_OFF);
    const uint32_t back = BUS_OFF_TICK + 1u + CANSOCK_RESTART_MS;
    assert_int_equal(pair_ctl.restart_calls, 1);
    unsigned first_after = n_seen;
    for (unsigned i = 0; i < n_seen; i++) {
        if (seen_tick[i] > BUS_OFF_TICK + 1u) {
            assert_true(seen_tick[i] > back); /* nothing while bus-off */
            if (first_after == n_seen) {
                first_after = i;
            }
        }
    }
    assert_true(first_after < n_seen);
    assert_int_equal(seen[first_after].id, PROTO_ID_EMERGENCY(0));
    struct fs_dbc_emergency_t e;
    assert_int_equal(fs_dbc_emergency_unpack(&e, seen[first_after].data, 8), 0);
    assert_int_equal(e.fault_code, FLT_BUS_OFF);
    assert_int_equal(app_state(app), APP_FAULT);
    pair_reset();
}

#define BURST_FRAMES 270u /* above HAL_SIM_RX_QUEUE, below what the socket pair holds (278) */
#define BURST_TICK 20u

static void burst_tick(void *ctx)
{
    (void)ctx;
    hal_host_set_time_us((uint64_t)k * 1000u);
    app_tick(app, false);
    struct can_frame lf;
    while (pair_take(&lf)) {
    }
    if (k == BURST_TICK) { /* one write each, at once: what vcan hands over without a bit rate */
        const uint8_t data[8] = {0x21u, 1u, 2u, 3u, 4u, 5u, 6u, 7u};
        for (unsigned i = 0; i < BURST_FRAMES; i++) {
            pair_put(0x123u, 8u, data); /* an identifier the device ignores */
        }
    }
    k++;
}

static void test_burst_beyond_the_fifo_waits_in_the_socket(void **state)
{
    (void)state;
    _Static_assert(BURST_FRAMES > HAL_SIM_RX_QUEUE, "the burst must not fit the FIFO");
    pair_reset();
    hal_host_init();
    hal_host_flash_erase();
    hal_sim_can_reset();
    app_config_default(&cfg);
    hal_host_set_time_us(0u);
    k = 0u;
    app = app_device();
    app_init(app, &cfg);
    volatile sig_atomic_t stop = 0;
    const serve_socketcan_cfg_t sc = {.ifname = "can0",
                                      .ops = &pair_ops,
                                      .bitrate_bps = 0u,
                                      .speed = 20.0,
                                      .end_ns = 40ull * 1000000u,
                                      .node = 0u,
                                      .scenario = NULL,
                                      .tick = burst_tick,
                                      .ctx = NULL,
                                      .device_tx_dropped = app_tx_dropped(app),
                                      .stop = &stop};
    assert_int_equal(serve_socketcan_run(&sc), 0);
    assert_int_equal(hal_sim_can_rx_overflows(), 0u);
    assert_int_equal(hal_sim_can_rx_free(), HAL_SIM_RX_QUEUE); /* all taken by the device */
    pair_reset();
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_run_over_socket_pair),
        cmocka_unit_test(test_burst_beyond_the_fifo_waits_in_the_socket),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

/* The SocketCAN driver (cansock.h) over a socket pair carrying struct can_frame (pair_ops.h):
 * frame conversion against the kernel's documented layout, error frames, non-blocking transmit
 * with a full queue (EAGAIN from the socket, ENOBUFS from the interface), bus-off and its
 * recovery, bit rate requests, and the refusals of open. Runs where the kernel has no AF_CAN. */
#define _GNU_SOURCE
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <cmocka.h>

#include <errno.h>
#include <fcntl.h>
#include <unistd.h>

#include "cansock.h"
#include "pair_ops.h"

static cansock_t drv;
static char err[200];

static int setup(void **state)
{
    (void)state;
    pair_reset();
    memset(err, 0, sizeof(err));
    assert_int_equal(cansock_open(&drv, &pair_ops, "can0", err, sizeof(err)), 0);
    return 0;
}

static int teardown(void **state)
{
    (void)state;
    cansock_close(&drv);
    pair_reset();
    return 0;
}

/* struct can_frame as <linux/can.h> documents it: can_id (host order u32, bit 31 EFF, 30 RTR,
 * 29 ERR) at offset 0, len at 4, three pad/reserved bytes, data[8] at 8; 16 bytes. */
static void test_conversion_matches_kernel_layout(void **state)
{
    (void)state;
    assert_int_equal(sizeof(struct can_frame), 16);
    const can_frame_t f = {.id = 0x1A3, .len = 3, .data = {0xDE, 0xAD, 0xBE, 0xEF, 1, 2, 3, 4}};
    struct can_frame lf;
    memset(&lf, 0x55, sizeof(lf));
    assert_true(cansock_to_linux(&f, &lf));
    uint8_t raw[16];
    memcpy(raw, &lf, sizeof(raw));
    uint32_t id;
    memcpy(&id, raw, 4);
    assert_int_equal(id, 0x1A3);
    const uint8_t expect_tail[12] = {3, 0, 0, 0, 0xDE, 0xAD, 0xBE, 0, 0, 0, 0, 0};
    assert_memory_equal(raw + 4, expect_tail, 12);       /* data beyond dlc zero, pads zero */

    /* refused, output untouched: 29-bit id, dlc 9 */
    memset(&lf, 0x55, sizeof(lf));
    const can_frame_t big_id = {.id = 0x800, .len = 1};
    const can_frame_t big_dlc = {.id = 0x100, .len = 9};
    assert_false(cansock_to_linux(&big_id, &lf));
    assert_false(cansock_to_linux(&big_dlc, &lf));
    assert_int_equal(lf.can_id, 0x55555555u);

    /* back: a data frame, data beyond len zeroed */
    uint8_t in_raw[16] = {0x81, 0x06, 0, 0, 2, 0, 0, 0, 0x3E, 0x80, 0x77, 0x77, 0x77, 0x77, 0x77, 0x77};
    struct can_frame in;
    memcpy(&in, in_raw, sizeof(in));
    can_frame_t out;
    memset(&out, 0xAA, sizeof(out));
    assert_int_equal(cansock_from_linux(&in, &out), CANSOCK_RX_DATA);
    assert_int_equal(out.id, 0x681);
    assert_int_equal(out.len, 2);
    const uint8_t expect_data[8] = {0x3E, 0x80, 0, 0, 0, 0, 0, 0};
    assert_memory_equal(out.data, expect_data, 8);

    in.can_id = 0x681u | CAN_EFF_FLAG;
    assert_int_equal(cansock_from_linux(&in, &out), CANSOCK_RX_FOREIGN);
    in.can_id = 0x681u | CAN_RTR_FLAG;
    assert_int_equal(cansock_from_linux(&in, &out), CANSOCK_RX_FOREIGN);
    in.can_id = CAN_ERR_FLAG | CAN_ERR_BUSOFF;
    assert_int_equal(cansock_from_linux(&in, &out), CANSOCK_RX_ERROR);
    in.can_id = 0x681u;
    in.len = 9u;
    assert_int_equal(cansock_from_linux(&in, &out), CANSOCK_RX_FOREIGN);
}

static void test_open_makes_non_blocking_and_refuses_bad_names(void **state)
{
    (void)state;
    assert_true((fcntl(drv.fd, F_GETFL) & O_NONBLOCK) != 0);
    assert_string_equal(drv.ifname, "can0");
    cansock_t c;
    static const char *const bad[] = {"", "0123456789abcdef", "a/b", "a b", "can0:1", ".", ".."};
    for (size_t i = 0; i < sizeof(bad) / sizeof(bad[0]); i++) {
        const int fd_before = pair_ctl.bus_fd;
        assert_int_equal(cansock_open(&c, &pair_ops, bad[i], err, sizeof(err)), -EINVAL);
        assert_non_null(strstr(err, "invalid interface name"));
        assert_int_equal(pair_ctl.bus_fd, fd_before);     /* open_raw never called */
        assert_int_equal(c.fd, -1);
    }
    assert_int_equal(cansock_open(&c, &pair_ops, "0123456789abcde", err, sizeof(err)), 0);  /* 15 */
    cansock_close(&c);
    pair_ctl.open_result = -ENODEV;
    assert_int_equal(cansock_open(&c, &pair_ops, "can7", err, sizeof(err)), -ENODEV);
    assert_non_null(strstr(err, "can7"));
    assert_null(strchr(err, '\n'));
    assert_int_equal(c.fd, -1);
}

static void test_send_and_receive(void **state)
{
    (void)state;
    const can_frame_t tx = {.id = 0x190, .len = 8, .data = {1, 2, 3, 4, 5, 6, 7, 8}};
    assert_true(cansock_send(&drv, &tx));
    struct can_frame seen;
    assert_true(pair_take(&seen));
    assert_int_equal(seen.can_id, 0x190);
    assert_int_equal(seen.len, 8);
    assert_memory_equal(seen.data, tx.data, 8);
    assert_false(pair_take(&seen));

    can_frame_t rx;
    assert_false(cansock_receive(&drv, &rx, 0u));         /* nothing: does not block */
    /* foreign and error frames are consumed on the way to the next data frame */
    pair_put(0x18FF0001u | CAN_EFF_FLAG, 2, (const uint8_t[]){9, 9});
    pair_put(0x601u | CAN_RTR_FLAG, 0, NULL);
    uint8_t cnt[8] = {0, 0, 0, 0, 0, 0, 96, 12};
    pair_put(CAN_ERR_FLAG | CAN_ERR_ACK | CAN_ERR_CNT, CAN_ERR_DLC, cnt);
    pair_put(0x601, 3, (const uint8_t[]){0x02, 0x3E, 0x00});
    pair_put(0x110, 8, (const uint8_t[]){1, 1, 1, 1, 1, 1, 1, 1});
    assert_true(cansock_receive(&drv, &rx, 0u));
    assert_int_equal(rx.id, 0x601);
    assert_int_equal(rx.len, 3);
    assert_int_equal(rx.data[1], 0x3E);
    assert_true(cansock_receive(&drv, &rx, 0u));
    assert_int_equal(rx.id, 0x110);                       /* bus order kept */
    assert_false(cansock_receive(&drv, &rx, 0u));
    assert_int_equal(drv.st.rx_frames, 2);
    assert_int_equal(drv.st.rx_foreign, 2);
    assert_int_equal(drv.st.error_frames, 1);
    assert_int_equal(drv.st.tx_err_counter, 96);
    assert_int_equal(drv.st.rx_err_counter, 12);
    assert_false(drv.bus_off);                            /* an ACK error is not bus-off */
    /* a frame that cannot go on the wire is refused without writing */
    const can_frame_t bad = {.id = 0x800, .len = 1};
    assert_false(cansock_send(&drv, &bad));
    assert_false(pair_take(&seen));
}

/* The socket's buffer fills when nobody drains the bus: EAGAIN, the frame is refused (not
 * lost in the driver, not blocking); tx_idle is false until the bus took every frame. */
static void test_full_queue_eagain_then_drains(void **state)
{
    (void)state;
    can_frame_t f = {.id = 0x1A0, .len = 8};
    uint32_t sent = 0u;
    while (sent < 100000u) {
        memcpy(f.data, &sent, sizeof(sent));
        if (!cansock_send(&drv, &f)) {
            break;
        }
        sent++;
    }
    assert_true(sent > 0u && sent < 100000u);
    assert_int_equal(drv.st.tx_full, 1);
    assert_int_equal(drv.st.tx_errors, 0);
    assert_false(cansock_tx_idle(&drv));
    assert_false(cansock_send(&drv, &f));                  /* still full */
    assert_int_equal(drv.st.tx_full, 2);
    struct can_frame seen;
    for (uint32_t i = 0; i < sent; i++) {
        assert_true(pair_take(&seen));
        uint32_t k;
        memcpy(&k, seen.data, sizeof(k));
        assert_int_equal(k, i);                            /* every accepted frame, in order */
    }
    assert_false(pair_take(&seen));
    assert_true(cansock_tx_idle(&drv));
    assert_true(cansock_send(&drv, &f));
    assert_int_equal(drv.st.tx_frames, sent + 1u);
}

/* ENOBUFS is how a CAN raw socket reports the interface's queue (txqueuelen) full: refused as
 * "full", the next write goes through; other errors are counted apart with their errno. */
static void test_enobufs_and_write_errors(void **state)
{
    (void)state;
    const can_frame_t f = {.id = 0x180, .len = 8};
    pair_ctl.write_fail_count = 2u;
    pair_ctl.write_fail_errno = ENOBUFS;
    assert_false(cansock_send(&drv, &f));
    assert_false(cansock_send(&drv, &f));
    assert_true(cansock_send(&drv, &f));
    assert_int_equal(drv.st.tx_full, 2);
    assert_int_equal(drv.st.tx_frames, 1);
    struct can_frame seen;
    assert_true(pair_take(&seen));
    assert_false(pair_take(&seen));
    pair_ctl.write_fail_count = 1u;
    pair_ctl.write_fail_errno = ENETDOWN;
    assert_false(cansock_send(&drv, &f));
    assert_int_equal(drv.st.tx_errors, 1);
    assert_int_equal(drv.last_tx_errno, ENETDOWN);
    assert_int_equal(drv.st.tx_full, 2);
}

/* Bus-off: latched from the error frame, every send refused; a restart is requested 100 ms
 * later and every 100 ms while it fails; Linux's "restarted" error frame clears it. */
static void test_bus_off_and_recovery(void **state)
{
    (void)state;
    can_frame_t rx;
    const can_frame_t f = {.id = 0x180, .len = 8};
    pair_put(CAN_ERR_FLAG | CAN_ERR_BUSOFF, CAN_ERR_DLC, NULL);
    pair_put(0x110, 8, (const uint8_t[]){0, 0, 0, 0, 0, 0, 0, 0});
    assert_true(cansock_receive(&drv, &rx, 5000u));       /* the data frame behind it */
    assert_true(drv.bus_off);
    assert_int_equal(drv.st.bus_offs, 1);
    assert_false(cansock_send(&drv, &f));
    assert_int_equal(drv.st.tx_bus_off, 1);
    struct can_frame seen;
    assert_false(pair_take(&seen));                        /* nothing reached the bus */
    /* a second bus-off frame while off is not a new transition */
    pair_put(CAN_ERR_FLAG | CAN_ERR_BUSOFF, CAN_ERR_DLC, NULL);
    assert_false(cansock_receive(&drv, &rx, 6000u));
    assert_int_equal(drv.st.bus_offs, 1);

    pair_ctl.restart_result = -EPERM;
    assert_false(cansock_receive(&drv, &rx, 104999u));
    assert_int_equal(pair_ctl.restart_calls, 0);           /* not before 100 ms */
    assert_false(cansock_receive(&drv, &rx, 105000u));
    assert_int_equal(pair_ctl.restart_calls, 1);
    assert_int_equal(drv.st.restart_failures, 1);
    assert_int_equal(drv.last_restart_errno, EPERM);
    assert_true(drv.bus_off);
    assert_false(cansock_receive(&drv, &rx, 150000u));
    assert_int_equal(pair_ctl.restart_calls, 1);           /* retried 100 ms later, not sooner */
    pair_ctl.restart_result = 0;
    assert_false(cansock_receive(&drv, &rx, 205000u));     /* restart, its frame read at once */
    assert_int_equal(pair_ctl.restart_calls, 2);
    assert_false(drv.bus_off);
    assert_true(cansock_send(&drv, &f));
    assert_true(pair_take(&seen));
    assert_int_equal(drv.st.restarts, 2);
    assert_int_equal(drv.st.error_frames, 3);

    /* a controller that restarted itself (restart-ms): the "restarted" frame alone clears */
    pair_put(CAN_ERR_FLAG | CAN_ERR_BUSOFF, CAN_ERR_DLC, NULL);
    assert_false(cansock_receive(&drv, &rx, 300000u));
    assert_true(drv.bus_off);
    pair_put(CAN_ERR_FLAG | CAN_ERR_RESTARTED, CAN_ERR_DLC, NULL);
    assert_false(cansock_receive(&drv, &rx, 310000u));
    assert_false(drv.bus_off);
    assert_int_equal(drv.st.bus_offs, 2);

    /* EBUSY from the restart: the controller is not bus-off any more */
    pair_put(CAN_ERR_FLAG | CAN_ERR_BUSOFF, CAN_ERR_DLC, NULL);
    assert_false(cansock_receive(&drv, &rx, 400000u));
    pair_ctl.restart_result = -EBUSY;
    assert_false(cansock_receive(&drv, &rx, 500000u));
    assert_false(drv.bus_off);
}

static void test_bitrate_requests(void **state)
{
    (void)state;
    pair_ctl.bitrate_bps = 500000u;
    assert_int_equal(cansock_set_bitrate(&drv, 500000u, err, sizeof(err)), 1);
    assert_int_equal(pair_ctl.set_calls, 0);               /* already there: nothing touched */
    assert_int_equal(cansock_set_bitrate(&drv, 1000000u, err, sizeof(err)), 0);
    assert_int_equal(pair_ctl.set_calls, 1);
    assert_int_equal(pair_ctl.bitrate_bps, 1000000u);

    pair_ctl.set_result = -EPERM;
    assert_int_equal(cansock_set_bitrate(&drv, 250000u, err, sizeof(err)), -EPERM);
    assert_non_null(strstr(err, "CAP_NET_ADMIN"));
    assert_non_null(strstr(err, "left as configured (1000000 bit/s)"));
    assert_null(strchr(err, '\n'));
    assert_int_equal(pair_ctl.bitrate_bps, 1000000u);

    pair_ctl.set_result = -EINVAL;
    assert_int_equal(cansock_set_bitrate(&drv, 250000u, err, sizeof(err)), -EINVAL);
    assert_non_null(strstr(err, "cannot set can0 to 250000 bit/s"));

    pair_ctl.get_result = -EOPNOTSUPP;
    const unsigned calls = pair_ctl.set_calls;
    assert_int_equal(cansock_set_bitrate(&drv, 250000u, err, sizeof(err)), -EOPNOTSUPP);
    assert_non_null(strstr(err, "no bit timing"));
    assert_int_equal(pair_ctl.set_calls, calls);           /* a vcan is never taken down */
}

/* The real operating-system side on this machine: without AF_CAN (or without the interface)
 * open fails with one line naming the cause. */
static void test_linux_ops_fail_with_one_line(void **state)
{
    (void)state;
    cansock_t c;
    const int r = cansock_open(&c, NULL, "nosuchcan9", err, sizeof(err));
    assert_true(r < 0);
    assert_true(strstr(err, "AF_CAN") != NULL || strstr(err, "nosuchcan9") != NULL);
    assert_null(strchr(err, '\n'));
    assert_int_equal(c.fd, -1);
}

/* struct canfd_frame as <linux/can.h> documents it: can_id at 0, len at 4, flags at 5 (CANFD_BRS
 * 0x01, CANFD_FDF 0x04), two reserved bytes, data[64] at 8; 72 bytes (CANFD_MTU). */
static void test_fd_conversion_matches_kernel_layout(void **state)
{
    (void)state;
    assert_int_equal(sizeof(struct canfd_frame), 72);
    can_frame_t f = {.id = 0x680, .len = 64, .flags = CAN_FRAME_FD | CAN_FRAME_BRS};
    for (uint8_t i = 0; i < 64u; i++) {
        f.data[i] = (uint8_t)(i + 1u);
    }
    struct canfd_frame lf;
    memset(&lf, 0x55, sizeof(lf));
    assert_int_equal(cansock_to_linux_fd(&f, &lf), CANFD_MTU);
    uint8_t raw[72];
    memcpy(raw, &lf, sizeof(raw));
    uint32_t id;
    memcpy(&id, raw, 4);
    assert_int_equal(id, 0x680);
    assert_int_equal(raw[4], 64);
    assert_int_equal(raw[5], 0x01 | 0x04);
    assert_int_equal(raw[6], 0);
    assert_int_equal(raw[7], 0);
    assert_memory_equal(raw + 8, f.data, 64);
    /* a classic frame goes out in struct can_frame's 16 bytes */
    const can_frame_t c8 = {.id = 0x190, .len = 8, .data = {1, 2, 3, 4, 5, 6, 7, 8}};
    assert_int_equal(cansock_to_linux_fd(&c8, &lf), CAN_MTU);
    /* refused: FD length 13 (not a DLC length), BRS on a classic frame, 29-bit id */
    const can_frame_t bad_len = {.id = 0x680, .len = 13, .flags = CAN_FRAME_FD};
    const can_frame_t brs_classic = {.id = 0x680, .len = 8, .flags = CAN_FRAME_BRS};
    const can_frame_t big_id = {.id = 0x800, .len = 12, .flags = CAN_FRAME_FD};
    assert_int_equal(cansock_to_linux_fd(&bad_len, &lf), 0);
    assert_int_equal(cansock_to_linux_fd(&brs_classic, &lf), 0);
    assert_int_equal(cansock_to_linux_fd(&big_id, &lf), 0);
    /* back: flags from CANFD_BRS, 20 bytes; a bad FD length is foreign */
    struct canfd_frame in;
    memset(&in, 0, sizeof(in));
    in.can_id = 0x600;
    in.len = 20;
    in.flags = CANFD_BRS | CANFD_FDF;
    memset(in.data, 0xA5, 20);
    can_frame_t out;
    assert_int_equal(cansock_from_linux_fd(&in, CANFD_MTU, &out), CANSOCK_RX_DATA);
    assert_int_equal(out.id, 0x600);
    assert_int_equal(out.len, 20);
    assert_int_equal(out.flags, CAN_FRAME_FD | CAN_FRAME_BRS);
    in.len = 21;
    assert_int_equal(cansock_from_linux_fd(&in, CANFD_MTU, &out), CANSOCK_RX_FOREIGN);
    assert_int_equal(cansock_from_linux_fd(&in, 40u, &out), CANSOCK_RX_FOREIGN);
}

/* CAN FD over the pair: refused on a classic-only interface (the socket stays classic and FD
 * frames are refused on the way out); enabled, 64-byte BRS frames both ways and classic frames
 * still pass. */
static void test_fd_mode(void **state)
{
    (void)state;
    const can_frame_t fd64 = {.id = 0x680, .len = 64, .flags = CAN_FRAME_FD | CAN_FRAME_BRS,
                              .data = {0x10, 0x40, 0xAB}};
    const can_frame_t c8 = {.id = 0x180, .len = 8, .data = {1, 2, 3, 4, 5, 6, 7, 8}};
    pair_ctl.fd_capable = false;
    assert_int_equal(cansock_enable_fd(&drv, err, sizeof(err)), -EOPNOTSUPP);
    assert_non_null(strstr(err, "not CAN FD capable"));
    assert_false(drv.fd_mode);
    assert_false(cansock_send(&drv, &fd64));

    pair_ctl.fd_capable = true;
    assert_int_equal(cansock_enable_fd(&drv, err, sizeof(err)), 0);
    assert_true(drv.fd_mode);
    assert_true(cansock_send(&drv, &fd64));
    assert_true(cansock_send(&drv, &c8));
    struct canfd_frame lf;
    assert_int_equal(pair_take_any(&lf), CANFD_MTU);
    assert_int_equal(lf.len, 64);
    assert_int_equal(lf.flags, CANFD_BRS | CANFD_FDF);
    assert_int_equal(lf.data[2], 0xAB);
    assert_int_equal(pair_take_any(&lf), CAN_MTU);
    assert_int_equal(lf.len, 8);
    assert_int_equal(drv.st.tx_frames, 2);
    assert_int_equal(drv.st.tx_fd_frames, 1);

    const uint8_t d[48] = {0x30, 0x00, 0x00, 7};
    pair_put_fd(0x600, 48, CANFD_BRS | CANFD_FDF, d);
    pair_put(0x601, 2, d);
    pair_put_fd(CAN_ERR_FLAG | CAN_ERR_BUSOFF, CAN_ERR_DLC, 0, NULL); /* an error frame, FD-sized */
    can_frame_t f;
    assert_true(cansock_receive(&drv, &f, 0));
    assert_int_equal(f.id, 0x600);
    assert_int_equal(f.len, 48);
    assert_int_equal(f.flags, CAN_FRAME_FD | CAN_FRAME_BRS);
    assert_int_equal(f.data[3], 7);
    assert_true(cansock_receive(&drv, &f, 0));
    assert_int_equal(f.id, 0x601);
    assert_int_equal(f.flags, 0);
    assert_false(cansock_receive(&drv, &f, 0));
    assert_true(drv.bus_off);
    assert_int_equal(drv.st.rx_fd_frames, 1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_conversion_matches_kernel_layout),
        cmocka_unit_test_setup_teardown(test_open_makes_non_blocking_and_refuses_bad_names, setup, teardown),
        cmocka_unit_test_setup_teardown(test_send_and_receive, setup, teardown),
        cmocka_unit_test_setup_teardown(test_full_queue_eagain_then_drains, setup, teardown),
        cmocka_unit_test_setup_teardown(test_enobufs_and_write_errors, setup, teardown),
        cmocka_unit_test_setup_teardown(test_bus_off_and_recovery, setup, teardown),
        cmocka_unit_test_setup_teardown(test_bitrate_requests, setup, teardown),
        cmocka_unit_test(test_linux_ops_fail_with_one_line),
        cmocka_unit_test(test_fd_conversion_matches_kernel_layout),
        cmocka_unit_test_setup_teardown(test_fd_mode, setup, teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

/* SocketCAN backend of the host port: open an interface, send a frame, receive one sent by a
 * second raw socket. Needs AF_CAN and a virtual interface (ip link add dev vcan0 type vcan; ip
 * link set up vcan0); where the kernel has no SocketCAN the test is skipped with that message. */
#define _GNU_SOURCE
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <cmocka.h>

#include <errno.h>
#include <linux/can.h>
#include <net/if.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <unistd.h>

#include "hal_host.h"

#define IFACE "vcan0"

static void test_socketcan_roundtrip(void **state)
{
    (void)state;
    const int probe = socket(PF_CAN, SOCK_RAW, CAN_RAW);
    if (probe < 0) {
        fprintf(stderr, "SKIP: no SocketCAN in this kernel (socket(AF_CAN): %s)\n", strerror(errno));
        skip();
    }
    struct ifreq ifr;
    memset(&ifr, 0, sizeof(ifr));
    memcpy(ifr.ifr_name, IFACE, sizeof(IFACE));
    if (ioctl(probe, SIOCGIFINDEX, &ifr) < 0) {
        close(probe);
        fprintf(stderr, "SKIP: no %s interface (ip link add dev %s type vcan && ip link set up %s)\n",
                IFACE, IFACE, IFACE);
        skip();
    }
    struct sockaddr_can addr;
    memset(&addr, 0, sizeof(addr));
    addr.can_family = AF_CAN;
    addr.can_ifindex = ifr.ifr_ifindex;
    assert_int_equal(bind(probe, (struct sockaddr *)&addr, sizeof(addr)), 0);

    char err[160];
    assert_int_equal(hal_socketcan_open(IFACE, 0u, err, sizeof(err)), 0);
    const can_frame_t tx = {.id = 0x181, .len = 3, .data = {1, 2, 3}};
    assert_true(hal_can_send(&tx));
    struct can_frame seen;
    assert_int_equal(read(probe, &seen, sizeof(seen)), (ssize_t)sizeof(seen));
    assert_int_equal(seen.can_id, 0x181);
    assert_int_equal(seen.can_dlc, 3);
    struct can_frame other = {.can_id = 0x601, .can_dlc = 2, .data = {0x3E, 0x00}};
    assert_int_equal(write(probe, &other, sizeof(other)), (ssize_t)sizeof(other));
    can_frame_t rx;
    bool got = false;
    for (int i = 0; i < 100 && !got; i++) {
        got = hal_can_receive(&rx);
        if (!got) {
            usleep(1000);
        }
    }
    assert_true(got);
    assert_int_equal(rx.id, 0x601);
    assert_int_equal(rx.data[0], 0x3E);
    assert_false(hal_can_bus_off());
    hal_socketcan_close();
    close(probe);
}

static void test_missing_interface_named(void **state)
{
    (void)state;
    char err[160];
    const int rc = hal_socketcan_open("nosuchcan9", 0u, err, sizeof(err));
    assert_true(rc < 0);
    /* either no AF_CAN at all, or the interface is named in the message */
    assert_true(strstr(err, "AF_CAN") != NULL || strstr(err, "nosuchcan9") != NULL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_socketcan_roundtrip),
        cmocka_unit_test(test_missing_interface_named),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

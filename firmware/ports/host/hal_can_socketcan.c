/* Host port, SocketCAN backend: a raw CAN socket (non-blocking) for a real Linux controller or
 * adapter; libsocketcan sets the bitrate and restarts after bus-off. */
#define _GNU_SOURCE
#include "hal_host.h"

#include <errno.h>
#include <fcntl.h>
#include <linux/can.h>
#include <linux/can/error.h>
#include <linux/can/raw.h>
#include <linux/sockios.h>
#include <net/if.h>
#include <stdio.h>
#include <string.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <unistd.h>

#include <libsocketcan.h>

static int g_sock = -1;
static char g_ifname[IFNAMSIZ];
static bool g_bus_off;

int hal_socketcan_open(const char *ifname, uint32_t bitrate, char *err, uint32_t err_len)
{
    if (strlen(ifname) >= IFNAMSIZ) {
        snprintf(err, err_len, "interface name '%s' too long", ifname);
        return -EINVAL;
    }
    if (bitrate > 0u) {
        if (can_do_stop(ifname) != 0 || can_set_bitrate(ifname, bitrate) != 0 ||
            can_do_start(ifname) != 0) {
            const int e = errno != 0 ? errno : EIO;
            snprintf(err, err_len, "cannot set bitrate %u on %s: %s", bitrate, ifname, strerror(e));
            return -e;
        }
    }
    const int s = socket(PF_CAN, SOCK_RAW, CAN_RAW);
    if (s < 0) {
        const int e = errno;
        snprintf(err, err_len, "socket(AF_CAN) failed: %s (no SocketCAN in this kernel?)",
                 strerror(e));
        return -e;
    }
    struct ifreq ifr;
    memset(&ifr, 0, sizeof(ifr));
    memcpy(ifr.ifr_name, ifname, strlen(ifname));
    if (ioctl(s, SIOCGIFINDEX, &ifr) < 0) {
        const int e = errno;
        snprintf(err, err_len, "no CAN interface '%s': %s", ifname, strerror(e));
        close(s);
        return -e;
    }
    const can_err_mask_t mask = CAN_ERR_BUSOFF | CAN_ERR_RESTARTED;
    (void)setsockopt(s, SOL_CAN_RAW, CAN_RAW_ERR_FILTER, &mask, sizeof(mask));
    struct sockaddr_can addr;
    memset(&addr, 0, sizeof(addr));
    addr.can_family = AF_CAN;
    addr.can_ifindex = ifr.ifr_ifindex;
    if (bind(s, (struct sockaddr *)&addr, sizeof(addr)) < 0) {
        const int e = errno;
        snprintf(err, err_len, "bind to '%s' failed: %s", ifname, strerror(e));
        close(s);
        return -e;
    }
    (void)fcntl(s, F_SETFL, fcntl(s, F_GETFL) | O_NONBLOCK);
    g_sock = s;
    memcpy(g_ifname, ifname, strlen(ifname) + 1u);
    g_bus_off = false;
    return 0;
}

void hal_socketcan_close(void)
{
    if (g_sock >= 0) {
        close(g_sock);
        g_sock = -1;
    }
}

bool hal_can_send(const can_frame_t *frame)
{
    if (g_sock < 0 || frame->dlc > CAN_FRAME_MAX_DLC) {
        return false;
    }
    struct can_frame f;
    memset(&f, 0, sizeof(f));
    f.can_id = frame->id & CAN_SFF_MASK;
    f.can_dlc = frame->dlc;
    memcpy(f.data, frame->data, frame->dlc);
    return write(g_sock, &f, sizeof(f)) == (ssize_t)sizeof(f);
}

bool hal_can_receive(can_frame_t *frame)
{
    while (g_sock >= 0) {
        struct can_frame f;
        const ssize_t n = read(g_sock, &f, sizeof(f));
        if (n != (ssize_t)sizeof(f)) {
            return false;
        }
        if ((f.can_id & CAN_ERR_FLAG) != 0u) {
            if ((f.can_id & CAN_ERR_BUSOFF) != 0u) {
                g_bus_off = true;
                (void)can_do_restart(g_ifname); /* the fault latches; the bus may come back */
            }
            if ((f.can_id & CAN_ERR_RESTARTED) != 0u) {
                g_bus_off = false;
            }
            continue;
        }
        if ((f.can_id & (CAN_EFF_FLAG | CAN_RTR_FLAG)) != 0u) {
            continue; /* 11-bit data frames only on this product */
        }
        frame->id = f.can_id & CAN_SFF_MASK;
        frame->dlc = f.can_dlc;
        memcpy(frame->data, f.data, CAN_FRAME_MAX_DLC);
        return true;
    }
    return false;
}

bool hal_can_bus_off(void)
{
    return g_bus_off;
}

bool hal_can_tx_idle(void)
{
    /* bytes of frames written to the socket that the driver has not sent yet */
    int pending = 0;
    if (g_sock < 0 || ioctl(g_sock, SIOCOUTQ, &pending) != 0) {
        return true;
    }
    return pending == 0;
}

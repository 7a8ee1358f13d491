/* cansock_linux_ops (see cansock.h): an AF_CAN raw socket, libsocketcan for the bit rate and the
 * bus-off restart. libsocketcan reports its own failures on stderr (perror); the callers of the
 * driver print one line of their own, so stderr is pointed at /dev/null around its calls. */
#define _GNU_SOURCE
#include "cansock.h"

#include <errno.h>
#include <fcntl.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <stdio.h>
#include <string.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <unistd.h>

#include <libsocketcan.h>

static int quiet_begin(void)
{
    fflush(stderr);
    const int saved = dup(STDERR_FILENO);
    const int nul = open("/dev/null", O_WRONLY | O_CLOEXEC);
    if (saved >= 0 && nul >= 0) {
        (void)dup2(nul, STDERR_FILENO);
    }
    if (nul >= 0) {
        close(nul);
    }
    return saved;
}

static void quiet_end(int saved)
{
    if (saved >= 0) {
        fflush(stderr);
        (void)dup2(saved, STDERR_FILENO);
        close(saved);
    }
}

/* -errno of a failed libsocketcan call (EIO when it failed without setting errno) */
static int failed(void)
{
    return errno != 0 ? -errno : -EIO;
}

static int linux_open_raw(const char *ifname, char *err, uint32_t err_len)
{
    const int s = socket(PF_CAN, SOCK_RAW | SOCK_CLOEXEC, CAN_RAW);
    if (s < 0) {
        const int e = errno;
        snprintf(err, err_len,
                 "socket(AF_CAN) failed: %s (this kernel has no SocketCAN: "
                 "modprobe can_raw, or serve the bus over TCP without --socketcan)",
                 strerror(e));
        return -e;
    }
    struct ifreq ifr;
    memset(&ifr, 0, sizeof(ifr));
    memcpy(ifr.ifr_name, ifname, strnlen(ifname, IFNAMSIZ - 1u));
    if (ioctl(s, SIOCGIFINDEX, &ifr) < 0) {
        const int e = errno;
        snprintf(err, err_len, "no CAN interface '%s': %s", ifname, strerror(e));
        close(s);
        return -e;
    }
    const can_err_mask_t mask = CANSOCK_ERR_MASK;
    if (setsockopt(s, SOL_CAN_RAW, CAN_RAW_ERR_FILTER, &mask, sizeof(mask)) != 0) {
        const int e = errno;
        snprintf(err, err_len, "cannot enable error frames on '%s': %s", ifname, strerror(e));
        close(s);
        return -e;
    }
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
    return s;
}

static int linux_get_bitrate(const char *ifname, uint32_t *bitrate_bps)
{
    if (if_nametoindex(ifname) == 0u) {
        return -ENODEV;
    }
    struct can_bittiming bt;
    memset(&bt, 0, sizeof(bt));
    struct can_bittiming_const btc;
    memset(&btc, 0, sizeof(btc));
    const int q = quiet_begin();
    const int r = can_get_bittiming(ifname, &bt);
    /* a controller whose rate was never set reports no bit timing but its limits (vcan: neither) */
    const int c = r != 0 ? can_get_bittiming_const(ifname, &btc) : 0;
    quiet_end(q);
    if (r != 0 && c != 0) {
        return -EOPNOTSUPP; /* the interface exists but has no CAN bit timing */
    }
    *bitrate_bps = r == 0 ? bt.bitrate : 0u;
    return 0;
}

static int linux_set_bitrate(const char *ifname, uint32_t bitrate_bps)
{
    const int q = quiet_begin();
    errno = 0;
    int r = 0;
    if (can_do_stop(ifname) != 0) {
        r = failed(); /* EPERM without CAP_NET_ADMIN: nothing changed */
    } else {
        if (can_set_bitrate(ifname, bitrate_bps) != 0) {
            r = failed();
        }
        errno = 0;
        if (can_do_start(ifname) != 0 && r == 0) {
            r = failed();
        }
    }
    quiet_end(q);
    return r;
}

static int linux_restart(const char *ifname)
{
    const int q = quiet_begin();
    errno = 0;
    const int r = can_do_restart(ifname) != 0 ? failed() : 0;
    quiet_end(q);
    return r;
}

static ssize_t linux_write_frame(int fd, const void *frame, size_t size)
{
    return write(fd, frame, size);
}

static int linux_enable_fd(int fd, const char *ifname, char *err, uint32_t err_len)
{
    struct ifreq ifr;
    memset(&ifr, 0, sizeof(ifr));
    memcpy(ifr.ifr_name, ifname, strnlen(ifname, IFNAMSIZ - 1u));
    if (ioctl(fd, SIOCGIFMTU, &ifr) < 0) {
        const int e = errno;
        snprintf(err, err_len, "cannot read the MTU of '%s': %s", ifname, strerror(e));
        return -e;
    }
    if (ifr.ifr_mtu != (int)CANFD_MTU) {
        snprintf(err, err_len,
                 "%s is not CAN FD capable (MTU %d; CAN FD needs %u: an FD controller, or "
                 "ip link set %s mtu %u on vcan)",
                 ifname, ifr.ifr_mtu, (unsigned)CANFD_MTU, ifname, (unsigned)CANFD_MTU);
        return -EOPNOTSUPP;
    }
    const int on = 1;
    if (setsockopt(fd, SOL_CAN_RAW, CAN_RAW_FD_FRAMES, &on, sizeof(on)) != 0) {
        const int e = errno;
        snprintf(err, err_len, "cannot enable CAN FD frames on '%s': %s", ifname, strerror(e));
        return -e;
    }
    return 0;
}

const cansock_ops_t cansock_linux_ops = {
    .open_raw = linux_open_raw,
    .get_bitrate = linux_get_bitrate,
    .set_bitrate = linux_set_bitrate,
    .restart = linux_restart,
    .write_frame = linux_write_frame,
    .enable_fd = linux_enable_fd,
};

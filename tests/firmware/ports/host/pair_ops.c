/* cansock_ops_t over a socket pair (see pair_ops.h). */
#define _GNU_SOURCE
#include "pair_ops.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <unistd.h>

pair_ctl_t pair_ctl = {.bus_fd = -1};

void pair_reset(void)
{
    if (pair_ctl.bus_fd >= 0) {
        close(pair_ctl.bus_fd);
    }
    memset(&pair_ctl, 0, sizeof(pair_ctl));
    pair_ctl.bus_fd = -1;
}

static int pair_open_raw(const char *ifname, char *err, uint32_t err_len)
{
    if (pair_ctl.open_result < 0) {
        snprintf(err, err_len, "no CAN interface '%s': %s", ifname, strerror(-pair_ctl.open_result));
        return pair_ctl.open_result;
    }
    int sv[2];
    if (socketpair(AF_UNIX, SOCK_SEQPACKET, 0, sv) != 0) {
        snprintf(err, err_len, "socketpair: %s", strerror(errno));
        return -errno;
    }
    (void)fcntl(sv[1], F_SETFL, fcntl(sv[1], F_GETFL) | O_NONBLOCK);
    pair_ctl.bus_fd = sv[1];
    return sv[0];                   /* blocking: the driver must make it non-blocking itself */
}

static int pair_get_bitrate(const char *ifname, uint32_t *bitrate_bps)
{
    (void)ifname;
    if (pair_ctl.get_result == 0) {
        *bitrate_bps = pair_ctl.bitrate_bps;
    }
    return pair_ctl.get_result;
}

static int pair_set_bitrate(const char *ifname, uint32_t bitrate_bps)
{
    (void)ifname;
    pair_ctl.set_calls++;
    if (pair_ctl.set_result == 0) {
        pair_ctl.bitrate_bps = bitrate_bps;
    }
    return pair_ctl.set_result;
}

static int pair_restart(const char *ifname)
{
    (void)ifname;
    pair_ctl.restart_calls++;
    if (pair_ctl.restart_result == 0) {
        pair_put(CAN_ERR_FLAG | CAN_ERR_RESTARTED, CAN_ERR_DLC, NULL);   /* as Linux's can_restart() */
    }
    return pair_ctl.restart_result;
}

static ssize_t pair_write_frame(int fd, const void *frame, size_t size)
{
    if (pair_ctl.write_fail_count > 0u) {
        pair_ctl.write_fail_count--;
        errno = pair_ctl.write_fail_errno;
        return -1;
    }
    return write(fd, frame, size);
}

static int pair_enable_fd(int fd, const char *ifname, char *err, uint32_t err_len)
{
    (void)fd;
    if (!pair_ctl.fd_capable) {
        snprintf(err, err_len, "%s is not CAN FD capable (MTU 16)", ifname);
        return -EOPNOTSUPP;
    }
    return 0;
}

const cansock_ops_t pair_ops = {
    .open_raw = pair_open_raw,
    .get_bitrate = pair_get_bitrate,
    .set_bitrate = pair_set_bitrate,
    .restart = pair_restart,
    .write_frame = pair_write_frame,
    .enable_fd = pair_enable_fd,
};

void pair_put(uint32_t can_id, uint8_t len, const uint8_t *data)
{
    struct can_frame f;
    memset(&f, 0, sizeof(f));
    f.can_id = can_id;
    f.len = len;
    if (data != NULL) {
        memcpy(f.data, data, len > CAN_MAX_DLEN ? CAN_MAX_DLEN : len);
    }
    if (write(pair_ctl.bus_fd, &f, sizeof(f)) != (ssize_t)sizeof(f)) {
        abort();
    }
}

bool pair_take(struct can_frame *f)
{
    return read(pair_ctl.bus_fd, f, sizeof(*f)) == (ssize_t)sizeof(*f);
}

void pair_put_fd(uint32_t can_id, uint8_t len, uint8_t flags, const uint8_t *data)
{
    struct canfd_frame f;
    memset(&f, 0, sizeof(f));
    f.can_id = can_id;
    f.len = len;
    f.flags = flags;
    if (data != NULL) {
        memcpy(f.data, data, len > CANFD_MAX_DLEN ? CANFD_MAX_DLEN : len);
    }
    if (write(pair_ctl.bus_fd, &f, sizeof(f)) != (ssize_t)sizeof(f)) {
        abort();
    }
}

ssize_t pair_take_any(struct canfd_frame *f)
{
    return read(pair_ctl.bus_fd, f, sizeof(*f));
}

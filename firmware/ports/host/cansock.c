/* SocketCAN driver of the host port (see cansock.h): the part that does not depend on how the
 * socket was opened. */
#define _GNU_SOURCE
#include "cansock.h"

#include <errno.h>
#include <fcntl.h>
#include <linux/can/error.h>
#include <linux/sockios.h>
#include <stdio.h>
#include <string.h>
#include <sys/ioctl.h>
#include <unistd.h>

#define US_PER_MS 1000u

void cansock_init(cansock_t *c)
{
    memset(c, 0, sizeof(*c));
    c->fd = -1;
}

bool cansock_valid_ifname(const char *name)
{
    const size_t n = strlen(name);
    if (n == 0u || n >= CANSOCK_IFNAME_MAX || strcmp(name, ".") == 0 || strcmp(name, "..") == 0) {
        return false;
    }
    for (size_t i = 0; i < n; i++) {
        const unsigned char ch = (unsigned char)name[i];
        if (ch == '/' || ch == ':' || ch <= ' ' || ch == 0x7Fu) {
            return false;
        }
    }
    return true;
}

int cansock_open(cansock_t *c, const cansock_ops_t *ops, const char *ifname, char *err,
                 uint32_t err_len)
{
    cansock_init(c);
    c->ops = ops != NULL ? ops : &cansock_linux_ops;
    if (!cansock_valid_ifname(ifname)) {
        snprintf(err, err_len,
                 "invalid interface name '%.40s' (1..%u characters, no '/', ':' or spaces)", ifname,
                 CANSOCK_IFNAME_MAX - 1u);
        return -EINVAL;
    }
    const int fd = c->ops->open_raw(ifname, err, err_len);
    if (fd < 0) {
        return fd;
    }
    const int fl = fcntl(fd, F_GETFL);
    if (fl < 0 || fcntl(fd, F_SETFL, fl | O_NONBLOCK) != 0) {
        const int e = errno;
        snprintf(err, err_len, "cannot make the socket of %s non-blocking: %s", ifname,
                 strerror(e));
        close(fd);
        return -e;
    }
    c->fd = fd;
    memcpy(c->ifname, ifname, strlen(ifname) + 1u);
    return 0;
}

int cansock_set_bitrate(cansock_t *c, uint32_t bitrate_bps, char *err, uint32_t err_len)
{
    uint32_t now_bps = 0u;
    const int g = c->ops->get_bitrate(c->ifname, &now_bps);
    if (g == -EOPNOTSUPP) {
        snprintf(err, err_len, "%s has no bit timing (a virtual interface such as vcan has none)",
                 c->ifname);
        return g;
    }
    if (g == 0 && now_bps == bitrate_bps) {
        return 1;
    }
    const int r = c->ops->set_bitrate(c->ifname, bitrate_bps);
    if (r == 0) {
        return 0;
    }
    char was[40] = "unknown bit rate";
    if (g == 0) {
        snprintf(was, sizeof(was), "%u bit/s", now_bps);
    }
    if (r == -EPERM || r == -EACCES) {
        snprintf(err, err_len,
                 "setting %s to %u bit/s needs CAP_NET_ADMIN (root, or setcap "
                 "cap_net_admin+ep on the program); %s left as configured (%s)",
                 c->ifname, bitrate_bps, c->ifname, was);
    } else {
        snprintf(err, err_len, "cannot set %s to %u bit/s: %s (was %s)", c->ifname, bitrate_bps,
                 strerror(-r), was);
    }
    return r;
}

int cansock_enable_fd(cansock_t *c, char *err, uint32_t err_len)
{
    if (c->fd < 0) {
        snprintf(err, err_len, "CAN FD on a closed interface");
        return -EBADF;
    }
    if (c->ops->enable_fd == NULL) {
        snprintf(err, err_len, "%s: CAN FD not supported here", c->ifname);
        return -EOPNOTSUPP;
    }
    const int r = c->ops->enable_fd(c->fd, c->ifname, err, err_len);
    if (r == 0) {
        c->fd_mode = true;
    }
    return r;
}

void cansock_close(cansock_t *c)
{
    if (c->fd >= 0) {
        close(c->fd);
        c->fd = -1;
    }
}

bool cansock_to_linux(const can_frame_t *f, struct can_frame *out)
{
    if (f->id > CAN_SFF_MASK || f->len > CAN_MAX_DLEN || (f->flags & CAN_FRAME_FD) != 0u) {
        return false;
    }
    memset(out, 0, sizeof(*out));
    out->can_id = f->id;
    out->len = f->len;
    memcpy(out->data, f->data, f->len);
    return true;
}

size_t cansock_to_linux_fd(const can_frame_t *f, struct canfd_frame *out)
{
    if (f->id > CAN_SFF_MASK || !can_frame_len_ok(f)) {
        return 0u;
    }
    if ((f->flags & CAN_FRAME_FD) == 0u) {
        struct can_frame cf;
        if (!cansock_to_linux(f, &cf)) {
            return 0u;
        }
        memset(out, 0, sizeof(*out));
        memcpy(out, &cf, sizeof(cf)); /* struct can_frame is the head of struct canfd_frame */
        return CAN_MTU;
    }
    memset(out, 0, sizeof(*out));
    out->can_id = f->id;
    out->len = f->len;
    out->flags = (uint8_t)(CANFD_FDF | ((f->flags & CAN_FRAME_BRS) != 0u ? CANFD_BRS : 0u));
    memcpy(out->data, f->data, f->len);
    return CANFD_MTU;
}

cansock_rx_kind_t cansock_from_linux_fd(const struct canfd_frame *in, size_t size, can_frame_t *out)
{
    if (size == CAN_MTU) {
        struct can_frame cf;
        memcpy(&cf, in, sizeof(cf));
        return cansock_from_linux(&cf, out);
    }
    if (size != CANFD_MTU) {
        return CANSOCK_RX_FOREIGN;
    }
    if ((in->can_id & CAN_ERR_FLAG) != 0u) {
        return CANSOCK_RX_ERROR;
    }
    const can_frame_t probe = {.len = in->len, .flags = CAN_FRAME_FD};
    if ((in->can_id & (CAN_EFF_FLAG | CAN_RTR_FLAG)) != 0u || !can_frame_len_ok(&probe)) {
        return CANSOCK_RX_FOREIGN;
    }
    memset(out, 0, sizeof(*out));
    out->id = in->can_id & CAN_SFF_MASK;
    out->len = in->len;
    out->flags = (uint8_t)(CAN_FRAME_FD | ((in->flags & CANFD_BRS) != 0u ? CAN_FRAME_BRS : 0u));
    memcpy(out->data, in->data, in->len);
    return CANSOCK_RX_DATA;
}

cansock_rx_kind_t cansock_from_linux(const struct can_frame *in, can_frame_t *out)
{
    if ((in->can_id & CAN_ERR_FLAG) != 0u) {
        return CANSOCK_RX_ERROR;
    }
    if ((in->can_id & (CAN_EFF_FLAG | CAN_RTR_FLAG)) != 0u || in->len > CAN_MAX_DLEN) {
        return CANSOCK_RX_FOREIGN;
    }
    memset(out, 0, sizeof(*out));
    out->id = in->can_id & CAN_SFF_MASK;
    out->len = in->len;
    memcpy(out->data, in->data, in->len);
    return CANSOCK_RX_DATA;
}

bool cansock_send(cansock_t *c, const can_frame_t *f)
{
    struct canfd_frame lf;
    size_t size = 0u;
    if (c->fd_mode) {
        size = cansock_to_linux_fd(f, &lf);
    } else {
        struct can_frame cf;
        if (cansock_to_linux(f, &cf)) {
            memcpy(&lf, &cf, sizeof(cf));
            size = CAN_MTU;
        }
    }
    if (c->fd < 0 || size == 0u) {
        return false;
    }
    if (c->bus_off) {
        c->st.tx_bus_off++;
        return false;
    }
    const ssize_t n = c->ops->write_frame(c->fd, &lf, size);
    if (n == (ssize_t)size) {
        c->st.tx_frames++;
        c->st.tx_fd_frames += size == CANFD_MTU ? 1u : 0u;
        return true;
    }
    const int e = n < 0 ? errno : EIO;
    if (e == EAGAIN || e == EWOULDBLOCK || e == ENOBUFS) {
        c->st.tx_full++;
    } else {
        c->st.tx_errors++;
        c->last_tx_errno = e;
    }
    return false;
}

void cansock_on_error_frame(cansock_t *c, const struct can_frame *f, uint64_t now_us)
{
    c->st.error_frames++;
    if ((f->can_id & CAN_ERR_CNT) != 0u) {
        c->st.tx_err_counter = f->data[6];
        c->st.rx_err_counter = f->data[7];
    }
    if ((f->can_id & CAN_ERR_BUSOFF) != 0u && !c->bus_off) {
        c->bus_off = true;
        c->st.bus_offs++;
        c->restart_at_us = now_us + (uint64_t)CANSOCK_RESTART_MS * US_PER_MS;
    }
    if ((f->can_id & CAN_ERR_RESTARTED) != 0u) {
        c->bus_off = false;
    }
}

/* While bus-off: ask for a restart every CANSOCK_RESTART_MS. It fails without CAP_NET_ADMIN or
 * when the interface restarts itself (ip link ... restart-ms); the "restarted" frame clears, and
 * so does EBUSY (Linux's answer when the controller is not bus-off any more). */
static void restart_when_timed_out(cansock_t *c, uint64_t now_us)
{
    if (!c->bus_off || now_us < c->restart_at_us) {
        return;
    }
    c->restart_at_us = now_us + (uint64_t)CANSOCK_RESTART_MS * US_PER_MS;
    c->st.restarts++;
    const int r = c->ops->restart(c->ifname);
    if (r == -EBUSY) {
        c->bus_off = false;
    } else if (r != 0) {
        c->st.restart_failures++;
        c->last_restart_errno = -r;
    }
}

bool cansock_receive(cansock_t *c, can_frame_t *f, uint64_t now_us)
{
    restart_when_timed_out(c, now_us);
    for (uint32_t skipped = 0u; c->fd >= 0 && skipped <= CANSOCK_RX_SKIP_MAX; skipped++) {
        struct canfd_frame lf;
        const ssize_t n = read(c->fd, &lf, c->fd_mode ? CANFD_MTU : CAN_MTU);
        if (n <= 0) {
            if (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR) {
                c->st.rx_errors++; /* e.g. ENETDOWN once when the interface goes down */
            }
            return false; /* nothing (more) to read; 0: the peer closed */
        }
        if (n != (ssize_t)CAN_MTU && (n != (ssize_t)CANFD_MTU || !c->fd_mode)) {
            c->st.rx_errors++;
            continue;
        }
        switch (cansock_from_linux_fd(&lf, (size_t)n, f)) {
        case CANSOCK_RX_DATA:
            c->st.rx_frames++;
            c->st.rx_fd_frames += (f->flags & CAN_FRAME_FD) != 0u ? 1u : 0u;
            return true;
        case CANSOCK_RX_ERROR: {
            struct can_frame ef;
            memcpy(&ef, &lf, sizeof(ef));
            cansock_on_error_frame(c, &ef, now_us);
            break;
        }
        case CANSOCK_RX_FOREIGN:
        default: c->st.rx_foreign++; break;
        }
    }
    return false;
}

bool cansock_tx_idle(const cansock_t *c)
{
    int pending = 0;
    if (c->fd < 0 || ioctl(c->fd, SIOCOUTQ, &pending) != 0) {
        return true;
    }
    return pending == 0;
}

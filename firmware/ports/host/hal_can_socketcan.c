/* Host port, SocketCAN backend: the HAL's CAN functions over one cansock_ driver (cansock.h): a
 * non-blocking raw socket on a Linux controller or adapter, libsocketcan for the bit rate and the
 * restart after bus-off. */
#include "hal_host.h"

#include <errno.h>

#include "cansock.h"

static cansock_t g_can = {.fd = -1};

int hal_socketcan_open_with(const struct cansock_ops *ops, const char *ifname, uint32_t bitrate,
                            char *err, uint32_t err_len)
{
    cansock_close(&g_can);
    const int r = cansock_open(&g_can, ops, ifname, err, err_len);
    if (r != 0 || bitrate == 0u) {
        return r;
    }
    const int b = cansock_set_bitrate(&g_can, bitrate, err, err_len);
    if (b < 0) {
        cansock_close(&g_can);
        return b;
    }
    return 0;
}

int hal_socketcan_open(const char *ifname, uint32_t bitrate, char *err, uint32_t err_len)
{
    return hal_socketcan_open_with(&cansock_linux_ops, ifname, bitrate, err, err_len);
}

void hal_socketcan_close(void)
{
    cansock_close(&g_can);
}

const struct cansock *hal_socketcan_driver(void)
{
    return &g_can;
}

bool hal_can_send(const can_frame_t *frame)
{
    return cansock_send(&g_can, frame);
}

bool hal_can_receive(can_frame_t *frame)
{
    return cansock_receive(&g_can, frame, hal_time_us());
}

bool hal_can_bus_off(void)
{
    return g_can.bus_off;
}

uint32_t hal_can_tx_free(void)
{
    return UINT32_MAX; /* the kernel queues (its qdisc, not this process, orders the frames) */
}

bool hal_can_send_bulk(const can_frame_t *frame, uint32_t keep)
{
    return hal_can_tx_free() > keep && hal_can_send(frame);
}

bool hal_can_tx_idle(void)
{
    return cansock_tx_idle(&g_can);
}

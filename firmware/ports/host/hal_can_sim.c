/* Host port, simulator CAN backend: two bounded FIFOs exchanged with hil_sim/bus. */
#include "hal_host.h"

#include <string.h>

static struct {
    can_frame_t tx[HAL_SIM_TX_QUEUE];
    uint32_t tx_head, tx_len;
    can_frame_t rx[HAL_SIM_RX_QUEUE];
    uint32_t rx_head, rx_len;
    bool bus_off;
    uint32_t rx_overflows;
} q;

void hal_sim_can_reset(void)
{
    memset(&q, 0, sizeof(q));
}

bool hal_can_send(const can_frame_t *frame)
{
    if (q.bus_off || q.tx_len >= HAL_SIM_TX_QUEUE || frame->dlc > CAN_FRAME_MAX_DLC) {
        return false;
    }
    q.tx[(q.tx_head + q.tx_len) % HAL_SIM_TX_QUEUE] = *frame;
    q.tx_len++;
    return true;
}

bool hal_can_receive(can_frame_t *frame)
{
    if (q.rx_len == 0u) {
        return false;
    }
    *frame = q.rx[q.rx_head];
    q.rx_head = (q.rx_head + 1u) % HAL_SIM_RX_QUEUE;
    q.rx_len--;
    return true;
}

bool hal_can_bus_off(void)
{
    return q.bus_off;
}

bool hal_can_tx_idle(void)
{
    return q.tx_len == 0u;
}

bool hal_sim_can_deliver(const can_frame_t *f)
{
    if (q.rx_len >= HAL_SIM_RX_QUEUE) {
        q.rx_overflows++;
        return false;
    }
    q.rx[(q.rx_head + q.rx_len) % HAL_SIM_RX_QUEUE] = *f;
    q.rx_len++;
    return true;
}

bool hal_sim_can_tx_peek(can_frame_t *f)
{
    if (q.tx_len == 0u) {
        return false;
    }
    *f = q.tx[q.tx_head];
    return true;
}

void hal_sim_can_tx_pop(void)
{
    if (q.tx_len > 0u) {
        q.tx_head = (q.tx_head + 1u) % HAL_SIM_TX_QUEUE;
        q.tx_len--;
    }
}

void hal_sim_can_set_bus_off(bool off)
{
    q.bus_off = off;
    if (off) {
        q.tx_len = 0u;
    }
}

uint32_t hal_sim_can_rx_overflows(void)
{
    return q.rx_overflows;
}

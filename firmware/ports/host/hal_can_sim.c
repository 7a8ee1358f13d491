/* Host port, simulator CAN backend: a transmit queue kept in identifier order (lowest first,
 * frames with the same identifier in the order they were queued: what the bus takes next is what
 * a controller's mailbox arbitration would send next) and a receive FIFO, exchanged with
 * hil_sim/bus. */
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

static can_frame_t *tx_at(uint32_t i)
{
    return &q.tx[(q.tx_head + i) % HAL_SIM_TX_QUEUE];
}

/* Insert in identifier order: after every queued frame with id <= f's (behind_equal), or before
 * every frame with id >= f's (a frame taken back from the bus goes first among its equals). */
static bool tx_insert(const can_frame_t *f, bool behind_equal)
{
    if (q.tx_len >= HAL_SIM_TX_QUEUE || !can_frame_len_ok(f)) {
        return false;
    }
    uint32_t pos = q.tx_len;
    while (pos > 0u &&
           (tx_at(pos - 1u)->id > f->id || (!behind_equal && tx_at(pos - 1u)->id == f->id))) {
        *tx_at(pos) = *tx_at(pos - 1u);
        pos--;
    }
    *tx_at(pos) = *f;
    q.tx_len++;
    return true;
}

bool hal_can_send(const can_frame_t *frame)
{
    return !q.bus_off && tx_insert(frame, true);
}

uint32_t hal_can_tx_free(void)
{
    return HAL_SIM_TX_QUEUE - q.tx_len;
}

bool hal_can_send_bulk(const can_frame_t *frame, uint32_t keep)
{
    return hal_can_tx_free() > keep && hal_can_send(frame);
}

bool hal_sim_can_tx_requeue(const can_frame_t *f)
{
    return tx_insert(f, false);
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
    if (q.bus_off) {
        return false; /* a controller off the bus receives nothing either */
    }
    if (q.rx_len >= HAL_SIM_RX_QUEUE) {
        q.rx_overflows++;
        return false;
    }
    q.rx[(q.rx_head + q.rx_len) % HAL_SIM_RX_QUEUE] = *f;
    q.rx_len++;
    return true;
}

uint32_t hal_sim_can_rx_free(void)
{
    return HAL_SIM_RX_QUEUE - q.rx_len;
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

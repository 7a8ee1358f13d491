/* The simulator's bus (hil_sim/bus/bus_model.h) arbitrates ALL pending frames of all sources by
 * identifier, and the host port's transmit queue (hal_can_sim.c) hands frames over in
 * identifier order: a low identifier queued behind a high one at the same node is not held back
 * (what a controller with several mailboxes does; a single FIFO per node did hold it back). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "bus_model.h"
#include "hal_host.h"

static bus_t bus;                /* large: static */
static can_frame_t got[64];
static unsigned n_got;

static void on_frame(void *ctx, const bus_item_t *it, uint64_t t_end_ns)
{
    (void)ctx;
    (void)t_end_ns;
    if (n_got < 64u) {
        got[n_got++] = it->f;
    }
}

static can_frame_t frame(uint32_t id, uint8_t tag)
{
    can_frame_t f;
    memset(&f, 0, sizeof f);
    f.id = id;
    f.len = 8u;
    f.data[0] = tag;
    return f;
}

static void test_all_pending_frames_arbitrate(void **state)
{
    (void)state;
    bus_init(&bus, 1000000u);
    n_got = 0u;
    /* node 0: a UDS answer, then an emergency frame; node 1: a flood of 0x300 */
    can_frame_t uds = frame(0x680u, 1u), emcy = frame(0x080u, 2u);
    assert_true(bus_enqueue(&bus, 0u, &uds, false, 0u));
    for (uint8_t i = 0; i < 20u; i++) {
        can_frame_t f = frame(0x300u, i);
        assert_true(bus_enqueue(&bus, 1u, &f, false, 0u));
    }
    assert_true(bus_enqueue(&bus, 0u, &emcy, false, 0u));
    assert_int_equal(bus_pending(&bus, 0u), 2u);
    bus_run(&bus, 1000000000ull, on_frame, NULL);
    assert_int_equal(n_got, 22u);
    assert_int_equal(got[0].id, 0x080u);                 /* first, ahead of the node's UDS frame */
    for (unsigned i = 1; i <= 20u; i++) {
        assert_int_equal(got[i].id, 0x300u);
        assert_int_equal(got[i].data[0], i - 1u);        /* same identifier: in order */
    }
    assert_int_equal(got[21].id, 0x680u);                /* lowest priority: last */
    /* the least urgent waiting frame of a node can be taken back (mailbox abort) */
    assert_true(bus_enqueue(&bus, 0u, &uds, false, 2000000000ull));
    assert_true(bus_enqueue(&bus, 0u, &emcy, false, 2000000000ull));
    bus_item_t w;
    assert_true(bus_least_urgent(&bus, 0u, true, &w));
    assert_int_equal(w.f.id, 0x680u);
    assert_int_equal(bus_pending(&bus, 0u), 1u);
}

static void test_frames_wait_for_their_enqueue_time(void **state)
{
    (void)state;
    bus_init(&bus, 1000000u);
    n_got = 0u;
    can_frame_t a = frame(0x400u, 1u), b = frame(0x100u, 2u);
    assert_true(bus_enqueue(&bus, 1u, &a, false, 0u));
    assert_true(bus_enqueue(&bus, 0u, &b, false, 50000u));   /* 50 us later: a is on the wire */
    bus_run(&bus, 1000000ull, on_frame, NULL);
    assert_int_equal(n_got, 2u);
    assert_int_equal(got[0].id, 0x400u);
    assert_int_equal(got[1].id, 0x100u);
}

static void test_host_port_queue_by_priority(void **state)
{
    (void)state;
    hal_sim_can_reset();
    const uint32_t ids[5] = {0x680u, 0x1A0u, 0x680u, 0x080u, 0x180u};
    for (uint8_t i = 0; i < 5u; i++) {
        can_frame_t f = frame(ids[i], i);
        assert_true(hal_can_send(&f));
    }
    assert_int_equal(hal_can_tx_free(), HAL_SIM_TX_QUEUE - 5u);
    can_frame_t f;
    static const uint32_t want_id[5] = {0x080u, 0x180u, 0x1A0u, 0x680u, 0x680u};
    static const uint8_t want_tag[5] = {3u, 4u, 1u, 0u, 2u};
    for (unsigned i = 0; i < 5u; i++) {
        assert_true(hal_sim_can_tx_peek(&f));
        assert_int_equal(f.id, want_id[i]);
        assert_int_equal(f.data[0], want_tag[i]);
        if (i == 3u) {
            /* taken by the bus, then given back: first again among its identifier */
            hal_sim_can_tx_pop();
            assert_true(hal_sim_can_tx_requeue(&f));
            assert_true(hal_sim_can_tx_peek(&f));
            assert_int_equal(f.data[0], 0u);
        }
        hal_sim_can_tx_pop();
    }
    assert_false(hal_sim_can_tx_peek(&f));
    assert_true(hal_can_tx_idle());
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_all_pending_frames_arbitrate),
        cmocka_unit_test(test_frames_wait_for_their_enqueue_time),
        cmocka_unit_test(test_host_port_queue_by_priority),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

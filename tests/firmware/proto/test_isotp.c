/* ISO-TP: single/first/consecutive/flow-control frames, block size, STmin, N_Bs/N_Cr timeouts,
 * padding, sequence numbers, overflow, checked frame by frame (ISO 15765-2 layouts). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "isotp.h"

#define QCAP 1024u
typedef struct {
    can_frame_t f[QCAP];
    uint64_t t_us[QCAP];
    unsigned n;
    unsigned head;
    unsigned refuse; /* refuse this many sends (driver full) */
    uint64_t now_us;
} queue_t;

static bool q_send(void *ctx, const can_frame_t *frame)
{
    queue_t *q = ctx;
    if (q->refuse > 0u) {
        q->refuse--;
        return false;
    }
    assert_true(q->n < QCAP);
    q->t_us[q->n] = q->now_us;
    q->f[q->n++] = *frame;
    return true;
}

static queue_t qa, qb; /* frames sent by a (to b) and by b (to a) */
static isotp_link_t la, lb;

static int setup(void **state)
{
    (void)state;
    memset(&qa, 0, sizeof(qa));
    memset(&qb, 0, sizeof(qb));
    isotp_config_t ca, cb;
    isotp_config_default(&ca, 0x601, 0x681);
    isotp_config_default(&cb, 0x681, 0x601);
    isotp_init(&la, &ca, q_send, &qa);
    isotp_init(&lb, &cb, q_send, &qb);
    return 0;
}

/* Deliver queued frames both ways and poll both links at 100 us steps until quiet. */
static void run(uint64_t *now, uint64_t until_us)
{
    while (*now <= until_us) {
        qa.now_us = qb.now_us = *now;
        isotp_poll(&la, *now);
        isotp_poll(&lb, *now);
        while (qa.head < qa.n) {
            isotp_on_frame(&lb, &qa.f[qa.head++], *now);
        }
        while (qb.head < qb.n) {
            isotp_on_frame(&la, &qb.f[qb.head++], *now);
        }
        *now += 100u;
    }
}

static void fill(uint8_t *buf, unsigned n)
{
    for (unsigned i = 0; i < n; i++) {
        buf[i] = (uint8_t)(i * 7u + 3u);
    }
}

static void test_single_frame_padded(void **state)
{
    (void)state;
    const uint8_t msg[3] = {0x22, 0xF1, 0x90};
    assert_int_equal(isotp_send(&la, msg, 3, 0), PROTO_OK);
    assert_int_equal(qa.n, 1);
    const uint8_t expect[8] = {0x03, 0x22, 0xF1, 0x90, 0xCC, 0xCC, 0xCC, 0xCC};
    assert_int_equal(qa.f[0].id, 0x601);
    assert_int_equal(qa.f[0].len, 8);
    assert_memory_equal(qa.f[0].data, expect, 8);
    isotp_on_frame(&lb, &qa.f[0], 0);
    const uint8_t *got = NULL;
    assert_int_equal(isotp_rx_peek(&lb, &got), 3);
    assert_memory_equal(got, msg, 3);
    isotp_rx_release(&lb);
    assert_int_equal(isotp_rx_peek(&lb, &got), 0);
}

static void test_unpadded_single_frame_accepted_short_dlc_refused(void **state)
{
    (void)state;
    can_frame_t f = {.id = 0x681, .len = 3, .data = {0x02, 0x3E, 0x00}};
    isotp_on_frame(&la, &f, 0);
    const uint8_t *got = NULL;
    assert_int_equal(isotp_rx_peek(&la, &got), 2);
    isotp_rx_release(&la);
    f.data[0] = 0x05; /* claims 5 bytes in a 3-byte frame */
    isotp_on_frame(&la, &f, 0);
    assert_int_equal(isotp_rx_peek(&la, &got), 0);
    assert_int_equal(la.last_error, PROTO_ERR_ISOTP_FORMAT);
    f.id = 0x682; /* another id: ignored */
    f.data[0] = 0x01;
    isotp_on_frame(&la, &f, 0);
    assert_int_equal(isotp_rx_peek(&la, &got), 0);
}

static void check_multi(unsigned len, uint8_t bs, uint8_t stmin)
{
    setup(NULL);
    lb.cfg.block_size = bs;
    lb.cfg.st_min = stmin;
    static uint8_t msg[ISOTP_MAX_PAYLOAD];
    fill(msg, len);
    uint64_t now = 0;
    assert_int_equal(isotp_send(&la, msg, (uint16_t)len, now), PROTO_OK);
    /* first frame: 0x1L LL + 6 data bytes */
    assert_int_equal(qa.f[0].data[0], 0x10 | (len >> 8));
    assert_int_equal(qa.f[0].data[1], len & 0xFF);
    assert_memory_equal(&qa.f[0].data[2], msg, 6);
    run(&now, 20u * 1000u * 1000u);
    const uint8_t *got = NULL;
    assert_int_equal(isotp_rx_peek(&lb, &got), len);
    assert_memory_equal(got, msg, len);
    const unsigned n_cf = (len - 6u + 6u) / 7u;
    assert_int_equal(qa.n, 1u + n_cf);
    /* sequence numbers 1..15,0,1..; last CF padded with 0xCC */
    for (unsigned i = 1; i <= n_cf; i++) {
        assert_int_equal(qa.f[i].data[0], 0x20 | (i & 0xF));
        assert_int_equal(qa.f[i].len, 8);
    }
    const unsigned last_n = len - 6u - 7u * (n_cf - 1u);
    for (unsigned k = 1u + last_n; k < 8u; k++) {
        assert_int_equal(qa.f[n_cf].data[k], ISOTP_PADDING);
    }
    /* flow controls: one after the FF, then one per block */
    const unsigned expect_fc = bs == 0 ? 1u : 1u + (n_cf - 1u) / bs;
    assert_int_equal(qb.n, expect_fc);
    for (unsigned i = 0; i < qb.n; i++) {
        assert_int_equal(qb.f[i].data[0], 0x30);
        assert_int_equal(qb.f[i].data[1], bs);
        assert_int_equal(qb.f[i].data[2], stmin);
    }
    /* STmin respected between consecutive CFs of a block */
    const uint64_t st_us = isotp_stmin_to_us(stmin);
    for (unsigned i = 2; i <= n_cf; i++) {
        if (bs != 0u && (i - 1u) % bs == 0u) {
            continue; /* first CF of a block follows its FC */
        }
        assert_true(qa.t_us[i] - qa.t_us[i - 1] >= st_us);
    }
    assert_false(isotp_tx_busy(&la));
}

static void test_multi_frame_max_length(void **state)
{
    (void)state;
    check_multi(ISOTP_MAX_PAYLOAD, 0, 0);
}

static void test_multi_frame_block_size(void **state)
{
    (void)state;
    check_multi(8, 0, 0);
    check_multi(100, 3, 0);
    check_multi(1334, 8, 0);
}

static void test_multi_block_max_length(void **state)
{
    (void)state;
    /* 4095 bytes (585 CFs) received in blocks: FC after every block, the sender waits for it and
     * keeps STmin between CFs (1 ms; 300 us), the receiver reassembles every byte */
    check_multi(ISOTP_MAX_PAYLOAD, 8, 0x01);
    check_multi(ISOTP_MAX_PAYLOAD, 0x20, 0xF3);
    check_multi(ISOTP_MAX_PAYLOAD, 0xFF, 0x00);
    check_multi(ISOTP_MAX_PAYLOAD, 1, 0x00);
}

static void test_stmin(void **state)
{
    (void)state;
    check_multi(50, 0, 5);                              /* 5 ms */
    check_multi(50, 2, 0xF5);                           /* 500 us */
    assert_int_equal(isotp_stmin_to_us(0x80), 127000u); /* reserved -> 127 ms */
    assert_int_equal(isotp_stmin_to_us(0xF1), 100u);
    assert_int_equal(isotp_stmin_to_us(0x7F), 127000u);
}

static void test_wrong_sequence_number_aborts(void **state)
{
    (void)state;
    uint8_t msg[30];
    fill(msg, sizeof(msg));
    assert_int_equal(isotp_send(&la, msg, sizeof(msg), 0), PROTO_OK);
    isotp_on_frame(&lb, &qa.f[0], 0); /* FF */
    isotp_on_frame(&la, &qb.f[0], 0); /* FC */
    isotp_poll(&la, 0);               /* CFs 1..4 */
    assert_int_equal(qa.n, 5);
    isotp_on_frame(&lb, &qa.f[1], 0);
    isotp_on_frame(&lb, &qa.f[3], 0); /* SN 3 where 2 is expected */
    assert_int_equal(lb.last_error, PROTO_ERR_ISOTP_WRONG_SN);
    isotp_on_frame(&lb, &qa.f[2], 0);
    isotp_on_frame(&lb, &qa.f[4], 0);
    const uint8_t *got = NULL;
    assert_int_equal(isotp_rx_peek(&lb, &got), 0); /* nothing delivered */
}

static void test_timeout_n_cr(void **state)
{
    (void)state;
    can_frame_t ff = {.id = 0x601, .len = 8, .data = {0x10, 0x14, 1, 2, 3, 4, 5, 6}};
    isotp_on_frame(&lb, &ff, 0);
    assert_int_equal(qb.n, 1); /* FC CTS */
    isotp_poll(&lb, ISOTP_DEFAULT_N_CR_US);
    assert_int_equal(lb.rx_state, ISOTP_RX_RECEIVING); /* exactly N_Cr: still waiting */
    isotp_poll(&lb, ISOTP_DEFAULT_N_CR_US + 1u);
    assert_int_equal(lb.last_error, PROTO_ERR_ISOTP_TIMEOUT_CR);
    can_frame_t cf = {.id = 0x601, .len = 8, .data = {0x21, 7, 8, 9, 10, 11, 12, 13}};
    isotp_on_frame(&lb, &cf, ISOTP_DEFAULT_N_CR_US + 2u); /* late CF: ignored */
    const uint8_t *got = NULL;
    assert_int_equal(isotp_rx_peek(&lb, &got), 0);
}

static void test_timeout_n_bs_and_wait(void **state)
{
    (void)state;
    uint8_t msg[20];
    fill(msg, sizeof(msg));
    assert_int_equal(isotp_send(&la, msg, sizeof(msg), 0), PROTO_OK);
    assert_true(isotp_tx_busy(&la));
    assert_int_equal(isotp_send(&la, msg, sizeof(msg), 0), PROTO_ERR_ISOTP_BUSY);
    /* FC WAIT restarts N_Bs */
    can_frame_t wait = {.id = 0x681, .len = 3, .data = {0x31, 0, 0}};
    isotp_on_frame(&la, &wait, 900000u);
    isotp_poll(&la, 1500000u);
    assert_true(isotp_tx_busy(&la));
    isotp_poll(&la, 1900001u);
    assert_false(isotp_tx_busy(&la));
    assert_int_equal(la.last_error, PROTO_ERR_ISOTP_TIMEOUT_BS);
    /* too many WAITs abort */
    assert_int_equal(isotp_send(&la, msg, sizeof(msg), 2000000u), PROTO_OK);
    for (unsigned i = 0; i <= ISOTP_DEFAULT_WFT_MAX; i++) {
        isotp_on_frame(&la, &wait, 2000000u + i);
    }
    assert_false(isotp_tx_busy(&la));
    assert_int_equal(la.last_error, PROTO_ERR_ISOTP_WFT);
}

static void test_overflow(void **state)
{
    (void)state;
    /* FF with 32-bit escape length: FC overflow */
    can_frame_t ff = {.id = 0x601, .len = 8, .data = {0x10, 0x00, 0x00, 0x00, 0x10, 0x00, 1, 2}};
    isotp_on_frame(&lb, &ff, 0);
    assert_int_equal(qb.n, 1);
    assert_int_equal(qb.f[0].data[0], 0x32);
    assert_int_equal(lb.last_error, PROTO_ERR_ISOTP_OVERFLOW);
    /* the sender aborts on FC overflow */
    uint8_t msg[20];
    fill(msg, sizeof(msg));
    assert_int_equal(isotp_send(&la, msg, sizeof(msg), 0), PROTO_OK);
    isotp_on_frame(&la, &qb.f[0], 0);
    assert_false(isotp_tx_busy(&la));
    assert_int_equal(la.last_error, PROTO_ERR_ISOTP_OVERFLOW);
    /* oversize or empty send refused */
    static uint8_t big[ISOTP_MAX_PAYLOAD + 1u];
    assert_int_equal(isotp_send(&la, big, (uint16_t)sizeof(big), 0), PROTO_ERR_ISOTP_OVERFLOW);
    assert_int_equal(isotp_send(&la, big, 0, 0), PROTO_ERR_ISOTP_OVERFLOW);
    /* FF announcing <= 7 bytes is malformed */
    can_frame_t small = {.id = 0x601, .len = 8, .data = {0x10, 0x05, 1, 2, 3, 4, 5, 6}};
    isotp_on_frame(&lb, &small, 0);
    assert_int_equal(lb.last_error, PROTO_ERR_ISOTP_FORMAT);
}

static void test_driver_full_retried(void **state)
{
    (void)state;
    uint8_t msg[40];
    fill(msg, sizeof(msg));
    qa.refuse = 1; /* FF refused once */
    assert_int_equal(isotp_send(&la, msg, sizeof(msg), 0), PROTO_OK);
    assert_int_equal(qa.n, 0);
    uint64_t now = 0;
    qb.refuse = 1; /* first FC attempt refused */
    run(&now, 10000);
    const uint8_t *got = NULL;
    assert_int_equal(isotp_rx_peek(&lb, &got), sizeof(msg));
    assert_memory_equal(got, msg, sizeof(msg));
    /* single frame also retried */
    isotp_rx_release(&lb);
    qa.refuse = 2;
    assert_int_equal(isotp_send(&la, msg, 5, now), PROTO_OK);
    run(&now, now + 1000);
    assert_int_equal(isotp_rx_peek(&lb, &got), 5);
}

static void test_new_first_frame_restarts(void **state)
{
    (void)state;
    can_frame_t ff = {.id = 0x601, .len = 8, .data = {0x10, 0x0A, 1, 2, 3, 4, 5, 6}};
    isotp_on_frame(&lb, &ff, 0);
    can_frame_t ff2 = {.id = 0x601, .len = 8, .data = {0x10, 0x09, 9, 9, 9, 9, 9, 9}};
    isotp_on_frame(&lb, &ff2, 10);
    assert_int_equal(lb.last_error, PROTO_ERR_ISOTP_UNEXPECTED);
    can_frame_t cf = {.id = 0x601, .len = 8, .data = {0x21, 8, 8, 8, 0xCC, 0xCC, 0xCC, 0xCC}};
    isotp_on_frame(&lb, &cf, 20);
    const uint8_t *got = NULL;
    assert_int_equal(isotp_rx_peek(&lb, &got), 9);
    const uint8_t expect[9] = {9, 9, 9, 9, 9, 9, 8, 8, 8};
    assert_memory_equal(got, expect, 9);
}

/* ---- CAN FD (tx_dl 64), frames checked byte by byte against ISO 15765-2:2016 layouts ---- */

static int setup_fd(void **state)
{
    (void)state;
    memset(&qa, 0, sizeof(qa));
    memset(&qb, 0, sizeof(qb));
    isotp_config_t ca, cb;
    isotp_config_default(&ca, 0x601, 0x681);
    isotp_config_default(&cb, 0x681, 0x601);
    ca.tx_dl = cb.tx_dl = 64u;
    ca.brs = true;
    isotp_init(&la, &ca, q_send, &qa);
    isotp_init(&lb, &cb, q_send, &qb);
    return 0;
}

static void test_fd_single_frames(void **state)
{
    (void)state;
    uint8_t msg[62];
    fill(msg, sizeof(msg));
    /* up to 7 bytes: the 4-bit length, padded to 8 */
    assert_int_equal(isotp_send(&la, msg, 5, 0), PROTO_OK);
    assert_int_equal(qa.n, 1);
    assert_int_equal(qa.f[0].len, 8);
    assert_int_equal(qa.f[0].flags, CAN_FRAME_FD | CAN_FRAME_BRS);
    const uint8_t sf5[8] = {0x05, msg[0], msg[1], msg[2], msg[3], msg[4], 0xCC, 0xCC};
    assert_memory_equal(qa.f[0].data, sf5, 8);
    /* 20 bytes: escape (0x00, 20), 22 bytes padded to 24 */
    assert_int_equal(isotp_send(&la, msg, 20, 0), PROTO_OK);
    assert_int_equal(qa.f[1].len, 24);
    assert_int_equal(qa.f[1].data[0], 0x00);
    assert_int_equal(qa.f[1].data[1], 20);
    assert_memory_equal(&qa.f[1].data[2], msg, 20);
    assert_int_equal(qa.f[1].data[22], 0xCC);
    assert_int_equal(qa.f[1].data[23], 0xCC);
    /* 62 bytes: the largest single frame, 64 bytes exactly */
    assert_int_equal(isotp_send(&la, msg, 62, 0), PROTO_OK);
    assert_int_equal(qa.n, 3);
    assert_int_equal(qa.f[2].len, 64);
    assert_int_equal(lb.cfg.brs, false);
    const uint8_t *got = NULL;
    isotp_on_frame(&lb, &qa.f[1], 0);
    assert_int_equal(isotp_rx_peek(&lb, &got), 20);
    assert_memory_equal(got, msg, 20);
    isotp_rx_release(&lb);
    isotp_on_frame(&lb, &qa.f[2], 0);
    assert_int_equal(isotp_rx_peek(&lb, &got), 62);
    assert_memory_equal(got, msg, 62);
    isotp_rx_release(&lb);
    /* an escape length of 7 or less, or longer than the frame, is refused */
    can_frame_t bad = {.id = 0x601, .len = 12, .flags = CAN_FRAME_FD, .data = {0x00, 5}};
    isotp_on_frame(&lb, &bad, 0);
    bad.data[1] = 11;
    isotp_on_frame(&lb, &bad, 0);
    assert_int_equal(isotp_rx_peek(&lb, &got), 0);
    assert_int_equal(lb.last_error, PROTO_ERR_ISOTP_FORMAT);
    assert_int_equal(lb.error_count, 2);
}

static void test_fd_multi_frame(void **state)
{
    (void)state;
    uint8_t msg[100];
    fill(msg, sizeof(msg));
    uint64_t now = 0u;
    assert_int_equal(isotp_send(&la, msg, 100, now), PROTO_OK);
    /* FF: 0x10 0x64, 62 data bytes, 64 bytes long */
    assert_int_equal(qa.n, 1);
    assert_int_equal(qa.f[0].len, 64);
    assert_int_equal(qa.f[0].data[0], 0x10);
    assert_int_equal(qa.f[0].data[1], 100);
    assert_memory_equal(&qa.f[0].data[2], msg, 62);
    run(&now, 2000u);
    /* FC of the receiver: an FD frame padded to 8 */
    assert_int_equal(qb.n, 1);
    assert_int_equal(qb.f[0].len, 8);
    assert_int_equal(qb.f[0].flags, CAN_FRAME_FD);
    const uint8_t fc[8] = {0x30, 0, 0, 0xCC, 0xCC, 0xCC, 0xCC, 0xCC};
    assert_memory_equal(qb.f[0].data, fc, 8);
    /* the last CF: 0x21 + 38 bytes = 39, padded to 48 */
    assert_int_equal(qa.n, 2);
    assert_int_equal(qa.f[1].len, 48);
    assert_int_equal(qa.f[1].data[0], 0x21);
    assert_memory_equal(&qa.f[1].data[1], &msg[62], 38);
    for (unsigned i = 39; i < 48; i++) {
        assert_int_equal(qa.f[1].data[i], 0xCC);
    }
    const uint8_t *got = NULL;
    assert_int_equal(isotp_rx_peek(&lb, &got), 100);
    assert_memory_equal(got, msg, 100);
}

static void test_fd_max_length_and_short_cf_refused(void **state)
{
    (void)state;
    static uint8_t msg[ISOTP_MAX_PAYLOAD];
    fill(msg, sizeof(msg));
    uint64_t now = 0u;
    assert_int_equal(isotp_send(&la, msg, ISOTP_MAX_PAYLOAD, now), PROTO_OK);
    run(&now, 100000u);
    /* FF (62 bytes) + ceil((4095 - 62) / 63) = 65 CFs */
    assert_int_equal(qa.n, 66);
    assert_int_equal(qa.f[65].len, 8); /* the last CF: 0x2N + 1 byte */
    const uint8_t *got = NULL;
    assert_int_equal(isotp_rx_peek(&lb, &got), ISOTP_MAX_PAYLOAD);
    assert_memory_equal(got, msg, ISOTP_MAX_PAYLOAD);
    isotp_rx_release(&lb);
    /* a CF shorter than RX_DL before the end aborts the reception */
    qa.head = 0u;
    isotp_on_frame(&lb, &qa.f[0], now);
    can_frame_t cf = qa.f[1];
    cf.len = 32u;
    isotp_on_frame(&lb, &cf, now);
    assert_int_equal(lb.last_error, PROTO_ERR_ISOTP_FORMAT);
    assert_int_equal(lb.rx_state, ISOTP_RX_IDLE);
}

static void test_fd_config_falls_back_to_classic(void **state)
{
    (void)state;
    isotp_config_t c;
    isotp_config_default(&c, 0x601, 0x681);
    assert_int_equal(c.tx_dl, 8);
    c.tx_dl = 32u; /* not 8 or 64 */
    c.brs = true;
    isotp_init(&la, &c, q_send, &qa);
    assert_int_equal(la.cfg.tx_dl, 8);
    assert_false(la.cfg.brs);
    const uint8_t msg[3] = {1, 2, 3};
    assert_int_equal(isotp_send(&la, msg, 3, 0), PROTO_OK);
    assert_int_equal(qa.f[0].flags, 0);
    assert_int_equal(qa.f[0].len, 8);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(test_single_frame_padded, setup),
        cmocka_unit_test_setup(test_unpadded_single_frame_accepted_short_dlc_refused, setup),
        cmocka_unit_test_setup(test_multi_frame_max_length, setup),
        cmocka_unit_test_setup(test_multi_frame_block_size, setup),
        cmocka_unit_test_setup(test_multi_block_max_length, setup),
        cmocka_unit_test_setup(test_stmin, setup),
        cmocka_unit_test_setup(test_wrong_sequence_number_aborts, setup),
        cmocka_unit_test_setup(test_timeout_n_cr, setup),
        cmocka_unit_test_setup(test_timeout_n_bs_and_wait, setup),
        cmocka_unit_test_setup(test_overflow, setup),
        cmocka_unit_test_setup(test_driver_full_retried, setup),
        cmocka_unit_test_setup(test_new_first_frame_restarts, setup),
        cmocka_unit_test_setup(test_fd_single_frames, setup_fd),
        cmocka_unit_test_setup(test_fd_multi_frame, setup_fd),
        cmocka_unit_test_setup(test_fd_max_length_and_short_cf_refused, setup_fd),
        cmocka_unit_test_setup(test_fd_config_falls_back_to_classic, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

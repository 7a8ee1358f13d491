/* Authenticated host frames (secoc): the frame MAC against a one-shot AES-CMAC of the documented
 * input (sec_cmac, itself checked against SP 800-38B in test_cmac.c), the key derivation against
 * a one-shot HMAC-SHA256 (RFC 4231 vectors in test_sha256.c), the freshness window (lost
 * frames absorbed up to 255, more refused), replays, a frame
 * without a key, a MAC from another key, the key discarded after 64 wrong MACs in a row, and the
 * verification in slices of any size against secoc_verify. */
#include <setjmp.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "secoc.h"

static const uint8_t KEY[SECOC_KEY_LEN] = {0x30, 0x31, 0x32, 0x33, 0x34, 0x35, 0x36, 0x37,
                                           0x38, 0x39, 0x61, 0x62, 0x63, 0x64, 0x65, 0x66};

static can_frame_t frame(uint32_t id, uint8_t mode)
{
    can_frame_t f;
    memset(&f, 0, sizeof f);
    f.id = id;
    f.len = 8u;
    f.data[0] = mode;
    f.data[1] = 0xE8;
    f.data[2] = 0x03;
    return f;
}

static void test_frame_mac_is_truncated_cmac_of_id_payload_fv(void **state)
{
    (void)state;
    secoc_t s;
    secoc_init(&s);
    secoc_set_key(&s, KEY);
    can_frame_t f = frame(0x105u, 3u);
    uint8_t mac[SECOC_MAC_LEN];
    secoc_mac(&s, &f, 0x01020304u, mac);
    const uint8_t msg[9] = {0x05, 0x01, 3u, 0xE8, 0x03, 0x01, 0x02, 0x03, 0x04};
    uint8_t ref[SEC_AES_BLOCK];
    sec_cmac_t c;
    sec_cmac_init(&c, KEY);
    sec_cmac(&c, msg, sizeof msg, ref);
    assert_memory_equal(mac, ref, SECOC_MAC_LEN);
}

/* The value from the host's reference (forceskill.wire.dbc.key_confirmation, AES-CMAC checked
 * against SP 800-38B) for the key 00 01 .. 0F; 0 without a key. */
static void test_key_confirmation_matches_the_host(void **state)
{
    (void)state;
    uint8_t key[SECOC_KEY_LEN];
    for (unsigned i = 0; i < SECOC_KEY_LEN; i++) {
        key[i] = (uint8_t)i;
    }
    secoc_t s;
    secoc_init(&s);
    assert_int_equal(secoc_confirm(&s), 0u);
    secoc_set_key(&s, key);
    assert_int_equal(secoc_confirm(&s), 0x03329AEBu);
}

static void test_key_is_truncated_hmac_of_label_and_nonces(void **state)
{
    (void)state;
    uint8_t dev[SECOC_NONCE_LEN], host[SECOC_NONCE_LEN], msg[64], ref[SEC_SHA256_LEN];
    uint8_t key[SECOC_KEY_LEN];
    memset(dev, 0x11, sizeof dev);
    memset(host, 0x22, sizeof host);
    const size_t n = strlen(SECOC_LABEL);
    memcpy(msg, SECOC_LABEL, n);
    memcpy(&msg[n], dev, SECOC_NONCE_LEN);
    memcpy(&msg[n + SECOC_NONCE_LEN], host, SECOC_NONCE_LEN);
    sec_hmac_sha256(KEY, 16u, msg, (uint32_t)(n + 2u * SECOC_NONCE_LEN), ref);
    secoc_derive_key(KEY, 16u, dev, host, key);
    assert_memory_equal(key, ref, SECOC_KEY_LEN);
}

static void test_freshness_window_replay_and_keys(void **state)
{
    (void)state;
    secoc_t tx, rx;
    secoc_init(&rx);
    can_frame_t f = frame(0x100u, 2u);
    assert_int_equal(secoc_verify(&rx, &f, SECOC_CH_COMMAND), SEC_ERR_NO_KEY);
    uint8_t dev[SECOC_NONCE_LEN], host[SECOC_NONCE_LEN];
    memset(dev, 0x11, sizeof dev);
    memset(host, 0x22, sizeof host);
    secoc_start_session(&tx, KEY, 16u, dev, host);
    uint8_t key[SECOC_KEY_LEN];
    secoc_derive_key(KEY, 16u, dev, host, key);
    secoc_set_key(&rx, key);
    /* in order, then 255 lost frames in a row absorbed (the next FV is the last + 256) */
    for (int i = 0; i < 3; i++) {
        (void)secoc_protect(&tx, &f, SECOC_CH_COMMAND);
        assert_int_equal(secoc_verify(&rx, &f, SECOC_CH_COMMAND), SEC_OK);
    }
    const can_frame_t old = f;
    assert_int_equal(secoc_verify(&rx, &f, SECOC_CH_COMMAND), SEC_ERR_REPLAY);
    for (int i = 0; i < 256; i++) {
        (void)secoc_protect(&tx, &f, SECOC_CH_COMMAND);
    }
    assert_int_equal(secoc_verify(&rx, &f, SECOC_CH_COMMAND), SEC_OK);
    assert_int_equal(rx.fv[SECOC_CH_COMMAND], 259u);
    /* a replay from more than 256 values back is no longer recognised as one: a wrong MAC */
    can_frame_t replay = old;
    assert_int_equal(secoc_verify(&rx, &replay, SECOC_CH_COMMAND), SEC_ERR_MAC);
    /* 256 lost frames in a row are beyond the window; the channels are independent */
    for (int i = 0; i < 257; i++) {
        (void)secoc_protect(&tx, &f, SECOC_CH_COMMAND);
    }
    assert_int_equal(secoc_verify(&rx, &f, SECOC_CH_COMMAND), SEC_ERR_MAC);
    can_frame_t hb = frame(0x110u, 0u);
    (void)secoc_protect(&tx, &hb, SECOC_CH_HEARTBEAT);
    assert_int_equal(secoc_verify(&rx, &hb, SECOC_CH_HEARTBEAT), SEC_OK);
    /* a changed payload, id or MAC bit fails */
    (void)secoc_protect(&tx, &hb, SECOC_CH_HEARTBEAT);
    hb.data[0] ^= 1u;
    assert_int_equal(secoc_verify(&rx, &hb, SECOC_CH_HEARTBEAT), SEC_ERR_MAC);
    /* another host session's key */
    secoc_t other;
    memset(host, 0x33, sizeof host);
    secoc_start_session(&other, KEY, 16u, dev, host);
    other.fv[SECOC_CH_HEARTBEAT] = rx.fv[SECOC_CH_HEARTBEAT];
    (void)secoc_protect(&other, &hb, SECOC_CH_HEARTBEAT);
    assert_int_equal(secoc_verify(&rx, &hb, SECOC_CH_HEARTBEAT), SEC_ERR_MAC);
    assert_int_equal(rx.accepted, 5u);
    assert_int_equal(rx.replayed, 1u);
    assert_int_equal(rx.no_key, 1u);
    assert_int_equal(rx.bad_mac, 4u);
    assert_int_equal(rx.last_refusal, SEC_ERR_MAC);
}

static void test_key_discarded_after_64_wrong_macs(void **state)
{
    (void)state;
    secoc_t rx;
    secoc_init(&rx);
    secoc_set_key(&rx, KEY);
    can_frame_t f = frame(0x100u, 3u);
    for (unsigned i = 0; i < SECOC_MAX_BAD_MAC; i++) {
        f.data[SECOC_FV_BYTE] = (uint8_t)(i + 1u);
        f.data[3] = (uint8_t)i; /* a guess */
        assert_true(rx.keyed);
        assert_int_equal(secoc_verify(&rx, &f, SECOC_CH_COMMAND), SEC_ERR_MAC);
    }
    assert_false(rx.keyed);
    assert_int_equal(rx.revoked, 1u);
    assert_int_equal(secoc_verify(&rx, &f, SECOC_CH_COMMAND), SEC_ERR_NO_KEY);
    assert_int_equal(rx.bad_mac, SECOC_MAX_BAD_MAC);
    assert_int_equal(rx.last_refusal, SEC_ERR_NO_KEY);
}

/* One frame through secoc_verify on a and through the sliced job at k rounds a call on b: the
 * same status, the same receiver state after it, and the calls the rounds need (10 an
 * encryption: one for an accepted frame, two for one that fails after its freshness window, the
 * second from the call after the first's end when the budget left is short of it). */
static sec_status_t verify_both(secoc_t *a, secoc_t *b, const can_frame_t *f, secoc_channel_t ch,
                                uint32_t k, uint32_t *calls)
{
    const sec_status_t whole = secoc_verify(a, f, ch);
    secoc_job_t j;
    secoc_verify_begin(b, &j, f, ch);
    *calls = 0u;
    for (;;) {
        uint32_t budget = k;
        const bool done = secoc_verify_run(b, &j, &budget);
        if (budget != k || !done) {
            (*calls)++;
        }
        if (done) {
            break;
        }
        assert_true(*calls < 100u);
    }
    assert_int_equal(j.status, whole);
    assert_memory_equal(a->fv, b->fv, sizeof a->fv);
    assert_int_equal(a->keyed, b->keyed);
    assert_int_equal(a->bad_in_row, b->bad_in_row);
    assert_int_equal(a->accepted, b->accepted);
    assert_int_equal(a->bad_mac, b->bad_mac);
    assert_int_equal(a->replayed, b->replayed);
    assert_int_equal(a->no_key, b->no_key);
    assert_int_equal(a->revoked, b->revoked);
    assert_int_equal(a->last_refusal, b->last_refusal);
    return whole;
}

static void test_sliced_verification_is_secoc_verify(void **state)
{
    (void)state;
    for (uint32_t k = 1u; k <= 12u; k++) {
        secoc_t tx, a, b;
        secoc_init(&a);
        secoc_init(&b);
        uint32_t calls = 0u;
        can_frame_t f = frame(0x100u, 2u);
        assert_int_equal(verify_both(&a, &b, &f, SECOC_CH_COMMAND, k, &calls), SEC_ERR_NO_KEY);
        assert_int_equal(calls, 0u); /* refused without an encryption */
        secoc_init(&tx);
        secoc_set_key(&tx, KEY);
        secoc_set_key(&a, KEY);
        secoc_set_key(&b, KEY);
        /* the second block from a call of its own, the budget being short of it */
        const uint32_t one = (10u + k - 1u) / k, two = 2u * one;
        for (int i = 0; i < 300; i++) { /* past the first window: replays are recognised */
            (void)secoc_protect(&tx, &f, SECOC_CH_HEARTBEAT);
            assert_int_equal(verify_both(&a, &b, &f, SECOC_CH_HEARTBEAT, k, &calls), SEC_OK);
            assert_int_equal(calls, one);
        }
        assert_int_equal(verify_both(&a, &b, &f, SECOC_CH_HEARTBEAT, k, &calls), SEC_ERR_REPLAY);
        assert_int_equal(calls, two);
        can_frame_t forged = f;
        forged.data[SECOC_FV_BYTE] = (uint8_t)(forged.data[SECOC_FV_BYTE] + 1u);
        forged.data[3] ^= 0x5Au;
        assert_int_equal(verify_both(&a, &b, &forged, SECOC_CH_HEARTBEAT, k, &calls), SEC_ERR_MAC);
        assert_int_equal(calls, two);
        for (unsigned i = 0; i < SECOC_MAX_BAD_MAC; i++) { /* until the key is discarded */
            (void)verify_both(&a, &b, &forged, SECOC_CH_HEARTBEAT, k, &calls);
        }
        assert_false(b.keyed);
        assert_int_equal(b.revoked, 1u);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_frame_mac_is_truncated_cmac_of_id_payload_fv),
        cmocka_unit_test(test_key_is_truncated_hmac_of_label_and_nonces),
        cmocka_unit_test(test_key_confirmation_matches_the_host),
        cmocka_unit_test(test_freshness_window_replay_and_keys),
        cmocka_unit_test(test_key_discarded_after_64_wrong_macs),
        cmocka_unit_test(test_sliced_verification_is_secoc_verify),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

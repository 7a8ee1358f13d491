/* Authenticated host frames (secoc): the HMAC of the precomputed key states against RFC 4231
 * test cases 1-5 (keys up to one block; case 5 truncated to 128 bits as the RFC gives it), the
 * frame MAC against a one-shot HMAC-SHA256 of the documented input, the freshness window (lost
 * frames absorbed up to 255, more refused), replays, a frame
 * without a key, a MAC from another key, and the key discarded after 64 wrong MACs in a row. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "secoc.h"

static void hex(const char *s, uint8_t *out, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        unsigned v = 0;
        for (int k = 0; k < 2; k++) {
            const char c = s[2 * i + (size_t)k];
            v = v * 16u + (unsigned)(c <= '9' ? c - '0' : (c | 0x20) - 'a' + 10);
        }
        out[i] = (uint8_t)v;
    }
}

static void test_hmac_rfc4231_cases_1_to_5(void **state)
{
    (void)state;
    static const char *const mac[5] = {
        "b0344c61d8db38535ca8afceaf0bf12b881dc200c9833da726e9376c2e32cff7",
        "5bdcc146bf60754e6a042426089575c75a003f089d2739839dec58b964ec3843",
        "773ea91e36800e46854db8ebd09181a72959098b3ef8c122d9635514ced565fe",
        "82558a389a443c0ea4cc819899f2083a85f0faa3e578f8077a2e3ff46729665b",
        "a3b6167473100ee06e0c796c2955552b",
    };
    uint8_t key[25], msg[50];
    uint32_t key_len = 0u, msg_len = 0u;
    for (unsigned c = 0; c < 5u; c++) {
        switch (c) {
        case 0: memset(key, 0x0b, 20); key_len = 20; memcpy(msg, "Hi There", 8); msg_len = 8; break;
        case 1: memcpy(key, "Jefe", 4); key_len = 4; memcpy(msg, "what do ya want for nothing?", 28);
            msg_len = 28; break;
        case 2: memset(key, 0xaa, 20); key_len = 20; memset(msg, 0xdd, 50); msg_len = 50; break;
        case 3: for (uint8_t i = 0; i < 25u; i++) { key[i] = (uint8_t)(i + 1u); }
            key_len = 25; memset(msg, 0xcd, 50); msg_len = 50; break;
        default: memset(key, 0x0c, 20); key_len = 20; memcpy(msg, "Test With Truncation", 20);
            msg_len = 20; break;
        }
        secoc_t s;
        secoc_init(&s);
        secoc_set_key(&s, key, key_len);
        uint8_t out[SEC_SHA256_LEN], want[SEC_SHA256_LEN];
        secoc_hmac(&s, msg, msg_len, out);
        const size_t n = strlen(mac[c]) / 2u;
        hex(mac[c], want, n);
        assert_memory_equal(out, want, n);
    }
}

static const uint8_t KEY[SECOC_KEY_LEN] = "0123456789abcdef0123456789abcde";

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

static void test_frame_mac_is_truncated_hmac_of_id_payload_fv(void **state)
{
    (void)state;
    secoc_t s;
    secoc_init(&s);
    secoc_set_key(&s, KEY, SECOC_KEY_LEN);
    can_frame_t f = frame(0x105u, 3u);
    uint8_t mac[SECOC_MAC_LEN];
    secoc_mac(&s, &f, 0x01020304u, mac);
    const uint8_t msg[9] = {0x05, 0x01, 3u, 0xE8, 0x03, 0x01, 0x02, 0x03, 0x04};
    uint8_t ref[SEC_SHA256_LEN];
    sec_hmac_sha256(KEY, SECOC_KEY_LEN, msg, sizeof msg, ref);
    assert_memory_equal(mac, ref, SECOC_MAC_LEN);
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
    secoc_set_key(&rx, key, SECOC_KEY_LEN);
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
    secoc_set_key(&rx, KEY, SECOC_KEY_LEN);
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
    uint8_t st[SECOC_STATS_LEN];
    secoc_stats_encode(&rx, st);
    assert_int_equal(st[7], SECOC_MAX_BAD_MAC); /* wrong MAC count, big-endian */
    assert_int_equal(st[19], 1u);                /* keys discarded */
    assert_int_equal((st[20] << 8) | st[21], SEC_ERR_NO_KEY);
    assert_int_equal(st[22], 0u);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_hmac_rfc4231_cases_1_to_5),
        cmocka_unit_test(test_frame_mac_is_truncated_hmac_of_id_payload_fv),
        cmocka_unit_test(test_freshness_window_replay_and_keys),
        cmocka_unit_test(test_key_discarded_after_64_wrong_macs),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

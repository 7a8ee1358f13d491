/* SHA-256 against the FIPS 180-4 examples (NIST CSRC "SHA256.pdf" example values, plus the
 * one-million-'a' vector of FIPS 180-2 appendix B.3), HMAC-SHA256 against every test case of
 * RFC 4231 section 4 (case 5 truncated to 128 bits as the RFC gives it), and the constant-time
 * compare. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <cmocka.h>

#include "sec_sha256.h"

static void hex_to_bytes(const char *hex, uint8_t *out, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        unsigned v = 0;
        (void)sscanf(hex + 2 * i, "%2x", &v);
        out[i] = (uint8_t)v;
    }
}

static void assert_digest(const uint8_t *got, const char *hex, size_t n)
{
    uint8_t want[32];
    hex_to_bytes(hex, want, n);
    assert_memory_equal(got, want, n);
}

static void test_fips_vectors(void **state)
{
    (void)state;
    uint8_t d[32];
    sec_sha256((const uint8_t *)"abc", 3, d);
    assert_digest(d, "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad", 32);
    sec_sha256((const uint8_t *)"", 0, d);
    assert_digest(d, "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855", 32);
    const char *m448 = "abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq";
    sec_sha256((const uint8_t *)m448, (uint32_t)strlen(m448), d);
    assert_digest(d, "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1", 32);
    const char *m896 = "abcdefghbcdefghicdefghijdefghijkefghijklfghijklmghijklmnhijklmnoijklmnopjklmnopq"
                       "klmnopqrlmnopqrsmnopqrstnopqrstu";
    sec_sha256((const uint8_t *)m896, (uint32_t)strlen(m896), d);
    assert_digest(d, "cf5b16a778af8380036ce59e7b0492370b249b11e8f07a51afac45037afee9d1", 32);
}

static void test_million_a_incremental(void **state)
{
    (void)state;
    /* fed in odd-sized pieces so every block-boundary path of update is exercised */
    static uint8_t a[997];
    memset(a, 'a', sizeof a);
    sec_sha256_t s;
    sec_sha256_init(&s);
    uint32_t left = 1000000u;
    while (left > 0u) {
        const uint32_t k = left < sizeof a ? left : (uint32_t)sizeof a;
        sec_sha256_update(&s, a, k);
        left -= k;
    }
    uint8_t d[32];
    sec_sha256_final(&s, d);
    assert_digest(d, "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0", 32);
}

static void test_padding_boundaries(void **state)
{
    (void)state;
    /* lengths 55, 56, 63, 64, 65 straddle the one-/two-block padding cases: one-shot and
     * byte-by-byte must agree (both checked against the FIPS vectors above for the engine). */
    uint8_t msg[130];
    for (uint32_t i = 0; i < sizeof msg; i++) {
        msg[i] = (uint8_t)(i * 7u + 1u);
    }
    const uint32_t lens[] = {55, 56, 57, 63, 64, 65, 119, 120, 128, 130};
    for (size_t j = 0; j < sizeof lens / sizeof lens[0]; j++) {
        uint8_t d1[32], d2[32];
        sec_sha256(msg, lens[j], d1);
        sec_sha256_t s;
        sec_sha256_init(&s);
        for (uint32_t i = 0; i < lens[j]; i++) {
            sec_sha256_update(&s, &msg[i], 1);
        }
        sec_sha256_final(&s, d2);
        assert_memory_equal(d1, d2, 32);
    }
}

static void test_feed_in_slices_equals_one_shot(void **state)
{
    (void)state;
    /* sec_sha256_feed with a budget of 1..64 rounds a call, chunks of 1..130 bytes, then its
     * padding and digest: the same digest as the one-shot (FIPS-checked) hash; no call runs
     * more rounds than its budget */
    uint8_t msg[300];
    for (uint32_t i = 0; i < sizeof msg; i++) {
        msg[i] = (uint8_t)(i * 13u + 5u);
    }
    const uint32_t lens[] = {0, 1, 55, 56, 64, 65, 128, 191, 300};
    const uint32_t budgets[] = {1, 7, 16, 64};
    const uint32_t chunks[] = {1, 64, 130};
    for (size_t j = 0; j < sizeof lens / sizeof lens[0]; j++) {
        for (size_t b = 0; b < sizeof budgets / sizeof budgets[0]; b++) {
            for (size_t c = 0; c < sizeof chunks / sizeof chunks[0]; c++) {
                uint8_t d1[32], d2[32];
                sec_sha256(msg, lens[j], d1);
                sec_sha256_t s;
                sec_sha256_job_t job;
                memset(&job, 0, sizeof job);
                sec_sha256_init(&s);
                uint8_t pad[SEC_SHA256_PAD_MAX];
                uint32_t off = 0, calls = 0, padded = 0, pad_len = 0;
                for (;;) {
                    const uint8_t *p = padded ? pad : msg;
                    const uint32_t end = padded ? pad_len : lens[j];
                    uint32_t n = end - off < chunks[c] ? end - off : chunks[c];
                    uint32_t rounds = budgets[b];
                    off += sec_sha256_feed(&s, &job, p + off, n, &rounds);
                    assert_true(rounds <= budgets[b]);
                    calls++;
                    assert_true(calls < 100000u);
                    if (off < end || job.active) {
                        continue;
                    }
                    if (padded) {
                        break;
                    }
                    pad_len = sec_sha256_padding(&s, pad);
                    padded = 1;
                    off = 0;
                }
                sec_sha256_digest(&s, d2);
                assert_memory_equal(d1, d2, 32);
            }
        }
    }
}

typedef struct {
    uint8_t key[131];
    uint32_t key_len;
    uint8_t data[160];
    uint32_t data_len;
    const char *mac_hex;
    uint32_t mac_len;
} rfc4231_case_t;

static void test_rfc4231_all_cases(void **state)
{
    (void)state;
    static rfc4231_case_t c[7];
    memset(c, 0, sizeof c);
    /* 1 */
    memset(c[0].key, 0x0b, 20); c[0].key_len = 20;
    memcpy(c[0].data, "Hi There", 8); c[0].data_len = 8;
    c[0].mac_hex = "b0344c61d8db38535ca8afceaf0bf12b881dc200c9833da726e9376c2e32cff7"; c[0].mac_len = 32;
    /* 2 */
    memcpy(c[1].key, "Jefe", 4); c[1].key_len = 4;
    memcpy(c[1].data, "what do ya want for nothing?", 28); c[1].data_len = 28;
    c[1].mac_hex = "5bdcc146bf60754e6a042426089575c75a003f089d2739839dec58b964ec3843"; c[1].mac_len = 32;
    /* 3 */
    memset(c[2].key, 0xaa, 20); c[2].key_len = 20;
    memset(c[2].data, 0xdd, 50); c[2].data_len = 50;
    c[2].mac_hex = "773ea91e36800e46854db8ebd09181a72959098b3ef8c122d9635514ced565fe"; c[2].mac_len = 32;
    /* 4 */
    for (uint32_t i = 0; i < 25; i++) { c[3].key[i] = (uint8_t)(i + 1u); }
    c[3].key_len = 25;
    memset(c[3].data, 0xcd, 50); c[3].data_len = 50;
    c[3].mac_hex = "82558a389a443c0ea4cc819899f2083a85f0faa3e578f8077a2e3ff46729665b"; c[3].mac_len = 32;
    /* 5: truncated to 128 bits */
    memset(c[4].key, 0x0c, 20); c[4].key_len = 20;
    memcpy(c[4].data, "Test With Truncation", 20); c[4].data_len = 20;
    c[4].mac_hex = "a3b6167473100ee06e0c796c2955552b"; c[4].mac_len = 16;
    /* 6 */
    memset(c[5].key, 0xaa, 131); c[5].key_len = 131;
    const char *d6 = "Test Using Larger Than Block-Size Key - Hash Key First";
    memcpy(c[5].data, d6, strlen(d6)); c[5].data_len = (uint32_t)strlen(d6);
    c[5].mac_hex = "60e431591ee0b67f0d8a26aacbf5b77f8e0bc6213728c5140546040f0ee37f54"; c[5].mac_len = 32;
    /* 7 */
    memset(c[6].key, 0xaa, 131); c[6].key_len = 131;
    const char *d7 = "This is a test using a larger than block-size key and a larger than "
                     "block-size data. The key needs to be hashed before being used by the HMAC "
                     "algorithm.";
    memcpy(c[6].data, d7, strlen(d7)); c[6].data_len = (uint32_t)strlen(d7);
    c[6].mac_hex = "9b09ffa71b942fcb27635fbcd5b0e944bfdc63644f0713938a7f51535c3a35e2"; c[6].mac_len = 32;

    for (size_t i = 0; i < 7; i++) {
        uint8_t mac[32];
        sec_hmac_sha256(c[i].key, c[i].key_len, c[i].data, c[i].data_len, mac);
        assert_digest(mac, c[i].mac_hex, c[i].mac_len);
        /* incremental API, message split in two */
        sec_hmac_t h;
        sec_hmac_init(&h, c[i].key, c[i].key_len);
        sec_hmac_update(&h, c[i].data, c[i].data_len / 3u);
        sec_hmac_update(&h, c[i].data + c[i].data_len / 3u, c[i].data_len - c[i].data_len / 3u);
        uint8_t mac2[32];
        sec_hmac_final(&h, mac2);
        assert_memory_equal(mac, mac2, 32);
    }
}

/* The HMAC in slices (sec_hmac_job, the device's SecurityAccess check and motion key) equals the
 * one-shot HMAC for keys of 0..64 bytes and messages of 0..64 bytes, at 1, 7, 64 and unbounded
 * rounds a call. */
static void test_hmac_job_equals_one_shot(void **state)
{
    (void)state;
    static const uint32_t budgets[4] = {1u, 7u, 64u, UINT32_MAX};
    uint8_t key[64], msg[64], want[SEC_SHA256_LEN], got[SEC_SHA256_LEN];
    for (uint32_t i = 0; i < 64u; i++) {
        key[i] = (uint8_t)(0x5Au ^ (i * 7u));
        msg[i] = (uint8_t)(i * 13u + 1u);
    }
    static sec_hmac_job_t job;
    for (uint32_t kl = 0; kl <= 64u; kl += 16u) {
        for (uint32_t ml = 0; ml <= 64u; ml++) {
            sec_hmac_sha256(key, kl, msg, ml, want);
            for (unsigned b = 0; b < 4u; b++) {
                assert_true(sec_hmac_job_begin(&job, key, kl, msg, ml));
                unsigned calls = 0u;
                while (!sec_hmac_job_run(&job, budgets[b], got)) {
                    assert_true(++calls < 2000u);
                }
                assert_memory_equal(got, want, SEC_SHA256_LEN);
            }
        }
    }
    assert_false(sec_hmac_job_begin(&job, key, 65u, msg, 1u));
    assert_false(sec_hmac_job_begin(&job, key, 16u, msg, 65u));
}

static void test_ct_equal(void **state)
{
    (void)state;
    uint8_t a[16], b[16];
    for (uint32_t i = 0; i < 16; i++) {
        a[i] = (uint8_t)(i * 13u);
        b[i] = a[i];
    }
    assert_int_equal(sec_ct_equal(a, b, 16), 1);
    assert_int_equal(sec_ct_equal(a, b, 0), 1);
    for (uint32_t i = 0; i < 16; i++) {
        for (uint32_t bit = 0; bit < 8; bit++) {
            b[i] ^= (uint8_t)(1u << bit);
            assert_int_equal(sec_ct_equal(a, b, 16), 0);
            b[i] ^= (uint8_t)(1u << bit);
        }
    }
    assert_int_equal(sec_ct_equal(NULL, b, 16), 0);
}

/* Every start alignment and length up to 3 words past a 16-byte step: exactly [off, off+len)
 * zeroed, the bytes around it untouched. */
static void test_wipe_exact_range(void **state)
{
    (void)state;
    uint8_t buf[96];
    for (uint32_t off = 0u; off < 8u; off++) {
        for (uint32_t len = 0u; len <= 60u; len++) {
            for (uint32_t i = 0u; i < sizeof buf; i++) {
                buf[i] = (uint8_t)(0xA5u ^ i);
            }
            sec_wipe(&buf[off], len);
            for (uint32_t i = 0u; i < sizeof buf; i++) {
                const bool inside = i >= off && i < off + len;
                assert_int_equal(buf[i], inside ? 0u : (uint8_t)(0xA5u ^ i));
            }
        }
    }
    sec_wipe(NULL, 16u); /* nothing to wipe: no access */
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fips_vectors),
        cmocka_unit_test(test_million_a_incremental),
        cmocka_unit_test(test_padding_boundaries),
        cmocka_unit_test(test_feed_in_slices_equals_one_shot),
        cmocka_unit_test(test_rfc4231_all_cases),
        cmocka_unit_test(test_hmac_job_equals_one_shot),
        cmocka_unit_test(test_ct_equal),
        cmocka_unit_test(test_wipe_exact_range),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

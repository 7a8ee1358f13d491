/* AES-128 and AES-CMAC (sec_aes.h) against the published vectors: the FIPS 197 appendix C.1
 * example, the SP 800-38B appendix D.1 subkeys (K1, K2) and its four AES-128 examples (messages of
 * 0, 16, 40 and 64 bytes; the same as RFC 4493 section 4), and the CMAC of every length 0..64
 * against the one the blocks' encryptions give by the definition (SP 800-38B 6.2). */
#include <setjmp.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "sec_aes.h"

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

static void test_aes128_fips197_c1(void **state)
{
    (void)state;
    uint8_t key[16], pt[16], ct[16], out[16];
    hex("000102030405060708090a0b0c0d0e0f", key, 16);
    hex("00112233445566778899aabbccddeeff", pt, 16);
    hex("69c4e0d86a7b0430d8cdb78070b4c55a", ct, 16);
    sec_aes128_t a;
    sec_aes128_init(&a, key);
    sec_aes128_encrypt(&a, pt, out);
    assert_memory_equal(out, ct, 16);
    sec_aes128_encrypt(&a, pt, pt); /* in place */
    assert_memory_equal(pt, ct, 16);
}

static const char KEY_D1[] = "2b7e151628aed2a6abf7158809cf4f3c";
static const char MSG_D1[] = "6bc1bee22e409f96e93d7e117393172a"
                             "ae2d8a571e03ac9c9eb76fac45af8e51"
                             "30c81c46a35ce411e5fbc1191a0a52ef"
                             "f69f2445df4f9b17ad2b417be66c3710";

static void test_cmac_sp800_38b_subkeys(void **state)
{
    (void)state;
    uint8_t key[16], k1[16], k2[16];
    hex(KEY_D1, key, 16);
    hex("fbeed618357133667c85e08f7236a8de", k1, 16);
    hex("f7ddac306ae266ccf90bc11ee46d513b", k2, 16);
    sec_cmac_t c;
    sec_cmac_init(&c, key);
    assert_memory_equal(c.k1, k1, 16);
    assert_memory_equal(c.k2, k2, 16);
}

static void test_cmac_sp800_38b_examples_1_to_4(void **state)
{
    (void)state;
    static const uint32_t len[4] = {0u, 16u, 40u, 64u};
    static const char *const tag[4] = {
        "bb1d6929e95937287fa37d129b756746",
        "070a16b46b4d4144f79bdd9dd04a287c",
        "dfa66747de9ae63030ca32611497c827",
        "51f0bebf7e3b9d92fc49741779363cfe",
    };
    uint8_t key[16], msg[64], want[16], out[16];
    hex(KEY_D1, key, 16);
    hex(MSG_D1, msg, 64);
    sec_cmac_t c;
    sec_cmac_init(&c, key);
    for (unsigned i = 0; i < 4u; i++) {
        hex(tag[i], want, 16);
        sec_cmac(&c, msg, len[i], out);
        assert_memory_equal(out, want, 16);
    }
}

/* The definition: M_1..M_n blocks, the last XOR K1 if complete, else padded 10* XOR K2; C_i =
 * E(C_{i-1} XOR M_i). */
/* The encryption in slices of 1..11 rounds a call: the FIPS 197 ciphertext, each call runs
 * what its budget allows, and the job ends after exactly 10 rounds. */
static void test_aes128_job_in_slices(void **state)
{
    (void)state;
    uint8_t key[16], pt[16], ct[16], out[16];
    hex("000102030405060708090a0b0c0d0e0f", key, 16);
    hex("00112233445566778899aabbccddeeff", pt, 16);
    hex("69c4e0d86a7b0430d8cdb78070b4c55a", ct, 16);
    sec_aes128_t a;
    sec_aes128_init(&a, key);
    for (uint32_t k = 1u; k <= 11u; k++) {
        sec_aes128_job_t j;
        sec_aes128_job_begin(&j, &a, pt);
        memset(out, 0, sizeof out);
        uint32_t calls = 0u, used = 0u;
        bool done = false;
        while (!done) {
            uint32_t budget = k;
            done = sec_aes128_job_run(&j, &a, &budget, out);
            used += k - budget;
            calls++;
            assert_true(calls <= 10u);
            assert_true(done || budget == 0u); /* a call stops early only at the end */
        }
        assert_int_equal(used, 10u);
        assert_int_equal(calls, (10u + k - 1u) / k);
        assert_memory_equal(out, ct, 16);
    }
    /* a call with no budget runs nothing */
    sec_aes128_job_t j;
    sec_aes128_job_begin(&j, &a, pt);
    uint32_t none = 0u;
    assert_false(sec_aes128_job_run(&j, &a, &none, out));
    assert_int_equal(j.round, 0u);
}

static void cmac_by_definition(const sec_cmac_t *c, const uint8_t *m, uint32_t len, uint8_t *out)
{
    const uint32_t n = len == 0u ? 1u : (len + 15u) / 16u;
    const int complete = len != 0u && len % 16u == 0u;
    uint8_t x[16] = {0};
    for (uint32_t b = 0; b < n; b++) {
        uint8_t blk[16] = {0};
        const uint32_t take = (b + 1u < n || complete) ? 16u : len - 16u * b;
        memcpy(blk, m + 16u * b, take);
        if (b + 1u == n) {
            if (!complete) {
                blk[take] = 0x80u;
            }
            for (int i = 0; i < 16; i++) {
                blk[i] ^= complete ? c->k1[i] : c->k2[i];
            }
        }
        for (int i = 0; i < 16; i++) {
            x[i] ^= blk[i];
        }
        sec_aes128_encrypt(&c->aes, x, x);
    }
    memcpy(out, x, 16);
}

static void test_cmac_every_length_to_64(void **state)
{
    (void)state;
    uint8_t key[16], msg[64], a[16], b[16];
    hex(KEY_D1, key, 16);
    hex(MSG_D1, msg, 64);
    sec_cmac_t c;
    sec_cmac_init(&c, key);
    for (uint32_t len = 0; len <= 64u; len++) {
        sec_cmac(&c, msg, len, a);
        cmac_by_definition(&c, msg, len, b);
        assert_memory_equal(a, b, 16);
        if (len <= 16u) { /* the one-block form: its block encrypted is the CMAC */
            uint8_t blk[16];
            sec_cmac_one_block(&c, msg, len, blk);
            sec_aes128_encrypt(&c.aes, blk, blk);
            assert_memory_equal(blk, b, 16);
        }
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_aes128_fips197_c1),
        cmocka_unit_test(test_aes128_job_in_slices),
        cmocka_unit_test(test_cmac_sp800_38b_subkeys),
        cmocka_unit_test(test_cmac_sp800_38b_examples_1_to_4),
        cmocka_unit_test(test_cmac_every_length_to_64),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

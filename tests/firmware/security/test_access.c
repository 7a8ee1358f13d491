/* SecurityAccess seed/key: the key scheme against an independent HMAC (Python's hmac module,
 * value quoted below), sequence rules, the NRCs 0x13/0x24/0x35/0x36/0x37/0x22, the delay after
 * a wrong key, lockout after max_attempts, boot delay, relock, and time wrap-around. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <cmocka.h>

#include "sec_access.h"
#include "sec_sha256.h"

/* Deterministic test RNG (xorshift32), or a fixed seed, or failure. */
typedef struct {
    uint32_t x;
    int mode; /* 0 xorshift, 1 fixed pattern, 2 fail, 3 all zeros */
} test_rng_t;

static int rng_fill(void *ctx, uint8_t *buf, uint32_t len)
{
    test_rng_t *r = (test_rng_t *)ctx;
    for (uint32_t i = 0; i < len; i++) {
        switch (r->mode) {
        case 1: buf[i] = (uint8_t)(0xA0u + i); break;
        case 2: return -1;
        case 3: buf[i] = 0; break;
        default:
            r->x ^= r->x << 13;
            r->x ^= r->x >> 17;
            r->x ^= r->x << 5;
            buf[i] = (uint8_t)r->x;
            break;
        }
    }
    return 0;
}

static test_rng_t g_rng;

static void setup_cfg(sec_config_t *cfg)
{
    sec_default_config(cfg);
    for (uint32_t i = 0; i < 32; i++) {
        cfg->secret[i] = (uint8_t)i;
    }
    cfg->secret_len = 32;
    g_rng.x = 0x12345678u;
    g_rng.mode = 0;
    cfg->rng = rng_fill;
    cfg->rng_ctx = &g_rng;
    assert_int_equal(sec_config_validate(cfg), SEC_OK);
}

static void test_key_matches_independent_hmac(void **state)
{
    (void)state;
    sec_config_t cfg;
    setup_cfg(&cfg);
    uint8_t seed[SEC_SEED_LEN], key[SEC_KEY_LEN];
    for (uint32_t i = 0; i < SEC_SEED_LEN; i++) {
        seed[i] = (uint8_t)(0xA0u + i);
    }
    sec_compute_key(&cfg, seed, key);
    /* python3: hmac.new(bytes(range(32)), bytes(range(0xA0,0xB0)), hashlib.sha256).hexdigest()[:32] */
    static const uint8_t want[16] = {0xb1, 0x48, 0x97, 0x27, 0xb2, 0x60, 0x2a, 0x0e,
                                     0x04, 0x7c, 0xb2, 0x37, 0x58, 0x0a, 0x4c, 0x79};
    assert_memory_equal(key, want, 16);
}

/* Each tester its own seed: another tester's request voids nothing, a key answers only its own
 * tester's seed (the other tester, with no seed of its own, gets 0x24), and the shared attempt
 * counter counts wrong keys from either. */
static void test_seeds_per_tester(void **state)
{
    (void)state;
    sec_config_t cfg;
    setup_cfg(&cfg);
    sec_state_t st;
    sec_init(&cfg, &st, 0);
    uint8_t seed0[SEC_SEED_LEN], seed1[SEC_SEED_LEN], key0[SEC_KEY_LEN];
    assert_int_equal(sec_request_seed(&cfg, &st, 0u, 1000, seed0), SEC_NRC_NONE);
    sec_compute_key(&cfg, seed0, key0);
    assert_int_equal(sec_send_key(&cfg, &st, 1u, 1001, key0, SEC_KEY_LEN), SEC_NRC_SEQUENCE_ERROR);
    assert_int_equal(sec_request_seed(&cfg, &st, 1u, 1002, seed1), SEC_NRC_NONE);
    assert_memory_not_equal(seed0, seed1, SEC_SEED_LEN);
    assert_int_equal(sec_send_key(&cfg, &st, 1u, 1003, key0, SEC_KEY_LEN), SEC_NRC_INVALID_KEY);
    assert_int_equal(st.failed, 1u);
    /* positive control: tester 0's seed survived both; its key unlocks once the delay is over */
    assert_int_equal(sec_send_key(&cfg, &st, 0u, 2004, key0, SEC_KEY_LEN), SEC_NRC_NONE);
    assert_true(sec_is_unlocked(&st));
    assert_int_equal(sec_request_seed(&cfg, &st, 2u, 2005, seed1), SEC_NRC_CONDITIONS);
}

static void test_unlock_flow(void **state)
{
    (void)state;
    sec_config_t cfg;
    setup_cfg(&cfg);
    sec_state_t st;
    sec_init(&cfg, &st, 0);
    uint8_t seed[SEC_SEED_LEN], key[SEC_KEY_LEN];
    /* boot delay */
    assert_int_equal(sec_request_seed(&cfg, &st, 0u, 999, seed), SEC_NRC_DELAY_NOT_EXPIRED);
    assert_int_equal(sec_request_seed(&cfg, &st, 0u, 1000, seed), SEC_NRC_NONE);
    assert_false(sec_is_unlocked(&st));
    sec_compute_key(&cfg, seed, key);
    assert_int_equal(sec_send_key(&cfg, &st, 0u, 1001, key, SEC_KEY_LEN), SEC_NRC_NONE);
    assert_true(sec_is_unlocked(&st));
    /* already unlocked: zero seed; a key now is out of sequence */
    uint8_t zero[SEC_SEED_LEN] = {0};
    assert_int_equal(sec_request_seed(&cfg, &st, 0u, 1002, seed), SEC_NRC_NONE);
    assert_memory_equal(seed, zero, SEC_SEED_LEN);
    assert_int_equal(sec_send_key(&cfg, &st, 0u, 1003, key, SEC_KEY_LEN), SEC_NRC_SEQUENCE_ERROR);
    /* relock: the old key does not work for a new seed */
    sec_lock(&st);
    assert_false(sec_is_unlocked(&st));
    assert_int_equal(sec_request_seed(&cfg, &st, 0u, 1004, seed), SEC_NRC_NONE);
    assert_int_equal(sec_send_key(&cfg, &st, 0u, 1005, key, SEC_KEY_LEN), SEC_NRC_INVALID_KEY);
    assert_false(sec_is_unlocked(&st));
}

/* sendKey in slices (sec_send_key_begin/run, the device's 0x78 path): pending until the four
 * compressions are done, then the same answers as sec_send_key; the attempt is counted as a
 * wrong key from its begin until a correct key's check ends, and a relock drops the check. */
static void test_sliced_send_key(void **state)
{
    (void)state;
    sec_config_t cfg;
    setup_cfg(&cfg);
    sec_state_t st;
    sec_init(&cfg, &st, 0);
    uint8_t seed[SEC_SEED_LEN], key[SEC_KEY_LEN];
    assert_int_equal(sec_request_seed(&cfg, &st, 0u, 1000, seed), SEC_NRC_NONE);
    sec_compute_key(&cfg, seed, key);
    assert_int_equal(sec_send_key_begin(&cfg, &st, 0u, key, SEC_KEY_LEN), SEC_NRC_PENDING);
    assert_int_equal(st.failed, 1u);
    unsigned calls = 1u;
    while (sec_send_key_run(&cfg, &st, 1001, 8u) == SEC_NRC_PENDING) {
        calls++;
        assert_false(sec_is_unlocked(&st));
    }
    assert_true(sec_is_unlocked(&st));
    assert_int_equal(st.failed, 0u);
    assert_int_equal(calls, 33u); /* 4 x 64 rounds, 8 a call, then the digests and the comparison */
    assert_int_equal(sec_send_key_run(&cfg, &st, 1002, 8u), SEC_NRC_SEQUENCE_ERROR);
    /* a wrong key: counted at the begin, delay after the check */
    sec_lock(&st);
    assert_int_equal(sec_request_seed(&cfg, &st, 0u, 1003, seed), SEC_NRC_NONE);
    key[0] ^= 1u;
    assert_int_equal(sec_send_key_begin(&cfg, &st, 0u, key, SEC_KEY_LEN), SEC_NRC_PENDING);
    assert_int_equal(sec_send_key_run(&cfg, &st, 1004, UINT32_MAX), SEC_NRC_INVALID_KEY);
    assert_int_equal(st.failed, 1u);
    assert_int_equal(sec_request_seed(&cfg, &st, 0u, 1005, seed), SEC_NRC_DELAY_NOT_EXPIRED);
    /* a relock while the check runs: dropped, still counted */
    assert_int_equal(sec_request_seed(&cfg, &st, 0u, 2004, seed), SEC_NRC_NONE);
    sec_compute_key(&cfg, seed, key);
    assert_int_equal(sec_send_key_begin(&cfg, &st, 0u, key, SEC_KEY_LEN), SEC_NRC_PENDING);
    assert_int_equal(sec_send_key_run(&cfg, &st, 2005, 8u), SEC_NRC_PENDING);
    sec_lock(&st);
    assert_int_equal(sec_send_key_run(&cfg, &st, 2006, UINT32_MAX), SEC_NRC_SEQUENCE_ERROR);
    assert_false(sec_is_unlocked(&st));
    assert_int_equal(st.failed, 2u);
}

static void test_sequence_and_length(void **state)
{
    (void)state;
    sec_config_t cfg;
    setup_cfg(&cfg);
    cfg.boot_delay_ms = 0;
    sec_state_t st;
    sec_init(&cfg, &st, 0);
    uint8_t seed[SEC_SEED_LEN], key[SEC_KEY_LEN];
    assert_int_equal(sec_send_key(&cfg, &st, 0u, 0, key, SEC_KEY_LEN), SEC_NRC_SEQUENCE_ERROR);
    assert_int_equal(sec_request_seed(&cfg, &st, 0u, 0, seed), SEC_NRC_NONE);
    sec_compute_key(&cfg, seed, key);
    assert_int_equal(sec_send_key(&cfg, &st, 0u, 0, key, SEC_KEY_LEN - 1), SEC_NRC_INCORRECT_LENGTH);
    /* the seed was consumed by that answer: the right key is now out of sequence */
    assert_int_equal(sec_send_key(&cfg, &st, 0u, 0, key, SEC_KEY_LEN), SEC_NRC_SEQUENCE_ERROR);
    assert_false(sec_is_unlocked(&st));
    /* every seed is fresh */
    uint8_t s2[SEC_SEED_LEN];
    assert_int_equal(sec_request_seed(&cfg, &st, 0u, 0, seed), SEC_NRC_NONE);
    assert_int_equal(sec_request_seed(&cfg, &st, 0u, 0, s2), SEC_NRC_NONE);
    assert_memory_not_equal(seed, s2, SEC_SEED_LEN);
    /* only the latest seed's key is accepted */
    sec_compute_key(&cfg, seed, key);
    assert_int_equal(sec_send_key(&cfg, &st, 0u, 0, key, SEC_KEY_LEN), SEC_NRC_INVALID_KEY);
}

static void test_every_bit_flip_rejected(void **state)
{
    (void)state;
    sec_config_t cfg;
    setup_cfg(&cfg);
    cfg.boot_delay_ms = 0;
    cfg.delay_ms = 0;
    cfg.max_attempts = 255;
    sec_state_t st;
    sec_init(&cfg, &st, 0);
    uint8_t seed[SEC_SEED_LEN], key[SEC_KEY_LEN];
    for (uint32_t bit = 0; bit < 8u * SEC_KEY_LEN; bit++) {
        assert_int_equal(sec_request_seed(&cfg, &st, 0u, 0, seed), SEC_NRC_NONE);
        sec_compute_key(&cfg, seed, key);
        key[bit / 8u] ^= (uint8_t)(1u << (bit % 8u));
        const sec_nrc_t r = sec_send_key(&cfg, &st, 0u, 0, key, SEC_KEY_LEN);
        assert_true(r == SEC_NRC_INVALID_KEY || r == SEC_NRC_EXCEEDED_ATTEMPTS);
        assert_false(sec_is_unlocked(&st));
        if (r == SEC_NRC_EXCEEDED_ATTEMPTS) {
            break;
        }
    }
}

static void test_delay_and_lockout(void **state)
{
    (void)state;
    sec_config_t cfg;
    setup_cfg(&cfg);
    cfg.boot_delay_ms = 0;
    sec_state_t st;
    sec_init(&cfg, &st, 0);
    uint8_t seed[SEC_SEED_LEN], key[SEC_KEY_LEN];
    uint8_t wrong[SEC_KEY_LEN];
    memset(wrong, 0x55, sizeof wrong);
    uint32_t t = 100;
    /* attempt 1: invalid key, then the delay */
    assert_int_equal(sec_request_seed(&cfg, &st, 0u, t, seed), SEC_NRC_NONE);
    assert_int_equal(sec_send_key(&cfg, &st, 0u, t, wrong, SEC_KEY_LEN), SEC_NRC_INVALID_KEY);
    assert_int_equal(sec_request_seed(&cfg, &st, 0u, t + 999, seed), SEC_NRC_DELAY_NOT_EXPIRED);
    t += 1000;
    /* attempt 2 */
    assert_int_equal(sec_request_seed(&cfg, &st, 0u, t, seed), SEC_NRC_NONE);
    assert_int_equal(sec_send_key(&cfg, &st, 0u, t, wrong, SEC_KEY_LEN), SEC_NRC_INVALID_KEY);
    t += 1000;
    /* attempt 3 reaches max_attempts: 0x36 and the lockout */
    assert_int_equal(sec_request_seed(&cfg, &st, 0u, t, seed), SEC_NRC_NONE);
    assert_int_equal(sec_send_key(&cfg, &st, 0u, t, wrong, SEC_KEY_LEN), SEC_NRC_EXCEEDED_ATTEMPTS);
    assert_true(st.locked_out != 0u);
    assert_int_equal(sec_send_key(&cfg, &st, 0u, t, wrong, SEC_KEY_LEN), SEC_NRC_SEQUENCE_ERROR);
    assert_int_equal(sec_request_seed(&cfg, &st, 0u, t + 1000, seed), SEC_NRC_DELAY_NOT_EXPIRED);
    assert_int_equal(sec_request_seed(&cfg, &st, 0u, t + 9999, seed), SEC_NRC_DELAY_NOT_EXPIRED);
    /* relock (session change) does not reset the lockout */
    sec_lock(&st);
    assert_int_equal(sec_request_seed(&cfg, &st, 0u, t + 9999, seed), SEC_NRC_DELAY_NOT_EXPIRED);
    /* lockout over: counter reset, the right key unlocks */
    t += 10000;
    assert_int_equal(sec_request_seed(&cfg, &st, 0u, t, seed), SEC_NRC_NONE);
    assert_int_equal(st.failed, 0);
    sec_compute_key(&cfg, seed, key);
    assert_int_equal(sec_send_key(&cfg, &st, 0u, t, key, SEC_KEY_LEN), SEC_NRC_NONE);
    assert_true(sec_is_unlocked(&st));
}

/* Power-up from the record kept across resets: a lockout, and a count of max_attempts wrong keys
 * whose lockout was never recorded (the power failed between the two writes), both restart the
 * lockout; fewer wrong keys the delay; none the boot delay. */
static void test_restore_from_the_record(void **state)
{
    (void)state;
    sec_config_t cfg;
    setup_cfg(&cfg);
    uint8_t seed[SEC_SEED_LEN];
    static const struct {
        uint8_t failed, locked_out;
        uint32_t wait_ms;
    } cases[] = {{0u, 0u, 1000u}, {2u, 0u, 1000u}, {3u, 0u, 10000u}, {0u, 1u, 10000u}};
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        sec_state_t st;
        const uint32_t t = 5000u;
        sec_restore(&cfg, &st, t, cases[i].failed, cases[i].locked_out);
        assert_int_equal(sec_request_seed(&cfg, &st, 0u, t + cases[i].wait_ms - 1u, seed),
                         SEC_NRC_DELAY_NOT_EXPIRED);
        assert_int_equal(sec_request_seed(&cfg, &st, 0u, t + cases[i].wait_ms, seed), SEC_NRC_NONE);
        uint8_t rec[SEC_RECORD_LEN], failed = 0xFFu, locked = 0xFFu;
        sec_record_encode(&st, rec);
        assert_true(sec_record_decode(rec, SEC_RECORD_LEN, &failed, &locked));
        assert_int_equal(locked, 0u); /* the lockout served: the count starts again */
        assert_int_equal(failed, cases[i].wait_ms == 10000u ? 0u : cases[i].failed);
    }
}

static void test_configurable_attempts_and_wrap(void **state)
{
    (void)state;
    sec_config_t cfg;
    setup_cfg(&cfg);
    cfg.boot_delay_ms = 0;
    cfg.max_attempts = 5;
    sec_state_t st;
    /* time close to the 32-bit wrap of the millisecond clock */
    uint32_t t = 0xFFFFFF00u;
    sec_init(&cfg, &st, t);
    uint8_t seed[SEC_SEED_LEN], wrong[SEC_KEY_LEN];
    memset(wrong, 0, sizeof wrong);
    for (int i = 1; i <= 5; i++) {
        assert_int_equal(sec_request_seed(&cfg, &st, 0u, t, seed), SEC_NRC_NONE);
        const sec_nrc_t r = sec_send_key(&cfg, &st, 0u, t, wrong, SEC_KEY_LEN);
        assert_int_equal(r, i < 5 ? SEC_NRC_INVALID_KEY : SEC_NRC_EXCEEDED_ATTEMPTS);
        assert_int_equal(sec_request_seed(&cfg, &st, 0u, t + 1, seed), SEC_NRC_DELAY_NOT_EXPIRED);
        t += (i < 5) ? cfg.delay_ms : 0u; /* crosses 2^32 here */
    }
    assert_int_equal(sec_request_seed(&cfg, &st, 0u, t + cfg.lockout_ms - 1u, seed),
                     SEC_NRC_DELAY_NOT_EXPIRED);
    assert_int_equal(sec_request_seed(&cfg, &st, 0u, t + cfg.lockout_ms, seed), SEC_NRC_NONE);
}

static void test_rng_failures_and_config(void **state)
{
    (void)state;
    sec_config_t cfg;
    setup_cfg(&cfg);
    cfg.boot_delay_ms = 0;
    sec_state_t st;
    sec_init(&cfg, &st, 0);
    uint8_t seed[SEC_SEED_LEN], key[SEC_KEY_LEN];
    g_rng.mode = 2;
    assert_int_equal(sec_request_seed(&cfg, &st, 0u, 0, seed), SEC_NRC_CONDITIONS);
    g_rng.mode = 3;
    assert_int_equal(sec_request_seed(&cfg, &st, 0u, 0, seed), SEC_NRC_CONDITIONS);
    assert_int_equal(sec_send_key(&cfg, &st, 0u, 0, key, SEC_KEY_LEN), SEC_NRC_SEQUENCE_ERROR);
    g_rng.mode = 0;
    sec_config_t bad = cfg;
    bad.secret_len = 8;
    assert_int_equal(sec_config_validate(&bad), SEC_ERR_CONFIG);
    bad = cfg;
    bad.max_attempts = 0;
    assert_int_equal(sec_config_validate(&bad), SEC_ERR_CONFIG);
    bad = cfg;
    bad.rng = NULL;
    assert_int_equal(sec_config_validate(&bad), SEC_ERR_NULL_ARG);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_key_matches_independent_hmac),
        cmocka_unit_test(test_unlock_flow),
        cmocka_unit_test(test_seeds_per_tester),
        cmocka_unit_test(test_sliced_send_key),
        cmocka_unit_test(test_sequence_and_length),
        cmocka_unit_test(test_every_bit_flip_rejected),
        cmocka_unit_test(test_delay_and_lockout),
        cmocka_unit_test(test_restore_from_the_record),
        cmocka_unit_test(test_configurable_attempts_and_wrap),
        cmocka_unit_test(test_rng_failures_and_config),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

/* UDS SecurityAccess (ISO 14229-1 service 0x27) seed/key logic, transport-free.
 *
 * Scheme: requestSeed returns SEC_SEED_LEN fresh random bytes from the HAL random source;
 *   key = first SEC_KEY_LEN (16) bytes of HMAC-SHA256(device_secret, seed)
 * Truncating HMAC-SHA256 to 128 bits
 * follows RFC 2104 section 5 / NIST SP 800-107 (>= 64 bits and >= half the output). Each seed
 * answers one sendKey only (valid or not); a new requestSeed issues a new seed.
 *
 * Attempts: every wrong key increments a counter and starts a delay (delay_ms) during which
 * requestSeed answers 0x37 requiredTimeDelayNotExpired. The wrong key that reaches max_attempts
 * answers 0x36 exceededNumberOfAttempts and starts the lockout (lockout_ms), also answered with
 * 0x37. A correct key resets the counter. The counter survives sec_lock (session change). A
 * power cycle cannot be used to skip the delay: sec_init starts a boot delay (boot_delay_ms,
 * default = delay_ms) during which requestSeed also answers 0x37 (ISO 14229-1 allows this), and
 * an application that keeps the counter in non-volatile memory (sec_record_*) restores it with
 * sec_restore, which restarts the lockout at power-up after a lockout (ISO 14229-1: the delay
 * timer is active on power-up). One state serves every level; each level has its own config
 * (its own secret). Each tester (a UDS request id, 0..SEC_TESTERS-1) has its own seed: a key is
 * checked against the seed its own tester was sent, so another tester's seed request voids
 * nothing and a key read off the bus is worthless on another id. The attempt counter is shared:
 * wrong keys from any tester start the delay and the lockout for every tester. */
#ifndef SEC_ACCESS_H
#define SEC_ACCESS_H

#include <stdbool.h>
#include <stdint.h>
#include "sec_sha256.h"
#include "sec_status.h"

#define SEC_SEED_LEN 16u
#define SEC_KEY_LEN 16u
#define SEC_SECRET_MAX 64u
#define SEC_TESTERS 2u    /* testers with a seed of their own */
#define SEC_RECORD_LEN 4u /* attempt record: magic 'S', failed, locked_out, ~failed */

/** Result of a SecurityAccess step: 0 = positive response, else the UDS NRC to send. */
typedef enum {
    SEC_NRC_NONE = 0x00,
    SEC_NRC_INCORRECT_LENGTH = 0x13,  /* incorrectMessageLengthOrInvalidFormat */
    SEC_NRC_SEQUENCE_ERROR = 0x24,    /* requestSequenceError: sendKey without a fresh seed */
    SEC_NRC_INVALID_KEY = 0x35,       /* invalidKey */
    SEC_NRC_EXCEEDED_ATTEMPTS = 0x36, /* exceededNumberOfAttempts (lockout starts) */
    SEC_NRC_DELAY_NOT_EXPIRED = 0x37, /* requiredTimeDelayNotExpired */
    SEC_NRC_CONDITIONS = 0x22,        /* conditionsNotCorrect: random source failed */
    SEC_NRC_PENDING = 0x78,           /* responsePending: the key's check goes on */
} sec_nrc_t;

/** Random source of the HAL: fill buf with len unpredictable bytes; 0 on success. */
typedef int (*sec_rng_fn)(void *ctx, uint8_t *buf, uint32_t len);

/** Configuration (device secret from protected storage, policy). */
typedef struct {
    uint8_t secret[SEC_SECRET_MAX];
    uint8_t secret_len;     /* 16..64 bytes */
    uint8_t max_attempts;   /* wrong keys before lockout (default 3, 1..255) */
    uint32_t delay_ms;      /* after each wrong key (default 1000) */
    uint32_t lockout_ms;    /* after max_attempts wrong keys (default 10000) */
    uint32_t boot_delay_ms; /* after power-up (default 1000; 0 = none) */
    sec_rng_fn rng;
    void *rng_ctx;
} sec_config_t;

/** Session state. */
typedef struct {
    uint8_t seed[SEC_TESTERS][SEC_SEED_LEN];
    uint8_t seed_valid[SEC_TESTERS]; /* a seed was issued to the tester and not yet answered */
    uint8_t unlocked;
    uint8_t failed; /* wrong keys since the last success (or lockout end) */
    uint8_t locked_out;
    uint32_t wait_until_ms;   /* requestSeed refused (0x37) before this time */
    uint8_t waiting;          /* wait_until_ms is in force */
    uint8_t checking;         /* a sendKey's check runs (sec_send_key_run) */
    uint8_t key[SEC_KEY_LEN]; /* the key being checked */
    sec_hmac_job_t job;       /* its expected value, HMAC-SHA256(secret, seed), in slices */
} sec_state_t;

/** Fill defaults (secret left empty: the caller copies the device secret in). */
void sec_default_config(sec_config_t *cfg);

/** Check secret length, attempts and the rng pointer. */
sec_status_t sec_config_validate(const sec_config_t *cfg);

/** Power-up: locked, no seed, counter zero, requestSeed refused until now_ms + boot_delay_ms. */
void sec_init(const sec_config_t *cfg, sec_state_t *st, uint32_t now_ms);

/** Power-up with the attempt record kept across resets: counter restored; requestSeed refused
 *  for lockout_ms after a lockout (or a count of max_attempts), else delay_ms after a wrong key,
 *  else boot_delay_ms. */
void sec_restore(const sec_config_t *cfg, sec_state_t *st, uint32_t now_ms, uint8_t failed,
                 uint8_t locked_out);

/** Encode the attempt counter of st into rec[SEC_RECORD_LEN] (what the application stores). */
void sec_record_encode(const sec_state_t *st, uint8_t rec[SEC_RECORD_LEN]);

/** Decode a stored record; false (nothing written) if len or its check bytes are wrong. */
bool sec_record_decode(const uint8_t *rec, uint32_t len, uint8_t *failed, uint8_t *locked_out);

/** requestSeed of tester (0..SEC_TESTERS-1) at now_ms: seed_out[SEC_SEED_LEN] gets a fresh seed
 *  (the tester's previous one void, the other testers' kept), or all zeros if already unlocked
 *  (ISO 14229-1). Returns 0x37 during a delay/lockout, 0x22 if the RNG fails or tester is bad. */
sec_nrc_t sec_request_seed(const sec_config_t *cfg, sec_state_t *st, uint8_t tester,
                           uint32_t now_ms, uint8_t seed_out[SEC_SEED_LEN]);

/** sendKey of tester at now_ms: 0 unlocks; 0x24 without an outstanding seed of that tester, 0x13
 *  on a wrong length, 0x35 wrong key, 0x36 wrong key that reaches max_attempts; the seed is
 *  consumed. */
sec_nrc_t sec_send_key(const sec_config_t *cfg, sec_state_t *st, uint8_t tester, uint32_t now_ms,
                       const uint8_t *key, uint32_t key_len);

/** sendKey in slices: the checks of sec_send_key that need no hash (0x24, 0x13), else the
 *  seed is consumed, the attempt counted as a wrong key until the check ends, and
 *  SEC_NRC_PENDING returned; sec_send_key_run finishes it. */
sec_nrc_t sec_send_key_begin(const sec_config_t *cfg, sec_state_t *st, uint8_t tester,
                             const uint8_t *key, uint32_t key_len);

/** Up to rounds SHA-256 rounds of the check begun (4 x 64 in all): SEC_NRC_PENDING while it
 *  runs, then sec_send_key's answer at now_ms. 0x24 if no check runs. */
sec_nrc_t sec_send_key_run(const sec_config_t *cfg, sec_state_t *st, uint32_t now_ms,
                           uint32_t rounds);

/** True if writes are allowed (an unlocked session). */
bool sec_is_unlocked(const sec_state_t *st);

/** Relock (session change, ECUReset, S3 timeout); keeps the attempt counter and delays; a
 *  check that runs is dropped (its seed is used up). */
void sec_lock(sec_state_t *st);

/** The key a tester computes for seed (for the tests and the host tools' reference). */
void sec_compute_key(const sec_config_t *cfg, const uint8_t seed[SEC_SEED_LEN],
                     uint8_t key_out[SEC_KEY_LEN]);

#endif /* SEC_ACCESS_H */

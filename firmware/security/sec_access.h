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
 * default = delay_ms) during which requestSeed also answers 0x37 (ISO 14229-1 allows this). */
#ifndef SEC_ACCESS_H
#define SEC_ACCESS_H

#include <stdbool.h>
#include <stdint.h>
#include "sec_status.h"

#define SEC_SEED_LEN 16u
#define SEC_KEY_LEN 16u
#define SEC_SECRET_MAX 64u

/** Result of a SecurityAccess step: 0 = positive response, else the UDS NRC to send. */
typedef enum {
    SEC_NRC_NONE = 0x00,
    SEC_NRC_INCORRECT_LENGTH = 0x13,  /* incorrectMessageLengthOrInvalidFormat */
    SEC_NRC_SEQUENCE_ERROR = 0x24,    /* requestSequenceError: sendKey without a fresh seed */
    SEC_NRC_INVALID_KEY = 0x35,       /* invalidKey */
    SEC_NRC_EXCEEDED_ATTEMPTS = 0x36, /* exceededNumberOfAttempts (lockout starts) */
    SEC_NRC_DELAY_NOT_EXPIRED = 0x37, /* requiredTimeDelayNotExpired */
    SEC_NRC_CONDITIONS = 0x22,        /* conditionsNotCorrect: random source failed */
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
    uint8_t seed[SEC_SEED_LEN];
    uint8_t seed_valid; /* a seed was issued and not yet answered */
    uint8_t unlocked;
    uint8_t failed; /* wrong keys since the last success (or lockout end) */
    uint8_t locked_out;
    uint32_t wait_until_ms; /* requestSeed refused (0x37) before this time */
    uint8_t waiting;        /* wait_until_ms is in force */
} sec_state_t;

/** Fill defaults (secret left empty: the caller copies the device secret in). */
void sec_default_config(sec_config_t *cfg);

/** Check secret length, attempts and the rng pointer. */
sec_status_t sec_config_validate(const sec_config_t *cfg);

/** Power-up: locked, no seed, counter zero, requestSeed refused until now_ms + boot_delay_ms. */
void sec_init(const sec_config_t *cfg, sec_state_t *st, uint32_t now_ms);

/** requestSeed at now_ms: seed_out[SEC_SEED_LEN] gets a fresh seed, or all zeros if already
 *  unlocked (ISO 14229-1). Returns 0x37 during a delay/lockout, 0x22 if the RNG fails. */
sec_nrc_t sec_request_seed(const sec_config_t *cfg, sec_state_t *st, uint32_t now_ms,
                           uint8_t seed_out[SEC_SEED_LEN]);

/** sendKey at now_ms: 0 unlocks; 0x24 without an outstanding seed, 0x13 on a wrong length,
 *  0x35 wrong key, 0x36 wrong key that reaches max_attempts; the seed is consumed. */
sec_nrc_t sec_send_key(const sec_config_t *cfg, sec_state_t *st, uint32_t now_ms,
                       const uint8_t *key, uint32_t key_len);

/** True if writes are allowed (an unlocked session). */
bool sec_is_unlocked(const sec_state_t *st);

/** Relock (session change, ECUReset, S3 timeout); keeps the attempt counter and delays. */
void sec_lock(sec_state_t *st);

/** The key a tester computes for seed (for the tests and the host tools' reference). */
void sec_compute_key(const sec_config_t *cfg, const uint8_t seed[SEC_SEED_LEN],
                     uint8_t key_out[SEC_KEY_LEN]);

#endif /* SEC_ACCESS_H */

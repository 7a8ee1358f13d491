/* SHA-256 (FIPS 180-4) and HMAC-SHA256 (RFC 2104 / FIPS 198-1), checked against the FIPS 180-4
 * examples and every RFC 4231 test case (tests/firmware/security). No heap, bounded work per
 * byte, no data-dependent branches on message or key contents. */
#ifndef SEC_SHA256_H
#define SEC_SHA256_H

#include <stdbool.h>
#include <stdint.h>

#define SEC_SHA256_LEN 32u
#define SEC_SHA256_BLOCK 64u

/** Incremental SHA-256 state. */
typedef struct {
    uint32_t h[8];
    uint64_t total_len; /* bytes hashed so far */
    uint8_t block[SEC_SHA256_BLOCK];
    uint32_t block_len;
} sec_sha256_t;

#define SEC_SHA256_PAD_MAX 72u /* the longest padding of a message (0x80, zeros, length) */

/** A block's compression spread over calls (sec_sha256_feed): the schedule's window, the working
 *  variables, the next of its 64 rounds. */
typedef struct {
    uint32_t w[16];
    uint32_t v[8];
    uint32_t round;
    uint32_t active; /* 1 while a block is being compressed */
} sec_sha256_job_t;

/** Start a hash. */
void sec_sha256_init(sec_sha256_t *s);

/** Add len bytes. */
void sec_sha256_update(sec_sha256_t *s, const uint8_t *data, uint32_t len);

/** Finish into out[32]; the state must be re-initialised before reuse. */
void sec_sha256_final(sec_sha256_t *s, uint8_t out[SEC_SHA256_LEN]);

/** Add up to len bytes in bounded work: at most *rounds compression rounds (64 a block, the
 *  budget decreased by those run), a full block's compression carried in job (zeroed before the
 *  first call) across calls. Returns the bytes taken; they are all in the hash once a call
 *  returns len with job->active 0. Do not mix with sec_sha256_update while job->active. */
uint32_t sec_sha256_feed(sec_sha256_t *s, sec_sha256_job_t *job, const uint8_t *data, uint32_t len,
                         uint32_t *rounds);

/** The padding sec_sha256_final adds for the bytes hashed so far, into pad; returns its length
 *  (9..72). Feeding it then sec_sha256_digest is sec_sha256_final. */
uint32_t sec_sha256_padding(const sec_sha256_t *s, uint8_t pad[SEC_SHA256_PAD_MAX]);

/** The digest of a hash whose padding was added (sec_sha256_padding) into out[32]; wipes *s. */
void sec_sha256_digest(sec_sha256_t *s, uint8_t out[SEC_SHA256_LEN]);

/** One-shot SHA-256 of data. */
void sec_sha256(const uint8_t *data, uint32_t len, uint8_t out[SEC_SHA256_LEN]);

/** Incremental HMAC-SHA256 state. */
typedef struct {
    sec_sha256_t inner;
    uint8_t okey[SEC_SHA256_BLOCK]; /* key XOR opad */
} sec_hmac_t;

/** Start an HMAC with key (any length; keys longer than 64 bytes are hashed first). */
void sec_hmac_init(sec_hmac_t *h, const uint8_t *key, uint32_t key_len);

/** Add message bytes. */
void sec_hmac_update(sec_hmac_t *h, const uint8_t *data, uint32_t len);

/** Finish into out[32] and wipe the key material from *h. */
void sec_hmac_final(sec_hmac_t *h, uint8_t out[SEC_SHA256_LEN]);

/** One-shot HMAC-SHA256. */
void sec_hmac_sha256(const uint8_t *key, uint32_t key_len, const uint8_t *msg, uint32_t msg_len,
                     uint8_t out[SEC_SHA256_LEN]);

#define SEC_HMAC_JOB_MSG_MAX 64u /* the longest message of a sec_hmac_job_t */

/** An HMAC-SHA256 of a short message (key and message up to 64 bytes each: four compressions)
 *  spread over calls in bounded work (sec_hmac_job_run). */
typedef struct {
    sec_sha256_t inner, outer;
    sec_sha256_job_t job;
    uint8_t ikey[SEC_SHA256_BLOCK]; /* key XOR ipad */
    uint8_t okey[SEC_SHA256_BLOCK]; /* key XOR opad */
    uint8_t msg[SEC_HMAC_JOB_MSG_MAX];
    uint8_t buf[SEC_SHA256_PAD_MAX]; /* the padding or the inner digest being fed */
    const uint8_t *chunk;            /* what is being fed: chunk_len bytes, chunk_off of them in */
    uint32_t msg_len, chunk_len, chunk_off;
    uint32_t stage;
} sec_hmac_job_t;

/** Start the HMAC of msg (len <= SEC_HMAC_JOB_MSG_MAX, copied) under key (key_len <= 64 bytes):
 *  no compression yet. False (nothing started) if a length is out of range. */
bool sec_hmac_job_begin(sec_hmac_job_t *j, const uint8_t *key, uint32_t key_len, const uint8_t *msg,
                        uint32_t len);

/** Up to rounds more compression rounds (4 x 64 in all, ~40-55 instructions each on a Cortex-M4);
 *  true once out[32] holds the MAC (key pads and digests wiped as they are used). */
bool sec_hmac_job_run(sec_hmac_job_t *j, uint32_t rounds, uint8_t out[SEC_SHA256_LEN]);

/** Constant-time comparison: 1 if the len bytes are equal, 0 otherwise; the time depends on
 *  len only. */
int sec_ct_equal(const uint8_t *a, const uint8_t *b, uint32_t len);

/** Overwrite len bytes with zeros in a way the compiler does not remove. */
void sec_wipe(void *p, uint32_t len);

#endif /* SEC_SHA256_H */

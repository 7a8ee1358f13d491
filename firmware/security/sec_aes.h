/* AES-128 encryption (FIPS 197) and AES-CMAC (NIST SP 800-38B, RFC 4493), checked against the
 * FIPS 197 example and the SP 800-38B AES-128 examples (tests/firmware/security/test_cmac.c).
 * Encryption only (CMAC needs no inverse cipher), one 1 KiB round table with rotations; no heap,
 * no branch on key or data. A table lookup's time does not depend on its index on a core
 * without a data cache (Cortex-M3/M4); on a cached core it may (docs/protocol.md). */
#ifndef SEC_AES_H
#define SEC_AES_H

#include <stdbool.h>
#include <stdint.h>

#define SEC_AES_BLOCK 16u
#define SEC_AES128_KEY_LEN 16u

/** An AES-128 key schedule (the 44 round-key words). */
typedef struct {
    uint32_t rk[44];
} sec_aes128_t;

/** An AES-CMAC key: the schedule and the subkeys K1, K2 of SP 800-38B section 6.1. */
typedef struct {
    sec_aes128_t aes;
    uint8_t k1[SEC_AES_BLOCK];
    uint8_t k2[SEC_AES_BLOCK];
} sec_cmac_t;

/** A block encryption in slices (sec_aes128_job_begin, then _run): the state after `round` of
 *  the cipher's 10 rounds. */
typedef struct {
    uint32_t s[4];
    uint32_t round;
} sec_aes128_job_t;

/** Expand key into the round keys. */
void sec_aes128_init(sec_aes128_t *a, const uint8_t key[SEC_AES128_KEY_LEN]);

/** Encrypt one block (in and out may be the same buffer). */
void sec_aes128_encrypt(const sec_aes128_t *a, const uint8_t in[SEC_AES_BLOCK],
                        uint8_t out[SEC_AES_BLOCK]);

/** Starts encrypting in (the initial round key; no round run yet). */
void sec_aes128_job_begin(sec_aes128_job_t *j, const sec_aes128_t *a,
                          const uint8_t in[SEC_AES_BLOCK]);

/** Runs at most *rounds of the job's remaining rounds (*rounds decreases by those run); true
 *  once the tenth has run, out then holds the ciphertext (sec_aes128_encrypt's). */
bool sec_aes128_job_run(sec_aes128_job_t *j, const sec_aes128_t *a, uint32_t *rounds,
                        uint8_t out[SEC_AES_BLOCK]);

/** The CMAC key of key: its schedule and subkeys (one block encryption). */
void sec_cmac_init(sec_cmac_t *c, const uint8_t key[SEC_AES128_KEY_LEN]);

/** sec_cmac_init's first half: the key's schedule only (about one block encryption's work). */
void sec_cmac_init_schedule(sec_cmac_t *c, const uint8_t key[SEC_AES128_KEY_LEN]);

/** sec_cmac_init's second half, after sec_cmac_init_schedule: the subkeys K1, K2 (one block
 *  encryption). */
void sec_cmac_init_subkeys(sec_cmac_t *c);

/** AES-CMAC of len bytes (any length, 0 too) into out[16]; ceil(len / 16) encryptions, one for
 *  len <= 16. */
/** The block a CMAC of a message of len <= SEC_AES_BLOCK bytes encrypts last (msg padded,
 *  xor K1 or K2): its MAC is sec_aes128_encrypt(&c->aes, block). */
void sec_cmac_one_block(const sec_cmac_t *c, const uint8_t *msg, uint32_t len,
                        uint8_t block[SEC_AES_BLOCK]);

void sec_cmac(const sec_cmac_t *c, const uint8_t *msg, uint32_t len, uint8_t out[SEC_AES_BLOCK]);

#endif /* SEC_AES_H */

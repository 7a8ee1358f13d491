/* The verification of a stored firmware image (boot_image.h: header, payload SHA-256, HMAC tag)
 * in bounded slices: boot_verify_begin reads and checks the header, each boot_verify_run does at
 * most a given number of SHA-256 compression rounds (64 per 64-byte block; the payload's blocks go
 * into both the hash and the MAC) until the result is known. boot_image_verify is begin + one run
 * without a bound. */
#ifndef BOOT_VERIFY_H
#define BOOT_VERIFY_H

#include <stdbool.h>
#include <stdint.h>
#include "boot_image.h"
#include "fls.h"
#include "sec_sha256.h"

/** A verification in progress (all of it in this struct: no heap, bounded stack). */
typedef struct {
    const fls_dev_t *dev;
    uint32_t pos;  /* flash address of the next payload byte */
    uint32_t left; /* payload bytes not read yet */
    boot_image_header_t hdr;
    uint8_t raw[BOOT_IMAGE_HEADER_SIZE]; /* the header's bytes (the MAC covers them) */
    uint8_t buf[SEC_SHA256_PAD_MAX];     /* the chunk being fed: payload, padding, ipad */
    const uint8_t *chunk;                /* what is fed now, chunk_len bytes, chunk_off taken */
    uint32_t chunk_len, chunk_off;
    sec_sha256_t *into; /* the hash it goes into */
    uint8_t stage;
    sec_sha256_t sha;
    sec_hmac_t mac;
    sec_sha256_t outer;
    sec_sha256_job_t job;
    uint8_t digest[SEC_SHA256_LEN];
    boot_status_t status; /* the result once done */
    bool done;
} boot_verify_t;

/** Start verifying the image at dev address addr within a region of cap bytes (boot_image_verify's
 *  checks and codes): the header is read and checked here (an error ends it: done, status set). */
void boot_verify_begin(boot_verify_t *v, const fls_dev_t *dev, uint32_t addr, uint32_t cap,
                       uint32_t want_target, const uint8_t *key, uint32_t key_len);

/** At most rounds compression rounds more, or one stage's end (a digest, a comparison, a flash
 *  read of at most 64 bytes) in a call that compressed nothing (rounds UINT32_MAX: all of it);
 *  true once done (v->status: BOOT_OK or 705/706/flash error; v->hdr the parsed header). */
bool boot_verify_run(boot_verify_t *v, uint32_t rounds);

/** Abandon a verification: wipes the key material. */
void boot_verify_wipe(boot_verify_t *v);

/** Verify the image stored at dev address addr within a region of cap bytes: header (701-703),
 *  fits (700 if the header says more than cap), payload SHA-256 (705), tag (706). */
boot_status_t boot_image_verify(const fls_dev_t *dev, uint32_t addr, uint32_t cap,
                                uint32_t want_target, const uint8_t *key, uint32_t key_len,
                                boot_image_header_t *out);

#endif /* BOOT_VERIFY_H */

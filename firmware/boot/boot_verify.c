/* A stored firmware image's verification in bounded slices (boot_verify.h). */
#include "boot_verify.h"

#include <stddef.h>
#include <string.h>

enum {
    BV_IPAD = 0, /* the key XOR ipad block into the MAC */
    BV_HEADER,   /* the header into the MAC */
    BV_PAY_SHA,  /* the chunk into the hash */
    BV_PAY_MAC,  /* the chunk into the MAC */
    BV_SHA_PAD,  /* the hash's padding */
    BV_MAC_PAD,  /* the MAC's inner padding */
    BV_OKEY,     /* the key XOR opad block into the outer hash */
    BV_INNER,    /* the inner digest into the outer hash */
    BV_OUT_PAD   /* the outer padding, then the tag compared */
};

static void feed_next(boot_verify_t *v, const uint8_t *p, uint32_t n, sec_sha256_t *into,
                      uint8_t stage)
{
    v->chunk = p;
    v->chunk_len = n;
    v->chunk_off = 0u;
    v->into = into;
    v->stage = stage;
}

static void finish(boot_verify_t *v, boot_status_t st)
{
    v->status = st;
    v->done = true;
    sec_wipe(&v->mac, (uint32_t)sizeof v->mac);
    sec_wipe(&v->job, (uint32_t)sizeof v->job);
}

void boot_verify_begin(boot_verify_t *v, const fls_dev_t *dev, uint32_t addr, uint32_t cap,
                       uint32_t want_target, const uint8_t *key, uint32_t key_len)
{
    /* the fields a verification reads before it writes them (the rest is set as it goes, and
     * the whole struct was wiped at the previous one's end): not all ~1 KiB of it, ~470
     * instructions on the Cortex-M4 */
    v->dev = dev;
    v->pos = 0u;
    v->left = 0u;
    (void)memset(&v->hdr, 0, sizeof v->hdr);
    v->chunk = NULL;
    v->chunk_len = 0u;
    v->chunk_off = 0u;
    v->into = NULL;
    v->stage = 0u;
    v->job.active = 0u;
    v->status = BOOT_OK;
    v->done = false;
    if (dev == NULL || key == NULL) {
        finish(v, BOOT_ERR_ARG);
        return;
    }
    if (cap < BOOT_IMAGE_OVERHEAD) {
        finish(v, BOOT_ERR_TRUNCATED);
        return;
    }
    if (dev->read(dev->ctx, addr, v->raw, BOOT_IMAGE_HEADER_SIZE) != 0) {
        finish(v, BOOT_ERR_FLASH);
        return;
    }
    const boot_status_t st = boot_image_parse_header(v->raw, want_target, &v->hdr);
    if (st != BOOT_OK || v->hdr.payload_length > cap - BOOT_IMAGE_OVERHEAD) {
        finish(v, st != BOOT_OK ? st : BOOT_ERR_TRUNCATED);
        return;
    }
    v->pos = addr + BOOT_IMAGE_HEADER_SIZE;
    v->left = v->hdr.payload_length;
    uint8_t k0[SEC_SHA256_BLOCK];
    (void)memset(k0, 0, sizeof k0);
    if (key_len > SEC_SHA256_BLOCK) {
        sec_sha256(key, key_len, k0); /* a long key: hashed first (once, not sliced) */
    } else {
        (void)memcpy(k0, key, key_len);
    }
    for (uint32_t i = 0u; i < SEC_SHA256_BLOCK; i++) {
        v->buf[i] = (uint8_t)(k0[i] ^ 0x36u);
        v->mac.okey[i] = (uint8_t)(k0[i] ^ 0x5Cu);
    }
    sec_wipe(k0, (uint32_t)sizeof k0);
    sec_sha256_init(&v->sha);
    sec_sha256_init(&v->mac.inner);
    feed_next(v, v->buf, SEC_SHA256_BLOCK, &v->mac.inner, BV_IPAD);
}

/* The chunk of v->stage is in: on to the next stage's (reads, digests, comparisons). */
static void advance(boot_verify_t *v)
{
    switch (v->stage) {
    case BV_IPAD: feed_next(v, v->raw, BOOT_IMAGE_HEADER_SIZE, &v->mac.inner, BV_HEADER); return;
    case BV_HEADER:
    case BV_PAY_MAC:
        if (v->stage == BV_PAY_MAC) {
            v->pos += v->chunk_len;
            v->left -= v->chunk_len;
        }
        if (v->left == 0u) {
            feed_next(v, v->buf, sec_sha256_padding(&v->sha, v->buf), &v->sha, BV_SHA_PAD);
            return;
        }
        {
            const uint32_t n = v->left < SEC_SHA256_BLOCK ? v->left : SEC_SHA256_BLOCK;
            if (v->dev->read(v->dev->ctx, v->pos, v->buf, n) != 0) {
                finish(v, BOOT_ERR_FLASH);
                return;
            }
            feed_next(v, v->buf, n, &v->sha, BV_PAY_SHA);
        }
        return;
    case BV_PAY_SHA: feed_next(v, v->buf, v->chunk_len, &v->mac.inner, BV_PAY_MAC); return;
    case BV_SHA_PAD:
        sec_sha256_digest(&v->sha, v->digest);
        if (!sec_ct_equal(v->digest, v->hdr.payload_sha256, SEC_SHA256_LEN)) {
            finish(v, BOOT_ERR_HASH);
            return;
        }
        feed_next(v, v->buf, sec_sha256_padding(&v->mac.inner, v->buf), &v->mac.inner, BV_MAC_PAD);
        return;
    case BV_MAC_PAD:
        sec_sha256_digest(&v->mac.inner, v->digest);
        sec_sha256_init(&v->outer);
        feed_next(v, v->mac.okey, SEC_SHA256_BLOCK, &v->outer, BV_OKEY);
        return;
    case BV_OKEY: feed_next(v, v->digest, SEC_SHA256_LEN, &v->outer, BV_INNER); return;
    case BV_INNER:
        feed_next(v, v->buf, sec_sha256_padding(&v->outer, v->buf), &v->outer, BV_OUT_PAD);
        return;
    default:
        sec_sha256_digest(&v->outer, v->digest);
        if (v->dev->read(v->dev->ctx, v->pos, v->buf, BOOT_IMAGE_TAG_SIZE) != 0) {
            finish(v, BOOT_ERR_FLASH);
            return;
        }
        finish(v, sec_ct_equal(v->digest, v->buf, BOOT_IMAGE_TAG_SIZE) ? BOOT_OK : BOOT_ERR_TAG);
        sec_wipe(v->digest, (uint32_t)sizeof v->digest);
        return;
    }
}

bool boot_verify_run(boot_verify_t *v, uint32_t rounds)
{
    const bool sliced = rounds != UINT32_MAX;
    while (!v->done) {
        const uint32_t budget = rounds;
        v->chunk_off += sec_sha256_feed(v->into, &v->job, v->chunk + v->chunk_off,
                                        v->chunk_len - v->chunk_off, &rounds);
        if (v->chunk_off < v->chunk_len || v->job.active != 0u) {
            return false; /* the budget is spent */
        }
        if (sliced && rounds != budget) {
            return false; /* a call that compressed leaves the stage's end to the next one */
        }
        advance(v); /* a digest, a comparison, a flash read: a slice of its own when sliced */
        if (sliced) {
            return v->done;
        }
    }
    return true;
}

void boot_verify_wipe(boot_verify_t *v)
{
    sec_wipe(v, (uint32_t)sizeof *v);
}

boot_status_t boot_image_verify(const fls_dev_t *dev, uint32_t addr, uint32_t cap,
                                uint32_t want_target, const uint8_t *key, uint32_t key_len,
                                boot_image_header_t *out)
{
    if (dev == NULL || key == NULL || out == NULL) {
        return BOOT_ERR_ARG;
    }
    static boot_verify_t v; /* ~700 bytes: not on the boot's stack (one caller at a time) */
    boot_verify_begin(&v, dev, addr, cap, want_target, key, key_len);
    (void)boot_verify_run(&v, UINT32_MAX);
    *out = v.hdr;
    const boot_status_t st = v.status;
    boot_verify_wipe(&v);
    return st;
}

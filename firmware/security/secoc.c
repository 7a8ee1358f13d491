/* Authenticated host frames (SecOC style): see secoc.h. */
#include "secoc.h"

#include <string.h>

#define SECOC_MSG_LEN (2u + SECOC_PAYLOAD_LEN + 4u) /* id (2), payload, FV (4) */

void secoc_init(secoc_t *s)
{
    memset(s, 0, sizeof(*s));
}

void secoc_derive_key(const uint8_t *secret, uint32_t secret_len,
                      const uint8_t dev_nonce[SECOC_NONCE_LEN],
                      const uint8_t host_nonce[SECOC_NONCE_LEN], uint8_t key[SECOC_KEY_LEN])
{
    static const char label[] = SECOC_LABEL;
    sec_hmac_t h;
    uint8_t out[SEC_SHA256_LEN];
    sec_hmac_init(&h, secret, secret_len);
    sec_hmac_update(&h, (const uint8_t *)label, (uint32_t)(sizeof label - 1u));
    sec_hmac_update(&h, dev_nonce, SECOC_NONCE_LEN);
    sec_hmac_update(&h, host_nonce, SECOC_NONCE_LEN);
    sec_hmac_final(&h, out);
    memcpy(key, out, SECOC_KEY_LEN);
    sec_wipe(out, sizeof out);
}

void secoc_set_key(secoc_t *s, const uint8_t key[SECOC_KEY_LEN])
{
    secoc_set_key_begin(s, key);
    secoc_set_key_finish(s);
}

void secoc_set_key_begin(secoc_t *s, const uint8_t key[SECOC_KEY_LEN])
{
    s->keyed = false;
    sec_cmac_init_schedule(&s->cmac, key);
}

void secoc_set_key_finish(secoc_t *s)
{
    sec_cmac_init_subkeys(&s->cmac);
    s->fv[SECOC_CH_COMMAND] = 0u;
    s->fv[SECOC_CH_HEARTBEAT] = 0u;
    s->bad_in_row = 0u;
    s->keyed = true;
}

void secoc_start_session(secoc_t *s, const uint8_t *secret, uint32_t secret_len,
                         const uint8_t dev_nonce[SECOC_NONCE_LEN],
                         const uint8_t host_nonce[SECOC_NONCE_LEN])
{
    uint8_t key[SECOC_KEY_LEN];
    secoc_derive_key(secret, secret_len, dev_nonce, host_nonce, key);
    secoc_init(s);
    secoc_set_key(s, key);
    sec_wipe(key, sizeof key);
}

void secoc_forget(secoc_t *s)
{
    sec_wipe(&s->cmac, (uint32_t)sizeof s->cmac);
    s->keyed = false;
}

static const char confirm_label[] = SECOC_CONFIRM_LABEL;
_Static_assert(sizeof confirm_label - 1u > SEC_AES_BLOCK &&
                   sizeof confirm_label - 1u <= 2u * SEC_AES_BLOCK,
               "the confirmation's message is two CMAC blocks");

void secoc_confirm_first(const secoc_t *s, uint8_t x[SEC_AES_BLOCK])
{
    sec_aes128_encrypt(&s->cmac.aes, (const uint8_t *)confirm_label, x);
}

uint32_t secoc_confirm_finish(const secoc_t *s, const uint8_t x[SEC_AES_BLOCK])
{
    if (!s->keyed) {
        return 0u;
    }
    uint8_t last[SEC_AES_BLOCK];
    sec_cmac_one_block(&s->cmac, (const uint8_t *)&confirm_label[SEC_AES_BLOCK],
                       (uint32_t)(sizeof confirm_label - 1u - SEC_AES_BLOCK), last);
    for (uint32_t i = 0u; i < SEC_AES_BLOCK; i++) {
        last[i] ^= x[i];
    }
    sec_aes128_encrypt(&s->cmac.aes, last, last);
    return ((uint32_t)last[0] << 24) | ((uint32_t)last[1] << 16) | ((uint32_t)last[2] << 8) |
           (uint32_t)last[3];
}

uint32_t secoc_confirm(const secoc_t *s)
{
    uint8_t x[SEC_AES_BLOCK];
    secoc_confirm_first(s, x);
    return secoc_confirm_finish(s, x);
}

/* The block the MAC of frame f at freshness value fv encrypts (the CMAC of its one-block
 * message: id low, id high, payload, FV big-endian). */
static void mac_block(const secoc_t *s, const can_frame_t *f, uint32_t fv,
                      uint8_t block[SEC_AES_BLOCK])
{
    uint8_t m[SECOC_MSG_LEN];
    m[0] = (uint8_t)(f->id & 0xFFu);
    m[1] = (uint8_t)((f->id >> 8) & 0x07u);
    memcpy(&m[2], f->data, SECOC_PAYLOAD_LEN);
    m[5] = (uint8_t)(fv >> 24);
    m[6] = (uint8_t)(fv >> 16);
    m[7] = (uint8_t)(fv >> 8);
    m[8] = (uint8_t)fv;
    sec_cmac_one_block(&s->cmac, m, SECOC_MSG_LEN, block);
}

void secoc_mac(const secoc_t *s, const can_frame_t *f, uint32_t fv, uint8_t mac[SECOC_MAC_LEN])
{
    uint8_t block[SEC_AES_BLOCK];
    mac_block(s, f, fv, block);
    sec_aes128_encrypt(&s->cmac.aes, block, block);
    memcpy(mac, block, SECOC_MAC_LEN);
}

uint32_t secoc_protect(secoc_t *s, can_frame_t *f, secoc_channel_t ch)
{
    const uint32_t fv = ++s->fv[ch];
    f->data[SECOC_FV_BYTE] = (uint8_t)(fv & 0xFFu);
    secoc_mac(s, f, fv, &f->data[SECOC_MAC_OFFSET]);
    return fv;
}

void secoc_raise_floor(secoc_t *s, secoc_channel_t ch, uint8_t low8)
{
    /* ahead of the last accepted value by less than half the window: the sender's newer frames;
     * else an older value (a heartbeat built before a command it reached the device after) */
    const uint32_t last = s->fv[ch];
    const uint32_t ahead = (uint32_t)(uint8_t)(low8 - (uint8_t)last);
    if (ahead < SECOC_FV_WINDOW / 2u && last + ahead >= last) {
        s->fv[ch] = last + ahead;
    }
}

static sec_status_t refuse(secoc_t *s, sec_status_t why, uint32_t *count)
{
    (*count)++;
    s->last_refusal = (uint16_t)why;
    return why;
}

/* Starts the encryption of the MAC of the job's frame at freshness value fv. */
static void job_mac_begin(const secoc_t *s, secoc_job_t *j, uint32_t fv, uint8_t phase)
{
    uint8_t block[SEC_AES_BLOCK];
    mac_block(s, &j->f, fv, block);
    sec_aes128_job_begin(&j->aes, &s->cmac.aes, block);
    j->phase = phase;
}

static void job_end(secoc_job_t *j, sec_status_t status)
{
    j->status = status;
    j->phase = 0u;
}

void secoc_verify_begin(secoc_t *s, secoc_job_t *j, const can_frame_t *f, secoc_channel_t ch)
{
    j->f = *f;
    j->ch = (uint8_t)ch;
    j->status = SEC_OK;
    j->replay_check = true;
    if (!s->keyed) {
        job_end(j, refuse(s, SEC_ERR_NO_KEY, &s->no_key));
        return;
    }
    const uint32_t last = s->fv[ch];
    const uint32_t low = f->data[SECOC_FV_BYTE];
    uint32_t fv = (last & ~(SECOC_FV_WINDOW - 1u)) | low;
    if (fv <= last) {
        fv += SECOC_FV_WINDOW;
        if (fv < last) { /* the 32-bit counter is used up: a new key restarts it */
            job_end(j, refuse(s, SEC_ERR_FRESHNESS, &s->no_key));
            return;
        }
    }
    j->fv = fv;
    job_mac_begin(s, j, fv, 1u);
}

void secoc_verify_begin_fast(secoc_t *s, secoc_job_t *j, const can_frame_t *f, secoc_channel_t ch)
{
    secoc_verify_begin(s, j, f, ch);
    j->replay_check = false;
}

bool secoc_verify_run(secoc_t *s, secoc_job_t *j, uint32_t *rounds)
{
    while (j->phase != 0u) {
        uint8_t out[SEC_AES_BLOCK];
        if (!sec_aes128_job_run(&j->aes, &s->cmac.aes, rounds, out)) {
            return false;
        }
        const bool match = sec_ct_equal(out, &j->f.data[SECOC_MAC_OFFSET], SECOC_MAC_LEN) == 1;
        if (j->phase == 1u && match) {
            s->fv[j->ch] = j->fv;
            s->bad_in_row = 0u;
            s->accepted++;
            job_end(j, SEC_OK);
        } else if (j->phase == 1u && j->fv >= SECOC_FV_WINDOW && j->replay_check) {
            job_mac_begin(s, j, j->fv - SECOC_FV_WINDOW, 2u); /* a genuine frame already used? */
            if (*rounds < 10u) {
                return false; /* a budget short of the block: its rounds from the next call (a
                                 block's end, a comparison and a block's start are this one's) */
            }
        } else if (match) {
            job_end(j, refuse(s, SEC_ERR_REPLAY, &s->replayed));
        } else {
            job_end(j, refuse(s, SEC_ERR_MAC, &s->bad_mac));
            if (++s->bad_in_row >= SECOC_MAX_BAD_MAC) {
                secoc_forget(s);
                s->revoked++;
            }
        }
    }
    return true;
}

sec_status_t secoc_verify(secoc_t *s, const can_frame_t *f, secoc_channel_t ch)
{
    secoc_job_t j;
    uint32_t rounds = UINT32_MAX;
    secoc_verify_begin(s, &j, f, ch);
    (void)secoc_verify_run(s, &j, &rounds);
    return j.status;
}

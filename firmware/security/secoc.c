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
    sec_cmac_init(&s->cmac, key);
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

uint32_t secoc_confirm(const secoc_t *s)
{
    static const char label[] = SECOC_CONFIRM_LABEL;
    if (!s->keyed) {
        return 0u;
    }
    uint8_t out[SEC_AES_BLOCK];
    sec_cmac(&s->cmac, (const uint8_t *)label, (uint32_t)(sizeof label - 1u), out);
    return ((uint32_t)out[0] << 24) | ((uint32_t)out[1] << 16) | ((uint32_t)out[2] << 8) |
           (uint32_t)out[3];
}

void secoc_mac(const secoc_t *s, const can_frame_t *f, uint32_t fv, uint8_t mac[SECOC_MAC_LEN])
{
    uint8_t m[SECOC_MSG_LEN];
    m[0] = (uint8_t)(f->id & 0xFFu);
    m[1] = (uint8_t)((f->id >> 8) & 0x07u);
    memcpy(&m[2], f->data, SECOC_PAYLOAD_LEN);
    m[5] = (uint8_t)(fv >> 24);
    m[6] = (uint8_t)(fv >> 16);
    m[7] = (uint8_t)(fv >> 8);
    m[8] = (uint8_t)fv;
    uint8_t out[SEC_AES_BLOCK];
    sec_cmac(&s->cmac, m, SECOC_MSG_LEN, out);
    memcpy(mac, out, SECOC_MAC_LEN);
}

uint32_t secoc_protect(secoc_t *s, can_frame_t *f, secoc_channel_t ch)
{
    const uint32_t fv = ++s->fv[ch];
    f->data[SECOC_FV_BYTE] = (uint8_t)(fv & 0xFFu);
    secoc_mac(s, f, fv, &f->data[SECOC_MAC_OFFSET]);
    return fv;
}

static sec_status_t refuse(secoc_t *s, sec_status_t why, uint32_t *count)
{
    (*count)++;
    s->last_refusal = (uint16_t)why;
    return why;
}

/* True if the frame's MAC is the one for freshness value fv. */
static bool mac_matches(const secoc_t *s, const can_frame_t *f, uint32_t fv)
{
    uint8_t mac[SECOC_MAC_LEN];
    secoc_mac(s, f, fv, mac);
    return sec_ct_equal(mac, &f->data[SECOC_MAC_OFFSET], SECOC_MAC_LEN) == 1;
}

sec_status_t secoc_verify(secoc_t *s, const can_frame_t *f, secoc_channel_t ch)
{
    if (!s->keyed) {
        return refuse(s, SEC_ERR_NO_KEY, &s->no_key);
    }
    const uint32_t last = s->fv[ch];
    const uint32_t low = f->data[SECOC_FV_BYTE];
    uint32_t fv = (last & ~(SECOC_FV_WINDOW - 1u)) | low;
    if (fv <= last) {
        fv += SECOC_FV_WINDOW;
        if (fv < last) { /* the 32-bit counter is used up: a new key restarts it */
            return refuse(s, SEC_ERR_FRESHNESS, &s->no_key);
        }
    }
    if (mac_matches(s, f, fv)) {
        s->fv[ch] = fv;
        s->bad_in_row = 0u;
        s->accepted++;
        return SEC_OK;
    }
    if (fv >= SECOC_FV_WINDOW && mac_matches(s, f, fv - SECOC_FV_WINDOW)) {
        return refuse(s, SEC_ERR_REPLAY, &s->replayed); /* a genuine frame already used */
    }
    (void)refuse(s, SEC_ERR_MAC, &s->bad_mac);
    if (++s->bad_in_row >= SECOC_MAX_BAD_MAC) {
        secoc_forget(s);
        s->revoked++;
    }
    return SEC_ERR_MAC;
}

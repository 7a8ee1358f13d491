/* UDS SecurityAccess seed/key logic: see sec_access.h. */
#include "sec_access.h"

#include <stddef.h>
#include <string.h>

#include "sec_sha256.h"

void sec_default_config(sec_config_t *cfg)
{
    if (cfg == NULL) {
        return;
    }
    (void)memset(cfg, 0, sizeof *cfg);
    cfg->max_attempts = 3u;
    cfg->delay_ms = 1000u;
    cfg->lockout_ms = 10000u;
    cfg->boot_delay_ms = 1000u;
}

sec_status_t sec_config_validate(const sec_config_t *cfg)
{
    if (cfg == NULL || cfg->rng == NULL) {
        return SEC_ERR_NULL_ARG;
    }
    if (cfg->secret_len < 16u || cfg->secret_len > SEC_SECRET_MAX || cfg->max_attempts == 0u) {
        return SEC_ERR_CONFIG;
    }
    /* bound the waits so now_ms + wait never compares wrongly across a wrap (< 2^31 ms) */
    if (cfg->delay_ms > 0x7FFFFFFFu || cfg->lockout_ms > 0x7FFFFFFFu ||
        cfg->boot_delay_ms > 0x7FFFFFFFu) {
        return SEC_ERR_CONFIG;
    }
    return SEC_OK;
}

static void start_wait(sec_state_t *st, uint32_t now_ms, uint32_t wait_ms)
{
    if (wait_ms == 0u) {
        st->waiting = 0u;
        return;
    }
    st->waiting = 1u;
    st->wait_until_ms = now_ms + wait_ms;
}

void sec_init(const sec_config_t *cfg, sec_state_t *st, uint32_t now_ms)
{
    if (st == NULL) {
        return;
    }
    (void)memset(st, 0, sizeof *st);
    if (cfg != NULL) {
        start_wait(st, now_ms, cfg->boot_delay_ms);
    }
}

void sec_compute_key(const sec_config_t *cfg, const uint8_t seed[SEC_SEED_LEN],
                     uint8_t key_out[SEC_KEY_LEN])
{
    if (cfg == NULL || seed == NULL || key_out == NULL) {
        return;
    }
    uint8_t mac[SEC_SHA256_LEN];
    const uint32_t klen = (cfg->secret_len > SEC_SECRET_MAX) ? SEC_SECRET_MAX : cfg->secret_len;
    sec_hmac_sha256(cfg->secret, klen, seed, SEC_SEED_LEN, mac);
    (void)memcpy(key_out, mac, SEC_KEY_LEN);
    sec_wipe(mac, sizeof mac);
}

sec_nrc_t sec_request_seed(const sec_config_t *cfg, sec_state_t *st, uint32_t now_ms,
                           uint8_t seed_out[SEC_SEED_LEN])
{
    if (cfg == NULL || st == NULL || seed_out == NULL || cfg->rng == NULL) {
        return SEC_NRC_CONDITIONS;
    }
    if (st->unlocked != 0u) {
        (void)memset(seed_out, 0, SEC_SEED_LEN); /* ISO 14229-1: already unlocked -> zero seed */
        return SEC_NRC_NONE;
    }
    if (st->waiting != 0u) {
        if ((int32_t)(now_ms - st->wait_until_ms) < 0) {
            return SEC_NRC_DELAY_NOT_EXPIRED;
        }
        st->waiting = 0u;
        if (st->locked_out != 0u) {
            st->locked_out = 0u;
            st->failed = 0u;
        }
    }
    st->seed_valid = 0u;
    if (cfg->rng(cfg->rng_ctx, st->seed, SEC_SEED_LEN) != 0) {
        return SEC_NRC_CONDITIONS;
    }
    uint8_t any = 0u;
    for (uint32_t i = 0u; i < SEC_SEED_LEN; i++) {
        any = (uint8_t)(any | st->seed[i]);
    }
    if (any == 0u) { /* the zero seed means "unlocked"; a source that gives it is broken */
        return SEC_NRC_CONDITIONS;
    }
    st->seed_valid = 1u;
    (void)memcpy(seed_out, st->seed, SEC_SEED_LEN);
    return SEC_NRC_NONE;
}

sec_nrc_t sec_send_key(const sec_config_t *cfg, sec_state_t *st, uint32_t now_ms,
                       const uint8_t *key, uint32_t key_len)
{
    if (cfg == NULL || st == NULL) {
        return SEC_NRC_CONDITIONS;
    }
    if (st->seed_valid == 0u) {
        return SEC_NRC_SEQUENCE_ERROR;
    }
    st->seed_valid = 0u; /* one answer per seed, right or wrong */
    if (key == NULL || key_len != SEC_KEY_LEN) {
        sec_wipe(st->seed, SEC_SEED_LEN);
        return SEC_NRC_INCORRECT_LENGTH;
    }
    uint8_t expect[SEC_KEY_LEN];
    sec_compute_key(cfg, st->seed, expect);
    const int ok = sec_ct_equal(expect, key, SEC_KEY_LEN);
    sec_wipe(expect, sizeof expect);
    sec_wipe(st->seed, SEC_SEED_LEN);
    if (ok != 0) {
        st->unlocked = 1u;
        st->failed = 0u;
        return SEC_NRC_NONE;
    }
    if (st->failed < 0xFFu) {
        st->failed++;
    }
    if (st->failed >= cfg->max_attempts) {
        st->locked_out = 1u;
        start_wait(st, now_ms, cfg->lockout_ms);
        return SEC_NRC_EXCEEDED_ATTEMPTS;
    }
    start_wait(st, now_ms, cfg->delay_ms);
    return SEC_NRC_INVALID_KEY;
}

bool sec_is_unlocked(const sec_state_t *st)
{
    return st != NULL && st->unlocked != 0u;
}

void sec_lock(sec_state_t *st)
{
    if (st != NULL) {
        st->unlocked = 0u;
        st->seed_valid = 0u;
        sec_wipe(st->seed, SEC_SEED_LEN);
    }
}

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

void sec_restore(const sec_config_t *cfg, sec_state_t *st, uint32_t now_ms, uint8_t failed,
                 uint8_t locked_out)
{
    sec_init(cfg, st, now_ms);
    if (st == NULL || cfg == NULL) {
        return;
    }
    st->failed = failed;
    /* a record that counts max_attempts wrong keys is a lockout: the power failed after the
     * last wrong key was counted and before its lockout was recorded */
    st->locked_out = (locked_out != 0u || failed >= cfg->max_attempts) ? 1u : 0u;
    uint32_t wait_ms = cfg->boot_delay_ms;
    if (st->locked_out != 0u) {
        wait_ms = cfg->lockout_ms;
    } else if (failed != 0u && cfg->delay_ms > wait_ms) {
        wait_ms = cfg->delay_ms;
    }
    start_wait(st, now_ms, wait_ms);
}

void sec_record_encode(const sec_state_t *st, uint8_t rec[SEC_RECORD_LEN])
{
    rec[0] = (uint8_t)'S';
    rec[1] = st->failed;
    rec[2] = st->locked_out;
    rec[3] = (uint8_t)(st->failed ^ 0xFFu);
}

bool sec_record_decode(const uint8_t *rec, uint32_t len, uint8_t *failed, uint8_t *locked_out)
{
    if (rec == NULL || len != SEC_RECORD_LEN || rec[0] != (uint8_t)'S' || rec[2] > 1u ||
        (uint8_t)(rec[3] ^ rec[1]) != 0xFFu) {
        return false;
    }
    *failed = rec[1];
    *locked_out = rec[2];
    return true;
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

sec_nrc_t sec_request_seed(const sec_config_t *cfg, sec_state_t *st, uint8_t tester,
                           uint32_t now_ms, uint8_t seed_out[SEC_SEED_LEN])
{
    if (cfg == NULL || st == NULL || seed_out == NULL || cfg->rng == NULL ||
        tester >= SEC_TESTERS) {
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
    uint8_t *seed = st->seed[tester];
    st->seed_valid[tester] = 0u;
    if (cfg->rng(cfg->rng_ctx, seed, SEC_SEED_LEN) != 0) {
        return SEC_NRC_CONDITIONS;
    }
    uint8_t any = 0u;
    for (uint32_t i = 0u; i < SEC_SEED_LEN; i++) {
        any = (uint8_t)(any | seed[i]);
    }
    if (any == 0u) { /* the zero seed means "unlocked"; a source that gives it is broken */
        return SEC_NRC_CONDITIONS;
    }
    st->seed_valid[tester] = 1u;
    (void)memcpy(seed_out, seed, SEC_SEED_LEN);
    return SEC_NRC_NONE;
}

sec_nrc_t sec_send_key_begin(const sec_config_t *cfg, sec_state_t *st, uint8_t tester,
                             const uint8_t *key, uint32_t key_len)
{
    if (cfg == NULL || st == NULL || tester >= SEC_TESTERS) {
        return SEC_NRC_CONDITIONS;
    }
    if (st->seed_valid[tester] == 0u) {
        return SEC_NRC_SEQUENCE_ERROR;
    }
    uint8_t *seed = st->seed[tester];
    st->seed_valid[tester] = 0u; /* one answer per seed, right or wrong */
    if (key == NULL || key_len != SEC_KEY_LEN) {
        sec_wipe(seed, SEC_SEED_LEN);
        return SEC_NRC_INCORRECT_LENGTH;
    }
    if (st->checking != 0u) { /* another tester's key is being checked: this seed stays used */
        sec_wipe(seed, SEC_SEED_LEN);
        return SEC_NRC_CONDITIONS;
    }
    const uint32_t klen = (cfg->secret_len > SEC_SECRET_MAX) ? SEC_SECRET_MAX : cfg->secret_len;
    (void)sec_hmac_job_begin(&st->job, cfg->secret, klen, seed, SEC_SEED_LEN);
    sec_wipe(seed, SEC_SEED_LEN);
    (void)memcpy(st->key, key, SEC_KEY_LEN);
    st->checking = 1u;
    if (st->failed < 0xFFu) {
        st->failed++; /* counted as wrong until the check says otherwise: a reset meanwhile
                         keeps it counted (the application stores the record now) */
    }
    return SEC_NRC_PENDING;
}

sec_nrc_t sec_send_key_run(const sec_config_t *cfg, sec_state_t *st, uint32_t now_ms,
                           uint32_t rounds)
{
    if (cfg == NULL || st == NULL || st->checking == 0u) {
        return SEC_NRC_SEQUENCE_ERROR;
    }
    uint8_t mac[SEC_SHA256_LEN];
    if (!sec_hmac_job_run(&st->job, rounds, mac)) {
        return SEC_NRC_PENDING;
    }
    st->checking = 0u;
    const int ok = sec_ct_equal(mac, st->key, SEC_KEY_LEN);
    sec_wipe(mac, sizeof mac);
    sec_wipe(st->key, SEC_KEY_LEN);
    if (ok != 0) {
        st->unlocked = 1u;
        st->failed = 0u;
        return SEC_NRC_NONE;
    }
    if (st->failed >= cfg->max_attempts) {
        st->locked_out = 1u;
        start_wait(st, now_ms, cfg->lockout_ms);
        return SEC_NRC_EXCEEDED_ATTEMPTS;
    }
    start_wait(st, now_ms, cfg->delay_ms);
    return SEC_NRC_INVALID_KEY;
}

sec_nrc_t sec_send_key(const sec_config_t *cfg, sec_state_t *st, uint8_t tester, uint32_t now_ms,
                       const uint8_t *key, uint32_t key_len)
{
    const sec_nrc_t nrc = sec_send_key_begin(cfg, st, tester, key, key_len);
    return nrc == SEC_NRC_PENDING ? sec_send_key_run(cfg, st, now_ms, UINT32_MAX) : nrc;
}

bool sec_is_unlocked(const sec_state_t *st)
{
    return st != NULL && st->unlocked != 0u;
}

void sec_lock(sec_state_t *st)
{
    if (st != NULL) {
        st->unlocked = 0u;
        (void)memset(st->seed_valid, 0, sizeof st->seed_valid);
        sec_wipe(st->seed, (uint32_t)sizeof st->seed);
        if (st->checking != 0u) { /* a finished check wiped its own key material */
            st->checking = 0u;
            sec_wipe(st->key, SEC_KEY_LEN);
            sec_wipe(&st->job, (uint32_t)sizeof st->job);
        }
    }
}

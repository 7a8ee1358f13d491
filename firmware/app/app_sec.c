/* Security of the device (app_sec.h): the SecurityAccess configuration per level, the wrong-key
 * record kept across resets, a sendKey's check and the motion key of a host session. */
#include "app_internal.h"

#include <string.h>

static int rng_adapter(void *ctx, uint8_t *buf, uint32_t len)
{
    (void)ctx;
    return hal_random(buf, len);
}

const sec_config_t *app_sec_config(const app_t *app, uint8_t level)
{
    if (level == UDS_SEC_LEVEL_WRITE) {
        return &app->sec.cfg[0];
    }
    return level == UDS_SEC_LEVEL_FIRMWARE ? &app->sec.cfg[1] : NULL;
}

void app_sec_persist(app_t *app)
{
    app->sec.store.dirty = app->sec.store.ok;
    app->sec.store.noted_tick = app->tick; /* one heavy job a tick: the record's next tick */
}

/* A round stores the state as it is at its start: a change during the write (dirty again) takes
 * another round. A write that fails or cannot start is tried again after the next change. */
static fs_job_status_t store_job(app_t *app)
{
    app_sec_store_t *r = &app->sec.store;
    FS_JOB_BEGIN(&r->job);
    r->dirty = false;
    sec_record_encode(&app->sec.access, r->rec);
    if (memcmp(r->rec, r->saved, sizeof r->saved) != 0 &&
        nvm_write_begin(&r->writer, &r->nvm, 0u, r->rec, (uint32_t)sizeof r->rec) == NVM_OK) {
        do {
            FS_JOB_YIELD(&r->job);
        } while (!nvm_write_run(&r->writer, APP_SEC_FLASH_UNITS_PER_TICK));
        if (r->writer.status == NVM_OK) {
            memcpy(r->saved, r->rec, sizeof r->saved);
        }
    }
    FS_JOB_END(&r->job);
}

void app_sec_store_step(app_t *app)
{
    (void)store_job(app);
}

bool app_sec_persisted(const app_t *app)
{
    return !fs_job_running(&app->sec.store.job) && !app->sec.store.dirty;
}

/* One secret per level from the HAL; the attempt counter from the record kept across resets
 * (none or unreadable: the lockout delay runs at power-up, the safe side). */
void app_sec_setup(app_t *app)
{
    static const uint8_t levels[APP_SEC_LEVELS] = {UDS_SEC_LEVEL_WRITE, UDS_SEC_LEVEL_FIRMWARE};
    for (unsigned i = 0; i < APP_SEC_LEVELS; i++) {
        sec_config_t *c = &app->sec.cfg[i];
        sec_default_config(c);
        uint8_t secret_len = 0u;
        const uint8_t *secret = hal_device_secret(levels[i], &secret_len);
        if (secret_len > SEC_SECRET_MAX) {
            secret_len = SEC_SECRET_MAX;
        }
        memcpy(c->secret, secret, secret_len);
        c->secret_len = secret_len;
        c->rng = rng_adapter;
        c->rng_ctx = app;
    }
    uint8_t failed = 0u, locked_out = 1u;
    app_sec_store_t *r = &app->sec.store;
    const fls_dev_t *dev = hal_sec_flash();
    r->ok = dev != NULL && nvm_init(&r->nvm, dev) == NVM_OK;
    if (r->ok) {
        uint8_t rec[SEC_RECORD_LEN];
        uint32_t len = 0u;
        const nvm_status_t st = nvm_read(&r->nvm, 0u, rec, (uint32_t)sizeof rec, &len);
        if (st == NVM_OK && sec_record_decode(rec, len, &failed, &locked_out)) {
            memcpy(r->saved, rec, sizeof rec);
        } else if (nvm_dir(&r->nvm, 0u) != NULL && nvm_dir(&r->nvm, 0u)->valid == 0u) {
            failed = 0u; /* a fresh device: no record yet */
            locked_out = 0u;
        }
    }
    sec_restore(&app->sec.cfg[0], &app->sec.access, app->now_ms, failed, locked_out);
}

uint8_t app_sec_key_check_begin(app_t *app, uint8_t level, const uint8_t *key, uint16_t len)
{
    const sec_config_t *cfg = app_sec_config(app, level);
    if (cfg == NULL) {
        return UDS_NRC_SUBFUNCTION_NOT_SUPPORTED;
    }
    /* the attempt counts as wrong until checked, and is stored before the check runs: the
     * wrong-key counter survives reset and power-up */
    const uint8_t nrc = (uint8_t)sec_send_key_begin(cfg, &app->sec.access, app->diag.uds.tester,
                                                    key, len);
    app->sec.key_level = level;
    app_sec_persist(app);
    fs_job_reset(&app->sec.key_check); /* an earlier, abandoned check's result is not this one's */
    return nrc;
}

/* The attempt stored first, then its check: the record's write and the HMAC never share a tick;
 * answered once the result is stored too. */
static fs_job_status_t key_check_job(app_t *app, const sec_config_t *cfg)
{
    fs_job_t *j = &app->sec.key_check;
    FS_JOB_BEGIN(j);
    FS_JOB_WAIT_UNTIL(j, app_sec_persisted(app));
    while ((app->sec.key_nrc = (uint8_t)sec_send_key_run(cfg, &app->sec.access, app->now_ms,
                                                         APP_SEC_ROUNDS_PER_TICK)) ==
           UDS_NRC_RESPONSE_PENDING) {
        FS_JOB_YIELD(j);
    }
    app_sec_persist(app);
    FS_JOB_WAIT_UNTIL(j, app_sec_persisted(app));
    FS_JOB_END(j);
}

uint8_t app_sec_key_check_run(app_t *app)
{
    const sec_config_t *cfg = app_sec_config(app, app->sec.key_level);
    if (cfg == NULL) {
        return UDS_NRC_CONDITIONS_NOT_CORRECT;
    }
    return key_check_job(app, cfg) == FS_JOB_DONE ? app->sec.key_nrc : UDS_NRC_RESPONSE_PENDING;
}

uint8_t app_motion_key_begin(app_t *app, const uint8_t *host_nonce, uint16_t len)
{
    if (len != SECOC_NONCE_LEN) {
        return UDS_NRC_INCORRECT_LENGTH;
    }
    if (app->state == APP_TEACH || app->state == APP_EXECUTE) {
        return UDS_NRC_CONDITIONS_NOT_CORRECT; /* never re-keyed while a motion runs */
    }
    app_motion_key_t *m = &app->sec.motion;
    uint8_t dev_nonce[SECOC_NONCE_LEN];
    if (hal_random(dev_nonce, SECOC_NONCE_LEN) != 0) {
        return UDS_NRC_CONDITIONS_NOT_CORRECT;
    }
    memcpy(m->host_nonce, host_nonce, SECOC_NONCE_LEN);
    memcpy(m->dev_nonce, dev_nonce, SECOC_NONCE_LEN);
    secoc_forget(&app->auth.secoc); /* the old session ends now */
    m->confirm = 0u;
    fs_job_reset(&m->job); /* the derivation starts at the next call */
    m->requested = true;
    app->auth.run_opts_fv = 0u;
    app_commands_void(app); /* a frame of the old session is not verified with the new key */
    return UDS_NRC_RESPONSE_PENDING;
}

/* The derivation's start, its end, the key's schedule and subkeys, and the confirmation each
 * take a call of their own: each is about one to two block encryptions. */
static fs_job_status_t motion_key_job(app_t *app, uint32_t rounds)
{
    app_motion_key_t *m = &app->sec.motion;
    static const char label[] = SECOC_LABEL;
    uint8_t buf[sizeof label - 1u + 2u * SECOC_NONCE_LEN]; /* the message, then the digest */
    FS_JOB_BEGIN(&m->job);
    memcpy(buf, label, sizeof label - 1u);
    memcpy(&buf[sizeof label - 1u], m->dev_nonce, SECOC_NONCE_LEN);
    memcpy(&buf[sizeof label - 1u + SECOC_NONCE_LEN], m->host_nonce, SECOC_NONCE_LEN);
    (void)sec_hmac_job_begin(&m->hmac, app->sec.cfg[0].secret, app->sec.cfg[0].secret_len, buf,
                             (uint32_t)sizeof buf);
    FS_JOB_YIELD(&m->job);
    while (!sec_hmac_job_run(&m->hmac, rounds, buf)) {
        FS_JOB_YIELD(&m->job);
    }
    memcpy(m->key, buf, SECOC_KEY_LEN); /* the first bytes (secoc_derive_key) */
    sec_wipe(buf, sizeof buf);
    FS_JOB_YIELD(&m->job);
    secoc_set_key_begin(&app->auth.secoc, m->key);
    sec_wipe(m->key, sizeof m->key);
    FS_JOB_YIELD(&m->job);
    secoc_set_key_finish(&app->auth.secoc);
    FS_JOB_YIELD(&m->job);
    secoc_confirm_first(&app->auth.secoc, m->key); /* the key's buffer, wiped: free */
    FS_JOB_YIELD(&m->job);
    m->confirm = secoc_confirm_finish(&app->auth.secoc, m->key); /* kept: DID 0x0302 reads it */
    sec_wipe(m->key, sizeof m->key);
    FS_JOB_END(&m->job);
}

uint8_t app_motion_key_run(app_t *app, uint32_t rounds)
{
    if (!app->sec.motion.requested) {
        return UDS_NRC_CONDITIONS_NOT_CORRECT;
    }
    if (motion_key_job(app, rounds) == FS_JOB_PENDING) {
        return UDS_NRC_RESPONSE_PENDING;
    }
    app->sec.motion.requested = false;
    return UDS_NRC_OK;
}

uint8_t app_motion_key(app_t *app, const uint8_t *host_nonce, uint16_t len)
{
    uint8_t nrc = app_motion_key_begin(app, host_nonce, len);
    while (nrc == UDS_NRC_RESPONSE_PENDING) {
        nrc = app_motion_key_run(app, UINT32_MAX);
    }
    return nrc;
}

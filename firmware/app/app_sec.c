/* Security of the device (see app_internal.h): the SecurityAccess configuration per level, the
 * wrong-key record kept across resets, and the motion key of a host session. */
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
        return &app->sec_cfg[0];
    }
    return level == UDS_SEC_LEVEL_FIRMWARE ? &app->sec_cfg[1] : NULL;
}

void app_sec_persist(app_t *app)
{
    app->sec_dirty = app->sec_nvm_ok;
    app->sec_hold_tick = app->tick; /* one heavy job a tick: the write's first unit next tick */
}

void app_sec_persist_step(app_t *app)
{
    if (app->sec_writing) {
        if (nvm_write_run(&app->sec_writer, APP_SEC_FLASH_UNITS_PER_TICK)) {
            app->sec_writing = false;
            if (app->sec_writer.status == NVM_OK) {
                memcpy(app->sec_saved, app->sec_wr_rec, sizeof app->sec_saved);
            } else {
                app->sec_dirty = false; /* not stored: tried again after the next request */
            }
        }
        return;
    }
    if (!app->sec_dirty) {
        return;
    }
    sec_record_encode(&app->sec, app->sec_wr_rec);
    if (memcmp(app->sec_wr_rec, app->sec_saved, sizeof app->sec_saved) == 0) {
        app->sec_dirty = false;
        return;
    }
    app->sec_writing = nvm_write_begin(&app->sec_writer, &app->sec_nvm, 0u, app->sec_wr_rec,
                                       (uint32_t)sizeof app->sec_wr_rec) == NVM_OK;
    if (!app->sec_writing) {
        app->sec_dirty = false; /* the write cannot start: as a failed one */
    }
}

bool app_sec_persisted(const app_t *app)
{
    return !app->sec_writing && !app->sec_dirty;
}

/* One secret per level from the HAL; the attempt counter from the record kept across resets
 * (none or unreadable: the lockout delay runs at power-up, the safe side). */
void app_sec_setup(app_t *app)
{
    static const uint8_t levels[APP_SEC_LEVELS] = {UDS_SEC_LEVEL_WRITE, UDS_SEC_LEVEL_FIRMWARE};
    for (unsigned i = 0; i < APP_SEC_LEVELS; i++) {
        sec_config_t *c = &app->sec_cfg[i];
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
    const fls_dev_t *dev = hal_sec_flash();
    app->sec_nvm_ok = dev != NULL && nvm_init(&app->sec_nvm, dev) == NVM_OK;
    if (app->sec_nvm_ok) {
        uint8_t rec[SEC_RECORD_LEN];
        uint32_t len = 0u;
        const nvm_status_t st = nvm_read(&app->sec_nvm, 0u, rec, (uint32_t)sizeof rec, &len);
        if (st == NVM_OK && sec_record_decode(rec, len, &failed, &locked_out)) {
            memcpy(app->sec_saved, rec, sizeof rec);
        } else if (nvm_dir(&app->sec_nvm, 0u) != NULL && nvm_dir(&app->sec_nvm, 0u)->valid == 0u) {
            failed = 0u; /* a fresh device: no record yet */
            locked_out = 0u;
        }
    }
    sec_restore(&app->sec_cfg[0], &app->sec, app->now_ms, failed, locked_out);
}

uint8_t app_motion_key_begin(app_t *app, const uint8_t *host_nonce, uint16_t len)
{
    if (len != SECOC_NONCE_LEN) {
        return UDS_NRC_INCORRECT_LENGTH;
    }
    if (app->state == APP_TEACH || app->state == APP_EXECUTE) {
        return UDS_NRC_CONDITIONS_NOT_CORRECT; /* never re-keyed while a motion runs */
    }
    uint8_t dev_nonce[SECOC_NONCE_LEN];
    if (hal_random(dev_nonce, SECOC_NONCE_LEN) != 0) {
        return UDS_NRC_CONDITIONS_NOT_CORRECT;
    }
    memcpy(app->motion_host_nonce, host_nonce, SECOC_NONCE_LEN);
    app->motion_job_due = true; /* the derivation starts at the next call */
    secoc_forget(&app->secoc);  /* the old session ends now */
    app->motion_confirm = 0u;
    app->motion_key_due = false;
    app->motion_subkeys_due = false;
    app->motion_confirm_due = false;
    app->motion_confirm_half = false;
    memcpy(app->secoc_dev_nonce, dev_nonce, SECOC_NONCE_LEN);
    app->run_opts_fv = 0u;
    app_commands_void(app); /* a frame of the old session is not verified with the new key */
    app->motion_keying = true;
    return UDS_NRC_RESPONSE_PENDING;
}

uint8_t app_motion_key_run(app_t *app, uint32_t rounds)
{
    if (!app->motion_keying) {
        return UDS_NRC_CONDITIONS_NOT_CORRECT;
    }
    if (app->motion_confirm_due && !app->motion_confirm_half) {
        secoc_confirm_first(&app->secoc, app->motion_key); /* the key's buffer, wiped: free */
        app->motion_confirm_half = true;
        return UDS_NRC_RESPONSE_PENDING;
    }
    if (app->motion_confirm_due) {
        app->motion_confirm_due = false;
        app->motion_confirm_half = false;
        app->motion_keying = false;
        /* kept: DID 0x0302 reads it */
        app->motion_confirm = secoc_confirm_finish(&app->secoc, app->motion_key);
        sec_wipe(app->motion_key, sizeof app->motion_key);
        return UDS_NRC_OK;
    }
    /* the device nonce (a block encryption of the port's generator), the derivation's start,
     * its end, the key's schedule and subkeys, and the confirmation each take a call of their
     * own: each is about one to two block encryptions */
    if (app->motion_job_due) {
        static const char label[] = SECOC_LABEL;
        uint8_t msg[sizeof label - 1u + 2u * SECOC_NONCE_LEN];
        memcpy(msg, label, sizeof label - 1u);
        memcpy(&msg[sizeof label - 1u], app->secoc_dev_nonce, SECOC_NONCE_LEN);
        memcpy(&msg[sizeof label - 1u + SECOC_NONCE_LEN], app->motion_host_nonce, SECOC_NONCE_LEN);
        const sec_config_t *c = &app->sec_cfg[0];
        (void)sec_hmac_job_begin(&app->motion_job, c->secret, c->secret_len, msg,
                                 (uint32_t)sizeof msg);
        app->motion_job_due = false;
        return UDS_NRC_RESPONSE_PENDING;
    }
    if (app->motion_key_due) {
        app->motion_key_due = false;
        secoc_set_key_begin(&app->secoc, app->motion_key);
        sec_wipe(app->motion_key, sizeof app->motion_key);
        app->motion_subkeys_due = true;
        return UDS_NRC_RESPONSE_PENDING;
    }
    if (app->motion_subkeys_due) {
        app->motion_subkeys_due = false;
        secoc_set_key_finish(&app->secoc);
        app->motion_confirm_due = true;
        return UDS_NRC_RESPONSE_PENDING;
    }
    uint8_t out[SEC_SHA256_LEN];
    if (!sec_hmac_job_run(&app->motion_job, rounds, out)) {
        return UDS_NRC_RESPONSE_PENDING;
    }
    memcpy(app->motion_key, out, SECOC_KEY_LEN); /* the first bytes (secoc_derive_key) */
    sec_wipe(out, sizeof out);
    app->motion_key_due = true;
    return UDS_NRC_RESPONSE_PENDING;
}

uint8_t app_motion_key(app_t *app, const uint8_t *host_nonce, uint16_t len)
{
    uint8_t nrc = app_motion_key_begin(app, host_nonce, len);
    while (nrc == UDS_NRC_RESPONSE_PENDING) {
        nrc = app_motion_key_run(app, UINT32_MAX);
    }
    return nrc;
}

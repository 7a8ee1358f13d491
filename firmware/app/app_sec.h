/* The device's security state (app_sec.c): the SecurityAccess configuration per level and its
 * attempt state, the attempt record kept across resets, a sendKey's check, and the motion key of
 * a host session. Its long work (HMACs, the record's flash write, the key's schedule) runs as
 * jobs (fs_job.h), a slice a call, driven by the tick (the record) and the UDS server's resume
 * (a sendKey's check, the motion key). */
#ifndef APP_SEC_H
#define APP_SEC_H

#include <stdbool.h>
#include <stdint.h>
#include "fs_job.h"
#include "nvm.h"
#include "sec_access.h"
#include "sec_sha256.h"
#include "app.h"
#include "secoc.h"

#define APP_SEC_LEVELS 2u /* SecurityAccess levels 1 and 3, one secret each */

/** The attempt record (sec_record_encode) and its write in slices. */
typedef struct {
    fs_job_t job;                  /* app_sec_store_step */
    nvm_t nvm;                     /* the record's storage (hal_sec_flash), kept across resets */
    bool ok;                       /* nvm holds: there is storage */
    bool dirty;                    /* the attempt state may differ from what is stored */
    uint32_t noted_tick;           /* the tick of the last app_sec_persist: no slice in it */
    uint8_t saved[SEC_RECORD_LEN]; /* the record as last stored */
    uint8_t rec[SEC_RECORD_LEN];   /* the record being written */
    nvm_writer_t writer;           /* its write */
} app_sec_store_t;

/** The motion key of a host session: its derivation and the key's confirmation. */
typedef struct {
    fs_job_t job;                        /* the derivation (app_motion_key_run) */
    bool requested;                      /* a derivation was begun and has not ended */
    sec_hmac_job_t hmac;                 /* HMAC(secret, label | device nonce | host nonce) */
    uint8_t dev_nonce[SECOC_NONCE_LEN];  /* the device nonce of the key in use */
    uint8_t host_nonce[SECOC_NONCE_LEN]; /* the host nonce of the key being derived */
    uint8_t key[SECOC_KEY_LEN];          /* the derived key until installed, then scratch */
    uint32_t confirm;                    /* secoc_confirm of the key in use (0: none) */
} app_motion_key_t;

/** The device's security state. */
typedef struct {
    /* [0] level 1 (skills, settings), [1] level 3 (firmware) */
    sec_config_t cfg[APP_SEC_LEVELS];
    sec_state_t access;    /* one attempt counter for both levels, a seed per tester */
    app_sec_store_t store; /* the attempt record */
    fs_job_t key_check;    /* a sendKey's check: the attempt stored, checked, the result stored */
    uint8_t key_nrc;       /* its result */
    uint8_t key_level;     /* the level its key was sent for */
    app_motion_key_t motion;
} app_sec_t;

/** SecurityAccess config of a level (1 or 3); NULL for any other level. */
const sec_config_t *app_sec_config(const app_t *app, uint8_t level);

/** One secret per level from the HAL; the attempt counter from the record kept across resets
 *  (none or unreadable: the lockout delay runs at power-up, the safe side). At app_init. */
void app_sec_setup(app_t *app);

/** Note that the attempt state may have changed (after every seed/key request): the record is
 *  stored by app_sec_store_step in the ticks that follow (not this one: the request has it). */
void app_sec_persist(app_t *app);

/* app_sec_store_pending (app_internal.h, inline: asked every tick): app_sec_store_step has work
 * and the tick is not one that noted a change. */

/** A slice of storing the attempt record (a job): a write in progress goes on, or one starts when
 *  the record differs from the one stored. */
void app_sec_store_step(app_t *app);

/** True once nothing is left to store: the record as the state is now is stored, or its write
 *  failed (tried again after the next request), or there is no record storage. */
bool app_sec_persisted(const app_t *app);

/** Begin a sendKey's check (the UDS hook): its attempt counts as wrong until checked. Returns
 *  UDS_NRC_RESPONSE_PENDING (app_sec_key_check_run finishes it) or a refusal's NRC. */
uint8_t app_sec_key_check_begin(app_t *app, uint8_t level, const uint8_t *key, uint16_t len);

/** A slice of the sendKey check begun (a job: the attempt stored first, the key's HMAC in
 *  APP_SEC_ROUNDS_PER_TICK rounds a call, the result stored): UDS_NRC_RESPONSE_PENDING until the
 *  answer, then the answer. */
uint8_t app_sec_key_check_run(app_t *app);

/** Begin the motion key of a host session from its nonce (DID 0x0302 write): forgets the key
 *  in use, draws the device nonce; the derivation starts at the next app_motion_key_run.
 *  Returns UDS_NRC_RESPONSE_PENDING or a refusal's NRC. */
uint8_t app_motion_key_begin(app_t *app, const uint8_t *host_nonce, uint16_t len);

/** A slice of the derivation begun (a job: the HMAC in rounds SHA-256 rounds a call, then the
 *  key's schedule, its subkeys and its confirmation a call each): UDS_NRC_RESPONSE_PENDING while
 *  it runs, then 0 with the key in use. */
uint8_t app_motion_key_run(app_t *app, uint32_t rounds);

#endif /* APP_SEC_H */

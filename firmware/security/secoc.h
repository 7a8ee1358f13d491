/* Authenticated host frames, SecOC style (docs/protocol.md): a MAC truncated to 24 bits and a
 * 32-bit freshness value (FV) per frame channel, of which only the low 8 bits travel.
 *
 * Key: derived per host session, never sent: the first 16 bytes of HMAC-SHA256(level-1 secret,
 * SECOC_LABEL || device nonce || host nonce). MAC = first 3 bytes of AES-128-CMAC(key, id low,
 * id high, payload bytes 0..2, FV big-endian): one AES block encryption per frame (sec_aes.h),
 * within one tick of the Cortex-M images. The frame carries the MAC in bytes 3..5 and FV bits
 * 0..7 in byte 6 (its low nibble is the E2E counter). The receiver rebuilds the FV as the
 * smallest value above the last accepted one with those low bits: up to 255 lost frames in a row
 * are absorbed; more need a new key (the host re-establishes it). A frame whose MAC matches an FV
 * already used is a replay (a second encryption, only for a frame that fails). SECOC_MAX_BAD_MAC
 * wrong MACs in a row discard the key (a brute force needs a new SecurityAccess every
 * SECOC_MAX_BAD_MAC guesses). No heap; constant-time tag comparison. */
#ifndef SECOC_H
#define SECOC_H

#include <stdbool.h>
#include <stdint.h>
#include "can_frame.h"
#include "sec_aes.h"
#include "sec_sha256.h"
#include "sec_status.h"

#define SECOC_KEY_LEN 16u /* an AES-128 key */
#define SECOC_NONCE_LEN 16u
#define SECOC_MAC_LEN 3u /* 24 MAC bits in data bytes 3..5 */
#define SECOC_MAC_OFFSET 3u
#define SECOC_PAYLOAD_LEN 3u /* data bytes 0..2 are the authenticated payload */
#define SECOC_FV_BYTE 6u     /* FV bits 0..7 (bits 0..3 double as the E2E counter) */
#define SECOC_FV_WINDOW 256u /* 2^(FV bits in the frame) */
/* wrong MACs in a row (no accepted frame between) that discard the key: a key nobody uses is
 * guessed at most this often before a new SecurityAccess; the host's heartbeat (every 10 ms)
 * resets the count, so a flood of 3,000 forged frames a second (30 between two heartbeats, 85 ms
 * to reach it) leaves a working session alone */
#define SECOC_MAX_BAD_MAC 256u
#define SECOC_LABEL "forceskill secoc v3"            /* protocol version 3: AES-CMAC */
#define SECOC_CONFIRM_LABEL "forceskill key confirm" /* secoc_confirm's message */

/** The authenticated frame channels, each with its own freshness value. */
typedef enum {
    SECOC_CH_COMMAND = 0,
    SECOC_CH_HEARTBEAT = 1,
    SECOC_CHANNELS = 2
} secoc_channel_t;

/** Receiver (device) or sender (host) state of one session key. */
typedef struct {
    sec_cmac_t cmac;             /* the key's AES schedule and CMAC subkeys */
    uint32_t fv[SECOC_CHANNELS]; /* receiver: last accepted FV; sender: last sent FV */
    bool keyed;                  /* a key is established */
    uint16_t bad_in_row;         /* wrong MACs since the last accepted frame */
    uint32_t accepted, bad_mac, replayed, no_key, revoked; /* frames and discarded keys */
    uint16_t last_refusal; /* SEC_ERR_* of the last refused frame, 0 if none */
} secoc_t;

/** A frame's verification in slices (secoc_verify_begin, then secoc_verify_run): the frame, the
 *  freshness value its MAC is checked at, the encryption in flight. */
typedef struct {
    can_frame_t f;
    uint32_t fv;
    uint8_t ch;
    uint8_t phase;     /* 1: the MAC at fv; 2: at fv - SECOC_FV_WINDOW (is it a replay); 0: done */
    bool replay_check; /* a frame that fails takes phase 2 (secoc_verify_begin sets it) */
    sec_status_t status; /* the result once done */
    sec_aes128_job_t aes;
} secoc_job_t;

/** No key, every counter zero. */
void secoc_init(secoc_t *s);

/** The session key of a host session: HMAC-SHA256(secret, SECOC_LABEL || dev || host), its
 *  first SECOC_KEY_LEN bytes (four SHA-256 compressions: app.c spreads them over ticks with
 *  sec_hmac_job, this is the one-shot reference). */
void secoc_derive_key(const uint8_t *secret, uint32_t secret_len,
                      const uint8_t dev_nonce[SECOC_NONCE_LEN],
                      const uint8_t host_nonce[SECOC_NONCE_LEN], uint8_t key[SECOC_KEY_LEN]);

/** A host's side of a session: secoc_init, then the key derived from secret and both nonces. */
void secoc_start_session(secoc_t *s, const uint8_t *secret, uint32_t secret_len,
                         const uint8_t dev_nonce[SECOC_NONCE_LEN],
                         const uint8_t host_nonce[SECOC_NONCE_LEN]);

/** Use key from now on: both freshness values restart at 0; counters kept. */
void secoc_set_key(secoc_t *s, const uint8_t key[SECOC_KEY_LEN]);

/** secoc_set_key in two calls, each about one block encryption's work: the key's schedule (no
 *  key in use until the second call) ... */
void secoc_set_key_begin(secoc_t *s, const uint8_t key[SECOC_KEY_LEN]);

/** ... then its subkeys, the freshness values' restart, and the key in use. */
void secoc_set_key_finish(secoc_t *s);

/** Discard the key (frames are refused with SEC_ERR_NO_KEY until a new one is set). */
void secoc_forget(secoc_t *s);

/** The key's confirmation: the first 4 bytes of AES-CMAC(key, SECOC_CONFIRM_LABEL) as a
 *  big-endian word, 0 without a key (a host compares it with its own key's). */
uint32_t secoc_confirm(const secoc_t *s);

/** secoc_confirm in two calls of one block encryption each: the first block's into x, then the
 *  confirmation from it (0 without a key). */
void secoc_confirm_first(const secoc_t *s, uint8_t x[SEC_AES_BLOCK]);
uint32_t secoc_confirm_finish(const secoc_t *s, const uint8_t x[SEC_AES_BLOCK]);

/** The 24-bit MAC of a frame's id and payload (data bytes 0..2) at freshness value fv. */
void secoc_mac(const secoc_t *s, const can_frame_t *f, uint32_t fv, uint8_t mac[SECOC_MAC_LEN]);

/** Sender: advance channel ch's FV and write it (low 8 bits, byte 6) and the MAC (bytes 3..5);
 *  the caller then adds the E2E CRC (its counter = the FV's low nibble). Returns the FV. */
uint32_t secoc_protect(secoc_t *s, can_frame_t *f, secoc_channel_t ch);

/** Receiver: check frame f of channel ch (one AES encryption, two for a frame that fails).
 *  SEC_OK accepts it (its FV becomes the last); SEC_ERR_NO_KEY, SEC_ERR_MAC, SEC_ERR_REPLAY,
 *  SEC_ERR_FRESHNESS refuse it, counted. */
sec_status_t secoc_verify(secoc_t *s, const can_frame_t *f, secoc_channel_t ch);

/** Receiver: the sender has sent channel ch's frames up to a freshness value whose low 8 bits are
 *  low8 (told on another, authenticated channel): every frame at or below it not yet accepted is
 *  refused from now on. The value is the last accepted one plus (low8 - its low 8 bits) mod 256
 *  when that is below 128; a value behind it (told before a frame that arrived first) changes
 *  nothing. */
void secoc_raise_floor(secoc_t *s, secoc_channel_t ch, uint8_t low8);

/** secoc_verify in slices: starts checking frame f of channel ch (a refusal that needs no
 *  encryption, no key or freshness used up, ends the job at once). */
void secoc_verify_begin(secoc_t *s, secoc_job_t *j, const can_frame_t *f, secoc_channel_t ch);

/** secoc_verify_begin without the replay check: a frame that fails is refused as a wrong MAC after
 *  one encryption (a receiver under a flood of forged frames halves their cost). */
void secoc_verify_begin_fast(secoc_t *s, secoc_job_t *j, const can_frame_t *f, secoc_channel_t ch);

/** Runs at most *rounds AES rounds of the job (*rounds decreases by those run; an encryption
 *  is 10; a budget left short of the replay check's second block runs it from the next call);
 *  true once done, j->status then holds secoc_verify's result, counted as it counts. */
bool secoc_verify_run(secoc_t *s, secoc_job_t *j, uint32_t *rounds);

/** True while a verification begun has not ended (it ends in secoc_verify_run, or abandoned). */
static inline bool secoc_verify_busy(const secoc_job_t *j)
{
    return j->phase != 0u;
}

/** Abandon the verification in flight, if any: its frame is never acted on. */
static inline void secoc_verify_abandon(secoc_job_t *j)
{
    j->phase = 0u;
}

#endif /* SECOC_H */

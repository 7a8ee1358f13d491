/* Bootloader decision logic: two application slots (A = 0, B = 1) and a small boot-state record
 * kept in the power-loss-safe record store (nvm_). Pure over an explicit config/state and the
 * flash HAL (fls_), so the same code runs on the host/HIL port and on Cortex-M (docs/update.md).
 *
 * Rules at every reset (boot_select):
 *  1. a test image (marked by fwu_mark_test) is verified (hash, tag, target, no downgrade unless
 *     the state carries BOOT_FLAG_ALLOW_DOWNGRADE, stored data readable) and, if it passes, booted
 *     ONCE: the attempt is recorded before the jump;
 *  2. a test image already booted once and not confirmed (boot_confirm) is dropped: revert;
 *  3. otherwise the active (confirmed) image is verified and booted; if it fails, the other slot
 *     is tried (recovery); if neither verifies, nothing is started (BOOT_ERR_NO_IMAGE).
 * A record write is atomic (nvm_: old or complete new record after a power loss at any write). */
#ifndef BOOT_H
#define BOOT_H

#include <stdbool.h>
#include <stdint.h>
#include "boot_image.h"
#include "fls.h"
#include "nvm.h"

#define BOOT_SLOT_COUNT 2u
#define BOOT_SLOT_NONE 0xFFu
#define BOOT_FLAG_ALLOW_DOWNGRADE 0x01u /* test image may be older than the active one */
#define BOOT_STATE_VERSION 1u
#define BOOT_STATE_LEN 16u /* bytes of the state record payload */

/** Where and what: filled by the port once. */
typedef struct {
    const fls_dev_t *app_dev;            /* flash holding both application slots */
    uint32_t slot_addr[BOOT_SLOT_COUNT]; /* sector-aligned start of slot A and slot B */
    uint32_t slot_size;                  /* bytes per slot, a multiple of the sector size */
    nvm_t *state_nvm;    /* record store (initialised with nvm_init) for the state */
    uint16_t state_slot; /* record index of the boot state in state_nvm */
    uint32_t target_id;  /* BOOT_TARGET_* of this device */
    const uint8_t *key;  /* device key of the image tag (HMAC-SHA256) */
    uint32_t key_len;
    uint16_t skill_min, skill_max;   /* format versions of the stored skills (0,0 = none) */
    uint16_t config_min, config_max; /* format versions of the stored configuration */
} boot_config_t;

/** The persistent boot state (record payload, BOOT_STATE_LEN bytes little-endian). */
typedef struct {
    uint8_t active_slot;     /* confirmed image, BOOT_SLOT_NONE on a fresh device */
    uint8_t test_slot;       /* image to try once, BOOT_SLOT_NONE if none */
    uint8_t test_attempts;   /* boots of the test image so far (0 or 1) */
    uint8_t confirmed;       /* 1: the active image confirmed itself after its self-test */
    uint8_t test_flags;      /* BOOT_FLAG_* given with the test request */
    uint32_t active_version; /* fw_version of the active image (information) */
} boot_state_t;

/** How the last boot_select decided. */
typedef enum {
    BOOT_PATH_NONE = 0,         /* nothing bootable */
    BOOT_PATH_ACTIVE = 1,       /* the active, confirmed image */
    BOOT_PATH_TEST = 2,         /* the test image, first and only unconfirmed boot */
    BOOT_PATH_REVERTED = 3,     /* the test image did not confirm: back to the active one */
    BOOT_PATH_TEST_REFUSED = 4, /* the test image failed verification: active one */
    BOOT_PATH_RECOVERED = 5,    /* the active image failed verification: the other slot */
    BOOT_PATH_FIRST = 6,        /* no state record yet: best verified slot adopted */
} boot_path_t;

/** Run-time view of the boot. */
typedef struct {
    const boot_config_t *cfg;
    boot_state_t state;
    uint8_t running_slot; /* slot started, BOOT_SLOT_NONE if none */
    uint8_t test_boot;    /* 1: the running image is on test and must confirm */
    boot_path_t path;
    boot_status_t refusal;       /* why a candidate was refused on this boot (0 if none) */
    boot_image_header_t running; /* header of the running image (valid if running_slot set) */
} boot_t;

/** Encode/decode the state record payload (pure). Decode refuses a wrong version or slot. */
void boot_state_encode(const boot_state_t *s, uint8_t out[BOOT_STATE_LEN]);
bool boot_state_decode(const uint8_t in[BOOT_STATE_LEN], boot_state_t *s);

/** Read the state record; a missing or unreadable record gives the fresh state (returns false). */
bool boot_state_load(const boot_config_t *cfg, boot_state_t *s);

/** Write the state record atomically (BOOT_ERR_FLASH if nvm_write fails). */
boot_status_t boot_state_store(const boot_config_t *cfg, const boot_state_t *s);

/** Verify the image in slot for this device (header, fits, hash, tag, target). */
boot_status_t boot_slot_verify(const boot_config_t *cfg, uint8_t slot, boot_image_header_t *out);

/** Decide which slot to start at reset (rules above); updates and persists the state. Returns
 *  BOOT_OK with b->running_slot set, or BOOT_ERR_NO_IMAGE. */
boot_status_t boot_select(boot_t *b, const boot_config_t *cfg);

/** Called by the running image after its self-test passed: a test image becomes the active
 *  one. No-op (BOOT_OK) when already confirmed. */
boot_status_t boot_confirm(boot_t *b);

/** For an application image that is separate from the bootloader (Cortex-M): confirm slot if
 *  the state says it is on its single test boot; BOOT_OK (nothing written) otherwise. */
boot_status_t boot_confirm_slot(const boot_config_t *cfg, uint8_t slot);

/** Check a verified candidate against the running image: downgrade (707) unless flags allow it,
 *  stored data formats (708/709). */
boot_status_t boot_check_candidate(const boot_t *b, const boot_image_header_t *h, uint8_t flags);

/** Mark slot to be tried once at the next reset (verifies it first; fwu_mark_test calls it). */
boot_status_t boot_mark_test(boot_t *b, uint8_t slot, uint8_t flags);

/** The slot an update may write: the one not running (BOOT_SLOT_NONE never: with nothing
 *  running, slot B unless A is empty... see boot.c). */
uint8_t boot_inactive_slot(const boot_t *b);

#endif /* BOOT_H */

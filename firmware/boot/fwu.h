/* Firmware update receiver: the device side of `forceskill flash` (docs/update.md). The UDS
 * server (firmware/proto/uds.c) checks session, security level, lengths and the block counter;
 * its application hooks call these functions when the RequestDownload address is
 * FWU_DOWNLOAD_ADDRESS, and route RoutineControl FWU_RID_* and ReadDataByIdentifier
 * FWU_DID_STATUS here. Each function returns BOOT_OK or a 7xx status; fwu_nrc() gives the
 * negative response code to send (each refusal its own code, table in docs/update.md).
 *
 * Flow: fwu_begin (erases nothing yet) -> fwu_data in order (each sector of the inactive slot is
 * erased just before its first byte is programmed; header checked as soon as it is complete:
 * magic, format, target, length) -> fwu_end (flush, then hash + tag verified from flash) ->
 * fwu_mark_test (downgrade and data-format checks, boot state records the test slot) -> ECUReset
 * -> boot_select boots it once -> the image calls boot_confirm after its self-test. */
#ifndef FWU_H
#define FWU_H

#include <stdbool.h>
#include <stdint.h>
#include "boot.h"
#include "boot_verify.h"
#include "fs_job.h"
#include "fs_uds_ids.h" /* FWU_DOWNLOAD_ADDRESS, FWU_RID_*, FWU_DID_STATUS */
#include "fs_wire.h"    /* fs_wire_fwu_status_t: FWU_DID_STATUS's record (wire.toml) */

#define FWU_STATUS_LEN FS_WIRE_FWU_STATUS_LEN
#define FWU_BLOCK_MAX 4096u /* the longest TransferData block fwu_data_step takes */
#define FWU_OPT_ALLOW_DOWNGRADE BOOT_FLAG_ALLOW_DOWNGRADE

typedef enum {
    FWU_IDLE = 0,      /* no download */
    FWU_RECEIVING = 1, /* between fwu_begin and fwu_end */
    FWU_RECEIVED = 2,  /* complete and verified in the inactive slot */
    FWU_MARKED = 3,    /* marked for a test boot at the next reset */
} fwu_phase_t;

/** Receiver state (one per device). */
typedef struct {
    boot_t *boot;
    fwu_phase_t phase;
    uint8_t slot;        /* slot being written */
    uint32_t size;       /* bytes announced by RequestDownload */
    uint32_t received;   /* bytes accepted so far */
    uint32_t programmed; /* bytes programmed (received minus the staged tail) */
    uint32_t erased;     /* bytes of the slot erased so far, from its start */
    bool erasing;        /* fwu_data_step: a background erase was started and not yet seen done */
    bool header_ok;      /* the header was checked (image_version set) */
    uint8_t hdr[BOOT_IMAGE_HEADER_SIZE];
    uint8_t tail[16]; /* bytes waiting for a full write unit */
    uint32_t tail_len;
    uint32_t crc32;              /* zlib CRC-32 of the received bytes (RequestTransferExit reply) */
    uint32_t image_version;      /* fw_version of the received image, 0 before its header */
    boot_status_t last;          /* last refusal, 0 if none */
    fs_job_t verify_job;         /* fwu_end_step: the image's verification, a job (fs_job.h) */
    boot_status_t verify_status; /* its verdict, when it ends */
    boot_verify_t verify;
    fs_job_t block_job;         /* fwu_data_step: a TransferData block in pieces, a job */
    boot_status_t block_status; /* its verdict, when it ends */
    uint32_t block_off;         /* its offset in the image, its length and the bytes taken */
    uint32_t block_len;
    uint32_t block_pos;
    const uint8_t *block_src; /* the block, the caller's until it is done */
} fwu_t;

/** Attach to a booted device (boot_select already run). */
void fwu_init(fwu_t *f, boot_t *boot);

/** RequestDownload of size bytes into the inactive slot. authorised: programming session with
 *  SecurityAccess level UDS_SEC_LEVEL_FIRMWARE unlocked (720 otherwise). Refused while the
 *  running image is on test (725), for a size below header+tag (726) or above a slot (704). */
boot_status_t fwu_begin(fwu_t *f, bool authorised, uint32_t size);

/** TransferData: len bytes at offset (must equal the bytes received so far: 722; more than
 *  announced: 724). Header refusals 700-703 as soon as 128 bytes are in; 711 on flash errors.
 *  Any refusal ends the download. */
boot_status_t fwu_data(fwu_t *f, bool authorised, uint32_t offset, const uint8_t *data,
                       uint32_t len);

/** TransferData in slices: the first call (data not NULL) checks what fwu_data checks first
 *  (720, 722, 724) and takes the block (len <= FWU_BLOCK_MAX; data must stay valid and unchanged
 *  until *done, nothing is copied); each later call (data NULL) takes at most max_bytes of it
 *  through fwu_data; *done false while it goes on, then fwu_data's result (any refusal ends the
 *  download). */
boot_status_t fwu_data_step(fwu_t *f, bool authorised, uint32_t offset, const uint8_t *data,
                            uint32_t len, uint32_t max_bytes, bool *done);

/** RequestTransferExit: all announced bytes in (722), then hash (705) and tag (706) are checked
 *  on the bytes read back from flash. *crc32_out (may be NULL) = CRC-32 of the image. */
boot_status_t fwu_end(fwu_t *f, bool authorised, uint32_t *crc32_out);

/** RequestTransferExit in slices: the first call only checks (the request's own), the second
 *  flushes and starts the verification (the header read and checked, no round yet), each later
 *  call runs at most rounds SHA-256 compression rounds of it, the last one its state's wipe and
 *  the verdict; *done false while it goes on (the image is neither received nor markable
 *  meanwhile), then fwu_end's result. */
boot_status_t fwu_end_step(fwu_t *f, bool authorised, uint32_t *crc32_out, uint32_t rounds,
                           bool *done);

/** Abandon a download (session change, S3 timeout). The slot is left unbootable, not marked. */
void fwu_abort(fwu_t *f);

/** RoutineControl FWU_RID_MARK_TEST: the received image will be booted once at the next reset.
 *  Refused before fwu_end succeeded (722), downgrade without FWU_OPT_ALLOW_DOWNGRADE (707),
 *  stored skills/configuration the image cannot read (708/709). */
boot_status_t fwu_mark_test(fwu_t *f, bool authorised, uint8_t options);

/** RoutineControl FWU_RID_CONFIRM (or the application's own call after its self-test). */
boot_status_t fwu_confirm(fwu_t *f);

/** FWU_DID_STATUS record (fs_wire_fwu_status_t of wire.toml, packed by its generated codec):
 *  running version, running slot, on-test, active slot, pending test slot, boot path, target,
 *  last refusal, received image version, update phase. Returns the bytes written (0 if cap is
 *  short). */
uint16_t fwu_status(const fwu_t *f, uint8_t *out, uint16_t cap);

/** UDS negative response code for a status (0x00 for BOOT_OK). */
uint8_t fwu_nrc(boot_status_t st);

#endif /* FWU_H */

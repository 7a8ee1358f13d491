/* Status codes: Firmware image and update.
 * generated from firmware/base/codes.toml by tools/gen_codes.py; do not edit. */
#ifndef BOOT_STATUS_H
#define BOOT_STATUS_H

#include <stdint.h>
#include "uds_nrc.h"

/** Firmware image and update (700-729, firmware/boot). */
typedef enum {
    BOOT_OK = 0,
    BOOT_ERR_TRUNCATED = 700,     /* fewer bytes than header + payload_length + tag */
    BOOT_ERR_MAGIC = 701,         /* magic is not "FSFW" */
    BOOT_ERR_FORMAT = 702,        /* format version, header size, flags or reserved bytes wrong */
    BOOT_ERR_TARGET = 703,        /* image built for another target */
    BOOT_ERR_TOO_LARGE = 704,     /* image larger than a slot */
    BOOT_ERR_HASH = 705,          /* SHA-256 of the payload differs from the header's */
    BOOT_ERR_TAG = 706,           /* HMAC-SHA256 tag wrong: not authorised for this device */
    BOOT_ERR_DOWNGRADE = 707,     /* older than the running image and not forced */
    /* stored skills in a format the image can neither read nor migrate */
    BOOT_ERR_SKILL_FORMAT = 708,
    BOOT_ERR_CONFIG_FORMAT = 709, /* stored configuration likewise */
    BOOT_ERR_NO_IMAGE = 710,      /* no slot holds a bootable, authorised image */
    BOOT_ERR_FLASH = 711,         /* the flash HAL refused a read, erase or write */
    BOOT_ERR_ARG = 712,           /* NULL pointer or slot index out of range */
    FWU_ERR_LOCKED = 720,         /* not in the programming session with SecurityAccess unlocked */
    /* service out of order (no download active, exit too early, ...) */
    FWU_ERR_SEQUENCE = 722,
    FWU_ERR_BLOCK_COUNTER = 723,  /* TransferData block sequence counter not the expected one */
    FWU_ERR_OVERRUN = 724,        /* more data than announced in RequestDownload */
    /* running image not yet confirmed: its fallback must not be overwritten */
    FWU_ERR_TEST_PENDING = 725,
    FWU_ERR_RANGE = 726,          /* address, size or data format of RequestDownload not accepted */
} boot_status_t;

/** The UDS negative response code of a status (UDS_NRC_OK for BOOT_OK). */
static inline uint8_t boot_status_nrc(boot_status_t st)
{
    switch (st) {
    case BOOT_OK: return UDS_NRC_OK;
    case BOOT_ERR_TRUNCATED: return UDS_NRC_FW_TRUNCATED;
    case BOOT_ERR_MAGIC: return UDS_NRC_FW_HEADER;
    case BOOT_ERR_FORMAT: return UDS_NRC_FW_HEADER;
    case BOOT_ERR_TARGET: return UDS_NRC_FW_TARGET;
    case BOOT_ERR_TOO_LARGE: return UDS_NRC_UPLOAD_DOWNLOAD_NOT_ACCEPTED;
    case BOOT_ERR_HASH: return UDS_NRC_FW_HASH;
    case BOOT_ERR_TAG: return UDS_NRC_FW_TAG;
    case BOOT_ERR_DOWNGRADE: return UDS_NRC_FW_DOWNGRADE;
    case BOOT_ERR_SKILL_FORMAT: return UDS_NRC_FW_SKILL_FORMAT;
    case BOOT_ERR_CONFIG_FORMAT: return UDS_NRC_FW_CONFIG_FORMAT;
    case BOOT_ERR_FLASH: return UDS_NRC_PROGRAMMING_FAILURE;
    case FWU_ERR_LOCKED: return UDS_NRC_SECURITY_ACCESS_DENIED;
    case FWU_ERR_SEQUENCE: return UDS_NRC_REQUEST_SEQUENCE_ERROR;
    case FWU_ERR_BLOCK_COUNTER: return UDS_NRC_WRONG_BLOCK_COUNTER;
    case FWU_ERR_OVERRUN: return UDS_NRC_TRANSFER_SUSPENDED;
    case FWU_ERR_TEST_PENDING: return UDS_NRC_CONDITIONS_NOT_CORRECT;
    case FWU_ERR_RANGE: return UDS_NRC_REQUEST_OUT_OF_RANGE;
    default: return UDS_NRC_GENERAL_REJECT;
    }
}

#endif /* BOOT_STATUS_H */

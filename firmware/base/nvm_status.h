/* Status codes: Storage: slot records.
 * generated from firmware/base/codes.toml by tools/gen_codes.py; do not edit. */
#ifndef NVM_STATUS_H
#define NVM_STATUS_H

/** Storage: slot records (530-549, nvm_*). */
typedef enum {
    NVM_OK = 0,
    NVM_ERR_NULL_ARG = 530,        /* a required pointer was NULL */
    NVM_ERR_SLOT = 531,            /* slot index out of range */
    NVM_ERR_TOO_LARGE = 532,       /* payload larger than a slot holds */
    NVM_ERR_EMPTY = 533,           /* the slot holds no valid record */
    NVM_ERR_FLASH = 534,           /* the flash HAL reported an erase/program/read failure */
    NVM_ERR_VERIFY = 535,          /* read-back after programming differs from what was written */
    NVM_ERR_REC_MAGIC = 536,       /* record magic wrong (or erased flash) */
    NVM_ERR_REC_VERSION = 537,     /* unsupported record format version */
    NVM_ERR_REC_LENGTH = 538,      /* record length field impossible for the buffer/sector */
    NVM_ERR_REC_CRC = 539,         /* record CRC-32 mismatch */
    NVM_ERR_REC_UNCOMMITTED = 540, /* commit word not written: an interrupted write */
    NVM_ERR_GEOMETRY = 541,        /* flash geometry unusable (sector too small, too few sectors) */
    NVM_ERR_BUFFER = 542,          /* caller's buffer too small for the record */
    NVM_ERR_PAYLOAD = 543,         /* payload rejected by the content check (e.g. skill_parse) */
} nvm_status_t;

#endif /* NVM_STATUS_H */

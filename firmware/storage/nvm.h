/* Slot storage: double-buffered, versioned, CRC-checked records in (simulated) flash, used
 * ping-pong like ODrive's stm32_nvm.c. Every slot owns two sectors (copies A and B). A record:
 *
 *   offset size field
 *   0      4    magic    0x524D564E ("NVMR")
 *   4      2    format   NVM_RECORD_VERSION
 *   6      2    slot     slot index (a copy found under another slot is invalid)
 *   8      4    seq      sequence number, +1 per write of this slot (serial-number compare)
 *   12     4    length   payload bytes (<= NVM_PAYLOAD_MAX for the geometry)
 *   16     4    crc32    zlib CRC-32 over bytes [0,16) and the payload
 *   20     12   reserved 0xFF
 *   32     L    payload
 *   32+L'  4    commit   0x00C0FFEE, programmed last (L' = L rounded up to write_unit, min 4)
 *
 * A copy is valid iff magic, version, slot, length, commit and CRC all check; the valid copy
 * with the newest seq wins. A write erases the copy that does not hold the newest record,
 * programs header+payload, then the commit word, then reads back and verifies. The newest
 * record is never touched, and the new one becomes valid only with its last program; so a
 * power loss at any erase or program leaves either the old record or the complete new one.
 * nvm_write is not for use inside the control tick (erase takes milliseconds on real flash);
 * the sliced nvm_write_begin/nvm_write_run spreads one write over ticks (the application's
 * download commit), and the tick only swaps pointers (nvm_bank_*). */
#ifndef NVM_H
#define NVM_H

#include <stdbool.h>
#include <stdint.h>
#include "fs_budget.h"
#include "nvm_status.h"
#include "fls.h"
#include "fs_wire_const.h"

#define NVM_RECORD_MAGIC 0x524D564Eu
#define NVM_RECORD_VERSION 1u
#define NVM_COMMIT_WORD 0x00C0FFEEu
#define NVM_HEADER_SIZE 32u
#define NVM_COMMIT_SIZE 4u
#define NVM_MAX_SLOTS FS_SLOT_COUNT /* the device's skill slots (wire.toml) */

/** Information about one parsed record. */
typedef struct {
    uint16_t slot;
    uint32_t seq;
    uint32_t length;         /* payload bytes */
    uint32_t crc32;          /* the stored CRC (covers header bytes 0..15 and the payload) */
    uint32_t payload_offset; /* offset of the payload from the record start */
} nvm_record_info_t;

/** Directory entry of one slot (what the slot-directory data identifier reports). */
typedef struct {
    uint8_t valid;      /* a valid record exists */
    uint8_t copy;       /* 0 = A, 1 = B: which copy holds it */
    uint8_t both_valid; /* the other copy is valid too (an older version) */
    uint32_t seq;
    uint32_t length;
    uint32_t crc32;
} nvm_dir_entry_t;

/** Storage handle. */
typedef struct {
    const fls_dev_t *dev;
    uint16_t n_slots; /* min(NVM_MAX_SLOTS, sector_count / 2) */
    nvm_dir_entry_t dir[NVM_MAX_SLOTS];
} nvm_t;

/** zlib-compatible CRC-32 continuing from crc (start with 0); equal to skill_crc32 (tested),
 *  kept here so the storage does not depend on the numeric layer of the core. */
uint32_t nvm_crc32(uint32_t crc, const uint8_t *data, uint32_t len);

/** Parse and check one record image held in memory (pure; the fuzz harness and tests use it;
 *  nvm_init checks flash with the same header checks, streaming). buf holds the start of a
 *  sector (len bytes) laid out for a write unit <= 4; expected_slot 0xFFFF accepts any slot.
 *  Order of checks: magic, version, slot, length, commit, CRC. */
nvm_status_t nvm_record_parse(const uint8_t *buf, uint32_t len, uint16_t expected_slot,
                              nvm_record_info_t *out);

/** Build a record image for payload into out (out_cap bytes); *out_len gets its length. */
nvm_status_t nvm_record_build(uint16_t slot, uint32_t seq, const uint8_t *payload, uint32_t len,
                              uint32_t write_unit, uint8_t *out, uint32_t out_cap,
                              uint32_t *out_len);

/** Largest payload a slot can hold on this geometry. */
uint32_t nvm_payload_max(const fls_dev_t *dev);

/** Attach to flash and scan every slot's two copies (builds the directory). */
nvm_status_t nvm_init(nvm_t *n, const fls_dev_t *dev);

/** Directory entry of a slot (NULL if slot is out of range). */
const nvm_dir_entry_t *nvm_dir(const nvm_t *n, uint16_t slot);

/** Write payload as the slot's new record (erase inactive copy, program, commit, verify). */
nvm_status_t nvm_write(nvm_t *n, uint16_t slot, const uint8_t *payload, uint32_t len);

/* Bytes of the CRC or of the final scan in a unit of nvm_write_run (programming and read-back
 * go 256 bytes a unit, one power-loss point each): ~450 instructions on the M4F. */
#define NVM_SLICE_BYTES 64u

/** nvm_write in slices (nvm_write_begin, then nvm_write_run until it returns true): the same
 *  steps, flash contents and result, a unit of work per step (the erase's start or one poll of
 *  a background erase (fls.h busy), the commit word, NVM_SLICE_BYTES of the CRC or the final
 *  scan, or up to 256 bytes programmed or read back). The payload and *n must
 *  stay in place and unused by other writes until it is done; the newest record stays readable
 *  throughout (the new one becomes valid with the commit word). */
typedef struct {
    nvm_t *n;
    const uint8_t *payload;
    uint32_t len;
    uint32_t seq;  /* the new record's sequence number */
    uint32_t base; /* the target copy's address */
    uint32_t pos;  /* progress inside the stage */
    uint32_t crc;  /* the record's CRC */
    uint32_t scan_crc;
    uint16_t slot;
    uint8_t target; /* the copy written */
    uint8_t stage;  /* internal */
    uint8_t scan;   /* the copy the final scan reads */
    bool ok[2];     /* the final scan's verdict per copy */
    nvm_record_info_t info[2];
    uint8_t hdr[NVM_HEADER_SIZE];
    nvm_status_t status; /* NVM_OK while running or once written; the error once done */
} nvm_writer_t;

/** Start a write (the argument checks of nvm_write: their error is returned, and the writer is
 *  then done). */
nvm_status_t nvm_write_begin(nvm_writer_t *w, nvm_t *n, uint16_t slot, const uint8_t *payload,
                             uint32_t len);

/** At most max_units units of the write; true once done (w->status as nvm_write returns). */
bool nvm_write_run(nvm_writer_t *w, uint32_t max_units);

/** Read the newest valid record of a slot into buf (cap bytes); *len gets the payload length.
 *  The CRC is re-checked on the data read. */
nvm_status_t nvm_read(const nvm_t *n, uint16_t slot, uint8_t *buf, uint32_t cap, uint32_t *len);

/* NVM_READ_CHUNK: payload bytes a unit of nvm_read_run reads and checks (fs_budget.h) */

/** nvm_read in slices (nvm_read_begin, then nvm_read_run until it returns true): the same checks
 *  and result, a unit of work per step (the header, or NVM_READ_CHUNK bytes of the payload read
 *  and added to the CRC). *n and buf must stay in place until it is done. */
typedef struct {
    const nvm_t *n;
    uint8_t *buf;
    uint32_t base; /* the newest copy's address */
    uint32_t pos;  /* payload bytes read */
    uint32_t crc;  /* the CRC so far */
    uint32_t len;  /* the payload length once read */
    nvm_record_info_t info;
    uint16_t slot;
    bool head_done;
    bool done;
    nvm_status_t status; /* NVM_OK while running or once read; the error once done */
} nvm_reader_t;

/** Start a read of slot into buf (cap bytes): the argument and directory checks of nvm_read
 *  (their error is returned, and the reader is then done). */
nvm_status_t nvm_read_begin(nvm_reader_t *r, const nvm_t *n, uint16_t slot, uint8_t *buf,
                            uint32_t cap);

/** At most max_units units of the read; true once done (r->status as nvm_read returns, r->len
 *  the payload length). */
bool nvm_read_run(nvm_reader_t *r, uint32_t max_units);

/** Erase both copies of a slot (the slot becomes empty). */
nvm_status_t nvm_erase_slot(nvm_t *n, uint16_t slot);

#endif /* NVM_H */

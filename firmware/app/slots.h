/* The skill store of the device (prefix slots_): the slot cache (a parsed copy of each valid
 * slot with its CRC, length, peak force and path extent), the transfer buffer of a download or a
 * read-back, and a download's commit in bounded slices (parse, parameter checks, the skill's own
 * rollout, the slot's flash write). The UDS hooks (app_uds.c) check security and state and call
 * it; the run checks (app_run.c) read the cache. Hardware only through the fls_dev_t it is
 * given. No floating point of its own beyond the checks' limits. */
#ifndef SLOTS_H
#define SLOTS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include "fs_budget.h"
#include "fs_job.h"
#include "fls.h"
#include "fs_real.h"
#include "nvm.h"
#include "skill.h"
#include "skill_check.h"
#include "fs_exec.h"

#define SLOTS_N NVM_MAX_SLOTS           /* slot numbers 1..SLOTS_N on the wire */
#define SLOTS_IMAGE_MAX SKILL_IMAGE_MAX /* the longest image a slot holds */

/* The slices of a download's commit and of a read-back a tick: SLOTS_*_PER_TICK, fs_budget.h. */

/** The stages of a download's commit (one slice a tick at least). */
enum {
    SLOTS_COMMIT_PARSE = 0, /* skill_parse_run, SLOTS_PARSE_UNITS_PER_TICK units a slice */
    SLOTS_COMMIT_PARAMS,    /* skchk_params_run, SLOTS_PARAMS_UNITS_PER_TICK units a slice,
                               then skchk_stiffness, skchk_begin */
    SLOTS_COMMIT_CONVERT,   /* the fixed-point build: the skill in fixed point,
                               SLOTS_CONVERT_UNITS_PER_TICK units a slice (exec_store_run's
                               first stage), then the rollout's begin */
    SLOTS_COMMIT_CHECK,     /* the rollout, SLOTS_CHECK_STEPS_PER_TICK steps a slice
                               (exec_store_run's last stage; the fixed-point build: on the
                               converted skill) */
    SLOTS_COMMIT_WRITE,     /* the slot's flash record, SLOTS_FLASH_UNITS_PER_TICK units a
                               slice */
    SLOTS_COMMIT_SWAP       /* the checked skill (and its fixed-point model) into the slot's
                               cache, SLOTS_SWAP_BYTES_PER_TICK bytes a slice (no run starts
                               while the commit runs) */
};

/** What a commit checks a download against (the device's configuration when it starts). */
typedef struct {
    fs_real_t dt_s;              /* the control tick of the rollout */
    fs_real_t stiffness_max_Npm; /* stiffer skills are refused (227) */
    fs_real_t force_max_N;       /* the x force limit: the rollout's peak (223) */
    fs_real_t path_max_m;        /* the y workspace's extent: the y path (225) */
} slots_limits_t;

/** The skill store: storage, the cache per slot (index slot - 1), the transfer and commit. */
typedef struct {
    nvm_t nvm;
    bool nvm_ok;            /* storage opened (slots_init) */
    skill_t skill[SLOTS_N]; /* parsed copy of each valid slot */
    bool valid[SLOTS_N];
    uint32_t crc[SLOTS_N]; /* CRC-32 field of each valid image */
    uint32_t len[SLOTS_N];
    fs_real_t peak_N[SLOTS_N];      /* peak |f_hat| of each valid slot at goal scale 1 */
    fs_real_t path_m[SLOTS_N];      /* extent max|p| of each valid slot's y path (0: none) */
    uint8_t image[SLOTS_IMAGE_MAX]; /* transfer scratch (download staging / upload) */
    uint32_t xfer_slot;             /* 1..SLOTS_N of the download */
    uint32_t xfer_size;
    uint16_t last_transfer_status; /* fs_status / nvm status of the last download */
    skill_t staging;               /* validation target of a download */
    skill_parser_t parser;         /* the parse of staging, spread over ticks */
    skchk_params_t params;         /* parameter check of staging, spread over ticks */
    exec_store_prep_t prep;        /* staging prepared for the executor (its rollout checked),
                                    * spread over ticks */
    uint8_t prep_stage;            /* the preparation's stage (exec_store_stages) */
    nvm_writer_t writer;           /* the slot's flash write, spread over ticks */
    fs_job_t commit;               /* a download's commit (slots_committing): a slice a call */
    uint8_t commit_stage;          /* SLOTS_COMMIT_*: the commit's stage while it runs */
    fs_status_t commit_status;     /* its refusal, FS_OK while it runs or once it passed */
    uint32_t swap_pos;             /* SLOTS_COMMIT_SWAP: bytes of staging copied */
    slots_limits_t lim;            /* the commit's limits, taken at its first slice */
    nvm_reader_t reader;           /* a read-back's record read and CRC, spread over ticks */
    fs_job_t read;                 /* a read-back (slots_upload_begin): 0x78 while it runs */
    uint8_t read_nrc;              /* its answer once it ended */
    exec_store_t store[SLOTS_N];   /* each valid slot's skill prepared for the executor (the
                                  * fixed-point build: its model, what an execution runs) */
    exec_store_t staging_store;    /* staging prepared (the commit's) */
} slots_t;

/** Open storage on dev (NULL: none) and fill the cache from it; no transfer. */
void slots_init(slots_t *b, const fls_dev_t *dev);

/** Fill the cache from storage again (each slot read, parsed and checked without limits). */
void slots_reload(slots_t *b);

/** The cached skill of slot 1..SLOTS_N, NULL for an empty or out-of-range slot. */
const skill_t *slots_skill(const slots_t *b, uint32_t slot);

/** The executor's model of slot 1..SLOTS_N (exec_step_t.model_fx: the fixed-point build's,
 *  converted at its commit or load; the real builds' the skill's own), NULL for an empty or
 *  out-of-range slot. */
const exec_model_t *slots_model(const slots_t *b, uint32_t slot);

/** True if any slot holds a valid skill. */
bool slots_any(const slots_t *b);

/** Start a download of size bytes into slot 1..SLOTS_N: a UDS NRC (0x31 slot or size out of
 *  range, 0x70 storage not open; 0 started, the last transfer status "in progress"). */
uint8_t slots_download_begin(slots_t *b, uint32_t slot, uint32_t size);

/** Store a block of the download at offset: a UDS NRC (0x71 beyond the announced size). */
uint8_t slots_download_data(slots_t *b, uint32_t offset, const uint8_t *d, uint16_t len);

/** True while a download's commit runs (nothing starts meanwhile). */
static inline bool slots_committing(const slots_t *b)
{
    return fs_job_running(&b->commit);
}

/** One slice of the download's commit (the first call starts it with lim): 0x78 while it goes
 *  on; 0 once the slot holds the new skill (*crc_out its CRC-32); 0x72 on a refusal (the last
 *  transfer status gives the check's or the storage's code, the slot keeps what it held). */
uint8_t slots_commit_step(slots_t *b, const slots_limits_t *lim, uint32_t *crc_out);

/** End a transfer without its commit: a download in progress is "interrupted" (status), a commit
 *  in progress stops, nothing is written. */
void slots_abort(slots_t *b);

/** Refuse a download's commit (the device left IDLE or security dropped since it began): the
 *  commit stops, the status is "interrupted", the slot keeps what it holds. */
void slots_refuse_commit(slots_t *b);

/** Start a read-back of slot 1..SLOTS_N of size bytes (its stored length), the record read and
 *  its CRC checked a slice a call: 0x78 while it goes on (call again with the same arguments);
 *  then a UDS NRC (0x31 out of range or another size, 0x70 empty or unreadable slot; 0 the
 *  image is in the transfer buffer). */
uint8_t slots_upload_begin(slots_t *b, uint32_t slot, uint32_t size);

/** Copy len bytes of the read-back at offset into out: a UDS NRC (0x31 beyond its end). */
uint8_t slots_upload_data(const slots_t *b, uint32_t offset, uint8_t *out, uint16_t len);

/** Erase slot 1..SLOTS_N in storage and the cache: a UDS NRC (0x22 storage not open, 0x72 the
 *  erase failed). */
uint8_t slots_erase(slots_t *b, uint32_t slot);

#endif /* SLOTS_H */

/* The skill store of the device (see slots.h). */
#include "slots.h"

#include <string.h>

#include "fs_wire_const.h"
#include "uds_nrc.h"

/* A stored skill's check without limits on slot s's parsed skill: its peak force and path
 * extent, for the run checks (the limits may have changed since its commit); the skill is
 * prepared into the slot's store (the fixed-point build: its model, the rollout it runs). */
static fs_status_t check_slot(slots_t *b, uint16_t s, fs_real_t *peak_N, fs_real_t *path_m)
{
    return exec_store_check(&b->skill[s], &b->store[s], (fs_real_t)FS_TICK_S, peak_N, path_m);
}

void slots_init(slots_t *b, const fls_dev_t *dev)
{
    memset(b, 0, sizeof(*b));
    b->last_transfer_status = FS_TRANSFER_NONE;
    b->nvm_ok = dev != NULL && nvm_init(&b->nvm, dev) == NVM_OK;
    slots_reload(b);
}

void slots_reload(slots_t *b)
{
    for (uint16_t s = 0; s < SLOTS_N; s++) {
        b->valid[s] = false;
        if (!b->nvm_ok) {
            continue;
        }
        uint32_t len = 0u;
        fs_real_t peak = FS_R(0.0);
        fs_real_t path = FS_R(0.0);
        if (nvm_read(&b->nvm, s, b->image, sizeof(b->image), &len) == NVM_OK &&
            skill_parse(b->image, len, &b->skill[s]) == FS_OK &&
            check_slot(b, s, &peak, &path) == FS_OK) {
            b->valid[s] = true;
            b->peak_N[s] = peak;
            b->path_m[s] = path;
            b->crc[s] = skill_crc32(0u, b->image, len - SKILL_CRC_SIZE);
            b->len[s] = len;
        }
    }
}

const skill_t *slots_skill(const slots_t *b, uint32_t slot)
{
    return (slot >= 1u && slot <= SLOTS_N && b->valid[slot - 1u]) ? &b->skill[slot - 1u] : NULL;
}

const exec_model_t *slots_model(const slots_t *b, uint32_t slot)
{
    if (slot < 1u || slot > SLOTS_N || !b->valid[slot - 1u]) {
        return NULL;
    }
    return exec_store_model(&b->store[slot - 1u], &b->skill[slot - 1u]);
}

bool slots_any(const slots_t *b)
{
    bool any = false;
    for (unsigned i = 0; i < SLOTS_N; i++) {
        any = any || b->valid[i];
    }
    return any;
}

uint8_t slots_download_begin(slots_t *b, uint32_t slot, uint32_t size)
{
    if (slot < 1u || slot > SLOTS_N || size < SKILL_HEADER_SIZE_V2 + SKILL_CRC_SIZE ||
        size > SLOTS_IMAGE_MAX) {
        return UDS_NRC_REQUEST_OUT_OF_RANGE;
    }
    if (!b->nvm_ok) {
        return UDS_NRC_UPLOAD_DOWNLOAD_NOT_ACCEPTED;
    }
    b->xfer_slot = slot;
    b->xfer_size = size;
    b->last_transfer_status = FS_TRANSFER_IN_PROGRESS;
    return UDS_NRC_OK;
}

uint8_t slots_download_data(slots_t *b, uint32_t offset, const uint8_t *d, uint16_t len)
{
    if (offset > b->xfer_size || len > b->xfer_size - offset) {
        return UDS_NRC_TRANSFER_SUSPENDED;
    }
    memcpy(&b->image[offset], d, len);
    return UDS_NRC_OK;
}

/* Up to max_bytes more of staging (the skill, then in the fixed-point build its model) into the
 * slot's cache; true once it is all there. */
static bool swap_slice(slots_t *b, uint32_t max_bytes)
{
    const uint32_t s = b->xfer_slot - 1u;
    struct {
        uint8_t *dst;
        const uint8_t *src;
        uint32_t len;
    } const part[] = {
        {(uint8_t *)&b->skill[s], (const uint8_t *)&b->staging, (uint32_t)sizeof(skill_t)},
        {(uint8_t *)&b->store[s], (const uint8_t *)&b->staging_store, exec_store_size()},
    };
    uint32_t base = 0u;
    for (size_t i = 0; i < sizeof part / sizeof part[0]; i++) {
        if (b->swap_pos < base + part[i].len) {
            const uint32_t at = b->swap_pos - base;
            const uint32_t rest = part[i].len - at;
            const uint32_t n = rest < max_bytes ? rest : max_bytes;
            memcpy(&part[i].dst[at], &part[i].src[at], n);
            b->swap_pos += n;
            max_bytes -= n;
            if (max_bytes == 0u) {
                return false; /* the next slice goes on (or finds it all there) */
            }
        }
        base += part[i].len;
    }
    return true;
}

/* The slot's cache once the new skill is in it: valid, its figures, the transfer's status. */
static void commit_done(slots_t *b)
{
    const uint32_t s = b->xfer_slot - 1u;
    b->valid[s] = true;
    b->peak_N[s] = exec_store_peak_N(&b->prep);
    b->path_m[s] = exec_store_path_m(&b->prep);
    b->last_transfer_status = 0u;
    b->crc[s] = b->parser.crc; /* the image's CRC-32, checked by the parse */
    b->len[s] = b->xfer_size;
}

/* A commit that ends before its answer: once its record is written (the swap), the cache is
 * finished now, so the slot holds what storage holds. */
static void commit_cut(slots_t *b)
{
    if (fs_job_running(&b->commit) && b->commit_stage == SLOTS_COMMIT_SWAP) {
        (void)swap_slice(b, UINT32_MAX);
        commit_done(b);
    }
}

/* A download's commit, a slice a call (a job): each stage's set-up a slice of its own, then its
 * slices (parse, parameters, the fixed-point conversion, the rollout, the slot's flash write, the
 * cache's swap). Ends with b->commit_status the refusal, or FS_OK with the write's result in
 * b->writer.status (the swap only after a write that worked). */
/* long: one straight line through the commit's stages, a yield between slices */
static fs_job_status_t commit_job(slots_t *b)
{
    fs_job_t *j = &b->commit;
    FS_JOB_BEGIN(j);
    b->commit_stage = SLOTS_COMMIT_PARSE;
    skill_parse_begin(&b->parser, b->image, b->xfer_size, &b->staging);
    FS_JOB_YIELD(j);
    while (!skill_parse_run(&b->parser, SLOTS_PARSE_UNITS_PER_TICK)) {
        FS_JOB_YIELD(j);
    }
    if ((b->commit_status = b->parser.status) != FS_OK) {
        FS_JOB_EXIT(j); /* e.g. 204 CRC: the old skill stays */
    }
    FS_JOB_YIELD(j);
    b->commit_stage = SLOTS_COMMIT_PARAMS;
    skchk_params_begin(&b->params, &b->staging);
    FS_JOB_YIELD(j);
    while (!skchk_params_run(&b->params, SLOTS_PARAMS_UNITS_PER_TICK)) {
        FS_JOB_YIELD(j);
    }
    if ((b->commit_status = b->params.status) != FS_OK) {
        FS_JOB_EXIT(j);
    }
    FS_JOB_YIELD(j);
    /* the skill prepared for the executor, its stages (the fixed-point build: the conversion,
     * SLOTS_COMMIT_CONVERT, before the rollout) ending with the rollout, SLOTS_COMMIT_CHECK */
    b->prep_stage = 0u;
    while (b->prep_stage < exec_store_stages()) {
        b->commit_stage = (uint8_t)(SLOTS_COMMIT_CHECK + 1u + b->prep_stage - exec_store_stages());
        b->commit_status = (b->prep_stage == 0u)
                               ? skchk_stiffness(&b->staging, b->lim.stiffness_max_Npm)
                               : FS_OK;
        exec_store_begin(&b->prep, b->prep_stage, &b->staging, &b->staging_store, b->lim.dt_s,
                         b->lim.force_max_N, b->lim.path_max_m);
        if (b->commit_status != FS_OK) {
            FS_JOB_EXIT(j);
        }
        FS_JOB_YIELD(j);
        while (!exec_store_run(&b->prep, b->prep_stage,
                               b->commit_stage == SLOTS_COMMIT_CHECK
                                   ? SLOTS_CHECK_STEPS_PER_TICK
                                   : SLOTS_CONVERT_UNITS_PER_TICK)) {
            FS_JOB_YIELD(j);
        }
        /* 3xx: the skill does not fit the fixed-point executor; 222/223/225/300: the rollout */
        if ((b->commit_status = exec_store_status(&b->prep, b->prep_stage)) != FS_OK) {
            FS_JOB_EXIT(j); /* slot unchanged */
        }
        FS_JOB_YIELD(j);
        b->prep_stage++;
    }
    b->commit_stage = SLOTS_COMMIT_WRITE;
    (void)nvm_write_begin(&b->writer, &b->nvm, (uint16_t)(b->xfer_slot - 1u), b->image,
                          b->xfer_size); /* its argument errors end the write at once */
    FS_JOB_YIELD(j);
    while (!nvm_write_run(&b->writer, SLOTS_FLASH_UNITS_PER_TICK)) {
        FS_JOB_YIELD(j);
    }
    if (b->writer.status != NVM_OK) {
        FS_JOB_EXIT(j);
    }
    /* the cache changes from the next slice on: nothing reads it meanwhile (a run does not
     * start while the commit runs, the UDS server answers others busy) */
    FS_JOB_YIELD(j);
    b->commit_stage = SLOTS_COMMIT_SWAP;
    b->swap_pos = 0u;
    FS_JOB_YIELD(j);
    while (!swap_slice(b, SLOTS_SWAP_BYTES_PER_TICK)) {
        FS_JOB_YIELD(j);
    }
    FS_JOB_END(j);
}

uint8_t slots_commit_step(slots_t *b, const slots_limits_t *lim, uint32_t *crc_out)
{
    if (!fs_job_running(&b->commit)) {
        /* the commit, a bounded slice a tick (0x78 meanwhile) */
        b->lim = *lim;
        b->commit_status = FS_OK;
    }
    if (commit_job(b) == FS_JOB_PENDING) {
        return UDS_NRC_RESPONSE_PENDING;
    }
    if (b->commit_status != FS_OK) {
        b->last_transfer_status = (uint16_t)b->commit_status; /* the old skill stays */
        return UDS_NRC_PROGRAMMING_FAILURE;
    }
    const nvm_status_t ns = b->writer.status;
    if (ns != NVM_OK) {
        b->last_transfer_status = (uint16_t)ns;
        slots_reload(b); /* whatever storage holds now */
        return UDS_NRC_PROGRAMMING_FAILURE;
    }
    /* the cache swapped in slices (SLOTS_COMMIT_SWAP): UDS runs at the start of a tick and
     * downloads only in IDLE */
    commit_done(b);
    *crc_out = b->parser.crc;
    return UDS_NRC_OK;
}

void slots_abort(slots_t *b)
{
    commit_cut(b);
    if (b->last_transfer_status == FS_TRANSFER_IN_PROGRESS) {
        b->last_transfer_status = FS_TRANSFER_INTERRUPTED; /* interrupted: nothing was written */
    }
    fs_job_reset(&b->commit); /* a commit in progress ends with the transfer */
    fs_job_reset(&b->read);
    b->xfer_size = 0u;
}

void slots_refuse_commit(slots_t *b)
{
    if (fs_job_running(&b->commit) && b->commit_stage == SLOTS_COMMIT_SWAP) {
        commit_cut(b); /* its record is written: the slot holds the new skill */
        fs_job_reset(&b->commit);
        return;
    }
    fs_job_reset(&b->commit);
    b->last_transfer_status = FS_TRANSFER_INTERRUPTED;
}

/* The read-back of slot's record, its CRC checked a slice a call; b->read_nrc its answer. */
static fs_job_status_t read_job(slots_t *b, uint32_t slot, uint32_t size)
{
    fs_job_t *j = &b->read;
    FS_JOB_BEGIN(j);
    b->read_nrc = UDS_NRC_REQUEST_OUT_OF_RANGE;
    if (slot < 1u || slot > SLOTS_N || !b->nvm_ok) {
        FS_JOB_EXIT(j);
    }
    b->read_nrc = UDS_NRC_UPLOAD_DOWNLOAD_NOT_ACCEPTED; /* an empty or unreadable slot */
    if (nvm_read_begin(&b->reader, &b->nvm, (uint16_t)(slot - 1u), b->image, sizeof(b->image)) !=
        NVM_OK) {
        FS_JOB_EXIT(j);
    }
    FS_JOB_YIELD(j); /* the request's own tick reads nothing more */
    while (!nvm_read_run(&b->reader, SLOTS_READ_UNITS_PER_TICK)) {
        FS_JOB_YIELD(j);
    }
    if (b->reader.status == NVM_OK) {
        b->read_nrc = (size == b->reader.len) ? UDS_NRC_OK : UDS_NRC_REQUEST_OUT_OF_RANGE;
        b->xfer_size = (size == b->reader.len) ? b->reader.len : b->xfer_size;
    }
    FS_JOB_END(j);
}

uint8_t slots_upload_begin(slots_t *b, uint32_t slot, uint32_t size)
{
    return (read_job(b, slot, size) == FS_JOB_DONE) ? b->read_nrc : UDS_NRC_RESPONSE_PENDING;
}

uint8_t slots_upload_data(const slots_t *b, uint32_t offset, uint8_t *out, uint16_t len)
{
    if (offset > b->xfer_size || len > b->xfer_size - offset) {
        return UDS_NRC_REQUEST_OUT_OF_RANGE;
    }
    memcpy(out, &b->image[offset], len);
    return UDS_NRC_OK;
}

uint8_t slots_erase(slots_t *b, uint32_t slot)
{
    if (!b->nvm_ok) {
        return UDS_NRC_CONDITIONS_NOT_CORRECT;
    }
    if (nvm_erase_slot(&b->nvm, (uint16_t)(slot - 1u)) != NVM_OK) {
        return UDS_NRC_PROGRAMMING_FAILURE;
    }
    b->valid[slot - 1u] = false;
    return UDS_NRC_OK;
}

/* Firmware update receiver (fwu.h). */
#include "fwu.h"

#include <stddef.h>
#include <string.h>

void fwu_init(fwu_t *f, boot_t *boot)
{
    memset(f, 0, sizeof *f);
    f->boot = boot;
    f->phase = FWU_IDLE;
}

static boot_status_t refuse(fwu_t *f, boot_status_t st)
{
    f->last = st;
    if (f->phase == FWU_RECEIVING) {
        f->phase = FWU_IDLE;
    }
    return st;
}

/* Program n bytes at slot offset off (n a multiple of the write unit, inside one sector),
 * erasing the sector first if this is its first byte. */
static boot_status_t program(fwu_t *f, uint32_t off, const uint8_t *p, uint32_t n)
{
    const boot_config_t *cfg = f->boot->cfg;
    const fls_dev_t *dev = cfg->app_dev;
    const uint32_t base = cfg->slot_addr[f->slot];
    while (off + n > f->erased) {
        if (dev->erase(dev->ctx, (base + f->erased) / dev->sector_size) != 0 ||
            fls_wait(dev) != 0) {
            return BOOT_ERR_FLASH;
        }
        f->erased += dev->sector_size;
    }
    return dev->program(dev->ctx, base + off, p, n) == 0 ? BOOT_OK : BOOT_ERR_FLASH;
}

/* Stage len bytes: full write units go to flash, at most one unit waits in tail. */
static boot_status_t put(fwu_t *f, const uint8_t *p, uint32_t len)
{
    const fls_dev_t *dev = f->boot->cfg->app_dev;
    const uint32_t wu = dev->write_unit;
    while (len > 0u) {
        if (f->tail_len > 0u || len < wu) {
            uint32_t n = wu - f->tail_len;
            if (n > len) {
                n = len;
            }
            memcpy(&f->tail[f->tail_len], p, n);
            f->tail_len += n;
            p += n;
            len -= n;
            if (f->tail_len == wu) {
                boot_status_t st = program(f, f->programmed, f->tail, wu);
                if (st != BOOT_OK) {
                    return st;
                }
                f->programmed += wu;
                f->tail_len = 0u;
            }
            continue;
        }
        const uint32_t to_sector_end = dev->sector_size - (f->programmed % dev->sector_size);
        uint32_t n = len - (len % wu);
        if (n > to_sector_end) {
            n = to_sector_end;
        }
        boot_status_t st = program(f, f->programmed, p, n);
        if (st != BOOT_OK) {
            return st;
        }
        f->programmed += n;
        p += n;
        len -= n;
    }
    return BOOT_OK;
}

boot_status_t fwu_begin(fwu_t *f, bool authorised, uint32_t size)
{
    if (!authorised) {
        return refuse(f, FWU_ERR_LOCKED);
    }
    boot_t *b = f->boot;
    const boot_config_t *cfg = b->cfg;
    if (b->test_boot) {
        return refuse(f, FWU_ERR_TEST_PENDING); /* the other slot is our fallback */
    }
    if (size < BOOT_IMAGE_OVERHEAD + 1u) {
        return refuse(f, FWU_ERR_RANGE);
    }
    if (size > cfg->slot_size) {
        return refuse(f, BOOT_ERR_TOO_LARGE);
    }
    const uint8_t slot = boot_inactive_slot(b);
    if (b->state.test_slot == slot) {
        /* a test marked earlier (no reset since): cancel it before its slot is overwritten */
        boot_state_t s = b->state;
        s.test_slot = BOOT_SLOT_NONE;
        s.test_attempts = 0u;
        s.test_flags = 0u;
        if (boot_state_store(cfg, &s) != BOOT_OK) {
            return refuse(f, BOOT_ERR_FLASH);
        }
        b->state = s;
    }
    f->phase = FWU_RECEIVING;
    f->slot = slot;
    f->size = size;
    f->received = 0u;
    f->programmed = 0u;
    f->erased = 0u;
    f->erasing = false;
    f->header_ok = false;
    f->tail_len = 0u;
    f->crc32 = 0u;
    f->image_version = 0u;
    f->last = BOOT_OK;
    return BOOT_OK;
}

static boot_status_t check_header(fwu_t *f)
{
    boot_image_header_t h;
    boot_status_t st = boot_image_parse_header(f->hdr, f->boot->cfg->target_id, &h);
    if (st != BOOT_OK) {
        return st;
    }
    const uint32_t total = boot_image_total_len(&h);
    if (f->size < total) {
        return BOOT_ERR_TRUNCATED;
    }
    if (f->size > total) {
        return BOOT_ERR_FORMAT; /* trailing bytes after the tag */
    }
    f->image_version = h.fw_version;
    f->header_ok = true;
    return BOOT_OK;
}

boot_status_t fwu_data(fwu_t *f, bool authorised, uint32_t offset, const uint8_t *data,
                       uint32_t len)
{
    if (!authorised) {
        return refuse(f, FWU_ERR_LOCKED);
    }
    if (f->phase != FWU_RECEIVING || offset != f->received || data == NULL) {
        return refuse(f, FWU_ERR_SEQUENCE);
    }
    if (len > f->size - f->received) {
        return refuse(f, FWU_ERR_OVERRUN);
    }
    /* Keep a copy of the header to check it before anything of the payload is written. */
    if (f->received < BOOT_IMAGE_HEADER_SIZE) {
        uint32_t n = BOOT_IMAGE_HEADER_SIZE - f->received;
        if (n > len) {
            n = len;
        }
        memcpy(&f->hdr[f->received], data, n);
        if (f->received + n == BOOT_IMAGE_HEADER_SIZE && !f->header_ok) {
            boot_status_t st = check_header(f);
            if (st != BOOT_OK) {
                return refuse(f, st);
            }
        }
    }
    boot_status_t st = put(f, data, len);
    if (st != BOOT_OK) {
        return refuse(f, st);
    }
    f->crc32 = nvm_crc32(f->crc32, data, len);
    f->received += len;
    return BOOT_OK;
}

/* True once the image's header is in and valid counting the next k bytes of the block (its
 * bytes copied as fwu_data copies them): nothing is erased for a header that fwu_data refuses. */
static bool header_ok_ahead(fwu_t *f, uint32_t k)
{
    if (f->received >= BOOT_IMAGE_HEADER_SIZE) {
        return true;
    }
    const uint32_t n = BOOT_IMAGE_HEADER_SIZE - f->received;
    if (k < n) {
        return false; /* not whole in this piece: program() erases when it gets there */
    }
    if (!f->header_ok) {
        memcpy(&f->hdr[f->received], &f->block_src[f->block_pos], n);
        (void)check_header(f); /* a refusal comes from fwu_data, which checks it again */
    }
    return f->header_ok;
}

/* A device with a background erase (fls.h busy): one call of a step polls the erase in
 * progress (the poll that sees it end is its own call too: a device that erases in slices does
 * the last one in it), or starts the erase of the sector that the next k bytes of the block reach
 * first; *done false then (the piece waits for the next call). Otherwise *done true. */
static boot_status_t erase_ahead(fwu_t *f, uint32_t k, bool *done)
{
    const fls_dev_t *dev = f->boot->cfg->app_dev;
    *done = true;
    if (dev->busy == NULL) {
        return BOOT_OK;
    }
    const int b = dev->busy(dev->ctx);
    if (b != 0 || f->erasing) {
        f->erasing = b > 0;
        *done = false;
        return b < 0 ? BOOT_ERR_FLASH : BOOT_OK;
    }
    if (f->programmed + f->tail_len + k > f->erased && header_ok_ahead(f, k)) {
        const uint32_t base = f->boot->cfg->slot_addr[f->slot];
        if (dev->erase(dev->ctx, (base + f->erased) / dev->sector_size) != 0) {
            return BOOT_ERR_FLASH;
        }
        f->erased += dev->sector_size;
        f->erasing = true;
        *done = false;
    }
    return BOOT_OK;
}

/* One call's piece of the block in progress: the erase ahead (a call of its own while a
 * background erase runs), else at most max_bytes of the block programmed through fwu_data. True
 * once the block ended, f->block_status its verdict. */
static bool block_piece(fwu_t *f, bool authorised, uint32_t max_bytes)
{
    const uint32_t rest = f->block_len - f->block_pos;
    uint32_t k = rest < max_bytes ? rest : max_bytes;
    if (!f->header_ok && f->received < BOOT_IMAGE_HEADER_SIZE) {
        /* a header not yet found good is taken whole (pieces may be shorter): the erase starts
         * only for a good one, and fwu_data refuses a bad one before anything is programmed */
        const uint32_t hk = BOOT_IMAGE_HEADER_SIZE - f->received;
        k = hk <= k ? k : (hk < rest ? hk : rest);
    }
    /* fwu_data's first checks before anything is erased (its refusals come from it) */
    bool erased = true;
    const boot_status_t es = (authorised && f->phase == FWU_RECEIVING) ? erase_ahead(f, k, &erased)
                                                                       : BOOT_OK;
    if (es != BOOT_OK) {
        f->block_status = refuse(f, es);
        return true;
    }
    if (!erased) {
        return false;
    }
    f->block_status = fwu_data(f, authorised, f->block_off + f->block_pos,
                               &f->block_src[f->block_pos], k);
    f->block_pos += k;
    return f->block_status != BOOT_OK || f->block_pos >= f->block_len;
}

/* A TransferData block in pieces, a job: the request's own call only takes the block, each later
 * call one piece (block_piece). */
static fs_job_status_t block_job(fwu_t *f, bool authorised, uint32_t max_bytes)
{
    FS_JOB_BEGIN(&f->block_job);
    FS_JOB_YIELD(&f->block_job);
    while (!block_piece(f, authorised, max_bytes)) {
        FS_JOB_YIELD(&f->block_job);
    }
    FS_JOB_END(&f->block_job);
}

boot_status_t fwu_data_step(fwu_t *f, bool authorised, uint32_t offset, const uint8_t *data,
                            uint32_t len, uint32_t max_bytes, bool *done)
{
    *done = true;
    if (data != NULL) {
        fs_job_reset(&f->block_job);
        if (!authorised) {
            return refuse(f, FWU_ERR_LOCKED);
        }
        if (f->phase != FWU_RECEIVING || offset != f->received) {
            return refuse(f, FWU_ERR_SEQUENCE);
        }
        if (len > f->size - f->received || len > FWU_BLOCK_MAX) {
            return refuse(f, FWU_ERR_OVERRUN);
        }
        if (len == 0u) {
            return BOOT_OK;
        }
        f->block_src = data; /* the caller keeps it until the block is done: no copy */
        f->block_off = offset;
        f->block_len = len;
        f->block_pos = 0u;
        (void)block_job(f, authorised, max_bytes); /* its first call: the block taken */
        *done = false;
        return BOOT_OK;
    }
    if (!fs_job_running(&f->block_job)) {
        return refuse(f, FWU_ERR_SEQUENCE);
    }
    if (block_job(f, authorised, max_bytes) == FS_JOB_PENDING) {
        *done = false;
        return BOOT_OK;
    }
    return f->block_status;
}

/* The staged tail to flash (padded with 0xFF to a write unit). */
static boot_status_t flush_tail(fwu_t *f)
{
    if (f->tail_len == 0u) {
        return BOOT_OK;
    }
    const uint32_t wu = f->boot->cfg->app_dev->write_unit;
    memset(&f->tail[f->tail_len], 0xFF, wu - f->tail_len);
    boot_status_t st = program(f, f->programmed, f->tail, wu);
    if (st == BOOT_OK) {
        f->programmed += wu;
        f->tail_len = 0u;
    }
    return st;
}

/* The received image's verification, a job: the request's own call only yields (its tick also
 * took and answered the request), the next flushes the tail and sets the verification up (the
 * header read and the key), then rounds SHA-256 rounds a call, then the state's wipe and the
 * verdict (f->verify_status) in a call of their own. */
static fs_job_status_t verify_job(fwu_t *f, uint32_t rounds)
{
    const boot_config_t *cfg = f->boot->cfg;
    FS_JOB_BEGIN(&f->verify_job);
    FS_JOB_YIELD(&f->verify_job);
    f->verify_status = flush_tail(f);
    if (f->verify_status != BOOT_OK) {
        FS_JOB_EXIT(&f->verify_job);
    }
    boot_verify_begin(&f->verify, cfg->app_dev, cfg->slot_addr[f->slot], cfg->slot_size,
                      cfg->target_id, cfg->key, cfg->key_len);
    FS_JOB_YIELD(&f->verify_job);
    while (!boot_verify_run(&f->verify, rounds)) {
        FS_JOB_YIELD(&f->verify_job);
    }
    FS_JOB_YIELD(&f->verify_job); /* the slot is not usable until the verdict */
    f->verify_status = f->verify.status;
    boot_verify_wipe(&f->verify);
    FS_JOB_END(&f->verify_job);
}

/* A verification abandoned: its state wiped, the next transfer exit starts it over. */
static void verify_abandon(fwu_t *f)
{
    if (fs_job_running(&f->verify_job)) {
        boot_verify_wipe(&f->verify);
        fs_job_reset(&f->verify_job);
    }
}

boot_status_t fwu_end_step(fwu_t *f, bool authorised, uint32_t *crc32_out, uint32_t rounds,
                           bool *done)
{
    *done = true;
    if (!authorised) {
        verify_abandon(f);
        return refuse(f, FWU_ERR_LOCKED);
    }
    if (f->phase != FWU_RECEIVING || f->received != f->size) {
        verify_abandon(f);
        return refuse(f, FWU_ERR_SEQUENCE);
    }
    if (verify_job(f, rounds) == FS_JOB_PENDING) {
        *done = false;
        return BOOT_OK;
    }
    if (f->verify_status != BOOT_OK) {
        return refuse(f, f->verify_status);
    }
    if (crc32_out != NULL) {
        *crc32_out = f->crc32;
    }
    f->phase = FWU_RECEIVED;
    return BOOT_OK;
}

boot_status_t fwu_end(fwu_t *f, bool authorised, uint32_t *crc32_out)
{
    bool done = false;
    boot_status_t st;
    do {
        st = fwu_end_step(f, authorised, crc32_out, UINT32_MAX, &done);
    } while (!done);
    return st;
}

void fwu_abort(fwu_t *f)
{
    fs_job_reset(&f->block_job);
    verify_abandon(f);
    if (f->phase == FWU_RECEIVING) {
        f->phase = FWU_IDLE;
    }
}

boot_status_t fwu_mark_test(fwu_t *f, bool authorised, uint8_t options)
{
    if (!authorised) {
        return refuse(f, FWU_ERR_LOCKED);
    }
    if (f->phase != FWU_RECEIVED && f->phase != FWU_MARKED) {
        return refuse(f, FWU_ERR_SEQUENCE);
    }
    boot_status_t st = boot_mark_test(f->boot, f->slot, options);
    if (st != BOOT_OK) {
        return refuse(f, st);
    }
    f->phase = FWU_MARKED;
    return BOOT_OK;
}

boot_status_t fwu_confirm(fwu_t *f)
{
    boot_status_t st = boot_confirm(f->boot);
    return st == BOOT_OK ? BOOT_OK : refuse(f, st);
}

uint16_t fwu_status(const fwu_t *f, uint8_t *out, uint16_t cap)
{
    if (out == NULL) {
        return 0u;
    }
    const boot_t *b = f->boot;
    const bool running = b->running_slot < BOOT_SLOT_COUNT;
    const fs_wire_fwu_status_t v = {
        .running_version = running ? b->running.fw_version : 0u,
        .running_slot = b->running_slot,
        .on_test = b->test_boot != 0u ? 1u : 0u,
        .active_slot = b->state.active_slot,
        .test_slot = b->state.test_slot,
        .path = (uint8_t)b->path,
        .target = (uint8_t)b->cfg->target_id,
        .last_refusal = (uint16_t)(f->last != BOOT_OK ? f->last : b->refusal),
        .received_version = f->image_version,
        .phase = (uint8_t)f->phase,
    };
    return fs_wire_fwu_status_pack(&v, out, cap);
}

uint8_t fwu_nrc(boot_status_t st)
{
    return boot_status_nrc(st);
}

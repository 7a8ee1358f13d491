/* Slot storage: see nvm.h for the record layout and the power-loss argument. */
#include "nvm.h"

#include <stddef.h>
#include <string.h>

#define NVM_CHUNK 256u /* bytes per program/read call (one power-loss point each) */
#define NVM_SEQ_OFF 8u
#define NVM_CRC_COVER 16u /* header bytes covered by the CRC */

/* ---- CRC-32 (zlib: reflected polynomial 0xEDB88320, init/final xor 0xFFFFFFFF) ----------- */

static const uint32_t crc_nibble[16] = {
    0x00000000u, 0x1DB71064u, 0x3B6E20C8u, 0x26D930ACu, 0x76DC4190u, 0x6B6B51F4u,
    0x4DB26158u, 0x5005713Cu, 0xEDB88320u, 0xF00F9344u, 0xD6D6A3E8u, 0xCB61B38Cu,
    0x9B64C2B0u, 0x86D3D2D4u, 0xA00AE278u, 0xBDBDF21Cu,
};

uint32_t nvm_crc32(uint32_t crc, const uint8_t *data, uint32_t len)
{
    uint32_t c = ~crc;
    if (data == NULL) {
        return crc;
    }
    for (uint32_t i = 0u; i < len; i++) {
        c ^= data[i];
        c = (c >> 4) ^ crc_nibble[c & 0x0Fu];
        c = (c >> 4) ^ crc_nibble[c & 0x0Fu];
    }
    return ~c;
}

/* ---- little-endian helpers ------------------------------------------------------------- */

static uint32_t rd32(const uint8_t *p)
{
    return (uint32_t)p[0] | ((uint32_t)p[1] << 8) | ((uint32_t)p[2] << 16) | ((uint32_t)p[3] << 24);
}

static uint16_t rd16(const uint8_t *p)
{
    return (uint16_t)((uint32_t)p[0] | ((uint32_t)p[1] << 8));
}

static void wr32(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)v;
    p[1] = (uint8_t)(v >> 8);
    p[2] = (uint8_t)(v >> 16);
    p[3] = (uint8_t)(v >> 24);
}

static void wr16(uint8_t *p, uint16_t v)
{
    p[0] = (uint8_t)v;
    p[1] = (uint8_t)(v >> 8);
}

/* ---- record layout --------------------------------------------------------------------- */

static uint32_t unit_of(uint32_t write_unit)
{
    return (write_unit < NVM_COMMIT_SIZE) ? NVM_COMMIT_SIZE : write_unit;
}

/* Offset of the commit word for a payload of len bytes. */
static uint32_t commit_offset(uint32_t len, uint32_t write_unit)
{
    const uint32_t u = unit_of(write_unit);
    return NVM_HEADER_SIZE + ((len + u - 1u) / u) * u;
}

/* Total record size (header, padded payload, commit unit). */
static uint32_t record_size(uint32_t len, uint32_t write_unit)
{
    return commit_offset(len, write_unit) + unit_of(write_unit);
}

static bool write_unit_ok(uint32_t wu)
{
    return wu >= 1u && wu <= 16u && (wu & (wu - 1u)) == 0u;
}

uint32_t nvm_payload_max(const fls_dev_t *dev)
{
    if (dev == NULL || !write_unit_ok(dev->write_unit)) {
        return 0u;
    }
    const uint32_t u = unit_of(dev->write_unit);
    if (dev->sector_size < NVM_HEADER_SIZE + 2u * u) {
        return 0u;
    }
    /* largest multiple of u that leaves room for the header and the commit unit */
    return ((dev->sector_size - NVM_HEADER_SIZE - u) / u) * u;
}

/* Checks on the 32-byte header alone; the largest acceptable length is len_max. */
static nvm_status_t header_check(const uint8_t *h, uint16_t expected_slot, uint32_t len_max,
                                 nvm_record_info_t *out)
{
    if (rd32(h) != NVM_RECORD_MAGIC) {
        return NVM_ERR_REC_MAGIC;
    }
    if (rd16(h + 4u) != NVM_RECORD_VERSION) {
        return NVM_ERR_REC_VERSION;
    }
    const uint16_t slot = rd16(h + 6u);
    if (expected_slot != 0xFFFFu && slot != expected_slot) {
        return NVM_ERR_SLOT;
    }
    const uint32_t length = rd32(h + 12u);
    if (length > len_max) {
        return NVM_ERR_REC_LENGTH;
    }
    out->slot = slot;
    out->seq = rd32(h + NVM_SEQ_OFF);
    out->length = length;
    out->crc32 = rd32(h + 16u);
    out->payload_offset = NVM_HEADER_SIZE;
    return NVM_OK;
}

nvm_status_t nvm_record_parse(const uint8_t *buf, uint32_t len, uint16_t expected_slot,
                              nvm_record_info_t *out)
{
    if (buf == NULL || out == NULL) {
        return NVM_ERR_NULL_ARG;
    }
    if (len < NVM_HEADER_SIZE) {
        return NVM_ERR_REC_LENGTH;
    }
    /* A buffer of len bytes holds at most len - header - commit bytes of payload (with the
     * smallest commit unit, 4 bytes). */
    const uint32_t len_max = (len >= NVM_HEADER_SIZE + NVM_COMMIT_SIZE)
                                 ? len - NVM_HEADER_SIZE - NVM_COMMIT_SIZE
                                 : 0u;
    nvm_record_info_t info;
    nvm_status_t s = header_check(buf, expected_slot, len_max, &info);
    if (s != NVM_OK) {
        return s;
    }
    /* The commit offset depends on the write unit; the buffer form assumes the smallest unit
     * (4 bytes), the layout every geometry with write_unit <= 4 produces. */
    const uint32_t c_off = commit_offset(info.length, NVM_COMMIT_SIZE);
    if (c_off + NVM_COMMIT_SIZE > len) {
        return NVM_ERR_REC_LENGTH;
    }
    if (rd32(buf + c_off) != NVM_COMMIT_WORD) {
        return NVM_ERR_REC_UNCOMMITTED;
    }
    uint32_t crc = nvm_crc32(0u, buf, NVM_CRC_COVER);
    crc = nvm_crc32(crc, buf + NVM_HEADER_SIZE, info.length);
    if (crc != info.crc32) {
        return NVM_ERR_REC_CRC;
    }
    *out = info;
    return NVM_OK;
}

nvm_status_t nvm_record_build(uint16_t slot, uint32_t seq, const uint8_t *payload, uint32_t len,
                              uint32_t write_unit, uint8_t *out, uint32_t out_cap,
                              uint32_t *out_len)
{
    if (out == NULL || out_len == NULL || (payload == NULL && len != 0u)) {
        return NVM_ERR_NULL_ARG;
    }
    if (!write_unit_ok(write_unit)) {
        return NVM_ERR_GEOMETRY;
    }
    if (len > 0x7FFFFFFFu - 64u) {
        return NVM_ERR_TOO_LARGE;
    }
    const uint32_t total = record_size(len, write_unit);
    if (total > out_cap) {
        return NVM_ERR_BUFFER;
    }
    (void)memset(out, 0xFF, total);
    wr32(out, NVM_RECORD_MAGIC);
    wr16(out + 4u, (uint16_t)NVM_RECORD_VERSION);
    wr16(out + 6u, slot);
    wr32(out + NVM_SEQ_OFF, seq);
    wr32(out + 12u, len);
    if (len != 0u) {
        (void)memcpy(out + NVM_HEADER_SIZE, payload, len);
    }
    uint32_t crc = nvm_crc32(0u, out, NVM_CRC_COVER);
    crc = nvm_crc32(crc, payload, len);
    wr32(out + 16u, crc);
    wr32(out + commit_offset(len, write_unit), NVM_COMMIT_WORD);
    *out_len = total;
    return NVM_OK;
}

/* ---- flash-backed operations ----------------------------------------------------------- */

static uint32_t copy_addr(const nvm_t *n, uint16_t slot, uint8_t copy)
{
    return ((uint32_t)slot * 2u + copy) * n->dev->sector_size;
}

/* The head of one copy's scan: header checks, the commit word, and the CRC of the header's
 * covered bytes into *crc. */
static nvm_status_t scan_head(const nvm_t *n, uint16_t slot, uint8_t copy, nvm_record_info_t *info,
                              uint32_t *crc)
{
    const fls_dev_t *d = n->dev;
    const uint32_t base = copy_addr(n, slot, copy);
    uint8_t buf[NVM_HEADER_SIZE];
    if (d->read(d->ctx, base, buf, NVM_HEADER_SIZE) != 0) {
        return NVM_ERR_FLASH;
    }
    const nvm_status_t s = header_check(buf, slot, nvm_payload_max(d), info);
    if (s != NVM_OK) {
        return s;
    }
    *crc = nvm_crc32(0u, buf, NVM_CRC_COVER);
    uint8_t cw[4];
    if (d->read(d->ctx, base + commit_offset(info->length, d->write_unit), cw, 4u) != 0) {
        return NVM_ERR_FLASH;
    }
    return (rd32(cw) != NVM_COMMIT_WORD) ? NVM_ERR_REC_UNCOMMITTED : NVM_OK;
}

/* The payload's CRC from off, one NVM_CHUNK at most, continued in *crc. */
static nvm_status_t scan_chunk(const nvm_t *n, uint16_t slot, uint8_t copy,
                               const nvm_record_info_t *info, uint32_t off, uint32_t *crc)
{
    const fls_dev_t *d = n->dev;
    uint8_t buf[NVM_CHUNK];
    const uint32_t k = (info->length - off < NVM_CHUNK) ? info->length - off : NVM_CHUNK;
    if (d->read(d->ctx, copy_addr(n, slot, copy) + NVM_HEADER_SIZE + off, buf, k) != 0) {
        return NVM_ERR_FLASH;
    }
    *crc = nvm_crc32(*crc, buf, k);
    return NVM_OK;
}

/* Scan one copy in place (streaming, NVM_CHUNK bytes of RAM). */
static nvm_status_t scan_copy(const nvm_t *n, uint16_t slot, uint8_t copy, nvm_record_info_t *info)
{
    uint32_t crc = 0u;
    nvm_status_t s = scan_head(n, slot, copy, info, &crc);
    for (uint32_t off = 0u; s == NVM_OK && off < info->length; off += NVM_CHUNK) {
        s = scan_chunk(n, slot, copy, info, off, &crc);
    }
    if (s != NVM_OK) {
        return s;
    }
    return (crc == info->crc32) ? NVM_OK : NVM_ERR_REC_CRC;
}

/* serial-number arithmetic: a newer than b */
static bool seq_newer(uint32_t a, uint32_t b)
{
    return (int32_t)(a - b) > 0;
}

/* The slot's directory entry from the scans of its two copies (the newest valid one wins). */
static void dir_set(nvm_t *n, uint16_t slot, const bool ok[2], const nvm_record_info_t inf[2])
{
    nvm_dir_entry_t *e = &n->dir[slot];
    (void)memset(e, 0, sizeof *e);
    if (!ok[0] && !ok[1]) {
        return;
    }
    uint8_t best = (uint8_t)(ok[0] ? 0u : 1u);
    if (ok[0] && ok[1] && seq_newer(inf[1].seq, inf[0].seq)) {
        best = 1u;
    }
    e->valid = 1u;
    e->copy = best;
    e->both_valid = (ok[0] && ok[1]) ? 1u : 0u;
    e->seq = inf[best].seq;
    e->length = inf[best].length;
    e->crc32 = inf[best].crc32;
}

static void rescan_slot(nvm_t *n, uint16_t slot)
{
    nvm_record_info_t inf[2];
    bool ok[2];
    for (uint8_t c = 0u; c < 2u; c++) {
        ok[c] = scan_copy(n, slot, c, &inf[c]) == NVM_OK;
    }
    dir_set(n, slot, ok, inf);
}

nvm_status_t nvm_init(nvm_t *n, const fls_dev_t *dev)
{
    if (n == NULL || dev == NULL || dev->erase == NULL || dev->program == NULL ||
        dev->read == NULL) {
        return NVM_ERR_NULL_ARG;
    }
    (void)memset(n, 0, sizeof *n);
    if (nvm_payload_max(dev) == 0u || dev->sector_count < 2u) {
        return NVM_ERR_GEOMETRY;
    }
    n->dev = dev;
    const uint32_t slots = dev->sector_count / 2u;
    n->n_slots = (uint16_t)((slots > NVM_MAX_SLOTS) ? NVM_MAX_SLOTS : slots);
    for (uint16_t s = 0u; s < n->n_slots; s++) {
        rescan_slot(n, s);
    }
    return NVM_OK;
}

const nvm_dir_entry_t *nvm_dir(const nvm_t *n, uint16_t slot)
{
    if (n == NULL || slot >= n->n_slots) {
        return NULL;
    }
    return &n->dir[slot];
}

/* Program len bytes of src at addr in NVM_CHUNK pieces, padding the last one with 0xFF to the
 * write unit (programming 0xFF leaves erased bytes erased). */
static nvm_status_t program_range(const fls_dev_t *d, uint32_t addr, const uint8_t *src,
                                  uint32_t len)
{
    uint8_t buf[NVM_CHUNK];
    const uint32_t wu = d->write_unit;
    for (uint32_t off = 0u; off < len; off += NVM_CHUNK) {
        const uint32_t k = (len - off < NVM_CHUNK) ? len - off : NVM_CHUNK;
        const uint32_t kp = ((k + wu - 1u) / wu) * wu;
        (void)memset(buf, 0xFF, kp);
        (void)memcpy(buf, src + off, k);
        if (d->program(d->ctx, addr + off, buf, kp) != 0) {
            return NVM_ERR_FLASH;
        }
    }
    return NVM_OK;
}

/* Compare flash at addr with src (len bytes). */
static nvm_status_t verify_range(const fls_dev_t *d, uint32_t addr, const uint8_t *src,
                                 uint32_t len)
{
    uint8_t buf[NVM_CHUNK];
    for (uint32_t off = 0u; off < len; off += NVM_CHUNK) {
        const uint32_t k = (len - off < NVM_CHUNK) ? len - off : NVM_CHUNK;
        if (d->read(d->ctx, addr + off, buf, k) != 0) {
            return NVM_ERR_FLASH;
        }
        if (memcmp(buf, src + off, k) != 0) {
            return NVM_ERR_VERIFY;
        }
    }
    return NVM_OK;
}

/* The stages of a write, in nvm_write's order. */
enum {
    NW_CRC,    /* the record's CRC over the payload, NVM_CHUNK bytes a unit */
    NW_ERASE,  /* erase the target copy */
    NW_PROG,   /* the header, then the payload, NVM_CHUNK bytes a unit */
    NW_VERIFY, /* read back and compare, the same pieces */
    NW_COMMIT, /* the commit word */
    NW_SCAN,   /* the slot's two copies scanned as at boot, NVM_CHUNK bytes a unit */
    NW_DONE
};

nvm_status_t nvm_write_begin(nvm_writer_t *w, nvm_t *n, uint16_t slot, const uint8_t *payload,
                             uint32_t len)
{
    w->stage = NW_DONE;
    w->status = NVM_OK;
    if (n == NULL || n->dev == NULL || (payload == NULL && len != 0u)) {
        w->status = NVM_ERR_NULL_ARG;
    } else if (slot >= n->n_slots) {
        w->status = NVM_ERR_SLOT;
    } else if (len > nvm_payload_max(n->dev)) {
        w->status = NVM_ERR_TOO_LARGE;
    }
    if (w->status != NVM_OK) {
        return w->status;
    }
    const nvm_dir_entry_t *e = &n->dir[slot];
    w->n = n;
    w->payload = payload;
    w->len = len;
    w->slot = slot;
    /* Target: the copy that does not hold the newest record. */
    w->target = (e->valid != 0u) ? (uint8_t)(1u - e->copy) : 0u;
    w->seq = (e->valid != 0u) ? e->seq + 1u : 1u;
    w->base = copy_addr(n, slot, w->target);
    (void)memset(w->hdr, 0xFF, sizeof w->hdr);
    wr32(w->hdr, NVM_RECORD_MAGIC);
    wr16(w->hdr + 4u, (uint16_t)NVM_RECORD_VERSION);
    wr16(w->hdr + 6u, slot);
    wr32(w->hdr + NVM_SEQ_OFF, w->seq);
    wr32(w->hdr + 12u, len);
    w->crc = nvm_crc32(0u, w->hdr, NVM_CRC_COVER);
    w->pos = 0u;
    w->scan = 0u;
    w->stage = NW_CRC;
    return NVM_OK;
}

/* One unit of the program or verify stage: the header at pos 0, then the payload piece by
 * piece (pos counts payload bytes + 1); true once the stage is done. */
static bool write_piece(nvm_writer_t *w, bool verify)
{
    const fls_dev_t *d = w->n->dev;
    if (w->pos == 0u) {
        w->status = verify ? verify_range(d, w->base, w->hdr, NVM_HEADER_SIZE)
                           : program_range(d, w->base, w->hdr, NVM_HEADER_SIZE);
        w->pos = 1u;
        return w->len == 0u;
    }
    const uint32_t off = w->pos - 1u;
    const uint32_t k = (w->len - off < NVM_CHUNK) ? w->len - off : NVM_CHUNK;
    const uint32_t addr = w->base + NVM_HEADER_SIZE + off;
    w->status = verify ? verify_range(d, addr, w->payload + off, k)
                       : program_range(d, addr, w->payload + off, k);
    w->pos += k;
    return off + k >= w->len;
}

/* One unit of the final scan (copy w->scan: its head at pos 0, then its payload's CRC); true
 * once both copies are scanned and the directory entry is set. */
static bool write_scan(nvm_writer_t *w)
{
    const uint8_t c = w->scan;
    nvm_record_info_t *inf = &w->info[c];
    bool copy_done = false;
    if (w->pos == 0u) {
        w->ok[c] = scan_head(w->n, w->slot, c, inf, &w->scan_crc) == NVM_OK;
        copy_done = !w->ok[c] || inf->length == 0u;
        w->pos = 1u;
    } else {
        const uint32_t off = w->pos - 1u;
        w->ok[c] = scan_chunk(w->n, w->slot, c, inf, off, &w->scan_crc) == NVM_OK;
        w->pos += NVM_CHUNK;
        copy_done = !w->ok[c] || off + NVM_CHUNK >= inf->length;
    }
    if (copy_done) {
        w->ok[c] = w->ok[c] && w->scan_crc == inf->crc32;
        w->pos = 0u;
        w->scan++;
    }
    if (w->scan < 2u) {
        return false;
    }
    dir_set(w->n, w->slot, w->ok, w->info);
    const nvm_dir_entry_t *ne = &w->n->dir[w->slot];
    if (w->status == NVM_OK && (ne->valid == 0u || ne->copy != w->target || ne->seq != w->seq)) {
        w->status = NVM_ERR_VERIFY;
    }
    return true;
}

bool nvm_write_run(nvm_writer_t *w, uint32_t max_units)
{
    const fls_dev_t *d = (w->stage != NW_DONE) ? w->n->dev : NULL;
    for (uint32_t u = 0u; u < max_units && w->stage != NW_DONE; u++) {
        bool next = true;
        switch (w->stage) {
        case NW_CRC: {
            const uint32_t k = (w->len - w->pos < NVM_CHUNK) ? w->len - w->pos : NVM_CHUNK;
            w->crc = nvm_crc32(w->crc, w->payload + w->pos, k);
            w->pos += k;
            next = w->pos >= w->len;
            if (next) {
                wr32(w->hdr + 16u, w->crc);
            }
            break;
        }
        case NW_ERASE:
            if (d->erase(d->ctx, (uint32_t)w->slot * 2u + w->target) != 0) {
                w->status = NVM_ERR_FLASH;
            }
            break;
        case NW_PROG: next = write_piece(w, false); break;
        /* Verify the body before committing: a record that would read back wrong never becomes
         * valid. */
        case NW_VERIFY: next = write_piece(w, true); break;
        case NW_COMMIT: {
            uint8_t cw[16];
            (void)memset(cw, 0xFF, sizeof cw);
            wr32(cw, NVM_COMMIT_WORD);
            if (d->program(d->ctx, w->base + commit_offset(w->len, d->write_unit), cw,
                           unit_of(d->write_unit)) != 0) {
                w->status = NVM_ERR_FLASH;
            }
            break;
        }
        /* Final verification through the same path as boot: scan the whole record. */
        default: next = write_scan(w); break;
        }
        if (w->status != NVM_OK && w->stage < NW_SCAN) {
            next = true; /* a failed step: straight to the scan (storage as it is now) */
            w->stage = (uint8_t)(NW_SCAN - 1u);
        }
        if (next) {
            w->stage++;
            w->pos = 0u;
        }
    }
    return w->stage == NW_DONE;
}

nvm_status_t nvm_write(nvm_t *n, uint16_t slot, const uint8_t *payload, uint32_t len)
{
    nvm_writer_t w;
    if (nvm_write_begin(&w, n, slot, payload, len) != NVM_OK) {
        return w.status;
    }
    while (!nvm_write_run(&w, UINT32_MAX)) {
    }
    return w.status;
}

nvm_status_t nvm_read(const nvm_t *n, uint16_t slot, uint8_t *buf, uint32_t cap, uint32_t *len)
{
    if (n == NULL || n->dev == NULL || buf == NULL || len == NULL) {
        return NVM_ERR_NULL_ARG;
    }
    if (slot >= n->n_slots) {
        return NVM_ERR_SLOT;
    }
    const nvm_dir_entry_t *e = &n->dir[slot];
    if (e->valid == 0u) {
        return NVM_ERR_EMPTY;
    }
    if (e->length > cap) {
        return NVM_ERR_BUFFER;
    }
    const fls_dev_t *d = n->dev;
    const uint32_t base = copy_addr(n, slot, e->copy);
    uint8_t hdr[NVM_HEADER_SIZE];
    if (d->read(d->ctx, base, hdr, NVM_HEADER_SIZE) != 0 ||
        d->read(d->ctx, base + NVM_HEADER_SIZE, buf, e->length) != 0) {
        return NVM_ERR_FLASH;
    }
    nvm_record_info_t info;
    nvm_status_t s = header_check(hdr, slot, nvm_payload_max(d), &info);
    if (s != NVM_OK) {
        return s;
    }
    if (info.length != e->length || info.seq != e->seq) {
        return NVM_ERR_REC_LENGTH;
    }
    uint32_t crc = nvm_crc32(0u, hdr, NVM_CRC_COVER);
    crc = nvm_crc32(crc, buf, info.length);
    if (crc != info.crc32) {
        return NVM_ERR_REC_CRC;
    }
    *len = info.length;
    return NVM_OK;
}

nvm_status_t nvm_erase_slot(nvm_t *n, uint16_t slot)
{
    if (n == NULL || n->dev == NULL) {
        return NVM_ERR_NULL_ARG;
    }
    if (slot >= n->n_slots) {
        return NVM_ERR_SLOT;
    }
    const fls_dev_t *d = n->dev;
    const nvm_dir_entry_t *e = &n->dir[slot];
    /* Older copy first: an interrupted erase leaves the newest record readable. */
    const uint8_t first = (e->valid != 0u) ? (uint8_t)(1u - e->copy) : 0u;
    nvm_status_t s = NVM_OK;
    if (d->erase(d->ctx, (uint32_t)slot * 2u + first) != 0 ||
        d->erase(d->ctx, (uint32_t)slot * 2u + (uint8_t)(1u - first)) != 0) {
        s = NVM_ERR_FLASH;
    }
    rescan_slot(n, slot);
    return s;
}

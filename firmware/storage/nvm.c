/* Slot storage: see nvm.h for the record layout and the power-loss argument. */
#include "nvm.h"

#include <stddef.h>
#include <string.h>

#define NVM_CHUNK 256u /* bytes per program/read call (one power-loss point each) */
#define NVM_SEQ_OFF 8u
#define NVM_CRC_COVER 16u /* header bytes covered by the CRC */

/* ---- CRC-32 (zlib: reflected polynomial 0xEDB88320, init/final xor 0xFFFFFFFF) ----------- */

/* One entry per byte value (1 KiB of constants): one lookup per byte, about half the
 * instructions of a nibble table on a Cortex-M (a slot's CRC runs in the control tick's slices). */
static const uint32_t crc_table[256] = {
    0x00000000u, 0x77073096u, 0xEE0E612Cu, 0x990951BAu, 0x076DC419u, 0x706AF48Fu, 0xE963A535u,
    0x9E6495A3u, 0x0EDB8832u, 0x79DCB8A4u, 0xE0D5E91Eu, 0x97D2D988u, 0x09B64C2Bu, 0x7EB17CBDu,
    0xE7B82D07u, 0x90BF1D91u, 0x1DB71064u, 0x6AB020F2u, 0xF3B97148u, 0x84BE41DEu, 0x1ADAD47Du,
    0x6DDDE4EBu, 0xF4D4B551u, 0x83D385C7u, 0x136C9856u, 0x646BA8C0u, 0xFD62F97Au, 0x8A65C9ECu,
    0x14015C4Fu, 0x63066CD9u, 0xFA0F3D63u, 0x8D080DF5u, 0x3B6E20C8u, 0x4C69105Eu, 0xD56041E4u,
    0xA2677172u, 0x3C03E4D1u, 0x4B04D447u, 0xD20D85FDu, 0xA50AB56Bu, 0x35B5A8FAu, 0x42B2986Cu,
    0xDBBBC9D6u, 0xACBCF940u, 0x32D86CE3u, 0x45DF5C75u, 0xDCD60DCFu, 0xABD13D59u, 0x26D930ACu,
    0x51DE003Au, 0xC8D75180u, 0xBFD06116u, 0x21B4F4B5u, 0x56B3C423u, 0xCFBA9599u, 0xB8BDA50Fu,
    0x2802B89Eu, 0x5F058808u, 0xC60CD9B2u, 0xB10BE924u, 0x2F6F7C87u, 0x58684C11u, 0xC1611DABu,
    0xB6662D3Du, 0x76DC4190u, 0x01DB7106u, 0x98D220BCu, 0xEFD5102Au, 0x71B18589u, 0x06B6B51Fu,
    0x9FBFE4A5u, 0xE8B8D433u, 0x7807C9A2u, 0x0F00F934u, 0x9609A88Eu, 0xE10E9818u, 0x7F6A0DBBu,
    0x086D3D2Du, 0x91646C97u, 0xE6635C01u, 0x6B6B51F4u, 0x1C6C6162u, 0x856530D8u, 0xF262004Eu,
    0x6C0695EDu, 0x1B01A57Bu, 0x8208F4C1u, 0xF50FC457u, 0x65B0D9C6u, 0x12B7E950u, 0x8BBEB8EAu,
    0xFCB9887Cu, 0x62DD1DDFu, 0x15DA2D49u, 0x8CD37CF3u, 0xFBD44C65u, 0x4DB26158u, 0x3AB551CEu,
    0xA3BC0074u, 0xD4BB30E2u, 0x4ADFA541u, 0x3DD895D7u, 0xA4D1C46Du, 0xD3D6F4FBu, 0x4369E96Au,
    0x346ED9FCu, 0xAD678846u, 0xDA60B8D0u, 0x44042D73u, 0x33031DE5u, 0xAA0A4C5Fu, 0xDD0D7CC9u,
    0x5005713Cu, 0x270241AAu, 0xBE0B1010u, 0xC90C2086u, 0x5768B525u, 0x206F85B3u, 0xB966D409u,
    0xCE61E49Fu, 0x5EDEF90Eu, 0x29D9C998u, 0xB0D09822u, 0xC7D7A8B4u, 0x59B33D17u, 0x2EB40D81u,
    0xB7BD5C3Bu, 0xC0BA6CADu, 0xEDB88320u, 0x9ABFB3B6u, 0x03B6E20Cu, 0x74B1D29Au, 0xEAD54739u,
    0x9DD277AFu, 0x04DB2615u, 0x73DC1683u, 0xE3630B12u, 0x94643B84u, 0x0D6D6A3Eu, 0x7A6A5AA8u,
    0xE40ECF0Bu, 0x9309FF9Du, 0x0A00AE27u, 0x7D079EB1u, 0xF00F9344u, 0x8708A3D2u, 0x1E01F268u,
    0x6906C2FEu, 0xF762575Du, 0x806567CBu, 0x196C3671u, 0x6E6B06E7u, 0xFED41B76u, 0x89D32BE0u,
    0x10DA7A5Au, 0x67DD4ACCu, 0xF9B9DF6Fu, 0x8EBEEFF9u, 0x17B7BE43u, 0x60B08ED5u, 0xD6D6A3E8u,
    0xA1D1937Eu, 0x38D8C2C4u, 0x4FDFF252u, 0xD1BB67F1u, 0xA6BC5767u, 0x3FB506DDu, 0x48B2364Bu,
    0xD80D2BDAu, 0xAF0A1B4Cu, 0x36034AF6u, 0x41047A60u, 0xDF60EFC3u, 0xA867DF55u, 0x316E8EEFu,
    0x4669BE79u, 0xCB61B38Cu, 0xBC66831Au, 0x256FD2A0u, 0x5268E236u, 0xCC0C7795u, 0xBB0B4703u,
    0x220216B9u, 0x5505262Fu, 0xC5BA3BBEu, 0xB2BD0B28u, 0x2BB45A92u, 0x5CB36A04u, 0xC2D7FFA7u,
    0xB5D0CF31u, 0x2CD99E8Bu, 0x5BDEAE1Du, 0x9B64C2B0u, 0xEC63F226u, 0x756AA39Cu, 0x026D930Au,
    0x9C0906A9u, 0xEB0E363Fu, 0x72076785u, 0x05005713u, 0x95BF4A82u, 0xE2B87A14u, 0x7BB12BAEu,
    0x0CB61B38u, 0x92D28E9Bu, 0xE5D5BE0Du, 0x7CDCEFB7u, 0x0BDBDF21u, 0x86D3D2D4u, 0xF1D4E242u,
    0x68DDB3F8u, 0x1FDA836Eu, 0x81BE16CDu, 0xF6B9265Bu, 0x6FB077E1u, 0x18B74777u, 0x88085AE6u,
    0xFF0F6A70u, 0x66063BCAu, 0x11010B5Cu, 0x8F659EFFu, 0xF862AE69u, 0x616BFFD3u, 0x166CCF45u,
    0xA00AE278u, 0xD70DD2EEu, 0x4E048354u, 0x3903B3C2u, 0xA7672661u, 0xD06016F7u, 0x4969474Du,
    0x3E6E77DBu, 0xAED16A4Au, 0xD9D65ADCu, 0x40DF0B66u, 0x37D83BF0u, 0xA9BCAE53u, 0xDEBB9EC5u,
    0x47B2CF7Fu, 0x30B5FFE9u, 0xBDBDF21Cu, 0xCABAC28Au, 0x53B39330u, 0x24B4A3A6u, 0xBAD03605u,
    0xCDD70693u, 0x54DE5729u, 0x23D967BFu, 0xB3667A2Eu, 0xC4614AB8u, 0x5D681B02u, 0x2A6F2B94u,
    0xB40BBE37u, 0xC30C8EA1u, 0x5A05DF1Bu, 0x2D02EF8Du,
};

uint32_t nvm_crc32(uint32_t crc, const uint8_t *data, uint32_t len)
{
    uint32_t c = ~crc;
    if (data == NULL) {
        return crc;
    }
    uint32_t i = 0u;
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
    /* four bytes a load (a little-endian word's low byte is the first): the same table steps */
    for (; i + 4u <= len; i += 4u) {
        uint32_t w;
        memcpy(&w, &data[i], sizeof w);
        c ^= w;
        c = (c >> 8) ^ crc_table[c & 0xFFu];
        c = (c >> 8) ^ crc_table[c & 0xFFu];
        c = (c >> 8) ^ crc_table[c & 0xFFu];
        c = (c >> 8) ^ crc_table[c & 0xFFu];
    }
#endif
    for (; i < len; i++) {
        c = (c >> 8) ^ crc_table[(c ^ data[i]) & 0xFFu];
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

/* The payload's CRC from off, step bytes at most (<= NVM_CHUNK), continued in *crc. */
static nvm_status_t scan_chunk(const nvm_t *n, uint16_t slot, uint8_t copy,
                               const nvm_record_info_t *info, uint32_t off, uint32_t step,
                               uint32_t *crc)
{
    const fls_dev_t *d = n->dev;
    uint8_t buf[NVM_CHUNK];
    const uint32_t m = step < NVM_CHUNK ? step : NVM_CHUNK;
    const uint32_t k = (info->length - off < m) ? info->length - off : m;
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
        s = scan_chunk(n, slot, copy, info, off, NVM_CHUNK, &crc);
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
    NW_CRC,    /* the record's CRC over the payload, NVM_SLICE_BYTES a unit */
    NW_ERASE,  /* erase the target copy */
    NW_PROG,   /* the header, then the payload, NVM_CHUNK bytes a unit */
    NW_VERIFY, /* read back and compare, the same pieces */
    NW_COMMIT, /* the commit word */
    NW_SCAN,   /* the slot's two copies scanned as at boot, NVM_SLICE_BYTES a unit */
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
        w->ok[c] = scan_chunk(w->n, w->slot, c, inf, off, NVM_SLICE_BYTES, &w->scan_crc) == NVM_OK;
        w->pos += NVM_SLICE_BYTES;
        copy_done = !w->ok[c] || off + NVM_SLICE_BYTES >= inf->length;
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
            const uint32_t k = (w->len - w->pos < NVM_SLICE_BYTES) ? w->len - w->pos
                                                                   : NVM_SLICE_BYTES;
            w->crc = nvm_crc32(w->crc, w->payload + w->pos, k);
            w->pos += k;
            next = w->pos >= w->len;
            if (next) {
                wr32(w->hdr + 16u, w->crc);
            }
            break;
        }
        case NW_ERASE:
            /* started, then (a device with a background erase) one busy() poll a unit */
            if (w->pos == 0u) {
                if (d->erase(d->ctx, (uint32_t)w->slot * 2u + w->target) != 0) {
                    w->status = NVM_ERR_FLASH;
                }
                w->pos = 1u;
                next = d->busy == NULL;
            } else {
                const int b = d->busy(d->ctx);
                if (b < 0) {
                    w->status = NVM_ERR_FLASH;
                }
                next = b <= 0;
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

nvm_status_t nvm_read_begin(nvm_reader_t *r, const nvm_t *n, uint16_t slot, uint8_t *buf,
                            uint32_t cap)
{
    (void)memset(r, 0, sizeof(*r));
    r->n = n;
    r->buf = buf;
    r->slot = slot;
    r->done = true;
    if (n == NULL || n->dev == NULL || buf == NULL) {
        r->status = NVM_ERR_NULL_ARG;
    } else if (slot >= n->n_slots) {
        r->status = NVM_ERR_SLOT;
    } else if (n->dir[slot].valid == 0u) {
        r->status = NVM_ERR_EMPTY;
    } else if (n->dir[slot].length > cap) {
        r->status = NVM_ERR_BUFFER;
    } else {
        r->base = copy_addr(n, slot, n->dir[slot].copy);
        r->done = false;
    }
    return r->status;
}

/* The reader's first unit: the record's header, checked against the directory entry. */
static nvm_status_t read_head(nvm_reader_t *r)
{
    const fls_dev_t *d = r->n->dev;
    const nvm_dir_entry_t *e = &r->n->dir[r->slot];
    uint8_t hdr[NVM_HEADER_SIZE];
    if (d->read(d->ctx, r->base, hdr, NVM_HEADER_SIZE) != 0) {
        return NVM_ERR_FLASH;
    }
    const nvm_status_t s = header_check(hdr, r->slot, nvm_payload_max(d), &r->info);
    if (s != NVM_OK) {
        return s;
    }
    if (r->info.length != e->length || r->info.seq != e->seq) {
        return NVM_ERR_REC_LENGTH;
    }
    r->crc = nvm_crc32(0u, hdr, NVM_CRC_COVER);
    return NVM_OK;
}

bool nvm_read_run(nvm_reader_t *r, uint32_t max_units)
{
    for (uint32_t u = 0u; u < max_units && !r->done; u++) {
        if (!r->head_done) {
            r->status = read_head(r);
            r->head_done = true;
        } else {
            const fls_dev_t *d = r->n->dev;
            const uint32_t k = (r->info.length - r->pos < NVM_READ_CHUNK) ? r->info.length - r->pos
                                                                          : NVM_READ_CHUNK;
            if (d->read(d->ctx, r->base + NVM_HEADER_SIZE + r->pos, r->buf + r->pos, k) != 0) {
                r->status = NVM_ERR_FLASH;
            } else {
                r->crc = nvm_crc32(r->crc, r->buf + r->pos, k);
                r->pos += k;
            }
        }
        if (r->status == NVM_OK && r->head_done && r->pos >= r->info.length) {
            r->len = r->info.length;
            r->status = r->crc == r->info.crc32 ? NVM_OK : NVM_ERR_REC_CRC;
            r->done = true;
        }
        r->done = r->done || r->status != NVM_OK;
    }
    return r->done;
}

nvm_status_t nvm_read(const nvm_t *n, uint16_t slot, uint8_t *buf, uint32_t cap, uint32_t *len)
{
    if (len == NULL) {
        return NVM_ERR_NULL_ARG;
    }
    nvm_reader_t r;
    if (nvm_read_begin(&r, n, slot, buf, cap) != NVM_OK) {
        return r.status;
    }
    while (!nvm_read_run(&r, UINT32_MAX)) {
    }
    if (r.status == NVM_OK) {
        *len = r.len;
    }
    return r.status;
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
    if (d->erase(d->ctx, (uint32_t)slot * 2u + first) != 0 || fls_wait(d) != 0 ||
        d->erase(d->ctx, (uint32_t)slot * 2u + (uint8_t)(1u - first)) != 0 || fls_wait(d) != 0) {
        s = NVM_ERR_FLASH;
    }
    rescan_slot(n, slot);
    return s;
}

/* Bootloader and update receiver (firmware/boot) on the RAM-backed flash with power-loss
 * injection (firmware/storage/fls_ram). SHA-256/HMAC themselves are tested against FIPS 180-4
 * and RFC 4231 in tests/firmware/security; here the image code is checked against an image
 * written by the Python tool (hashlib/hmac of the standard library). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "boot.h"
#include "boot_fls_window.h"
#include "boot_verify.h"
#include "fls_ram.h"
#include "fwu.h"
#include "nvm.h"
#include "sec_sha256.h"

/* Geometry: 1 KiB sectors, 8-byte write unit (so TransferData blocks leave partial units).
 *   sectors 0-1   boot state (nvm, 1 record)
 *   sectors 2-5   skills (nvm, 2 records)
 *   sectors 6-29  slot A (24 KiB), sectors 30-53 slot B */
#define SECTOR 1024u
#define WU 8u
#define SLOT_SECTORS 24u
#define N_SECTORS (6u + 2u * SLOT_SECTORS)
#define SLOT_SIZE (SLOT_SECTORS * SECTOR)
#define IMG_MAX SLOT_SIZE

static const uint8_t DEV_KEY[32] = {
    0x40, 0x41, 0x42, 0x43, 0x44, 0x45, 0x46, 0x47, 0x48, 0x49, 0x4a, 0x4b, 0x4c, 0x4d, 0x4e, 0x4f,
    0x50, 0x51, 0x52, 0x53, 0x54, 0x55, 0x56, 0x57, 0x58, 0x59, 0x5a, 0x5b, 0x5c, 0x5d, 0x5e, 0x5f};
static const uint8_t OTHER_KEY[32] = {1, 2, 3};

/* One simulated device. */
typedef struct {
    uint8_t mem[N_SECTORS * SECTOR];
    fls_ram_t ram;
    fls_dev_t flash;
    boot_fls_window_t w_state, w_skills, w_app;
    fls_dev_t state_dev, skills_dev, app_dev;
    nvm_t state_nvm, skills_nvm;
    boot_config_t cfg;
    boot_t boot;
    fwu_t fwu;
} dev_t_;

static dev_t_ D; /* static: the flash is large for a stack */

static void attach(dev_t_ *d)
{
    assert_int_equal(boot_fls_window_init(&d->w_state, &d->state_dev, &d->flash, 0u, 2u), 0);
    assert_int_equal(boot_fls_window_init(&d->w_skills, &d->skills_dev, &d->flash, 2u, 4u), 0);
    assert_int_equal(boot_fls_window_init(&d->w_app, &d->app_dev, &d->flash, 6u, 2u * SLOT_SECTORS),
                     0);
    (void)nvm_init(&d->state_nvm, &d->state_dev);
    (void)nvm_init(&d->skills_nvm, &d->skills_dev);
    memset(&d->cfg, 0, sizeof d->cfg);
    d->cfg.app_dev = &d->app_dev;
    d->cfg.slot_addr[0] = 0u;
    d->cfg.slot_addr[1] = SLOT_SIZE;
    d->cfg.slot_size = SLOT_SIZE;
    d->cfg.state_nvm = &d->state_nvm;
    d->cfg.state_slot = 0u;
    d->cfg.target_id = BOOT_TARGET_HOST;
    d->cfg.key = DEV_KEY;
    d->cfg.key_len = sizeof DEV_KEY;
    d->cfg.skill_min = 1u; /* skills of format 1 are stored (written below) */
    d->cfg.skill_max = 1u;
    d->cfg.config_min = 1u;
    d->cfg.config_max = 1u;
}

static void dev_fresh(dev_t_ *d)
{
    memset(d, 0, sizeof *d);
    fls_ram_init(&d->ram, &d->flash, d->mem, SECTOR, N_SECTORS, WU);
    attach(d);
}

/* Power back on: same memory, rescan the record stores, run the bootloader. */
static boot_status_t dev_reset(dev_t_ *d)
{
    fls_ram_power_cycle(&d->ram);
    attach(d);
    const boot_status_t st = boot_select(&d->boot, &d->cfg);
    fwu_init(&d->fwu, &d->boot);
    return st;
}

static uint32_t put_le32(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)v;
    p[1] = (uint8_t)(v >> 8);
    p[2] = (uint8_t)(v >> 16);
    p[3] = (uint8_t)(v >> 24);
    return v;
}

static void put_le16(uint8_t *p, uint16_t v)
{
    p[0] = (uint8_t)v;
    p[1] = (uint8_t)(v >> 8);
}

/* Build an image (header || payload || tag) into out; returns its length. The payload is a
 * deterministic pattern seeded by the version. */
typedef struct {
    uint32_t version;
    uint32_t target;
    uint32_t payload_len;
    uint16_t skill, skill_oldest, config, config_oldest;
    const uint8_t *key;
} img_spec_t;

static img_spec_t spec(uint32_t version)
{
    img_spec_t s = {version, BOOT_TARGET_HOST, 5000u, 1u, 1u, 1u, 1u, DEV_KEY};
    return s;
}

static uint32_t make_image(const img_spec_t *s, uint8_t *out)
{
    memset(out, 0, BOOT_IMAGE_HEADER_SIZE);
    uint8_t *pl = out + BOOT_IMAGE_HEADER_SIZE;
    for (uint32_t i = 0; i < s->payload_len; i++) {
        pl[i] = (uint8_t)((i * 31u + s->version * 7u + (i >> 8)) & 0xFFu);
    }
    put_le32(out, BOOT_IMAGE_MAGIC);
    put_le16(out + 4, BOOT_IMAGE_FORMAT_VERSION);
    put_le16(out + 6, BOOT_IMAGE_HEADER_SIZE);
    put_le32(out + 8, s->version);
    put_le32(out + 12, s->payload_len);
    put_le32(out + 16, s->target);
    put_le16(out + 24, s->skill);
    put_le16(out + 26, s->skill_oldest);
    put_le16(out + 28, s->config);
    put_le16(out + 30, s->config_oldest);
    sec_sha256(pl, s->payload_len, out + 64);
    memcpy(out + 96, "test-image", 10);
    sec_hmac_sha256(s->key, 32u, out, BOOT_IMAGE_HEADER_SIZE + s->payload_len, pl + s->payload_len);
    return BOOT_IMAGE_OVERHEAD + s->payload_len;
}

/* Factory programming: write an image straight into a slot (not through fwu). */
static void factory_program(dev_t_ *d, uint8_t slot, const uint8_t *img, uint32_t len)
{
    const uint32_t base = d->cfg.slot_addr[slot];
    for (uint32_t s = 0; s < SLOT_SECTORS; s++) {
        assert_int_equal(d->app_dev.erase(d->app_dev.ctx, base / SECTOR + s), 0);
    }
    uint8_t unit[SECTOR];
    for (uint32_t off = 0; off < len; off += SECTOR) {
        uint32_t n = len - off < SECTOR ? len - off : SECTOR;
        memset(unit, 0xFF, sizeof unit);
        memcpy(unit, img + off, n);
        uint32_t padded = (n + WU - 1u) / WU * WU;
        assert_int_equal(d->app_dev.program(d->app_dev.ctx, base + off, unit, padded), 0);
    }
}

static uint8_t IMG[IMG_MAX];
static uint8_t IMG2[IMG_MAX];

/* Stream an image through the receiver in blocks of varying size (as TransferData would). */
static boot_status_t download(dev_t_ *d, const uint8_t *img, uint32_t len, uint32_t announced)
{
    boot_status_t st = fwu_begin(&d->fwu, true, announced);
    if (st != BOOT_OK) {
        return st;
    }
    static const uint32_t blocks[] = {100u, 1021u, 7u, 4093u, 333u};
    uint32_t off = 0, k = 0;
    while (off < len) {
        uint32_t n = blocks[k++ % 5u];
        if (n > len - off) {
            n = len - off;
        }
        st = fwu_data(&d->fwu, true, off, img + off, n);
        if (st != BOOT_OK) {
            return st;
        }
        off += n;
    }
    return fwu_end(&d->fwu, true, NULL);
}

/* Device with v1.0.0 in slot A, booted and confirmed, and two skills stored. */
static const uint8_t SKILL0[40] = "FSKL\x01\x00 skill zero, format 1 .......";
static const uint8_t SKILL1[40] = "FSKL\x01\x00 skill one, format 1 ........";

static void device_with_factory_image(dev_t_ *d)
{
    dev_fresh(d);
    uint32_t len = make_image(
        &(img_spec_t){BOOT_VERSION(1, 0, 0), BOOT_TARGET_HOST, 5000u, 1, 1, 1, 1, DEV_KEY}, IMG);
    factory_program(d, 0u, IMG, len);
    assert_int_equal(nvm_write(&d->skills_nvm, 0u, SKILL0, sizeof SKILL0), NVM_OK);
    assert_int_equal(nvm_write(&d->skills_nvm, 1u, SKILL1, sizeof SKILL1), NVM_OK);
    assert_int_equal(dev_reset(d), BOOT_OK);
    assert_int_equal(d->boot.path, BOOT_PATH_FIRST);
    assert_int_equal(d->boot.running_slot, 0u);
    assert_int_equal(d->boot.running.fw_version, BOOT_VERSION(1, 0, 0));
    assert_false(d->boot.test_boot);
}

static void assert_skills_intact(dev_t_ *d)
{
    uint8_t buf[64];
    uint32_t len = 0;
    assert_int_equal(nvm_read(&d->skills_nvm, 0u, buf, sizeof buf, &len), NVM_OK);
    assert_int_equal(len, sizeof SKILL0);
    assert_memory_equal(buf, SKILL0, sizeof SKILL0);
    assert_int_equal(nvm_read(&d->skills_nvm, 1u, buf, sizeof buf, &len), NVM_OK);
    assert_memory_equal(buf, SKILL1, sizeof SKILL1);
}

/* ---- image format ---- */

static void test_golden_image_from_python(void **state)
{
    (void)state;
    FILE *fp = fopen(BOOT_VECTOR_DIR "/golden_host_1.2.3.fwimg", "rb");
    assert_non_null(fp);
    const uint32_t len = (uint32_t)fread(IMG, 1, sizeof IMG, fp);
    fclose(fp);
    assert_int_equal(len, 1160u);
    boot_image_header_t h;
    assert_int_equal(boot_image_parse_header(IMG, BOOT_TARGET_HOST, &h), BOOT_OK);
    assert_int_equal(h.fw_version, BOOT_VERSION(1, 2, 3));
    assert_int_equal(h.payload_length, 1000u);
    assert_string_equal(h.build_id, "golden-1");
    /* verify from flash: hash and tag computed by Python's hashlib/hmac */
    dev_fresh(&D);
    factory_program(&D, 1u, IMG, len);
    assert_int_equal(boot_slot_verify(&D.cfg, 1u, &h), BOOT_OK);
    /* the same bytes under another key, for another target, or with one payload bit flipped */
    D.cfg.key = OTHER_KEY;
    assert_int_equal(boot_slot_verify(&D.cfg, 1u, &h), BOOT_ERR_TAG);
    D.cfg.key = DEV_KEY;
    D.cfg.target_id = BOOT_TARGET_CORTEX_M3;
    assert_int_equal(boot_slot_verify(&D.cfg, 1u, &h), BOOT_ERR_TARGET);
    D.cfg.target_id = BOOT_TARGET_HOST;
    IMG[BOOT_IMAGE_HEADER_SIZE + 500u] ^= 0x01u;
    factory_program(&D, 1u, IMG, len);
    assert_int_equal(boot_slot_verify(&D.cfg, 1u, &h), BOOT_ERR_HASH);
}

/* The golden image verified in slices of at most `rounds` SHA-256 rounds a call: the result of the
 * one-call verification after ceil(compressions * 64 / rounds) calls or so, never sooner. */
static boot_status_t verify_sliced(uint32_t rounds, uint32_t *calls)
{
    static boot_verify_t v;
    boot_verify_begin(&v, D.cfg.app_dev, D.cfg.slot_addr[1], D.cfg.slot_size, D.cfg.target_id,
                      D.cfg.key, D.cfg.key_len);
    *calls = 1u;
    while (!boot_verify_run(&v, rounds)) {
        (*calls)++;
    }
    return v.status;
}

static void test_golden_image_verified_in_slices(void **state)
{
    (void)state;
    FILE *fp = fopen(BOOT_VECTOR_DIR "/golden_host_1.2.3.fwimg", "rb");
    assert_non_null(fp);
    const uint32_t len = (uint32_t)fread(IMG, 1, sizeof IMG, fp);
    fclose(fp);
    dev_fresh(&D);
    factory_program(&D, 1u, IMG, len);
    /* 1,000 bytes of payload: the hash 16 blocks with its padding, the MAC's inner hash 19 (key,
     * header, payload, padding) and its outer 2: 37 blocks of 64 rounds; each of the ~40 stage
     * ends (a digest, a comparison, a read) is a call of its own, after the call that compressed
     * the stage's last rounds */
    const uint32_t budgets[] = {1u, 16u, 37u, 64u};
    for (size_t i = 0; i < sizeof budgets / sizeof budgets[0]; i++) {
        uint32_t calls = 0u;
        assert_int_equal(verify_sliced(budgets[i], &calls), BOOT_OK);
        assert_true(calls >= (37u * 64u) / budgets[i]);
        assert_true(calls <= (37u * 64u) / budgets[i] + 80u);
    }
    uint32_t calls = 0u;
    D.cfg.key = OTHER_KEY;
    assert_int_equal(verify_sliced(16u, &calls), BOOT_ERR_TAG);
    D.cfg.key = DEV_KEY;
    IMG[BOOT_IMAGE_HEADER_SIZE + 999u] ^= 0x80u;
    factory_program(&D, 1u, IMG, len);
    assert_int_equal(verify_sliced(16u, &calls), BOOT_ERR_HASH);
}

/* The reference of the sliced-transfer tests: a 6,000-byte image downloaded in whole blocks on a
 * factory device, its slot's bytes into whole, its slot and CRC-32; the download then aborted. */
static uint32_t whole_download(uint8_t whole[IMG_MAX], uint8_t *slot, uint32_t *crc_whole)
{
    device_with_factory_image(&D);
    const uint32_t len = make_image(
        &(img_spec_t){BOOT_VERSION(1, 1, 0), BOOT_TARGET_HOST, 6000u, 1, 1, 1, 1, DEV_KEY}, IMG);
    assert_int_equal(download(&D, IMG, len, len), BOOT_OK);
    *slot = D.fwu.slot;
    *crc_whole = D.fwu.crc32;
    assert_int_equal(D.app_dev.read(D.app_dev.ctx, D.cfg.slot_addr[*slot], whole, len), 0);
    fwu_abort(&D.fwu);
    return len;
}

/* TransferData in slices (fwu_data_step, 128 bytes a call): the same slot contents, CRC-32 and
 * verdict as the whole blocks of fwu_data, a block taken in ceil(len / 128) calls after the one
 * that keeps it; a refusal (a block past the announced size) before anything is kept. */
static void test_data_in_slices_same_as_whole_blocks(void **state)
{
    (void)state;
    static uint8_t whole[IMG_MAX], sliced[IMG_MAX];
    uint8_t slot = 0u;
    uint32_t crc_whole = 0u;
    const uint32_t len = whole_download(whole, &slot, &crc_whole);
    assert_int_equal(fwu_begin(&D.fwu, true, len), BOOT_OK);
    static const uint32_t blocks[] = {100u, 1021u, 7u, 4093u, 333u};
    uint32_t off = 0u, k = 0u;
    while (off < len) {
        uint32_t n = blocks[k++ % 5u];
        n = n > len - off ? len - off : n;
        bool done = false;
        assert_int_equal(fwu_data_step(&D.fwu, true, off, IMG + off, n, 128u, &done), BOOT_OK);
        assert_false(done);
        uint32_t calls = 0u;
        while (!done) {
            assert_int_equal(fwu_data_step(&D.fwu, true, off, NULL, n, 128u, &done), BOOT_OK);
            calls++;
        }
        assert_int_equal(calls, (n + 127u) / 128u);
        off += n;
    }
    assert_int_equal(fwu_end(&D.fwu, true, NULL), BOOT_OK);
    assert_int_equal(D.fwu.slot, slot);
    assert_int_equal(D.fwu.crc32, crc_whole);
    assert_int_equal(D.app_dev.read(D.app_dev.ctx, D.cfg.slot_addr[slot], sliced, len), 0);
    assert_memory_equal(sliced, whole, len);
    fwu_abort(&D.fwu);
    assert_int_equal(fwu_begin(&D.fwu, true, 300u), BOOT_OK);
    bool done = false;
    assert_int_equal(fwu_data_step(&D.fwu, true, 0u, IMG, 301u, 128u, &done), FWU_ERR_OVERRUN);
    assert_true(done);
    assert_int_equal(fwu_data_step(&D.fwu, true, 0u, NULL, 301u, 128u, &done), FWU_ERR_SEQUENCE);
}

/* A flash whose erase runs in the background (fls.h busy), over the device's RAM flash: erase()
 * notes the sector, the third busy() poll erases it; a program or read while an erase is
 * pending fails the test. */
static fls_dev_t g_bg_raw;
static int g_bg_pending = -1, g_bg_polls;
static uint32_t g_bg_erases;
static uint32_t g_bg_call, g_bg_started_in, g_bg_sync; /* erases begun and ended in one call */

static int bg_erase(void *ctx, uint32_t sector)
{
    g_bg_started_in = g_bg_call;
    (void)ctx;
    assert_int_equal(g_bg_pending, -1);
    g_bg_pending = (int)sector;
    g_bg_polls = 0;
    g_bg_erases++;
    return 0;
}

static int bg_busy(void *ctx)
{
    (void)ctx;
    if (g_bg_pending < 0) {
        return 0;
    }
    if (++g_bg_polls < 3) {
        return 1;
    }
    const int r = g_bg_raw.erase(g_bg_raw.ctx, (uint32_t)g_bg_pending);
    g_bg_pending = -1;
    g_bg_sync += g_bg_started_in == g_bg_call ? 1u : 0u;
    return r != 0 ? -1 : 0;
}

static int bg_program(void *ctx, uint32_t addr, const uint8_t *d, uint32_t len)
{
    (void)ctx;
    assert_int_equal(g_bg_pending, -1);
    return g_bg_raw.program(g_bg_raw.ctx, addr, d, len);
}

static int bg_read(void *ctx, uint32_t addr, uint8_t *d, uint32_t len)
{
    (void)ctx;
    assert_int_equal(g_bg_pending, -1);
    return g_bg_raw.read(g_bg_raw.ctx, addr, d, len);
}

/* The device's flash with a background erase (the windows forward busy()). */
static void background_erase(dev_t_ *d)
{
    g_bg_raw = d->flash;
    g_bg_pending = -1;
    g_bg_erases = 0u;
    d->flash.erase = bg_erase;
    d->flash.busy = bg_busy;
    d->flash.program = bg_program;
    d->flash.read = bg_read;
    attach(d);
}

/* The image downloaded whole into whole (its slot and CRC-32), then the same download begun
 * again on the flash with the background erase (no synchronous wait counted); returns its length. */
static uint32_t background_download_begin(uint8_t whole[IMG_MAX], uint8_t *slot, uint32_t *crc)
{
    const uint32_t len = whole_download(whole, slot, crc);
    background_erase(&D);
    g_bg_sync = 0u;
    assert_int_equal(fwu_begin(&D.fwu, true, len), BOOT_OK);
    return len;
}

/* After a download of the image whole: a header for another target, in pieces of piece bytes,
 * is refused (BOOT_ERR_TARGET) without an erase, the slot's first sector keeping whole's bytes. */
static void refused_header_erases_nothing(const uint8_t *whole, uint32_t piece)
{
    static uint8_t sector[SECTOR];
    fwu_abort(&D.fwu);
    const uint32_t len2 = make_image(
        &(img_spec_t){BOOT_VERSION(1, 2, 0), BOOT_TARGET_HOST + 1u, 600u, 1, 1, 1, 1, DEV_KEY},
        IMG2);
    assert_int_equal(fwu_begin(&D.fwu, true, len2), BOOT_OK);
    const uint32_t erases = g_bg_erases;
    bool done = false;
    assert_int_equal(fwu_data_step(&D.fwu, true, 0u, IMG2, 300u, piece, &done), BOOT_OK);
    assert_int_equal(fwu_data_step(&D.fwu, true, 0u, NULL, 300u, piece, &done), BOOT_ERR_TARGET);
    assert_true(done);
    assert_int_equal(g_bg_erases, erases);
    assert_int_equal(D.app_dev.read(D.app_dev.ctx, D.cfg.slot_addr[D.fwu.slot], sector, SECTOR), 0);
    assert_memory_equal(sector, whole, SECTOR);
}

/* TransferData in slices on a flash with a background erase: each sector's erase is started by
 * a call of its own and polled a call at a time (3 polls, the one that sees it done a call of
 * its own too) once the header is in, the slot's contents and CRC-32 are
 * those of the synchronous flash; a block whose header is refused erases nothing. */
static void test_data_in_slices_background_erase(void **state)
{
    (void)state;
    static uint8_t whole[IMG_MAX], sliced[IMG_MAX];
    uint8_t slot = 0u;
    uint32_t crc_whole = 0u;
    const uint32_t len = background_download_begin(whole, &slot, &crc_whole);
    static const uint32_t blocks[] = {100u, 1021u, 7u, 4093u, 333u};
    uint32_t off = 0u, k = 0u, calls = 0u;
    while (off < len) {
        uint32_t n = blocks[k++ % 5u];
        n = n > len - off ? len - off : n;
        bool done = false;
        assert_int_equal(fwu_data_step(&D.fwu, true, off, IMG + off, n, 128u, &done), BOOT_OK);
        while (!done) {
            assert_int_equal(fwu_data_step(&D.fwu, true, off, NULL, n, 128u, &done), BOOT_OK);
            calls++;
        }
        calls -= (n + 127u) / 128u;
        off += n;
    }
    const uint32_t sectors = (len + SECTOR - 1u) / SECTOR;
    assert_int_equal(g_bg_erases, sectors);
    /* per sector, its start, 2 polls still busy and the poll that sees it done; but the first:
     * the first block (100 bytes) leaves the header incomplete, so its bytes' program() erases
     * the sector and waits */
    assert_int_equal(calls, (sectors - 1u) * 4u);
    assert_int_equal(fwu_end(&D.fwu, true, NULL), BOOT_OK);
    assert_int_equal(D.fwu.crc32, crc_whole);
    assert_int_equal(D.app_dev.read(D.app_dev.ctx, D.cfg.slot_addr[slot], sliced, len), 0);
    assert_memory_equal(sliced, whole, len);
    /* a refused header (another target): the slot's first sector keeps its bytes */
    refused_header_erases_nothing(whole, 128u);
}

/* Pieces shorter than the image's header (fwu_uds.h FWU_DATA_BYTES_PER_CALL on a port): the
 * header is taken whole, so with a first block that holds it no erase starts and ends inside one
 * call (none waits for a sector), the slot and CRC-32 are those of whole blocks, and a refused
 * header erases nothing. */
static void test_data_in_short_pieces(void **state)
{
    (void)state;
    static uint8_t whole[IMG_MAX], sliced[IMG_MAX];
    uint8_t slot = 0u;
    uint32_t crc_whole = 0u;
    const uint32_t len = background_download_begin(whole, &slot, &crc_whole);
    static const uint32_t blocks[] = {300u, 1021u, 7u, 4093u, 333u};
    uint32_t off = 0u, k = 0u;
    while (off < len) {
        uint32_t n = blocks[k++ % 5u];
        n = n > len - off ? len - off : n;
        bool done = false;
        g_bg_call++;
        assert_int_equal(fwu_data_step(&D.fwu, true, off, IMG + off, n, 48u, &done), BOOT_OK);
        while (!done) {
            g_bg_call++;
            assert_int_equal(fwu_data_step(&D.fwu, true, off, NULL, n, 48u, &done), BOOT_OK);
        }
        off += n;
    }
    assert_int_equal(g_bg_erases, (len + SECTOR - 1u) / SECTOR);
    assert_int_equal(g_bg_sync, 0u);
    assert_int_equal(fwu_end(&D.fwu, true, NULL), BOOT_OK);
    assert_int_equal(D.fwu.crc32, crc_whole);
    assert_int_equal(D.app_dev.read(D.app_dev.ctx, D.cfg.slot_addr[slot], sliced, len), 0);
    assert_memory_equal(sliced, whole, len);
    refused_header_erases_nothing(whole, 48u);
}

static void test_header_refusals(void **state)
{
    (void)state;
    boot_image_header_t h;
    uint32_t len = make_image(
        &(img_spec_t){BOOT_VERSION(1, 0, 0), BOOT_TARGET_HOST, 64u, 1, 1, 1, 1, DEV_KEY}, IMG);
    (void)len;
    assert_int_equal(boot_image_parse_header(IMG, BOOT_TARGET_HOST, &h), BOOT_OK);
    uint8_t bad[BOOT_IMAGE_HEADER_SIZE];
    memcpy(bad, IMG, sizeof bad);
    bad[0] ^= 1u;
    assert_int_equal(boot_image_parse_header(bad, 0u, &h), BOOT_ERR_MAGIC);
    memcpy(bad, IMG, sizeof bad);
    bad[4] = 2u; /* format version 2 */
    assert_int_equal(boot_image_parse_header(bad, 0u, &h), BOOT_ERR_FORMAT);
    memcpy(bad, IMG, sizeof bad);
    bad[40] = 1u; /* reserved byte */
    assert_int_equal(boot_image_parse_header(bad, 0u, &h), BOOT_ERR_FORMAT);
    memcpy(bad, IMG, sizeof bad);
    bad[20] = 1u; /* unknown flag */
    assert_int_equal(boot_image_parse_header(bad, 0u, &h), BOOT_ERR_FORMAT);
    memcpy(bad, IMG, sizeof bad);
    bad[32] = 64u; /* entry offset at the payload end */
    assert_int_equal(boot_image_parse_header(bad, 0u, &h), BOOT_ERR_FORMAT);
    memcpy(bad, IMG, sizeof bad);
    put_le16(bad + 26, 2u); /* skill oldest > native */
    assert_int_equal(boot_image_parse_header(bad, 0u, &h), BOOT_ERR_FORMAT);
    assert_int_equal(boot_image_parse_header(IMG, BOOT_TARGET_CORTEX_M4F, &h), BOOT_ERR_TARGET);
    /* data formats: stored v1 skills need oldest <= 1 <= native */
    h.skill_format = 2u;
    h.skill_format_oldest = 2u;
    assert_int_equal(boot_image_check_data(&h, 1u, 1u, 1u, 1u), BOOT_ERR_SKILL_FORMAT);
    h.skill_format_oldest = 1u;
    assert_int_equal(boot_image_check_data(&h, 1u, 1u, 1u, 1u), BOOT_OK);
    assert_int_equal(boot_image_check_data(&h, 1u, 3u, 1u, 1u), BOOT_ERR_SKILL_FORMAT);
    assert_int_equal(boot_image_check_data(&h, 0u, 0u, 2u, 2u), BOOT_ERR_CONFIG_FORMAT);
}

static void test_state_record_round_trip(void **state)
{
    (void)state;
    /* padding bytes are zeroed on both sides so the byte comparison sees only the fields */
    boot_state_t s, t;
    memset(&s, 0, sizeof s);
    memset(&t, 0, sizeof t);
    s.active_slot = 1u;
    s.test_slot = 0u;
    s.test_attempts = 1u;
    s.confirmed = 1u;
    s.test_flags = BOOT_FLAG_ALLOW_DOWNGRADE;
    s.active_version = 0x01020003u;
    uint8_t buf[BOOT_STATE_LEN];
    boot_state_encode(&s, buf);
    assert_true(boot_state_decode(buf, &t));
    assert_memory_equal(&s, &t, sizeof s);
    buf[0] = 9u;
    assert_false(boot_state_decode(buf, &t));
    boot_state_encode(&s, buf);
    buf[1] = 2u; /* slot C does not exist */
    assert_false(boot_state_decode(buf, &t));
}

/* ---- update flow ---- */

static void test_full_update_and_confirm(void **state)
{
    (void)state;
    device_with_factory_image(&D);
    uint32_t len = make_image(
        &(img_spec_t){BOOT_VERSION(1, 1, 0), BOOT_TARGET_HOST, 9001u, 1, 1, 1, 1, DEV_KEY}, IMG);
    assert_int_equal(download(&D, IMG, len, len), BOOT_OK);
    assert_int_equal(D.fwu.slot, 1u);
    assert_int_equal(D.fwu.phase, FWU_RECEIVED);
    assert_int_equal(fwu_mark_test(&D.fwu, true, 0u), BOOT_OK);
    uint8_t st[FWU_STATUS_LEN];
    assert_int_equal(fwu_status(&D.fwu, st, sizeof st), FWU_STATUS_LEN);
    assert_int_equal(st[7], 1u); /* pending test slot B */
    assert_int_equal(st[16], FWU_MARKED);
    /* ECUReset: the new image runs on test */
    assert_int_equal(dev_reset(&D), BOOT_OK);
    assert_int_equal(D.boot.path, BOOT_PATH_TEST);
    assert_int_equal(D.boot.running_slot, 1u);
    assert_true(D.boot.test_boot);
    assert_int_equal(D.boot.running.fw_version, BOOT_VERSION(1, 1, 0));
    assert_int_equal(fwu_status(&D.fwu, st, sizeof st), FWU_STATUS_LEN);
    assert_int_equal(st[0] << 24 | st[1] << 16 | st[2] << 8 | st[3], BOOT_VERSION(1, 1, 0));
    assert_int_equal(st[5], 1u); /* on test */
    /* its self-test passes: it confirms itself; later resets keep it */
    assert_int_equal(fwu_confirm(&D.fwu), BOOT_OK);
    assert_false(D.boot.test_boot);
    for (int i = 0; i < 3; i++) {
        assert_int_equal(dev_reset(&D), BOOT_OK);
        assert_int_equal(D.boot.path, BOOT_PATH_ACTIVE);
        assert_int_equal(D.boot.running_slot, 1u);
        assert_int_equal(D.boot.running.fw_version, BOOT_VERSION(1, 1, 0));
    }
    assert_skills_intact(&D);
    /* the next update goes to slot A (the old image), and so on */
    len = make_image(
        &(img_spec_t){BOOT_VERSION(1, 2, 0), BOOT_TARGET_HOST, 777u, 1, 1, 1, 1, DEV_KEY}, IMG);
    assert_int_equal(download(&D, IMG, len, len), BOOT_OK);
    assert_int_equal(D.fwu.slot, 0u);
    assert_int_equal(fwu_mark_test(&D.fwu, true, 0u), BOOT_OK);
    assert_int_equal(dev_reset(&D), BOOT_OK);
    assert_int_equal(D.boot.running_slot, 0u);
    assert_int_equal(fwu_confirm(&D.fwu), BOOT_OK);
    assert_int_equal(dev_reset(&D), BOOT_OK);
    assert_int_equal(D.boot.running.fw_version, BOOT_VERSION(1, 2, 0));
}

static void test_revert_when_self_test_fails(void **state)
{
    (void)state;
    device_with_factory_image(&D);
    uint32_t len = make_image(
        &(img_spec_t){BOOT_VERSION(2, 0, 0), BOOT_TARGET_HOST, 3000u, 1, 1, 1, 1, DEV_KEY}, IMG);
    assert_int_equal(download(&D, IMG, len, len), BOOT_OK);
    assert_int_equal(fwu_mark_test(&D.fwu, true, 0u), BOOT_OK);
    assert_int_equal(dev_reset(&D), BOOT_OK);
    assert_int_equal(D.boot.path, BOOT_PATH_TEST);
    /* self-test fails: no confirm; while on test, no new download may overwrite the fallback */
    assert_int_equal(fwu_begin(&D.fwu, true, len), FWU_ERR_TEST_PENDING);
    assert_int_equal(fwu_nrc(FWU_ERR_TEST_PENDING), 0x22u);
    assert_int_equal(dev_reset(&D), BOOT_OK);
    assert_int_equal(D.boot.path, BOOT_PATH_REVERTED);
    assert_int_equal(D.boot.running_slot, 0u);
    assert_int_equal(D.boot.running.fw_version, BOOT_VERSION(1, 0, 0));
    assert_int_equal(D.boot.state.test_slot, BOOT_SLOT_NONE);
    assert_int_equal(dev_reset(&D), BOOT_OK);
    assert_int_equal(D.boot.path, BOOT_PATH_ACTIVE);
    assert_int_equal(D.boot.running_slot, 0u);
    assert_skills_intact(&D);
}

static void test_bootloader_refuses_tampered_test_image(void **state)
{
    (void)state;
    device_with_factory_image(&D);
    uint32_t len = make_image(
        &(img_spec_t){BOOT_VERSION(1, 5, 0), BOOT_TARGET_HOST, 3000u, 1, 1, 1, 1, DEV_KEY}, IMG);
    assert_int_equal(download(&D, IMG, len, len), BOOT_OK);
    assert_int_equal(fwu_mark_test(&D.fwu, true, 0u), BOOT_OK);
    /* one payload bit of slot B cleared after the check (NOR programming only clears bits) */
    uint8_t unit[WU];
    const uint32_t addr = SLOT_SIZE + 1024u;
    assert_int_equal(D.app_dev.read(D.app_dev.ctx, addr, unit, WU), 0);
    for (uint32_t i = 0; i < WU; i++) {
        if (unit[i] != 0u) {
            unit[i] = (uint8_t)(unit[i] & (unit[i] - 1u));
            break;
        }
    }
    assert_int_equal(D.app_dev.program(D.app_dev.ctx, addr, unit, WU), 0);
    assert_int_equal(dev_reset(&D), BOOT_OK);
    assert_int_equal(D.boot.path, BOOT_PATH_TEST_REFUSED);
    assert_int_equal(D.boot.refusal, BOOT_ERR_HASH);
    assert_int_equal(D.boot.running_slot, 0u);
    assert_int_equal(D.boot.running.fw_version, BOOT_VERSION(1, 0, 0));
}

static void test_recovery_when_active_image_is_damaged(void **state)
{
    (void)state;
    device_with_factory_image(&D);
    uint32_t len = make_image(
        &(img_spec_t){BOOT_VERSION(1, 1, 0), BOOT_TARGET_HOST, 2000u, 1, 1, 1, 1, DEV_KEY}, IMG);
    assert_int_equal(download(&D, IMG, len, len), BOOT_OK);
    assert_int_equal(fwu_mark_test(&D.fwu, true, 0u), BOOT_OK);
    assert_int_equal(dev_reset(&D), BOOT_OK);
    assert_int_equal(fwu_confirm(&D.fwu), BOOT_OK);
    /* the active image (slot B) loses its header */
    assert_int_equal(D.app_dev.erase(D.app_dev.ctx, SLOT_SIZE / SECTOR), 0);
    assert_int_equal(dev_reset(&D), BOOT_OK);
    assert_int_equal(D.boot.path, BOOT_PATH_RECOVERED);
    assert_int_equal(D.boot.refusal, BOOT_ERR_MAGIC);
    assert_int_equal(D.boot.running_slot, 0u);
    assert_int_equal(D.boot.state.active_slot, 0u);
    /* and with both slots damaged nothing is started */
    assert_int_equal(D.app_dev.erase(D.app_dev.ctx, 0u), 0);
    assert_int_equal(dev_reset(&D), BOOT_ERR_NO_IMAGE);
    assert_int_equal(D.boot.running_slot, BOOT_SLOT_NONE);
}

/* ---- refusals, each with its own code ---- */

static void test_wrong_tag_refused(void **state)
{
    (void)state;
    device_with_factory_image(&D);
    uint32_t len = make_image(
        &(img_spec_t){BOOT_VERSION(1, 1, 0), BOOT_TARGET_HOST, 3000u, 1, 1, 1, 1, OTHER_KEY}, IMG);
    assert_int_equal(download(&D, IMG, len, len), BOOT_ERR_TAG);
    assert_int_equal(fwu_nrc(BOOT_ERR_TAG), 0xF4u);
    assert_int_equal(fwu_mark_test(&D.fwu, true, 0u), FWU_ERR_SEQUENCE);
    assert_int_equal(dev_reset(&D), BOOT_OK);
    assert_int_equal(D.boot.running.fw_version, BOOT_VERSION(1, 0, 0));
    assert_int_equal(D.boot.path, BOOT_PATH_ACTIVE);
}

static void test_wrong_target_refused(void **state)
{
    (void)state;
    device_with_factory_image(&D);
    uint32_t len = make_image(
        &(img_spec_t){BOOT_VERSION(1, 1, 0), BOOT_TARGET_CORTEX_M3, 3000u, 1, 1, 1, 1, DEV_KEY},
        IMG);
    assert_int_equal(fwu_begin(&D.fwu, true, len), BOOT_OK);
    /* refused as soon as the header is in, before any payload is written */
    assert_int_equal(fwu_data(&D.fwu, true, 0u, IMG, 100u), BOOT_OK);
    assert_int_equal(fwu_data(&D.fwu, true, 100u, IMG + 100, 100u), BOOT_ERR_TARGET);
    assert_int_equal(fwu_nrc(BOOT_ERR_TARGET), 0xF1u);
    assert_int_equal(D.fwu.programmed, 96u); /* only header bytes reached flash */
    assert_int_equal(fwu_data(&D.fwu, true, 200u, IMG + 200, 100u), FWU_ERR_SEQUENCE);
}

static void test_truncated_refused(void **state)
{
    (void)state;
    device_with_factory_image(&D);
    uint32_t len = make_image(
        &(img_spec_t){BOOT_VERSION(1, 1, 0), BOOT_TARGET_HOST, 3000u, 1, 1, 1, 1, DEV_KEY}, IMG);
    /* a file cut short: announced size smaller than the header says */
    assert_int_equal(download(&D, IMG, len - 100u, len - 100u), BOOT_ERR_TRUNCATED);
    assert_int_equal(fwu_nrc(BOOT_ERR_TRUNCATED), 0xF2u);
    /* a transfer stopped early: exit before all announced bytes */
    assert_int_equal(fwu_begin(&D.fwu, true, len), BOOT_OK);
    assert_int_equal(fwu_data(&D.fwu, true, 0u, IMG, 1000u), BOOT_OK);
    assert_int_equal(fwu_end(&D.fwu, true, NULL), FWU_ERR_SEQUENCE);
    assert_int_equal(fwu_nrc(FWU_ERR_SEQUENCE), 0x24u);
    /* announced larger than the image: trailing bytes are a format error */
    assert_int_equal(fwu_begin(&D.fwu, true, len + 8u), BOOT_OK);
    assert_int_equal(fwu_data(&D.fwu, true, 0u, IMG, 200u), BOOT_ERR_FORMAT);
    assert_int_equal(fwu_nrc(BOOT_ERR_FORMAT), 0xF0u);
}

static void test_corrupted_transfer_refused(void **state)
{
    (void)state;
    device_with_factory_image(&D);
    uint32_t len = make_image(
        &(img_spec_t){BOOT_VERSION(1, 1, 0), BOOT_TARGET_HOST, 3000u, 1, 1, 1, 1, DEV_KEY}, IMG);
    IMG[2000] ^= 0x10u;
    assert_int_equal(download(&D, IMG, len, len), BOOT_ERR_HASH);
    assert_int_equal(fwu_nrc(BOOT_ERR_HASH), 0xF3u);
}

static void test_downgrade_refused_unless_forced(void **state)
{
    (void)state;
    device_with_factory_image(&D);
    uint32_t len = make_image(
        &(img_spec_t){BOOT_VERSION(0, 9, 7), BOOT_TARGET_HOST, 3000u, 1, 1, 1, 1, DEV_KEY}, IMG);
    assert_int_equal(download(&D, IMG, len, len), BOOT_OK);
    assert_int_equal(fwu_mark_test(&D.fwu, true, 0u), BOOT_ERR_DOWNGRADE);
    assert_int_equal(fwu_nrc(BOOT_ERR_DOWNGRADE), 0xF5u);
    assert_int_equal(dev_reset(&D), BOOT_OK);
    assert_int_equal(D.boot.path, BOOT_PATH_ACTIVE); /* nothing was marked */
    assert_int_equal(download(&D, IMG, len, len), BOOT_OK);
    assert_int_equal(fwu_mark_test(&D.fwu, true, FWU_OPT_ALLOW_DOWNGRADE), BOOT_OK);
    assert_int_equal(dev_reset(&D), BOOT_OK);
    assert_int_equal(D.boot.path, BOOT_PATH_TEST);
    assert_int_equal(D.boot.running.fw_version, BOOT_VERSION(0, 9, 7));
    /* the same version again is not a downgrade */
    assert_int_equal(fwu_confirm(&D.fwu), BOOT_OK);
    assert_int_equal(download(&D, IMG, len, len), BOOT_OK);
    assert_int_equal(fwu_mark_test(&D.fwu, true, 0u), BOOT_OK);
}

static void test_bootloader_refuses_downgrade_marked_without_flag(void **state)
{
    (void)state;
    /* A state record that names an older test image without the flag (e.g. written by an
     * older firmware): the bootloader applies the rule itself. */
    device_with_factory_image(&D);
    uint32_t len = make_image(
        &(img_spec_t){BOOT_VERSION(0, 1, 0), BOOT_TARGET_HOST, 3000u, 1, 1, 1, 1, DEV_KEY}, IMG);
    factory_program(&D, 1u, IMG, len);
    boot_state_t s = D.boot.state;
    s.test_slot = 1u;
    s.test_attempts = 0u;
    s.test_flags = 0u;
    assert_int_equal(boot_state_store(&D.cfg, &s), BOOT_OK);
    assert_int_equal(dev_reset(&D), BOOT_OK);
    assert_int_equal(D.boot.path, BOOT_PATH_TEST_REFUSED);
    assert_int_equal(D.boot.refusal, BOOT_ERR_DOWNGRADE);
    assert_int_equal(D.boot.running_slot, 0u);
}

static void test_data_format_refused(void **state)
{
    (void)state;
    device_with_factory_image(&D);
    /* an image that reads only skill format 2: stored v1 skills would be misread */
    uint32_t len = make_image(
        &(img_spec_t){BOOT_VERSION(1, 1, 0), BOOT_TARGET_HOST, 3000u, 2, 2, 1, 1, DEV_KEY}, IMG);
    assert_int_equal(download(&D, IMG, len, len), BOOT_OK);
    assert_int_equal(fwu_mark_test(&D.fwu, true, 0u), BOOT_ERR_SKILL_FORMAT);
    assert_int_equal(fwu_nrc(BOOT_ERR_SKILL_FORMAT), 0xF6u);
    /* configuration likewise */
    len = make_image(
        &(img_spec_t){BOOT_VERSION(1, 1, 0), BOOT_TARGET_HOST, 3000u, 1, 1, 3, 2, DEV_KEY}, IMG);
    assert_int_equal(download(&D, IMG, len, len), BOOT_OK);
    assert_int_equal(fwu_mark_test(&D.fwu, true, 0u), BOOT_ERR_CONFIG_FORMAT);
    assert_int_equal(fwu_nrc(BOOT_ERR_CONFIG_FORMAT), 0xF7u);
    /* an image that migrates from v1 (native 2, oldest 1) is accepted */
    len = make_image(
        &(img_spec_t){BOOT_VERSION(1, 1, 0), BOOT_TARGET_HOST, 3000u, 2, 1, 1, 1, DEV_KEY}, IMG);
    assert_int_equal(download(&D, IMG, len, len), BOOT_OK);
    assert_int_equal(fwu_mark_test(&D.fwu, true, 0u), BOOT_OK);
    assert_skills_intact(&D);
}

static void test_access_and_sequence_refusals(void **state)
{
    (void)state;
    device_with_factory_image(&D);
    const img_spec_t sp = spec(BOOT_VERSION(1, 1, 0));
    uint32_t len = make_image(&sp, IMG);
    assert_int_equal(fwu_begin(&D.fwu, false, len), FWU_ERR_LOCKED);
    assert_int_equal(fwu_nrc(FWU_ERR_LOCKED), 0x33u);
    assert_int_equal(fwu_begin(&D.fwu, true, SLOT_SIZE + 1u), BOOT_ERR_TOO_LARGE);
    assert_int_equal(fwu_nrc(BOOT_ERR_TOO_LARGE), 0x70u);
    assert_int_equal(fwu_begin(&D.fwu, true, BOOT_IMAGE_OVERHEAD), FWU_ERR_RANGE);
    assert_int_equal(fwu_nrc(FWU_ERR_RANGE), 0x31u);
    assert_int_equal(fwu_data(&D.fwu, true, 0u, IMG, 10u), FWU_ERR_SEQUENCE);
    assert_int_equal(fwu_begin(&D.fwu, true, len), BOOT_OK);
    assert_int_equal(fwu_data(&D.fwu, true, 0u, IMG, 10u), BOOT_OK);
    assert_int_equal(fwu_data(&D.fwu, false, 10u, IMG + 10, 10u), FWU_ERR_LOCKED);
    assert_int_equal(fwu_begin(&D.fwu, true, len), BOOT_OK);
    assert_int_equal(fwu_data(&D.fwu, true, 5u, IMG, 10u), FWU_ERR_SEQUENCE); /* gap */
    assert_int_equal(fwu_begin(&D.fwu, true, 300u), BOOT_OK);
    assert_int_equal(fwu_data(&D.fwu, true, 0u, IMG, 301u), FWU_ERR_OVERRUN);
    assert_int_equal(fwu_nrc(FWU_ERR_OVERRUN), 0x71u);
    assert_int_equal(fwu_nrc(FWU_ERR_BLOCK_COUNTER), 0x73u);
    assert_int_equal(fwu_nrc(BOOT_ERR_FLASH), 0x72u);
    /* an aborted download (session change) is not markable */
    assert_int_equal(fwu_begin(&D.fwu, true, len), BOOT_OK);
    fwu_abort(&D.fwu);
    assert_int_equal(fwu_end(&D.fwu, true, NULL), FWU_ERR_SEQUENCE);
    assert_int_equal(fwu_mark_test(&D.fwu, false, 0u), FWU_ERR_LOCKED);
    /* every refusal code maps to a distinct NRC, except the two header-format ones */
    static const boot_status_t codes[] = {
        BOOT_ERR_TRUNCATED,     BOOT_ERR_MAGIC,  BOOT_ERR_TARGET,      BOOT_ERR_TOO_LARGE,
        BOOT_ERR_HASH,          BOOT_ERR_TAG,    BOOT_ERR_DOWNGRADE,   BOOT_ERR_SKILL_FORMAT,
        BOOT_ERR_CONFIG_FORMAT, BOOT_ERR_FLASH,  FWU_ERR_LOCKED,       FWU_ERR_SEQUENCE,
        FWU_ERR_BLOCK_COUNTER,  FWU_ERR_OVERRUN, FWU_ERR_TEST_PENDING, FWU_ERR_RANGE};
    for (size_t i = 0; i < sizeof codes / sizeof codes[0]; i++) {
        assert_int_not_equal(fwu_nrc(codes[i]), 0u);
        for (size_t j = 0; j < i; j++) {
            assert_int_not_equal(fwu_nrc(codes[i]), fwu_nrc(codes[j]));
        }
    }
}

static void test_new_download_cancels_pending_test(void **state)
{
    (void)state;
    device_with_factory_image(&D);
    const img_spec_t sp = spec(BOOT_VERSION(1, 1, 0));
    uint32_t len = make_image(&sp, IMG);
    assert_int_equal(download(&D, IMG, len, len), BOOT_OK);
    assert_int_equal(fwu_mark_test(&D.fwu, true, 0u), BOOT_OK);
    /* a second download into the same slot before any reset: the mark is dropped first */
    assert_int_equal(fwu_begin(&D.fwu, true, len), BOOT_OK);
    assert_int_equal(D.boot.state.test_slot, BOOT_SLOT_NONE);
    assert_int_equal(fwu_data(&D.fwu, true, 0u, IMG, 500u), BOOT_OK);
    assert_int_equal(dev_reset(&D), BOOT_OK); /* interrupted: old image, no test */
    assert_int_equal(D.boot.path, BOOT_PATH_ACTIVE);
    assert_int_equal(D.boot.running_slot, 0u);
}

/* ---- random damage is never accepted ---- */

static uint32_t xorshift(uint32_t *st)
{
    *st ^= *st << 13;
    *st ^= *st >> 17;
    *st ^= *st << 5;
    return *st;
}

static void test_random_damage_never_accepted(void **state)
{
    (void)state;
    /* 3000 images, each with 1-4 flipped bits anywhere (header, payload, tag) or cut short:
     * every one is refused by the receiver or by the mark routine, never started. */
    device_with_factory_image(&D);
    const uint32_t len = make_image(
        &(img_spec_t){BOOT_VERSION(1, 1, 0), BOOT_TARGET_HOST, 1500u, 1, 1, 1, 1, DEV_KEY}, IMG2);
    uint32_t rng = 0x9E3779B9u, refused = 0;
    uint32_t by_code[16] = {0};
    for (int i = 0; i < 3000; i++) {
        memcpy(IMG, IMG2, len);
        uint32_t n = len;
        const uint32_t kind = xorshift(&rng) % 8u;
        if (kind == 0u) {
            n = xorshift(&rng) % len; /* truncated (the download announces n) */
        } else {
            for (uint32_t f = 0; f < 1u + kind % 4u; f++) {
                const uint32_t pos = xorshift(&rng) % len;
                IMG[pos] ^= (uint8_t)(1u << (xorshift(&rng) % 8u));
            }
        }
        if (n == len && memcmp(IMG, IMG2, len) == 0) {
            continue; /* flips cancelled out */
        }
        boot_status_t st = download(&D, IMG, n, n);
        if (st == BOOT_OK) {
            st = fwu_mark_test(&D.fwu, true, 0u);
        }
        assert_int_not_equal(st, BOOT_OK);
        if (st == FWU_ERR_RANGE) {
            st = BOOT_ERR_TRUNCATED; /* cut below header + tag: refused at begin */
        }
        assert_true(st >= 700 && st < 716); /* an image refusal, not a protocol one */
        by_code[st - 700]++;
        refused++;
    }
    assert_int_equal(dev_reset(&D), BOOT_OK);
    assert_int_equal(D.boot.path, BOOT_PATH_ACTIVE);
    assert_int_equal(D.boot.running.fw_version, BOOT_VERSION(1, 0, 0));
    print_message("boot_random_damage refused=%u truncated=%u magic=%u format=%u target=%u "
                  "too_large=%u hash=%u tag=%u downgrade=%u\n",
                  refused, by_code[0], by_code[1], by_code[2], by_code[3], by_code[4], by_code[5],
                  by_code[6], by_code[7]);
    assert_true(by_code[5] > 0u && by_code[6] > 0u && by_code[0] > 0u);
}

/* ---- power loss at every flash write ---- */

/* The whole update, as far as it gets: download, mark, reset (test boot), confirm, reset.
 * Returns 1 if it ran to the end (no power loss happened). */
static int update_sequence(dev_t_ *d, const uint8_t *img, uint32_t len)
{
    if (download(d, img, len, len) != BOOT_OK)
        return 0;
    if (fwu_mark_test(&d->fwu, true, 0u) != BOOT_OK)
        return 0;
    /* soft reset: the flash keeps power, the armed loss stays armed */
    attach(d);
    if (boot_select(&d->boot, &d->cfg) != BOOT_OK)
        return 0;
    fwu_init(&d->fwu, &d->boot);
    if (d->boot.path != BOOT_PATH_TEST)
        return 0;
    if (fwu_confirm(&d->fwu) != BOOT_OK)
        return 0;
    attach(d);
    if (boot_select(&d->boot, &d->cfg) != BOOT_OK)
        return 0;
    return d->ram.dead ? 0 : 1;
}

static void test_power_loss_at_every_write(void **state)
{
    (void)state;
    const uint32_t v_old = BOOT_VERSION(1, 0, 0), v_new = BOOT_VERSION(1, 1, 0);
    const uint32_t len = make_image(
        &(img_spec_t){v_new, BOOT_TARGET_HOST, 6000u, 1, 1, 1, 1, DEV_KEY}, IMG2);
    uint32_t k = 1, old_seen = 0, new_seen = 0, test_seen = 0;
    for (;; k++) {
        device_with_factory_image(&D);
        const uint32_t ops0 = D.ram.ops;
        fls_ram_set_power_loss(&D.ram, k);
        const int completed = update_sequence(&D, IMG2, len);
        const uint32_t ops_run = D.ram.ops - ops0;
        /* power comes back: the device must start an authorised image, old or new */
        assert_int_equal(dev_reset(&D), BOOT_OK);
        boot_image_header_t h;
        assert_int_equal(boot_slot_verify(&D.cfg, D.boot.running_slot, &h), BOOT_OK);
        assert_true(h.fw_version == v_old || h.fw_version == v_new);
        assert_skills_intact(&D);
        if (D.boot.path == BOOT_PATH_TEST) {
            test_seen++; /* marked before the loss, not yet tried: tried now, once */
            assert_int_equal(fwu_confirm(&D.fwu), BOOT_OK);
            assert_int_equal(dev_reset(&D), BOOT_OK);
        }
        if (D.boot.running.fw_version == v_old) {
            old_seen++;
            /* and the update can simply be run again */
            assert_int_equal(update_sequence(&D, IMG2, len), 1);
        } else {
            new_seen++;
        }
        assert_int_equal(D.boot.running.fw_version, v_new);
        assert_false(D.boot.test_boot);
        if (completed) {
            assert_true(ops_run < k); /* no loss happened: every write point was covered */
            break;
        }
    }
    print_message("boot_power_loss writes=%u old=%u new=%u via_test_boot=%u "
                  "(a loss at each of the %u erase/program operations of one update; then one run "
                  "without loss)\n",
                  k - 1u, old_seen, new_seen - 1u, test_seen, k - 1u);
    assert_true(k > 20u);
    assert_true(old_seen > 0u);
    assert_true(new_seen > 0u);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_golden_image_from_python),
        cmocka_unit_test(test_golden_image_verified_in_slices),
        cmocka_unit_test(test_data_in_slices_same_as_whole_blocks),
        cmocka_unit_test(test_data_in_slices_background_erase),
        cmocka_unit_test(test_data_in_short_pieces),
        cmocka_unit_test(test_header_refusals),
        cmocka_unit_test(test_state_record_round_trip),
        cmocka_unit_test(test_full_update_and_confirm),
        cmocka_unit_test(test_revert_when_self_test_fails),
        cmocka_unit_test(test_bootloader_refuses_tampered_test_image),
        cmocka_unit_test(test_recovery_when_active_image_is_damaged),
        cmocka_unit_test(test_wrong_tag_refused),
        cmocka_unit_test(test_wrong_target_refused),
        cmocka_unit_test(test_truncated_refused),
        cmocka_unit_test(test_corrupted_transfer_refused),
        cmocka_unit_test(test_downgrade_refused_unless_forced),
        cmocka_unit_test(test_bootloader_refuses_downgrade_marked_without_flag),
        cmocka_unit_test(test_data_format_refused),
        cmocka_unit_test(test_access_and_sequence_refusals),
        cmocka_unit_test(test_new_download_cancels_pending_test),
        cmocka_unit_test(test_random_damage_never_accepted),
        cmocka_unit_test(test_power_loss_at_every_write),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

/* A device for the host-side flash tests, assembled from the real firmware modules: the UDS
 * server (firmware/proto/uds.c), SecurityAccess (firmware/security/sec_access.c), the update
 * receiver through its UDS binding (firmware/boot/fwu_uds.c), the bootloader logic (boot.c) and
 * the RAM flash with power-loss injection (firmware/storage/fls_ram.c). The uds_app_t hooks
 * below are the integration an application needs (docs/update.md, "Integration").
 * Built as a shared library by tests/boot/test_flash_uds.py and driven through ctypes; ISO-TP
 * on the device side is can-isotp there. */
#include <stdint.h>
#include <string.h>

#include "boot.h"
#include "boot_fls_window.h"
#include "fls_ram.h"
#include "fwu.h"
#include "fwu_uds.h"
#include "nvm.h"
#include "sec_access.h"
#include "uds.h"

#define SECTOR 4096u
#define SLOT_SECTORS 32u /* 128 KiB slots */
#define N_SECTORS (2u + 2u * SLOT_SECTORS)

static const uint8_t DEV_KEY[32] = {
    0x40, 0x41, 0x42, 0x43, 0x44, 0x45, 0x46, 0x47, 0x48, 0x49, 0x4a, 0x4b, 0x4c, 0x4d, 0x4e, 0x4f,
    0x50, 0x51, 0x52, 0x53, 0x54, 0x55, 0x56, 0x57, 0x58, 0x59, 0x5a, 0x5b, 0x5c, 0x5d, 0x5e, 0x5f};

static struct {
    uint8_t mem[N_SECTORS * SECTOR];
    fls_ram_t ram;
    fls_dev_t flash, state_dev, app_dev;
    boot_fls_window_t w_state, w_app;
    nvm_t state_nvm;
    boot_config_t cfg;
    boot_t boot;
    fwu_t fwu;
    sec_config_t sec_cfg;
    sec_state_t sec;
    uds_server_t srv;
    uint32_t now_ms;
    int selftest_ok;
    int firmware_xfer; /* the active download is a firmware image */
    boot_status_t boot_status;
} D;

static uint32_t rng_state = 0x12345678u;

static int rng(void *ctx, uint8_t *buf, uint32_t len)
{
    (void)ctx;
    for (uint32_t i = 0; i < len; i++) {
        rng_state ^= rng_state << 13;
        rng_state ^= rng_state >> 17;
        rng_state ^= rng_state << 5;
        buf[i] = (uint8_t)rng_state;
    }
    return 0;
}

/* ---- uds_app_t hooks: firmware parts delegate to fwu_uds_* ---- */

static uint8_t h_read_did(void *ctx, uint16_t did, uint8_t *out, uint16_t cap, uint16_t *out_len)
{
    (void)ctx;
    if (did == FWU_DID_STATUS) {
        return fwu_uds_read_did(&D.fwu, out, cap, out_len);
    }
    return UDS_NRC_REQUEST_OUT_OF_RANGE;
}

static uint8_t h_routine(void *ctx, uint8_t sub, uint16_t rid, const uint8_t *data, uint16_t len,
                         uint8_t *out, uint16_t cap, uint16_t *out_len)
{
    (void)ctx;
    if (fwu_uds_owns_rid(rid)) {
        return fwu_uds_routine(&D.fwu, &D.srv, sub, rid, data, len, out, cap, out_len);
    }
    return UDS_NRC_REQUEST_OUT_OF_RANGE;
}

static uint8_t h_session_allowed(void *ctx, uint8_t session)
{
    (void)ctx;
    (void)session;
    return UDS_NRC_OK;
}

static uint8_t h_ecu_reset(void *ctx, uint8_t type)
{
    (void)ctx;
    return type == 1u || type == 3u ? UDS_NRC_OK : UDS_NRC_SUBFUNCTION_NOT_SUPPORTED;
}

static void power_on(void);

static void h_reset_now(void *ctx, uint8_t type)
{
    (void)ctx;
    (void)type;
    power_on();
}

static uint8_t h_security_seed(void *ctx, uint8_t level, uint8_t *seed, uint16_t cap, uint16_t *len)
{
    (void)ctx;
    (void)level;
    if (cap < SEC_SEED_LEN) {
        return UDS_NRC_RESPONSE_TOO_LONG;
    }
    const sec_nrc_t nrc = sec_request_seed(&D.sec_cfg, &D.sec, 0u, D.now_ms, seed);
    *len = SEC_SEED_LEN;
    return (uint8_t)nrc;
}

static uint8_t h_security_key(void *ctx, uint8_t level, const uint8_t *key, uint16_t len)
{
    (void)ctx;
    (void)level;
    return (uint8_t)sec_send_key(&D.sec_cfg, &D.sec, 0u, D.now_ms, key, len);
}

static uint8_t h_download_begin(void *ctx, uint32_t addr, uint32_t size)
{
    (void)ctx;
    if (addr == FWU_DOWNLOAD_ADDRESS) {
        D.firmware_xfer = 1;
        return fwu_uds_download_begin(&D.fwu, &D.srv, size);
    }
    D.firmware_xfer = 0;
    return UDS_NRC_REQUEST_OUT_OF_RANGE; /* skill slots: the application's own code */
}

static uint8_t h_download_data(void *ctx, uint32_t offset, const uint8_t *data, uint16_t len)
{
    (void)ctx;
    return D.firmware_xfer ? fwu_uds_download_data(&D.fwu, &D.srv, offset, data, len)
                           : UDS_NRC_REQUEST_SEQUENCE_ERROR;
}

static uint8_t h_download_end(void *ctx, uint32_t *crc32_out)
{
    (void)ctx;
    return D.firmware_xfer ? fwu_uds_download_end(&D.fwu, &D.srv, crc32_out)
                           : UDS_NRC_REQUEST_SEQUENCE_ERROR;
}

static void h_transfer_abort(void *ctx)
{
    (void)ctx;
    if (D.firmware_xfer) {
        fwu_abort(&D.fwu);
    }
}

static uint8_t h_upload_begin(void *ctx, uint32_t addr, uint32_t size)
{
    (void)ctx;
    (void)addr;
    (void)size;
    return UDS_NRC_REQUEST_OUT_OF_RANGE;
}

static uint8_t h_upload_data(void *ctx, uint32_t offset, uint8_t *out, uint16_t len)
{
    (void)ctx;
    (void)offset;
    (void)out;
    (void)len;
    return UDS_NRC_REQUEST_SEQUENCE_ERROR;
}

/* Reset: flash keeps its contents; bootloader decides; the application starts, runs its
 * self-test and confirms itself if it passes. */
static void power_on(void)
{
    fls_ram_power_cycle(&D.ram);
    (void)boot_fls_window_init(&D.w_state, &D.state_dev, &D.flash, 0u, 2u);
    (void)boot_fls_window_init(&D.w_app, &D.app_dev, &D.flash, 2u, 2u * SLOT_SECTORS);
    (void)nvm_init(&D.state_nvm, &D.state_dev);
    D.boot_status = boot_select(&D.boot, &D.cfg);
    fwu_init(&D.fwu, &D.boot);
    sec_init(&D.sec_cfg, &D.sec, D.now_ms);
    const uds_app_t app = {.ctx = NULL,
                           .read_did = h_read_did,
                           .write_did = NULL,
                           .routine = h_routine,
                           .session_allowed = h_session_allowed,
                           .ecu_reset = h_ecu_reset,
                           .reset_now = h_reset_now,
                           .security_seed = h_security_seed,
                           .security_key = h_security_key,
                           .download_begin = h_download_begin,
                           .download_data = h_download_data,
                           .download_end = h_download_end,
                           .transfer_abort = h_transfer_abort,
                           .upload_begin = h_upload_begin,
                           .upload_data = h_upload_data};
    uds_server_init(&D.srv, &app);
    D.firmware_xfer = 0;
    if (D.boot_status == BOOT_OK && D.boot.test_boot) {
        if (D.selftest_ok) {
            (void)boot_confirm(&D.boot);
        } else {
            /* the new image's self-test failed: it resets the device without confirming (as a
             * watchdog would); the bootloader reverts */
            D.boot_status = boot_select(&D.boot, &D.cfg);
            fwu_init(&D.fwu, &D.boot);
        }
    }
}

/* ---- C ABI for ctypes ---- */

int dev_create(const uint8_t *secret, uint32_t secret_len);
int dev_factory(const uint8_t *img, uint32_t len);
void dev_set_selftest(int ok);
uint16_t dev_handle(const uint8_t *req, uint16_t len, uint8_t *resp, uint16_t cap, uint32_t now_ms);
void dev_after_response(void);
uint32_t dev_running_version(void);
int dev_running_slot(void);
int dev_path(void);
int dev_boot_status(void);
void dev_power_loss_at(uint32_t n);
void dev_power_cycle(void);

int dev_create(const uint8_t *secret, uint32_t secret_len)
{
    memset(&D, 0, sizeof D);
    fls_ram_init(&D.ram, &D.flash, D.mem, SECTOR, N_SECTORS, 8u);
    D.cfg.app_dev = &D.app_dev;
    D.cfg.slot_addr[0] = 0u;
    D.cfg.slot_addr[1] = SLOT_SECTORS * SECTOR;
    D.cfg.slot_size = SLOT_SECTORS * SECTOR;
    D.cfg.state_nvm = &D.state_nvm;
    D.cfg.target_id = BOOT_TARGET_HOST;
    D.cfg.key = DEV_KEY;
    D.cfg.key_len = sizeof DEV_KEY;
    D.cfg.skill_min = 2u; /* stored skills of image format 2 (docs/skill_format.md) */
    D.cfg.skill_max = 2u;
    D.cfg.config_min = 1u;
    D.cfg.config_max = 1u;
    sec_default_config(&D.sec_cfg);
    if (secret_len > SEC_SECRET_MAX) {
        return -1;
    }
    memcpy(D.sec_cfg.secret, secret, secret_len);
    D.sec_cfg.secret_len = (uint8_t)secret_len;
    D.sec_cfg.boot_delay_ms = 0u; /* tests reset often; the delay rule is sec_access's test */
    D.sec_cfg.rng = rng;
    D.selftest_ok = 1;
    return (int)sec_config_validate(&D.sec_cfg);
}

int dev_factory(const uint8_t *img, uint32_t len)
{
    (void)boot_fls_window_init(&D.w_app, &D.app_dev, &D.flash, 2u, 2u * SLOT_SECTORS);
    for (uint32_t s = 0; s < SLOT_SECTORS; s++) {
        if (D.app_dev.erase(D.app_dev.ctx, s) != 0) {
            return -1;
        }
    }
    uint8_t unit[SECTOR];
    for (uint32_t off = 0; off < len; off += SECTOR) {
        const uint32_t n = len - off < SECTOR ? len - off : SECTOR;
        memset(unit, 0xFF, sizeof unit);
        memcpy(unit, img + off, n);
        if (D.app_dev.program(D.app_dev.ctx, off, unit, (n + 7u) / 8u * 8u) != 0) {
            return -1;
        }
    }
    power_on();
    return (int)D.boot_status;
}

void dev_set_selftest(int ok)
{
    D.selftest_ok = ok;
}

uint16_t dev_handle(const uint8_t *req, uint16_t len, uint8_t *resp, uint16_t cap, uint32_t now_ms)
{
    D.now_ms = now_ms;
    uds_server_poll(&D.srv, now_ms);
    uint16_t n = uds_server_handle(&D.srv, req, len, resp, cap, now_ms);
    while (D.srv.pending_sid != 0u) {
        /* a request answered 0x78 (the transfer exit's verification in slices): its slices
         * back to back, the final answer instead of the pending one */
        n = uds_server_resume(&D.srv, resp, cap, now_ms);
    }
    return n;
}

void dev_after_response(void)
{
    uds_server_after_response(&D.srv);
}

uint32_t dev_running_version(void)
{
    return D.boot.running_slot < BOOT_SLOT_COUNT ? D.boot.running.fw_version : 0u;
}

int dev_running_slot(void)
{
    return D.boot.running_slot;
}

int dev_path(void)
{
    return (int)D.boot.path;
}

int dev_boot_status(void)
{
    return (int)D.boot_status;
}

void dev_power_loss_at(uint32_t n)
{
    fls_ram_set_power_loss(&D.ram, n);
}

void dev_power_cycle(void)
{
    power_on();
}

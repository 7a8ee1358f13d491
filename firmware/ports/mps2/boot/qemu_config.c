/* qemu demo configuration (qemu_config.h). */
#include "qemu_config.h"

#include "boot_cm_flash.h"
#include "qemu_layout.h"

#ifndef FS_BOOT_TARGET
#define FS_BOOT_TARGET BOOT_TARGET_CORTEX_M3
#endif

/* Device key of the image tag. A product keeps it in protected storage (OTP / read-protected
 * flash); the demo compiles in the development key of host/forceskill/model/fwimage.py (DEV_KEY). */
static const uint8_t ql_key[32] = {0x40, 0x41, 0x42, 0x43, 0x44, 0x45, 0x46, 0x47, 0x48, 0x49, 0x4a,
                                   0x4b, 0x4c, 0x4d, 0x4e, 0x4f, 0x50, 0x51, 0x52, 0x53, 0x54, 0x55,
                                   0x56, 0x57, 0x58, 0x59, 0x5a, 0x5b, 0x5c, 0x5d, 0x5e, 0x5f};

static boot_cm_flash_t ql_app_flash, ql_state_flash;
static fls_dev_t ql_app_dev, ql_state_dev;
static nvm_t ql_state_nvm;

int ql_config(boot_config_t *cfg)
{
    boot_cm_flash_init(&ql_app_flash, &ql_app_dev, QL_SLOT_A_ADDR, QL_SECTOR_SIZE,
                       2u * QL_SLOT_SIZE / QL_SECTOR_SIZE);
    boot_cm_flash_init(&ql_state_flash, &ql_state_dev, QL_STATE_ADDR, QL_SECTOR_SIZE,
                       QL_STATE_SECTORS);
    const int st = (int)nvm_init(&ql_state_nvm, &ql_state_dev);
    cfg->app_dev = &ql_app_dev;
    cfg->slot_addr[0] = 0u;
    cfg->slot_addr[1] = QL_SLOT_B_ADDR - QL_SLOT_A_ADDR;
    cfg->slot_size = QL_SLOT_SIZE;
    cfg->state_nvm = &ql_state_nvm;
    cfg->state_slot = 0u;
    cfg->target_id = FS_BOOT_TARGET;
    cfg->key = ql_key;
    cfg->key_len = (uint32_t)sizeof ql_key;
    cfg->skill_min = 0u; /* the demo stores no skills or configuration */
    cfg->skill_max = 0u;
    cfg->config_min = 0u;
    cfg->config_max = 0u;
    return st;
}

const char *ql_status_name(boot_status_t st)
{
    switch (st) {
    case BOOT_OK: return "ok";
    case BOOT_ERR_TRUNCATED: return "truncated";
    case BOOT_ERR_MAGIC: return "no image (magic)";
    case BOOT_ERR_FORMAT: return "header format";
    case BOOT_ERR_TARGET: return "wrong target";
    case BOOT_ERR_TOO_LARGE: return "too large";
    case BOOT_ERR_HASH: return "payload SHA-256 mismatch";
    case BOOT_ERR_TAG: return "authentication tag wrong";
    case BOOT_ERR_DOWNGRADE: return "downgrade";
    case BOOT_ERR_SKILL_FORMAT: return "skill format";
    case BOOT_ERR_CONFIG_FORMAT: return "config format";
    case BOOT_ERR_NO_IMAGE: return "no bootable image";
    case BOOT_ERR_FLASH: return "flash error";
    default: return "error";
    }
}

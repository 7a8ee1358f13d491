/* The device's firmware update (app_fw.h). */
#include "app_fw.h"

#include <string.h>
#include "hal.h"
#include "skill.h"

void app_fw_init(app_fw_t *fw, uint8_t target_id, bool any_skill)
{
    /* the bootloader's decision runs here on the host port (flash kept across ECUReset); the
     * image confirms itself once its self-test has passed (first tick) */
    const fls_dev_t *dev = hal_fw_flash();
    const uint32_t slot_sectors = hal_fw_slot_sectors();
    (void)boot_fls_window_init(&fw->w_state, &fw->state_dev, dev, 0u, 2u);
    (void)boot_fls_window_init(&fw->w_slots, &fw->slots_dev, dev, 2u, 2u * slot_sectors);
    (void)nvm_init(&fw->state_nvm, &fw->state_dev);
    boot_config_t *bc = &fw->boot_cfg;
    bc->app_dev = &fw->slots_dev;
    bc->slot_addr[0] = 0u;
    bc->slot_addr[1] = slot_sectors * dev->sector_size;
    bc->slot_size = slot_sectors * dev->sector_size;
    bc->state_nvm = &fw->state_nvm;
    bc->state_slot = 0u;
    bc->target_id = target_id;
    uint8_t key_len = 0u;
    bc->key = hal_fw_key(&key_len);
    bc->key_len = key_len;
    bc->skill_min = any_skill ? (uint16_t)SKILL_FORMAT_VERSION_MIN : 0u;
    bc->skill_max = any_skill ? (uint16_t)SKILL_FORMAT_VERSION : 0u;
    bc->config_min = 0u; /* gains/limits are not persisted yet */
    bc->config_max = 0u;
    (void)boot_select(&fw->boot, bc);
    fwu_init(&fw->fwu, &fw->boot);
}

bool app_fw_self_test(app_fw_t *fw, bool config_ok, bool storage_ok)
{
    if (!fw->boot.test_boot) {
        return true;
    }
    if (!config_ok || !storage_ok) {
        return false;
    }
    /* simulator only: a host-target payload starting with this marker stands for a build whose
     * self-test fails (HIL test of the revert path, docs/update.md) */
    static const char fail_marker[] = "FSHOST-SELFTEST-FAIL";
    uint8_t head[sizeof fail_marker - 1u];
    const boot_config_t *bc = &fw->boot_cfg;
    if (bc->app_dev->read(bc->app_dev->ctx,
                          bc->slot_addr[fw->boot.running_slot] + BOOT_IMAGE_HEADER_SIZE, head,
                          (uint32_t)sizeof head) == 0 &&
        memcmp(head, fail_marker, sizeof head) == 0) {
        return false;
    }
    return boot_confirm(&fw->boot) == BOOT_OK;
}

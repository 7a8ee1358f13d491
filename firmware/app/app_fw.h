/* The device's firmware update (app_fw.c, over firmware/boot): the update flash's windows, the
 * bootloader's decision as this image sees it, the download of a new image (fwu) and the
 * running image's self-test on its test boot. */
#ifndef APP_FW_H
#define APP_FW_H

#include <stdbool.h>
#include <stdint.h>
#include "boot.h"
#include "boot_fls_window.h"
#include "fls.h"
#include "fwu.h"
#include "nvm.h"

/** The firmware update's state. */
typedef struct {
    boot_fls_window_t w_state, w_slots; /* the update flash: its state sectors, its two slots */
    fls_dev_t state_dev, slots_dev;
    nvm_t state_nvm;        /* the bootloader's state record */
    boot_config_t boot_cfg; /* the slots, the key, the data formats this image reads */
    boot_t boot;            /* the bootloader's decision (running slot, on test) */
    fwu_t fwu;              /* a new image's download, verification and activation */
    bool xfer;              /* the active UDS download is a firmware image */
    bool self_test_ok;      /* the running image passed its self-test (boot tick) */
} app_fw_t;

/** The update flash (hal_fw_flash) and the bootloader's decision for this image: target
 *  target_id, the skill formats it reads (none while no skill is stored: any_skill false). */
void app_fw_init(app_fw_t *fw, uint8_t target_id, bool any_skill);

/** The running image's self-test on its test boot (safety configuration valid, storage readable
 *  when config_ok and storage_ok) and its confirmation: true if confirmed or not on test. */
bool app_fw_self_test(app_fw_t *fw, bool config_ok, bool storage_ok);

#endif /* APP_FW_H */

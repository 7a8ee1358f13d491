/* Tiny test application for the qemu bootloader demo: says where it runs, runs a self-test
 * (verifies its own image), confirms itself if it is on its test boot, and exits. */
#include <stdbool.h>
#include <stdint.h>
#include "boot.h"
#include "qemu_config.h"
#include "qemu_layout.h"
#include "cm_semihost.h"

#define SCB_VTOR (*(volatile uint32_t *)0xE000ED08u)

int main(void)
{
    static boot_config_t cfg;
    (void)ql_config(&cfg);
    const uint32_t vt = SCB_VTOR;
    const uint8_t slot = vt >= QL_SLOT_B_ADDR ? 1u : 0u;
    boot_image_header_t h;
    const boot_status_t st = boot_slot_verify(&cfg, slot, &h);
    sh_puts("app: forceskill test application running from slot ");
    sh_puts(slot == 0u ? "A" : "B");
    sh_puts(", vector table ");
    sh_puthex(vt);
    sh_puts(", version ");
    sh_putdec(h.fw_version >> 24);
    sh_puts(".");
    sh_putdec((h.fw_version >> 16) & 0xFFu);
    sh_puts(".");
    sh_putdec(h.fw_version & 0xFFFFu);
    sh_puts("\n");
    if (st != BOOT_OK) {
        sh_puts("app: self-test FAILED: own image does not verify\n");
        return 5;
    }
    boot_state_t before;
    const bool on_test = boot_state_load(&cfg, &before) && before.test_slot == slot &&
                         before.test_attempts == 1u;
    const boot_status_t c = boot_confirm_slot(&cfg, slot);
    boot_state_t after;
    (void)boot_state_load(&cfg, &after);
    sh_puts("app: self-test passed");
    if (on_test) {
        sh_puts(c == BOOT_OK && after.active_slot == slot && after.test_slot == BOOT_SLOT_NONE
                    ? "; test boot confirmed: this image is now the active one\n"
                    : "; confirm FAILED\n");
    } else {
        sh_puts("; already the active image\n");
    }
    return c == BOOT_OK ? 0 : 6;
}

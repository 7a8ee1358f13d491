/* The Cortex-M bootloader (qemu mps2 demo): verify both slots, apply the A/B rules of boot.h,
 * start the chosen image through its vector table, or stay here if nothing is authorised. */
#include <stdint.h>
#include "boot.h"
#include "qemu_config.h"
#include "qemu_layout.h"
#include "cm_semihost.h"

#define SCB_VTOR (*(volatile uint32_t *)0xE000ED08u)

static void put_version(uint32_t v)
{
    sh_putdec(v >> 24);
    sh_puts(".");
    sh_putdec((v >> 16) & 0xFFu);
    sh_puts(".");
    sh_putdec(v & 0xFFFFu);
}

static const char *const PATH[] = {"none",
                                   "active",
                                   "test (first boot, must confirm)",
                                   "reverted (test image did not confirm)",
                                   "active (test image refused)",
                                   "recovered (other slot)",
                                   "first boot"};

__attribute__((noreturn)) static void start(uint32_t vt)
{
    const uint32_t sp = ((const volatile uint32_t *)vt)[0];
    const uint32_t pc = ((const volatile uint32_t *)vt)[1];
    SCB_VTOR = vt;
    __asm__ volatile("msr msp, %0\n\tdsb\n\tisb\n\tbx %1" : : "r"(sp), "r"(pc) : "memory");
    __builtin_unreachable();
}

int main(void)
{
    static boot_config_t cfg;
    static boot_t b;
    sh_puts("boot: forceskill bootloader, target id ");
    sh_putdec(FS_BOOT_TARGET);
    sh_puts("\n");
    (void)ql_config(&cfg);
    for (uint8_t s = 0u; s < BOOT_SLOT_COUNT; s++) {
        boot_image_header_t h;
        const boot_status_t st = boot_slot_verify(&cfg, s, &h);
        sh_puts(s == 0u ? "boot: slot A: " : "boot: slot B: ");
        if (st == BOOT_OK) {
            sh_puts("version ");
            put_version(h.fw_version);
            sh_puts(" build '");
            sh_puts(h.build_id);
            sh_puts("' verified (SHA-256 + HMAC-SHA256 tag)\n");
        } else {
            sh_puts("refused: ");
            sh_puts(ql_status_name(st));
            sh_puts(" (");
            sh_putdec((uint32_t)st);
            sh_puts(")\n");
        }
    }
    const boot_status_t st = boot_select(&b, &cfg);
    if (st != BOOT_OK) {
        sh_puts("boot: no bootable image: staying in the bootloader (");
        sh_putdec((uint32_t)st);
        sh_puts(")\n");
        return 3;
    }
    const uint32_t base = (b.running_slot == 0u ? QL_SLOT_A_ADDR : QL_SLOT_B_ADDR);
    const uint32_t vt = base + BOOT_IMAGE_HEADER_SIZE + b.running.entry_offset;
    const uint32_t sp = ((const volatile uint32_t *)vt)[0];
    const uint32_t pc = ((const volatile uint32_t *)vt)[1];
    /* the image is authorised; still refuse a vector table that cannot be right */
    if ((vt & 0x7Fu) != 0u || (pc & 1u) == 0u || pc < base || pc >= base + QL_SLOT_SIZE ||
        sp < 0x20000000u || sp > QL_RAM_TOP) {
        sh_puts("boot: vector table of the chosen image is invalid: not started\n");
        return 4;
    }
    sh_puts("boot: starting slot ");
    sh_puts(b.running_slot == 0u ? "A" : "B");
    sh_puts(", version ");
    put_version(b.running.fw_version);
    sh_puts(", path ");
    sh_puts(PATH[b.path]);
    sh_puts("\n");
    start(vt);
}

/* Memory map of the bootloader demo on qemu mps2-an385/an386 (docs/update.md). QEMU models the
 * 4 MiB code SSRAM at 0x00000000 as RAM, so it stands in for flash here: the fls_ driver below
 * (boot_cm_flash.c) gives it NOR semantics (erase to 0xFF, programming only clears bits).
 * Keep in sync with boot.ld and app.ld.in. */
#ifndef QEMU_LAYOUT_H
#define QEMU_LAYOUT_H

#define QL_SECTOR_SIZE 0x1000u    /* 4 KiB erase sectors */
#define QL_BOOT_ADDR 0x00000000u  /* bootloader, 64 KiB */
#define QL_STATE_ADDR 0x00010000u /* boot state: 2 sectors (one nvm record, two copies) */
#define QL_STATE_SECTORS 2u
#define QL_SLOT_A_ADDR 0x00020000u /* application slot A, 256 KiB */
#define QL_SLOT_B_ADDR 0x00060000u /* application slot B, 256 KiB */
#define QL_SLOT_SIZE 0x00040000u
#define QL_ENTRY_OFFSET \
    0x180u /* vector table offset in the payload (slot + 0x200: VTOR
                                         alignment for up to 128 vectors) */
#define QL_RAM_TOP 0x20400000u

#endif /* QEMU_LAYOUT_H */

/* fls_ driver for memory-mapped "flash" (qemu's code SSRAM) with NOR semantics. */
#ifndef BOOT_CM_FLASH_H
#define BOOT_CM_FLASH_H

#include <stdint.h>
#include "fls.h"

/* Bytes of a sector erased per busy() poll: the emulated controller's erase spread over the
 * polls, as a real one erases in the background (its memset, ~0.5 instructions a byte, is the
 * emulation's and counts in the tick: 1,024 bytes put the M4F's worst FWUPDATE tick at 2,287). */
#define BOOT_CM_FLASH_ERASE_SLICE_BYTES 256u

/** One region: base address and geometry, and the erase in progress (erase_left bytes of
 *  sector erase_sector still to erase; 0: none). */
typedef struct {
    uintptr_t base;
    uint32_t sector_size;
    uint32_t sector_count;
    uint32_t erase_sector;
    uint32_t erase_left;
} boot_cm_flash_t;

/** Fill *dev for sector_count sectors of sector_size bytes at base (write unit 4); its erase
 *  runs BOOT_CM_FLASH_ERASE_SLICE_BYTES a busy() poll (fls.h). */
void boot_cm_flash_init(boot_cm_flash_t *f, fls_dev_t *dev, uintptr_t base, uint32_t sector_size,
                        uint32_t sector_count);

#endif /* BOOT_CM_FLASH_H */

/* fls_ driver for memory-mapped "flash" (qemu's code SSRAM) with NOR semantics. */
#ifndef BOOT_CM_FLASH_H
#define BOOT_CM_FLASH_H

#include <stdint.h>
#include "fls.h"

/** One region: base address and geometry. */
typedef struct {
    uintptr_t base;
    uint32_t sector_size;
    uint32_t sector_count;
} boot_cm_flash_t;

/** Fill *dev for sector_count sectors of sector_size bytes at base (write unit 4). */
void boot_cm_flash_init(boot_cm_flash_t *f, fls_dev_t *dev, uintptr_t base, uint32_t sector_size,
                        uint32_t sector_count);

#endif /* BOOT_CM_FLASH_H */

/* Memory-mapped NOR flash emulation for qemu (boot_cm_flash.h). */
#include "boot_cm_flash.h"

#include <string.h>

static int cm_erase(void *ctx, uint32_t sector)
{
    const boot_cm_flash_t *f = (const boot_cm_flash_t *)ctx;
    if (sector >= f->sector_count) {
        return -1;
    }
    memset((void *)(f->base + sector * f->sector_size), 0xFF, f->sector_size);
    return 0;
}

static int cm_read(void *ctx, uint32_t addr, uint8_t *data, uint32_t len)
{
    const boot_cm_flash_t *f = (const boot_cm_flash_t *)ctx;
    if ((uint64_t)addr + len > (uint64_t)f->sector_size * f->sector_count) {
        return -1;
    }
    memcpy(data, (const void *)(f->base + addr), len);
    return 0;
}

static int cm_program(void *ctx, uint32_t addr, const uint8_t *data, uint32_t len)
{
    const boot_cm_flash_t *f = (const boot_cm_flash_t *)ctx;
    if ((uint64_t)addr + len > (uint64_t)f->sector_size * f->sector_count) {
        return -1;
    }
    uint32_t i = 0u;
    if (((f->base + addr) & 3u) == 0u) {
        /* whole words (the write unit): 4 bytes per access */
        volatile uint32_t *w = (volatile uint32_t *)(f->base + addr);
        for (; i + 4u <= len; i += 4u) {
            uint32_t d;
            memcpy(&d, &data[i], 4u);
            w[i / 4u] = w[i / 4u] & d; /* NOR: programming clears bits only */
        }
    }
    volatile uint8_t *p = (volatile uint8_t *)(f->base + addr);
    for (; i < len; i++) {
        p[i] = (uint8_t)(p[i] & data[i]); /* NOR: programming clears bits only */
    }
    return 0;
}

void boot_cm_flash_init(boot_cm_flash_t *f, fls_dev_t *dev, uintptr_t base, uint32_t sector_size,
                        uint32_t sector_count)
{
    f->base = base;
    f->sector_size = sector_size;
    f->sector_count = sector_count;
    dev->sector_size = sector_size;
    dev->sector_count = sector_count;
    dev->write_unit = 4u;
    dev->erase = cm_erase;
    dev->program = cm_program;
    dev->read = cm_read;
    dev->ctx = f;
}

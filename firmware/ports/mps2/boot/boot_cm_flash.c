/* Memory-mapped NOR flash emulation for qemu (boot_cm_flash.h). */
#include "boot_cm_flash.h"

#include <string.h>

/* One slice of the erase in progress: its next bytes set to 0xFF; 1 while bytes are left. */
static int cm_busy(void *ctx)
{
    boot_cm_flash_t *f = (boot_cm_flash_t *)ctx;
    if (f->erase_left == 0u) {
        return 0;
    }
    const uint32_t n = (f->erase_left < BOOT_CM_FLASH_ERASE_SLICE_BYTES)
                           ? f->erase_left
                           : BOOT_CM_FLASH_ERASE_SLICE_BYTES;
    const uint32_t off = f->sector_size - f->erase_left;
    memset((void *)(f->base + f->erase_sector * f->sector_size + off), 0xFF, n);
    f->erase_left -= n;
    return f->erase_left != 0u ? 1 : 0;
}

/* The erase in progress to its end (before any other access). */
static void cm_finish(boot_cm_flash_t *f)
{
    while (cm_busy(f) != 0) {
    }
}

static int cm_erase(void *ctx, uint32_t sector)
{
    boot_cm_flash_t *f = (boot_cm_flash_t *)ctx;
    cm_finish(f);
    if (sector >= f->sector_count) {
        return -1;
    }
    f->erase_sector = sector; /* started: cm_busy erases it slice by slice */
    f->erase_left = f->sector_size;
    return 0;
}

static int cm_read(void *ctx, uint32_t addr, uint8_t *data, uint32_t len)
{
    boot_cm_flash_t *f = (boot_cm_flash_t *)ctx;
    cm_finish(f);
    if ((uint64_t)addr + len > (uint64_t)f->sector_size * f->sector_count) {
        return -1;
    }
    memcpy(data, (const void *)(f->base + addr), len);
    return 0;
}

static int cm_program(void *ctx, uint32_t addr, const uint8_t *data, uint32_t len)
{
    boot_cm_flash_t *f = (boot_cm_flash_t *)ctx;
    cm_finish(f);
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
    f->erase_sector = 0u;
    f->erase_left = 0u;
    dev->sector_size = sector_size;
    dev->sector_count = sector_count;
    dev->write_unit = 4u;
    dev->erase = cm_erase;
    dev->program = cm_program;
    dev->read = cm_read;
    dev->busy = cm_busy;
    dev->ctx = f;
}

/* Flash window (boot_fls_window.h). */
#include "boot_fls_window.h"

#include <stddef.h>

/* 1 if [addr, addr+len) lies inside the window. */
static int inside(const boot_fls_window_t *w, uint32_t addr, uint32_t len)
{
    const uint64_t size = (uint64_t)w->sector_count * w->parent->sector_size;
    return (uint64_t)addr + len <= size;
}

static int win_erase(void *ctx, uint32_t sector)
{
    const boot_fls_window_t *w = (const boot_fls_window_t *)ctx;
    if (sector >= w->sector_count) {
        return -1;
    }
    return w->parent->erase(w->parent->ctx, w->first_sector + sector);
}

static int win_busy(void *ctx)
{
    const boot_fls_window_t *w = (const boot_fls_window_t *)ctx;
    return w->parent->busy(w->parent->ctx);
}

static int win_program(void *ctx, uint32_t addr, const uint8_t *data, uint32_t len)
{
    const boot_fls_window_t *w = (const boot_fls_window_t *)ctx;
    if (!inside(w, addr, len)) {
        return -1;
    }
    return w->parent->program(w->parent->ctx, w->first_sector * w->parent->sector_size + addr, data,
                              len);
}

static int win_read(void *ctx, uint32_t addr, uint8_t *data, uint32_t len)
{
    const boot_fls_window_t *w = (const boot_fls_window_t *)ctx;
    if (!inside(w, addr, len)) {
        return -1;
    }
    return w->parent->read(w->parent->ctx, w->first_sector * w->parent->sector_size + addr, data,
                           len);
}

int boot_fls_window_init(boot_fls_window_t *w, fls_dev_t *dev, const fls_dev_t *parent,
                         uint32_t first_sector, uint32_t sector_count)
{
    if (w == NULL || dev == NULL || parent == NULL || sector_count == 0u ||
        first_sector > parent->sector_count || sector_count > parent->sector_count - first_sector) {
        return -1;
    }
    w->parent = parent;
    w->first_sector = first_sector;
    w->sector_count = sector_count;
    dev->sector_size = parent->sector_size;
    dev->sector_count = sector_count;
    dev->write_unit = parent->write_unit;
    dev->erase = win_erase;
    dev->program = win_program;
    dev->read = win_read;
    dev->busy = (parent->busy != NULL) ? win_busy : NULL;
    dev->ctx = w;
    return 0;
}

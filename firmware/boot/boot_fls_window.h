/* A window onto a range of sectors of another flash device, itself a flash device (fls.h): lets
 * one physical flash hold the boot-state records, the skill records and both application slots,
 * each seen from its own address 0. Used by the ports and the tests. */
#ifndef BOOT_FLS_WINDOW_H
#define BOOT_FLS_WINDOW_H

#include <stdint.h>
#include "fls.h"

/** Window state: sectors [first_sector, first_sector + sector_count) of parent. */
typedef struct {
    const fls_dev_t *parent;
    uint32_t first_sector;
    uint32_t sector_count;
} boot_fls_window_t;

/** Fill *dev as the window (same sector size and write unit as parent). Returns 0, or -1 if the
 *  range does not fit the parent. */
int boot_fls_window_init(boot_fls_window_t *w, fls_dev_t *dev, const fls_dev_t *parent,
                         uint32_t first_sector, uint32_t sector_count);

#endif /* BOOT_FLS_WINDOW_H */

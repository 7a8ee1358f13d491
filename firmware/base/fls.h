/* Flash HAL contract used by the slot storage (nvm_*): NOR-flash semantics.
 * - erase(sector) sets every byte of the sector to 0xFF;
 * - program(addr, data, len) can only clear bits (new = old & data); addr and len are multiples
 *   of write_unit; programming does not cross a sector boundary;
 * - read(addr, data, len) copies bytes out.
 * Each returns 0 on success, non-zero on failure. A port implements the three functions over
 * its flash controller (the host and the tests use fls_ram.h). Not re-entrant: the caller
 * serialises access (nvm is only called outside the control tick). */
#ifndef FLS_H
#define FLS_H

#include <stdint.h>

/** One flash device (or region) given to the storage. */
typedef struct {
    uint32_t sector_size; /* bytes per erase sector */
    uint32_t sector_count;
    uint32_t write_unit; /* programming granularity in bytes (1, 4, 8, ...; <= 16) */
    int (*erase)(void *ctx, uint32_t sector);
    int (*program)(void *ctx, uint32_t addr, const uint8_t *data, uint32_t len);
    int (*read)(void *ctx, uint32_t addr, uint8_t *data, uint32_t len);
    void *ctx; /* the port's device handle, passed back to every call */
} fls_dev_t;

#endif /* FLS_H */

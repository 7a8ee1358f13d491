/* Flash HAL contract used by the slot storage (nvm_*): NOR-flash semantics.
 * - erase(sector) sets every byte of the sector to 0xFF;
 * - program(addr, data, len) can only clear bits (new = old & data); addr and len are multiples
 *   of write_unit; programming does not cross a sector boundary;
 * - read(addr, data, len) copies bytes out;
 * - busy (optional): NULL when erase() finishes the sector before it returns. Otherwise erase()
 *   only starts it and busy() advances it, non-zero while it goes on (a flash controller's busy
 *   flag polled): the caller polls busy() down to 0 before its next call. A program() or read()
 *   while busy finishes the erase first, so a caller that never polls still sees NOR semantics.
 * Each returns 0 on success, non-zero on failure. A port implements the three functions over
 * its flash controller (the host and the tests use fls_ram.h). Not re-entrant: the caller
 * serialises access (nvm is only called outside the control tick). */
#ifndef FLS_H
#define FLS_H

#include <stddef.h>
#include <stdint.h>

/** One flash device (or region) given to the storage. */
typedef struct {
    uint32_t sector_size; /* bytes per erase sector */
    uint32_t sector_count;
    uint32_t write_unit; /* programming granularity in bytes (1, 4, 8, ...; <= 16) */
    int (*erase)(void *ctx, uint32_t sector);
    int (*program)(void *ctx, uint32_t addr, const uint8_t *data, uint32_t len);
    int (*read)(void *ctx, uint32_t addr, uint8_t *data, uint32_t len);
    int (*busy)(void *ctx); /* NULL: a synchronous erase; see above */
    void *ctx;              /* the port's device handle, passed back to every call */
} fls_dev_t;

/** Poll d's erase in progress to its end (no-op for a synchronous erase); 0, or non-zero when
 *  the device reports a failure (busy() < 0). */
static inline int fls_wait(const fls_dev_t *d)
{
    int b = (d->busy != NULL) ? d->busy(d->ctx) : 0;
    while (b > 0) {
        b = d->busy(d->ctx);
    }
    return b;
}

#endif /* FLS_H */

/* RAM-backed simulated NOR flash with power-loss injection: see fls_ram.h. */
#include "fls_ram.h"

#include <stddef.h>
#include <string.h>

/* Count one erase/program; true if this one is the torn operation (power lost during it). */
static int op_begin(fls_ram_t *f, int *torn)
{
    if (f->dead != 0u) {
        return -1;
    }
    f->ops++;
    f->total_ops++;
    *torn = (f->power_loss_at != 0u && f->ops == f->power_loss_at) ? 1 : 0;
    return 0;
}

static int ram_erase(void *ctx, uint32_t sector)
{
    fls_ram_t *f = (fls_ram_t *)ctx;
    int torn = 0;
    if (f == NULL || sector >= f->sector_count || op_begin(f, &torn) != 0) {
        return -1;
    }
    f->erase_count++;
    uint8_t *p = f->mem + (size_t)sector * f->sector_size;
    if (torn != 0) {
        (void)memset(p, 0xFF, f->sector_size / 2u); /* the rest keeps its old contents */
        f->dead = 1u;
        return -1;
    }
    (void)memset(p, 0xFF, f->sector_size);
    return 0;
}

static int ram_program(void *ctx, uint32_t addr, const uint8_t *data, uint32_t len)
{
    fls_ram_t *f = (fls_ram_t *)ctx;
    int torn = 0;
    if (f == NULL || data == NULL || len == 0u || (addr % f->write_unit) != 0u ||
        (len % f->write_unit) != 0u) {
        return -1;
    }
    const uint64_t size = (uint64_t)f->sector_size * f->sector_count;
    if ((uint64_t)addr + len > size ||
        (addr / f->sector_size) != ((addr + len - 1u) / f->sector_size)) {
        return -1;
    }
    if (op_begin(f, &torn) != 0) {
        return -1;
    }
    f->program_count++;
    uint32_t n = len;
    if (torn != 0) {
        /* first half of the write units complete, the next unit half programmed */
        const uint32_t units = len / f->write_unit;
        n = (units / 2u) * f->write_unit + (f->write_unit + 1u) / 2u;
        if (n > len) {
            n = len;
        }
    }
    for (uint32_t i = 0u; i < n; i++) {
        f->mem[addr + i] &= data[i]; /* NOR: programming only clears bits */
    }
    if (torn != 0) {
        f->dead = 1u;
        return -1;
    }
    return 0;
}

static int ram_read(void *ctx, uint32_t addr, uint8_t *data, uint32_t len)
{
    fls_ram_t *f = (fls_ram_t *)ctx;
    if (f == NULL || data == NULL || f->dead != 0u) {
        return -1;
    }
    const uint64_t size = (uint64_t)f->sector_size * f->sector_count;
    if ((uint64_t)addr + len > size) {
        return -1;
    }
    (void)memcpy(data, f->mem + addr, len);
    return 0;
}

void fls_ram_init(fls_ram_t *f, fls_dev_t *dev, uint8_t *mem, uint32_t sector_size,
                  uint32_t sector_count, uint32_t write_unit)
{
    if (f == NULL || dev == NULL || mem == NULL) {
        return;
    }
    f->mem = mem;
    f->sector_size = sector_size;
    f->sector_count = sector_count;
    f->write_unit = (write_unit == 0u) ? 1u : write_unit;
    f->ops = 0u;
    f->total_ops = 0u;
    f->power_loss_at = 0u;
    f->dead = 0u;
    f->erase_count = 0u;
    f->program_count = 0u;
    (void)memset(mem, 0xFF, (size_t)sector_size * sector_count);
    dev->sector_size = sector_size;
    dev->sector_count = sector_count;
    dev->write_unit = f->write_unit;
    dev->erase = ram_erase;
    dev->program = ram_program;
    dev->read = ram_read;
    dev->busy = NULL; /* a synchronous erase */
    dev->ctx = f;
}

void fls_ram_set_power_loss(fls_ram_t *f, uint32_t n)
{
    if (f != NULL) {
        f->power_loss_at = (n == 0u) ? 0u : f->ops + n;
    }
}

void fls_ram_power_cycle(fls_ram_t *f)
{
    if (f != NULL) {
        f->dead = 0u;
        f->ops = 0u;
        f->power_loss_at = 0u;
    }
}

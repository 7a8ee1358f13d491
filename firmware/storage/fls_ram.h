/* RAM-backed simulated NOR flash for the host port and the tests, with power-loss injection:
 * every erase and program counts as one write operation; when the counter reaches
 * power_loss_at (1-based) that operation is torn (a program writes only its first half of
 * write units; an erase clears only the first half of the sector to 0xFF, leaving the rest as
 * it was) and the device then refuses every further operation until fls_ram_power_cycle. */
#ifndef FLS_RAM_H
#define FLS_RAM_H

#include <stdint.h>
#include "fls.h"

/** Simulated flash: the caller provides the storage (sector_size * sector_count bytes). */
typedef struct {
    uint8_t *mem;
    uint32_t sector_size;
    uint32_t sector_count;
    uint32_t write_unit;
    uint32_t ops;           /* erase + program operations since the last power cycle */
    uint32_t total_ops;     /* erase + program operations since fls_ram_init */
    uint32_t power_loss_at; /* 0 = never; else tear the op with ops == power_loss_at */
    uint8_t dead;           /* power lost: every call fails until fls_ram_power_cycle */
    uint32_t erase_count;
    uint32_t program_count;
} fls_ram_t;

/** Initialise over mem (erased to 0xFF) and fill *dev with the HAL functions. */
void fls_ram_init(fls_ram_t *f, fls_dev_t *dev, uint8_t *mem, uint32_t sector_size,
                  uint32_t sector_count, uint32_t write_unit);

/** Arm a power loss at the n-th erase/program from now (0 disarms). */
void fls_ram_set_power_loss(fls_ram_t *f, uint32_t n);

/** Power back on: the memory keeps its contents, the op counter restarts, no loss armed. */
void fls_ram_power_cycle(fls_ram_t *f);

#endif /* FLS_RAM_H */

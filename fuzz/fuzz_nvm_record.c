/* libFuzzer harness: the storage's record parser and its flash scan.
 * 1. nvm_record_parse on the raw input (any slot);
 * 2. the input is laid into a 4-sector simulated flash, nvm_init scans it and every slot the
 *    directory calls valid must read back with a matching CRC; then a write to every slot must
 *    succeed and read back exactly, whatever garbage was there (abort() otherwise). */
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "fls_ram.h"
#include "nvm.h"

#define SECTOR 512u
#define SECTORS 4u

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static uint8_t mem[SECTOR * SECTORS];
    static uint8_t buf[SECTOR];
    if (size > SECTOR * SECTORS) {
        size = SECTOR * SECTORS;
    }
    nvm_record_info_t info;
    if (nvm_record_parse(data, (uint32_t)size, 0xFFFFu, &info) == NVM_OK) {
        if ((uint64_t)info.payload_offset + info.length + NVM_COMMIT_SIZE > size) {
            abort();
        }
        if (nvm_crc32(nvm_crc32(0u, data, 16u), data + info.payload_offset, info.length) !=
            info.crc32) {
            abort();
        }
    }
    fls_ram_t ram;
    fls_dev_t dev;
    fls_ram_init(&ram, &dev, mem, SECTOR, SECTORS, 4u);
    memcpy(mem, data, size);
    nvm_t n;
    if (nvm_init(&n, &dev) != NVM_OK) {
        abort();
    }
    for (uint16_t s = 0; s < n.n_slots; s++) {
        const nvm_dir_entry_t *e = nvm_dir(&n, s);
        uint32_t len = 0;
        const nvm_status_t r = nvm_read(&n, s, buf, sizeof buf, &len);
        if (e->valid != 0u && (r != NVM_OK || len != e->length)) {
            abort();
        }
        if (e->valid == 0u && r != NVM_ERR_EMPTY) {
            abort();
        }
    }
    const uint32_t wl = (uint32_t)(size % 200u);
    for (uint16_t s = 0; s < n.n_slots; s++) {
        if (nvm_write(&n, s, data, wl) != NVM_OK) {
            abort();
        }
        uint32_t len = 0;
        if (nvm_read(&n, s, buf, sizeof buf, &len) != NVM_OK || len != wl ||
            (wl != 0u && memcmp(buf, data, wl) != 0)) {
            abort();
        }
    }
    return 0;
}

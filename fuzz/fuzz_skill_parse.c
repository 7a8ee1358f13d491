/* libFuzzer harness: skill_parse (firmware/core) on arbitrary bytes, twice: as given, and with
 * the trailing CRC-32 recomputed (so the fuzzer reaches the checks behind the CRC: sizes,
 * finite values, ranges, centres, gains). Beyond "no crash / no sanitizer report", an accepted
 * image must satisfy the documented invariants and every refusal must be a documented code,
 * else abort(). */
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "skill.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void check_one(const uint8_t *data, size_t size)
{
    static skill_t sk;
    const fs_status_t s = skill_parse(data, (uint32_t)size, &sk);
    if (s == FS_OK) {
        const uint16_t n = sk.dmp.n_kernels;
        if (n == 0u || n > DMP_MAX_KERNELS || size != skill_image_size(n)) {
            abort();
        }
        if (skill_crc32(0u, data, (uint32_t)size - SKILL_CRC_SIZE) !=
            ((uint32_t)data[size - 4] | ((uint32_t)data[size - 3] << 8) |
             ((uint32_t)data[size - 2] << 16) | ((uint32_t)data[size - 1] << 24))) {
            abort();
        }
        for (uint16_t i = 0; i < n; i++) {
            if (!fs_isfinite(sk.dmp.weight[i]) || !(sk.dmp.width[i] > 0) || sk.dmp.centre[i] < 0 ||
                sk.dmp.centre[i] > 1) {
                abort();
            }
        }
        if (!(sk.dmp.p.beta <= sk.dmp.p.alpha / 4 * (1 + 1e-6))) {
            abort();
        }
    } else if (!((s >= 200 && s < 300) || (s >= 100 && s <= 112))) {
        abort(); /* every refusal is a documented code: 2xx image, 1xx parameters */
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static uint8_t fixed[SKILL_IMAGE_MAX + 64u];
    check_one(data, size);
    if (size >= SKILL_HEADER_SIZE_V2 + SKILL_CRC_SIZE && size <= sizeof fixed) {
        memcpy(fixed, data, size);
        const uint32_t crc = skill_crc32(0u, fixed, (uint32_t)size - SKILL_CRC_SIZE);
        for (uint32_t i = 0; i < 4u; i++) {
            fixed[size - 4u + i] = (uint8_t)(crc >> (8u * i));
        }
        check_one(fixed, size);
    }
    return 0;
}

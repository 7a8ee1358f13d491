/* Firmware image, format version 1 (docs/update.md): header (128 bytes) || payload || tag (32).
 * Little-endian. tag = HMAC-SHA256(device key, header || payload) (firmware/security). Parsing is
 * pure; verification streams the image out of flash through the fls_ HAL in small chunks.
 *
 *   offset size field
 *   0      4    magic                0x57465346 ("FSFW")
 *   4      2    format_version       1
 *   6      2    header_size          128
 *   8      4    fw_version           major<<24 | minor<<16 | patch
 *   12     4    payload_length       bytes
 *   16     4    target_id            1 cortex-m4f, 2 cortex-m3, 3 host
 *   20     4    flags                0 (others refused)
 *   24     2    skill_format         skill image version the firmware reads natively
 *   26     2    skill_format_oldest  oldest stored skill version it migrates from
 *   28     2    config_format        configuration record version, natively
 *   30     2    config_format_oldest oldest stored configuration version it migrates from
 *   32     4    entry_offset         Cortex-M: vector table offset from the payload start
 *   36     28   reserved             0
 *   64     32   payload_sha256
 *   96     32   build_id             ASCII, NUL-padded (e.g. git describe)
 */
#ifndef BOOT_IMAGE_H
#define BOOT_IMAGE_H

#include <stdint.h>
#include "boot_status.h"
#include "fls.h"
#include "fs_wire_const.h"

#define BOOT_IMAGE_MAGIC 0x57465346u
#define BOOT_IMAGE_FORMAT_VERSION 1u
#define BOOT_IMAGE_HEADER_SIZE 128u
#define BOOT_IMAGE_TAG_SIZE 32u
#define BOOT_IMAGE_OVERHEAD (BOOT_IMAGE_HEADER_SIZE + BOOT_IMAGE_TAG_SIZE)

/* image target ids (wire.toml: the host's image tools share them) */
#define BOOT_TARGET_CORTEX_M4F FS_TARGET_CORTEX_M4F
#define BOOT_TARGET_CORTEX_M3 FS_TARGET_CORTEX_M3
#define BOOT_TARGET_HOST FS_TARGET_HOST

/** Pack a semantic version the way the header stores it. */
#define BOOT_VERSION(major, minor, patch) \
    (((uint32_t)(major) << 24) | ((uint32_t)(minor) << 16) | (uint32_t)(patch))

/** Decoded header fields. */
typedef struct {
    uint32_t fw_version;
    uint32_t payload_length;
    uint32_t target_id;
    uint16_t skill_format, skill_format_oldest;
    uint16_t config_format, config_format_oldest;
    uint32_t entry_offset;
    uint8_t payload_sha256[32];
    char build_id[33]; /* NUL-terminated copy */
} boot_image_header_t;

/** Parse and check the 128 header bytes (magic 701, format/flags/reserved/entry 702, target 703
 *  unless want_target is 0). Pure. */
boot_status_t boot_image_parse_header(const uint8_t hdr[BOOT_IMAGE_HEADER_SIZE],
                                      uint32_t want_target, boot_image_header_t *out);

/** Total image bytes (header + payload + tag) for a parsed header. */
uint32_t boot_image_total_len(const boot_image_header_t *h);

/** Check that stored data can be read by the image: each of skill/config "min..max stored
 *  version" (0,0 = nothing stored) must lie in [oldest, native] (708 / 709). */
boot_status_t boot_image_check_data(const boot_image_header_t *h, uint16_t skill_min,
                                    uint16_t skill_max, uint16_t config_min, uint16_t config_max);

#endif /* BOOT_IMAGE_H */

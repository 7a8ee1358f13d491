/* Firmware image header parsing and streaming verification (boot_image.h). */
#include "boot_image.h"

#include <stddef.h>

static uint32_t rd_u32(const uint8_t *p)
{
    return (uint32_t)p[0] | ((uint32_t)p[1] << 8) | ((uint32_t)p[2] << 16) | ((uint32_t)p[3] << 24);
}

static uint16_t rd_u16(const uint8_t *p)
{
    return (uint16_t)((uint32_t)p[0] | ((uint32_t)p[1] << 8));
}

boot_status_t boot_image_parse_header(const uint8_t hdr[BOOT_IMAGE_HEADER_SIZE],
                                      uint32_t want_target, boot_image_header_t *out)
{
    if (hdr == NULL || out == NULL) {
        return BOOT_ERR_ARG;
    }
    if (rd_u32(hdr) != BOOT_IMAGE_MAGIC) {
        return BOOT_ERR_MAGIC;
    }
    out->fw_version = rd_u32(hdr + 8);
    out->payload_length = rd_u32(hdr + 12);
    out->target_id = rd_u32(hdr + 16);
    out->skill_format = rd_u16(hdr + 24);
    out->skill_format_oldest = rd_u16(hdr + 26);
    out->config_format = rd_u16(hdr + 28);
    out->config_format_oldest = rd_u16(hdr + 30);
    out->entry_offset = rd_u32(hdr + 32);
    uint8_t reserved_or = 0u;
    for (uint32_t i = 36u; i < 64u; i++) {
        reserved_or |= hdr[i];
    }
    if (rd_u16(hdr + 4) != BOOT_IMAGE_FORMAT_VERSION || rd_u16(hdr + 6) != BOOT_IMAGE_HEADER_SIZE ||
        rd_u32(hdr + 20) != 0u || reserved_or != 0u || out->payload_length == 0u ||
        out->payload_length > 0xFFFFFFFFu - BOOT_IMAGE_OVERHEAD || (out->entry_offset & 3u) != 0u ||
        out->entry_offset >= out->payload_length || out->skill_format_oldest == 0u ||
        out->skill_format_oldest > out->skill_format || out->config_format_oldest == 0u ||
        out->config_format_oldest > out->config_format) {
        return BOOT_ERR_FORMAT;
    }
    for (uint32_t i = 0u; i < 32u; i++) {
        out->payload_sha256[i] = hdr[64u + i];
        out->build_id[i] = (char)hdr[96u + i];
    }
    out->build_id[32] = '\0';
    if (want_target != 0u && out->target_id != want_target) {
        return BOOT_ERR_TARGET;
    }
    return BOOT_OK;
}

uint32_t boot_image_total_len(const boot_image_header_t *h)
{
    return h->payload_length + BOOT_IMAGE_OVERHEAD;
}

static boot_status_t check_range(uint16_t lo, uint16_t hi, uint16_t oldest, uint16_t native,
                                 boot_status_t err)
{
    if (lo == 0u && hi == 0u) {
        return BOOT_OK; /* nothing stored */
    }
    return (lo >= oldest && hi <= native && lo <= hi) ? BOOT_OK : err;
}

boot_status_t boot_image_check_data(const boot_image_header_t *h, uint16_t skill_min,
                                    uint16_t skill_max, uint16_t config_min, uint16_t config_max)
{
    if (h == NULL) {
        return BOOT_ERR_ARG;
    }
    boot_status_t st = check_range(skill_min, skill_max, h->skill_format_oldest, h->skill_format,
                                   BOOT_ERR_SKILL_FORMAT);
    if (st != BOOT_OK) {
        return st;
    }
    return check_range(config_min, config_max, h->config_format_oldest, h->config_format,
                       BOOT_ERR_CONFIG_FORMAT);
}

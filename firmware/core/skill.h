/* Skill image v1 (docs/skill_format.md): little-endian, versioned header, arrays of centres,
 * widths and weights, CRC-32 (zlib) over everything before it. Python writes it
 * (host/forceskill/skill.py); this parses and validates it into a ready dmp_model_t. */
#ifndef SKILL_H
#define SKILL_H

#include <stdint.h>
#include "dmp.h"
#include "fs_status.h"
#include "pfc.h"

#define SKILL_MAGIC 0x4C4B5346u /* bytes "FSKL" */
#define SKILL_FORMAT_VERSION 1u
#define SKILL_HEADER_SIZE 128u
#define SKILL_CRC_SIZE 4u
#define SKILL_KERNEL_BYTES 24u /* per kernel: centre, width, weight (f64 each) */
/** Bytes of an image with n kernels, and of the largest image this firmware accepts. */
#define SKILL_IMAGE_SIZE(n) \
    (SKILL_HEADER_SIZE + SKILL_KERNEL_BYTES * (uint32_t)(n) + SKILL_CRC_SIZE)
#define SKILL_IMAGE_MAX SKILL_IMAGE_SIZE(DMP_MAX_KERNELS)
#define SKILL_FLAG_END_RELEASE 0x0001u /* end policy: 0 hold, 1 release (ramp to 0 in 0.5 s) */
#define SKILL_FLAG_Y_AXIS 0x0002u      /* reserved: y-axis position DMP (refused in v1) */
#define SKILL_RELEASE_TIME_S 0.5

/** End policy after the skill's duration. */
typedef enum {
    SKILL_END_HOLD = 0,
    SKILL_END_RELEASE = 1
} skill_end_t;

/** A parsed, validated skill. */
typedef struct {
    dmp_model_t dmp;
    pfc_axis_gains_t gains; /* x-axis gains the skill was fitted with */
    fs_real_t surface_m;    /* object surface position during the demonstration */
    skill_end_t end_policy;
} skill_t;

/** Total image length in bytes for N kernels. */
uint32_t skill_image_size(uint16_t n_kernels);

/** zlib-compatible CRC-32, continuing from crc (start with 0). */
uint32_t skill_crc32(uint32_t crc, const uint8_t *data, uint32_t len);

/** Parse and validate an image (magic, version, sizes, CRC, finite values, ranges, gains
 *  consistent with alpha/beta/gamma, beta <= alpha/4); on error *out is unspecified. */
fs_status_t skill_parse(const uint8_t *buf, uint32_t len, skill_t *out);

#endif /* SKILL_H */

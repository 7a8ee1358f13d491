/* Skill image v2 (docs/skill_format.md): little-endian, versioned header, arrays of centres,
 * widths and weights, CRC-32 (zlib) over everything before it. Python writes it
 * (host/forceskill/model/skill.py); this parses and validates it into a ready dmp_model_t. */
#ifndef SKILL_H
#define SKILL_H

#include <stdint.h>
#include "dmp.h"
#include "fs_status.h"
#include "pfc.h"

#define SKILL_MAGIC 0x4C4B5346u /* bytes "FSKL" */
#define SKILL_FORMAT_VERSION 2u
#define SKILL_HEADER_SIZE 136u
#define SKILL_CRC_SIZE 4u
#define SKILL_KERNEL_BYTES 24u /* per kernel: centre, width, weight (f64 each) */
/** Bytes of an image with n kernels, and of the largest image this firmware accepts. */
#define SKILL_IMAGE_SIZE(n) \
    (SKILL_HEADER_SIZE + SKILL_KERNEL_BYTES * (uint32_t)(n) + SKILL_CRC_SIZE)
#define SKILL_IMAGE_MAX SKILL_IMAGE_SIZE(DMP_MAX_KERNELS)
#define SKILL_FLAG_END_RELEASE 0x0001u /* end policy: 0 hold, 1 release (ramp to 0 in 0.5 s) */
#define SKILL_FLAG_Y_AXIS 0x0002u      /* reserved: y-axis position DMP (refused) */
#define SKILL_RELEASE_TIME_S 0.5

/** End policy after the skill's duration. */
typedef enum {
    SKILL_END_HOLD = 0,
    SKILL_END_RELEASE = 1
} skill_end_t;

/** A parsed, validated skill. */
typedef struct {
    dmp_model_t dmp;         /* the DMP, in force units (independent of k) */
    dmp_gains_t fit_gains;   /* gains stored in the image (kkf = k*k_f, kki = k*k_i) */
    pfc_axis_gains_t gains;  /* x-axis controller gains at the nominal k (k_f = kkf/k, ...) */
    fs_real_t stiffness_Npm; /* nominal object stiffness k: x_d = surface + f_hat/k */
    fs_real_t surface_m;     /* object surface position during the demonstration */
    skill_end_t end_policy;
} skill_t;

/** Total image length in bytes for N kernels. */
uint32_t skill_image_size(uint16_t n_kernels);

/** zlib-compatible CRC-32, continuing from crc (start with 0). */
uint32_t skill_crc32(uint32_t crc, const uint8_t *data, uint32_t len);

/** Parse and validate an image (magic, version, sizes, CRC, finite values, ranges, gains
 *  consistent with alpha/beta/gamma, beta <= alpha/4); on error *out is unspecified. An image of
 *  another version (v1 stored metres and k-dependent gains) is refused with 202. */
fs_status_t skill_parse(const uint8_t *buf, uint32_t len, skill_t *out);

#endif /* SKILL_H */

/* Skill image v2..v5 (docs/skill_format.md): little-endian, versioned header, arrays of
 * centres, widths and weights (v3/v4 with the y DMP: and the y weights), CRC-32 (zlib) over
 * everything before it; v4 adds the kind (discrete or periodic) and the periodic DMP's fields,
 * v5 the demonstrated band (lower and upper force bounds over the skill's normalised time).
 * Python writes it (host/forceskill/model/skill.py); this parses and validates it into a ready
 * dmp_model_t. */
#ifndef SKILL_H
#define SKILL_H

#include <stdbool.h>
#include <stdint.h>
#include "fs_budget.h"
#include "dmp.h"
#include "fs_status.h"
#include "pfc.h"

#define SKILL_MAGIC 0x4C4B5346u     /* bytes "FSKL" */
#define SKILL_FORMAT_VERSION 5u     /* native: the kind, the DMPs and an optional band */
#define SKILL_FORMAT_VERSION_MIN 2u /* oldest read: force only (v1 is refused) */
#define SKILL_HEADER_SIZE_V2 136u
#define SKILL_HEADER_SIZE 152u    /* v3: the v2 header, then y_start_m and goal_y_m */
#define SKILL_HEADER_SIZE_V4 208u /* v4: the v3 header, 6 periodic f64, kind u16, reserved */
#define SKILL_HEADER_SIZE_V5 216u /* v5: the v4 header, the band's point count u16, 3 reserved */
#define SKILL_BAND_MIN_POINTS 2u
/* v5: the band's points, lower and upper (f64 each in the image); a build may take fewer (the
 * Cortex-M3 image: 64, firmware/ports/mps2/CMakeLists.txt) and refuses a band with more (234) */
#ifndef SKILL_BAND_MAX_POINTS
#define SKILL_BAND_MAX_POINTS 128u
#endif
#define SKILL_CRC_SIZE 4u
#define SKILL_KERNEL_BYTES 24u   /* per kernel: centre, width, weight (f64 each) */
#define SKILL_KERNEL_BYTES_Y 32u /* ... and the y weight (v3 with the y DMP) */
/** Bytes of a v5 image with n kernels, the y DMP and the largest band, and of the largest image
 *  this firmware accepts. */
#define SKILL_IMAGE_SIZE(n)                                                                      \
    (SKILL_HEADER_SIZE_V5 + SKILL_KERNEL_BYTES_Y * (uint32_t)(n) + 16u * SKILL_BAND_MAX_POINTS + \
     SKILL_CRC_SIZE)
#define SKILL_IMAGE_MAX SKILL_IMAGE_SIZE(DMP_MAX_KERNELS)
#define SKILL_FLAG_END_RELEASE 0x0001u /* end policy: 0 hold, 1 release (ramp to 0 in 0.5 s) */
#define SKILL_FLAG_Y_AXIS 0x0002u      /* v3: the position DMP on y is present (v2: refused) */
#define SKILL_RELEASE_TIME_S 0.5
#define SKILL_KIND_DISCRETE 0u
#define SKILL_KIND_PERIODIC 1u          /* v4: a rhythmic skill (docs/math.md section 5) */
#define SKILL_CONTACT_TAU_MS_MAX 10000u /* v4: the contact-wait time constant's largest value */
/* The core runs periodic skills (dmp_periodic_step, in double, float32 and fixed point): a build
 * that cannot (a port without the periodic executor) defines SKILL_PERIODIC_SUPPORTED 0 and
 * refuses a valid periodic image with FS_ERR_SKILL_NO_PERIODIC after every check of the format. */
#ifndef SKILL_PERIODIC_SUPPORTED
#define SKILL_PERIODIC_SUPPORTED 1
#endif

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
    uint8_t kind; /* SKILL_KIND_DISCRETE (v2, v3 and v4 kind 0) or SKILL_KIND_PERIODIC */
    /* v4's contact wait (docs/math.md, "A phase that waits for contact"): contact is lost while
     * f_hat - f_contact > contact_threshold_N; 0 = off (every other version) */
    fs_real_t contact_threshold_N;
    fs_real_t contact_tau_s; /* the phase rate's first-order time constant */
    /* v5's demonstrated band: band_n points uniform over the normalised time t/T in [0, 1] (a
     * periodic skill: over one period), lower and upper force bounds in N; 0 points: none */
    uint16_t band_n;
    fs_real_t band_lo_N[SKILL_BAND_MAX_POINTS];
    fs_real_t band_hi_N[SKILL_BAND_MAX_POINTS];
} skill_t;

/** Total image length in bytes for N kernels of a v2 image (force only): 136 + 24 N + 4. */
uint32_t skill_image_size(uint16_t n_kernels);

/** Total image length in bytes for N kernels of an image of format version (2, 3 or 4) with or
 *  without the y DMP (v3 and v4 only): v3 152 + 24 N (+ 8 N) + 4, v4 the same after 208. */
uint32_t skill_image_size_v(uint16_t version, uint16_t n_kernels, uint8_t has_y);

/** skill_image_size_v for any version up to 5: v5 the v4 arrays after a 216-byte header, then
 *  the band's band_n lower and band_n upper bounds (+ 16 band_n). */
uint32_t skill_image_size_band(uint16_t version, uint16_t n_kernels, uint8_t has_y,
                               uint16_t band_n);

/** zlib-compatible CRC-32, continuing from crc (start with 0). */
uint32_t skill_crc32(uint32_t crc, const uint8_t *data, uint32_t len);

/** A parse in slices (skill_parse_begin, then skill_parse_run until it returns true): the checks
 *  and results of skill_parse, in its order, at most a bounded amount of work per call, so a
 *  device checks a download over several control ticks. A unit of work is one kernel's value in
 *  one pass, SKILL_PARSE_F64_PER_UNIT float64 fields in the finiteness pass, SKILL_PARSE_CRC_BYTES
 *  bytes of the CRC, SKILL_PARSE_INIT_KERNELS kernels of a pass of dmp_model_init (a periodic
 *  model's reach pass counting SKILL_PARSE_REACH_UNITS), or one of the header's stages. The
 *  image and *out must stay in place until the parse is done. */
typedef struct {
    const uint8_t *buf;
    uint32_t len;
    skill_t *out;
    uint32_t crc;       /* CRC-32 of the bytes read so far (the whole body once past the CRC) */
    uint32_t pos;       /* progress inside the stage */
    uint32_t header;    /* header size of the image */
    uint16_t version;   /* format version */
    uint16_t n;         /* kernels */
    uint8_t has_y;      /* the y DMP is present */
    uint8_t kind;       /* SKILL_KIND_* (v4: read with the kernel count) */
    uint16_t band_n;    /* v5: the band's points (read with the kernel count) */
    uint8_t stage;      /* internal */
    double derived[3];  /* alpha, beta, gamma of the stored gains (checked in the next unit) */
    dmp_init_t init;    /* the model's derivation (dmp_model_init in slices) */
    fs_status_t status; /* FS_OK while running or once valid; the refusal once done */
} skill_parser_t;
#define SKILL_PARSE_CRC_BYTES 32u
#define SKILL_PARSE_F64_PER_UNIT 4u

/** The band of a parsed skill with one (band_n > 0) at the normalised time s = t/(T*time_scale)
 *  (a discrete skill: clamped to [0, 1]; a periodic one: its fraction, the band repeats every
 *  period), linear between points and scaled as f_hat is: discrete f0 + goal_scale*(b - f0),
 *  periodic goal_scale*g + amplitude_scale*(b - g), g the mean force. FS_ERR_NULL_ARG for NULL,
 *  FS_ERR_SKILL_BAND for a skill without a band (*lo, *hi untouched). */
fs_status_t skill_band_at(const skill_t *sk, fs_real_t s, fs_real_t goal_scale,
                          fs_real_t amplitude_scale, fs_real_t *lo_N, fs_real_t *hi_N);

/** Start a parse of buf[0..len) into *out (FS_ERR_NULL_ARG at once for NULL). */
void skill_parse_begin(skill_parser_t *p, const uint8_t *buf, uint32_t len, skill_t *out);

/** At most max_units units of the parse; true once done (p->status: FS_OK, *out filled, and
 *  p->crc the image's CRC-32; or skill_parse's error). */
bool skill_parse_run(skill_parser_t *p, uint32_t max_units);

/** Parse and validate an image of version 2 to 5 (magic, version, sizes, CRC, kind, finite
 *  values, ranges, centres, gains consistent with alpha/beta/gamma, beta <= alpha/4, with the y
 *  DMP 0 < beta_y <= alpha/4, flags, v4's contact wait (233), a periodic skill's amplitude and
 *  period, v5's band: 2..SKILL_BAND_MAX_POINTS points, reserved 0, lower <= upper (234)); on
 *  error *out is
 *  unspecified. Another version is refused with 202; a valid periodic skill with 232 by a build
 *  without SKILL_PERIODIC_SUPPORTED. */
fs_status_t skill_parse(const uint8_t *buf, uint32_t len, skill_t *out);

#endif /* SKILL_H */

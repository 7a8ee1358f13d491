/* Skill image v2/v3 parser (docs/skill_format.md). Every check runs on the stored float64 values in
 * double, in the documented order, so the double and float builds accept and reject the same
 * images as the Python reader; the float build then rounds the values to float. */
#include "skill.h"

#include <float.h>
#include <stddef.h>

/* Header field offsets (docs/skill_format.md). */
#define OFF_MAGIC 0u
#define OFF_VERSION 4u
#define OFF_HEADER_SIZE 6u
#define OFF_TOTAL_LENGTH 8u
#define OFF_N_KERNELS 12u
#define OFF_FLAGS 14u
#define OFF_DT 16u
#define OFF_TAU 24u
#define OFF_ALPHA 32u
#define OFF_BETA 40u
#define OFF_GAMMA 48u
#define OFF_STIFFNESS 56u
#define OFF_GOAL 64u /* goal_N */
#define OFF_DURATION 72u
#define OFF_M_D 80u
#define OFF_K_D 88u
#define OFF_K_P 96u
#define OFF_KKF 104u /* k*k_f, N/m */
#define OFF_KKI 112u /* k*k_i, N/(m s) */
#define OFF_SURFACE 120u
#define OFF_FORCE0 128u
#define OFF_Y_START 136u /* v3 */
#define OFF_GOAL_Y 144u  /* v3 */
#define SKILL_N_HEADER_F64_V2 15u
#define SKILL_N_HEADER_F64_V3 17u

/* alpha/beta/gamma stored vs derived from the stored gains: relative agreement required. */
#define SKILL_GAINS_REL_TOL 1e-9

uint32_t skill_image_size(uint16_t n_kernels)
{
    return skill_image_size_v(2u, n_kernels, 0u);
}

uint32_t skill_image_size_v(uint16_t version, uint16_t n_kernels, uint8_t has_y)
{
    if (version == 2u) {
        return SKILL_HEADER_SIZE_V2 + SKILL_KERNEL_BYTES * (uint32_t)n_kernels + SKILL_CRC_SIZE;
    }
    return SKILL_HEADER_SIZE +
           ((has_y != 0u) ? SKILL_KERNEL_BYTES_Y : SKILL_KERNEL_BYTES) * (uint32_t)n_kernels +
           SKILL_CRC_SIZE;
}

/* Reflected polynomial 0xEDB88320 (zlib), processed a nibble at a time: 16-entry table. */
static const uint32_t crc_nibble[16] = {
    0x00000000u, 0x1DB71064u, 0x3B6E20C8u, 0x26D930ACu, 0x76DC4190u, 0x6B6B51F4u,
    0x4DB26158u, 0x5005713Cu, 0xEDB88320u, 0xF00F9344u, 0xD6D6A3E8u, 0xCB61B38Cu,
    0x9B64C2B0u, 0x86D3D2D4u, 0xA00AE278u, 0xBDBDF21Cu,
};

uint32_t skill_crc32(uint32_t crc, const uint8_t *data, uint32_t len)
{
    crc = ~crc;
    for (uint32_t i = 0u; i < len; i++) {
        crc ^= data[i];
        crc = (crc >> 4) ^ crc_nibble[crc & 0x0Fu];
        crc = (crc >> 4) ^ crc_nibble[crc & 0x0Fu];
    }
    return ~crc;
}

static uint16_t rd_u16(const uint8_t *b, uint32_t off)
{
    return (uint16_t)((uint16_t)b[off] | (uint16_t)((uint16_t)b[off + 1u] << 8));
}

static uint32_t rd_u32(const uint8_t *b, uint32_t off)
{
    return (uint32_t)b[off] | ((uint32_t)b[off + 1u] << 8) | ((uint32_t)b[off + 2u] << 16) |
           ((uint32_t)b[off + 3u] << 24);
}

/* IEEE-754 binary64, little-endian in the image; reinterpreted through a union (no memcpy). */
static double rd_f64(const uint8_t *b, uint32_t off)
{
    union {
        uint64_t u;
        double d;
    } v;
    v.u = 0u;
    for (uint32_t i = 8u; i > 0u; i--) {
        v.u = (v.u << 8) | (uint64_t)b[off + i - 1u];
    }
    return v.d;
}

static int rel_close(double a, double b, double rel)
{
    const double fa = fabs(a);
    const double fb = fabs(b);
    return fabs(a - b) <= rel * ((fa > fb) ? fa : fb);
}

#ifdef FS_REAL_FLOAT
/* Round a validated double to the float core: nonzero if it fits the float range. */
static int to_real(double d, fs_real_t *out)
{
    if (fabs(d) > (double)FLT_MAX) {
        return 0;
    }
    *out = (fs_real_t)d;
    return 1;
}
#else
static int to_real(double d, fs_real_t *out)
{
    *out = d;
    return 1;
}
#endif

/* The layout of a framed image: its version, header size, kernel count and y DMP flag. */
typedef struct {
    uint16_t version;
    uint16_t n;
    uint32_t header;
    uint8_t has_y;
} skill_layout_t;

/* The frame of an image: magic, version, header size, length, CRC, kernel count (into *lay). */
static fs_status_t check_frame(const uint8_t *buf, uint32_t len, skill_layout_t *lay)
{
    if (len < OFF_HEADER_SIZE) {
        return FS_ERR_SKILL_TOO_SHORT;
    }
    if (rd_u32(buf, OFF_MAGIC) != SKILL_MAGIC) {
        return FS_ERR_SKILL_MAGIC;
    }
    const uint16_t version = rd_u16(buf, OFF_VERSION);
    if (version < SKILL_FORMAT_VERSION_MIN || version > SKILL_FORMAT_VERSION) {
        return FS_ERR_SKILL_VERSION;
    }
    const uint32_t header = (version == 2u) ? SKILL_HEADER_SIZE_V2 : SKILL_HEADER_SIZE;
    if (len < header) {
        return FS_ERR_SKILL_TOO_SHORT;
    }
    if (rd_u16(buf, OFF_HEADER_SIZE) != header) {
        return FS_ERR_SKILL_HEADER_SIZE;
    }
    const uint16_t n = rd_u16(buf, OFF_N_KERNELS);
    const uint32_t total = rd_u32(buf, OFF_TOTAL_LENGTH);
    const uint8_t has_y = (uint8_t)(version >= 3u &&
                                    (rd_u16(buf, OFF_FLAGS) & SKILL_FLAG_Y_AXIS) != 0u);
    if (total != len || total != skill_image_size_v(version, n, has_y)) {
        return FS_ERR_SKILL_LENGTH;
    }
    const uint32_t body = total - SKILL_CRC_SIZE;
    if (rd_u32(buf, body) != skill_crc32(0u, buf, body)) {
        return FS_ERR_SKILL_CRC;
    }
    if (n == 0u || n > DMP_MAX_KERNELS) {
        return FS_ERR_SKILL_KERNELS;
    }
    lay->version = version;
    lay->n = n;
    lay->header = header;
    lay->has_y = has_y;
    return FS_OK;
}

/* The gains of a framed image: the stored alpha/beta/gamma those the fit gains derive (and
 * monotone); with a y DMP, its beta (the law with k_f = k_i = 0 on alpha) monotone too. */
static fs_status_t check_gains(const uint8_t *buf, uint8_t has_y)
{
    const double gain[5] = {rd_f64(buf, OFF_M_D), rd_f64(buf, OFF_K_D), rd_f64(buf, OFF_K_P),
                            rd_f64(buf, OFF_KKF), rd_f64(buf, OFF_KKI)};
    const double stored[3] = {rd_f64(buf, OFF_ALPHA), rd_f64(buf, OFF_BETA),
                              rd_f64(buf, OFF_GAMMA)};
    double derived[3];
    if (dmp_derive_f64(gain, derived) != FS_OK ||
        !rel_close(stored[0], derived[0], SKILL_GAINS_REL_TOL) ||
        !rel_close(stored[1], derived[1], SKILL_GAINS_REL_TOL) ||
        !rel_close(stored[2], derived[2], SKILL_GAINS_REL_TOL) ||
        stored[1] > stored[0] / 4.0 * (1.0 + DMP_MONOTONE_REL_TOL)) {
        return FS_ERR_SKILL_GAINS;
    }
    const double beta_y = gain[2] / (gain[0] * stored[0]) - 1.0;
    if (has_y != 0u &&
        (!(beta_y > 0.0) || beta_y > stored[0] / 4.0 * (1.0 + DMP_MONOTONE_REL_TOL))) {
        return FS_ERR_SKILL_GAINS;
    }
    return FS_OK;
}

/* The values of a framed image, in double: all finite, the timing, stiffness, goal and widths in
 * range, the centres increasing in [0, 1], the gains (check_gains), no unknown flag. */
static fs_status_t check_values(const uint8_t *buf, const skill_layout_t *lay)
{
    const uint32_t n = lay->n;
    /* Every float64 field: 15 (v3: 17) in the header from OFF_DT, then 3N (4N with the y DMP)
     * array entries, contiguous. */
    const uint32_t n_f64 = ((lay->version == 2u) ? SKILL_N_HEADER_F64_V2 : SKILL_N_HEADER_F64_V3) +
                           ((lay->has_y != 0u) ? 4u : 3u) * n;
    for (uint32_t i = 0u; i < n_f64; i++) {
        if (!isfinite(rd_f64(buf, OFF_DT + 8u * i))) {
            return FS_ERR_SKILL_NOT_FINITE;
        }
    }
    const double dt = rd_f64(buf, OFF_DT);
    const double duration = rd_f64(buf, OFF_DURATION);
    const uint32_t off_c = lay->header;
    const uint32_t off_s = lay->header + 8u * n;
    if (!(dt > 0.0) || dt > 0.1 || !(rd_f64(buf, OFF_TAU) > 0.0) || !(duration > 0.0) ||
        duration > 3600.0 || !(rd_f64(buf, OFF_STIFFNESS) > 0.0) ||
        !(rd_f64(buf, OFF_GOAL) > 0.0)) {
        return FS_ERR_SKILL_RANGE;
    }
    for (uint32_t i = 0u; i < n; i++) {
        if (!(rd_f64(buf, off_s + 8u * i) > 0.0)) {
            return FS_ERR_SKILL_RANGE;
        }
    }
    double prev = 0.0;
    for (uint32_t i = 0u; i < n; i++) {
        const double c = rd_f64(buf, off_c + 8u * i);
        if (c < 0.0 || c > 1.0 || (i > 0u && !(c > prev))) {
            return FS_ERR_SKILL_CENTRES;
        }
        prev = c;
    }
    const fs_status_t st = check_gains(buf, lay->has_y);
    if (st != FS_OK) {
        return st;
    }
    const uint16_t known = (lay->version == 2u)
                               ? (uint16_t)SKILL_FLAG_END_RELEASE
                               : (uint16_t)(SKILL_FLAG_END_RELEASE | SKILL_FLAG_Y_AXIS);
    if ((rd_u16(buf, OFF_FLAGS) & (uint16_t)~known) != 0u) {
        return FS_ERR_SKILL_UNSUPPORTED;
    }
    return FS_OK;
}

/* Fill the y DMP from a valid image in the core's type (zeros without one): 0 if a value does
 * not fit it. */
static int fill_path(const uint8_t *buf, const skill_layout_t *lay, dmp_model_t *m)
{
    m->has_y = lay->has_y;
    m->beta_y = FS_R(0.0);
    m->goal_y_m = FS_R(0.0);
    m->y_start_m = FS_R(0.0);
    if (lay->has_y == 0u) {
        return 1;
    }
    const double beta_y = rd_f64(buf, OFF_K_P) / (rd_f64(buf, OFF_M_D) * rd_f64(buf, OFF_ALPHA)) -
                          1.0;
    const uint32_t off_wy = lay->header + 24u * (uint32_t)lay->n;
    int ok = to_real(beta_y, &m->beta_y) && to_real(rd_f64(buf, OFF_GOAL_Y), &m->goal_y_m) &&
             to_real(rd_f64(buf, OFF_Y_START), &m->y_start_m);
    for (uint32_t i = 0u; ok && i < lay->n; i++) {
        ok = to_real(rd_f64(buf, off_wy + 8u * i), &m->y_weight[i]);
    }
    return ok;
}

/* Fill the skill from a valid image in the core's type: 0 if a value does not fit it. */
static int fill_skill(const uint8_t *buf, const skill_layout_t *lay, skill_t *out)
{
    const uint32_t n = lay->n;
    const uint32_t off_c = lay->header;
    const uint32_t off_s = lay->header + 8u * n;
    const uint32_t off_w = lay->header + 16u * n;
    dmp_model_t *m = &out->dmp;
    m->n_kernels = lay->n;
    int ok = to_real(rd_f64(buf, OFF_ALPHA), &m->p.alpha) &&
             to_real(rd_f64(buf, OFF_BETA), &m->p.beta) &&
             to_real(rd_f64(buf, OFF_GAMMA), &m->p.gamma) &&
             to_real(rd_f64(buf, OFF_DT), &m->dt_s) && to_real(rd_f64(buf, OFF_TAU), &m->tau_s) &&
             to_real(rd_f64(buf, OFF_GOAL), &m->goal_N) &&
             to_real(rd_f64(buf, OFF_FORCE0), &m->force0_N) &&
             to_real(rd_f64(buf, OFF_STIFFNESS), &out->stiffness_Npm) &&
             to_real(rd_f64(buf, OFF_DURATION), &m->duration_s) &&
             to_real(rd_f64(buf, OFF_M_D), &out->fit_gains.m_d_kg) &&
             to_real(rd_f64(buf, OFF_K_D), &out->fit_gains.k_d_Nspm) &&
             to_real(rd_f64(buf, OFF_K_P), &out->fit_gains.k_p_Npm) &&
             to_real(rd_f64(buf, OFF_KKF), &out->fit_gains.kkf_Npm) &&
             to_real(rd_f64(buf, OFF_KKI), &out->fit_gains.kki_Npms) &&
             to_real(rd_f64(buf, OFF_SURFACE), &out->surface_m);
    for (uint32_t i = 0u; ok && i < n; i++) {
        ok = to_real(rd_f64(buf, off_c + 8u * i), &m->centre[i]) &&
             to_real(rd_f64(buf, off_s + 8u * i), &m->width[i]) &&
             to_real(rd_f64(buf, off_w + 8u * i), &m->weight[i]);
    }
    return ok && fill_path(buf, lay, m);
}

fs_status_t skill_parse(const uint8_t *buf, uint32_t len, skill_t *out)
{
    if (buf == NULL || out == NULL) {
        return FS_ERR_NULL_ARG;
    }
    skill_layout_t lay = {0u, 0u, 0u, 0u};
    fs_status_t st = check_frame(buf, len, &lay);
    if (st == FS_OK) {
        st = check_values(buf, &lay);
    }
    if (st != FS_OK) {
        return st;
    }
    /* Valid in double: fill the model in the core's type. The float build can still refuse a
     * value beyond the float range (207) or one that rounding made invalid (dmp_model_init). */
    if (!fill_skill(buf, &lay, out) ||
        dmp_gains_at_stiffness(&out->fit_gains, out->stiffness_Npm, &out->gains) != FS_OK) {
        return FS_ERR_SKILL_RANGE;
    }
    const uint16_t flags = rd_u16(buf, OFF_FLAGS);
    out->end_policy = ((flags & SKILL_FLAG_END_RELEASE) != 0u) ? SKILL_END_RELEASE : SKILL_END_HOLD;
    return dmp_model_init(&out->dmp);
}

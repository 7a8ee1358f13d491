/* Skill image v2 parser (docs/skill_format.md). Every check runs on the stored float64 values in
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
#define SKILL_N_HEADER_F64 15u

/* alpha/beta/gamma stored vs derived from the stored gains: relative agreement required. */
#define SKILL_GAINS_REL_TOL 1e-9

uint32_t skill_image_size(uint16_t n_kernels)
{
    return SKILL_IMAGE_SIZE(n_kernels);
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

/* The frame of an image: magic, version, header size, length, CRC, kernel count (into *n). */
static fs_status_t check_frame(const uint8_t *buf, uint32_t len, uint16_t *n_out)
{
    if (len < OFF_HEADER_SIZE) {
        return FS_ERR_SKILL_TOO_SHORT;
    }
    if (rd_u32(buf, OFF_MAGIC) != SKILL_MAGIC) {
        return FS_ERR_SKILL_MAGIC;
    }
    if (rd_u16(buf, OFF_VERSION) != SKILL_FORMAT_VERSION) {
        return FS_ERR_SKILL_VERSION;
    }
    if (len < SKILL_HEADER_SIZE) {
        return FS_ERR_SKILL_TOO_SHORT;
    }
    if (rd_u16(buf, OFF_HEADER_SIZE) != SKILL_HEADER_SIZE) {
        return FS_ERR_SKILL_HEADER_SIZE;
    }
    const uint16_t n = rd_u16(buf, OFF_N_KERNELS);
    const uint32_t total = rd_u32(buf, OFF_TOTAL_LENGTH);
    if (total != len || total != skill_image_size(n)) {
        return FS_ERR_SKILL_LENGTH;
    }
    const uint32_t body = total - SKILL_CRC_SIZE;
    if (rd_u32(buf, body) != skill_crc32(0u, buf, body)) {
        return FS_ERR_SKILL_CRC;
    }
    if (n == 0u || n > DMP_MAX_KERNELS) {
        return FS_ERR_SKILL_KERNELS;
    }
    *n_out = n;
    return FS_OK;
}

/* The values of a framed image with n kernels, in double: all finite, the timing, stiffness,
 * goal and widths in range, the centres increasing in [0, 1], the stored alpha/beta/gamma those
 * the fit gains derive (and monotone), no unknown flag. */
static fs_status_t check_values(const uint8_t *buf, uint16_t n)
{
    /* Every float64 field: 15 in the header from OFF_DT, then 3N array entries, contiguous. */
    const uint32_t n_f64 = SKILL_N_HEADER_F64 + 3u * (uint32_t)n;
    for (uint32_t i = 0u; i < n_f64; i++) {
        if (!isfinite(rd_f64(buf, OFF_DT + 8u * i))) {
            return FS_ERR_SKILL_NOT_FINITE;
        }
    }
    const double dt = rd_f64(buf, OFF_DT);
    const double duration = rd_f64(buf, OFF_DURATION);
    const uint32_t off_c = SKILL_HEADER_SIZE;
    const uint32_t off_s = SKILL_HEADER_SIZE + 8u * (uint32_t)n;
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
    if ((rd_u16(buf, OFF_FLAGS) & (uint16_t)~SKILL_FLAG_END_RELEASE) != 0u) {
        return FS_ERR_SKILL_UNSUPPORTED;
    }
    return FS_OK;
}

/* Fill the skill from a valid image in the core's type: 0 if a value does not fit it. */
static int fill_skill(const uint8_t *buf, uint16_t n, skill_t *out)
{
    const uint32_t off_c = SKILL_HEADER_SIZE;
    const uint32_t off_s = SKILL_HEADER_SIZE + 8u * (uint32_t)n;
    const uint32_t off_w = SKILL_HEADER_SIZE + 16u * (uint32_t)n;
    dmp_model_t *m = &out->dmp;
    m->n_kernels = n;
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
    return ok;
}

fs_status_t skill_parse(const uint8_t *buf, uint32_t len, skill_t *out)
{
    if (buf == NULL || out == NULL) {
        return FS_ERR_NULL_ARG;
    }
    uint16_t n = 0u;
    fs_status_t st = check_frame(buf, len, &n);
    if (st == FS_OK) {
        st = check_values(buf, n);
    }
    if (st != FS_OK) {
        return st;
    }
    /* Valid in double: fill the model in the core's type. The float build can still refuse a
     * value beyond the float range (207) or one that rounding made invalid (dmp_model_init). */
    if (!fill_skill(buf, n, out) ||
        dmp_gains_at_stiffness(&out->fit_gains, out->stiffness_Npm, &out->gains) != FS_OK) {
        return FS_ERR_SKILL_RANGE;
    }
    const uint16_t flags = rd_u16(buf, OFF_FLAGS);
    out->end_policy = ((flags & SKILL_FLAG_END_RELEASE) != 0u) ? SKILL_END_RELEASE : SKILL_END_HOLD;
    return dmp_model_init(&out->dmp);
}

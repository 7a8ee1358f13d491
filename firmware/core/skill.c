/* Skill image v2..v5 parser (docs/skill_format.md). Every check runs on the stored float64 values in
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
#define OFF_Y_START 136u    /* v3 */
#define OFF_GOAL_Y 144u     /* v3 */
#define OFF_AMPLITUDE 152u  /* v4: the periodic DMP's six f64 (amplitude, e0, z0, I0, y p0, y z0) */
#define OFF_KIND 200u       /* v4: kind u16 */
#define OFF_CONTACT_CN 202u /* v4: contact-wait threshold u16, 0.01 N (0: off) */
#define OFF_CONTACT_MS 204u /* v4: contact-wait time constant u16, ms */
#define OFF_RESERVED 206u   /* v4: reserved u16 (0) */
#define OFF_BAND_N 208u     /* v5: the band's point count u16, then three reserved u16 (0) */
#define SKILL_N_HEADER_F64_V2 15u
#define SKILL_N_HEADER_F64_V3 17u
#define SKILL_N_HEADER_F64_V4 23u
#define SKILL_N_PERIODIC_F64 6u
#define SKILL_TWO_PI 6.283185307179586
/* a periodic skill's duration is its period: |T - 2*pi*tau| <= this * T */
#define SKILL_PERIOD_REL_TOL 1e-9

/* alpha/beta/gamma stored vs derived from the stored gains: relative agreement required. */
#define SKILL_GAINS_REL_TOL 1e-9

uint32_t skill_image_size(uint16_t n_kernels)
{
    return skill_image_size_v(2u, n_kernels, 0u);
}

uint32_t skill_image_size_v(uint16_t version, uint16_t n_kernels, uint8_t has_y)
{
    return skill_image_size_band(version, n_kernels, has_y, 0u);
}

uint32_t skill_image_size_band(uint16_t version, uint16_t n_kernels, uint8_t has_y, uint16_t band_n)
{
    if (version == 2u) {
        return SKILL_HEADER_SIZE_V2 + SKILL_KERNEL_BYTES * (uint32_t)n_kernels + SKILL_CRC_SIZE;
    }
    const uint32_t header = (version >= 5u)   ? SKILL_HEADER_SIZE_V5
                            : (version >= 4u) ? SKILL_HEADER_SIZE_V4
                                              : SKILL_HEADER_SIZE;
    const uint32_t band = (version >= 5u) ? 16u * (uint32_t)band_n : 0u;
    return header +
           ((has_y != 0u) ? SKILL_KERNEL_BYTES_Y : SKILL_KERNEL_BYTES) * (uint32_t)n_kernels +
           band + SKILL_CRC_SIZE;
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

/* 64 bits, little-endian in the image, as two 32-bit words (cheap on a 32-bit core). */
static uint64_t rd_u64(const uint8_t *b, uint32_t off)
{
    return (uint64_t)rd_u32(b, off) | ((uint64_t)rd_u32(b, off + 4u) << 32);
}

/* IEEE-754 binary64 from its bits; reinterpreted through a union (no memcpy). */
static double f64_of(uint64_t bits)
{
    union {
        uint64_t u;
        double d;
    } v;
    v.u = bits;
    return v.d;
}

static double rd_f64(const uint8_t *b, uint32_t off)
{
    return f64_of(rd_u64(b, off));
}

/* The binary64 at off is finite (its exponent field is not all ones). */
static int rd_f64_finite(const uint8_t *b, uint32_t off)
{
    return ((rd_u64(b, off) >> 52) & 0x7FFu) != 0x7FFu;
}

static int rel_close(double a, double b, double rel)
{
    const double fa = fabs(a);
    const double fb = fabs(b);
    return fabs(a - b) <= rel * ((fa > fb) ? fa : fb);
}

#ifdef FS_REAL_FLOAT
/* FLT_MAX as a binary64 bit pattern: the order of non-negative doubles is that of their bits. */
#define SKILL_FLT_MAX_BITS 0x47EFFFFFE0000000ull
_Static_assert(FLT_MAX == 3.40282346638528859811704183484516925e+38F, "IEEE-754 binary32");

/* Round a validated double to the float core: nonzero if it fits the float range (|d| <= FLT_MAX,
 * compared on the bits: no software double compare on a core without a double FPU). */
static int to_real(double d, fs_real_t *out)
{
    union {
        double d;
        uint64_t u;
    } v;
    v.d = d;
    if ((v.u & 0x7FFFFFFFFFFFFFFFull) > SKILL_FLT_MAX_BITS) {
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

/* The frame of an image: magic, version, header size, length (into the parser; the CRC and the
 * kernel count follow in their own stage). */
static fs_status_t check_frame(skill_parser_t *p)
{
    const uint8_t *buf = p->buf;
    const uint32_t len = p->len;
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
    const uint32_t header = (version == 2u)   ? SKILL_HEADER_SIZE_V2
                            : (version == 3u) ? SKILL_HEADER_SIZE
                            : (version == 4u) ? SKILL_HEADER_SIZE_V4
                                              : SKILL_HEADER_SIZE_V5;
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
    const uint16_t band_n = (version >= 5u) ? rd_u16(buf, OFF_BAND_N) : 0u;
    if (total != len || total != skill_image_size_band(version, n, has_y, band_n)) {
        return FS_ERR_SKILL_LENGTH;
    }
    p->band_n = band_n;
    p->version = version;
    p->n = n;
    p->header = header;
    p->has_y = has_y;
    return FS_OK;
}

/* The five gains of a framed image. */
static void read_gains(const uint8_t *buf, double gain[5])
{
    gain[0] = rd_f64(buf, OFF_M_D);
    gain[1] = rd_f64(buf, OFF_K_D);
    gain[2] = rd_f64(buf, OFF_K_P);
    gain[3] = rd_f64(buf, OFF_KKF);
    gain[4] = rd_f64(buf, OFF_KKI);
}

/* Part i of the alpha/beta/gamma the fit gains derive, into the parser (a unit each: one double
 * division and the derivation's checks, in software on a core without a double FPU). */
static fs_status_t derive_gains(skill_parser_t *p, uint32_t i)
{
    double gain[5];
    read_gains(p->buf, gain);
    return dmp_derive_f64_part(gain, p->derived, i) == FS_OK ? FS_OK : FS_ERR_SKILL_GAINS;
}

/* The gains of a framed image: the stored alpha/beta/gamma those derived (and monotone); with a
 * y DMP, its beta (the law with k_f = k_i = 0 on alpha) monotone too. */
static fs_status_t check_gains(const uint8_t *buf, const double derived[3], uint8_t has_y)
{
    const double stored[3] = {rd_f64(buf, OFF_ALPHA), rd_f64(buf, OFF_BETA),
                              rd_f64(buf, OFF_GAMMA)};
    if (!rel_close(stored[0], derived[0], SKILL_GAINS_REL_TOL) ||
        !rel_close(stored[1], derived[1], SKILL_GAINS_REL_TOL) ||
        !rel_close(stored[2], derived[2], SKILL_GAINS_REL_TOL) ||
        stored[1] > stored[0] / 4.0 * (1.0 + DMP_MONOTONE_REL_TOL)) {
        return FS_ERR_SKILL_GAINS;
    }
    if (has_y == 0u) {
        return FS_OK;
    }
    const double beta_y = rd_f64(buf, OFF_K_P) / (rd_f64(buf, OFF_M_D) * stored[0]) - 1.0;
    return (!(beta_y > 0.0) || beta_y > stored[0] / 4.0 * (1.0 + DMP_MONOTONE_REL_TOL))
               ? FS_ERR_SKILL_GAINS
               : FS_OK;
}

/* The header's values in range: the timing, stiffness and goal. */
static fs_status_t check_header_range(const uint8_t *buf)
{
    const double dt = rd_f64(buf, OFF_DT);
    const double duration = rd_f64(buf, OFF_DURATION);
    if (!(dt > 0.0) || dt > 0.1 || !(rd_f64(buf, OFF_TAU) > 0.0) || !(duration > 0.0) ||
        duration > 3600.0 || !(rd_f64(buf, OFF_STIFFNESS) > 0.0) ||
        !(rd_f64(buf, OFF_GOAL) > 0.0)) {
        return FS_ERR_SKILL_RANGE;
    }
    return FS_OK;
}

/* The gains (check_gains) and no unknown flag. */
static fs_status_t check_gains_flags(const uint8_t *buf, const double derived[3], uint16_t version,
                                     uint8_t has_y)
{
    const fs_status_t st = check_gains(buf, derived, has_y);
    if (st != FS_OK) {
        return st;
    }
    const uint16_t known = (version == 2u) ? (uint16_t)SKILL_FLAG_END_RELEASE
                                           : (uint16_t)(SKILL_FLAG_END_RELEASE | SKILL_FLAG_Y_AXIS);
    return ((rd_u16(buf, OFF_FLAGS) & (uint16_t)~known) != 0u) ? FS_ERR_SKILL_UNSUPPORTED : FS_OK;
}

/* v4: the contact wait's time constant at most 10 s and 0 without a threshold (233); a discrete
 * skill's periodic fields 0 (228); a periodic skill's amplitude > 0 (230),
 * T = 2*pi*tau (229), and runnable by this build (232). */
static fs_status_t check_kind(const uint8_t *buf, uint16_t version, uint8_t kind)
{
    if (version < 4u) {
        return FS_OK;
    }
    const uint16_t tau_ms = rd_u16(buf, OFF_CONTACT_MS);
    if (tau_ms > SKILL_CONTACT_TAU_MS_MAX || (rd_u16(buf, OFF_CONTACT_CN) == 0u && tau_ms != 0u)) {
        return FS_ERR_SKILL_CONTACT_WAIT;
    }
    if (kind == SKILL_KIND_DISCRETE) {
        for (uint32_t k = 0u; k < SKILL_N_PERIODIC_F64; k++) {
            if (rd_f64(buf, OFF_AMPLITUDE + 8u * k) != 0.0) {
                return FS_ERR_SKILL_KIND;
            }
        }
        return FS_OK;
    }
    if (!(rd_f64(buf, OFF_AMPLITUDE) > 0.0)) {
        return FS_ERR_SKILL_AMPLITUDE;
    }
    const double duration = rd_f64(buf, OFF_DURATION);
    if (fabs(duration - SKILL_TWO_PI * rd_f64(buf, OFF_TAU)) > SKILL_PERIOD_REL_TOL * duration) {
        return FS_ERR_SKILL_PERIOD;
    }
    return SKILL_PERIODIC_SUPPORTED ? FS_OK : FS_ERR_SKILL_NO_PERIODIC;
}

/* The header's values in the core's type (the y DMP's scalars too, zeros without one): 0 if a
 * value does not fit it. */
static int fill_header(const uint8_t *buf, uint8_t has_y, uint8_t kind, skill_t *out)
{
    dmp_model_t *m = &out->dmp;
    m->has_y = has_y;
    m->beta_y = FS_R(0.0);
    m->goal_y_m = FS_R(0.0);
    m->y_start_m = FS_R(0.0);
    m->periodic = (kind == SKILL_KIND_PERIODIC) ? 1u : 0u;
    m->amplitude_N = FS_R(0.0);
    m->cycle_e0_N = FS_R(0.0);
    m->cycle_z0_N = FS_R(0.0);
    m->cycle_i0_N = FS_R(0.0);
    m->cycle_q0_m = FS_R(0.0);
    m->cycle_zq0_m = FS_R(0.0);
    if (m->periodic != 0u && has_y != 0u &&
        !(to_real(rd_f64(buf, OFF_AMPLITUDE + 32u), &m->cycle_q0_m) &&
          to_real(rd_f64(buf, OFF_AMPLITUDE + 40u), &m->cycle_zq0_m))) {
        return 0;
    }
    if (m->periodic != 0u && !(to_real(rd_f64(buf, OFF_AMPLITUDE), &m->amplitude_N) &&
                               to_real(rd_f64(buf, OFF_AMPLITUDE + 8u), &m->cycle_e0_N) &&
                               to_real(rd_f64(buf, OFF_AMPLITUDE + 16u), &m->cycle_z0_N) &&
                               to_real(rd_f64(buf, OFF_AMPLITUDE + 24u), &m->cycle_i0_N))) {
        return 0;
    }
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
    if (ok && has_y != 0u) {
        const double beta_y = rd_f64(buf, OFF_K_P) /
                                  (rd_f64(buf, OFF_M_D) * rd_f64(buf, OFF_ALPHA)) -
                              1.0;
        ok = to_real(beta_y, &m->beta_y) && to_real(rd_f64(buf, OFF_GOAL_Y), &m->goal_y_m) &&
             to_real(rd_f64(buf, OFF_Y_START), &m->y_start_m);
    }
    return ok;
}

/* Kernel i's centre, width, weight (and y weight) in the core's type: 0 if one does not fit. */
static int fill_kernel(const skill_parser_t *p, uint32_t i)
{
    const uint8_t *buf = p->buf;
    const uint32_t off = p->header + 8u * i;
    const uint32_t n8 = 8u * (uint32_t)p->n;
    dmp_model_t *m = &p->out->dmp;
    return to_real(rd_f64(buf, off), &m->centre[i]) &&
           to_real(rd_f64(buf, off + n8), &m->width[i]) &&
           to_real(rd_f64(buf, off + 2u * n8), &m->weight[i]) &&
           (p->has_y == 0u || to_real(rd_f64(buf, off + 3u * n8), &m->y_weight[i]));
}

/* The stages of a parse, in skill_parse's order of checks. */
enum {
    SP_FRAME,   /* magic, version, header size, length */
    SP_CRC,     /* the CRC, SKILL_PARSE_CRC_BYTES bytes a unit; then the kernel count */
    SP_FINITE,  /* every float64 field finite, SKILL_PARSE_F64_PER_UNIT a unit */
    SP_RANGE,   /* the header's ranges */
    SP_WIDTHS,  /* every width > 0, one a unit */
    SP_CENTRES, /* the centres increasing in [0, 1], one a unit */
    SP_DERIVE,  /* alpha, beta, gamma from the fit gains, DMP_DERIVE_PARTS units */
    SP_GAINS,   /* the stored ones against them, and the flags */
    SP_KIND,    /* the kind's fields (v4) */
    SP_BAND,    /* v5: each band point's lower <= upper, in the core's type, one a unit */
    SP_FILL,    /* the header's values in the core's type */
    SP_KERNELS, /* each kernel's values in the core's type, one a unit */
    SP_FINISH,  /* the x-axis gains and the end policy */
    SP_MODEL,   /* dmp_model_init, SKILL_PARSE_INIT_KERNELS kernels of a pass a unit */
    SP_DONE
};

void skill_parse_begin(skill_parser_t *p, const uint8_t *buf, uint32_t len, skill_t *out)
{
    p->buf = buf;
    p->len = len;
    p->out = out;
    p->crc = 0u;
    p->pos = 0u;
    p->header = 0u;
    p->version = 0u;
    p->n = 0u;
    p->has_y = 0u;
    p->kind = SKILL_KIND_DISCRETE;
    p->band_n = 0u;
    p->stage = SP_FRAME;
    p->status = (buf == NULL || out == NULL) ? FS_ERR_NULL_ARG : FS_OK;
    if (p->status != FS_OK) {
        p->stage = SP_DONE;
    }
}

/* v5: band point i's lower bound at most its upper one (234), both in the core's type; true once
 * the last point is done (at once without a band). */
static bool parse_band(skill_parser_t *p, uint32_t i)
{
    if (p->band_n == 0u) {
        return true;
    }
    const uint32_t off = p->header + 8u * ((p->has_y != 0u) ? 4u : 3u) * (uint32_t)p->n + 8u * i;
    const double lo = rd_f64(p->buf, off);
    const double hi = rd_f64(p->buf, off + 8u * (uint32_t)p->band_n);
    if (!(lo <= hi)) {
        p->status = FS_ERR_SKILL_BAND;
    } else if (!(to_real(lo, &p->out->band_lo_N[i]) && to_real(hi, &p->out->band_hi_N[i]))) {
        p->status = FS_ERR_SKILL_RANGE; /* valid in double, beyond the core's type */
    }
    return i + 1u >= p->band_n;
}

/* One unit of the per-item stages: true once the stage's last item is done. */
static bool parse_item(skill_parser_t *p)
{
    const uint8_t *buf = p->buf;
    const uint32_t n = p->n;
    const uint32_t i = p->pos++;
    switch (p->stage) {
    case SP_FINITE: {
        /* 15 (v3: 17, v4: 23) header fields from OFF_DT, then 3N (4N with the y DMP) from the
         * header's end (v4: after the kind) */
        const uint32_t n_hdr = (p->version == 2u)   ? SKILL_N_HEADER_F64_V2
                               : (p->version == 3u) ? SKILL_N_HEADER_F64_V3
                                                    : SKILL_N_HEADER_F64_V4;
        const uint32_t n_f64 = n_hdr + ((p->has_y != 0u) ? 4u : 3u) * n + 2u * p->band_n;
        const uint32_t first = i * SKILL_PARSE_F64_PER_UNIT;
        for (uint32_t k = first; k < n_f64 && k < first + SKILL_PARSE_F64_PER_UNIT; k++) {
            const uint32_t off = (k < n_hdr) ? OFF_DT + 8u * k : p->header + 8u * (k - n_hdr);
            if (!rd_f64_finite(buf, off)) {
                p->status = FS_ERR_SKILL_NOT_FINITE;
            }
        }
        return first + SKILL_PARSE_F64_PER_UNIT >= n_f64;
    }
    case SP_WIDTHS:
        if (!(rd_f64(buf, p->header + 8u * n + 8u * i) > 0.0)) {
            p->status = FS_ERR_SKILL_RANGE;
        }
        return i + 1u >= n;
    case SP_CENTRES: {
        /* discrete: phases of u~ in [0, 1]; periodic: angles in [0, 2*pi) */
        const double c = rd_f64(buf, p->header + 8u * i);
        const int periodic = (p->kind == SKILL_KIND_PERIODIC);
        const int out_of_range = periodic ? (c < 0.0 || !(c < SKILL_TWO_PI)) : (c < 0.0 || c > 1.0);
        if (out_of_range || (i > 0u && !(c > rd_f64(buf, p->header + 8u * (i - 1u))))) {
            p->status = periodic ? FS_ERR_SKILL_PHASES : FS_ERR_SKILL_CENTRES;
        }
        return i + 1u >= n;
    }
    case SP_DERIVE: p->status = derive_gains(p, i); return i + 1u >= DMP_DERIVE_PARTS;
    case SP_BAND: return parse_band(p, i);
    case SP_KERNELS:
        if (!fill_kernel(p, i)) {
            p->status = FS_ERR_SKILL_RANGE; /* valid in double, beyond the core's type */
        }
        return i + 1u >= n;
    default: return true;
    }
}

/* The stages done in one unit each (frame, ranges, gains, kind, fill, finish). */
static void parse_once(skill_parser_t *p)
{
    const uint8_t *buf = p->buf;
    skill_t *out = p->out;
    switch (p->stage) {
    case SP_FRAME: p->status = check_frame(p); break;
    case SP_RANGE: p->status = check_header_range(buf); break;
    case SP_GAINS: p->status = check_gains_flags(buf, p->derived, p->version, p->has_y); break;
    case SP_KIND: p->status = check_kind(buf, p->version, p->kind); break;
    case SP_FILL:
        out->dmp.n_kernels = p->n;
        if (!fill_header(buf, p->has_y, p->kind, out)) {
            p->status = FS_ERR_SKILL_RANGE;
        }
        break;
    case SP_FINISH:
        /* valid in double: the float build can still refuse a value that rounding made invalid */
        if (dmp_gains_at_stiffness(&out->fit_gains, out->stiffness_Npm, &out->gains) != FS_OK) {
            p->status = FS_ERR_SKILL_RANGE;
            break;
        }
        out->end_policy = ((rd_u16(buf, OFF_FLAGS) & SKILL_FLAG_END_RELEASE) != 0u)
                              ? SKILL_END_RELEASE
                              : SKILL_END_HOLD;
        out->kind = p->kind;
        out->band_n = p->band_n;
        out->contact_threshold_N = FS_R(0.0);
        out->contact_tau_s = FS_R(0.0);
        if (p->version >= 4u) {
            out->contact_threshold_N = (fs_real_t)rd_u16(buf, OFF_CONTACT_CN) * FS_R(0.01);
            out->contact_tau_s = (fs_real_t)rd_u16(buf, OFF_CONTACT_MS) * FS_R(0.001);
        }
        dmp_model_init_begin(&p->init);
        break;
    default: break;
    }
}

/* One unit of the CRC stage: true once the CRC and the kernel count are checked. */
static bool parse_crc(skill_parser_t *p)
{
    const uint32_t body = p->len - SKILL_CRC_SIZE;
    const uint32_t take = (body - p->pos < SKILL_PARSE_CRC_BYTES) ? body - p->pos
                                                                  : SKILL_PARSE_CRC_BYTES;
    p->crc = skill_crc32(p->crc, &p->buf[p->pos], take);
    p->pos += take;
    if (p->pos < body) {
        return false;
    }
    if (rd_u32(p->buf, body) != p->crc) {
        p->status = FS_ERR_SKILL_CRC;
    } else if (p->n == 0u || p->n > DMP_MAX_KERNELS) {
        p->status = FS_ERR_SKILL_KERNELS;
    } else if (p->version >= 4u) {
        const uint16_t kind = rd_u16(p->buf, OFF_KIND);
        if (kind > SKILL_KIND_PERIODIC || rd_u16(p->buf, OFF_RESERVED) != 0u) {
            p->status = FS_ERR_SKILL_KIND;
        } else if (p->version >= 5u &&
                   (p->band_n < SKILL_BAND_MIN_POINTS || p->band_n > SKILL_BAND_MAX_POINTS ||
                    rd_u16(p->buf, OFF_BAND_N + 2u) != 0u ||
                    rd_u16(p->buf, OFF_BAND_N + 4u) != 0u ||
                    rd_u16(p->buf, OFF_BAND_N + 6u) != 0u)) {
            p->status = FS_ERR_SKILL_BAND;
        }
        p->kind = (uint8_t)kind;
    }
    return true;
}

bool skill_parse_run(skill_parser_t *p, uint32_t max_units)
{
    for (uint32_t u = 0u; u < max_units && p->stage != SP_DONE; u++) {
        bool stage_done = true;
        if (p->stage == SP_CRC) {
            stage_done = parse_crc(p);
        } else if (p->stage == SP_MODEL) {
            if (dmp_model_init_next_is_reach(&p->out->dmp, &p->init)) {
                if (u != 0u && u + SKILL_PARSE_REACH_UNITS > max_units) {
                    break; /* a reach that does not fit this call's units: the next call's */
                }
                u += SKILL_PARSE_REACH_UNITS - 1u;
            }
            stage_done = dmp_model_init_run(&p->out->dmp, &p->init,
                                            (p->kind == SKILL_KIND_PERIODIC)
                                                ? SKILL_PARSE_INIT_PERIODIC_KERNELS
                                                : SKILL_PARSE_INIT_KERNELS);
            p->status = stage_done ? p->init.status : FS_OK;
        } else if (p->stage == SP_FINITE || p->stage == SP_WIDTHS || p->stage == SP_CENTRES ||
                   p->stage == SP_DERIVE || p->stage == SP_BAND || p->stage == SP_KERNELS) {
            stage_done = parse_item(p);
        } else {
            parse_once(p);
        }
        if (p->status != FS_OK) {
            p->stage = SP_DONE;
        } else if (stage_done) {
            p->stage++;
            p->pos = 0u;
        }
    }
    return p->stage == SP_DONE;
}

fs_status_t skill_parse(const uint8_t *buf, uint32_t len, skill_t *out)
{
    skill_parser_t p;
    skill_parse_begin(&p, buf, len, out);
    while (!skill_parse_run(&p, UINT32_MAX)) {
    }
    return p.status;
}

fs_status_t skill_band_at(const skill_t *sk, fs_real_t s, fs_real_t goal_scale,
                          fs_real_t amplitude_scale, fs_real_t *lo_N, fs_real_t *hi_N)
{
    if (sk == NULL || lo_N == NULL || hi_N == NULL) {
        return FS_ERR_NULL_ARG;
    }
    if (sk->band_n < SKILL_BAND_MIN_POINTS) {
        return FS_ERR_SKILL_BAND;
    }
    const int periodic = (sk->kind == SKILL_KIND_PERIODIC);
    fs_real_t x = (s > FS_R(0.0)) ? s : FS_R(0.0); /* also NaN -> 0 */
    if (periodic && x < FS_R(4.0e9)) {
        x = x - (fs_real_t)(uint32_t)x; /* the fraction of the period */
    }
    x = (x > FS_R(1.0)) ? FS_R(1.0) : x;
    const fs_real_t pos = x * (fs_real_t)(sk->band_n - 1u);
    uint32_t i = (uint32_t)pos;
    if (i > (uint32_t)sk->band_n - 2u) {
        i = (uint32_t)sk->band_n - 2u;
    }
    const fs_real_t frac = pos - (fs_real_t)i;
    const fs_real_t lo = sk->band_lo_N[i] + frac * (sk->band_lo_N[i + 1u] - sk->band_lo_N[i]);
    const fs_real_t hi = sk->band_hi_N[i] + frac * (sk->band_hi_N[i + 1u] - sk->band_hi_N[i]);
    if (periodic) {
        const fs_real_t g = sk->dmp.goal_N;
        *lo_N = goal_scale * g + amplitude_scale * (lo - g);
        *hi_N = goal_scale * g + amplitude_scale * (hi - g);
    } else {
        const fs_real_t f0 = sk->dmp.force0_N;
        *lo_N = f0 + goal_scale * (lo - f0);
        *hi_N = f0 + goal_scale * (hi - f0);
    }
    return FS_OK;
}

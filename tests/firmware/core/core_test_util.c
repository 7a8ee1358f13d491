/* Test-only helpers; see core_test_util.h. */
#include "core_test_util.h"

#include <math.h>
#include <string.h>

double tu_uniform(uint64_t *state, double lo, double hi)
{
    uint64_t x = *state;
    x ^= x >> 12;
    x ^= x << 25;
    x ^= x >> 27;
    *state = x;
    const uint64_t r = x * 0x2545F4914F6CDD1DULL;
    return lo + (hi - lo) * ((double)(r >> 11) / 9007199254740992.0);
}

/* u~ after n steps of the discrete phase recursion (same update order as dmp_step). */
static double phase_after(double alpha, double beta, double dt_s, double tau_s, long n)
{
    double u = 0.0;
    double v = 0.0;
    const double k = dt_s / tau_s;
    for (long i = 0; i < n; i++) {
        const double v_next = v + k * alpha * (beta * (1.0 - u) - v);
        u = u + k * v;
        v = v_next;
    }
    return u;
}

double tu_tau_for_duration(double alpha, double beta, double dt_s, double duration_s)
{
    const long n = lround(duration_s / dt_s);
    double lo = 0.01 * duration_s; /* u(T) close to 1 */
    double hi = 10.0 * duration_s; /* u(T) small */
    for (int it = 0; it < 200; it++) {
        const double mid = 0.5 * (lo + hi);
        if (phase_after(alpha, beta, dt_s, mid, n) > 0.99) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    return 0.5 * (lo + hi);
}

void tu_centres_widths(double alpha, double beta, double dt_s, double tau_s, double duration_s,
                       uint16_t n, double *centre, double *width)
{
    const long steps = lround(duration_s / dt_s);
    const double k = dt_s / tau_s;
    double u = 0.0;
    double v = 0.0;
    long step = 0;
    for (uint16_t i = 0; i < n; i++) {
        const double t_i = (n > 1) ? duration_s * (double)i / (double)(n - 1) : 0.0;
        double pos = t_i / dt_s;
        if (pos > (double)steps) {
            pos = (double)steps;
        }
        long j = (long)floor(pos);
        if (j >= steps) {
            j = steps - 1;
        }
        while (step < j) {
            const double v_next = v + k * alpha * (beta * (1.0 - u) - v);
            u = u + k * v;
            v = v_next;
            step++;
        }
        const double u_next = u + k * v;
        const double frac = pos - (double)j;
        centre[i] = u + frac * (u_next - u);
    }
    for (uint16_t i = 0; i + 1 < n; i++) {
        width[i] = 0.5 * (centre[i + 1] - centre[i]);
    }
    width[n - 1] = (n > 1) ? width[n - 2] : 0.5;
}

void tu_default_desc(tu_skill_desc_t *d, uint16_t n, double stiffness_Npm, double duration_s)
{
    memset(d, 0, sizeof(*d));
    d->n_kernels = n;
    d->flags = 0;
    d->dt_s = 0.001;
    d->m_d = 40.0;
    d->k_d = 400.0;
    d->k_p = 1170.0;
    d->kkf = 540.0;
    d->kki = 4860.0;
    d->stiffness_Npm = stiffness_Npm;
    d->alpha = d->k_d / d->m_d - 1.0;
    d->gamma = d->kki / (d->m_d * d->alpha);
    d->beta = (d->k_p + (d->kkf - d->kki / d->alpha)) / (d->m_d * d->alpha) - 1.0;
    d->duration_s = duration_s;
    d->goal_N = 5.0;
    d->force0_N = 0.0;
    d->surface_m = 0.001;
    d->tau_s = tu_tau_for_duration(d->alpha, d->beta, d->dt_s, duration_s);
    tu_centres_widths(d->alpha, d->beta, d->dt_s, d->tau_s, duration_s, n, d->centre, d->width);
    for (uint16_t i = 0; i < n; i++) {
        const double s = (double)i / (double)(n > 1 ? n - 1 : 1);
        d->weight[i] = 40.0 * sin(3.0 * s) + 15.0 * cos(11.0 * s) - 5.0;
    }
}

fs_status_t tu_model_from_desc(const tu_skill_desc_t *d, dmp_model_t *m)
{
    memset(m, 0, sizeof(*m));
    m->n_kernels = d->n_kernels;
    m->p.alpha = (fs_real_t)d->alpha;
    m->p.beta = (fs_real_t)d->beta;
    m->p.gamma = (fs_real_t)d->gamma;
    m->dt_s = (fs_real_t)d->dt_s;
    m->tau_s = (fs_real_t)d->tau_s;
    m->goal_N = (fs_real_t)d->goal_N;
    m->force0_N = (fs_real_t)d->force0_N;
    m->duration_s = (fs_real_t)d->duration_s;
    for (uint16_t i = 0; i < d->n_kernels && i < DMP_MAX_KERNELS; i++) {
        m->centre[i] = (fs_real_t)d->centre[i];
        m->width[i] = (fs_real_t)d->width[i];
        m->weight[i] = (fs_real_t)d->weight[i];
    }
    return dmp_model_init(m);
}

void tu_put_u16(uint8_t *b, uint32_t off, uint16_t v)
{
    b[off] = (uint8_t)(v & 0xFFu);
    b[off + 1] = (uint8_t)(v >> 8);
}

void tu_put_u32(uint8_t *b, uint32_t off, uint32_t v)
{
    for (uint32_t i = 0; i < 4; i++) {
        b[off + i] = (uint8_t)(v >> (8 * i));
    }
}

void tu_put_f64(uint8_t *b, uint32_t off, double v)
{
    uint64_t u;
    memcpy(&u, &v, sizeof(u));
    for (uint32_t i = 0; i < 8; i++) {
        b[off + i] = (uint8_t)(u >> (8 * i));
    }
}

void tu_fix_crc(uint8_t *b, uint32_t len)
{
    tu_put_u32(b, len - 4u, skill_crc32(0u, b, len - 4u));
}

uint32_t tu_write_image(const tu_skill_desc_t *d, uint8_t *buf, uint32_t cap)
{
    const uint32_t n = d->n_kernels;
    const uint32_t len = SKILL_HEADER_SIZE_V2 + 24u * n + 4u;
    if (len > cap) {
        return 0;
    }
    memset(buf, 0, len);
    tu_put_u32(buf, 0, 0x4C4B5346u);
    tu_put_u16(buf, 4, 2u);
    tu_put_u16(buf, 6, SKILL_HEADER_SIZE_V2);
    tu_put_u32(buf, 8, len);
    tu_put_u16(buf, 12, (uint16_t)n);
    tu_put_u16(buf, 14, d->flags);
    const double hdr[15] = {d->dt_s, d->tau_s, d->alpha, d->beta, d->gamma,
                            d->stiffness_Npm, d->goal_N, d->duration_s, d->m_d, d->k_d,
                            d->k_p, d->kkf, d->kki, d->surface_m, d->force0_N};
    for (uint32_t i = 0; i < 15; i++) {
        tu_put_f64(buf, 16 + 8 * i, hdr[i]);
    }
    const uint32_t h = SKILL_HEADER_SIZE_V2;
    for (uint32_t i = 0; i < n; i++) {
        tu_put_f64(buf, h + 8 * i, d->centre[i]);
        tu_put_f64(buf, h + 8 * n + 8 * i, d->width[i]);
        tu_put_f64(buf, h + 16 * n + 8 * i, d->weight[i]);
    }
    tu_fix_crc(buf, len);
    return len;
}

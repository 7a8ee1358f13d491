/* Test-only helpers for the core tests: realistic kernel layouts computed the way the fit does
 * (docs/math.md section 3), a small skill-image byte writer, and a deterministic RNG. Compiled
 * into each test executable against fs_core or fs_core_f32 (fs_real_t follows the library). */
#ifndef CORE_TEST_UTIL_H
#define CORE_TEST_UTIL_H

#include <stddef.h>
#include <stdint.h>

#include "dmp.h"
#include "skill.h"

/** Deterministic xorshift64* RNG, uniform in [lo, hi). */
double tu_uniform(uint64_t *state, double lo, double hi);

/** tau such that the discrete critically damped phase (alpha, beta = alpha/4, dt) reaches
 *  u~(T) = 0.99 after round(T/dt) steps (bisection, like the fit). */
double tu_tau_for_duration(double alpha, double beta, double dt_s, double duration_s);

/** Centres c_i = u~(t_i), t_i = linspace(0, T, N) (linear interpolation of the discrete phase),
 *  widths sigma_i = 0.5*(c_{i+1} - c_i), sigma_N = sigma_{N-1}; into double arrays. */
void tu_centres_widths(double alpha, double beta, double dt_s, double tau_s, double duration_s,
                       uint16_t n, double *centre, double *width);

/** Description of a skill in double, the way the Python writer would hold it. */
typedef struct {
    uint16_t n_kernels;
    uint16_t flags;
    double dt_s, tau_s, alpha, beta, gamma, stiffness_Npm, goal_N, duration_s;
    double m_d, k_d, k_p, kkf, kki, surface_m, force0_N;
    double centre[DMP_MAX_KERNELS];
    double width[DMP_MAX_KERNELS];
    double weight[DMP_MAX_KERNELS];
} tu_skill_desc_t;

/** A realistic skill: default gains, stiffness k (stored only: the DMP does not depend on it),
 *  duration T, N kernels, goal 5 N, smooth (dimensionless) weights, starting force 0. */
void tu_default_desc(tu_skill_desc_t *d, uint16_t n, double stiffness_Npm, double duration_s);

/** Copy a description into a dmp_model_t and run dmp_model_init (returns its status). */
fs_status_t tu_model_from_desc(const tu_skill_desc_t *d, dmp_model_t *m);

/** Serialise a description as an image v2 (little-endian, CRC last) into buf; returns length. */
uint32_t tu_write_image(const tu_skill_desc_t *d, uint8_t *buf, uint32_t cap);

/** Little-endian writers for patching images in tests. */
void tu_put_u16(uint8_t *b, uint32_t off, uint16_t v);
void tu_put_u32(uint8_t *b, uint32_t off, uint32_t v);
void tu_put_f64(uint8_t *b, uint32_t off, double v);

/** Recompute and store the CRC of an image of total length len. */
void tu_fix_crc(uint8_t *b, uint32_t len);

#endif /* CORE_TEST_UTIL_H */

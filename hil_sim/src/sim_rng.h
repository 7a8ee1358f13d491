/* Deterministic pseudo-random numbers for the simulator: splitmix64 seeds xoshiro256**
 * (Blackman & Vigna). Own implementation so a seed gives the same stream on every platform. */
#ifndef SIM_RNG_H
#define SIM_RNG_H

#include <stdint.h>

/** xoshiro256** state. */
typedef struct {
    uint64_t s[4];
    double spare; /* second value of the last polar-method pair */
    int has_spare;
} sim_rng_t;

/** Seed the generator from one 64-bit value through splitmix64 (never all-zero). */
void sim_rng_seed(sim_rng_t *r, uint64_t seed);

/** Next 64 random bits. */
uint64_t sim_rng_next(sim_rng_t *r);

/** Uniform double in [0, 1) with 53 random bits. */
double sim_rng_uniform(sim_rng_t *r);

/** Uniform double in [lo, hi). */
double sim_rng_range(sim_rng_t *r, double lo, double hi);

/** Standard normal (Marsaglia polar method: each accepted pair gives two values; deterministic). */
double sim_rng_gauss(sim_rng_t *r);

#endif /* SIM_RNG_H */

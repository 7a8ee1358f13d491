/* The side-by-side DMP step benchmark (bench_step_minimal): the core's dmp_step against a
 * minimal step written from the equations, on the same parsed skill. step_pair.c is compiled
 * once per real type (double: step_pair_f64, float32: step_pair_f32). */
#ifndef STEP_PAIR_H
#define STEP_PAIR_H

#include <stdint.h>

#define STEP_PAIR_MAX_REPS 201u

/** What one real type measured. */
typedef struct {
    int status;              /* 0 ok; > 0 the core's fs_status_t refusing the image */
    uint16_t n_kernels;
    uint32_t n_steps;        /* one rollout: round(T/dt) steps */
    uint32_t reps;           /* timed rollouts of each step, interleaved */
    double ours_ns;          /* median ns per step, dmp_step */
    double minimal_ns;       /* median ns per step, the minimal step */
    double max_rel_diff;     /* max |f_ours - f_min| / max |f_ours| over the rollout */
    double checksum;         /* sum of f_hat of our first rollout (keeps the work) */
} step_pair_result_t;

/** Parse img (double core) and time reps interleaved rollouts of both steps. */
void step_pair_f64(const uint8_t *img, uint32_t len, uint32_t reps, step_pair_result_t *out);

/** The same with the float32 core and a float32 minimal step. */
void step_pair_f32(const uint8_t *img, uint32_t len, uint32_t reps, step_pair_result_t *out);

#endif /* STEP_PAIR_H */

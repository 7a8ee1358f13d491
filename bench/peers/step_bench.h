/* Benchmark driver for one force-DMP step of the C core (bench/peers): the same skill
 * image stepped by the double core (fs_core) and the float core (fs_core_f32). Each core is
 * compiled in its own translation unit (step_impl.c, twice) because both define dmp_model_t. */
#ifndef STEP_BENCH_H
#define STEP_BENCH_H

#include <stdint.h>

#define STEP_BENCH_MAX_REPS 1000u

/** What one core measured over reps rollouts of the whole skill. */
typedef struct {
    int status;                          /* fs_status_t of parse/validate, 0 = ok */
    uint32_t n_steps;                    /* steps per rollout: round(T/dt) */
    uint32_t reps;
    uint16_t n_kernels;
    double ns_per_step[STEP_BENCH_MAX_REPS];
    double checksum;                     /* sum of f_hat over the first rollout (keeps the work) */
    double max_force_N;                  /* max f_hat over the first rollout */
    double mean_active_kernels;          /* kernels within the cutoff, mean over the first rollout */
    uint32_t sizeof_model;               /* sizeof(dmp_model_t) */
    uint32_t sizeof_state;               /* sizeof(dmp_state_t) */
    uint32_t sizeof_skill;               /* sizeof(skill_t) */
} step_bench_result_t;

/** Parse img with the double core and time reps rollouts (after one warm-up rollout). */
void step_bench_f64(const uint8_t *img, uint32_t len, uint32_t reps, step_bench_result_t *out);

/** The same with the float32 core. */
void step_bench_f32(const uint8_t *img, uint32_t len, uint32_t reps, step_bench_result_t *out);

/** The same with the fixed-point core (dmpfx_step; mean_active_kernels then holds the number of
 *  saturation events of the warm-up rollout). Built only where firmware/fixed exists. */
void step_bench_fixed(const uint8_t *img, uint32_t len, uint32_t reps, step_bench_result_t *out);

/** Monotonic clock in ns. */
uint64_t step_bench_now_ns(void);

#endif /* STEP_BENCH_H */

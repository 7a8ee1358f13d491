/* dmp_step benchmark entry points (bench_step.c compiled for each core type). */
#ifndef BENCH_CORE_STEP_H
#define BENCH_CORE_STEP_H

#include <stdint.h>

/** Median ns per dmp_step over `runs` 17 000-step rollouts with N kernels; adds the outputs to
 *  *f_sink (keeps the work observable). Returns -1 on setup failure. */
double bench_core_step_double(uint16_t n_kernels, int runs, double *f_sink);
double bench_core_step_float(uint16_t n_kernels, int runs, double *f_sink);

#endif

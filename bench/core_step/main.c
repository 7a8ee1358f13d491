/* bench_core_step: cost of one dmp_step (the 1 kHz tick's DMP part) on this host, double and
 * float cores, N = 10..200 kernels; median of several 17 000-step rollouts. Built -O2 without
 * sanitizers whatever the build type. Not a test: it prints figures. */
#include <stdio.h>

#include "bench_core_step.h"

int main(void)
{
    const unsigned short ns[] = {10, 20, 50, 100, 200};
    const int runs = 9;
    double sink = 0.0;
    int rc = 0;
    for (size_t i = 0; i < sizeof(ns) / sizeof(ns[0]); i++) {
        const double d = bench_core_step_double(ns[i], runs, &sink);
        const double f = bench_core_step_float(ns[i], runs, &sink);
        if (d < 0.0 || f < 0.0) {
            fprintf(stderr, "bench_core_step: model setup failed for N=%u\n", ns[i]);
            rc = 1;
            continue;
        }
        printf("dmp_step ns/step N=%u double=%.1f float=%.1f\n", ns[i], d, f);
    }
    printf("(median of %d rollouts of 17000 steps; checksum %.6g)\n", runs, sink);
    return rc;
}

/* fs_bench_step SKILL_IMAGE [REPS] [CORE]: ns per DMP step of the double, float and (where
 * firmware/fixed is built) fixed-point cores on one skill; CORE is double|float|fixed|all.
 * Prints one line per core:
 *   step core=double kernels=N steps=S reps=R ns_median=.. ns_min=.. ns_max=.. active_mean=..
 *        max_force_N=.. checksum=..
 * and one line of static sizes per core:
 *   sizeof core=double model=B state=B skill=B
 * A core that rejects the image prints "step core=C status=CODE" (its fs_status_t) instead.
 * Exit status 0 on success, 2 on a bad argument or file, 3 on a non-deterministic rollout. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "step_bench.h"

#define MAX_IMAGE 65536u

static uint8_t g_image[MAX_IMAGE];
static step_bench_result_t g_res;

uint64_t step_bench_now_ns(void)
{
    struct timespec ts;
    (void)clock_gettime(CLOCK_MONOTONIC, &ts);
    return (uint64_t)ts.tv_sec * 1000000000u + (uint64_t)ts.tv_nsec;
}

static int cmp_double(const void *a, const void *b)
{
    const double x = *(const double *)a;
    const double y = *(const double *)b;
    return (x > y) - (x < y);
}

static int report(const char *core, step_bench_result_t *r)
{
    if (r->status > 0) {
        /* a core that refuses the skill is a result, not a failure of the benchmark */
        printf("step core=%s status=%d\n", core, r->status);
        printf("sizeof core=%s model=%u state=%u skill=%u\n", core, (unsigned)r->sizeof_model,
               (unsigned)r->sizeof_state, (unsigned)r->sizeof_skill);
        fprintf(stderr, "fs_bench_step: %s core rejected the image: status %d\n", core, r->status);
        return 0;
    }
    if (r->status < 0) {
        fprintf(stderr, "fs_bench_step: %s core: rollouts differ between repetitions\n", core);
        return 3;
    }
    qsort(r->ns_per_step, r->reps, sizeof(double), cmp_double);
    const uint32_t n = r->reps;
    const double median = (n % 2u) ? r->ns_per_step[n / 2u]
                                    : 0.5 * (r->ns_per_step[n / 2u - 1u] + r->ns_per_step[n / 2u]);
    printf("step core=%s kernels=%u steps=%u reps=%u ns_median=%.3f ns_min=%.3f ns_max=%.3f "
           "active_mean=%.3f max_force_N=%.6f checksum=%.9e\n",
           core, (unsigned)r->n_kernels, (unsigned)r->n_steps, (unsigned)n, median,
           r->ns_per_step[0], r->ns_per_step[n - 1u], r->mean_active_kernels, r->max_force_N,
           r->checksum);
    printf("sizeof core=%s model=%u state=%u skill=%u\n", core, (unsigned)r->sizeof_model,
           (unsigned)r->sizeof_state, (unsigned)r->sizeof_skill);
    return 0;
}

int main(int argc, char **argv)
{
    if (argc < 2 || argc > 4) {
        fprintf(stderr, "usage: fs_bench_step SKILL_IMAGE [REPS] [double|float|fixed|all]\n");
        return 2;
    }
    long reps = 11;
    if (argc >= 3) {
        char *end = NULL;
        reps = strtol(argv[2], &end, 10);
        if (end == argv[2] || *end != '\0' || reps < 1 || reps > (long)STEP_BENCH_MAX_REPS) {
            fprintf(stderr, "fs_bench_step: REPS must be 1..%u, got '%s'\n", STEP_BENCH_MAX_REPS,
                    argv[2]);
            return 2;
        }
    }
    const char *which = (argc == 4) ? argv[3] : "all";
    if (strcmp(which, "double") != 0 && strcmp(which, "float") != 0 && strcmp(which, "fixed") != 0 &&
        strcmp(which, "all") != 0) {
        fprintf(stderr, "fs_bench_step: core must be double, float, fixed or all, got '%s'\n", which);
        return 2;
    }
    FILE *f = fopen(argv[1], "rb");
    if (f == NULL) {
        fprintf(stderr, "fs_bench_step: cannot open %s\n", argv[1]);
        return 2;
    }
    const size_t len = fread(g_image, 1, MAX_IMAGE, f);
    (void)fclose(f);
    if (len == 0u || len == MAX_IMAGE) {
        fprintf(stderr, "fs_bench_step: %s: empty or larger than %u bytes\n", argv[1], MAX_IMAGE);
        return 2;
    }
    int rc = 0;
    if (strcmp(which, "double") == 0 || strcmp(which, "all") == 0) {
        step_bench_f64(g_image, (uint32_t)len, (uint32_t)reps, &g_res);
        rc = report("double", &g_res);
    }
    if (rc == 0 && (strcmp(which, "float") == 0 || strcmp(which, "all") == 0)) {
        step_bench_f32(g_image, (uint32_t)len, (uint32_t)reps, &g_res);
        rc = report("float", &g_res);
    }
#ifdef STEP_BENCH_HAVE_FIXED
    if (rc == 0 && (strcmp(which, "fixed") == 0 || strcmp(which, "all") == 0)) {
        step_bench_fixed(g_image, (uint32_t)len, (uint32_t)reps, &g_res);
        rc = report("fixed", &g_res);
    }
#endif
    return rc;
}

/* bench_step_minimal SKILL_IMAGE... [--reps R]: ns per DMP step of the core's dmp_step and of a
 * minimal step written from the equations (step_pair.c), side by side on the same skill, double
 * and float32, built -O2 without sanitizers. One line per skill and type:
 *   step_pair core=double skill=NAME kernels=N steps=S reps=R ours_ns=.. minimal_ns=..
 *             ratio=.. max_rel_diff=..
 * ratio = ours/minimal (medians of R interleaved rollouts). Exit 1 if the outputs differ by more
 * than 1e-12 (double) or 1e-5 (float) of the peak force: the two must compute the same step. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "step_pair.h"

#define MAX_IMAGE 65536u

static uint8_t g_image[MAX_IMAGE];
static step_pair_result_t g_res;

static int report(const char *core, const char *name, const step_pair_result_t *r, double tol)
{
    if (r->status != 0) {
        fprintf(stderr, "bench_step_minimal: %s: %s core refused the skill (status %d)\n", name,
                core, r->status);
        return 1;
    }
    printf("step_pair core=%s skill=%s kernels=%u steps=%u reps=%u ours_ns=%.2f minimal_ns=%.2f "
           "ratio=%.3f max_rel_diff=%.2e\n",
           core, name, (unsigned)r->n_kernels, (unsigned)r->n_steps, (unsigned)r->reps,
           r->ours_ns, r->minimal_ns, r->ours_ns / r->minimal_ns, r->max_rel_diff);
    if (!(r->max_rel_diff <= tol)) {
        fprintf(stderr, "bench_step_minimal: %s %s: outputs differ by %.3g of the peak (> %.0e)\n",
                name, core, r->max_rel_diff, tol);
        return 1;
    }
    return 0;
}

int main(int argc, char **argv)
{
    long reps = 61;
    int rc = 0;
    int n_images = 0;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--reps") == 0 && i + 1 < argc) {
            char *end = NULL;
            reps = strtol(argv[++i], &end, 10);
            if (*end != '\0' || reps < 1 || reps > (long)STEP_PAIR_MAX_REPS) {
                fprintf(stderr, "bench_step_minimal: --reps must be 1..%u\n", STEP_PAIR_MAX_REPS);
                return 2;
            }
        }
    }
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--reps") == 0) {
            i++;
            continue;
        }
        FILE *f = fopen(argv[i], "rb");
        if (f == NULL) {
            fprintf(stderr, "bench_step_minimal: cannot open %s\n", argv[i]);
            return 2;
        }
        const size_t len = fread(g_image, 1, MAX_IMAGE, f);
        (void)fclose(f);
        if (len == 0u || len == MAX_IMAGE) {
            fprintf(stderr, "bench_step_minimal: %s: empty or too large\n", argv[i]);
            return 2;
        }
        const char *name = strrchr(argv[i], '/');
        name = (name != NULL) ? name + 1 : argv[i];
        n_images++;
        step_pair_f64(g_image, (uint32_t)len, (uint32_t)reps, &g_res);
        rc |= report("double", name, &g_res, 1e-12);
        step_pair_f32(g_image, (uint32_t)len, (uint32_t)reps, &g_res);
        rc |= report("float", name, &g_res, 1e-5);
    }
    if (n_images == 0) {
        fprintf(stderr, "usage: bench_step_minimal SKILL_IMAGE... [--reps R]\n");
        return 2;
    }
    return rc;
}

/* One core's step benchmark; compiled once per core with STEP_BENCH_FN naming the entry point
 * (step_bench_f64 against fs_core, step_bench_f32 against fs_core_f32, FS_REAL_FLOAT set). */
#include <math.h>
#include <stddef.h>
#include <string.h>

#include "skill.h"
#include "step_bench.h"

#ifndef STEP_BENCH_FN
#error "define STEP_BENCH_FN"
#endif

static skill_t g_skill;   /* static: the model is ~12 KB (double), not for the stack */

static double rollout(const dmp_model_t *m, uint32_t n_steps, double *max_f, double *active)
{
    dmp_state_t s;
    const dmp_run_t run = {FS_R(1.0), FS_R(1.0)};
    double sum = 0.0;
    double act = 0.0;
    dmp_state_reset(&s);
    for (uint32_t i = 0; i < n_steps; ++i) {
        if (active != NULL) {
            act += (double)dmp_active_kernels(m, s.u);
        }
        const fs_real_t f = dmp_step(m, &s, &run, NULL);
        sum += (double)f;
        if (max_f != NULL && (double)f > *max_f) {
            *max_f = (double)f;
        }
    }
    if (active != NULL) {
        *active = act / (double)n_steps;
    }
    return sum;
}

void STEP_BENCH_FN(const uint8_t *img, uint32_t len, uint32_t reps, step_bench_result_t *out)
{
    memset(out, 0, sizeof(*out));
    out->sizeof_model = (uint32_t)sizeof(dmp_model_t);
    out->sizeof_state = (uint32_t)sizeof(dmp_state_t);
    out->sizeof_skill = (uint32_t)sizeof(skill_t);
    fs_status_t st = skill_parse(img, len, &g_skill);
    if (st != FS_OK) {
        out->status = (int)st;
        return;
    }
    const dmp_run_t run = {FS_R(1.0), FS_R(1.0)};
    st = dmp_run_validate(&run);
    if (st != FS_OK) {
        out->status = (int)st;
        return;
    }
    const dmp_model_t *m = &g_skill.dmp;
    out->n_kernels = m->n_kernels;
    out->n_steps = (uint32_t)lround((double)m->duration_s / (double)m->dt_s);
    if (reps > STEP_BENCH_MAX_REPS) {
        reps = STEP_BENCH_MAX_REPS;
    }
    out->reps = reps;
    out->max_force_N = -HUGE_VAL;
    /* warm-up rollout: also the checksum, the peak force and the active-kernel count */
    out->checksum = rollout(m, out->n_steps, &out->max_force_N, &out->mean_active_kernels);
    for (uint32_t r = 0; r < reps; ++r) {
        const uint64_t t0 = step_bench_now_ns();
        const double sum = rollout(m, out->n_steps, NULL, NULL);
        const uint64_t t1 = step_bench_now_ns();
        if (sum != out->checksum) {
            out->status = -1;   /* a rollout must be deterministic */
        }
        out->ns_per_step[r] = (double)(t1 - t0) / (double)out->n_steps;
    }
}

/* The fixed-point core's step benchmark (firmware/fixed): the skill is parsed by the
 * double core and converted once by dmpfx_from_model, as on the Cortex-M3; the tick is dmpfx_step. */
#include <math.h>
#include <stddef.h>
#include <string.h>

#include "dmpfx.h"
#include "skill.h"
#include "step_bench.h"

static skill_t g_skill_fx;
static dmpfx_model_t g_model_fx;

static double rollout_fx(const dmpfx_run_t *run, uint32_t n_steps, double *max_f, uint32_t *sat)
{
    dmpfx_state_t s;
    double sum = 0.0;
    dmpfx_state_reset(&s);
    for (uint32_t i = 0; i < n_steps; ++i) {
        const double f = (double)dmpfx_step(&g_model_fx, run, &s, NULL) / 65536.0;
        sum += f;
        if (max_f != NULL && f > *max_f) {
            *max_f = f;
        }
    }
    if (sat != NULL) {
        *sat = s.sat_events;
    }
    return sum;
}

void step_bench_fixed(const uint8_t *img, uint32_t len, uint32_t reps, step_bench_result_t *out)
{
    memset(out, 0, sizeof(*out));
    out->sizeof_model = (uint32_t)sizeof(dmpfx_model_t);
    out->sizeof_state = (uint32_t)sizeof(dmpfx_state_t);
    out->sizeof_skill = (uint32_t)sizeof(skill_t);
    fs_status_t st = skill_parse(img, len, &g_skill_fx);
    if (st == FS_OK) {
        st = dmpfx_from_model(&g_skill_fx.dmp, &g_model_fx);
    }
    dmpfx_run_t run;
    if (st == FS_OK) {
        st = dmpfx_run_init(&g_model_fx, 1.0, 1.0, &run);
    }
    if (st != FS_OK) {
        out->status = (int)st;
        return;
    }
    out->n_kernels = g_model_fx.n_kernels;
    out->n_steps = (uint32_t)lround(g_skill_fx.dmp.duration_s / g_skill_fx.dmp.dt_s);
    if (reps > STEP_BENCH_MAX_REPS) {
        reps = STEP_BENCH_MAX_REPS;
    }
    out->reps = reps;
    out->max_force_N = -HUGE_VAL;
    uint32_t sat = 0;
    out->checksum = rollout_fx(&run, out->n_steps, &out->max_force_N, &sat);
    out->mean_active_kernels = (double)sat;   /* fixed core: saturation events of the warm-up */
    for (uint32_t r = 0; r < reps; ++r) {
        const uint64_t t0 = step_bench_now_ns();
        const double sum = rollout_fx(&run, out->n_steps, NULL, NULL);
        const uint64_t t1 = step_bench_now_ns();
        if (sum != out->checksum) {
            out->status = -1;
        }
        out->ns_per_step[r] = (double)(t1 - t0) / (double)out->n_steps;
    }
}

/* Float32 half of test_f32_vs_double (see f32_side.h). */
#include "f32_side.h"

#include <math.h>
#include <stddef.h>

#include "fs_num.h"
#include "skill.h"

static skill_t sk;

long f32_parse_rollout(const uint8_t *image, uint32_t len, double goal_scale, double time_scale,
                       double *out, long cap)
{
    const fs_status_t st = skill_parse(image, len, &sk);
    if (st != FS_OK) {
        return -(long)st;
    }
    const dmp_run_t run = {(fs_real_t)goal_scale, (fs_real_t)time_scale};
    const long n = lround((double)sk.dmp.duration_s * time_scale / (double)sk.dmp.dt_s);
    if (n + 1 > cap) {
        return 0;
    }
    dmp_state_t s;
    dmp_state_reset(&s);
    out[0] = (double)sk.dmp.force0_N;
    for (long i = 1; i <= n; i++) {
        out[i] = (double)dmp_step(&sk.dmp, &s, &run, NULL);
    }
    return n + 1;
}

double f32_exp_neg(double e)
{
    return (double)fs_num_exp_neg((fs_expo_t)e);
}

double f32_kernel_cutoff(void)
{
    return (double)FS_NUM_CUTOFF;
}

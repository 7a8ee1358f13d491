/* The float32 half of bench_periodic_drift: the float core's parser and periodic step (its
 * symbols carry _f32; this file is compiled with FS_REAL_FLOAT). */
#include "f32_side.h"

#include <stddef.h>

#include "skill.h"

static skill_t sk32;

int pd_f32_rollout(const uint8_t *img, uint32_t len, long rows, double *f, double *x_end)
{
    if (skill_parse(img, len, &sk32) != FS_OK || sk32.dmp.periodic == 0u) {
        return -1;
    }
    dmp_state_t s;
    dmp_periodic_reset(&sk32.dmp, &s, 1.0f);
    f[0] = (double)(sk32.dmp.force0_N + sk32.dmp.goal_N + s.y_N);
    for (long n = 1; n <= rows; n++) {
        f[n] = (double)dmp_periodic_step(&sk32.dmp, &s, NULL, 1.0f, NULL);
    }
    *x_end = (double)s.u;
    return 0;
}

/* fixed_compare SKILL GOAL_SCALE TIME_SCALE: roll a skill image out with the fixed-point DMP and
 * with the float64 core, print the max difference in % of max force, exit 1 above 0.02 % (the
 * aim; the limit is 0.1 %) or on a saturation; once converted with the measured peaks
 * (dmpfx_from_model) and once as the executor converts (dmpfx_from_model_bound). Used by paper_tasks_fixed.py on the skills
 * fitted from the HIL simulator's demonstrations of the four paper tasks. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "dmpfx.h"
#include "skill.h"

#define LIMIT_REL 2e-4

static uint8_t image[SKILL_IMAGE_MAX];
static skill_t skill;
static dmpfx_model_t model;

/* Roll m out against the float64 core, print the difference; 0 within LIMIT_REL without a
 * saturation, else 1. */
static int compare(const char *name, const char *what, const dmpfx_model_t *m, double gs, double ts)
{
    dmpfx_run_t run;
    const fs_status_t st = dmpfx_run_init(m, gs, ts, &run);
    if (st != FS_OK) {
        printf("fixed_compare %s%s: rejected with %d\n", name, what, (int)st);
        return 1;
    }
    const dmp_run_t rd = {gs, ts};
    dmp_state_t sd;
    dmpfx_state_t sf;
    dmp_state_reset(&sd);
    dmpfx_state_reset(&sf);
    const long rows = lround(skill.dmp.duration_s * ts / skill.dmp.dt_s);
    double err = 0.0;
    double f_max = 0.0;
    for (long n = 1; n <= rows; n++) {
        const double fd = dmp_step(&skill.dmp, &sd, &rd, NULL);
        const double ff = fx_to_double(dmpfx_step(m, &run, &sf, NULL), 16u);
        err = fmax(err, fabs(ff - fd));
        f_max = fmax(f_max, fabs(fd));
    }
    const double rel = err / f_max;
    printf("fixed vs float64%s %s N=%u goal=%g time=%g T=%.2f s: %.5f %% of max force %.3f N "
           "(saturations %u; value shift %d, nominal peak of h/x/z/I %.3g of Q8.24's 128, |v~| "
           "%.3f)\n",
           what, name, (unsigned)skill.dmp.n_kernels, gs, ts, skill.dmp.duration_s, 100.0 * rel,
           f_max, sf.sat_events, (int)m->value_shift, m->peak_q24 / 16777216.0,
           m->peak_v_q30 / 1073741824.0);
    return (rel <= LIMIT_REL && sf.sat_events == 0u) ? 0 : 1;
}

int main(int argc, char **argv)
{
    if (argc != 4) {
        fprintf(stderr, "usage: %s SKILL GOAL_SCALE TIME_SCALE\n", argv[0]);
        return 2;
    }
    FILE *f = fopen(argv[1], "rb");
    if (f == NULL) {
        fprintf(stderr, "cannot open %s\n", argv[1]);
        return 2;
    }
    const uint32_t len = (uint32_t)fread(image, 1, sizeof(image), f);
    fclose(f);
    const double gs = strtod(argv[2], NULL);
    const double ts = strtod(argv[3], NULL);
    fs_status_t st = skill_parse(image, len, &skill);
    if (st == FS_OK) {
        st = dmpfx_from_model(&skill.dmp, &model);
    }
    if (st != FS_OK) {
        printf("fixed_compare %s: rejected with %d\n", argv[1], (int)st);
        return 1;
    }
    int rc = compare(argv[1], "", &model, gs, ts);
    /* the executor's conversion (no rollout, estimated peaks) */
    st = dmpfx_from_model_bound(&skill.dmp, &model);
    if (st != FS_OK) {
        printf("fixed_compare %s: rejected by the bound conversion with %d\n", argv[1], (int)st);
        return 1;
    }
    rc |= compare(argv[1], " (bound conversion)", &model, gs, ts);
    return rc;
}

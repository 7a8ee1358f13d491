/* Host reference for the Cortex-M3 benchmark: the same skill rolled out by the fixed-point DMP
 * (fs_fixed) on the host, printed in the benchmark's format (f_hat Q16.16, hex). The M3 image
 * must match it bit for bit: same integer code, no floating point in the tick. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "dmpfx.h"
#include "skill.h"

static uint8_t image[SKILL_IMAGE_MAX];
static skill_t skill;
static dmpfx_model_t model;

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
    fs_status_t st = skill_parse(image, len, &skill);
    if (st == FS_OK) {
        st = dmpfx_from_model(&skill.dmp, &model);
    }
    const double gs = strtod(argv[2], NULL);
    const double ts = strtod(argv[3], NULL);
    dmpfx_run_t run;
    if (st == FS_OK) {
        st = dmpfx_run_init(&model, gs, ts, &run);
    }
    if (st != FS_OK) {
        fprintf(stderr, "skill rejected: %d\n", (int)st);
        return 1;
    }
    const long rows = lround(skill.dmp.duration_s * ts / skill.dmp.dt_s);
    dmpfx_state_t s;
    dmpfx_state_reset(&s);
    static uint32_t path_bits[8000];
    for (long n = 0; n < rows; n++) {
        int32_t p = 0;
        const uint32_t bits = (uint32_t)dmpfx_step_xy(&model, &run, &s, NULL, &p);
        if (n < 8000) {
            path_bits[n] = (uint32_t)p;
        }
        printf("%s %08x%s", (n % 8) == 0 ? "fhat" : "", bits, ((n % 8) == 7 || n + 1 == rows) ? "\n" : "");
    }
    for (long n = 0; n < rows && n < 8000; n++) {
        printf("%s %08x%s", (n % 8) == 0 ? "ypath" : "", path_bits[n], ((n % 8) == 7 || n + 1 == rows) ? "\n" : "");
    }
    return 0;
}

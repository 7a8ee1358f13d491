/* Host reference for the Cortex-M4F benchmark: the same skill rolled out by the float32 core
 * (fs_core_f32) on the host, printed in the benchmark's format (f_hat float32 bits, hex). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dmp.h"
#include "skill.h"

static uint8_t image[SKILL_IMAGE_MAX];
static skill_t skill;

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
    const fs_status_t st = skill_parse(image, len, &skill);
    if (st != FS_OK) {
        fprintf(stderr, "skill rejected: %d\n", (int)st);
        return 1;
    }
    const double gs = strtod(argv[2], NULL);
    const double ts = strtod(argv[3], NULL);
    const dmp_run_t run = {(float)gs, (float)ts};
    const long rows = lround((double)skill.dmp.duration_s * ts / (double)skill.dmp.dt_s);
    dmp_state_t s;
    dmp_state_reset(&s);
    static uint32_t path_bits[8000];
    for (long n = 0; n < rows; n++) {
        float p = 0.0f;
        const float fh = dmp_step_xy(&skill.dmp, &s, &run, NULL, 1.0f, &p);
        uint32_t bits;
        memcpy(&bits, &fh, sizeof(bits));
        if (n < 8000) {
            memcpy(&path_bits[n], &p, sizeof(bits));
        }
        printf("%s %08x%s", (n % 8) == 0 ? "fhat" : "", bits, ((n % 8) == 7 || n + 1 == rows) ? "\n" : "");
    }
    for (long n = 0; n < rows && n < 8000; n++) {
        printf("%s %08x%s", (n % 8) == 0 ? "ypath" : "", path_bits[n], ((n % 8) == 7 || n + 1 == rows) ? "\n" : "");
    }
    return 0;
}

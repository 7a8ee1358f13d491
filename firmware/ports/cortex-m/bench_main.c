/* Benchmark image: the full control tick (cm_tick.h) over a whole embedded skill, each tick
 * between the two markers so bench/qemu_tick.sh can count its instructions in the qemu exec
 * trace. Prints f_hat of every tick (raw bits, hex) for comparison with the host build, then
 * the y DMP's p of every tick from a second, unmarked run of the same rollout (one row buffer:
 * the RAM holds one). */
#include <stdint.h>

#include "cm_bench.h"
#include "cm_tick.h"
#include "semihost.h"

#ifndef CM_BENCH_GOAL_SCALE
#define CM_BENCH_GOAL_SCALE 1.0
#endif
#ifndef CM_BENCH_TIME_SCALE
#define CM_BENCH_TIME_SCALE 1.0
#endif
#define CM_BENCH_MAX_ROWS 8000u

static uint32_t bench_out[CM_BENCH_MAX_ROWS];

/* Rows of raw bits, 8 per line after the tag ("fhat", "ypath"). */
static void bench_print_rows(const char *tag, const uint32_t *v, uint32_t rows)
{
    for (uint32_t n = 0u; n < rows; n++) {
        if ((n % 8u) == 0u) {
            sh_buf_str(tag);
        }
        sh_buf_str(" ");
        sh_buf_hex32(v[n]);
        if ((n % 8u) == 7u || n + 1u == rows) {
            sh_buf_str("\n");
        }
    }
}

int main(void)
{
    const fs_status_t st = cm_tick_init(cm_bench_skill, cm_bench_skill_len, CM_BENCH_GOAL_SCALE,
                                        CM_BENCH_TIME_SCALE);
    if (st != FS_OK) {
        sh_buf_str("bench: skill rejected, status ");
        sh_buf_u32((uint32_t)st);
        sh_buf_str("\n");
        sh_flush();
        return 1;
    }
    const uint32_t rows = cm_tick_rows();
    if (rows > CM_BENCH_MAX_ROWS) {
        sh_puts("bench: skill longer than CM_BENCH_MAX_ROWS\n");
        return 1;
    }
    cm_plant_init(cm_tick_surface_m(), 200.0);
    for (uint32_t n = 0u; n < rows; n++) {
        cm_plant_sense();
        cm_bench_mark_begin();
        const uint32_t f = cm_tick();
        cm_bench_mark_end();
        bench_out[n] = f;
        cm_plant_step();
    }
    bench_print_rows("fhat", bench_out, rows);
    const uint32_t faults = cm_tick_faults(); /* of the marked run */
    (void)cm_tick_init(cm_bench_skill, cm_bench_skill_len, CM_BENCH_GOAL_SCALE,
                       CM_BENCH_TIME_SCALE);
    cm_plant_init(cm_tick_surface_m(), 200.0);
    for (uint32_t n = 0u; n < rows; n++) {
        cm_plant_sense();
        (void)cm_tick();
        bench_out[n] = cm_tick_path_bits();
        cm_plant_step();
    }
    bench_print_rows("ypath", bench_out, rows);
    sh_buf_str("bench numeric=");
    sh_buf_str(cm_tick_numeric());
    sh_buf_str(" rows=");
    sh_buf_u32(rows);
    sh_buf_str(" faults=");
    sh_buf_u32(faults | cm_tick_faults());
    sh_buf_str("\n");
    sh_flush();
    return 0;
}

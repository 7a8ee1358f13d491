/* The 1 kHz loop image: SysTick at 1 kHz (25 MHz core clock on mps2) raises a flag, the main
 * loop sleeps (wfi) until it, then runs one control tick. A tick still running when the next
 * SysTick fires is an overrun (counted; the application latches a fault on it). Runs the
 * embedded skill once and prints a summary. */
#include <stdint.h>

#include "cm_bench.h"
#include "cm_tick.h"
#include "semihost.h"

#define SYST_CSR (*(volatile uint32_t *)0xE000E010u)
#define SYST_RVR (*(volatile uint32_t *)0xE000E014u)
#define SYST_CVR (*(volatile uint32_t *)0xE000E018u)
#define CM_CORE_CLOCK_HZ 25000000u /* mps2-an385/an386 SYSCLK */
#define CM_TICK_HZ 1000u

static volatile uint32_t loop_pending;
static volatile uint32_t loop_overruns;
static volatile uint32_t loop_busy;

void SysTick_Handler(void)
{
    if (loop_busy != 0u || loop_pending != 0u) {
        loop_overruns = loop_overruns + 1u;
    }
    loop_pending = 1u;
}

int main(void)
{
    if (cm_tick_init(cm_bench_skill, cm_bench_skill_len, 1.0, 1.0) != FS_OK) {
        sh_puts("loop: skill rejected\n");
        return 1;
    }
    const uint32_t rows = cm_tick_rows();
    cm_plant_init(cm_tick_surface_m(), 200.0);
    SYST_RVR = CM_CORE_CLOCK_HZ / CM_TICK_HZ - 1u;
    SYST_CVR = 0u;
    SYST_CSR = 0x7u; /* enable, interrupt, processor clock */
    double f_max = 0.0;
    for (uint32_t n = 0u; n < rows; n++) {
        while (loop_pending == 0u) {
            __asm__ volatile("wfi");
        }
        loop_pending = 0u;
        loop_busy = 1u;
        cm_plant_sense();
        const double f = cm_tick_fhat_N(cm_tick());
        cm_plant_step();
        loop_busy = 0u;
        f_max = (f > f_max) ? f : f_max;
    }
    SYST_CSR = 0u;
    sh_buf_str("loop numeric=");
    sh_buf_str(cm_tick_numeric());
    sh_buf_str(" ticks=");
    sh_buf_u32(rows);
    sh_buf_str(" overruns=");
    sh_buf_u32(loop_overruns);
    sh_buf_str(" faults=");
    sh_buf_u32(cm_tick_faults());
    sh_buf_str(" fhat_max_mN=");
    sh_buf_u32((uint32_t)(f_max * 1000.0 + 0.5));
    sh_buf_str("\n");
    sh_flush();
    return (loop_overruns == 0u) ? 0 : 1;
}

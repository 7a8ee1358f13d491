/* Calibration image for the instruction counter: exactly 100 nops (plus the call and return)
 * between the markers, three times. bench/qemu_tick.sh requires the counter to report
 * 1 (bl) + 100 + 1 (bx lr) + 1 (bl to the end marker) = 103 for each, which proves that one
 * trace line is one executed instruction with this qemu and these options. */
#include "cm_port.h"
#include "cm_semihost.h"

void cm_nops_100(void);
__attribute__((naked, noinline)) void cm_nops_100(void)
{
    __asm__ volatile(".rept 100\n\tnop\n\t.endr\n\tbx lr");
}

int main(void)
{
    for (int i = 0; i < 3; i++) {
        cm_port_mark_begin();
        cm_nops_100();
        cm_port_mark_end();
    }
    sh_puts("count_check done\n");
    return 0;
}

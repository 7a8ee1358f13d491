/* Minimal Cortex-M startup shared by the bootloader and the test application: 16 system
 * vectors, .data copy, .bss clear, main(). Faults print and end the qemu run (exit code 99). */
#include <stdint.h>
#include <string.h>
#include "semihost.h"

extern uint32_t _estack, _sidata, _sdata, _edata, _sbss, _ebss;
int main(void);
void Reset_Handler(void);
void Fault_Handler(void);

void Reset_Handler(void)
{
    memcpy(&_sdata, &_sidata, (size_t)((uintptr_t)&_edata - (uintptr_t)&_sdata));
    memset(&_sbss, 0, (size_t)((uintptr_t)&_ebss - (uintptr_t)&_sbss));
    sh_exit((uint32_t)main());
}

void Fault_Handler(void)
{
    sh_puts("fault: exception taken\n");
    sh_exit(99u);
}

typedef void (*vector_t)(void);

__attribute__((section(".isr_vector"), used)) const vector_t fs_vectors[16] = {
    (vector_t)(uintptr_t)&_estack,
    Reset_Handler,
    Fault_Handler,
    Fault_Handler,
    Fault_Handler,
    Fault_Handler,
    Fault_Handler,
    0,
    0,
    0,
    0,
    Fault_Handler,
    Fault_Handler,
    0,
    Fault_Handler,
    Fault_Handler,
};

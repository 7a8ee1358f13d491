/* Start-up for Cortex-M3/M4F on qemu mps2-an385/an386, shared by every image of the board (the
 * product, the bootloader and its test application): vector table, .data/.bss set-up, FPU
 * enable (M4F), then main; main's return value is qemu's exit status, an unexpected exception
 * ends the run with status CM_FAULT_EXIT. Symbols from the shared sections (cortex-m-sections.ld).
 * No libc start-up code (-nostartfiles): no heap, no constructors, no argv. */
#include <stdint.h>

#include "cm_semihost.h"

/* Linker-script symbols: addresses only (sections are word aligned). */
extern uint32_t __data_load[], __data_start[], __data_end[], __bss_start[], __bss_end[];
extern uint32_t __stack_top[];
int main(void);
void Reset_Handler(void);
void Default_Handler(void);
void HardFault_Handler(void);
void NMI_Handler(void) __attribute__((weak, alias("Default_Handler")));
void SysTick_Handler(void) __attribute__((weak, alias("Default_Handler")));
void UART0RX_Handler(void) __attribute__((weak, alias("Default_Handler")));
void UART0TX_Handler(void) __attribute__((weak, alias("Default_Handler")));

#define SCB_CPACR (*(volatile uint32_t *)0xE000ED88u)
#define CM_FAULT_EXIT 99u

void Reset_Handler(void)
{
    const uint32_t n_data = (uint32_t)((uintptr_t)__data_end - (uintptr_t)__data_start) / 4u;
    for (uint32_t i = 0u; i < n_data; i++) {
        __data_start[i] = __data_load[i];
    }
    const uint32_t n_bss = (uint32_t)((uintptr_t)__bss_end - (uintptr_t)__bss_start) / 4u;
    for (uint32_t i = 0u; i < n_bss; i++) {
        __bss_start[i] = 0u;
    }
#if defined(__ARM_FP)
    SCB_CPACR |= (0xFu << 20); /* CP10, CP11 full access */
    __asm__ volatile("dsb\n\tisb" ::: "memory");
#endif
    sh_exit((uint32_t)main());
}

void Default_Handler(void)
{
    sh_puts("fault: unexpected exception\n");
    sh_exit(CM_FAULT_EXIT);
}

void HardFault_Handler(void)
{
    sh_puts("fault: HardFault\n");
    sh_exit(CM_FAULT_EXIT);
}

typedef void (*cm_vector_t)(void);

#define CM_N_VECTORS 48u /* 16 core + 32 external (the MPS2 boards use IRQ 0..31) */

/* Core vectors and the external interrupts this port uses: UART0 RX (IRQ 0) and TX (IRQ 1). */
__attribute__((section(".vectors"), used)) static const cm_vector_t cm_vectors[CM_N_VECTORS] = {
    (cm_vector_t)(uintptr_t)__stack_top, /* initial main stack pointer */
    Reset_Handler,
    NMI_Handler,       /* NMI: the watchdog's first expiry */
    HardFault_Handler, /* HardFault */
    Default_Handler,   /* MemManage */
    Default_Handler,   /* BusFault */
    Default_Handler,   /* UsageFault */
    0,
    0,
    0,
    0,               /* reserved */
    Default_Handler, /* SVCall */
    Default_Handler, /* DebugMonitor */
    0,               /* reserved */
    Default_Handler, /* PendSV */
    SysTick_Handler, /* SysTick */
    UART0RX_Handler, /* IRQ 0 */
    UART0TX_Handler, /* IRQ 1 */
    Default_Handler,
    Default_Handler,
    Default_Handler,
    Default_Handler,
    Default_Handler,
    Default_Handler,
    Default_Handler,
    Default_Handler,
    Default_Handler,
    Default_Handler,
    Default_Handler,
    Default_Handler,
    Default_Handler,
    Default_Handler,
    Default_Handler,
    Default_Handler,
    Default_Handler,
    Default_Handler,
    Default_Handler,
    Default_Handler,
    Default_Handler,
    Default_Handler,
    Default_Handler,
    Default_Handler,
    Default_Handler,
    Default_Handler,
    Default_Handler,
    Default_Handler,
    Default_Handler,
    Default_Handler,
};

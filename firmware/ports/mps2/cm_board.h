/* Registers and memory map of qemu's MPS2 boards used by the Cortex-M port (AN385 Cortex-M3,
 * AN386 Cortex-M4F; identical peripherals): SysTick and SCB of the core, CMSDK APB UART0 and
 * the CMSDK APB watchdog, and the 16 MiB PSRAM that holds the port's flash (docs/cortex-m.md).
 * Reset behaviour (qemu 7.2, checked): a SYSRESETREQ or a watchdog reset restores every image
 * that qemu loaded (-kernel, -device loader) and keeps the rest of memory; the PSRAM is the
 * machine's main RAM, which `hil_sim pil` backs with a file, so it also survives qemu. */
#ifndef CM_BOARD_H
#define CM_BOARD_H

#include <stdint.h>

#define CM_REG(addr) (*(volatile uint32_t *)(addr))

#define CM_CORE_CLOCK_HZ 25000000u /* SYSCLK of both boards */

/* SysTick */
#define CM_SYST_CSR CM_REG(0xE000E010u)
#define CM_SYST_RVR CM_REG(0xE000E014u)
#define CM_SYST_CVR CM_REG(0xE000E018u)
#define CM_SYST_CSR_ENABLE_TICKINT_CLK 0x7u

/* SCB and NVIC */
#define CM_SCB_AIRCR CM_REG(0xE000ED0Cu)
#define CM_SCB_AIRCR_SYSRESETREQ 0x05FA0004u
#define CM_SCB_SHPR3 CM_REG(0xE000ED20u) /* SysTick priority: bits 31..24 */
#define CM_NVIC_ISER0 CM_REG(0xE000E100u)
#define CM_NVIC_ISPR0 CM_REG(0xE000E200u)
#define CM_NVIC_IPR(n) (*(volatile uint8_t *)(0xE000E400u + (n)))

/* CMSDK APB UART0 (board serial port 0): RX interrupt IRQ 0, TX interrupt IRQ 1 */
#define CM_UART0_BASE 0x40004000u
#define CM_UART_DATA CM_REG(CM_UART0_BASE + 0x00u)
#define CM_UART_STATE CM_REG(CM_UART0_BASE + 0x04u)
#define CM_UART_CTRL CM_REG(CM_UART0_BASE + 0x08u)
#define CM_UART_INTSTATUS CM_REG(CM_UART0_BASE + 0x0Cu) /* write 1s: INTCLEAR */
#define CM_UART_BAUDDIV CM_REG(CM_UART0_BASE + 0x10u)
#define CM_UART_STATE_TXFULL 0x1u
#define CM_UART_STATE_RXFULL 0x2u
#define CM_UART_CTRL_TX_EN 0x1u
#define CM_UART_CTRL_RX_EN 0x2u
#define CM_UART_CTRL_TX_INT 0x4u
#define CM_UART_CTRL_RX_INT 0x8u
#define CM_UART_INT_TX 0x1u
#define CM_UART_INT_RX 0x2u
#define CM_UART0_RX_IRQ 0u
#define CM_UART0_TX_IRQ 1u

/* CMSDK APB watchdog (WDOGCLK = SYSCLK): first expiry raises NMI, the second resets the board */
#define CM_WDG_BASE 0x40008000u
#define CM_WDG_LOAD CM_REG(CM_WDG_BASE + 0x000u)
#define CM_WDG_VALUE CM_REG(CM_WDG_BASE + 0x004u)
#define CM_WDG_CTRL CM_REG(CM_WDG_BASE + 0x008u)
#define CM_WDG_INTCLR CM_REG(CM_WDG_BASE + 0x00Cu)
#define CM_WDG_LOCK CM_REG(CM_WDG_BASE + 0xC00u)
#define CM_WDG_UNLOCK_KEY 0x1ACCE551u
#define CM_WDG_CTRL_INTEN_RESEN 0x3u

/* PSRAM (the machine's main RAM): the port's flash, see cm_flash_layout below */
#define CM_PSRAM_BASE 0x21000000u
#define CM_PSRAM_SIZE 0x01000000u

/* Parameter block written by `hil_sim pil` (-device loader) at the top of the code SSRAM:
 * the plant's scenario and the random seed (hil_sim/pil/pil_plant.h). */
#define CM_PARAMS_ADDR 0x003F0000u
#define CM_PARAMS_MAX 0x00010000u

#endif /* CM_BOARD_H */

/* UART0 byte link (see cm_uart.h). The transmit ring has one consumer (the TX interrupt, and the
 * pump kicked with interrupts masked) and two producers that never overlap: thread context with
 * interrupts masked, and the RX interrupt's receiver (the TX interrupt has its priority, so it
 * cannot run meanwhile). */
#include "cm_uart.h"

#include "cm_board.h"

static cm_uart_rx_fn rx_fn;
static volatile uint32_t rx_allowed; /* bytes the RX interrupt may still take this tick */
static volatile uint8_t tx_ring[CM_UART_TX_RING];
static volatile uint32_t tx_head; /* written by the producers */
static volatile uint32_t tx_tail; /* written by the pump */

void UART0RX_Handler(void);
void UART0TX_Handler(void);

static void rx_ignore(uint8_t byte)
{
    (void)byte;
}

void cm_uart_init(cm_uart_rx_fn rx)
{
    rx_fn = rx != 0 ? rx : rx_ignore;
    rx_allowed = 0u;
    tx_head = tx_tail = 0u;
    CM_UART_BAUDDIV = 16u;
    CM_UART_CTRL = CM_UART_CTRL_TX_EN | CM_UART_CTRL_RX_EN | CM_UART_CTRL_TX_INT |
                   CM_UART_CTRL_RX_INT;
    CM_NVIC_IPR(CM_UART0_RX_IRQ) = 0x40u; /* above SysTick (0x80): bytes are never lost to a tick */
    CM_NVIC_IPR(CM_UART0_TX_IRQ) = 0x40u;
    CM_NVIC_ISER0 = (1u << CM_UART0_RX_IRQ) | (1u << CM_UART0_TX_IRQ);
}

void UART0RX_Handler(void)
{
    CM_UART_INTSTATUS = CM_UART_INT_RX;
    while ((CM_UART_STATE & CM_UART_STATE_RXFULL) != 0u) {
        const uint32_t allowed = rx_allowed;
        if (allowed == 0u) {
            CM_UART_CTRL &= ~CM_UART_CTRL_RX_INT; /* budget spent: resume at the next tick */
            return;
        }
        rx_allowed = allowed - 1u;
        rx_fn((uint8_t)CM_UART_DATA);
    }
}

/* Move bytes from the ring to the UART while it takes them (called with the TX IRQ masked or
 * from an interrupt handler of its priority). */
static void tx_pump(void)
{
    uint32_t t = tx_tail;
    const uint32_t h = tx_head;
    while (t != h && (CM_UART_STATE & CM_UART_STATE_TXFULL) == 0u) {
        CM_UART_DATA = tx_ring[t % CM_UART_TX_RING];
        t++;
    }
    tx_tail = t;
}

void UART0TX_Handler(void)
{
    CM_UART_INTSTATUS = CM_UART_INT_TX;
    tx_pump();
}

void cm_uart_rx_budget(uint32_t bytes)
{
    __asm__ volatile("cpsid i" ::: "memory");
    rx_allowed = bytes;
    CM_UART_CTRL |= CM_UART_CTRL_RX_INT;
    __asm__ volatile("cpsie i" ::: "memory");
    if ((CM_UART_STATE & CM_UART_STATE_RXFULL) != 0u) {
        CM_NVIC_ISPR0 = 1u << CM_UART0_RX_IRQ; /* a byte already waits: take it now */
    }
}

uint32_t cm_uart_tx_room(void)
{
    return CM_UART_TX_RING - (tx_head - tx_tail);
}

/* Copy len bytes into the ring and start sending them; the caller excludes the other producer. */
static bool tx_push(const char *data, uint32_t len)
{
    uint32_t h = tx_head;
    if (len > CM_UART_TX_RING - (h - tx_tail)) {
        return false;
    }
    for (uint32_t i = 0u; i < len; i++) {
        tx_ring[h % CM_UART_TX_RING] = (uint8_t)data[i];
        h++;
    }
    tx_head = h;
    tx_pump(); /* start (or continue) the transmission */
    return true;
}

bool cm_uart_write(const char *data, uint32_t len)
{
    __asm__ volatile("cpsid i" ::: "memory");
    const bool ok = tx_push(data, len);
    __asm__ volatile("cpsie i" ::: "memory");
    return ok;
}

bool cm_uart_write_isr(const char *data, uint32_t len)
{
    return tx_push(data, len);
}

bool cm_uart_tx_empty(void)
{
    return tx_tail == tx_head;
}

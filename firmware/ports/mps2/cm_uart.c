/* UART0 byte queues (see cm_uart.h). Single producer / single consumer rings: the interrupt
 * handlers own one index each, the tick context the other. */
#include "cm_uart.h"

#include "cm_board.h"

static volatile uint8_t rx_ring[CM_UART_RX_RING];
static volatile uint32_t rx_head; /* written by the RX interrupt */
static volatile uint32_t rx_tail; /* written by the tick */
static volatile uint32_t rx_lost;
static volatile uint32_t rx_allowed; /* bytes the RX interrupt may still take this tick */
static volatile uint8_t tx_ring[CM_UART_TX_RING];
static volatile uint32_t tx_head; /* written by the tick */
static volatile uint32_t tx_tail; /* written by the TX interrupt (and the tick's kick) */

void UART0RX_Handler(void);
void UART0TX_Handler(void);

void cm_uart_init(void)
{
    rx_head = rx_tail = rx_lost = 0u;
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
        if (rx_allowed == 0u) {
            CM_UART_CTRL &= ~CM_UART_CTRL_RX_INT; /* budget spent: resume at the next tick */
            return;
        }
        rx_allowed = rx_allowed - 1u;
        const uint8_t b = (uint8_t)CM_UART_DATA;
        const uint32_t h = rx_head;
        if (h - rx_tail < CM_UART_RX_RING) {
            rx_ring[h % CM_UART_RX_RING] = b;
            rx_head = h + 1u;
        } else {
            rx_lost = rx_lost + 1u;
        }
    }
}

/* Move bytes from the ring to the UART while it takes them (called with the TX IRQ masked or
 * from the handler itself). */
static void tx_pump(void)
{
    while (tx_tail != tx_head && (CM_UART_STATE & CM_UART_STATE_TXFULL) == 0u) {
        CM_UART_DATA = tx_ring[tx_tail % CM_UART_TX_RING];
        tx_tail = tx_tail + 1u;
    }
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

bool cm_uart_getc(uint8_t *byte)
{
    const uint32_t t = rx_tail;
    if (t == rx_head) {
        return false;
    }
    *byte = rx_ring[t % CM_UART_RX_RING];
    rx_tail = t + 1u;
    return true;
}

uint32_t cm_uart_tx_room(void)
{
    return CM_UART_TX_RING - (tx_head - tx_tail);
}

bool cm_uart_write(const char *data, uint32_t len)
{
    if (len > cm_uart_tx_room()) {
        return false;
    }
    uint32_t h = tx_head;
    for (uint32_t i = 0u; i < len; i++) {
        tx_ring[h % CM_UART_TX_RING] = (uint8_t)data[i];
        h++;
    }
    tx_head = h;
    __asm__ volatile("cpsid i" ::: "memory");
    tx_pump(); /* start (or continue) the transmission */
    __asm__ volatile("cpsie i" ::: "memory");
    return true;
}

bool cm_uart_tx_empty(void)
{
    return tx_tail == tx_head;
}

uint32_t cm_uart_rx_overflows(void)
{
    return rx_lost;
}

/* UART0 byte link (see cm_uart.h). The receive ring has one producer (the RX interrupt) and one
 * consumer (cm_uart_read, thread context). The transmit ring has one consumer (the TX interrupt,
 * and the pump kicked with interrupts masked) and one producer (thread context with interrupts
 * masked). */
#include "cm_uart.h"

#include "cm_board.h"

static volatile uint32_t rx_allowed; /* bytes the RX interrupt may still take */
static volatile uint8_t rx_ring[CM_UART_RX_RING];
static volatile uint32_t rx_head; /* written by the RX interrupt */
static volatile uint32_t rx_tail; /* written by cm_uart_read */
static volatile uint8_t tx_ring[CM_UART_TX_RING];
static volatile uint32_t tx_head; /* written by the producers */
static volatile uint32_t tx_tail; /* written by the pump */

void UART0RX_Handler(void);
void UART0TX_Handler(void);

void cm_uart_init(void)
{
    rx_allowed = 0u;
    rx_head = rx_tail = 0u;
    tx_head = tx_tail = 0u;
    CM_UART_BAUDDIV = 16u;
    CM_UART_CTRL = CM_UART_CTRL_TX_EN | CM_UART_CTRL_RX_EN | CM_UART_CTRL_TX_INT |
                   CM_UART_CTRL_RX_INT;
    CM_NVIC_IPR(CM_UART0_RX_IRQ) = 0x40u; /* above SysTick (0x80): bytes are never lost to a tick */
    CM_NVIC_IPR(CM_UART0_TX_IRQ) = 0x40u;
    CM_NVIC_ISER0 = (1u << CM_UART0_RX_IRQ) | (1u << CM_UART0_TX_IRQ);
}

/* Each received byte into the ring, O(1) a byte: no parsing here. With the budget spent or the
 * ring full the interrupt is masked (the byte waits in the UART, the rest in the host's socket)
 * until cm_uart_rx_budget gives more. */
void UART0RX_Handler(void)
{
    CM_UART_INTSTATUS = CM_UART_INT_RX;
    uint32_t h = rx_head;
    uint32_t allowed = rx_allowed;
    while ((CM_UART_STATE & CM_UART_STATE_RXFULL) != 0u) {
        if (allowed == 0u || h - rx_tail >= CM_UART_RX_RING) {
            CM_UART_CTRL &= ~CM_UART_CTRL_RX_INT;
            break;
        }
        rx_ring[h % CM_UART_RX_RING] = (uint8_t)CM_UART_DATA;
        h++;
        allowed--;
    }
    rx_head = h;
    rx_allowed = allowed;
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

void cm_uart_rx_cap(uint32_t bytes)
{
    __asm__ volatile("cpsid i" ::: "memory");
    if (rx_allowed > bytes) {
        rx_allowed = bytes;
    }
    __asm__ volatile("cpsie i" ::: "memory");
}

uint32_t cm_uart_read(uint8_t *out, uint32_t max)
{
    uint32_t t = rx_tail;
    const uint32_t h = rx_head;
    uint32_t n = 0u;
    while (n < max && t != h) {
        out[n++] = rx_ring[t % CM_UART_RX_RING];
        t++;
    }
    __asm__ volatile("" ::: "memory"); /* the bytes read before the room is given back */
    rx_tail = t;
    return n;
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

bool cm_uart_tx_empty(void)
{
    return tx_tail == tx_head;
}

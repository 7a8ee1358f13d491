/* Interrupt-driven byte link over the board's CMSDK UART0 (cm_board.h): the RX interrupt only
 * stores each received byte in a ring (qemu delivers the next byte only once the data register is
 * read; the UART has no FIFO), which thread context reads (cm_uart_read); transmitted bytes leave
 * from a ring through the TX interrupt. */
#ifndef CM_UART_H
#define CM_UART_H

#include <stdbool.h>
#include <stdint.h>

#define CM_UART_TX_RING 8192u /* bytes (power of two): ~370 frames of text */
#define CM_UART_RX_RING 512u  /* bytes (power of two): over two ticks' receive budget */

/** Enable the UART and its interrupts, empty both rings. */
void cm_uart_init(void);

/** Allow the RX interrupt to take up to bytes more bytes (called once per tick): the emulated
 *  UART has no baud rate, so this budget gives the link the throughput of a real one; bytes
 *  beyond it wait in the UART (and the host's socket) until the next tick. */
void cm_uart_rx_budget(uint32_t bytes);

/** Lower the RX interrupt's remaining budget to at most bytes (the bytes a real UART's baud rate
 *  delivers in a span of time, cm_port.h). */
void cm_uart_rx_cap(uint32_t bytes);
/** Copy up to max received bytes, oldest first, out of the receive ring; returns how many. */
uint32_t cm_uart_read(uint8_t *out, uint32_t max);
/** Free room of the transmit ring in bytes. */
uint32_t cm_uart_tx_room(void);

/** Queue len bytes for transmission (thread context); false (nothing queued) if they do not
 *  fit. */
bool cm_uart_write(const char *data, uint32_t len);


/** True when every queued byte has left. */
bool cm_uart_tx_empty(void);

#endif /* CM_UART_H */

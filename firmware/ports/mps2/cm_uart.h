/* Interrupt-driven byte link over the board's CMSDK UART0 (cm_board.h): each received byte is
 * handed to the receiver's handler from the RX interrupt (qemu delivers the next byte only once
 * the data register is read; the UART has no FIFO), transmitted bytes leave from a ring through
 * the TX interrupt. */
#ifndef CM_UART_H
#define CM_UART_H

#include <stdbool.h>
#include <stdint.h>

#define CM_UART_TX_RING 8192u /* bytes (power of two): ~370 frames of text */

/** Receiver of the bytes: called from the RX interrupt with each byte, in order. */
typedef void (*cm_uart_rx_fn)(uint8_t byte);

/** Enable the UART and its interrupts, empty the transmit ring; rx gets every received byte. */
void cm_uart_init(cm_uart_rx_fn rx);

/** Allow the RX interrupt to take up to bytes more bytes (called once per tick): the emulated
 *  UART has no baud rate, so this budget gives the link the throughput of a real one; bytes
 *  beyond it wait in the UART (and the host's socket) until the next tick. */
void cm_uart_rx_budget(uint32_t bytes);

/** Free room of the transmit ring in bytes. */
uint32_t cm_uart_tx_room(void);

/** Queue len bytes for transmission (thread context); false (nothing queued) if they do not
 *  fit. */
bool cm_uart_write(const char *data, uint32_t len);

/** cm_uart_write from the receiver's handler (inside the RX interrupt). */
bool cm_uart_write_isr(const char *data, uint32_t len);

/** True when every queued byte has left. */
bool cm_uart_tx_empty(void);

#endif /* CM_UART_H */

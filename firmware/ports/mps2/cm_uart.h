/* Interrupt-driven byte queues over the board's CMSDK UART0 (cm_board.h): received bytes are
 * taken by the RX interrupt into a ring (qemu delivers the next byte only once the data register
 * is read), transmitted bytes leave from a ring through the TX interrupt. */
#ifndef CM_UART_H
#define CM_UART_H

#include <stdbool.h>
#include <stdint.h>

#define CM_UART_RX_RING 4096u /* bytes (power of two): > one 4 KiB TransferData in SLCAN */
#define CM_UART_TX_RING 8192u /* bytes (power of two): ~370 frames of text */

/** Enable the UART, its interrupts and empty both rings. */
void cm_uart_init(void);

/** Allow the RX interrupt to take up to bytes more bytes (called once per tick): the emulated
 *  UART has no baud rate, so this budget gives the link the throughput of a real one; bytes
 *  beyond it wait in the UART (and the host's socket) until the next tick. */
void cm_uart_rx_budget(uint32_t bytes);

/** Take one received byte; false if none. */
bool cm_uart_getc(uint8_t *byte);

/** Free room of the transmit ring in bytes. */
uint32_t cm_uart_tx_room(void);

/** Queue len bytes for transmission; false (nothing queued) if they do not fit. */
bool cm_uart_write(const char *data, uint32_t len);

/** True when every queued byte has left. */
bool cm_uart_tx_empty(void);

/** Bytes lost because the receive ring was full. */
uint32_t cm_uart_rx_overflows(void);

#endif /* CM_UART_H */

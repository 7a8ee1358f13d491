/* End-to-end protection of the safety frames (Emergency, HostCommand, HostHeartbeat,
 * DeviceStatus): a 4-bit rolling counter in data bits 48..51 and a CRC-8 in byte 7.
 * CRC-8 SAE J1850 (as AUTOSAR Crc_CalculateCRC8): poly 0x1D, init 0xFF, xorout 0xFF, no
 * reflection; check value over "123456789" = 0x4B. It covers the identifier (low byte, high
 * byte) and then data bytes 0..6, so a frame routed to the wrong id fails the check. */
#ifndef E2E_H
#define E2E_H

#include <stdbool.h>
#include <stdint.h>
#include "can_frame.h"
#include "proto_ids.h"

#define E2E_COUNTER_MASK 0x0Fu
#define E2E_FRAME_LEN 8u /* a safety frame's length: the CRC is its last byte */

/** CRC-8 SAE J1850 over len bytes continuing from crc (start with 0xFF, xor the end with 0xFF). */
uint8_t e2e_crc8_update(uint8_t crc, const uint8_t *data, uint32_t len);

/** Complete CRC-8 SAE J1850 (init 0xFF, xorout 0xFF) of a buffer. */
uint8_t e2e_crc8(const uint8_t *data, uint32_t len);

/** CRC byte of an 8-byte safety frame: over id (LE, 2 bytes) then data[0..6]. */
uint8_t e2e_frame_crc(const can_frame_t *f);

/** Write counter (low 4 bits) into data bits 48..51 and the CRC into data[7]; sets len 8. */
void e2e_protect(can_frame_t *f, uint8_t counter);

/** True if f is a safety frame with a valid CRC (len at least 8); nothing recorded. */
bool e2e_frame_ok(const can_frame_t *f);

/** Receiver state of one protected frame id: the last accepted counter. */
typedef struct {
    uint8_t last_counter;
    bool seen;
} e2e_rx_t;

/** Reset the receiver (the next valid frame is accepted whatever its counter). */
void e2e_rx_reset(e2e_rx_t *rx);

/** Check a received frame: len at least 8, CRC, counter different from the last accepted one.
 *  Accepts and remembers the counter only when everything is valid. */
proto_status_t e2e_check(e2e_rx_t *rx, const can_frame_t *f);

#endif /* E2E_H */

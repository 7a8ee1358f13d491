/* CRC-8 SAE J1850 and the rolling counter of safety frames (see e2e.h). */
#include "e2e.h"

#define E2E_POLY 0x1Du
#define E2E_COUNTER_SHIFT 0u /* counter in the low nibble of data[6] = bits 48..51 */

uint8_t e2e_crc8_update(uint8_t crc, const uint8_t *data, uint32_t len)
{
    for (uint32_t i = 0; i < len; i++) {
        crc ^= data[i];
        for (uint8_t b = 0; b < 8u; b++) {
            crc = (uint8_t)(((crc & 0x80u) != 0u) ? (((uint32_t)crc << 1) ^ E2E_POLY)
                                                  : ((uint32_t)crc << 1));
        }
    }
    return crc;
}

uint8_t e2e_crc8(const uint8_t *data, uint32_t len)
{
    return (uint8_t)(e2e_crc8_update(0xFFu, data, len) ^ 0xFFu);
}

uint8_t e2e_frame_crc(const can_frame_t *f)
{
    const uint8_t id_bytes[2] = {(uint8_t)(f->id & 0xFFu), (uint8_t)((f->id >> 8) & 0x07u)};
    uint8_t crc = e2e_crc8_update(0xFFu, id_bytes, 2u);
    crc = e2e_crc8_update(crc, f->data, 7u);
    return (uint8_t)(crc ^ 0xFFu);
}

void e2e_protect(can_frame_t *f, uint8_t counter)
{
    f->dlc = 8u;
    f->data[6] = (uint8_t)((f->data[6] & 0xF0u) |
                           ((counter & E2E_COUNTER_MASK) << E2E_COUNTER_SHIFT));
    f->data[7] = e2e_frame_crc(f);
}

void e2e_rx_reset(e2e_rx_t *rx)
{
    rx->last_counter = 0u;
    rx->seen = false;
}

proto_status_t e2e_check(e2e_rx_t *rx, const can_frame_t *f)
{
    if (f->dlc < 8u) {
        return PROTO_ERR_DLC;
    }
    if (e2e_frame_crc(f) != f->data[7]) {
        return PROTO_ERR_E2E_CRC;
    }
    const uint8_t counter = (uint8_t)((f->data[6] >> E2E_COUNTER_SHIFT) & E2E_COUNTER_MASK);
    if (rx->seen && counter == rx->last_counter) {
        return PROTO_ERR_E2E_COUNTER;
    }
    rx->last_counter = counter;
    rx->seen = true;
    return PROTO_OK;
}

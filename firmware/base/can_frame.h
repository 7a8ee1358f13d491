/* One classic CAN frame as every firmware layer passes it (HAL, ISO-TP, frame codecs).
 * 11-bit identifiers only on this product; dlc 0..8, unused data bytes undefined. */
#ifndef CAN_FRAME_H
#define CAN_FRAME_H

#include <stdint.h>

#define CAN_FRAME_MAX_DLC 8u
#define CAN_STD_ID_MASK 0x7FFu

/** A classic CAN data frame. */
typedef struct {
    uint32_t id; /* 11-bit identifier */
    uint8_t dlc; /* 0..8 */
    uint8_t data[CAN_FRAME_MAX_DLC];
} can_frame_t;

#endif /* CAN_FRAME_H */

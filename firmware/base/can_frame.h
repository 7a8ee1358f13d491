/* One CAN frame as every firmware layer passes it (HAL, ISO-TP, frame codecs): classic CAN or
 * CAN FD, 11-bit identifiers only on this product. `len` is the number of data bytes (never the
 * 4-bit DLC code): 0..8 on classic CAN, one of 0..8, 12, 16, 20, 24, 32, 48, 64 on CAN FD;
 * data bytes from len on are undefined. can_dlc_to_len / can_len_to_dlc map the DLC code of the
 * wire to the length and back. CAN_FRAME_MAX_LEN (64 by default) sizes data[]: a port whose
 * controller is classic only may build with 8 to keep its frame queues small. */
#ifndef CAN_FRAME_H
#define CAN_FRAME_H

#include <stdbool.h>
#include <stdint.h>

#define CAN_CLASSIC_MAX_LEN 8u
#define CAN_FD_MAX_LEN 64u
#ifndef CAN_FRAME_MAX_LEN
#define CAN_FRAME_MAX_LEN CAN_FD_MAX_LEN
#endif
#if CAN_FRAME_MAX_LEN != CAN_CLASSIC_MAX_LEN && CAN_FRAME_MAX_LEN != CAN_FD_MAX_LEN
#error "CAN_FRAME_MAX_LEN must be 8 (classic only) or 64 (CAN FD)"
#endif
#define CAN_STD_ID_MASK 0x7FFu
#define CAN_FRAME_FD 0x01u  /* flags: a CAN FD frame (FDF) */
#define CAN_FRAME_BRS 0x02u /* flags: bit-rate switch in the data phase (FD only) */

/** A CAN data frame, classic or FD. */
typedef struct {
    uint32_t id;   /* 11-bit identifier */
    uint8_t len;   /* data bytes (see above) */
    uint8_t flags; /* CAN_FRAME_FD, CAN_FRAME_BRS; 0: classic */
    uint8_t data[CAN_FRAME_MAX_LEN];
} can_frame_t;

/** Data bytes of a DLC code (0..15): 0..8, then 12, 16, 20, 24, 32, 48, 64 (classic CAN codes
 *  9..15 also mean 8: pass fd false). */
static inline uint8_t can_dlc_to_len(uint8_t dlc, bool fd)
{
    static const uint8_t fd_len[16] = {0u, 1u,  2u,  3u,  4u,  5u,  6u,  7u,
                                       8u, 12u, 16u, 20u, 24u, 32u, 48u, 64u};
    if (!fd) {
        return dlc > 8u ? 8u : dlc;
    }
    return fd_len[dlc & 0x0Fu];
}

/** Smallest DLC code whose length holds len bytes (15 for anything over 48). */
static inline uint8_t can_len_to_dlc(uint8_t len)
{
    if (len <= 8u) {
        return len;
    }
    uint8_t dlc = 9u;
    while (dlc < 15u && can_dlc_to_len(dlc, true) < len) {
        dlc++;
    }
    return dlc;
}

/** The valid frame length that carries len bytes: len up to 8, else the next FD length. */
static inline uint8_t can_fd_round_len(uint8_t len)
{
    return can_dlc_to_len(can_len_to_dlc(len), true);
}

/** True if the frame's length is one its kind can carry (classic 0..8, FD a valid FD length
 *  up to CAN_FRAME_MAX_LEN) and BRS is set only on an FD frame. */
static inline bool can_frame_len_ok(const can_frame_t *f)
{
    if ((f->flags & CAN_FRAME_FD) == 0u) {
        return f->len <= CAN_CLASSIC_MAX_LEN && (f->flags & CAN_FRAME_BRS) == 0u;
    }
    return f->len <= CAN_FRAME_MAX_LEN && can_fd_round_len(f->len) == f->len;
}

#endif /* CAN_FRAME_H */

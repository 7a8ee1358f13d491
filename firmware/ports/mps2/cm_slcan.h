/* SLCAN (Lawicel CAN232/CANUSB ASCII protocol) over a byte stream: the CAN link of the Cortex-M
 * images, carried by the board's UART, so python-can's stock `slcan` interface reaches the
 * device. Pure code (no hardware): bytes in -> frames and replies out; frames -> a text line.
 *
 * Commands (each ends with CR; the reply is CR for OK, BEL for an error):
 *   Sn set bitrate (n 0..8), sxxyy set BTR (both accepted and ignored: the UART has no bit
 *   timing), O open, L open listen-only, C close, V version (reply "V1010"), v ("vFS01"),
 *   N serial number ("NFS01"), F status flags ("F00"), Zn timestamps (accepted, none sent),
 *   Mxxxxxxxx / mxxxxxxxx acceptance code/mask (accepted, everything passes),
 *   tiiildd..  transmit a standard frame (reply "z"), Tiiiiiiiildd.. extended (reply "Z";
 *   dropped: the product uses 11-bit identifiers only), riiil / Riiiiiiiil remote (replied,
 *   dropped). Frames are taken only while open (and not listen-only); others answer BEL.
 * Received frames are sent to the host as "tiiildd..\r" while open. The channel starts open
 * (as Lawicel's auto-startup), so a board reset does not silence a host that stays connected. */
#ifndef CM_SLCAN_H
#define CM_SLCAN_H

#include <stdbool.h>
#include <stdint.h>
#include "can_frame.h"

#define SLCAN_LINE_MAX 32u       /* longest command: "T" + 8 + 1 + 16 = 26 characters */
#define SLCAN_REPLY_MAX 8u       /* longest reply: "V1010\r" */
#define SLCAN_FRAME_TEXT_MAX 22u /* "t" + 3 + 1 + 16 + "\r" */

/** Parser state of one SLCAN channel. */
typedef struct {
    char line[SLCAN_LINE_MAX];
    uint32_t len;
    bool overlong; /* the current line exceeded SLCAN_LINE_MAX: answered BEL */
    bool open;     /* after O (or L) until C */
    bool listen_only;
    uint8_t bitrate_code; /* last Sn (0..8; 8 = 1 Mbit/s, the default) */
    uint32_t errors;      /* commands answered with BEL */
} slcan_t;

/** Open channel (auto-startup), 1 Mbit/s, empty line. */
void slcan_init(slcan_t *s);

/** Feed one received byte. When it completes a command, writes the reply (CR-terminated, or
 *  BEL) to reply and its length to *reply_len, and returns true with *frame filled if the
 *  command carried a standard data frame for the device. *reply_len is 0 while a line is open. */
bool slcan_feed(slcan_t *s, uint8_t byte, can_frame_t *frame, char reply[SLCAN_REPLY_MAX],
                uint32_t *reply_len);

/** The common case of slcan_feed, inline for a receive interrupt: store byte if it continues
 *  the current line (not a line end, the line not full) and return true; false if the byte needs
 *  slcan_feed (nothing changed). */
static inline bool slcan_take(slcan_t *s, uint8_t byte)
{
    const uint32_t n = s->len;
    if (byte == (uint8_t)'\r' || byte == (uint8_t)'\n' || n >= SLCAN_LINE_MAX) {
        return false;
    }
    s->line[n] = (char)byte;
    s->len = n + 1u;
    return true;
}

/** Text of a frame for the host ("tiiildd..\r"); returns its length (0 if the id or length is
 *  invalid, or the frame is CAN FD). */
uint32_t slcan_encode(const can_frame_t *frame, char out[SLCAN_FRAME_TEXT_MAX]);

#endif /* CM_SLCAN_H */

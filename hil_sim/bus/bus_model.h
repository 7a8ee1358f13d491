/* Classic CAN bus timing model: frame length in bits with bit stuffing (actual, from the frame's
 * content and its CRC-15, or the worst case), and an arbitrated bus shared by several sources
 * (the device and each socketcand client): one frame at a time; when the bus goes idle, the
 * lowest identifier among ALL frames waiting at every source wins (as controllers with several
 * transmit mailboxes arbitrate them by identifier); frames of one source with the same
 * identifier leave in the order they were queued. Times are in nanoseconds of simulated time. */
#ifndef BUS_MODEL_H
#define BUS_MODEL_H

#include <stdbool.h>
#include <stdint.h>
#include "can_frame.h"

#define BUS_MAX_SOURCES 17u /* source 0: the device; 1..16: clients */
#define BUS_FIFO_CAP 4096u  /* frames waiting per source */
#define BUS_DEFAULT_BITRATE 1000000u

/** CRC-15 of CAN (poly 0x4599, init 0) over nbits bits given MSB-first in bits[]. */
uint16_t busm_crc15(const uint8_t *bits, uint32_t nbits);

/** Bits on the wire for this classic frame (len 0..8) with its actual stuff bits: SOF..CRC stuffed, then CRC
 *  delimiter, ACK slot and delimiter, EOF (7) and intermission (3). */
uint32_t busm_frame_bits(const can_frame_t *f, bool extended);

/** Worst-case bits for a classic frame of len data bytes (stuff bit after every 4 bits after the first). */
uint32_t busm_frame_bits_worst(uint8_t len, bool extended);

/** Bits without any stuffing (the minimum). */
uint32_t busm_frame_bits_min(uint8_t len, bool extended);

/** One frame waiting for or on the bus. */
typedef struct {
    can_frame_t f;
    bool extended;
    uint8_t src;
    uint64_t t_enqueue_ns;
} bus_item_t;

/** Frames waiting at one source, kept sorted by arbitration key (then by arrival). */
typedef struct {
    bus_item_t items[BUS_FIFO_CAP];
    uint32_t head;
    uint32_t len;
    uint64_t last_t_ns; /* enqueue times never go back within a source */
} bus_fifo_t;

/** Arbitration key: lower wins (the identifier bits as sent; a standard frame wins over an
 *  extended one with the same base identifier). */
uint32_t busm_key(const can_frame_t *f, bool extended);

/** Called when a frame has been transmitted completely (t_end_ns: end of its EOF). */
typedef void (*bus_deliver_fn)(void *ctx, const bus_item_t *item, uint64_t t_end_ns);

/** The shared bus. */
typedef struct {
    uint64_t bit_ns;       /* 1e9 / bitrate */
    uint64_t idle_from_ns; /* the bus is free from this time */
    bool in_flight;
    bus_item_t cur;
    uint64_t cur_end_ns;
    bus_fifo_t fifo[BUS_MAX_SOURCES];
    /* statistics */
    uint64_t frames;
    uint64_t bits;
    uint64_t dropped; /* enqueue refused: fifo full */
} bus_t;

/** Idle bus at bitrate (bit/s). */
void bus_init(bus_t *b, uint32_t bitrate);

/** Queue a frame from src at t_ns; false (counted as dropped) if that source's FIFO is full or
 *  the frame is not a classic one (this model times classic CAN only). */
bool bus_enqueue(bus_t *b, uint8_t src, const can_frame_t *f, bool extended, uint64_t t_ns);

/** Free places in a source's FIFO. */
uint32_t bus_room(const bus_t *b, uint8_t src);

/** Frames a source has waiting (not counting one on the wire). */
uint32_t bus_pending(const bus_t *b, uint8_t src);

/** The least urgent frame a source has waiting (highest key, the latest among equals); with take,
 *  it is also removed (a controller aborting that mailbox). False if none waits. */
bool bus_least_urgent(bus_t *b, uint8_t src, bool take, bus_item_t *out);

/** Discard everything a source has queued (client disconnected). */
void bus_flush_source(bus_t *b, uint8_t src);

/** Advance the bus to t_ns: every frame whose transmission ends at or before t_ns is delivered
 *  (in bus order) through cb. */
void bus_run(bus_t *b, uint64_t t_ns, bus_deliver_fn cb, void *ctx);

/** Time of the next delivery if nothing else is queued (UINT64_MAX if the bus is idle and empty). */
uint64_t bus_next_event_ns(const bus_t *b);

#endif /* BUS_MODEL_H */

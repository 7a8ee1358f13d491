/* CAN bus timing model and arbitration (see bus_model.h). */
#include "bus_model.h"

#include <string.h>

#define TAIL_BITS 13u /* CRC delimiter 1, ACK slot 1, ACK delimiter 1, EOF 7, intermission 3 */

uint16_t busm_crc15(const uint8_t *bits, uint32_t nbits)
{
    uint16_t crc = 0u;
    for (uint32_t i = 0; i < nbits; i++) {
        const uint16_t nxt = (uint16_t)(bits[i] ^ ((crc >> 14) & 1u));
        crc = (uint16_t)(((uint32_t)crc << 1) & 0x7FFFu);
        if (nxt != 0u) {
            crc ^= 0x4599u;
        }
    }
    return crc;
}

static uint32_t put_bits(uint8_t *bits, uint32_t pos, uint32_t value, uint32_t n)
{
    for (uint32_t i = 0; i < n; i++) {
        bits[pos + i] = (uint8_t)((value >> (n - 1u - i)) & 1u);
    }
    return pos + n;
}

uint32_t busm_frame_bits(const can_frame_t *f, bool extended)
{
    uint8_t bits[160];
    uint32_t n = 0u;
    const uint8_t dlc = f->len;    /* bus_enqueue takes classic frames only: 0..8 */
    n = put_bits(bits, n, 0u, 1u); /* SOF */
    if (!extended) {
        n = put_bits(bits, n, f->id & 0x7FFu, 11u);
        n = put_bits(bits, n, 0u, 3u); /* RTR, IDE, r0 */
    } else {
        n = put_bits(bits, n, (f->id >> 18) & 0x7FFu, 11u);
        n = put_bits(bits, n, 3u, 2u); /* SRR 1, IDE 1 */
        n = put_bits(bits, n, f->id & 0x3FFFFu, 18u);
        n = put_bits(bits, n, 0u, 3u); /* RTR, r1, r0 */
    }
    n = put_bits(bits, n, dlc, 4u);
    for (uint8_t i = 0; i < dlc; i++) {
        n = put_bits(bits, n, f->data[i], 8u);
    }
    const uint16_t crc = busm_crc15(bits, n);
    n = put_bits(bits, n, crc, 15u);
    /* stuffing over SOF..CRC: after 5 equal bits insert the complement (it starts a new run) */
    uint32_t stuff = 0u;
    uint32_t run = 1u;
    uint8_t last = bits[0];
    for (uint32_t i = 1; i < n; i++) {
        if (bits[i] == last) {
            run++;
        } else {
            run = 1u;
            last = bits[i];
        }
        if (run == 5u) {
            stuff++;
            last = (uint8_t)(last ^ 1u); /* the stuff bit */
            run = 1u;
        }
    }
    return n + stuff + TAIL_BITS;
}

uint32_t busm_frame_bits_min(uint8_t len, bool extended)
{
    const uint32_t d = len > CAN_CLASSIC_MAX_LEN ? CAN_CLASSIC_MAX_LEN : len;
    return (extended ? 54u : 34u) + 8u * d + TAIL_BITS;
}

uint32_t busm_frame_bits_worst(uint8_t len, bool extended)
{
    const uint32_t d = len > CAN_CLASSIC_MAX_LEN ? CAN_CLASSIC_MAX_LEN : len;
    const uint32_t stuffed = (extended ? 54u : 34u) + 8u * d;
    return stuffed + (stuffed - 1u) / 4u + TAIL_BITS;
}

void bus_init(bus_t *b, uint32_t bitrate)
{
    memset(b, 0, sizeof(*b));
    b->bit_ns = 1000000000ull / (bitrate > 0u ? bitrate : BUS_DEFAULT_BITRATE);
}

uint32_t busm_key(const can_frame_t *f, bool extended)
{
    return extended ? (((f->id >> 18) & 0x7FFu) << 19) | (1u << 18) | (f->id & 0x3FFFFu)
                    : ((f->id & 0x7FFu) << 19);
}

static bus_item_t *fifo_at(bus_fifo_t *q, uint32_t i)
{
    return &q->items[(q->head + i) % BUS_FIFO_CAP];
}

bool bus_enqueue(bus_t *b, uint8_t src, const can_frame_t *f, bool extended, uint64_t t_ns)
{
    if (src >= BUS_MAX_SOURCES || b->fifo[src].len >= BUS_FIFO_CAP ||
        (f->flags & CAN_FRAME_FD) != 0u || !can_frame_len_ok(f)) {
        b->dropped++;
        return false;
    }
    /* sorted insert from the tail: after every frame with a key <= this one (a source that
     * sends one identifier appends in O(1)) */
    bus_fifo_t *q = &b->fifo[src];
    if (t_ns < q->last_t_ns) {
        t_ns = q->last_t_ns; /* a frame read later is never eligible earlier (order kept) */
    }
    q->last_t_ns = t_ns;
    const uint32_t key = busm_key(f, extended);
    uint32_t pos = q->len;
    while (pos > 0u && busm_key(&fifo_at(q, pos - 1u)->f, fifo_at(q, pos - 1u)->extended) > key) {
        *fifo_at(q, pos) = *fifo_at(q, pos - 1u);
        pos--;
    }
    bus_item_t *it = fifo_at(q, pos);
    it->f = *f;
    it->extended = extended;
    it->src = src;
    it->t_enqueue_ns = t_ns;
    q->len++;
    return true;
}

uint32_t bus_pending(const bus_t *b, uint8_t src)
{
    return src < BUS_MAX_SOURCES ? b->fifo[src].len : 0u;
}

bool bus_least_urgent(bus_t *b, uint8_t src, bool take, bus_item_t *out)
{
    if (src >= BUS_MAX_SOURCES || b->fifo[src].len == 0u) {
        return false;
    }
    bus_fifo_t *q = &b->fifo[src];
    *out = *fifo_at(q, q->len - 1u);
    if (take) {
        q->len--;
    }
    return true;
}

uint32_t bus_room(const bus_t *b, uint8_t src)
{
    return src < BUS_MAX_SOURCES ? BUS_FIFO_CAP - b->fifo[src].len : 0u;
}

void bus_flush_source(bus_t *b, uint8_t src)
{
    if (src < BUS_MAX_SOURCES) {
        b->fifo[src].len = 0u;
    }
}

/* The winner of arbitration at time t: the lowest key among the frames of every source queued by
 * t (each source's list is sorted, so its first frame queued by t is its best). Returns the
 * source and, in *idx, the frame's index in its list; *earliest gets the earliest enqueue time
 * of a frame queued after t when nothing is eligible. */
static int arbitrate(bus_t *b, uint64_t t, uint32_t *idx, uint64_t *earliest)
{
    int best = -1;
    uint32_t best_key = 0u;
    *earliest = UINT64_MAX;
    for (uint32_t s = 0; s < BUS_MAX_SOURCES; s++) {
        bus_fifo_t *q = &b->fifo[s];
        for (uint32_t i = 0; i < q->len; i++) {
            const bus_item_t *it = fifo_at(q, i);
            if (it->t_enqueue_ns > t) {
                if (it->t_enqueue_ns < *earliest) {
                    *earliest = it->t_enqueue_ns;
                }
                continue;
            }
            const uint32_t key = busm_key(&it->f, it->extended);
            if (best < 0 || key < best_key) {
                best = (int)s;
                best_key = key;
                *idx = i;
            }
            break;
        }
    }
    return best;
}

/* Remove the frame at index i of a source's list (later frames move up one place). */
static bus_item_t fifo_remove(bus_fifo_t *q, uint32_t i)
{
    const bus_item_t it = *fifo_at(q, i);
    if (i == 0u) {
        q->head = (q->head + 1u) % BUS_FIFO_CAP;
    } else {
        for (uint32_t j = i; j + 1u < q->len; j++) {
            *fifo_at(q, j) = *fifo_at(q, j + 1u);
        }
    }
    q->len--;
    return it;
}

void bus_run(bus_t *b, uint64_t t_ns, bus_deliver_fn cb, void *ctx)
{
    for (;;) {
        if (b->in_flight) {
            if (b->cur_end_ns > t_ns) {
                return;
            }
            b->in_flight = false;
            b->idle_from_ns = b->cur_end_ns;
            cb(ctx, &b->cur, b->cur_end_ns);
            continue;
        }
        uint64_t earliest = UINT64_MAX;
        uint64_t start = b->idle_from_ns;
        uint32_t idx = 0u;
        int s = arbitrate(b, start, &idx, &earliest);
        if (s < 0) {
            if (earliest == UINT64_MAX || earliest > t_ns) {
                if (b->idle_from_ns < t_ns && earliest > t_ns) {
                    b->idle_from_ns = t_ns; /* bus idle until now */
                }
                return;
            }
            start = earliest;
            b->idle_from_ns = earliest;
            s = arbitrate(b, start, &idx, &earliest);
        }
        if (start > t_ns) {
            return;
        }
        b->cur = fifo_remove(&b->fifo[s], idx);
        const uint32_t bits = busm_frame_bits(&b->cur.f, b->cur.extended);
        b->cur_end_ns = start + (uint64_t)bits * b->bit_ns;
        b->in_flight = true;
        b->frames++;
        b->bits += bits;
    }
}

uint64_t bus_next_event_ns(const bus_t *b)
{
    if (b->in_flight) {
        return b->cur_end_ns;
    }
    uint64_t earliest = UINT64_MAX;
    for (uint32_t s = 0; s < BUS_MAX_SOURCES; s++) {
        const bus_fifo_t *q = &b->fifo[s];
        for (uint32_t i = 0; i < q->len; i++) {
            const uint64_t t = q->items[(q->head + i) % BUS_FIFO_CAP].t_enqueue_ns;
            const uint64_t start = t > b->idle_from_ns ? t : b->idle_from_ns;
            if (start < earliest) {
                earliest = start;
            }
            if (t <= b->idle_from_ns) {
                break; /* nothing in this list can start earlier */
            }
        }
    }
    return earliest;
}

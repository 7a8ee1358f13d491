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
    const uint8_t dlc = f->dlc > 8u ? 8u : f->dlc;
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

uint32_t busm_frame_bits_min(uint8_t dlc, bool extended)
{
    const uint32_t d = dlc > 8u ? 8u : dlc;
    return (extended ? 54u : 34u) + 8u * d + TAIL_BITS;
}

uint32_t busm_frame_bits_worst(uint8_t dlc, bool extended)
{
    const uint32_t d = dlc > 8u ? 8u : dlc;
    const uint32_t stuffed = (extended ? 54u : 34u) + 8u * d;
    return stuffed + (stuffed - 1u) / 4u + TAIL_BITS;
}

void bus_init(bus_t *b, uint32_t bitrate)
{
    memset(b, 0, sizeof(*b));
    b->bit_ns = 1000000000ull / (bitrate > 0u ? bitrate : BUS_DEFAULT_BITRATE);
}

bool bus_enqueue(bus_t *b, uint8_t src, const can_frame_t *f, bool extended, uint64_t t_ns)
{
    if (src >= BUS_MAX_SOURCES || b->fifo[src].len >= BUS_FIFO_CAP) {
        b->dropped++;
        return false;
    }
    bus_fifo_t *q = &b->fifo[src];
    bus_item_t *it = &q->items[(q->head + q->len) % BUS_FIFO_CAP];
    it->f = *f;
    it->extended = extended;
    it->src = src;
    it->t_enqueue_ns = t_ns;
    q->len++;
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

/* The winner of arbitration at time t: lowest id among FIFO heads queued by t (extended ids
 * compare by their base id first; a standard frame wins over an extended one with the same base). */
static int arbitrate(const bus_t *b, uint64_t t, uint64_t *earliest)
{
    int best = -1;
    uint32_t best_key = 0u;
    *earliest = UINT64_MAX;
    for (uint32_t s = 0; s < BUS_MAX_SOURCES; s++) {
        const bus_fifo_t *q = &b->fifo[s];
        if (q->len == 0u) {
            continue;
        }
        const bus_item_t *it = &q->items[q->head];
        if (it->t_enqueue_ns > t) {
            if (it->t_enqueue_ns < *earliest) {
                *earliest = it->t_enqueue_ns;
            }
            continue;
        }
        const uint32_t key = it->extended ? (((it->f.id >> 18) & 0x7FFu) << 19) | (1u << 18) |
                                                (it->f.id & 0x3FFFFu)
                                          : ((it->f.id & 0x7FFu) << 19);
        if (best < 0 || key < best_key) {
            best = (int)s;
            best_key = key;
        }
    }
    return best;
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
        int s = arbitrate(b, start, &earliest);
        if (s < 0) {
            if (earliest == UINT64_MAX || earliest > t_ns) {
                if (b->idle_from_ns < t_ns && earliest > t_ns) {
                    b->idle_from_ns = t_ns; /* bus idle until now */
                }
                return;
            }
            start = earliest;
            b->idle_from_ns = earliest;
            s = arbitrate(b, start, &earliest);
        }
        if (start > t_ns) {
            return;
        }
        bus_fifo_t *q = &b->fifo[s];
        b->cur = q->items[q->head];
        q->head = (q->head + 1u) % BUS_FIFO_CAP;
        q->len--;
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
        if (b->fifo[s].len != 0u) {
            const uint64_t t = b->fifo[s].items[b->fifo[s].head].t_enqueue_ns;
            const uint64_t start = t > b->idle_from_ns ? t : b->idle_from_ns;
            if (start < earliest) {
                earliest = start;
            }
        }
    }
    return earliest;
}

/* libFuzzer harness: ISO-TP reception and transmission state machines (firmware/proto, read-only
 * use). The input is a script: per step one control byte (frame for us / foreign id / poll /
 * start a send) and up to 9 bytes of frame (dlc + data); time advances by a fuzzed amount.
 * Invariants: a completed message has 1..ISOTP_MAX_PAYLOAD bytes inside the buffer; frames the
 * link sends are 8 bytes (padded) on the tx id. */
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "isotp.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static bool send_cb(void *ctx, const can_frame_t *f)
{
    (void)ctx;
    if (f->id != 0x681u || f->len != 8u) {
        abort();
    }
    return true;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static isotp_link_t link;
    static uint8_t payload[ISOTP_MAX_PAYLOAD];
    isotp_config_t cfg;
    isotp_config_default(&cfg, 0x681u, 0x601u);
    if (size > 0) {
        cfg.block_size = data[0];
        cfg.st_min = (size > 1) ? data[1] : 0u;
    }
    isotp_init(&link, &cfg, send_cb, NULL);
    uint64_t now = 0;
    size_t i = (size > 2) ? 2 : size;
    while (i < size) {
        const uint8_t ctl = data[i++];
        now += (uint64_t)(ctl >> 3) * 50000u;   /* 0..1.55 s per step */
        switch (ctl & 7u) {
        case 0:
        case 1:
        case 2: {
            can_frame_t f;
            memset(&f, 0, sizeof f);
            f.id = (ctl & 7u) == 2u ? 0x123u : 0x601u;
            if (i < size) {
                f.len = (uint8_t)(data[i++] % 9u);
            }
            for (uint8_t b = 0; b < f.len && i < size; b++) {
                f.data[b] = data[i++];
            }
            isotp_on_frame(&link, &f, now);
            break;
        }
        case 3: {
            const uint8_t *msg = NULL;
            const uint16_t n = isotp_rx_peek(&link, &msg);
            if (n != 0u) {
                if (n > ISOTP_MAX_PAYLOAD || msg == NULL) {
                    abort();
                }
                volatile uint8_t sink = msg[n - 1u];   /* must be inside the buffer */
                (void)sink;
                isotp_rx_release(&link);
            }
            break;
        }
        case 4: {
            uint16_t len = 1;
            if (i + 1 < size) {
                len = (uint16_t)(((uint16_t)data[i] << 8 | data[i + 1]) % (ISOTP_MAX_PAYLOAD + 2u));
                i += 2;
            }
            memset(payload, 0xA5, sizeof payload);
            (void)isotp_send(&link, payload, len, now);
            break;
        }
        default:
            isotp_poll(&link, now);
            break;
        }
    }
    return 0;
}

/* SLCAN codec (see cm_slcan.h). */
#include "cm_slcan.h"

#include <string.h>

#define SLCAN_CR '\r'
#define SLCAN_BEL '\a'

static const char HEX[16] = {'0', '1', '2', '3', '4', '5', '6', '7',
                             '8', '9', 'A', 'B', 'C', 'D', 'E', 'F'};

void slcan_init(slcan_t *s)
{
    memset(s, 0, sizeof(*s));
    s->bitrate_code = 8u;
    s->open = true; /* auto-startup: a board reset does not silence a connected host */
}

/* Value of one hex digit (0-9, A-F, a-f) without a table: 0..15, or 16 or more if c is none. */
static inline uint32_t hex_nibble(char c)
{
    const uint32_t u = (uint32_t)(uint8_t)c;
    const uint32_t d = u - (uint32_t)'0';
    if (d < 10u) {
        return d;
    }
    const uint32_t a = (u | 0x20u) - (uint32_t)'a'; /* 'A'..'F' -> 'a'..'f' */
    return a < 6u ? a + 10u : 16u;
}

/* n hex digits at p -> *out; false if one is not a hex digit. */
static inline bool hex_value(const char *p, uint32_t n, uint32_t *out)
{
    uint32_t v = 0u;
    uint32_t bad = 0u;
    for (uint32_t i = 0u; i < n; i++) {
        const uint32_t d = hex_nibble(p[i]);
        bad |= d;
        v = (v << 4) | (d & 0xFu);
    }
    *out = v;
    return (bad & 0x10u) == 0u;
}

/* A frame command: id_digits 3 (t, r) or 8 (T, R); data unless remote. Validates the length. */
static bool parse_frame(const char *line, uint32_t len, uint32_t id_digits, bool remote,
                        can_frame_t *f)
{
    if (len < 1u + id_digits + 1u) {
        return false;
    }
    uint32_t id = 0u;
    uint32_t dlc = 0u;
    if (!hex_value(&line[1], id_digits, &id) || !hex_value(&line[1u + id_digits], 1u, &dlc) ||
        dlc > CAN_CLASSIC_MAX_LEN) {
        return false;
    }
    if (id_digits == 3u && id > CAN_STD_ID_MASK) {
        return false;
    }
    const uint32_t n_data = remote ? 0u : dlc;
    if (len != 1u + id_digits + 1u + 2u * n_data) {
        return false;
    }
    f->id = id;
    f->len = (uint8_t)dlc;
    f->flags = 0u;
    const char *p = &line[2u + id_digits];
    uint32_t bad = 0u;
    for (uint32_t i = 0u; i < n_data; i++) {
        const uint32_t hi = hex_nibble(p[2u * i]);
        const uint32_t lo = hex_nibble(p[2u * i + 1u]);
        bad |= hi | lo;
        f->data[i] = (uint8_t)(((hi & 0xFu) << 4) | (lo & 0xFu));
    }
    return (bad & 0x10u) == 0u;
}

static uint32_t reply_text(char reply[SLCAN_REPLY_MAX], const char *text)
{
    const uint32_t n = (uint32_t)strlen(text);
    memcpy(reply, text, n);
    reply[n] = SLCAN_CR;
    return n + 1u;
}

/* Execute one complete command line; returns true if it carried a frame for the device. */
static bool execute(slcan_t *s, can_frame_t *frame, char reply[SLCAN_REPLY_MAX],
                    uint32_t *reply_len)
{
    const char *l = s->line;
    const uint32_t n = s->len;
    bool ok = false;
    bool deliver = false;
    const char *text = "";
    can_frame_t f;
    switch (n > 0u ? l[0] : '\0') {
    case '\0':
        ok = true; /* empty line: a keep-alive CR */
        break;
    case 'S':
        if (n == 2u && l[1] >= '0' && l[1] <= '8') {
            s->bitrate_code = (uint8_t)(l[1] - '0');
            ok = true;
        }
        break;
    case 's': ok = (n == 5u); break;
    case 'O':
    case 'L':
        ok = (n == 1u);
        if (ok) {
            s->open = true;
            s->listen_only = (l[0] == 'L');
        }
        break;
    case 'C':
        ok = (n == 1u);
        if (ok) {
            s->open = false;
            s->listen_only = false;
        }
        break;
    case 'V':
        ok = (n == 1u);
        text = "V1010";
        break;
    case 'v':
        ok = (n == 1u);
        text = "vFS01";
        break;
    case 'N':
        ok = (n == 1u);
        text = "NFS01";
        break;
    case 'F':
        ok = (n == 1u);
        text = "F00";
        break;
    case 'Z': ok = (n == 2u && (l[1] == '0' || l[1] == '1')); break;
    case 'M':
    case 'm': ok = (n == 9u); break;
    case 't':
    case 'r':
        ok = s->open && !s->listen_only && parse_frame(l, n, 3u, l[0] == 'r', &f);
        text = "z";
        deliver = ok && l[0] == 't';
        break;
    case 'T':
    case 'R':
        ok = s->open && !s->listen_only && parse_frame(l, n, 8u, l[0] == 'R', &f);
        text = "Z";
        break;
    default: break;
    }
    if (!ok) {
        s->errors++;
        reply[0] = SLCAN_BEL;
        *reply_len = 1u;
        return false;
    }
    *reply_len = reply_text(reply, text);
    if (deliver) {
        *frame = f;
    }
    return deliver;
}

bool slcan_feed(slcan_t *s, uint8_t byte, can_frame_t *frame, char reply[SLCAN_REPLY_MAX],
                uint32_t *reply_len)
{
    *reply_len = 0u;
    if (byte == (uint8_t)SLCAN_CR) {
        bool got = false;
        if (s->overlong) {
            s->errors++;
            reply[0] = SLCAN_BEL;
            *reply_len = 1u;
        } else {
            got = execute(s, frame, reply, reply_len);
        }
        s->len = 0u;
        s->overlong = false;
        return got;
    }
    if (byte == (uint8_t)'\n') {
        return false; /* tolerate CR LF line ends */
    }
    if (s->len < SLCAN_LINE_MAX) {
        s->line[s->len++] = (char)byte;
    } else {
        s->overlong = true;
    }
    return false;
}

uint32_t slcan_encode(const can_frame_t *frame, char out[SLCAN_FRAME_TEXT_MAX])
{
    if (frame->id > CAN_STD_ID_MASK || frame->len > CAN_CLASSIC_MAX_LEN ||
        (frame->flags & CAN_FRAME_FD) != 0u) {
        return 0u; /* SLCAN carries classic frames only */
    }
    uint32_t k = 0u;
    out[k++] = 't';
    out[k++] = HEX[(frame->id >> 8) & 0xFu];
    out[k++] = HEX[(frame->id >> 4) & 0xFu];
    out[k++] = HEX[frame->id & 0xFu];
    out[k++] = HEX[frame->len];
    for (uint32_t i = 0u; i < frame->len; i++) {
        out[k++] = HEX[frame->data[i] >> 4];
        out[k++] = HEX[frame->data[i] & 0xFu];
    }
    out[k++] = SLCAN_CR;
    return k;
}

/* SLCAN codec (firmware/ports/mps2/cm_slcan.c) against the Lawicel command set as python-can's
 * slcan interface uses it: every reply, every frame form, malformed input, line limits. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>
#include <stdlib.h>

#include "cm_slcan.h"

typedef struct {
    char reply[256];
    uint32_t reply_len;
    can_frame_t frames[8];
    uint32_t n_frames;
} feed_result_t;

/* Feed a whole string; collect the replies and the frames. */
static void feed(slcan_t *s, const char *text, feed_result_t *r)
{
    memset(r, 0, sizeof(*r));
    for (const char *p = text; *p != '\0'; p++) {
        char reply[SLCAN_REPLY_MAX];
        uint32_t n = 0u;
        can_frame_t f;
        if (slcan_feed(s, (uint8_t)*p, &f, reply, &n)) {
            r->frames[r->n_frames++] = f;
        }
        memcpy(&r->reply[r->reply_len], reply, n);
        r->reply_len += n;
    }
}

static void test_python_can_open_sequence(void **state)
{
    (void)state;
    slcan_t s;
    slcan_init(&s);
    feed_result_t r;
    feed(&s, "C\rS8\rO\rV\r", &r); /* close, 1 Mbit/s, open, version */
    assert_int_equal(r.reply_len, 9u);
    assert_memory_equal(r.reply, "\r\r\rV1010\r", 9u);
    assert_true(s.open);
    assert_int_equal(s.bitrate_code, 8);
    feed(&s, "F\rN\rv\rZ0\rM00000000\rmFFFFFFFF\rs031C\r", &r);
    assert_memory_equal(r.reply, "F00\rNFS01\rvFS01\r\r\r\r\r", r.reply_len);
}

static void test_frames_in(void **state)
{
    (void)state;
    slcan_t s;
    slcan_init(&s);
    feed_result_t r;
    feed(&s, "t7E080211223344556677\rt1000\rr1234\r", &r);
    assert_int_equal(r.n_frames, 2u); /* the remote frame is answered, dropped */
    assert_int_equal(r.frames[0].id, 0x7E0u);
    assert_int_equal(r.frames[0].len, 8u);
    const uint8_t want[8] = {0x02, 0x11, 0x22, 0x33, 0x44, 0x55, 0x66, 0x77};
    assert_memory_equal(r.frames[0].data, want, 8u);
    assert_int_equal(r.frames[1].id, 0x100u);
    assert_int_equal(r.frames[1].len, 0u);
    assert_memory_equal(r.reply, "z\rz\rz\r", 6u);
    /* lower-case hex is accepted too */
    feed(&s, "t7e01ab\r", &r);
    assert_int_equal(r.n_frames, 1u);
    assert_int_equal(r.frames[0].data[0], 0xABu);
    /* an extended frame is acknowledged and dropped (11-bit product) */
    feed(&s, "T123456782AABB\r", &r);
    assert_int_equal(r.n_frames, 0u);
    assert_memory_equal(r.reply, "Z\r", 2u);
}

static void test_malformed_is_bel_and_changes_nothing(void **state)
{
    (void)state;
    slcan_t s;
    slcan_init(&s);
    const char *bad[] = {"t7E09\r", "t8001\r", "t7E0211\r", "t7E0111X\r", "tG000\r",
                         "S9\r",    "O1\r",    "Q\r",       "t7E01112\r", "Z2\r"};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        feed_result_t r;
        feed(&s, bad[i], &r);
        assert_int_equal(r.n_frames, 0u);
        assert_int_equal(r.reply_len, 1u);
        assert_int_equal(r.reply[0], '\a');
    }
    assert_int_equal(s.errors, sizeof bad / sizeof bad[0]);
    assert_true(s.open);
    assert_int_equal(s.bitrate_code, 8);
}

static void test_closed_or_listen_only_takes_no_frame(void **state)
{
    (void)state;
    slcan_t s;
    slcan_init(&s);
    feed_result_t r;
    feed(&s, "C\rt1000\rL\rt1000\rO\rt1000\r", &r);
    assert_int_equal(r.n_frames, 1u);
    assert_memory_equal(r.reply, "\r\a\r\a\rz\r", 7u);
}

static void test_overlong_line_and_crlf(void **state)
{
    (void)state;
    slcan_t s;
    slcan_init(&s);
    char line[64];
    memset(line, '1', sizeof line);
    line[0] = 't';
    line[sizeof line - 2] = '\r';
    line[sizeof line - 1] = '\0';
    feed_result_t r;
    feed(&s, line, &r);
    assert_int_equal(r.n_frames, 0u);
    assert_memory_equal(r.reply, "\a", 1u);
    feed(&s, "t1001AA\r\n", &r); /* the line after it parses again */
    assert_int_equal(r.n_frames, 1u);
    assert_int_equal(r.reply_len, 2u);
}

static void test_encode(void **state)
{
    (void)state;
    can_frame_t f = {.id = 0x190u, .len = 3u, .data = {0x01, 0xA0, 0xFF}};
    char out[SLCAN_FRAME_TEXT_MAX];
    const uint32_t n = slcan_encode(&f, out);
    assert_int_equal(n, 12u);
    assert_memory_equal(out,
                        "t1903"
                        "01A0FF"
                        "\r",
                        12u);
    f.len = 8u;
    assert_int_equal(slcan_encode(&f, out), SLCAN_FRAME_TEXT_MAX);
    /* what the codec writes, it reads back */
    slcan_t s;
    slcan_init(&s);
    can_frame_t back;
    char reply[SLCAN_REPLY_MAX];
    uint32_t rl = 0u;
    bool got = false;
    for (uint32_t i = 0; i < SLCAN_FRAME_TEXT_MAX; i++) {
        got = slcan_feed(&s, (uint8_t)out[i], &back, reply, &rl) || got;
    }
    assert_true(got);
    assert_int_equal(back.id, f.id);
    assert_memory_equal(back.data, f.data, 8u);
    f.id = 0x800u;
    assert_int_equal(slcan_encode(&f, out), 0u);
    f.id = 0x7FFu;
    f.len = 9u;
    assert_int_equal(slcan_encode(&f, out), 0u);
}

/* The port's receive path (slcan_take first, slcan_feed for what it leaves) against slcan_feed
 * alone, byte by byte over every command form, line ends, malformed and overlong lines: the same
 * replies, frames and parser state. */
static void test_take_then_feed_equals_feed(void **state)
{
    (void)state;
    static const char text[] =
        "C\rS8\rO\rV\rt7E080211223344556677\r\nt1000\rr1234\rT123456782AABB\rt7E0111X\r"
        "t12345678901234567890123456789012345678\rF\rL\rt1000\rO\rt7e01ab\r\r";
    slcan_t a;
    slcan_t b;
    slcan_init(&a);
    slcan_init(&b);
    for (const char *p = text; *p != '\0'; p++) {
        const uint8_t byte = (uint8_t)*p;
        char ra[SLCAN_REPLY_MAX];
        char rb[SLCAN_REPLY_MAX];
        uint32_t na = 0u;
        uint32_t nb = 0u;
        can_frame_t fa;
        can_frame_t fb;
        memset(&fa, 0, sizeof fa);
        memset(&fb, 0, sizeof fb);
        const bool ga = slcan_feed(&a, byte, &fa, ra, &na);
        bool gb = false;
        if (!slcan_take(&b, byte)) {
            gb = slcan_feed(&b, byte, &fb, rb, &nb);
        }
        assert_int_equal(ga, gb);
        assert_int_equal(na, nb);
        assert_memory_equal(ra, rb, na);
        if (ga) {
            assert_memory_equal(&fa, &fb, sizeof fa);
        }
        assert_int_equal(a.len, b.len);
        assert_int_equal(a.overlong, b.overlong);
        assert_int_equal(a.errors, b.errors);
        assert_int_equal(a.open, b.open);
    }
    assert_true(a.errors >= 3u); /* X digit, overlong line, frame while listen-only */
}

/* The table-free hex decoder against the C library: every byte value in each digit position of
 * a frame's id and data is accepted exactly when strtoul reads it as a hex digit (and the id
 * stays 11-bit), with strtoul's value. */
static void test_hex_digits_against_strtoul(void **state)
{
    (void)state;
    static const uint32_t positions[] = {1u, 2u, 3u, 5u, 6u}; /* in "t1231A5": id, data */
    for (uint32_t c = 1u; c < 256u; c++) {
        const char ch[2] = {(char)c, '\0'};
        char *end = NULL;
        (void)strtoul(ch, &end, 16);
        const bool is_hex = end == &ch[1];
        for (size_t k = 0u; k < sizeof positions / sizeof positions[0]; k++) {
            char line[] = "t1231A5\r";
            line[positions[k]] = (char)c;
            if (c == '\r' || c == '\n') {
                continue; /* line ends, not digits */
            }
            const char id_text[4] = {line[1], line[2], line[3], '\0'};
            const char data_text[3] = {line[5], line[6], '\0'};
            const unsigned long id = strtoul(id_text, NULL, 16);
            const bool want = is_hex && id <= 0x7FFu;
            slcan_t s;
            slcan_init(&s);
            feed_result_t r;
            feed(&s, line, &r);
            assert_int_equal(r.n_frames, want ? 1u : 0u);
            if (!want) {
                assert_memory_equal(r.reply, "\a", 1u);
                continue;
            }
            assert_int_equal(r.frames[0].id, id);
            assert_int_equal(r.frames[0].len, 1u);
            assert_int_equal(r.frames[0].data[0], strtoul(data_text, NULL, 16));
        }
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_python_can_open_sequence),
        cmocka_unit_test(test_frames_in),
        cmocka_unit_test(test_malformed_is_bel_and_changes_nothing),
        cmocka_unit_test(test_closed_or_listen_only_takes_no_frame),
        cmocka_unit_test(test_overlong_line_and_crlf),
        cmocka_unit_test(test_encode),
        cmocka_unit_test(test_hex_digits_against_strtoul),
        cmocka_unit_test(test_take_then_feed_equals_feed),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

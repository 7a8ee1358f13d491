/* The generated UDS payload codecs (fs_wire.h) against the golden vectors the host's codecs
 * wrote (tests/vectors/wire.txt, tests/vectors/wire_generate.py): every good vector unpacks and
 * packs back to the same bytes, every bad one is refused with its status and leaves the record
 * unchanged; and a few values against the layouts of docs/protocol.md. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "fs_wire.h"
#include "vectors_io.h"

#define TEXT_MAX 16384u
#define PAYLOAD_MAX 256u

/* Unpack, then (when it unpacked) pack back; the unpack status, the packed length in *n_out. */
#define TRY(name)                                                                                 \
    static proto_status_t try_##name(const uint8_t *d, uint16_t len, uint8_t *out, uint16_t *n_out) \
    {                                                                                             \
        fs_wire_##name##_t v;                                                                     \
        memset(&v, 0xA5, sizeof(v));                                                              \
        fs_wire_##name##_t before = v;                                                            \
        const proto_status_t st = fs_wire_##name##_unpack(&v, d, len);                            \
        if (st != PROTO_OK) {                                                                     \
            assert_memory_equal(&v, &before, sizeof(v)); /* refused: unchanged */                 \
            return st;                                                                            \
        }                                                                                         \
        *n_out = fs_wire_##name##_pack(&v, out, PAYLOAD_MAX);                                     \
        assert_int_equal(fs_wire_##name##_pack(&v, out, (uint16_t)(*n_out - 1u)), 0u);            \
        *n_out = fs_wire_##name##_pack(&v, out, PAYLOAD_MAX);                                     \
        return st;                                                                                \
    }
FS_WIRE_RECORDS(TRY)
#undef TRY

typedef proto_status_t (*try_fn)(const uint8_t *, uint16_t, uint8_t *, uint16_t *);
typedef struct {
    const char *name;
    try_fn fn;
} entry_t;

#define ENTRY(name) {#name, try_##name},
static const entry_t RECORDS[] = {FS_WIRE_RECORDS(ENTRY)};
#undef ENTRY

static try_fn find(const char *name)
{
    for (size_t i = 0; i < sizeof RECORDS / sizeof RECORDS[0]; i++) {
        if (strcmp(RECORDS[i].name, name) == 0) {
            return RECORDS[i].fn;
        }
    }
    return NULL;
}

static uint16_t from_hex(const char *hex, uint8_t *out)
{
    uint16_t n = 0u;
    for (; hex[0] != '\0' && hex[1] != '\0' && n < PAYLOAD_MAX; hex += 2) {
        unsigned b = 0u;
        assert_int_equal(sscanf(hex, "%2x", &b), 1);
        out[n++] = (uint8_t)b;
    }
    return n;
}

static void test_every_golden_vector(void **state)
{
    (void)state;
    static uint8_t text[TEXT_MAX + 1u];
    const uint32_t n = tv_read("wire.txt", text, TEXT_MAX);
    assert_true(n > 0u && n < TEXT_MAX);
    text[n] = '\0';
    unsigned good = 0u, bad = 0u;
    for (char *line = strtok((char *)text, "\n"); line != NULL; line = strtok(NULL, "\n")) {
        if (line[0] == '#') {
            continue;
        }
        char name[32], hex[2u * PAYLOAD_MAX + 1u];
        int expect = -1;
        assert_int_equal(sscanf(line, "%31s %512s %d", name, hex, &expect), 3);
        const try_fn fn = find(name);
        assert_non_null(fn);
        uint8_t d[PAYLOAD_MAX], out[PAYLOAD_MAX];
        const uint16_t len = from_hex(hex, d);
        uint16_t n_out = 0u;
        const proto_status_t st = fn(d, len, out, &n_out);
        assert_int_equal(st, expect);
        if (st == PROTO_OK) {
            assert_int_equal(n_out, len);
            assert_memory_equal(out, d, len);
            good++;
        } else {
            bad++;
        }
    }
    assert_true(good >= sizeof RECORDS / sizeof RECORDS[0]);
    assert_true(bad > 0u);
}

static void test_values_of_the_documented_layouts(void **state)
{
    (void)state;
    fs_wire_mark_test_t m;
    assert_int_equal(fs_wire_mark_test_unpack(&m, NULL, 0u), PROTO_OK); /* no options: none */
    assert_int_equal(m.has_options, 0u);
    assert_int_equal(m.options, 0u);
    const uint8_t run[] = {1u, 0x05u, 0xDCu, 0x03u, 0xE8u, 2u};
    fs_wire_run_skill_t r;
    assert_int_equal(fs_wire_run_skill_unpack(&r, run, sizeof run), PROTO_OK);
    assert_int_equal(r.slot, 1u);
    assert_int_equal(r.goal_scale, 1500u);
    assert_int_equal(r.time_scale, 1000u);
    assert_int_equal(r.end, 2u);
    assert_int_equal(r.has_path_scale, 0u);
    assert_int_equal(r.path_scale, FS_WIRE_SCALE_STEPS); /* absent: 1 */
    /* the value in the build's real type, as the device computed it before the codecs */
    const float g = FS_WIRE_REAL(float, r.goal_scale);
    assert_true(g == 1500.0f * 0.001f);
    const double gd = FS_WIRE_REAL(double, r.goal_scale);
    assert_true(gd == 1500.0 * 0.001);

    const uint8_t stiff[] = {0x48u, 0xF4u, 0x24u, 0x00u}; /* 5e5 as float32 */
    fs_wire_stiffness_max_t k;
    assert_int_equal(fs_wire_stiffness_max_unpack(&k, stiff, sizeof stiff), PROTO_OK);
    assert_true(k.stiffness_max_Npm == 5e5f);
}

static void test_pack_refuses_out_of_range(void **state)
{
    (void)state;
    uint8_t out[PAYLOAD_MAX];
    const fs_wire_erase_slot_t e = {FS_SLOT_COUNT + 1u};
    assert_int_equal(fs_wire_erase_slot_pack(&e, out, sizeof out), 0u);
    fs_wire_run_sequence_t s;
    memset(&s, 0, sizeof(s));
    assert_int_equal(fs_wire_run_sequence_pack(&s, out, sizeof out), 0u); /* no step */
    s.n_steps = 1u;
    assert_int_equal(fs_wire_run_sequence_pack(&s, out, sizeof out), 10u);
    s.end = 3u;
    assert_int_equal(fs_wire_run_sequence_pack(&s, out, sizeof out), 0u);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_every_golden_vector),
        cmocka_unit_test(test_values_of_the_documented_layouts),
        cmocka_unit_test(test_pack_refuses_out_of_range),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

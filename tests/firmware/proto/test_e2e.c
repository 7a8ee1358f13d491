/* E2E protection: CRC-8 SAE J1850 against the AUTOSAR CRC routines test vectors, and the
 * rolling counter / CRC check of safety frames. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "e2e.h"

static void test_crc8_standard_vectors(void **state)
{
    (void)state;
    /* AUTOSAR SWS CRC Library, CRC8 (SAE J1850) check values */
    static const uint8_t v1[] = {0x00, 0x00, 0x00, 0x00};
    static const uint8_t v2[] = {0xF2, 0x01, 0x83};
    static const uint8_t v3[] = {0x0F, 0xAA, 0x00, 0x55};
    static const uint8_t v4[] = {0x00, 0xFF, 0x55, 0x11};
    static const uint8_t v5[] = {0x33, 0x22, 0x55, 0xAA, 0xBB, 0xCC, 0xDD, 0xEE, 0xFF};
    static const uint8_t v6[] = {0x92, 0x6B, 0x55};
    static const uint8_t v7[] = {0xFF, 0xFF, 0xFF, 0xFF};
    static const uint8_t check[] = "123456789";
    assert_int_equal(e2e_crc8(v1, 4), 0x59);
    assert_int_equal(e2e_crc8(v2, 3), 0x37);
    assert_int_equal(e2e_crc8(v3, 4), 0x79);
    assert_int_equal(e2e_crc8(v4, 4), 0xB8);
    assert_int_equal(e2e_crc8(v5, 9), 0xCB);
    assert_int_equal(e2e_crc8(v6, 3), 0x8C);
    assert_int_equal(e2e_crc8(v7, 4), 0x74);
    assert_int_equal(e2e_crc8(check, 9), 0x4B);
}

static void test_protect_and_check(void **state)
{
    (void)state;
    can_frame_t f = {.id = 0x181, .len = 8, .data = {1, 2, 3, 4, 5, 6, 0xA0, 0}};
    e2e_protect(&f, 5);
    assert_int_equal(f.data[6], 0xA5);            /* upper nibble kept, counter in the low nibble */
    const uint8_t covered[9] = {0x81, 0x01, 1, 2, 3, 4, 5, 6, 0xA5};
    assert_int_equal(f.data[7], e2e_crc8(covered, 9));
    e2e_rx_t rx;
    e2e_rx_reset(&rx);
    assert_int_equal(e2e_check(&rx, &f), PROTO_OK);
    assert_int_equal(e2e_check(&rx, &f), PROTO_ERR_E2E_COUNTER);   /* same counter again: stale */
    e2e_protect(&f, 6);
    assert_int_equal(e2e_check(&rx, &f), PROTO_OK);
    /* any single bit flip is detected */
    for (unsigned byte = 0; byte < 8; byte++) {
        for (unsigned bit = 0; bit < 8; bit++) {
            can_frame_t g = f;
            g.data[byte] ^= (uint8_t)(1u << bit);
            e2e_rx_t fresh;
            e2e_rx_reset(&fresh);
            proto_status_t st = e2e_check(&fresh, &g);
            assert_int_equal(st, PROTO_ERR_E2E_CRC);
        }
    }
    /* the same payload on another id fails (id is covered) */
    can_frame_t h = f;
    h.id = 0x182;
    e2e_rx_t fresh;
    e2e_rx_reset(&fresh);
    assert_int_equal(e2e_check(&fresh, &h), PROTO_ERR_E2E_CRC);
    h = f;
    h.len = 7;
    assert_int_equal(e2e_check(&fresh, &h), PROTO_ERR_DLC);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_crc8_standard_vectors),
        cmocka_unit_test(test_protect_and_check),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

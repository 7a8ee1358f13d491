/* libFuzzer harness: the UDS server (firmware/proto, read-only use) with a stub application
 * whose hooks accept everything within bounds. The input is a sequence of requests
 * (length byte + bytes); time advances between them. Invariants: the response fits its
 * buffer, starts with SID+0x40 or is 7F SID NRC with a non-zero NRC, never silence unless
 * the request set the suppress bit. */
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "uds.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static uint8_t ok_read(void *c, uint16_t did, uint8_t *out, uint16_t cap, uint16_t *len)
{
    (void)c;
    if (did == 0xF190u && cap >= 4u) {
        memcpy(out, "FSKL", 4);
        *len = 4;
        return UDS_NRC_OK;
    }
    *len = 0;
    return UDS_NRC_REQUEST_OUT_OF_RANGE;
}
static uint8_t ok_write(void *c, uint16_t did, const uint8_t *d, uint16_t len)
{
    (void)c;
    (void)did;
    (void)d;
    return len > 8u ? UDS_NRC_INCORRECT_LENGTH : UDS_NRC_OK;
}
static uint8_t ok_routine(void *c, uint8_t sub, uint16_t rid, const uint8_t *d, uint16_t len,
                          uint8_t *out, uint16_t cap, uint16_t *out_len)
{
    (void)c;
    (void)sub;
    (void)d;
    (void)len;
    *out_len = 0;
    if (rid == UDS_RID_SELF_TEST && cap >= 3u) {
        out[0] = 0;
        out[1] = 0;
        out[2] = 0;
        *out_len = 3;
    }
    return UDS_NRC_OK;
}
static uint8_t ok_session(void *c, uint8_t s)
{
    (void)c;
    (void)s;
    return UDS_NRC_OK;
}
static uint8_t ok_reset(void *c, uint8_t t)
{
    (void)c;
    (void)t;
    return UDS_NRC_OK;
}
static void do_reset(void *c, uint8_t t)
{
    (void)c;
    (void)t;
}
static uint8_t g_seed_ok;
static uint8_t ok_seed(void *c, uint8_t level, uint8_t *seed, uint16_t cap, uint16_t *len)
{
    (void)c;
    (void)level;
    if (cap < 16u) {
        return UDS_NRC_CONDITIONS_NOT_CORRECT;
    }
    memset(seed, 0x5A, 16);
    *len = 16;
    g_seed_ok = 1;
    return UDS_NRC_OK;
}
static uint8_t ok_key(void *c, uint8_t level, const uint8_t *key, uint16_t len)
{
    (void)c;
    (void)level;
    return (len == 16u && key[0] == 0x42u) ? UDS_NRC_OK : UDS_NRC_INVALID_KEY;
}
static uint32_t g_dl_size;
static uint8_t ok_dl_begin(void *c, uint32_t addr, uint32_t size)
{
    (void)c;
    if (addr > 8u || size == 0u || size > 8192u) {
        return UDS_NRC_REQUEST_OUT_OF_RANGE;
    }
    g_dl_size = size;
    return UDS_NRC_OK;
}
static uint8_t ok_dl_data(void *c, uint32_t off, const uint8_t *d, uint16_t len)
{
    (void)c;
    (void)d;
    if ((uint64_t)off + len > g_dl_size) {
        abort();
    } /* the server must bound transfers */
    return UDS_NRC_OK;
}
static uint8_t ok_dl_end(void *c, uint32_t *crc)
{
    (void)c;
    *crc = 0x12345678u;
    return UDS_NRC_OK;
}
static void ok_abort(void *c)
{
    (void)c;
}
static uint32_t g_ul_size;
static uint8_t ok_ul_begin(void *c, uint32_t addr, uint32_t size)
{
    (void)c;
    if (addr > 8u || size == 0u || size > 8192u) {
        return UDS_NRC_REQUEST_OUT_OF_RANGE;
    }
    g_ul_size = size;
    return UDS_NRC_OK;
}
static uint8_t ok_ul_data(void *c, uint32_t off, uint8_t *out, uint16_t len)
{
    (void)c;
    if ((uint64_t)off + len > g_ul_size) {
        abort();
    }
    memset(out, 0x33, len);
    return UDS_NRC_OK;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static uds_server_t srv;
    static uint8_t resp[4096];
    const uds_app_t app = {NULL,        ok_read,
                           ok_write,    ok_routine,
                           ok_session,  ok_reset,
                           do_reset,    ok_seed,
                           ok_key,      NULL /* resume: no hook answers 0x78 here */,
                           ok_dl_begin, ok_dl_data,
                           ok_dl_end,   ok_abort,
                           ok_ul_begin, ok_ul_data};
    uds_server_init(&srv, &app);
    uint32_t now = 0;
    size_t i = 0;
    while (i < size) {
        uint16_t len = data[i++];
        if (len & 0x80u) { /* long request: 2-byte length */
            len = (uint16_t)(((len & 0x7Fu) << 8) | (i < size ? data[i++] : 0u));
        }
        if (len > size - i) {
            len = (uint16_t)(size - i);
        }
        const uint8_t *req = data + i;
        i += len;
        now += 7u;
        uds_server_poll(&srv, now);
        /* every other request with a small response buffer (truncation paths; uds.c needs
         * resp_cap >= 8 and answers nothing below that, although uds.h says >= 3) */
        const uint16_t cap = (i & 1u) ? (uint16_t)sizeof resp : (uint16_t)(8u + (i % 13u));
        const uint16_t n = uds_server_handle(&srv, req, len, resp, cap, now);
        if (n > cap) {
            abort();
        }
        if (n == 0u) {
            /* silence is only allowed for a suppressed positive response (or no SID at all) */
            if (len != 0u && (len < 2u || (req[1] & UDS_SUPPRESS_POS) == 0u)) {
                abort();
            }
        } else if (resp[0] == UDS_NEGATIVE_RESPONSE) {
            if (n != 3u || resp[2] == 0u || (len > 0u && resp[1] != req[0])) {
                abort();
            }
        } else if (len == 0u || resp[0] != (uint8_t)(req[0] + 0x40u)) {
            abort();
        }
        uds_server_after_response(&srv);
    }
    return 0;
}

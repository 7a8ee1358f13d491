/* UDS server: every service, its positive response layout (ISO 14229-1) and every negative
 * response code the server gives, against a fake application that records the calls. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <cmocka.h>

#include "uds.h"

typedef struct {
    uint8_t store[8192];
    uint32_t size;
    uint32_t addr;
    uint8_t begin_nrc, data_nrc, end_nrc, key_nrc, did_nrc, routine_nrc, session_nrc, reset_nrc;
    unsigned begin_calls, data_calls, end_calls, abort_calls, reset_calls, write_calls;
    uint8_t last_reset;
    uint16_t written_did;
    uint8_t written[16];
    uint16_t written_len;
    uint8_t routine_sub;
    uint16_t routine_rid;
    unsigned resume_left; /* resume: calls still answered 0x78 */
    uint8_t resume_nrc;   /* then this */
    uint8_t resume_sid;
    uint16_t resume_arg;
} fake_t;

static fake_t fk;
static uds_server_t srv;
static uint8_t resp[4100];

static uint8_t f_read_did(void *ctx, uint16_t did, uint8_t *out, uint16_t cap, uint16_t *n)
{
    (void)ctx;
    if (did == 0xF190) {
        if (cap < 4u) return UDS_NRC_RESPONSE_TOO_LONG;
        memcpy(out, "FS01", 4);
        *n = 4;
        return UDS_NRC_OK;
    }
    if (did == 0x0100) {
        out[0] = 0xAB;
        *n = 1;
        return UDS_NRC_OK;
    }
    return UDS_NRC_REQUEST_OUT_OF_RANGE;
}
static uint8_t f_write_did(void *ctx, uint16_t did, const uint8_t *d, uint16_t len)
{
    (void)ctx;
    fk.write_calls++;
    if (fk.did_nrc) return fk.did_nrc;
    fk.written_did = did;
    memcpy(fk.written, d, len < 16 ? len : 16);
    fk.written_len = len;
    return UDS_NRC_OK;
}
static uint8_t f_routine(void *ctx, uint8_t sub, uint16_t rid, const uint8_t *d, uint16_t len,
                         uint8_t *out, uint16_t cap, uint16_t *n)
{
    (void)ctx; (void)d; (void)len; (void)cap;
    fk.routine_sub = sub;
    fk.routine_rid = rid;
    if (fk.routine_nrc) return fk.routine_nrc;
    out[0] = 0x00;
    *n = 1;
    return UDS_NRC_OK;
}
static uint8_t f_session(void *ctx, uint8_t s) { (void)ctx; (void)s; return fk.session_nrc; }
static uint8_t f_reset(void *ctx, uint8_t t) { (void)ctx; (void)t; return fk.reset_nrc; }
static void f_reset_now(void *ctx, uint8_t t) { (void)ctx; fk.reset_calls++; fk.last_reset = t; }
static uint8_t f_seed(void *ctx, uint8_t level, uint8_t *seed, uint16_t cap, uint16_t *len)
{
    (void)ctx; (void)cap;
    for (uint8_t i = 0; i < 4; i++) seed[i] = (uint8_t)(0x10u * level + i);
    *len = 4;
    return UDS_NRC_OK;
}
static uint8_t f_key(void *ctx, uint8_t level, const uint8_t *key, uint16_t len)
{
    (void)ctx;
    if (fk.key_nrc) return fk.key_nrc;
    /* key = seed xor 0xFF (the fake's rule) */
    if (len != 4) return UDS_NRC_INVALID_KEY;
    for (uint8_t i = 0; i < 4; i++) {
        if (key[i] != (uint8_t)((0x10u * level + i) ^ 0xFFu)) return UDS_NRC_INVALID_KEY;
    }
    return UDS_NRC_OK;
}
static uint8_t f_resume(void *ctx, uint8_t sid, uint16_t arg)
{
    (void)ctx;
    fk.resume_sid = sid;
    fk.resume_arg = arg;
    if (fk.resume_left > 0u) {
        fk.resume_left--;
        return UDS_NRC_RESPONSE_PENDING;
    }
    return fk.resume_nrc;
}
static uint8_t f_dl_begin(void *ctx, uint32_t addr, uint32_t size)
{
    (void)ctx;
    fk.begin_calls++;
    if (fk.begin_nrc) return fk.begin_nrc;
    if (size > sizeof(fk.store)) return UDS_NRC_REQUEST_OUT_OF_RANGE;
    fk.addr = addr;
    fk.size = size;
    return UDS_NRC_OK;
}
static uint8_t f_dl_data(void *ctx, uint32_t off, const uint8_t *d, uint16_t len)
{
    (void)ctx;
    fk.data_calls++;
    if (fk.data_nrc) return fk.data_nrc;
    memcpy(&fk.store[off], d, len);
    return UDS_NRC_OK;
}
static uint8_t f_dl_end(void *ctx, uint32_t *crc)
{
    (void)ctx;
    fk.end_calls++;
    *crc = 0x11223344u;
    return fk.end_nrc;
}
static void f_abort(void *ctx) { (void)ctx; fk.abort_calls++; }
static uint8_t f_ul_begin(void *ctx, uint32_t addr, uint32_t size)
{
    (void)ctx;
    if (addr != 1u) return UDS_NRC_REQUEST_OUT_OF_RANGE;
    if (size != fk.size) return UDS_NRC_REQUEST_OUT_OF_RANGE;
    return UDS_NRC_OK;
}
static uint8_t f_ul_data(void *ctx, uint32_t off, uint8_t *out, uint16_t len)
{
    (void)ctx;
    memcpy(out, &fk.store[off], len);
    return UDS_NRC_OK;
}

static int setup(void **state)
{
    (void)state;
    memset(&fk, 0, sizeof(fk));
    const uds_app_t app = {
        .ctx = &fk, .read_did = f_read_did, .write_did = f_write_did, .routine = f_routine,
        .session_allowed = f_session, .ecu_reset = f_reset, .reset_now = f_reset_now,
        .security_seed = f_seed, .security_key = f_key, .download_begin = f_dl_begin,
        .download_data = f_dl_data, .download_end = f_dl_end, .transfer_abort = f_abort,
        .upload_begin = f_ul_begin, .upload_data = f_ul_data, .resume = f_resume};
    uds_server_init(&srv, &app);
    return 0;
}

static uint16_t req(const uint8_t *r, uint16_t len)
{
    memset(resp, 0, sizeof(resp));
    return uds_server_handle(&srv, r, len, resp, (uint16_t)sizeof(resp), 0);
}

#define REQ(...) do { static const uint8_t r_[] = {__VA_ARGS__}; n = req(r_, (uint16_t)sizeof(r_)); } while (0)
#define EXPECT_NRC(sid, nrc) do { assert_int_equal(n, 3); assert_int_equal(resp[0], 0x7F); \
    assert_int_equal(resp[1], sid); assert_int_equal(resp[2], nrc); } while (0)

static void unlock(uint8_t session)
{
    uint16_t n;
    uint8_t r[2] = {0x10, session};
    n = req(r, 2);
    assert_int_equal(resp[0], 0x50);
    REQ(0x27, 0x01);
    assert_int_equal(n, 6);
    uint8_t key[6] = {0x27, 0x02};
    for (int i = 0; i < 4; i++) key[2 + i] = (uint8_t)(resp[2 + i] ^ 0xFFu);
    n = req(key, 6);
    assert_int_equal(n, 2);
    assert_int_equal(resp[0], 0x67);
}

static void test_unknown_service_and_empty(void **state)
{
    (void)state;
    uint16_t n;
    REQ(0x85, 0x01);
    EXPECT_NRC(0x85, UDS_NRC_SERVICE_NOT_SUPPORTED);
    n = req(resp, 0);
    assert_int_equal(n, 0);
}

static void test_session_control(void **state)
{
    (void)state;
    uint16_t n;
    REQ(0x10, 0x03);
    assert_int_equal(n, 6);
    const uint8_t expect[6] = {0x50, 0x03, 0x00, 50, 0x01, 0xF4};   /* P2 50 ms, P2* 5000 ms */
    assert_memory_equal(resp, expect, 6);
    assert_int_equal(srv.session, UDS_SESSION_EXTENDED);
    REQ(0x10, 0x04);
    EXPECT_NRC(0x10, UDS_NRC_SUBFUNCTION_NOT_SUPPORTED);
    REQ(0x10);
    EXPECT_NRC(0x10, UDS_NRC_INCORRECT_LENGTH);
    REQ(0x10, 0x01, 0x00);
    EXPECT_NRC(0x10, UDS_NRC_INCORRECT_LENGTH);
    fk.session_nrc = UDS_NRC_CONDITIONS_NOT_CORRECT;
    REQ(0x10, 0x02);
    EXPECT_NRC(0x10, UDS_NRC_CONDITIONS_NOT_CORRECT);
    assert_int_equal(srv.session, UDS_SESSION_EXTENDED);
    fk.session_nrc = 0;
    REQ(0x10, 0x81);                                 /* suppress positive response */
    assert_int_equal(n, 0);
    assert_int_equal(srv.session, UDS_SESSION_DEFAULT);
}

static void test_session_timeout_s3(void **state)
{
    (void)state;
    unlock(UDS_SESSION_PROGRAMMING);
    uds_server_poll(&srv, UDS_S3_MS);
    assert_int_equal(srv.session, UDS_SESSION_PROGRAMMING);
    uds_server_poll(&srv, UDS_S3_MS + 1u);
    assert_int_equal(srv.session, UDS_SESSION_DEFAULT);
    assert_int_equal(srv.unlocked_level, 0);
}

static void test_ecu_reset(void **state)
{
    (void)state;
    uint16_t n;
    REQ(0x11, 0x01);
    assert_int_equal(n, 2);
    assert_int_equal(resp[0], 0x51);
    assert_int_equal(fk.reset_calls, 0);               /* only after the response went out */
    uds_server_after_response(&srv);
    assert_int_equal(fk.reset_calls, 1);
    assert_int_equal(fk.last_reset, 1);
    REQ(0x11, 0x02);
    EXPECT_NRC(0x11, UDS_NRC_SUBFUNCTION_NOT_SUPPORTED);
    REQ(0x11);
    EXPECT_NRC(0x11, UDS_NRC_INCORRECT_LENGTH);
    fk.reset_nrc = UDS_NRC_CONDITIONS_NOT_CORRECT;
    REQ(0x11, 0x03);
    EXPECT_NRC(0x11, UDS_NRC_CONDITIONS_NOT_CORRECT);
}

static void test_security_access(void **state)
{
    (void)state;
    uint16_t n;
    REQ(0x27, 0x01);
    EXPECT_NRC(0x27, UDS_NRC_SERVICE_NOT_IN_SESSION);   /* default session */
    REQ(0x10, 0x03);
    REQ(0x27, 0x03);
    EXPECT_NRC(0x27, UDS_NRC_SUBFUNCTION_NOT_IN_SESSION); /* firmware level: programming only */
    REQ(0x27, 0x05);
    EXPECT_NRC(0x27, UDS_NRC_SUBFUNCTION_NOT_SUPPORTED);
    REQ(0x27);
    EXPECT_NRC(0x27, UDS_NRC_INCORRECT_LENGTH);
    REQ(0x27, 0x02, 0, 0, 0, 0);
    EXPECT_NRC(0x27, UDS_NRC_REQUEST_SEQUENCE_ERROR);   /* key without seed */
    REQ(0x27, 0x01);
    assert_int_equal(n, 6);
    assert_int_equal(resp[0], 0x67);
    REQ(0x27, 0x02, 0, 0, 0, 0);
    EXPECT_NRC(0x27, UDS_NRC_INVALID_KEY);
    REQ(0x27, 0x02, 0, 0, 0, 0);
    EXPECT_NRC(0x27, UDS_NRC_REQUEST_SEQUENCE_ERROR);   /* one key per seed */
    fk.key_nrc = UDS_NRC_EXCEEDED_ATTEMPTS;
    REQ(0x27, 0x01);
    REQ(0x27, 0x02, 0, 0, 0, 0);
    EXPECT_NRC(0x27, UDS_NRC_EXCEEDED_ATTEMPTS);
    fk.key_nrc = UDS_NRC_DELAY_NOT_EXPIRED;
    REQ(0x27, 0x01);
    REQ(0x27, 0x02, 0, 0, 0, 0);
    EXPECT_NRC(0x27, UDS_NRC_DELAY_NOT_EXPIRED);
    fk.key_nrc = 0;
    unlock(UDS_SESSION_EXTENDED);
    assert_int_equal(srv.unlocked_level, 1);
    REQ(0x27, 0x01);                                   /* already unlocked: zero seed */
    const uint8_t zero[6] = {0x67, 0x01, 0, 0, 0, 0};
    assert_memory_equal(resp, zero, 6);
    REQ(0x10, 0x02);                                   /* session change locks */
    assert_int_equal(srv.unlocked_level, 0);
}

static void test_read_did(void **state)
{
    (void)state;
    uint16_t n;
    REQ(0x22, 0xF1, 0x90);
    assert_int_equal(n, 7);
    const uint8_t expect[7] = {0x62, 0xF1, 0x90, 'F', 'S', '0', '1'};
    assert_memory_equal(resp, expect, 7);
    REQ(0x22, 0xF1, 0x90, 0x01, 0x00);                 /* two DIDs in one request */
    assert_int_equal(n, 10);
    assert_int_equal(resp[9], 0xAB);
    REQ(0x22, 0x12, 0x34);
    EXPECT_NRC(0x22, UDS_NRC_REQUEST_OUT_OF_RANGE);
    REQ(0x22, 0xF1);
    EXPECT_NRC(0x22, UDS_NRC_INCORRECT_LENGTH);
    REQ(0x22, 0xF1, 0x90, 0x01);
    EXPECT_NRC(0x22, UDS_NRC_INCORRECT_LENGTH);
    uint8_t small[8];
    static const uint8_t r[] = {0x22, 0xF1, 0x90};
    n = uds_server_handle(&srv, r, 3, small, sizeof(small), 0);
    assert_int_equal(n, 7);                            /* fits exactly */
}

static void test_write_did(void **state)
{
    (void)state;
    uint16_t n;
    REQ(0x2E, 0x01, 0x00, 0x05);
    EXPECT_NRC(0x2E, UDS_NRC_SERVICE_NOT_IN_SESSION);
    REQ(0x10, 0x03);
    REQ(0x2E, 0x01, 0x00, 0x05);
    EXPECT_NRC(0x2E, UDS_NRC_SECURITY_ACCESS_DENIED);
    assert_int_equal(fk.write_calls, 0);
    unlock(UDS_SESSION_EXTENDED);
    REQ(0x2E, 0x01, 0x00, 0x05, 0x06);
    assert_int_equal(n, 3);
    const uint8_t expect[3] = {0x6E, 0x01, 0x00};
    assert_memory_equal(resp, expect, 3);
    assert_int_equal(fk.written_did, 0x0100);
    assert_int_equal(fk.written_len, 2);
    REQ(0x2E, 0x01, 0x00);
    EXPECT_NRC(0x2E, UDS_NRC_INCORRECT_LENGTH);
    fk.did_nrc = UDS_NRC_REQUEST_OUT_OF_RANGE;
    REQ(0x2E, 0x01, 0x00, 0xFF);
    EXPECT_NRC(0x2E, UDS_NRC_REQUEST_OUT_OF_RANGE);
}

static void test_routine_control(void **state)
{
    (void)state;
    uint16_t n;
    REQ(0x31, 0x01, 0x02, 0x01, 0x01);
    assert_int_equal(n, 5);
    const uint8_t expect[5] = {0x71, 0x01, 0x02, 0x01, 0x00};
    assert_memory_equal(resp, expect, 5);
    assert_int_equal(fk.routine_rid, 0x0201);
    REQ(0x31, 0x04, 0x02, 0x01);
    EXPECT_NRC(0x31, UDS_NRC_SUBFUNCTION_NOT_SUPPORTED);
    REQ(0x31, 0x01, 0x02);
    EXPECT_NRC(0x31, UDS_NRC_INCORRECT_LENGTH);
    fk.routine_nrc = UDS_NRC_REQUEST_SEQUENCE_ERROR;
    REQ(0x31, 0x02, 0x02, 0x01);
    EXPECT_NRC(0x31, UDS_NRC_REQUEST_SEQUENCE_ERROR);
    fk.routine_nrc = 0;
    REQ(0x31, 0x01, 0xFF, 0x00, 0x01);                 /* erase needs session + security */
    EXPECT_NRC(0x31, UDS_NRC_SERVICE_NOT_IN_SESSION);
    REQ(0x10, 0x03);
    REQ(0x31, 0x01, 0xFF, 0x00, 0x01);
    EXPECT_NRC(0x31, UDS_NRC_SECURITY_ACCESS_DENIED);
    unlock(UDS_SESSION_EXTENDED);
    REQ(0x31, 0x01, 0xFF, 0x00, 0x01);
    assert_int_equal(resp[0], 0x71);
    REQ(0x31, 0x81, 0x02, 0x01, 0x01);                 /* suppressed positive response */
    assert_int_equal(n, 0);
}

static void test_download_upload(void **state)
{
    (void)state;
    uint16_t n;
    REQ(0x34, 0x00, 0x11, 0x01, 0x10);
    EXPECT_NRC(0x34, UDS_NRC_SERVICE_NOT_IN_SESSION);
    REQ(0x10, 0x02);
    REQ(0x34, 0x00, 0x11, 0x01, 0x10);
    EXPECT_NRC(0x34, UDS_NRC_SECURITY_ACCESS_DENIED);
    unlock(UDS_SESSION_PROGRAMMING);
    REQ(0x34, 0x01, 0x11, 0x01, 0x10);
    EXPECT_NRC(0x34, UDS_NRC_REQUEST_OUT_OF_RANGE);    /* compression not supported */
    REQ(0x34, 0x00, 0x51, 0x01, 0x10);
    EXPECT_NRC(0x34, UDS_NRC_REQUEST_OUT_OF_RANGE);    /* 5-byte size field */
    REQ(0x34, 0x00, 0x12, 0x01, 0x10);
    EXPECT_NRC(0x34, UDS_NRC_INCORRECT_LENGTH);        /* alfi says 2 address bytes */
    fk.begin_nrc = UDS_NRC_UPLOAD_DOWNLOAD_NOT_ACCEPTED;
    REQ(0x34, 0x00, 0x11, 0x01, 0x10);
    EXPECT_NRC(0x34, UDS_NRC_UPLOAD_DOWNLOAD_NOT_ACCEPTED);
    fk.begin_nrc = 0;
    REQ(0x36, 0x01, 0xAA);
    EXPECT_NRC(0x36, UDS_NRC_REQUEST_SEQUENCE_ERROR);   /* no transfer */
    REQ(0x37);
    EXPECT_NRC(0x37, UDS_NRC_REQUEST_SEQUENCE_ERROR);
    /* 16 bytes into address 1 in two blocks */
    REQ(0x34, 0x00, 0x44, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00, 0x10);
    assert_int_equal(n, 4);
    const uint8_t expect[4] = {0x74, 0x20, 0x0F, 0xFF};
    assert_memory_equal(resp, expect, 4);
    assert_int_equal(fk.addr, 1);
    assert_int_equal(fk.size, 16);
    REQ(0x34, 0x00, 0x11, 0x01, 0x10);
    EXPECT_NRC(0x34, UDS_NRC_CONDITIONS_NOT_CORRECT);   /* one transfer at a time */
    REQ(0x36, 0x02, 1, 2, 3);
    EXPECT_NRC(0x36, UDS_NRC_WRONG_BLOCK_COUNTER);
    REQ(0x36, 0x01);
    EXPECT_NRC(0x36, UDS_NRC_INCORRECT_LENGTH);
    REQ(0x36, 0x01, 0, 1, 2, 3, 4, 5, 6, 7);
    assert_int_equal(n, 2);
    assert_int_equal(resp[0], 0x76);
    assert_int_equal(resp[1], 0x01);
    REQ(0x36, 0x01, 9, 9, 9, 9, 9, 9, 9, 9);            /* repeated block: acknowledged, not rewritten */
    assert_int_equal(resp[0], 0x76);
    assert_int_equal(fk.data_calls, 1);
    REQ(0x37);
    EXPECT_NRC(0x37, UDS_NRC_REQUEST_SEQUENCE_ERROR);   /* incomplete: aborted */
    assert_int_equal(fk.abort_calls, 1);
    assert_int_equal(fk.end_calls, 0);
    /* again, complete, with overflow attempt */
    REQ(0x34, 0x00, 0x11, 0x01, 0x10);
    REQ(0x36, 0x01, 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16);
    EXPECT_NRC(0x36, UDS_NRC_TRANSFER_SUSPENDED);       /* 17 bytes where 16 were announced */
    fk.data_nrc = UDS_NRC_PROGRAMMING_FAILURE;
    REQ(0x36, 0x01, 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
    EXPECT_NRC(0x36, UDS_NRC_PROGRAMMING_FAILURE);
    fk.data_nrc = 0;
    REQ(0x36, 0x01, 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
    assert_int_equal(resp[0], 0x76);
    fk.end_nrc = UDS_NRC_PROGRAMMING_FAILURE;          /* e.g. skill_parse refuses the image */
    REQ(0x37);
    EXPECT_NRC(0x37, UDS_NRC_PROGRAMMING_FAILURE);
    fk.end_nrc = 0;
    REQ(0x34, 0x00, 0x11, 0x01, 0x10);
    REQ(0x36, 0x01, 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
    REQ(0x37);
    assert_int_equal(n, 5);
    const uint8_t exit_ok[5] = {0x77, 0x11, 0x22, 0x33, 0x44};
    assert_memory_equal(resp, exit_ok, 5);
    /* read it back */
    REQ(0x35, 0x00, 0x11, 0x02, 0x10);
    EXPECT_NRC(0x35, UDS_NRC_REQUEST_OUT_OF_RANGE);     /* wrong address */
    REQ(0x35, 0x00, 0x11, 0x01, 0x10);
    assert_int_equal(resp[0], 0x75);
    REQ(0x36, 0x01, 0x00);
    EXPECT_NRC(0x36, UDS_NRC_INCORRECT_LENGTH);
    REQ(0x36, 0x01);
    assert_int_equal(n, 18);
    assert_int_equal(resp[0], 0x76);
    for (int i = 0; i < 16; i++) assert_int_equal(resp[2 + i], i);
    REQ(0x36, 0x02);
    EXPECT_NRC(0x36, UDS_NRC_REQUEST_SEQUENCE_ERROR);   /* nothing left */
    REQ(0x37);
    assert_int_equal(n, 1);
    assert_int_equal(resp[0], 0x77);
    /* transfers outside the programming session */
    REQ(0x10, 0x03);
    REQ(0x36, 0x01);
    EXPECT_NRC(0x36, UDS_NRC_SERVICE_NOT_IN_SESSION);
    REQ(0x37);
    EXPECT_NRC(0x37, UDS_NRC_SERVICE_NOT_IN_SESSION);
}

/* RequestTransferExit whose validation takes several ticks: 7F 37 78 at once, other requests
 * 7F SID 21 meanwhile, no repeat before UDS_PENDING_REPEAT_MS, then the final answer. */
static void test_transfer_exit_pending(void **state)
{
    (void)state;
    uint16_t n;
    unlock(UDS_SESSION_PROGRAMMING);
    REQ(0x34, 0x00, 0x11, 0x01, 0x04);
    assert_int_equal(n, 4);
    REQ(0x36, 0x01, 1, 2, 3, 4);
    assert_int_equal(n, 2);
    fk.end_nrc = UDS_NRC_RESPONSE_PENDING;
    REQ(0x37);
    EXPECT_NRC(0x37, UDS_NRC_RESPONSE_PENDING);
    assert_int_equal(srv.pending_sid, 0x37);
    REQ(0x3E, 0x00);
    EXPECT_NRC(0x3E, UDS_NRC_BUSY_REPEAT_REQUEST);
    n = uds_server_resume(&srv, resp, (uint16_t)sizeof(resp), 100u);
    assert_int_equal(n, 0);                                /* still working, no repeat yet */
    n = uds_server_resume(&srv, resp, (uint16_t)sizeof(resp), UDS_PENDING_REPEAT_MS + 1u);
    EXPECT_NRC(0x37, UDS_NRC_RESPONSE_PENDING);            /* repeated within P2* */
    fk.end_nrc = UDS_NRC_OK;
    n = uds_server_resume(&srv, resp, (uint16_t)sizeof(resp), UDS_PENDING_REPEAT_MS + 2u);
    assert_int_equal(n, 5);
    const uint8_t expect[5] = {0x77, 0x11, 0x22, 0x33, 0x44};
    assert_memory_equal(resp, expect, 5);
    assert_int_equal(srv.pending_sid, 0);
    assert_int_equal(fk.end_calls, 4);
    REQ(0x3E, 0x00);
    assert_int_equal(n, 2);
    /* a refusal after pending: the final answer is the NRC */
    REQ(0x34, 0x00, 0x11, 0x01, 0x04);
    REQ(0x36, 0x01, 1, 2, 3, 4);
    fk.end_nrc = UDS_NRC_RESPONSE_PENDING;
    REQ(0x37);
    fk.end_nrc = UDS_NRC_PROGRAMMING_FAILURE;
    n = uds_server_resume(&srv, resp, (uint16_t)sizeof(resp), 10u);
    EXPECT_NRC(0x37, UDS_NRC_PROGRAMMING_FAILURE);
    assert_int_equal(uds_server_resume(&srv, resp, (uint16_t)sizeof(resp), 20u), 0);
}

/* A sendKey or a DID write whose hook answers 0x78: 7F SID 78 at once, other requests 0x21
 * meanwhile, the resume hook asked each call with the level or DID, then the final response
 * (the level unlocked only then; a refusal's NRC as the final answer). */
static void test_security_and_write_pending(void **state)
{
    (void)state;
    uint16_t n;
    REQ(0x10, 0x03);
    REQ(0x27, 0x01);
    uint8_t key[6] = {0x27, 0x02};
    for (int i = 0; i < 4; i++) key[2 + i] = (uint8_t)(resp[2 + i] ^ 0xFFu);
    fk.key_nrc = UDS_NRC_RESPONSE_PENDING;
    fk.resume_left = 2u;
    fk.resume_nrc = UDS_NRC_OK;
    n = req(key, 6);
    EXPECT_NRC(0x27, UDS_NRC_RESPONSE_PENDING);
    assert_int_equal(srv.unlocked_level, 0);
    REQ(0x22, 0x01, 0x00);
    EXPECT_NRC(0x22, UDS_NRC_BUSY_REPEAT_REQUEST);
    assert_int_equal(uds_server_resume(&srv, resp, (uint16_t)sizeof resp, 1), 0);
    assert_int_equal(fk.resume_sid, 0x27);
    assert_int_equal(fk.resume_arg, 1);
    assert_int_equal(uds_server_resume(&srv, resp, (uint16_t)sizeof resp, 2), 0);
    assert_int_equal(srv.unlocked_level, 0);
    n = uds_server_resume(&srv, resp, (uint16_t)sizeof resp, 3);
    assert_int_equal(n, 2);
    assert_int_equal(resp[0], 0x67);
    assert_int_equal(resp[1], 0x02);
    assert_int_equal(srv.unlocked_level, 1);
    assert_int_equal(srv.pending_sid, 0);
    /* a DID write answered 0x78, refused at the end */
    fk.did_nrc = UDS_NRC_RESPONSE_PENDING;
    fk.resume_left = 0u;
    fk.resume_nrc = UDS_NRC_CONDITIONS_NOT_CORRECT;
    REQ(0x2E, 0x03, 0x02, 0xAA);
    EXPECT_NRC(0x2E, UDS_NRC_RESPONSE_PENDING);
    n = uds_server_resume(&srv, resp, (uint16_t)sizeof resp, 4);
    EXPECT_NRC(0x2E, UDS_NRC_CONDITIONS_NOT_CORRECT);
    assert_int_equal(fk.resume_arg, 0x0302);
    /* accepted at the end: 6E DID */
    fk.resume_nrc = UDS_NRC_OK;
    REQ(0x2E, 0x03, 0x02, 0xAA);
    n = uds_server_resume(&srv, resp, (uint16_t)sizeof resp, 5);
    assert_int_equal(n, 3);
    assert_int_equal(resp[0], 0x6E);
    assert_int_equal(resp[1], 0x03);
    assert_int_equal(resp[2], 0x02);
}

/* A routine start answered 0x78: the final response 71 01 RID from the resume hook (no status
 * record), or its refusal; stop and results are never pending. */
static void test_routine_start_pending(void **state)
{
    (void)state;
    uint16_t n;
    fk.routine_nrc = UDS_NRC_RESPONSE_PENDING;
    fk.resume_left = 1u;
    fk.resume_nrc = UDS_NRC_OK;
    REQ(0x31, 0x01, 0x02, 0x01, 0x01);
    EXPECT_NRC(0x31, UDS_NRC_RESPONSE_PENDING);
    assert_int_equal(srv.pending_sid, 0x31);
    assert_int_equal(uds_server_resume(&srv, resp, (uint16_t)sizeof resp, 1), 0);
    assert_int_equal(fk.resume_sid, 0x31);
    assert_int_equal(fk.resume_arg, 0x0201);
    n = uds_server_resume(&srv, resp, (uint16_t)sizeof resp, 2);
    assert_int_equal(n, 4);
    assert_int_equal(resp[0], 0x71);
    assert_int_equal(resp[1], 0x01);
    assert_int_equal(resp[2], 0x02);
    assert_int_equal(resp[3], 0x01);
    assert_int_equal(srv.pending_sid, 0);
    /* refused at the end with its NRC */
    fk.resume_nrc = UDS_NRC_REQUEST_OUT_OF_RANGE;
    REQ(0x31, 0x01, 0x02, 0x01, 0x01);
    EXPECT_NRC(0x31, UDS_NRC_RESPONSE_PENDING);
    n = uds_server_resume(&srv, resp, (uint16_t)sizeof resp, 3);
    EXPECT_NRC(0x31, UDS_NRC_REQUEST_OUT_OF_RANGE);
    /* a stop answered 0x78 is not kept pending */
    REQ(0x31, 0x02, 0x02, 0x01);
    EXPECT_NRC(0x31, UDS_NRC_RESPONSE_PENDING);
    assert_int_equal(srv.pending_sid, 0);
}

static void test_block_counter_wraps(void **state)
{
    (void)state;
    uint16_t n;
    unlock(UDS_SESSION_PROGRAMMING);
    REQ(0x34, 0x00, 0x21, 0x01, 0x01, 0x2C);           /* address 1, 300 bytes, 1 per block */
    assert_int_equal(resp[0], 0x74);
    uint8_t r[3] = {0x36, 0x01, 0};
    for (unsigned i = 1; i <= 300; i++) {
        r[1] = (uint8_t)i;                             /* 0xFF -> 0x00 -> 0x01 */
        r[2] = (uint8_t)(i * 3u);
        n = req(r, 3);
        if (n != 2) fprintf(stderr, "i=%u resp %02x %02x %02x\n", i, resp[0], resp[1], resp[2]);
        assert_int_equal(n, 2);
        assert_int_equal(resp[0], 0x76);
    }
    REQ(0x37);
    assert_int_equal(resp[0], 0x77);
    assert_int_equal(fk.store[299], (uint8_t)(300u * 3u));
}

static void test_tester_present(void **state)
{
    (void)state;
    uint16_t n;
    REQ(0x3E, 0x00);
    assert_int_equal(n, 2);
    assert_int_equal(resp[0], 0x7E);
    REQ(0x3E, 0x80);
    assert_int_equal(n, 0);
    REQ(0x3E, 0x01);
    EXPECT_NRC(0x3E, UDS_NRC_SUBFUNCTION_NOT_SUPPORTED);
    REQ(0x3E);
    EXPECT_NRC(0x3E, UDS_NRC_INCORRECT_LENGTH);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(test_unknown_service_and_empty, setup),
        cmocka_unit_test_setup(test_session_control, setup),
        cmocka_unit_test_setup(test_session_timeout_s3, setup),
        cmocka_unit_test_setup(test_ecu_reset, setup),
        cmocka_unit_test_setup(test_security_access, setup),
        cmocka_unit_test_setup(test_read_did, setup),
        cmocka_unit_test_setup(test_write_did, setup),
        cmocka_unit_test_setup(test_routine_control, setup),
        cmocka_unit_test_setup(test_download_upload, setup),
        cmocka_unit_test_setup(test_security_and_write_pending, setup),
        cmocka_unit_test_setup(test_routine_start_pending, setup),
        cmocka_unit_test_setup(test_block_counter_wraps, setup),
        cmocka_unit_test_setup(test_tester_present, setup),
        cmocka_unit_test_setup(test_transfer_exit_pending, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

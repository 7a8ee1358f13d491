/* UDS server (ISO 14229-1): session, security and transfer sequencing (see uds.h). */
#include "uds.h"

#include <string.h>

#include "fs_wire.h"

static uint16_t negative(uint8_t *resp, uint8_t sid, uint8_t nrc)
{
    resp[0] = UDS_NEGATIVE_RESPONSE;
    resp[1] = sid;
    resp[2] = nrc;
    return 3u;
}

static void xfer_abort(uds_server_t *srv)
{
    if (srv->xfer != UDS_XFER_NONE && srv->app.transfer_abort != NULL) {
        srv->app.transfer_abort(srv->app.ctx);
    }
    srv->xfer = UDS_XFER_NONE;
}

static void enter_session(uds_server_t *srv, uint8_t session)
{
    if (session != srv->session) {
        xfer_abort(srv);
    }
    srv->session = session;
    srv->unlocked_level = 0u; /* every session change locks (ISO 14229-1 9.4) */
    (void)memset(srv->seed_level, 0, sizeof srv->seed_level);
}

void uds_server_init(uds_server_t *srv, const uds_app_t *app)
{
    memset(srv, 0, sizeof(*srv));
    srv->app = *app;
    srv->session = UDS_SESSION_DEFAULT;
}

static uint16_t be16(const uint8_t *p)
{
    return (uint16_t)(((uint16_t)p[0] << 8) | p[1]);
}

static uint32_t be_n(const uint8_t *p, uint8_t n)
{
    uint32_t v = 0u;
    for (uint8_t i = 0; i < n; i++) {
        v = (v << 8) | p[i];
    }
    return v;
}

/* A hook answered 0x78: its final response is due from uds_server_resume. */
static void pend(uds_server_t *srv, uint8_t sid, uint16_t arg)
{
    srv->pending_sid = sid;
    srv->pending_arg = arg;
    srv->pending_since_ms = srv->last_request_ms;
}

/* ---- 0x10 ---- */
static uint16_t svc_dsc(uds_server_t *srv, const uint8_t *req, uint16_t len, uint8_t *resp)
{
    if (len != 2u) {
        return negative(resp, req[0], UDS_NRC_INCORRECT_LENGTH);
    }
    const uint8_t sub = (uint8_t)(req[1] & 0x7Fu);
    if (sub != UDS_SESSION_DEFAULT && sub != UDS_SESSION_PROGRAMMING &&
        sub != UDS_SESSION_EXTENDED) {
        return negative(resp, req[0], UDS_NRC_SUBFUNCTION_NOT_SUPPORTED);
    }
    if (srv->app.session_allowed != NULL) {
        const uint8_t nrc = srv->app.session_allowed(srv->app.ctx, sub);
        if (nrc != UDS_NRC_OK) {
            return negative(resp, req[0], nrc);
        }
    }
    enter_session(srv, sub);
    if ((req[1] & UDS_SUPPRESS_POS) != 0u) {
        return 0u;
    }
    resp[0] = (uint8_t)(req[0] + 0x40u);
    resp[1] = sub;
    resp[2] = (uint8_t)(UDS_P2_MS >> 8);
    resp[3] = (uint8_t)(UDS_P2_MS & 0xFFu);
    resp[4] = (uint8_t)((UDS_P2_STAR_MS / 10u) >> 8); /* P2* in units of 10 ms */
    resp[5] = (uint8_t)((UDS_P2_STAR_MS / 10u) & 0xFFu);
    return 6u;
}

/* ---- 0x11 ---- */
static uint16_t svc_reset(uds_server_t *srv, const uint8_t *req, uint16_t len, uint8_t *resp)
{
    if (len != 2u) {
        return negative(resp, req[0], UDS_NRC_INCORRECT_LENGTH);
    }
    const uint8_t sub = (uint8_t)(req[1] & 0x7Fu);
    if (sub != 0x01u && sub != 0x03u) {
        return negative(resp, req[0], UDS_NRC_SUBFUNCTION_NOT_SUPPORTED);
    }
    if (srv->app.ecu_reset == NULL) {
        return negative(resp, req[0], UDS_NRC_CONDITIONS_NOT_CORRECT);
    }
    const uint8_t nrc = srv->app.ecu_reset(srv->app.ctx, sub);
    if (nrc != UDS_NRC_OK) {
        return negative(resp, req[0], nrc);
    }
    srv->pending_reset = sub;
    if ((req[1] & UDS_SUPPRESS_POS) != 0u) {
        return 0u;
    }
    resp[0] = (uint8_t)(req[0] + 0x40u);
    resp[1] = sub;
    return 2u;
}

/* ---- 0x27 ---- */
static uint16_t svc_security(uds_server_t *srv, const uint8_t *req, uint16_t len, uint8_t *resp,
                             uint16_t cap)
{
    if (len < 2u) {
        return negative(resp, req[0], UDS_NRC_INCORRECT_LENGTH);
    }
    const uint8_t sub = (uint8_t)(req[1] & 0x7Fu);
    const uint8_t t = (srv->tester < UDS_TESTERS) ? srv->tester : 0u; /* each its own seed */
    const bool is_seed = (sub & 1u) != 0u;
    const uint8_t level = is_seed ? sub : (uint8_t)(sub - 1u);
    if (level != UDS_SEC_LEVEL_WRITE && level != UDS_SEC_LEVEL_FIRMWARE) {
        return negative(resp, req[0], UDS_NRC_SUBFUNCTION_NOT_SUPPORTED);
    }
    if (srv->session == UDS_SESSION_DEFAULT) {
        return negative(resp, req[0], UDS_NRC_SERVICE_NOT_IN_SESSION);
    }
    if (level == UDS_SEC_LEVEL_FIRMWARE && srv->session != UDS_SESSION_PROGRAMMING) {
        return negative(resp, req[0], UDS_NRC_SUBFUNCTION_NOT_IN_SESSION);
    }
    if (srv->app.security_seed == NULL || srv->app.security_key == NULL) {
        return negative(resp, req[0], UDS_NRC_CONDITIONS_NOT_CORRECT);
    }
    resp[0] = (uint8_t)(req[0] + 0x40u);
    resp[1] = sub;
    if (is_seed) {
        if (len != 2u) {
            return negative(resp, req[0], UDS_NRC_INCORRECT_LENGTH);
        }
        if (srv->unlocked_level == level) {
            /* already unlocked: a zero seed (ISO 14229-1 9.4.2) */
            memset(&resp[2], 0, 4u);
            return 6u;
        }
        uint16_t seed_len = 0u;
        const uint8_t nrc = srv->app.security_seed(srv->app.ctx, level, &resp[2],
                                                   (uint16_t)(cap - 2u), &seed_len);
        if (nrc != UDS_NRC_OK) {
            srv->seed_level[t] = 0u;
            return negative(resp, req[0], nrc);
        }
        srv->seed_level[t] = level;
        return (uint16_t)(2u + seed_len);
    }
    if (len < 3u) {
        return negative(resp, req[0], UDS_NRC_INCORRECT_LENGTH);
    }
    if (srv->seed_level[t] != level) {
        return negative(resp, req[0], UDS_NRC_REQUEST_SEQUENCE_ERROR);
    }
    srv->seed_level[t] = 0u; /* one key per seed */
    const uint8_t nrc = srv->app.security_key(srv->app.ctx, level, &req[2], (uint16_t)(len - 2u));
    if (nrc == UDS_NRC_RESPONSE_PENDING) {
        pend(srv, req[0], level);
    }
    if (nrc != UDS_NRC_OK) {
        return negative(resp, req[0], nrc);
    }
    srv->unlocked_level = level;
    return 2u;
}

/* ---- 0x22 ---- */
static uint16_t svc_rdbi(uds_server_t *srv, const uint8_t *req, uint16_t len, uint8_t *resp,
                         uint16_t cap)
{
    if (len < 3u || (len - 1u) % 2u != 0u) {
        return negative(resp, req[0], UDS_NRC_INCORRECT_LENGTH);
    }
    uint16_t pos = 0u;
    resp[pos++] = (uint8_t)(req[0] + 0x40u);
    for (uint16_t i = 1u; i + 1u < len; i = (uint16_t)(i + 2u)) {
        const uint16_t did = be16(&req[i]);
        if ((uint16_t)(pos + 2u) > cap) {
            return negative(resp, req[0], UDS_NRC_RESPONSE_TOO_LONG);
        }
        resp[pos] = req[i];
        resp[pos + 1u] = req[i + 1u];
        uint16_t n = 0u;
        const uint8_t nrc = srv->app.read_did(srv->app.ctx, did, &resp[pos + 2u],
                                              (uint16_t)(cap - pos - 2u), &n);
        if (nrc != UDS_NRC_OK) {
            return negative(resp, req[0], nrc);
        }
        pos = (uint16_t)(pos + 2u + n);
    }
    return pos;
}

/* ---- 0x2E ---- */
static uint16_t svc_wdbi(uds_server_t *srv, const uint8_t *req, uint16_t len, uint8_t *resp)
{
    if (len < 4u) {
        return negative(resp, req[0], UDS_NRC_INCORRECT_LENGTH);
    }
    if (srv->session == UDS_SESSION_DEFAULT) {
        return negative(resp, req[0], UDS_NRC_SERVICE_NOT_IN_SESSION);
    }
    const uint16_t did = be16(&req[1]);
    if (srv->unlocked_level != UDS_SEC_LEVEL_WRITE) {
        return negative(resp, req[0], UDS_NRC_SECURITY_ACCESS_DENIED);
    }
    const uint8_t nrc = srv->app.write_did(srv->app.ctx, did, &req[3], (uint16_t)(len - 3u));
    if (nrc == UDS_NRC_RESPONSE_PENDING) {
        pend(srv, req[0], did);
    }
    if (nrc != UDS_NRC_OK) {
        return negative(resp, req[0], nrc);
    }
    resp[0] = (uint8_t)(req[0] + 0x40u);
    resp[1] = req[1];
    resp[2] = req[2];
    return 3u;
}

/* ---- 0x31 ---- */
static uint16_t svc_routine(uds_server_t *srv, const uint8_t *req, uint16_t len, uint8_t *resp,
                            uint16_t cap)
{
    if (len < 4u) {
        return negative(resp, req[0], UDS_NRC_INCORRECT_LENGTH);
    }
    const uint8_t sub = (uint8_t)(req[1] & 0x7Fu);
    if (sub != UDS_ROUTINE_START && sub != UDS_ROUTINE_STOP && sub != UDS_ROUTINE_RESULTS) {
        return negative(resp, req[0], UDS_NRC_SUBFUNCTION_NOT_SUPPORTED);
    }
    const uint16_t rid = be16(&req[2]);
    if (rid == UDS_RID_ERASE_SLOT && srv->session == UDS_SESSION_DEFAULT) {
        return negative(resp, req[0], UDS_NRC_SERVICE_NOT_IN_SESSION);
    }
    if (rid == UDS_RID_ERASE_SLOT && srv->unlocked_level != UDS_SEC_LEVEL_WRITE) {
        return negative(resp, req[0], UDS_NRC_SECURITY_ACCESS_DENIED);
    }
    uint16_t n = 0u;
    const uint8_t nrc = srv->app.routine(srv->app.ctx, sub, rid, &req[4], (uint16_t)(len - 4u),
                                         &resp[4], (uint16_t)(cap - 4u), &n);
    if (nrc == UDS_NRC_RESPONSE_PENDING && sub == UDS_ROUTINE_START) {
        pend(srv, req[0], rid); /* the final response (no status record) from the resume hook */
    }
    if (nrc != UDS_NRC_OK) {
        return negative(resp, req[0], nrc);
    }
    if ((req[1] & UDS_SUPPRESS_POS) != 0u) {
        return 0u;
    }
    resp[0] = (uint8_t)(req[0] + 0x40u);
    resp[1] = sub;
    resp[2] = req[2];
    resp[3] = req[3];
    return (uint16_t)(4u + n);
}

/* Answer of RequestDownload/RequestUpload: the transfer set up and a positive response with
 * the block length, or the NRC (0x78 included). */
static uint16_t transfer_answer(uds_server_t *srv, uint8_t sid, uint8_t nrc, uint32_t size,
                                uint8_t *resp)
{
    if (nrc != UDS_NRC_OK) {
        return negative(resp, sid, nrc);
    }
    srv->xfer = sid == UDS_SID_REQ_DOWNLOAD ? UDS_XFER_DOWNLOAD : UDS_XFER_UPLOAD;
    srv->xfer_size = size;
    srv->xfer_pos = 0u;
    srv->xfer_counter = 1u;
    srv->xfer_last_len = 0u;
    resp[0] = (uint8_t)(sid + 0x40u);
    const uint32_t block = sid == UDS_SID_REQ_DOWNLOAD ? UDS_MAX_BLOCK_LENGTH
                                                       : UDS_UPLOAD_BLOCK_LENGTH;
    resp[1] = 0x20u; /* lengthFormatIdentifier: 2-byte maxNumberOfBlockLength */
    resp[2] = (uint8_t)(block >> 8);
    resp[3] = (uint8_t)(block & 0xFFu);
    return 4u;
}

/* ---- 0x34 / 0x35 ---- */
static uint16_t svc_request_transfer(uds_server_t *srv, const uint8_t *req, uint16_t len,
                                     uint8_t *resp)
{
    if (len < 3u) {
        return negative(resp, req[0], UDS_NRC_INCORRECT_LENGTH);
    }
    if (srv->session != UDS_SESSION_PROGRAMMING) {
        return negative(resp, req[0], UDS_NRC_SERVICE_NOT_IN_SESSION);
    }
    const uint8_t dfi = req[1];
    const uint8_t size_len = (uint8_t)(req[2] >> 4);
    const uint8_t addr_len = (uint8_t)(req[2] & 0x0Fu);
    if (size_len < 1u || size_len > 4u || addr_len < 1u || addr_len > 4u) {
        return negative(resp, req[0], UDS_NRC_REQUEST_OUT_OF_RANGE);
    }
    if (len != (uint16_t)(3u + size_len + addr_len)) {
        return negative(resp, req[0], UDS_NRC_INCORRECT_LENGTH);
    }
    const bool download = req[0] == UDS_SID_REQ_DOWNLOAD;
    if (download && srv->unlocked_level == 0u) {
        return negative(resp, req[0], UDS_NRC_SECURITY_ACCESS_DENIED);
    }
    if (dfi != 0x00u) {
        return negative(resp, req[0], UDS_NRC_REQUEST_OUT_OF_RANGE); /* no compression/encryption */
    }
    if (srv->xfer != UDS_XFER_NONE) {
        return negative(resp, req[0], UDS_NRC_CONDITIONS_NOT_CORRECT); /* one transfer at a time */
    }
    const uint32_t addr = be_n(&req[3], addr_len);
    const uint32_t size = be_n(&req[3u + addr_len], size_len);
    const uint8_t nrc = download ? srv->app.download_begin(srv->app.ctx, addr, size)
                                 : srv->app.upload_begin(srv->app.ctx, addr, size);
    if (nrc == UDS_NRC_RESPONSE_PENDING && !download) {
        srv->pending_sid = req[0]; /* uds_server_resume asks upload_begin again */
        srv->pending_since_ms = srv->last_request_ms;
        srv->pending_addr = addr;
        srv->pending_size = size;
    }
    return transfer_answer(srv, req[0], nrc, size, resp);
}

/* ---- 0x36 ---- */
/* Answer of a TransferData download block: the block counted and a positive response, or the
 * NRC (0x78 included). */
static uint16_t data_answer(uds_server_t *srv, uint8_t nrc, uint8_t counter, uint16_t n,
                            uint8_t *resp)
{
    if (nrc != UDS_NRC_OK) {
        return negative(resp, UDS_SID_TRANSFER_DATA, nrc);
    }
    srv->xfer_pos += n;
    srv->xfer_last_len = n;
    srv->xfer_counter = (uint8_t)(srv->xfer_counter + 1u);
    resp[0] = (uint8_t)(UDS_SID_TRANSFER_DATA + 0x40u);
    resp[1] = counter;
    return 2u;
}

static uint16_t svc_transfer_data(uds_server_t *srv, const uint8_t *req, uint16_t len,
                                  uint8_t *resp, uint16_t cap)
{
    if (len < 2u) {
        return negative(resp, req[0], UDS_NRC_INCORRECT_LENGTH);
    }
    if (srv->session != UDS_SESSION_PROGRAMMING) {
        return negative(resp, req[0], UDS_NRC_SERVICE_NOT_IN_SESSION);
    }
    if (srv->xfer == UDS_XFER_NONE) {
        return negative(resp, req[0], UDS_NRC_REQUEST_SEQUENCE_ERROR);
    }
    const uint8_t counter = req[1];
    const uint8_t previous = (uint8_t)(srv->xfer_counter - 1u);
    const bool repeat = srv->xfer_last_len != 0u && counter == previous;
    if (counter != srv->xfer_counter && !repeat) {
        return negative(resp, req[0], UDS_NRC_WRONG_BLOCK_COUNTER);
    }
    resp[0] = (uint8_t)(req[0] + 0x40u);
    resp[1] = counter;
    if (srv->xfer == UDS_XFER_DOWNLOAD) {
        const uint16_t n = (uint16_t)(len - 2u);
        if (n == 0u || n > UDS_MAX_BLOCK_LENGTH - 2u) {
            return negative(resp, req[0], UDS_NRC_INCORRECT_LENGTH);
        }
        if (repeat) {
            return 2u; /* block already written: acknowledge again (ISO 14229-1 14.5) */
        }
        if (srv->xfer_pos + n > srv->xfer_size) {
            return negative(resp, req[0], UDS_NRC_TRANSFER_SUSPENDED); /* more than announced */
        }
        const uint8_t nrc = srv->app.download_data(srv->app.ctx, srv->xfer_pos, &req[2], n);
        if (nrc == UDS_NRC_RESPONSE_PENDING) {
            srv->pending_sid = req[0]; /* uds_server_resume asks download_data (data NULL) again */
            srv->pending_since_ms = srv->last_request_ms;
            srv->pending_addr = counter;
            srv->pending_size = n;
        }
        return data_answer(srv, nrc, counter, n, resp);
    }
    /* upload */
    if (len != 2u) {
        return negative(resp, req[0], UDS_NRC_INCORRECT_LENGTH);
    }
    uint32_t offset = srv->xfer_pos;
    if (repeat) {
        offset -= srv->xfer_last_len;
    } else if (srv->xfer_pos >= srv->xfer_size) {
        return negative(resp, req[0], UDS_NRC_REQUEST_SEQUENCE_ERROR); /* all data sent */
    }
    uint32_t n = srv->xfer_size - offset;
    if (n > UDS_UPLOAD_BLOCK_LENGTH - 2u) {
        n = UDS_UPLOAD_BLOCK_LENGTH - 2u;
    }
    if (n > (uint32_t)cap - 2u) {
        n = (uint32_t)cap - 2u;
    }
    const uint8_t nrc = srv->app.upload_data(srv->app.ctx, offset, &resp[2], (uint16_t)n);
    if (nrc != UDS_NRC_OK) {
        return negative(resp, req[0], nrc);
    }
    if (!repeat) {
        srv->xfer_pos += n;
        srv->xfer_last_len = (uint16_t)n;
        srv->xfer_counter = (uint8_t)(srv->xfer_counter + 1u);
    }
    resp[0] = (uint8_t)(req[0] + 0x40u);
    resp[1] = counter;
    return (uint16_t)(2u + n);
}

/* ---- 0x37 ---- */
/* Answer of RequestTransferExit: positive with the image's CRC-32, or the NRC. */
static uint16_t exit_answer(uint8_t *resp, uint8_t nrc, uint32_t crc)
{
    if (nrc != UDS_NRC_OK) {
        return negative(resp, UDS_SID_TRANSFER_EXIT, nrc);
    }
    resp[0] = (uint8_t)(UDS_SID_TRANSFER_EXIT + 0x40u);
    const fs_wire_transfer_exit_t v = {crc};
    return (uint16_t)(1u + fs_wire_transfer_exit_pack(&v, &resp[1], FS_WIRE_TRANSFER_EXIT_LEN));
}

static uint16_t svc_transfer_exit(uds_server_t *srv, const uint8_t *req, uint8_t *resp)
{
    if (srv->session != UDS_SESSION_PROGRAMMING) {
        return negative(resp, req[0], UDS_NRC_SERVICE_NOT_IN_SESSION);
    }
    if (srv->xfer == UDS_XFER_NONE) {
        return negative(resp, req[0], UDS_NRC_REQUEST_SEQUENCE_ERROR);
    }
    if (srv->xfer_pos != srv->xfer_size) {
        xfer_abort(srv);
        return negative(resp, req[0], UDS_NRC_REQUEST_SEQUENCE_ERROR); /* incomplete */
    }
    resp[0] = (uint8_t)(req[0] + 0x40u);
    if (srv->xfer == UDS_XFER_UPLOAD) {
        srv->xfer = UDS_XFER_NONE;
        return 1u;
    }
    uint32_t crc = 0u;
    srv->xfer = UDS_XFER_NONE;
    const uint8_t nrc = srv->app.download_end(srv->app.ctx, &crc);
    if (nrc == UDS_NRC_RESPONSE_PENDING) {
        pend(srv, req[0], 0u);
    }
    return exit_answer(resp, nrc, crc);
}

/* ---- 0x3E ---- */
static uint16_t svc_tester_present(const uint8_t *req, uint16_t len, uint8_t *resp)
{
    if (len != 2u) {
        return negative(resp, req[0], UDS_NRC_INCORRECT_LENGTH);
    }
    if ((req[1] & 0x7Fu) != 0x00u) {
        return negative(resp, req[0], UDS_NRC_SUBFUNCTION_NOT_SUPPORTED);
    }
    if ((req[1] & UDS_SUPPRESS_POS) != 0u) {
        return 0u;
    }
    resp[0] = (uint8_t)(req[0] + 0x40u);
    resp[1] = 0x00u;
    return 2u;
}

uint16_t uds_server_handle(uds_server_t *srv, const uint8_t *req, uint16_t len, uint8_t *resp,
                           uint16_t resp_cap, uint32_t now_ms)
{
    if (len == 0u || resp_cap < 8u) {
        return 0u;
    }
    srv->last_request_ms = now_ms;
    if (srv->pending_sid != 0u) {
        return negative(resp, req[0], UDS_NRC_BUSY_REPEAT_REQUEST); /* one request at a time */
    }
    switch (req[0]) {
    case UDS_SID_DSC: return svc_dsc(srv, req, len, resp);
    case UDS_SID_ECU_RESET: return svc_reset(srv, req, len, resp);
    case UDS_SID_SECURITY: return svc_security(srv, req, len, resp, resp_cap);
    case UDS_SID_RDBI: return svc_rdbi(srv, req, len, resp, resp_cap);
    case UDS_SID_WDBI: return svc_wdbi(srv, req, len, resp);
    case UDS_SID_ROUTINE: return svc_routine(srv, req, len, resp, resp_cap);
    case UDS_SID_REQ_DOWNLOAD:
    case UDS_SID_REQ_UPLOAD: return svc_request_transfer(srv, req, len, resp);
    case UDS_SID_TRANSFER_DATA: return svc_transfer_data(srv, req, len, resp, resp_cap);
    case UDS_SID_TRANSFER_EXIT: return svc_transfer_exit(srv, req, resp);
    case UDS_SID_TESTER_PRESENT: return svc_tester_present(req, len, resp);
    default: return negative(resp, req[0], UDS_NRC_SERVICE_NOT_SUPPORTED);
    }
}

void uds_server_after_response(uds_server_t *srv)
{
    if (srv->pending_reset != 0u) {
        const uint8_t type = srv->pending_reset;
        srv->pending_reset = 0u;
        xfer_abort(srv);
        enter_session(srv, UDS_SESSION_DEFAULT);
        if (srv->app.reset_now != NULL) {
            srv->app.reset_now(srv->app.ctx, type);
        }
    }
}

/* The final response of a pending sendKey, DID write or routine start (nrc from the resume
 * hook). */
static uint16_t resumed_answer(uds_server_t *srv, uint8_t sid, uint8_t nrc, uint8_t *resp)
{
    if (nrc != UDS_NRC_OK) {
        return negative(resp, sid, nrc);
    }
    resp[0] = (uint8_t)(sid + 0x40u);
    if (sid == UDS_SID_SECURITY) {
        srv->unlocked_level = (uint8_t)srv->pending_arg;
        resp[1] = (uint8_t)(srv->pending_arg + 1u); /* the sendKey subfunction */
        return 2u;
    }
    uint16_t n = 1u;
    if (sid == UDS_SID_ROUTINE) {
        resp[n++] = UDS_ROUTINE_START;
    }
    resp[n++] = (uint8_t)(srv->pending_arg >> 8); /* the DID or the routine's id */
    resp[n++] = (uint8_t)srv->pending_arg;
    return n;
}

uint16_t uds_server_resume(uds_server_t *srv, uint8_t *resp, uint16_t resp_cap, uint32_t now_ms)
{
    const uint8_t sid = srv->pending_sid;
    const bool hook = sid == UDS_SID_TRANSFER_EXIT || sid == UDS_SID_REQ_UPLOAD ||
                      sid == UDS_SID_TRANSFER_DATA ||
                      ((sid == UDS_SID_SECURITY || sid == UDS_SID_WDBI || sid == UDS_SID_ROUTINE) &&
                       srv->app.resume != NULL);
    if (!hook || resp_cap < 8u) {
        srv->pending_sid = 0u;
        return 0u;
    }
    uint32_t crc = 0u;
    uint8_t nrc;
    if (sid == UDS_SID_TRANSFER_EXIT) {
        nrc = srv->app.download_end(srv->app.ctx, &crc);
    } else if (sid == UDS_SID_REQ_UPLOAD) {
        nrc = srv->app.upload_begin(srv->app.ctx, srv->pending_addr, srv->pending_size);
    } else if (sid == UDS_SID_TRANSFER_DATA) {
        nrc = srv->app.download_data(srv->app.ctx, srv->xfer_pos, NULL,
                                     (uint16_t)srv->pending_size);
    } else {
        nrc = srv->app.resume(srv->app.ctx, sid, srv->pending_arg);
    }
    srv->last_request_ms = now_ms; /* the session stays while the server works */
    if (nrc == UDS_NRC_RESPONSE_PENDING) {
        if ((uint32_t)(now_ms - srv->pending_since_ms) < UDS_PENDING_REPEAT_MS) {
            return 0u;
        }
        srv->pending_since_ms = now_ms;
        return negative(resp, sid, nrc);
    }
    srv->pending_sid = 0u;
    if (sid == UDS_SID_TRANSFER_DATA) {
        return data_answer(srv, nrc, (uint8_t)srv->pending_addr, (uint16_t)srv->pending_size, resp);
    }
    if (sid == UDS_SID_TRANSFER_EXIT) {
        return exit_answer(resp, nrc, crc);
    }
    if (sid == UDS_SID_REQ_UPLOAD) {
        return transfer_answer(srv, sid, nrc, srv->pending_size, resp);
    }
    return resumed_answer(srv, sid, nrc, resp);
}

void uds_server_poll(uds_server_t *srv, uint32_t now_ms)
{
    if (uds_server_session_expired(srv, now_ms)) {
        xfer_abort(srv);
        enter_session(srv, UDS_SESSION_DEFAULT);
    }
}

/* UDS server (ISO 14229-1) over one ISO-TP link. The server checks sessions, security, lengths
 * and transfer sequencing; everything device-specific (data identifiers, routines, slot
 * storage, seed/key, reset) is delegated to the application through uds_app_t, which answers
 * with 0 (positive) or a negative response code. Every refusal is a specific NRC, never silence
 * (except when the request suppresses the positive response, ISO 14229 bit 0x80).
 *
 * Services: 0x10 DiagnosticSessionControl, 0x11 ECUReset, 0x27 SecurityAccess,
 * 0x22/0x2E Read/WriteDataByIdentifier, 0x31 RoutineControl, 0x34 RequestDownload,
 * 0x35 RequestUpload, 0x36 TransferData, 0x37 RequestTransferExit, 0x3E TesterPresent.
 * Session rules (docs/protocol.md): 0x2E, 0x27 need a non-default session; 0x34-0x37 need the
 * programming session. Security levels, each with its own secret: 0x2E and slot erase need level
 * 1 (UDS_SEC_LEVEL_WRITE); 0x34 needs a level unlocked and the application checks which one the
 * address needs (skill slot: 1, firmware: 3); firmware routines check level 3 themselves. */
#ifndef UDS_H
#define UDS_H

#include <stdbool.h>
#include <stdint.h>
#include "fs_budget.h"
#include "fs_uds_ids.h"
#include "uds_nrc.h"

/* Service identifiers */
#define UDS_SID_DSC 0x10u
#define UDS_SID_ECU_RESET 0x11u
#define UDS_SID_SECURITY 0x27u
#define UDS_SID_RDBI 0x22u
#define UDS_SID_WDBI 0x2Eu
#define UDS_SID_ROUTINE 0x31u
#define UDS_SID_REQ_DOWNLOAD 0x34u
#define UDS_SID_REQ_UPLOAD 0x35u
#define UDS_SID_TRANSFER_DATA 0x36u
#define UDS_SID_TRANSFER_EXIT 0x37u
#define UDS_SID_TESTER_PRESENT 0x3Eu
#define UDS_NEGATIVE_RESPONSE 0x7Fu
#define UDS_SUPPRESS_POS 0x80u

/* Negative response codes (UDS_NRC_*): uds_nrc.h, generated from firmware/base/codes.toml. */

/* Sessions */
#define UDS_SESSION_DEFAULT 0x01u
#define UDS_SESSION_PROGRAMMING 0x02u
#define UDS_SESSION_EXTENDED 0x03u

/* Routine control sub-functions. The device's security levels (requestSeed sub-function; sendKey
 * is level + 1) and routine identifiers are in fs_uds_ids.h. */
#define UDS_ROUTINE_START 0x01u
#define UDS_ROUTINE_STOP 0x02u
#define UDS_ROUTINE_RESULTS 0x03u

/* Timing reported in the DSC response and enforced by the server */
#define UDS_P2_MS 50u
#define UDS_P2_STAR_MS 5000u
#define UDS_S3_MS 5000u             /* non-default session falls back after this silence */
#define UDS_PENDING_REPEAT_MS 2000u /* 0x78 repeated well within P2* */

/* Transfer block size announced in 0x74/0x75 responses: bytes per 0x36 request incl. SID and
 * counter; fits one ISO-TP message. */
#define UDS_MAX_BLOCK_LENGTH 4095u
/* The same for an upload, UDS_UPLOAD_BLOCK_LENGTH (fs_budget.h; 0x75's answer, each 0x36
 * response at most this long): a smaller block bounds the copies of one TransferData answer,
 * which the Cortex-M images serve inside a 1 ms tick. */

/** Device hooks. Each returns UDS_NRC_OK or a negative response code. Output buffers have the
 *  capacity given; *out_len receives the bytes written. */
typedef struct {
    void *ctx;
    uint8_t (*read_did)(void *ctx, uint16_t did, uint8_t *out, uint16_t cap, uint16_t *out_len);
    /** Write a DID; called only in a non-default session with level UDS_SEC_LEVEL_WRITE. */
    uint8_t (*write_did)(void *ctx, uint16_t did, const uint8_t *data, uint16_t len);
    /** RoutineControl; sub is 1 start, 2 stop, 3 results. */
    uint8_t (*routine)(void *ctx, uint8_t sub, uint16_t rid, const uint8_t *data, uint16_t len,
                       uint8_t *out, uint16_t cap, uint16_t *out_len);
    /** May the session change now (e.g. refused while executing)? */
    uint8_t (*session_allowed)(void *ctx, uint8_t session);
    /** Check an ECU reset (1 hard, 3 soft); the reset itself happens in reset_now after the
     *  positive response has been sent. */
    uint8_t (*ecu_reset)(void *ctx, uint8_t type);
    void (*reset_now)(void *ctx, uint8_t type);
    /** Security: produce a seed for level, then check a key (the module keeps attempt counters
     *  and delays; it answers 0x35, 0x36 or 0x37). */
    uint8_t (*security_seed)(void *ctx, uint8_t level, uint8_t *seed, uint16_t cap, uint16_t *len);
    uint8_t (*security_key)(void *ctx, uint8_t level, const uint8_t *key, uint16_t len);
    /** A sendKey (security_key), a DID write (write_did) or a routine start (routine)
     *  answered UDS_NRC_RESPONSE_PENDING goes on: sid with its level, DID or routine id. The
     *  server answers 7F SID 78 first, calls this from uds_server_resume until it returns
     *  anything else, then gives the final response (a routine's without a status record). */
    uint8_t (*resume)(void *ctx, uint8_t sid, uint16_t arg);
    /** Download of size bytes into memory/slot address addr (0x34): accept or refuse. */
    uint8_t (*download_begin)(void *ctx, uint32_t addr, uint32_t size);
    /** A block of the download at offset. UDS_NRC_RESPONSE_PENDING: the application kept the
     *  block and writes it in slices; the server answers 7F 36 78 and calls download_data again
     *  with data NULL (same offset and len) from uds_server_resume until it returns anything
     *  else. */
    uint8_t (*download_data)(void *ctx, uint32_t offset, const uint8_t *data, uint16_t len);
    /** End of transfer: validate (e.g. skill_parse) and commit; on refusal keep the old data.
     *  UDS_NRC_RESPONSE_PENDING: the validation goes on; the server answers 7F 37 78 and calls
     *  download_end again from uds_server_resume until it returns anything else. */
    uint8_t (*download_end)(void *ctx, uint32_t *crc32_out);
    void (*transfer_abort)(void *ctx);
    /** Upload of size bytes from addr (0x35). UDS_NRC_RESPONSE_PENDING: the read-back goes on;
     *  the server answers 7F 35 78 and calls upload_begin again with the same arguments from
     *  uds_server_resume until it returns anything else. */
    uint8_t (*upload_begin)(void *ctx, uint32_t addr, uint32_t size);
    uint8_t (*upload_data)(void *ctx, uint32_t offset, uint8_t *out, uint16_t len);
} uds_app_t;

#define UDS_TESTERS 2u /* request ids served (the application's tester index: srv->tester) */

typedef enum {
    UDS_XFER_NONE = 0,
    UDS_XFER_DOWNLOAD = 1,
    UDS_XFER_UPLOAD = 2
} uds_xfer_t;

/** Server state. */
typedef struct {
    uds_app_t app;
    uint8_t session;
    uint8_t unlocked_level; /* 0: locked, else the level unlocked */
    uint8_t tester;         /* the tester (request id index) of the request being handled */
    uint8_t seed_level[UDS_TESTERS]; /* per tester: the level whose seed awaits a key, 0: none */
    uint32_t last_request_ms;
    uds_xfer_t xfer;
    uint32_t xfer_size;
    uint32_t xfer_pos;
    uint8_t xfer_counter;      /* counter expected next */
    uint16_t xfer_last_len;    /* length of the last accepted block (for a repeated counter) */
    uint8_t pending_reset;     /* reset type to perform after the response, 0 if none */
    uint8_t pending_sid;       /* request answered 0x78 whose final response is due, 0 if none */
    uint16_t pending_arg;      /* its SecurityAccess level or DID (0x27, 0x2E) */
    uint32_t pending_since_ms; /* when 0x78 was last sent */
    uint32_t pending_addr;     /* answered 0x78: RequestUpload's address and size, or ... */
    uint32_t pending_size;     /* ... TransferData's block counter and length */
} uds_server_t;

/** Initialise in the default session, locked, no transfer. */
void uds_server_init(uds_server_t *srv, const uds_app_t *app);

/** Handle one request; writes the response (positive or 7F SID NRC) into resp and returns its
 *  length (0: no response, suppressed). resp_cap must be >= 3. */
uint16_t uds_server_handle(uds_server_t *srv, const uint8_t *req, uint16_t len, uint8_t *resp,
                           uint16_t resp_cap, uint32_t now_ms);

/** Call once the response has been transmitted (ISO 14229-1: the positive response of ECUReset
 *  precedes the reset; the application waits until its transport and CAN queue are empty):
 *  performs a pending ECU reset. srv->pending_reset != 0 tells that one is waiting. */
void uds_server_after_response(uds_server_t *srv);

/** A request answered with 0x78 (srv->pending_sid != 0): asks the application again and writes
 *  the final response into resp (returns its length), or, while still pending, a repeated
 *  7F SID 78 every UDS_PENDING_REPEAT_MS (else returns 0). Call every tick while pending and the
 *  transport is free. Meanwhile other requests are answered 0x21 busyRepeatRequest. */
uint16_t uds_server_resume(uds_server_t *srv, uint8_t *resp, uint16_t resp_cap, uint32_t now_ms);

/** Session timeout (S3): back to default, locked, transfer aborted. Call every tick (or when
 *  uds_server_session_expired). */
void uds_server_poll(uds_server_t *srv, uint32_t now_ms);

/** True if the session expired at now_ms (a non-default session past S3: uds_server_poll has work). Inline: asked
 *  every tick. */
static inline bool uds_server_session_expired(const uds_server_t *srv, uint32_t now_ms)
{
    return srv->session != UDS_SESSION_DEFAULT &&
           (uint32_t)(now_ms - srv->last_request_ms) > UDS_S3_MS;
}

/** A tester's RequestDownload of size bytes to addr (no compression or encryption, a 4-byte
 *  address and size) into out; returns its length, UDS_REQ_DOWNLOAD_LEN. */
#define UDS_REQ_DOWNLOAD_LEN 11u
static inline uint16_t uds_request_download(uint8_t out[UDS_REQ_DOWNLOAD_LEN], uint32_t addr,
                                            uint32_t size)
{
    out[0] = UDS_SID_REQ_DOWNLOAD;
    out[1] = 0x00u;
    out[2] = 0x44u;
    for (uint32_t i = 0u; i < 4u; i++) {
        out[3u + i] = (uint8_t)(addr >> (24u - 8u * i));
        out[7u + i] = (uint8_t)(size >> (24u - 8u * i));
    }
    return (uint16_t)UDS_REQ_DOWNLOAD_LEN;
}

#endif /* UDS_H */

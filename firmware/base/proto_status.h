/* Status codes: Protocol: E2E protection, ISO-TP.
 * generated from firmware/base/codes.toml by tools/gen_codes.py; do not edit. */
#ifndef PROTO_STATUS_H
#define PROTO_STATUS_H

/** Protocol: E2E protection, ISO-TP (4xx). */
typedef enum {
    PROTO_OK = 0,
    PROTO_ERR_E2E_CRC = 400,          /* safety frame CRC-8 mismatch */
    PROTO_ERR_E2E_COUNTER = 401,      /* rolling counter repeated (stale or replayed frame) */
    PROTO_ERR_DLC = 402,              /* frame shorter than its DBC length */
    PROTO_ERR_ISOTP_TIMEOUT_BS = 410, /* sender: no flow control within N_Bs */
    PROTO_ERR_ISOTP_TIMEOUT_CR = 411, /* receiver: no consecutive frame within N_Cr */
    PROTO_ERR_ISOTP_WRONG_SN = 412,   /* receiver: consecutive frame out of sequence */
    /* message longer than the buffer (FC overflow sent/received) */
    PROTO_ERR_ISOTP_OVERFLOW = 413,
    /* frame type not valid in the current state (ignored/aborted) */
    PROTO_ERR_ISOTP_UNEXPECTED = 414,
    PROTO_ERR_ISOTP_BUSY = 415,       /* a transmission is already in progress */
    PROTO_ERR_ISOTP_WFT = 416,        /* too many FC WAIT frames */
    PROTO_ERR_ISOTP_FORMAT = 417,     /* malformed PCI (length 0, SF too long, reserved type) */
    /* a UDS payload of a length its record (wire.toml) does not allow */
    PROTO_ERR_WIRE_LENGTH = 418,
    PROTO_ERR_WIRE_RANGE = 419,       /* a UDS payload field outside its range (wire.toml) */
} proto_status_t;

#endif /* PROTO_STATUS_H */

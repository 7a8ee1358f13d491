/* CAN identifiers of one node (docs/protocol.md): id = base + node, node 0..15. The DBC
 * (forceskill.dbc) lists the cyclic frames for node 0; the generated FS_DBC_*_FRAME_ID are the bases. */
#ifndef PROTO_IDS_H
#define PROTO_IDS_H

#include <stdint.h>
#include "fs_dbc.h"

#define PROTO_NODE_MAX 15u
#define PROTO_DEFAULT_NODE 0u

#define PROTO_ID_EMERGENCY(node)   (FS_DBC_EMERGENCY_FRAME_ID + (uint32_t)(node))
#define PROTO_ID_HOST_COMMAND(node) (FS_DBC_HOST_COMMAND_FRAME_ID + (uint32_t)(node))
#define PROTO_ID_HOST_HEARTBEAT(node) (FS_DBC_HOST_HEARTBEAT_FRAME_ID + (uint32_t)(node))
#define PROTO_ID_STATUS(node)      (FS_DBC_DEVICE_STATUS_FRAME_ID + (uint32_t)(node))
#define PROTO_ID_TELEM_POS(node)   (FS_DBC_TELEMETRY_POSITION_FRAME_ID + (uint32_t)(node))
#define PROTO_ID_TELEM_FORCE(node) (FS_DBC_TELEMETRY_FORCE_FRAME_ID + (uint32_t)(node))
#define PROTO_ID_UDS_REQUEST(node)  (0x600u + (uint32_t)(node))   /* host -> device (ISO-TP) */
#define PROTO_ID_UDS_RESPONSE(node) (0x680u + (uint32_t)(node))   /* device -> host (ISO-TP) */

/** Protocol status codes (the 4xx range of fs_status.h). */
typedef enum {
    PROTO_OK = 0,
    PROTO_ERR_E2E_CRC = 400,        /* safety frame CRC-8 mismatch */
    PROTO_ERR_E2E_COUNTER = 401,    /* rolling counter repeated (stale or replayed frame) */
    PROTO_ERR_DLC = 402,            /* frame shorter than its DBC length */
    PROTO_ERR_ISOTP_TIMEOUT_BS = 410, /* sender: no flow control within N_Bs */
    PROTO_ERR_ISOTP_TIMEOUT_CR = 411, /* receiver: no consecutive frame within N_Cr */
    PROTO_ERR_ISOTP_WRONG_SN = 412, /* receiver: consecutive frame out of sequence */
    PROTO_ERR_ISOTP_OVERFLOW = 413, /* message longer than the buffer (FC overflow sent/received) */
    PROTO_ERR_ISOTP_UNEXPECTED = 414, /* frame type not valid in the current state (ignored/aborted) */
    PROTO_ERR_ISOTP_BUSY = 415,     /* a transmission is already in progress */
    PROTO_ERR_ISOTP_WFT = 416,      /* too many FC WAIT frames */
    PROTO_ERR_ISOTP_FORMAT = 417,   /* malformed PCI (length 0, SF too long, reserved type) */
} proto_status_t;

#endif /* PROTO_IDS_H */

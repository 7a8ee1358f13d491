/* CAN identifiers of one node: id = base + node, node 0..PROTO_NODE_MAX (docs/codes.md);
 * the DBC lists the cyclic frames of node 0 with the same bases.
 * generated from firmware/base/codes.toml by tools/gen_codes.py; do not edit. */
#ifndef PROTO_IDS_H
#define PROTO_IDS_H

#include <stdint.h>
#include "proto_status.h"

#define PROTO_NODE_MAX 15u
#define PROTO_DEFAULT_NODE 0u

#define PROTO_ID_EMERGENCY(node) (0x080u + (uint32_t)(node)) /* device: once on every new fault */
/* host: one command per valid frame */
#define PROTO_ID_HOST_COMMAND(node) (0x100u + (uint32_t)(node))
/* host: heartbeat while it drives the device */
#define PROTO_ID_HOST_HEARTBEAT(node) (0x110u + (uint32_t)(node))
#define PROTO_ID_STATUS(node) (0x180u + (uint32_t)(node)) /* device: status every 10 ms */
#define PROTO_ID_TELEM_POS(node) (0x190u + (uint32_t)(node)) /* device: telemetry, position part */
#define PROTO_ID_TELEM_FORCE(node) (0x1A0u + (uint32_t)(node)) /* device: telemetry, force part */
/* host -> device UDS request (ISO-TP) */
#define PROTO_ID_UDS_REQUEST(node) (0x600u + (uint32_t)(node))
/* device -> host UDS response (ISO-TP) */
#define PROTO_ID_UDS_RESPONSE(node) (0x680u + (uint32_t)(node))
/* second tester -> device UDS request (ISO-TP) */
#define PROTO_ID_UDS_REQUEST_2(node) (0x640u + (uint32_t)(node))
/* device -> second tester UDS response (ISO-TP) */
#define PROTO_ID_UDS_RESPONSE_2(node) (0x6C0u + (uint32_t)(node))

#endif /* PROTO_IDS_H */

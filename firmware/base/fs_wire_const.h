/* The values the device and the host share (docs/protocol.md).
 * generated from firmware/base/wire.toml by tools/gen_codes.py; do not edit. */
#ifndef FS_WIRE_CONST_H
#define FS_WIRE_CONST_H

/* One step of every scaled wire field (goal, time and path scales, durations): value =
 * count * FS_WIRE_SCALE; also the factor of the DBC's HostCommand scales. */
#define FS_WIRE_SCALE 0.001
#define FS_WIRE_SCALE_STEPS 1000u /* counts per unit, 1 / FS_WIRE_SCALE */

/* skill slots of a device, numbered 1..SLOT_COUNT (UDS addresses, HostCommand.Slot) */
#define FS_SLOT_COUNT 8u
/* control tick period in microseconds (the device runs at 1 kHz) */
#define FS_TICK_US 1000u
#define FS_TICK_S 0.001 /* FS_TICK_US in seconds */
/* steps of a RUN_SEQUENCE start at most */
#define FS_SEQUENCE_STEPS_MAX 8u
/* default |force command| limit force_max_N of each axis */
#define FS_FORCE_LIMIT_N 50.0
/* default skill stiffness limit (DID 0x0140) of a dynamics-compensated drive */
#define FS_STIFFNESS_MAX_NPM 500000.0
/* default skill stiffness limit of a carriage rendered by admittance */
#define FS_STIFFNESS_MAX_RENDERED_NPM 30000.0
/* highest stiffness a skill may declare and DID 0x0140 may be set to */
#define FS_STIFFNESS_CEILING_NPM 100000000.0
/* DID 0x0201: a download is in progress */
#define FS_TRANSFER_IN_PROGRESS 65535u
/* DID 0x0201: the last download was interrupted or its commit refused */
#define FS_TRANSFER_INTERRUPTED 65534u
/* DID 0x0201: no download since power-up */
#define FS_TRANSFER_NONE 65533u
/* firmware image target id: Cortex-M4F (qemu mps2-an386) */
#define FS_TARGET_CORTEX_M4F 1u
/* firmware image target id: Cortex-M3 (qemu mps2-an385) */
#define FS_TARGET_CORTEX_M3 2u
/* firmware image target id: the host port (simulator) */
#define FS_TARGET_HOST 3u

#endif /* FS_WIRE_CONST_H */

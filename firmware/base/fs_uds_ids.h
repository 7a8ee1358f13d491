/* UDS identifiers of the device: data identifiers (0x22/0x2E), routine identifiers (0x31),
 * security levels (0x27) and the firmware download address (0x34).
 * generated from firmware/base/codes.toml by tools/gen_codes.py; do not edit. */
#ifndef FS_UDS_IDS_H
#define FS_UDS_IDS_H

#define DID_SW_VERSION 0xF189u         /* software version, ASCII */
/* proto major, minor, skill format, max kernels u16, slots u8 */
#define DID_VERSIONS 0xF1A0u
#define DID_GAINS_X 0x0100u            /* gains x: m_d, k_d, k_p, k_f, k_i (f32 x5) */
#define DID_GAINS_Y 0x0101u            /* gains y */
/* limits x: force_max, slew_max, pos_min, pos_max, vel_max, contact_max */
#define DID_LIMITS_X 0x0110u
#define DID_LIMITS_Y 0x0111u           /* limits y */
#define DID_COMM 0x0120u               /* telemetry period ms u8, host timeout ms u16 */
#define DID_OBJECT 0x0130u             /* use_model u8, m_v, d_v, k1, k2, layer, surface (f32 x6) */
/* n u8; per slot: valid u8, length u32, crc u32, N u16, T f32, end u8 */
#define DID_SLOT_DIR 0x0200u
#define DID_LAST_TRANSFER 0x0201u      /* status code u16 of the last download (0 ok) */
#define DID_DEVICE_STATE 0x0300u       /* state u8, fault u16, slot u8, step u8, tick u32 */
/* highest nominal skill stiffness the device accepts, N/m (f32) */
#define DID_STIFFNESS_MAX 0x0140u
/* latched mask u32, causes present mask u32 (bit n: fault 500+n) */
#define DID_FAULT_CAUSES 0x0301u
/* write: host nonce (16 bytes) establishes the motion key; read: device nonce (16), keyed u8,
 * key confirmation u32 */
#define DID_MOTION_KEY 0x0302u
/* authenticated host frames: accepted, wrong MAC, replay, no key, keys discarded u32; last
 * refusal u16; keyed u8; FV command, FV heartbeat u32 */
#define DID_AUTH_STATS 0x0303u
/* contact wait of the running or last execution: hold ms u32, losses u16, phase rate u16 (1e-3) */
#define DID_CONTACT_WAIT 0x0304u
/* band check of the running or last execution: checked, outside, longest ms u32; largest
 * excursion u16 (1e-3 band widths); first excursion ms u32; outside now u8; stop ms u16 */
#define DID_BAND 0x0305u
#define FWU_DID_STATUS 0xF1B0u         /* update status: FWU_STATUS_LEN bytes, see fwu_status() */

/* start: slot u8, goal_scale u16 (1e-3), time_scale u16 (1e-3), end u8 */
#define UDS_RID_RUN_SKILL 0x0201u
/* start: end u8, then per step slot u8, goal u16, time u16, duration_ms u32 */
#define UDS_RID_RUN_SEQUENCE 0x0202u
#define UDS_RID_SELF_TEST 0x0203u      /* start: runs the checks; results: status u8, code u16 */
/* start: clear latched faults (refused while a cause persists) */
#define UDS_RID_CLEAR_FAULTS 0x0204u
#define UDS_RID_ERASE_SLOT 0xFF00u     /* start: slot u8 (security level 1) */
#define FWU_RID_MARK_TEST 0x0F01u      /* start; option u8: bit 0 allow downgrade */
#define FWU_RID_CONFIRM 0x0F02u        /* start; the running image confirms itself */

#define UDS_SEC_LEVEL_WRITE 0x01u      /* skills, gains, limits: extended or programming session */
#define UDS_SEC_LEVEL_FIRMWARE 0x03u   /* firmware images: programming session only */

#define FWU_DOWNLOAD_ADDRESS 0xF0000000u /* RequestDownload memoryAddress of "the inactive slot" */

#endif /* FS_UDS_IDS_H */

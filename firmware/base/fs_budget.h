/* The per-tick budgets of the firmware's long and bus work, for every image, in one table: how
 * much of a job (fs_job.h) or of the bus's work one tick may do beside the control path. Each
 * figure keeps a tick with that work within its image's budget (the M4F 3,000 instructions, the
 * M3 8,000; bench/qemu_tick.sh measures them); the host build (hil_sim, the tests) takes large
 * slices where a PC's tick has room.
 *
 * The build names the image's column (firmware/CMakeLists.txt, firmware/app/CMakeLists.txt):
 *   FS_BUDGET_M4F, FS_BUDGET_M3   the Cortex-M images (FS_CORTEX_TARGET)
 *   FS_BUDGET_SLOTS_F32, _FX      the skill store of the float32 and the fixed-point application
 *                                 builds (their executors' cost), in the images and on the host
 *   none                          the host build */
#ifndef FS_BUDGET_H
#define FS_BUDGET_H

#if defined(FS_BUDGET_M4F) || defined(FS_BUDGET_M3)
#define FS_BUDGET_MCU 1
#endif

/* ---------------------------------------------------------------- CAN and UDS (firmware/app) */

/* CAN frames drained from the controller per tick (each stamped; the rest wait a tick). */
#define APP_RX_FRAMES_PER_TICK 64u
/* ISO-TP frames (both links) queued per tick: a long response's consecutive frames leave at the
 * bus's pace (the MPS2 port sends 9 a tick), not 32 encoded and queued in one tick. */
#define APP_TP_FRAMES_PER_TICK 9u
/* ISO-TP frames queued in a tick that verified a frame's MAC (~850 instructions on the M4F) or
 * did the UDS server's work (a request served, a job's slice: a read-back block's copy, ~250),
 * at ~90 instructions a consecutive frame's encode and queue: the two together within the
 * tick's budget. The answer's own first frame counts in this share. */
#define APP_TP_FRAMES_BUSY_TICK 3u
#ifdef FS_BUDGET_MCU
/* ISO-TP frames queued in an EXECUTE tick (a read-back during a run): the control path and a
 * run's frames take ~1,500-1,650 instructions on the M4F, a frame ~150 (3 put the M4F's worst
 * such tick at 2,313, 5 with a block's copy at 3,346) ... */
#define APP_TP_FRAMES_EXEC_TICK 2u
/* ... and none in an EXECUTE tick that verified a MAC or did the server's work (the control path
 * and either one take the budget; the frames leave in the next tick without such work, so a bus
 * flooded with frames to verify holds a read-back during a run). */
#define APP_TP_FRAMES_EXEC_BUSY_TICK 0u
#else
#define APP_TP_FRAMES_EXEC_TICK 5u
#define APP_TP_FRAMES_EXEC_BUSY_TICK 3u
#endif
/* AES rounds of MAC verification a tick (secoc_verify_run: an AES-128 block is 10 rounds, ~620
 * instructions on the M4F; a frame that fails takes a second block, its replay check), the
 * rounds a verification's start counts for (the frame's copy, the freshness value, the CMAC's
 * subkey and first block: ~220 instructions on the M4F, three rounds' and their call) and the
 * verifications started a tick. The host build verifies every frame the bus can carry in a tick
 * within that tick (8 frames of a start and two blocks); on the Cortex-M images a start is a
 * tick's whole share, the rounds 4 a tick, one start a tick (a start and 4 rounds in one tick put
 * the M4F's worst EXECUTE tick at 2,191, a whole block beside EXECUTE's work at 3,230; 3 rounds a
 * tick, a frame acting a tick later, 2,037 rather than 2,063). */
#define APP_MAC_BEGIN_ROUNDS 4u
#ifdef FS_BUDGET_MCU
#define APP_MAC_ROUNDS_PER_TICK 4u
#define APP_MAC_FRAMES_PER_TICK 1u
#else
#define APP_MAC_FRAMES_PER_TICK 8u
#define APP_MAC_ROUNDS_PER_TICK (APP_MAC_FRAMES_PER_TICK * (APP_MAC_BEGIN_ROUNDS + 20u))
#endif
/* Bytes of a read-back's TransferData answer (0x75's block length, SID and counter included):
 * the block's copies (~0.9 instructions a byte on the M4F) fit a tick beside EXECUTE's work. */
#ifdef FS_BUDGET_MCU
#define UDS_UPLOAD_BLOCK_LENGTH 258u
#else
#define UDS_UPLOAD_BLOCK_LENGTH UDS_MAX_BLOCK_LENGTH
#endif

/* ---------------------------------------------------------------- security (firmware/app) */

/* SHA-256 rounds per tick of a SecurityAccess key check or a motion key derivation (four
 * compressions of 64 rounds, answered 0x78 first): ~40-65 instructions a round on the M4F, a
 * stage's end (padding, digest, wipes) in a call of its own after a call that compressed; 33
 * ticks in all. */
#define APP_SEC_ROUNDS_PER_TICK 8u
/* Units of the SecurityAccess record's flash write a tick (nvm_write_run: the erase's start or a
 * poll, a piece programmed or read back, NVM_SLICE_BYTES of the CRC or the scan). */
#define APP_SEC_FLASH_UNITS_PER_TICK 1u

/* ---------------------------------------------------------------- firmware update (firmware/boot) */

/* Bytes of a TransferData block programmed and added to the image's CRC-32 per call of
 * fwu_uds_download_data (one call a tick while the block is answered 0x78; the image's header is
 * taken whole whatever the size): ~600 instructions for 64 bytes on the M4F (the CRC ~5 a byte,
 * the programming ~4), beside a tick's status and telemetry frames, the UART's bytes and a
 * heartbeat's arrival (96 bytes put the M4F's worst FWUPDATE tick at 2,200). */
#ifdef FS_BUDGET_MCU
#define FWU_DATA_BYTES_PER_CALL 64u
#else
#define FWU_DATA_BYTES_PER_CALL 128u
#endif
/* SHA-256 compression rounds of the image's verification per call of fwu_uds_download_end (one
 * call a tick while the transfer exit is answered 0x78): 16 rounds, a quarter block, at most ~870
 * instructions on the M4F (docs/cortex-m.md). */
#define FWU_VERIFY_ROUNDS_PER_CALL 16u

/* ---------------------------------------------------------------- the skill store (firmware/app) */

/* Payload bytes a unit of a record's read (nvm_read_run: a CRC-32 at ~4 instructions a byte and
 * a copy) reads and checks: a read-back during a run within a tick (on the M4F 64 put that tick
 * at 3,530). */
#if defined(FS_BUDGET_M4F)
#define NVM_READ_CHUNK 32u
#elif defined(FS_BUDGET_M3)
#define NVM_READ_CHUNK 64u
#else
#define NVM_READ_CHUNK 128u
#endif
/* Kernels of a parse unit's model derivation (skill_parse_run's dmp_model_init pass), and of a
 * periodic model's (a sine, a cosine, a square root and an arcsine a kernel): on the M3 (software
 * float) a kernel is ~300 instructions of divisions and products. */
#ifdef FS_BUDGET_M3
#define SKILL_PARSE_INIT_KERNELS 4u
#define SKILL_PARSE_INIT_PERIODIC_KERNELS 1u
#else
#define SKILL_PARSE_INIT_KERNELS 8u
#define SKILL_PARSE_INIT_PERIODIC_KERNELS 2u
#endif
/* The parse units a unit of a periodic model's reach pass counts for (an arcsine and a square
 * root a kernel: ~2,500 instructions in software float, the M3's two units a tick of them 6,349):
 * one reach unit a tick where a tick takes two units. */
#define SKILL_PARSE_REACH_UNITS 2u
/* The slices of a download's commit and of a read-back, per tick while the host waits (0x78):
 *   SLOTS_PARSE_UNITS_PER_TICK    units of the image's parse (skill_parse_run: one kernel's
 *                                 value, 32 bytes of the CRC; at most ~450 instructions, M4F)
 *   SLOTS_PARAMS_UNITS_PER_TICK   units of the parameter check (skchk_params_run: the scalars,
 *                                 SKCHK_PARAMS_KERNELS_PER_UNIT kernels; ~180 instructions)
 *   SLOTS_CONVERT_UNITS_PER_TICK  units of the skill's conversion to fixed point (the
 *                                 fixed-point build: dmpfx_bound_run, one kernel or one window)
 *   SLOTS_CHECK_STEPS_PER_TICK    DMP steps of the skill's own rollout (skill_check.h: ~480
 *                                 instructions on the M4F; dmpfx_check_run on the M3, ~1,000)
 *   SLOTS_FLASH_UNITS_PER_TICK    units of the slot's flash write (nvm_write_run: the erase, the
 *                                 commit word, NVM_SLICE_BYTES of the CRC or the final scan, or
 *                                 NVM_CHUNK bytes programmed or read back; ~700 instructions)
 *   SLOTS_READ_UNITS_PER_TICK     units of a read-back's record read (nvm_read_run: its header
 *                                 or NVM_READ_CHUNK bytes) while RequestUpload waits
 *   SLOTS_SWAP_BYTES_PER_TICK     bytes of the checked skill copied into the slot's cache once
 *                                 its record is written (the whole skill_t in one tick was 5,096
 *                                 instructions of memcpy on the M4F)
 * The M3 converts 1 unit and checks 3 steps a tick: commit ticks 3,953 / 6,526 / 12,569 over 923
 * ticks for the bench's 2 s skill, within the 2 s after which the device repeats its 0x78. The
 * host build: a PC's tick has room, and an upload over the simulated bus is not slowed by ~40
 * ticks of parse and write. */
#if defined(FS_BUDGET_SLOTS_FX)
#define SLOTS_PARSE_UNITS_PER_TICK 2u
#define SLOTS_PARAMS_UNITS_PER_TICK 2u
#define SLOTS_CONVERT_UNITS_PER_TICK 1u
#define SLOTS_CHECK_STEPS_PER_TICK 3u
#define SLOTS_FLASH_UNITS_PER_TICK 1u
#define SLOTS_SWAP_BYTES_PER_TICK 1024u
#elif defined(FS_BUDGET_SLOTS_F32)
#define SLOTS_PARSE_UNITS_PER_TICK 1u
#define SLOTS_PARAMS_UNITS_PER_TICK 4u
#define SLOTS_CONVERT_UNITS_PER_TICK 8u
#define SLOTS_CHECK_STEPS_PER_TICK 2u
#define SLOTS_FLASH_UNITS_PER_TICK 1u
#define SLOTS_SWAP_BYTES_PER_TICK 1024u
#else
#define SLOTS_PARSE_UNITS_PER_TICK 1024u
#define SLOTS_PARAMS_UNITS_PER_TICK UINT32_MAX
#define SLOTS_CONVERT_UNITS_PER_TICK 8u
#define SLOTS_CHECK_STEPS_PER_TICK 100u
#define SLOTS_FLASH_UNITS_PER_TICK 64u
#define SLOTS_SWAP_BYTES_PER_TICK 1048576u
#endif
#define SLOTS_READ_UNITS_PER_TICK 1u

#endif /* FS_BUDGET_H */

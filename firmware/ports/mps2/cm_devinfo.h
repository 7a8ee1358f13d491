/* The device-unique area of the Cortex-M port: the last 4 KiB of the board's PSRAM (cm_board.h),
 * outside every flash region the application programs or erases, written once when the board is
 * provisioned (`hil_sim pil` when it creates the board's flash file) and only read by the image.
 * It holds one SecurityAccess secret per level (hal_device_secret). Little-endian layout:
 *   u32 magic "FSDI", u32 version 1,
 *   per level (1, then 3): u8 length 1..CM_DEVINFO_SECRET_MAX, then CM_DEVINFO_SECRET_MAX bytes.
 * An erased area (no magic) is an unprovisioned device: every level's secret is unknown (length
 * 0) and SecurityAccess refuses. Shared by the image (cm_hal.c) and hil_sim (sim_pil.c). */
#ifndef CM_DEVINFO_H
#define CM_DEVINFO_H

#define CM_DEVINFO_ADDR 0x21FFF000u   /* CM_PSRAM_BASE + CM_PSRAM_SIZE - 4 KiB */
#define CM_DEVINFO_OFFSET 0x00FFF000u /* the same from the start of the PSRAM */
#define CM_DEVINFO_SIZE 4096u
#define CM_DEVINFO_MAGIC 0x49445346u /* "FSDI" */
#define CM_DEVINFO_VERSION 1u
#define CM_DEVINFO_SECRET_MAX 64u
#define CM_DEVINFO_LEVELS 2u /* level 1 (skills), level 3 (firmware) */
#define CM_DEVINFO_SECRET_OFF(i) (8u + (i) * (1u + CM_DEVINFO_SECRET_MAX))

#endif /* CM_DEVINFO_H */

/* The Cortex-M port of firmware/hal/hal.h on qemu's MPS2 boards (docs/cortex-m.md): CAN over
 * UART0 in SLCAN (cm_slcan.h, cm_uart.h), time from the 1 kHz SysTick, flash in the PSRAM
 * (NOR semantics), the CMSDK watchdog, reset by SYSRESETREQ. Sensors and actuator are the
 * board's sensor/actuator side (cm_plant.h). This header is the port's own part beyond hal.h,
 * used by the image's main loop (mps2_main.c). */
#ifndef CM_PORT_H
#define CM_PORT_H

#include <stdbool.h>
#include <stdint.h>
#include "hal.h"

#define CM_PORT_TICK_HZ 1000u
#define CM_PORT_WDG_TIMEOUT_MS 200u
/* Pacing (cm_port_wait_tick): iterations of an empty loop between two reads of the host's clock,
 * ~8 us of the board's time (4 instructions each at 250 MIPS) */
#define CM_PORT_PACE_SPIN 500u
/* Bytes of SLCAN text the UART takes per tick: 192 = 8.7 frames of 8 bytes per ms, the frame rate
 * of a 1 Mbit/s CAN bus (~7.4 frames per ms) with a margin, i.e. a 1.92 Mbaud UART; the budget is
 * given anew at the end of each tick (cm_port_end_tick), so the bytes that waited for it arrive in
 * the slack after the tick rather than in bulk inside the next one. The emulated UART has no baud
 * rate: while a tick runs, the port lets it take at most CM_PORT_RX_BYTES_IN_TICK bytes, what a
 * 1.92 Mbaud line delivers during the longest tick the budget allows (bench/qemu_tick.sh: 3,000
 * instructions at 168 MHz on the M4F = 17.9 us -> 3.4 bytes; 8,000 at 72 MHz on the M3 = 111 us
 * -> 21.3 bytes), rounded up, plus the byte already waiting in the data register: 5 and 23. The
 * RX interrupt only stores bytes in the UART's ring (cm_uart.c, a few instructions a byte). The
 * port's loop parses the text after the tick (cm_port_end_tick, CM_PORT_RX_CHUNK bytes at a time,
 * while the 256-frame queue has room for a chunk's commands: a backlog waits in the ring, then in
 * the UART and the host's socket, no frame is dropped): the emulated CAN controller's work,
 * outside app_tick as a CAN peripheral's is. hal_can_receive hands the tick at most
 * CM_PORT_RX_FRAMES_PER_TICK frames (9: the budget's 8.7 frames of 8 bytes a millisecond, so the
 * queue does not grow at the link's full rate). */
#define CM_PORT_RX_BYTES_PER_TICK 192u
#ifndef CM_PORT_RX_BYTES_IN_TICK
#define CM_PORT_RX_BYTES_IN_TICK 5u
#endif
#define CM_PORT_RX_FRAMES_PER_TICK 9u
#define CM_PORT_RX_CHUNK 32u
/* The transmit side likewise: a queue of CM_PORT_TX_QUEUE frames (hal_can_send refuses when it is
 * full, as a CAN controller's mailboxes do), of which up to CM_PORT_TX_FRAMES_PER_TICK leave per
 * tick. */
#define CM_PORT_TX_QUEUE 32u
#define CM_PORT_TX_FRAMES_PER_TICK 9u /* watchdog: NMI after this, board reset after twice */

/* Flash map in the PSRAM (cm_board.h): the skill slots (hal_flash), the firmware update
 * region (hal_fw_flash: boot state, slot A, slot B), the geometry of the host port, and the
 * SecurityAccess record (hal_sec_flash); the device-unique area is cm_devinfo.h. */
#define CM_FLASH_SKILL_ADDR 0x21000000u
#define CM_FLASH_SKILL_SECTOR 8192u
#define CM_FLASH_SKILL_SECTORS 16u
#define CM_FLASH_FW_ADDR 0x21100000u
#define CM_FLASH_FW_SECTOR 4096u
#define CM_FLASH_FW_SLOT_SECTORS 64u
#define CM_FLASH_FW_SECTORS (2u + 2u * CM_FLASH_FW_SLOT_SECTORS)
/* hal_sec_flash: two sectors of the SecurityAccess attempt record */
#define CM_FLASH_SEC_ADDR 0x21200000u
#define CM_FLASH_SEC_SECTOR 4096u

/** Start the port: UART and SLCAN, flash, random seed (from seed, seed_len bytes). */
void cm_port_init(const uint8_t *seed, uint32_t seed_len);

/** Start the SysTick at CM_PORT_TICK_HZ and the watchdog (after the application's init). pace:
 *  the emulator's clock runs free (qemu -icount sleep=off), so hold each tick until the host's
 *  clock (semihosting) has reached the device's time. */
void cm_port_start_ticks(bool pace);

/** SysTicks that found the previous one still pending while the core slept (the emulator's
 *  clock caught up with the host's after the host descheduled it; not an overrun). */
uint32_t cm_port_skipped(void);

/** Core clock cycles since the SysTick started (wraps every 172 s; differences are exact). */
uint32_t cm_port_cycles(void);

/** Sleep until the next SysTick; returns true if the previous tick overran (a SysTick arrived
 *  while it was running). */
bool cm_port_wait_tick(void);

/** End of one tick: feed the watchdog; perform a requested reset (hal_request_reset). */
void cm_port_end_tick(void);

/** Ticks that started late (a SysTick arrived while a tick was still running). */
uint32_t cm_port_overruns(void);
/** Received frames lost because the port's receive queue was full (none: the parse waits). */
uint32_t cm_port_rx_dropped(void);

/** The sample hal_sensors_read returns during the coming tick (the plant's sense fills it). */
hal_sensors_t *cm_port_sensors(void);

/** The actuator's command as the last tick left it (hal_actuator_enable, hal_actuator_force):
 *  each axis' force into force_N (0 while disabled); true while the power stage is enabled. */
bool cm_port_actuator(fs_real_t force_N[HAL_AXES]);


/** Empty functions around the application tick, which bench/qemu_tick.sh finds in the exec trace
 *  to count the instructions of each tick (no other effect). */
void cm_port_mark_begin(void);

/** See cm_port_mark_begin. */
void cm_port_mark_end(void);

/** Empty functions called after cm_port_mark_end, one per kind of tick, so the trace tells which
 *  kind the counted tick was: IDLE, TEACH, EXECUTE, a skill transfer (download, commit or
 *  read-back, in any state), a firmware download (through its transfer exit), FAULT (the tick
 *  that latched it and the ramp after), anything else. */
void cm_port_mark_idle(void);

/** See cm_port_mark_idle. */
void cm_port_mark_teach(void);

/** See cm_port_mark_idle. */
void cm_port_mark_execute(void);

/** See cm_port_mark_idle. */
void cm_port_mark_upload(void);

/** See cm_port_mark_idle. */
void cm_port_mark_fwupdate(void);

/** See cm_port_mark_idle. */
void cm_port_mark_fault(void);

/** See cm_port_mark_idle. */
void cm_port_mark_other(void);

#endif /* CM_PORT_H */

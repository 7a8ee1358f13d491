/* Host port of the HAL (hal.h): what a Linux process needs to run the device firmware.
 * Common part (hal_host.c): time (monotonic clock, or driven by the simulator), random bytes
 * (getrandom), a RAM flash for the slots (fls_ram), the device secret, sensor and actuator
 * mailboxes filled/read by whoever owns the hardware or the plant, and the reset request.
 * CAN backends, one per library:
 *   hal_can_sim.c        queues exchanged with the simulator's bus (hil_sim/bus)
 *   hal_can_socketcan.c  Linux SocketCAN raw socket (driver cansock.h), libsocketcan for
 *                        bitrate/restart */
#ifndef HAL_HOST_H
#define HAL_HOST_H

#include <stdbool.h>
#include <stdint.h>
#include "hal.h"

#define HAL_HOST_FLASH_SECTOR \
    65536u /* one skill record of N = 1024 with the y DMP (32,924 B + 36 B) fits */
#define HAL_HOST_FLASH_SECTORS 16u /* 2 copies x 8 slots */
#define HAL_HOST_FW_SECTOR 4096u   /* firmware flash: boot state + 2 slots of 64 sectors */
#define HAL_HOST_FW_SLOT_SECTORS 64u
#define HAL_HOST_FW_SECTORS (2u + 2u * HAL_HOST_FW_SLOT_SECTORS)
#define HAL_HOST_SECRET_DEFAULT \
    "forceskill-simulator-secret-0001" /* level 1, 32 bytes, docs/protocol.md */
#define HAL_HOST_FW_SECRET_DEFAULT "forceskill-simulator-fwsecret-03" /* level 3, 32 bytes */
#define HAL_HOST_SEC_SECTOR 256u /* SecurityAccess attempt record: 2 sectors */

/** Reset the port: erase nothing, clear mailboxes and the reset request; time back to the clock. */
void hal_host_init(void);

/** Drive time from the caller (simulator) instead of the monotonic clock. */
void hal_host_set_time_us(uint64_t t_us);

/** Sensor mailbox: the plant/hardware writes the latest readings. */
void hal_host_set_sensors(const hal_sensors_t *s);

/** Actuator mailbox: enable flag and commanded force per axis. */
void hal_host_get_actuator(bool *enable, fs_real_t force_N[HAL_AXES]);

/** Replace the SecurityAccess secret of level 1 or 3 (16..64 bytes). */
void hal_host_set_secret(uint8_t level, const uint8_t *secret, uint8_t len);

/** True once after the firmware requested a reset (type in *type). */
bool hal_host_take_reset(uint8_t *type);

/** Erase the whole RAM flash of the skill slots and the SecurityAccess record (a fresh device). */
void hal_host_flash_erase(void);

/** Erase the firmware update region (boot state and both image slots): a device never updated. */
void hal_host_fw_flash_erase(void);

/* Power-cut injection over every flash region (the power-cut runner, hil_sim/faults): the erase
 * and program operations of the slots, the firmware region and the SecurityAccess record are
 * counted in one sequence and logged. */
#define HAL_HOST_FLASH_REGIONS 3u
#define HAL_HOST_REGION_SLOTS 0u
#define HAL_HOST_REGION_FIRMWARE 1u
#define HAL_HOST_REGION_SECURITY 2u
#define HAL_HOST_FLASH_LOG 4096u /* operations logged after hal_host_flash_erase */

/** One logged flash operation: its region, kind (0 erase, 1 program), address and length. */
typedef struct {
    uint8_t region;
    uint8_t kind;
    uint32_t addr;
    uint32_t len;
} hal_host_flash_op_t;

/** Cut the power just after n more erase/program operations (in any region): from then on every
 *  one fails and changes nothing, until hal_host_flash_power_on. */
void hal_host_flash_cut_after(uint32_t n);

/** True once the cut armed by hal_host_flash_cut_after has happened. */
bool hal_host_flash_cut(void);

/** Power back on: no cut armed; the flash keeps its contents. */
void hal_host_flash_power_on(void);

/** Erase/program operations done since hal_host_flash_erase (the cut ones not counted). */
uint32_t hal_host_flash_ops(void);

/** The i-th operation since hal_host_flash_erase (NULL beyond the log). */
const hal_host_flash_op_t *hal_host_flash_op(uint32_t i);

/* ---- simulator CAN backend (hal_can_sim.c) ---- */

#define HAL_SIM_TX_QUEUE 64u  /* driver transmit queue (frames) */
#define HAL_SIM_RX_QUEUE 256u /* receive FIFO (frames); overflow drops the newest */

/** Empty both queues and clear bus-off. */
void hal_sim_can_reset(void);

/** The bus delivers a frame to the device; false (dropped) if the rx FIFO is full or the
 *  controller is bus-off (off the bus, it receives nothing). */
bool hal_sim_can_deliver(const can_frame_t *f);

/** Frames the rx FIFO can take now (a bridge that reads no more leaves the rest with the bus). */
uint32_t hal_sim_can_rx_free(void);

/** The most urgent frame the device queued for transmission (lowest identifier, the oldest among
 *  equal identifiers; not removed); false if none. */
bool hal_sim_can_tx_peek(can_frame_t *f);

/** Remove the frame hal_sim_can_tx_peek gives: the bus has it (hal_can_tx_idle is true once all
 *  are taken; frames the bus holds survive a device reset, as a controller's last frame on the
 *  wire). */
void hal_sim_can_tx_pop(void);

/** Give back a frame the bus had taken but not sent (a mailbox aborted for a more urgent frame):
 *  it goes first among the queued frames with its identifier. False if the queue is full. */
bool hal_sim_can_tx_requeue(const can_frame_t *f);

/** Set or clear the bus-off condition (fault injection). */
void hal_sim_can_set_bus_off(bool off);

/** Frames dropped because the rx FIFO was full. */
uint32_t hal_sim_can_rx_overflows(void);

/* ---- SocketCAN backend (hal_can_socketcan.c) ---- */

/** Open ifname (e.g. "can0"); bitrate > 0 then sets that rate with libsocketcan unless the
 *  interface has it (link down and up; needs CAP_NET_ADMIN). Returns 0, or -errno with a
 *  message in err (closed again if the rate could not be set). */
int hal_socketcan_open(const char *ifname, uint32_t bitrate, char *err, uint32_t err_len);

/** Close the socket. */
void hal_socketcan_close(void);

struct cansock_ops;
struct cansock;

/** hal_socketcan_open through other operating-system calls (cansock.h; tests: a socket pair). */
int hal_socketcan_open_with(const struct cansock_ops *ops, const char *ifname, uint32_t bitrate,
                            char *err, uint32_t err_len);

/** The driver behind the HAL functions (bus-off state, counters). */
const struct cansock *hal_socketcan_driver(void);

#endif /* HAL_HOST_H */

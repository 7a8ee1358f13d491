/* Host port of the HAL (hal.h): what a Linux process needs to run the device firmware.
 * Common part (hal_host.c): time (monotonic clock, or driven by the simulator), random bytes
 * (getrandom), a RAM flash for the slots (fls_ram), the device secret, sensor and actuator
 * mailboxes filled/read by whoever owns the hardware or the plant, and the reset request.
 * CAN backends, one per library:
 *   hal_can_sim.c        queues exchanged with the simulator's bus (hil_sim/bus)
 *   hal_can_socketcan.c  Linux SocketCAN raw socket, libsocketcan for bitrate/restart */
#ifndef HAL_HOST_H
#define HAL_HOST_H

#include <stdbool.h>
#include <stdint.h>
#include "hal.h"

#define HAL_HOST_FLASH_SECTOR 8192u /* one skill record of N = 256 (6,276 B + 36 B) fits */
#define HAL_HOST_FLASH_SECTORS 16u  /* 2 copies x 8 slots */
#define HAL_HOST_FW_SECTOR 4096u    /* firmware flash: boot state + 2 slots of 64 sectors */
#define HAL_HOST_FW_SLOT_SECTORS 64u
#define HAL_HOST_FW_SECTORS (2u + 2u * HAL_HOST_FW_SLOT_SECTORS)
#define HAL_HOST_SECRET_DEFAULT "forceskill-simulator-secret-0001" /* 32 bytes, docs/protocol.md */

/** Reset the port: erase nothing, clear mailboxes and the reset request; time back to the clock. */
void hal_host_init(void);

/** Drive time from the caller (simulator) instead of the monotonic clock. */
void hal_host_set_time_us(uint64_t t_us);

/** Sensor mailbox: the plant/hardware writes the latest readings. */
void hal_host_set_sensors(const hal_sensors_t *s);

/** Actuator mailbox: enable flag and commanded force per axis. */
void hal_host_get_actuator(bool *enable, fs_real_t force_N[HAL_AXES]);

/** Replace the device secret (16..64 bytes). */
void hal_host_set_secret(const uint8_t *secret, uint8_t len);

/** True once after the firmware requested a reset (type in *type). */
bool hal_host_take_reset(uint8_t *type);

/** Erase the whole RAM flash (a fresh device). */
void hal_host_flash_erase(void);

/* ---- simulator CAN backend (hal_can_sim.c) ---- */

#define HAL_SIM_TX_QUEUE 64u  /* driver transmit queue (frames) */
#define HAL_SIM_RX_QUEUE 256u /* receive FIFO (frames); overflow drops the newest */

/** Empty both queues and clear bus-off. */
void hal_sim_can_reset(void);

/** The bus delivers a frame to the device; false (dropped) if the rx FIFO is full. */
bool hal_sim_can_deliver(const can_frame_t *f);

/** Oldest frame the device queued for transmission (not removed); false if none. */
bool hal_sim_can_tx_peek(can_frame_t *f);

/** Remove the oldest queued frame: the bus has it (hal_can_tx_idle is true once all are taken;
 *  frames the bus holds survive a device reset, as a controller's last frame on the wire). */
void hal_sim_can_tx_pop(void);

/** Set or clear the bus-off condition (fault injection). */
void hal_sim_can_set_bus_off(bool off);

/** Frames dropped because the rx FIFO was full. */
uint32_t hal_sim_can_rx_overflows(void);

/* ---- SocketCAN backend (hal_can_socketcan.c) ---- */

/** Open ifname (e.g. "can0"); bitrate > 0 configures it with libsocketcan first (needs
 *  CAP_NET_ADMIN and the interface down). Returns 0, or -errno with a message in err. */
int hal_socketcan_open(const char *ifname, uint32_t bitrate, char *err, uint32_t err_len);

/** Close the socket. */
void hal_socketcan_close(void);

#endif /* HAL_HOST_H */

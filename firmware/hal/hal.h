/* The hardware contract of the forceskill firmware (what every port implements, like
 * CANopenNode's CO_driver.h). The application (firmware/app) reaches hardware only through
 * these functions; a port (firmware/ports/<target>) implements them over its drivers or over the
 * simulator. All functions are non-blocking and called from the 1 kHz tick context only, so a
 * port needs no locking unless its drivers run in interrupts (then CAN queues are the boundary).
 *
 * Units: positions m, forces N, time us. Axis 0 is x (constrained, into the object), axis 1 y. */
#ifndef HAL_H
#define HAL_H

#include <stdbool.h>
#include <stdint.h>
#include "can_frame.h"
#include "fls.h"
#include "fs_real.h"

#define HAL_AXES 2u

/** One sample of every sensor, as the tick sees it (the port applies calibration). */
typedef struct {
    fs_real_t pos_m[HAL_AXES];            /* encoders */
    fs_real_t force_contact_N[HAL_AXES];  /* tip sensor (x; y reads 0 where absent) */
    fs_real_t force_operator_N[HAL_AXES]; /* handle sensor */
} hal_sensors_t;

/* ---- CAN (classic, 11-bit ids) ---- */

/** Queue a frame for transmission; false if the transmit queue is full (retry next tick). The
 *  port sends queued frames by priority, lowest identifier first (frames with the same identifier
 *  in order), as a controller arbitrating its transmit mailboxes does. */
bool hal_can_send(const can_frame_t *frame);

/** Free places in the transmit queue (the application keeps some for its urgent frames);
 *  UINT32_MAX if the port cannot tell. */
uint32_t hal_can_tx_free(void);

/** hal_can_send of a bulk frame: queued only while more than keep places are free (the rest
 *  stay for urgent frames); false if not queued. One call for both tests. */
bool hal_can_send_bulk(const can_frame_t *frame, uint32_t keep);

/** Take the next received frame; false if none. Frames arrive in bus order. */
bool hal_can_receive(can_frame_t *frame);

/** True while the CAN controller is bus-off. */
bool hal_can_bus_off(void);

/** True when every frame queued with hal_can_send has left the transmit queue for the bus
 *  (e.g. a response that must go out before an ECUReset). */
bool hal_can_tx_idle(void);

/* ---- time ---- */

/** Monotonic time in microseconds since power-up (wraps after 584,000 years). */
uint64_t hal_time_us(void);

/** hal_time_us, and the same instant in whole milliseconds in *now_ms (now_us / 1000 truncated
 *  to 32 bits): one sample for both, no 64-bit division in the tick. */
uint64_t hal_time_us_ms(uint32_t *now_ms);

/* ---- sensors and actuator ---- */

/** Read all sensors (the latest samples). */
void hal_sensors_read(hal_sensors_t *out);

/** Enable (true) or disable (false) the actuator power stage. */
void hal_actuator_enable(bool enable);

/** Command the actuator force per axis; ignored while disabled. The caller has applied the limits. */
void hal_actuator_force(const fs_real_t force_N[HAL_AXES]);

/* ---- platform ---- */

/** Fill buf with len unpredictable bytes (security seeds); 0 on success. */
int hal_random(uint8_t *buf, uint32_t len);

/** The flash region that holds the skill slots. */
const fls_dev_t *hal_flash(void);

/** The flash region of the firmware update (firmware/boot, docs/update.md): sectors 0-1 the
 *  boot state record, then application slot A, then slot B (hal_fw_slot_sectors() each). */
const fls_dev_t *hal_fw_flash(void);

/** Sectors per application slot in hal_fw_flash(). */
uint32_t hal_fw_slot_sectors(void);

/** The device key of the firmware image tag (HMAC-SHA256, from protected storage). */
const uint8_t *hal_fw_key(uint8_t *len);

/** The per-device SecurityAccess secret of one level (UDS_SEC_LEVEL_WRITE 1, _FIRMWARE 3; from
 *  protected storage, a different secret per level); *len gets its length (0: level unknown). */
const uint8_t *hal_device_secret(uint8_t level, uint8_t *len);

/** Two sectors that keep the SecurityAccess attempt record (wrong-key counter, lockout) across
 *  reset and power loss (an nvm slot 0); NULL if the port has none: the application then starts
 *  every power-up with the full lockout delay. */
const fls_dev_t *hal_sec_flash(void);

/** Request a reset (ECUReset): the port restarts the firmware after the current tick. */
void hal_request_reset(uint8_t type);

#endif /* HAL_H */

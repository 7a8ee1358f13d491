/* The sensor/actuator side of the MPS2 images. The boards have no sensors and no drive, so an
 * image links a library that provides hal_sensors_read / hal_actuator_* and these three calls
 * around each tick; the product image links the processor-in-the-loop plant (hil_sim/pil,
 * CMake option FS_MPS2_PLANT). A board with real sensors implements hal.h's part in its HAL and
 * these calls as its sampling and output stages. */
#ifndef CM_PLANT_H
#define CM_PLANT_H

#include <stdbool.h>
#include <stdint.h>
#include "app.h"

/** What the plant's parameters give the port before app_init. */
typedef struct {
    bool loaded;         /* a parameter block was found (else defaults: a plant at rest) */
    bool pace;           /* hold each tick until the host's clock reaches the device's */
    const uint8_t *seed; /* random seed of hal_random */
    uint32_t seed_len;   /* bytes at seed */
} cm_plant_params_t;

/** Load the plant (its scenario), fill *cfg for it (node, host timeout, gains, drive) and *p. */
void cm_plant_load(cm_plant_params_t *p, app_config_t *cfg);

/** Sample the sensors for app's coming tick (hal_sensors_read returns them). */
void cm_plant_sense(const app_t *app);

/** Advance the plant over the tick just run, with its actuator output. */
void cm_plant_advance(const app_t *app);

/** For the bench's trace marks only: true while a UDS transfer of app is open or its request
 *  answered 0x78 is pending; *firmware: that transfer is a firmware download. */
bool cm_plant_transfer(const app_t *app, bool *firmware);

#endif /* CM_PLANT_H */

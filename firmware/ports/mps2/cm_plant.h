/* The sensor/actuator side of the MPS2 images, the interface the board's main loop (cm_main,
 * mps2_main.c) needs from a plant. The boards have no sensors and no drive: an image's own
 * `main` passes cm_main a plant, and the port hands its samples to hal_sensors_read and its
 * actuator commands (hal_actuator_*) back to it around each tick. The port names no plant: the
 * processor-in-the-loop image (hil_sim/pil: pil_main.c, pil_plant.c) is assembled beside the
 * simulator's plant, which implements this interface. A board with real sensors implements these
 * calls as its sampling and output stages. */
#ifndef CM_PLANT_H
#define CM_PLANT_H

#include <stdbool.h>
#include <stdint.h>
#include "app.h"
#include "hal.h"

/** What the plant's parameters give the port before app_init. */
typedef struct {
    bool loaded;         /* a parameter block was found (else defaults: a plant at rest) */
    bool pace;           /* hold each tick until the host's clock reaches the device's */
    const uint8_t *seed; /* random seed of hal_random */
    uint32_t seed_len;   /* bytes at seed */
} cm_plant_params_t;

/** The actuator's command after a tick: the power stage and each axis' force (0 when off). */
typedef struct {
    bool enabled;
    fs_real_t force_N[HAL_AXES];
} cm_actuator_t;

/** A plant: the calls the main loop makes around each tick. */
typedef struct {
    /** Load the plant (its scenario), fill *cfg for it (node, host timeout, gains, drive) and *p. */
    void (*load)(cm_plant_params_t *p, app_config_t *cfg);
    /** Sample the sensors for app's coming tick into *out (what hal_sensors_read returns). */
    void (*sense)(const app_t *app, hal_sensors_t *out);
    /** Advance the plant over the tick just run, with the actuator's command of that tick. */
    void (*advance)(const app_t *app, const cm_actuator_t *act);
    /** For the bench's trace marks only: true while a UDS transfer of app is open or its request
     *  answered 0x78 is pending; *firmware: that transfer is a firmware download. */
    bool (*transfer)(const app_t *app, bool *firmware);
} cm_plant_t;

/** The product image's main loop (mps2_main.c): load the plant, cm_port_init, app_init, then per
 *  SysTick sense, app_tick, advance, cm_port_end_tick. Returns only if the board stops. */
int cm_main(const cm_plant_t *plant);

#endif /* CM_PLANT_H */

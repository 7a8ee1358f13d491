/* The device application's public surface: what a port's main needs to run the device. The
 * application (state machine BOOT -> IDLE -> TEACH | EXECUTE -> FAULT, the 1 kHz tick, the
 * cyclic frames of forceskill.dbc and the UDS server) reaches the hardware only through hal.h;
 * a main initialises the HAL, then
 *
 *     app_t *app = app_device();
 *     app_config_default(app_device_config());
 *     app_init(app, app_device_config());
 *     for (;;) { (void)app_poll(app); }
 *
 * The device state app_t and its configuration app_config_t are opaque here: their fields, and
 * the functions the application's modules share, are in app_internal.h (firmware/app and its
 * white-box tests and fuzzers); the simulator configures and reads the device through
 * app_config.h. */
#ifndef APP_H
#define APP_H

#include <stdbool.h>
#include <stdint.h>
#include "app_sm.h"

/** The whole device (fields: app_internal.h). */
typedef struct app app_t;

/** The device configuration (fields: app_internal.h). */
typedef struct app_config app_config_t;

/** The device's one instance (static storage in app_device.c, linked only when used). */
app_t *app_device(void);

/** The configuration of app_device() (static storage; fill it with app_config_default). */
app_config_t *app_device_config(void);

/** Factory defaults: node 0, default gains/limits/safety, ideal drive, telemetry 1 ms. */
void app_config_default(app_config_t *cfg);

/** Boot: state BOOT, storage scan, UDS/ISO-TP/security set up; the first tick goes to IDLE. */
void app_init(app_t *app, const app_config_t *cfg);

/** One 1 kHz tick. overrun: the previous tick did not finish in time (latches a fault). */
void app_tick(app_t *app, bool overrun);

/** 1 kHz scheduler for ports with a free-running clock (hal_time_us): runs app_tick when the
 *  next 1 ms boundary is due and returns true. A tick that starts a whole period or more late
 *  (the previous one overran) is flagged as an overrun, which latches FLT_TICK_OVERRUN; the
 *  schedule then restarts from now (no burst of catch-up ticks). */
bool app_poll(app_t *app);

/** The device state (BOOT, IDLE, TEACH, EXECUTE, FAULT). */
app_state_t app_state(const app_t *app);

/** The latched fault's code (5xx, flt_codes.h), 0 when none. */
uint16_t app_fault_code(const app_t *app);

#endif /* APP_H */

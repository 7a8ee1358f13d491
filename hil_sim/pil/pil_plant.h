/* Processor-in-the-loop plant of the Cortex-M image: the simulator's plant, operator and sensor
 * models (hil_sim/src: sim_couple, sim_model, sim_rng) linked into the image behind
 * the sensor/actuator part of hal.h. Its scenario comes from the parameter block that
 * `hil_sim pil` loads at CM_PARAMS_ADDR (hil_sim/src/sim_params.h). The plant runs in the same
 * 1 kHz loop as the application, before (sensors) and after (actuator) each app_tick. */
#ifndef PIL_PLANT_H
#define PIL_PLANT_H

#include <stdbool.h>
#include <stdint.h>
#include "app.h"
#include "sim_params.h"
#include "sim_scenario.h"

/** Read the parameter block; false if there is none (the scenario then is a plant at rest
 *  without operator, node 0, host timeout 100 ms, a fixed seed). */
bool pil_plant_load(sim_scenario_t *sc, sim_params_dev_t *dev);

/** Start the plant of scenario sc (kept by reference). */
void pil_plant_init(const sim_scenario_t *sc);

/** Sample the sensors for the coming tick of app (hal_sensors_read returns them). */
void pil_plant_sense(const app_t *app);

/** Advance the plant over the tick with the actuator output of app's tick. */
void pil_plant_advance(const app_t *app);

#endif /* PIL_PLANT_H */

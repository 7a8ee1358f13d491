/* The plant as a device sees it through hal.h, one firmware tick at a time: shared by
 * `hil_sim serve` (host port) and the processor-in-the-loop Cortex-M image (`hil_sim pil`,
 * firmware/ports/cortex-m/cm_pil.c). Per tick: the operator demonstrates while the device is in
 * TEACH (seeded as the scenario says, one demonstration after the other), every sensor is
 * sampled and delayed (sim_couple), the device ticks, then the plant advances with the actuator
 * command held, or the drive parks the handle while the device is idle. */
#ifndef SIM_PLANT_H
#define SIM_PLANT_H

#include <stdbool.h>
#include <stdint.h>
#include "app.h"
#include "hal.h"
#include "sim_couple.h"
#include "sim_model.h"
#include "sim_rng.h"
#include "sim_scenario.h"

/** Plant, operator and sensor pipeline state. */
typedef struct {
    sim_axis_t ax[2];
    sim_drive_t drv[2];
    sim_operator_t op;
    sim_rng_t rng_sens;
    uint64_t teach_count;
    uint32_t teach_start_tick;
    bool teaching;
    sim_sample_t ring[SIM_COUPLE_RING];
    uint64_t n_tick;
} sim_plant_t;

/** The device configured as the scenario's controller (app_config_default, then the scenario's
 *  m_d, plant, velocity filter, object model, carriage, F_max) with node and host timeout. */
void sim_plant_app_config(const sim_scenario_t *sc, uint8_t node, uint16_t host_timeout_ms,
                          app_config_t *cfg);

/** Plant at the scenario's start position, at rest; sensors seeded from the scenario. */
void sim_plant_init(sim_plant_t *p, const sim_scenario_t *sc);

/** Sensors the device reads at this tick: teach = the device is in TEACH, dev_tick its tick
 *  counter (the operator's clock starts when TEACH starts). */
void sim_plant_sense(sim_plant_t *p, const sim_scenario_t *sc, bool teach, uint32_t dev_tick,
                     hal_sensors_t *hs);

/** Advance the plant over the tick after the device's tick: enable/force_N its actuator output,
 *  state its state (parked in IDLE and BOOT; the ideal drive is dynamics-compensated in
 *  EXECUTE). */
void sim_plant_advance(sim_plant_t *p, const sim_scenario_t *sc, bool enable,
                       const fs_real_t force_N[2], app_state_t state);

#endif /* SIM_PLANT_H */

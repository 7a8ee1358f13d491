/* Device <-> plant coupling of one 1 ms firmware tick, shared by the simulators that run the
 * device application against the plant (hil_sim/bus/serve.c and hil_sim/faults): sample every
 * sensor of the plant, then advance the plant over the tick with the actuator command held, or
 * park it while the device is idle. */
#ifndef SIM_COUPLE_H
#define SIM_COUPLE_H

#include <stdbool.h>
#include <stdint.h>
#include "hal.h"
#include "sim_model.h"
#include "sim_rng.h"
#include "sim_scenario.h"

#define SIM_PARK_TAU_S 0.05   /* idle: the drive brings the handle back to the start position */
#define SIM_PARK_VMAX_MPS 0.5 /* ... at most this fast: 0.5 mm per tick, 1/10 of the device's
                                 encoder-jump limit (an uncapped first-order park moved a handle
                                 0.29 m away by 5.8 mm in one tick: an encoder jump to the device;
                                 0.1 m/s left the handle still moving when the next run started) */

/** One sample of the sensors: x, y encoders (m), tip (contact) force x, handle force x, y (N). */
typedef struct {
    double x_m, y_m, contact_N, operator_x_N, operator_y_N;
} sim_sample_t;

#define SIM_COUPLE_RING 8u /* sensor pipeline length: > the largest delay_samples (4) */

/** Sample the encoders and force sensors of the plant now (ax, drv: both axes; noise from rng,
 *  in that order). */
void sim_couple_sample(const sim_scenario_t *sc, const sim_axis_t *ax, const sim_drive_t *drv,
                       sim_rng_t *rng, sim_sample_t *out);

/** The sensor pipeline: store tick n_tick's sample in ring and return the sample the device sees
 *  at that tick (the one of tick n_tick - delay_samples, or of tick 0 before that). */
const sim_sample_t *sim_couple_delay(sim_sample_t ring[SIM_COUPLE_RING], uint64_t n_tick,
                                     int delay_samples, const sim_sample_t *now);

/** The device's HAL view of a sample (a contact force sensor on x only). */
void sim_couple_to_hal(const sim_sample_t *m, hal_sensors_t *hs);

/** Advance the plant one firmware tick (sc->dt_s): parked = the device is idle (the drive parks
 *  the handle at the start position, time constant SIM_PARK_TAU_S, speed capped at
 *  SIM_PARK_VMAX_MPS, contact from the spring only), else sc->substeps substeps with
 *  drv[].force_cmd_N held. */
void sim_couple_advance(const sim_scenario_t *sc, sim_axis_t ax[2], const sim_drive_t drv[2],
                        bool parked);

#endif /* SIM_COUPLE_H */

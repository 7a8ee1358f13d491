/* Device <-> plant coupling of one 1 ms firmware tick, shared by the three simulators that run
 * the device application (firmware/app app_tick, through the host port of hal.h) against the
 * plant: the paper experiments (sim_run.c), the fault rig (hil_sim/faults) and the bus simulator
 * (hil_sim/bus/serve.c). The device configured as the scenario's controller, the plant at its
 * start, the host's cyclic frames; per tick: sample every sensor of the plant, hand the device's
 * actuator output to the drives, then advance the plant over the tick with the command held, or
 * park it while the device is idle. */
#ifndef SIM_COUPLE_H
#define SIM_COUPLE_H

#include <stdbool.h>
#include <stdint.h>
#include "app_config.h"
#include "secoc.h"
#include "can_frame.h"
#include "hal.h"
#include "sim_model.h"
#include "sim_rng.h"
#include "sim_scenario.h"

#define SIM_PARK_TAU_S 0.05 /* idle: the drive brings the handle back to the start position */
#define SIM_PARK_VMAX_MPS \
    0.5 /* ... at most this fast: 0.5 mm per tick, 1/10 of the device's
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

/** The device configured as the scenario's controller: app_config_default, then the plant
 *  (carriage rendering on the realistic plant), m_d, velocity filter, object model, phase
 *  stopping, carriage compensation and the force limit from sc. */
void sim_couple_device_config(const sim_scenario_t *sc, app_config_t *cfg);

/** The plant at the scenario's start: both axes at rest at start_x_m / start_y_m, each drive
 *  prepared for sc's plant (its carriage and, on x, its object). */
void sim_couple_plant_init(const sim_scenario_t *sc, sim_axis_t ax[2], sim_drive_t drv[2]);

/** The device's actuator output into the drives: force_N while enable, else 0; the ideal drive
 *  is dynamics-compensated while state is EXECUTE. Returns enable; cmd_N (may be NULL) receives
 *  the commands. */
bool sim_couple_drive(const sim_scenario_t *sc, app_state_t state, bool enable,
                      const fs_real_t force_N[2], sim_drive_t drv[2], double cmd_N[2]);

/** The host port's actuator output (hal_host_get_actuator) into the drives, as sim_couple_drive
 *  for app's state (sim_couple_host.c). */
bool sim_couple_actuate(const sim_scenario_t *sc, const app_t *app, sim_drive_t drv[2],
                        double cmd_N[2]);

/** True when the drive parks the handle: the device in IDLE or BOOT (every TEACH or EXECUTE
 *  starts where `hil_sim run` starts), or in FAULT once its stop ramp has switched the actuator
 *  off (a free handle would drift out of the sensor range and no fault could be cleared). */
bool sim_couple_parked(app_state_t state, bool enable);

/** The object a run's plant meets: the scenario's, its surface moved by away_* during an
 *  execution (the same for the lockstep run and the bus-driven plants). */
typedef struct {
    sim_object_t object; /* the object now (its surface moved by the scenario's away_*) */
    uint64_t exec_start; /* the tick the running execution started */
    bool executing;
} sim_couple_away_t;

/** Points drv at the object of tick n_tick in state (an execution's start noted) for the tick's
 *  plant step; sim_couple_away_end puts the scenario's object back after it. */
void sim_couple_away_begin(sim_couple_away_t *a, const sim_scenario_t *sc, app_state_t state,
                           uint64_t n_tick, sim_drive_t *drv);

/** The scenario's own object back in drv after the tick's plant step. */
void sim_couple_away_end(const sim_scenario_t *sc, sim_drive_t *drv);

/** Plant, operator and sensor pipeline of a device run one tick at a time against a bus
 *  (hil_sim serve, the processor-in-the-loop Cortex-M image of hil_sim pil). */
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
    sim_couple_away_t away;
} sim_couple_plant_t;

/** How far the object's surface has moved away t_s into an execution (the scenario's away_*:
 *  smoothstep ramps of away_ramp_s, a step without). */
double sim_couple_away_m(const sim_scenario_t *sc, double t_s);

/** The plant at the scenario's start (sim_couple_plant_init), sensor noise seeded from sc. */
void sim_couple_start(sim_couple_plant_t *p, const sim_scenario_t *sc);

/** The sensors the device reads at its coming tick: teach = the device is in TEACH (the operator
 *  demonstrates, seeded by sc's seed + the demonstration's number, its clock from dev_tick at the
 *  start of TEACH), every sensor sampled and delayed. */
void sim_couple_sense(sim_couple_plant_t *p, const sim_scenario_t *sc, bool teach,
                      uint32_t dev_tick, hal_sensors_t *hs);

/** After the device's tick: its actuator output (enable, force_N) into the drives for state,
 *  then the plant over the tick, parked as sim_couple_parked says. Returns enable. */
bool sim_couple_step(sim_couple_plant_t *p, const sim_scenario_t *sc, app_state_t state,
                     bool enable, const fs_real_t force_N[2]);

/** An in-process host's session with app: the device establishes its motion key (as the DID
 *  0x0302 write does) and host gets the same key, derived from the level-1 secret and both
 *  nonces. Returns 0, or the device's UDS NRC. */
uint8_t sim_couple_host_session(app_t *app, secoc_t *host);

/** The host's heartbeat frame for node (telemetry period in ms, 0 = the device's), authenticated
 *  with host's session (freshness value, MAC, E2E). */
void sim_couple_heartbeat_frame(secoc_t *host, uint8_t node, uint8_t telemetry_period_ms,
                                can_frame_t *f);

/** The host's command frames for node (mode APP_CMD_*, slot 1.., goal and time scale, end 0 skill
 *  / 1 hold / 2 release), authenticated: EXECUTE is two frames (RUN_OPTIONS, then EXECUTE), any
 *  other mode one. Returns the number of frames written to f. */
unsigned sim_couple_command_frames(secoc_t *host, uint8_t node, uint8_t mode, uint8_t slot,
                                   double goal_scale, double time_scale, uint8_t end,
                                   can_frame_t f[2]);

#endif /* SIM_COUPLE_H */

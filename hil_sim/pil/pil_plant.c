/* PIL plant behind hal.h's sensors and actuator (see pil_plant.h). */
#include "pil_plant.h"

#include <string.h>

#include "cm_board.h"
#include "fs_wire_const.h"
#include "hal.h"
#include "sim_couple.h"

static const sim_scenario_t *g_sc;
static sim_couple_plant_t g_plant;
static hal_sensors_t g_sens;
static bool g_enable;
static fs_real_t g_force_N[HAL_AXES];

bool pil_plant_load(sim_scenario_t *sc, sim_params_dev_t *dev)
{
    const uint8_t *blk = (const uint8_t *)(uintptr_t)CM_PARAMS_ADDR;
    if (sim_params_unpack(blk, CM_PARAMS_MAX, sc, dev) == 0) {
        return true;
    }
    /* no block: a plant at rest on the ideal drive, the simulator's defaults where it matters */
    memset(sc, 0, sizeof(*sc));
    sc->dt_s = FS_TICK_S;
    sc->substeps = 10;
    sc->seed = 1u;
    sc->m_d_kg = 40.0;
    sc->force_max_N = 50.0;
    sc->object.surface_m = 0.001;
    sc->object.k1_Npm = sc->object.k2_Npm = 100.0;
    sc->object.layer_depth_m = 0.019;
    sc->object.d_v_Nspm = 50.0;
    sc->object.m_v_kg = 10.0;
    sc->carriage.carriage_kg = 2.0;
    sc->carriage.act_max_N = 200.0;
    sc->carriage.act_lag_s = 0.0005;
    sc->tip.range_N = sc->handle.range_N = 100.0;
    sc->tip.bits = sc->handle.bits = 16u;
    sc->encoder_m = 1e-6;
    sc->vel_cutoff_Hz = 50.0;
    memset(dev, 0, sizeof(*dev));
    dev->host_timeout_ms = 100u;
    return false;
}

void pil_plant_init(const sim_scenario_t *sc)
{
    g_sc = sc;
    sim_couple_start(&g_plant, sc);
    memset(&g_sens, 0, sizeof(g_sens));
    g_enable = false;
    g_force_N[0] = g_force_N[1] = FS_R(0.0);
}

void pil_plant_sense(const app_t *app)
{
    /* the tick about to run is app->tick + 1 */
    sim_couple_sense(&g_plant, g_sc, app->state == APP_TEACH, app->tick, &g_sens);
}

void pil_plant_advance(const app_t *app)
{
    (void)sim_couple_step(&g_plant, g_sc, app->state, g_enable, g_force_N);
}

void hal_sensors_read(hal_sensors_t *out)
{
    *out = g_sens;
}

void hal_actuator_enable(bool enable)
{
    g_enable = enable;
    if (!enable) {
        g_force_N[0] = g_force_N[1] = FS_R(0.0);
    }
}

void hal_actuator_force(const fs_real_t force_N[HAL_AXES])
{
    if (g_enable) {
        g_force_N[0] = force_N[0];
        g_force_N[1] = force_N[1];
    }
}

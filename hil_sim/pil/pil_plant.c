/* Processor-in-the-loop plant of the MPS2 images (pil_plant.h; the interface is the port's
 * cm_plant.h): the simulator's plant, operator and sensor models (hil_sim/src: sim_couple,
 * sim_model, sim_rng) behind the board's sensors and actuator. Its scenario comes from the
 * parameter block that `hil_sim pil` loads at CM_PARAMS_ADDR (hil_sim/src/sim_params.h). The
 * port's main loop (cm_main) runs it in the same 1 kHz loop as the application, before (sensors)
 * and after (actuator) each app_tick. */
#include "pil_plant.h"

#include <string.h>

#include "cm_board.h"
#include "fs_wire_const.h"
#include "sim_couple.h"
#include "sim_params.h"

static sim_scenario_t g_sc_store;
static const sim_scenario_t *g_sc = &g_sc_store;
static sim_params_dev_t g_dev;
static sim_couple_plant_t g_plant;

/* Read the parameter block; false if there is none (the scenario then is a plant at rest
 * without operator, node 0, host timeout 100 ms, a fixed seed). */
static bool plant_params(sim_scenario_t *sc, sim_params_dev_t *dev)
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

static void plant_load(cm_plant_params_t *p, app_config_t *cfg)
{
    p->loaded = plant_params(&g_sc_store, &g_dev);
    sim_couple_start(&g_plant, g_sc);
    sim_couple_device_config(g_sc, cfg);
    cfg->node = (uint8_t)g_dev.node;
    cfg->saf.wdg.timeout_ms = (uint16_t)g_dev.host_timeout_ms;
    p->pace = (g_dev.flags & SIM_PARAMS_PACE) != 0u;
    p->seed = g_dev.seed;
    p->seed_len = SIM_PARAMS_SEED_LEN;
}

static void plant_sense(const app_t *app, hal_sensors_t *out)
{
    /* the tick about to run is app_tick_count + 1 */
    sim_couple_sense(&g_plant, g_sc, app_state(app) == APP_TEACH, app_tick_count(app), out);
}

static void plant_advance(const app_t *app, const cm_actuator_t *act)
{
    (void)sim_couple_step(&g_plant, g_sc, app_state(app), act->enabled, act->force_N);
}

static bool plant_transfer(const app_t *app, bool *firmware)
{
    *firmware = app_transfer_is_firmware(app);
    return app_transfer_busy(app);
}

const cm_plant_t pil_plant = {plant_load, plant_sense, plant_advance, plant_transfer};

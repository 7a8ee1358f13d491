/* The plant one device tick at a time (see sim_plant.h). */
#include "sim_plant.h"

#include <math.h>
#include <string.h>

void sim_plant_app_config(const sim_scenario_t *sc, uint8_t node, uint16_t host_timeout_ms,
                          app_config_t *cfg)
{
    app_config_default(cfg);
    cfg->node = node;
    cfg->render_carriage = (uint8_t)(sc->plant == SIM_PLANT_REALISTIC);
    cfg->gains[0].m_d_kg = (fs_real_t)sc->m_d_kg;
    cfg->gains[1].m_d_kg = (fs_real_t)sc->m_d_kg;
    cfg->vel_cutoff_Hz = (fs_real_t)sc->vel_cutoff_Hz;
    cfg->exec.use_model = (uint8_t)(sc->use_model != 0);
    cfg->exec.object.m_v_kg = (fs_real_t)sc->object.m_v_kg;
    cfg->exec.object.d_v_Nspm = (fs_real_t)sc->object.d_v_Nspm;
    cfg->exec.object.k1_Npm = (fs_real_t)sc->object.k1_Npm;
    cfg->exec.object.k2_Npm = (fs_real_t)sc->object.k2_Npm;
    cfg->exec.object.layer_depth_m = (fs_real_t)sc->object.layer_depth_m;
    cfg->exec.object.surface_m = (fs_real_t)sc->object.surface_m;
    cfg->exec.phase_stop_gain_per_N2 = (fs_real_t)sc->phase_stop_gain_per_N2;
    cfg->render.carriage_kg = (fs_real_t)sc->carriage.carriage_kg;
    cfg->render.viscous_Nspm = (fs_real_t)sc->carriage.viscous_Nspm;
    cfg->render.coulomb_N = (fs_real_t)sc->carriage.coulomb_N;
    cfg->render.motor_max_N = (fs_real_t)sc->carriage.act_max_N;
    for (unsigned a = 0; a < PFC_AXES; a++) {
        cfg->saf.lim.axis[a].force_max_N = (fs_real_t)sc->force_max_N;
    }
    cfg->saf.wdg.timeout_ms = host_timeout_ms;
}

void sim_plant_init(sim_plant_t *p, const sim_scenario_t *sc)
{
    memset(p, 0, sizeof(*p));
    p->ax[0].pos_m = sc->start_x_m;
    p->ax[1].pos_m = sc->start_y_m;
    const double h = sc->dt_s / (double)sc->substeps;
    for (int a = 0; a < 2; a++) {
        sim_drive_t *d = &p->drv[a];
        d->kind = sc->plant;
        d->mass_kg = sc->plant == SIM_PLANT_REALISTIC ? sc->carriage.carriage_kg : sc->m_d_kg;
        d->carriage = &sc->carriage;
        d->object = (a == 0) ? &sc->object : NULL;
        d->act_limit_N = sc->carriage.act_max_N;
        d->act_alpha = 1.0 - exp(-h / sc->carriage.act_lag_s);
        sim_drive_prepare(d);
    }
    sim_rng_seed(&p->rng_sens, sc->seed ^ 0x5EB5C0DEDA7A5EEDull);
}

void sim_plant_sense(sim_plant_t *p, const sim_scenario_t *sc, bool teach, uint32_t dev_tick,
                     hal_sensors_t *hs)
{
    /* operator: demonstrates from the moment the device enters TEACH */
    if (teach && !p->teaching) {
        sim_operator_cfg_t opc = sc->op;
        opc.duration_s = sc->duration_s;
        sim_rng_t rng_op;
        sim_rng_seed(&rng_op, sc->seed + p->teach_count);   /* first demonstration: the scenario seed */
        sim_operator_init(&p->op, &opc, &rng_op);
        p->teach_start_tick = dev_tick;
        p->teach_count++;
    }
    p->teaching = teach;
    double fprof[2] = {0.0, 0.0};
    const double p_true = p->ax[0].pos_m - sc->object.surface_m;
    if (teach && sc->op.task != SIM_TASK_NONE) {
        const double t = (double)(dev_tick - p->teach_start_tick) * sc->dt_s;
        sim_operator_force(&p->op, t, p_true, sc->object.layer_depth_m, fprof);
    }
    for (int a = 0; a < 2; a++) {
        p->drv[a].force_ext_N = fprof[a];
        p->drv[a].hand_damping_Nspm = teach ? sc->op.hand_damping_Nspm : 0.0;
    }
    sim_sample_t smp;
    sim_couple_sample(sc, p->ax, p->drv, &p->rng_sens, &smp);
    sim_couple_to_hal(sim_couple_delay(p->ring, p->n_tick, sc->delay_samples, &smp), hs);
}

void sim_plant_advance(sim_plant_t *p, const sim_scenario_t *sc, bool enable,
                       const fs_real_t force_N[2], app_state_t state)
{
    const bool ideal = sc->plant == SIM_PLANT_IDEAL;
    for (int a = 0; a < 2; a++) {
        p->drv[a].force_cmd_N = enable ? (double)force_N[a] : 0.0;
        /* the ideal drive is dynamics-compensated while the law runs (as hil_sim run) */
        p->drv[a].prescribed = (uint8_t)(ideal && state == APP_EXECUTE);
    }
    /* a parked device: in IDLE the simulated drive brings the handle back to the scenario's start
     * position and holds it at rest, so every TEACH or EXECUTE starts where `hil_sim run` starts */
    sim_couple_advance(sc, p->ax, p->drv, state == APP_IDLE || state == APP_BOOT);
    p->n_tick++;
}

/* Device <-> plant coupling of one tick (see sim_couple.h). */
#include "sim_couple.h"

#include <math.h>
#include <string.h>

#include "e2e.h"
#include "fs_dbc.h"
#include "proto_ids.h"
#include "uds.h"

void sim_couple_sample(const sim_scenario_t *sc, const sim_axis_t *ax, const sim_drive_t *drv,
                       sim_rng_t *rng, sim_sample_t *out)
{
    out->x_m = sim_encoder_read(ax[0].pos_m, sc->encoder_m);
    out->y_m = sim_encoder_read(ax[1].pos_m, sc->encoder_m);
    out->contact_N = sim_force_read(&sc->tip, ax[0].contact_N, rng);
    out->operator_x_N = sim_force_read(&sc->handle, sim_operator_handle_N(&drv[0], &ax[0]), rng);
    out->operator_y_N = sim_force_read(&sc->handle, sim_operator_handle_N(&drv[1], &ax[1]), rng);
}

const sim_sample_t *sim_couple_delay(sim_sample_t ring[SIM_COUPLE_RING], uint64_t n_tick,
                                     int delay_samples, const sim_sample_t *now)
{
    ring[n_tick % SIM_COUPLE_RING] = *now;
    const uint64_t d = (uint64_t)delay_samples > n_tick ? n_tick : (uint64_t)delay_samples;
    return &ring[(n_tick - d) % SIM_COUPLE_RING];
}

void sim_couple_to_hal(const sim_sample_t *m, hal_sensors_t *hs)
{
    hs->pos_m[0] = (fs_real_t)m->x_m;
    hs->pos_m[1] = (fs_real_t)m->y_m;
    hs->force_contact_N[0] = (fs_real_t)m->contact_N;
    hs->force_contact_N[1] = FS_R(0.0);
    hs->force_operator_N[0] = (fs_real_t)m->operator_x_N;
    hs->force_operator_N[1] = (fs_real_t)m->operator_y_N;
}

void sim_couple_advance(const sim_scenario_t *sc, sim_axis_t ax[2], const sim_drive_t drv[2],
                        bool parked)
{
    const double dt = sc->dt_s;
    if (parked) {
        const double start[2] = {sc->start_x_m, sc->start_y_m};
        const double k = dt / SIM_PARK_TAU_S > 1.0 ? 1.0 : dt / SIM_PARK_TAU_S;
        const double step_max = SIM_PARK_VMAX_MPS * dt;
        for (int a = 0; a < 2; a++) {
            double step = (start[a] - ax[a].pos_m) * k;
            step = step > step_max ? step_max : (step < -step_max ? -step_max : step);
            ax[a].pos_m += step;
            ax[a].vel_mps = 0.0;
            ax[a].acc_mps2 = 0.0;
            ax[a].act_N = 0.0;
        }
        ax[0].contact_N = 0.0;
        if (ax[0].pos_m > sc->object.surface_m) {
            ax[0].contact_N = sim_object_spring_N(&sc->object, ax[0].pos_m - sc->object.surface_m);
        }
        return;
    }
    const double h = dt / (double)sc->substeps;
    sim_drive_t dy = drv[1];
    for (int k = 0; k < sc->substeps; k++) {
        sim_axis_substep(&ax[0], &drv[0], h);
        /* the tip slides on the surface: Coulomb friction along y, mu times the contact force */
        dy.friction_N = sc->object.friction_mu * ax[0].contact_N;
        sim_axis_substep(&ax[1], &dy, h);
    }
}

void sim_couple_device_config(const sim_scenario_t *sc, app_config_t *cfg)
{
    app_config_default(cfg);
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
    cfg->exec.object.surface_m = (fs_real_t)(sc->object.surface_m + sc->surface_error_m);
    cfg->exec.surface_from_contact = (uint8_t)(sc->surface_from_contact != 0);
    cfg->exec.phase_stop_gain_per_N2 = (fs_real_t)sc->phase_stop_gain_per_N2;
    cfg->render.carriage_kg = (fs_real_t)sc->carriage.carriage_kg;
    cfg->render.viscous_Nspm = (fs_real_t)sc->carriage.viscous_Nspm;
    cfg->render.coulomb_N = (fs_real_t)sc->carriage.coulomb_N;
    cfg->render.motor_max_N = (fs_real_t)sc->carriage.act_max_N;
    for (unsigned a = 0; a < PFC_AXES; a++) {
        cfg->saf.lim.axis[a].force_max_N = (fs_real_t)sc->force_max_N;
    }
    cfg->stiffness_max_Npm = sc->stiffness_max_Npm > 0.0
                                 ? (fs_real_t)sc->stiffness_max_Npm
                                 : app_stiffness_max_default_Npm(cfg->render_carriage);
}

void sim_couple_plant_init(const sim_scenario_t *sc, sim_axis_t ax[2], sim_drive_t drv[2])
{
    memset(ax, 0, 2u * sizeof(ax[0]));
    ax[0].pos_m = sc->start_x_m;
    ax[1].pos_m = sc->start_y_m;
    const double h = sc->dt_s / (double)sc->substeps;
    for (int a = 0; a < 2; a++) {
        sim_drive_t *d = &drv[a];
        memset(d, 0, sizeof(*d));
        d->kind = sc->plant;
        d->mass_kg = sc->plant == SIM_PLANT_REALISTIC ? sc->carriage.carriage_kg : sc->m_d_kg;
        d->carriage = &sc->carriage;
        d->object = (a == 0) ? &sc->object : NULL;
        d->act_limit_N = sc->carriage.act_max_N;
        d->act_alpha = 1.0 - exp(-h / sc->carriage.act_lag_s);
        sim_drive_prepare(d);
    }
}

bool sim_couple_drive(const sim_scenario_t *sc, app_state_t state, bool enable,
                      const fs_real_t force_N[2], sim_drive_t drv[2], double cmd_N[2])
{
    const bool ideal = sc->plant == SIM_PLANT_IDEAL;
    for (int a = 0; a < 2; a++) {
        drv[a].force_cmd_N = enable ? (double)force_N[a] : 0.0;
        drv[a].prescribed = (uint8_t)(ideal && state == APP_EXECUTE);
        if (cmd_N != NULL) {
            cmd_N[a] = drv[a].force_cmd_N;
        }
    }
    return enable;
}

bool sim_couple_parked(app_state_t state, bool enable)
{
    return state == APP_IDLE || state == APP_BOOT || (state == APP_FAULT && !enable);
}

void sim_couple_start(sim_couple_plant_t *p, const sim_scenario_t *sc)
{
    memset(p, 0, sizeof(*p));
    sim_couple_plant_init(sc, p->ax, p->drv);
    sim_rng_seed(&p->rng_sens, sc->seed ^ 0x5EB5C0DEDA7A5EEDull);
}

void sim_couple_sense(sim_couple_plant_t *p, const sim_scenario_t *sc, bool teach,
                      uint32_t dev_tick, hal_sensors_t *hs)
{
    /* operator: demonstrates from the moment the device enters TEACH */
    if (teach && !p->teaching) {
        sim_operator_cfg_t opc = sc->op;
        opc.duration_s = sc->duration_s;
        sim_rng_t rng_op;
        sim_rng_seed(&rng_op,
                     sc->seed + p->teach_count); /* first demonstration: the scenario seed */
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
        fprof[1] += sim_operator_path_force(&p->op, t, sc->start_y_m, p->ax[1].pos_m);
    }
    for (int a = 0; a < 2; a++) {
        p->drv[a].force_ext_N = fprof[a];
        p->drv[a].hand_damping_Nspm = teach ? sc->op.hand_damping_Nspm : 0.0;
    }
    sim_sample_t smp;
    sim_couple_sample(sc, p->ax, p->drv, &p->rng_sens, &smp);
    sim_couple_to_hal(sim_couple_delay(p->ring, p->n_tick, sc->delay_samples, &smp), hs);
}

/* 0 at r <= 0 rising smoothly to 1 at r >= 1. */
static double smoothstep(double r)
{
    r = (r < 0.0) ? 0.0 : ((r > 1.0) ? 1.0 : r);
    return r * r * (3.0 - 2.0 * r);
}

double sim_couple_away_m(const sim_scenario_t *sc, double t_s)
{
    const double t0 = sc->away_at_s;
    const double t1 = sc->away_at_s + sc->away_for_s;
    const double ramp = sc->away_ramp_s;
    if (!(sc->away_for_s > 0.0) || t_s < t0 || t_s >= t1 + ramp) {
        return 0.0;
    }
    if (!(ramp > 0.0)) {
        return (t_s < t1) ? sc->away_m : 0.0;
    }
    return sc->away_m *
           ((t_s < t1) ? smoothstep((t_s - t0) / ramp) : 1.0 - smoothstep((t_s - t1) / ramp));
}

void sim_couple_away_begin(sim_couple_away_t *a, const sim_scenario_t *sc, app_state_t state,
                           uint64_t n_tick, sim_drive_t *drv)
{
    if (state == APP_EXECUTE && !a->executing) {
        a->exec_start = n_tick;
    }
    a->executing = (state == APP_EXECUTE);
    a->object = sc->object;
    if (a->executing) {
        const double t_s = (double)(n_tick - a->exec_start) * sc->dt_s;
        a->object.surface_m += sim_couple_away_m(sc, t_s);
        if (sc->gives_k2_Npm > 0.0 && t_s >= sc->gives_at_s) { /* the inner layer gave way */
            a->object.k2_Npm = sc->gives_k2_Npm;
        }
    }
    drv->object = &a->object;
    sim_drive_prepare(drv);
}

void sim_couple_away_end(const sim_scenario_t *sc, sim_drive_t *drv)
{
    drv->object = &sc->object;
}

bool sim_couple_step(sim_couple_plant_t *p, const sim_scenario_t *sc, app_state_t state,
                     bool enable, const fs_real_t force_N[2])
{
    (void)sim_couple_drive(sc, state, enable, force_N, p->drv, NULL);
    sim_couple_away_begin(&p->away, sc, state, p->n_tick, &p->drv[0]);
    sim_couple_advance(sc, p->ax, p->drv, sim_couple_parked(state, enable));
    sim_couple_away_end(sc, &p->drv[0]);
    p->n_tick++;
    return enable;
}

uint8_t sim_couple_host_session(app_t *app, secoc_t *host)
{
    static const uint8_t nonce[SECOC_NONCE_LEN] = "sim host nonce!";
    const uint8_t nrc = app_motion_key(app, nonce, SECOC_NONCE_LEN);
    if (nrc != 0u) {
        return nrc;
    }
    uint8_t len = 0u;
    const uint8_t *secret = hal_device_secret(UDS_SEC_LEVEL_WRITE, &len);
    secoc_start_session(host, secret, len, app_motion_nonce(app), nonce);
    return 0u;
}

/* MAC, freshness value and E2E CRC of a packed host frame (its E2E counter: the FV's low 4 bits). */
static void host_protect(secoc_t *host, secoc_channel_t ch, can_frame_t *f)
{
    const uint32_t fv = secoc_protect(host, f, ch);
    e2e_protect(f, (uint8_t)(fv & E2E_COUNTER_MASK));
}

void sim_couple_heartbeat_frame(secoc_t *host, uint8_t node, uint8_t telemetry_period_ms,
                                can_frame_t *f)
{
    struct fs_dbc_host_heartbeat_t h;
    memset(&h, 0, sizeof(h));
    h.telemetry_period = telemetry_period_ms;
    h.command_freshness = (uint8_t)host->fv[SECOC_CH_COMMAND]; /* the last command sent */
    memset(f, 0, sizeof(*f));
    f->id = PROTO_ID_HOST_HEARTBEAT(node);
    f->len = FS_DBC_HOST_HEARTBEAT_LENGTH;
    (void)fs_dbc_host_heartbeat_pack(f->data, &h, sizeof(f->data));
    host_protect(host, SECOC_CH_HEARTBEAT, f);
}

static void command_frame(secoc_t *host, uint8_t node, const struct fs_dbc_host_command_t *c,
                          can_frame_t *f)
{
    memset(f, 0, sizeof(*f));
    f->id = PROTO_ID_HOST_COMMAND(node);
    f->len = FS_DBC_HOST_COMMAND_LENGTH;
    (void)fs_dbc_host_command_pack(f->data, c, sizeof(f->data));
    host_protect(host, SECOC_CH_COMMAND, f);
}

unsigned sim_couple_command_frames(secoc_t *host, uint8_t node, uint8_t mode, uint8_t slot,
                                   double goal_scale, double time_scale, uint8_t end,
                                   can_frame_t f[2])
{
    struct fs_dbc_host_command_t c;
    unsigned n = 0u;
    if (mode == APP_CMD_EXECUTE) {
        memset(&c, 0, sizeof(c));
        c.mode = APP_CMD_RUN_OPTIONS;
        c.time_scale = fs_dbc_host_command_time_scale_encode(time_scale);
        c.end_policy = end;
        command_frame(host, node, &c, &f[n++]);
    }
    memset(&c, 0, sizeof(c));
    c.mode = mode;
    c.slot = slot;
    c.goal_scale = fs_dbc_host_command_goal_scale_encode(goal_scale);
    command_frame(host, node, &c, &f[n++]);
    return n;
}

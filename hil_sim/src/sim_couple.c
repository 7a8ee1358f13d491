/* Device <-> plant coupling of one tick (see sim_couple.h). */
#include "sim_couple.h"

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
    for (int k = 0; k < sc->substeps; k++) {
        sim_axis_substep(&ax[0], &drv[0], h);
        sim_axis_substep(&ax[1], &drv[1], h);
    }
}

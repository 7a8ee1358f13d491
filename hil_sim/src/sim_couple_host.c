/* The part of the device <-> plant coupling that reads the host port of hal.h (see sim_couple.h):
 * kept apart so that the Cortex-M image links sim_couple.c without the host port. */
#include "hal_host.h"
#include "sim_couple.h"

bool sim_couple_actuate(const sim_scenario_t *sc, const app_t *app, sim_drive_t drv[2],
                        double cmd_N[2])
{
    bool enable = false;
    fs_real_t f[2];
    hal_host_get_actuator(&enable, f);
    return sim_couple_drive(sc, app_state(app), enable, f, drv, cmd_N);
}

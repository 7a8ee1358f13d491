/* The device's one static instance for a port's main (app.h); its own object file, so builds
 * that keep their own app_t (the simulator, tests) do not carry a second one. */
#include "app_internal.h"

static app_t g_app;
static app_config_t g_cfg;

app_t *app_device(void)
{
    return &g_app;
}

app_config_t *app_device_config(void)
{
    return &g_cfg;
}

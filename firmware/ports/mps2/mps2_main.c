/* The product image on qemu's MPS2 boards: the application (firmware/app, app_tick) on the
 * Cortex-M port of hal.h, run by the 1 kHz SysTick, with the processor-in-the-loop plant around
 * each tick (docs/cortex-m.md). Runs until the board is reset or powered off; every 10 s of
 * device time it reports its load on the semihosting console (`hil_sim pil` shows it). */
#include <stdint.h>

#include "app.h"
#include "cm_board.h"
#include "pil_plant.h"
#include "cm_port.h"
#include "cm_semihost.h"
#include "sim_couple.h"

#define CM_REPORT_TICKS 10000u

static app_t g_app;
static app_config_t g_cfg;
static sim_scenario_t g_sc;

static void report(uint32_t loop_max, uint32_t tick_max)
{
    const uint32_t per_us = CM_CORE_CLOCK_HZ / 1000000u;
    sh_buf_str("fs_pil: tick ");
    sh_buf_u32(g_app.tick);
    sh_buf_str(" state ");
    sh_buf_u32((uint32_t)g_app.state);
    sh_buf_str(" overruns ");
    sh_buf_u32(cm_port_overruns());
    sh_buf_str(" skipped ");
    sh_buf_u32(cm_port_skipped());
    sh_buf_str(" longest loop (plant + app_tick) ");
    sh_buf_u32(loop_max / per_us);
    sh_buf_str(" us, app_tick ");
    sh_buf_u32(tick_max / per_us);
    sh_buf_str(" us\n");
    sh_flush();
}

/* A UDS transfer is open or its request pending (a commit or a verification in slices). */
static bool transferring(const app_t *app)
{
    return app->uds.xfer != UDS_XFER_NONE || app->uds.pending_sid != 0u;
}

/* The kind of the tick just counted (cm_port_mark_idle): xfer if a transfer was open before or
 * after it (the tick that ends one counts with it). */
static void mark_kind(bool xfer)
{
    if (g_app.state == APP_FAULT) {
        cm_port_mark_fault();
    } else if (xfer && g_app.fw_xfer) {
        cm_port_mark_fwupdate();
    } else if (xfer) {
        cm_port_mark_upload();
    } else if (g_app.state == APP_IDLE) {
        cm_port_mark_idle();
    } else if (g_app.state == APP_TEACH) {
        cm_port_mark_teach();
    } else if (g_app.state == APP_EXECUTE) {
        cm_port_mark_execute();
    } else {
        cm_port_mark_other();
    }
}

int main(void)
{
    sim_params_dev_t dev;
    const bool have_params = pil_plant_load(&g_sc, &dev);
    cm_port_init(dev.seed, SIM_PARAMS_SEED_LEN);
    pil_plant_init(&g_sc);
    sim_couple_device_config(&g_sc, &g_cfg);
    g_cfg.node = (uint8_t)dev.node;
    g_cfg.saf.wdg.timeout_ms = (uint16_t)dev.host_timeout_ms;
    app_init(&g_app, &g_cfg);
    sh_puts(have_params ? "fs_pil: started (scenario from hil_sim pil)\n"
                        : "fs_pil: started (no parameter block: plant at rest)\n");
    cm_port_start_ticks(have_params && (dev.flags & SIM_PARAMS_PACE) != 0u);
    uint32_t loop_max = 0u;
    uint32_t tick_max = 0u;
    bool xfer_before = false;
    for (;;) {
        const bool overrun = cm_port_wait_tick();
        const uint32_t c0 = cm_port_cycles();
        pil_plant_sense(&g_app);
        const uint32_t c1 = cm_port_cycles();
        cm_port_mark_begin();
        app_tick(&g_app, overrun);
        cm_port_mark_end();
        const bool xfer_after = transferring(&g_app);
        mark_kind(xfer_before || xfer_after);
        xfer_before = xfer_after;
        const uint32_t c2 = cm_port_cycles();
        pil_plant_advance(&g_app);
        const uint32_t c3 = cm_port_cycles();
        tick_max = (c2 - c1 > tick_max) ? c2 - c1 : tick_max;
        loop_max = (c3 - c0 > loop_max) ? c3 - c0 : loop_max;
        if (g_app.tick % CM_REPORT_TICKS == 0u) {
            report(loop_max, tick_max);
        }
        cm_port_end_tick();
    }
}

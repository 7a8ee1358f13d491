/* The main loop of the product image on qemu's MPS2 boards (cm_main, cm_plant.h): the
 * application (firmware/app, app_tick) on the Cortex-M port of hal.h, run by the 1 kHz SysTick,
 * with the plant the image's `main` passes (the board's sensor/actuator side) around each tick
 * (docs/cortex-m.md). Runs until the board is reset or powered off; every 10 s of device time it
 * reports its load on the semihosting console (`hil_sim pil` shows it). */
#include <stdint.h>

#include "app.h"
#include "cm_board.h"
#include "cm_plant.h"
#include "cm_port.h"
#include "cm_semihost.h"

#define CM_REPORT_TICKS 10000u

static void report(const app_t *app, uint32_t ticks, uint32_t loop_max, uint32_t tick_max)
{
    const uint32_t per_us = CM_CORE_CLOCK_HZ / 1000000u;
    sh_buf_str("fs_pil: tick ");
    sh_buf_u32(ticks);
    sh_buf_str(" state ");
    sh_buf_u32((uint32_t)app_state(app));
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

/* The kind of the tick just counted (cm_port_mark_idle): xfer if a transfer was open before or
 * after it (the tick that ends one counts with it). */
static void mark_kind(const app_t *app, bool xfer, bool fw)
{
    const app_state_t st = app_state(app);
    if (st == APP_FAULT) {
        cm_port_mark_fault();
    } else if (xfer && fw) {
        cm_port_mark_fwupdate();
    } else if (xfer) {
        cm_port_mark_upload();
    } else if (st == APP_IDLE) {
        cm_port_mark_idle();
    } else if (st == APP_TEACH) {
        cm_port_mark_teach();
    } else if (st == APP_EXECUTE) {
        cm_port_mark_execute();
    } else {
        cm_port_mark_other();
    }
}

int cm_main(const cm_plant_t *plant)
{
    app_t *app = app_device();
    cm_plant_params_t p;
    plant->load(&p, app_device_config());
    cm_port_init(p.seed, p.seed_len);
    app_init(app, app_device_config());
    sh_puts(p.loaded ? "fs_pil: started (scenario from hil_sim pil)\n"
                     : "fs_pil: started (no parameter block: plant at rest)\n");
    cm_port_start_ticks(p.loaded && p.pace);
    uint32_t loop_max = 0u;
    uint32_t tick_max = 0u;
    uint32_t ticks = 0u;
    bool xfer_before = false;
    for (;;) {
        const bool overrun = cm_port_wait_tick();
        const uint32_t c0 = cm_port_cycles();
        plant->sense(app, cm_port_sensors());
        const uint32_t c1 = cm_port_cycles();
        cm_port_mark_begin();
        app_tick(app, overrun);
        cm_port_mark_end();
        bool fw = false;
        const bool xfer_after = plant->transfer(app, &fw);
        mark_kind(app, xfer_before || xfer_after, fw);
        xfer_before = xfer_after;
        const uint32_t c2 = cm_port_cycles();
        cm_actuator_t act;
        act.enabled = cm_port_actuator(act.force_N);
        plant->advance(app, &act);
        const uint32_t c3 = cm_port_cycles();
        tick_max = (c2 - c1 > tick_max) ? c2 - c1 : tick_max;
        loop_max = (c3 - c0 > loop_max) ? c3 - c0 : loop_max;
        ticks++;
        if (ticks % CM_REPORT_TICKS == 0u) {
            report(app, ticks, loop_max, tick_max);
        }
        cm_port_end_tick();
    }
}

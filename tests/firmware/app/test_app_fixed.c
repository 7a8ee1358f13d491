/* The application's fixed-point build (fs_app_fx: the Cortex-M3 image's) on the host port: a
 * tick whose DMP step saturates (exec_tick's FS_ERR_FIXED_OVERFLOW) stops the run. The fault
 * "skill invalid" (512) is latched in that tick and the stop ramp starts, the run status holds
 * 300 and the saturated tick is counted; a run that does not saturate keeps executing. */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "app_internal.h"
#include "hal_host.h"
#include "vectors_io.h"

#ifndef FS_EXEC_FIXED
#error "this test is the fixed-point build's (fs_app_fx)"
#endif

static app_t app;
static app_config_t cfg;
static uint64_t t_us;
static uint8_t image[APP_IMAGE_MAX];

static void tick(void)
{
    t_us += 1000u;
    hal_host_set_time_us(t_us);
    app_tick(&app, false);
    can_frame_t f;
    while (hal_sim_can_tx_peek(&f)) {
        hal_sim_can_tx_pop();
    }
}

/* Boot to IDLE with slot 1 holding a press skill (peak 4.84 N at goal 1), then start it. */
static void start_press(void)
{
    hal_host_init();
    hal_host_flash_erase();
    hal_sim_can_reset();
    t_us = 0u;
    hal_sensors_t s;
    memset(&s, 0, sizeof(s));
    s.pos_m[0] = 0.001f;
    hal_host_set_sensors(&s);
    app_config_default(&cfg);
    hal_host_set_time_us(0u);
    app_init(&app, &cfg);
    tick();
    assert_int_equal(app.state, APP_IDLE);
    const uint32_t len = tv_read("press_n50_lwr_hold.skill", image, sizeof image);
    assert_true(len > 0u);
    assert_int_equal(skill_parse(image, len, &app.slot_skill[0]), FS_OK);
    app.slot_valid[0] = true;
    app.slot_peak_N[0] = 4.84f;
    app.slot_path_m[0] = 0.0f;
    app_run_request_t req;
    memset(&req, 0, sizeof req);
    req.source = APP_RUN_FROM_LOCAL;
    req.n_steps = 1u;
    req.step[0].slot = 1u;
    req.step[0].goal_scale = 1.0f;
    req.step[0].time_scale = 1.0f;
    req.step[0].path_scale = 1.0f;
    assert_int_equal(app_run_start(&app, &req), UDS_NRC_OK);
    assert_int_equal(app.state, APP_EXECUTE);
}

static void test_a_run_that_fits_keeps_executing(void **state)
{
    (void)state;
    start_press();
    for (unsigned i = 0; i < 50u; i++) {
        tick();
    }
    assert_int_equal(app.state, APP_EXECUTE);
    assert_int_equal(app.saf_out.fault_code, 0u);
    assert_int_equal(app.exec_saturated_ticks, 0u);
    assert_int_equal(app.exec.dmp.sat_events, 0u);
}

static void test_a_saturated_dmp_step_faults_the_run(void **state)
{
    (void)state;
    start_press();
    for (unsigned i = 0; i < 50u; i++) {
        tick();
    }
    const uint16_t run_status = app.last_run_status;
    assert_int_equal(run_status, FS_OK);
    /* the DMP's force states at the two ends of their range: this tick's z - y leaves Q8.24 */
    app.exec.dmp.y_acc = -(int64_t)FX_ACC_HI_MAX * ((int64_t)1 << 32);
    app.exec.dmp.z_acc = (int64_t)FX_ACC_HI_MAX * ((int64_t)1 << 32);
    tick();
    assert_int_equal(app.exec_saturated_ticks, 1u);
    assert_int_equal(app.last_run_status, FS_ERR_FIXED_OVERFLOW);
    assert_int_equal(app.state, APP_FAULT);
    assert_int_equal(app.saf_out.fault_code, FLT_SKILL_INVALID);
    /* the stop ramp: finite, within the force limit, actuator still on for its 40 ticks */
    assert_true(app.saf_out.actuator_enable);
    for (unsigned a = 0; a < PFC_AXES; a++) {
        assert_true(fs_isfinite(app.force_out_N[a]));
        assert_true(fs_fabs(app.force_out_N[a]) <= cfg.saf.lim.axis[a].force_max_N);
    }
    for (unsigned i = 0; i < 40u; i++) {
        tick();
    }
    assert_false(app.saf_out.actuator_enable);
    assert_int_equal(app.exec_saturated_ticks, 1u); /* FAULT runs no DMP */
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_a_run_that_fits_keeps_executing),
        cmocka_unit_test(test_a_saturated_dmp_step_faults_the_run),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

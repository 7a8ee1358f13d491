/* The application's fixed-point build (fs_app_fx: the Cortex-M3 image's) on the host port: the
 * telemetry's integer scaling against the float64 reference, its rate through a fault; a
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

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "app_internal.h"
#include "fs_dbc.h"
#include "hal_host.h"
#include "proto_ids.h"
#include "vectors_io.h"

#ifndef FS_EXEC_FIXED
#error "this test is the fixed-point build's (fs_app_fx)"
#endif

static app_t app;
static app_config_t cfg;
static uint64_t t_us;
static uint8_t image[APP_IMAGE_MAX];

static struct fs_dbc_telemetry_position_t tel_pos; /* the last telemetry the device sent */
static struct fs_dbc_telemetry_force_t tel_force;
static unsigned n_tel;

static void tick(void)
{
    t_us += 1000u;
    hal_host_set_time_us(t_us);
    app_tick(&app, false);
    can_frame_t f;
    while (hal_sim_can_tx_peek(&f)) {
        if (f.id == PROTO_ID_TELEM_POS(0)) {
            assert_int_equal(fs_dbc_telemetry_position_unpack(&tel_pos, f.data, f.len), 0);
            n_tel++;
        } else if (f.id == PROTO_ID_TELEM_FORCE(0)) {
            assert_int_equal(fs_dbc_telemetry_force_unpack(&tel_force, f.data, f.len), 0);
        }
        hal_sim_can_tx_pop();
    }
}

/* Boot to IDLE with slot 1 holding a press skill (peak 4.84 N at goal 1) and its fixed-point
 * model (the commit's conversion), then start it. */
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
    assert_int_equal(skill_parse(image, len, &app.slots.skill[0]), FS_OK);
    assert_int_equal(dmpfx_from_model_bound(&app.slots.skill[0].dmp, &app.slots.store[0]), FS_OK);
    app.slots.valid[0] = true;
    app.slots.peak_N[0] = 4.84f;
    app.slots.path_m[0] = 0.0f;
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
    assert_int_equal(app.ctl.exec_saturated_ticks, 0u);
    assert_int_equal(app.ctl.exec.dmp.sat_events, 0u);
}

static void test_a_saturated_dmp_step_faults_the_run(void **state)
{
    (void)state;
    start_press();
    for (unsigned i = 0; i < 50u; i++) {
        tick();
    }
    const uint16_t run_status = app.ctl.last_run_status;
    assert_int_equal(run_status, FS_OK);
    /* the DMP's force states at the two ends of their range: this tick's z - y leaves Q8.24 */
    app.ctl.exec.dmp.y_acc = -(int64_t)FX_ACC_HI_MAX * ((int64_t)1 << 32);
    app.ctl.exec.dmp.z_acc = (int64_t)FX_ACC_HI_MAX * ((int64_t)1 << 32);
    tick();
    assert_int_equal(app.ctl.exec_saturated_ticks, 1u);
    assert_int_equal(app.ctl.last_run_status, FS_ERR_FIXED_OVERFLOW);
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
    assert_int_equal(app.ctl.exec_saturated_ticks, 1u); /* FAULT runs no DMP */
}

/* The float64 reference of a telemetry value: v / unit rounded half away from zero, clamped;
 * NaN or infinite -> 0 (the float builds' exec_num_counts, in double). */
static long ref_counts(float v, double unit, long lo, long hi)
{
    if (!isfinite(v)) {
        return 0;
    }
    const double r = (double)v / unit;
    const double c = (r < 0.0) ? ceil(r - 0.5) : floor(r + 0.5);
    return (c > (double)hi) ? hi : ((c < (double)lo) ? lo : (long)c);
}

static float vec_value(unsigned i, float span, uint32_t *rng)
{
    static const float special[] = {0.0f,       -0.0f,      5e-7f,     -5e-7f,  1e-7f,   8.388607f,
                                    -8.388608f, 8.3886075f, 9.0f,      -100.0f, 327.67f, 327.675f,
                                    -327.685f,  -327.68f,   0.005f,    -0.005f, 0.015f,  1e30f,
                                    -1e30f,     INFINITY,   -INFINITY, NAN};
    const unsigned n_special = (unsigned)(sizeof special / sizeof special[0]);
    if (i < n_special) {
        return special[i];
    }
    *rng = *rng * 1664525u + 1013904223u;
    return span * ((float)(*rng >> 8) / 8388608.0f - 1.0f);
}

/* The fixed build's telemetry scaling (integers from the float's bits) against the float64
 * reference on the same sensor values: at most one count apart (a value within a Q format's LSB
 * of a rounding tie), the bound printed. */
static void test_telemetry_counts_match_the_float64_reference(void **state)
{
    (void)state;
    start_press();
    hal_sensors_t s;
    memset(&s, 0, sizeof s);
    uint32_t rng = 12345u;
    long worst_pos = 0, worst_force = 0;
    unsigned differ = 0u, n = 0u;
    for (unsigned i = 0; i < 2000u; i++) {
        s.pos_m[0] = vec_value(i, 10.0f, &rng);
        s.pos_m[1] = vec_value((i * 7u) % 2000u, 0.5f, &rng);
        s.force_contact_N[0] = vec_value(i, 400.0f, &rng);
        s.force_operator_N[0] = vec_value((i * 3u) % 2000u, 30.0f, &rng);
        hal_host_set_sensors(&s);
        const unsigned before = n_tel;
        /* a fault latches on the first wild value: the telemetry kept at 1 kHz in FAULT, as
         * while a host keeps sending */
        app.fault_fast_until_ms = app.now_ms + 10u;
        tick();
        if (n_tel == before) {
            continue;
        }
        const long d[4] = {
            labs((long)tel_pos.pos_x - ref_counts(s.pos_m[0], 1e-6, -8388608, 8388607)),
            labs((long)tel_pos.pos_y - ref_counts(s.pos_m[1], 1e-6, -4194304, 4194303)),
            labs((long)tel_force.force_contact -
                 ref_counts(s.force_contact_N[0], 0.01, -32768, 32767)),
            labs((long)tel_force.force_operator -
                 ref_counts(s.force_operator_N[0], 0.01, -32768, 32767))};
        worst_pos = d[0] > worst_pos ? d[0] : worst_pos;
        worst_pos = d[1] > worst_pos ? d[1] : worst_pos;
        worst_force = d[2] > worst_force ? d[2] : worst_force;
        worst_force = d[3] > worst_force ? d[3] : worst_force;
        differ += (d[0] + d[1] + d[2] + d[3] != 0) ? 1u : 0u;
        n++;
    }
    printf("telemetry_counts fixed vs float64: %u samples, %u with a difference, max |diff| "
           "position %ld um, force %ld x 0.01 N\n",
           n, differ, worst_pos, worst_force);
    assert_true(n > 1900u);
    assert_true(worst_pos <= 1 && worst_force <= 1);
    assert_true(differ * 100u <= n); /* ties are rare: at most 1 % of the samples */
}

/* Host silence during a run: FAULT 500, the telemetry at 1 kHz through the 40 ms stop ramp and
 * 20 ms after it, then IDLE's 100 ms (no host asks for more). */
static void test_telemetry_through_a_fault_then_slow(void **state)
{
    (void)state;
    start_press();
    unsigned guard = 0u;
    while (app.state == APP_EXECUTE && guard++ < 1000u) {
        tick();
    }
    assert_int_equal(app.state, APP_FAULT);
    assert_int_equal(app.saf_out.fault_code, FLT_HOST_SILENCE);
    unsigned fast = 0u;
    for (unsigned i = 0; i < 59u; i++) { /* the latch tick was the first of the 60 */
        const unsigned before = n_tel;
        tick();
        fast += (n_tel == before + 1u) ? 1u : 0u;
    }
    assert_int_equal(fast, 59u);
    assert_false(app.saf_out.actuator_enable); /* the ramp ended inside the fast window */
    const unsigned before = n_tel;
    for (unsigned i = 0; i < 300u; i++) {
        tick();
    }
    assert_true(n_tel - before >= 2u && n_tel - before <= 4u); /* every 100 ms */
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_telemetry_through_a_fault_then_slow),
        cmocka_unit_test(test_telemetry_counts_match_the_float64_reference),
        cmocka_unit_test(test_a_run_that_fits_keeps_executing),
        cmocka_unit_test(test_a_saturated_dmp_step_faults_the_run),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

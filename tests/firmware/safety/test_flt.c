/* Fault list (latching, first fault, emergency queue, guarded clear), sensor plausibility
 * (each sensor fault), the ramp (linear, monotone, exact zero) and the supervisor's clear and
 * re-arm rules. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <math.h>
#include <cmocka.h>

#include "flt.h"
#include "saf.h"

static void test_latch_and_first_fault(void **state)
{
    (void)state;
    flt_state_t f;
    flt_init(&f);
    assert_false(flt_active(&f));
    assert_int_equal(flt_active_code(&f), 0);
    assert_true(flt_raise(&f, FLT_SENSOR_SPIKE, 10));
    assert_false(flt_raise(&f, FLT_SENSOR_SPIKE, 11)); /* already latched: no new frame */
    assert_true(flt_raise(&f, FLT_BUS_OFF, 12));
    assert_false(flt_raise(&f, FLT_NONE, 13));
    assert_false(flt_raise(&f, (flt_code_t)499, 13));
    assert_false(flt_raise(&f, (flt_code_t)(FLT_CODE_FIRST + FLT_COUNT), 13));
    assert_true(flt_active(&f));
    assert_int_equal(flt_active_code(&f), FLT_SENSOR_SPIKE); /* the first one */
    assert_true(flt_is_latched(&f, FLT_BUS_OFF));
    assert_false(flt_is_latched(&f, FLT_HOST_SILENCE));
    /* emergency frames: one per newly latched fault, in order */
    flt_emcy_t e;
    assert_true(flt_emcy_peek(&f, &e)); /* peek keeps it queued */
    assert_int_equal(e.code, FLT_SENSOR_SPIKE);
    assert_true(flt_emcy_peek(&f, &e));
    assert_int_equal(e.code, FLT_SENSOR_SPIKE);
    assert_true(flt_emcy_pop(&f, &e));
    assert_int_equal(e.code, FLT_SENSOR_SPIKE);
    assert_int_equal(e.tick, 10);
    assert_int_equal(e.n_latched, 1);
    assert_true(flt_emcy_pop(&f, &e));
    assert_int_equal(e.code, FLT_BUS_OFF);
    assert_int_equal(e.n_latched, 2);
    assert_int_equal(e.latched_mask, FLT_BIT(FLT_SENSOR_SPIKE) | FLT_BIT(FLT_BUS_OFF));
    assert_false(flt_emcy_pop(&f, &e));
    assert_false(flt_emcy_peek(&f, &e));
    /* clearing refused while a latched fault's cause is present; nothing is cleared */
    assert_int_equal(flt_clear_request(&f, FLT_BIT(FLT_BUS_OFF)), FLT_BUS_OFF);
    assert_true(flt_active(&f));
    assert_int_equal(flt_active_code(&f), FLT_SENSOR_SPIKE);
    /* a present cause of a fault that is not latched does not block */
    assert_int_equal(flt_clear_request(&f, FLT_BIT(FLT_WORKSPACE)), FLT_NONE);
    assert_false(flt_active(&f));
    assert_int_equal(f.raise_count[FLT_SENSOR_SPIKE - FLT_CODE_FIRST], 1);
    /* every code latches, has a name, and the queue holds all of them */
    for (uint32_t c = FLT_CODE_FIRST; c < FLT_CODE_FIRST + FLT_COUNT; c++) {
        assert_true(flt_raise(&f, (flt_code_t)c, c));
        assert_string_not_equal(flt_name((uint16_t)c), "UNKNOWN");
    }
    assert_string_equal(flt_name(0), "NONE");
    assert_string_equal(flt_name(499), "UNKNOWN");
    for (uint32_t c = FLT_CODE_FIRST; c < FLT_CODE_FIRST + FLT_COUNT; c++) {
        assert_true(flt_emcy_pop(&f, &e));
        assert_int_equal(e.code, c);
    }
    assert_false(flt_emcy_pop(&f, &e));
}

static void meas_ok(saf_meas_t m[2], uint32_t k)
{
    /* a plausible, slightly noisy reading */
    m[0].pos_m = FS_R(0.01) + (fs_real_t)(k % 7u) * FS_R(1e-6);
    m[0].vel_mps = FS_R(0.0);
    m[0].force_N = FS_R(10.0) + (fs_real_t)(k % 5u) * FS_R(0.01);
    m[1].pos_m = FS_R(0.0);
    m[1].vel_mps = FS_R(0.0);
    m[1].force_N = FS_R(0.0);
}

static void test_sensor_checks(void **state)
{
    (void)state;
    sen_config_t cfg;
    sen_default_config(&cfg);
    assert_int_equal(sen_config_validate(&cfg), SAF_OK);
    sen_state_t st;
    sen_reset(&st);
    sen_prepare(&cfg, &st);
    saf_meas_t m[2];
    for (uint32_t k = 0; k < 1000; k++) {
        meas_ok(m, k);
        assert_int_equal(sen_check(&cfg, &st, m), 0);
    }
    meas_ok(m, 0);
    m[0].force_N = (fs_real_t)NAN;
    assert_int_equal(sen_check(&cfg, &st, m), FLT_BIT(FLT_SENSOR_NAN));
    meas_ok(m, 1);
    m[1].vel_mps = (fs_real_t)INFINITY;
    assert_int_equal(sen_check(&cfg, &st, m), FLT_BIT(FLT_SENSOR_NAN));
    meas_ok(m, 2);
    assert_int_equal(sen_check(&cfg, &st, m), 0); /* previous good reading kept */
    meas_ok(m, 3);
    m[0].vel_mps = FS_R(11.0);
    assert_int_equal(sen_check(&cfg, &st, m), FLT_BIT(FLT_SENSOR_RANGE));
    meas_ok(m, 4);
    m[1].pos_m = FS_R(1.5); /* also a jump of 1.5 m */
    assert_int_equal(sen_check(&cfg, &st, m),
                     FLT_BIT(FLT_SENSOR_RANGE) | FLT_BIT(FLT_ENCODER_JUMP));
    sen_reset(&st);
    sen_prepare(&cfg, &st);
    meas_ok(m, 5);
    assert_int_equal(sen_check(&cfg, &st, m), 0);
    meas_ok(m, 6);
    m[0].force_N += FS_R(20.5);
    assert_int_equal(sen_check(&cfg, &st, m), FLT_BIT(FLT_SENSOR_SPIKE));
    meas_ok(m, 7);
    m[0].force_N += FS_R(20.5); /* the same offset: no change relative to the last reading */
    assert_int_equal(sen_check(&cfg, &st, m), 0);
    sen_reset(&st);
    sen_prepare(&cfg, &st);
    meas_ok(m, 8);
    assert_int_equal(sen_check(&cfg, &st, m), 0);
    meas_ok(m, 9);
    m[0].pos_m += FS_R(0.006);
    assert_int_equal(sen_check(&cfg, &st, m), FLT_BIT(FLT_ENCODER_JUMP));
    /* stuck: a bit-identical non-zero force for stuck_ticks readings */
    sen_reset(&st);
    sen_prepare(&cfg, &st);
    uint32_t first = 0;
    for (uint32_t k = 1; k <= 1000 && first == 0; k++) {
        meas_ok(m, 0);
        m[0].pos_m = FS_R(0.01) + (fs_real_t)k * FS_R(1e-7);
        if (sen_check(&cfg, &st, m) & FLT_BIT(FLT_SENSOR_STUCK)) {
            first = k;
        }
    }
    assert_int_equal(first, cfg.axis[0].stuck_ticks);
    /* a constant zero force (no contact) is not "stuck" */
    sen_reset(&st);
    sen_prepare(&cfg, &st);
    for (uint32_t k = 0; k < 2000; k++) {
        meas_ok(m, 0);
        m[0].force_N = FS_R(0.0);
        assert_int_equal(sen_check(&cfg, &st, m), 0);
    }
}

static void test_ramp(void **state)
{
    (void)state;
    wdg_config_t c;
    wdg_default_config(&c);
    assert_int_equal(wdg_config_validate(&c), SAF_OK);
    assert_int_equal(wdg_ramp_ticks(&c), 40);
    wdg_ramp_t r;
    const fs_real_t from[2] = {FS_R(-37.3), FS_R(12.0)};
    wdg_ramp_start(&r, &c, from);
    fs_real_t out[2], prev[2] = {from[0], from[1]};
    uint32_t k = 0;
    bool done = false;
    while (!done) {
        done = wdg_ramp_step(&r, out);
        k++;
        for (int i = 0; i < 2; i++) {
            assert_true(fabs((double)out[i]) <= fabs((double)prev[i]));
            /* linear: from * (n - k) / n */
            assert_true(fabs((double)out[i] - (double)from[i] * (40.0 - k) / 40.0) < 1e-4);
            prev[i] = out[i];
        }
    }
    assert_int_equal(k, 40);
    assert_true(out[0] == FS_R(0.0) && out[1] == FS_R(0.0));
    assert_true(wdg_ramp_step(&r, out));
    /* configuration limits */
    c.timeout_ms = 19;
    assert_int_equal(wdg_config_validate(&c), SAF_ERR_TIMEOUT);
    c.timeout_ms = 501;
    assert_int_equal(wdg_config_validate(&c), SAF_ERR_TIMEOUT);
    c.timeout_ms = 500;
    c.ramp_ms = 51;
    assert_int_equal(wdg_config_validate(&c), SAF_ERR_RAMP);
    c.ramp_ms = 0;
    assert_int_equal(wdg_config_validate(&c), SAF_ERR_RAMP);
    /* the slew limit must allow the ramp */
    saf_config_t sc;
    saf_default_config(&sc);
    assert_int_equal(saf_config_validate(&sc), SAF_OK);
    sc.lim.axis[0].slew_max_N = FS_R(1.0); /* 1 N/tick * 40 ticks < 50 N */
    assert_int_equal(saf_config_validate(&sc), SAF_ERR_RAMP);
}

static void tick(const saf_config_t *cfg, saf_state_t *st, saf_input_t *in, saf_output_t *out,
                 uint32_t k, bool host, fs_real_t req)
{
    in->tick = k;
    in->now_ms = k;
    in->host_frame = host;
    meas_ok(in->meas, k);
    in->force_req_N[0] = req;
    in->force_req_N[1] = FS_R(0.0);
    saf_step(cfg, st, in, out);
}

static void test_supervisor_clear_and_no_resume(void **state)
{
    (void)state;
    saf_config_t cfg;
    saf_default_config(&cfg);
    saf_state_t st;
    saf_init(&st);
    saf_prepare(&cfg, &st);
    saf_input_t in;
    memset(&in, 0, sizeof in);
    saf_output_t out;
    uint32_t k = 0;
    for (; k < 100; k++) {
        tick(&cfg, &st, &in, &out, k, true, FS_R(30.0));
    }
    assert_true(fabs((double)out.force_cmd_N[0] - 30.0) < 1e-9);
    /* bus-off for 5 ticks: latched, ramp, actuator off */
    for (uint32_t j = 0; j < 5; j++, k++) {
        in.causes = FLT_BIT(FLT_BUS_OFF);
        tick(&cfg, &st, &in, &out, k, true, FS_R(30.0));
    }
    assert_int_equal(out.fault_code, FLT_BUS_OFF);
    /* a clear while the bus is still off is refused */
    assert_int_equal(saf_clear_request(&cfg, &st, k), FLT_BUS_OFF);
    in.causes = 0u;
    for (uint32_t j = 0; j < 100; j++, k++) {
        tick(&cfg, &st, &in, &out, k, true, FS_R(30.0));
    }
    /* the cause is gone but the fault stays latched and the output stays off: no resume */
    assert_true(out.stopping);
    assert_false(out.actuator_enable);
    assert_true(out.force_cmd_N[0] == FS_R(0.0));
    assert_int_equal(out.fault_code, FLT_BUS_OFF);
    /* clear accepted; the skill's request (still 30 N) does not come back by itself */
    assert_int_equal(saf_clear_request(&cfg, &st, k), FLT_NONE);
    for (uint32_t j = 0; j < 100; j++, k++) {
        tick(&cfg, &st, &in, &out, k, true, FS_R(30.0));
        assert_true(out.force_cmd_N[0] == FS_R(0.0));
        assert_true(out.actuator_enable);
        assert_int_equal(out.fault_code, 0);
    }
    /* only after a zero request (the application went to IDLE) does a new command act */
    tick(&cfg, &st, &in, &out, k++, true, FS_R(0.0));
    tick(&cfg, &st, &in, &out, k++, true, FS_R(30.0));
    assert_true(fabs((double)out.force_cmd_N[0] - 2.0) < 1e-9); /* and slew-limited */
    /* host silence: the clear request is itself a host frame, so it is accepted */
    for (uint32_t j = 0; j < 200; j++, k++) {
        tick(&cfg, &st, &in, &out, k, false, FS_R(30.0));
    }
    assert_int_equal(out.fault_code, FLT_HOST_SILENCE);
    assert_int_equal(saf_clear_request(&cfg, &st, k), FLT_NONE);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_latch_and_first_fault),
        cmocka_unit_test(test_sensor_checks),
        cmocka_unit_test(test_ramp),
        cmocka_unit_test(test_supervisor_clear_and_no_resume),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

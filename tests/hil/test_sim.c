/* Tests of the HIL models (hil_sim/src): references are the published splitmix64 output, analytic
 * motion under a constant force, the static equilibrium of the two-layer object, the 16-bit
 * quantisation step, and the scenario parser's file:line messages. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "sim_model.h"
#include "sim_rng.h"
#include "sim_scenario.h"

/* splitmix64 seeded with 0 gives 0xE220A8397B1DCDAF first (Vigna's reference splitmix64.c). */
static void test_rng_reference_and_determinism(void **state)
{
    (void)state;
    sim_rng_t a, b;
    sim_rng_seed(&a, 0);
    assert_true(a.s[0] == 0xE220A8397B1DCDAFull);
    sim_rng_seed(&a, 42);
    sim_rng_seed(&b, 42);
    for (int i = 0; i < 1000; i++) {
        assert_true(sim_rng_next(&a) == sim_rng_next(&b));
    }
    double sum = 0.0, sq = 0.0;
    for (int i = 0; i < 100000; i++) {
        const double g = sim_rng_gauss(&a);
        sum += g;
        sq += g * g;
    }
    assert_true(fabs(sum / 1e5) < 0.02);
    assert_true(fabs(sq / 1e5 - 1.0) < 0.02);
}

static const sim_object_t OBJ = {0.0, 0.001, 100.0, 180.0, 0.019, 50.0, 10.0, 0.0};

static void test_object_spring(void **state)
{
    (void)state;
    assert_true(sim_object_spring_N(&OBJ, -0.01) == 0.0);
    assert_true(fabs(sim_object_spring_N(&OBJ, 0.01) - 1.0) < 1e-12);
    assert_true(fabs(sim_object_spring_N(&OBJ, 0.029) - (1.9 + 1.8)) < 1e-12);
}

static sim_drive_t teach_drive(double force_N, const sim_object_t *obj)
{
    sim_drive_t d;
    memset(&d, 0, sizeof d);
    d.kind = SIM_PLANT_IDEAL;
    d.mass_kg = 40.0;
    d.force_ext_N = force_N;
    d.hand_damping_Nspm = 0.0;
    d.object = obj;
    sim_drive_prepare(&d);
    return d;
}

/* constant force, no object: x = F/(2m) t^2 (semi-implicit Euler: relative error ~ h/t) */
static void test_free_motion_analytic(void **state)
{
    (void)state;
    sim_axis_t a;
    memset(&a, 0, sizeof a);
    sim_drive_t d = teach_drive(4.0, NULL);
    for (int n = 0; n < 10000; n++) {
        sim_axis_substep(&a, &d, 1e-4);
    }
    const double exact = 4.0 / 80.0 * 1.0;
    assert_true(fabs(a.pos_m - exact) / exact < 2e-4);
    assert_true(fabs(a.vel_mps - 0.1) < 1e-12);
}

/* constant operator force on the two-layer object settles where F(p) = f; contact = f */
static void test_static_equilibrium_two_layers(void **state)
{
    (void)state;
    sim_axis_t a;
    memset(&a, 0, sizeof a);
    a.pos_m = 0.001;
    sim_drive_t d = teach_drive(3.0, &OBJ);
    d.hand_damping_Nspm = 30.0;
    for (int n = 0; n < 400000; n++) {
        sim_axis_substep(&a, &d, 1e-4);
    }
    const double p_exp = 0.019 + (3.0 - 1.9) / 180.0;
    assert_true(fabs((a.pos_m - 0.001) - p_exp) < 1e-7);
    assert_true(fabs(a.contact_N - 3.0) < 1e-5);
}

/* the object never pulls: a retracting tool sees contact >= 0; prescribed (ideal EXECUTE) too */
static void test_unilateral_contact(void **state)
{
    (void)state;
    sim_axis_t a;
    memset(&a, 0, sizeof a);
    a.pos_m = 0.011;
    sim_drive_t d = teach_drive(-20.0, &OBJ);
    int opened = 0;
    for (int n = 0; n < 20000; n++) {
        sim_axis_substep(&a, &d, 1e-4);
        assert_true(a.contact_N >= 0.0);
        if (a.contact_N == 0.0 && a.pos_m > 0.001) {
            opened = 1;
        }
    }
    assert_true(opened); /* damping would have pulled: the contact opened inside the object */
    sim_drive_t e = d;
    e.prescribed = 1;
    e.force_cmd_N = -400.0;
    sim_drive_prepare(&e);
    memset(&a, 0, sizeof a);
    a.pos_m = 0.005;
    sim_axis_substep(&a, &e, 1e-4);
    assert_true(a.contact_N == 0.0);
    assert_true(fabs(a.acc_mps2 + 10.0) < 1e-12);
}

/* realistic: actuator lag 0.5 ms (63 % after one time constant) and the +-limit */
static void test_actuator_lag_and_limit(void **state)
{
    (void)state;
    sim_carriage_t c = {2.0, 200.0, 0.0005, 0.0, 0.0};
    sim_axis_t a;
    memset(&a, 0, sizeof a);
    sim_drive_t d;
    memset(&d, 0, sizeof d);
    d.kind = SIM_PLANT_REALISTIC;
    d.mass_kg = 2.0;
    d.carriage = &c;
    d.force_cmd_N = 500.0; /* above the limit */
    d.act_limit_N = 200.0;
    d.act_alpha = 1.0 - exp(-1e-5 / 0.0005);
    sim_drive_prepare(&d);
    for (int n = 0; n < 50; n++) { /* 0.5 ms at 10 us */
        sim_axis_substep(&a, &d, 1e-5);
    }
    assert_true(fabs(a.act_N - 200.0 * (1.0 - exp(-1.0))) < 1e-9);
    for (int n = 0; n < 2000; n++) {
        sim_axis_substep(&a, &d, 1e-5);
    }
    assert_true(a.act_N <= 200.0 && a.act_N > 199.99);
}

static void test_coulomb_friction_sticks(void **state)
{
    (void)state;
    sim_carriage_t c = {2.0, 200.0, 0.0005, 5.0, 1.0};
    sim_axis_t a;
    memset(&a, 0, sizeof a);
    sim_drive_t d;
    memset(&d, 0, sizeof d);
    d.kind = SIM_PLANT_REALISTIC;
    d.mass_kg = 2.0;
    d.carriage = &c;
    d.force_cmd_N = 0.9; /* below the 1 N Coulomb force: stays */
    d.act_limit_N = 200.0;
    d.act_alpha = 1.0 - exp(-1e-4 / 0.0005);
    sim_drive_prepare(&d);
    for (int n = 0; n < 10000; n++) {
        sim_axis_substep(&a, &d, 1e-4);
    }
    assert_true(a.pos_m == 0.0);
    d.force_cmd_N = 2.0; /* 1 N net: steady state v = 1/5 m/s */
    for (int n = 0; n < 100000; n++) {
        sim_axis_substep(&a, &d, 1e-4);
    }
    assert_true(fabs(a.vel_mps - 0.2) < 1e-3);
}

static void test_sensor_quantisation(void **state)
{
    (void)state;
    sim_rng_t r;
    sim_rng_seed(&r, 1);
    sim_force_sensor_t s = {0.0, 0.0, 100.0, 16u};
    const double lsb = 100.0 / 32768.0;
    assert_true(fabs(sim_force_read(&s, 1.0, &r) - lsb * floor(1.0 / lsb + 0.5)) < 1e-15);
    assert_true(fabs(sim_force_read(&s, 500.0, &r) - 32767.0 * lsb) < 1e-12);
    assert_true(fabs(sim_force_read(&s, -500.0, &r) + 100.0) < 1e-12);
    s.bias_N = 0.5;
    assert_true(fabs(sim_force_read(&s, 1.0, &r) - lsb * floor(1.5 / lsb + 0.5)) < 1e-15);
    assert_true(fabs(sim_encoder_read(0.0123456789, 1e-6) - 0.012346) < 1e-15);
}

/* engraving operator: levels inside the configured range, zero at the start and after release */
static void test_engraving_operator(void **state)
{
    (void)state;
    sim_scenario_t sc;
    sim_scenario_defaults(&sc);
    sim_operator_cfg_t c = sc.op;
    c.task = SIM_TASK_ENGRAVING;
    c.duration_s = 8.0;
    c.release_s = 0.8;
    c.tremor_frac = 0.0;
    sim_rng_t r;
    sim_rng_seed(&r, 3);
    sim_operator_t op;
    sim_operator_init(&op, &c, &r);
    assert_true(op.n_levels >= 3);
    double f[2];
    sim_operator_force(&op, 0.0, 0.0, 0.019, f);
    assert_true(f[0] == 0.0);
    for (double t = 1.0; t < 7.2; t += 0.01) {
        sim_operator_force(&op, t, 0.0, 0.019, f);
        assert_true(f[0] >= c.level_min_N - 1e-9 && f[0] <= c.level_max_N + 1e-9);
    }
    sim_operator_force(&op, 8.0, 0.0, 0.019, f);
    assert_true(fabs(f[0]) < 1e-12);
}

/* pressing operator: goes high only after the inner layer is reached plus the reaction time */
static void test_pressing_operator_waits_for_layer(void **state)
{
    (void)state;
    sim_scenario_t sc;
    sim_scenario_defaults(&sc);
    sim_operator_cfg_t c = sc.op;
    c.task = SIM_TASK_PRESSING;
    c.duration_s = 8.0;
    c.release_s = 0.0;
    c.tremor_frac = 0.0;
    c.jitter = 0.0;
    sim_rng_t r;
    sim_rng_seed(&r, 3);
    sim_operator_t op;
    sim_operator_init(&op, &c, &r);
    double f[2];
    for (double t = 0.0; t < 2.0; t += 0.001) {
        sim_operator_force(&op, t, 0.01, 0.019, f); /* not at the layer */
    }
    assert_true(fabs(f[0] - c.low_N) < 1e-12);
    sim_operator_force(&op, 2.0, 0.019, 0.019, f); /* layer reached at t = 2 */
    sim_operator_force(&op, 2.0 + op.reaction_s - 0.001, 0.02, 0.019, f);
    assert_true(fabs(f[0] - c.low_N) < 1e-12);
    assert_true(op.reaction_s >= 0.2 && op.reaction_s <= 0.35);
    sim_operator_force(&op, 2.0 + op.reaction_s + c.ramp_s, 0.03, 0.019, f);
    assert_true(fabs(f[0] - c.high_N) < 1e-12);
}

static void test_scenario_parse_ok(void **state)
{
    (void)state;
    sim_scenario_t sc;
    char err[SIM_ERR_MAX];
    sim_scenario_defaults(&sc);
    const char *text = "# comment\nname = \"x\"  # trailing\nmode = \"execute\"\nseed = 7\n"
                       "[object]\nk1_Npm = 250\n[execute]\nskills = [\"a.skill\", \"b.skill\"]\n"
                       "step_durations_s = [8, 9.5]\ngoal_scale = 1.5\nmodel = \"none\"\n"
                       "[fault]\nkind = \"force_spike\"\nat_s = 1\nvalue = 5\n";
    assert_int_equal(sim_scenario_parse(&sc, text, "t.toml", err), 0);
    assert_string_equal(sc.name, "x");
    assert_int_equal(sc.mode, SIM_MODE_EXECUTE);
    assert_true(sc.seed == 7u);
    assert_true(sc.object.k1_Npm == 250.0);
    assert_int_equal(sc.n_skills, 2);
    assert_string_equal(sc.skill_path[1], "b.skill");
    assert_true(sc.step_duration_s[1] == 9.5);
    assert_true(sc.goal_scale == 1.5);
    assert_int_equal(sc.use_model, 0);
    assert_int_equal(sc.fault.kind, SIM_FAULT_FORCE_SPIKE);
    assert_int_equal(sim_scenario_check(&sc, err), 0);
}

static void expect_error(const char *text, const char *needle)
{
    sim_scenario_t sc;
    char err[SIM_ERR_MAX];
    sim_scenario_defaults(&sc);
    assert_int_equal(sim_scenario_parse(&sc, text, "bad.toml", err), -1);
    if (strstr(err, needle) == NULL) {
        fail_msg("message '%s' lacks '%s'", err, needle);
    }
}

static void test_scenario_errors_name_file_and_line(void **state)
{
    (void)state;
    expect_error("name = \"a\"\n\n[object]\nfoo = 1\n", "bad.toml:4: unknown key 'foo' in [object]");
    expect_error("[objects]\n", "bad.toml:1: unknown section [objects]");
    expect_error("duration_s = \"long\"\n", "bad.toml:1: 'duration_s' must be a number");
    expect_error("name = \"a\n", "bad.toml:1: unterminated string");
    expect_error("\n[object]\nk1_Npm = -5\n", "bad.toml:3: 'k1_Npm' = -5 is outside");
    expect_error("seed = 1.5\n", "bad.toml:1: 'seed' must be an integer");
    expect_error("[execute]\nskills = [\"a\", 2]\n", "bad.toml:2: array mixes");
    expect_error("mode = \"dance\"\n", "mode must be \"teach\" or \"execute\"");
    expect_error("duration_s = 5 6\n", "bad.toml:1: unexpected text after the value");
    expect_error("just words\n", "bad.toml:1: expected 'key = value'");
    expect_error("[fault]\nkind = \"meteor\"\n", "bad.toml:2: fault kind must be one of");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_rng_reference_and_determinism),
        cmocka_unit_test(test_object_spring),
        cmocka_unit_test(test_free_motion_analytic),
        cmocka_unit_test(test_static_equilibrium_two_layers),
        cmocka_unit_test(test_unilateral_contact),
        cmocka_unit_test(test_actuator_lag_and_limit),
        cmocka_unit_test(test_coulomb_friction_sticks),
        cmocka_unit_test(test_sensor_quantisation),
        cmocka_unit_test(test_engraving_operator),
        cmocka_unit_test(test_pressing_operator_waits_for_layer),
        cmocka_unit_test(test_scenario_parse_ok),
        cmocka_unit_test(test_scenario_errors_name_file_and_line),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

/* Tests of firmware/app/fs_exec (skill execution). References: the Python rollouts of the golden
 * vectors (tests/vectors, written by host/forceskill), the analytic static deformation of the
 * two-layer object, the control law's y-axis expression with the default gains, and exact
 * linearity of goal scaling. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "fs_exec.h"

#ifndef FS_VECTORS_DIR
#error "FS_VECTORS_DIR must be defined"
#endif

#define DT 0.001

static skill_t g_press;   /* press_n50_ridge_release.skill */
static skill_t g_engrave; /* engrave_n50_lwr_hold.skill */
static skill_t g_wipe;    /* periodic_n50_ridge.skill (format v4, periodic) */

static void load_skill(const char *name, skill_t *out)
{
    char path[512];
    static uint8_t buf[16384];
    snprintf(path, sizeof path, "%s/%s", FS_VECTORS_DIR, name);
    FILE *f = fopen(path, "rb");
    assert_non_null(f);
    size_t n = fread(buf, 1, sizeof buf, f);
    fclose(f);
    assert_int_equal(skill_parse(buf, (uint32_t)n, out), FS_OK);
}

/* the golden rollout t,f_hat[,y_hat] into f (and y, a skill with a y path, unless NULL);
 * returns rows */
static size_t load_rollout_xy(const char *name, double *f, double *y, size_t cap)
{
    char path[512];
    snprintf(path, sizeof path, "%s/%s", FS_VECTORS_DIR, name);
    FILE *fp = fopen(path, "r");
    assert_non_null(fp);
    char line[256];
    size_t n = 0;
    assert_non_null(fgets(line, sizeof line, fp)); /* header */
    while (fgets(line, sizeof line, fp) != NULL && n < cap) {
        double t = 0.0, y_n = 0.0;
        const int got = sscanf(line, "%lf,%lf,%lf", &t, &f[n], &y_n);
        assert_true(got == ((y != NULL) ? 3 : 2) || (y == NULL && got == 3));
        if (y != NULL) {
            y[n] = y_n;
        }
        n++;
    }
    fclose(fp);
    return n;
}

/* the golden rollout t,f_hat; returns rows */
static size_t load_rollout(const char *name, double *f, size_t cap)
{
    return load_rollout_xy(name, f, NULL, cap);
}

static int setup(void **state)
{
    (void)state;
    load_skill("press_n50_ridge_release.skill", &g_press);
    load_skill("engrave_n50_lwr_hold.skill", &g_engrave);
    load_skill("periodic_n50_ridge.skill", &g_wipe);
    return 0;
}

static exec_meas_t zero_meas(void)
{
    exec_meas_t m;
    memset(&m, 0, sizeof m);
    return m;
}

static exec_step_t step_of(const skill_t *s, double goal, double ts, double dur, skill_end_t end)
{
    exec_step_t st = {s, goal, ts, dur, end, 1.0, 1.0, 0u, 0};
    return st;
}

/* Open loop (measurements held at 0 but the contact force at the skill's starting force f0, so
 * execution starts where the skill does), no model: f_hat equals the Python reference rollout. */
static void run_golden(const skill_t *sk, const char *csv, double goal, double ts)
{
    static double ref[40000];
    size_t rows = load_rollout(csv, ref, 40000);
    assert_true(rows > 100);
    exec_config_t cfg;
    exec_config_default(&cfg);
    static exec_state_t st;
    exec_step_t s = step_of(sk, goal, ts, 0.0, SKILL_END_HOLD);
    assert_int_equal(exec_start(&cfg, &st, &s, 1, 0.0), FS_OK);
    double fmax = 0.0;
    for (size_t i = 0; i < rows; i++) {
        fmax = fmax > fabs(ref[i]) ? fmax : fabs(ref[i]);
    }
    exec_meas_t m = zero_meas();
    m.force_contact_N = sk->dmp.force0_N;
    double worst = 0.0;
    for (size_t n = 1; n < rows; n++) {
        exec_out_t o;
        assert_int_equal(exec_tick(&cfg, &st, &m, &o), FS_OK);
        double e = fabs(o.force_hat_N - ref[n]);
        worst = e > worst ? e : worst;
    }
    assert_true(worst <= 1e-6 * fmax);
}

static void test_open_loop_matches_python_rollouts(void **state)
{
    (void)state;
    run_golden(&g_press, "press_n50_ridge_release_g1_t1.csv", 1.0, 1.0);
    run_golden(&g_press, "press_n50_ridge_release_g1p5_t1.csv", 1.5, 1.0);
    run_golden(&g_press, "press_n50_ridge_release_g1_t1p3.csv", 1.0, 1.3);
    run_golden(&g_engrave, "engrave_n50_lwr_hold_g1p5_t1p3.csv", 1.5, 1.3);
}

static void test_goal_scaling_is_exact(void **state)
{
    (void)state;
    exec_config_t cfg;
    exec_config_default(&cfg);
    static exec_state_t a, b;
    exec_step_t s1 = step_of(&g_engrave, 1.0, 1.0, 0.0, SKILL_END_HOLD);
    exec_step_t s2 = step_of(&g_engrave, 1.5, 1.0, 0.0, SKILL_END_HOLD);
    assert_int_equal(exec_start(&cfg, &a, &s1, 1, 0.0), FS_OK);
    assert_int_equal(exec_start(&cfg, &b, &s2, 1, 0.0), FS_OK);
    exec_meas_t m = zero_meas();
    const double f0 = g_engrave.dmp.force0_N;
    assert_true(f0 > 0.5); /* the engraving vector starts in contact */
    m.force_contact_N = f0;
    for (int n = 0; n < 6000; n++) {
        exec_out_t oa, ob;
        exec_tick(&cfg, &a, &m, &oa);
        exec_tick(&cfg, &b, &m, &ob);
        /* exact for the part above the starting force */
        assert_true(fabs((ob.force_hat_N - f0) - 1.5 * (oa.force_hat_N - f0)) <=
                    1e-9 * (1.0 + fabs(ob.force_hat_N)));
    }
}

/* Execution starts from the measured contact force without a jump, whatever the skill's f0, and
 * follows the skill's own profile once the difference has faded out (EXEC_BLEND_S). */
static void test_starts_from_measured_force(void **state)
{
    (void)state;
    static double ref[40000];
    const size_t rows = load_rollout("engrave_n50_lwr_hold_g1_t1.csv", ref, 40000);
    exec_config_t cfg;
    exec_config_default(&cfg);
    const double measured[] = {0.0, 2.7, -0.3};
    for (size_t j = 0; j < 3; j++) {
        static exec_state_t st;
        exec_step_t s = step_of(&g_engrave, 1.0, 1.0, 0.0, SKILL_END_HOLD);
        assert_int_equal(exec_start(&cfg, &st, &s, 1, 0.0), FS_OK);
        exec_meas_t m = zero_meas();
        m.force_contact_N = measured[j];
        double prev = measured[j];
        double max_step = 0.0;
        double worst_after = 0.0;
        const size_t blend_rows = (size_t)(EXEC_BLEND_S / 0.001);
        for (size_t n = 1; n < rows; n++) {
            exec_out_t o;
            assert_int_equal(exec_tick(&cfg, &st, &m, &o), FS_OK);
            max_step = fmax(max_step, fabs(o.force_hat_N - prev));
            prev = o.force_hat_N;
            if (n >= blend_rows) {
                worst_after = fmax(worst_after, fabs(o.force_hat_N - ref[n]));
            }
        }
        /* no jump: the largest change per tick is the skill's own slope (< 0.05 N/ms here) */
        assert_true(max_step < 0.05);
        assert_true(worst_after <= 1e-9 * 10.0);
    }
}

/* surface_from_contact: the reference is built on x - f/k measured at the first tick, not on the
 * configured surface (0.5 mm off here); without it, on the configured one. */
static void test_surface_from_contact(void **state)
{
    (void)state;
    exec_config_t cfg;
    exec_config_default(&cfg);
    const double k = g_engrave.stiffness_Npm;
    const double surface = 0.001, f_c = 2.0;
    cfg.object.surface_m = surface + 0.0005;
    for (int from_contact = 0; from_contact <= 1; from_contact++) {
        cfg.surface_from_contact = (uint8_t)from_contact;
        static exec_state_t st;
        exec_step_t s = step_of(&g_engrave, 1.0, 1.0, 0.0, SKILL_END_HOLD);
        assert_int_equal(exec_start(&cfg, &st, &s, 1, 0.0), FS_OK);
        exec_meas_t m = zero_meas();
        m.pos_m[0] = surface + f_c / k;
        m.force_contact_N = f_c;
        for (int n = 0; n < 50; n++) {
            exec_out_t o;
            assert_int_equal(exec_tick(&cfg, &st, &m, &o), FS_OK);
            const double want = (from_contact ? surface : surface + 0.0005) + o.force_hat_N / k;
            assert_true(fabs(o.pos_ref_m - want) <= 1e-12);
        }
    }
}

/* hold keeps the last force; release ramps linearly to 0 in 0.5 s, then done */
static void test_end_policies(void **state)
{
    (void)state;
    exec_config_t cfg;
    exec_config_default(&cfg);
    static exec_state_t st;
    exec_meas_t m = zero_meas();
    exec_out_t o;
    const int n_dur = 2000; /* 2 s step */
    for (int pol = 0; pol < 2; pol++) {
        exec_step_t s = step_of(&g_press, 1.0, 1.0, 2.0, pol ? SKILL_END_RELEASE : SKILL_END_HOLD);
        assert_int_equal(exec_start(&cfg, &st, &s, 1, 0.0), FS_OK);
        double f_end = 0.0;
        for (int n = 0; n < n_dur; n++) {
            exec_tick(&cfg, &st, &m, &o);
            f_end = o.force_hat_N;
        }
        assert_true(f_end > 0.5);
        for (int n = 1; n <= 1000; n++) {
            exec_tick(&cfg, &st, &m, &o);
            if (pol == 0) {
                assert_true(o.force_hat_N == f_end);
                assert_int_equal(o.done, 0);
            } else if (n < 500) {
                assert_true(fabs(o.force_hat_N - f_end * (1.0 - n * DT / 0.5)) < 1e-9 * f_end);
            } else {
                assert_true(o.force_hat_N == 0.0);
                assert_int_equal(o.done, 1);
            }
        }
    }
}

/* Sequence A (1.2 s of a 1.5 s skill) then B: no jump at the switch, and B's own profile after EXEC_BLEND_S. */
static void test_sequence_continuity(void **state)
{
    (void)state;
    exec_config_t cfg;
    exec_config_default(&cfg);
    static exec_state_t seq, solo;
    exec_step_t steps[2] = {step_of(&g_press, 1.0, 1.0, 1.2, SKILL_END_HOLD),
                            step_of(&g_engrave, 1.0, 1.0, 0.0, SKILL_END_HOLD)};
    assert_int_equal(exec_start(&cfg, &seq, steps, 2, 0.0), FS_OK);
    assert_int_equal(exec_start(&cfg, &solo, &steps[1], 1, 0.0), FS_OK);
    exec_meas_t m = zero_meas();
    exec_out_t o, os;
    double prev = 0.0, max_step_a = 0.0, f_switch = 0.0;
    for (int n = 0; n < 1200; n++) {
        exec_tick(&cfg, &seq, &m, &o);
        if (n > 0) {
            max_step_a = fmax(max_step_a, fabs(o.force_hat_N - prev));
        }
        prev = o.force_hat_N;
        f_switch = prev;
    }
    assert_int_equal(o.step, 1);
    assert_true(f_switch > 1.0);   /* a naive restart would drop by this much */
    exec_tick(&cfg, &seq, &m, &o); /* first tick of B */
    exec_tick(&cfg, &solo, &m, &os);
    assert_true(fabs(o.force_hat_N - f_switch) <= 2.0 * max_step_a);
    assert_true(fabs(o.force_hat_N - f_switch) < 0.01 * f_switch);
    const int n_blend = (int)(EXEC_BLEND_S / DT + 0.5);
    for (int n = 1; n < n_blend + 1000; n++) {
        exec_tick(&cfg, &seq, &m, &o);
        exec_tick(&cfg, &solo, &m, &os);
        if (n >= n_blend) {
            assert_true(o.force_hat_N == os.force_hat_N);
        }
    }
}

/* With the object model the reference settles where F(p) = f_hat (held): analytic two-layer inverse. */
static void test_model_reference_static_inverse(void **state)
{
    (void)state;
    exec_config_t cfg;
    exec_config_default(&cfg);
    cfg.use_model = 1;
    cfg.object = (exec_object_t){10.0, 50.0, 100.0, 180.0, 0.019, 0.001};
    static exec_state_t st;
    exec_step_t s = step_of(&g_press, 1.0, 1.0, 2.0, SKILL_END_HOLD);
    assert_int_equal(exec_start(&cfg, &st, &s, 1, 0.0), FS_OK);
    exec_meas_t m = zero_meas();
    exec_out_t o;
    double p_prev = 0.0, pd_prev = 0.0;
    for (int n = 0; n < 30000; n++) {
        exec_tick(&cfg, &st, &m, &o);
        /* every tick: the object's equation holds for the reference it produced */
        const double lhs = 10.0 * st.ref_pdd + 50.0 * pd_prev +
                           exec_object_force(&cfg.object, p_prev);
        if (st.ref_p > 0.0) {
            assert_true(fabs(lhs - o.force_hat_N) < 1e-9 * (1.0 + fabs(o.force_hat_N)));
        }
        p_prev = st.ref_p;
        pd_prev = st.ref_pd;
    }
    const double f = o.force_hat_N;
    const double f1 = 100.0 * 0.019;
    const double p_exp = (f <= f1) ? f / 100.0 : 0.019 + (f - f1) / 180.0;
    assert_true(fabs((o.pos_ref_m - 0.001) - p_exp) < 1e-6);
}

static void test_nonfinite_measurement_commands_zero(void **state)
{
    (void)state;
    exec_config_t cfg;
    exec_config_default(&cfg);
    static exec_state_t st;
    exec_step_t s = step_of(&g_press, 1.0, 1.0, 0.0, SKILL_END_HOLD);
    assert_int_equal(exec_start(&cfg, &st, &s, 1, 0.0), FS_OK);
    exec_meas_t m = zero_meas();
    m.force_contact_N = NAN;
    exec_out_t o;
    assert_int_equal(exec_tick(&cfg, &st, &m, &o), FS_ERR_NOT_FINITE);
    assert_true(o.force_cmd_N[0] == 0.0 && o.force_cmd_N[1] == 0.0);
    m = zero_meas();
    m.pos_m[1] = INFINITY;
    assert_int_equal(exec_tick(&cfg, &st, &m, &o), FS_ERR_NOT_FINITE);
}

static void test_start_validation(void **state)
{
    (void)state;
    exec_config_t cfg;
    exec_config_default(&cfg);
    static exec_state_t st;
    exec_step_t s[9];
    for (int i = 0; i < 9; i++) {
        s[i] = step_of(&g_press, 1.0, 1.0, 0.0, SKILL_END_HOLD);
    }
    assert_int_equal(exec_start(&cfg, &st, s, 0, 0.0), FS_ERR_SCALE_INVALID);
    assert_int_equal(exec_start(&cfg, &st, s, 9, 0.0), FS_ERR_SCALE_INVALID);
    assert_int_equal(exec_start(&cfg, &st, s, 8, 0.0), FS_OK);
    s[3].skill = NULL;
    assert_int_equal(exec_start(&cfg, &st, s, 8, 0.0), FS_ERR_NULL_ARG);
    s[3].skill = &g_press;
    s[2].time_scale = 0.0;
    assert_int_equal(exec_start(&cfg, &st, s, 8, 0.0), FS_ERR_SCALE_INVALID);
    s[2].time_scale = 1.0;
    s[1].goal_scale = NAN;
    assert_int_equal(exec_start(&cfg, &st, s, 8, 0.0), FS_ERR_SCALE_INVALID);
    s[1].goal_scale = 1.0;
    cfg.use_model = 1;
    cfg.object.m_v_kg = 0.0;
    assert_int_equal(exec_start(&cfg, &st, s, 1, 0.0), FS_ERR_MASS_NONPOSITIVE);
    cfg.object.m_v_kg = 10.0;
    cfg.object.k2_Npm = -1.0;
    assert_int_equal(exec_start(&cfg, &st, s, 1, 0.0), FS_ERR_STIFFNESS_NONPOSITIVE);
    exec_config_default(&cfg);
    cfg.phase_stop_gain_per_N2 = -1.0;
    assert_int_equal(exec_start(&cfg, &st, s, 1, 0.0), FS_ERR_GAIN_NEGATIVE);
    exec_config_default(&cfg);
    cfg.pfc.gains[0].k_d_Nspm = 10.0; /* k_d <= m_d */
    assert_int_not_equal(exec_start(&cfg, &st, s, 1, 0.0), FS_OK);
}

/* y holds its start position: the law with k_f = k_i = 0, f = k_p*(y0 - y) - k_d*vy. */
static void test_y_axis_holds_position(void **state)
{
    (void)state;
    exec_config_t cfg;
    exec_config_default(&cfg);
    static exec_state_t st;
    exec_step_t s = step_of(&g_press, 1.0, 1.0, 0.0, SKILL_END_HOLD);
    assert_int_equal(exec_start(&cfg, &st, &s, 1, 0.002), FS_OK);
    exec_meas_t m = zero_meas();
    m.pos_m[1] = 0.0015;
    m.vel_mps[1] = 0.01;
    exec_out_t o;
    exec_tick(&cfg, &st, &m, &o);
    const double expect = 1170.0 * (0.002 - 0.0015) - 400.0 * 0.01;
    assert_true(fabs(o.force_cmd_N[1] - expect) < 1e-9);
}

/* Saturation: whatever the error, |f_cmd| <= the configured limit. */
static void test_output_saturated(void **state)
{
    (void)state;
    exec_config_t cfg;
    exec_config_default(&cfg);
    cfg.pfc.limits[0].force_max_N = 5.0;
    cfg.pfc.limits[1].force_max_N = 5.0;
    static exec_state_t st;
    exec_step_t s = step_of(&g_press, 20.0, 1.0, 0.0, SKILL_END_HOLD);
    assert_int_equal(exec_start(&cfg, &st, &s, 1, 0.0), FS_OK);
    exec_meas_t m = zero_meas();
    m.pos_m[0] = -0.5;
    m.pos_m[1] = 0.3;
    exec_out_t o;
    for (int n = 0; n < 3000; n++) {
        exec_tick(&cfg, &st, &m, &o);
        assert_true(fabs(o.force_cmd_N[0]) <= 5.0 && fabs(o.force_cmd_N[1]) <= 5.0);
    }
}

/* Phase stopping: a persistent force error slows the phase, so f_hat rises later. */
static void test_phase_stopping_slows_the_skill(void **state)
{
    (void)state;
    exec_config_t a, b;
    exec_config_default(&a);
    exec_config_default(&b);
    b.phase_stop_gain_per_N2 = 1.0;
    static exec_state_t sa, sb;
    exec_step_t s = step_of(&g_press, 1.0, 1.0, 0.0, SKILL_END_HOLD);
    assert_int_equal(exec_start(&a, &sa, &s, 1, 0.0), FS_OK);
    assert_int_equal(exec_start(&b, &sb, &s, 1, 0.0), FS_OK);
    exec_meas_t m = zero_meas(); /* no contact force: the error equals f_hat */
    exec_out_t oa, ob;
    for (int n = 0; n < 1500; n++) {
        exec_tick(&a, &sa, &m, &oa);
        exec_tick(&b, &sb, &m, &ob);
    }
    assert_true(sb.dmp.u < sa.dmp.u);
    assert_true(ob.force_hat_N < oa.force_hat_N);
}

static void test_velocity_filter(void **state)
{
    (void)state;
    exec_vel_t v;
    exec_vel_init(&v, 50.0, DT);
    double est = 0.0;
    for (int n = 0; n < 500; n++) {
        est = exec_vel_update(&v, 0.02 * n * DT, DT); /* 0.02 m/s ramp */
    }
    assert_true(fabs(est - 0.02) < 1e-9);
    for (int n = 0; n < 500; n++) {
        est = exec_vel_update(&v, 0.01, DT);
    }
    assert_true(fabs(est) < 1e-9);
}

/* Rendering: with the virtual and real carriage together, the motor force is m_c*acc minus the
 * (low-passed) external force plus friction compensation; and it is limited. */
static void test_render(void **state)
{
    (void)state;
    exec_render_cfg_t c;
    exec_render_default(&c);
    exec_render_t r;
    exec_render_reset(&r, 0.0);
    /* first tick from rest: virtual state moves by acc*dt, dt*acc*dt */
    const double acc = 10.0 / 40.0;
    double f = exec_render_step(&c, &r, 10.0, 40.0, 3.0, 0.0, 0.0, DT);
    const double lp = DT / (DT + 1.0 / (2.0 * 3.14159265358979323846 * c.ext_cutoff_Hz));
    double expect = 2.0 * acc + c.kp_Npm * (acc * DT * DT) + c.kd_Nspm * (acc * DT) - lp * 3.0;
    assert_true(fabs(f - expect) < 1e-9);
    exec_render_reset(&r, 0.0);
    f = exec_render_step(&c, &r, 1e6, 40.0, 0.0, 0.0, 0.0, DT);
    assert_true(f == c.motor_max_N);
}

/* A skill with the y DMP: the executor's y reference equals the Python rollout of the path
 * (wipe_n50_ridge_release_g1p5_t1p3_p1p5.csv: goal 1.5, time 1.3, path 1.5) shifted to the start
 * position, the force equals its f_hat once the start blend is over, and an ideal y carriage
 * (acceleration f_cmd/m_d) driven by the law tracks the path within 50 um (measured 16.5 um on
 * a 7.5 mm path); the end holds y. */
static void test_y_path_tracked(void **state)
{
    (void)state;
    static skill_t sk;
    load_skill("wipe_n50_ridge_release.skill", &sk);
    assert_int_equal(sk.dmp.has_y, 1u);
    static double f_ref[4000];
    static double y_ref[4000];
    const size_t rows = load_rollout_xy("wipe_n50_ridge_release_g1p5_t1p3_p1p5.csv", f_ref, y_ref,
                                        4000u);
    exec_config_t cfg;
    exec_config_default(&cfg);
    cfg.pfc.gains[0] = sk.gains;
    exec_step_t s = step_of(&sk, 1.5, 1.3, 0.0, SKILL_END_HOLD);
    s.path_scale = 1.5;
    exec_state_t st;
    const double y_start = 0.1;
    assert_int_equal(exec_start(&cfg, &st, &s, 1, y_start), FS_OK);
    exec_meas_t m = zero_meas();
    m.pos_m[1] = y_start;
    m.force_contact_N = (double)sk.dmp.force0_N;
    double e_ref = 0.0, e_track = 0.0, e_f = 0.0, ext = 0.0;
    exec_out_t out;
    const double m_d = (double)cfg.pfc.gains[1].m_d_kg;
    for (size_t n = 1; n < rows; n++) {
        assert_int_equal(exec_tick(&cfg, &st, &m, &out), FS_OK);
        const double want = y_start + (y_ref[n] - (double)sk.dmp.y_start_m);
        e_ref = fmax(e_ref, fabs((double)out.y_ref_m - want));
        if ((double)n * DT > EXEC_BLEND_S) {
            e_f = fmax(e_f, fabs((double)out.force_hat_N - f_ref[n]));
        }
        /* ideal carriage on y: semi-implicit Euler of acc = f_cmd/m_d */
        m.vel_mps[1] += (double)out.force_cmd_N[1] / m_d * DT;
        m.pos_m[1] += m.vel_mps[1] * DT;
        e_track = fmax(e_track, fabs(m.pos_m[1] - want));
        ext = fmax(ext, fabs(want - y_start));
        m.force_contact_N = out.force_hat_N;
    }
    printf("y path: reference vs python %.3g m, ideal carriage tracking %.3g m, force %.3g N, "
           "extent %.4f m\n",
           e_ref, e_track, e_f, ext);
    assert_true(ext > 0.005);
    assert_true(e_ref <= 1e-9 + 1e-6 * ext);
    assert_true(e_f <= 1e-6 * 10.0);
    assert_true(e_track <= 5e-5); /* the backward differences lag the feed-forward one tick */
    const double y_end = (double)out.y_ref_m;
    for (int k = 0; k < 500; k++) {
        assert_int_equal(exec_tick(&cfg, &st, &m, &out), FS_OK);
    }
    assert_true(fabs((double)out.y_ref_m - y_end) <= 1e-12);
}

/* A periodic step, open loop from its starting force: f_hat equals the Python rollout of the
 * periodic vectors over their cycles (duration cycles*T*time_scale) at goal, amplitude and time
 * scales. */
static void run_golden_periodic(const char *csv, double goal, double amp, double ts, double cycles)
{
    static double ref[40000];
    const size_t rows = load_rollout(csv, ref, 40000);
    exec_config_t cfg;
    exec_config_default(&cfg);
    static exec_state_t st;
    exec_step_t s = step_of(&g_wipe, goal, ts, cycles * g_wipe.dmp.duration_s * ts, SKILL_END_HOLD);
    s.amplitude_scale = amp;
    assert_int_equal(exec_start(&cfg, &st, &s, 1, 0.0), FS_OK);
    exec_meas_t m = zero_meas();
    m.force_contact_N = ref[0];
    double worst = 0.0, f_max = 0.0;
    exec_out_t o;
    for (size_t n = 1; n < rows; n++) {
        assert_int_equal(exec_tick(&cfg, &st, &m, &o), FS_OK);
        worst = fmax(worst, fabs(o.force_hat_N - ref[n]));
        f_max = fmax(f_max, fabs(ref[n]));
        assert_int_equal(o.done, 0u);
    }
    /* the duration's end: hold the last value */
    assert_int_equal(exec_tick(&cfg, &st, &m, &o), FS_OK);
    assert_true(fabs(o.force_hat_N - ref[rows - 1u]) <= 1e-6 * f_max);
    printf("periodic exec %s: max err %.3g of max|f|\n", csv, worst / f_max);
    assert_true(worst <= 1e-6 * f_max);
}

static void test_periodic_matches_python_rollouts(void **state)
{
    (void)state;
    run_golden_periodic("periodic_n50_ridge_g1_a1_t1_c2.csv", 1.0, 1.0, 1.0, 2.0);
    run_golden_periodic("periodic_n50_ridge_g1p5_a0p5_t1_c1.csv", 1.5, 0.5, 1.0, 1.0);
    run_golden_periodic("periodic_n50_ridge_g1_a1p5_t1p3_c1p5.csv", 1.0, 1.5, 1.3, 1.5);
}

/* Until stopped: a periodic step runs past any number of cycles and repeats its cycle (the
 * 1x rollout returns to its start every period, 1e-9 of max force). */
static void test_periodic_until_stopped(void **state)
{
    (void)state;
    exec_config_t cfg;
    exec_config_default(&cfg);
    static exec_state_t st;
    exec_step_t s = step_of(&g_wipe, 1.0, 1.0, 0.0, SKILL_END_HOLD);
    s.until_stopped = 1u;
    assert_int_equal(exec_start(&cfg, &st, &s, 1, 0.0), FS_OK);
    const long p = lround(g_wipe.dmp.duration_s / g_wipe.dmp.dt_s);
    exec_meas_t m = zero_meas();
    m.force_contact_N = g_wipe.dmp.goal_N + g_wipe.dmp.cycle_e0_N;
    static double first[2000];
    assert_true(p < 2000);
    double worst = 0.0;
    for (long n = 0; n < 40 * p; n++) {
        exec_out_t o;
        assert_int_equal(exec_tick(&cfg, &st, &m, &o), FS_OK);
        assert_int_equal(o.done, 0u);
        if (n < p) {
            first[n] = o.force_hat_N;
        } else {
            worst = fmax(worst, fabs(o.force_hat_N - first[n % p]));
        }
    }
    printf("periodic exec until stopped: 40 cycles, max deviation from the first %.3g N\n", worst);
    assert_true(worst <= 1e-6 * g_wipe.dmp.goal_N);
    exec_step_t neg = s;
    neg.amplitude_scale = -1.0;
    assert_int_equal(exec_start(&cfg, &st, &neg, 1, 0.0), FS_ERR_SCALE_INVALID);
}

/* A sequence discrete approach -> periodic strokes -> discrete release: the force is continuous
 * at both switches (a jump of at most one DMP step) and the periodic step runs its cycles. */
static void test_periodic_in_sequence(void **state)
{
    (void)state;
    exec_config_t cfg;
    exec_config_default(&cfg);
    static exec_state_t st;
    const double period = g_wipe.dmp.duration_s;
    exec_step_t steps[3] = {step_of(&g_press, 1.0, 1.0, 1.5, SKILL_END_HOLD),
                            step_of(&g_wipe, 1.0, 1.0, 5.0 * period, SKILL_END_HOLD),
                            step_of(&g_press, 1.0, 1.0, 1.0, SKILL_END_RELEASE)};
    assert_int_equal(exec_start(&cfg, &st, steps, 3, 0.0), FS_OK);
    exec_meas_t m = zero_meas();
    m.force_contact_N = g_press.dmp.force0_N;
    double prev = g_press.dmp.force0_N, worst_jump = 0.0;
    uint8_t step = 0u;
    long ticks_periodic = 0;
    exec_out_t o;
    for (int n = 0; n < 6000 && !st.done; n++) {
        assert_int_equal(exec_tick(&cfg, &st, &m, &o), FS_OK);
        if (o.step != step) {
            worst_jump = fmax(worst_jump, fabs(o.force_hat_N - prev));
            step = o.step;
        }
        ticks_periodic += (o.step == 1u) ? 1 : 0;
        prev = o.force_hat_N;
    }
    printf("periodic in a sequence: jump at the switches %.3g N, %ld periodic ticks\n", worst_jump,
           ticks_periodic);
    assert_int_equal(step, 2u);
    assert_true(labs(ticks_periodic - lround(5.0 * period / g_wipe.dmp.dt_s)) <= 1);
    assert_true(worst_jump < 0.05);
}

/* A periodic skill with the y path ramps its path in over the first turn and, a step of known
 * length, out over its last: the y reference is y(start) + r_n*p_n, r the product of the
 * smoothsteps of the phase x_n = n*dt/(2 pi tau) (1 from the first wrap) and of the ticks left
 * (N - n)*dt/(2 pi tau) (1 until the last turn), p_n the Python rollout of the path
 * (periodic_y_n50_ridge_g1_a1_t1_c2_p1.csv, 2 cycles). Without the ramps the path starts at its
 * stroke speed (0.46 m/s here) and stops from it; with them y starts and ends at rest, at its
 * start, and its acceleration is nowhere larger than the path's own. */
static void test_periodic_path_ramped_in_and_out(void **state)
{
    (void)state;
    static skill_t sk;
    load_skill("periodic_y_n50_ridge.skill", &sk);
    assert_int_equal(sk.dmp.periodic, 1u);
    assert_int_equal(sk.dmp.has_y, 1u);
    static double f_hat[4000];
    static double y_hat[4000];
    const size_t rows = load_rollout_xy("periodic_y_n50_ridge_g1_a1_t1_c2_p1.csv", f_hat, y_hat,
                                        4000u);
    double acc_path = 0.0; /* the path's own largest acceleration */
    for (size_t n = 2; n < rows; n++) {
        acc_path = fmax(acc_path, fabs(y_hat[n] - 2.0 * y_hat[n - 1u] + y_hat[n - 2u]) / (DT * DT));
    }
    exec_config_t cfg;
    exec_config_default(&cfg);
    cfg.pfc.gains[0] = sk.gains;
    static exec_state_t st;
    const exec_step_t s = step_of(&sk, 1.0, 1.0, 2.0 * sk.dmp.duration_s, SKILL_END_HOLD);
    const double y_start = -0.02;
    assert_int_equal(exec_start(&cfg, &st, &s, 1, y_start), FS_OK);
    exec_meas_t m = zero_meas();
    m.pos_m[1] = y_start;
    m.force_contact_N = sk.dmp.goal_N + sk.dmp.cycle_e0_N;
    const double turn_ticks = 2.0 * 3.14159265358979323846 * (double)sk.dmp.tau_s / DT;
    const size_t n_end = rows - 1u; /* the step's ticks: 2 cycles */
    double e_ref = 0.0, ext = 0.0, acc = 0.0;
    double y_prev = y_start, v_prev = 0.0, v_first = 0.0, v_last = 0.0;
    exec_out_t o;
    for (size_t n = 1; n <= n_end; n++) {
        assert_int_equal(exec_tick(&cfg, &st, &m, &o), FS_OK);
        const double x = (double)n / turn_ticks;
        const double u = (double)(n_end - n) / turn_ticks;
        const double r_in = (x < 1.0) ? x * x * (3.0 - 2.0 * x) : 1.0;
        const double r_out = (u < 1.0) ? u * u * (3.0 - 2.0 * u) : 1.0;
        const double p = y_hat[n] - (double)sk.dmp.y_start_m;
        e_ref = fmax(e_ref, fabs((double)o.y_ref_m - (y_start + r_in * r_out * p)));
        ext = fmax(ext, fabs(p));
        const double v = ((double)o.y_ref_m - y_prev) / DT;
        v_first = (n == 1u) ? v : v_first;
        v_last = v;
        acc = (n > 1u) ? fmax(acc, fabs(v - v_prev) / DT) : acc;
        y_prev = (double)o.y_ref_m;
        v_prev = v;
    }
    printf("periodic path ramped in and out: reference vs python %.3g m (extent %.4f m), first / "
           "last tick %.3g / %.3g m/s, end %.3g m from the start, max acceleration %.3g m/s^2 "
           "(the path's own %.3g)\n",
           e_ref, ext, v_first, v_last, (double)o.y_ref_m - y_start, acc, acc_path);
    assert_true(ext > 0.02);
    assert_true(e_ref <= 1e-9 + 1e-6 * ext);
    assert_true(fabs(v_first) < 1e-4 && fabs(v_last) < 1e-4); /* at rest (the path: 0.46 m/s) */
    assert_true(fabs((double)o.y_ref_m - y_start) <= 1e-12);
    assert_true(acc <= acc_path);
    for (int k = 0; k < 100; k++) { /* the end holds it */
        assert_int_equal(exec_tick(&cfg, &st, &m, &o), FS_OK);
        assert_true(fabs((double)o.y_ref_m - y_start) <= 1e-12);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_periodic_matches_python_rollouts),
        cmocka_unit_test(test_periodic_until_stopped),
        cmocka_unit_test(test_periodic_in_sequence),
        cmocka_unit_test(test_open_loop_matches_python_rollouts),
        cmocka_unit_test(test_goal_scaling_is_exact),
        cmocka_unit_test(test_starts_from_measured_force),
        cmocka_unit_test(test_surface_from_contact),
        cmocka_unit_test(test_end_policies),
        cmocka_unit_test(test_sequence_continuity),
        cmocka_unit_test(test_model_reference_static_inverse),
        cmocka_unit_test(test_nonfinite_measurement_commands_zero),
        cmocka_unit_test(test_start_validation),
        cmocka_unit_test(test_y_axis_holds_position),
        cmocka_unit_test(test_output_saturated),
        cmocka_unit_test(test_phase_stopping_slows_the_skill),
        cmocka_unit_test(test_velocity_filter),
        cmocka_unit_test(test_render),
        cmocka_unit_test(test_y_path_tracked),
        cmocka_unit_test(test_periodic_path_ramped_in_and_out),
    };
    return cmocka_run_group_tests(tests, setup, NULL);
}

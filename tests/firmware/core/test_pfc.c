/* Parallel force/position law (pfc.c) against analytic results:
 *  - x axis on a spring with the dynamics-compensated ideal device (m_d*xdd = f_cmd): the force
 *    integral drives f -> f_d even with a wrong position reference; with k_i = 0 the steady state
 *    is the analytic PD equilibrium x = (k_p*x_d + k_f*f_d)/(k_p + k*k_f);
 *  - output saturation is never exceeded; anti-windup keeps the integral bounded and the recovery
 *    from a long unreachable demand short (compared with a naive PI written here);
 *  - y axis (k_f = k_i = 0) step response equals the analytic second-order solution.
 * Plants are integrated with sub-steps; the controller runs at its own dt (zero-order hold). */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <cmocka.h>

#include "pfc.h"

#define SUBSTEPS 20
#define D_V 50.0 /* object damping, Ns/m (the paper's objects, docs/hil.md) */

static void ref_zero(pfc_axis_ref_t ref[PFC_AXES])
{
    for (unsigned a = 0; a < PFC_AXES; a++) {
        ref[a].pos_m = 0.0;
        ref[a].vel_mps = 0.0;
        ref[a].acc_mps2 = 0.0;
        ref[a].force_N = 0.0;
    }
}

/* x axis on a spring f = k*x, ideal compensated device m_d*xdd = f_cmd; returns f at the end. */
static double spring_run(const pfc_config_t *cfg, double k, double f_d, double x_d, double t_end,
                         double *x_end, double *cmd_max)
{
    pfc_state_t st;
    pfc_reset(&st);
    pfc_axis_ref_t ref[PFC_AXES];
    pfc_axis_meas_t meas[PFC_AXES] = {{0}};
    double cmd[PFC_AXES];
    ref_zero(ref);
    ref[0].pos_m = x_d;
    ref[0].force_N = f_d;
    double x = 0.0, xd = 0.0;
    const double m = cfg->gains[0].m_d_kg;
    const double h = cfg->dt_s / SUBSTEPS;
    *cmd_max = 0.0;
    const long n = lround(t_end / cfg->dt_s);
    for (long i = 0; i < n; i++) {
        meas[0].pos_m = x;
        meas[0].vel_mps = xd;
        meas[0].force_N = k * x;
        pfc_step(cfg, &st, ref, meas, cmd);
        *cmd_max = fmax(*cmd_max, fabs(cmd[0]));
        for (int j = 0; j < SUBSTEPS; j++) {
            xd += h * cmd[0] / m;
            x += h * xd;
        }
    }
    *x_end = x;
    return k * x;
}

static void test_x_spring_steady_state(void **state)
{
    (void)state;
    pfc_config_t cfg;
    pfc_default_config(&cfg);
    assert_int_equal(pfc_config_validate(&cfg), FS_OK);
    const double ks[] = {100.0, 280.0, 600.0};
    for (size_t i = 0; i < 3; i++) {
        const double k = ks[i], f_d = 10.0;
        /* position reference off by 50 %: only the integral can bring f to f_d */
        const double x_d = 0.5 * f_d / k;
        double x, cmd_max;
        const double f = spring_run(&cfg, k, f_d, x_d, 20.0, &x, &cmd_max);
        printf("spring k=%g: f(20 s) = %.6f N (f_d = %g), max |f_cmd| %.2f N\n", k, f, f_d, cmd_max);
        assert_true(fabs(f - f_d) < 1e-3);
        assert_true(cmd_max <= cfg.limits[0].force_max_N);
        /* k_i = 0: analytic PD equilibrium */
        pfc_config_t pd = cfg;
        pd.gains[0].k_i_per_s = 0.0;
        (void)spring_run(&pd, k, f_d, x_d, 20.0, &x, &cmd_max);
        const double x_eq = (1170.0 * x_d + 3.0 * f_d) / (1170.0 + 3.0 * k);
        assert_true(fabs(x - x_eq) < 1e-6 * x_eq);
        assert_true(fabs(k * x - f_d) > 0.1); /* and it misses f_d */
    }
}

/* Uncompensated device pushing a paper object (spring k, damper d_v = 50 Ns/m):
 * m*xdd = f_cmd - f, f = k*x + d_v*xd, so a demand above F_max is unreachable and the output stays
 * saturated (which also removes the controller's damping: the object's d_v settles the device).
 * f_d = f_high for 3 s, then 20 N. */
typedef struct {
    double i_max;      /* max |integral| during the run */
    double cmd_max;    /* max |f_cmd| */
    double recovery_s; /* time after the switch until |f - 20| < 1 N for good */
} windup_result_t;

static windup_result_t windup_run(int naive, double f_high)
{
    pfc_config_t cfg;
    pfc_default_config(&cfg);
    const double k = 280.0, m = cfg.gains[0].m_d_kg, dt = cfg.dt_s;
    const pfc_axis_gains_t *g = &cfg.gains[0];
    pfc_state_t st;
    pfc_reset(&st);
    pfc_axis_ref_t ref[PFC_AXES];
    pfc_axis_meas_t meas[PFC_AXES] = {{0}};
    double cmd[PFC_AXES];
    ref_zero(ref);
    double x = 0.0, xd = 0.0, naive_i = 0.0;
    windup_result_t r = {0.0, 0.0, 0.0};
    double last_bad = 0.0;
    const double h = dt / SUBSTEPS;
    for (long i = 0; i < 10000; i++) {
        const double t = (double)i * dt;
        const double f_d = (t < 3.0) ? f_high : 20.0;
        const double f = k * x + D_V * xd;
        ref[0].force_N = f_d;
        ref[0].pos_m = f_d / k;
        meas[0].pos_m = x;
        meas[0].vel_mps = xd;
        meas[0].force_N = f;
        double u;
        if (naive) {
            /* textbook PI law, saturated output, integral unbounded and always integrating */
            const double unsat = g->k_d_Nspm * (0.0 - xd) + g->k_p_Npm * (ref[0].pos_m - x) +
                                 g->k_f * (f_d - f) + g->k_i_per_s * naive_i;
            u = fmax(-50.0, fmin(50.0, unsat));
            naive_i += dt * (f_d - f);
            r.i_max = fmax(r.i_max, fabs(naive_i));
        } else {
            pfc_step(&cfg, &st, ref, meas, cmd);
            u = cmd[0];
            r.i_max = fmax(r.i_max, fabs(st.force_err_integral_Ns[0]));
            assert_true(fabs(st.force_err_integral_Ns[0]) <= cfg.limits[0].integral_max_Ns);
        }
        r.cmd_max = fmax(r.cmd_max, fabs(u));
        if (t >= 3.0 && fabs(f - 20.0) >= 1.0) {
            last_bad = t;
        }
        for (int j = 0; j < SUBSTEPS; j++) {
            xd += h * (u - k * x - D_V * xd) / m;
            x += h * xd;
        }
    }
    r.recovery_s = last_bad - 3.0 + dt;
    return r;
}

static void test_x_saturation_antiwindup(void **state)
{
    (void)state;
    pfc_config_t cfg;
    pfc_default_config(&cfg);
    /* reference: the same switch from a reachable 45 N (no sustained saturation) */
    const windup_result_t base = windup_run(0, 45.0);
    const windup_result_t aw = windup_run(0, 80.0);
    const windup_result_t nv = windup_run(1, 80.0);
    printf("switch 45 N -> 20 N: recovery %.3f s (closed-loop settling); 80 N (unreachable, F_max "
           "50 N) -> 20 N: max |I_f| %.3f Ns (bound %.3f), recovery %.3f s; naive PI: max |I_f| "
           "%.2f Ns, recovery %.3f s\n", base.recovery_s, aw.i_max,
           (double)cfg.limits[0].integral_max_Ns, aw.recovery_s, nv.i_max, nv.recovery_s);
    assert_true(aw.cmd_max <= cfg.limits[0].force_max_N);
    assert_true(base.cmd_max <= cfg.limits[0].force_max_N);
    assert_true(aw.i_max <= cfg.limits[0].integral_max_Ns);
    /* 3 s of saturation cost at most 0.5 s more than the plain closed-loop settling ... */
    assert_true(aw.recovery_s < base.recovery_s + 0.5);
    /* ... while the naive integral winds up and takes far longer */
    assert_true(nv.recovery_s > 2.0 * aw.recovery_s);
}

/* The limit holds for any input, including extreme references. */
static void test_saturation_never_exceeded(void **state)
{
    (void)state;
    pfc_config_t cfg;
    pfc_default_config(&cfg);
    pfc_state_t st;
    pfc_reset(&st);
    pfc_axis_ref_t ref[PFC_AXES];
    pfc_axis_meas_t meas[PFC_AXES] = {{0}};
    double cmd[PFC_AXES];
    ref_zero(ref);
    uint64_t s = 88172645463325252ULL;
    for (int i = 0; i < 100000; i++) {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        const double r = (double)(s >> 11) / 9007199254740992.0 - 0.5;
        for (unsigned a = 0; a < PFC_AXES; a++) {
            ref[a].pos_m = r * (i % 7);
            ref[a].vel_mps = -r * (i % 3);
            ref[a].acc_mps2 = r * 100.0;
            ref[a].force_N = 1000.0 * r;
            meas[a].pos_m = -r;
            meas[a].force_N = (i % 2) ? 1e6 * r : -r;
        }
        pfc_step(&cfg, &st, ref, meas, cmd);
        for (unsigned a = 0; a < PFC_AXES; a++) {
            assert_true(fabs(cmd[a]) <= cfg.limits[a].force_max_N);
            assert_true(fabs(st.force_err_integral_Ns[a]) <= cfg.limits[a].integral_max_Ns);
        }
    }
    /* the y axis (k_i = 0) never accumulates */
    assert_true(st.force_err_integral_Ns[1] == 0.0);
    /* NaN measurement: no command, integral unchanged */
    const double i_before = st.force_err_integral_Ns[0];
    meas[0].force_N = NAN;
    pfc_step(&cfg, &st, ref, meas, cmd);
    assert_true(cmd[0] == 0.0);
    assert_true(st.force_err_integral_Ns[0] == i_before);
}

/* y axis: m*xdd + k_d*xd + k_p*x = k_p*x_d, a step of x_d from rest. Underdamped here:
 * zeta = k_d/(2 sqrt(m k_p)) = 0.925, omega_n = sqrt(k_p/m) = 5.41 rad/s. */
static double y_step_error(double ctrl_dt)
{
    pfc_config_t cfg;
    pfc_default_config(&cfg);
    cfg.dt_s = ctrl_dt;
    pfc_state_t st;
    pfc_reset(&st);
    pfc_axis_ref_t ref[PFC_AXES];
    pfc_axis_meas_t meas[PFC_AXES] = {{0}};
    double cmd[PFC_AXES];
    ref_zero(ref);
    const double step = 0.01, m = 40.0, kd = 400.0, kp = 1170.0;
    ref[1].pos_m = step;
    const double wn = sqrt(kp / m), zeta = kd / (2.0 * sqrt(m * kp));
    const double wd = wn * sqrt(1.0 - zeta * zeta);
    double y = 0.0, yd = 0.0, err = 0.0;
    const long n = lround(3.0 / ctrl_dt);
    for (long i = 0; i < n; i++) {
        meas[1].pos_m = y;
        meas[1].vel_mps = yd;
        pfc_step(&cfg, &st, ref, meas, cmd);
        /* free mass under constant force over the tick: exact */
        y += yd * ctrl_dt + 0.5 * cmd[1] / m * ctrl_dt * ctrl_dt;
        yd += cmd[1] / m * ctrl_dt;
        const double t = (double)(i + 1) * ctrl_dt;
        const double ya = step * (1.0 - exp(-zeta * wn * t) *
                                            (cos(wd * t) + zeta / sqrt(1.0 - zeta * zeta) * sin(wd * t)));
        err = fmax(err, fabs(y - ya));
    }
    assert_true(fabs(y - step) < 1e-3 * step);
    return err / step;
}

static void test_y_step_response(void **state)
{
    (void)state;
    const double e_1ms = y_step_error(1e-3);
    const double e_01ms = y_step_error(1e-4);
    printf("y step vs analytic 2nd order: max error %.3g of step at 1 kHz, %.3g at 10 kHz\n",
           e_1ms, e_01ms);
    assert_true(e_1ms < 1e-2);
    assert_true(e_01ms < 1e-3);
    assert_true(e_01ms < 0.2 * e_1ms); /* converges with the control rate (zero-order hold) */
}

static void test_config_validate(void **state)
{
    (void)state;
    pfc_config_t c0, c;
    pfc_default_config(&c0);
    assert_int_equal(pfc_config_validate(&c0), FS_OK);
    assert_int_equal(pfc_config_validate(NULL), FS_ERR_NULL_ARG);
    c = c0; c.gains[1].k_p_Npm = NAN;
    assert_int_equal(pfc_config_validate(&c), FS_ERR_NOT_FINITE);
    c = c0; c.gains[0].m_d_kg = 0.0;
    assert_int_equal(pfc_config_validate(&c), FS_ERR_MASS_NONPOSITIVE);
    c = c0; c.gains[0].k_i_per_s = -1.0;
    assert_int_equal(pfc_config_validate(&c), FS_ERR_GAIN_NEGATIVE);
    c = c0; c.gains[1].k_d_Nspm = 40.0;
    assert_int_equal(pfc_config_validate(&c), FS_ERR_KD_LE_MD);
    c = c0; c.limits[0].force_max_N = 0.0;
    assert_int_equal(pfc_config_validate(&c), FS_ERR_LIMIT_INVALID);
    c = c0; c.limits[1].integral_max_Ns = -1.0;
    assert_int_equal(pfc_config_validate(&c), FS_ERR_LIMIT_INVALID);
    c = c0; c.dt_s = 0.0;
    assert_int_equal(pfc_config_validate(&c), FS_ERR_DT_INVALID);
    /* pfc_default_config */
    assert_true(c0.gains[0].m_d_kg == 40.0 && c0.gains[0].k_d_Nspm == 400.0 &&
                c0.gains[0].k_p_Npm == 1170.0 && c0.gains[0].k_f == 3.0 &&
                c0.gains[0].k_i_per_s == 27.0 && c0.gains[1].k_f == 0.0 &&
                c0.gains[1].k_i_per_s == 0.0 && c0.limits[0].force_max_N == 50.0 &&
                c0.dt_s == 0.001);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_x_spring_steady_state),
        cmocka_unit_test(test_x_saturation_antiwindup),
        cmocka_unit_test(test_saturation_never_exceeded),
        cmocka_unit_test(test_y_step_response),
        cmocka_unit_test(test_config_validate),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

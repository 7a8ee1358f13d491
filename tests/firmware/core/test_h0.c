/* With h = 0 the DMP (corrected eq. 14, time-varying goal g'(t), tau = 1)
 * reproduces the closed-loop parallel force/position law on a spring f = k*x, both integrated by
 * forward Euler with the same dt, to round-off (1e-10 relative) for random stable gain sets; the
 * paper's printed beta does not. The closed-loop integrator below is written independently of
 * dmp.c: it works in (x, xd, I) with the law's own coefficients. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <cmocka.h>

#include "core_test_util.h"
#include "dmp.h"

#define DT 0.001
#define PI 3.14159265358979323846
#define N_STEPS 8000 /* 8 s */

/* Demonstration-like references: a force ramp, a hold with a bump, a release; the position
 * reference follows a surface at 1 mm plus the spring's deflection. */
static double demo_force(double t)
{
    const double ramp = (t < 1.5) ? 0.5 * (1.0 - cos(PI * t / 1.5)) : 1.0;
    const double release = (t > 6.0) ? 0.5 * (1.0 + cos(PI * fmin(t - 6.0, 1.5) / 1.5)) : 1.0;
    return (12.0 + 4.0 * sin(2.1 * t)) * ramp * release;
}

static double demo_pos(double t, double k)
{
    return 0.001 + demo_force(t) / k + 0.002 * sin(0.7 * t);
}

/* The skill's stiffness-independent gains for controller gains g on stiffness k. */
static dmp_gains_t to_dmp_gains(const pfc_axis_gains_t *g, double k)
{
    const dmp_gains_t d = {g->m_d_kg, g->k_d_Nspm, g->k_p_Npm, k * g->k_f, k * g->k_i_per_s};
    return d;
}

/* Max |y_dmp - k*x_law| / max |k*x_law| over the run (the DMP in force units against the law in
 * metres); beta_override < 0 uses the derived beta. */
static double h0_error(const pfc_axis_gains_t *g, double k, double beta_override)
{
    const dmp_gains_t dg = to_dmp_gains(g, k);
    dmp_params_t p;
    assert_int_equal(dmp_params_from_gains(&dg, &p), FS_OK);
    if (beta_override > 0.0) {
        p.beta = beta_override;
    }
    /* One kernel with weight 0: h = 0 exactly. goal_N = 1 and goal_scale = k*g'(t_n), so
     * g_e = k*g'(t_n) exactly. */
    dmp_model_t m = {0};
    m.n_kernels = 1;
    m.dt_s = DT;
    m.tau_s = 1.0;
    m.goal_N = 1.0;
    m.force0_N = 0.0;
    m.duration_s = N_STEPS * DT;
    m.centre[0] = 0.0;
    m.width[0] = 0.5;
    m.weight[0] = 0.0;
    /* initialise with the derived (valid) beta, then install the override if any */
    assert_int_equal(dmp_params_from_gains(&dg, &m.p), FS_OK);
    assert_int_equal(dmp_model_init(&m), FS_OK);
    m.p = p;
    dmp_state_t s;
    dmp_state_reset(&s);

    /* Closed loop: m_d*xdd + k_d*xd + (k_p + k*k_f)*x + k*k_i*I = k_p*x_d + k_f*f_d + k_i*F_d */
    double x = 0.0, xd = 0.0, ix = 0.0;
    double f_int = 0.0; /* F_d = int f_d, left Riemann sum: the same value feeds both systems */
    double err_max = 0.0, x_max = 0.0;
    for (int n = 0; n < N_STEPS; n++) {
        const double t = n * DT;
        const double f_d = demo_force(t);
        const double x_d = demo_pos(t, k);
        const double rhs = g->k_p_Npm * x_d + g->k_f * f_d + g->k_i_per_s * f_int;
        const double xdd = (rhs - g->k_d_Nspm * xd - (g->k_p_Npm + k * g->k_f) * x -
                            k * g->k_i_per_s * ix) / g->m_d_kg;
        const double x_next = x + DT * xd;
        const double xd_next = xd + DT * xdd;
        const double ix_next = ix + DT * x;
        x = x_next;
        xd = xd_next;
        ix = ix_next;

        const dmp_run_t run = {dmp_goal(&p, &dg, k * x_d, f_d, f_int), 1.0};
        const double f_hat = dmp_step(&m, &s, &run, NULL);
        assert_true(f_hat == s.y_N);
        err_max = fmax(err_max, fabs(s.y_N - k * x));
        x_max = fmax(x_max, fabs(k * x));
        f_int += DT * f_d;
    }
    assert_true(x_max > 1e-2);
    return err_max / x_max;
}

/* Random stable gains: alpha in [2, 15], beta in [0.05, 1]*alpha/4, k_i, k, m_d random, k_f random
 * share of what keeps k_p >= 0. gamma is kept moderate so Euler at 1 ms is itself stable. */
static void random_gains(uint64_t *rng, pfc_axis_gains_t *g, double *k)
{
    for (;;) {
        const double m_d = tu_uniform(rng, 5.0, 80.0);
        const double alpha = tu_uniform(rng, 2.0, 15.0);
        const double beta = tu_uniform(rng, 0.05, 1.0) * alpha / 4.0;
        const double kk = tu_uniform(rng, 50.0, 2000.0);
        const double k_i = tu_uniform(rng, 0.0, 40.0);
        const double gamma = kk * k_i / (m_d * alpha);
        if (gamma > 60.0) {
            continue;
        }
        /* k_p + k*k_f = m_d*(alpha*(beta + 1) + gamma) */
        const double total = m_d * (alpha * (beta + 1.0) + gamma);
        const double k_f = tu_uniform(rng, 0.0, 0.9) * total / kk;
        g->m_d_kg = m_d;
        g->k_d_Nspm = m_d * (alpha + 1.0);
        g->k_i_per_s = k_i;
        g->k_f = k_f;
        g->k_p_Npm = total - kk * k_f;
        *k = kk;
        return;
    }
}

static void test_h0_matches_closed_loop(void **state)
{
    (void)state;
    uint64_t rng = 0x9E3779B97F4A7C15ULL;
    double worst = 0.0;
    pfc_config_t cfg;
    pfc_default_config(&cfg);
    /* Default gains on the paper's stiffnesses, then random stable sets. */
    const double ks[] = {100.0, 280.0, 600.0};
    for (size_t i = 0; i < 3; i++) {
        worst = fmax(worst, h0_error(&cfg.gains[0], ks[i], -1.0));
    }
    for (int i = 0; i < 12; i++) {
        pfc_axis_gains_t g;
        double k;
        random_gains(&rng, &g, &k);
        const double e = h0_error(&g, k, -1.0);
        worst = fmax(worst, e);
    }
    printf("h=0 DMP vs closed-loop law: max relative error %.3g (15 gain sets)\n", worst);
    assert_true(worst <= 1e-10);
}

/* The printed beta, (k_p + k_f - gamma)/(m_d*alpha) - 1, drops k (and m_d): it does not reproduce
 * the law. With the default gains the k terms nearly cancel, so the gap is "only" 0.2-0.5 % of max
 * x, i.e. 10^7 times the round-off agreement above; on other gain sets it ranges up to ~20 %. */
static void test_printed_beta_fails(void **state)
{
    (void)state;
    pfc_config_t cfg;
    pfc_default_config(&cfg);
    double smallest = INFINITY, largest = 0.0;
    int sets = 0;
    uint64_t rng = 0xD1B54A32D192ED03ULL;
    for (int i = 0; i < 15; i++) {
        pfc_axis_gains_t g = cfg.gains[0];
        double k = (i == 0) ? 100.0 : (i == 1) ? 280.0 : 600.0;
        if (i >= 3) {
            random_gains(&rng, &g, &k);
        }
        const dmp_gains_t dg = to_dmp_gains(&g, k);
        dmp_params_t p;
        assert_int_equal(dmp_params_from_gains(&dg, &p), FS_OK);
        const double beta_printed = (g.k_p_Npm + g.k_f - p.gamma) / (g.m_d_kg * p.alpha) - 1.0;
        if (!(beta_printed > 0.0)) {
            continue; /* unstable outright; nothing to compare */
        }
        const double e = h0_error(&g, k, beta_printed);
        if (i < 3) {
            printf("printed beta, default gains, k=%g: beta %.4f (corrected %.4f), error %.3g\n",
                   k, beta_printed, p.beta, e);
        }
        smallest = fmin(smallest, e);
        largest = fmax(largest, e);
        sets++;
    }
    printf("printed beta over %d gain sets: relative error %.3g .. %.3g\n", sets, smallest, largest);
    assert_true(sets >= 8);
    assert_true(smallest > 5e-4); /* > 10^6 times the round-off agreement of the corrected beta */
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_h0_matches_closed_loop),
        cmocka_unit_test(test_printed_beta_fails),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

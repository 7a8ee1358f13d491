/* Run-time modulation of a learned skill: goal scaling is exact (linear system, zero initial
 * conditions), time scaling stretches the output (to Euler accuracy), and the coupling input
 * (phase slow-down, additive term) acts as documented in dmp.h. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <cmocka.h>

#include "core_test_util.h"
#include "dmp.h"

#define T_S 17.0
#define MAX_STEPS 40000

static tu_skill_desc_t desc;
static dmp_model_t model;
static double f1[MAX_STEPS + 1];
static double fs[MAX_STEPS + 1];

/* Rows n = 0..round(T*time_scale/dt) of f_hat (row 0 is 0), as docs/math.md section 2. */
static long rollout(double goal_scale, double time_scale, double *out)
{
    const long n = lround(T_S * time_scale / 0.001);
    assert_true(n <= MAX_STEPS);
    dmp_state_t s;
    dmp_state_reset(&s);
    const dmp_run_t run = {goal_scale, time_scale};
    assert_int_equal(dmp_run_validate(&run), FS_OK);
    out[0] = model.force0_N;
    for (long i = 1; i <= n; i++) {
        out[i] = dmp_step(&model, &s, &run, NULL);
    }
    return n;
}

static double max_abs(const double *a, long n)
{
    double m = 0.0;
    for (long i = 0; i <= n; i++) {
        m = fmax(m, fabs(a[i]));
    }
    return m;
}

static int setup(void **state)
{
    (void)state;
    tu_default_desc(&desc, 50, 280.0, T_S);
    return tu_model_from_desc(&desc, &model) == FS_OK ? 0 : -1;
}

static void test_goal_scaling_exact(void **state)
{
    (void)state;
    const long n = rollout(1.0, 1.0, f1);
    const double m1 = max_abs(f1, n);
    assert_true(m1 > 1.0);
    const double scales[] = {0.25, 0.5, 1.5, 2.0, 3.7, -1.0};
    double worst = 0.0;
    for (size_t k = 0; k < sizeof(scales) / sizeof(scales[0]); k++) {
        const double s = scales[k];
        assert_int_equal(rollout(s, 1.0, fs), n);
        double e = 0.0;
        for (long i = 0; i <= n; i++) {
            e = fmax(e, fabs(fs[i] - s * f1[i]));
        }
        e /= fabs(s) * m1;
        worst = fmax(worst, e);
    }
    printf("goal scaling: max |f_s - s*f_1| / (|s| max|f_1|) = %.3g\n", worst);
    assert_true(worst <= 1e-9);
}

/* time_scale 2 (and 0.5) against the 1x rollout at the matching time. The discrete systems differ
 * only by the Euler step relative to tau (dt/(2 tau) vs dt/tau), so the gap is first order in
 * dt/tau: it must be small and halve when dt halves. */
static double time_scale_error(double ts)
{
    const long n1 = rollout(1.0, 1.0, f1);
    const long ns = rollout(1.0, ts, fs);
    const double m1 = max_abs(f1, n1);
    double e = 0.0;
    if (ts >= 1.0) {
        const long r = lround(ts);
        assert_int_equal(ns, r * n1);
        for (long i = 0; i <= n1; i++) {
            e = fmax(e, fabs(fs[r * i] - f1[i]));
        }
    } else {
        const long r = lround(1.0 / ts);
        assert_int_equal(n1, r * ns);
        for (long i = 0; i <= ns; i++) {
            e = fmax(e, fabs(fs[i] - f1[r * i]));
        }
    }
    return e / m1;
}

static void test_time_scaling_stretches(void **state)
{
    (void)state;
    const double e2 = time_scale_error(2.0);
    const double e05 = time_scale_error(0.5);
    /* Same comparison at dt = 0.5 ms (tau unchanged): first-order Euler error halves. */
    model.dt_s = 0.0005;
    const long n_half = lround(T_S / 0.0005);
    assert_true(n_half <= MAX_STEPS);
    dmp_state_t s;
    dmp_state_reset(&s);
    const dmp_run_t r1 = {1.0, 1.0};
    const dmp_run_t r2 = {1.0, 2.0};
    static double a[MAX_STEPS + 1];
    a[0] = 0.0;
    for (long i = 1; i <= n_half; i++) {
        a[i] = dmp_step(&model, &s, &r1, NULL);
    }
    dmp_state_reset(&s);
    double e_fine = 0.0, m = max_abs(a, n_half);
    double prev = 0.0;
    for (long i = 1; i <= 2 * n_half; i++) {
        prev = dmp_step(&model, &s, &r2, NULL);
        if (i % 2 == 0 && i / 2 <= n_half) {
            e_fine = fmax(e_fine, fabs(prev - a[i / 2]));
        }
    }
    model.dt_s = 0.001;
    e_fine /= m;
    printf("time scaling: max |f_2x(2n) - f_1x(n)|/max|f| = %.3g (dt 1 ms), %.3g (dt 0.5 ms); "
           "0.5x: %.3g\n", e2, e_fine, e05);
    assert_true(e2 <= 5e-3);
    assert_true(e05 <= 1e-2);
    assert_true(e2 > 0.0);
    assert_true(fabs(e_fine / e2 - 0.5) < 0.1);
}

static void state_equal(const dmp_state_t *a, const dmp_state_t *b)
{
    assert_true(a->u == b->u && a->v == b->v && a->integral_y == b->integral_y &&
                a->y_N == b->y_N && a->z == b->z);
}

/* Advance to mid-skill (u ~ 0.5) so every state is nonzero. */
static void mid_state(dmp_state_t *s)
{
    dmp_state_reset(s);
    for (int i = 0; i < 6000; i++) {
        (void)dmp_step(&model, s, NULL, NULL);
    }
    assert_true(s->u > 0.2 && s->y_N != 0.0);
}

static void test_coupling_phase_freeze(void **state)
{
    (void)state;
    dmp_state_t s0, s;
    mid_state(&s0);
    /* infinite slow-down: every state frozen exactly */
    s = s0;
    const dmp_coupling_t freeze = {0.0, INFINITY};
    for (int i = 0; i < 1000; i++) {
        (void)dmp_step(&model, &s, NULL, &freeze);
    }
    state_equal(&s, &s0);
    /* a huge finite slow-down: the phase does not visibly advance in 5 s */
    s = s0;
    const dmp_coupling_t slow = {0.0, 1e12};
    for (int i = 0; i < 5000; i++) {
        (void)dmp_step(&model, &s, NULL, &slow);
    }
    printf("phase slow-down 1e12: u advanced %.3g in 5000 steps (free: %.3g per step)\n",
           s.u - s0.u, s0.v * 0.001 / model.tau_s);
    assert_true(fabs(s.u - s0.u) < 1e-12);
    /* slow-down sd is the same as time_scale (1 + sd) */
    dmp_state_t a = s0, b = s0;
    const dmp_coupling_t sd = {0.0, 1.5};
    const dmp_run_t ts = {1.0, 2.5};
    for (int i = 0; i < 100; i++) {
        assert_true(dmp_step(&model, &a, NULL, &sd) == dmp_step(&model, &b, &ts, NULL));
    }
    state_equal(&a, &b);
    /* negative or NaN slow-down counts as 0 */
    a = s0;
    b = s0;
    const dmp_coupling_t neg = {0.0, -0.5};
    const dmp_coupling_t nan_c = {0.0, NAN};
    dmp_state_t c = s0;
    (void)dmp_step(&model, &a, NULL, &neg);
    (void)dmp_step(&model, &b, NULL, NULL);
    (void)dmp_step(&model, &c, NULL, &nan_c);
    state_equal(&a, &b);
    state_equal(&c, &b);
}

static void test_coupling_term_y(void **state)
{
    (void)state;
    dmp_state_t s0, a, b;
    mid_state(&s0);
    const double c = 0.0123, sd = 0.7, ts = 1.3;
    const dmp_run_t run = {1.0, ts};
    const dmp_coupling_t with = {c, sd};
    const dmp_coupling_t without = {0.0, sd};
    a = s0;
    b = s0;
    const double fa = dmp_step(&model, &a, &run, &with);
    const double fb = dmp_step(&model, &b, &run, &without);
    /* tau*yd gains c: y' moves by dt/(tau*ts*(1+sd))*c, the other states are untouched */
    const double want = 0.001 / (model.tau_s * ts * (1.0 + sd)) * c;
    /* the difference of two y ~ 1 N values carries ~1e-16 absolute round-off */
    assert_true(fabs((a.y_N - b.y_N) - want) <= 1e-7 * want);
    assert_true(fabs((fa - fb) - want) <= 1e-7 * want);
    assert_true(a.u == b.u && a.v == b.v && a.z == b.z && a.integral_y == b.integral_y);
}

/* The kernel window kept in the state is a hint: a step from any window (from the start, from
 * the end, from a phase far ahead or behind) gives the same f_hat and state, bit for bit, as the
 * rollout's own, and the next window is the same. */
static void test_window_hint_never_changes_the_step(void **state)
{
    (void)state;
    dmp_state_t s;
    dmp_state_reset(&s);
    const uint16_t n = model.n_kernels;
    const uint16_t hints[][2] = {{0u, 0u}, {n, n}, {n, 0u}, {0u, n}, {7u, 9u}, {40u, 12u}, {65535u, 65535u}};
    int checked = 0;
    for (int i = 0; i < 17000; i++) {
        if (i % 97 == 0) {
            dmp_state_t ref = s;
            const double f_ref = dmp_step(&model, &ref, NULL, NULL);
            for (size_t h = 0; h < sizeof hints / sizeof hints[0]; h++) {
                dmp_state_t t = s;
                t.window[0] = hints[h][0];
                t.window[1] = hints[h][1];
                assert_true(dmp_step(&model, &t, NULL, NULL) == f_ref);
                state_equal(&t, &ref);
                assert_int_equal(t.window[0], ref.window[0]);
                checked++;
            }
        }
        (void)dmp_step(&model, &s, NULL, NULL);
    }
    assert_true(checked > 1000);
}

static void test_phase_stop_factor(void **state)
{
    (void)state;
    assert_true(dmp_phase_stop_factor(2.0, 0.5) == 2.0);
    assert_true(fabs(dmp_phase_stop_factor(-3.0, 0.1) - 0.9) <= 1e-15);
    assert_true(dmp_phase_stop_factor(0.0, 10.0) == 0.0);
    assert_true(dmp_phase_stop_factor(2.0, -1.0) == 0.0);
    assert_true(isinf(dmp_phase_stop_factor(NAN, 1.0)));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_goal_scaling_exact),
        cmocka_unit_test(test_time_scaling_stretches),
        cmocka_unit_test(test_coupling_phase_freeze),
        cmocka_unit_test(test_coupling_term_y),
        cmocka_unit_test(test_window_hint_never_changes_the_step),
        cmocka_unit_test(test_phase_stop_factor),
    };
    return cmocka_run_group_tests(tests, setup, NULL);
}

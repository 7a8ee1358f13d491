/* The fixed-point build's integer tick (exec_tick_q of fs_control_exec_fx, no floating point)
 * against the float64 executor (fs_control_exec) tick by tick on the same sequences and the same
 * measurements: the float64 executor runs closed loop on a spring contact (x, starting 1 N above
 * the first skill's f0, so the start's carry is blended out) and a free carriage (y); its
 * measurements are rounded to Q8.24 / Q16.16 and replayed into exec_tick_q. Every tick must
 * give the same status, step and done, and the values within the bounds of the existing
 * fixed-vs-float64 check (test_exec_fixed.c: the fixed-point DMP's accuracy against float64):
 * f_hat within 0.01 % of the float64 run's max |f_hat|, the law's commands within 0.1 % of its
 * max |f_cmd| + 1 mN, y_d within 0.01 % of max |f_hat|/k + 0.01 % of max |y_d|; x_d likewise
 * within 0.01 % of max |f_hat|/k + 0.01 % of max |x_d - surface| + 1 LSB of Q8.24 (its output
 * format). One bound is new: a run with a periodic y path allows 0.2 % of max |f_cmd| (+ 1 mN)
 * on the commands. Its y command is m_d*ydd_d + ..., ydd_d the second difference of the
 * fixed-point periodic y DMP's path, which differs from float64's by the DMP's own accuracy: on
 * periodic_y_n50_ridge (goal 1.2, one cycle, test_exec_fixed.c's case) the float32-boundary
 * executor this tick replaced (commit 722affd) measured 0.514 % there, the integer tick
 * 0.110 % (the same fixed-point DMP, its path differenced at the accumulators' resolution).
 * Each feature's run, and a mutation of one constant of the integer tick per feature that must
 * break the agreement. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include <cmocka.h>

#include "exec_fixed_side.h"
#include "fs_exec.h"
#include "vectors_io.h"

#define DT 0.001
#define MAX_TICKS 16000u
#define HAT_REL_LIMIT 1e-4
#define CMD_REL_LIMIT 1e-3
#define CMD_ABS_LIMIT_N 1e-3
#define CMD_REL_LIMIT_PERIODIC_Y 2e-3 /* a periodic y path's run (see above) */
#define Q24_LSB_M (1.0 / 16777216.0)
#define CARRY_N 1.0 /* the contact force at the start above the first skill's f0 */

static uint8_t g_image[EXEC_SIDE_MAX_STEPS][SKILL_IMAGE_MAX];
static skill_t g_skill[EXEC_SIDE_MAX_STEPS];
static exec_state_t g_state;
static exec_side_meas_t g_meas[MAX_TICKS];
static exec_side_out_t g_ref[MAX_TICKS];
static exec_side_out_t g_q[MAX_TICKS];
static exec_side_out_t g_q_prepared[MAX_TICKS];

/* One run: the sequence (skill names and step fields), the configuration's switches, how long
 * it runs, the contact lost in [lost_from_s, lost_to_s), a NaN position at nan_tick (0: none). */
typedef struct {
    const char *name;
    const char *skill[EXEC_SIDE_MAX_STEPS];
    exec_side_step_t step[EXEC_SIDE_MAX_STEPS]; /* image fields filled by the test */
    uint8_t n_steps;
    uint8_t use_model, surface_from_contact;
    double surface_m, stop_gain, y_hold_m;
    double run_s;
    double lost_from_s, lost_to_s;
    uint32_t nan_tick;
    double cmd_rel; /* the commands' relative bound (0: CMD_REL_LIMIT) */
} case_t;

/* Step fields: goal, time, duration, path, amplitude, end (0 hold, 1 release), until stopped,
 * contact threshold, tau. */
#define STEP(g, t, d, p, a, e, u, th, tau)  \
    {                                       \
        0, 0u, g, t, d, p, a, e, u, th, tau \
    }
#define PLAIN(g, t, e) STEP(g, t, 0.0, 1.0, 1.0, e, 0u, 0.0, 0.0)

static const case_t k_cases[] = {
    /* 0: the spring reference, the start's carry blend, release (and a NaN tick) */
    {"spring, carry, release",
     {"engrave_n50_ridge_release.skill"},
     {PLAIN(1.5, 1.3, 1u)},
     1u,
     0u,
     0u,
     0.0,
     0.0,
     0.0,
     3.4,
     0.0,
     0.0,
     1200u,
     0.0},
    /* 1: the object model's reference, a held end */
    {"object model, hold",
     {"press_n50_lwr_hold.skill"},
     {PLAIN(1.0, 1.0, 0u)},
     1u,
     1u,
     0u,
     0.0,
     0.0,
     0.0,
     2.5,
     0.0,
     0.0,
     0u,
     0.0},
    /* 2: a sequence: a y path, then a force skill, then the model-free press held; the carry at
     * each switch and y_hold advanced by the finished path */
    {"sequence y path, carry, hold",
     {"wipe_n50_ridge_release.skill", "engrave_n50_ridge_release.skill",
      "press_n50_lwr_hold.skill"},
     {PLAIN(1.0, 1.0, 1u), STEP(1.2, 1.0, 1.5, 1.0, 1.0, 1u, 0u, 0.0, 0.0), PLAIN(1.0, 1.0, 0u)},
     3u,
     0u,
     0u,
     0.0,
     0.0,
     0.01,
     6.5,
     0.0,
     0.0,
     0u,
     0.0},
    /* 3: a sequence into the object model, released */
    {"sequence model, release",
     {"press_n50_lwr_hold.skill", "wipe_n50_ridge_release.skill"},
     {PLAIN(1.0, 1.0, 0u), STEP(1.0, 1.2, 0.0, 0.5, 1.0, 1u, 0u, 0.0, 0.0)},
     2u,
     1u,
     0u,
     0.0,
     0.0,
     -0.02,
     5.0,
     0.0,
     0.0,
     0u,
     0.0},
    /* 4: the surface from the first contact (the configured one 2 mm off) */
    {"surface from contact",
     {"engrave_n50_ridge_release.skill"},
     {PLAIN(1.0, 1.0, 1u)},
     1u,
     0u,
     1u,
     0.002,
     0.0,
     0.0,
     3.0,
     0.0,
     0.0,
     0u,
     0.0},
    /* 5: the surface from contact on the object model */
    {"surface from contact, model",
     {"press_n50_lwr_hold.skill"},
     {PLAIN(1.0, 1.0, 0u)},
     1u,
     1u,
     1u,
     -0.003,
     0.0,
     0.0,
     2.0,
     0.0,
     0.0,
     0u,
     0.0},
    /* 6: phase stopping (the phase-stop factor as a rate) */
    {"phase stop",
     {"engrave_n100_lwr_release.skill"},
     {PLAIN(1.0, 1.0, 1u)},
     1u,
     0u,
     0u,
     0.0,
     0.05,
     0.0,
     3.5,
     0.0,
     0.0,
     0u,
     0.0},
    /* 7: the contact wait, the contact lost for 0.3 s, with phase stopping */
    {"contact wait",
     {"press_n50_lwr_hold.skill"},
     {STEP(1.0, 1.0, 0.0, 1.0, 1.0, 0u, 0u, 0.5, 0.02)},
     1u,
     0u,
     0u,
     0.0,
     0.01,
     0.0,
     2.5,
     0.6,
     0.9,
     0u,
     0.0},
    /* 8: a periodic step with a y path run until stopped (2.6 cycles here) */
    {"periodic until stopped",
     {"periodic_y_n50_ridge.skill"},
     {STEP(1.2, 1.0, 0.0, 1.0, 0.8, 0u, 1u, 0.0, 0.0)},
     1u,
     0u,
     0u,
     0.0,
     0.0,
     0.0,
     1.3,
     0.0,
     0.0,
     0u,
     CMD_REL_LIMIT_PERIODIC_Y},
    /* 9: periodic cycles for a duration after a discrete step, released; a contact wait on the
     * periodic step */
    {"sequence periodic, release",
     {"engrave_n50_ridge_release.skill", "periodic_n50_ridge.skill"},
     {PLAIN(1.0, 1.0, 1u), STEP(1.5, 1.3, 1.3, 1.0, 1.0, 1u, 0u, 1.0, 0.05)},
     2u,
     0u,
     0u,
     0.0,
     0.0,
     0.0,
     4.5,
     2.3,
     2.5,
     0u,
     0.0},
};

static void load(const case_t *c, exec_side_seq_t *seq)
{
    seq->n_steps = c->n_steps;
    seq->use_model = c->use_model;
    seq->surface_from_contact = c->surface_from_contact;
    seq->surface_m = c->surface_m;
    seq->phase_stop_gain_per_N2 = c->stop_gain;
    seq->y_hold_m = c->y_hold_m;
    seq->saturate_at = 0u;
    seq->via_wrapper = 0u;
    seq->prepare = 0u;
    seq->mutation = EXEC_SIDE_MUT_NONE;
    for (uint8_t i = 0u; i < c->n_steps; i++) {
        seq->step[i] = c->step[i];
        const uint32_t n = tv_read(c->skill[i], g_image[i], sizeof g_image[i]);
        assert_true(n > 0u);
        seq->step[i].image = g_image[i];
        seq->step[i].image_len = n;
        assert_int_equal(skill_parse(g_image[i], n, &g_skill[i]), FS_OK);
        if (c->step[i].contact_threshold_N > 0.0) {
            g_skill[i].contact_threshold_N = c->step[i].contact_threshold_N;
            g_skill[i].contact_tau_s = c->step[i].contact_tau_s;
        }
    }
}

/* The float64 executor closed loop on the case (as test_exec_fixed.c's run_float64, with a
 * sequence); records each tick's measurements and outputs; returns the ticks. */
static size_t run_float64(const case_t *c, const exec_side_seq_t *seq)
{
    exec_config_t cfg;
    exec_config_default(&cfg);
    cfg.pfc.gains[0] = g_skill[0].gains;
    cfg.pfc.gains[1].m_d_kg = g_skill[0].gains.m_d_kg;
    cfg.use_model = seq->use_model;
    cfg.surface_from_contact = seq->surface_from_contact;
    cfg.object.surface_m = seq->surface_m;
    cfg.phase_stop_gain_per_N2 = seq->phase_stop_gain_per_N2;
    exec_step_t steps[EXEC_SIDE_MAX_STEPS];
    for (uint8_t i = 0u; i < seq->n_steps; i++) {
        const exec_side_step_t *s = &seq->step[i];
        steps[i] = (exec_step_t){&g_skill[i],
                                 s->goal_scale,
                                 s->time_scale,
                                 s->duration_s,
                                 (skill_end_t)s->end_policy,
                                 s->path_scale,
                                 s->amplitude_scale,
                                 s->until_stopped,
                                 0};
    }
    assert_int_equal(exec_start(&cfg, &g_state, steps, seq->n_steps, seq->y_hold_m), FS_OK);
    const double k = g_skill[0].stiffness_Npm;
    const double m = g_skill[0].gains.m_d_kg;
    double x[2] = {(g_skill[0].dmp.force0_N + CARRY_N) / k, seq->y_hold_m};
    double v[2] = {0.0, 0.0};
    const size_t n = (size_t)(c->run_s / DT);
    assert_true(n <= MAX_TICKS);
    for (size_t i = 0; i < n; i++) {
        const double t = (double)i * DT;
        const int lost = t >= c->lost_from_s && t < c->lost_to_s;
        const double f_c = (x[0] > 0.0 && !lost) ? k * x[0] : 0.0;
        exec_meas_t me = {{x[0], x[1]}, {v[0], v[1]}, f_c};
        if (c->nan_tick != 0u && i == c->nan_tick) {
            me.pos_m[0] = NAN;
        }
        exec_out_t o;
        g_ref[i].status = (int)exec_tick(&cfg, &g_state, &me, &o);
        g_meas[i] = (exec_side_meas_t){{me.pos_m[0], me.pos_m[1]}, {v[0], v[1]}, f_c};
        g_ref[i].force_cmd_N[0] = o.force_cmd_N[0];
        g_ref[i].force_cmd_N[1] = o.force_cmd_N[1];
        g_ref[i].force_hat_N = o.force_hat_N;
        g_ref[i].pos_ref_m = o.pos_ref_m;
        g_ref[i].y_ref_m = o.y_ref_m;
        g_ref[i].step = o.step;
        g_ref[i].done = o.done;
        const double acc[2] = {(o.force_cmd_N[0] - f_c) / m, o.force_cmd_N[1] / m};
        for (unsigned a = 0; a < 2u; a++) {
            v[a] += acc[a] * DT;
            x[a] += v[a] * DT;
        }
    }
    return n;
}

/* The largest deviations of one comparison and whether all ticks are within the bounds. */
typedef struct {
    double hat_err, hat_max, cmd_err, cmd_max, cmd_bound, x_err, x_bound, y_err, y_bound;
    size_t mismatch; /* ticks whose status, step or done differ */
    size_t steps, dones;
    int pass;
} cmp_t;

static cmp_t compare(const case_t *c, size_t n)
{
    cmp_t r = {0};
    double x_max = 0.0, y_max = 0.0;
    /* the reference's surface: the configured one, or taken from the first contact */
    const double k = g_skill[0].stiffness_Npm;
    const double surface = (c->surface_from_contact != 0u)
                               ? g_ref[0].pos_ref_m - (g_meas[0].force_contact_N / k)
                               : c->surface_m;
    for (size_t i = 0; i < n; i++) {
        r.hat_max = fmax(r.hat_max, fabs(g_ref[i].force_hat_N));
        x_max = fmax(x_max, fabs(g_ref[i].pos_ref_m - surface));
        y_max = fmax(y_max, fabs(g_ref[i].y_ref_m));
        for (unsigned a = 0; a < 2u; a++) {
            r.cmd_max = fmax(r.cmd_max, fabs(g_ref[i].force_cmd_N[a]));
        }
    }
    double k_min = k;
    for (uint8_t i = 0u; i < c->n_steps; i++) {
        k_min = fmin(k_min, g_skill[i].stiffness_Npm);
    }
    r.cmd_bound = ((c->cmd_rel > 0.0) ? c->cmd_rel : CMD_REL_LIMIT) * r.cmd_max + CMD_ABS_LIMIT_N;
    r.x_bound = HAT_REL_LIMIT * r.hat_max / k_min + HAT_REL_LIMIT * x_max + Q24_LSB_M;
    r.y_bound = HAT_REL_LIMIT * r.hat_max / k_min + HAT_REL_LIMIT * y_max + Q24_LSB_M;
    for (size_t i = 0; i < n; i++) {
        if (g_q[i].status != g_ref[i].status || g_q[i].step != g_ref[i].step ||
            g_q[i].done != g_ref[i].done) {
            r.mismatch++;
        }
        r.steps = (g_ref[i].step > r.steps) ? g_ref[i].step : r.steps;
        r.dones += g_ref[i].done;
        r.hat_err = fmax(r.hat_err, fabs(g_q[i].force_hat_N - g_ref[i].force_hat_N));
        r.x_err = fmax(r.x_err, fabs(g_q[i].pos_ref_m - g_ref[i].pos_ref_m));
        r.y_err = fmax(r.y_err, fabs(g_q[i].y_ref_m - g_ref[i].y_ref_m));
        for (unsigned a = 0; a < 2u; a++) {
            r.cmd_err = fmax(r.cmd_err, fabs(g_q[i].force_cmd_N[a] - g_ref[i].force_cmd_N[a]));
        }
    }
    r.pass = r.mismatch == 0u && r.hat_err <= HAT_REL_LIMIT * r.hat_max &&
             r.cmd_err <= r.cmd_bound && r.x_err <= r.x_bound && r.y_err <= r.y_bound;
    return r;
}

static void print_cmp(const char *what, const cmp_t *r)
{
    printf("%-30s f_hat %.2e N (bound %.2e), f_cmd %.2e N (bound %.2e), x_d %.2e m (bound "
           "%.2e), y_d %.2e m (bound %.2e), %zu status/step/done mismatches (last step %zu, "
           "%zu ticks done): %s\n",
           what, r->hat_err, HAT_REL_LIMIT * r->hat_max, r->cmd_err, r->cmd_bound, r->x_err,
           r->x_bound, r->y_err, r->y_bound, r->mismatch, r->steps, r->dones,
           r->pass ? "within" : "BEYOND");
}

static cmp_t run_case(const case_t *c, int mutation, uint32_t saturate_at, uint8_t via_wrapper,
                      size_t *n_out)
{
    exec_side_seq_t seq;
    load(c, &seq);
    const size_t n = run_float64(c, &seq);
    seq.mutation = mutation;
    seq.via_wrapper = via_wrapper;
    seq.saturate_at = saturate_at;
    assert_int_equal(exec_side_q_replay(&seq, g_meas, g_q, n), 0);
    if (n_out != NULL) {
        *n_out = n;
    }
    return compare(c, n);
}

static void test_q_matches_float64(void **state)
{
    (void)state;
    for (size_t i = 0; i < sizeof k_cases / sizeof k_cases[0]; i++) {
        const case_t *c = &k_cases[i];
        const cmp_t r = run_case(c, EXEC_SIDE_MUT_NONE, 0u, 0u, NULL);
        print_cmp(c->name, &r);
        assert_true(r.hat_max > 1.0);
        assert_true(r.pass);
        /* the application's path: exec_tick, the float32 boundary over exec_tick_q */
        const cmp_t w = run_case(c, EXEC_SIDE_MUT_NONE, 0u, 1u, NULL);
        print_cmp("  via exec_tick", &w);
        assert_true(w.pass);
        if (c->lost_to_s > c->lost_from_s) { /* the hold counted alike (exec_contact_hold_ms) */
            printf("  phase held: float64 %u ms, integer %u ms\n",
                   (unsigned)exec_contact_hold_ms(&g_state), (unsigned)exec_side_q_hold_ms());
            assert_true(exec_contact_hold_ms(&g_state) > 0u);
            assert_true(abs((int)exec_contact_hold_ms(&g_state) - (int)exec_side_q_hold_ms()) <= 1);
        }
    }
    /* the features are exercised: a switch, a release's done, a NaN tick's status */
    size_t n = 0;
    cmp_t r = run_case(&k_cases[2], EXEC_SIDE_MUT_NONE, 0u, 0u, &n);
    assert_int_equal(r.steps, 2u);
    r = run_case(&k_cases[0], EXEC_SIDE_MUT_NONE, 0u, 0u, &n);
    assert_true(r.dones > 0u);
    assert_int_equal(g_q[k_cases[0].nan_tick].status, FS_ERR_NOT_FINITE);
    assert_true(g_q[k_cases[0].nan_tick].force_cmd_N[0] == 0.0);
}

/* One wrong constant of the integer tick breaks the agreement on the run that uses it. */
/* exec_prepare_next after every tick (the application's, after the actuator's write: the DMP's
 * blend and the object model's forces of the next tick computed ahead) leaves every output of
 * every case bit for bit as without it, through the float32 boundary too. */
static void test_prepare_same(void **state)
{
    (void)state;
    for (size_t i = 0; i < sizeof k_cases / sizeof k_cases[0]; i++) {
        for (uint8_t wrapper = 0u; wrapper <= 1u; wrapper++) {
            exec_side_seq_t seq;
            load(&k_cases[i], &seq);
            const size_t n = run_float64(&k_cases[i], &seq);
            seq.via_wrapper = wrapper;
            assert_int_equal(exec_side_q_replay(&seq, g_meas, g_q, n), 0);
            seq.prepare = 1u;
            assert_int_equal(exec_side_q_replay(&seq, g_meas, g_q_prepared, n), 0);
            assert_memory_equal(g_q, g_q_prepared, n * sizeof g_q[0]);
        }
    }
}

static void test_mutations_fail(void **state)
{
    (void)state;
    static const struct {
        int mutation;
        size_t case_index;
        const char *what;
    } k_mut[] = {
        {EXEC_SIDE_MUT_BLEND, 0u, "blend increment +1 %"},
        {EXEC_SIDE_MUT_RELEASE, 0u, "release increment +1 %"},
        {EXEC_SIDE_MUT_INV_K, 0u, "1/k +1 %"},
        {EXEC_SIDE_MUT_INV_M, 1u, "1/m_v +1 %"},
        {EXEC_SIDE_MUT_STOP, 6u, "phase-stop gain +10 %"},
        {EXEC_SIDE_MUT_CONTACT, 7u, "contact gain +10 %"},
        {EXEC_SIDE_MUT_CARRY, 2u, "step 1 start force +10 mN"},
    };
    for (size_t i = 0; i < sizeof k_mut / sizeof k_mut[0]; i++) {
        const cmp_t r = run_case(&k_cases[k_mut[i].case_index], k_mut[i].mutation, 0u, 0u, NULL);
        char what[64];
        (void)snprintf(what, sizeof what, "mutation %s", k_mut[i].what);
        print_cmp(what, &r);
        assert_false(r.pass);
    }
}

/* A DMP step that saturates returns FS_ERR_FIXED_OVERFLOW in its tick (the ticks before it
 * agree with the float64 run). */
static void test_saturation_status(void **state)
{
    (void)state;
    const uint32_t at = 700u;
    size_t n = 0;
    (void)run_case(&k_cases[0], EXEC_SIDE_MUT_NONE, at, 0u, &n);
    for (size_t i = 0; i < at; i++) {
        assert_int_equal(g_q[i].status, g_ref[i].status);
    }
    assert_int_equal(g_q[at].status, FS_ERR_FIXED_OVERFLOW);
    printf("saturation at tick %u: status %d\n", (unsigned)at, g_q[at].status);
}

/* A start whose configuration leaves the integer tick's formats is refused (303, the fixed build's
 * 3xx codes): y beyond the Q.55 path's +-64 m. */
static void test_start_refuses_out_of_range(void **state)
{
    (void)state;
    exec_side_seq_t seq;
    load(&k_cases[0], &seq);
    seq.y_hold_m = 100.0;
    assert_int_equal(exec_side_q_replay(&seq, g_meas, g_q, 0u), FS_ERR_FIXED_CONFIG);
    seq.y_hold_m = 63.0;
    assert_int_equal(exec_side_q_replay(&seq, g_meas, g_q, 0u), FS_OK);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_q_matches_float64),
        cmocka_unit_test(test_prepare_same),
        cmocka_unit_test(test_mutations_fail),
        cmocka_unit_test(test_saturation_status),
        cmocka_unit_test(test_start_refuses_out_of_range),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

/* The supervisor's integer build (fs_safety_fx, the Cortex-M3 image's) against the double build
 * (fs_safety), tick by tick on random trials with the same inputs (generated on the integer
 * grid, so both see the same values): limits that bind, slew and its leaky bucket, workspace and
 * velocity gates, the contact force limit, sensor range, spikes, encoder jumps, stuck readings,
 * NaN readings and requests, host silence and the stop ramp, clears and the re-arm. Every tick:
 * the same fault code, causes, limiter flags, enable and stop state, the same clear result,
 * and commands within 1e-3 N (printed: the integer slew adds its rounding a binding tick, the
 * ramp truncates). */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <cmocka.h>

#include "saf.h"
#include "saf_fixed_side.h"

static uint32_t rng = 20261203u;

static uint32_t next(void)
{
    rng = rng * 1664525u + 1013904223u;
    return rng >> 8; /* 24 bits */
}

static double uni(double lo, double hi)
{
    return lo + (hi - lo) * (double)next() / 16777216.0;
}

/* v on a grid of 2^-g (exact in double and in the integer formats) */
static double grid(double v, int g)
{
    return ldexp(round(ldexp(v, g)), -g);
}

static double of_q(int32_t q, int frac)
{
    return (q == INT32_MIN) ? (double)NAN : ldexp((double)q, -frac);
}

static int32_t q_of(double v, int frac)
{
    return isfinite(v) ? (int32_t)llround(ldexp(v, frac)) : INT32_MIN;
}

static saf_config_t dcfg;
static saf_state_t dst;

static void double_reset(const side_cfg_t *c)
{
    saf_default_config(&dcfg);
    for (unsigned a = 0; a < SAF_AXES; a++) {
        dcfg.lim.axis[a].force_max_N = c->force_max_N;
        dcfg.lim.axis[a].slew_max_N = c->slew_max_N;
        dcfg.lim.axis[a].contact_force_max_N = c->contact_force_max_N;
        dcfg.sen.axis[a].spike_N = c->spike_N;
        dcfg.sen.axis[a].jump_m = c->jump_m;
        dcfg.sen.axis[a].stuck_ticks = c->stuck_ticks;
    }
    dcfg.lim.slew_fault_ticks = c->slew_fault_ticks;
    dcfg.wdg.timeout_ms = c->timeout_ms;
    saf_init(&dst);
    saf_prepare(&dcfg, &dst);
}

static void double_step(const side_in_t *in, side_out_t *out)
{
    out->clear_result = 0u;
    if (in->clear) {
        out->clear_result = (uint16_t)saf_clear_request(&dcfg, &dst, in->now_ms);
    }
    saf_input_t s;
    memset(&s, 0, sizeof s);
    s.tick = in->tick;
    s.now_ms = in->now_ms;
    s.host_frame = in->host_frame;
    for (unsigned a = 0; a < SAF_AXES; a++) {
        s.meas[a].pos_m = of_q(in->pos_q24[a], 24);
        s.meas[a].vel_mps = of_q(in->vel_q24[a], 24);
        s.meas[a].force_N = of_q(in->force_q16[a], 16);
        s.force_req_N[a] = of_q(in->req_q16[a], 16);
    }
    saf_output_t o;
    saf_step(&dcfg, &dst, &s, &o);
    for (unsigned a = 0; a < SAF_AXES; a++) {
        out->cmd_q16[a] = q_of(o.force_cmd_N[a], 16); /* compared in N below, not as integers */
    }
    out->enable = o.actuator_enable;
    out->stopping = o.stopping;
    out->fault_code = o.fault_code;
    out->cause_mask = o.cause_mask;
    out->lim_flags = o.lim_flags;
}

typedef struct {
    double worst_N;
    uint32_t ticks, faults, clears, binding, mismatches;
} tally_t;

/* One trial of n ticks into t (mutate_slew: added to the double side's slew limit). */
static void trial(uint32_t n, tally_t *t, double mutate_slew)
{
    side_cfg_t c;
    c.force_max_N = grid(uni(5.0, 100.0), 8);
    c.slew_max_N = grid(uni(0.1, 5.0), 8);
    c.contact_force_max_N = grid(uni(30.0, 80.0), 8);
    c.spike_N = grid(uni(5.0, 30.0), 8);
    c.jump_m = grid(uni(0.002, 0.01), 20);
    c.timeout_ms = (uint16_t)uni(50.0, 300.0);
    c.stuck_ticks = (next() & 1u) ? 0u : (uint16_t)uni(50.0, 300.0);
    c.slew_fault_ticks = (uint16_t)uni(0.0, 80.0);
    /* a validated configuration: the ramp can reach zero within the slew limit */
    while (c.slew_max_N * 40.0 < c.force_max_N) {
        c.slew_max_N *= 2.0;
    }
    side_fx_reset(&c);
    c.slew_max_N += mutate_slew; /* the mutation check: the double side sees another slew */
    double_reset(&c);
    double pos[2] = {0.0, 0.0}, force[2] = {5.0, 0.0}, req[2] = {0.0, 0.0};
    uint32_t silent_until = 0u, rearm_until = 0u;
    for (uint32_t k = 1; k <= n; k++) {
        side_in_t in;
        memset(&in, 0, sizeof in);
        in.tick = k;
        in.now_ms = k;
        if (k > silent_until && next() % 3000u == 0u) {
            silent_until = k + (uint32_t)uni(20.0, 400.0); /* the host goes quiet */
        }
        in.host_frame = k > silent_until;
        in.clear = (k % 500u == 0u);
        if (in.clear) {
            req[0] = 0.0; /* the request back at zero re-arms the output after a clear */
            req[1] = 0.0;
            rearm_until = k + 30u;
        }
        for (unsigned a = 0; a < 2u; a++) {
            const uint32_t ev = next() % 6000u;
            pos[a] += uni(-2e-4, 2e-4);
            if (ev == 1u) {
                pos[a] += (next() & 1u) ? 0.02 : -0.02; /* an encoder jump */
            }
            if (pos[a] > 0.7 || pos[a] < -0.7) {
                pos[a] *= 0.5; /* beyond the workspace (0.5 m) now and then, back later */
            }
            if (ev != 2u) { /* ev 2: the force reading repeats (stuck) */
                force[a] += uni(-0.5, 0.5);
            }
            if (ev == 3u) {
                force[a] += 40.0; /* a spike */
            }
            force[a] = (force[a] > 90.0 || force[a] < -90.0) ? 0.0 : force[a];
            if (k < rearm_until) {
                req[a] = 0.0;
            } else if (next() % 50u == 0u) {
                req[a] = uni(-150.0, 150.0); /* beyond the force limit too */
            } else {
                req[a] += uni(-1.0, 1.0);
            }
            in.pos_q24[a] = q_of(grid(pos[a], 24), 24);
            /* over 1 m/s now and then (ev 6) */
            in.vel_q24[a] = q_of(grid((ev == 6u) ? uni(1.0, 1.3) : uni(-0.8, 0.8), 24), 24);
            in.force_q16[a] = q_of(grid(force[a], 16), 16);
            in.req_q16[a] = q_of(grid(req[a], 16), 16);
            if (ev == 4u) {
                in.force_q16[a] = INT32_MIN; /* a NaN reading */
            }
            if (ev == 5u) {
                in.req_q16[a] = INT32_MIN; /* a NaN request */
            }
        }
        side_out_t fx, db;
        side_fx_step(&in, &fx);
        double_step(&in, &db);
        if (fx.fault_code != db.fault_code || fx.cause_mask != db.cause_mask ||
            fx.lim_flags != db.lim_flags || fx.enable != db.enable || fx.stopping != db.stopping ||
            fx.clear_result != db.clear_result) {
            t->mismatches++;
        }
        for (unsigned a = 0; a < 2u; a++) {
            const double d = fabs(ldexp((double)fx.cmd_q16[a], -16) -
                                  ldexp((double)db.cmd_q16[a], -16));
            t->worst_N = (d > t->worst_N) ? d : t->worst_N;
        }
        t->ticks++;
        t->faults += (fx.stopping && fx.fault_code != 0u) ? 1u : 0u;
        t->clears += (in.clear && fx.clear_result == 0u && fx.stopping == false) ? 1u : 0u;
        t->binding += ((fx.lim_flags & LIM_F_SLEW) != 0u) ? 1u : 0u;
    }
}

static void test_integer_build_is_the_double_one(void **state)
{
    (void)state;
    tally_t t;
    memset(&t, 0, sizeof t);
    for (uint32_t i = 0; i < 40u; i++) {
        trial(4000u, &t, 0.0);
    }
    printf("fs_safety_fx vs fs_safety: %u ticks (%u stopping, %u slew-bound), the same codes, "
           "causes and flags every tick; max |command difference| %.3g N (bound 1e-3)\n",
           (unsigned)t.ticks, (unsigned)t.faults, (unsigned)t.binding, t.worst_N);
    assert_true(t.faults > 10000u && t.binding > 1000u); /* the trials reach what they test */
    assert_int_equal(t.mismatches, 0u);
    assert_true(t.worst_N <= 1e-3);
}

/* The comparison sees a one-constant change: the double side with its slew 1/256 N larger. */
static void test_a_mutation_is_seen(void **state)
{
    (void)state;
    tally_t t;
    memset(&t, 0, sizeof t);
    for (uint32_t i = 0; i < 5u; i++) {
        trial(4000u, &t, 1.0 / 256.0);
    }
    printf("mutation (slew + 1/256 N on one side): %u ticks differ, max |command difference| "
           "%.3g N\n",
           (unsigned)t.mismatches, t.worst_N);
    assert_true(t.mismatches > 0u || t.worst_N > 1e-3);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_integer_build_is_the_double_one),
        cmocka_unit_test(test_a_mutation_is_seen),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

/* Fault injection through the supervisor at 1 kHz, one scenario per fault code: the device is
 * pressing (request 40 N on x, -20 N on y, plausible noisy sensors), the fault's cause appears
 * at its onset tick, later disappears. Measured per fault: detection time and time to zero force
 * (both from the onset), worst |force| after onset; checked: detected within its bound, |force|
 * non-increasing from detection and zero within 50 ms of it, actuator disabled, clear refused
 * while the cause persists, still latched (no resume) after the cause is gone, clear accepted.
 * Writes the table to FS_SAFETY_OUT/safety_table.md (docs/safety.md quotes it). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <math.h>
#include <cmocka.h>

#include "saf.h"

#define K_ONSET 1000u  /* earliest onset tick (device pressing steadily by then) */
#define K_REMOVE 2500u /* the cause is removed here */
#define K_END 3000u

static uint64_t g_rng = 0x6A09E667F3BCC909ull;

static double noise(void)
{
    g_rng ^= g_rng >> 12;
    g_rng ^= g_rng << 25;
    g_rng ^= g_rng >> 27;
    const uint64_t r = g_rng * 0x2545F4914F6CDD1Dull;
    return ((double)(r >> 11) * (1.0 / 9007199254740992.0) - 0.5) * 0.04;
}

typedef struct {
    flt_code_t code;
    const char *injection; /* what the scenario does */
    double bound_ms;       /* detection bound from onset */
    const char *bound_text;
    bool persistent; /* the cause lasts until K_REMOVE (else one tick) */
} scenario_t;

/* Builds the inputs of tick k for scenario s. Returns true if the cause is present at k
 * (the onset is the first such tick). */
static bool inject(const scenario_t *s, const saf_config_t *cfg, uint32_t k, saf_input_t *in,
                   const fs_real_t cmd_prev[2])
{
    const bool active = k >= K_ONSET && (s->persistent ? k < K_REMOVE : k == K_ONSET);
    const bool after = k >= K_ONSET && k < K_REMOVE;
    memset(in, 0, sizeof *in);
    in->tick = k;
    in->now_ms = k;
    in->host_frame = (k % 10u) == 0u;
    for (int i = 0; i < 2; i++) {
        in->meas[i].pos_m = (fs_real_t)(0.01 + 1e-5 * noise());
        in->meas[i].vel_mps = (fs_real_t)(0.01 * noise());
        in->meas[i].force_N = (fs_real_t)(0.5 * (double)cmd_prev[i] + noise());
    }
    in->force_req_N[0] = FS_R(40.0);
    in->force_req_N[1] = FS_R(-20.0);
    const double dk = (double)k - (double)K_ONSET;
    (void)dk;
    bool cause = false;
    switch (s->code) {
    case FLT_HOST_SILENCE:
        /* last frame at K_ONSET, none until K_REMOVE */
        if (k > K_ONSET && k < K_REMOVE) {
            in->host_frame = false;
        }
        cause = k >= K_ONSET && k < K_REMOVE; /* onset: the last frame, at K_ONSET */
        (void)cfg;
        break;
    case FLT_BUS_OFF:
        in->causes = active ? FLT_BIT(FLT_BUS_OFF) : 0u;
        cause = active;
        break;
    case FLT_TICK_OVERRUN:
        in->causes = active ? FLT_BIT(FLT_TICK_OVERRUN) : 0u;
        cause = active;
        break;
    case FLT_SKILL_INVALID:
        in->causes = active ? FLT_BIT(FLT_SKILL_INVALID) : 0u;
        cause = active;
        break;
    case FLT_STORAGE:
        in->causes = active ? FLT_BIT(FLT_STORAGE) : 0u;
        cause = active;
        break;
    case FLT_BAND:
        in->causes = active ? FLT_BIT(FLT_BAND) : 0u;
        cause = active;
        break;
    case FLT_SENSOR_NAN:
        if (active) {
            in->meas[0].force_N = (fs_real_t)NAN;
            cause = true;
        }
        break;
    case FLT_SENSOR_RANGE:
        /* a broken wire: the reading jumps to 250 N, beyond the 200 N range (the same tick
         * also latches SENSOR_SPIKE and FORCE_LIMIT; RANGE is reported first) */
        if (after) {
            in->meas[0].force_N = FS_R(250.0);
            cause = true;
        }
        break;
    case FLT_SENSOR_STUCK:
        if (after) {
            in->meas[0].force_N = FS_R(19.987);
            cause = true;
        }
        break;
    case FLT_SENSOR_SPIKE:
        if (active) {
            in->meas[0].force_N = (fs_real_t)((double)in->meas[0].force_N + 30.0);
            cause = true;
        }
        break;
    case FLT_ENCODER_JUMP:
        if (active) {
            in->meas[0].pos_m = (fs_real_t)((double)in->meas[0].pos_m + 0.010);
            cause = true;
        }
        break;
    case FLT_FORCE_LIMIT:
        /* contact force climbs 1 N per tick past the 60 N contact limit */
        if (after) {
            const double f = 20.0 + (dk + 1.0);
            in->meas[0].force_N = (fs_real_t)f;
            cause = f > 60.0;
        }
        break;
    case FLT_SLEW_LIMIT:
        if (active) {
            in->force_req_N[0] = (k & 1u) ? FS_R(50.0) : FS_R(-50.0);
            cause = true; /* onset of the oscillation; detection by the leaky bucket */
        }
        break;
    case FLT_WORKSPACE:
        /* drifts out at 0.5 m/s past the 0.5 m workspace edge */
        if (after) {
            const double x = 0.01 + 0.0005 * (dk + 1.0);
            in->meas[0].pos_m = (fs_real_t)x;
            in->meas[0].vel_mps = FS_R(0.5);
            cause = x > 0.5;
        }
        break;
    case FLT_VELOCITY:
        if (after) {
            const double v = 0.05 * (dk + 1.0);
            in->meas[0].vel_mps = (fs_real_t)(v > 2.0 ? 2.0 : v);
            cause = v > 1.0;
        }
        break;
    case FLT_CMD_NOT_FINITE:
        if (active) {
            in->force_req_N[0] = (fs_real_t)NAN;
            cause = true;
        }
        break;
    default: break;
    }
    return cause;
}

typedef struct {
    double det_ms, zero_ms, worst_N, force_at_onset_N;
    bool pass, monotone, refused_while_present, latched_after_removal, cleared;
} result_t;

static result_t run_scenario(const scenario_t *s)
{
    saf_config_t cfg;
    saf_default_config(&cfg);
    saf_state_t st;
    saf_init(&st);
    saf_prepare(&cfg, &st);
    saf_input_t in;
    saf_output_t out;
    fs_real_t prev[2] = {FS_R(0.0), FS_R(0.0)};
    result_t r;
    memset(&r, 0, sizeof r);
    r.monotone = true;
    uint32_t k_onset = 0, k_det = 0, k_zero = 0;
    bool refused = false, tried_refuse = false;
    for (uint32_t k = 1; k < K_END; k++) {
        const bool cause = inject(s, &cfg, k, &in, prev);
        if (cause && k_onset == 0u) {
            k_onset = k;
            r.force_at_onset_N = fabs((double)prev[0]);
        }
        saf_step(&cfg, &st, &in, &out);
        if (k_det == 0u && out.fault_code != 0u) {
            k_det = k;
            assert_int_equal(out.fault_code, s->code); /* the right code, first */
        }
        if (k_onset != 0u) {
            for (int i = 0; i < 2; i++) {
                const double a = fabs((double)out.force_cmd_N[i]);
                if (a > r.worst_N) {
                    r.worst_N = a;
                }
            }
        }
        if (k_det != 0u) {
            for (int i = 0; i < 2; i++) {
                if (fabs((double)out.force_cmd_N[i]) > fabs((double)prev[i])) {
                    r.monotone = false;
                }
            }
            if (k_zero == 0u && out.force_cmd_N[0] == FS_R(0.0) &&
                out.force_cmd_N[1] == FS_R(0.0)) {
                k_zero = k;
                assert_false(out.actuator_enable);
            }
            /* a clear while the cause persists must be refused */
            if (!tried_refuse && s->persistent && cause && s->code != FLT_HOST_SILENCE) {
                tried_refuse = true;
                refused = saf_clear_request(&cfg, &st, k) == s->code;
            }
        }
        prev[0] = out.force_cmd_N[0];
        prev[1] = out.force_cmd_N[1];
    }
    if (!s->persistent || s->code == FLT_HOST_SILENCE) {
        refused =
            true; /* a one-tick cause (or silence, ended by the request) has nothing to refuse */
    }
    r.refused_while_present = refused;
    r.latched_after_removal = out.fault_code == s->code && !out.actuator_enable &&
                              out.force_cmd_N[0] == FS_R(0.0);
    r.cleared = saf_clear_request(&cfg, &st, K_END) == FLT_NONE;
    r.det_ms = (k_det != 0u && k_onset != 0u) ? (double)(k_det - k_onset) : -1.0;
    r.zero_ms = (k_zero != 0u && k_onset != 0u) ? (double)(k_zero - k_onset) : -1.0;
    const double ramp_ms = (k_zero != 0u) ? (double)(k_zero - k_det) + 1.0 : 1e9;
    r.pass = k_det != 0u && r.det_ms >= 0.0 && r.det_ms <= s->bound_ms && ramp_ms <= 50.0 &&
             r.monotone && r.worst_N <= (double)cfg.lim.axis[0].force_max_N &&
             r.refused_while_present && r.latched_after_removal && r.cleared;
    return r;
}

static void test_fault_table(void **state)
{
    (void)state;
    static const scenario_t sc[] = {
        {FLT_HOST_SILENCE, "host frames stop (onset: last frame)", 101.0, "timeout+1", true},
        {FLT_BUS_OFF, "bus-off flag from the CAN driver", 0.0, "same tick", true},
        {FLT_SENSOR_NAN, "force reading NaN", 0.0, "same tick", true},
        {FLT_SENSOR_RANGE, "force reading jumps to 250 N (range 200 N)", 0.0, "same tick", true},
        {FLT_SENSOR_STUCK, "force reading frozen at 19.987 N", 499.0, "stuck_ticks-1", true},
        {FLT_SENSOR_SPIKE, "one reading +30 N", 0.0, "same tick", false},
        {FLT_ENCODER_JUMP, "one position reading +10 mm", 0.0, "same tick", false},
        {FLT_FORCE_LIMIT, "contact force climbs 1 N/tick past 60 N", 0.0, "same tick", true},
        {FLT_SLEW_LIMIT, "request oscillates +-50 N every tick", 200.0, "4*slew_fault_ticks", true},
        {FLT_WORKSPACE, "x drifts out at 0.5 m/s past 0.5 m", 0.0, "same tick", true},
        {FLT_VELOCITY, "velocity reading climbs past 1 m/s", 0.0, "same tick", true},
        {FLT_TICK_OVERRUN, "scheduler reports one overrun", 0.0, "same tick", false},
        {FLT_SKILL_INVALID, "active skill reported invalid", 0.0, "same tick", true},
        {FLT_CMD_NOT_FINITE, "control law outputs NaN once", 0.0, "same tick", false},
        {FLT_STORAGE, "flash error reported", 0.0, "same tick", true},
        {FLT_BAND, "outside the band for the run's stop time", 0.0, "same tick", true},
    };
    const size_t n = sizeof sc / sizeof sc[0];
    assert_int_equal(n, FLT_COUNT);
    FILE *f = fopen(FS_SAFETY_OUT "/safety_table.md", "w");
    char line[512];
    const char
        *hdr = "| code | fault | injection | detection (ms) | bound | time to zero force (ms) | "
               "force at onset (N) | worst force (N) | monotone | refused while present | "
               "latched after cause gone | pass |\n"
               "|---:|---|---|---:|---|---:|---:|---:|---|---|---|---|\n";
    fputs(hdr, stdout);
    if (f != NULL) {
        fputs(hdr, f);
    }
    uint32_t passed = 0;
    for (size_t i = 0; i < n; i++) {
        const result_t r = run_scenario(&sc[i]);
        snprintf(line, sizeof line,
                 "| %u | %s | %s | %.0f | %s | %.0f | %.1f | %.1f | %s | %s | %s | %s |\n",
                 (unsigned)sc[i].code, flt_name((uint16_t)sc[i].code), sc[i].injection, r.det_ms,
                 sc[i].bound_text, r.zero_ms, r.force_at_onset_N, r.worst_N,
                 r.monotone ? "yes" : "NO", r.refused_while_present ? "yes" : "NO",
                 r.latched_after_removal ? "yes" : "NO", r.pass ? "pass" : "FAIL");
        fputs(line, stdout);
        if (f != NULL) {
            fputs(line, f);
        }
        if (r.pass) {
            passed++;
        }
    }
    snprintf(line, sizeof line,
             "\n%u/%u faults pass (defaults: F_max 50 N, slew 2 N/tick, "
             "timeout 100 ms, ramp 40 ms, 1 kHz).\n",
             (unsigned)passed, (unsigned)n);
    fputs(line, stdout);
    if (f != NULL) {
        fputs(line, f);
        fclose(f);
    }
    assert_int_equal(passed, n);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fault_table),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

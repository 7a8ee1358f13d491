/* 1,000 randomised host-silence trials through the supervisor at 1 kHz (fixed seed).
 * Each trial: a random timeout in 20..500 ms (every 4th trial the default 100 ms), host frames
 * at random real times (gaps below the timeout; a frame arriving between ticks is seen at the
 * next tick), a random force request (sometimes beyond the limit) and plausible noisy sensor
 * readings; the host then goes silent. Checked on every trial:
 *   - no fault while the host talks; the fault is FLT_HOST_SILENCE and nothing else;
 *   - detection between timeout and timeout + 1 ms after the last frame really arrived;
 *   - from detection, |force| non-increasing on both axes every tick, exactly zero within
 *     50 ms, then the actuator disabled;
 *   - the fault stays latched and the output zero when the host comes back (no auto-resume);
 *     a clear is accepted, and the old request still does not come back by itself.
 * Figures go to stdout and to FS_SAFETY_OUT/host_silence.txt. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <math.h>
#include <cmocka.h>

#include "saf.h"

#define TWO_PI 6.283185307179586

static uint64_t g_rng = 0xD1B54A32D192ED03ull;

static double uniform(double lo, double hi)
{
    g_rng ^= g_rng >> 12;
    g_rng ^= g_rng << 25;
    g_rng ^= g_rng >> 27;
    const uint64_t r = g_rng * 0x2545F4914F6CDD1Dull;
    return lo + (hi - lo) * ((double)(r >> 11) * (1.0 / 9007199254740992.0));
}

typedef struct {
    double amp, bias, freq, amp_y;
} profile_t;

static fs_real_t request(const profile_t *p, uint32_t k, int axis)
{
    const double t = (double)k * 1e-3;
    if (axis == 0) {
        return (fs_real_t)(p->bias + p->amp * sin(TWO_PI * p->freq * t));
    }
    return (fs_real_t)(p->amp_y * cos(TWO_PI * p->freq * t));
}

static void measure(saf_meas_t m[2], const fs_real_t cmd[2], uint32_t k)
{
    for (int i = 0; i < 2; i++) {
        const double noise = uniform(-0.02, 0.02);
        m[i].force_N = (fs_real_t)(0.5 * (double)cmd[i] + noise);
        m[i].pos_m = (fs_real_t)(0.01 + 1e-6 * (double)(k % 13u) + 1e-7 * noise);
        m[i].vel_mps = (fs_real_t)(0.01 * noise);
    }
}

static void test_host_silence_trials(void **state)
{
    (void)state;
    const uint32_t trials = 1000u;
    double worst_det_over_ms = -1e9, best_det_over_ms = 1e9, worst_ramp_ms = 0.0;
    double worst_total_default_ms = 0.0, worst_total_any_over_timeout_ms = 0.0;
    double worst_force_N = 0.0;
    uint32_t n_default = 0;
    for (uint32_t trial = 0; trial < trials; trial++) {
        saf_config_t cfg;
        saf_default_config(&cfg);
        const uint32_t timeout = (trial % 4u == 0u) ? 100u : (uint32_t)uniform(20.0, 501.0);
        cfg.wdg.timeout_ms = (uint16_t)timeout;
        assert_int_equal(saf_config_validate(&cfg), SAF_OK);
        saf_state_t st;
        saf_init(&st);
        saf_prepare(&cfg, &st);
        profile_t p = {uniform(0.0, 40.0), uniform(-20.0, 20.0), uniform(0.1, 3.0),
                       uniform(0.0, 30.0)};
        if (trial % 10u == 3u) {
            p.amp = 200.0; /* a request far beyond the limit */
        }
        const double run_ms = uniform(200.0, 2000.0);
        const double gap_max = (timeout - 2u < 50u) ? (double)(timeout - 2u) : 50.0;
        double next_frame = uniform(0.0, 1.0);
        double last_frame = -1.0;
        uint32_t k_det = 0, k_zero = 0;
        double last_before_silence = 0.0;
        fs_real_t prev_cmd[2] = {FS_R(0.0), FS_R(0.0)};
        saf_input_t in;
        memset(&in, 0, sizeof in);
        saf_output_t out;
        const uint32_t end_silence = (uint32_t)run_ms + timeout + 200u;
        const uint32_t end = end_silence + 500u;
        for (uint32_t k = 1; k <= end; k++) {
            const bool host_back = k > end_silence;
            /* frames that arrived in (k-1, k] are seen at tick k */
            bool host = false;
            while (next_frame <= (double)k && (next_frame <= run_ms || host_back)) {
                host = true;
                last_frame = next_frame;
                next_frame += uniform(0.3, gap_max);
            }
            if (host_back && !host && next_frame > run_ms && next_frame < (double)end_silence) {
                next_frame = (double)k + uniform(0.0, 1.0);
            }
            in.tick = k;
            in.now_ms = k;
            in.host_frame = host;
            measure(in.meas, prev_cmd, k);
            in.force_req_N[0] = request(&p, k, 0);
            in.force_req_N[1] = request(&p, k, 1);
            saf_step(&cfg, &st, &in, &out);
            for (int i = 0; i < 2; i++) {
                assert_true(isfinite((double)out.force_cmd_N[i]));
                assert_true(fabs((double)out.force_cmd_N[i]) <= 50.0);
                if (fabs((double)out.force_cmd_N[i]) > worst_force_N) {
                    worst_force_N = fabs((double)out.force_cmd_N[i]);
                }
            }
            if (k_det == 0u && out.fault_code != 0u) {
                k_det = k;
                assert_int_equal(out.fault_code, FLT_HOST_SILENCE);
                assert_int_equal(out.cause_mask, FLT_BIT(FLT_HOST_SILENCE));
                last_before_silence = last_frame;
                const double lat = (double)k - last_frame; /* since the last frame arrived */
                assert_true(lat >= (double)timeout);
                assert_true(lat <= (double)timeout + 1.0);
                if (lat - timeout > worst_det_over_ms) {
                    worst_det_over_ms = lat - timeout;
                }
                if (lat - timeout < best_det_over_ms) {
                    best_det_over_ms = lat - timeout;
                }
            }
            if (k_det == 0u) {
                assert_int_equal(out.fault_code, 0);
                assert_true(out.actuator_enable);
            } else {
                /* monotone in magnitude from the last command before detection */
                for (int i = 0; i < 2; i++) {
                    assert_true(fabs((double)out.force_cmd_N[i]) <= fabs((double)prev_cmd[i]));
                }
                assert_int_equal(out.fault_code, FLT_HOST_SILENCE);
                assert_true(out.stopping);
                if (k_zero == 0u && out.force_cmd_N[0] == FS_R(0.0) &&
                    out.force_cmd_N[1] == FS_R(0.0)) {
                    k_zero = k;
                }
                if (k_zero != 0u) {
                    assert_true(out.force_cmd_N[0] == FS_R(0.0));
                    assert_true(out.force_cmd_N[1] == FS_R(0.0));
                    assert_false(out.actuator_enable);
                }
            }
            prev_cmd[0] = out.force_cmd_N[0];
            prev_cmd[1] = out.force_cmd_N[1];
        }
        assert_true(k_det != 0u);
        assert_true(k_zero != 0u);
        /* time to zero counted from detection (the tick of detection is ramp step 1) */
        const double ramp_ms = (double)(k_zero - k_det) + 1.0;
        assert_true(ramp_ms <= 50.0);
        if (ramp_ms > worst_ramp_ms) {
            worst_ramp_ms = ramp_ms;
        }
        /* from the last frame's real arrival to the first tick of exactly zero force */
        const double total_from_silence = (double)k_zero - last_before_silence;
        if (total_from_silence - timeout > worst_total_any_over_timeout_ms) {
            worst_total_any_over_timeout_ms = total_from_silence - timeout;
        }
        if (timeout == 100u) {
            n_default++;
            if (total_from_silence > worst_total_default_ms) {
                worst_total_default_ms = total_from_silence;
            }
        }
        /* the host came back 500 ms ago and the request is non-zero: still latched, still off */
        assert_int_equal(out.fault_code, FLT_HOST_SILENCE);
        assert_false(out.actuator_enable);
        /* clear accepted now; the still non-zero request does not resume */
        assert_int_equal(saf_clear_request(&cfg, &st, end), FLT_NONE);
        for (uint32_t k = end + 1u; k <= end + 50u; k++) {
            in.tick = k;
            in.now_ms = k;
            in.host_frame = true;
            measure(in.meas, prev_cmd, k);
            in.force_req_N[0] = FS_R(25.0);
            in.force_req_N[1] = FS_R(-25.0);
            saf_step(&cfg, &st, &in, &out);
            assert_true(out.force_cmd_N[0] == FS_R(0.0) && out.force_cmd_N[1] == FS_R(0.0));
            assert_int_equal(out.fault_code, 0);
        }
    }
    char line[512];
    snprintf(line, sizeof line,
             "host_silence trials=%u detection_after_timeout_ms min=%.3f max=%.3f (bound 1) "
             "ramp_to_zero_ms max=%.0f (bound 50) silence_to_zero_ms_at_100ms_timeout max=%.0f "
             "(bound 150, %u trials) worst_force_N=%.3f latched_no_resume=%u/%u\n",
             trials, best_det_over_ms, worst_det_over_ms, worst_ramp_ms, worst_total_default_ms,
             n_default, worst_force_N, trials, trials);
    fputs(line, stdout);
#ifdef FS_REAL_FLOAT
    FILE *f = fopen(FS_SAFETY_OUT "/host_silence_f32.txt", "w");
#else
    FILE *f = fopen(FS_SAFETY_OUT "/host_silence.txt", "w");
#endif
    if (f != NULL) {
        fputs(line, f);
        fclose(f);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_host_silence_trials),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

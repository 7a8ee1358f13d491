/* Control tick, float32 build (Cortex-M4F with FPv4-SP): fs_core_f32 (dmp_step, pfc_step). */
#include <math.h>
#include <string.h>

#include "cm_hal.h"
#include "cm_tick.h"
#include "dmp.h"
#include "pfc.h"
#include "skill.h"

#define DT_S 0.001f
#define INV_DT 1000.0f
#define ENC_M_PER_COUNT (1.0f / (float)(1u << CM_HAL_ENC_FRAC_BITS))
#define FORCE_N_PER_COUNT (1.0f / (float)(1u << CM_HAL_FORCE_FRAC_BITS))
#define COUNTS_PER_N ((float)(1u << CM_HAL_FORCE_FRAC_BITS))

static skill_t cm_skill;
static dmp_state_t cm_dmp;
static dmp_run_t cm_run;
static pfc_config_t cm_pfc;
static pfc_state_t cm_pfc_state;
static float cm_prev_pos_m[CM_HAL_AXES];
static float cm_prev_pos_d_m;
static float cm_hold_y_m;
static float cm_prev_y_d_m;
static uint32_t cm_path_bits;
static float cm_last_cmd_N[CM_HAL_AXES];
static uint32_t cm_faults;
static uint32_t cm_rows;
static uint8_t cm_seq;

fs_status_t cm_tick_init(const uint8_t *image, uint32_t len, double goal_scale, double time_scale)
{
    fs_status_t st = skill_parse(image, len, &cm_skill);
    if (st != FS_OK) {
        return st;
    }
    cm_run.goal_scale = (float)goal_scale;
    cm_run.time_scale = (float)time_scale;
    pfc_default_config(&cm_pfc);
    st = pfc_config_validate(&cm_pfc);
    if (st != FS_OK) {
        return st;
    }
    dmp_state_reset(&cm_dmp);
    pfc_reset(&cm_pfc_state);
    const double rows = (double)cm_skill.dmp.duration_s * time_scale / (double)cm_skill.dmp.dt_s;
    cm_rows = (uint32_t)(rows + 0.5);
    cm_prev_pos_m[0] = cm_prev_pos_m[1] = 0.0f;
    cm_prev_pos_d_m = cm_skill.surface_m;
    cm_hold_y_m = 0.0f;
    cm_prev_y_d_m = 0.0f;
    cm_last_cmd_N[0] = cm_last_cmd_N[1] = 0.0f;
    cm_faults = 0u;
    cm_seq = 0u;
    return FS_OK;
}

uint32_t cm_tick_path_bits(void)
{
    return cm_path_bits;
}

uint32_t cm_tick_rows(void)
{
    return cm_rows;
}
double cm_tick_surface_m(void)
{
    return (double)cm_skill.surface_m;
}
uint32_t cm_tick_faults(void)
{
    return cm_faults;
}
const char *cm_tick_numeric(void)
{
    return "float";
}

double cm_tick_fhat_N(uint32_t bits)
{
    float f;
    memcpy(&f, &bits, sizeof(f));
    return (double)f;
}

static float cm_clamp(float v, float lo, float hi)
{
    return (v > hi) ? hi : ((v < lo) ? lo : v);
}

static void cm_put_i16(uint8_t *b, float v_N)
{
    const float c = cm_clamp(v_N * 100.0f, -32768.0f, 32767.0f); /* 0.01 N per count */
    const int16_t i = (int16_t)c;
    b[0] = (uint8_t)((uint16_t)i & 0xFFu);
    b[1] = (uint8_t)((uint16_t)i >> 8);
}

uint32_t cm_tick(void)
{
    /* 1. sensors */
    cm_hal_sensors_t raw;
    cm_hal_sensors_read(&raw);
    pfc_axis_meas_t meas[PFC_AXES];
    for (uint32_t a = 0u; a < PFC_AXES; a++) {
        const float pos = (float)raw.enc_count[a] * ENC_M_PER_COUNT;
        meas[a].pos_m = pos;
        meas[a].vel_mps = (pos - cm_prev_pos_m[a]) * INV_DT;
        meas[a].force_N = (float)raw.force_count[a] * FORCE_N_PER_COUNT;
        cm_prev_pos_m[a] = pos;
    }
    /* 2. DMP */
#if CM_TICK_DMP == 2
    float path_m = 0.0f;
    const float f_hat = dmp_step_xy(&cm_skill.dmp, &cm_dmp, &cm_run, NULL, 1.0f, &path_m);
#elif CM_TICK_DMP == 1
    const float path_m = 0.0f;
    const float f_hat = dmp_step(&cm_skill.dmp, &cm_dmp, &cm_run, NULL);
#else
    const float path_m = 0.0f;
    const float f_hat = cm_skill.dmp.force0_N;
#endif
    /* 3. reference */
    pfc_axis_ref_t ref[PFC_AXES];
    const float pos_d = cm_skill.surface_m + f_hat / cm_skill.stiffness_Npm;
    ref[0].pos_m = pos_d;
    ref[0].vel_mps = (pos_d - cm_prev_pos_d_m) * INV_DT;
    ref[0].acc_mps2 = 0.0f;
    ref[0].force_N = f_hat;
    cm_prev_pos_d_m = pos_d;
    const float y_d = cm_hold_y_m + path_m;
    ref[1].pos_m = y_d;
    ref[1].vel_mps = (y_d - cm_prev_y_d_m) * INV_DT;
    cm_prev_y_d_m = y_d;
    memcpy(&cm_path_bits, &path_m, sizeof(cm_path_bits));
    ref[1].acc_mps2 = 0.0f;
    ref[1].force_N = 0.0f;
    /* 4. control law */
    float cmd[PFC_AXES];
    pfc_step(&cm_pfc, &cm_pfc_state, ref, meas, cmd);
    /* 5. safety limits */
    int32_t out[PFC_AXES];
    for (uint32_t a = 0u; a < PFC_AXES; a++) {
        if (meas[a].pos_m < (float)CM_WORKSPACE_MIN_M ||
            meas[a].pos_m > (float)CM_WORKSPACE_MAX_M) {
            cm_faults |= CM_FAULT_WORKSPACE;
        }
        if (fabsf(meas[a].vel_mps) > (float)CM_SPEED_MAX_MPS) {
            cm_faults |= CM_FAULT_SPEED;
        }
        if (!isfinite(cmd[a])) {
            cm_faults |= CM_FAULT_NOT_FINITE;
        }
        float c = (cm_faults != 0u) ? 0.0f : cmd[a];
        c = cm_clamp(c, -(float)CM_FORCE_MAX_N, (float)CM_FORCE_MAX_N);
        c = cm_clamp(c, cm_last_cmd_N[a] - (float)CM_SLEW_N_PER_TICK,
                     cm_last_cmd_N[a] + (float)CM_SLEW_N_PER_TICK);
        cm_last_cmd_N[a] = c;
        out[a] = (int32_t)(c * COUNTS_PER_N);
    }
    /* 6. telemetry and actuator */
    uint8_t frame[8];
    cm_put_i16(&frame[0], f_hat);
    cm_put_i16(&frame[2], cm_last_cmd_N[0]);
    cm_put_i16(&frame[4], cm_last_cmd_N[1]);
    frame[6] = (uint8_t)cm_faults;
    frame[7] = cm_seq++;
    cm_hal_telemetry_write(frame);
    cm_hal_actuator_write(out);
    uint32_t bits;
    memcpy(&bits, &f_hat, sizeof(bits));
    return bits;
}

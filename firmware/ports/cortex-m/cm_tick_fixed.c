/* Control tick, fixed-point build (Cortex-M3, no FPU): dmpfx_step and pfcfx_step. The skill is
 * parsed in double (soft-float, once at init) and converted with range validation. */
#include "cm_hal.h"
#include "cm_tick.h"
#include "dmpfx.h"
#include "pfcfx.h"
#include "skill.h"

#define INV_DT 1000
#define ENC_TO_Q24_SHIFT (24u - CM_HAL_ENC_FRAC_BITS)
#define FORCE_TO_Q16_SHIFT (16u - CM_HAL_FORCE_FRAC_BITS)

static skill_t cm_skill;
static dmpfx_model_t cm_model;
static dmpfx_run_t cm_run;
static dmpfx_state_t cm_dmp;
static pfcfx_config_t cm_pfc;
static pfcfx_state_t cm_pfc_state;
static int32_t cm_prev_pos_q24[CM_HAL_AXES];
static int32_t cm_prev_pos_d_q24;
static int32_t cm_surface_q24;
static int64_t cm_inv_k_q32; /* 1/k, m/N, Q.32: x_d = surface + f_hat/k */
static int32_t cm_hold_y_q24;
static int32_t cm_prev_y_d_q24;
static int32_t cm_path_q24;
static int32_t cm_last_cmd_q16[CM_HAL_AXES];
static int32_t cm_force_max_q16;
static int32_t cm_slew_q16;
static int32_t cm_ws_min_q24;
static int32_t cm_ws_max_q24;
static int32_t cm_speed_max_q24;
static uint32_t cm_faults;
static uint32_t cm_rows;
static uint8_t cm_seq;

fs_status_t cm_tick_init(const uint8_t *image, uint32_t len, double goal_scale, double time_scale)
{
    fs_status_t st = skill_parse(image, len, &cm_skill);
    if (st == FS_OK) {
        st = dmpfx_from_model(&cm_skill.dmp, &cm_model);
    }
    if (st == FS_OK) {
        st = dmpfx_run_init(&cm_model, goal_scale, time_scale, &cm_run);
    }
    pfc_config_t cfg;
    pfc_default_config(&cfg);
    if (st == FS_OK) {
        st = pfcfx_from_config(&cfg, &cm_pfc);
    }
    if (st == FS_OK) {
        st = fx_from_double(cm_skill.surface_m, 24u, INT32_MAX, &cm_surface_q24);
    }
    if (st == FS_OK) {
        const double inv_k = ldexp(1.0 / cm_skill.stiffness_Npm, 32);
        st = (inv_k < ldexp(1.0, 32)) ? FS_OK : FS_ERR_FIXED_OVERFLOW;
        cm_inv_k_q32 = (int64_t)(inv_k + 0.5);
    }
    if (st == FS_OK) {
        st = fx_from_double(CM_FORCE_MAX_N, 16u, INT32_MAX, &cm_force_max_q16);
    }
    if (st == FS_OK) {
        st = fx_from_double(CM_SLEW_N_PER_TICK, 16u, INT32_MAX, &cm_slew_q16);
    }
    if (st == FS_OK) {
        st = fx_from_double(CM_WORKSPACE_MIN_M, 24u, INT32_MAX, &cm_ws_min_q24);
    }
    if (st == FS_OK) {
        st = fx_from_double(CM_WORKSPACE_MAX_M, 24u, INT32_MAX, &cm_ws_max_q24);
    }
    if (st == FS_OK) {
        st = fx_from_double(CM_SPEED_MAX_MPS, 24u, INT32_MAX, &cm_speed_max_q24);
    }
    if (st != FS_OK) {
        return st;
    }
    dmpfx_state_reset(&cm_dmp);
    pfcfx_reset(&cm_pfc_state);
    const double rows = cm_skill.dmp.duration_s * time_scale / cm_skill.dmp.dt_s;
    cm_rows = (uint32_t)(rows + 0.5);
    cm_prev_pos_q24[0] = cm_prev_pos_q24[1] = 0;
    cm_prev_pos_d_q24 = cm_surface_q24;
    cm_hold_y_q24 = 0;
    cm_prev_y_d_q24 = 0;
    cm_last_cmd_q16[0] = cm_last_cmd_q16[1] = 0;
    cm_faults = 0u;
    cm_seq = 0u;
    return FS_OK;
}

uint32_t cm_tick_path_bits(void)
{
    return (uint32_t)cm_path_q24;
}

uint32_t cm_tick_rows(void)
{
    return cm_rows;
}
double cm_tick_surface_m(void)
{
    return cm_skill.surface_m;
}
uint32_t cm_tick_faults(void)
{
    return cm_faults;
}
const char *cm_tick_numeric(void)
{
    return "fixed";
}
double cm_tick_fhat_N(uint32_t bits)
{
    return fx_to_double((int32_t)bits, 16u);
}

/* Q16.16 N -> int16 telemetry in 0.01 N (saturated). */
static void cm_put_i16(uint8_t *b, int32_t v_q16)
{
    const int32_t c = fx_clamp_sym(fx_sat32(((int64_t)v_q16 * 100) >> 16), 32767);
    b[0] = (uint8_t)((uint32_t)c & 0xFFu);
    b[1] = (uint8_t)(((uint32_t)c >> 8) & 0xFFu);
}

uint32_t cm_tick(void)
{
    /* 1. sensors */
    cm_hal_sensors_t raw;
    cm_hal_sensors_read(&raw);
    pfcfx_meas_t meas[PFC_AXES];
    for (uint32_t a = 0u; a < PFC_AXES; a++) {
        const int32_t pos = fx_mul_int_sat(raw.enc_count[a], 1 << ENC_TO_Q24_SHIFT);
        meas[a].pos_m = pos;
        meas[a].vel_mps = fx_mul_int_sat(fx_sub_sat(pos, cm_prev_pos_q24[a]), INV_DT);
        meas[a].force_N = fx_mul_int_sat(raw.force_count[a], 1 << FORCE_TO_Q16_SHIFT);
        cm_prev_pos_q24[a] = pos;
    }
    /* 2. DMP */
#if CM_TICK_DMP == 2
    int32_t path_q24 = 0;
    const int32_t f_hat = dmpfx_step_xy(&cm_model, &cm_run, &cm_dmp, NULL, &path_q24);
#elif CM_TICK_DMP == 1
    const int32_t path_q24 = 0;
    const int32_t f_hat = dmpfx_step(&cm_model, &cm_run, &cm_dmp, NULL);
#else
    const int32_t path_q24 = 0;
    const int32_t f_hat = cm_model.force0_q16;
#endif
    /* 3. reference */
    pfcfx_ref_t ref[PFC_AXES];
    const int32_t pos_d = fx_add_sat(cm_surface_q24,
                                     fx_sat32(((int64_t)f_hat * cm_inv_k_q32) >> 24));
    ref[0].pos_m = pos_d;
    ref[0].vel_mps = fx_mul_int_sat(fx_sub_sat(pos_d, cm_prev_pos_d_q24), INV_DT);
    ref[0].acc_mps2 = 0;
    ref[0].force_N = f_hat;
    cm_prev_pos_d_q24 = pos_d;
    const int32_t y_d = fx_add_sat(cm_hold_y_q24, path_q24);
    ref[1].pos_m = y_d;
    ref[1].vel_mps = fx_mul_int_sat(fx_sub_sat(y_d, cm_prev_y_d_q24), INV_DT);
    cm_prev_y_d_q24 = y_d;
    cm_path_q24 = path_q24;
    ref[1].acc_mps2 = 0;
    ref[1].force_N = 0;
    /* 4. control law */
    int32_t cmd[PFC_AXES];
    pfcfx_step(&cm_pfc, &cm_pfc_state, ref, meas, cmd);
    /* 5. safety limits */
    int32_t out[PFC_AXES];
    for (uint32_t a = 0u; a < PFC_AXES; a++) {
        if (meas[a].pos_m < cm_ws_min_q24 || meas[a].pos_m > cm_ws_max_q24) {
            cm_faults |= CM_FAULT_WORKSPACE;
        }
        if (fx_abs_sat(meas[a].vel_mps) > cm_speed_max_q24) {
            cm_faults |= CM_FAULT_SPEED;
        }
        int32_t c = (cm_faults != 0u) ? 0 : cmd[a];
        c = fx_clamp_sym(c, cm_force_max_q16);
        /* |last| <= force_max and slew < 2^31 - force_max: no overflow */
        const int32_t last = cm_last_cmd_q16[a];
        if (c > last + cm_slew_q16) {
            c = last + cm_slew_q16;
        } else if (c < last - cm_slew_q16) {
            c = last - cm_slew_q16;
        }
        cm_last_cmd_q16[a] = c;
        out[a] = c >> FORCE_TO_Q16_SHIFT;
    }
    /* 6. telemetry and actuator */
    uint8_t frame[8];
    cm_put_i16(&frame[0], f_hat);
    cm_put_i16(&frame[2], cm_last_cmd_q16[0]);
    cm_put_i16(&frame[4], cm_last_cmd_q16[1]);
    frame[6] = (uint8_t)cm_faults;
    frame[7] = cm_seq++;
    cm_hal_telemetry_write(frame);
    cm_hal_actuator_write(out);
    return (uint32_t)f_hat;
}

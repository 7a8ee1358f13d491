/* Markers and plant model of the Cortex-M images (see cm_bench.h). The plant runs outside the
 * measured region (soft-float on the M3: its cost is not the tick's). */
#include "cm_bench.h"

#include "cm_hal.h"

void cm_bench_mark_begin(void)
{
    __asm__ volatile("" ::: "memory");
}

void cm_bench_mark_end(void)
{
    __asm__ volatile("" ::: "memory");
}

#define PLANT_M_D_KG 40.0f /* the law's m_d: its command is m_d * xdd */
#define PLANT_DT_S 0.001f

static float plant_pos_m[CM_HAL_AXES];
static float plant_vel_mps[CM_HAL_AXES];
static float plant_surface_m;
static float plant_k_Npm;

void cm_plant_init(double surface_m, double stiffness_Npm)
{
    plant_surface_m = (float)surface_m;
    plant_k_Npm = (float)stiffness_Npm;
    plant_pos_m[0] = plant_surface_m;
    plant_pos_m[1] = 0.0f;
    plant_vel_mps[0] = plant_vel_mps[1] = 0.0f;
}

void cm_plant_sense(void)
{
    const float pen = plant_pos_m[0] - plant_surface_m;
    const float f = (pen > 0.0f) ? plant_k_Npm * pen : 0.0f;
    for (uint32_t a = 0u; a < CM_HAL_AXES; a++) {
        cm_hal_regs.sensors.enc_count[a] = (int32_t)(plant_pos_m[a] *
                                                     (float)(1u << CM_HAL_ENC_FRAC_BITS));
    }
    cm_hal_regs.sensors.force_count[0] = (int32_t)(f * (float)(1u << CM_HAL_FORCE_FRAC_BITS));
    cm_hal_regs.sensors.force_count[1] = 0;
}

void cm_plant_step(void)
{
    for (uint32_t a = 0u; a < CM_HAL_AXES; a++) {
        const float f = (float)cm_hal_regs.actuator_count[a] /
                        (float)(1u << CM_HAL_FORCE_FRAC_BITS);
        plant_vel_mps[a] += f / PLANT_M_D_KG * PLANT_DT_S;
        plant_pos_m[a] += plant_vel_mps[a] * PLANT_DT_S;
    }
}

/* Register-level HAL of the Cortex-M images (see cm_hal.h). */
#include "cm_hal.h"

cm_hal_regs_t cm_hal_regs;

void cm_hal_sensors_read(cm_hal_sensors_t *out)
{
    for (uint32_t a = 0u; a < CM_HAL_AXES; a++) {
        out->enc_count[a] = cm_hal_regs.sensors.enc_count[a];
        out->force_count[a] = cm_hal_regs.sensors.force_count[a];
    }
}

void cm_hal_actuator_write(const int32_t count[CM_HAL_AXES])
{
    for (uint32_t a = 0u; a < CM_HAL_AXES; a++) {
        cm_hal_regs.actuator_count[a] = count[a];
    }
}

void cm_hal_telemetry_write(const uint8_t frame[8])
{
    for (uint32_t w = 0u; w < 2u; w++) {
        const uint8_t *b = &frame[4u * w];
        cm_hal_regs.telemetry[w] = (uint32_t)b[0] | ((uint32_t)b[1] << 8) | ((uint32_t)b[2] << 16) |
                                   ((uint32_t)b[3] << 24);
    }
    cm_hal_regs.telemetry_seq = cm_hal_regs.telemetry_seq + 1u;
}

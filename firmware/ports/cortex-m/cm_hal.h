/* Minimal HAL of the Cortex-M images: the sensor and actuator registers of a servo front-end,
 * memory-mapped (here a RAM block the benchmark's plant model writes, as an ADC/encoder DMA
 * would). Raw integers with binary scales, so both numeric builds convert without division:
 *   encoder   1 count = 2^-20 m    (~0.95 um)      -> Q8.24: << 4,  float: * 2^-20
 *   force ADC 1 count = 2^-10 N    (~1 mN)         -> Q16.16: << 6, float: * 2^-10
 *   actuator  1 count = 2^-10 N.
 * firmware/hal/hal.h is the application's contract (fs_real_t units); this is the register level
 * beneath it for the benchmark, kept minimal so the tick cost is the control law's. */
#ifndef CM_HAL_H
#define CM_HAL_H

#include <stdint.h>

#define CM_HAL_AXES 2u
#define CM_HAL_ENC_FRAC_BITS 20u
#define CM_HAL_FORCE_FRAC_BITS 10u

/** Sensor registers (read by the tick). */
typedef struct {
    int32_t enc_count[CM_HAL_AXES];
    int32_t force_count[CM_HAL_AXES];
} cm_hal_sensors_t;

/** Register block of the front-end. */
typedef struct {
    volatile cm_hal_sensors_t sensors;
    volatile int32_t actuator_count[CM_HAL_AXES];
    volatile uint32_t actuator_enable;
    volatile uint32_t telemetry[2]; /* 8-byte frame, little-endian words */
    volatile uint32_t telemetry_seq;
} cm_hal_regs_t;

/** The register block (a plant model or a driver fills sensors). */
extern cm_hal_regs_t cm_hal_regs;

/** Latch the latest sensor sample. */
void cm_hal_sensors_read(cm_hal_sensors_t *out);

/** Write the actuator force (counts of 2^-10 N) of both axes. */
void cm_hal_actuator_write(const int32_t count[CM_HAL_AXES]);

/** Queue one 8-byte telemetry frame (the CAN status frame's payload). */
void cm_hal_telemetry_write(const uint8_t frame[8]);

#endif /* CM_HAL_H */

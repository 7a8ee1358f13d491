/* The full 1 kHz control tick of the Cortex-M images, one implementation per numeric build:
 * cm_tick_float.c (float32 core, M4F) and cm_tick_fixed.c (fixed point, M3). Per tick:
 *   1. sensors through the HAL (cm_hal_sensors_read), converted to units; velocity by difference
 *   2. DMP step (N kernels of the embedded skill) -> f_hat
 *   3. reference: x_d = surface + x_dmp (= f_hat/k), xd_d by difference, xdd_d = 0, f_d = f_hat;
 *      y: y_d = start + p of the skill's y DMP (stepped with the force DMP, dmp_step_xy /
 *      dmpfx_step_xy: each kernel activation once for both), yd_d by difference, ydd_d = 0;
 *      a skill without a y DMP holds the start position
 *   4. parallel force/position law, 2 DOF (pfc_step / pfcfx_step)
 *   5. safety limits at the last stage: workspace and speed (latch a fault: command 0),
 *      |f| <= F_max, slew <= CM_SLEW_N_PER_TICK
 *   6. telemetry packed into 8 bytes, actuator write through the HAL. */
#ifndef CM_TICK_H
#define CM_TICK_H

#include <stdint.h>
#include "fs_status.h"

#define CM_FORCE_MAX_N 50.0        /* default F_max (pfc_default_config) */
#define CM_SLEW_N_PER_TICK 2.0     /* force slew limit per 1 ms tick */
#define CM_WORKSPACE_MIN_M (-0.05) /* position workspace of both axes */
#define CM_WORKSPACE_MAX_M 0.25
#define CM_SPEED_MAX_MPS 1.0
#define CM_FAULT_WORKSPACE 0x01u /* latched safety faults (telemetry byte 6) */
#define CM_FAULT_SPEED 0x02u
#define CM_FAULT_NOT_FINITE 0x04u

/* What the tick steps (bench/qemu_tick.sh measures the parts by building the images with
 * -DCM_TICK_DMP=N in CMAKE_C_FLAGS): 2 both DMPs (the product: dmp_step_xy), 1 the force DMP
 * alone (dmp_step: the tick before the y DMP), 0 no DMP (f_hat = f0: the tick without its DMP
 * part, for measuring only; its f_hat comparison with the host fails by design). */
#ifndef CM_TICK_DMP
#define CM_TICK_DMP 2
#endif

/** Parse the skill image, convert it for this numeric build, reset all state. */
fs_status_t cm_tick_init(const uint8_t *image, uint32_t len, double goal_scale, double time_scale);

/** Number of ticks of one rollout: round(T*time_scale/dt). */
uint32_t cm_tick_rows(void);

/** Object surface position of the skill (m), for the plant model. */
double cm_tick_surface_m(void);

/** One control tick. Returns f_hat's raw bits (float32 bits, or Q16.16 N) for comparison with
 *  the host build. */
uint32_t cm_tick(void);

/** The y DMP's p of the last tick (m above the path's start) as raw bits (float32 bits, or
 *  Q8.24 m), for comparison with the host build; 0 without a y DMP. */
uint32_t cm_tick_path_bits(void);

/** Latched safety faults (CM_FAULT_*). */
uint32_t cm_tick_faults(void);

/** f_hat raw bits -> N (for the plant model and printing). */
double cm_tick_fhat_N(uint32_t bits);

/** Name of the numeric build ("float" or "fixed"). */
const char *cm_tick_numeric(void);

#endif /* CM_TICK_H */

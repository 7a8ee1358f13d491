/* Benchmark support shared by the Cortex-M images: the embedded skill (generated at build time
 * from a golden vector), the measured-region markers, and a plant model that feeds the HAL. */
#ifndef CM_BENCH_H
#define CM_BENCH_H

#include <stdint.h>

/** The skill image the benchmark runs (generated from FS_BENCH_SKILL, see CMakeLists.txt). */
extern const uint8_t cm_bench_skill[];
extern const uint32_t cm_bench_skill_len;

/** Markers around the measured region: never inlined, so each is a call the qemu exec trace
 *  shows by name; the counter counts the instructions strictly between them. */
void cm_bench_mark_begin(void) __attribute__((noinline));
void cm_bench_mark_end(void) __attribute__((noinline));

/** Plant: an ideal acceleration-controlled carriage (xdd = f_cmd/m_d, as the law assumes) per
 *  axis, the x axis against a spring object at the skill's surface. Writes the HAL sensors. */
void cm_plant_init(double surface_m, double stiffness_Npm);

/** Write the current plant state into the sensor registers. */
void cm_plant_sense(void);

/** Advance the plant by 1 ms with the actuator registers' force. */
void cm_plant_step(void);

/** SysTick exception handler (weak default in startup.c; the loop image defines it). */
void SysTick_Handler(void);

#endif /* CM_BENCH_H */

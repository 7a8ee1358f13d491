/* The integer build of the supervisor (fs_safety_fx) behind plain types, so a test compares it
 * with the double build in one executable (saf_fixed_side.c is compiled with SAF_FIXED). */
#ifndef SAF_FIXED_SIDE_H
#define SAF_FIXED_SIDE_H

#include <stdbool.h>
#include <stdint.h>

/** The configuration both builds get: the defaults with these changed. */
typedef struct {
    double force_max_N, slew_max_N, contact_force_max_N, spike_N, jump_m;
    uint16_t timeout_ms, stuck_ticks, slew_fault_ticks;
} side_cfg_t;

/** One tick's inputs in Q16.16 (forces) and Q8.24 (positions, velocities); INT32_MIN: not
 *  finite. */
typedef struct {
    uint32_t tick, now_ms;
    bool host_frame, clear;
    int32_t pos_q24[2], vel_q24[2], force_q16[2], req_q16[2];
} side_in_t;

/** One tick's outputs. */
typedef struct {
    int32_t cmd_q16[2];
    bool enable, stopping;
    uint16_t fault_code, clear_result;
    uint32_t cause_mask, lim_flags;
} side_out_t;

/** saf_default_config with c's values, saf_init, saf_prepare. */
void side_fx_reset(const side_cfg_t *c);

/** saf_clear_request if in->clear, then saf_step. */
void side_fx_step(const side_in_t *in, side_out_t *out);

#endif /* SAF_FIXED_SIDE_H */

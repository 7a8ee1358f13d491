/* The control law's tick (pfc.h), written once over the numeric layer (fs_num.h) and compiled
 * three ways: by pfc.c into fs_core (double) and fs_core_f32 (float32), and by
 * firmware/fixed/pfcfx.c into fs_fixed. Per axis:
 *   unsat = m_d*xdd_d + k_d*(xd_d - xd) + k_p*(x_d - x) + k_f*(f_d - f) + k_i*I_f
 *   f_cmd = clamp(unsat, force_max); I_f += dt*(f_d - f) unless the output is saturated in the
 *   direction the error grows it (conditional integration), clamped to integral_max; axes with
 *   k_i = 0 keep I_f at 0; an unsat that is NaN (real layer only) commands 0 and holds I_f.
 * The including file includes its public header, fs_num.h, then defines PFC_TICK_CONFIG,
 * PFC_TICK_STATE, PFC_TICK_REF and PFC_TICK_MEAS (its types, with the field names of pfc.h in
 * the layer's types) and includes this file once. */
#ifndef PFC_TICK_H
#define PFC_TICK_H

#include <stdint.h>

#if !defined(PFC_TICK_CONFIG) || !defined(PFC_TICK_STATE) || !defined(PFC_TICK_REF) || \
    !defined(PFC_TICK_MEAS)
#error "define PFC_TICK_CONFIG, PFC_TICK_STATE, PFC_TICK_REF, PFC_TICK_MEAS before pfc_tick.h"
#endif

/** One control tick, both axes: saturated force command per axis into force_cmd[PFC_AXES]. */
static inline void pfc_tick_step(const PFC_TICK_CONFIG *cfg, PFC_TICK_STATE *st,
                                 const PFC_TICK_REF ref[PFC_AXES],
                                 const PFC_TICK_MEAS meas[PFC_AXES], fs_force_t force_cmd[PFC_AXES])
{
    for (uint32_t a = 0u; a < PFC_AXES; a++) {
        const fs_gain_t m_d = cfg->gains[a].m_d_kg;
        const fs_gain_t k_d = cfg->gains[a].k_d_Nspm;
        const fs_gain_t k_p = cfg->gains[a].k_p_Npm;
        const fs_gain_t k_f = cfg->gains[a].k_f;
        const fs_gain_t k_i = cfg->gains[a].k_i_per_s;
        const fs_force_t force_max = cfg->limits[a].force_max_N;
        const fs_force_t force_err = fs_num_sub(ref[a].force_N, meas[a].force_N);
        const fs_val_t i_f = st->force_err_integral_Ns[a];
        /* Forward Euler like the DMP: the output uses the integral up to the previous tick. */
        const fs_wide_t sum = fs_num_gain_val(m_d, ref[a].acc_mps2) +
                              fs_num_gain_val(k_d, fs_num_sub(ref[a].vel_mps, meas[a].vel_mps)) +
                              fs_num_gain_val(k_p, fs_num_sub(ref[a].pos_m, meas[a].pos_m)) +
                              fs_num_gain_force(k_f, force_err) + fs_num_gain_val(k_i, i_f);
        if (fs_num_is_nan(sum)) {
            /* A NaN input: command nothing and keep the integral finite. Detecting the bad
             * sensor and faulting is the safety layer's job (firmware/safety). */
            force_cmd[a] = FS_NUM_ZERO;
            continue;
        }
        const fs_force_t unsat = fs_num_wide_force(sum);
        force_cmd[a] = fs_num_clamp(unsat, force_max);

        /* Conditional integration: hold the integral while the output is saturated and this
         * error would drive it further into saturation (k_i >= 0, so the sign of the error is
         * the sign of the integral's contribution). */
        const int windup = (unsat > force_max && force_err > FS_NUM_ZERO) ||
                           (unsat < -force_max && force_err < FS_NUM_ZERO);
        if (k_i > FS_NUM_ZERO && !windup) {
            st->force_err_integral_Ns[a] = fs_num_clamp(
                fs_num_add(i_f, fs_num_dt_force(cfg->dt_s, force_err)),
                cfg->limits[a].integral_max_Ns);
        }
    }
}

#endif /* PFC_TICK_H */

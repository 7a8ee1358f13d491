/* The fixed-point executor's half of test_exec_fixed (compiled against fs_app_exec_fx). */
#include "exec_fixed_side.h"

#include "fs_exec.h"

static skill_t side_skill;
static dmpfx_model_t side_model; /* the skill in fixed point, converted as the device does */
static exec_state_t side_state;

/* the application's start of a one-step run (app_start_sequence): x gains from the skill, y
 * the default law's with the skill's m_d, limits and dt of the defaults */
static void side_config(const exec_side_run_t *run, exec_config_t *cfg)
{
    exec_config_default(cfg);
    cfg->pfc.gains[0] = side_skill.gains;
    cfg->pfc.gains[1].m_d_kg = side_skill.gains.m_d_kg;
    cfg->use_model = run->use_model;
    cfg->phase_stop_gain_per_N2 = (fs_real_t)run->phase_stop_gain_per_N2;
}

int exec_side_fixed_replay(const exec_side_run_t *run, double y_hold_m,
                           const exec_side_meas_t *meas, exec_side_out_t *out, size_t n)
{
    fs_status_t st = skill_parse(run->image, run->image_len, &side_skill);
    if (st != FS_OK) {
        return (int)st;
    }
    if (run->contact_threshold_N > 0.0) {
        side_skill.contact_threshold_N = (fs_real_t)run->contact_threshold_N;
        side_skill.contact_tau_s = (fs_real_t)run->contact_tau_s;
    }
    st = dmpfx_from_model_bound(&side_skill.dmp, &side_model);
    if (st != FS_OK) {
        return (int)st;
    }
    exec_config_t cfg;
    side_config(run, &cfg);
    const exec_step_t step = {&side_skill,
                              (fs_real_t)run->goal_scale,
                              (fs_real_t)run->time_scale,
                              FS_R(0.0),
                              side_skill.end_policy,
                              (fs_real_t)run->path_scale,
                              FS_R(1.0),
                              0u,
                              &side_model};
    st = exec_start(&cfg, &side_state, &step, 1u, (fs_real_t)y_hold_m);
    if (st != FS_OK) {
        return (int)st;
    }
    for (size_t i = 0; i < n; i++) {
        exec_meas_t m;
        for (unsigned a = 0; a < PFC_AXES; a++) {
            m.pos_m[a] = (fs_real_t)meas[i].pos_m[a];
            m.vel_mps[a] = (fs_real_t)meas[i].vel_mps[a];
        }
        m.force_contact_N = (fs_real_t)meas[i].force_contact_N;
        exec_out_t o;
        out[i].status = (int)exec_tick(&cfg, &side_state, &m, &o);
        out[i].force_cmd_N[0] = (double)o.force_cmd_N[0];
        out[i].force_cmd_N[1] = (double)o.force_cmd_N[1];
        out[i].force_hat_N = (double)o.force_hat_N;
        out[i].pos_ref_m = (double)o.pos_ref_m;
        out[i].y_ref_m = (double)o.y_ref_m;
    }
    return 0;
}

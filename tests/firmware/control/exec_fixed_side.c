/* The fixed-point executor's half of test_exec_fixed (compiled against fs_app_exec_fx). */
#include "exec_fixed_side.h"

#include <math.h>

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

/* ---- exec_tick_q over a sequence ---- */

static skill_t seq_skill[EXEC_SIDE_MAX_STEPS];
static dmpfx_model_t seq_model[EXEC_SIDE_MAX_STEPS];

/* v in Q format (rounded, saturated), NaN/inf as INT32_MIN (exec_meas_q_t's not finite). */
static int32_t side_q(double v, unsigned frac)
{
    if (!isfinite(v)) {
        return INT32_MIN;
    }
    int32_t q = 0;
    if (fx_from_double(v, frac, INT32_MAX, &q) != FS_OK) {
        return (v > 0.0) ? INT32_MAX : -INT32_MAX;
    }
    return q;
}

/* A mantissa scaled by 1 + rel (the mutations). */
static uint32_t side_bump(uint32_t v, double rel)
{
    return (uint32_t)((double)v * (1.0 + rel));
}

static void side_mutate(exec_state_t *st, int mutation)
{
    exec_num_t *q = &st->n;
    switch (mutation) {
    case EXEC_SIDE_MUT_BLEND: q->c.blend_inc_q32 = side_bump(q->c.blend_inc_q32, 0.01); break;
    case EXEC_SIDE_MUT_RELEASE: q->c.release_inc_q32 = side_bump(q->c.release_inc_q32, 0.01); break;
    case EXEC_SIDE_MUT_INV_K: q->step[0].inv_k.mant = side_bump(q->step[0].inv_k.mant, 0.01); break;
    case EXEC_SIDE_MUT_INV_M: q->c.inv_m.mant = side_bump(q->c.inv_m.mant, 0.01); break;
    case EXEC_SIDE_MUT_STOP: q->c.stop_gain.mant = side_bump(q->c.stop_gain.mant, 0.1); break;
    case EXEC_SIDE_MUT_CONTACT:
        q->step[0].contact_gain_q31 = side_bump(q->step[0].contact_gain_q31, 0.1);
        break;
    case EXEC_SIDE_MUT_CARRY: q->step[1].start_force_q32 += (int64_t)(0.01 * 4294967296.0); break;
    default: break;
    }
}

/* Parse and convert the sequence's skills, configure and start (as side_config, the first
 * step's gains). */
static int side_seq_start(const exec_side_seq_t *seq, exec_config_t *cfg)
{
    exec_step_t steps[EXEC_SIDE_MAX_STEPS];
    for (uint8_t i = 0u; i < seq->n_steps; i++) {
        const exec_side_step_t *s = &seq->step[i];
        fs_status_t st = skill_parse(s->image, s->image_len, &seq_skill[i]);
        if (st != FS_OK) {
            return (int)st;
        }
        if (s->contact_threshold_N > 0.0) {
            seq_skill[i].contact_threshold_N = (fs_real_t)s->contact_threshold_N;
            seq_skill[i].contact_tau_s = (fs_real_t)s->contact_tau_s;
        }
        st = dmpfx_from_model_bound(&seq_skill[i].dmp, &seq_model[i]);
        if (st != FS_OK) {
            return (int)st;
        }
        steps[i] = (exec_step_t){&seq_skill[i],
                                 (fs_real_t)s->goal_scale,
                                 (fs_real_t)s->time_scale,
                                 (fs_real_t)s->duration_s,
                                 (skill_end_t)s->end_policy,
                                 (fs_real_t)s->path_scale,
                                 (fs_real_t)s->amplitude_scale,
                                 s->until_stopped,
                                 &seq_model[i]};
    }
    exec_config_default(cfg);
    cfg->pfc.gains[0] = seq_skill[0].gains;
    cfg->pfc.gains[1].m_d_kg = seq_skill[0].gains.m_d_kg;
    cfg->use_model = seq->use_model;
    cfg->surface_from_contact = seq->surface_from_contact;
    cfg->object.surface_m = (fs_real_t)seq->surface_m;
    cfg->phase_stop_gain_per_N2 = (fs_real_t)seq->phase_stop_gain_per_N2;
    return (int)exec_start(cfg, &side_state, steps, seq->n_steps, (fs_real_t)seq->y_hold_m);
}

/* exec_tick on the float32 measurements, its outputs back in Q formats (the wrapper's path). */
static int side_wrapper_tick(const exec_config_t *cfg, const exec_side_meas_t *me, exec_out_q_t *o)
{
    exec_meas_t m;
    for (unsigned a = 0; a < PFC_AXES; a++) {
        m.pos_m[a] = (fs_real_t)me->pos_m[a];
        m.vel_mps[a] = (fs_real_t)me->vel_mps[a];
    }
    m.force_contact_N = (fs_real_t)me->force_contact_N;
    exec_out_t out;
    const int rc = (int)exec_tick(cfg, &side_state, &m, &out);
    o->force_cmd_q16[0] = fx_from_float(out.force_cmd_N[0], 16u);
    o->force_cmd_q16[1] = fx_from_float(out.force_cmd_N[1], 16u);
    o->force_hat_q16 = fx_from_float(out.force_hat_N, 16u);
    o->pos_ref_q24 = fx_from_float(out.pos_ref_m, 24u);
    o->y_ref_q24 = fx_from_float(out.y_ref_m, 24u);
    o->step = out.step;
    o->done = out.done;
    return rc;
}

/* An integer tick's outputs as doubles. */
static void side_outputs(exec_side_out_t *out, const exec_out_q_t *o)
{
    out->force_cmd_N[0] = fx_to_double(o->force_cmd_q16[0], 16u);
    out->force_cmd_N[1] = fx_to_double(o->force_cmd_q16[1], 16u);
    out->force_hat_N = fx_to_double(o->force_hat_q16, 16u);
    out->pos_ref_m = fx_to_double(o->pos_ref_q24, 24u);
    out->y_ref_m = fx_to_double(o->y_ref_q24, 24u);
    out->step = o->step;
    out->done = o->done;
}

int exec_side_q_replay(const exec_side_seq_t *seq, const exec_side_meas_t *meas,
                       exec_side_out_t *out, size_t n)
{
    exec_config_t cfg;
    const int rc = side_seq_start(seq, &cfg);
    if (rc != 0) {
        return rc;
    }
    side_mutate(&side_state, seq->mutation);
    for (size_t i = 0; i < n; i++) {
        exec_meas_q_t m;
        for (unsigned a = 0; a < PFC_AXES; a++) {
            m.pos_q24[a] = side_q(meas[i].pos_m[a], 24u);
            m.vel_q24[a] = side_q(meas[i].vel_mps[a], 24u);
        }
        m.force_contact_q16 = side_q(meas[i].force_contact_N, 16u);
        if (seq->saturate_at > 0u && i == seq->saturate_at) { /* beyond the Q8.24 headroom */
            side_state.dmp.y_acc = -(int64_t)FX_ACC_HI_MAX * ((int64_t)1 << 32);
            side_state.dmp.z_acc = (int64_t)FX_ACC_HI_MAX * ((int64_t)1 << 32);
        }
        exec_out_q_t o;
        if (seq->via_wrapper != 0u) {
            out[i].status = side_wrapper_tick(&cfg, &meas[i], &o);
        } else {
            out[i].status = (int)exec_tick_q(&cfg, &side_state, &m, &o);
        }
        side_outputs(&out[i], &o);
        if (seq->prepare != 0u) {
            exec_prepare_next(&side_state);
        }
    }
    return 0;
}

uint32_t exec_side_q_hold_ms(void)
{
    return exec_contact_hold_ms(&side_state);
}

void exec_side_band(uint32_t out[5])
{
    out[0] = side_state.band_checked_ticks;
    out[1] = side_state.band_out_ticks;
    out[2] = side_state.band_longest_ticks;
    out[3] = side_state.band_first_tick;
    out[4] = exec_band_max_milli(&side_state);
}

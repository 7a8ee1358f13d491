/* The fixed-point layer's own parts of the executor (fs_control_exec_fx only): the run's
 * preparation (every constant of the integer tick derived at the run's start, in exec_start_run's
 * slices: software double on the M3, so the tick and a switch between steps are integer only),
 * exec_tick as the float32 boundary over the integer tick, and the integer velocity estimator.
 * Units: exec_num_fixed.h. */
#include <math.h>

#include "fs_exec.h"

/* Parts of the start a step (exec_prepare_step) and of the configuration (exec_prepare_cfg_q). */
#define EXEC_STEP_PARTS 7u
#define EXEC_CFG_PARTS 6u

/* round(v * 2^frac) within +-FX_S61_MAX; FS_ERR_FIXED_CONFIG if v is not finite or beyond. */
static fs_status_t exec_to_q(double v, int frac, int64_t *out)
{
    const double x = floor(ldexp(v, frac) + 0.5);
    if (!(x <= (double)FX_S61_MAX && x >= -(double)FX_S61_MAX)) {
        *out = 0;
        return FS_ERR_FIXED_CONFIG;
    }
    *out = (int64_t)x;
    return FS_OK;
}

/* ceil(v * 2^32) for 0 <= v < 1 (a per-tick increment of a ramp that ends at 2^32). */
static uint32_t exec_inc_q32(double v)
{
    const double x = ceil(ldexp(v, 32));
    return (x >= 4294967295.0) ? UINT32_MAX : ((x > 0.0) ? (uint32_t)x : 0u);
}

/* A constant factor between formats; its status folded into *rc (the first failure kept). */
static fx_scale_t exec_scale(double v, int32_t in_frac, int32_t out_frac, fs_status_t *rc)
{
    fx_scale_t k;
    const fs_status_t r = fx_scale_from_double(v, in_frac, out_frac, &k);
    if (r != FS_OK && *rc == FS_OK) {
        *rc = FS_ERR_FIXED_CONFIG;
    }
    return k;
}

/* The integer constants of step i (its run derived), first half: forces, path base, 1/k. */
static fs_status_t exec_prepare_step_q(exec_state_t *st, uint8_t i)
{
    const exec_step_t *s = &st->steps[i];
    const dmpfx_model_t *m = s->model_fx;
    const dmpfx_run_t *run = &st->n.run[i];
    exec_step_q_t *q = &st->n.step[i];
    fs_status_t rc = exec_to_q((double)s->skill->dmp.force0_N, 32, &q->force0_q32);
    if (rc == FS_OK) {
        rc = exec_to_q((double)exec_step_start_force(s), 32, &q->start_force_q32);
    }
    if (rc == FS_OK) {
        rc = exec_to_q((double)s->skill->contact_threshold_N, 32, &q->contact_threshold_q32);
    }
    q->path0_q55 = 0;
    if (m->periodic != 0u) { /* + 2^s*g_e: Q8.24 * Q20.12 = N Q.36 */
        q->force0_q32 += fx_rshift_round((int64_t)run->goal_q24 * m->out_scale_q12, 4u);
        q->path0_q55 = (m->has_y != 0u) ? (int64_t)run->goal_y_q24 * EXEC_Q31_ONE : 0;
    }
    q->y_shift = (uint8_t)(23 - m->value_shift); /* s in [-12, 18]: 5..35 */
    q->inv_k = exec_scale(1.0 / (double)s->skill->stiffness_Npm, 32, 48, &rc);
    return rc;
}

/* The integer constants of step i, second half: length, ramp, contact wait, the band. */
static fs_status_t exec_prepare_step_band_q(exec_state_t *st, uint8_t i, fs_real_t dt_s)
{
    const exec_step_t *s = &st->steps[i];
    exec_step_q_t *q = &st->n.step[i];
    const double dt = (double)dt_s;
    q->ticks = exec_step_ticks(s, dt_s);
    q->ramp_inc_q32 = exec_inc_q32((double)dt_s /
                                   ((double)s->skill->dmp.duration_s * (double)s->time_scale));
    q->contact_wait = (s->skill->contact_threshold_N > FS_R(0.0)) ? 1u : 0u;
    const double gain = dt / ((double)s->skill->contact_tau_s + dt);
    q->contact_gain_q31 = (gain >= 0.0 && gain <= 1.0) ? (uint32_t)floor(ldexp(gain, 31) + 0.5)
                                                       : (uint32_t)EXEC_Q31_ONE;
    /* the band scaled as f_hat is (skill_band_at): c0 + k*b */
    const int periodic = (s->skill->dmp.periodic != 0u);
    const double gs = (double)s->goal_scale;
    const double k = periodic ? (double)s->amplitude_scale : gs;
    const double c0 = periodic ? (gs - k) * (double)s->skill->dmp.goal_N
                               : (1.0 - gs) * (double)s->skill->dmp.force0_N;
    fs_status_t rc = exec_to_q(c0, 32, &q->band_c0_q32);
    int64_t k_q16 = 0;
    if (rc == FS_OK) {
        rc = exec_to_q(k, 16, &k_q16);
    }
    q->band_k_q16 = (k_q16 <= INT32_MAX) ? (int32_t)k_q16 : INT32_MAX;
    return rc;
}

/* Part part (0..EXEC_CFG_PARTS - 1) of the run's integer constants (the last parts of
 * exec_start_run, each a few software-double conversions): the tick's time constants, the object
 * model's gains, its reciprocals, then the phase stop's and the starting state. */
static fs_status_t exec_prepare_cfg_q(const exec_config_t *cfg, exec_state_t *st, uint8_t part)
{
    exec_cfg_q_t *c = &st->n.c;
    const double dt = (double)cfg->pfc.dt_s;
    fs_status_t rc = FS_OK;
    if (part == 0u) {
        const double inv_dt = 1.0 / dt;
        c->inv_dt_x = exec_scale(inv_dt, 48, 48, &rc);
        c->inv_dt_y = exec_scale(inv_dt, 55, 48, &rc);
        c->inv_dt_yd = exec_scale(inv_dt, 48, 40, &rc);
        return rc;
    }
    if (part == 1u) {
        c->dt = exec_scale(dt, 48, 48, &rc);
        c->hold_ms = exec_scale(dt * 1000.0, 31, 0, &rc);
        c->blend_inc_q32 = exec_inc_q32(dt / EXEC_BLEND_S);
        c->release_inc_q32 = exec_inc_q32(dt / SKILL_RELEASE_TIME_S);
        return rc;
    }
    const exec_object_t *o = &cfg->object;
    const int model = (cfg->use_model != 0u);
    if (part == 2u) {
        c->d_v = exec_scale(model ? (double)o->d_v_Nspm : 0.0, 48, 32, &rc);
        c->k1 = exec_scale(model ? (double)o->k1_Npm : 0.0, 48, 32, &rc);
        c->k2 = exec_scale(model ? (double)o->k2_Npm : 0.0, 48, 32, &rc);
        return rc;
    }
    if (part == 3u) { /* the model's three divisions, one ... */
        c->inv_m = exec_scale(model ? 1.0 / (double)o->m_v_kg : 0.0, 32, 48, &rc);
        return rc;
    }
    if (part == 4u) { /* ... and two */
        c->inv_k1 = exec_scale(model ? 1.0 / (double)o->k1_Npm : 0.0, 32, 48, &rc);
        c->inv_k2 = exec_scale(model ? 1.0 / (double)o->k2_Npm : 0.0, 32, 48, &rc);
        return rc;
    }
    c->phase_stop = (cfg->phase_stop_gain_per_N2 > FS_R(0.0)) ? 1u : 0u;
    c->use_model = (uint8_t)model;
    st->n.pre_ok = 0u; /* no model forces of another run's constants (exec_num_model_prepare) */
    c->stop_gain = exec_scale((double)cfg->phase_stop_gain_per_N2, 32, 24, &rc);
    const double layer = model ? (double)o->layer_depth_m : 0.0;
    fs_status_t r2 = exec_to_q(layer, 48, &c->layer_q48);
    if (r2 == FS_OK) {
        r2 = exec_to_q(model ? (double)o->k1_Npm * layer : 0.0, 32, &c->f_layer_q32);
    }
    if (r2 == FS_OK) {
        r2 = exec_to_q((double)o->surface_m, 48, &st->surface);
    }
    if (r2 == FS_OK) {
        r2 = exec_to_q((double)st->y_start_m, 55, &st->y_hold);
    }
    st->ref_prev_pos = st->surface;
    st->y_ref = st->y_hold;
    return (rc != FS_OK) ? rc : r2;
}

/* Part part (0..6) of step i's per-run constants and starting state from its fixed-point model
 * (exec_start_run: a part a call, each a bounded piece of software double on the M3): the force
 * DMP's rates and goal, the periodic DMP's, the y DMP's, the starting state, then the integer
 * tick's in two (the periodic, path and state parts in one call put the M3's worst tick at
 * 5,373). */
static fs_status_t exec_prepare_step(const exec_config_t *cfg, exec_state_t *st, uint8_t i,
                                     uint8_t part)
{
    const exec_step_t *s = &st->steps[i];
    const dmpfx_model_t *m = s->model_fx;
    dmpfx_run_t *run = &st->n.run[i];
    switch (part) {
    case 0u: return dmpfx_run_rates(m, (double)s->goal_scale, (double)s->time_scale, run);
    case 1u: return dmpfx_run_goal(m, (double)s->goal_scale, (double)s->time_scale, run);
    case 2u: return dmpfx_run_periodic(m, (double)s->amplitude_scale, run);
    case 3u: return dmpfx_run_path(m, (double)s->path_scale, run);
    case 5u: return exec_prepare_step_q(st, i);
    case 6u: return exec_prepare_step_band_q(st, i, cfg->pfc.dt_s);
    default: break;
    }
    if (m->periodic != 0u) { /* the starting state, from the run's constants */
        dmpfx_periodic_reset(m, run, &st->n.dmp_start[i]);
    } else {
        dmpfx_state_reset(&st->n.dmp_start[i]);
    }
    return FS_OK;
}

uint32_t exec_prep_parts(uint8_t n_steps)
{
    return EXEC_STEP_PARTS * n_steps + EXEC_CFG_PARTS;
}

fs_status_t exec_prep_run(const exec_config_t *cfg, exec_state_t *st, uint32_t part)
{
    const uint32_t steps = EXEC_STEP_PARTS * st->n_steps;
    return (part < steps) ? exec_prepare_step(cfg, st, (uint8_t)(part / EXEC_STEP_PARTS),
                                              (uint8_t)(part % EXEC_STEP_PARTS))
                          : exec_prepare_cfg_q(cfg, st, (uint8_t)(part - steps));
}

/* A float32 measurement in Q format, INT32_MIN if not finite. */
static int32_t exec_meas_to_q(fs_real_t v, unsigned frac_bits)
{
    return fs_isfinite(v) ? fx_from_float(v, frac_bits) : INT32_MIN;
}

fs_status_t exec_tick(const exec_config_t *cfg, exec_state_t *st, const exec_meas_t *meas,
                      exec_out_t *out)
{
    exec_meas_q_t mq;
    for (uint32_t a = 0u; a < PFC_AXES; a++) {
        mq.pos_q24[a] = exec_meas_to_q(meas->pos_m[a], 24u);
        mq.vel_q24[a] = exec_meas_to_q(meas->vel_mps[a], 24u);
    }
    mq.force_contact_q16 = exec_meas_to_q(meas->force_contact_N, 16u);
    exec_out_q_t oq;
    const fs_status_t rc = exec_tick_q(cfg, st, &mq, &oq);
    out->force_cmd_N[0] = fx_to_float(oq.force_cmd_q16[0], 16u);
    out->force_cmd_N[1] = fx_to_float(oq.force_cmd_q16[1], 16u);
    out->force_hat_N = fx_to_float(oq.force_hat_q16, 16u);
    out->pos_ref_m = fx_to_float(oq.pos_ref_q24, 24u);
    out->y_ref_m = fx_to_float(oq.y_ref_q24, 24u);
    out->step = oq.step;
    out->done = oq.done;
    return rc;
}

void exec_num_vel_init(exec_vel_t *v, fs_real_t dt_s)
{
    v->n.prev_q24 = 0;
    v->n.vel_q24 = 0;
    v->n.not_finite = 0u;
    const fs_real_t a = (v->alpha > FS_R(0.0) && v->alpha < FS_R(1.0)) ? v->alpha : FS_R(1.0);
    v->n.alpha_q30 = fx_from_float(a, 30u);
    v->n.inv_dt_q16 = (dt_s > FS_R(0.0)) ? fx_from_float(FS_R(1.0) / dt_s, 16u) : 0;
}

static int32_t sat_q(int64_t x)
{
    return (x > INT32_MAX) ? INT32_MAX : ((x <= INT32_MIN) ? INT32_MIN + 1 : (int32_t)x);
}

int32_t exec_vel_update_q(exec_vel_t *v, int32_t pos_q24)
{
    exec_vel_n_t *n = &v->n;
    if (pos_q24 == INT32_MIN || n->not_finite != 0u) {
        n->not_finite = 1u;
        return INT32_MIN;
    }
    if (v->primed == 0u) {
        n->prev_q24 = pos_q24;
        v->primed = 1u;
        return n->vel_q24;
    }
    /* (pos - prev)/dt: a Q8.24 difference times 1/dt in Q16.16, rounded half up */
    const int64_t raw = sat_q((((int64_t)pos_q24 - n->prev_q24) * n->inv_dt_q16 + 0x8000) >> 16);
    n->prev_q24 = pos_q24;
    const int64_t e = raw - n->vel_q24; /* within +-2^32: times alpha (<= 2^30) fits int64 */
    n->vel_q24 = sat_q(n->vel_q24 + ((e * n->alpha_q30 + 0x20000000) >> 30));
    return n->vel_q24;
}

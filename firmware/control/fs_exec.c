/* Skill execution: see fs_exec.h for the algorithm and the continuity/end-policy decisions. */
#include "fs_exec.h"

#define EXEC_PI FS_R(3.14159265358979323846)
/* Coulomb compensation uses v/(|v| + this): smooth through zero so encoder noise at rest does
 * not chatter the motor between +-coulomb_N. */
#define EXEC_COULOMB_SMOOTH_MPS FS_R(1e-3)

void exec_config_default(exec_config_t *cfg)
{
    pfc_default_config(&cfg->pfc);
    cfg->use_model = 0u;
    cfg->object.m_v_kg = FS_R(10.0);
    cfg->object.d_v_Nspm = FS_R(50.0);
    cfg->object.k1_Npm = FS_R(100.0);
    cfg->object.k2_Npm = FS_R(100.0);
    cfg->object.layer_depth_m = FS_R(0.019);
    cfg->object.surface_m = FS_R(0.0);
    cfg->phase_stop_gain_per_N2 = FS_R(0.0);
    cfg->surface_from_contact = 0u;
}

/* The most ticks of a step (46 days at 1 kHz): a periodic step run until stopped. */
#define EXEC_TICKS_MAX 4000000000u

static uint32_t exec_ticks(fs_real_t t_s, fs_real_t dt_s)
{
    fs_real_t n = t_s / dt_s + FS_R(0.5);
    if (!(n > FS_R(0.0))) {
        return 0u;
    }
    if (n > FS_R(4.0e9)) {
        return EXEC_TICKS_MAX;
    }
    return (uint32_t)n;
}

/* The step's first force: f0, or a periodic step's f0 + goal_scale*g + amplitude_scale*e0. */
static fs_real_t exec_step_start_force(const exec_step_t *s)
{
    const dmp_model_t *m = &s->skill->dmp;
    if (m->periodic == 0u) {
        return m->force0_N;
    }
    return m->force0_N + s->goal_scale * m->goal_N + s->amplitude_scale * m->cycle_e0_N;
}

static fs_real_t exec_step_duration(const exec_step_t *s)
{
    if (s->duration_s > FS_R(0.0)) {
        return s->duration_s;
    }
    return s->skill->dmp.duration_s * s->time_scale;
}

/* The running step's DMP from its starting state and its length in ticks at dt_s (the
 * fixed-point build selects the state exec_start derived). */
static fs_status_t exec_begin_step(exec_state_t *st, fs_real_t dt_s)
{
    const exec_step_t *s = &st->steps[st->step];
    const uint8_t periodic = s->skill->dmp.periodic;
    st->step_ticks = (periodic != 0u && s->until_stopped != 0u)
                         ? EXEC_TICKS_MAX
                         : exec_ticks(exec_step_duration(s), dt_s);
    st->t_step_s = FS_R(0.0);
    st->step_tick = 0u;
    st->force_dmp_N = exec_step_start_force(s);
#ifdef FS_EXEC_FIXED
    st->dmp = st->dmp_start[st->step]; /* derived by exec_start */
    st->dmp_saturated = 0u;
    return FS_OK;
#else
    if (periodic != 0u) {
        dmp_periodic_reset_xy(&s->skill->dmp, &st->dmp, s->amplitude_scale, s->path_scale);
    } else {
        dmp_state_reset(&st->dmp);
    }
    st->run.goal_scale = s->goal_scale;
    st->run.time_scale = s->time_scale;
    return FS_OK;
#endif
}

#ifdef FS_EXEC_FIXED
/* Part part (0, 1) of step i's per-run constants and starting state from its fixed-point model
 * (exec_start_run: a part a call, each a bounded piece of software double on the M3): the force
 * DMP's, then the periodic and y DMPs' and the starting state. */
static fs_status_t exec_prepare_step(exec_state_t *st, uint8_t i, uint8_t part)
{
    const exec_step_t *s = &st->steps[i];
    const dmpfx_model_t *m = s->model_fx;
    dmpfx_run_t *run = &st->run[i];
    if (part == 0u) {
        return dmpfx_run_force(m, (double)s->goal_scale, (double)s->time_scale, run);
    }
    fs_status_t rc = dmpfx_run_periodic(m, (double)s->amplitude_scale, run);
    if (rc == FS_OK) {
        rc = dmpfx_run_path(m, (double)s->path_scale, run);
    }
    if (m->periodic != 0u) {
        dmpfx_periodic_reset(m, run, &st->dmp_start[i]);
    } else {
        dmpfx_state_reset(&st->dmp_start[i]);
    }
    return rc;
}
#endif

/* One DMP step of the running step s (coupling cp may be NULL): returns f_hat, p into path_m. */
static fs_real_t exec_dmp_step(exec_state_t *st, const exec_step_t *s, const dmp_coupling_t *cp)
{
#ifdef FS_EXEC_FIXED
    /* the tick's slow-down as the rate 1/(1 + slowdown) (NaN or <= 0: 1; +inf: 0) */
    dmpfx_coupling_t c = {0, FX_Q31_ONE_U};
    if (cp != 0 && cp->phase_slowdown > FS_R(0.0)) {
        c.rate_q31 = (uint32_t)fx_from_float(FS_R(1.0) / (FS_R(1.0) + cp->phase_slowdown), 31u);
    }
    const uint32_t ev = st->dmp.sat_events;
    const dmpfx_model_t *m = s->model_fx;
    const dmpfx_run_t *run = &st->run[st->step];
    if (m->periodic != 0u) {
        (void)dmpfx_periodic_step_xy(m, run, &st->dmp, (cp != 0) ? &c : 0, 0);
        st->dmp_saturated = (st->dmp.sat_events != ev) ? 1u : 0u;
        /* p = s_p*g_y + q, q from its accumulator (as the discrete path's) */
        st->path_m = (m->has_y != 0u) ? fx_to_float(run->goal_y_q24, 24u) +
                                            fx_acc_to_float(st->dmp.path_acc, -55)
                                      : FS_R(0.0);
        /* f0 + 2^s*(g_e + e): the goal in Q8.24 units, e from its accumulator */
        return s->skill->dmp.force0_N +
               fx_to_float(run->goal_q24, 24u) * fx_to_float(m->out_scale_q12, 12u) +
               fx_acc_to_float(st->dmp.y_acc, m->value_shift - 55);
    }
    (void)dmpfx_step_xy(m, run, &st->dmp, (cp != 0) ? &c : 0, 0);
    st->dmp_saturated = (st->dmp.sat_events != ev) ? 1u : 0u;
    /* y and p from their accumulators (value * 2^31 of Q8.24, y in units of 2^s N), not from
     * the Q8.24 views: the references' velocities and accelerations are their differences, and
     * a view's LSB (6e-8 m) differenced twice at 1 kHz would be 0.06 m/s^2 */
    st->path_m = fx_acc_to_float(st->dmp.path_acc, -55);
    return s->skill->dmp.force0_N + fx_acc_to_float(st->dmp.y_acc, m->value_shift - 55);
#else
    if (s->skill->dmp.periodic != 0u) {
        return dmp_periodic_step_xy(&s->skill->dmp, &st->dmp, &st->run, s->amplitude_scale, cp,
                                    s->path_scale, &st->path_m);
    }
    return dmp_step_xy(&s->skill->dmp, &st->dmp, &st->run, cp, s->path_scale, &st->path_m);
#endif
}

/* The control law of one tick (the fixed-point build: references and measurements converted in,
 * commands out). */
static void exec_law_step(const exec_config_t *cfg, exec_state_t *st,
                          const pfc_axis_ref_t ref[PFC_AXES], const pfc_axis_meas_t m[PFC_AXES],
                          fs_real_t force_cmd_N[PFC_AXES])
{
#ifdef FS_EXEC_FIXED
    (void)cfg;
    pfcfx_ref_t rq[PFC_AXES];
    pfcfx_meas_t mq[PFC_AXES];
    int32_t cmd_q16[PFC_AXES];
    for (uint32_t a = 0u; a < PFC_AXES; a++) {
        rq[a].pos_m = fx_from_float(ref[a].pos_m, 24u);
        rq[a].vel_mps = fx_from_float(ref[a].vel_mps, 24u);
        rq[a].acc_mps2 = fx_from_float(ref[a].acc_mps2, 24u);
        rq[a].force_N = fx_from_float(ref[a].force_N, 16u);
        mq[a].pos_m = fx_from_float(m[a].pos_m, 24u);
        mq[a].vel_mps = fx_from_float(m[a].vel_mps, 24u);
        mq[a].force_N = fx_from_float(m[a].force_N, 16u);
    }
    pfcfx_step(&st->pfc_cfg, &st->pfc, rq, mq, cmd_q16);
    for (uint32_t a = 0u; a < PFC_AXES; a++) {
        force_cmd_N[a] = fx_to_float(cmd_q16[a], 16u);
    }
#else
    pfc_step(&cfg->pfc, &st->pfc, ref, m, force_cmd_N);
#endif
}

/* FS_OK, or (the fixed-point build) FS_ERR_FIXED_OVERFLOW when this tick's DMP step saturated. */
static fs_status_t exec_dmp_status(exec_state_t *st)
{
#ifdef FS_EXEC_FIXED
    const uint8_t saturated = st->dmp_saturated;
    st->dmp_saturated = 0u;
    return (saturated != 0u) ? FS_ERR_FIXED_OVERFLOW : FS_OK;
#else
    (void)st;
    return FS_OK;
#endif
}

/* The law's state from zero (the fixed-point build converts cfg->pfc, which exec_start
 * validated: 303 if it does not fit). */
static fs_status_t exec_law_reset(const exec_config_t *cfg, exec_state_t *st)
{
#ifdef FS_EXEC_FIXED
    pfcfx_reset(&st->pfc);
    return pfcfx_from_valid_config(&cfg->pfc, &st->pfc_cfg); /* validated by exec_start */
#else
    (void)cfg;
    pfc_reset(&st->pfc);
    return FS_OK;
#endif
}

/* A step's skill (and, the fixed-point build, its model) and its scales (exec_start). */
static fs_status_t exec_check_step(const exec_step_t *s)
{
    if (s->skill == 0) {
        return FS_ERR_NULL_ARG;
    }
#ifdef FS_EXEC_FIXED
    if (s->model_fx == 0) {
        return FS_ERR_NULL_ARG;
    }
#endif
    if (s->skill->dmp.periodic != 0u &&
        (!fs_isfinite(s->amplitude_scale) || s->amplitude_scale < FS_R(0.0))) {
        return FS_ERR_SCALE_INVALID;
    }
    if (!fs_isfinite(s->goal_scale) || !fs_isfinite(s->time_scale) || !fs_isfinite(s->duration_s) ||
        s->time_scale <= FS_R(0.0) || !fs_isfinite(s->path_scale) || s->path_scale < FS_R(0.0)) {
        return FS_ERR_SCALE_INVALID;
    }
    return FS_OK;
}

/* The contact wait at an execution's start: rate 1, nothing held. */
static void exec_contact_reset(exec_state_t *st)
{
    st->contact_rate = FS_R(1.0);
    st->contact_hold_s = FS_R(0.0);
    st->contact_defer = FS_R(0.0);
    st->contact_losses = 0u;
    st->contact_lost = 0u;
}

fs_status_t exec_start_begin(const exec_config_t *cfg, exec_state_t *st, const exec_step_t *steps,
                             uint8_t n_steps, fs_real_t y_hold_m)
{
    if (cfg == 0 || st == 0 || steps == 0) {
        return FS_ERR_NULL_ARG;
    }
    if (n_steps == 0u || n_steps > EXEC_MAX_STEPS) {
        return FS_ERR_SCALE_INVALID;
    }
    fs_status_t rc = pfc_config_validate(&cfg->pfc);
    if (rc != FS_OK) {
        return rc;
    }
    if (!fs_isfinite(y_hold_m) || !fs_isfinite(cfg->object.surface_m) ||
        !fs_isfinite(cfg->phase_stop_gain_per_N2)) {
        return FS_ERR_NOT_FINITE;
    }
    if (cfg->phase_stop_gain_per_N2 < FS_R(0.0)) {
        return FS_ERR_GAIN_NEGATIVE;
    }
    if (cfg->use_model != 0u) {
        const exec_object_t *o = &cfg->object;
        if (!fs_isfinite(o->m_v_kg) || !fs_isfinite(o->d_v_Nspm) || !fs_isfinite(o->k1_Npm) ||
            !fs_isfinite(o->k2_Npm) || !fs_isfinite(o->layer_depth_m)) {
            return FS_ERR_NOT_FINITE;
        }
        if (o->m_v_kg <= FS_R(0.0)) {
            return FS_ERR_MASS_NONPOSITIVE;
        }
        if (o->k1_Npm <= FS_R(0.0) || o->k2_Npm <= FS_R(0.0)) {
            return FS_ERR_STIFFNESS_NONPOSITIVE;
        }
        if (o->d_v_Nspm < FS_R(0.0) || o->layer_depth_m < FS_R(0.0)) {
            return FS_ERR_GAIN_NEGATIVE;
        }
    }
    for (uint8_t i = 0u; i < n_steps; i++) {
        rc = exec_check_step(&steps[i]);
        if (rc != FS_OK) {
            return rc;
        }
        st->steps[i] = steps[i];
    }
    st->n_steps = n_steps;
    st->step = 0u;
    st->ending = 0u;
    st->done = 0u;
    st->t_end_s = FS_R(0.0);
    st->force_hat_N = FS_R(0.0);
    st->force_carry_N = FS_R(0.0);
    st->force_end_N = FS_R(0.0);
    st->ref_p_m = FS_R(0.0);
    st->ref_pd_mps = FS_R(0.0);
    st->ref_pdd_mps2 = FS_R(0.0);
    st->ref_prev_pos_m = cfg->object.surface_m;
    st->surface_m = cfg->object.surface_m;
    st->y_hold_m = y_hold_m;
    st->path_m = FS_R(0.0);
    st->y_ref_m = y_hold_m;
    st->y_ref_vel_mps = FS_R(0.0);
    st->start_pending = 1u;
    st->prepared = 0u;
    exec_contact_reset(st);
    return exec_law_reset(cfg, st);
}

fs_status_t exec_start_run(const exec_config_t *cfg, exec_state_t *st, bool *done)
{
    *done = false;
#ifdef FS_EXEC_FIXED
    /* every step's constants before the run: a later switch only selects them, cannot fail */
    if (st->prepared < 2u * st->n_steps) {
        const uint8_t p = st->prepared++;
        return exec_prepare_step(st, (uint8_t)(p / 2u), (uint8_t)(p % 2u));
    }
#endif
    *done = true;
    return exec_begin_step(st, cfg->pfc.dt_s);
}

fs_status_t exec_start(const exec_config_t *cfg, exec_state_t *st, const exec_step_t *steps,
                       uint8_t n_steps, fs_real_t y_hold_m)
{
    fs_status_t rc = exec_start_begin(cfg, st, steps, n_steps, y_hold_m);
    bool done = false;
    while (rc == FS_OK && !done) {
        rc = exec_start_run(cfg, st, &done);
    }
    return rc;
}

fs_real_t exec_object_force(const exec_object_t *obj, fs_real_t p_m)
{
    if (p_m <= FS_R(0.0)) {
        return FS_R(0.0);
    }
    if (p_m <= obj->layer_depth_m) {
        return obj->k1_Npm * p_m;
    }
    return obj->k1_Npm * obj->layer_depth_m + obj->k2_Npm * (p_m - obj->layer_depth_m);
}

/* f/k, 0 for f <= 0 (the unilateral spring-only reference). */
static fs_real_t exec_spring_deformation(fs_real_t stiffness_Npm, fs_real_t force_N)
{
    return (force_N > FS_R(0.0)) ? force_N / stiffness_Npm : FS_R(0.0);
}

fs_real_t exec_object_deformation(const exec_object_t *obj, fs_real_t force_N)
{
    if (!(force_N > FS_R(0.0))) {
        return FS_R(0.0);
    }
    const fs_real_t f_layer = obj->k1_Npm * obj->layer_depth_m;
    if (force_N <= f_layer) {
        return force_N / obj->k1_Npm;
    }
    return obj->layer_depth_m + (force_N - f_layer) / obj->k2_Npm;
}

/* 1 at t = 0 falling smoothly (smoothstep) to 0 at EXEC_BLEND_S. */
static fs_real_t exec_blend(fs_real_t t_s)
{
    fs_real_t r = t_s / ((fs_real_t)EXEC_BLEND_S);
    if (r >= FS_R(1.0)) {
        return FS_R(0.0);
    }
    return FS_R(1.0) - r * r * (FS_R(3.0) - FS_R(2.0) * r);
}

/* The skill's contact wait for this tick: the phase rate from the last f_hat and the measured
 * contact force, the hold and the losses counted; 0 (rate 1) for a skill without one. */
static int exec_contact_wait(exec_state_t *st, const skill_t *sk, fs_real_t f_contact_N,
                             fs_real_t dt)
{
    if (!(sk->contact_threshold_N > FS_R(0.0))) {
        st->contact_rate = FS_R(1.0);
        return 0;
    }
    const fs_real_t gain = dt / (sk->contact_tau_s + dt);
    st->contact_rate = dmp_contact_rate(st->contact_rate, st->force_hat_N, f_contact_N,
                                        sk->contact_threshold_N, gain);
    const uint8_t lost = (uint8_t)((st->force_hat_N - f_contact_N <= sk->contact_threshold_N) ? 0u
                                                                                              : 1u);
    if (lost != 0u && st->contact_lost == 0u && st->contact_losses < UINT16_MAX) {
        st->contact_losses++;
    }
    st->contact_lost = lost;
    st->contact_hold_s += (FS_R(1.0) - st->contact_rate) * dt;
    /* the step lasts as long in phase: one tick more for every tick the phase fell behind */
    st->contact_defer += FS_R(1.0) - st->contact_rate;
    if (st->contact_defer >= FS_R(1.0)) {
        st->contact_defer -= FS_R(1.0);
        st->step_ticks += (st->step_ticks < EXEC_TICKS_MAX) ? 1u : 0u;
    }
    return 1;
}

uint32_t exec_contact_hold_ms(const exec_state_t *st)
{
    const fs_real_t ms = st->contact_hold_s * FS_R(1000.0) + FS_R(0.5);
    return (ms > FS_R(0.0)) ? (uint32_t)ms : 0u;
}

static fs_real_t exec_reference_force(const exec_config_t *cfg, exec_state_t *st,
                                      const exec_meas_t *meas)
{
    const fs_real_t dt = cfg->pfc.dt_s;
    if (st->ending != 0u) {
        const exec_step_t *last = &st->steps[st->n_steps - 1u];
        if (last->end_policy == SKILL_END_HOLD) {
            return st->force_end_N;
        }
        st->t_end_s += dt;
        fs_real_t r = FS_R(1.0) - st->t_end_s / ((fs_real_t)SKILL_RELEASE_TIME_S);
        if (r <= FS_R(0.0)) {
            st->done = 1u;
            return FS_R(0.0);
        }
        return st->force_end_N * r;
    }
    const exec_step_t *s = &st->steps[st->step];
    if (st->start_pending != 0u) {
        /* start from the measured contact force: the difference to the skill's starting force
         * fades out like a carry between steps */
        st->start_pending = 0u;
        st->force_carry_N = meas->force_contact_N - exec_step_start_force(s);
        const fs_real_t p0 = (cfg->use_model != 0u)
                                 ? exec_object_deformation(&cfg->object, meas->force_contact_N)
                                 : exec_spring_deformation(s->skill->stiffness_Npm,
                                                           meas->force_contact_N);
        if (cfg->use_model != 0u) {
            st->ref_p_m = p0;
        }
        if (cfg->surface_from_contact != 0u) {
            st->surface_m = meas->pos_m[0] - p0;
            st->ref_prev_pos_m = meas->pos_m[0];
        }
    }
    dmp_coupling_t coupling = {FS_R(0.0), FS_R(0.0)};
    const dmp_coupling_t *cp = 0;
    if (cfg->phase_stop_gain_per_N2 > FS_R(0.0)) {
        coupling.phase_slowdown = dmp_phase_stop_factor(meas->force_contact_N - st->force_hat_N,
                                                        cfg->phase_stop_gain_per_N2);
        cp = &coupling;
    }
    if (exec_contact_wait(st, s->skill, meas->force_contact_N, dt)) {
        coupling.phase_slowdown = dmp_slowdown_at_rate(coupling.phase_slowdown, st->contact_rate);
        cp = &coupling;
    }
    st->force_dmp_N = exec_dmp_step(st, s, cp);
    st->t_step_s += dt;
    fs_real_t f = st->force_dmp_N + st->force_carry_N * exec_blend(st->t_step_s);

    if (++st->step_tick >= st->step_ticks) { /* counted: no float division in the tick */
        if ((uint8_t)(st->step + 1u) < st->n_steps) {
            st->y_hold_m += st->path_m; /* the next step's path starts where this one ended */
            st->path_m = FS_R(0.0);
            st->step++;
            st->force_carry_N = f - exec_step_start_force(&st->steps[st->step]);
            (void)exec_begin_step(st, dt); /* checked by exec_start */
        } else {
            st->ending = 1u;
            st->force_end_N = f;
            st->t_end_s = FS_R(0.0);
        }
    }
    return f;
}

fs_status_t exec_tick(const exec_config_t *cfg, exec_state_t *st, const exec_meas_t *meas,
                      exec_out_t *out)
{
    out->step = st->step;
    out->done = st->done;
    if (!fs_isfinite(meas->pos_m[0]) || !fs_isfinite(meas->pos_m[1]) ||
        !fs_isfinite(meas->vel_mps[0]) || !fs_isfinite(meas->vel_mps[1]) ||
        !fs_isfinite(meas->force_contact_N)) {
        out->force_cmd_N[0] = FS_R(0.0);
        out->force_cmd_N[1] = FS_R(0.0);
        out->force_hat_N = st->force_hat_N;
        out->pos_ref_m = st->surface_m + st->ref_p_m;
        out->y_ref_m = st->y_ref_m;
        return FS_ERR_NOT_FINITE;
    }
    const fs_real_t dt = cfg->pfc.dt_s;
    const fs_real_t f_hat = exec_reference_force(cfg, st, meas);
    st->force_hat_N = f_hat;

    pfc_axis_ref_t ref[PFC_AXES];
    if (cfg->use_model != 0u) {
        const exec_object_t *o = &cfg->object;
        fs_real_t pdd = (f_hat - o->d_v_Nspm * st->ref_pd_mps - exec_object_force(o, st->ref_p_m)) /
                        o->m_v_kg;
        fs_real_t pd = st->ref_pd_mps + pdd * dt;
        fs_real_t p = st->ref_p_m + pd * dt;
        if (p < FS_R(0.0)) { /* unilateral: the reference cannot pull the surface out */
            p = FS_R(0.0);
            pd = FS_R(0.0);
            pdd = FS_R(0.0);
        }
        st->ref_p_m = p;
        st->ref_pd_mps = pd;
        st->ref_pdd_mps2 = pdd;
        ref[0].pos_m = st->surface_m + p;
        ref[0].vel_mps = pd;
        ref[0].acc_mps2 = pdd;
    } else {
        const fs_real_t p = exec_spring_deformation(st->steps[st->step].skill->stiffness_Npm,
                                                    f_hat);
        const fs_real_t x_d = st->surface_m + p;
        st->ref_p_m = p;
        ref[0].pos_m = x_d;
        ref[0].vel_mps = (x_d - st->ref_prev_pos_m) / dt;
        ref[0].acc_mps2 = FS_R(0.0);
        st->ref_prev_pos_m = x_d;
    }
    ref[0].force_N = f_hat;
    /* y: the path (a step without a y DMP keeps p = 0: y holds), derivatives by differences */
    const fs_real_t y_d = st->y_hold_m + st->path_m;
    const fs_real_t yd_d = (y_d - st->y_ref_m) / dt;
    ref[1].pos_m = y_d;
    ref[1].vel_mps = yd_d;
    ref[1].acc_mps2 = (yd_d - st->y_ref_vel_mps) / dt;
    ref[1].force_N = FS_R(0.0);
    st->y_ref_m = y_d;
    st->y_ref_vel_mps = yd_d;

    pfc_axis_meas_t m[PFC_AXES];
    m[0].pos_m = meas->pos_m[0];
    m[0].vel_mps = meas->vel_mps[0];
    m[0].force_N = meas->force_contact_N;
    m[1].pos_m = meas->pos_m[1];
    m[1].vel_mps = meas->vel_mps[1];
    m[1].force_N = FS_R(0.0);
    exec_law_step(cfg, st, ref, m, out->force_cmd_N);

    out->force_hat_N = f_hat;
    out->pos_ref_m = ref[0].pos_m;
    out->y_ref_m = y_d;
    out->step = st->step;
    out->done = st->done;
    return exec_dmp_status(st);
}

void exec_vel_init(exec_vel_t *v, fs_real_t cutoff_Hz, fs_real_t dt_s)
{
    v->prev_pos_m = FS_R(0.0);
    v->vel_mps = FS_R(0.0);
    v->alpha = dt_s / (dt_s + FS_R(1.0) / (FS_R(2.0) * EXEC_PI * cutoff_Hz));
    v->primed = 0u;
#ifdef FS_EXEC_FIXED
    v->prev_q24 = 0;
    v->vel_q24 = 0;
    v->not_finite = 0u;
    const fs_real_t a = (v->alpha > FS_R(0.0) && v->alpha < FS_R(1.0)) ? v->alpha : FS_R(1.0);
    v->alpha_q30 = fx_from_float(a, 30u);
    v->inv_dt_q16 = (dt_s > FS_R(0.0)) ? fx_from_float(FS_R(1.0) / dt_s, 16u) : 0;
#endif
}

fs_real_t exec_vel_update(exec_vel_t *v, fs_real_t pos_m, fs_real_t dt_s)
{
    if (v->primed == 0u) {
        v->prev_pos_m = pos_m;
        v->primed = 1u;
        return v->vel_mps;
    }
    const fs_real_t raw = (pos_m - v->prev_pos_m) / dt_s;
    v->prev_pos_m = pos_m;
    v->vel_mps += v->alpha * (raw - v->vel_mps);
    return v->vel_mps;
}

#ifdef FS_EXEC_FIXED
static int32_t sat_q(int64_t x)
{
    return (x > INT32_MAX) ? INT32_MAX : ((x <= INT32_MIN) ? INT32_MIN + 1 : (int32_t)x);
}

int32_t exec_vel_update_q(exec_vel_t *v, int32_t pos_q24)
{
    if (pos_q24 == INT32_MIN || v->not_finite != 0u) {
        v->not_finite = 1u;
        return INT32_MIN;
    }
    if (v->primed == 0u) {
        v->prev_q24 = pos_q24;
        v->primed = 1u;
        return v->vel_q24;
    }
    /* (pos - prev)/dt: a Q8.24 difference times 1/dt in Q16.16, rounded half up */
    const int64_t raw = sat_q((((int64_t)pos_q24 - v->prev_q24) * v->inv_dt_q16 + 0x8000) >> 16);
    v->prev_q24 = pos_q24;
    const int64_t e = raw - v->vel_q24; /* within +-2^32: times alpha (<= 2^30) fits int64 */
    v->vel_q24 = sat_q(v->vel_q24 + ((e * v->alpha_q30 + 0x20000000) >> 30));
    return v->vel_q24;
}
#endif

void exec_render_default(exec_render_cfg_t *cfg)
{
    cfg->carriage_kg = FS_R(2.0);
    cfg->viscous_Nspm = FS_R(5.0);
    cfg->coulomb_N = FS_R(1.0);
    cfg->kp_Npm = FS_R(60000.0);
    cfg->kd_Nspm = FS_R(1200.0);
    cfg->ext_ff = FS_R(1.0);
    cfg->ext_cutoff_Hz = FS_R(20.0);
    cfg->motor_max_N = FS_R(200.0);
}

void exec_render_reset(exec_render_t *r, fs_real_t pos_m)
{
    r->pos_m = pos_m;
    r->vel_mps = FS_R(0.0);
    r->ext_lp_N = FS_R(0.0);
}

fs_real_t exec_render_step(const exec_render_cfg_t *cfg, exec_render_t *r, fs_real_t force_total_N,
                           fs_real_t m_d_kg, fs_real_t force_ext_meas_N, fs_real_t pos_m,
                           fs_real_t vel_mps, fs_real_t dt_s)
{
    const fs_real_t acc = force_total_N / m_d_kg;
    const fs_real_t lp = dt_s / (dt_s + FS_R(1.0) / (FS_R(2.0) * EXEC_PI * cfg->ext_cutoff_Hz));
    r->ext_lp_N += lp * (force_ext_meas_N - r->ext_lp_N);
    r->vel_mps += acc * dt_s;
    r->pos_m += r->vel_mps * dt_s;
    fs_real_t f = cfg->carriage_kg * acc + cfg->kp_Npm * (r->pos_m - pos_m) +
                  cfg->kd_Nspm * (r->vel_mps - vel_mps) - cfg->ext_ff * r->ext_lp_N +
                  cfg->viscous_Nspm * vel_mps +
                  cfg->coulomb_N * vel_mps / (fs_fabs(vel_mps) + EXEC_COULOMB_SMOOTH_MPS);
    if (f > cfg->motor_max_N) {
        f = cfg->motor_max_N;
    } else if (f < -cfg->motor_max_N) {
        f = -cfg->motor_max_N;
    }
    return f;
}

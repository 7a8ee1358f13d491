/* Skill execution: see fs_exec.h for the algorithm and the continuity/end-policy decisions. */
#include "fs_exec.h"

#ifdef FS_EXEC_FIXED
#include <math.h>
#endif

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

static void exec_band_tally(exec_state_t *st, uint8_t outside);

#ifndef FS_EXEC_FIXED
/* The running step's DMP from its starting state and its length in ticks at dt_s. */
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
    if (periodic != 0u) {
        dmp_periodic_reset_xy(&s->skill->dmp, &st->dmp, s->amplitude_scale, s->path_scale);
    } else {
        dmp_state_reset(&st->dmp);
    }
    st->path_ramp = (periodic != 0u && s->skill->dmp.has_y != 0u) ? 1u : 0u;
    st->path_ramp_out = (st->path_ramp != 0u && s->until_stopped == 0u) ? 1u : 0u;
    st->path_ramp_inv = dt_s / (s->skill->dmp.duration_s * s->time_scale); /* a turn: 1/ticks */
    st->run.goal_scale = s->goal_scale;
    st->run.time_scale = s->time_scale;
    st->band_s = FS_R(0.0); /* the band scaled as f_hat is (skill_band_at) */
    const dmp_model_t *m = &s->skill->dmp;
    st->band_k = (periodic != 0u) ? s->amplitude_scale : s->goal_scale;
    st->band_c0_N = (periodic != 0u) ? (s->goal_scale - s->amplitude_scale) * m->goal_N
                                     : (FS_R(1.0) - s->goal_scale) * m->force0_N;
    return FS_OK;
}

/* The band's check of this tick (before the DMP step): the contact force less the carry's
 * share of the last f_hat against the band at the step's normalised time, which then advances
 * at the contact wait's phase rate. */
static void exec_band_check(exec_state_t *st, fs_real_t f_c_N)
{
    st->band_run_ticks++;
    const skill_t *sk = st->steps[st->step].skill;
    if (sk->band_n < SKILL_BAND_MIN_POINTS || st->ending != 0u || st->start_pending != 0u) {
        st->band_outside = 0u;
        return;
    }
    const fs_real_t x = (st->band_s < FS_R(1.0)) ? st->band_s : FS_R(1.0);
    const fs_real_t pos = x * (fs_real_t)(sk->band_n - 1u);
    uint32_t i = (uint32_t)pos;
    i = (i > (uint32_t)sk->band_n - 2u) ? (uint32_t)sk->band_n - 2u : i;
    const fs_real_t fr = pos - (fs_real_t)i;
    const fs_real_t lo_b = sk->band_lo_N[i] + fr * (sk->band_lo_N[i + 1u] - sk->band_lo_N[i]);
    const fs_real_t hi_b = sk->band_hi_N[i] + fr * (sk->band_hi_N[i + 1u] - sk->band_hi_N[i]);
    const fs_real_t f = f_c_N - (st->force_hat_N - st->force_dmp_N);
    const fs_real_t lo = st->band_c0_N + st->band_k * lo_b;
    const fs_real_t hi = st->band_c0_N + st->band_k * hi_b;
    const fs_real_t d = (f > hi) ? f - hi : ((f < lo) ? lo - f : FS_R(0.0));
    exec_band_tally(st, (d > FS_R(0.0)) ? 1u : 0u);
    if (d > FS_R(0.0)) { /* a new largest excursion: one division */
        const fs_real_t w = hi - lo;
        if (d > st->band_max_widths * w) {
            st->band_max_widths = (w > FS_R(0.0)) ? d / w : FS_R(65536.0);
        }
    }
    st->band_s += st->path_ramp_inv * st->contact_rate;
    if (sk->kind == SKILL_KIND_PERIODIC && st->band_s >= FS_R(1.0)) {
        st->band_s -= FS_R(1.0);
    }
}

/* The periodic path's ramp factor at x in [0, 1) (in: the phase in turns over the first turn;
 * out: the ticks left over a turn's ticks): smoothstep, its slope 0 at both ends. */
static fs_real_t exec_path_ramp(fs_real_t x)
{
    return x * x * (FS_R(3.0) - FS_R(2.0) * x);
}

/* One DMP step of the running step s (coupling cp may be NULL): returns f_hat, p into path_m. */
static fs_real_t exec_dmp_step(exec_state_t *st, const exec_step_t *s, const dmp_coupling_t *cp)
{
    if (s->skill->dmp.periodic != 0u) {
        const fs_real_t x0 = st->dmp.u;
        const fs_real_t f = dmp_periodic_step_xy(
            &s->skill->dmp, &st->dmp, &st->run, s->amplitude_scale, cp, s->path_scale, &st->path_m);
        if (st->path_ramp != 0u) {
            if (st->dmp.u < x0) { /* the phase wrapped: the first turn is over */
                st->path_ramp = 0u;
            } else {
                st->path_m *= exec_path_ramp(st->dmp.u);
            }
        }
        if (st->path_ramp_out != 0u) { /* out over the step's last turn of ticks, to rest */
            const fs_real_t u = (fs_real_t)(st->step_ticks - st->step_tick - 1u) *
                                st->path_ramp_inv;
            if (u < FS_R(1.0)) {
                st->path_m *= exec_path_ramp(u);
            }
        }
        return f;
    }
    return dmp_step_xy(&s->skill->dmp, &st->dmp, &st->run, cp, s->path_scale, &st->path_m);
}
#endif

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

/* The band's check at an execution's start: nothing counted. */
static void exec_band_reset(exec_state_t *st)
{
    st->band_s = FS_R(0.0);
    st->band_c0_N = FS_R(0.0);
    st->band_k = FS_R(1.0);
    st->band_run_ticks = 0u;
    st->band_checked_ticks = 0u;
    st->band_out_ticks = 0u;
    st->band_streak_ticks = 0u;
    st->band_longest_ticks = 0u;
    st->band_first_tick = 0u;
    st->band_max_q16 = 0u;
    st->band_max_widths = FS_R(0.0);
    st->band_outside = 0u;
    st->band_any = 0u; /* a run without a band skips the check: one test a tick */
    for (uint8_t i = 0u; i < st->n_steps; i++) {
        if (st->steps[i].skill->band_n >= SKILL_BAND_MIN_POINTS) {
            st->band_any = 1u;
        }
    }
}

/* One checked tick counted, inside or outside the band. */
static void exec_band_tally(exec_state_t *st, uint8_t outside)
{
    st->band_checked_ticks++;
    st->band_outside = outside;
    if (outside == 0u) {
        st->band_streak_ticks = 0u;
        return;
    }
    st->band_out_ticks++;
    st->band_streak_ticks++;
    if (st->band_streak_ticks > st->band_longest_ticks) {
        st->band_longest_ticks = st->band_streak_ticks;
    }
    if (st->band_first_tick == 0u) {
        st->band_first_tick = st->band_run_ticks;
    }
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
    st->path_ramp = 0u;
    st->path_ramp_out = 0u;
    st->path_ramp_inv = FS_R(0.0);
    st->prepared = 0u;
    exec_contact_reset(st);
    exec_band_reset(st);
    return exec_law_reset(cfg, st);
}

#ifdef FS_EXEC_FIXED
static fs_status_t exec_prepare_step(const exec_config_t *cfg, exec_state_t *st, uint8_t i,
                                     uint8_t part);
static fs_status_t exec_prepare_cfg_q(const exec_config_t *cfg, exec_state_t *st, uint8_t part);
/* Parts of the start a step (exec_prepare_step) and of the configuration (exec_prepare_cfg_q). */
#define EXEC_STEP_PARTS 3u
#define EXEC_CFG_PARTS 4u
static void exec_begin_step_q(exec_state_t *st);
#endif

fs_status_t exec_start_run(const exec_config_t *cfg, exec_state_t *st, bool *done)
{
    *done = false;
#ifdef FS_EXEC_FIXED
    /* every step's constants before the run: a later switch only selects them, cannot fail */
    const uint8_t steps = (uint8_t)(EXEC_STEP_PARTS * st->n_steps);
    if (st->prepared < steps + EXEC_CFG_PARTS) {
        const uint8_t p = st->prepared++;
        return (p < steps) ? exec_prepare_step(cfg, st, (uint8_t)(p / EXEC_STEP_PARTS),
                                               (uint8_t)(p % EXEC_STEP_PARTS))
                           : exec_prepare_cfg_q(cfg, st, (uint8_t)(p - steps));
    }
    *done = true;
    exec_begin_step_q(st);
    return FS_OK;
#else
    *done = true;
    return exec_begin_step(st, cfg->pfc.dt_s);
#endif
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

#ifndef FS_EXEC_FIXED
/* f/k, 0 for f <= 0 (the unilateral spring-only reference). */
static fs_real_t exec_spring_deformation(fs_real_t stiffness_Npm, fs_real_t force_N)
{
    return (force_N > FS_R(0.0)) ? force_N / stiffness_Npm : FS_R(0.0);
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

uint16_t exec_band_max_milli(const exec_state_t *st)
{
    const fs_real_t m = st->band_max_widths * FS_R(1000.0) + FS_R(0.5);
    return (m < FS_R(65535.0)) ? (uint16_t)m : 65535u;
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

/* True if every value of meas is finite: x - x is +0 for a finite x, NaN for inf and NaN, so
 * the sum of those is 0 exactly when all are finite (one compare for five values). */
static bool exec_meas_finite(const exec_meas_t *meas)
{
    const fs_real_t z = (meas->pos_m[0] - meas->pos_m[0]) + (meas->pos_m[1] - meas->pos_m[1]) +
                        (meas->vel_mps[0] - meas->vel_mps[0]) +
                        (meas->vel_mps[1] - meas->vel_mps[1]) +
                        (meas->force_contact_N - meas->force_contact_N);
    return z == FS_R(0.0);
}

fs_status_t exec_tick(const exec_config_t *cfg, exec_state_t *st, const exec_meas_t *meas,
                      exec_out_t *out)
{
    if (!exec_meas_finite(meas)) {
        out->step = st->step;
        out->done = st->done;
        out->force_cmd_N[0] = FS_R(0.0);
        out->force_cmd_N[1] = FS_R(0.0);
        out->force_hat_N = st->force_hat_N;
        out->pos_ref_m = st->surface_m + st->ref_p_m;
        out->y_ref_m = st->y_ref_m;
        return FS_ERR_NOT_FINITE;
    }
    const fs_real_t dt = cfg->pfc.dt_s;
    if (st->band_any != 0u) {
        exec_band_check(st, meas->force_contact_N);
    }
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
    pfc_step(&cfg->pfc, &st->pfc, ref, m, out->force_cmd_N);

    out->force_hat_N = f_hat;
    out->pos_ref_m = ref[0].pos_m;
    out->y_ref_m = y_d;
    out->step = st->step;
    out->done = st->done;
    return exec_dmp_status(st);
}
#else
/* The integer executor (exec_tick_q): every constant below is derived at the run's start, in
 * exec_start_run's slices (software double on the M3), so the tick and a switch between steps
 * are integer only. Units: exec_q_t in fs_exec.h. */
#define EXEC_Q31_ONE ((int64_t)1 << 31)
#define EXEC_Q32_ONE ((uint64_t)1 << 32)

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

/* The integer constants of step i (its run derived): forces, path base, 1/k, length, contact
 * wait. */
static fs_status_t exec_prepare_step_q(exec_state_t *st, uint8_t i, fs_real_t dt_s)
{
    const exec_step_t *s = &st->steps[i];
    const dmpfx_model_t *m = s->model_fx;
    const dmpfx_run_t *run = &st->run[i];
    exec_step_q_t *q = &st->q.step[i];
    const double dt = (double)dt_s;
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
    q->ticks = (s->skill->dmp.periodic != 0u && s->until_stopped != 0u)
                   ? EXEC_TICKS_MAX
                   : exec_ticks(exec_step_duration(s), dt_s);
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
    if (rc == FS_OK) {
        rc = exec_to_q(c0, 32, &q->band_c0_q32);
    }
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
    exec_cfg_q_t *c = &st->q.c;
    const double dt = (double)cfg->pfc.dt_s;
    fs_status_t rc = FS_OK;
    if (part == 0u) {
        const double inv_dt = 1.0 / dt;
        c->inv_dt_x = exec_scale(inv_dt, 48, 48, &rc);
        c->inv_dt_y = exec_scale(inv_dt, 55, 48, &rc);
        c->inv_dt_yd = exec_scale(inv_dt, 48, 40, &rc);
        c->dt = exec_scale(dt, 48, 48, &rc);
        c->hold_ms = exec_scale(dt * 1000.0, 31, 0, &rc);
        c->blend_inc_q32 = exec_inc_q32(dt / EXEC_BLEND_S);
        c->release_inc_q32 = exec_inc_q32(dt / SKILL_RELEASE_TIME_S);
        return rc;
    }
    const exec_object_t *o = &cfg->object;
    const int model = (cfg->use_model != 0u);
    if (part == 1u) {
        c->use_model = cfg->use_model;
        c->d_v = exec_scale(model ? (double)o->d_v_Nspm : 0.0, 48, 32, &rc);
        c->k1 = exec_scale(model ? (double)o->k1_Npm : 0.0, 48, 32, &rc);
        c->k2 = exec_scale(model ? (double)o->k2_Npm : 0.0, 48, 32, &rc);
        return rc;
    }
    if (part == 2u) { /* the model's three divisions */
        c->inv_m = exec_scale(model ? 1.0 / (double)o->m_v_kg : 0.0, 32, 48, &rc);
        c->inv_k1 = exec_scale(model ? 1.0 / (double)o->k1_Npm : 0.0, 32, 48, &rc);
        c->inv_k2 = exec_scale(model ? 1.0 / (double)o->k2_Npm : 0.0, 32, 48, &rc);
        return rc;
    }
    c->surface_from_contact = cfg->surface_from_contact;
    c->phase_stop = (cfg->phase_stop_gain_per_N2 > FS_R(0.0)) ? 1u : 0u;
    c->stop_gain = exec_scale((double)cfg->phase_stop_gain_per_N2, 32, 24, &rc);
    const double layer = model ? (double)o->layer_depth_m : 0.0;
    exec_q_t *q = &st->q;
    fs_status_t r2 = exec_to_q(layer, 48, &c->layer_q48);
    if (r2 == FS_OK) {
        r2 = exec_to_q(model ? (double)o->k1_Npm * layer : 0.0, 32, &c->f_layer_q32);
    }
    if (r2 == FS_OK) {
        r2 = exec_to_q((double)o->surface_m, 48, &q->surface_q48);
    }
    if (r2 == FS_OK) {
        r2 = exec_to_q((double)st->y_hold_m, 55, &q->y_hold_q55);
    }
    q->prev_x_q48 = q->surface_q48;
    q->y_ref_q55 = q->y_hold_q55;
    q->y_ref_vel_q48 = 0;
    q->f_hat_q32 = 0;
    q->f_carry_q32 = 0;
    q->f_end_q32 = 0;
    q->p_q48 = 0;
    q->pd_q48 = 0;
    q->path_q55 = 0;
    q->hold_q31 = 0u;
    q->defer_q31 = 0u;
    q->end_tick = 0u;
    q->contact_rate_q31 = (uint32_t)EXEC_Q31_ONE;
    q->band_off_q32 = 0;
    q->band_s_q32 = 0u;
    return (rc != FS_OK) ? rc : r2;
}

/* Part part (0..2) of step i's per-run constants and starting state from its fixed-point model
 * (exec_start_run: a part a call, each a bounded piece of software double on the M3): the force
 * DMP's, then the periodic and y DMPs' and the starting state, then the integer tick's. */
static fs_status_t exec_prepare_step(const exec_config_t *cfg, exec_state_t *st, uint8_t i,
                                     uint8_t part)
{
    const exec_step_t *s = &st->steps[i];
    const dmpfx_model_t *m = s->model_fx;
    dmpfx_run_t *run = &st->run[i];
    if (part == 0u) {
        return dmpfx_run_force(m, (double)s->goal_scale, (double)s->time_scale, run);
    }
    if (part == 2u) {
        return exec_prepare_step_q(st, i, cfg->pfc.dt_s);
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

/* The running step's DMP from its starting state and its length (integers: a switch in the
 * tick selects what exec_start derived). */
static void exec_begin_step_q(exec_state_t *st)
{
    const dmpfx_model_t *m = st->steps[st->step].model_fx;
    st->step_ticks = st->q.step[st->step].ticks;
    st->step_tick = 0u;
    st->dmp = st->dmp_start[st->step];
    st->dmp_saturated = 0u;
    st->path_ramp = (m->periodic != 0u && m->has_y != 0u) ? 1u : 0u;
    st->path_ramp_out = (st->path_ramp != 0u && st->steps[st->step].until_stopped == 0u) ? 1u : 0u;
    st->q.band_s_q32 = 0u;
}

/* N Q.32 -> Q16.16, saturated. */
static int32_t exec_q16(int64_t f_q32)
{
    return fx_sat32(fx_rshift_round(fx_clamp61(f_q32), 16u));
}

/* Q.(24 + sh) -> Q8.24, saturated. */
static int32_t exec_q24(int64_t v, unsigned sh)
{
    return fx_sat32(fx_rshift_round(fx_clamp61(v), sh));
}

/* exec_q24 of a value already within +-FX_S61_MAX (clamped or scaled): the same, no clamp. */
static int32_t exec_q24_bounded(int64_t v, unsigned sh)
{
    return fx_sat32(fx_rshift_round(v, sh));
}

/* 1/(1 + x) in Q1.31 for x >= 0 in Q.24: one 64/32 division of 32-bit divides. */
static uint32_t exec_rate_q31(uint64_t x_q24)
{
    const uint64_t den = x_q24 + ((uint64_t)1 << 24);
    if (den < EXEC_Q32_ONE) {
        return fx_udiv64_32_round((uint64_t)1 << 55, (uint32_t)den);
    }
    const uint64_t den8 = (den >> 16 < EXEC_Q32_ONE) ? den >> 16 : EXEC_Q32_ONE - 1u;
    return fx_udiv64_32_round((uint64_t)1 << 39, (uint32_t)den8);
}

/* The phase-stop rate 1/(1 + g*(f_c - f_hat)^2) (Q1.31; 1 without phase stopping). */
static uint32_t exec_phase_stop_rate(const exec_state_t *st, int64_t f_c_q32)
{
    if (st->q.c.phase_stop == 0u) {
        return (uint32_t)EXEC_Q31_ONE;
    }
    const int64_t e = exec_q16(f_c_q32 - st->q.f_hat_q32);
    const int64_t x = fx_scale_apply(e * e, st->q.c.stop_gain); /* e^2 N^2 Q.32 -> Q.24 */
    return exec_rate_q31((uint64_t)((x > 0) ? x : 0));
}

/* The skill's contact wait for this tick in integers (exec_contact_wait's): the rate follows 1
 * in contact, 0 once f_hat exceeds f_c by more than the threshold; the hold and losses counted,
 * the step one tick longer for each tick of phase held. */
static void exec_contact_wait_q(exec_state_t *st, const exec_step_q_t *sq, int64_t f_c_q32)
{
    exec_q_t *q = &st->q;
    if (sq->contact_wait == 0u) {
        q->contact_rate_q31 = (uint32_t)EXEC_Q31_ONE;
        return;
    }
    const uint8_t lost = (uint8_t)((q->f_hat_q32 - f_c_q32 <= sq->contact_threshold_q32) ? 0u : 1u);
    const int64_t target = (lost != 0u) ? 0 : EXEC_Q31_ONE;
    const int64_t r = (int64_t)q->contact_rate_q31;
    const int64_t nr = r + fx_rshift_round((target - r) * (int64_t)sq->contact_gain_q31, 31u);
    q->contact_rate_q31 = (uint32_t)((nr < 0) ? 0 : ((nr > EXEC_Q31_ONE) ? EXEC_Q31_ONE : nr));
    if (lost != 0u && st->contact_lost == 0u && st->contact_losses < UINT16_MAX) {
        st->contact_losses++;
    }
    st->contact_lost = lost;
    const uint64_t held = (uint64_t)EXEC_Q31_ONE - q->contact_rate_q31;
    q->hold_q31 += held;
    q->defer_q31 += held;
    if (q->defer_q31 >= (uint64_t)EXEC_Q31_ONE) {
        q->defer_q31 -= (uint64_t)EXEC_Q31_ONE;
        st->step_ticks += (st->step_ticks < EXEC_TICKS_MAX) ? 1u : 0u;
    }
}

/* exec_path_ramp in integers: smoothstep of x in [0, 1) Q.30, Q1.31. */
static uint32_t exec_path_ramp_q31(int64_t x_q30)
{
    const int64_t x2 = fx_rshift_round(x_q30 * x_q30, 30u);
    const int64_t s = fx_rshift_round(x2 * (((int64_t)3 << 30) - 2 * x_q30), 30u);
    return (uint32_t)(s * 2);
}

/* One DMP step of the running step at the phase rate rate_q31: f_dmp in N Q.32, p into path_q55
 * (both from the accumulators: the references' derivatives are their differences). */
static int64_t exec_dmp_step_q(exec_state_t *st, uint32_t rate_q31)
{
    const exec_step_t *s = &st->steps[st->step];
    const exec_step_q_t *sq = &st->q.step[st->step];
    const dmpfx_model_t *m = s->model_fx;
    const dmpfx_run_t *run = &st->run[st->step];
    const dmpfx_coupling_t c = {0, rate_q31};
    const uint32_t ev = st->dmp.sat_events;
    if (m->periodic != 0u) {
        const int64_t x0 = st->dmp.u_acc;
        (void)dmpfx_periodic_step_xy(m, run, &st->dmp, &c, 0);
        st->q.path_q55 = (m->has_y != 0u) ? sq->path0_q55 + st->dmp.path_acc : 0;
        if (st->path_ramp != 0u) {
            if (st->dmp.u_acc < x0) { /* the phase wrapped: the first turn is over */
                st->path_ramp = 0u;
            } else { /* the phase: turns Q.61 */
                st->q.path_q55 = fx_mul64_u32(fx_clamp61(st->q.path_q55),
                                              exec_path_ramp_q31(st->dmp.u_acc >> 31), 31u);
            }
        }
        if (st->path_ramp_out != 0u) { /* out over the step's last turn of ticks, to rest */
            const uint64_t u = (uint64_t)(st->step_ticks - st->step_tick - 1u) * sq->ramp_inc_q32;
            if (u < EXEC_Q32_ONE) {
                st->q.path_q55 = fx_mul64_u32(fx_clamp61(st->q.path_q55),
                                              exec_path_ramp_q31((int64_t)(u >> 2)), 31u);
            }
        }
    } else {
        (void)dmpfx_step_xy(m, run, &st->dmp, &c, 0);
        st->q.path_q55 = st->dmp.path_acc;
    }
    st->dmp_saturated = (st->dmp.sat_events != ev) ? 1u : 0u;
    return sq->force0_q32 + fx_rshift_round_var(st->dmp.y_acc, sq->y_shift);
}

/* 1 at t = 0 falling smoothly (smoothstep) to 0 at EXEC_BLEND_S, Q1.31, t = ticks*dt. */
static int64_t exec_blend_q31(const exec_state_t *st, uint32_t ticks)
{
    const uint64_t r32 = (uint64_t)ticks * st->q.c.blend_inc_q32;
    if (r32 >= EXEC_Q32_ONE) {
        return 0;
    }
    const int64_t r = (int64_t)(r32 >> 2); /* Q.30 */
    const int64_t r2 = fx_rshift_round(r * r, 30u);
    const int64_t s = fx_rshift_round(r2 * (((int64_t)3 << 30) - 2 * r), 30u);
    return (((int64_t)1 << 30) - s) * 2;
}

/* The end policy's f_hat: hold the last one, or ramp it to 0 over SKILL_RELEASE_TIME_S. */
static int64_t exec_end_force_q(exec_state_t *st)
{
    const exec_step_t *last = &st->steps[st->n_steps - 1u];
    if (last->end_policy == SKILL_END_HOLD) {
        return st->q.f_end_q32;
    }
    st->q.end_tick += (st->q.end_tick < EXEC_TICKS_MAX) ? 1u : 0u;
    const uint64_t t = (uint64_t)st->q.end_tick * st->q.c.release_inc_q32;
    if (t >= EXEC_Q32_ONE) {
        st->done = 1u;
        return 0;
    }
    return fx_mul64_u32(st->q.f_end_q32, (uint32_t)((EXEC_Q32_ONE - t) >> 1), 31u);
}

/* The first tick: the carry from the measured contact force, the surface from the contact. */
static void exec_first_tick_q(exec_state_t *st, const exec_meas_q_t *meas, int64_t f_c_q32)
{
    exec_q_t *q = &st->q;
    const exec_cfg_q_t *c = &q->c;
    st->start_pending = 0u;
    q->f_carry_q32 = f_c_q32 - q->step[st->step].start_force_q32;
    int64_t p0 = 0;
    if (f_c_q32 > 0 && c->use_model != 0u) {
        p0 = (f_c_q32 <= c->f_layer_q32)
                 ? fx_scale_apply(f_c_q32, c->inv_k1)
                 : c->layer_q48 + fx_scale_apply(f_c_q32 - c->f_layer_q32, c->inv_k2);
    } else if (f_c_q32 > 0) {
        p0 = fx_scale_apply(f_c_q32, q->step[st->step].inv_k);
    }
    if (c->use_model != 0u) {
        q->p_q48 = p0;
    }
    if (c->surface_from_contact != 0u) {
        const int64_t x = (int64_t)meas->pos_q24[0] * ((int64_t)1 << 24);
        q->surface_q48 = x - p0;
        q->prev_x_q48 = x;
    }
}

/* Band point i's lower (hi = 0) or upper (hi = 1) bound at fraction fr (Q.16) towards
 * point i + 1, N Q16.16 (the skill's float bounds read as integers). */
static int64_t exec_band_point_q16(const skill_t *sk, uint32_t i, int64_t fr_q16, int hi)
{
    const fs_real_t *b = (hi != 0) ? sk->band_hi_N : sk->band_lo_N;
    const int64_t a = fx_from_float(b[i], 16u);
    const int64_t c = fx_from_float(b[i + 1u], 16u);
    return a + (((c - a) * fr_q16) >> 16);
}

/* exec_band_check in integers: the contact force (N Q.32) less the carry's share of the last
 * f_hat against the band at the step's normalised time (Q.32 turns, advanced at the contact
 * wait's rate; a periodic skill's wraps every period). */
static void exec_band_check_q(exec_state_t *st, int64_t f_c_q32)
{
    st->band_run_ticks++;
    const skill_t *sk = st->steps[st->step].skill;
    if (sk->band_n < SKILL_BAND_MIN_POINTS || st->ending != 0u || st->start_pending != 0u) {
        st->band_outside = 0u;
        return;
    }
    exec_q_t *q = &st->q;
    const exec_step_q_t *sq = &q->step[st->step];
    const int periodic = (sk->kind == SKILL_KIND_PERIODIC);
    uint64_t x = q->band_s_q32;
    x = periodic ? (x & 0xFFFFFFFFu) : ((x > EXEC_Q32_ONE) ? EXEC_Q32_ONE : x);
    const uint64_t pos = x * (uint64_t)(sk->band_n - 1u);
    uint32_t i = (uint32_t)(pos >> 32);
    i = (i > (uint32_t)sk->band_n - 2u) ? (uint32_t)sk->band_n - 2u : i;
    const int64_t fr = (int64_t)((pos - ((uint64_t)i << 32)) >> 16);
    const int64_t lo_b = exec_band_point_q16(sk, i, fr, 0);
    const int64_t hi_b = exec_band_point_q16(sk, i, fr, 1);
    const int64_t lo = sq->band_c0_q32 + lo_b * sq->band_k_q16;
    const int64_t hi = sq->band_c0_q32 + hi_b * sq->band_k_q16;
    const int64_t f = f_c_q32 - q->band_off_q32;
    const int64_t d = (f > hi) ? f - hi : ((f < lo) ? lo - f : 0);
    exec_band_tally(st, (d > 0) ? 1u : 0u);
    if (d > 0) { /* a new largest excursion: one division (N Q16.16 over N Q16.16) */
        const uint64_t w16 = (uint64_t)((hi - lo) >> 16);
        const uint64_t d16 = (uint64_t)(d >> 16);
        if (d16 > ((w16 * st->band_max_q16) >> 16)) {
            const uint64_t e = (w16 > 0u && d16 < ((uint64_t)1 << 47)) ? (d16 << 16) / w16
                                                                       : UINT32_MAX;
            st->band_max_q16 = (e < UINT32_MAX) ? (uint32_t)e : UINT32_MAX;
        }
    }
    q->band_s_q32 += ((uint64_t)sq->ramp_inc_q32 * q->contact_rate_q31) >> 31;
}

/* The reference force of this tick (exec_reference_force's in integers), N Q.32. */
static int64_t exec_reference_force_q(exec_state_t *st, const exec_meas_q_t *meas)
{
    if (st->ending != 0u) {
        return exec_end_force_q(st);
    }
    exec_q_t *q = &st->q;
    const int64_t f_c = (int64_t)meas->force_contact_q16 * ((int64_t)1 << 16);
    if (st->start_pending != 0u) {
        exec_first_tick_q(st, meas, f_c);
    }
    const uint32_t stop_rate = exec_phase_stop_rate(st, f_c);
    exec_contact_wait_q(st, &q->step[st->step], f_c);
    const uint32_t rate = (uint32_t)fx_rshift_round((int64_t)stop_rate * q->contact_rate_q31, 31u);
    const int64_t f_dmp = exec_dmp_step_q(st, rate);
    const int64_t f = f_dmp + fx_mul64_u32(fx_clamp61(q->f_carry_q32),
                                           (uint32_t)exec_blend_q31(st, st->step_tick + 1u), 31u);
    q->band_off_q32 = f - f_dmp;
    if (++st->step_tick >= st->step_ticks) {
        if ((uint8_t)(st->step + 1u) < st->n_steps) {
            q->y_hold_q55 += q->path_q55; /* the next step's path starts where this one ended */
            q->path_q55 = 0;
            st->step++;
            q->f_carry_q32 = f - q->step[st->step].start_force_q32;
            exec_begin_step_q(st);
        } else {
            st->ending = 1u;
            q->f_end_q32 = f;
            q->end_tick = 0u;
        }
    }
    return f;
}

/* The x reference of this tick from f_hat into rq: the object model integrated forward
 * (unilateral), or x_d = surface + f_hat/k with xd_d by difference. */
static void exec_x_reference_q(exec_state_t *st, int64_t f_hat, pfcfx_ref_t *rq)
{
    exec_q_t *q = &st->q;
    const exec_cfg_q_t *c = &q->c;
    int64_t x_d;
    if (c->use_model != 0u) {
        const int64_t p_old = q->p_q48;
        const int64_t spring = (p_old <= 0) ? 0
                               : (p_old <= c->layer_q48)
                                   ? fx_scale_apply(p_old, c->k1)
                                   : c->f_layer_q32 + fx_scale_apply(p_old - c->layer_q48, c->k2);
        int64_t pdd = fx_scale_apply(f_hat - fx_scale_apply(q->pd_q48, c->d_v) - spring, c->inv_m);
        int64_t pd = fx_clamp61(q->pd_q48 + fx_scale_apply(pdd, c->dt));
        int64_t p = fx_clamp61(p_old + fx_scale_apply(pd, c->dt));
        if (p < 0) { /* unilateral: the reference cannot pull the surface out */
            p = 0;
            pd = 0;
            pdd = 0;
        }
        q->p_q48 = p;
        q->pd_q48 = pd;
        x_d = fx_clamp61(q->surface_q48 + p);
        rq->vel_mps = exec_q24_bounded(pd, 24u);
        rq->acc_mps2 = exec_q24_bounded(pdd, 24u);
    } else {
        const int64_t p = (f_hat > 0) ? fx_scale_apply(f_hat, q->step[st->step].inv_k) : 0;
        x_d = fx_clamp61(q->surface_q48 + p);
        q->p_q48 = p;
        rq->vel_mps = exec_q24_bounded(fx_scale_apply(x_d - q->prev_x_q48, c->inv_dt_x), 24u);
        rq->acc_mps2 = 0;
        q->prev_x_q48 = x_d;
    }
    rq->pos_m = exec_q24_bounded(x_d, 24u);
    rq->force_N = exec_q24_bounded(f_hat, 16u);
}

/* The y reference: the path (p = 0 without a y DMP: y holds), derivatives by differences of the
 * Q.55 path (the accumulators' resolution, not the Q8.24 view). */
static void exec_y_reference_q(exec_state_t *st, pfcfx_ref_t *rq)
{
    exec_q_t *q = &st->q;
    const int64_t y_d = fx_clamp61(q->y_hold_q55 + q->path_q55);
    int64_t yd = 0;
    int64_t ydd = 0;
    /* a y that holds (no y DMP, or a path at rest) has no derivatives: two scalings skipped */
    if (y_d != q->y_ref_q55 || q->y_ref_vel_q48 != 0) {
        yd = fx_scale_apply(y_d - q->y_ref_q55, q->c.inv_dt_y);
        ydd = fx_scale_apply(yd - q->y_ref_vel_q48, q->c.inv_dt_yd);
    }
    rq->pos_m = exec_q24_bounded(y_d, 31u);
    rq->vel_mps = exec_q24_bounded(yd, 24u);
    rq->acc_mps2 = exec_q24_bounded(ydd, 16u);
    rq->force_N = 0;
    q->y_ref_q55 = y_d;
    q->y_ref_vel_q48 = yd;
}

/* 1 if any measurement is INT32_MIN (not finite). */
static int exec_meas_q_invalid(const exec_meas_q_t *m)
{
    return m->pos_q24[0] == INT32_MIN || m->pos_q24[1] == INT32_MIN || m->vel_q24[0] == INT32_MIN ||
           m->vel_q24[1] == INT32_MIN || m->force_contact_q16 == INT32_MIN;
}

fs_status_t exec_tick_q(const exec_config_t *cfg, exec_state_t *st, const exec_meas_q_t *meas,
                        exec_out_q_t *out)
{
    (void)cfg; /* its constants were derived by exec_start */
    exec_q_t *q = &st->q;
    if (exec_meas_q_invalid(meas)) {
        out->step = st->step;
        out->done = st->done;
        out->force_cmd_q16[0] = 0;
        out->force_cmd_q16[1] = 0;
        out->force_hat_q16 = exec_q16(q->f_hat_q32);
        out->pos_ref_q24 = exec_q24(q->surface_q48 + q->p_q48, 24u);
        out->y_ref_q24 = exec_q24(q->y_ref_q55, 31u);
        return FS_ERR_NOT_FINITE;
    }
    if (st->band_any != 0u) {
        exec_band_check_q(st, (int64_t)meas->force_contact_q16 * ((int64_t)1 << 16));
    }
    const int64_t f_hat = fx_clamp61(exec_reference_force_q(st, meas));
    q->f_hat_q32 = f_hat;
    pfcfx_ref_t rq[PFC_AXES];
    exec_x_reference_q(st, f_hat, &rq[0]);
    exec_y_reference_q(st, &rq[1]);
    pfcfx_meas_t mq[PFC_AXES];
    for (uint32_t a = 0u; a < PFC_AXES; a++) {
        mq[a].pos_m = meas->pos_q24[a];
        mq[a].vel_mps = meas->vel_q24[a];
    }
    mq[0].force_N = meas->force_contact_q16;
    mq[1].force_N = 0;
    pfcfx_step(&st->pfc_cfg, &st->pfc, rq, mq, out->force_cmd_q16);
    out->force_hat_q16 = rq[0].force_N;
    out->pos_ref_q24 = rq[0].pos_m;
    out->y_ref_q24 = rq[1].pos_m;
    out->step = st->step;
    out->done = st->done;
    return exec_dmp_status(st);
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
    st->force_hat_N = out->force_hat_N; /* the float view of the integer state */
    st->contact_rate = fx_to_float((int32_t)(st->q.contact_rate_q31 >> 1), 30u);
    return rc;
}

uint16_t exec_band_max_milli(const exec_state_t *st)
{
    const uint64_t m = ((uint64_t)st->band_max_q16 * 1000u + 32768u) >> 16;
    return (m < 65535u) ? (uint16_t)m : 65535u;
}

uint32_t exec_contact_hold_ms(const exec_state_t *st)
{
    const uint64_t held = st->q.hold_q31;
    const int64_t ms = fx_scale_apply((held > (uint64_t)FX_S61_MAX) ? FX_S61_MAX : (int64_t)held,
                                      st->q.c.hold_ms);
    return (ms < (int64_t)UINT32_MAX) ? (uint32_t)ms : UINT32_MAX;
}
#endif

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
    return exec_vel_step(v, pos_m, dt_s);
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

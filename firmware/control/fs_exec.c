/* Skill execution: see fs_exec.h for the algorithm and the continuity/end-policy decisions.
 * The tick is written once over the executor's numeric layer (exec_num_real_api.h: fs_real_t;
 * exec_num_fixed_api.h: Q formats, integers only); a layer's run preparation is its own
 * (exec_prep_parts/exec_prep_run: none in the real layer, fs_exec_fixed.c in the fixed one). */
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

/* The running step's DMP from its starting state and its length in ticks. */
static void exec_begin_step(const exec_config_t *cfg, exec_state_t *st)
{
    const exec_step_t *s = &st->steps[st->step];
    const dmp_model_t *m = &s->skill->dmp;
    st->step_ticks = exec_num_begin_step(cfg, st);
    st->step_tick = 0u;
    st->t_step = 0u;
    st->f_dmp = exec_num_start_force(st, st->step);
    st->path_ramp = (m->periodic != 0u && m->has_y != 0u) ? 1u : 0u;
    st->path_ramp_out = (st->path_ramp != 0u && s->until_stopped == 0u) ? 1u : 0u;
    st->band_s = 0u; /* the band scaled as f_hat is (skill_band_at) */
    /* a discrete DMP steps every tick until the end policy (exec_prepare_next) */
    st->prep_next = (m->periodic == 0u) ? 1u : 0u;
}

static void exec_band_tally(exec_state_t *st, uint8_t outside);

/* The band's check of this tick (before the DMP step): the contact force less the carry's
 * share of the last f_hat against the band at the step's normalised time, which then advances
 * at the contact wait's phase rate. */
static void exec_band_check(exec_state_t *st, exec_nf_t f_c)
{
    st->band_run_ticks++;
    const skill_t *sk = st->steps[st->step].skill;
    if (sk->band_n < SKILL_BAND_MIN_POINTS || st->ending != 0u || st->start_pending != 0u) {
        st->band_outside = 0u;
        return;
    }
    const int periodic = (sk->kind == SKILL_KIND_PERIODIC);
    exec_nf_t lo;
    exec_nf_t hi;
    exec_num_band_bounds(st, sk, periodic, &lo, &hi);
    const exec_nf_t f = f_c - (st->f_hat - st->f_dmp);
    const exec_nf_t d = (f > hi) ? f - hi : ((f < lo) ? lo - f : 0);
    exec_band_tally(st, (d > 0) ? 1u : 0u);
    if (d > 0) { /* a new largest excursion: one division */
        exec_num_band_excursion(st, d, hi - lo);
    }
    st->band_s = exec_num_band_advance(st, periodic);
}

/* One DMP step of the running step s at the coupling c: returns f_dmp, p into path. A periodic
 * y path ramps in over its first turn and out over the step's last one. */
static exec_nf_t exec_dmp_step(exec_state_t *st, const exec_step_t *s, const exec_ncoupling_t *c)
{
    if (s->skill->dmp.periodic == 0u) {
        return exec_num_dmp_discrete(st, s, c);
    }
    const exec_nphase_t x0 = exec_num_phase(st);
    const exec_nf_t f = exec_num_dmp_periodic(st, s, c);
    if (st->path_ramp != 0u) {
        if (exec_num_phase(st) < x0) { /* the phase wrapped: the first turn is over */
            st->path_ramp = 0u;
        } else {
            exec_num_ramp_in(st);
        }
    }
    if (st->path_ramp_out != 0u) { /* out over the step's last turn of ticks, to rest */
        exec_num_ramp_out(st, st->step_ticks - st->step_tick - 1u);
    }
    return f;
}

/* A step's skill and its scales (exec_start; the layer's own needs, e.g. a model). */
static fs_status_t exec_check_step(const exec_step_t *s)
{
    if (s->skill == 0) {
        return FS_ERR_NULL_ARG;
    }
    if (exec_num_check_step(s) != FS_OK) {
        return FS_ERR_NULL_ARG;
    }
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
    st->contact_rate = EXEC_NUM_RATE_ONE;
    st->contact_hold = 0u;
    st->contact_defer = 0u;
    st->contact_losses = 0u;
    st->contact_lost = 0u;
}

/* The band's check at an execution's start: nothing counted. */
static void exec_band_reset(exec_state_t *st)
{
    st->band_s = 0u;
    st->band_run_ticks = 0u;
    st->band_checked_ticks = 0u;
    st->band_out_ticks = 0u;
    st->band_streak_ticks = 0u;
    st->band_longest_ticks = 0u;
    st->band_first_tick = 0u;
    st->band_max = 0u;
    st->band_outside = 0u;
    st->band_any = 0u; /* a run without a band skips the check: one test a tick */
    exec_num_band_reset(st);
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

/* The configuration's checks (exec_start_begin). */
static fs_status_t exec_check_config(const exec_config_t *cfg, fs_real_t y_hold_m)
{
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
    return FS_OK;
}

fs_status_t exec_start_load(exec_state_t *st, const exec_step_t *steps, uint8_t n_steps,
                            fs_real_t y_hold_m)
{
    if (st == 0 || steps == 0) {
        return FS_ERR_NULL_ARG;
    }
    if (n_steps == 0u || n_steps > EXEC_MAX_STEPS) {
        return FS_ERR_SCALE_INVALID;
    }
    if (!fs_isfinite(y_hold_m)) { /* exec_check_config's too: a refusal here changes nothing */
        return FS_ERR_NOT_FINITE;
    }
    for (uint8_t i = 0u; i < n_steps; i++) {
        const fs_status_t rc = exec_check_step(&steps[i]);
        if (rc != FS_OK) {
            return rc;
        }
    }
    for (uint8_t i = 0u; i < n_steps; i++) {
        st->steps[i] = steps[i];
    }
    st->n_steps = n_steps;
    st->y_start_m = y_hold_m;
    return FS_OK;
}

fs_status_t exec_start_reset(const exec_config_t *cfg, exec_state_t *st)
{
    if (cfg == 0 || st == 0) {
        return FS_ERR_NULL_ARG;
    }
    const fs_real_t y_hold_m = st->y_start_m;
    const fs_status_t rc = exec_check_config(cfg, y_hold_m);
    if (rc != FS_OK) {
        return rc;
    }
    st->step = 0u;
    st->ending = 0u;
    st->done = 0u;
    st->prep_next = 0u; /* until the first step begins */
    st->t_end = 0u;
    st->f_hat = 0;
    st->f_dmp = 0;
    st->f_carry = 0;
    st->f_end = 0;
    st->ref_p = 0;
    st->ref_pd = 0;
    st->ref_pdd = 0;
    st->path = 0;
    st->y_ref_vel = 0;
    exec_num_start_positions(cfg, st, y_hold_m); /* surface, previous x_d, y_base and y_d */
    st->start_pending = 1u;
    st->path_ramp = 0u;
    st->path_ramp_out = 0u;
    st->prepared = 0u;
    exec_contact_reset(st);
    exec_band_reset(st);
    return exec_num_law_reset(cfg, st);
}

fs_status_t exec_start_begin(const exec_config_t *cfg, exec_state_t *st, const exec_step_t *steps,
                             uint8_t n_steps, fs_real_t y_hold_m)
{
    if (cfg == 0 || st == 0 || steps == 0) {
        return FS_ERR_NULL_ARG;
    }
    /* the configuration first, as before the halves: a refusal changes nothing in st */
    fs_status_t rc = exec_check_config(cfg, y_hold_m);
    if (rc == FS_OK) {
        rc = exec_start_load(st, steps, n_steps, y_hold_m);
    }
    return (rc != FS_OK) ? rc : exec_start_reset(cfg, st);
}

fs_status_t exec_start_run(const exec_config_t *cfg, exec_state_t *st, bool *done)
{
    *done = false;
    /* the layer's preparation of every step before the run: a later switch only selects it */
    if (st->prepared < exec_prep_parts(st->n_steps)) {
        return exec_prep_run(cfg, st, st->prepared++);
    }
    *done = true;
    exec_begin_step(cfg, st);
    return FS_OK;
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

/* The skill's contact wait for this tick: the phase rate from the last f_hat and the measured
 * contact force, the hold and the losses counted; 0 (rate 1) for a skill without one. */
static int exec_contact_wait(const exec_config_t *cfg, exec_state_t *st, const skill_t *sk,
                             exec_nf_t f_c)
{
    if (!exec_num_contact_on(st, sk)) {
        st->contact_rate = EXEC_NUM_RATE_ONE;
        return 0;
    }
    const uint8_t lost = (uint8_t)((st->f_hat - f_c <= exec_num_contact_threshold(st, sk)) ? 0u
                                                                                           : 1u);
    st->contact_rate = exec_num_contact_rate(cfg, st, sk, lost, f_c);
    if (lost != 0u && st->contact_lost == 0u && st->contact_losses < UINT16_MAX) {
        st->contact_losses++;
    }
    st->contact_lost = lost;
    const exec_nsum_t held = EXEC_NUM_SUM_ONE - st->contact_rate;
    st->contact_hold = exec_num_hold_add(cfg, st->contact_hold, held);
    /* the step lasts as long in phase: one tick more for every tick the phase fell behind */
    st->contact_defer += held;
    if (st->contact_defer >= EXEC_NUM_SUM_ONE) {
        st->contact_defer -= EXEC_NUM_SUM_ONE;
        st->step_ticks += (st->step_ticks < EXEC_TICKS_MAX) ? 1u : 0u;
    }
    return 1;
}

/* The first tick: the carry from the measured contact force, the surface from the contact. */
static void exec_first_tick(const exec_config_t *cfg, exec_state_t *st, const exec_meas_n_t *meas,
                            exec_nf_t f_c)
{
    /* start from the measured contact force: the difference to the skill's starting force fades
     * out like a carry between steps */
    st->start_pending = 0u;
    st->f_carry = f_c - exec_num_start_force(st, st->step);
    const exec_nx_t p0 = exec_num_deformation(cfg, st, f_c);
    if (cfg->use_model != 0u) {
        st->ref_p = p0;
    }
    if (cfg->surface_from_contact != 0u) {
        const exec_nx_t x = exec_num_meas_x(meas);
        st->surface = x - p0;
        st->ref_prev_pos = x;
    }
}

/* The end policy's f_hat: hold the last one, or ramp it to 0 over SKILL_RELEASE_TIME_S. */
static exec_nf_t exec_end_force(const exec_config_t *cfg, exec_state_t *st)
{
    const exec_step_t *last = &st->steps[st->n_steps - 1u];
    if (last->end_policy == SKILL_END_HOLD) {
        return st->f_end;
    }
    return exec_num_release(cfg, st);
}

static exec_nf_t exec_reference_force(const exec_config_t *cfg, exec_state_t *st,
                                      const exec_meas_n_t *meas)
{
    if (st->ending != 0u) {
        return exec_end_force(cfg, st);
    }
    const exec_step_t *s = &st->steps[st->step];
    const exec_nf_t f_c = exec_num_meas_force(meas);
    if (st->start_pending != 0u) {
        exec_first_tick(cfg, st, meas, f_c);
    }
    exec_ncoupling_t c = exec_num_phase_stop(cfg, st, f_c);
    if (exec_contact_wait(cfg, st, s->skill, f_c)) {
        c = exec_num_at_rate(c, st->contact_rate);
    }
    const exec_nf_t f_dmp = exec_dmp_step(st, s, &c);
    st->f_dmp = f_dmp;
    st->t_step = exec_num_clock_tick(exec_num_dt(cfg), st->t_step);
    const exec_nf_t f = f_dmp + exec_num_carry(st);

    if (++st->step_tick >= st->step_ticks) { /* counted: no division in the tick */
        if ((uint8_t)(st->step + 1u) < st->n_steps) {
            st->y_hold += st->path; /* the next step's path starts where this one ended */
            st->path = 0;
            st->step++;
            st->f_carry = f - exec_num_start_force(st, st->step);
            exec_begin_step(cfg, st); /* derived by exec_start */
        } else {
            st->ending = 1u;
            st->prep_next = 0u; /* no DMP step from now */
            st->f_end = f;
            st->t_end = 0u;
        }
    }
    return f;
}

/* The x reference of this tick from f_hat into ref: the object model integrated forward
 * (semi-implicit Euler, unilateral), or x_d = surface + f_hat/k with xd_d by difference. */
static void exec_x_reference(const exec_config_t *cfg, exec_ndt_t dt, exec_state_t *st,
                             exec_nf_t f_hat, exec_nref_t *ref)
{
    exec_nx_t x_d;
    if (cfg->use_model != 0u) {
        exec_nx_t pdd = exec_num_model_acc(cfg, st, f_hat);
        exec_nx_t pd = exec_num_integrate(cfg, st, st->ref_pd, pdd);
        exec_nx_t p = exec_num_integrate(cfg, st, st->ref_p, pd);
        if (p < 0) { /* unilateral: the reference cannot pull the surface out */
            p = 0;
            pd = 0;
            pdd = 0;
        }
        st->ref_p = p;
        st->ref_pd = pd;
        st->ref_pdd = pdd;
        x_d = exec_num_x_add(st->surface, p);
        ref->vel_mps = exec_num_law_x(pd);
        ref->acc_mps2 = exec_num_law_x(pdd);
    } else {
        const exec_nx_t p = exec_num_spring(st, f_hat);
        x_d = exec_num_x_add(st->surface, p);
        st->ref_p = p;
        ref->vel_mps = exec_num_law_x(exec_num_x_rate(dt, st, x_d - st->ref_prev_pos));
        ref->acc_mps2 = 0;
        st->ref_prev_pos = x_d;
    }
    ref->pos_m = exec_num_law_x(x_d);
    ref->force_N = exec_num_law_f(f_hat);
}

/* The y reference: the path (p = 0 without a y DMP: y holds), derivatives by differences (the
 * fixed layer skips them for a y that holds). */
static void exec_y_reference(exec_ndt_t dt, exec_state_t *st, exec_nref_t *ref)
{
    const exec_ny_t y_d = exec_num_y_add(st->y_hold, st->path);
    exec_nx_t yd = 0;
    exec_nx_t ydd = 0;
    if (!exec_num_y_holds(st, y_d)) {
        yd = exec_num_y_rate(dt, st, y_d - st->y_ref);
        ydd = exec_num_yd_rate(dt, st, yd - st->y_ref_vel);
    }
    ref->pos_m = exec_num_law_y(y_d);
    ref->vel_mps = exec_num_law_x(yd);
    ref->acc_mps2 = exec_num_law_ydd(ydd);
    ref->force_N = 0;
    st->y_ref = y_d;
    st->y_ref_vel = yd;
}

fs_status_t exec_tick_n(const exec_config_t *cfg, exec_state_t *st, const exec_meas_n_t *meas,
                        exec_out_n_t *out)
{
    if (exec_num_meas_bad(meas)) {
        exec_num_out_held(st, out); /* 0 N, the last references */
        return FS_ERR_NOT_FINITE;
    }
    if (st->band_any != 0u) {
        exec_band_check(st, exec_num_meas_force(meas));
    }
    const exec_nf_t f_hat = exec_num_f_bound(exec_reference_force(cfg, st, meas));
    st->f_hat = f_hat;
    const exec_ndt_t dt = exec_num_dt(cfg);
    exec_nref_t ref[PFC_AXES];
    exec_x_reference(cfg, dt, st, f_hat, &ref[0]);
    exec_y_reference(dt, st, &ref[1]);
    exec_num_out_refs(ref, out);
    exec_num_law(cfg, st, ref, meas, out);
    out->step = st->step;
    out->done = st->done;
    return exec_num_status(st);
}

uint16_t exec_band_max_milli(const exec_state_t *st)
{
    return exec_num_band_milli(st->band_max);
}

uint32_t exec_contact_hold_ms(const exec_state_t *st)
{
    return exec_num_hold_ms(st);
}

fs_real_t exec_contact_rate(const exec_state_t *st)
{
    return exec_num_rate_real(st->contact_rate);
}

fs_real_t exec_force_hat_N(const exec_state_t *st)
{
    return exec_num_f_real(st->f_hat);
}

void exec_vel_init(exec_vel_t *v, fs_real_t cutoff_Hz, fs_real_t dt_s)
{
    v->prev_pos_m = FS_R(0.0);
    v->vel_mps = FS_R(0.0);
    v->alpha = dt_s / (dt_s + FS_R(1.0) / (FS_R(2.0) * EXEC_PI * cutoff_Hz));
    v->primed = 0u;
    exec_num_vel_init(v, dt_s);
}

fs_real_t exec_vel_update(exec_vel_t *v, fs_real_t pos_m, fs_real_t dt_s)
{
    return exec_vel_step(v, pos_m, dt_s);
}


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

EXEC_COLD int32_t exec_counts_edge(fs_real_t v, fs_real_t r, int32_t lo, int32_t hi)
{
    if (!(r > (fs_real_t)lo && r < (fs_real_t)hi)) { /* out of range, or NaN/inf (v or r) */
        if (!fs_isfinite(v)) {
            return 0;
        }
        return (r >= (fs_real_t)hi) ? hi : lo;
    }
    /* round half away from zero, as cantools --use-round (roundf) does */
    return (int32_t)(r < FS_R(0.0) ? r - FS_R(0.5) : r + FS_R(0.5));
}

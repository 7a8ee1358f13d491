/* The operations of the executor's real numeric layer (exec_num_real.h), over fs_exec.h's
 * types: the plain fs_real_t arithmetic, inline, so the tick written over the layer (fs_exec.c)
 * costs nothing over writing it in fs_real_t directly. The fixed layer's counterparts
 * (exec_num_fixed_api.h) have the same names and meanings. Included at the end of fs_exec.h. */
#ifndef EXEC_NUM_REAL_API_H
#define EXEC_NUM_REAL_API_H

#define EXEC_NUM_RATE_ONE FS_R(1.0)
#define EXEC_NUM_SUM_ONE FS_R(1.0)

/** The phase coupling of a tick: the DMP's slow-down, on (the DMP is coupled) or not. */
typedef struct {
    dmp_coupling_t c;
    uint8_t on;
} exec_ncoupling_t;
/** The tick's dt as the layer's operations take it (read once a tick). */
typedef fs_real_t exec_ndt_t;
static inline exec_ndt_t exec_num_dt(const exec_config_t *cfg)
{
    return cfg->pfc.dt_s;
}
/** A DMP's phase (monotone within a turn). */
typedef fs_real_t exec_nphase_t;

/** Parts of exec_start_run's preparation of a run: none (the real tick derives as it goes). */
static inline uint32_t exec_prep_parts(uint8_t n_steps)
{
    (void)n_steps;
    return 0u;
}

/** Part part of the preparation (none here). */
static inline fs_status_t exec_prep_run(const exec_config_t *cfg, exec_state_t *st, uint32_t part)
{
    (void)cfg;
    (void)st;
    (void)part;
    return FS_OK;
}

/** FS_OK: a step needs nothing beyond its skill. */
static inline fs_status_t exec_num_check_step(const exec_step_t *s)
{
    (void)s;
    return FS_OK;
}

/** The law's state from zero. */
static inline fs_status_t exec_num_law_reset(const exec_config_t *cfg, exec_state_t *st)
{
    (void)cfg;
    pfc_reset(&st->n.pfc);
    return FS_OK;
}

/** The positions a run starts from: the configured surface, y_base = y_d = y_hold_m. */
static inline void exec_num_start_positions(const exec_config_t *cfg, exec_state_t *st,
                                            fs_real_t y_hold_m)
{
    st->ref_prev_pos = cfg->object.surface_m;
    st->surface = cfg->object.surface_m;
    st->y_hold = y_hold_m;
    st->y_ref = y_hold_m;
}

/** The running step's DMP from its starting state, its run and constants; its length in ticks. */
static inline uint32_t exec_num_begin_step(const exec_config_t *cfg, exec_state_t *st)
{
    const exec_step_t *s = &st->steps[st->step];
    const dmp_model_t *m = &s->skill->dmp;
    const fs_real_t dt_s = cfg->pfc.dt_s;
    if (m->periodic != 0u) {
        dmp_periodic_reset_xy(m, &st->dmp, s->amplitude_scale, s->path_scale);
    } else {
        dmp_state_reset(&st->dmp);
    }
    st->n.path_ramp_inv = dt_s / (m->duration_s * s->time_scale); /* a turn: 1/ticks */
    st->n.run.goal_scale = s->goal_scale;
    st->n.run.time_scale = s->time_scale;
    st->n.band_k = (m->periodic != 0u) ? s->amplitude_scale : s->goal_scale;
    st->n.band_c0_N = (m->periodic != 0u) ? (s->goal_scale - s->amplitude_scale) * m->goal_N
                                          : (FS_R(1.0) - s->goal_scale) * m->force0_N;
    return exec_step_ticks(s, dt_s);
}

/** Step i's first force (the carry's reference). */
static inline exec_nf_t exec_num_start_force(const exec_state_t *st, uint8_t i)
{
    return exec_step_start_force(&st->steps[i]);
}

/** Nothing to forget at a run's start: the float layer reads the bounds as they are. */
static inline void exec_num_band_reset(exec_state_t *st)
{
    (void)st;
}

/** The band's bounds at the step's normalised time, scaled as f_hat (c0 + k*b). */
static inline void exec_num_band_bounds(exec_state_t *st, const skill_t *sk, int periodic,
                                        exec_nf_t *lo, exec_nf_t *hi)
{
    (void)periodic; /* band_s wraps as it advances */
    const fs_real_t x = (st->band_s < FS_R(1.0)) ? st->band_s : FS_R(1.0);
    const fs_real_t pos = x * (fs_real_t)(sk->band_n - 1u);
    uint32_t i = (uint32_t)pos;
    i = (i > (uint32_t)sk->band_n - 2u) ? (uint32_t)sk->band_n - 2u : i;
    const fs_real_t fr = pos - (fs_real_t)i;
    const fs_real_t lo_b = sk->band_lo_N[i] + fr * (sk->band_lo_N[i + 1u] - sk->band_lo_N[i]);
    const fs_real_t hi_b = sk->band_hi_N[i] + fr * (sk->band_hi_N[i + 1u] - sk->band_hi_N[i]);
    *lo = st->n.band_c0_N + st->n.band_k * lo_b;
    *hi = st->n.band_c0_N + st->n.band_k * hi_b;
}

/** An excursion d > 0 beyond a band of width w: the largest in widths kept. */
static inline void exec_num_band_excursion(exec_state_t *st, exec_nf_t d, exec_nf_t w)
{
    if (d > st->band_max * w) {
        st->band_max = (w > FS_R(0.0)) ? d / w : FS_R(65536.0);
    }
}

/** The band's normalised time one tick on, at the contact wait's rate (a periodic one wraps). */
static inline exec_nturn_t exec_num_band_advance(const exec_state_t *st, int periodic)
{
    fs_real_t s = st->band_s + st->n.path_ramp_inv * st->contact_rate;
    if (periodic && s >= FS_R(1.0)) {
        s -= FS_R(1.0);
    }
    return s;
}

/** The largest excursion in thousandths of a band width, saturated at 65535. */
static inline uint16_t exec_num_band_milli(exec_nwidth_t w)
{
    const fs_real_t m = w * FS_R(1000.0) + FS_R(0.5);
    return (m < FS_R(65535.0)) ? (uint16_t)m : 65535u;
}

/** True if the running skill waits for contact. */
static inline int exec_num_contact_on(const exec_state_t *st, const skill_t *sk)
{
    (void)st;
    return sk->contact_threshold_N > FS_R(0.0);
}

/** The running skill's contact threshold. */
static inline exec_nf_t exec_num_contact_threshold(const exec_state_t *st, const skill_t *sk)
{
    (void)st;
    return sk->contact_threshold_N;
}

/** The contact wait's next rate (dmp_contact_rate at gain dt/(tau + dt)). */
static inline exec_nrate_t exec_num_contact_rate(const exec_config_t *cfg, const exec_state_t *st,
                                                 const skill_t *sk, uint8_t lost, exec_nf_t f_c)
{
    (void)lost;
    const fs_real_t dt = cfg->pfc.dt_s;
    const fs_real_t gain = dt / (sk->contact_tau_s + dt);
    return dmp_contact_rate(st->contact_rate, st->f_hat, f_c, sk->contact_threshold_N, gain);
}

/** The hold's sum plus a tick's held share (1 - rate), times dt: seconds. */
static inline exec_nsum_t exec_num_hold_add(const exec_config_t *cfg, exec_nsum_t hold,
                                            exec_nsum_t held)
{
    return hold + held * cfg->pfc.dt_s;
}

/** The hold in ms, rounded. */
static inline uint32_t exec_num_hold_ms(const exec_state_t *st)
{
    const fs_real_t ms = st->contact_hold * FS_R(1000.0) + FS_R(0.5);
    return (ms > FS_R(0.0)) ? (uint32_t)ms : 0u;
}

/** The phase-stop coupling of this tick (off without phase stopping). */
static inline exec_ncoupling_t exec_num_phase_stop(const exec_config_t *cfg, const exec_state_t *st,
                                                   exec_nf_t f_c)
{
    exec_ncoupling_t c = {{FS_R(0.0), FS_R(0.0)}, 0u};
    if (cfg->phase_stop_gain_per_N2 > FS_R(0.0)) {
        c.c.phase_slowdown = dmp_phase_stop_factor(f_c - st->f_hat, cfg->phase_stop_gain_per_N2);
        c.on = 1u;
    }
    return c;
}

/** The coupling c with the phase also at the contact wait's rate. */
static inline exec_ncoupling_t exec_num_at_rate(exec_ncoupling_t c, exec_nrate_t rate)
{
    c.c.phase_slowdown = dmp_slowdown_at_rate(c.c.phase_slowdown, rate);
    c.on = 1u;
    return c;
}

/** The DMP's phase. */
static inline exec_nphase_t exec_num_phase(const exec_state_t *st)
{
    return st->dmp.u;
}

/** A discrete step's DMP step: f_dmp, p into path. */
static inline exec_nf_t exec_num_dmp_discrete(exec_state_t *st, const exec_step_t *s,
                                              const exec_ncoupling_t *c)
{
    const dmp_coupling_t *cp = (c->on != 0u) ? &c->c : 0;
    if (s->skill->dmp.has_y == 0u) { /* dmp_step_xy's own path for it, without its call */
        st->path = FS_R(0.0);
        return dmp_step(&s->skill->dmp, &st->dmp, &st->n.run, cp);
    }
    return dmp_step_xy(&s->skill->dmp, &st->dmp, &st->n.run, cp, s->path_scale, &st->path);
}

/** The object model's forces ahead: none in the real layer (its model step is a few
 *  operations, and the M4F's EXECUTE median has no room for the call). */
static inline void exec_num_model_prepare(exec_state_t *st)
{
    (void)st;
}

/** The next discrete DMP step's blend computed now (dmp_prepare). */
static inline void exec_num_dmp_prepare(exec_state_t *st, const exec_step_t *s)
{
    dmp_prepare(&s->skill->dmp, &st->dmp);
}

/** A periodic step's DMP step: f_dmp, p into path. */
static inline exec_nf_t exec_num_dmp_periodic(exec_state_t *st, const exec_step_t *s,
                                              const exec_ncoupling_t *c)
{
    return dmp_periodic_step_xy(&s->skill->dmp, &st->dmp, &st->n.run, s->amplitude_scale,
                                (c->on != 0u) ? &c->c : 0, s->path_scale, &st->path);
}

/* The periodic path's ramp factor at x in [0, 1): smoothstep, its slope 0 at both ends. */
static inline fs_real_t exec_num_path_ramp(fs_real_t x)
{
    return x * x * (FS_R(3.0) - FS_R(2.0) * x);
}

/** The path ramped in at the phase (turns) of the first turn. */
static inline void exec_num_ramp_in(exec_state_t *st)
{
    st->path *= exec_num_path_ramp(st->dmp.u);
}

/** The path ramped out when the step's ticks left are within its last turn. */
static inline void exec_num_ramp_out(exec_state_t *st, uint32_t left)
{
    const fs_real_t u = (fs_real_t)left * st->n.path_ramp_inv;
    if (u < FS_R(1.0)) {
        st->path *= exec_num_path_ramp(u);
    }
}

/** A clock one tick on. */
static inline exec_nclock_t exec_num_clock_tick(exec_ndt_t dt, exec_nclock_t t)
{
    return t + dt;
}

/** The carry's share of f_hat: f_carry faded out (smoothstep) over EXEC_BLEND_S of the step. */
static inline exec_nf_t exec_num_carry(const exec_state_t *st)
{
    fs_real_t r = st->t_step / ((fs_real_t)EXEC_BLEND_S);
    if (r >= FS_R(1.0)) {
        return st->f_carry * FS_R(0.0);
    }
    return st->f_carry * (FS_R(1.0) - r * r * (FS_R(3.0) - FS_R(2.0) * r));
}

/** The release's f_hat: f_end ramped to 0 over SKILL_RELEASE_TIME_S (done at 0). */
static inline exec_nf_t exec_num_release(const exec_config_t *cfg, exec_state_t *st)
{
    st->t_end += cfg->pfc.dt_s;
    fs_real_t r = FS_R(1.0) - st->t_end / ((fs_real_t)SKILL_RELEASE_TIME_S);
    if (r <= FS_R(0.0)) {
        st->done = 1u;
        return FS_R(0.0);
    }
    return st->f_end * r;
}

/** The measured contact force and x position. */
static inline exec_nf_t exec_num_meas_force(const exec_meas_n_t *m)
{
    return m->force_contact_N;
}
static inline exec_nx_t exec_num_meas_x(const exec_meas_n_t *m)
{
    return m->pos_m[0];
}

/** True if a measurement is not finite: x - x is +0 for a finite x, NaN for inf and NaN, so
 *  the sum of those is 0 exactly when all are finite (one compare for five values). */
static inline bool exec_num_meas_bad(const exec_meas_n_t *meas)
{
    const fs_real_t z = (meas->pos_m[0] - meas->pos_m[0]) + (meas->pos_m[1] - meas->pos_m[1]) +
                        (meas->vel_mps[0] - meas->vel_mps[0]) +
                        (meas->vel_mps[1] - meas->vel_mps[1]) +
                        (meas->force_contact_N - meas->force_contact_N);
    return !(z == FS_R(0.0));
}

/** The static deformation under the first tick's contact force (object model, or f/k). */
static inline exec_nx_t exec_num_deformation(const exec_config_t *cfg, const exec_state_t *st,
                                             exec_nf_t f_c)
{
    if (cfg->use_model != 0u) {
        return exec_object_deformation(&cfg->object, f_c);
    }
    return (f_c > FS_R(0.0)) ? f_c / st->steps[st->step].skill->stiffness_Npm : FS_R(0.0);
}

/** The model-free reference's deformation f/k, 0 for f <= 0. */
static inline exec_nx_t exec_num_spring(const exec_state_t *st, exec_nf_t f)
{
    return (f > FS_R(0.0)) ? f / st->steps[st->step].skill->stiffness_Npm : FS_R(0.0);
}

/** The object model's acceleration pdd = (f_hat - d_v*pd - F(p))/m_v at the reference's state. */
static inline exec_nx_t exec_num_model_acc(const exec_config_t *cfg, const exec_state_t *st,
                                           exec_nf_t f_hat)
{
    const exec_object_t *o = &cfg->object;
    return (f_hat - o->d_v_Nspm * st->ref_pd - exec_object_force(o, st->ref_p)) / o->m_v_kg;
}

/** v + a*dt. */
static inline exec_nx_t exec_num_integrate(const exec_config_t *cfg, const exec_state_t *st,
                                           exec_nx_t v, exec_nx_t a)
{
    (void)st;
    return v + a * cfg->pfc.dt_s;
}

/** True if y holds (no difference to take): never tested here, the divisions cost less. */
static inline bool exec_num_y_holds(const exec_state_t *st, exec_ny_t y_d)
{
    (void)st;
    (void)y_d;
    return false;
}

/** Sums of positions. */
static inline exec_nx_t exec_num_x_add(exec_nx_t a, exec_nx_t b)
{
    return a + b;
}
static inline exec_ny_t exec_num_y_add(exec_ny_t a, exec_ny_t b)
{
    return a + b;
}

/** A difference over one tick: of x, of y, of y's velocity. */
static inline exec_nx_t exec_num_x_rate(exec_ndt_t dt, const exec_state_t *st, exec_nx_t dx)
{
    (void)st;
    return dx / dt;
}
static inline exec_nx_t exec_num_y_rate(exec_ndt_t dt, const exec_state_t *st, exec_ny_t dy)
{
    (void)st;
    return dy / dt;
}
static inline exec_nx_t exec_num_yd_rate(exec_ndt_t dt, const exec_state_t *st, exec_nx_t dv)
{
    (void)st;
    return dv / dt;
}

/** Values as the law takes them (the same here). */
static inline fs_real_t exec_num_law_x(exec_nx_t v)
{
    return v;
}
static inline fs_real_t exec_num_law_y(exec_ny_t v)
{
    return v;
}
static inline fs_real_t exec_num_law_ydd(exec_nx_t v)
{
    return v;
}
static inline fs_real_t exec_num_law_f(exec_nf_t f)
{
    return f;
}
/** f_hat within the layer's range (any here). */
static inline exec_nf_t exec_num_f_bound(exec_nf_t f)
{
    return f;
}

/** The references' f_hat, x_d and y_d into out. */
static inline void exec_num_out_refs(const exec_nref_t ref[PFC_AXES], exec_out_n_t *out)
{
    out->force_hat_N = ref[0].force_N;
    out->pos_ref_m = ref[0].pos_m;
    out->y_ref_m = ref[1].pos_m;
}

/** The law on the references and this tick's measurements: its commands into out. */
static inline void exec_num_law(const exec_config_t *cfg, exec_state_t *st,
                                const exec_nref_t ref[PFC_AXES], const exec_meas_n_t *meas,
                                exec_out_n_t *out)
{
    pfc_axis_meas_t m[PFC_AXES];
    m[0].pos_m = meas->pos_m[0];
    m[0].vel_mps = meas->vel_mps[0];
    m[0].force_N = meas->force_contact_N;
    m[1].pos_m = meas->pos_m[1];
    m[1].vel_mps = meas->vel_mps[1];
    m[1].force_N = FS_R(0.0);
    pfc_step(&cfg->pfc, &st->n.pfc, ref, m, out->force_cmd_N);
}

/** A tick without finite measurements: 0 N, the last f_hat and references. */
static inline void exec_num_out_held(const exec_state_t *st, exec_out_n_t *out)
{
    out->step = st->step;
    out->done = st->done;
    out->force_cmd_N[0] = FS_R(0.0);
    out->force_cmd_N[1] = FS_R(0.0);
    out->force_hat_N = st->f_hat;
    out->pos_ref_m = st->surface + st->ref_p;
    out->y_ref_m = st->y_ref;
}

/** FS_OK: real arithmetic does not saturate. */
static inline fs_status_t exec_num_status(exec_state_t *st)
{
    (void)st;
    return FS_OK;
}

/** A rate, a force of the state as fs_real_t. */
static inline fs_real_t exec_num_rate_real(exec_nrate_t r)
{
    return r;
}
static inline fs_real_t exec_num_f_real(exec_nf_t f)
{
    return f;
}

/** The estimator's layer part (none). */
static inline void exec_num_vel_init(exec_vel_t *v, fs_real_t dt_s)
{
    (void)dt_s;
    v->n.unused = 0u;
}

/* ---- the native API of the application's tick (the layer's units) ---- */

/** A native force (a command, f_hat) as fs_real_t. */
static inline fs_real_t exec_force_real(exec_nmeas_force_t f)
{
    return f;
}

/** A sensor's position or velocity (m, m/s) in the layer's units (here the same). */
static inline exec_nmeas_pos_t exec_meas_pos_n(fs_real_t v)
{
    return v;
}

/** The estimator on a native position: exec_vel_step at dt_s. */
static inline exec_nmeas_pos_t exec_vel_step_n(exec_vel_t *v, exec_nmeas_pos_t pos, fs_real_t dt_s)
{
    return exec_vel_step(v, pos, dt_s);
}

/** A sensor's force (N) in the layer's units (here the same). */
static inline exec_nmeas_force_t exec_meas_force_n(fs_real_t v)
{
    return v;
}

/* ---- the application's tick sample: the executor's and the safety layer's units ---- */

/** The tick's sample beyond the sensors (hal_sensors_t) and the velocity estimate: none, the
 *  real units are theirs. */
typedef struct {
    uint8_t unused;
} exec_sample_t;

/** Read the tick's sample: each axis's velocity estimate (exec_vel_step at dt_s) into vel_mps. */
static inline void exec_sample_read(exec_sample_t *s, const hal_sensors_t *sens,
                                    exec_vel_t vel[PFC_AXES], fs_real_t vel_mps[PFC_AXES],
                                    bool vel_real, fs_real_t dt_s)
{
    (void)s;
    (void)vel_real;
    /* both axes written out: no loop in the tick */
    vel_mps[0] = exec_vel_step(&vel[0], sens->pos_m[0], dt_s);
    vel_mps[1] = exec_vel_step(&vel[1], sens->pos_m[1], dt_s);
}

/** Axis a's measured position of the sample (m). */
static inline exec_nmeas_pos_t exec_sample_pos(const exec_sample_t *s, const hal_sensors_t *sens,
                                               unsigned a)
{
    (void)s;
    return sens->pos_m[a];
}

/** Axis a's velocity estimate of the sample (m/s). */
static inline exec_nmeas_pos_t exec_sample_vel(const exec_sample_t *s,
                                               const fs_real_t vel_mps[PFC_AXES], unsigned a)
{
    (void)s;
    return vel_mps[a];
}

/** Axis a's measured contact force of the sample (N). */
static inline exec_nmeas_force_t exec_sample_force(const exec_sample_t *s,
                                                   const hal_sensors_t *sens, unsigned a)
{
    (void)s;
    return sens->force_contact_N[a];
}

/** Keep the executor's commands as this tick's request: nothing (the caller's float request
 *  is it, exec_out_cmd_req). */
static inline void exec_sample_request(exec_sample_t *s, const exec_out_n_t *out)
{
    (void)s;
    (void)out;
}

/** Forget this tick's request: nothing kept. */
static inline void exec_sample_request_clear(exec_sample_t *s)
{
    (void)s;
}

/** Axis a's request in the safety layer's units: req_N. */
static inline exec_nmeas_force_t exec_sample_req(const exec_sample_t *s, fs_real_t req_N,
                                                 unsigned a)
{
    (void)s;
    (void)a;
    return req_N;
}

/** exec_tick on the sample: the sensors and the velocity estimate. */
static inline fs_status_t exec_tick_sample(const exec_config_t *cfg, exec_state_t *st,
                                           const exec_sample_t *s, const hal_sensors_t *sens,
                                           const fs_real_t vel_mps[PFC_AXES], exec_out_n_t *out)
{
    (void)s;
    exec_meas_t m;
    m.pos_m[0] = sens->pos_m[0];
    m.pos_m[1] = sens->pos_m[1];
    m.vel_mps[0] = vel_mps[0];
    m.vel_mps[1] = vel_mps[1];
    m.force_contact_N = sens->force_contact_N[0];
    return exec_tick(cfg, st, &m, out);
}

/** The output's f_hat in the layer's units (N). */
static inline exec_nmeas_force_t exec_out_force_hat(const exec_out_n_t *out)
{
    return out->force_hat_N;
}

/** Axis a's command as fs_real_t (the rendered drive's). */
static inline fs_real_t exec_out_cmd_real(const exec_out_n_t *out, unsigned a)
{
    return out->force_cmd_N[a];
}

/** Axis a's command as the caller's float request. */
static inline fs_real_t exec_out_cmd_req(const exec_out_n_t *out, unsigned a)
{
    return out->force_cmd_N[a];
}

/* ---- telemetry counts from the layer's units ---- */

/** A constant as an opaque register value on the M4F: GCC otherwise loads the conversions'
 *  scales and bounds from the literal pool at each of the tick's six. */
static inline fs_real_t exec_num_reg(fs_real_t k)
{
#if defined(__GNUC__) && defined(__arm__) && defined(__ARM_FP) && defined(FS_REAL_FLOAT)
    __asm__("" : "+t"(k));
#endif
    return k;
}

/** The counts' scales, their bounds hi (as reals) and 0.5, each once in a register. */
typedef struct {
    fs_real_t pos_scale, pos_hi, pos_y_hi, force_scale, force_hi, half;
} exec_counts_k_t;

/** The counts' constants (exec_*_counts): taken once before a frame's conversions. */
static inline exec_counts_k_t exec_counts_k(void)
{
    exec_counts_k_t k;
    k.pos_scale = exec_num_reg(FS_R(1e-6));
    k.pos_hi = exec_num_reg((fs_real_t)8388607);
    k.pos_y_hi = exec_num_reg((fs_real_t)4194303);
    k.force_scale = exec_num_reg(FS_R(0.01));
    k.force_hi = exec_num_reg((fs_real_t)32767);
    k.half = exec_num_reg(FS_R(0.5));
    return k;
}

/** v / scale in counts, clamped to lo..hi (lo = -hi - 1, hi_r = hi), rounded half away from
 *  zero; NaN and inf 0. Inline: a frame's conversions share their constants. */
static inline int32_t exec_num_counts(fs_real_t v, fs_real_t scale, fs_real_t hi_r, fs_real_t half,
                                      int32_t lo, int32_t hi)
{
    const fs_real_t r = v / scale;
    const fs_real_t a = fs_fabs(r);
    if (a < hi_r) { /* |r| < hi: in range (NaN fails), the usual value */
        /* |r| + 0.5 truncated, the sign put back: r -+ 0.5 truncated (rounding is symmetric) */
        const int32_t n = (int32_t)(a + half);
        return (r < FS_R(0.0)) ? -n : n;
    }
    return exec_counts_edge(v, r, lo, hi);
}

/** A position (m) in um, 24 bits. */
static inline int32_t exec_pos_counts(exec_counts_k_t k, exec_nmeas_pos_t v)
{
    return exec_num_counts(v, k.pos_scale, k.pos_hi, k.half, -8388608, 8388607);
}

/** A y position (m) in um, 23 bits (+-4.19 m, beyond the sensor's range). */
static inline int32_t exec_pos_y_counts(exec_counts_k_t k, exec_nmeas_pos_t v)
{
    return exec_num_counts(v, k.pos_scale, k.pos_y_hi, k.half, -4194304, 4194303);
}

/** A force (N) in 0.01 N, 16 bits. */
static inline int16_t exec_force_counts(exec_counts_k_t k, exec_nmeas_force_t v)
{
    return (int16_t)exec_num_counts(v, k.force_scale, k.force_hi, k.half, -32768, 32767);
}

/** A force given as fs_real_t in 0.01 N, 16 bits (exec_force_counts). */
static inline int16_t exec_force_counts_real(exec_counts_k_t k, fs_real_t v)
{
    return exec_force_counts(k, v);
}

/* ---- a skill prepared for the executor (the skill store's commit and load) ---- */

/** What the executor needs of a stored skill beyond the skill itself: nothing. */
typedef struct {
    uint8_t unused;
} exec_store_t;

/** Bytes of an exec_store_t a store copies with its skill: none. */
static inline uint32_t exec_store_size(void)
{
    return 0u;
}

/** The executor's model of a stored skill sk (exec_step_t.model_fx): the skill's own. */
static inline const exec_model_t *exec_store_model(const exec_store_t *store, const skill_t *sk)
{
    (void)store;
    return &sk->dmp;
}

/** A preparation in slices (a download's commit): the skill's own rollout (skchk_run). */
typedef struct {
    skchk_t check;
} exec_store_prep_t;

/** Stages of the preparation, each begun and run in slices: the rollout. */
static inline uint32_t exec_store_stages(void)
{
    return 1u;
}

/** Begin stage k of preparing sk into store under the limits (dt, the x force's and the y path's
 *  extent); the outcome is exec_store_status's once exec_store_run returned true. */
static inline void exec_store_begin(exec_store_prep_t *p, uint32_t k, const skill_t *sk,
                                    exec_store_t *store, fs_real_t dt_s, fs_real_t force_max_N,
                                    fs_real_t path_max_m)
{
    (void)k;
    (void)store;
    skchk_begin(&p->check, sk, dt_s, force_max_N);
    p->check.path_max_m = path_max_m;
}

/** Up to units more of stage k (rollout steps); true once it ended. */
static inline bool exec_store_run(exec_store_prep_t *p, uint32_t k, uint32_t units)
{
    (void)k;
    return skchk_run(&p->check, units);
}

/** Stage k's outcome (222/223/225: the rollout leaves the limits). */
static inline fs_status_t exec_store_status(const exec_store_prep_t *p, uint32_t k)
{
    (void)k;
    return p->check.status;
}

/** The prepared skill's peak |f_hat| (N) and its y path's extent (m) at goal scale 1. */
static inline fs_real_t exec_store_peak_N(const exec_store_prep_t *p)
{
    return p->check.peak_N;
}
static inline fs_real_t exec_store_path_m(const exec_store_prep_t *p)
{
    return p->check.path_peak_m;
}

/** Prepare sk into store at once without limits (a store's load): its parameters and rollout,
 *  *peak_N and *path_m its figures. */
static inline fs_status_t exec_store_check(const skill_t *sk, exec_store_t *store, fs_real_t dt_s,
                                           fs_real_t *peak_N, fs_real_t *path_m)
{
    (void)store;
    const fs_status_t st = skchk_params(sk);
    if (st != FS_OK) {
        return st;
    }
    skchk_t c;
    skchk_begin(&c, sk, dt_s, FS_R(1e30));
    c.path_max_m = FS_R(1e30);
    while (!skchk_run(&c, UINT32_MAX)) {
    }
    *peak_N = c.peak_N;
    *path_m = c.path_peak_m;
    return c.status;
}

#endif /* EXEC_NUM_REAL_API_H */

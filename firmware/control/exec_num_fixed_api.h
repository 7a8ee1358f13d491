/* The operations of the executor's fixed-point numeric layer (exec_num_fixed.h), over fs_exec.h's
 * types: integers only (Q formats of exec_num_fixed.h, fx.h's rounding and saturation), every
 * constant derived before the run by exec_prep_run (fs_exec_fixed.c). The real layer's
 * counterparts (exec_num_real_api.h) have the same names and meanings. Included at the end of
 * fs_exec.h. */
#ifndef EXEC_NUM_FIXED_API_H
#define EXEC_NUM_FIXED_API_H

#define EXEC_Q31_ONE ((int64_t)1 << 31)
#define EXEC_Q32_ONE ((uint64_t)1 << 32)
#define EXEC_NUM_RATE_ONE ((uint32_t)1 << 31)
#define EXEC_NUM_SUM_ONE ((uint64_t)1 << 31)

/** The phase coupling of a tick: the phase rate, Q1.31 (1 uncoupled). */
typedef uint32_t exec_ncoupling_t;
/** The tick's dt as the layer's operations take it: none (the constants hold it). */
typedef uint8_t exec_ndt_t;
static inline exec_ndt_t exec_num_dt(const exec_config_t *cfg)
{
    (void)cfg;
    return 0u;
}
/** A DMP's phase: its accumulator, turns Q.61. */
typedef int64_t exec_nphase_t;

/** Parts of exec_start_run's preparation of a run of n_steps: each step's (5) and the
 *  configuration's (6), a few software-double conversions each. */
uint32_t exec_prep_parts(uint8_t n_steps);

/** Part part of the preparation (3xx codes: a scale or gain that does not fit its Q format). */
fs_status_t exec_prep_run(const exec_config_t *cfg, exec_state_t *st, uint32_t part);

/** exec_vel_update in integers, at the dt given to exec_vel_init: position and velocity in
 *  Q8.24 (m, m/s), INT32_MIN for a value that is not finite (a sample that was not finite
 *  makes every later velocity not finite, as NaN does in exec_vel_update). */
int32_t exec_vel_update_q(exec_vel_t *v, int32_t pos_q24);

/** The estimator's integer part from alpha and dt (exec_vel_init). */
void exec_num_vel_init(exec_vel_t *v, fs_real_t dt_s);

/** FS_OK if the step names its fixed-point model. */
static inline fs_status_t exec_num_check_step(const exec_step_t *s)
{
    return (s->model_fx == 0) ? FS_ERR_NULL_ARG : FS_OK;
}

/** The law's state from zero and its configuration in fixed point (validated by exec_start:
 *  303 if it does not fit). */
static inline fs_status_t exec_num_law_reset(const exec_config_t *cfg, exec_state_t *st)
{
    pfcfx_reset(&st->n.pfc);
    return pfcfx_from_valid_config(&cfg->pfc, &st->n.pfc_cfg);
}

/** The positions a run starts from: converted by the preparation (here none yet). */
static inline void exec_num_start_positions(const exec_config_t *cfg, exec_state_t *st,
                                            fs_real_t y_hold_m)
{
    (void)cfg;
    (void)y_hold_m;
    st->ref_prev_pos = 0;
    st->surface = 0;
    st->y_hold = 0;
    st->y_ref = 0;
}

/** The running step's DMP from its starting state (what the preparation derived); its length. */
static inline uint32_t exec_num_begin_step(const exec_config_t *cfg, exec_state_t *st)
{
    (void)cfg;
    st->dmp = st->n.dmp_start[st->step];
    st->n.dmp_saturated = 0u;
    return st->n.step[st->step].ticks;
}

/** Step i's first force (the carry's reference). */
static inline exec_nf_t exec_num_start_force(const exec_state_t *st, uint8_t i)
{
    return st->n.step[i].start_force_q32;
}

/* The bound q[0] at point i, q[1] at i + 1 (N Q16.16) at fraction fr (Q.16) towards i + 1. */
static inline int64_t exec_num_band_point(const int32_t q[2], int64_t fr_q16)
{
    return q[0] + ((((int64_t)q[1] - q[0]) * fr_q16) >> 16);
}

/** The band's segment cache forgotten (a run's start). */
static inline void exec_num_band_reset(exec_state_t *st)
{
    st->n.band_seg = 0u;
}

/** The band's bounds at the step's normalised time (Q.32; a periodic skill's wraps every
 *  period), scaled as f_hat (c0 + k*b), N Q.32. */
static inline void exec_num_band_bounds(exec_state_t *st, const skill_t *sk, int periodic,
                                        exec_nf_t *lo, exec_nf_t *hi)
{
    const exec_step_q_t *sq = &st->n.step[st->step];
    uint64_t x = st->band_s;
    x = periodic ? (x & 0xFFFFFFFFu) : ((x > EXEC_Q32_ONE) ? EXEC_Q32_ONE : x);
    const uint64_t pos = x * (uint64_t)(sk->band_n - 1u);
    uint32_t i = (uint32_t)(pos >> 32);
    i = (i > (uint32_t)sk->band_n - 2u) ? (uint32_t)sk->band_n - 2u : i;
    const int64_t fr = (int64_t)((pos - ((uint64_t)i << 32)) >> 16);
    const uint32_t seg = ((uint32_t)st->step << 8) + i + 1u;
    int32_t *q = st->n.band_q;
    if (st->n.band_seg != seg) {
        st->n.band_seg = seg;
        q[0] = fx_from_float(sk->band_lo_N[i], 16u);
        q[1] = fx_from_float(sk->band_lo_N[i + 1u], 16u);
        q[2] = fx_from_float(sk->band_hi_N[i], 16u);
        q[3] = fx_from_float(sk->band_hi_N[i + 1u], 16u);
    }
    *lo = sq->band_c0_q32 + exec_num_band_point(&q[0], fr) * sq->band_k_q16;
    *hi = sq->band_c0_q32 + exec_num_band_point(&q[2], fr) * sq->band_k_q16;
}

/** An excursion d > 0 beyond a band of width w: the largest in widths (Q16.16) kept, one
 *  division (N Q16.16 over N Q16.16). */
static inline void exec_num_band_excursion(exec_state_t *st, exec_nf_t d, exec_nf_t w)
{
    const uint64_t w16 = (uint64_t)(w >> 16);
    const uint64_t d16 = (uint64_t)(d >> 16);
    if (d16 > ((w16 * st->band_max) >> 16)) {
        const uint64_t e = (w16 > 0u && d16 < ((uint64_t)1 << 47)) ? (d16 << 16) / w16 : UINT32_MAX;
        st->band_max = (e < UINT32_MAX) ? (uint32_t)e : UINT32_MAX;
    }
}

/** The band's normalised time one tick on, at the contact wait's rate. */
static inline exec_nturn_t exec_num_band_advance(const exec_state_t *st, int periodic)
{
    (void)periodic; /* wrapped where it is read */
    return st->band_s + (((uint64_t)st->n.step[st->step].ramp_inc_q32 * st->contact_rate) >> 31);
}

/** The largest excursion in thousandths of a band width, saturated at 65535. */
static inline uint16_t exec_num_band_milli(exec_nwidth_t w)
{
    const uint64_t m = ((uint64_t)w * 1000u + 32768u) >> 16;
    return (m < 65535u) ? (uint16_t)m : 65535u;
}

/** True if the running skill waits for contact. */
static inline int exec_num_contact_on(const exec_state_t *st, const skill_t *sk)
{
    (void)sk;
    return st->n.step[st->step].contact_wait != 0u;
}

/** The running skill's contact threshold. */
static inline exec_nf_t exec_num_contact_threshold(const exec_state_t *st, const skill_t *sk)
{
    (void)sk;
    return st->n.step[st->step].contact_threshold_q32;
}

/** The contact wait's next rate: towards 0 (lost) or 1 at the step's gain, within 0..1. */
static inline exec_nrate_t exec_num_contact_rate(const exec_config_t *cfg, const exec_state_t *st,
                                                 const skill_t *sk, uint8_t lost, exec_nf_t f_c)
{
    (void)cfg;
    (void)sk;
    (void)f_c;
    const int64_t target = (lost != 0u) ? 0 : EXEC_Q31_ONE;
    const int64_t r = (int64_t)st->contact_rate;
    const int64_t gain = (int64_t)st->n.step[st->step].contact_gain_q31;
    const int64_t nr = r + fx_rshift_round((target - r) * gain, 31u);
    return (uint32_t)((nr < 0) ? 0 : ((nr > EXEC_Q31_ONE) ? EXEC_Q31_ONE : nr));
}

/** The hold's sum plus a tick's held share (1 - rate): ticks Q.31. */
static inline exec_nsum_t exec_num_hold_add(const exec_config_t *cfg, exec_nsum_t hold,
                                            exec_nsum_t held)
{
    (void)cfg;
    return hold + held;
}

/** The hold in ms, rounded. */
static inline uint32_t exec_num_hold_ms(const exec_state_t *st)
{
    const uint64_t held = st->contact_hold;
    const int64_t ms = fx_scale_apply((held > (uint64_t)FX_S61_MAX) ? FX_S61_MAX : (int64_t)held,
                                      st->n.c.hold_ms);
    return (ms < (int64_t)UINT32_MAX) ? (uint32_t)ms : UINT32_MAX;
}

/* 1/(1 + x) in Q1.31 for x >= 0 in Q.24: one 64/32 division of 32-bit divides. */
static inline uint32_t exec_num_rate_q31(uint64_t x_q24)
{
    const uint64_t den = x_q24 + ((uint64_t)1 << 24);
    if (den < EXEC_Q32_ONE) {
        return fx_udiv64_32_round((uint64_t)1 << 55, (uint32_t)den);
    }
    const uint64_t den8 = (den >> 16 < EXEC_Q32_ONE) ? den >> 16 : EXEC_Q32_ONE - 1u;
    return fx_udiv64_32_round((uint64_t)1 << 39, (uint32_t)den8);
}

/* N Q.32 -> Q16.16, saturated. */
static inline int32_t exec_num_q16(int64_t f_q32)
{
    return fx_sat32(fx_rshift_round(fx_clamp61(f_q32), 16u));
}

/* Q.(24 + sh) -> Q8.24, saturated. */
static inline int32_t exec_num_q24(int64_t v, unsigned sh)
{
    return fx_sat32(fx_rshift_round(fx_clamp61(v), sh));
}

/* exec_num_q24 of a value already within +-FX_S61_MAX (clamped or scaled): no clamp. */
static inline int32_t exec_num_q24_bounded(int64_t v, unsigned sh)
{
    return fx_sat32(fx_rshift_round(v, sh));
}

/** The phase-stop rate 1/(1 + g*(f_c - f_hat)^2) (1 without phase stopping). */
static inline exec_ncoupling_t exec_num_phase_stop(const exec_config_t *cfg, const exec_state_t *st,
                                                   exec_nf_t f_c)
{
    (void)cfg;
    if (st->n.c.phase_stop == 0u) {
        return EXEC_NUM_RATE_ONE;
    }
    const int64_t e = exec_num_q16(f_c - st->f_hat);
    const int64_t x = fx_scale_apply(e * e, st->n.c.stop_gain); /* e^2 N^2 Q.32 -> Q.24 */
    return exec_num_rate_q31((uint64_t)((x > 0) ? x : 0));
}

/** The coupling c with the phase also at the contact wait's rate. */
static inline exec_ncoupling_t exec_num_at_rate(exec_ncoupling_t c, exec_nrate_t rate)
{
    return (uint32_t)fx_rshift_round((int64_t)c * rate, 31u);
}

/** The DMP's phase. */
static inline exec_nphase_t exec_num_phase(const exec_state_t *st)
{
    return st->dmp.u_acc;
}

/* f_dmp from the accumulator, saturation of this step noted (sat_events before it: ev). */
static inline exec_nf_t exec_num_dmp_force(exec_state_t *st, uint32_t ev)
{
    const exec_step_q_t *sq = &st->n.step[st->step];
    st->n.dmp_saturated = (st->dmp.sat_events != ev) ? 1u : 0u;
    return sq->force0_q32 + fx_rshift_round_var(st->dmp.y_acc, sq->y_shift);
}

/** A discrete step's DMP step: f_dmp (N Q.32), p into path (the accumulator's Q.55). */
static inline exec_nf_t exec_num_dmp_discrete(exec_state_t *st, const exec_step_t *s,
                                              const exec_ncoupling_t *c)
{
    const dmpfx_coupling_t cq = {0, *c};
    const uint32_t ev = st->dmp.sat_events;
    (void)dmpfx_step_xy(s->model_fx, &st->n.run[st->step], &st->dmp, &cq, 0);
    st->path = st->dmp.path_acc;
    return exec_num_dmp_force(st, ev);
}

/** The next discrete DMP step's blend computed now (dmpfx_prepare). */
static inline void exec_num_dmp_prepare(exec_state_t *st, const exec_step_t *s)
{
    dmpfx_prepare(s->model_fx, &st->dmp);
}

/** A periodic step's DMP step: f_dmp (N Q.32), p into path (its base s_p*g_y added). */
static inline exec_nf_t exec_num_dmp_periodic(exec_state_t *st, const exec_step_t *s,
                                              const exec_ncoupling_t *c)
{
    const dmpfx_coupling_t cq = {0, *c};
    const uint32_t ev = st->dmp.sat_events;
    (void)dmpfx_periodic_step_xy(s->model_fx, &st->n.run[st->step], &st->dmp, &cq, 0);
    st->path = (s->model_fx->has_y != 0u) ? st->n.step[st->step].path0_q55 + st->dmp.path_acc : 0;
    return exec_num_dmp_force(st, ev);
}

/* The periodic path's ramp factor: smoothstep of x in [0, 1) Q.30, Q1.31. */
static inline uint32_t exec_num_path_ramp(int64_t x_q30)
{
    const int64_t x2 = fx_rshift_round(x_q30 * x_q30, 30u);
    const int64_t s = fx_rshift_round(x2 * (((int64_t)3 << 30) - 2 * x_q30), 30u);
    return (uint32_t)(s * 2);
}

/** The path ramped in at the phase (turns) of the first turn. */
static inline void exec_num_ramp_in(exec_state_t *st)
{
    st->path = fx_mul64_u32(fx_clamp61(st->path), exec_num_path_ramp(st->dmp.u_acc >> 31), 31u);
}

/** The path ramped out when the step's ticks left are within its last turn. */
static inline void exec_num_ramp_out(exec_state_t *st, uint32_t left)
{
    const uint64_t u = (uint64_t)left * st->n.step[st->step].ramp_inc_q32;
    if (u < EXEC_Q32_ONE) {
        st->path = fx_mul64_u32(fx_clamp61(st->path), exec_num_path_ramp((int64_t)(u >> 2)), 31u);
    }
}

/** A clock one tick on. */
static inline exec_nclock_t exec_num_clock_tick(exec_ndt_t dt, exec_nclock_t t)
{
    (void)dt;
    return t + 1u;
}

/** The carry's share of f_hat: f_carry faded out (smoothstep, Q1.31) over EXEC_BLEND_S. */
static inline exec_nf_t exec_num_carry(const exec_state_t *st)
{
    const uint64_t r32 = (uint64_t)st->t_step * st->n.c.blend_inc_q32;
    int64_t b = 0;
    if (r32 < EXEC_Q32_ONE) {
        const int64_t r = (int64_t)(r32 >> 2); /* Q.30 */
        const int64_t r2 = fx_rshift_round(r * r, 30u);
        const int64_t s = fx_rshift_round(r2 * (((int64_t)3 << 30) - 2 * r), 30u);
        b = (((int64_t)1 << 30) - s) * 2;
    }
    return fx_mul64_u32(fx_clamp61(st->f_carry), (uint32_t)b, 31u);
}

/** The release's f_hat: f_end ramped to 0 over SKILL_RELEASE_TIME_S (done at 0). */
static inline exec_nf_t exec_num_release(const exec_config_t *cfg, exec_state_t *st)
{
    (void)cfg;
    st->t_end += (st->t_end < EXEC_TICKS_MAX) ? 1u : 0u;
    const uint64_t t = (uint64_t)st->t_end * st->n.c.release_inc_q32;
    if (t >= EXEC_Q32_ONE) {
        st->done = 1u;
        return 0;
    }
    return fx_mul64_u32(st->f_end, (uint32_t)((EXEC_Q32_ONE - t) >> 1), 31u);
}

/** The measured contact force (N Q.32) and x position (Q.48). */
static inline exec_nf_t exec_num_meas_force(const exec_meas_n_t *m)
{
    return (int64_t)m->force_contact_q16 * ((int64_t)1 << 16);
}
static inline exec_nx_t exec_num_meas_x(const exec_meas_n_t *m)
{
    return (int64_t)m->pos_q24[0] * ((int64_t)1 << 24);
}

/** True if any measurement is INT32_MIN (not finite). */
static inline bool exec_num_meas_bad(const exec_meas_n_t *m)
{
    return m->pos_q24[0] == INT32_MIN || m->pos_q24[1] == INT32_MIN || m->vel_q24[0] == INT32_MIN ||
           m->vel_q24[1] == INT32_MIN || m->force_contact_q16 == INT32_MIN;
}

/** The static deformation under the first tick's contact force (object model, or f/k). */
static inline exec_nx_t exec_num_deformation(const exec_config_t *cfg, const exec_state_t *st,
                                             exec_nf_t f_c)
{
    const exec_cfg_q_t *c = &st->n.c;
    if (!(f_c > 0)) {
        return 0;
    }
    if (cfg->use_model != 0u) {
        return (f_c <= c->f_layer_q32)
                   ? fx_scale_apply(f_c, c->inv_k1)
                   : c->layer_q48 + fx_scale_apply(f_c - c->f_layer_q32, c->inv_k2);
    }
    return fx_scale_apply(f_c, st->n.step[st->step].inv_k);
}

/** The model-free reference's deformation f/k, 0 for f <= 0. */
static inline exec_nx_t exec_num_spring(const exec_state_t *st, exec_nf_t f)
{
    return (f > 0) ? fx_scale_apply(f, st->n.step[st->step].inv_k) : 0;
}

/** The object model's acceleration pdd = (f_hat - d_v*pd - F(p))/m_v at the reference's state. */
/* The object model's spring force at deformation p (N Q.32): two layers, none when p <= 0. */
static inline int64_t exec_num_spring_q(const exec_cfg_q_t *c, int64_t p)
{
    return (p <= 0)              ? 0
           : (p <= c->layer_q48) ? fx_scale_apply(p, c->k1)
                                 : c->f_layer_q32 + fx_scale_apply(p - c->layer_q48, c->k2);
}

static inline exec_nx_t exec_num_model_acc(const exec_config_t *cfg, const exec_state_t *st,
                                           exec_nf_t f_hat)
{
    (void)cfg;
    const exec_num_t *n = &st->n;
    const int64_t p = st->ref_p;
    const int64_t pd = st->ref_pd;
    /* the forces of the last tick's p and pd, if exec_num_model_prepare computed them after
     * its write (the same values) */
    const bool pre = n->pre_ok != 0u && n->pre_p == p && n->pre_pd == pd;
    const int64_t damp = pre ? n->pre_damp : fx_scale_apply(pd, n->c.d_v);
    const int64_t spring = pre ? n->pre_spring : exec_num_spring_q(&n->c, p);
    return fx_scale_apply(f_hat - damp - spring, n->c.inv_m);
}

/** The object model's damping and spring forces at the reference's present p and pd, for the
 *  next tick's exec_num_model_acc (after a tick's write: off the path to the actuator). */
static inline void exec_num_model_prepare(exec_state_t *st)
{
    exec_num_t *n = &st->n;
    if (n->c.use_model == 0u) {
        return;
    }
    n->pre_p = st->ref_p;
    n->pre_pd = st->ref_pd;
    n->pre_damp = fx_scale_apply(st->ref_pd, n->c.d_v);
    n->pre_spring = exec_num_spring_q(&n->c, st->ref_p);
    n->pre_ok = 1u;
}

/** v + a*dt, clamped. */
static inline exec_nx_t exec_num_integrate(const exec_config_t *cfg, const exec_state_t *st,
                                           exec_nx_t v, exec_nx_t a)
{
    (void)cfg;
    return fx_clamp61(v + fx_scale_apply(a, st->n.c.dt));
}

/** True if y holds (no y DMP, or a path at rest): its two scalings skipped. */
static inline bool exec_num_y_holds(const exec_state_t *st, exec_ny_t y_d)
{
    return y_d == st->y_ref && st->y_ref_vel == 0;
}

/** Sums of positions, clamped. */
static inline exec_nx_t exec_num_x_add(exec_nx_t a, exec_nx_t b)
{
    return fx_clamp61(a + b);
}
static inline exec_ny_t exec_num_y_add(exec_ny_t a, exec_ny_t b)
{
    return fx_clamp61(a + b);
}

/** A difference over one tick: of x (Q.48 -> Q.48), of y (Q.55 -> Q.48), of y's velocity
 *  (Q.48 -> Q.40). */
static inline exec_nx_t exec_num_x_rate(exec_ndt_t dt, const exec_state_t *st, exec_nx_t dx)
{
    (void)dt;
    return fx_scale_apply(dx, st->n.c.inv_dt_x);
}
static inline exec_nx_t exec_num_y_rate(exec_ndt_t dt, const exec_state_t *st, exec_ny_t dy)
{
    (void)dt;
    return fx_scale_apply(dy, st->n.c.inv_dt_y);
}
static inline exec_nx_t exec_num_yd_rate(exec_ndt_t dt, const exec_state_t *st, exec_nx_t dv)
{
    (void)dt;
    return fx_scale_apply(dv, st->n.c.inv_dt_yd);
}

/** Values as the law takes them: x's Q.48 and y's acceleration Q.40 in Q8.24, y Q.55 in Q8.24,
 *  a force N Q.32 in Q16.16 (all within +-FX_S61_MAX: clamped or scaled). */
static inline int32_t exec_num_law_x(exec_nx_t v)
{
    return exec_num_q24_bounded(v, 24u);
}
static inline int32_t exec_num_law_y(exec_ny_t v)
{
    return exec_num_q24_bounded(v, 31u);
}
static inline int32_t exec_num_law_ydd(exec_nx_t v)
{
    return exec_num_q24_bounded(v, 16u);
}
static inline int32_t exec_num_law_f(exec_nf_t f)
{
    return exec_num_q24_bounded(f, 16u);
}
/** f_hat within +-FX_S61_MAX. */
static inline exec_nf_t exec_num_f_bound(exec_nf_t f)
{
    return fx_clamp61(f);
}

/** The references' f_hat, x_d and y_d into out. */
static inline void exec_num_out_refs(const exec_nref_t ref[PFC_AXES], exec_out_n_t *out)
{
    out->force_hat_q16 = ref[0].force_N;
    out->pos_ref_q24 = ref[0].pos_m;
    out->y_ref_q24 = ref[1].pos_m;
}

/** The law on the references and this tick's measurements: its commands into out. */
static inline void exec_num_law(const exec_config_t *cfg, exec_state_t *st,
                                const exec_nref_t ref[PFC_AXES], const exec_meas_n_t *meas,
                                exec_out_n_t *out)
{
    (void)cfg;
    pfcfx_meas_t mq[PFC_AXES];
    for (uint32_t a = 0u; a < PFC_AXES; a++) {
        mq[a].pos_m = meas->pos_q24[a];
        mq[a].vel_mps = meas->vel_q24[a];
    }
    mq[0].force_N = meas->force_contact_q16;
    mq[1].force_N = 0;
    pfcfx_step(&st->n.pfc_cfg, &st->n.pfc, ref, mq, out->force_cmd_q16);
}

/** A tick without finite measurements: 0 N, the last f_hat and references. */
static inline void exec_num_out_held(const exec_state_t *st, exec_out_n_t *out)
{
    out->step = st->step;
    out->done = st->done;
    out->force_cmd_q16[0] = 0;
    out->force_cmd_q16[1] = 0;
    out->force_hat_q16 = exec_num_q16(st->f_hat);
    out->pos_ref_q24 = exec_num_q24(st->surface + st->ref_p, 24u);
    out->y_ref_q24 = exec_num_q24(st->y_ref, 31u);
}

/** FS_OK, or FS_ERR_FIXED_OVERFLOW when this tick's DMP step saturated. */
static inline fs_status_t exec_num_status(exec_state_t *st)
{
    const uint8_t saturated = st->n.dmp_saturated;
    st->n.dmp_saturated = 0u;
    return (saturated != 0u) ? FS_ERR_FIXED_OVERFLOW : FS_OK;
}

/** A rate, a force of the state as fs_real_t (software float on the M3: not in the tick). */
static inline fs_real_t exec_num_rate_real(exec_nrate_t r)
{
    return fx_to_float((int32_t)(r >> 1), 30u);
}
static inline fs_real_t exec_num_f_real(exec_nf_t f)
{
    return fx_to_float(exec_num_q16(f), 16u);
}

/* ---- the native API of the application's tick (the layer's units) ---- */

/** A native force (a command, f_hat; N Q16.16) as fs_real_t (software float on the M3). */
static inline fs_real_t exec_force_real(exec_nmeas_force_t f)
{
    return fx_to_float(f, 16u);
}

/** A sensor value in Q(frac), integer operations only: NaN or infinite -> INT32_MIN (not
 *  finite for the executor and the safety layer), finite values saturated to +-INT32_MAX. */
static inline int32_t exec_num_q_of_real(fs_real_t v, unsigned frac)
{
    uint32_t b;
    memcpy(&b, &v, sizeof b);
    if ((b & 0x7F800000u) == 0x7F800000u) {
        return INT32_MIN;
    }
    const int32_t q = fx_from_float(v, frac);
    return (q == INT32_MIN) ? INT32_MIN + 1 : q;
}

/** A sensor's position or velocity (m, m/s) in Q8.24 (exec_num_q_of_real). */
static inline exec_nmeas_pos_t exec_meas_pos_n(fs_real_t v)
{
    return exec_num_q_of_real(v, 24u);
}

/** A sensor's force (N) in Q16.16 (exec_num_q_of_real). */
static inline exec_nmeas_force_t exec_meas_force_n(fs_real_t v)
{
    return exec_num_q_of_real(v, 16u);
}

/** The estimator on a native position: exec_vel_update_q (dt as given to exec_vel_init). */
static inline exec_nmeas_pos_t exec_vel_step_n(exec_vel_t *v, exec_nmeas_pos_t pos, fs_real_t dt_s)
{
    (void)dt_s;
    return exec_vel_update_q(v, pos);
}

/* ---- the application's tick sample: the executor's and the safety layer's units ---- */

/** The tick's sensors in the integer tick's formats (INT32_MIN: not finite), converted once a
 *  tick, and this tick's request in Q16.16 (else the caller's float request is converted). */
typedef struct {
    exec_meas_q_t meas;               /* the executor's measurements */
    exec_nmeas_force_t force_y;       /* the y axis's measured force */
    exec_nmeas_force_t req[PFC_AXES]; /* the executor's command, when req_set */
    uint8_t req_set;                  /* req holds this tick's request */
} exec_sample_t;

/** Read the tick's sample from the sensors and run the velocity estimate (integers); vel_mps
 *  gets it as fs_real_t only if vel_real (the rendered drive computes in float). */
static inline void exec_sample_read(exec_sample_t *s, const hal_sensors_t *sens,
                                    exec_vel_t vel[PFC_AXES], fs_real_t vel_mps[PFC_AXES],
                                    bool vel_real, fs_real_t dt_s)
{
    (void)dt_s;
    for (unsigned a = 0; a < PFC_AXES; a++) {
        s->meas.pos_q24[a] = exec_meas_pos_n(sens->pos_m[a]);
        s->meas.vel_q24[a] = exec_vel_update_q(&vel[a], s->meas.pos_q24[a]);
        if (vel_real) {
            vel_mps[a] = fx_to_float(s->meas.vel_q24[a], 24u);
        }
    }
    s->meas.force_contact_q16 = exec_meas_force_n(sens->force_contact_N[0]);
    s->force_y = exec_meas_force_n(sens->force_contact_N[1]);
    s->req_set = 0u;
}

/** Axis a's measured position of the sample (m, Q8.24). */
static inline exec_nmeas_pos_t exec_sample_pos(const exec_sample_t *s, const hal_sensors_t *sens,
                                               unsigned a)
{
    (void)sens;
    return s->meas.pos_q24[a];
}

/** Axis a's velocity estimate of the sample (m/s, Q8.24). */
static inline exec_nmeas_pos_t exec_sample_vel(const exec_sample_t *s,
                                               const fs_real_t vel_mps[PFC_AXES], unsigned a)
{
    (void)vel_mps;
    return s->meas.vel_q24[a];
}

/** Axis a's measured contact force of the sample (N, Q16.16). */
static inline exec_nmeas_force_t exec_sample_force(const exec_sample_t *s,
                                                   const hal_sensors_t *sens, unsigned a)
{
    (void)sens;
    return (a == 0u) ? s->meas.force_contact_q16 : s->force_y;
}

/** Keep the executor's commands as this tick's request (no conversion). */
static inline void exec_sample_request(exec_sample_t *s, const exec_out_n_t *out)
{
    s->req[0] = out->force_cmd_q16[0];
    s->req[1] = out->force_cmd_q16[1];
    s->req_set = 1u;
}

/** Forget this tick's request: req_N (the caller's) is the request again. */
static inline void exec_sample_request_clear(exec_sample_t *s)
{
    s->req_set = 0u;
}

/** Axis a's request in the safety layer's units: the kept one, else req_N (0 stays 0). */
static inline exec_nmeas_force_t exec_sample_req(const exec_sample_t *s, fs_real_t req_N,
                                                 unsigned a)
{
    return (s->req_set != 0u) ? s->req[a] : (req_N == FS_R(0.0)) ? 0 : exec_meas_force_n(req_N);
}

/** exec_tick_n on the sample (integers only). */
static inline fs_status_t exec_tick_sample(const exec_config_t *cfg, exec_state_t *st,
                                           const exec_sample_t *s, const hal_sensors_t *sens,
                                           const fs_real_t vel_mps[PFC_AXES], exec_out_n_t *out)
{
    (void)sens;
    (void)vel_mps;
    return exec_tick_q(cfg, st, &s->meas, out);
}

/** The output's f_hat in the layer's units (N, Q16.16). */
static inline exec_nmeas_force_t exec_out_force_hat(const exec_out_n_t *out)
{
    return out->force_hat_q16;
}

/** Axis a's command as fs_real_t, for the rendered drive (software float on the M3). */
static inline fs_real_t exec_out_cmd_real(const exec_out_n_t *out, unsigned a)
{
    return fx_to_float(out->force_cmd_q16[a], 16u);
}

/** Axis a's command as the caller's float request: 0 (the request is the sample's,
 *  exec_sample_request). */
static inline fs_real_t exec_out_cmd_req(const exec_out_n_t *out, unsigned a)
{
    (void)out;
    (void)a;
    return FS_R(0.0);
}

/* ---- telemetry counts from the layer's units ---- */

/** The counts' constants: none (integer operations). */
typedef struct {
    uint8_t unused;
} exec_counts_k_t;

/** The counts' constants (exec_*_counts). */
static inline exec_counts_k_t exec_counts_k(void)
{
    exec_counts_k_t k;
    k.unused = 0u;
    return k;
}

/** q in Q(frac) in counts of 1/per_unit, clamped to lo..hi, rounded half away from zero as the
 *  float path rounds; INT32_MIN (not finite) -> 0 as NaN there. Integer operations only. */
static inline int32_t exec_num_q_counts(int32_t q, unsigned frac, int64_t per_unit, int32_t lo,
                                        int32_t hi)
{
    if (q == INT32_MIN) {
        return 0;
    }
    const int64_t mag = (q < 0) ? -(int64_t)q : (int64_t)q;
    int64_t c = (mag * per_unit + ((int64_t)1 << (frac - 1u))) >> frac;
    c = (q < 0) ? -c : c;
    return (c > (int64_t)hi) ? hi : ((c < (int64_t)lo) ? lo : (int32_t)c);
}

/** A position (Q8.24) in um, 24 bits. */
static inline int32_t exec_pos_counts(exec_counts_k_t k, exec_nmeas_pos_t v)
{
    (void)k;
    return exec_num_q_counts(v, 24u, 1000000, -8388608, 8388607);
}

/** A y position (Q8.24) in um, 23 bits. */
static inline int32_t exec_pos_y_counts(exec_counts_k_t k, exec_nmeas_pos_t v)
{
    (void)k;
    return exec_num_q_counts(v, 24u, 1000000, -4194304, 4194303);
}

/** A force (Q16.16) in 0.01 N, 16 bits. */
static inline int16_t exec_force_counts(exec_counts_k_t k, exec_nmeas_force_t v)
{
    (void)k;
    return (int16_t)exec_num_q_counts(v, 16u, 100, -32768, 32767);
}

/** A force given as fs_real_t in 0.01 N, 16 bits (its bits read: no float operation; NaN and
 *  inf 0). */
static inline int16_t exec_force_counts_real(exec_counts_k_t k, fs_real_t v)
{
    uint32_t b;
    memcpy(&b, &v, sizeof b);
    if ((b & 0x7F800000u) == 0x7F800000u) {
        return 0;
    }
    const int32_t q = fx_from_float(v, 16u);
    return exec_force_counts(k, (q == INT32_MIN) ? INT32_MIN + 1 : q);
}

/* ---- a skill prepared for the executor (the skill store's commit and load) ---- */

/** What the executor needs of a stored skill beyond the skill itself: its model in fixed
 *  point. */
typedef dmpfx_model_t exec_store_t;

/** Bytes of an exec_store_t a store copies with its skill. */
static inline uint32_t exec_store_size(void)
{
    return (uint32_t)sizeof(exec_store_t);
}

/** The executor's model of a stored skill (exec_step_t.model_fx): the converted one. */
static inline const exec_model_t *exec_store_model(const exec_store_t *store, const skill_t *sk)
{
    (void)sk;
    return store;
}

/** A preparation in slices (a download's commit): the conversion, then the converted model's
 *  rollout (the one the executor will run). */
typedef struct {
    dmpfx_conv_t conv;
    dmpfx_check_t check;
} exec_store_prep_t;

/** Stages of the preparation, each begun and run in slices: the conversion, the rollout. */
static inline uint32_t exec_store_stages(void)
{
    return 2u;
}

/** Begin stage k of preparing sk into store under the limits (dt, the x force's and the y path's
 *  extent); the outcome is exec_store_status's once exec_store_run returned true. */
static inline void exec_store_begin(exec_store_prep_t *p, uint32_t k, const skill_t *sk,
                                    exec_store_t *store, fs_real_t dt_s, fs_real_t force_max_N,
                                    fs_real_t path_max_m)
{
    if (k == 0u) {
        dmpfx_bound_begin(&p->conv, &sk->dmp, store);
    } else {
        dmpfx_check_begin(&p->check, store, sk->dmp.duration_s, dt_s, force_max_N, path_max_m);
    }
}

/** Up to units more of stage k (conversion units, rollout steps); true once it ended. */
static inline bool exec_store_run(exec_store_prep_t *p, uint32_t k, uint32_t units)
{
    return (k == 0u) ? dmpfx_bound_run(&p->conv, units) : dmpfx_check_run(&p->check, units);
}

/** Stage k's outcome (3xx: the skill does not fit the fixed-point executor; 223/225/300: the
 *  rollout leaves the limits or saturates). */
static inline fs_status_t exec_store_status(const exec_store_prep_t *p, uint32_t k)
{
    return (k == 0u) ? p->conv.status : p->check.status;
}

/** The prepared skill's peak |f_hat| (N) and its y path's extent (m) at goal scale 1. */
static inline fs_real_t exec_store_peak_N(const exec_store_prep_t *p)
{
    return dmpfx_check_peak_N(&p->check);
}
static inline fs_real_t exec_store_path_m(const exec_store_prep_t *p)
{
    return dmpfx_check_path_m(&p->check);
}

/** Prepare sk into store at once without limits (a store's load): its parameters, the
 *  conversion and the converted model's rollout, *peak_N and *path_m its figures. */
static inline fs_status_t exec_store_check(const skill_t *sk, exec_store_t *store, fs_real_t dt_s,
                                           fs_real_t *peak_N, fs_real_t *path_m)
{
    fs_status_t st = skchk_params(sk);
    if (st == FS_OK) {
        st = dmpfx_from_model_bound(&sk->dmp, store);
    }
    if (st != FS_OK) {
        return st;
    }
    dmpfx_check_t c;
    dmpfx_check_begin(&c, store, sk->dmp.duration_s, dt_s, FS_R(1e30), FS_R(1e30));
    while (!dmpfx_check_run(&c, UINT32_MAX)) {
    }
    *peak_N = dmpfx_check_peak_N(&c);
    *path_m = dmpfx_check_path_m(&c);
    return c.status;
}

#endif /* EXEC_NUM_FIXED_API_H */

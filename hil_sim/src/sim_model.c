/* HIL models: see sim_model.h and docs/hil.md. */
#include "sim_model.h"

#include <math.h>
#include <stddef.h>

/* Below this speed (m/s) an axis with Coulomb friction may stick. */
#define SIM_STICK_VEL_MPS 1e-6

double sim_smoothstep(double r)
{
    if (r <= 0.0) {
        return 0.0;
    }
    if (r >= 1.0) {
        return 1.0;
    }
    return r * r * (3.0 - 2.0 * r);
}

double sim_object_spring_N(const sim_object_t *o, double p_m)
{
    if (p_m <= 0.0) {
        return 0.0;
    }
    if (p_m <= o->layer_depth_m) {
        return o->k1_Npm * p_m;
    }
    return o->k1_Npm * o->layer_depth_m + o->k2_Npm * (p_m - o->layer_depth_m);
}

static double sgn(double v)
{
    return (v > 0.0) ? 1.0 : ((v < 0.0) ? -1.0 : 0.0);
}

void sim_drive_prepare(sim_drive_t *d)
{
    d->inv_mass = 1.0 / d->mass_kg;
    d->inv_mass_contact = 1.0 / (d->mass_kg + ((d->object != NULL) ? d->object->m_v_kg : 0.0));
}

void sim_axis_substep(sim_axis_t *a, const sim_drive_t *d, double dt_s)
{
    const sim_object_t *o = d->object;
    const double v0 = a->vel_mps;
    const double p = (o != NULL) ? a->pos_m - o->surface_m : 0.0;
    const int touching = (o != NULL) && (p > 0.0);
    /* contact force without the object's inertia */
    const double skin = (!touching || p >= o->skin_m) ? 1.0 : p / o->skin_m;
    const double c = touching ? skin * o->d_v_Nspm * v0 + sim_object_spring_N(o, p) : 0.0;
    const double mv = touching ? skin * o->m_v_kg : 0.0;
    double acc;
    double contact;
    double coulomb = (d->friction_N > 0.0) ? d->friction_N : 0.0;

    if (d->prescribed) {
        double fric = 0.0;
        if (coulomb > 0.0) {
            if (fabs(v0) > SIM_STICK_VEL_MPS) {
                fric = -coulomb * sgn(v0);
            } else {
                fric = (fabs(d->force_cmd_N) <= coulomb) ? -d->force_cmd_N
                                                         : -coulomb * sgn(d->force_cmd_N);
            }
        }
        acc = (d->force_cmd_N + fric) * d->inv_mass;
        contact = touching ? mv * acc + c : 0.0;
        if (contact < 0.0) {
            contact = 0.0;
        }
    } else {
        double drive = d->force_ext_N - d->hand_damping_Nspm * v0;
        if (d->kind == SIM_PLANT_REALISTIC) {
            double u = d->force_cmd_N;
            if (!(u == u)) {
                u = 0.0; /* an actuator driver rejects a NaN command */
            }
            if (u > d->act_limit_N) {
                u = d->act_limit_N;
            } else if (u < -d->act_limit_N) {
                u = -d->act_limit_N;
            }
            a->act_N += d->act_alpha * (u - a->act_N);
            drive += a->act_N - d->carriage->viscous_Nspm * v0;
            coulomb += d->carriage->coulomb_N;
        } else {
            drive += d->force_cmd_N;
        }
        double fric = 0.0;
        if (coulomb > 0.0) {
            if (fabs(v0) > SIM_STICK_VEL_MPS) {
                fric = -coulomb * sgn(v0);
            } else {
                const double f_try = drive - (c > 0.0 ? c : 0.0);
                fric = (fabs(f_try) <= coulomb) ? -f_try : -coulomb * sgn(f_try);
            }
        }
        contact = 0.0;
        acc = (drive + fric) * d->inv_mass;
        if (touching) {
            const double acc_c = (skin == 1.0) ? (drive + fric - c) * d->inv_mass_contact
                                               : (drive + fric - c) / (d->mass_kg + mv);
            const double f_c = mv * acc_c + c;
            if (f_c > 0.0) { /* same sign as the free-motion force: no chattering */
                acc = acc_c;
                contact = f_c;
            }
        }
    }
    double v = v0 + acc * dt_s;
    if (coulomb > 0.0 && v * v0 < 0.0) {
        v = 0.0; /* friction stops the axis at the velocity reversal */
    }
    a->vel_mps = v;
    a->pos_m += v * dt_s;
    a->acc_mps2 = acc;
    a->contact_N = contact;
}

double sim_operator_handle_N(const sim_drive_t *d, const sim_axis_t *a)
{
    return d->force_ext_N - d->hand_damping_Nspm * a->vel_mps;
}

void sim_operator_init(sim_operator_t *op, const sim_operator_cfg_t *cfg, sim_rng_t *rng)
{
    op->cfg = *cfg;
    op->low_N = cfg->low_N * (1.0 + sim_rng_range(rng, -cfg->jitter, cfg->jitter));
    op->high_N = cfg->high_N * (1.0 + sim_rng_range(rng, -cfg->jitter, cfg->jitter));
    op->reaction_s = sim_rng_range(rng, cfg->reaction_min_s, cfg->reaction_max_s);
    op->t_layer_s = -1.0;
    op->t_high_s = -1.0;
    for (int ax = 0; ax < 2; ax++) {
        op->tremor_hz[ax] = sim_rng_range(rng, 8.0, 12.0);
        op->tremor_phase[ax] = sim_rng_range(rng, 0.0, 6.283185307179586);
    }
    /* engraving: transition i starts at level_t_s[i] and ends at level_N[i]; transition 0 is
     * the ramp-up from 0 */
    op->n_levels = 0;
    if (cfg->task == SIM_TASK_ENGRAVING) {
        double t = 0.0;
        const double t_stop = cfg->duration_s - cfg->release_s;
        int i = 0;
        while (i < SIM_MAX_LEVELS && t < t_stop) {
            op->level_t_s[i] = t;
            op->level_N[i] = sim_rng_range(rng, cfg->level_min_N, cfg->level_max_N);
            t += (i == 0) ? cfg->ramp_s : cfg->transition_s;
            t += sim_rng_range(rng, cfg->dwell_min_s, cfg->dwell_max_s);
            i++;
        }
        op->n_levels = i;
    }
    /* wiping: the strokes' start times after the approach (their jitter drawn here, after the
     * engraving schedule, so other tasks keep their draws) */
    op->n_strokes = 0;
    if (cfg->task == SIM_TASK_WIPING && cfg->stroke_period_s > 0.0) {
        double t = cfg->ramp_s;
        int i = 0;
        while (i < SIM_MAX_STROKES && t < cfg->duration_s) {
            op->stroke_t_s[i] = t;
            t += cfg->stroke_period_s *
                 (1.0 + sim_rng_range(rng, -cfg->stroke_jitter, cfg->stroke_jitter));
            i++;
        }
        op->stroke_t_s[i] = t;
        op->n_strokes = i;
    }
    /* the path along y: drawn after everything else, so a scenario without one keeps its draws */
    op->n_path = 0;
    if (cfg->path_m > 0.0) {
        double t = 0.4;
        const double t_back = cfg->duration_s - cfg->release_s - cfg->path_move_s;
        int i = 0;
        while (i < SIM_MAX_LEVELS - 1 && t + cfg->path_move_s < t_back) {
            op->path_t_s[i] = t;
            op->path_y_m[i] = sim_rng_range(rng, -0.5, 1.0) * cfg->path_m;
            t += cfg->path_move_s +
                 sim_rng_range(rng, cfg->path_dwell_min_s, cfg->path_dwell_max_s);
            i++;
        }
        op->path_t_s[i] = (t_back > t) ? t_back : t;
        op->path_y_m[i] = 0.1 * cfg->path_m;
        op->n_path = i + 1;
    }
}

void sim_operator_path(const sim_operator_t *op, double t_s, double *y_m, double *yd_mps)
{
    double y = 0.0;
    double yd = 0.0;
    const double mv = op->cfg.path_move_s;
    for (int i = 0; i < op->n_path && op->path_t_s[i] <= t_s; i++) {
        const double from = (i == 0) ? 0.0 : op->path_y_m[i - 1];
        const double r = (t_s - op->path_t_s[i]) / mv;
        y = from + (op->path_y_m[i] - from) * sim_smoothstep(r);
        yd = (r < 1.0) ? (op->path_y_m[i] - from) * 6.0 * r * (1.0 - r) / mv : 0.0;
    }
    *y_m = y;
    *yd_mps = yd;
}

double sim_operator_path_force(const sim_operator_t *op, double t_s, double y0_m, double y_m)
{
    if (op->n_path == 0) {
        return 0.0;
    }
    double y = 0.0;
    double yd = 0.0;
    sim_operator_path(op, t_s, &y, &yd);
    return op->cfg.hand_stiffness_Npm * (y0_m + y - y_m) + op->cfg.hand_damping_Nspm * yd;
}

/* Engraving profile value at t from the transition schedule (transitions may overlap: each one
 * starts from the value the previous one had reached). */
static double engraving_profile(const sim_operator_t *op, double t)
{
    double from = 0.0;
    double value = 0.0;
    for (int i = 0; i < op->n_levels && op->level_t_s[i] <= t; i++) {
        const double dur = (i == 0) ? op->cfg.ramp_s : op->cfg.transition_s;
        if (i > 0) {
            /* value at the start of transition i, from transition i-1 */
            const double d_prev = (i == 1) ? op->cfg.ramp_s : op->cfg.transition_s;
            const double r = (op->level_t_s[i] - op->level_t_s[i - 1]) / d_prev;
            from = from + (op->level_N[i - 1] - from) * sim_smoothstep(r);
        }
        value = from + (op->level_N[i] - from) * sim_smoothstep((t - op->level_t_s[i]) / dur);
    }
    return value;
}

static double pressing_profile(sim_operator_t *op, double t, double p_m, double layer_depth_m)
{
    const sim_operator_cfg_t *c = &op->cfg;
    if (op->t_layer_s < 0.0 && p_m >= layer_depth_m) {
        op->t_layer_s = t;
        if (op->t_high_s < 0.0) {
            op->t_high_s = t + op->reaction_s;
        }
    }
    if (op->t_high_s < 0.0 && t >= c->layer_timeout_s) {
        op->t_high_s = t;
    }
    if (op->t_high_s < 0.0 || t < op->t_high_s) {
        return op->low_N * sim_smoothstep(t / c->ramp_s);
    }
    const double tau = t - op->t_high_s;
    const double start = op->low_N * sim_smoothstep(op->t_high_s / c->ramp_s);
    double f = (tau < c->ramp_s) ? start + (op->high_N - start) * sim_smoothstep(tau / c->ramp_s)
                                 : op->high_N;
    return f;
}

/* Wiping: the approach (smoothstep to the mean over ramp_s), then the strokes about it. */
static double wiping_profile(const sim_operator_t *op, double t)
{
    const sim_operator_cfg_t *c = &op->cfg;
    if (t < c->ramp_s || op->n_strokes == 0) {
        return c->stroke_mean_N * sim_smoothstep(t / c->ramp_s);
    }
    int i = 0;
    while (i + 1 < op->n_strokes && op->stroke_t_s[i + 1] <= t) {
        i++;
    }
    const double len = op->stroke_t_s[i + 1] - op->stroke_t_s[i];
    double s = (t - op->stroke_t_s[i]) / len;
    s = (s > 1.0) ? 1.0 : s;
    const double w = 6.283185307179586 * s;
    /* the first stroke grows in over its first quarter: the approach joins it smoothly */
    const double grow = (i == 0) ? sim_smoothstep(4.0 * s) : 1.0;
    return c->stroke_mean_N +
           grow * c->stroke_amp_N *
               (0.8 * sin(w) + 0.35 * sin(2.0 * w + 0.6) + 0.15 * sin(3.0 * w + 1.9));
}

/* Both tasks release over the last release_s of the demonstration (0: no release). */
static double release_factor(const sim_operator_cfg_t *c, double t)
{
    if (c->release_s <= 0.0) {
        return 1.0;
    }
    const double t_rel = c->duration_s - c->release_s;
    return (t > t_rel) ? 1.0 - sim_smoothstep((t - t_rel) / c->release_s) : 1.0;
}

void sim_operator_force(sim_operator_t *op, double t_s, double p_m, double layer_depth_m,
                        double force_N[2])
{
    double f = 0.0;
    if (op->cfg.task == SIM_TASK_PRESSING) {
        f = pressing_profile(op, t_s, p_m, layer_depth_m) * release_factor(&op->cfg, t_s);
    } else if (op->cfg.task == SIM_TASK_ENGRAVING) {
        f = engraving_profile(op, t_s) * release_factor(&op->cfg, t_s);
    } else if (op->cfg.task == SIM_TASK_WIPING) {
        f = wiping_profile(op, t_s) * release_factor(&op->cfg, t_s);
    }
    const double w = 6.283185307179586 * t_s;
    force_N[0] = f * (1.0 + op->cfg.tremor_frac * sin(w * op->tremor_hz[0] + op->tremor_phase[0]));
    force_N[1] = f * op->cfg.tremor_frac * sin(w * op->tremor_hz[1] + op->tremor_phase[1]);
}

double sim_force_read(const sim_force_sensor_t *s, double true_N, sim_rng_t *rng)
{
    const double v = true_N + s->bias_N + s->noise_N * sim_rng_gauss(rng);
    if (s->bits == 0u || !(v == v)) {
        return v;
    }
    const double half = (double)(1ull << (s->bits - 1u));
    const double lsb = s->range_N / half;
    double q = floor(v / lsb + 0.5);
    if (q > half - 1.0) {
        q = half - 1.0;
    } else if (q < -half) {
        q = -half;
    }
    return q * lsb;
}

double sim_encoder_read(double pos_m, double resolution_m)
{
    if (resolution_m <= 0.0) {
        return pos_m;
    }
    return floor(pos_m / resolution_m + 0.5) * resolution_m;
}

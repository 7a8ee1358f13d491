/* Device-side skill validation: ranges, step rule, own rollout (see skill_check.h). */
#include "skill_check.h"

#include <stddef.h>

static bool within(fs_real_t v, fs_real_t lo, fs_real_t hi)
{
    return fs_isfinite(v) && v >= lo && v <= hi;
}

/* Fastest rate of the DMP in DMP time (per unit of t/tau): below 1 + alpha + sqrt(gamma). */
static fs_real_t step_rate(const skill_t *s)
{
    return FS_R(1.0) + s->dmp.p.alpha + fs_sqrt(s->dmp.p.gamma);
}

static bool step_ok(const skill_t *s, fs_real_t dt_s, fs_real_t time_scale)
{
    const fs_real_t h = dt_s / (s->dmp.tau_s * time_scale) * step_rate(s);
    return fs_isfinite(h) && h <= (fs_real_t)(SKCHK_STEP_MAX);
}

/* The scalar ranges of skchk_params (its first check). */
static bool params_scalars_ok(const skill_t *s)
{
    const dmp_model_t *m = &s->dmp;
    const pfc_axis_gains_t *g = &s->gains;
    return within(m->tau_s, (fs_real_t)(SKCHK_TAU_MIN_S), (fs_real_t)(SKCHK_TAU_MAX_S)) &&
           within(m->goal_N, FS_R(0.0), (fs_real_t)(SKCHK_GOAL_MAX_N)) && m->goal_N > FS_R(0.0) &&
           within(m->force0_N, (fs_real_t)(-SKCHK_FORCE0_MAX_N), (fs_real_t)(SKCHK_FORCE0_MAX_N)) &&
           within(s->stiffness_Npm, FS_R(0.0), (fs_real_t)(SKCHK_STIFFNESS_MAX_NPM)) &&
           s->stiffness_Npm > FS_R(0.0) &&
           within(m->duration_s, FS_R(0.0), (fs_real_t)(SKCHK_DURATION_MAX_S)) &&
           within(m->p.alpha, FS_R(0.0), (fs_real_t)(SKCHK_ALPHA_MAX)) &&
           within(m->p.gamma, FS_R(0.0), (fs_real_t)(SKCHK_GAMMA_MAX)) &&
           within(g->m_d_kg, (fs_real_t)(SKCHK_MASS_MIN_KG), (fs_real_t)(SKCHK_MASS_MAX_KG)) &&
           within(g->k_d_Nspm, FS_R(0.0), (fs_real_t)(SKCHK_GAIN_MAX)) &&
           within(g->k_p_Npm, FS_R(0.0), (fs_real_t)(SKCHK_GAIN_MAX)) &&
           within(g->k_f, FS_R(0.0), (fs_real_t)(SKCHK_GAIN_MAX)) &&
           within(g->k_i_per_s, FS_R(0.0), (fs_real_t)(SKCHK_GAIN_MAX)) &&
           within(s->surface_m, (fs_real_t)(-SKCHK_SURFACE_MAX_M),
                  (fs_real_t)(SKCHK_SURFACE_MAX_M));
}

/* Kernel i's weight and width within range. */
static bool params_kernel_ok(const dmp_model_t *m, uint16_t i)
{
    const fs_real_t w_min = (m->periodic != 0u) ? (fs_real_t)(SKCHK_KAPPA_MIN)
                                                : (fs_real_t)(SKCHK_WIDTH_MIN);
    const fs_real_t w_max = (m->periodic != 0u) ? (fs_real_t)(SKCHK_KAPPA_MAX)
                                                : (fs_real_t)(SKCHK_WIDTH_MAX);
    return within(m->weight[i], (fs_real_t)(-SKCHK_WEIGHT_MAX), (fs_real_t)(SKCHK_WEIGHT_MAX)) &&
           within(m->width[i], w_min, w_max);
}

/* The y DMP's scalar ranges (a model with has_y). */
static bool params_y_scalars_ok(const dmp_model_t *m)
{
    return within(m->goal_y_m, (fs_real_t)(-SKCHK_SURFACE_MAX_M),
                  (fs_real_t)(SKCHK_SURFACE_MAX_M)) &&
           within(m->y_start_m, (fs_real_t)(-SKCHK_SURFACE_MAX_M),
                  (fs_real_t)(SKCHK_SURFACE_MAX_M));
}

/* The stages of the sliced parameter check (skchk_params_t.stage). */
enum {
    PARAMS_SCALARS = 0,
    PARAMS_KERNELS,
    PARAMS_Y,
    PARAMS_Y_WEIGHTS,
    PARAMS_STEP
};

void skchk_params_begin(skchk_params_t *c, const skill_t *s)
{
    c->skill = s;
    c->pos = 0u;
    c->stage = PARAMS_SCALARS;
    c->status = (s == NULL) ? FS_ERR_NULL_ARG : FS_OK;
    c->done = s == NULL;
}

/* One unit of the parameter check: its status (FS_OK while it goes on). */
static fs_status_t params_unit(skchk_params_t *c)
{
    const skill_t *s = c->skill;
    const dmp_model_t *m = &s->dmp;
    switch (c->stage) {
    case PARAMS_SCALARS:
        c->stage = PARAMS_KERNELS;
        return (params_scalars_ok(s) && m->n_kernels != 0u && m->n_kernels <= DMP_MAX_KERNELS)
                   ? FS_OK
                   : FS_ERR_SKCHK_RANGE;
    case PARAMS_KERNELS:
        for (uint32_t k = 0u; k < SKCHK_PARAMS_KERNELS_PER_UNIT && c->pos < m->n_kernels; k++) {
            if (!params_kernel_ok(m, c->pos++)) {
                return FS_ERR_SKCHK_RANGE;
            }
        }
        if (c->pos >= m->n_kernels) {
            c->pos = 0u;
            c->stage = (m->has_y != 0u) ? PARAMS_Y : PARAMS_STEP;
        }
        return FS_OK;
    case PARAMS_Y:
        c->stage = PARAMS_Y_WEIGHTS;
        return params_y_scalars_ok(m) ? FS_OK : FS_ERR_SKCHK_PATH;
    case PARAMS_Y_WEIGHTS:
        for (uint32_t k = 0u; k < SKCHK_PARAMS_KERNELS_PER_UNIT && c->pos < m->n_kernels; k++) {
            const uint16_t i = c->pos++;
            if (!within(m->y_weight[i], (fs_real_t)(-SKCHK_WEIGHT_MAX),
                        (fs_real_t)(SKCHK_WEIGHT_MAX))) {
                return FS_ERR_SKCHK_PATH;
            }
        }
        if (c->pos >= m->n_kernels) {
            c->stage = PARAMS_STEP;
        }
        return FS_OK;
    default: c->done = true; return step_ok(s, m->dt_s, FS_R(1.0)) ? FS_OK : FS_ERR_SKCHK_STEP;
    }
}

bool skchk_params_run(skchk_params_t *c, uint32_t max_units)
{
    for (uint32_t u = 0u; u < max_units && !c->done; u++) {
        c->status = params_unit(c);
        c->done = c->done || c->status != FS_OK;
    }
    return c->done;
}

fs_status_t skchk_params(const skill_t *s)
{
    skchk_params_t c;
    skchk_params_begin(&c, s);
    while (!skchk_params_run(&c, UINT32_MAX)) {
    }
    return c.status;
}

void skchk_begin(skchk_t *c, const skill_t *s, fs_real_t dt_s, fs_real_t force_max_N)
{
    c->skill = s;
    if (s->dmp.periodic != 0u) {
        dmp_periodic_reset_xy(&s->dmp, &c->dmp, FS_R(1.0), FS_R(1.0));
    } else {
        dmp_state_reset(&c->dmp);
    }
    const fs_real_t n = s->dmp.duration_s / dt_s + FS_R(0.5);
    c->steps_total = (fs_isfinite(n) && n > FS_R(0.0) && n < FS_R(4.0e9)) ? (uint32_t)n : 0u;
    c->steps_done = 0u;
    c->peak_N = FS_R(0.0);
    c->force_max_N = force_max_N;
    c->path_peak_m = FS_R(0.0);
    c->path_max_m = (fs_real_t)(SKCHK_PATH_MAX_M);
    c->status = FS_OK;
    c->done = c->steps_total == 0u;
}

bool skchk_run(skchk_t *c, uint32_t max_steps)
{
    const dmp_model_t *m = &c->skill->dmp;
    /* periodic: the bound |f0| + g + |e| (f = f0 + g + e at scales 1) */
    const fs_real_t fg = fs_fabs(m->force0_N) + m->goal_N;
    for (uint32_t i = 0u; i < max_steps && !c->done; i++) {
        fs_real_t p = FS_R(0.0);
        const fs_real_t f = (m->periodic != 0u)
                                ? fg + fs_fabs(dmp_periodic_step_xy(m, &c->dmp, NULL, FS_R(1.0),
                                                                    NULL, FS_R(1.0), &p) -
                                               m->force0_N - m->goal_N)
                                : dmp_step_xy(m, &c->dmp, NULL, NULL, FS_R(1.0), &p);
        const fs_real_t a = fs_fabs(f);
        const fs_real_t ap = fs_fabs(p);
        if (ap > c->path_peak_m) {
            c->path_peak_m = ap;
        }
        if (!fs_isfinite(f)) {
            c->status = FS_ERR_SKCHK_NOT_FINITE;
            c->done = true;
        } else if (!fs_isfinite(p) || c->path_peak_m > c->path_max_m) {
            c->status = FS_ERR_SKCHK_PATH;
            c->done = true;
        } else {
            if (a > c->peak_N) {
                c->peak_N = a;
            }
            if (c->peak_N > c->force_max_N) {
                c->status = FS_ERR_SKCHK_PEAK;
                c->done = true;
            }
        }
        c->steps_done++;
        if (c->steps_done >= c->steps_total) {
            c->done = true;
        }
    }
    return c->done;
}

fs_status_t skchk_skill(const skill_t *s, fs_real_t dt_s, fs_real_t force_max_N, fs_real_t *peak_N)
{
    const fs_status_t st = skchk_params(s);
    if (st != FS_OK) {
        return st;
    }
    skchk_t c;
    skchk_begin(&c, s, dt_s, force_max_N);
    while (!skchk_run(&c, UINT32_MAX)) {
    }
    if (peak_N != NULL) {
        *peak_N = c.peak_N;
    }
    return c.status;
}

fs_status_t skchk_run_path(const skill_t *s, fs_real_t path_peak_m, fs_real_t path_scale,
                           fs_real_t path_max_m)
{
    if (s == NULL) {
        return FS_ERR_NULL_ARG;
    }
    if (!fs_isfinite(path_scale) || path_scale < FS_R(0.0)) {
        return FS_ERR_SKCHK_PATH_SCALE;
    }
    const fs_real_t extent = path_scale * path_peak_m;
    return (fs_isfinite(extent) && extent <= path_max_m) ? FS_OK : FS_ERR_SKCHK_PATH_SCALE;
}

fs_status_t skchk_run_scales(const skill_t *s, fs_real_t peak_N, fs_real_t goal_scale,
                             fs_real_t time_scale, fs_real_t dt_s, fs_real_t force_max_N)
{
    if (s == NULL) {
        return FS_ERR_NULL_ARG;
    }
    if (!fs_isfinite(goal_scale) || !fs_isfinite(time_scale) || !(time_scale > FS_R(0.0))) {
        return FS_ERR_SCALE_INVALID;
    }
    if (!step_ok(s, dt_s, time_scale)) {
        return FS_ERR_SKCHK_STEP;
    }
    /* f_hat = f0 + goal_scale*y with |y| <= peak_N + |f0| at goal scale 1: a bound that is exact
     * (goal_scale*peak_N) for a skill starting from 0 N */
    const fs_real_t f0 = fs_fabs(s->dmp.force0_N);
    const fs_real_t peak = f0 + fs_fabs(goal_scale) * (peak_N + f0);
    return (fs_isfinite(peak) && peak <= force_max_N) ? FS_OK : FS_ERR_SKCHK_GOAL_SCALE;
}

fs_status_t skchk_run_scales_periodic(const skill_t *s, fs_real_t peak_N, fs_real_t goal_scale,
                                      fs_real_t amplitude_scale, fs_real_t time_scale,
                                      fs_real_t dt_s, fs_real_t force_max_N)
{
    if (s == NULL) {
        return FS_ERR_NULL_ARG;
    }
    if (!fs_isfinite(amplitude_scale) || amplitude_scale < FS_R(0.0) || !fs_isfinite(goal_scale) ||
        !fs_isfinite(time_scale) || !(time_scale > FS_R(0.0))) {
        return FS_ERR_SCALE_INVALID;
    }
    if (!step_ok(s, dt_s, time_scale)) {
        return FS_ERR_SKCHK_STEP;
    }
    const fs_real_t g = fs_fabs(goal_scale);
    const fs_real_t k = (amplitude_scale > g) ? amplitude_scale : g;
    const fs_real_t peak = k * peak_N;
    return (fs_isfinite(peak) && peak <= force_max_N) ? FS_OK : FS_ERR_SKCHK_GOAL_SCALE;
}

fs_status_t skchk_stiffness(const skill_t *s, fs_real_t stiffness_max_Npm)
{
    if (s == NULL) {
        return FS_ERR_NULL_ARG;
    }
    return (s->stiffness_Npm <= stiffness_max_Npm) ? FS_OK : FS_ERR_SKCHK_STIFFNESS;
}

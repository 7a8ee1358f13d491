/* Scenario files: their keys, defaults and checks (sim_scenario.h, docs/hil.md); the TOML
 * subset itself is read by sim_toml.c. */
#include "sim_scenario.h"

#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include "fs_wire_const.h"

typedef sim_toml_ctx_t ctx_t;
typedef sim_toml_value_t value_t;

void sim_scenario_defaults(sim_scenario_t *sc)
{
    memset(sc, 0, sizeof *sc);
    snprintf(sc->name, sizeof sc->name, "scenario");
    sc->mode = SIM_MODE_TEACH;
    sc->plant = SIM_PLANT_IDEAL;
    sc->duration_s = 0.0;
    sc->tail_s = 1.0;
    sc->dt_s = FS_TICK_S; /* the device's tick */
    sc->substeps = 10;
    sc->seed = 1;
    sc->start_x_m = 0.0;
    sc->start_y_m = 0.0;
    sc->m_d_kg = 40.0;
    sc->force_max_N = 50.0;
    sc->stiffness_max_Npm = 0.0;
    sc->object = (sim_object_t){.skin_m = 0.0,
                                .surface_m = 0.001,
                                .k1_Npm = 100.0,
                                .k2_Npm = 100.0,
                                .layer_depth_m = 0.019,
                                .d_v_Nspm = 50.0,
                                .m_v_kg = 10.0,
                                .friction_mu = 0.0};
    sc->carriage = (sim_carriage_t){.carriage_kg = 2.0,
                                    .act_max_N = 200.0,
                                    .act_lag_s = 0.0005,
                                    .viscous_Nspm = 5.0,
                                    .coulomb_N = 1.0};
    sc->op = (sim_operator_cfg_t){.task = SIM_TASK_NONE,
                                  .low_N = 2.5,
                                  .high_N = 4.5,
                                  .level_min_N = 1.5,
                                  .level_max_N = 4.0,
                                  .jitter = 0.1,
                                  .ramp_s = 1.0,
                                  .release_s = 1.0,
                                  .reaction_min_s = 0.2,
                                  .reaction_max_s = 0.35,
                                  .dwell_min_s = 0.6,
                                  .dwell_max_s = 1.4,
                                  .transition_s = 0.7,
                                  .layer_timeout_s = 5.0,
                                  .hand_damping_Nspm = 30.0,
                                  .tremor_frac = 0.01,
                                  .duration_s = 0.0,
                                  .path_m = 0.0,
                                  .path_move_s = 0.6,
                                  .path_dwell_min_s = 0.2,
                                  .path_dwell_max_s = 1.0,
                                  .hand_stiffness_Npm = 3000.0,
                                  .stroke_mean_N = 5.0,
                                  .stroke_amp_N = 1.5,
                                  .stroke_period_s = 1.0,
                                  .stroke_jitter = 0.0};
    sc->tip = (sim_force_sensor_t){.noise_N = 0.02, .bias_N = 0.0, .range_N = 100.0, .bits = 16u};
    sc->handle = sc->tip;
    sc->encoder_m = 1e-6;
    sc->delay_samples = 1;
    sc->vel_cutoff_Hz = 50.0;
    sc->goal_scale = 1.0;
    sc->time_scale = 1.0;
    sc->path_scale = 1.0;
    sc->use_model = 1;
    sc->end_policy = -1;
    sc->phase_stop_gain_per_N2 = 0.0;
    sc->surface_error_m = 0.0;
    sc->surface_from_contact = 0;
    sc->fault.kind = SIM_FAULT_NONE;
    sc->fault.duration_s = 1e9;
}

/* number keys: section, key, pointer offset into the scenario */
typedef struct {
    const char *section;
    const char *key;
    size_t offset;
    double lo, hi;
} num_key_t;

#define NK(sec, k, field, lo, hi)                       \
    {                                                   \
        sec, k, offsetof(sim_scenario_t, field), lo, hi \
    }
static const num_key_t NUM_KEYS[] = {
    NK("", "duration_s", duration_s, 0.0, 3600.0),
    NK("", "tail_s", tail_s, 0.0, 60.0),
    NK("", "start_x_m", start_x_m, -1.0, 1.0),
    NK("", "start_y_m", start_y_m, -1.0, 1.0),
    NK("", "m_d_kg", m_d_kg, 1e-3, 1e4),
    NK("", "force_max_N", force_max_N, 1e-3, 1e4),
    NK("", "stiffness_max_Npm", stiffness_max_Npm, 0.0, FS_STIFFNESS_CEILING_NPM),
    NK("object", "surface_m", object.surface_m, -1.0, 1.0),
    NK("object", "k1_Npm", object.k1_Npm, 1e-6, 1e7),
    NK("object", "k2_Npm", object.k2_Npm, 1e-6, 1e7),
    NK("object", "layer_depth_m", object.layer_depth_m, 0.0, 1.0),
    NK("object", "d_v_Nspm", object.d_v_Nspm, 0.0, 1e5),
    NK("object", "m_v_kg", object.m_v_kg, 0.0, 1e4),
    NK("object", "skin_m", object.skin_m, 0.0, 0.1),
    NK("object", "friction_mu", object.friction_mu, 0.0, 2.0),
    NK("object", "away_at_s", away_at_s, 0.0, 3600.0),
    NK("object", "away_for_s", away_for_s, 0.0, 3600.0),
    NK("object", "away_m", away_m, -1.0, 1.0),
    NK("object", "away_ramp_s", away_ramp_s, 0.0, 10.0),
    NK("object", "gives_at_s", gives_at_s, 0.0, 3600.0),
    NK("object", "gives_k2_Npm", gives_k2_Npm, 0.0, 1e7),
    NK("carriage", "mass_kg", carriage.carriage_kg, 1e-3, 1e3),
    NK("carriage", "act_max_N", carriage.act_max_N, 0.0, 1e5),
    NK("carriage", "act_lag_s", carriage.act_lag_s, 1e-6, 1.0),
    NK("carriage", "viscous_Nspm", carriage.viscous_Nspm, 0.0, 1e4),
    NK("carriage", "coulomb_N", carriage.coulomb_N, 0.0, 1e3),
    NK("operator", "low_force_N", op.low_N, 0.0, 1e3),
    NK("operator", "high_force_N", op.high_N, 0.0, 1e3),
    NK("operator", "level_min_N", op.level_min_N, 0.0, 1e3),
    NK("operator", "level_max_N", op.level_max_N, 0.0, 1e3),
    NK("operator", "jitter", op.jitter, 0.0, 0.9),
    NK("operator", "ramp_s", op.ramp_s, 1e-3, 100.0),
    NK("operator", "release_s", op.release_s, 0.0, 100.0),
    NK("operator", "reaction_min_s", op.reaction_min_s, 0.0, 10.0),
    NK("operator", "reaction_max_s", op.reaction_max_s, 0.0, 10.0),
    NK("operator", "dwell_min_s", op.dwell_min_s, 1e-2, 100.0),
    NK("operator", "dwell_max_s", op.dwell_max_s, 1e-2, 100.0),
    NK("operator", "transition_s", op.transition_s, 1e-3, 100.0),
    NK("operator", "layer_timeout_s", op.layer_timeout_s, 0.0, 3600.0),
    NK("operator", "hand_damping_Nspm", op.hand_damping_Nspm, 0.0, 1e4),
    NK("operator", "tremor_frac", op.tremor_frac, 0.0, 0.5),
    NK("operator", "path_m", op.path_m, 0.0, 0.4),
    NK("operator", "path_move_s", op.path_move_s, 0.05, 10.0),
    NK("operator", "path_dwell_min_s", op.path_dwell_min_s, 0.0, 100.0),
    NK("operator", "path_dwell_max_s", op.path_dwell_max_s, 0.0, 100.0),
    NK("operator", "hand_stiffness_Npm", op.hand_stiffness_Npm, 0.0, 1e6),
    NK("operator", "stroke_mean_N", op.stroke_mean_N, 0.0, 1e3),
    NK("operator", "stroke_amp_N", op.stroke_amp_N, 0.0, 1e3),
    NK("operator", "stroke_period_s", op.stroke_period_s, 0.05, 60.0),
    NK("operator", "stroke_jitter", op.stroke_jitter, 0.0, 0.2),
    NK("sensors", "force_noise_N", tip.noise_N, 0.0, 100.0),
    NK("sensors", "force_range_N", tip.range_N, 1e-3, 1e5),
    NK("sensors", "tip_bias_N", tip.bias_N, -100.0, 100.0),
    NK("sensors", "handle_bias_N", handle.bias_N, -100.0, 100.0),
    NK("sensors", "encoder_m", encoder_m, 0.0, 1e-2),
    NK("sensors", "vel_cutoff_Hz", vel_cutoff_Hz, 0.1, 499.0),
    NK("execute", "goal_scale", goal_scale, -100.0, 100.0),
    NK("execute", "time_scale", time_scale, 1e-3, 1e3),
    NK("execute", "path_scale", path_scale, 0.0, 65.535),
    NK("execute", "phase_stop_gain_per_N2", phase_stop_gain_per_N2, 0.0, 1e6),
    NK("execute", "surface_error_m", surface_error_m, -0.1, 0.1),
    NK("fault", "at_s", fault.at_s, 0.0, 3600.0),
    NK("fault", "value", fault.value, -1e6, 1e6),
    NK("fault", "duration_s", fault.duration_s, 0.0, 1e9),
};

/* Skill paths in a scenario are relative to the scenario file's folder. */
static int resolve_path(const ctx_t *c, const sim_scenario_t *sc, char *out, const char *path)
{
    int n;
    if (path[0] == '/' || sc->dir[0] == '\0') {
        n = snprintf(out, SIM_PATH_MAX, "%s", path);
    } else {
        n = snprintf(out, SIM_PATH_MAX, "%s/%s", sc->dir, path);
    }
    if (n < 0 || n >= SIM_PATH_MAX) {
        return sim_toml_fail(c, "skill path too long");
    }
    return 0;
}

/* A key of NUM_KEYS: 1 if it is one (applied, or -1 after an error), 0 if not. */
static int apply_number(sim_scenario_t *sc, const ctx_t *c, const char *sec, const char *key,
                        const value_t *v)
{
    for (size_t i = 0; i < sizeof NUM_KEYS / sizeof NUM_KEYS[0]; i++) {
        const num_key_t *k = &NUM_KEYS[i];
        if (strcmp(k->section, sec) != 0 || strcmp(k->key, key) != 0) {
            continue;
        }
        double *dst = (double *)(void *)((char *)sc + k->offset);
        if (sim_toml_number(c, key, v, k->lo, k->hi, dst) != 0) {
            return -1;
        }
        if (strcmp(sec, "sensors") == 0 &&
            (strcmp(key, "force_noise_N") == 0 || strcmp(key, "force_range_N") == 0)) {
            /* both force sensors share noise and range */
            *(double *)(void *)((char *)&sc->handle +
                                (k->offset - offsetof(sim_scenario_t, tip))) = v->num;
        }
        return 1;
    }
    return 0;
}

/* Keys before the first section; 1 if key is one of them (or -1), 0 if not. */
static int apply_top(sim_scenario_t *sc, const ctx_t *c, const char *key, const value_t *v)
{
    static const char *const MODES[] = {"teach", "execute"};
    static const char *const PLANTS[] = {"ideal", "realistic"};
    static const sim_plant_kind_t PLANT_OF[] = {SIM_PLANT_IDEAL, SIM_PLANT_REALISTIC};
    int i = 0;
    double n = 0.0;
    if (strcmp(key, "name") == 0) {
        return sim_toml_string(c, key, v, sc->name, sizeof sc->name) == 0 ? 1 : -1;
    }
    if (strcmp(key, "mode") == 0) {
        if (sim_toml_choice(c, key, v, "mode", MODES, 2, &i) != 0) {
            return -1;
        }
        sc->mode = i == 0 ? SIM_MODE_TEACH : SIM_MODE_EXECUTE;
        return 1;
    }
    if (strcmp(key, "plant") == 0) {
        if (sim_toml_choice(c, key, v, "plant", PLANTS, 2, &i) != 0) {
            return -1;
        }
        sc->plant = PLANT_OF[i];
        return 1;
    }
    if (strcmp(key, "seed") == 0) {
        if (sim_toml_integer(c, key, v, 0.0, 9007199254740992.0, &n) != 0) {
            return -1;
        }
        sc->seed = (uint64_t)n;
        return 1;
    }
    if (strcmp(key, "substeps") == 0) {
        if (sim_toml_integer(c, key, v, 1.0, 1000.0, &n) != 0) {
            return -1;
        }
        sc->substeps = (int)n;
        return 1;
    }
    return 0;
}

/* [operator] keys other than numbers. */
static int apply_operator(sim_scenario_t *sc, const ctx_t *c, const char *key, const value_t *v)
{
    static const char *const TASKS[] = {"pressing", "engraving", "wiping", "none"};
    static const sim_task_t TASK_OF[] = {SIM_TASK_PRESSING, SIM_TASK_ENGRAVING, SIM_TASK_WIPING,
                                         SIM_TASK_NONE};
    int i = 0;
    if (strcmp(key, "task") != 0) {
        return 0;
    }
    if (sim_toml_choice(c, key, v, "task", TASKS, 4, &i) != 0) {
        return -1;
    }
    sc->op.task = TASK_OF[i];
    return 1;
}

/* [sensors] keys other than numbers. */
static int apply_sensors(sim_scenario_t *sc, const ctx_t *c, const char *key, const value_t *v)
{
    double n = 0.0;
    if (strcmp(key, "force_bits") == 0) {
        if (sim_toml_integer(c, key, v, 0.0, 32.0, &n) != 0) {
            return -1;
        }
        sc->tip.bits = (unsigned)n;
        sc->handle.bits = (unsigned)n;
        return 1;
    }
    if (strcmp(key, "delay_samples") == 0) {
        if (sim_toml_integer(c, key, v, 0.0, 4.0, &n) != 0) {
            return -1;
        }
        sc->delay_samples = (int)n;
        return 1;
    }
    return 0;
}

/* [execute] skills and step_durations_s: the arrays. */
static int apply_execute_lists(sim_scenario_t *sc, const ctx_t *c, const char *key,
                               const value_t *v)
{
    if (strcmp(key, "skills") == 0) {
        if (v->type == SIM_TOML_STR) {
            sc->n_skills = 1;
            return resolve_path(c, sc, sc->skill_path[0], v->str) == 0 ? 1 : -1;
        }
        if (sim_toml_want(c, key, v, SIM_TOML_STRARR) != 0) {
            return -1;
        }
        sc->n_skills = v->n;
        for (int i = 0; i < v->n; i++) {
            if (resolve_path(c, sc, sc->skill_path[i], v->strs[i]) != 0) {
                return -1;
            }
        }
        return 1;
    }
    if (strcmp(key, "step_durations_s") == 0) {
        if (sim_toml_want(c, key, v, SIM_TOML_NUMARR) != 0) {
            return -1;
        }
        for (int i = 0; i < v->n; i++) {
            if (!(v->nums[i] > 0.0 && v->nums[i] <= 3600.0)) {
                return sim_toml_fail(c, "step_durations_s[%d] = %g must be in (0, 3600]", i,
                                     v->nums[i]);
            }
            sc->step_duration_s[i] = v->nums[i];
        }
        sc->n_step_durations = v->n;
        return 1;
    }
    return 0;
}

/* [execute] model, end_policy and surface: the choices. */
static int apply_execute_choices(sim_scenario_t *sc, const ctx_t *c, const char *key,
                                 const value_t *v)
{
    static const char *const MODELS[] = {"object", "none"};
    static const char *const POLICIES[] = {"skill", "hold", "release"};
    static const char *const SURFACES[] = {"config", "contact"};
    int i = 0;
    if (strcmp(key, "model") == 0) {
        if (sim_toml_choice(c, key, v, "model", MODELS, 2, &i) != 0) {
            return -1;
        }
        sc->use_model = i == 0 ? 1 : 0;
        return 1;
    }
    if (strcmp(key, "end_policy") == 0) {
        if (sim_toml_choice(c, key, v, "end_policy", POLICIES, 3, &i) != 0) {
            return -1;
        }
        sc->end_policy = i - 1;
        return 1;
    }
    if (strcmp(key, "surface") == 0) {
        if (sim_toml_choice(c, key, v, "surface", SURFACES, 2, &i) != 0) {
            return -1;
        }
        sc->surface_from_contact = i;
        return 1;
    }
    return 0;
}

/* [fault] kind. */
static int apply_fault(sim_scenario_t *sc, const ctx_t *c, const char *key, const value_t *v)
{
    static const char *const KINDS[] = {"none",        "force_spike",  "force_nan",
                                        "force_stuck", "encoder_jump", "actuator_saturation"};
    int i = 0;
    if (strcmp(key, "kind") != 0) {
        return 0;
    }
    if (sim_toml_choice(c, key, v, "fault kind", KINDS, 6, &i) != 0) {
        return -1;
    }
    sc->fault.kind = (sim_fault_kind_t)i;
    return 1;
}

/* One key of a scenario file (sim_toml_apply_fn). */
static int apply(void *user, const ctx_t *c, const char *sec, const char *key, const value_t *v)
{
    sim_scenario_t *sc = user;
    int r = apply_number(sc, c, sec, key, v);
    if (r == 0 && sec[0] == '\0') {
        r = apply_top(sc, c, key, v);
    } else if (r == 0 && strcmp(sec, "operator") == 0) {
        r = apply_operator(sc, c, key, v);
    } else if (r == 0 && strcmp(sec, "sensors") == 0) {
        r = apply_sensors(sc, c, key, v);
    } else if (r == 0 && strcmp(sec, "execute") == 0) {
        r = apply_execute_lists(sc, c, key, v);
        r = r != 0 ? r : apply_execute_choices(sc, c, key, v);
    } else if (r == 0 && strcmp(sec, "fault") == 0) {
        r = apply_fault(sc, c, key, v);
    }
    if (r != 0) {
        return r < 0 ? -1 : 0;
    }
    if (sec[0] == '\0') {
        return sim_toml_fail(c, "unknown key '%s'", key);
    }
    return sim_toml_fail(c, "unknown key '%s' in [%s]", key, sec);
}

static const char *const SECTIONS[] = {"object",  "carriage", "operator",
                                       "sensors", "execute",  "fault"};

int sim_scenario_parse(sim_scenario_t *sc, const char *text, const char *name,
                       char err[SIM_ERR_MAX])
{
    return sim_toml_parse(text, name, SECTIONS, sizeof SECTIONS / sizeof SECTIONS[0], apply, sc,
                          err);
}

int sim_scenario_load(sim_scenario_t *sc, const char *path, char err[SIM_ERR_MAX])
{
    const char *text = sim_toml_load(path, "scenario", err);
    if (text == NULL) {
        return -1;
    }
    snprintf(sc->path, sizeof sc->path, "%s", path);
    const char *slash = strrchr(path, '/');
    if (slash == NULL) {
        snprintf(sc->dir, sizeof sc->dir, ".");
    } else {
        snprintf(sc->dir, sizeof sc->dir, "%.*s", (int)(slash - path), path);
    }
    return sim_scenario_parse(sc, text, path, err);
}

int sim_scenario_check(const sim_scenario_t *sc, char err[SIM_ERR_MAX])
{
    const char *f = sc->path[0] ? sc->path : sc->name;
    if (sc->mode == SIM_MODE_TEACH) {
        if (!(sc->duration_s > 0.0)) {
            snprintf(err, SIM_ERR_MAX, "%s: a teach scenario needs duration_s > 0", f);
            return -1;
        }
        if (sc->op.task == SIM_TASK_PRESSING &&
            sc->op.high_N * (1.0 + sc->op.jitter) > sc->force_max_N) {
            snprintf(err, SIM_ERR_MAX,
                     "%s: operator high_force_N %g (+jitter) exceeds force_max_N %g", f,
                     sc->op.high_N, sc->force_max_N);
            return -1;
        }
        if (sc->op.task == SIM_TASK_WIPING &&
            sc->op.stroke_mean_N + 1.3 * sc->op.stroke_amp_N > sc->force_max_N) {
            snprintf(err, SIM_ERR_MAX,
                     "%s: operator strokes (mean %g N, amplitude %g N) exceed "
                     "force_max_N %g",
                     f, sc->op.stroke_mean_N, sc->op.stroke_amp_N, sc->force_max_N);
            return -1;
        }
        if (sc->op.task == SIM_TASK_ENGRAVING && sc->op.level_max_N > sc->force_max_N) {
            snprintf(err, SIM_ERR_MAX, "%s: operator level_max_N %g exceeds force_max_N %g", f,
                     sc->op.level_max_N, sc->force_max_N);
            return -1;
        }
        if (sc->op.level_min_N > sc->op.level_max_N || sc->op.dwell_min_s > sc->op.dwell_max_s ||
            sc->op.reaction_min_s > sc->op.reaction_max_s) {
            snprintf(err, SIM_ERR_MAX, "%s: an operator min is above its max", f);
            return -1;
        }
    } else {
        if (sc->n_skills < 1) {
            snprintf(err, SIM_ERR_MAX,
                     "%s: an execute scenario needs at least one skill "
                     "([execute] skills = [...] or --skill FILE)",
                     f);
            return -1;
        }
        if (sc->n_step_durations != 0 && sc->n_step_durations != sc->n_skills) {
            snprintf(err, SIM_ERR_MAX, "%s: %d step durations for %d skills", f,
                     sc->n_step_durations, sc->n_skills);
            return -1;
        }
    }
    return 0;
}

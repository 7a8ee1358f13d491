/* Scenario TOML-subset parser: see sim_scenario.h and docs/hil.md. */
#include "sim_scenario.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define SIM_ARR_MAX SIM_MAX_SKILLS

typedef enum {
    V_NUM,
    V_STR,
    V_BOOL,
    V_NUMARR,
    V_STRARR
} vtype_t;

typedef struct {
    vtype_t type;
    double num;
    int b;
    char str[SIM_PATH_MAX];
    int n;
    double nums[SIM_ARR_MAX];
    char strs[SIM_ARR_MAX][SIM_PATH_MAX];
} value_t;

typedef struct {
    const char *file;
    int line;
    char *err;
} ctx_t;

static int fail(const ctx_t *c, const char *fmt, ...)
{
    char msg[SIM_ERR_MAX / 2];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    snprintf(c->err, SIM_ERR_MAX, "%s:%d: %s", c->file, c->line, msg);
    return -1;
}

void sim_scenario_defaults(sim_scenario_t *sc)
{
    memset(sc, 0, sizeof *sc);
    snprintf(sc->name, sizeof sc->name, "scenario");
    sc->mode = SIM_MODE_TEACH;
    sc->plant = SIM_PLANT_IDEAL;
    sc->duration_s = 0.0;
    sc->tail_s = 1.0;
    sc->dt_s = 0.001;
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
                                .m_v_kg = 10.0};
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
                                  .duration_s = 0.0};
    sc->tip = (sim_force_sensor_t){.noise_N = 0.02, .bias_N = 0.0, .range_N = 100.0, .bits = 16u};
    sc->handle = sc->tip;
    sc->encoder_m = 1e-6;
    sc->delay_samples = 1;
    sc->vel_cutoff_Hz = 50.0;
    sc->goal_scale = 1.0;
    sc->time_scale = 1.0;
    sc->use_model = 1;
    sc->end_policy = -1;
    sc->phase_stop_gain_per_N2 = 0.0;
    sc->surface_error_m = 0.0;
    sc->surface_from_contact = 0;
    sc->fault.kind = SIM_FAULT_NONE;
    sc->fault.duration_s = 1e9;
}

static char *skip_ws(char *p)
{
    while (*p == ' ' || *p == '\t') {
        p++;
    }
    return p;
}

/* Parse one scalar at *pp (number or string); advances *pp. */
static int parse_scalar(const ctx_t *c, char **pp, int *is_str, double *num, char *str)
{
    char *p = skip_ws(*pp);
    if (*p == '"') {
        p++;
        size_t n = 0;
        while (*p != '"') {
            if (*p == '\0') {
                return fail(c, "unterminated string");
            }
            if (*p == '\\' && (p[1] == '"' || p[1] == '\\')) {
                p++;
            }
            if (n + 1 >= SIM_PATH_MAX) {
                return fail(c, "string longer than %d characters", SIM_PATH_MAX - 1);
            }
            str[n++] = *p++;
        }
        str[n] = '\0';
        *pp = p + 1;
        *is_str = 1;
        return 0;
    }
    char *end = NULL;
    errno = 0;
    double v = strtod(p, &end);
    if (end == p) {
        char tok[32];
        size_t n = 0;
        while (p[n] != '\0' && p[n] != ',' && p[n] != ']' && !isspace((unsigned char)p[n]) &&
               n + 1 < sizeof tok) {
            tok[n] = p[n];
            n++;
        }
        tok[n] = '\0';
        return fail(c, "expected a number, a \"string\", true or false, got '%s'", tok);
    }
    if (errno == ERANGE || !isfinite(v)) {
        return fail(c, "number out of range");
    }
    *num = v;
    *is_str = 0;
    *pp = end;
    return 0;
}

static int parse_value(const ctx_t *c, char *p, value_t *v)
{
    p = skip_ws(p);
    if (strncmp(p, "true", 4) == 0 || strncmp(p, "false", 5) == 0) {
        v->type = V_BOOL;
        v->b = (p[0] == 't');
        p += v->b ? 4 : 5;
    } else if (*p == '[') {
        p++;
        v->n = 0;
        int kind = -1;
        p = skip_ws(p);
        while (*p != ']') {
            if (v->n >= SIM_ARR_MAX) {
                return fail(c, "array longer than %d items", SIM_ARR_MAX);
            }
            int is_str = 0;
            if (parse_scalar(c, &p, &is_str, &v->nums[v->n], v->strs[v->n]) != 0) {
                return -1;
            }
            if (kind >= 0 && kind != is_str) {
                return fail(c, "array mixes numbers and strings");
            }
            kind = is_str;
            v->n++;
            p = skip_ws(p);
            if (*p == ',') {
                p = skip_ws(p + 1);
            } else if (*p != ']') {
                return fail(c, "expected ',' or ']' in array (arrays must be on one line)");
            }
        }
        p++;
        v->type = (kind == 1) ? V_STRARR : V_NUMARR;
    } else {
        int is_str = 0;
        if (parse_scalar(c, &p, &is_str, &v->num, v->str) != 0) {
            return -1;
        }
        v->type = is_str ? V_STR : V_NUM;
    }
    p = skip_ws(p);
    if (*p != '\0' && *p != '#') {
        return fail(c, "unexpected text after the value: '%s'", p);
    }
    return 0;
}

static const char *type_name(vtype_t t)
{
    switch (t) {
    case V_NUM: return "a number";
    case V_STR: return "a string";
    case V_BOOL: return "true/false";
    case V_NUMARR: return "an array of numbers";
    default: return "an array of strings";
    }
}

static int want(const ctx_t *c, const char *key, const value_t *v, vtype_t t)
{
    if (v->type != t) {
        return fail(c, "'%s' must be %s, got %s", key, type_name(t), type_name(v->type));
    }
    return 0;
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
    NK("", "stiffness_max_Npm", stiffness_max_Npm, 0.0, 1e8),
    NK("object", "surface_m", object.surface_m, -1.0, 1.0),
    NK("object", "k1_Npm", object.k1_Npm, 1e-6, 1e7),
    NK("object", "k2_Npm", object.k2_Npm, 1e-6, 1e7),
    NK("object", "layer_depth_m", object.layer_depth_m, 0.0, 1.0),
    NK("object", "d_v_Nspm", object.d_v_Nspm, 0.0, 1e5),
    NK("object", "m_v_kg", object.m_v_kg, 0.0, 1e4),
    NK("object", "skin_m", object.skin_m, 0.0, 0.1),
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
    NK("sensors", "force_noise_N", tip.noise_N, 0.0, 100.0),
    NK("sensors", "force_range_N", tip.range_N, 1e-3, 1e5),
    NK("sensors", "tip_bias_N", tip.bias_N, -100.0, 100.0),
    NK("sensors", "handle_bias_N", handle.bias_N, -100.0, 100.0),
    NK("sensors", "encoder_m", encoder_m, 0.0, 1e-2),
    NK("sensors", "vel_cutoff_Hz", vel_cutoff_Hz, 0.1, 499.0),
    NK("execute", "goal_scale", goal_scale, -100.0, 100.0),
    NK("execute", "time_scale", time_scale, 1e-3, 1e3),
    NK("execute", "phase_stop_gain_per_N2", phase_stop_gain_per_N2, 0.0, 1e6),
    NK("execute", "surface_error_m", surface_error_m, -0.1, 0.1),
    NK("fault", "at_s", fault.at_s, 0.0, 3600.0),
    NK("fault", "value", fault.value, -1e6, 1e6),
    NK("fault", "duration_s", fault.duration_s, 0.0, 1e9),
};

static int set_int(const ctx_t *c, const char *key, const value_t *v, double lo, double hi,
                   double *out)
{
    if (want(c, key, v, V_NUM) != 0) {
        return -1;
    }
    if (v->num != floor(v->num) || v->num < lo || v->num > hi) {
        return fail(c, "'%s' must be an integer in [%g, %g], got %g", key, lo, hi, v->num);
    }
    *out = v->num;
    return 0;
}

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
        return fail(c, "skill path too long");
    }
    return 0;
}

static int apply(sim_scenario_t *sc, const ctx_t *c, const char *sec, const char *key,
                 const value_t *v)
{
    for (size_t i = 0; i < sizeof NUM_KEYS / sizeof NUM_KEYS[0]; i++) {
        const num_key_t *k = &NUM_KEYS[i];
        if (strcmp(k->section, sec) == 0 && strcmp(k->key, key) == 0) {
            if (want(c, key, v, V_NUM) != 0) {
                return -1;
            }
            if (v->num < k->lo || v->num > k->hi) {
                return fail(c, "'%s' = %g is outside [%g, %g]", key, v->num, k->lo, k->hi);
            }
            *(double *)(void *)((char *)sc + k->offset) = v->num;
            if (strcmp(sec, "sensors") == 0 &&
                (strcmp(key, "force_noise_N") == 0 || strcmp(key, "force_range_N") == 0)) {
                /* both force sensors share noise and range */
                *(double *)(void *)((char *)&sc->handle +
                                    (k->offset - offsetof(sim_scenario_t, tip))) = v->num;
            }
            return 0;
        }
    }
    double n = 0.0;
    if (strcmp(sec, "") == 0) {
        if (strcmp(key, "name") == 0) {
            if (want(c, key, v, V_STR) != 0) {
                return -1;
            }
            snprintf(sc->name, sizeof sc->name, "%.63s", v->str);
            return 0;
        }
        if (strcmp(key, "mode") == 0 || strcmp(key, "plant") == 0) {
            if (want(c, key, v, V_STR) != 0) {
                return -1;
            }
            if (strcmp(key, "mode") == 0) {
                if (strcmp(v->str, "teach") == 0) {
                    sc->mode = SIM_MODE_TEACH;
                } else if (strcmp(v->str, "execute") == 0) {
                    sc->mode = SIM_MODE_EXECUTE;
                } else {
                    return fail(c, "mode must be \"teach\" or \"execute\", got \"%s\"", v->str);
                }
            } else if (strcmp(v->str, "ideal") == 0) {
                sc->plant = SIM_PLANT_IDEAL;
            } else if (strcmp(v->str, "realistic") == 0) {
                sc->plant = SIM_PLANT_REALISTIC;
            } else {
                return fail(c, "plant must be \"ideal\" or \"realistic\", got \"%s\"", v->str);
            }
            return 0;
        }
        if (strcmp(key, "seed") == 0) {
            if (set_int(c, key, v, 0.0, 9007199254740992.0, &n) != 0) {
                return -1;
            }
            sc->seed = (uint64_t)n;
            return 0;
        }
        if (strcmp(key, "substeps") == 0) {
            if (set_int(c, key, v, 1.0, 1000.0, &n) != 0) {
                return -1;
            }
            sc->substeps = (int)n;
            return 0;
        }
    } else if (strcmp(sec, "operator") == 0 && strcmp(key, "task") == 0) {
        if (want(c, key, v, V_STR) != 0) {
            return -1;
        }
        if (strcmp(v->str, "pressing") == 0) {
            sc->op.task = SIM_TASK_PRESSING;
        } else if (strcmp(v->str, "engraving") == 0) {
            sc->op.task = SIM_TASK_ENGRAVING;
        } else if (strcmp(v->str, "none") == 0) {
            sc->op.task = SIM_TASK_NONE;
        } else {
            return fail(c, "task must be \"pressing\", \"engraving\" or \"none\", got \"%s\"",
                        v->str);
        }
        return 0;
    } else if (strcmp(sec, "sensors") == 0) {
        if (strcmp(key, "force_bits") == 0) {
            if (set_int(c, key, v, 0.0, 32.0, &n) != 0) {
                return -1;
            }
            sc->tip.bits = (unsigned)n;
            sc->handle.bits = (unsigned)n;
            return 0;
        }
        if (strcmp(key, "delay_samples") == 0) {
            if (set_int(c, key, v, 0.0, 4.0, &n) != 0) {
                return -1;
            }
            sc->delay_samples = (int)n;
            return 0;
        }
    } else if (strcmp(sec, "execute") == 0) {
        if (strcmp(key, "skills") == 0) {
            if (v->type == V_STR) {
                sc->n_skills = 1;
                return resolve_path(c, sc, sc->skill_path[0], v->str);
            }
            if (want(c, key, v, V_STRARR) != 0) {
                return -1;
            }
            sc->n_skills = v->n;
            for (int i = 0; i < v->n; i++) {
                if (resolve_path(c, sc, sc->skill_path[i], v->strs[i]) != 0) {
                    return -1;
                }
            }
            return 0;
        }
        if (strcmp(key, "step_durations_s") == 0) {
            if (want(c, key, v, V_NUMARR) != 0) {
                return -1;
            }
            for (int i = 0; i < v->n; i++) {
                if (!(v->nums[i] > 0.0 && v->nums[i] <= 3600.0)) {
                    return fail(c, "step_durations_s[%d] = %g must be in (0, 3600]", i, v->nums[i]);
                }
                sc->step_duration_s[i] = v->nums[i];
            }
            sc->n_step_durations = v->n;
            return 0;
        }
        if (strcmp(key, "model") == 0) {
            if (want(c, key, v, V_STR) != 0) {
                return -1;
            }
            if (strcmp(v->str, "object") == 0) {
                sc->use_model = 1;
            } else if (strcmp(v->str, "none") == 0) {
                sc->use_model = 0;
            } else {
                return fail(c, "model must be \"object\" or \"none\", got \"%s\"", v->str);
            }
            return 0;
        }
        if (strcmp(key, "end_policy") == 0) {
            if (want(c, key, v, V_STR) != 0) {
                return -1;
            }
            if (strcmp(v->str, "skill") == 0) {
                sc->end_policy = -1;
            } else if (strcmp(v->str, "hold") == 0) {
                sc->end_policy = 0;
            } else if (strcmp(v->str, "release") == 0) {
                sc->end_policy = 1;
            } else {
                return fail(c, "end_policy must be \"skill\", \"hold\" or \"release\", got \"%s\"",
                            v->str);
            }
            return 0;
        }
        if (strcmp(key, "surface") == 0) {
            if (want(c, key, v, V_STR) != 0) {
                return -1;
            }
            if (strcmp(v->str, "config") == 0) {
                sc->surface_from_contact = 0;
            } else if (strcmp(v->str, "contact") == 0) {
                sc->surface_from_contact = 1;
            } else {
                return fail(c, "surface must be \"config\" or \"contact\", got \"%s\"", v->str);
            }
            return 0;
        }
    } else if (strcmp(sec, "fault") == 0 && strcmp(key, "kind") == 0) {
        static const char *const names[] = {"none",        "force_spike",  "force_nan",
                                            "force_stuck", "encoder_jump", "actuator_saturation"};
        if (want(c, key, v, V_STR) != 0) {
            return -1;
        }
        for (int i = 0; i < 6; i++) {
            if (strcmp(v->str, names[i]) == 0) {
                sc->fault.kind = (sim_fault_kind_t)i;
                return 0;
            }
        }
        return fail(c,
                    "fault kind must be one of none, force_spike, force_nan, force_stuck, "
                    "encoder_jump, actuator_saturation; got \"%s\"",
                    v->str);
    }
    if (sec[0] == '\0') {
        return fail(c, "unknown key '%s'", key);
    }
    return fail(c, "unknown key '%s' in [%s]", key, sec);
}

static const char *const SECTIONS[] = {"object",  "carriage", "operator",
                                       "sensors", "execute",  "fault"};

int sim_scenario_parse(sim_scenario_t *sc, const char *text, const char *name,
                       char err[SIM_ERR_MAX])
{
    static value_t v; /* large (arrays of paths): not on the stack */
    ctx_t c = {name, 0, err};
    char section[32] = "";
    const char *p = text;
    char line[2048];
    while (*p != '\0') {
        const char *nl = strchr(p, '\n');
        size_t len = nl ? (size_t)(nl - p) : strlen(p);
        c.line++;
        if (len >= sizeof line) {
            return fail(&c, "line longer than %zu characters", sizeof line - 1);
        }
        memcpy(line, p, len);
        line[len] = '\0';
        p = nl ? nl + 1 : p + len;
        if (len > 0 && line[len - 1] == '\r') {
            line[len - 1] = '\0';
        }
        char *s = skip_ws(line);
        if (*s == '\0' || *s == '#') {
            continue;
        }
        if (*s == '[') {
            char *e = strchr(s, ']');
            if (e == NULL) {
                return fail(&c, "section header without ']'");
            }
            *e = '\0';
            char *rest = skip_ws(e + 1);
            if (*rest != '\0' && *rest != '#') {
                return fail(&c, "unexpected text after the section header");
            }
            const char *nm = skip_ws(s + 1);
            int known = 0;
            for (size_t i = 0; i < sizeof SECTIONS / sizeof SECTIONS[0]; i++) {
                if (strcmp(nm, SECTIONS[i]) == 0) {
                    known = 1;
                }
            }
            if (!known) {
                return fail(&c,
                            "unknown section [%s] (known: object, carriage, operator, "
                            "sensors, execute, fault)",
                            nm);
            }
            snprintf(section, sizeof section, "%s", nm);
            continue;
        }
        char *eq = strchr(s, '=');
        if (eq == NULL) {
            return fail(&c, "expected 'key = value'");
        }
        char *ke = eq;
        while (ke > s && (ke[-1] == ' ' || ke[-1] == '\t')) {
            ke--;
        }
        *ke = '\0';
        for (char *q = s; *q; q++) {
            if (!(isalnum((unsigned char)*q) || *q == '_')) {
                return fail(&c, "invalid key '%s'", s);
            }
        }
        if (*s == '\0') {
            return fail(&c, "empty key");
        }
        memset(&v, 0, sizeof v);
        if (parse_value(&c, eq + 1, &v) != 0) {
            return -1;
        }
        if (apply(sc, &c, section, s, &v) != 0) {
            return -1;
        }
    }
    return 0;
}

int sim_scenario_load(sim_scenario_t *sc, const char *path, char err[SIM_ERR_MAX])
{
    FILE *f = fopen(path, "rb");
    if (f == NULL) {
        snprintf(err, SIM_ERR_MAX, "%s: cannot open scenario: %s", path, strerror(errno));
        return -1;
    }
    static char text[1 << 16];
    size_t n = fread(text, 1, sizeof text - 1, f);
    int too_long = !feof(f);
    fclose(f);
    if (too_long) {
        snprintf(err, SIM_ERR_MAX, "%s: scenario larger than %zu bytes", path, sizeof text - 1);
        return -1;
    }
    text[n] = '\0';
    if (strlen(text) != n) {
        snprintf(err, SIM_ERR_MAX, "%s: scenario contains a NUL byte", path);
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

/* Fault scenario files: see fault_scenario.h. */
#include "fault_scenario.h"

#include <stdio.h>
#include <string.h>

static const char *const KINDS[] = {"host_silence", "host_corrupt",        "bus_off",
                                    "force_spike",  "force_nan",           "force_stuck",
                                    "encoder_jump", "actuator_saturation", "host_loss",
                                    "force_limit",  "tick_overrun",        "power_loss_upload"};
static const char *const PLANT_MODELS[] = {"ideal", "realistic"};

/* The string keys, as (key, field) of an fscen_t. */
typedef struct {
    const char *key;
    size_t offset;
    size_t cap;
} str_key_t;

#define SK(k, field)                                               \
    {                                                              \
        k, offsetof(fscen_t, field), sizeof(((fscen_t *)0)->field) \
    }
static const str_key_t STR_KEYS[] = {
    SK("name", name),
    SK("description", description),
    SK("plant", plant),
    SK("skill", skill),
    SK("neighbour_skill", neighbour),
    SK("new_skill", new_skill),
    SK("bound_text", bound_text),
};

/* The number keys and their ranges. */
typedef struct {
    const char *key;
    size_t offset;
    double lo, hi;
} num_key_t;

#define NK(k, field, lo, hi)                \
    {                                       \
        k, offsetof(fscen_t, field), lo, hi \
    }
static const num_key_t NUM_KEYS[] = {
    NK("goal_scale", goal_scale, -100.0, 100.0),
    NK("time_scale", time_scale, 1e-3, 1e3),
    NK("at_s", at_s, 0.0, 3600.0),
    NK("value", value, -1e6, 1e6),
    NK("duration_s", duration_s, 0.0, 3600.0),
    NK("detect_bound_ms", detect_bound_ms, 0.0, 1e6),
    NK("force_max_N", force_max_N, 0.0, 1e4),
};

/* One key of a fault scenario (sim_toml_apply_fn). */
static int apply(void *user, const sim_toml_ctx_t *c, const char *sec, const char *key,
                 const sim_toml_value_t *v)
{
    fscen_t *s = user;
    char *base = (char *)s;
    int i = 0;
    double n = 0.0;
    (void)sec; /* a flat file: the reader refuses every section */
    for (size_t k = 0; k < sizeof STR_KEYS / sizeof STR_KEYS[0]; k++) {
        if (strcmp(key, STR_KEYS[k].key) == 0) {
            return sim_toml_string(c, key, v, base + STR_KEYS[k].offset, STR_KEYS[k].cap);
        }
    }
    for (size_t k = 0; k < sizeof NUM_KEYS / sizeof NUM_KEYS[0]; k++) {
        if (strcmp(key, NUM_KEYS[k].key) == 0) {
            return sim_toml_number(c, key, v, NUM_KEYS[k].lo, NUM_KEYS[k].hi,
                                   (double *)(void *)(base + NUM_KEYS[k].offset));
        }
    }
    if (strcmp(key, "kind") == 0) {
        if (sim_toml_choice(c, key, v, "kind", KINDS, (int)(sizeof KINDS / sizeof KINDS[0]), &i) !=
            0) {
            return -1;
        }
        snprintf(s->kind, sizeof s->kind, "%s", KINDS[i]);
        return 0;
    }
    if (strcmp(key, "plant_model") == 0) {
        if (sim_toml_choice(c, key, v, "plant_model", PLANT_MODELS, 2, &i) != 0) {
            return -1;
        }
        snprintf(s->plant_model, sizeof s->plant_model, "%s", PLANT_MODELS[i]);
        return 0;
    }
    if (strcmp(key, "expect_code") == 0) {
        if (sim_toml_integer(c, key, v, 0.0, 65535.0, &n) != 0) {
            return -1;
        }
        s->expect_code = (int)n;
        return 0;
    }
    return sim_toml_fail(c, "unknown key '%s'", key);
}

void fscen_defaults(fscen_t *s)
{
    memset(s, 0, sizeof(*s));
    s->goal_scale = 1.0;
    s->time_scale = 1.0;
    s->duration_s = 0.001;
    s->detect_bound_ms = 1.0;
}

void fscen_join(char *out, const char *dir, const char *rel)
{
    if (rel[0] == '/') {
        snprintf(out, SIM_PATH_MAX, "%s", rel);
    } else {
        snprintf(out, SIM_PATH_MAX, "%.*s/%.*s", 200, dir, 300, rel);
    }
}

int fscen_parse(fscen_t *s, const char *text, const char *name, char err[SIM_ERR_MAX])
{
    if (sim_toml_parse(text, name, NULL, 0u, apply, s, err) != 0) {
        return -1;
    }
    if (s->name[0] == '\0' || s->plant[0] == '\0' || s->skill[0] == '\0' ||
        s->neighbour[0] == '\0' || s->kind[0] == '\0') {
        snprintf(err, SIM_ERR_MAX, "%s: needs name, plant, skill, neighbour_skill and kind", name);
        return -1;
    }
    if (strcmp(s->kind, "power_loss_upload") == 0 && s->new_skill[0] == '\0') {
        snprintf(err, SIM_ERR_MAX, "%s: power_loss_upload needs new_skill", name);
        return -1;
    }
    return 0;
}

int fscen_load(fscen_t *s, const char *path, char err[SIM_ERR_MAX])
{
    fscen_defaults(s);
    snprintf(s->file, sizeof s->file, "%s", path);
    snprintf(s->dir, sizeof s->dir, "%s", path);
    char *slash = strrchr(s->dir, '/');
    if (slash != NULL) {
        *slash = '\0';
    } else {
        snprintf(s->dir, sizeof s->dir, ".");
    }
    const char *text = sim_toml_load(path, "fault scenario", err);
    return text == NULL ? -1 : fscen_parse(s, text, path, err);
}

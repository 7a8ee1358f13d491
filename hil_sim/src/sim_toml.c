/* The simulator's TOML-subset reader: see sim_toml.h. */
#include "sim_toml.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define LINE_MAX_CHARS 2048

int sim_toml_fail(const sim_toml_ctx_t *c, const char *fmt, ...)
{
    char msg[SIM_ERR_MAX / 2];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    snprintf(c->err, SIM_ERR_MAX, "%s:%d: %s", c->file, c->line, msg);
    return -1;
}

static char *skip_ws(char *p)
{
    while (*p == ' ' || *p == '\t') {
        p++;
    }
    return p;
}

/* A "string" at p (p on the opening quote): \" and \\ escape; *pp after the closing quote. */
static int parse_string(const sim_toml_ctx_t *c, char **pp, char *str)
{
    char *p = *pp + 1;
    size_t n = 0;
    while (*p != '"') {
        if (*p == '\0') {
            return sim_toml_fail(c, "unterminated string");
        }
        if (*p == '\\' && (p[1] == '"' || p[1] == '\\')) {
            p++;
        }
        if (n + 1 >= SIM_PATH_MAX) {
            return sim_toml_fail(c, "string longer than %d characters", SIM_PATH_MAX - 1);
        }
        str[n++] = *p++;
    }
    str[n] = '\0';
    *pp = p + 1;
    return 0;
}

/* Parse one scalar at *pp (number or string); advances *pp. */
static int parse_scalar(const sim_toml_ctx_t *c, char **pp, int *is_str, double *num, char *str)
{
    char *p = skip_ws(*pp);
    if (*p == '"') {
        *pp = p;
        *is_str = 1;
        return parse_string(c, pp, str);
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
        return sim_toml_fail(c, "expected a number, a \"string\", true or false, got '%s'", tok);
    }
    if (errno == ERANGE || !isfinite(v)) {
        return sim_toml_fail(c, "number out of range");
    }
    *num = v;
    *is_str = 0;
    *pp = end;
    return 0;
}

/* A one-line array at *pp (on the '['): numbers or strings, not both. */
static int parse_array(const sim_toml_ctx_t *c, char **pp, sim_toml_value_t *v)
{
    char *p = skip_ws(*pp + 1);
    int kind = -1;
    v->n = 0;
    while (*p != ']') {
        if (v->n >= SIM_TOML_ARR_MAX) {
            return sim_toml_fail(c, "array longer than %d items", SIM_TOML_ARR_MAX);
        }
        int is_str = 0;
        if (parse_scalar(c, &p, &is_str, &v->nums[v->n], v->strs[v->n]) != 0) {
            return -1;
        }
        if (kind >= 0 && kind != is_str) {
            return sim_toml_fail(c, "array mixes numbers and strings");
        }
        kind = is_str;
        v->n++;
        p = skip_ws(p);
        if (*p == ',') {
            p = skip_ws(p + 1);
        } else if (*p != ']') {
            return sim_toml_fail(c, "expected ',' or ']' in array (arrays must be on one line)");
        }
    }
    *pp = p + 1;
    v->type = (kind == 1) ? SIM_TOML_STRARR : SIM_TOML_NUMARR;
    return 0;
}

static int parse_value(const sim_toml_ctx_t *c, char *p, sim_toml_value_t *v)
{
    p = skip_ws(p);
    if (strncmp(p, "true", 4) == 0 || strncmp(p, "false", 5) == 0) {
        v->type = SIM_TOML_BOOL;
        v->b = (p[0] == 't');
        p += v->b ? 4 : 5;
    } else if (*p == '[') {
        if (parse_array(c, &p, v) != 0) {
            return -1;
        }
    } else {
        int is_str = 0;
        if (parse_scalar(c, &p, &is_str, &v->num, v->str) != 0) {
            return -1;
        }
        v->type = is_str ? SIM_TOML_STR : SIM_TOML_NUM;
    }
    p = skip_ws(p);
    if (*p != '\0' && *p != '#') {
        return sim_toml_fail(c, "unexpected text after the value: '%s'", p);
    }
    return 0;
}

/* A [section] header at s (on the '['): the name into section if it is one of sections. */
static int parse_header(const sim_toml_ctx_t *c, char *s, const char *const *sections,
                        size_t n_sections, char *section, size_t cap)
{
    char *e = strchr(s, ']');
    if (e == NULL) {
        return sim_toml_fail(c, "section header without ']'");
    }
    *e = '\0';
    const char *rest = skip_ws(e + 1);
    if (*rest != '\0' && *rest != '#') {
        return sim_toml_fail(c, "unexpected text after the section header");
    }
    const char *nm = skip_ws(s + 1);
    char known[256] = "";
    size_t used = 0;
    for (size_t i = 0; i < n_sections; i++) {
        if (strcmp(nm, sections[i]) == 0) {
            snprintf(section, cap, "%s", nm);
            return 0;
        }
        int w = snprintf(known + used, sizeof known - used, "%s%s", i ? ", " : "", sections[i]);
        used += (w > 0 && (size_t)w < sizeof known - used) ? (size_t)w : 0u;
    }
    if (n_sections == 0u) {
        return sim_toml_fail(c, "unknown section [%s] (this file has no sections)", nm);
    }
    return sim_toml_fail(c, "unknown section [%s] (known: %s)", nm, known);
}

/* `key = value` at s: the key is cut in place, the value parsed into v. */
static int parse_pair(const sim_toml_ctx_t *c, char *s, char **key, sim_toml_value_t *v)
{
    char *eq = strchr(s, '=');
    if (eq == NULL) {
        return sim_toml_fail(c, "expected 'key = value'");
    }
    char *ke = eq;
    while (ke > s && (ke[-1] == ' ' || ke[-1] == '\t')) {
        ke--;
    }
    *ke = '\0';
    for (const char *q = s; *q; q++) {
        if (!(isalnum((unsigned char)*q) || *q == '_')) {
            return sim_toml_fail(c, "invalid key '%s'", s);
        }
    }
    if (*s == '\0') {
        return sim_toml_fail(c, "empty key");
    }
    *key = s;
    memset(v, 0, sizeof *v);
    return parse_value(c, eq + 1, v);
}

int sim_toml_parse(const char *text, const char *name, const char *const *sections,
                   size_t n_sections, sim_toml_apply_fn apply, void *user, char err[SIM_ERR_MAX])
{
    static sim_toml_value_t v; /* large (arrays of paths): not on the stack */
    sim_toml_ctx_t c = {name, 0, err};
    char section[32] = "";
    const char *p = text;
    char line[LINE_MAX_CHARS];
    while (*p != '\0') {
        const char *nl = strchr(p, '\n');
        size_t len = nl ? (size_t)(nl - p) : strlen(p);
        c.line++;
        if (len >= sizeof line) {
            return sim_toml_fail(&c, "line longer than %zu characters", sizeof line - 1);
        }
        memcpy(line, p, len);
        line[len] = '\0';
        p = nl ? nl + 1 : p + len;
        if (len > 0 && line[len - 1] == '\r') {
            line[len - 1] = '\0';
        }
        char *s = skip_ws(line);
        char *key = NULL;
        if (*s == '\0' || *s == '#') {
            continue;
        }
        if (*s == '[') {
            if (parse_header(&c, s, sections, n_sections, section, sizeof section) != 0) {
                return -1;
            }
        } else if (parse_pair(&c, s, &key, &v) != 0 || apply(user, &c, section, key, &v) != 0) {
            return -1;
        }
    }
    return 0;
}

const char *sim_toml_load(const char *path, const char *what, char err[SIM_ERR_MAX])
{
    static char text[SIM_TOML_TEXT_MAX];
    FILE *f = fopen(path, "rb");
    if (f == NULL) {
        snprintf(err, SIM_ERR_MAX, "%s: cannot open %s: %s", path, what, strerror(errno));
        return NULL;
    }
    size_t n = fread(text, 1, sizeof text - 1, f);
    int too_long = !feof(f);
    fclose(f);
    if (too_long) {
        snprintf(err, SIM_ERR_MAX, "%s: %s larger than %zu bytes", path, what, sizeof text - 1);
        return NULL;
    }
    text[n] = '\0';
    if (strlen(text) != n) {
        snprintf(err, SIM_ERR_MAX, "%s: %s contains a NUL byte", path, what);
        return NULL;
    }
    return text;
}

static const char *type_name(sim_toml_type_t t)
{
    switch (t) {
    case SIM_TOML_NUM: return "a number";
    case SIM_TOML_STR: return "a string";
    case SIM_TOML_BOOL: return "true/false";
    case SIM_TOML_NUMARR: return "an array of numbers";
    default: return "an array of strings";
    }
}

int sim_toml_want(const sim_toml_ctx_t *c, const char *key, const sim_toml_value_t *v,
                  sim_toml_type_t t)
{
    if (v->type != t) {
        return sim_toml_fail(c, "'%s' must be %s, got %s", key, type_name(t), type_name(v->type));
    }
    return 0;
}

int sim_toml_number(const sim_toml_ctx_t *c, const char *key, const sim_toml_value_t *v, double lo,
                    double hi, double *out)
{
    if (sim_toml_want(c, key, v, SIM_TOML_NUM) != 0) {
        return -1;
    }
    if (v->num < lo || v->num > hi) {
        return sim_toml_fail(c, "'%s' = %g is outside [%g, %g]", key, v->num, lo, hi);
    }
    *out = v->num;
    return 0;
}

int sim_toml_integer(const sim_toml_ctx_t *c, const char *key, const sim_toml_value_t *v, double lo,
                     double hi, double *out)
{
    if (sim_toml_want(c, key, v, SIM_TOML_NUM) != 0) {
        return -1;
    }
    if (v->num != floor(v->num) || v->num < lo || v->num > hi) {
        return sim_toml_fail(c, "'%s' must be an integer in [%g, %g], got %g", key, lo, hi, v->num);
    }
    *out = v->num;
    return 0;
}

int sim_toml_string(const sim_toml_ctx_t *c, const char *key, const sim_toml_value_t *v, char *out,
                    size_t cap)
{
    if (sim_toml_want(c, key, v, SIM_TOML_STR) != 0) {
        return -1;
    }
    if (strlen(v->str) >= cap) {
        return sim_toml_fail(c, "'%s' is longer than %zu characters", key, cap - 1u);
    }
    snprintf(out, cap, "%s", v->str);
    return 0;
}

int sim_toml_choice(const sim_toml_ctx_t *c, const char *key, const sim_toml_value_t *v,
                    const char *what, const char *const *names, int n, int *out)
{
    if (sim_toml_want(c, key, v, SIM_TOML_STR) != 0) {
        return -1;
    }
    char list[256] = "";
    size_t used = 0;
    for (int i = 0; i < n; i++) {
        if (strcmp(v->str, names[i]) == 0) {
            *out = i;
            return 0;
        }
        /* up to three: "a", "b" or "c"; more: one of a, b, c */
        const char *sep = i == 0 ? "" : (n <= 3 && i == n - 1) ? " or " : ", ";
        const char *q = n <= 3 ? "\"" : "";
        int w = snprintf(list + used, sizeof list - used, "%s%s%s%s", sep, q, names[i], q);
        used += (w > 0 && (size_t)w < sizeof list - used) ? (size_t)w : 0u;
    }
    if (n <= 3) {
        return sim_toml_fail(c, "%s must be %s, got \"%s\"", what, list, v->str);
    }
    return sim_toml_fail(c, "%s must be one of %s; got \"%s\"", what, list, v->str);
}

/* The one TOML-subset reader of the simulator's input files (scenarios of `hil_sim run` and
 * `hil_sim serve`, fault scenarios of `hil_sim faults`): comments (#), [section] headers,
 * key = value with value a number, a "string", true/false, or a one-line array of numbers or
 * strings. The reader splits lines and values; the caller's apply function gives each key its
 * meaning. Every error is one line "file:line: message" (no newline). */
#ifndef SIM_TOML_H
#define SIM_TOML_H

#include <stddef.h>

#define SIM_PATH_MAX 512 /* longest string value and path, NUL included */
#define SIM_TOML_ARR_MAX 8
#define SIM_ERR_MAX 640
#define SIM_TOML_TEXT_MAX (1 << 16) /* largest file sim_toml_load reads */

typedef enum {
    SIM_TOML_NUM,
    SIM_TOML_STR,
    SIM_TOML_BOOL,
    SIM_TOML_NUMARR,
    SIM_TOML_STRARR
} sim_toml_type_t;

/** One parsed value: the fields of its type are set. */
typedef struct {
    sim_toml_type_t type;
    double num;
    int b;
    char str[SIM_PATH_MAX];
    int n; /* array items */
    double nums[SIM_TOML_ARR_MAX];
    char strs[SIM_TOML_ARR_MAX][SIM_PATH_MAX];
} sim_toml_value_t;

/** Where the reader is: file name and 1-based line, for messages. */
typedef struct {
    const char *file;
    int line;
    char *err; /* SIM_ERR_MAX bytes */
} sim_toml_ctx_t;

/** Gives key (in section, "" before the first header) its value; 0, or -1 after sim_toml_fail. */
typedef int (*sim_toml_apply_fn)(void *user, const sim_toml_ctx_t *c, const char *section,
                                 const char *key, const sim_toml_value_t *v);

/** Parse text; sections lists the allowed [section] names (n_sections may be 0: a flat file).
 *  Calls apply for every key in file order; stops at the first error (-1, message in err). */
int sim_toml_parse(const char *text, const char *name, const char *const *sections,
                   size_t n_sections, sim_toml_apply_fn apply, void *user, char err[SIM_ERR_MAX]);

/** Read a whole file (at most SIM_TOML_TEXT_MAX - 1 bytes, no NUL byte; what names it in
 *  messages) into a static buffer reused by the next call; NULL with "path: problem" in err. */
const char *sim_toml_load(const char *path, const char *what, char err[SIM_ERR_MAX]);

/** Write "file:line: message" into c->err; returns -1. */
int sim_toml_fail(const sim_toml_ctx_t *c, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));

/** 0 if v has type t, else -1 with "'key' must be <t>, got <type>". */
int sim_toml_want(const sim_toml_ctx_t *c, const char *key, const sim_toml_value_t *v,
                  sim_toml_type_t t);

/** A number in [lo, hi] into *out; -1 with "'key' = v is outside [lo, hi]" otherwise. */
int sim_toml_number(const sim_toml_ctx_t *c, const char *key, const sim_toml_value_t *v, double lo,
                    double hi, double *out);

/** An integer in [lo, hi] into *out; -1 with "'key' must be an integer in [lo, hi]" otherwise. */
int sim_toml_integer(const sim_toml_ctx_t *c, const char *key, const sim_toml_value_t *v, double lo,
                     double hi, double *out);

/** A string into out (cap bytes, cap > 0); -1 if v is not a string or does not fit. */
int sim_toml_string(const sim_toml_ctx_t *c, const char *key, const sim_toml_value_t *v, char *out,
                    size_t cap);

/** The index of v among names[0..n) into *out; -1 with "what must be "a", "b" or "c", got "x"". */
int sim_toml_choice(const sim_toml_ctx_t *c, const char *key, const sim_toml_value_t *v,
                    const char *what, const char *const *names, int n, int *out);

#endif /* SIM_TOML_H */

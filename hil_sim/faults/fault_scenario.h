/* Fault scenario files of `hil_sim faults` (hil_sim/scenarios/faults/README.md): flat
 * key = value files read by the simulator's one TOML-subset reader (sim_toml.h). */
#ifndef FAULT_SCENARIO_H
#define FAULT_SCENARIO_H

#include "sim_toml.h"

/** One fault scenario; paths as written in the file (relative to dir). */
typedef struct {
    char file[SIM_PATH_MAX];
    char dir[SIM_PATH_MAX];
    char name[64];
    char description[256];
    char plant[SIM_PATH_MAX];
    char skill[SIM_PATH_MAX];
    char neighbour[SIM_PATH_MAX];
    char new_skill[SIM_PATH_MAX];
    char kind[32];
    char bound_text[64];
    char plant_model[16]; /* "" = the plant file's; "ideal" / "realistic" */
    double goal_scale, time_scale, at_s, value, duration_s;
    double force_max_N; /* device force limit for this scenario (0: the plant file's) */
    int expect_code;
    double detect_bound_ms;
} fscen_t;

/** Read a fault scenario file into s (defaults first); -1 with a one-line "file:line: message". */
int fscen_load(fscen_t *s, const char *path, char err[SIM_ERR_MAX]);

/** Parse fault scenario text (name in messages, relative paths against s->dir); same rules. */
int fscen_parse(fscen_t *s, const char *text, const char *name, char err[SIM_ERR_MAX]);

/** Defaults of a fault scenario (goal and time scale 1, duration 1 ms, bound 1 ms). */
void fscen_defaults(fscen_t *s);

/** Join dir and a relative path (an absolute rel is kept) into out (SIM_PATH_MAX bytes). */
void fscen_join(char *out, const char *dir, const char *rel);

#endif /* FAULT_SCENARIO_H */

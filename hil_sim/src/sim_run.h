/* Lockstep run of a scenario: the simulator owns the clock; each 1 ms firmware tick samples the
 * sensors, runs the firmware (fs_exec: DMP + parallel force/position law, or the TEACH
 * rendering), then integrates the plant in substeps. Deterministic for a seed. */
#ifndef SIM_RUN_H
#define SIM_RUN_H

#include <stdint.h>
#include <stdio.h>
#include "sim_scenario.h"
#include "skill.h"

/** Figures of one run (written as LOG.summary.json). */
typedef struct {
    uint64_t ticks;
    double sim_time_s;
    double max_force_N;       /* max logged contact force */
    double max_operator_N;    /* max logged operator force */
    double max_cmd_abs_N;     /* max |f_cmd| (x and y) */
    double max_hat_N;         /* max f_hat */
    double deformation_max_m; /* max true p = x - surface */
    double layer_reached_s;   /* first time p >= layer depth, -1 if never */
    double tracking_max_pct;  /* EXECUTE: max |f_contact - f_hat| / max f_hat */
    double tracking_rms_pct;
    uint64_t limit_violations; /* ticks with |f_cmd| > force_max_N */
    uint64_t saturated_ticks;  /* ticks with |f_cmd| at the limit */
    uint64_t nonfinite_ticks;  /* ticks where the firmware refused a non-finite measurement */
    double wall_s;
    double x_realtime;
} sim_summary_t;

/** Load and parse every skill of the scenario into skills[0..n_skills). -1 + message on error. */
int sim_load_skills(const sim_scenario_t *sc, skill_t *skills, char err[SIM_ERR_MAX]);

/** Run a checked scenario. log may be NULL (no CSV). Returns 0, or -1 with a message. */
int sim_run(const sim_scenario_t *sc, const skill_t *skills, FILE *log, sim_summary_t *sum,
            char err[SIM_ERR_MAX]);

/** Write the summary as JSON (scenario name, seed and the figures). */
int sim_write_summary(const sim_scenario_t *sc, const sim_summary_t *sum, const char *path);

#endif /* SIM_RUN_H */

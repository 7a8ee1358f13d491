/* Lockstep run of a scenario: the simulator owns the clock; each 1 ms tick samples the sensors,
 * runs the device application's tick (firmware/app app_tick on the host port of hal.h: state
 * machine, fs_exec, safety supervisor; the skills in its flash slots, the host's frames on its
 * simulated CAN queues), then integrates the plant in substeps (sim_couple.h, as hil_sim serve
 * and the fault rig). Deterministic for a seed. */
#ifndef SIM_RUN_H
#define SIM_RUN_H

#include <stdint.h>
#include <stdio.h>
#include "sim_scenario.h"
#include "skill.h"

/** One skill image as read from its file (validated by sim_load_skills). */
typedef struct {
    uint8_t data[SKILL_IMAGE_MAX + 1u];
    uint32_t len;
} sim_skill_image_t;

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
    double tracking_max_pct;  /* max |f_contact - f_hat| / max f_hat over the exec_ticks */
    double tracking_rms_pct;
    uint64_t limit_violations; /* ticks with |f_cmd| > force_max_N */
    uint64_t saturated_ticks;  /* ticks with |f_cmd| at the limit */
    uint64_t nonfinite_ticks;  /* ticks where the device saw a non-finite sensor reading */
    uint16_t fault_code;       /* the device's first fault (emergency frame), 0 if none */
    double fault_s;            /* when it latched, -1 if none */
    int final_state;           /* the device's state after the last tick (app_state_t) */
    uint64_t exec_ticks;       /* ticks the device ran in EXECUTE (the tracking figures' ticks) */
    double wall_s;
    double x_realtime;
} sim_summary_t;

/** Read every skill image of the scenario into images[0..n_skills), each checked by skill_parse.
 *  -1 + message on error. */
int sim_load_skills(const sim_scenario_t *sc, sim_skill_image_t *images, char err[SIM_ERR_MAX]);

/** Run a checked scenario: the skills go into the device's flash slots 1..n_skills. log may be
 *  NULL (no CSV). Returns 0, or -1 with a message. One run at a time (the host port is global). */
int sim_run(const sim_scenario_t *sc, const sim_skill_image_t *skills, FILE *log,
            sim_summary_t *sum, char err[SIM_ERR_MAX]);

/** Write the summary as JSON (scenario name, seed and the figures). */
int sim_write_summary(const sim_scenario_t *sc, const sim_summary_t *sum, const char *path);

#endif /* SIM_RUN_H */

/* Scenario files (docs/hil.md "Scenario format"), read by sim_toml.h's TOML subset: comments
 * (#), [section] headers, key = value with value a number, a "string", true/false, or a one-line
 * array of numbers or strings. Unknown sections/keys are errors (typos must not silently fall
 * back to defaults). Errors name file:line and the problem. */
#ifndef SIM_SCENARIO_H
#define SIM_SCENARIO_H

#include <stdint.h>
#include "sim_model.h"
#include "sim_toml.h"

#define SIM_MAX_SKILLS SIM_TOML_ARR_MAX

typedef enum {
    SIM_MODE_TEACH = 0,
    SIM_MODE_EXECUTE = 1
} sim_mode_t;

typedef enum {
    SIM_FAULT_NONE = 0,
    SIM_FAULT_FORCE_SPIKE,        /* tip sensor reads +value N extra for duration_s */
    SIM_FAULT_FORCE_NAN,          /* tip sensor reads NaN from at_s for duration_s */
    SIM_FAULT_FORCE_STUCK,        /* tip sensor repeats its reading at at_s for duration_s */
    SIM_FAULT_ENCODER_JUMP,       /* x encoder reads +value m from at_s on */
    SIM_FAULT_ACTUATOR_SATURATION /* actuator limited to value N from at_s for duration_s */
} sim_fault_kind_t;

/** One injected fault. */
typedef struct {
    sim_fault_kind_t kind;
    double at_s;
    double value;
    double duration_s;
} sim_fault_t;

/** Everything a run needs. Defaults: the figures of docs/hil.md (sim_scenario_defaults). */
typedef struct {
    char name[64];
    char path[SIM_PATH_MAX];
    char dir[SIM_PATH_MAX]; /* folder of the scenario file (relative skill paths) */
    sim_mode_t mode;
    sim_plant_kind_t plant;
    double duration_s; /* <= 0 in EXECUTE: sum of step durations + tail_s */
    double tail_s;
    double dt_s;  /* firmware tick, 1 ms */
    int substeps; /* plant substeps per tick (10 -> 0.1 ms) */
    uint64_t seed;
    double start_x_m, start_y_m;
    double m_d_kg;      /* rendered inertia (gains.m_d) */
    double force_max_N; /* F_max at the last stage (50 N) */
    double
        stiffness_max_Npm; /* the device's skill stiffness limit (0: its default for the plant) */
    sim_object_t object;
    /* [object] away_*: during an execution the object's surface moves away by away_m from
     * away_at_s for away_for_s (the surface ends under the tool, or the operator lifts the part),
     * over away_ramp_s each way (0: a step), then comes back */
    double away_at_s, away_for_s, away_m, away_ramp_s;
    /* [object] gives_*: during an execution the inner layer gives way at gives_at_s, its
     * stiffness k2 becoming gives_k2_Npm (0: it never does) */
    double gives_at_s, gives_k2_Npm;
    sim_carriage_t carriage;
    sim_operator_cfg_t op;
    sim_force_sensor_t tip, handle;
    double encoder_m;
    int delay_samples;    /* sensor pipeline delay in ticks (0..4) */
    double vel_cutoff_Hz; /* firmware velocity filter */
    /* execute */
    int n_skills;
    char skill_path[SIM_MAX_SKILLS][SIM_PATH_MAX];
    int n_step_durations;
    double step_duration_s[SIM_MAX_SKILLS];
    double goal_scale, time_scale;
    double path_scale; /* the y path of skills with a y DMP, about its start */
    int use_model;     /* 1: invert the object model for x_d */
    int end_policy;    /* -1: the skill's own; 0 hold; 1 release */
    double phase_stop_gain_per_N2;
    double surface_error_m;   /* the firmware's surface = the object's + this */
    int surface_from_contact; /* 1: the firmware takes the surface at the first tick */
    /* fault */
    sim_fault_t fault;
} sim_scenario_t;

/** Fill the defaults (docs/hil.md). */
void sim_scenario_defaults(sim_scenario_t *sc);

/** Parse a scenario file over the defaults; on error returns -1 with "file:line: message" in err. */
int sim_scenario_load(sim_scenario_t *sc, const char *path, char err[SIM_ERR_MAX]);

/** Parse scenario text (name is used in messages); same rules as sim_scenario_load. */
int sim_scenario_parse(sim_scenario_t *sc, const char *text, const char *name,
                       char err[SIM_ERR_MAX]);

/** Check cross-field consistency (positive durations, levels below F_max, ...); -1 + message. */
int sim_scenario_check(const sim_scenario_t *sc, char err[SIM_ERR_MAX]);

#endif /* SIM_SCENARIO_H */

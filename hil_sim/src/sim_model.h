/* HIL simulator models (docs/hil.md): per-axis plant (ideal / realistic), compliant object with
 * stiffness layers, seeded operator, force and position sensors. All in SI units, double.
 * See docs/hil.md for the equations and every parameter choice. */
#ifndef SIM_MODEL_H
#define SIM_MODEL_H

#include <stdint.h>
#include "sim_rng.h"

/* ---------------- object ---------------- */

/** Planar compliant object on the x axis: f = s(p)*(m_v*xdd + d_v*xd) + F(p), p = x - surface_m,
 *  F = k1*p up to layer_depth_m, then k2 beyond; unilateral (f >= 0, 0 for p <= 0).
 *  s(p) = min(1, p/skin_m) engages the object's inertia and damping over the first skin_m of
 *  penetration (contact skin, as Hunt-Crossley damping), so touching the surface at speed does
 *  not step the force; skin_m = 0 gives the plain linear model everywhere. */
typedef struct {
    double skin_m;
    double surface_m;
    double k1_Npm;
    double k2_Npm;
    double layer_depth_m;
    double d_v_Nspm;
    double m_v_kg;
    double friction_mu; /* Coulomb friction along y between tip and surface: mu * contact force */
} sim_object_t;

/** Spring part F(p) of the object (0 for p <= 0). */
double sim_object_spring_N(const sim_object_t *o, double p_m);

/* ---------------- plant ---------------- */

typedef enum {
    SIM_PLANT_IDEAL = 0,
    SIM_PLANT_REALISTIC = 1
} sim_plant_kind_t;

/** Carriage parameters of the realistic plant. */
typedef struct {
    double carriage_kg;  /* 2 kg */
    double act_max_N;    /* +-200 N actuator limit */
    double act_lag_s;    /* 0.5 ms first-order lag */
    double viscous_Nspm; /* 5 Ns/m */
    double coulomb_N;    /* 1 N */
} sim_carriage_t;

/** State of one axis. */
typedef struct {
    double pos_m;
    double vel_mps;
    double acc_mps2;
    double act_N;     /* realistic: actuator force after the lag */
    double contact_N; /* contact force at the end of the last substep */
} sim_axis_t;

/** How an axis is driven during one substep. */
typedef struct {
    sim_plant_kind_t kind;
    uint8_t prescribed; /* ideal EXECUTE: acc = force_cmd/mass (dynamics compensated) */
    double mass_kg;     /* ideal: m_d; realistic: carriage */
    double force_cmd_N; /* ideal: commanded total force; realistic: motor command */
    double force_ext_N; /* operator force without the hand damping (0 in EXECUTE) */
    double hand_damping_Nspm;
    const sim_carriage_t *carriage; /* realistic only */
    const sim_object_t *object;     /* NULL: no contact on this axis */
    double act_limit_N;             /* current actuator limit (fault injection may lower it) */
    double act_alpha;               /* realistic: 1 - exp(-dt/lag), precomputed for the substep */
    double inv_mass;                /* 1/mass_kg (sim_drive_prepare) */
    double inv_mass_contact;        /* 1/(mass_kg + m_v) (sim_drive_prepare) */
    double friction_N;              /* Coulomb friction of the surface on this axis (y: mu * the
                                     * x contact force, set every substep by sim_couple_advance) */
} sim_drive_t;

/** Precompute the drive's inverse masses (call after setting mass_kg and object). */
void sim_drive_prepare(sim_drive_t *d);

/** Advance one axis by dt_s (semi-implicit Euler; contact solved jointly with the object's
 *  inertia, force clipped at 0: the object never pulls). Coulomb friction friction_N (plus the
 *  realistic carriage's) opposes the motion, sticks below SIM_STICK_VEL_MPS while the driving
 *  force is within it, and acts in every mode, the prescribed one included (a disturbance the
 *  device's law has to reject). */
void sim_axis_substep(sim_axis_t *a, const sim_drive_t *d, double dt_s);

/** Operator force as the handle sensor sees it: profile minus hand damping. */
double sim_operator_handle_N(const sim_drive_t *d, const sim_axis_t *a);

/* ---------------- operator ---------------- */

typedef enum {
    SIM_TASK_NONE = 0,
    SIM_TASK_PRESSING = 1,
    SIM_TASK_ENGRAVING = 2,
    SIM_TASK_WIPING = 3 /* repeated strokes about a mean force (a periodic skill's demo) */
} sim_task_t;

#define SIM_MAX_LEVELS 64
#define SIM_MAX_STROKES 512

/** Operator parameters (from the scenario). */
typedef struct {
    sim_task_t task;
    double low_N, high_N;            /* pressing levels (nominal) */
    double level_min_N, level_max_N; /* engraving random levels */
    double jitter;                   /* pressing levels x (1 +- jitter), seeded */
    double ramp_s;                   /* pressing: ramp to low and to high; engraving: ramp-up */
    double release_s;                /* both: release over the last release_s */
    double reaction_min_s, reaction_max_s;
    double dwell_min_s, dwell_max_s; /* engraving: level change every 0.6-1.4 s */
    double transition_s;             /* engraving: 0.7 s smooth transitions */
    double layer_timeout_s;          /* pressing: go high anyway after this time */
    double hand_damping_Nspm;        /* 30 Ns/m */
    double tremor_frac;              /* 1 % of the force */
    double duration_s;
    /* the path along y (engraving, wiping: paper Fig. 6): waypoints in [-path_m/2, path_m] from
     * the start, a new one every path_dwell_min_s..path_dwell_max_s reached over path_move_s
     * (smoothstep), back near the start (path_m/10) before the release; the hand follows it as
     * a spring hand_stiffness_Npm with the hand damping's feed-forward. path_m = 0: no path */
    double path_m;
    double path_move_s;
    double path_dwell_min_s, path_dwell_max_s;
    double hand_stiffness_Npm;
    /* wiping: after the ramp_s approach to stroke_mean_N, strokes of period stroke_period_s
     * (each 1 +- stroke_jitter of it, seeded) whose force is stroke_mean_N + stroke_amp_N*
     * (0.8 sin(2 pi s) + 0.35 sin(4 pi s + 0.6) + 0.15 sin(6 pi s + 1.9)), s the stroke's phase
     * in [0, 1), until the release */
    double stroke_mean_N;
    double stroke_amp_N;
    double stroke_period_s;
    double stroke_jitter;
} sim_operator_cfg_t;

/** Operator state (seeded draws and the pressing phase). */
typedef struct {
    sim_operator_cfg_t cfg;
    double low_N, high_N, reaction_s;
    double t_layer_s; /* < 0 until the inner layer is reached */
    double t_high_s;  /* start of the ramp to the high level */
    int n_levels;
    double level_t_s[SIM_MAX_LEVELS]; /* start of each transition */
    double level_N[SIM_MAX_LEVELS];   /* level after the transition */
    double tremor_hz[2], tremor_phase[2];
    int n_path;
    double path_t_s[SIM_MAX_LEVELS]; /* start of each move */
    double path_y_m[SIM_MAX_LEVELS]; /* waypoint after the move, m from the start */
    int n_strokes;
    double stroke_t_s[SIM_MAX_STROKES + 1]; /* wiping: stroke i runs [stroke_t_s[i], [i+1]) */
} sim_operator_t;

/** Draw the seeded parameters (levels, reaction time, engraving schedule, tremor). */
void sim_operator_init(sim_operator_t *op, const sim_operator_cfg_t *cfg, sim_rng_t *rng);

/** Profile force of axis 0 (x, pushing) and axis 1 (y, tremor only) at t_s. Pressing needs to
 *  know when the inner layer is reached: pass the current deformation and the layer depth. */
void sim_operator_force(sim_operator_t *op, double t_s, double p_m, double layer_depth_m,
                        double force_N[2]);

/** The operator's intended path at t_s (m from the start) and its velocity. */
void sim_operator_path(const sim_operator_t *op, double t_s, double *y_m, double *yd_mps);

/** The hand's force along y that follows the path: hand_stiffness*(y0 + path(t) - y) plus
 *  hand_damping*path'(t) (the drive subtracts hand_damping*y'); 0 without a path. */
double sim_operator_path_force(const sim_operator_t *op, double t_s, double y0_m, double y_m);

/* ---------------- sensors ---------------- */

/** A force sensor: Gaussian noise, bias, 16-bit quantisation over +-range. */
typedef struct {
    double noise_N;
    double bias_N;
    double range_N;
    unsigned bits;
} sim_force_sensor_t;

/** One reading of a force sensor. */
double sim_force_read(const sim_force_sensor_t *s, double true_N, sim_rng_t *rng);

/** An encoder reading quantised to resolution_m (round to nearest). */
double sim_encoder_read(double pos_m, double resolution_m);

/** Smoothstep 3r^2 - 2r^3 clamped to [0, 1]. */
double sim_smoothstep(double r);

#endif /* SIM_MODEL_H */

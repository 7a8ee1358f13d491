/* Device-side validation of a parsed skill before it is committed to a slot, and of the goal
 * scale it is run with (docs/skill_format.md, "Device ranges and output check"). Takes a skill_t
 * as skill_parse fills it, so a new image format only changes the parser.
 *
 *  1. skchk_params: every parameter within the device's documented range (220) and the Euler
 *     step of the DMP well inside its stability region, dt*rate/tau <= SKCHK_STEP_MAX (221).
 *  2. The skill's own rollout at goal scale 1, time scale 1, no coupling, over its duration
 *     (exactly what fs_exec evaluates, hold/release only keep or ramp the last value): not
 *     finite (222) or a peak |f_hat| above the force limit (223) refuses the skill. The rollout
 *     is incremental (skchk_begin, then skchk_run with a step budget per call) so a device spreads
 *     it over idle ticks; skchk_skill does it in one call.
 *  3. skchk_run_scales: f_hat is linear in the goal (zero initial state), so goal_scale*peak is
 *     the run's peak; above the limit (224) or a time scale that breaks the step rule (221) is
 *     refused before any motion.
 *  4. The y half (a skill with the y DMP): y parameters in range (|g_y|, |y_start| within
 *     SKCHK_SURFACE_MAX_M, |w_y| <= SKCHK_WEIGHT_MAX) and the rollout's path finite with its
 *     extent max|p| from the start within path_max_m (the y workspace's width; default
 *     SKCHK_PATH_MAX_M), else 225; at run time path_scale*extent within it, else 226
 *     (skchk_run_path).
 *  A periodic skill (docs/math.md section 5): its widths within the kappa range, the rollout is
 *  one cycle from the stored cycle state (dmp_periodic_step), and peak_N is the bound
 *  |f0| + g + max|e| of its force (the run-time check scales it by the larger of the goal and
 *  amplitude scales: skchk_run_scales_periodic).
 *  5. skchk_stiffness: the skill's nominal stiffness within the device's limit (227), checked at
 *     commit and at start: on stiffer objects the device's force loop does not track (the limit
 *     is measured per device, docs/hil.md). */
#ifndef SKILL_CHECK_H
#define SKILL_CHECK_H

#include <stdbool.h>
#include <stdint.h>
#include "dmp.h"
#include "fs_real.h"
#include "fs_status.h"
#include "fs_wire_const.h"
#include "skill.h"

/* Device ranges (docs/skill_format.md); the image format itself allows wider values. */
#define SKCHK_TAU_MIN_S 1e-3
#define SKCHK_TAU_MAX_S 1e3
#define SKCHK_GOAL_MAX_N 1e7
#define SKCHK_FORCE0_MAX_N 1e3
#define SKCHK_STIFFNESS_MAX_NPM FS_STIFFNESS_CEILING_NPM
#define SKCHK_WEIGHT_MAX 1e4
#define SKCHK_WIDTH_MIN 1e-5
#define SKCHK_WIDTH_MAX 1.0
/* A periodic skill's widths are von Mises concentrations kappa_i (the fit's N = 50: 150). */
#define SKCHK_KAPPA_MIN 1e-3
#define SKCHK_KAPPA_MAX 1e7
#define SKCHK_DURATION_MAX_S 600.0
#define SKCHK_ALPHA_MAX 1e3
#define SKCHK_GAMMA_MAX 1e4
#define SKCHK_MASS_MIN_KG 1e-3
#define SKCHK_MASS_MAX_KG 1e4
#define SKCHK_GAIN_MAX 1e7
#define SKCHK_SURFACE_MAX_M 10.0
/* Euler step rule: dt/(tau*time_scale) * (1 + alpha + sqrt(gamma)) <= this (the fastest mode's
 * rate in DMP time is below 1 + alpha + sqrt(gamma); 0.5 keeps the step well inside the
 * forward-Euler stability disc |1 - h*lambda| < 1). */
#define SKCHK_STEP_MAX 0.5
/* Default largest extent of a y path from its start (m): the default y workspace's width. */
#define SKCHK_PATH_MAX_M 1.0

/** Incremental output check of one skill. */
typedef struct {
    const skill_t *skill;
    dmp_state_t dmp;
    uint32_t steps_total; /* DMP steps of the duration at the executor's dt */
    uint32_t steps_done;
    fs_real_t peak_N; /* max |f_hat| so far */
    fs_real_t force_max_N;
    fs_real_t path_peak_m; /* max |p| of the y DMP so far (0 without one) */
    fs_real_t path_max_m;  /* the y range: SKCHK_PATH_MAX_M unless set after skchk_begin */
    fs_status_t status;    /* FS_OK while running or passed; 222/223/225 once refused */
    bool done;
} skchk_t;

/** Parameter ranges and the step rule (220, 221; the y DMP's parameters 225; FS_ERR_NULL_ARG
 *  for NULL). */
fs_status_t skchk_params(const skill_t *s);

/** skchk_params in slices (skchk_params_begin, then skchk_params_run until it returns true):
 *  the same checks in the same order, a unit the scalar ranges, SKCHK_PARAMS_KERNELS_PER_UNIT
 *  kernels' weights and widths (or y weights), the y scalars or the step rule; then c->status
 *  is skchk_params's result. *s must stay in place until it is done. */
typedef struct {
    const skill_t *skill;
    uint16_t pos;  /* the next kernel of the stage */
    uint8_t stage; /* internal */
    bool done;
    fs_status_t status; /* FS_OK while running or once passed; the refusal once done */
} skchk_params_t;
#define SKCHK_PARAMS_KERNELS_PER_UNIT 4u

/** Start a sliced parameter check of s (NULL: FS_ERR_NULL_ARG at once). */
void skchk_params_begin(skchk_params_t *c, const skill_t *s);

/** At most max_units units of the parameter check; true once done (then c->status). */
bool skchk_params_run(skchk_params_t *c, uint32_t max_units);

/** Start the output check of s (parameters already checked) for an executor stepping every
 *  dt_s against the force limit force_max_N. */
void skchk_begin(skchk_t *c, const skill_t *s, fs_real_t dt_s, fs_real_t force_max_N);

/** Advance by at most max_steps DMP steps; true once finished (then c->status, c->peak_N). */
bool skchk_run(skchk_t *c, uint32_t max_steps);

/** Whole check in one call (tests, host tools): params, then the full rollout; *peak_N (may be
 *  NULL) gets the peak |f_hat| at goal scale 1. */
fs_status_t skchk_skill(const skill_t *s, fs_real_t dt_s, fs_real_t force_max_N, fs_real_t *peak_N);

/** Run-time path scale of a checked skill whose path extent is path_peak_m: finite, >= 0 and
 *  path_scale*path_peak_m <= path_max_m, else 226 (FS_ERR_NULL_ARG for NULL). */
fs_status_t skchk_run_path(const skill_t *s, fs_real_t path_peak_m, fs_real_t path_scale,
                           fs_real_t path_max_m);

/** Run-time scales of a checked skill with peak peak_N: goal_scale*peak_N <= force_max_N (224)
 *  and the step rule at time_scale (221). */
fs_status_t skchk_run_scales(const skill_t *s, fs_real_t peak_N, fs_real_t goal_scale,
                             fs_real_t time_scale, fs_real_t dt_s, fs_real_t force_max_N);

/** skchk_run_scales of a periodic skill (peak_N its bound |f0| + g + max|e|): the larger of
 *  goal_scale and amplitude_scale times the bound (224), amplitude_scale finite and >= 0 (109),
 *  the step rule at time_scale (221). */
fs_status_t skchk_run_scales_periodic(const skill_t *s, fs_real_t peak_N, fs_real_t goal_scale,
                                      fs_real_t amplitude_scale, fs_real_t time_scale,
                                      fs_real_t dt_s, fs_real_t force_max_N);

/** The skill's nominal stiffness at most stiffness_max_Npm (227; FS_ERR_NULL_ARG for NULL). */
fs_status_t skchk_stiffness(const skill_t *s, fs_real_t stiffness_max_Npm);

#endif /* SKILL_CHECK_H */

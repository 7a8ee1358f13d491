/* The runner of `hil_sim faults`: one fault scenario (fault_scenario.h) injected into the full
 * device application in lockstep with the plant (fault_rig.h), measured into one table row. */
#ifndef FAULT_RUN_H
#define FAULT_RUN_H

#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>

#include "fault_scenario.h"

#define FAULT_HOLD_MS 1000u     /* latched and zero for this long after detection */
#define FAULT_ZERO_BOUND_MS 50u /* force at zero within 50 ms of detection (docs/safety.md) */

/** One row of the fault table (hil_sim/scenarios/faults/README.md defines every figure). */
typedef struct {
    char name[64];
    char kind[32];
    char description[256];
    int expect_code;
    int code;             /* latched code (device state), 0 none */
    bool emcy_seen;       /* an emergency frame with the code reached the host */
    double emcy_delay_ms; /* from detection to that frame at the host (-1: none) */
    bool status_seen;     /* a status frame showed the code */
    double detect_ms;     /* -1: not applicable / not detected */
    double detect_bound_ms;
    char bound_text[64];
    double zero_ms; /* from detection to |F| = 0 on both axes */
    double force_at_onset_N;
    double worst_N;       /* max |commanded force| over the run, both axes */
    double contact_max_N; /* max true contact force on the object over the run */
    double f_max_N;
    bool monotone;
    bool latched; /* fault state, zero force, actuator off for HOLD_MS */
    bool cleared; /* clear accepted once the cause was gone, force stayed 0 */
    bool lost;    /* flash or slot cache changed (storage scenario: see note) */
    bool pass;
    char note[200];
} frow_t;

/** Write one CSV line per tick of the following runs to f (NULL: none); writes the header. */
void fault_run_trace(FILE *f);

/** Run one fault scenario into row (the plant file's seed unless seed_set); -1 with a one-line
 *  message in err when a file it names cannot be read (row then undefined). */
int fault_run_one(const fscen_t *fs, uint64_t seed, bool seed_set, frow_t *row, char *err,
                  size_t errn);

#endif /* FAULT_RUN_H */

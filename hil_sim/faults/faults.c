/* hil_sim faults (see faults.h): the command line. Scenario files: fault_scenario.h; the runner:
 * fault_run.h; the table: fault_report.h. */
#define _GNU_SOURCE
#include "faults.h"

#include <dirent.h>
#include <errno.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "fault_report.h"
#include "fault_run.h"
#include "fault_scenario.h"

#ifndef HIL_SIM_FAULTS_DIR
#define HIL_SIM_FAULTS_DIR "hil_sim/scenarios/faults"
#endif

#define MAX_SCEN 24

static const char FAULT_USAGE[] =
    "usage: hil_sim faults [--seed N] [--dir DIR] [-o TABLE.md] [--json OUT.json] [--only NAME]\n"
    "                      [--trace TICKS.csv]\n"
    "Inject every fault scenario (DIR/*.toml, default " HIL_SIM_FAULTS_DIR
    ") into the full device\n"
    "application (state machine, safety supervisor, skill storage, UDS) running in lockstep\n"
    "against the simulated plant, the host scripted over the simulated CAN queues. Prints and\n"
    "writes the table: detection time, time to zero force, worst force, latched, lost, pass.\n"
    "Exit 0 if every row passes, 1 if one fails, 2 on errors.\n"
    "scenario keys: name, description, plant (hil_sim scenario file), plant_model, skill,\n"
    "  neighbour_skill,"
    " new_skill, goal_scale, time_scale, kind (host_silence, host_corrupt, host_loss, bus_off,\n"
    "  force_spike, force_nan, force_stuck, encoder_jump, actuator_saturation, force_limit, "
    "tick_overrun,\n"
    "  power_loss_upload), at_s (after EXECUTE starts), value, duration_s, expect_code (0: no "
    "fault\n"
    "  may latch), detect_bound_ms, bound_text\n";

static int name_cmp(const void *a, const void *b)
{
    return strcmp(*(const char *const *)a, *(const char *const *)b);
}

/* The options of `hil_sim faults`. */
typedef struct {
    const char *dir, *out_md, *out_json, *only;
    uint64_t seed;
    bool seed_set;
    FILE *trace;
} fopts_t;

/* Parse argv into o; returns -1 to go on, else the exit status (0 after --help, 2 on errors). */
static int parse_args(int argc, char **argv, fopts_t *o)
{
    for (int i = 0; i < argc; i += 2) {
        const char *a = argv[i];
        if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0) {
            fputs(FAULT_USAGE, stdout);
            return 0;
        }
        const char *v = (i + 1 < argc) ? argv[i + 1] : NULL;
        if (v == NULL) {
            fprintf(stderr, "hil_sim faults: %s needs a value (or unknown option)\n%s", a,
                    FAULT_USAGE);
            return 2;
        }
        if (strcmp(a, "--seed") == 0) {
            char *end = NULL;
            errno = 0;
            const unsigned long long s = strtoull(v, &end, 10);
            if (end == v || *end != '\0' || errno != 0) {
                fprintf(stderr, "hil_sim faults: --seed needs an integer, got '%s'\n", v);
                return 2;
            }
            o->seed = (uint64_t)s;
            o->seed_set = true;
        } else if (strcmp(a, "--dir") == 0) {
            o->dir = v;
        } else if (strcmp(a, "-o") == 0) {
            o->out_md = v;
        } else if (strcmp(a, "--json") == 0) {
            o->out_json = v;
        } else if (strcmp(a, "--only") == 0) {
            o->only = v;
        } else if (strcmp(a, "--trace") == 0) {
            o->trace = fopen(v, "w");
            if (o->trace == NULL) {
                fprintf(stderr, "hil_sim faults: %s: %s\n", v, strerror(errno));
                return 2;
            }
            fault_run_trace(o->trace);
        } else {
            fprintf(stderr, "hil_sim faults: unknown option '%s'\n%s", a, FAULT_USAGE);
            return 2;
        }
    }
    return -1;
}

/* The *.toml file names of dir in name order (at most MAX_SCEN); -1 if dir cannot be read. */
static int list_scenarios(const char *dir, const char *sorted[MAX_SCEN])
{
    static char names[MAX_SCEN][256];
    DIR *d = opendir(dir);
    if (d == NULL) {
        return -1;
    }
    int n = 0;
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        const size_t l = strlen(e->d_name);
        if (l > 5u && strcmp(e->d_name + l - 5u, ".toml") == 0 && n < MAX_SCEN) {
            snprintf(names[n], sizeof names[n], "%s", e->d_name);
            sorted[n] = names[n];
            n++;
        }
    }
    closedir(d);
    qsort(sorted, (size_t)n, sizeof sorted[0], name_cmp);
    return n;
}

/* Load and run the n scenarios (those named --only) into rows; their count, or -1 on an error. */
static int run_all(const fopts_t *o, const char *const *sorted, int n, frow_t *rows)
{
    static fscen_t fs;
    char err[SIM_ERR_MAX + SIM_PATH_MAX];
    int nr = 0;
    for (int i = 0; i < n; i++) {
        char path[SIM_PATH_MAX];
        fscen_join(path, o->dir, sorted[i]);
        if (fscen_load(&fs, path, err) != 0) {
            fprintf(stderr, "hil_sim faults: %s\n", err);
            return -1;
        }
        if (o->only != NULL && strcmp(o->only, fs.name) != 0) {
            continue;
        }
        if (fault_run_one(&fs, o->seed, o->seed_set, &rows[nr], err, sizeof err) != 0) {
            fprintf(stderr, "hil_sim faults: %s\n", err);
            return -1;
        }
        nr++;
    }
    return nr;
}

/* Write the table (markdown) or the JSON of the rows to path; -1 if it cannot be opened. */
static int write_file(const char *path, bool json, const frow_t *rows, int n, uint64_t seed)
{
    FILE *f = fopen(path, "w");
    if (f == NULL) {
        fprintf(stderr, "hil_sim faults: %s: %s\n", path, strerror(errno));
        return -1;
    }
    if (json) {
        fault_write_json(f, rows, n, seed);
    } else {
        fault_write_table(f, rows, n, seed);
    }
    fclose(f);
    return 0;
}

int faults_cmd(int argc, char **argv)
{
    fopts_t o = {.dir = HIL_SIM_FAULTS_DIR, .seed = 1u};
    const int status = parse_args(argc, argv, &o);
    if (status >= 0) {
        return status;
    }
    const char *sorted[MAX_SCEN] = {NULL};
    const int n = list_scenarios(o.dir, sorted);
    if (n < 0) {
        fprintf(stderr, "hil_sim faults: %s: %s\n", o.dir, strerror(errno));
        return 2;
    }
    static frow_t rows[MAX_SCEN];
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    const int nr = run_all(&o, sorted, n, rows);
    clock_gettime(CLOCK_MONOTONIC, &t1);
    if (o.trace != NULL) {
        fault_run_trace(NULL);
        fclose(o.trace);
    }
    if (nr < 0) {
        return 2;
    }
    if (nr == 0) {
        fprintf(stderr, "hil_sim faults: no scenario in %s\n", o.dir);
        return 2;
    }
    fault_write_table(stdout, rows, nr, o.seed);
    printf("wall time %.2f s\n",
           (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec));
    if ((o.out_md != NULL && write_file(o.out_md, false, rows, nr, o.seed) != 0) ||
        (o.out_json != NULL && write_file(o.out_json, true, rows, nr, o.seed) != 0)) {
        return 2;
    }
    for (int i = 0; i < nr; i++) {
        if (!rows[i].pass) {
            return 1;
        }
    }
    return 0;
}

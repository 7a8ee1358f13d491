/* `hil_sim run`: see sim_cli.h and docs/hil.md. */
#include "sim_cli.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sim_run.h"
#include "sim_scenario.h"

static const char RUN_USAGE[] =
    "usage: hil_sim run SCENARIO.toml [options]\n"
    "  -o, --output LOG.csv    write the log (t,x,y,f_contact,f_operator,f_cmd,f_hat; SI units)\n"
    "                          and LOG.summary.json beside it (without -o the summary goes to "
    "stdout)\n"
    "  --seed N                operator and sensor seed (default: the scenario's)\n"
    "  --skill FILE [FILE...]  skill image(s) to execute in series (replaces the scenario's)\n"
    "  --goal-scale S          goal scale for every step (default: the scenario's, 1)\n"
    "  --time-scale S          time scale for every step (default 1)\n"
    "  --step-duration S [..]  duration of each step in s (default: each skill's T)\n"
    "  --plant ideal|realistic override the scenario's plant\n"
    "  --duration S            override the run length in s\n"
    "The device application runs the scenario (app_tick through the host port of hal.h): the\n"
    "skills go into its flash slots 1..n; the summary reports its first fault and final state.\n";

static int usage_error(const char *fmt, const char *arg)
{
    fprintf(stderr, "hil_sim run: ");
    fprintf(stderr, fmt, arg);
    fprintf(stderr, "\n%s", RUN_USAGE);
    return 2;
}

static int parse_num(const char *opt, const char *s, double *out)
{
    char *end = NULL;
    errno = 0;
    double v = strtod(s, &end);
    if (end == s || *end != '\0' || errno == ERANGE || !isfinite(v)) {
        fprintf(stderr, "hil_sim run: %s expects a number, got '%s'\n", opt, s);
        return -1;
    }
    *out = v;
    return 0;
}

/* The options of `hil_sim run`; have_* mark the ones given. */
typedef struct {
    const char *scenario, *out;
    const char *skills[SIM_MAX_SKILLS];
    int n_skills;
    double durations[SIM_MAX_SKILLS];
    int n_durations;
    int have_seed, have_goal, have_time, have_plant, have_duration;
    double seed, goal, tscale, duration;
    int plant;
} run_opts_t;

/* --seed, --goal-scale, --time-scale, --duration at argv[*i]; 0, or the exit status 2. */
static int parse_number_opt(int argc, char **argv, int *i, run_opts_t *o)
{
    const char *a = argv[*i];
    const int more = (*i + 1 < argc);
    double v = 0.0;
    if (!more || parse_num(a, argv[*i + 1], &v) != 0) {
        return more ? 2 : usage_error("%s needs a value", a);
    }
    const char *arg = argv[++*i];
    if (strcmp(a, "--seed") == 0) {
        if (v < 0.0 || v != floor(v) || v > 9007199254740992.0) {
            return usage_error("--seed must be a non-negative integer, got '%s'", arg);
        }
        o->seed = v;
        o->have_seed = 1;
    } else if (strcmp(a, "--goal-scale") == 0) {
        o->goal = v;
        o->have_goal = 1;
    } else if (strcmp(a, "--time-scale") == 0) {
        if (!(v > 0.0)) {
            return usage_error("--time-scale must be > 0, got '%s'", arg);
        }
        o->tscale = v;
        o->have_time = 1;
    } else {
        if (!(v > 0.0)) {
            return usage_error("--duration must be > 0, got '%s'", arg);
        }
        o->duration = v;
        o->have_duration = 1;
    }
    return 0;
}

/* --skill FILE [FILE...] and --step-duration S [S...] at argv[*i]; 0, or the exit status 2. */
static int parse_list_opt(int argc, char **argv, int *i, run_opts_t *o)
{
    const char *a = argv[*i];
    if (strcmp(a, "--skill") == 0) {
        if (*i + 1 >= argc || argv[*i + 1][0] == '-') {
            return usage_error("%s needs a file name", a);
        }
        while (*i + 1 < argc && argv[*i + 1][0] != '-') {
            if (o->n_skills >= SIM_MAX_SKILLS) {
                return usage_error("at most 8 skills, got more at '%s'", argv[*i + 1]);
            }
            o->skills[o->n_skills++] = argv[++*i];
        }
        return 0;
    }
    if (*i + 1 >= argc) {
        return usage_error("%s needs a value", a);
    }
    while (*i + 1 < argc && (argv[*i + 1][0] != '-' || argv[*i + 1][1] == '.')) {
        double v = 0.0;
        if (parse_num(a, argv[*i + 1], &v) != 0) {
            return 2;
        }
        if (!(v > 0.0) || o->n_durations >= SIM_MAX_SKILLS) {
            return usage_error("bad --step-duration '%s' (> 0, at most 8)", argv[*i + 1]);
        }
        o->durations[o->n_durations++] = v;
        ++*i;
    }
    return 0;
}

/* argv into o; -1 to go on, else the exit status (0 after --help, 2 on a usage error). */
static int parse_run_args(int argc, char **argv, run_opts_t *o)
{
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i];
        int rc = 0;
        if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0) {
            fputs(RUN_USAGE, stdout);
            return 0;
        } else if (strcmp(a, "-o") == 0 || strcmp(a, "--output") == 0) {
            if (i + 1 >= argc) {
                return usage_error("%s needs a file name", a);
            }
            o->out = argv[++i];
        } else if (strcmp(a, "--seed") == 0 || strcmp(a, "--goal-scale") == 0 ||
                   strcmp(a, "--time-scale") == 0 || strcmp(a, "--duration") == 0) {
            rc = parse_number_opt(argc, argv, &i, o);
        } else if (strcmp(a, "--plant") == 0) {
            if (i + 1 >= argc) {
                return usage_error("%s needs a value", a);
            }
            i++;
            if (strcmp(argv[i], "ideal") != 0 && strcmp(argv[i], "realistic") != 0) {
                return usage_error("--plant must be ideal or realistic, got '%s'", argv[i]);
            }
            o->plant = strcmp(argv[i], "realistic") == 0 ? 1 : 0;
            o->have_plant = 1;
        } else if (strcmp(a, "--skill") == 0 || strcmp(a, "--step-duration") == 0) {
            rc = parse_list_opt(argc, argv, &i, o);
        } else if (a[0] == '-' && a[1] != '\0') {
            return usage_error("unknown option '%s'", a);
        } else if (o->scenario == NULL) {
            o->scenario = a;
        } else {
            return usage_error("unexpected argument '%s'", a);
        }
        if (rc != 0) {
            return rc;
        }
    }
    if (o->scenario == NULL) {
        return usage_error("%s", "missing SCENARIO");
    }
    return -1;
}

/* Load the scenario, lay the options over it, check it, load its skills; 0 or the status 2. */
static int prepare(const run_opts_t *o, sim_scenario_t *sc, sim_skill_image_t *skills)
{
    char err[SIM_ERR_MAX];
    sim_scenario_defaults(sc);
    if (sim_scenario_load(sc, o->scenario, err) != 0) {
        fprintf(stderr, "hil_sim: %s\n", err);
        return 2;
    }
    sc->seed = o->have_seed ? (uint64_t)o->seed : sc->seed;
    sc->goal_scale = o->have_goal ? o->goal : sc->goal_scale;
    sc->time_scale = o->have_time ? o->tscale : sc->time_scale;
    sc->plant = o->have_plant ? (sim_plant_kind_t)o->plant : sc->plant;
    sc->duration_s = o->have_duration ? o->duration : sc->duration_s;
    if (o->n_skills > 0) {
        sc->n_skills = o->n_skills;
        for (int i = 0; i < o->n_skills; i++) {
            snprintf(sc->skill_path[i], SIM_PATH_MAX, "%s", o->skills[i]);
        }
    }
    if (o->n_durations > 0) {
        sc->n_step_durations = o->n_durations;
        memcpy(sc->step_duration_s, o->durations, sizeof(double) * (size_t)o->n_durations);
    }
    if (sc->mode == SIM_MODE_EXECUTE && o->n_skills == 0 && sc->n_skills == 0) {
        fprintf(stderr, "hil_sim: %s: execute scenario without skills: pass --skill FILE\n",
                o->scenario);
        return 2;
    }
    if (sim_scenario_check(sc, err) != 0 ||
        (sc->mode == SIM_MODE_EXECUTE && sim_load_skills(sc, skills, err) != 0)) {
        fprintf(stderr, "hil_sim: %s\n", err);
        return 2;
    }
    return 0;
}

/* Open the log out and name its summary (LOG.csv -> LOG.summary.json); NULL after a message. */
static FILE *open_log(const char *out, char *summary_path, size_t cap)
{
    FILE *log = fopen(out, "w");
    if (log == NULL) {
        fprintf(stderr, "hil_sim: %s: cannot write the log: %s\n", out, strerror(errno));
        return NULL;
    }
    size_t len = strlen(out);
    if (len >= 4 && strcmp(out + len - 4, ".csv") == 0) {
        len -= 4;
    }
    if (len > SIM_PATH_MAX) {
        fclose(log);
        fprintf(stderr, "hil_sim: output path too long\n");
        return NULL;
    }
    snprintf(summary_path, cap, "%.*s.summary.json", (int)len, out);
    return log;
}

int sim_cmd_run(int argc, char **argv)
{
    static sim_scenario_t sc;
    static sim_skill_image_t skills[SIM_MAX_SKILLS];
    char err[SIM_ERR_MAX];
    run_opts_t o = {.goal = 1.0, .tscale = 1.0};
    int rc = parse_run_args(argc, argv, &o);
    if (rc >= 0) {
        return rc;
    }
    if (prepare(&o, &sc, skills) != 0) {
        return 2;
    }
    FILE *log = NULL;
    char summary_path[SIM_PATH_MAX + 32];
    if (o.out != NULL && (log = open_log(o.out, summary_path, sizeof summary_path)) == NULL) {
        return 2;
    }
    sim_summary_t sum;
    rc = sim_run(&sc, skills, log, &sum, err);
    if (log != NULL && fclose(log) != 0) {
        rc = -1;
        snprintf(err, sizeof err, "%s: closing the log failed", o.out);
    }
    if (rc != 0) {
        fprintf(stderr, "hil_sim: %s\n", err);
        return 1;
    }
    if (o.out != NULL) {
        if (sim_write_summary(&sc, &sum, summary_path) != 0) {
            fprintf(stderr, "hil_sim: %s: cannot write the summary\n", summary_path);
            return 1;
        }
        printf("%s: %.3f s simulated in %.3f s (%.0fx real time); log %s, summary %s\n", sc.name,
               sum.sim_time_s, sum.wall_s, sum.x_realtime, o.out, summary_path);
    } else if (sim_write_summary(&sc, &sum, "/dev/stdout") != 0) {
        return 1;
    }
    return 0;
}

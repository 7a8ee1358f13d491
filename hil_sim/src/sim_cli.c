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
    "  --duration S            override the run length in s\n";

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

int sim_cmd_run(int argc, char **argv)
{
    static sim_scenario_t sc;
    static skill_t skills[SIM_MAX_SKILLS];
    char err[SIM_ERR_MAX];
    const char *scenario = NULL;
    const char *out = NULL;
    const char *cli_skills[SIM_MAX_SKILLS];
    int n_cli_skills = 0;
    double cli_durations[SIM_MAX_SKILLS];
    int n_cli_durations = 0;
    int have_seed = 0, have_goal = 0, have_time = 0, have_plant = 0, have_duration = 0;
    double seed = 0.0, goal = 1.0, tscale = 1.0, duration = 0.0;
    int plant = 0;

    for (int i = 0; i < argc; i++) {
        const char *a = argv[i];
        const int more = (i + 1 < argc);
        if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0) {
            fputs(RUN_USAGE, stdout);
            return 0;
        } else if (strcmp(a, "-o") == 0 || strcmp(a, "--output") == 0) {
            if (!more) {
                return usage_error("%s needs a file name", a);
            }
            out = argv[++i];
        } else if (strcmp(a, "--seed") == 0) {
            if (!more || parse_num(a, argv[i + 1], &seed) != 0) {
                return more ? 2 : usage_error("%s needs a value", a);
            }
            i++;
            if (seed < 0.0 || seed != floor(seed) || seed > 9007199254740992.0) {
                return usage_error("--seed must be a non-negative integer, got '%s'", argv[i]);
            }
            have_seed = 1;
        } else if (strcmp(a, "--goal-scale") == 0 || strcmp(a, "--time-scale") == 0 ||
                   strcmp(a, "--duration") == 0) {
            double v = 0.0;
            if (!more || parse_num(a, argv[i + 1], &v) != 0) {
                return more ? 2 : usage_error("%s needs a value", a);
            }
            i++;
            if (strcmp(a, "--goal-scale") == 0) {
                goal = v;
                have_goal = 1;
            } else if (strcmp(a, "--time-scale") == 0) {
                if (!(v > 0.0)) {
                    return usage_error("--time-scale must be > 0, got '%s'", argv[i]);
                }
                tscale = v;
                have_time = 1;
            } else {
                if (!(v > 0.0)) {
                    return usage_error("--duration must be > 0, got '%s'", argv[i]);
                }
                duration = v;
                have_duration = 1;
            }
        } else if (strcmp(a, "--plant") == 0) {
            if (!more) {
                return usage_error("%s needs a value", a);
            }
            i++;
            if (strcmp(argv[i], "ideal") == 0) {
                plant = 0;
            } else if (strcmp(argv[i], "realistic") == 0) {
                plant = 1;
            } else {
                return usage_error("--plant must be ideal or realistic, got '%s'", argv[i]);
            }
            have_plant = 1;
        } else if (strcmp(a, "--skill") == 0) {
            if (!more || argv[i + 1][0] == '-') {
                return usage_error("%s needs a file name", a);
            }
            while (i + 1 < argc && argv[i + 1][0] != '-') {
                if (n_cli_skills >= SIM_MAX_SKILLS) {
                    return usage_error("at most 8 skills, got more at '%s'", argv[i + 1]);
                }
                cli_skills[n_cli_skills++] = argv[++i];
            }
        } else if (strcmp(a, "--step-duration") == 0) {
            if (!more) {
                return usage_error("%s needs a value", a);
            }
            while (i + 1 < argc && (argv[i + 1][0] != '-' || argv[i + 1][1] == '.')) {
                double v = 0.0;
                if (parse_num(a, argv[i + 1], &v) != 0) {
                    return 2;
                }
                if (!(v > 0.0) || n_cli_durations >= SIM_MAX_SKILLS) {
                    return usage_error("bad --step-duration '%s' (> 0, at most 8)", argv[i + 1]);
                }
                cli_durations[n_cli_durations++] = v;
                i++;
            }
        } else if (a[0] == '-' && a[1] != '\0') {
            return usage_error("unknown option '%s'", a);
        } else if (scenario == NULL) {
            scenario = a;
        } else {
            return usage_error("unexpected argument '%s'", a);
        }
    }
    if (scenario == NULL) {
        return usage_error("%s", "missing SCENARIO");
    }
    sim_scenario_defaults(&sc);
    if (sim_scenario_load(&sc, scenario, err) != 0) {
        fprintf(stderr, "hil_sim: %s\n", err);
        return 2;
    }
    if (have_seed) {
        sc.seed = (uint64_t)seed;
    }
    if (have_goal) {
        sc.goal_scale = goal;
    }
    if (have_time) {
        sc.time_scale = tscale;
    }
    if (have_plant) {
        sc.plant = (sim_plant_kind_t)plant;
    }
    if (have_duration) {
        sc.duration_s = duration;
    }
    if (n_cli_skills > 0) {
        sc.n_skills = n_cli_skills;
        for (int i = 0; i < n_cli_skills; i++) {
            snprintf(sc.skill_path[i], SIM_PATH_MAX, "%s", cli_skills[i]);
        }
    }
    if (n_cli_durations > 0) {
        sc.n_step_durations = n_cli_durations;
        memcpy(sc.step_duration_s, cli_durations, sizeof(double) * (size_t)n_cli_durations);
    }
    if (sc.mode == SIM_MODE_EXECUTE && n_cli_skills == 0 && sc.n_skills == 0) {
        fprintf(stderr, "hil_sim: %s: execute scenario without skills: pass --skill FILE\n",
                scenario);
        return 2;
    }
    if (sim_scenario_check(&sc, err) != 0) {
        fprintf(stderr, "hil_sim: %s\n", err);
        return 2;
    }
    if (sc.mode == SIM_MODE_EXECUTE && sim_load_skills(&sc, skills, err) != 0) {
        fprintf(stderr, "hil_sim: %s\n", err);
        return 2;
    }

    FILE *log = NULL;
    char summary_path[SIM_PATH_MAX + 32];
    if (out != NULL) {
        log = fopen(out, "w");
        if (log == NULL) {
            fprintf(stderr, "hil_sim: %s: cannot write the log: %s\n", out, strerror(errno));
            return 2;
        }
        size_t len = strlen(out);
        if (len >= 4 && strcmp(out + len - 4, ".csv") == 0) {
            len -= 4;
        }
        if (len > SIM_PATH_MAX) {
            fclose(log);
            fprintf(stderr, "hil_sim: output path too long\n");
            return 2;
        }
        snprintf(summary_path, sizeof summary_path, "%.*s.summary.json", (int)len, out);
    }
    sim_summary_t sum;
    int rc = sim_run(&sc, skills, log, &sum, err);
    if (log != NULL && fclose(log) != 0) {
        rc = -1;
        snprintf(err, sizeof err, "%s: closing the log failed", out);
    }
    if (rc != 0) {
        fprintf(stderr, "hil_sim: %s\n", err);
        return 1;
    }
    if (out != NULL) {
        if (sim_write_summary(&sc, &sum, summary_path) != 0) {
            fprintf(stderr, "hil_sim: %s: cannot write the summary\n", summary_path);
            return 1;
        }
        printf("%s: %.3f s simulated in %.3f s (%.0fx real time); log %s, summary %s\n", sc.name,
               sum.sim_time_s, sum.wall_s, sum.x_realtime, out, summary_path);
    } else if (sim_write_summary(&sc, &sum, "/dev/stdout") != 0) {
        return 1;
    }
    return 0;
}

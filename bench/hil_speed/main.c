/* bench_hil_speed: lockstep speed of every paper scenario (both axes, one core).
 * Prints one line per scenario:
 *   hil_lockstep scenario=NAME x_realtime=X x_realtime_with_log=Y sim_s=S
 * x_realtime is simulated time / wall time without the CSV log (best of 5 runs), x_realtime_cpu
 * the same over the process CPU time (stable on a loaded machine);
 * x_realtime_with_log writes the full CSV log to /dev/null. Execution scenarios run the golden
 * N=50 skills of tests/vectors for the paper's step durations (the cost per tick does not depend
 * on which skill runs). Usage: bench_hil_speed [SCENARIO_DIR] */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "sim_run.h"
#include "sim_scenario.h"

typedef struct {
    const char *file;
    int n_skills;
    const char *skill[2];
    double duration_s;
} bench_case_t;

static const bench_case_t CASES[] = {
    {"pressing_task1_demo", 0, {NULL, NULL}, 0.0},
    {"pressing_task2_demo", 0, {NULL, NULL}, 0.0},
    {"engraving_task1_demo", 0, {NULL, NULL}, 0.0},
    {"engraving_task2_demo", 0, {NULL, NULL}, 0.0},
    {"pressing_task1_exec", 1, {"press_n50_ridge_release.skill", NULL}, 7.0},
    {"pressing_task2_exec", 1, {"press_n50_ridge_release.skill", NULL}, 6.0},
    {"engraving_task1_exec", 1, {"engrave_n50_ridge_release.skill", NULL}, 9.0},
    {"engraving_task2_exec", 1, {"engrave_n50_ridge_release.skill", NULL}, 10.0},
    {"reuse_200_1x", 2, {"engrave_n50_ridge_release.skill", "engrave_n50_ridge_release.skill"}, 0.0},
    {"reuse_300_1_5x", 2, {"engrave_n50_ridge_release.skill", "engrave_n50_ridge_release.skill"}, 0.0},
};

static double cpu_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static sim_scenario_t sc;
static sim_skill_image_t skills[SIM_MAX_SKILLS];

int main(int argc, char **argv)
{
    const char *dir = (argc > 1) ? argv[1] : HIL_SCENARIOS_DIR;
    char err[SIM_ERR_MAX];
    char path[SIM_PATH_MAX + 64];
    double worst = 1e300, worst_cpu = 1e300;
    for (size_t c = 0; c < sizeof CASES / sizeof CASES[0]; c++) {
        const bench_case_t *k = &CASES[c];
        sim_scenario_defaults(&sc);
        snprintf(path, sizeof path, "%s/%s.toml", dir, k->file);
        if (sim_scenario_load(&sc, path, err) != 0) {
            fprintf(stderr, "bench_hil_speed: %s\n", err);
            return 2;
        }
        if (k->n_skills > 0) {
            sc.n_skills = k->n_skills;
            for (int i = 0; i < k->n_skills; i++) {
                snprintf(sc.skill_path[i], SIM_PATH_MAX, "%s/%s", HIL_VECTORS_DIR, k->skill[i]);
            }
            if (sc.n_step_durations == 0 && k->duration_s > 0.0) {
                sc.n_step_durations = 1;
                sc.step_duration_s[0] = k->duration_s - sc.tail_s;
            }
            if (sim_load_skills(&sc, skills, err) != 0) {
                fprintf(stderr, "bench_hil_speed: %s\n", err);
                return 2;
            }
        }
        if (sim_scenario_check(&sc, err) != 0) {
            fprintf(stderr, "bench_hil_speed: %s\n", err);
            return 2;
        }
        sim_summary_t sum;
        double best = 0.0, best_log = 0.0, sim_s = 0.0, best_cpu = 0.0;
        for (int rep = 0; rep < 5; rep++) {
            const double c0 = cpu_s();
            if (sim_run(&sc, skills, NULL, &sum, err) != 0) {
                fprintf(stderr, "bench_hil_speed: %s\n", err);
                return 1;
            }
            const double cpu = cpu_s() - c0;
            best = (sum.x_realtime > best) ? sum.x_realtime : best;
            sim_s = sum.sim_time_s;
            if (cpu > 0.0 && sim_s / cpu > best_cpu) {
                best_cpu = sim_s / cpu;
            }
        }
        FILE *devnull = fopen("/dev/null", "w");
        if (devnull == NULL) {
            return 1;
        }
        for (int rep = 0; rep < 3; rep++) {
            if (sim_run(&sc, skills, devnull, &sum, err) != 0) {
                fprintf(stderr, "bench_hil_speed: %s\n", err);
                fclose(devnull);
                return 1;
            }
            best_log = (sum.x_realtime > best_log) ? sum.x_realtime : best_log;
        }
        fclose(devnull);
        printf("hil_lockstep scenario=%s x_realtime=%.0f x_realtime_cpu=%.0f x_realtime_with_log=%.0f "
               "sim_s=%.3f\n", sc.name, best, best_cpu, best_log, sim_s);
        worst = (best < worst) ? best : worst;
        worst_cpu = (best_cpu < worst_cpu) ? best_cpu : worst_cpu;
    }
    printf("hil_lockstep min_x_realtime=%.0f min_x_realtime_cpu=%.0f (must >= 1000, aim >= 5000)\n", worst,
           worst_cpu);
    return 0;
}

/* Lockstep scenario run: see sim_run.h and docs/hil.md. */
#define _POSIX_C_SOURCE 200809L
#include "sim_run.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "fs_exec.h"
#include "sim_rng.h"

#define SIM_RING 8 /* >= max delay_samples + 1 */

/* ---------------- skills ---------------- */

int sim_load_skills(const sim_scenario_t *sc, skill_t *skills, char err[SIM_ERR_MAX])
{
    static uint8_t buf[SKILL_IMAGE_MAX + 1u];
    for (int i = 0; i < sc->n_skills; i++) {
        const char *path = sc->skill_path[i];
        FILE *f = fopen(path, "rb");
        if (f == NULL) {
            snprintf(err, SIM_ERR_MAX, "%s: cannot open skill: %s", path, strerror(errno));
            return -1;
        }
        size_t n = fread(buf, 1, sizeof buf, f);
        fclose(f);
        if (n == sizeof buf) {
            snprintf(err, SIM_ERR_MAX, "%s: larger than any valid skill image", path);
            return -1;
        }
        fs_status_t rc = skill_parse(buf, (uint32_t)n, &skills[i]);
        if (rc != FS_OK) {
            snprintf(err, SIM_ERR_MAX, "%s: invalid skill image (error %d, see fs_status.h)", path,
                     (int)rc);
            return -1;
        }
    }
    return 0;
}

/* ---------------- CSV output ---------------- */

/* Fixed-point decimal formatting (6 decimals): exact, locale-free, ~10x faster than printf. */
static char *put_fixed6(char *p, double v)
{
    if (!(v == v)) {
        memcpy(p, "nan", 3);
        return p + 3;
    }
    if (v < 0.0) {
        *p++ = '-';
        v = -v;
    }
    if (v >= 9.0e12) {
        return p + sprintf(p, "%.6e", v);
    }
    uint64_t q = (uint64_t)(v * 1e6 + 0.5);
    uint64_t ip = q / 1000000u;
    uint32_t fp = (uint32_t)(q % 1000000u);
    char tmp[24];
    int n = 0;
    do {
        tmp[n++] = (char)('0' + (int)(ip % 10u));
        ip /= 10u;
    } while (ip != 0u);
    while (n > 0) {
        *p++ = tmp[--n];
    }
    *p++ = '.';
    for (int k = 5; k >= 0; k--) {
        p[k] = (char)('0' + (int)(fp % 10u));
        fp /= 10u;
    }
    return p + 6;
}

typedef struct {
    FILE *f;
    char buf[1 << 16];
    size_t len;
} logbuf_t;

static void log_flush(logbuf_t *lb)
{
    if (lb->f != NULL && lb->len > 0) {
        fwrite(lb->buf, 1, lb->len, lb->f);
    }
    lb->len = 0;
}

static void log_row(logbuf_t *lb, const double *v, int n)
{
    if (lb->len + 512u > sizeof lb->buf) {
        log_flush(lb);
    }
    char *p = lb->buf + lb->len;
    for (int i = 0; i < n; i++) {
        if (i > 0) {
            *p++ = ',';
        }
        p = put_fixed6(p, v[i]);
    }
    *p++ = '\n';
    lb->len = (size_t)(p - lb->buf);
}

/* ---------------- faults ---------------- */

static int fault_active(const sim_fault_t *fl, sim_fault_kind_t kind, double t)
{
    return fl->kind == kind && t >= fl->at_s - 1e-9 && t < fl->at_s + fl->duration_s - 1e-9;
}

/* ---------------- run ---------------- */

typedef struct {
    double x, y, fc, fop_x, fop_y;
} sample_t;

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

int sim_run(const sim_scenario_t *sc, const skill_t *skills, FILE *log, sim_summary_t *sum,
            char err[SIM_ERR_MAX])
{
    static logbuf_t lb;
    const double t0_wall = now_s();
    const double dt = sc->dt_s;
    const double h = dt / (double)sc->substeps;
    const int teach = (sc->mode == SIM_MODE_TEACH);
    const int realistic = (sc->plant == SIM_PLANT_REALISTIC);

    memset(sum, 0, sizeof *sum);
    sum->layer_reached_s = -1.0;

    /* independent streams: operator draws do not depend on how much sensor noise was drawn */
    sim_rng_t rng_op, rng_sens;
    sim_rng_seed(&rng_op, sc->seed);
    sim_rng_seed(&rng_sens, sc->seed ^ 0x5EB5C0DEDA7A5EEDull);

    sim_operator_cfg_t opc = sc->op;
    opc.duration_s = sc->duration_s;
    sim_operator_t op;
    if (teach) {
        sim_operator_init(&op, &opc, &rng_op);
    } else {
        opc.task = SIM_TASK_NONE;
        sim_operator_init(&op, &opc, &rng_op);
    }

    /* firmware side */
    static exec_config_t ecfg;
    static exec_state_t est;
    exec_config_default(&ecfg);
    double duration = sc->duration_s;
    if (!teach) {
        ecfg.pfc.gains[0] = skills[0].gains;
        ecfg.pfc.gains[1].m_d_kg = skills[0].gains.m_d_kg;
        for (unsigned a = 0; a < PFC_AXES; a++) {
            ecfg.pfc.limits[a].force_max_N = sc->force_max_N;
        }
        ecfg.pfc.dt_s = dt;
        ecfg.use_model = (uint8_t)(sc->use_model != 0);
        ecfg.object.m_v_kg = sc->object.m_v_kg;
        ecfg.object.d_v_Nspm = sc->object.d_v_Nspm;
        ecfg.object.k1_Npm = sc->object.k1_Npm;
        ecfg.object.k2_Npm = sc->object.k2_Npm;
        ecfg.object.layer_depth_m = sc->object.layer_depth_m;
        ecfg.object.surface_m = sc->object.surface_m;
        ecfg.phase_stop_gain_per_N2 = sc->phase_stop_gain_per_N2;
        exec_step_t steps[EXEC_MAX_STEPS];
        double total = 0.0;
        for (int i = 0; i < sc->n_skills; i++) {
            steps[i].skill = &skills[i];
            steps[i].goal_scale = sc->goal_scale;
            steps[i].time_scale = sc->time_scale;
            steps[i].duration_s = (sc->n_step_durations > 0) ? sc->step_duration_s[i] : 0.0;
            steps[i].end_policy = (sc->end_policy < 0) ? skills[i].end_policy
                                                       : (skill_end_t)sc->end_policy;
            total += (steps[i].duration_s > 0.0) ? steps[i].duration_s
                                                 : skills[i].dmp.duration_s * sc->time_scale;
        }
        fs_status_t rc = exec_start(&ecfg, &est, steps, (uint8_t)sc->n_skills, sc->start_y_m);
        if (rc != FS_OK) {
            snprintf(err, SIM_ERR_MAX, "%s: cannot start execution (error %d)", sc->path, (int)rc);
            return -1;
        }
        if (!(duration > 0.0)) {
            duration = total + sc->tail_s;
        }
    }
    const double m_d = teach ? sc->m_d_kg : (double)ecfg.pfc.gains[0].m_d_kg;

    exec_render_cfg_t rcfg;
    exec_render_default(&rcfg);
    rcfg.carriage_kg = sc->carriage.carriage_kg;
    rcfg.viscous_Nspm = sc->carriage.viscous_Nspm;
    rcfg.coulomb_N = sc->carriage.coulomb_N;
    rcfg.motor_max_N = sc->carriage.act_max_N;
    exec_render_t rend[2];
    exec_render_reset(&rend[0], sc->start_x_m);
    exec_render_reset(&rend[1], sc->start_y_m);
    exec_vel_t vel[2];
    exec_vel_init(&vel[0], sc->vel_cutoff_Hz, dt);
    exec_vel_init(&vel[1], sc->vel_cutoff_Hz, dt);

    sim_axis_t ax[2];
    memset(ax, 0, sizeof ax);
    ax[0].pos_m = sc->start_x_m;
    ax[1].pos_m = sc->start_y_m;

    sim_drive_t drv[2];
    for (int a = 0; a < 2; a++) {
        drv[a].kind = sc->plant;
        drv[a].prescribed = (uint8_t)(!teach && !realistic);
        drv[a].mass_kg = realistic ? sc->carriage.carriage_kg : m_d;
        drv[a].force_cmd_N = 0.0;
        drv[a].force_ext_N = 0.0;
        drv[a].hand_damping_Nspm = teach ? sc->op.hand_damping_Nspm : 0.0;
        drv[a].carriage = &sc->carriage;
        drv[a].object = (a == 0) ? &sc->object : NULL;
        drv[a].act_limit_N = sc->carriage.act_max_N;
        drv[a].act_alpha = 1.0 - exp(-h / sc->carriage.act_lag_s);
        sim_drive_prepare(&drv[a]);
    }

    lb.f = log;
    lb.len = 0;
    if (log != NULL) {
        const char *hdr = "t,x,y,f_contact,f_operator,f_cmd,f_hat\n";
        memcpy(lb.buf, hdr, strlen(hdr));
        lb.len = strlen(hdr);
    }

    sample_t ring[SIM_RING];
    const uint64_t n_ticks = (uint64_t)(duration / dt + 0.5);
    double stuck_fc = 0.0;
    int stuck_set = 0;
    double sq_err = 0.0;
    double max_err = 0.0;
    const double layer_depth = sc->object.layer_depth_m;

    for (uint64_t n = 0; n <= n_ticks; n++) {
        const double t = (double)n * dt;
        /* operator profile for this tick */
        double fprof[2] = {0.0, 0.0};
        const double p_true = ax[0].pos_m - sc->object.surface_m;
        if (teach) {
            sim_operator_force(&op, t, p_true, layer_depth, fprof);
        }
        drv[0].force_ext_N = fprof[0];
        drv[1].force_ext_N = fprof[1];

        /* sensors at t */
        sample_t s;
        double x_true = ax[0].pos_m;
        if (sc->fault.kind == SIM_FAULT_ENCODER_JUMP && t >= sc->fault.at_s - 1e-9) {
            x_true += sc->fault.value;
        }
        s.x = sim_encoder_read(x_true, sc->encoder_m);
        s.y = sim_encoder_read(ax[1].pos_m, sc->encoder_m);
        s.fc = sim_force_read(&sc->tip, ax[0].contact_N, &rng_sens);
        s.fop_x = sim_force_read(&sc->handle, sim_operator_handle_N(&drv[0], &ax[0]), &rng_sens);
        s.fop_y = sim_force_read(&sc->handle, sim_operator_handle_N(&drv[1], &ax[1]), &rng_sens);
        if (fault_active(&sc->fault, SIM_FAULT_FORCE_SPIKE, t)) {
            s.fc += sc->fault.value;
        } else if (fault_active(&sc->fault, SIM_FAULT_FORCE_NAN, t)) {
            s.fc = (double)NAN;
        } else if (fault_active(&sc->fault, SIM_FAULT_FORCE_STUCK, t)) {
            if (!stuck_set) {
                stuck_fc = s.fc;
                stuck_set = 1;
            }
            s.fc = stuck_fc;
        }
        ring[n % SIM_RING] = s;
        const uint64_t d = ((uint64_t)sc->delay_samples > n) ? n : (uint64_t)sc->delay_samples;
        const sample_t *m = &ring[(n - d) % SIM_RING];
        const double vx = exec_vel_update(&vel[0], m->x, dt);
        const double vy = exec_vel_update(&vel[1], m->y, dt);

        /* firmware */
        double f_cmd[2] = {0.0, 0.0};
        double f_hat = 0.0;
        double cmd_log = 0.0;
        if (teach) {
            const double tot_x = m->fop_x - m->fc;
            cmd_log = tot_x;
            if (realistic) {
                drv[0].force_cmd_N = exec_render_step(&rcfg, &rend[0], tot_x, m_d, tot_x, m->x, vx,
                                                      dt);
                drv[1].force_cmd_N = exec_render_step(&rcfg, &rend[1], m->fop_y, m_d, m->fop_y,
                                                      m->y, vy, dt);
            }
        } else {
            exec_meas_t em = {{m->x, m->y}, {vx, vy}, m->fc};
            exec_out_t eo;
            if (exec_tick(&ecfg, &est, &em, &eo) != FS_OK) {
                sum->nonfinite_ticks++;
            }
            f_cmd[0] = eo.force_cmd_N[0];
            f_cmd[1] = eo.force_cmd_N[1];
            f_hat = eo.force_hat_N;
            cmd_log = f_cmd[0];
            for (int a = 0; a < 2; a++) {
                const double fa = fabs(f_cmd[a]);
                if (fa > sum->max_cmd_abs_N) {
                    sum->max_cmd_abs_N = fa;
                }
                if (fa > sc->force_max_N * (1.0 + 1e-12)) {
                    sum->limit_violations++;
                }
                if (fa >= sc->force_max_N * (1.0 - 1e-9)) {
                    sum->saturated_ticks++;
                }
            }
            if (fault_active(&sc->fault, SIM_FAULT_ACTUATOR_SATURATION, t)) {
                const double lim = fabs(sc->fault.value);
                for (int a = 0; a < 2; a++) {
                    drv[a].act_limit_N = lim;
                    if (!realistic) {
                        f_cmd[a] = (f_cmd[a] > lim) ? lim : ((f_cmd[a] < -lim) ? -lim : f_cmd[a]);
                    }
                }
            } else {
                drv[0].act_limit_N = sc->carriage.act_max_N;
                drv[1].act_limit_N = sc->carriage.act_max_N;
            }
            if (realistic) {
                drv[0].force_cmd_N = exec_render_step(&rcfg, &rend[0], f_cmd[0], m_d, -m->fc, m->x,
                                                      vx, dt);
                drv[1].force_cmd_N = exec_render_step(&rcfg, &rend[1], f_cmd[1], m_d, 0.0, m->y, vy,
                                                      dt);
            } else {
                drv[0].force_cmd_N = f_cmd[0];
                drv[1].force_cmd_N = f_cmd[1];
            }
            if (f_hat > sum->max_hat_N) {
                sum->max_hat_N = f_hat;
            }
            const double e = fabs(s.fc - f_hat);
            if (e == e) {
                sq_err += e * e;
                if (e > max_err) {
                    max_err = e;
                }
            }
        }
        if (teach && fabs(cmd_log) > sum->max_cmd_abs_N) {
            sum->max_cmd_abs_N = fabs(cmd_log);
        }

        /* log (sensor values at t, the firmware's command and reference of this tick) */
        if (log != NULL) {
            const double row[7] = {t, s.x, s.y, s.fc, s.fop_x, cmd_log, f_hat};
            log_row(&lb, row, 7);
        }
        if (s.fc > sum->max_force_N) {
            sum->max_force_N = s.fc;
        }
        if (s.fop_x > sum->max_operator_N) {
            sum->max_operator_N = s.fop_x;
        }
        if (p_true > sum->deformation_max_m) {
            sum->deformation_max_m = p_true;
        }
        if (sum->layer_reached_s < 0.0 && p_true >= layer_depth) {
            sum->layer_reached_s = t;
        }
        if (n == n_ticks) {
            break;
        }
        /* plant: substeps over the tick with the command held (zero-order hold) */
        for (int k = 0; k < sc->substeps; k++) {
            sim_axis_substep(&ax[0], &drv[0], h);
            sim_axis_substep(&ax[1], &drv[1], h);
        }
    }
    log_flush(&lb);
    if (log != NULL && ferror(log)) {
        snprintf(err, SIM_ERR_MAX, "writing the log failed");
        return -1;
    }
    sum->ticks = n_ticks + 1u;
    sum->sim_time_s = (double)n_ticks * dt;
    if (!teach && sum->max_hat_N > 0.0) {
        sum->tracking_max_pct = 100.0 * max_err / sum->max_hat_N;
        sum->tracking_rms_pct = 100.0 * sqrt(sq_err / (double)sum->ticks) / sum->max_hat_N;
    }
    sum->wall_s = now_s() - t0_wall;
    sum->x_realtime = (sum->wall_s > 0.0) ? sum->sim_time_s / sum->wall_s : 0.0;
    return 0;
}

static void json_num(FILE *f, const char *key, double v, int last)
{
    if (v == v && !isinf(v)) {
        fprintf(f, "  \"%s\": %.9g%s\n", key, v, last ? "" : ",");
    } else {
        fprintf(f, "  \"%s\": null%s\n", key, last ? "" : ",");
    }
}

int sim_write_summary(const sim_scenario_t *sc, const sim_summary_t *s, const char *path)
{
    FILE *f = fopen(path, "w");
    if (f == NULL) {
        return -1;
    }
    fprintf(f, "{\n  \"scenario\": \"%s\",\n", sc->name);
    fprintf(f, "  \"mode\": \"%s\",\n  \"plant\": \"%s\",\n",
            sc->mode == SIM_MODE_TEACH ? "teach" : "execute",
            sc->plant == SIM_PLANT_IDEAL ? "ideal" : "realistic");
    fprintf(f, "  \"seed\": %llu,\n", (unsigned long long)sc->seed);
    fprintf(f, "  \"goal_scale\": %.9g,\n  \"time_scale\": %.9g,\n", sc->goal_scale,
            sc->time_scale);
    fprintf(f, "  \"force_limit_N\": %.9g,\n", sc->force_max_N);
    fprintf(f, "  \"ticks\": %llu,\n", (unsigned long long)s->ticks);
    json_num(f, "sim_time_s", s->sim_time_s, 0);
    json_num(f, "max_force_N", s->max_force_N, 0);
    json_num(f, "max_operator_force_N", s->max_operator_N, 0);
    json_num(f, "max_cmd_abs_N", s->max_cmd_abs_N, 0);
    json_num(f, "max_f_hat_N", s->max_hat_N, 0);
    json_num(f, "deformation_max_m", s->deformation_max_m, 0);
    json_num(f, "layer_reached_s", s->layer_reached_s >= 0.0 ? s->layer_reached_s : (double)NAN, 0);
    json_num(f, "tracking_max_pct",
             sc->mode == SIM_MODE_EXECUTE ? s->tracking_max_pct : (double)NAN, 0);
    json_num(f, "tracking_rms_pct",
             sc->mode == SIM_MODE_EXECUTE ? s->tracking_rms_pct : (double)NAN, 0);
    fprintf(f, "  \"limit_violations\": %llu,\n", (unsigned long long)s->limit_violations);
    fprintf(f, "  \"saturated_ticks\": %llu,\n", (unsigned long long)s->saturated_ticks);
    fprintf(f, "  \"nonfinite_ticks\": %llu,\n", (unsigned long long)s->nonfinite_ticks);
    json_num(f, "wall_time_s", s->wall_s, 0);
    json_num(f, "x_realtime", s->x_realtime, 1);
    fprintf(f, "}\n");
    return fclose(f) == 0 ? 0 : -1;
}

/* Lockstep scenario run: see sim_run.h and docs/hil.md. */
#define _POSIX_C_SOURCE 200809L
#include "sim_run.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "app_config.h"
#include "fs_dbc.h"
#include "hal_host.h"
#include "nvm.h"
#include "proto_ids.h"
#include "sim_couple.h"
#include "sim_rng.h"
#include "uds_nrc.h"

/* ---------------- skills ---------------- */

int sim_load_skills(const sim_scenario_t *sc, sim_skill_image_t *images, char err[SIM_ERR_MAX])
{
    static skill_t check;
    for (int i = 0; i < sc->n_skills; i++) {
        const char *path = sc->skill_path[i];
        sim_skill_image_t *img = &images[i];
        FILE *f = fopen(path, "rb");
        if (f == NULL) {
            snprintf(err, SIM_ERR_MAX, "%s: cannot open skill: %s", path, strerror(errno));
            return -1;
        }
        size_t n = fread(img->data, 1, sizeof img->data, f);
        fclose(f);
        if (n == sizeof img->data) {
            snprintf(err, SIM_ERR_MAX, "%s: larger than any valid skill image", path);
            return -1;
        }
        img->len = (uint32_t)n;
        fs_status_t rc = skill_parse(img->data, img->len, &check);
        if (rc != FS_OK) {
            snprintf(err, SIM_ERR_MAX, "%s: invalid skill image (error %d, see fs_status.h)", path,
                     (int)rc);
            return -1;
        }
        /* the force loop feeds back the object's inertia: k_f*m_v/m_d >= 1 oscillates into the
         * slew limit within a second of contact (forceskill run refuses such a skill) */
        const double k_f = (double)check.fit_gains.kkf_Npm / (double)check.stiffness_Npm;
        const double ratio = k_f * sc->object.m_v_kg / (double)check.fit_gains.m_d_kg;
        if (ratio >= 1.0) {
            fprintf(
                stderr,
                "hil_sim: warning: %s: its force gains are unstable on this scenario's %g kg "
                "object "
                "(k_f*m_v/m_d = %.3g >= 1): expect fault 508 within a second of contact; fit it "
                "with --object-mass %g\n",
                path, sc->object.m_v_kg, ratio, sc->object.m_v_kg);
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

/* ---------------- the device ---------------- */

#define SIM_RUN_HB_PERIOD_MS 10u  /* host heartbeat period (the forceskill host's) */
#define SIM_RUN_TELEMETRY_MS 100u /* telemetry the host asks for: the run logs its own */
#define SIM_RUN_START_TICKS 3u    /* ticks before t = 0: boot, then the command */

typedef struct {
    app_t *app; /* app_device(): one device per process */
    app_config_t cfg;
    secoc_t host;        /* the host's session: its key and freshness values */
    uint16_t fault_code; /* first emergency frame's code, 0 if none */
    uint64_t fault_tick;
} sim_dev_t;

/* Host frames into the device, device frames out of it (an emergency frame records the first
 * fault); heartbeats every SIM_RUN_HB_PERIOD_MS while the device acts. */
static void dev_host(sim_dev_t *d, uint64_t n_tick)
{
    can_frame_t f;
    if (n_tick % SIM_RUN_HB_PERIOD_MS == 0u) {
        sim_couple_heartbeat_frame(&d->host, d->cfg.node, SIM_RUN_TELEMETRY_MS, &f);
        (void)hal_sim_can_deliver(&f);
    }
    while (hal_sim_can_tx_peek(&f)) {
        hal_sim_can_tx_pop();
        struct fs_dbc_emergency_t m;
        if (f.id == PROTO_ID_EMERGENCY(d->cfg.node) && d->fault_code == 0u &&
            fs_dbc_emergency_unpack(&m, f.data, f.len) == 0) {
            d->fault_code = m.fault_code;
            d->fault_tick = n_tick;
        }
    }
}

/* Power the device up over a fresh flash holding the scenario's skills in slots 1..n, let it
 * boot with the handle at rest at the start, then start the TEACH or EXECUTE the scenario asks
 * for as the host would (a HostCommand frame; a sequence is a run request to app_run_start, the
 * device's one motion path). */
static int dev_flash_skills(const sim_scenario_t *sc, const sim_skill_image_t *skills,
                            char err[SIM_ERR_MAX])
{
    hal_host_init();
    hal_host_flash_erase();
    hal_sim_can_reset();
    nvm_t bank;
    if (nvm_init(&bank, hal_flash()) != NVM_OK) {
        snprintf(err, SIM_ERR_MAX, "%s: simulated flash failed", sc->path);
        return -1;
    }
    for (int i = 0; i < sc->n_skills; i++) {
        if (nvm_write(&bank, (uint16_t)i, skills[i].data, skills[i].len) != NVM_OK) {
            snprintf(err, SIM_ERR_MAX, "%s: skill %d does not fit a flash slot", sc->path, i + 1);
            return -1;
        }
    }
    return 0;
}

static int dev_start(sim_dev_t *d, const sim_scenario_t *sc, const sim_skill_image_t *skills,
                     double *total_s, char err[SIM_ERR_MAX])
{
    if (dev_flash_skills(sc, skills, err) != 0) {
        return -1;
    }
    memset(d, 0, sizeof(*d));
    d->app = app_device();
    sim_couple_device_config(sc, &d->cfg);
    hal_host_set_time_us(0u);
    app_init(d->app, &d->cfg);
    (void)sim_couple_host_session(d->app, &d->host);
    const hal_sensors_t rest = {{sc->start_x_m, sc->start_y_m}, {0.0, 0.0}, {0.0, 0.0}};
    hal_host_set_sensors(&rest);
    for (uint32_t k = 0; k < SIM_RUN_START_TICKS; k++) {
        hal_host_set_time_us((uint64_t)k * APP_TICK_US);
        if (k == SIM_RUN_START_TICKS - 2u) { /* one MAC a tick: the heartbeat, then TEACH */
            can_frame_t f;
            sim_couple_heartbeat_frame(&d->host, d->cfg.node, SIM_RUN_TELEMETRY_MS, &f);
            (void)hal_sim_can_deliver(&f);
        }
        if (k == SIM_RUN_START_TICKS - 1u) {
            if (sc->mode == SIM_MODE_TEACH) {
                can_frame_t c[2];
                (void)sim_couple_command_frames(&d->host, d->cfg.node, APP_CMD_TEACH, 0u, 0.0, 0.0,
                                                0u, c);
                (void)hal_sim_can_deliver(&c[0]);
            }
        }
        app_tick(d->app, false);
        dev_host(d, 1u);
    }
    *total_s = 0.0;
    if (sc->mode == SIM_MODE_EXECUTE) {
        app_run_request_t req;
        memset(&req, 0, sizeof(req));
        req.source = APP_RUN_FROM_LOCAL;
        for (int i = 0; i < sc->n_skills; i++) {
            const skill_t *sk = app_slot_skill(d->app, (uint8_t)(i + 1));
            if (sk == NULL) {
                snprintf(err, SIM_ERR_MAX, "%s: the device did not load skill %d", sc->path, i + 1);
                return -1;
            }
            app_run_step_t *s = &req.step[i];
            s->slot = (uint8_t)(i + 1);
            s->goal_scale = sc->goal_scale;
            s->time_scale = sc->time_scale;
            s->path_scale = sc->path_scale;
            s->amplitude_scale = 1.0;
            s->cycles = 1u; /* a periodic skill: its duration, or one cycle */
            s->duration_s = (sc->n_step_durations > 0) ? sc->step_duration_s[i] : 0.0;
            *total_s += (s->duration_s > 0.0) ? s->duration_s
                                              : (double)sk->dmp.duration_s * sc->time_scale;
        }
        req.end = (sc->end_policy < 0) ? 0u : (sc->end_policy == SKILL_END_HOLD ? 1u : 2u);
        req.n_steps = (uint8_t)sc->n_skills;
        const uint8_t nrc = app_run_start(d->app, &req);
        if (nrc != UDS_NRC_OK) {
            snprintf(err, SIM_ERR_MAX,
                     "%s: the device refused the sequence (NRC 0x%02X, status %u)", sc->path,
                     (unsigned)nrc, (unsigned)app_last_run_status(d->app));
            return -1;
        }
    }
    const app_state_t want = (sc->mode == SIM_MODE_TEACH) ? APP_TEACH : APP_EXECUTE;
    if (app_state(d->app) != want) {
        snprintf(err, SIM_ERR_MAX, "%s: the device is in state %d, not %d", sc->path,
                 (int)app_state(d->app), (int)want);
        return -1;
    }
    return 0;
}

/* ---------------- run ---------------- */

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Everything the lockstep loop carries from tick to tick. */
typedef struct {
    const sim_scenario_t *sc;
    int teach;
    sim_rng_t rng_op, rng_sens;
    sim_operator_t op;
    sim_axis_t ax[2];
    sim_drive_t drv[2];
    sim_couple_away_t away; /* the object the plant meets (the scenario's away_*) */
    sim_sample_t ring[SIM_COUPLE_RING];
    double stuck_fc;
    int stuck_set;
    double sq_err, max_err; /* |contact - reference| while executing */
    uint64_t exec_ticks;
    sim_dev_t dev;
    logbuf_t lb;
} run_t;

/* Seed the streams, start the operator and the device, set up the plant and the log; the run's
 * length in s into *duration_s. */
static int run_start(run_t *r, const sim_scenario_t *sc, const sim_skill_image_t *skills, FILE *log,
                     double *duration_s, char err[SIM_ERR_MAX])
{
    memset(r, 0, sizeof *r);
    r->sc = sc;
    r->teach = (sc->mode == SIM_MODE_TEACH);
    /* independent streams: operator draws do not depend on how much sensor noise was drawn */
    sim_rng_seed(&r->rng_op, sc->seed);
    sim_rng_seed(&r->rng_sens, sc->seed ^ 0x5EB5C0DEDA7A5EEDull);

    sim_operator_cfg_t opc = sc->op;
    opc.duration_s = sc->duration_s;
    if (!r->teach) {
        opc.task = SIM_TASK_NONE;
    }
    sim_operator_init(&r->op, &opc, &r->rng_op);

    /* the device: the product's application tick through the host port of hal.h */
    double total = 0.0;
    if (dev_start(&r->dev, sc, skills, &total, err) != 0) {
        return -1;
    }
    *duration_s = sc->duration_s;
    if (!r->teach && !(*duration_s > 0.0)) {
        *duration_s = total + sc->tail_s;
    }

    sim_couple_plant_init(sc, r->ax, r->drv);
    for (int a = 0; a < 2; a++) {
        r->drv[a].hand_damping_Nspm = r->teach ? sc->op.hand_damping_Nspm : 0.0;
    }
    r->lb.f = log;
    r->lb.len = 0;
    if (log != NULL) {
        const char *hdr = "t,x,y,f_contact,f_operator,f_cmd,f_hat\n";
        memcpy(r->lb.buf, hdr, strlen(hdr));
        r->lb.len = strlen(hdr);
    }
    return 0;
}

/* The sensors at t into *s, the scenario's faults injected on the physical sensor; returns the
 * sample the device reads this tick (after the pipeline delay). */
static const sim_sample_t *run_sense(run_t *r, uint64_t n, double t, sim_sample_t *s)
{
    const sim_scenario_t *sc = r->sc;
    sim_couple_sample(sc, r->ax, r->drv, &r->rng_sens, s);
    if (sc->fault.kind == SIM_FAULT_ENCODER_JUMP && t >= sc->fault.at_s - 1e-9) {
        s->x_m = sim_encoder_read(r->ax[0].pos_m + sc->fault.value, sc->encoder_m);
    }
    if (fault_active(&sc->fault, SIM_FAULT_FORCE_SPIKE, t)) {
        s->contact_N += sc->fault.value;
    } else if (fault_active(&sc->fault, SIM_FAULT_FORCE_NAN, t)) {
        s->contact_N = (double)NAN;
    } else if (fault_active(&sc->fault, SIM_FAULT_FORCE_STUCK, t)) {
        if (!r->stuck_set) {
            r->stuck_fc = s->contact_N;
            r->stuck_set = 1;
        }
        s->contact_N = r->stuck_fc;
    }
    return sim_couple_delay(r->ring, n, sc->delay_samples, s);
}

/* EXECUTE: the command against the limit, the injected actuator saturation, the tracking of the
 * reference while the skill runs (executing: the device was in EXECUTE before this tick). */
static void run_execute_figures(run_t *r, double t, const double f_cmd[2], double f_hat,
                                double contact_N, bool executing, sim_summary_t *sum)
{
    const sim_scenario_t *sc = r->sc;
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
            r->drv[a].act_limit_N = lim;
            if (sc->plant == SIM_PLANT_IDEAL) {
                const double c = r->drv[a].force_cmd_N;
                r->drv[a].force_cmd_N = (c > lim) ? lim : ((c < -lim) ? -lim : c);
            }
        }
    } else {
        r->drv[0].act_limit_N = sc->carriage.act_max_N;
        r->drv[1].act_limit_N = sc->carriage.act_max_N;
    }
    if (f_hat > sum->max_hat_N) {
        sum->max_hat_N = f_hat;
    }
    const double e = fabs(contact_N - f_hat);
    if (executing && e == e) {
        r->exec_ticks++;
        r->sq_err += e * e;
        if (e > r->max_err) {
            r->max_err = e;
        }
    }
}

/* The log row of tick t and the maxima every run reports. */
static void run_record(run_t *r, double t, const sim_sample_t *s, double cmd_log, double f_hat,
                       double p_true, sim_summary_t *sum)
{
    if (r->lb.f != NULL) {
        const double row[7] = {t, s->x_m, s->y_m, s->contact_N, s->operator_x_N, cmd_log, f_hat};
        log_row(&r->lb, row, 7);
    }
    if (s->contact_N > sum->max_force_N) {
        sum->max_force_N = s->contact_N;
    }
    if (s->operator_x_N > sum->max_operator_N) {
        sum->max_operator_N = s->operator_x_N;
    }
    if (p_true > sum->deformation_max_m) {
        sum->deformation_max_m = p_true;
    }
    if (sum->layer_reached_s < 0.0 && p_true >= r->sc->object.layer_depth_m) {
        sum->layer_reached_s = t;
    }
}

/* Tick n: operator, sensors, the device's tick and frames, its actuator, the figures. Returns
 * whether the device leaves the plant parked (idle, booting, or stopped with the drive off). */
static bool run_tick(run_t *r, uint64_t n, double t, sim_summary_t *sum)
{
    const sim_scenario_t *sc = r->sc;
    const uint64_t dev_tick = n + SIM_RUN_START_TICKS;
    hal_host_set_time_us(dev_tick * 1000u);
    /* operator profile for this tick */
    double fprof[2] = {0.0, 0.0};
    const double p_true = r->ax[0].pos_m - sc->object.surface_m;
    if (r->teach) {
        sim_operator_force(&r->op, t, p_true, sc->object.layer_depth_m, fprof);
        fprof[1] += sim_operator_path_force(&r->op, t, sc->start_y_m, r->ax[1].pos_m);
    }
    r->drv[0].force_ext_N = fprof[0];
    r->drv[1].force_ext_N = fprof[1];

    sim_sample_t s;
    const sim_sample_t *m = run_sense(r, n, t, &s);
    if (!(isfinite(m->contact_N) && isfinite(m->x_m) && isfinite(m->y_m))) {
        sum->nonfinite_ticks++;
    }
    hal_sensors_t hs;
    sim_couple_to_hal(m, &hs);
    hal_host_set_sensors(&hs);

    /* the device's tick, its frames, its actuator; tracking counts the ticks that run the
     * skill (from EXECUTE: once a sequence has released, the device idles, parked) */
    const bool executing = app_state(r->dev.app) == APP_EXECUTE;
    app_tick(r->dev.app, false);
    dev_host(&r->dev, dev_tick);
    double f_cmd[2];
    const bool enable = sim_couple_actuate(sc, r->dev.app, r->drv, f_cmd);
    const double f_hat = r->teach ? 0.0 : (double)app_force_ref_N(r->dev.app);
    /* TEACH logs the rendered total force (operator - contact), EXECUTE the law's x output */
    const double cmd_log = r->teach ? m->operator_x_N - m->contact_N : f_cmd[0];
    if (!r->teach) {
        run_execute_figures(r, t, f_cmd, f_hat, s.contact_N, executing, sum);
    } else if (fabs(cmd_log) > sum->max_cmd_abs_N) {
        sum->max_cmd_abs_N = fabs(cmd_log);
    }
    run_record(r, t, &s, cmd_log, f_hat, p_true, sum);
    return sim_couple_parked(app_state(r->dev.app), enable);
}

/* The summary's totals once the last tick has run. */
static void run_finish(const run_t *r, uint64_t n_ticks, double t0_wall, sim_summary_t *sum)
{
    const double dt = r->sc->dt_s;
    sum->ticks = n_ticks + 1u;
    sum->sim_time_s = (double)n_ticks * dt;
    sum->fault_code = r->dev.fault_code;
    sum->fault_s = (r->dev.fault_code != 0u)
                       ? (double)(r->dev.fault_tick - SIM_RUN_START_TICKS) * dt
                       : -1.0;
    sum->final_state = (int)app_state(r->dev.app);
    sum->exec_ticks = r->exec_ticks;
    if (!r->teach && sum->max_hat_N > 0.0 && r->exec_ticks > 0u) {
        sum->tracking_max_pct = 100.0 * r->max_err / sum->max_hat_N;
        sum->tracking_rms_pct = 100.0 * sqrt(r->sq_err / (double)r->exec_ticks) / sum->max_hat_N;
    }
    sum->wall_s = now_s() - t0_wall;
    sum->x_realtime = (sum->wall_s > 0.0) ? sum->sim_time_s / sum->wall_s : 0.0;
}

int sim_run(const sim_scenario_t *sc, const sim_skill_image_t *skills, FILE *log,
            sim_summary_t *sum, char err[SIM_ERR_MAX])
{
    static run_t r; /* large (device, log buffer): not on the stack */
    const double t0_wall = now_s();
    const double dt = sc->dt_s;

    memset(sum, 0, sizeof *sum);
    sum->layer_reached_s = -1.0;
    if (fabs(dt - FS_TICK_S) > 1e-12) {
        snprintf(err, SIM_ERR_MAX, "%s: the device ticks at 1 ms, dt_s is %g", sc->path, dt);
        return -1;
    }
    double duration = 0.0;
    if (run_start(&r, sc, skills, log, &duration, err) != 0) {
        return -1;
    }
    const uint64_t n_ticks = (uint64_t)(duration / dt + 0.5);
    for (uint64_t n = 0; n <= n_ticks; n++) {
        const bool parked = run_tick(&r, n, (double)n * dt, sum);
        if (n == n_ticks) {
            break;
        }
        /* plant over the tick, the command held; parked while the device is idle or stopped;
         * the object's surface moved by the scenario's away_* while executing */
        sim_couple_away_begin(&r.away, sc, app_state(r.dev.app), n, &r.drv[0]);
        sim_couple_advance(sc, r.ax, r.drv, parked);
        sim_couple_away_end(sc, &r.drv[0]);
    }
    log_flush(&r.lb);
    if (log != NULL && ferror(log)) {
        snprintf(err, SIM_ERR_MAX, "writing the log failed");
        return -1;
    }
    run_finish(&r, n_ticks, t0_wall, sum);
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
    fprintf(f, "  \"fault_code\": %u,\n", (unsigned)s->fault_code);
    json_num(f, "fault_s", s->fault_s >= 0.0 ? s->fault_s : (double)NAN, 0);
    fprintf(f, "  \"final_state\": %d,\n", s->final_state);
    fprintf(f, "  \"exec_ticks\": %llu,\n", (unsigned long long)s->exec_ticks);
    json_num(f, "wall_time_s", s->wall_s, 0);
    json_num(f, "x_realtime", s->x_realtime, 1);
    fprintf(f, "}\n");
    return fclose(f) == 0 ? 0 : -1;
}

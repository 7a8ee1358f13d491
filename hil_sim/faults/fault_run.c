/* The runner of `hil_sim faults`: see fault_run.h. */
#define _GNU_SOURCE
#include "fault_run.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "fault_rig.h"
#include "fs_wire_const.h"
#include "fls_ram.h"
#include "hal_host.h"

#define IMG_MAX 8192u
#define HOLD_MS FAULT_HOLD_MS
#define ZERO_BOUND_MS FAULT_ZERO_BOUND_MS


static rig_t g_rig;   /* large: static */
static FILE *g_trace; /* --trace: one CSV line per tick of the fault runs */

void fault_run_trace(FILE *f)
{
    g_trace = f;
    if (f != NULL) {
        fprintf(f, "tick,state,fault,cmd_x_N,cmd_y_N,enable,x_m,v_mps,contact_N,x_meas_m,"
                   "contact_meas_N\n");
    }
}

static void trace_tick(const rig_t *r)
{
    if (g_trace != NULL) {
        const sim_sample_t *m = &r->ring[(r->n_tick - 1u) % SIM_COUPLE_RING];
        fprintf(g_trace, "%llu,%d,%u,%.6f,%.6f,%d,%.6f,%.6f,%.6f,%.6f,%.6f\n",
                (unsigned long long)(r->n_tick - 1u), (int)app_state(r->app),
                (unsigned)app_fault_code(r->app), r->cmd_N[0], r->cmd_N[1], r->act_enable ? 1 : 0,
                r->ax[0].pos_m, r->ax[0].vel_mps, r->ax[0].contact_N, m->x_m, m->contact_N);
    }
}
static uint8_t g_img[IMG_MAX], g_nb[IMG_MAX], g_new[IMG_MAX], g_rd[IMG_MAX];
static uint32_t g_img_len, g_nb_len, g_new_len;

static double absd(double v)
{
    return v < 0.0 ? -v : v;
}

static double cmd_abs_max(const rig_t *r)
{
    const double a = absd(r->cmd_N[0]);
    const double b = absd(r->cmd_N[1]);
    return a > b ? a : b;
}

static bool emcy_has(const rig_t *r, uint16_t code)
{
    for (uint32_t i = 0; i < r->n_emcy; i++) {
        if (r->emcy[i].code == code) {
            return true;
        }
    }
    return false;
}

static fls_ram_t *flash_ram(void)
{
    /* the host port's slot flash is an fls_ram (hal_host.h): its handle is the device context */
    return (fls_ram_t *)hal_flash()->ctx;
}

static int setup_device(rig_t *r, const sim_scenario_t *sc)
{
    rig_init(r, sc);
    if (rig_flash_skill(r, 0u, g_img, g_img_len) != 0 ||
        rig_flash_skill(r, 1u, g_nb, g_nb_len) != 0) {
        return -1;
    }
    rig_boot(r);
    r->heartbeat_on = true;
    rig_run(r, 200u);
    return app_state(r->app) == APP_IDLE && (app_slot_skill(r->app, 1u) != NULL) &&
                   (app_slot_skill(r->app, 2u) != NULL)
               ? 0
               : -1;
}

/* What run_fault follows tick by tick (tick numbers; UINT64_MAX: not yet). */
typedef struct {
    uint64_t t_exec, t_inj, dur, end;
    uint64_t onset, det, zero;
    double prev[2];
    bool injected, monotone, hold_ok, was_exec;
} watch_t;

/* Apply the scenario's fault at tick t; returns its onset tick. */
static uint64_t inject(rig_t *r, const fscen_t *fs, uint64_t t)
{
    if (strcmp(fs->kind, "host_silence") == 0) {
        r->heartbeat_on = false;
        return r->last_host_tick;
    }
    if (strcmp(fs->kind, "host_corrupt") == 0) {
        r->inj.corrupt_host = true;
        return r->last_host_tick;
    }
    if (strcmp(fs->kind, "bus_off") == 0) {
        hal_sim_can_set_bus_off(true);
    } else if (strcmp(fs->kind, "force_spike") == 0) {
        r->inj.force_add_N = fs->value;
    } else if (strcmp(fs->kind, "force_nan") == 0) {
        r->inj.force_nan = true;
    } else if (strcmp(fs->kind, "force_stuck") == 0) {
        r->inj.force_stuck = true;
        r->inj.stuck_value_N = r->ring[(t - 1u) % SIM_COUPLE_RING].contact_N;
    } else if (strcmp(fs->kind, "encoder_jump") == 0) {
        r->inj.encoder_add_m = fs->value; /* from now on */
    } else if (strcmp(fs->kind, "actuator_saturation") == 0) {
        r->inj.act_limit_N = fs->value;
    } else if (strcmp(fs->kind, "host_loss") == 0) {
        r->inj.drop_p = fs->value;
    } else if (strcmp(fs->kind, "tick_overrun") == 0) {
        r->inj.stall_ticks = (uint32_t)fs->value;
    } else {
        return UINT64_MAX; /* force_limit: no injection, the onset is measured */
    }
    return t;
}

/* The cause goes away after duration_s (not the encoder jump, nor the host's silence). */
static void remove_cause(rig_t *r, const fscen_t *fs)
{
    r->inj.force_add_N = 0.0;
    r->inj.force_nan = false;
    r->inj.force_stuck = false;
    r->inj.act_limit_N = 0.0;
    r->inj.corrupt_host = false;
    r->inj.drop_p = 0.0;
    if (strcmp(fs->kind, "bus_off") == 0) {
        hal_sim_can_set_bus_off(false);
    }
}

/* After the step of tick t: onset (force_limit), worst force, detection, and from detection on
 * the ramp to zero and the latch. Returns false when the run stops here. */
static bool observe(rig_t *r, const fscen_t *fs, watch_t *w, frow_t *row, uint64_t t)
{
    const double contact_max = (double)r->cfg.saf.lim.axis[0].contact_force_max_N;
    /* the hostile goal scale: the onset is the first contact-force sample above the limit */
    if (strcmp(fs->kind, "force_limit") == 0 && w->onset == UINT64_MAX &&
        r->ring[t % SIM_COUPLE_RING].contact_N > contact_max) {
        w->onset = t;
        row->force_at_onset_N = cmd_abs_max(r);
    }
    const double fa = cmd_abs_max(r);
    if (fa > row->worst_N || isnan(fa)) {
        row->worst_N = isnan(fa) ? (double)INFINITY : fa;
    }
    if (w->det == UINT64_MAX && app_fault_code(r->app) != 0u) {
        w->det = t;
        row->code = app_fault_code(r->app);
        if (fs->expect_code == 0) {
            return false;
        }
        w->end = w->det + HOLD_MS;
        if (strcmp(fs->kind, "host_silence") == 0) {
            r->heartbeat_on = true; /* the host comes back: no resume all the same */
        }
    }
    if (w->det != UINT64_MAX) {
        for (int a = 0; a < 2; a++) {
            if (absd(r->cmd_N[a]) > absd(w->prev[a]) && t > w->det) {
                w->monotone = false;
            }
        }
        if (w->zero == UINT64_MAX && r->cmd_N[0] == 0.0 && r->cmd_N[1] == 0.0) {
            w->zero = t;
        }
        if (app_state(r->app) != APP_FAULT ||
            (w->zero != UINT64_MAX && (fa != 0.0 || r->act_enable))) {
            w->hold_ok = false;
        }
    }
    w->prev[0] = r->cmd_N[0];
    w->prev[1] = r->cmd_N[1];
    return true;
}

/* From EXECUTE to the end of the hold: inject, remove the cause, step, observe. */
static void run_ticks(rig_t *r, const fscen_t *fs, watch_t *w, frow_t *row)
{
    while (r->n_tick < w->end) {
        const uint64_t t = r->n_tick;
        if (t == w->t_inj) {
            row->force_at_onset_N = cmd_abs_max(r);
            w->was_exec = app_state(r->app) ==
                          APP_EXECUTE; /* the skill runs when the fault comes */
            w->injected = true;
            const uint64_t onset = inject(r, fs, t);
            w->onset = onset != UINT64_MAX ? onset : w->onset;
        }
        if (w->injected && t == w->t_inj + w->dur) {
            remove_cause(r, fs);
        }
        rig_step(r);
        trace_tick(r);
        if (t == w->t_inj && w->t_inj == w->t_exec) {
            w->was_exec = app_state(r->app) == APP_EXECUTE; /* at_s = 0: started by this command */
        }
        if (!observe(r, fs, w, row, t)) {
            break;
        }
    }
}

/* The figures every row has: F_max, contact, emergency and status frames, storage. */
static void row_common(const rig_t *r, const watch_t *w, uint32_t crc_before, frow_t *row)
{
    row->f_max_N = (double)r->cfg.saf.lim.axis[0].force_max_N;
    row->contact_max_N = r->contact_max_N;
    row->monotone = w->monotone;
    row->emcy_seen = row->code != 0 && emcy_has(r, (uint16_t)row->code);
    row->emcy_delay_ms = -1.0;
    for (uint32_t i = 0; i < r->n_emcy && w->det != UINT64_MAX; i++) {
        if (r->emcy[i].code == (uint16_t)row->code) {
            row->emcy_delay_ms = (double)(r->emcy[i].rx_tick - w->det);
            break;
        }
    }
    row->status_seen = r->status_fault == row->code && row->code != 0;
    const bool lost_flash = rig_flash_crc() != crc_before;
    row->lost = lost_flash || !(app_slot_skill(r->app, 1u) != NULL) ||
                !(app_slot_skill(r->app, 2u) != NULL);
}

/* expect_code = 0: no fault may latch; the skill runs to its end within the limits. */
static void row_no_fault(const rig_t *r, const watch_t *w, frow_t *row)
{
    row->latched = false;
    row->cleared = true;
    row->detect_ms = -1.0;
    row->zero_ms = -1.0;
    row->pass = w->was_exec && w->det == UINT64_MAX && row->worst_N <= row->f_max_N && !row->lost;
    snprintf(row->note, sizeof row->note, "%s; %u host frames lost",
             w->det == UINT64_MAX ? "no fault latched (none expected)" : "unexpected fault",
             (unsigned)r->host_dropped);
}

/* A detected fault: timings, the latch, then a clear once the cause is gone (the skill must
 * not resume), and the verdict. */
static void row_fault(rig_t *r, const fscen_t *fs, const watch_t *w, frow_t *row)
{
    row->detect_ms = (double)(w->det - w->onset);
    row->zero_ms = w->zero == UINT64_MAX ? -1.0 : (double)(w->zero - w->det);
    row->latched = w->hold_ok && w->zero != UINT64_MAX && r->n_tick >= w->det + HOLD_MS;

    r->heartbeat_on = true;
    rig_command(r, APP_CMD_CLEAR_FAULT, 0u, 0.0, 0.0, 0u);
    bool stayed_zero = true;
    for (int i = 0; i < 100; i++) {
        rig_step(r);
        stayed_zero = stayed_zero && cmd_abs_max(r) == 0.0;
    }
    row->cleared = app_state(r->app) == APP_IDLE && stayed_zero;
    if (!row->status_seen) {
        row->status_seen = r->status_fault == row->code; /* bus-off: status after recovery */
    }
    row->pass = w->was_exec && row->code == fs->expect_code &&
                row->detect_ms <= fs->detect_bound_ms && row->zero_ms >= 0.0 &&
                row->zero_ms <= (double)ZERO_BOUND_MS && row->worst_N <= row->f_max_N &&
                row->monotone && row->latched && row->cleared && !row->lost && row->emcy_seen;
    snprintf(row->note, sizeof row->note, "%s%s%s",
             w->was_exec ? "" : "not executing at injection; ",
             !row->emcy_seen                    ? "no emergency frame"
             : strcmp(fs->kind, "bus_off") == 0 ? "emergency frame after bus recovery"
                                                : "emergency frame",
             row->status_seen ? ", status frame" : "");
}

static void run_fault(const fscen_t *fs, const sim_scenario_t *sc, frow_t *row)
{
    rig_t *r = &g_rig;
    if (setup_device(r, sc) != 0) {
        snprintf(row->note, sizeof row->note, "device did not come up with both slots");
        return;
    }
    const uint32_t crc_before = rig_flash_crc();
    rig_command(r, APP_CMD_EXECUTE, 1u, fs->goal_scale, fs->time_scale, 0u);
    /* one MAC a tick: RUN_OPTIONS, then EXECUTE (behind a heartbeat due then): times from its
     * start */
    for (unsigned k = 0; k < 5u && app_state(r->app) != APP_EXECUTE; k++) {
        rig_step(r);
    }
    watch_t w = {.onset = UINT64_MAX, .det = UINT64_MAX, .zero = UINT64_MAX};
    w.monotone = true;
    w.hold_ok = true;
    w.t_exec = r->n_tick;
    w.t_inj = w.t_exec + (uint64_t)llround(fs->at_s * (double)FS_TICK_HZ);
    w.dur = (uint64_t)llround(fs->duration_s * (double)FS_TICK_HZ) > 0u
                ? (uint64_t)llround(fs->duration_s * (double)FS_TICK_HZ)
                : 1u;
    w.end = w.t_inj + 20000u; /* bounded: the run ends HOLD_MS after detection */
    if (fs->expect_code == 0) {
        w.end = w.t_inj + (uint64_t)llround(fs->duration_s * (double)FS_TICK_HZ) + 200u;
    }
    run_ticks(r, fs, &w, row);
    row_common(r, &w, crc_before, row);
    if (fs->expect_code == 0) {
        row_no_fault(r, &w, row);
    } else if (w.det == UINT64_MAX || w.onset == UINT64_MAX) {
        snprintf(row->note, sizeof row->note, "not detected (onset %s)",
                 w.onset == UINT64_MAX ? "never" : "seen");
    } else {
        row_fault(r, fs, &w, row);
    }
}

/* Power loss at every flash write of a skill upload over UDS (RequestTransferExit programs the
 * slot): reboot, then the slot holds the old or the complete new image, the neighbour intact. */
static void run_power_loss(const sim_scenario_t *sc, frow_t *row)
{
    rig_t *r = &g_rig;
    /* clean upload first: how many erase/program operations it takes */
    if (setup_device(r, sc) != 0 || rig_uds_unlock(r) != 0) {
        snprintf(row->note, sizeof row->note, "device/unlock failed");
        return;
    }
    const uint32_t ops0 = flash_ram()->total_ops;
    if (rig_uds_download(r, 1u, g_new, g_new_len) != 0u) {
        snprintf(row->note, sizeof row->note, "clean upload refused");
        return;
    }
    const uint32_t n_ops = flash_ram()->total_ops - ops0;
    uint32_t kept_old = 0u, got_new = 0u, bad = 0u, reupload_fail = 0u;
    for (uint32_t k = 1u; k <= n_ops; k++) {
        if (setup_device(r, sc) != 0 || rig_uds_unlock(r) != 0) {
            bad++;
            continue;
        }
        fls_ram_set_power_loss(flash_ram(), k);
        const uint8_t nrc = rig_uds_download(r, 1u, g_new, g_new_len);
        rig_run(r, 5u);
        /* power cycle: flash keeps its contents, the firmware boots again */
        fls_ram_power_cycle(flash_ram());
        rig_boot(r);
        r->heartbeat_on = true;
        rig_run(r, 50u);
        if (cmd_abs_max(r) > row->worst_N) {
            row->worst_N = cmd_abs_max(r);
        }
        if (r->contact_max_N > row->contact_max_N) {
            row->contact_max_N = r->contact_max_N;
        }
        uint32_t len = 0u;
        bool ok = rig_read_slot(0u, g_rd, IMG_MAX, &len) == 0;
        const bool is_old = ok && len == g_img_len && memcmp(g_rd, g_img, len) == 0;
        const bool is_new = ok && len == g_new_len && memcmp(g_rd, g_new, len) == 0;
        ok = ok && rig_read_slot(1u, g_rd, IMG_MAX, &len) == 0 && len == g_nb_len &&
             memcmp(g_rd, g_nb, len) == 0;
        ok = ok && (app_slot_skill(r->app, 1u) != NULL) && (app_slot_skill(r->app, 2u) != NULL) &&
             (is_old || is_new);
        if (!ok || (nrc == 0u && !is_new)) {
            bad++;
        } else if (is_new) {
            got_new++;
        } else {
            kept_old++;
        }
        /* the upload is then repeated and succeeds */
        if (rig_uds_unlock(r) != 0 || rig_uds_download(r, 1u, g_new, g_new_len) != 0u ||
            rig_read_slot(0u, g_rd, IMG_MAX, &len) != 0 || len != g_new_len ||
            memcmp(g_rd, g_new, len) != 0) {
            reupload_fail++;
        }
    }
    row->f_max_N = (double)r->cfg.saf.lim.axis[0].force_max_N;
    row->detect_ms = -1.0;
    row->zero_ms = -1.0;
    row->monotone = true;
    row->latched = true;
    row->cleared = true;
    row->lost = bad != 0u;
    row->pass = n_ops > 0u && bad == 0u && reupload_fail == 0u && row->worst_N <= row->f_max_N;
    snprintf(
        row->note, sizeof row->note,
        "%u power-loss points (every erase/program of the upload): old kept %u, new complete %u, "
        "corrupt %u; re-upload ok %u/%u",
        (unsigned)n_ops, (unsigned)kept_old, (unsigned)got_new, (unsigned)bad,
        (unsigned)(n_ops - reupload_fail), (unsigned)n_ops);
}

int fault_run_one(const fscen_t *fs, uint64_t seed, bool seed_set, frow_t *row, char *err,
                  size_t errn)
{
    memset(row, 0, sizeof(*row));
    snprintf(row->name, sizeof row->name, "%s", fs->name);
    snprintf(row->kind, sizeof row->kind, "%s", fs->kind);
    snprintf(row->description, sizeof row->description, "%s", fs->description);
    snprintf(row->bound_text, sizeof row->bound_text, "%s", fs->bound_text);
    row->expect_code = fs->expect_code;
    row->detect_bound_ms = fs->detect_bound_ms;
    row->emcy_delay_ms = -1.0;
    row->detect_ms = -1.0;
    row->zero_ms = -1.0;
    static sim_scenario_t sc;
    char path[SIM_PATH_MAX];
    char serr[SIM_ERR_MAX];
    fscen_join(path, fs->dir, fs->plant);
    sim_scenario_defaults(&sc);
    if (sim_scenario_load(&sc, path, serr) != 0) {
        snprintf(err, errn, "%.120s: %.900s", fs->file, serr);
        return -1;
    }
    if (seed_set) {
        sc.seed = seed;
    }
    if (fs->plant_model[0] != '\0') {
        sc.plant = strcmp(fs->plant_model, "realistic") == 0 ? SIM_PLANT_REALISTIC
                                                             : SIM_PLANT_IDEAL;
    }
    struct {
        const char *rel;
        uint8_t *buf;
        uint32_t *len;
    } imgs[] = {{fs->skill, g_img, &g_img_len},
                {fs->neighbour, g_nb, &g_nb_len},
                {fs->new_skill, g_new, &g_new_len}};
    for (size_t i = 0; i < 3u; i++) {
        *imgs[i].len = 0u;
        if (imgs[i].rel[0] == '\0') {
            continue;
        }
        fscen_join(path, fs->dir, imgs[i].rel);
        if (rig_read_file(path, imgs[i].buf, IMG_MAX, imgs[i].len) != 0) {
            snprintf(err, errn, "%s: cannot read skill %s", fs->file, path);
            return -1;
        }
    }
    if (fs->force_max_N > 0.0) {
        sc.force_max_N = fs->force_max_N;
    }
    if (strcmp(fs->kind, "power_loss_upload") == 0) {
        run_power_loss(&sc, row);
    } else {
        run_fault(fs, &sc, row);
    }
    return 0;
}

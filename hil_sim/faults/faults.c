/* hil_sim faults (see faults.h). Fault scenario files: a flat key = value subset of TOML
 * (# comments, numbers, "strings"); keys in FAULT_USAGE / docs/safety.md. */
#define _GNU_SOURCE
#include "faults.h"

#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "fault_rig.h"
#include "fls_ram.h"
#include "hal_host.h"

#ifndef HIL_SIM_FAULTS_DIR
#define HIL_SIM_FAULTS_DIR "hil_sim/scenarios/faults"
#endif

#define MAX_SCEN 24
#define IMG_MAX 8192u
#define HOLD_MS 1000u     /* latched and zero for this long after detection */
#define ZERO_BOUND_MS 50u /* force at zero within 50 ms of detection (docs/safety.md) */

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

typedef struct {
    char file[SIM_PATH_MAX];
    char dir[SIM_PATH_MAX];
    char name[64];
    char description[256];
    char plant[SIM_PATH_MAX];
    char skill[SIM_PATH_MAX];
    char neighbour[SIM_PATH_MAX];
    char new_skill[SIM_PATH_MAX];
    char kind[32];
    char bound_text[64];
    char plant_model[16]; /* "" = the plant file's; "ideal" / "realistic" */
    double goal_scale, time_scale, at_s, value, duration_s;
    int expect_code;
    double detect_bound_ms;
} fscen_t;

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

/* ---------------------------------------------------------------- scenario files */

static int read_file(const char *path, uint8_t *buf, uint32_t cap, uint32_t *len)
{
    FILE *f = fopen(path, "rb");
    if (f == NULL) {
        return -1;
    }
    const size_t n = fread(buf, 1, cap, f);
    const int bad = ferror(f) || !feof(f);
    fclose(f);
    *len = (uint32_t)n;
    return bad ? -1 : 0;
}

static void join(char *out, const char *dir, const char *rel)
{
    if (rel[0] == '/') {
        snprintf(out, SIM_PATH_MAX, "%s", rel);
    } else {
        snprintf(out, SIM_PATH_MAX, "%.*s/%.*s", 200, dir, 300, rel);
    }
}

static char *trim(char *s)
{
    while (*s == ' ' || *s == '\t') {
        s++;
    }
    char *e = s + strlen(s);
    while (e > s && (e[-1] == ' ' || e[-1] == '\t' || e[-1] == '\r' || e[-1] == '\n')) {
        *--e = '\0';
    }
    return s;
}

static int fscen_load(fscen_t *s, const char *path, char *err, size_t errn)
{
    memset(s, 0, sizeof(*s));
    snprintf(s->file, sizeof s->file, "%s", path);
    snprintf(s->dir, sizeof s->dir, "%s", path);
    char *slash = strrchr(s->dir, '/');
    if (slash != NULL) {
        *slash = '\0';
    } else {
        snprintf(s->dir, sizeof s->dir, ".");
    }
    s->goal_scale = 1.0;
    s->time_scale = 1.0;
    s->duration_s = 0.001;
    s->detect_bound_ms = 1.0;
    FILE *f = fopen(path, "r");
    if (f == NULL) {
        snprintf(err, errn, "%s: %s", path, strerror(errno));
        return -1;
    }
    char line[512];
    int ln = 0;
    while (fgets(line, sizeof line, f) != NULL) {
        ln++;
        char *p = line;
        bool in_str = false;
        for (char *q = p; *q != '\0'; q++) { /* strip a comment outside strings */
            if (*q == '"') {
                in_str = !in_str;
            } else if (*q == '#' && !in_str) {
                *q = '\0';
                break;
            }
        }
        p = trim(p);
        if (*p == '\0') {
            continue;
        }
        char *eq = strchr(p, '=');
        if (eq == NULL) {
            snprintf(err, errn, "%s:%d: expected key = value", path, ln);
            fclose(f);
            return -1;
        }
        *eq = '\0';
        char *key = trim(p);
        char *val = trim(eq + 1);
        char *str = NULL;
        double num = 0.0;
        const size_t vl = strlen(val);
        if (vl >= 2u && val[0] == '"' && val[vl - 1u] == '"') {
            val[vl - 1u] = '\0';
            str = val + 1;
        } else {
            char *end = NULL;
            num = strtod(val, &end);
            if (end == val || *end != '\0' || !isfinite(num)) {
                snprintf(err, errn, "%s:%d: %s needs a number or a \"string\"", path, ln, key);
                fclose(f);
                return -1;
            }
        }
        struct {
            const char *k;
            char *dst;
            size_t n;
        } strs[] = {{"name", s->name, sizeof s->name},
                    {"description", s->description, sizeof s->description},
                    {"plant", s->plant, sizeof s->plant},
                    {"skill", s->skill, sizeof s->skill},
                    {"neighbour_skill", s->neighbour, sizeof s->neighbour},
                    {"new_skill", s->new_skill, sizeof s->new_skill},
                    {"kind", s->kind, sizeof s->kind},
                    {"bound_text", s->bound_text, sizeof s->bound_text},
                    {"plant_model", s->plant_model, sizeof s->plant_model}};
        struct {
            const char *k;
            double *dst;
        } nums[] = {{"goal_scale", &s->goal_scale},
                    {"time_scale", &s->time_scale},
                    {"at_s", &s->at_s},
                    {"value", &s->value},
                    {"duration_s", &s->duration_s},
                    {"detect_bound_ms", &s->detect_bound_ms}};
        bool done = false;
        for (size_t i = 0; i < sizeof strs / sizeof strs[0] && !done; i++) {
            if (strcmp(key, strs[i].k) == 0) {
                if (str == NULL) {
                    snprintf(err, errn, "%s:%d: %s needs a \"string\"", path, ln, key);
                    fclose(f);
                    return -1;
                }
                snprintf(strs[i].dst, strs[i].n, "%s", str);
                done = true;
            }
        }
        for (size_t i = 0; i < sizeof nums / sizeof nums[0] && !done; i++) {
            if (strcmp(key, nums[i].k) == 0) {
                if (str != NULL) {
                    snprintf(err, errn, "%s:%d: %s needs a number", path, ln, key);
                    fclose(f);
                    return -1;
                }
                *nums[i].dst = num;
                done = true;
            }
        }
        if (!done && strcmp(key, "expect_code") == 0 && str == NULL) {
            s->expect_code = (int)num;
            done = true;
        }
        if (!done) {
            snprintf(err, errn, "%s:%d: unknown key '%s'", path, ln, key);
            fclose(f);
            return -1;
        }
    }
    fclose(f);
    static const char *const kinds[] = {"host_silence", "host_corrupt",        "bus_off",
                                        "force_spike",  "force_nan",           "force_stuck",
                                        "encoder_jump", "actuator_saturation", "host_loss",
                                        "force_limit",  "tick_overrun",        "power_loss_upload"};
    bool ok = false;
    for (size_t i = 0; i < sizeof kinds / sizeof kinds[0]; i++) {
        ok = ok || strcmp(s->kind, kinds[i]) == 0;
    }
    if (!ok || s->name[0] == '\0' || s->plant[0] == '\0' || s->skill[0] == '\0' ||
        s->neighbour[0] == '\0') {
        snprintf(err, errn, "%s: needs name, plant, skill, neighbour_skill and a known kind", path);
        return -1;
    }
    if (s->plant_model[0] != '\0' && strcmp(s->plant_model, "ideal") != 0 &&
        strcmp(s->plant_model, "realistic") != 0) {
        snprintf(err, errn, "%s: plant_model must be \"ideal\" or \"realistic\"", path);
        return -1;
    }
    if (strcmp(s->kind, "power_loss_upload") == 0 && s->new_skill[0] == '\0') {
        snprintf(err, errn, "%s: power_loss_upload needs new_skill", path);
        return -1;
    }
    return 0;
}

/* ---------------------------------------------------------------- running */

static rig_t g_rig;   /* large: static */
static FILE *g_trace; /* --trace: one CSV line per tick of the fault runs */

static void trace_tick(const rig_t *r)
{
    if (g_trace != NULL) {
        const sim_sample_t *m = &r->ring[(r->n_tick - 1u) % SIM_COUPLE_RING];
        fprintf(g_trace, "%llu,%d,%u,%.6f,%.6f,%d,%.6f,%.6f,%.6f,%.6f,%.6f\n",
                (unsigned long long)(r->n_tick - 1u), (int)r->app.state,
                (unsigned)r->app.saf_out.fault_code, r->cmd_N[0], r->cmd_N[1],
                r->act_enable ? 1 : 0, r->ax[0].pos_m, r->ax[0].vel_mps, r->ax[0].contact_N, m->x_m,
                m->contact_N);
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
    return r->app.state == APP_IDLE && r->app.slot_valid[0] && r->app.slot_valid[1] ? 0 : -1;
}

static void run_fault(const fscen_t *fs, const sim_scenario_t *sc, frow_t *row)
{
    rig_t *r = &g_rig;
    if (setup_device(r, sc) != 0) {
        snprintf(row->note, sizeof row->note, "device did not come up with both slots");
        return;
    }
    const uint32_t crc_before = rig_flash_crc();
    const bool hostile = strcmp(fs->kind, "force_limit") == 0;
    rig_command(r, APP_CMD_EXECUTE, 1u, fs->goal_scale, fs->time_scale, 0u);
    const uint64_t t_exec = r->n_tick;
    const uint64_t t_inj = t_exec + (uint64_t)llround(fs->at_s * 1000.0);
    const uint64_t dur = (uint64_t)llround(fs->duration_s * 1000.0) > 0u
                             ? (uint64_t)llround(fs->duration_s * 1000.0)
                             : 1u;
    const double contact_max = (double)r->cfg.saf.lim.axis[0].contact_force_max_N;
    uint64_t onset = UINT64_MAX, det = UINT64_MAX, zero = UINT64_MAX;
    double prev[2] = {0.0, 0.0};
    bool injected = false, monotone = true, hold_ok = true, was_exec = false;
    uint64_t end = t_inj + 20000u; /* bounded: the run ends HOLD_MS after detection */
    const bool expect_none = fs->expect_code == 0;
    if (expect_none) {
        end = t_inj + (uint64_t)llround(fs->duration_s * 1000.0) + 200u;
    }
    while (r->n_tick < end) {
        const uint64_t t = r->n_tick;
        if (t == t_inj) {
            row->force_at_onset_N = cmd_abs_max(r);
            was_exec = r->app.state == APP_EXECUTE; /* the skill runs when the fault comes */
            injected = true;
            if (strcmp(fs->kind, "host_silence") == 0) {
                r->heartbeat_on = false;
                onset = r->last_host_tick;
            } else if (strcmp(fs->kind, "host_corrupt") == 0) {
                r->inj.corrupt_host = true;
                onset = r->last_host_tick;
            } else if (strcmp(fs->kind, "bus_off") == 0) {
                hal_sim_can_set_bus_off(true);
                onset = t;
            } else if (strcmp(fs->kind, "force_spike") == 0) {
                r->inj.force_add_N = fs->value;
                onset = t;
            } else if (strcmp(fs->kind, "force_nan") == 0) {
                r->inj.force_nan = true;
                onset = t;
            } else if (strcmp(fs->kind, "force_stuck") == 0) {
                r->inj.force_stuck = true;
                r->inj.stuck_value_N = r->ring[(t - 1u) % SIM_COUPLE_RING].contact_N;
                onset = t;
            } else if (strcmp(fs->kind, "encoder_jump") == 0) {
                r->inj.encoder_add_m = fs->value; /* from now on */
                onset = t;
            } else if (strcmp(fs->kind, "actuator_saturation") == 0) {
                r->inj.act_limit_N = fs->value;
                onset = t;
            } else if (strcmp(fs->kind, "host_loss") == 0) {
                r->inj.drop_p = fs->value;
                onset = t;
            } else if (strcmp(fs->kind, "tick_overrun") == 0) {
                r->inj.stall_ticks = (uint32_t)fs->value;
                onset = t;
            }
        }
        if (injected && t == t_inj + dur) { /* the cause goes away (not encoder/silence) */
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
        rig_step(r);
        trace_tick(r);
        if (t == t_inj && t_inj == t_exec) {
            was_exec = r->app.state == APP_EXECUTE; /* at_s = 0: started by this tick's command */
        }
        /* the hostile goal scale: the onset is the first contact-force sample above the limit */
        if (hostile && onset == UINT64_MAX &&
            r->ring[t % SIM_COUPLE_RING].contact_N > contact_max) {
            onset = t;
            row->force_at_onset_N = cmd_abs_max(r);
        }
        const double fa = cmd_abs_max(r);
        if (fa > row->worst_N || isnan(fa)) {
            row->worst_N = isnan(fa) ? (double)INFINITY : fa;
        }
        if (det == UINT64_MAX && r->app.saf_out.fault_code != 0u) {
            det = t;
            row->code = r->app.saf_out.fault_code;
            if (expect_none) {
                break;
            }
            end = det + HOLD_MS;
            if (strcmp(fs->kind, "host_silence") == 0) {
                r->heartbeat_on = true; /* the host comes back: no resume all the same */
            }
        }
        if (det != UINT64_MAX) {
            for (int a = 0; a < 2; a++) {
                if (absd(r->cmd_N[a]) > absd(prev[a]) && t > det) {
                    monotone = false;
                }
            }
            if (zero == UINT64_MAX && r->cmd_N[0] == 0.0 && r->cmd_N[1] == 0.0) {
                zero = t;
            }
            if (r->app.state != APP_FAULT || (zero != UINT64_MAX && (fa != 0.0 || r->act_enable))) {
                hold_ok = false;
            }
        }
        prev[0] = r->cmd_N[0];
        prev[1] = r->cmd_N[1];
    }
    row->f_max_N = (double)r->cfg.saf.lim.axis[0].force_max_N;
    row->contact_max_N = r->contact_max_N;
    row->monotone = monotone;
    row->emcy_seen = row->code != 0 && emcy_has(r, (uint16_t)row->code);
    row->emcy_delay_ms = -1.0;
    for (uint32_t i = 0; i < r->n_emcy && det != UINT64_MAX; i++) {
        if (r->emcy[i].code == (uint16_t)row->code) {
            row->emcy_delay_ms = (double)(r->emcy[i].rx_tick - det);
            break;
        }
    }
    row->status_seen = r->status_fault == row->code && row->code != 0;
    const bool lost_flash = rig_flash_crc() != crc_before;
    row->lost = lost_flash || !r->app.slot_valid[0] || !r->app.slot_valid[1];
    if (expect_none) {
        /* no fault may latch: the skill runs to its end within the limits */
        row->latched = false;
        row->cleared = true;
        row->detect_ms = -1.0;
        row->zero_ms = -1.0;
        row->pass = was_exec && det == UINT64_MAX && row->worst_N <= row->f_max_N && !row->lost;
        snprintf(row->note, sizeof row->note, "%s; %u host frames lost",
                 det == UINT64_MAX ? "no fault latched (none expected)" : "unexpected fault",
                 (unsigned)r->host_dropped);
        return;
    }
    if (det == UINT64_MAX || onset == UINT64_MAX) {
        snprintf(row->note, sizeof row->note, "not detected (onset %s)",
                 onset == UINT64_MAX ? "never" : "seen");
        return;
    }
    row->detect_ms = (double)(det - onset);
    row->zero_ms = zero == UINT64_MAX ? -1.0 : (double)(zero - det);
    row->latched = hold_ok && zero != UINT64_MAX && r->n_tick >= det + HOLD_MS;

    /* the cause is gone: a clear is accepted and the skill does not resume */
    r->heartbeat_on = true;
    rig_command(r, APP_CMD_CLEAR_FAULT, 0u, 0.0, 0.0, 0u);
    bool stayed_zero = true;
    for (int i = 0; i < 100; i++) {
        rig_step(r);
        stayed_zero = stayed_zero && cmd_abs_max(r) == 0.0;
    }
    row->cleared = r->app.state == APP_IDLE && stayed_zero;
    if (!row->status_seen) {
        row->status_seen = r->status_fault == row->code; /* bus-off: status after recovery */
    }
    row->pass = was_exec && row->code == fs->expect_code && row->detect_ms <= fs->detect_bound_ms &&
                row->zero_ms >= 0.0 && row->zero_ms <= (double)ZERO_BOUND_MS &&
                row->worst_N <= row->f_max_N && row->monotone && row->latched && row->cleared &&
                !row->lost && row->emcy_seen;
    snprintf(row->note, sizeof row->note, "%s%s%s", was_exec ? "" : "not executing at injection; ",
             !row->emcy_seen                    ? "no emergency frame"
             : strcmp(fs->kind, "bus_off") == 0 ? "emergency frame after bus recovery"
                                                : "emergency frame",
             row->status_seen ? ", status frame" : "");
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
        ok = ok && r->app.slot_valid[0] && r->app.slot_valid[1] && (is_old || is_new);
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

static int run_one(const fscen_t *fs, uint64_t seed, bool seed_set, frow_t *row, char *err,
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
    join(path, fs->dir, fs->plant);
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
        join(path, fs->dir, imgs[i].rel);
        if (read_file(path, imgs[i].buf, IMG_MAX, imgs[i].len) != 0) {
            snprintf(err, errn, "%s: cannot read skill %s", fs->file, path);
            return -1;
        }
    }
    if (strcmp(fs->kind, "power_loss_upload") == 0) {
        run_power_loss(&sc, row);
    } else {
        run_fault(fs, &sc, row);
    }
    return 0;
}

/* ---------------------------------------------------------------- output */

static void fmt_ms(char *out, size_t n, double v)
{
    if (v < 0.0) {
        snprintf(out, n, "-");
    } else {
        snprintf(out, n, "%.0f", v);
    }
}

static void write_table(FILE *f, const frow_t *rows, int n, uint64_t seed)
{
    int passed = 0;
    fprintf(f,
            "| fault | injection | code | detection (ms) | bound (ms) | time to zero force (ms) | "
            "force at onset (N) | worst force (N) | F_max (N) | worst contact force (N) | latched "
            "1 s, no resume | clear after cause gone | lost | pass |\n");
    fprintf(f, "|---|---|---:|---:|---|---:|---:|---:|---:|---:|---|---|---|---|\n");
    for (int i = 0; i < n; i++) {
        const frow_t *r = &rows[i];
        char d[16], z[16], code[16];
        fmt_ms(d, sizeof d, r->detect_ms);
        fmt_ms(z, sizeof z, r->zero_ms);
        if (r->code != 0) {
            snprintf(code, sizeof code, "%d", r->code);
        } else {
            snprintf(code, sizeof code, "none");
        }
        const bool storage = strcmp(r->kind, "power_loss_upload") == 0;
        const bool none = r->expect_code == 0;
        fprintf(
            f, "| %s | %s | %s | %s | %s | %s | %.1f | %.1f | %.0f | %.1f | %s | %s | %s | %s |\n",
            r->name, r->description, storage ? "-" : code, d,
            (storage || none) ? "-" : r->bound_text, z, r->force_at_onset_N, r->worst_N, r->f_max_N,
            r->contact_max_N, (storage || none) ? "n/a" : (r->latched ? "yes" : "NO"),
            (storage || none) ? "n/a" : (r->cleared ? "yes" : "NO"), r->lost ? "YES" : "no",
            r->pass ? "pass" : "FAIL");
        passed += r->pass ? 1 : 0;
    }
    fprintf(f, "\n%d/%d fault scenarios pass (seed %llu).\n", passed, n, (unsigned long long)seed);
    for (int i = 0; i < n; i++) {
        fprintf(f, "- %s: %s\n", rows[i].name, rows[i].note);
    }
}

static void json_str(FILE *f, const char *s)
{
    fputc('"', f);
    for (; *s != '\0'; s++) {
        if (*s == '"' || *s == '\\') {
            fputc('\\', f);
        }
        fputc(*s, f);
    }
    fputc('"', f);
}

static void write_json(FILE *f, const frow_t *rows, int n, uint64_t seed)
{
    fprintf(f, "{\"seed\": %llu, \"hold_ms\": %u, \"zero_bound_ms\": %u, \"rows\": [\n",
            (unsigned long long)seed, HOLD_MS, ZERO_BOUND_MS);
    for (int i = 0; i < n; i++) {
        const frow_t *r = &rows[i];
        fprintf(f, "  {\"name\": ");
        json_str(f, r->name);
        fprintf(f, ", \"kind\": ");
        json_str(f, r->kind);
        fprintf(
            f,
            ", \"expect_code\": %d, \"code\": %d, \"detect_ms\": %.3f, \"detect_bound_ms\": %.3f, "
            "\"zero_ms\": %.3f, \"force_at_onset_N\": %.6f, \"worst_force_N\": %.6f, \"f_max_N\": "
            "%.3f, "
            "\"contact_max_N\": %.6f, \"emcy_delay_ms\": %.3f, "
            "\"monotone\": %s, \"latched\": %s, \"cleared\": %s, \"emcy_seen\": %s, "
            "\"status_seen\": %s, \"lost\": %s, \"pass\": %s, \"note\": ",
            r->expect_code, r->code, r->detect_ms, r->detect_bound_ms, r->zero_ms,
            r->force_at_onset_N, r->worst_N, r->f_max_N, r->contact_max_N, r->emcy_delay_ms,
            r->monotone ? "true" : "false", r->latched ? "true" : "false",
            r->cleared ? "true" : "false", r->emcy_seen ? "true" : "false",
            r->status_seen ? "true" : "false", r->lost ? "true" : "false",
            r->pass ? "true" : "false");
        json_str(f, r->note);
        fprintf(f, "}%s\n", i + 1 < n ? "," : "");
    }
    fprintf(f, "]}\n");
}

static int name_cmp(const void *a, const void *b)
{
    return strcmp(*(const char *const *)a, *(const char *const *)b);
}

int faults_cmd(int argc, char **argv)
{
    const char *dir = HIL_SIM_FAULTS_DIR;
    const char *out_md = NULL, *out_json = NULL, *only = NULL;
    uint64_t seed = 1u;
    bool seed_set = false;
    for (int i = 0; i < argc; i++) {
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
            seed = (uint64_t)s;
            seed_set = true;
        } else if (strcmp(a, "--dir") == 0) {
            dir = v;
        } else if (strcmp(a, "-o") == 0) {
            out_md = v;
        } else if (strcmp(a, "--json") == 0) {
            out_json = v;
        } else if (strcmp(a, "--only") == 0) {
            only = v;
        } else if (strcmp(a, "--trace") == 0) {
            g_trace = fopen(v, "w");
            if (g_trace == NULL) {
                fprintf(stderr, "hil_sim faults: %s: %s\n", v, strerror(errno));
                return 2;
            }
            fprintf(g_trace, "tick,state,fault,cmd_x_N,cmd_y_N,enable,x_m,v_mps,contact_N,x_meas_m,"
                             "contact_meas_N\n");
        } else {
            fprintf(stderr, "hil_sim faults: unknown option '%s'\n%s", a, FAULT_USAGE);
            return 2;
        }
        i++;
    }
    DIR *d = opendir(dir);
    if (d == NULL) {
        fprintf(stderr, "hil_sim faults: %s: %s\n", dir, strerror(errno));
        return 2;
    }
    static char names[MAX_SCEN][256];
    const char *sorted[MAX_SCEN] = {NULL};
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
    static frow_t rows[MAX_SCEN];
    int nr = 0;
    char err[SIM_ERR_MAX + SIM_PATH_MAX];
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    for (int i = 0; i < n; i++) {
        static fscen_t fs;
        char path[SIM_PATH_MAX];
        join(path, dir, sorted[i]);
        if (fscen_load(&fs, path, err, sizeof err) != 0) {
            fprintf(stderr, "hil_sim faults: %s\n", err);
            return 2;
        }
        if (only != NULL && strcmp(only, fs.name) != 0) {
            continue;
        }
        if (run_one(&fs, seed, seed_set, &rows[nr], err, sizeof err) != 0) {
            fprintf(stderr, "hil_sim faults: %s\n", err);
            return 2;
        }
        nr++;
    }
    clock_gettime(CLOCK_MONOTONIC, &t1);
    if (g_trace != NULL) {
        fclose(g_trace);
        g_trace = NULL;
    }
    if (nr == 0) {
        fprintf(stderr, "hil_sim faults: no scenario in %s\n", dir);
        return 2;
    }
    write_table(stdout, rows, nr, seed);
    printf("wall time %.2f s\n",
           (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec));
    if (out_md != NULL) {
        FILE *f = fopen(out_md, "w");
        if (f == NULL) {
            fprintf(stderr, "hil_sim faults: %s: %s\n", out_md, strerror(errno));
            return 2;
        }
        write_table(f, rows, nr, seed);
        fclose(f);
    }
    if (out_json != NULL) {
        FILE *f = fopen(out_json, "w");
        if (f == NULL) {
            fprintf(stderr, "hil_sim faults: %s: %s\n", out_json, strerror(errno));
            return 2;
        }
        write_json(f, rows, nr, seed);
        fclose(f);
    }
    for (int i = 0; i < nr; i++) {
        if (!rows[i].pass) {
            return 1;
        }
    }
    return 0;
}

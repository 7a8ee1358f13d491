/* `hil_sim powercut`: a power cut just after every flash operation of (a) a skill download into
 * slot 1 (RequestDownload to the commit's answer), (b) a firmware update (RequestDownload to
 * the new image confirmed after its test boot) and (c) the wrong key that locks SecurityAccess
 * out (its record's write), one run per operation; see fault_powercut.h. */
#include "fault_powercut.h"

#include <stdio.h>
#include <string.h>

#include "boot.h"
#include "fault_rig.h"
#include "fls_ram.h"
#include "fs_uds_ids.h"
#include "hal_host.h"
#include "nvm.h"
#include "sec_access.h"
#include "skill.h"
#include "uds.h"

#define PC_IMG_MAX 65536u
#define PC_SETTLE_MS 300u /* after the power comes back: boot, self-test, confirmation */

/* The operation a run cuts. */
typedef enum {
    PC_SKILL,     /* a skill download into slot 1 */
    PC_FW,        /* a firmware update 1.0.0 -> 1.1.0 */
    PC_WRONG_KEY, /* the wrong key that locks SecurityAccess out (the third after two) */
    PC_CASES
} pc_case_t;

static rig_t g_rig; /* large: static */
static uint8_t g_old[PC_IMG_MAX], g_new[PC_IMG_MAX], g_nb[PC_IMG_MAX], g_rd[PC_IMG_MAX];
static uint32_t g_old_len, g_new_len, g_nb_len;
static uint8_t g_fw[2][8192];
static uint32_t g_fw_len[2];
static boot_image_header_t g_fw_hdr[2];

/* The outcome of one cut point. */
typedef struct {
    uint8_t region, kind; /* the operation just before the cut (hal_host_flash_op_t) */
    uint8_t result;       /* 0 old, 1 new, 2 bad */
    char why[96];         /* a bad result's first failed check */
} pc_point_t;

static pc_point_t g_pts[HAL_HOST_FLASH_LOG];
static uint8_t g_clean_region[HAL_HOST_FLASH_LOG]; /* region of each operation, uncut run */
static bool g_torn;        /* --torn: operation i itself is torn (fls_ram), not completed */
static uint32_t g_key_ops; /* uncut run: the flash operations done when the key was answered */
static bool
    g_key_answered; /* this run's cut came after the key's answer (sent before the power went) */


/* FNV-1a of a whole flash device. */
static uint32_t dev_hash(const fls_dev_t *d, uint32_t from, uint32_t len)
{
    uint8_t buf[256];
    uint32_t h = 2166136261u;
    for (uint32_t pos = from; pos < from + len; pos += (uint32_t)sizeof buf) {
        const uint32_t n = from + len - pos < sizeof buf ? from + len - pos : (uint32_t)sizeof buf;
        if (d->read(d->ctx, pos, buf, n) != 0) {
            return 0u;
        }
        for (uint32_t i = 0; i < n; i++) {
            h = (h ^ buf[i]) * 16777619u;
        }
    }
    return h;
}

static uint32_t whole(const fls_dev_t *d)
{
    return dev_hash(d, 0u, d->sector_size * d->sector_count);
}

/* The firmware update (level 3 unlocked): the image into the inactive slot, mark it for a test
 * boot, ECUReset, then the test boot's self-test confirms it. 0 when the UDS steps were answered. */
static int fw_update(rig_t *r, unsigned which)
{
    if (rig_uds_download_to(r, FWU_DOWNLOAD_ADDRESS, g_fw[which], g_fw_len[which]) != 0u) {
        return -2;
    }
    uint8_t resp[16];
    const uint8_t mark[5] = {UDS_SID_ROUTINE, 0x01u, 0x0Fu, 0x01u, 0x00u};
    if (rig_uds(r, mark, 5u, resp, sizeof resp, 2000u) < 4u || resp[0] != 0x71u) {
        return -3;
    }
    const uint8_t reset[2] = {UDS_SID_ECU_RESET, 0x01u};
    (void)rig_uds(r, reset, 2u, resp, sizeof resp, 500u);
    rig_run(r, PC_SETTLE_MS);
    return 0;
}

/* A device with skills in slots 1 and 2 and firmware 1.0.0 installed and confirmed. */
static int setup(rig_t *r, const sim_scenario_t *sc)
{
    rig_init(r, sc);
    hal_host_fw_flash_erase();
    if (rig_flash_skill(r, 0u, g_old, g_old_len) != 0 || rig_flash_skill(r, 1u, g_nb, g_nb_len)) {
        return -1;
    }
    rig_boot(r);
    r->heartbeat_on = true;
    rig_run(r, 200u);
    if (rig_uds_unlock_level(r, UDS_SEC_LEVEL_FIRMWARE) != 0 || fw_update(r, 0u) != 0 ||
        app_boot(r->app)->running_slot == BOOT_SLOT_NONE ||
        app_boot(r->app)->running.fw_version != g_fw_hdr[0].fw_version ||
        !app_boot(r->app)->state.confirmed) {
        return -2;
    }
    return app_state(r->app) == APP_IDLE && (app_slot_skill(r->app, 1u) != NULL) &&
                   (app_slot_skill(r->app, 2u) != NULL)
               ? 0
               : -3;
}

/* What must not change in a run: the regions it does not write, and the old image's slot. */
typedef struct {
    uint32_t slots, fw, sec, old_slot; /* hashes */
    uint8_t old_index;                 /* the slot of firmware 1.0.0 */
} pc_keep_t;

/* The wrong-key record on the SecurityAccess flash, read through a fresh storage scan: 0 with
 * failed/locked_out decoded, -1 when there is none or it does not decode. */
static int sec_record_read(uint8_t *failed, uint8_t *locked_out)
{
    nvm_t n;
    uint8_t rec[SEC_RECORD_LEN];
    uint32_t len = 0u;
    if (nvm_init(&n, hal_sec_flash()) != NVM_OK ||
        nvm_read(&n, 0u, rec, (uint32_t)sizeof rec, &len) != NVM_OK) {
        return -1;
    }
    return sec_record_decode(rec, len, failed, locked_out) ? 0 : -1;
}

/* A seed request then a wrong key at level 1, waiting out the delay of the key before; returns
 * the key's answer (the NRC: 0x35 wrong, 0x36 the attempt that locks out), 0 if none. */
static uint8_t wrong_key(rig_t *r)
{
    uint8_t resp[64];
    const uint16_t n = rig_uds_seed(r, UDS_SEC_LEVEL_WRITE, resp, sizeof resp);
    if (n != 2u + SEC_SEED_LEN || resp[0] != 0x67u) {
        return 0u;
    }
    uint8_t sk[2u + SEC_KEY_LEN];
    memset(sk, 0xA5, sizeof sk);
    sk[0] = UDS_SID_SECURITY;
    sk[1] = (uint8_t)(UDS_SEC_LEVEL_WRITE + 1u);
    const uint16_t k = rig_uds(r, sk, (uint16_t)sizeof sk, resp, sizeof resp, 200u);
    return (k == 3u && resp[0] == UDS_NEGATIVE_RESPONSE) ? resp[2] : 0u;
}

/* Two wrong keys (the record then says 2 failed), in the programming session. 0 ok. */
static int two_wrong_keys(rig_t *r)
{
    uint8_t resp[16];
    const uint8_t dsc[2] = {UDS_SID_DSC, UDS_SESSION_PROGRAMMING};
    if (rig_uds(r, dsc, 2u, resp, sizeof resp, 200u) < 2u || resp[0] != 0x50u) {
        return -1;
    }
    uint8_t failed = 0u, locked = 0u;
    if (wrong_key(r) != UDS_NRC_INVALID_KEY || wrong_key(r) != UDS_NRC_INVALID_KEY ||
        sec_record_read(&failed, &locked) != 0 || failed != 2u || locked != 0u) {
        return -2;
    }
    return 0;
}

static void keep_take(const rig_t *r, pc_keep_t *k)
{
    const boot_config_t *bc = app_boot_config(r->app);
    k->slots = whole(hal_flash());
    k->fw = whole(hal_fw_flash());
    k->sec = whole(hal_sec_flash());
    k->old_index = app_boot(r->app)->running_slot;
    k->old_slot = dev_hash(bc->app_dev, bc->slot_addr[k->old_index], bc->slot_size);
}

static bool fail(pc_point_t *p, const char *why)
{
    p->result = 2u;
    snprintf(p->why, sizeof p->why, "%s", why);
    return false;
}

/* After a cut during a skill download: slot 1 holds the old or the new image, complete (its
 * parse and CRC: slot_valid, the stored bytes), slot 2 its own, the firmware and the
 * SecurityAccess record as they were. */
static bool check_skill(rig_t *r, const pc_keep_t *k, pc_point_t *p)
{
    uint32_t len = 0u;
    if (rig_read_slot(0u, g_rd, PC_IMG_MAX, &len) != 0 || !(app_slot_skill(r->app, 1u) != NULL)) {
        return fail(p, "slot 1 unreadable or invalid");
    }
    const bool is_old = len == g_old_len && memcmp(g_rd, g_old, len) == 0;
    const bool is_new = len == g_new_len && memcmp(g_rd, g_new, len) == 0;
    if (!is_old && !is_new) {
        return fail(p, "slot 1 neither the old nor the new image");
    }
    if (app_slot_crc(r->app, 1u) != skill_crc32(0u, g_rd, len - SKILL_CRC_SIZE)) {
        return fail(p, "slot 1 CRC");
    }
    if (rig_read_slot(1u, g_rd, PC_IMG_MAX, &len) != 0 || !(app_slot_skill(r->app, 2u) != NULL) ||
        len != g_nb_len || memcmp(g_rd, g_nb, len) != 0) {
        return fail(p, "slot 2 changed");
    }
    if (whole(hal_fw_flash()) != k->fw || whole(hal_sec_flash()) != k->sec) {
        return fail(p, "firmware region or SecurityAccess record changed");
    }
    p->result = is_new ? 1u : 0u;
    return true;
}

/* After a cut during a firmware update: the running image is 1.0.0 or 1.1.0, verified (hash and
 * tag), confirmed after the settle time (a test boot of 1.1.0 confirms itself), at most one test
 * boot recorded; slot of 1.0.0 untouched unless 1.1.0 runs confirmed from the other slot; skills
 * and the SecurityAccess record as they were. */
static bool check_fw(rig_t *r, const pc_keep_t *k, pc_point_t *p)
{
    const boot_t *b = app_boot(r->app);
    boot_image_header_t h;
    if (b->running_slot == BOOT_SLOT_NONE) {
        return fail(p, "nothing boots");
    }
    if (boot_slot_verify(app_boot_config(r->app), b->running_slot, &h) != BOOT_OK) {
        return fail(p, "the running image does not verify");
    }
    const bool is_old = h.fw_version == g_fw_hdr[0].fw_version;
    const bool is_new = h.fw_version == g_fw_hdr[1].fw_version;
    if (!is_old && !is_new) {
        return fail(p, "the running image is neither version");
    }
    if (!b->state.confirmed || b->state.test_attempts > 1u ||
        b->state.active_slot != b->running_slot) {
        return fail(p, "boot state: not confirmed, or more than one test boot");
    }
    const boot_config_t *bc = app_boot_config(r->app);
    if (dev_hash(bc->app_dev, bc->slot_addr[k->old_index], bc->slot_size) != k->old_slot) {
        return fail(p, "the slot of 1.0.0 changed");
    }
    if (whole(hal_flash()) != k->slots || whole(hal_sec_flash()) != k->sec) {
        return fail(p, "skills or SecurityAccess record changed");
    }
    if (!(app_slot_skill(r->app, 1u) != NULL) || !(app_slot_skill(r->app, 2u) != NULL)) {
        return fail(p, "a skill slot lost");
    }
    p->result = is_new ? 1u : 0u;
    return true;
}

/* After a cut during the wrong key that locks out: the record holds the two wrong keys before
 * (old, only where the key had not been answered yet) or the third counted or the lockout (new),
 * never fewer, and the device acts on it: once the power-up delay
 * is over, a seed request gets a seed (old) or 0x37 (new, the lockout restarted at power-up);
 * skills and firmware as they were. */
static bool check_wrong_key(rig_t *r, const pc_keep_t *k, pc_point_t *p)
{
    uint8_t failed = 0u, locked = 0u;
    if (sec_record_read(&failed, &locked) != 0) {
        return fail(p, "the wrong-key record does not read");
    }
    const bool is_old = failed == 2u && locked == 0u;
    const bool is_new = locked != 0u || failed >= 3u; /* counted: before its lockout is written */
    if (!is_old && !is_new) {
        return fail(p, "the wrong-key record lost a wrong key");
    }
    if (is_old && g_key_answered) {
        return fail(p, "the key was answered before it was counted");
    }
    uint8_t resp[64];
    const uint8_t dsc[2] = {UDS_SID_DSC, UDS_SESSION_PROGRAMMING};
    const uint8_t rs[2] = {UDS_SID_SECURITY, UDS_SEC_LEVEL_WRITE};
    rig_run(r, 1200u); /* the power-up delay (1 s) over */
    if (rig_uds(r, dsc, 2u, resp, sizeof resp, 200u) < 2u || resp[0] != 0x50u) {
        return fail(p, "no programming session after the boot");
    }
    const uint16_t n = rig_uds(r, rs, 2u, resp, sizeof resp, 200u);
    const bool seed = n == 2u + SEC_SEED_LEN && resp[0] == 0x67u;
    const bool delayed = n == 3u && resp[0] == UDS_NEGATIVE_RESPONSE &&
                         resp[2] == UDS_NRC_DELAY_NOT_EXPIRED;
    if (is_old ? !seed : !delayed) {
        return fail(p, is_old ? "no seed after the delay (old record)"
                              : "a seed during the lockout (new record)");
    }
    if (whole(hal_flash()) != k->slots || whole(hal_fw_flash()) != k->fw) {
        return fail(p, "skills or firmware changed");
    }
    p->result = is_new ? 1u : 0u;
    return true;
}

/* The simulated flash of a region (the host port keeps it as the device's ctx). */
static fls_ram_t *region_ram(uint8_t region)
{
    const fls_dev_t *d = region == HAL_HOST_REGION_SLOTS      ? hal_flash()
                         : region == HAL_HOST_REGION_FIRMWARE ? hal_fw_flash()
                                                              : hal_sec_flash();
    return (fls_ram_t *)d->ctx;
}

/* --torn: operation `cut` of the run (1-based, in the uncut run's order) is torn by its region's
 * fls_ram (a program writes half its units, an erase half the sector); the later ones fail. */
static void tear(uint32_t cut)
{
    const uint8_t rg = g_clean_region[cut - 1u];
    uint32_t k = 0u;
    for (uint32_t j = 0; j < cut; j++) {
        k += g_clean_region[j] == rg ? 1u : 0u;
    }
    fls_ram_set_power_loss(region_ram(rg), k);
}

/* One run: a fresh device, the operation (skill download or firmware update) with the power cut
 * just after `cut` flash operations of it (0: never), then the power back on and the device
 * booted again. The operation's flash operations are returned in *ops (uncut run). */
static int run_once(const sim_scenario_t *sc, pc_case_t op, uint32_t cut, uint32_t *ops,
                    pc_point_t *p)
{
    rig_t *r = &g_rig;
    const bool fw = op == PC_FW;
    if (setup(r, sc) != 0) {
        return -1;
    }
    if (op == PC_WRONG_KEY
            ? two_wrong_keys(r) != 0
            : rig_uds_unlock_level(r, fw ? UDS_SEC_LEVEL_FIRMWARE : UDS_SEC_LEVEL_WRITE) != 0) {
        return -1;
    }
    pc_keep_t k;
    keep_take(r, &k);
    const uint32_t ops0 = hal_host_flash_ops();
    if (cut != 0u) {
        hal_host_flash_cut_after(cut);
    }
    if (cut != 0u && g_torn) {
        tear(cut);
    }
    if (op == PC_FW) {
        (void)fw_update(r, 1u);
    } else if (op == PC_SKILL) {
        (void)rig_uds_download(r, 1u, g_new, g_new_len);
        rig_run(r, 5u);
    } else {
        const uint8_t nrc = wrong_key(r);
        if (cut == 0u) {
            g_key_ops = nrc != 0u ? hal_host_flash_ops() - ops0 : UINT32_MAX;
        }
        /* after op `cut` (during it, torn) the power is gone: the answer went out before iff
         * the uncut run had answered after at most that many operations */
        g_key_answered = cut != 0u && (g_torn ? cut > g_key_ops : cut >= g_key_ops);
        rig_run(r, 5u);
    }
    *ops = hal_host_flash_ops() - ops0;
    for (uint32_t i = 0; cut == 0u && i < *ops && i < HAL_HOST_FLASH_LOG; i++) {
        const hal_host_flash_op_t *o = hal_host_flash_op(ops0 + i);
        g_clean_region[i] = o != NULL ? o->region : 0u;
    }
    if (cut != 0u) {
        const hal_host_flash_op_t *o = hal_host_flash_op(ops0 + cut - 1u);
        p->region = o != NULL ? o->region : 0xFFu;
        p->kind = o != NULL ? o->kind : 0xFFu;
    }
    hal_host_flash_power_on();
    for (uint8_t rg = 0; rg < HAL_HOST_FLASH_REGIONS; rg++) {
        fls_ram_power_cycle(region_ram(rg));
    }
    rig_boot(r);
    r->heartbeat_on = true;
    rig_run(r, PC_SETTLE_MS);
    const bool ok = op == PC_FW      ? check_fw(r, &k, p)
                    : op == PC_SKILL ? check_skill(r, &k, p)
                                     : check_wrong_key(r, &k, p);
    return ok ? 0 : 1;
}

static const char *region_name(uint8_t r)
{
    static const char *const names[HAL_HOST_FLASH_REGIONS] = {"skill slots", "firmware",
                                                              "SecurityAccess record"};
    return r < HAL_HOST_FLASH_REGIONS ? names[r] : "?";
}

/* Every cut point of one operation; prints its table, returns the bad outcomes (or -1). */
static const char *const CASE_NAME[PC_CASES] = {"skill download", "firmware update", "wrong key"};
static const char *const CASE_TITLE[PC_CASES] = {"skill download into slot 1",
                                                 "firmware update 1.0.0 -> 1.1.0",
                                                 "the third wrong key (SecurityAccess lockout)"};
static const char *const CASE_END[PC_CASES] = {"RequestDownload to the commit's answer",
                                               "RequestDownload to the new image confirmed",
                                               "SecurityAccess sendKey to its answer"};

static int run_case(FILE *out, const sim_scenario_t *sc, pc_case_t op, bool verbose)
{
    uint32_t n = 0u;
    pc_point_t clean;
    memset(&clean, 0, sizeof clean);
    if (run_once(sc, op, 0u, &n, &clean) != 0 || clean.result != 1u || n == 0u ||
        n > HAL_HOST_FLASH_LOG) {
        fprintf(out, "%s: the uncut run failed (%s)\n", CASE_NAME[op], clean.why);
        return -1;
    }
    uint32_t count[HAL_HOST_FLASH_REGIONS][2][3];
    memset(count, 0, sizeof count);
    int bad = 0;
    for (uint32_t i = 1u; i <= n; i++) {
        pc_point_t *p = &g_pts[i - 1u];
        memset(p, 0, sizeof *p);
        uint32_t ops = 0u;
        if (run_once(sc, op, i, &ops, p) < 0) {
            p->result = 2u;
            snprintf(p->why, sizeof p->why, "set-up failed");
        }
        if (p->region < HAL_HOST_FLASH_REGIONS && p->kind < 2u) {
            count[p->region][p->kind][p->result]++;
        }
        bad += p->result == 2u ? 1 : 0;
        if (verbose || p->result == 2u) {
            fprintf(out, "  cut %s op %u (%s %s): %s %s\n", g_torn ? "during" : "after",
                    (unsigned)i, region_name(p->region), p->kind == 0u ? "erase" : "program",
                    p->result == 0u ? "old" : (p->result == 1u ? "new" : "BAD"), p->why);
        }
    }
    fprintf(out, "\n%s: %u cut points (%s every erase/program from %s)\n", CASE_TITLE[op],
            (unsigned)n, g_torn ? "during" : "just after", CASE_END[op]);
    if (op == PC_WRONG_KEY) {
        fprintf(out, "(the key answered after operation %u: the wrong key counted before it)\n",
                (unsigned)g_key_ops);
    }
    fprintf(out, "\n");
    fprintf(out, "| operation cut %s | cut points | runs old | runs new | bad |\n",
            g_torn ? "during" : "after");
    fprintf(out, "|---|---|---|---|---|\n");
    for (uint8_t rg = 0; rg < HAL_HOST_FLASH_REGIONS; rg++) {
        for (uint8_t kd = 0; kd < 2u; kd++) {
            const uint32_t *c = count[rg][kd];
            if (c[0] + c[1] + c[2] != 0u) {
                fprintf(out, "| %s %s | %u | %u | %u | %u |\n", region_name(rg),
                        kd == 0u ? "erase" : "program", (unsigned)(c[0] + c[1] + c[2]),
                        (unsigned)c[0], (unsigned)c[1], (unsigned)c[2]);
            }
        }
    }
    return bad;
}

static int load_inputs(FILE *err)
{
    static const char *const fw_files[2] = {FS_POWERCUT_VECTORS "/powercut_fw_1.0.0.fwimg",
                                            FS_POWERCUT_VECTORS "/powercut_fw_1.1.0.fwimg"};
    if (rig_read_file(FS_POWERCUT_VECTORS "/press_n50_lwr_hold.skill", g_old, PC_IMG_MAX,
                      &g_old_len) ||
        rig_read_file(FS_POWERCUT_VECTORS "/press_n10_ridge_release.skill", g_new, PC_IMG_MAX,
                      &g_new_len) ||
        rig_read_file(FS_POWERCUT_VECTORS "/engrave_n50_ridge_release.skill", g_nb, PC_IMG_MAX,
                      &g_nb_len)) {
        fprintf(err, "hil_sim powercut: cannot read the skill vectors in %s\n",
                FS_POWERCUT_VECTORS);
        return -1;
    }
    for (unsigned i = 0; i < 2u; i++) {
        if (rig_read_file(fw_files[i], g_fw[i], sizeof g_fw[i], &g_fw_len[i]) != 0 ||
            g_fw_len[i] < BOOT_IMAGE_HEADER_SIZE ||
            boot_image_parse_header(g_fw[i], 0u, &g_fw_hdr[i]) != BOOT_OK) {
            fprintf(err,
                    "hil_sim powercut: cannot read %s (tests/vectors/powercut_fw_generate.py)\n",
                    fw_files[i]);
            return -1;
        }
    }
    return 0;
}

int powercut_cmd(int argc, char **argv)
{
    bool verbose = false;
    for (int i = 0; i < argc; i++) {
        if (strcmp(argv[i], "-v") == 0 || strcmp(argv[i], "--verbose") == 0) {
            verbose = true;
        } else if (strcmp(argv[i], "--torn") == 0) {
            g_torn = true;
        } else {
            const bool help = strcmp(argv[i], "-h") == 0 || strcmp(argv[i], "--help") == 0;
            fprintf(help ? stdout : stderr,
                    "usage: hil_sim powercut [-v] [--torn]\n"
                    "A power cut just after every flash erase/program of a skill download, of "
                    "a firmware\nupdate and of the wrong key that locks SecurityAccess out, one "
                    "run each, then a boot: prints the count of cut "
                    "points and the outcome\ntable; -v one line per cut point. Exit 1 on any bad "
                    "outcome.\n--torn: the power fails during operation i instead (half "
                    "of it written).\n");
            return help ? 0 : 2;
        }
    }
    if (load_inputs(stderr) != 0) {
        return 2;
    }
    static sim_scenario_t sc;
    sim_scenario_defaults(&sc);
    int bad = 0;
    for (int op = 0; op < (int)PC_CASES; op++) {
        const int b = run_case(stdout, &sc, (pc_case_t)op, verbose);
        bad += b < 0 ? 1 : b;
    }
    printf("\nbad outcomes: %d\n", bad);
    return bad == 0 ? 0 : 1;
}

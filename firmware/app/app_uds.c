/* UDS device hooks of the application (see uds.h for the server, docs/protocol.md for the
 * identifiers): data identifiers, routines, SecurityAccess via sec_access, skill download into a
 * slot (validated by skill_parse, written by nvm, the old skill kept on any failure) and upload. */
#include <string.h>

#include "app_internal.h"
#include "fwu_uds.h"

/* Data identifiers (DID_*, fs_uds_ids.h): big-endian values, IEEE-754 float32 for reals. */
#define SLOT_DIR_ENTRY 16u

static void put_u16(uint8_t *p, uint16_t v)
{
    p[0] = (uint8_t)(v >> 8);
    p[1] = (uint8_t)v;
}

static void put_u32(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)(v >> 24);
    p[1] = (uint8_t)(v >> 16);
    p[2] = (uint8_t)(v >> 8);
    p[3] = (uint8_t)v;
}

static void put_f32(uint8_t *p, fs_real_t v)
{
    const float f = (float)v;
    uint32_t u;
    memcpy(&u, &f, sizeof(u));
    put_u32(p, u);
}

static uint16_t get_u16(const uint8_t *p)
{
    return (uint16_t)(((uint16_t)p[0] << 8) | p[1]);
}

static uint32_t get_u32(const uint8_t *p)
{
    return ((uint32_t)p[0] << 24) | ((uint32_t)p[1] << 16) | ((uint32_t)p[2] << 8) | p[3];
}

static fs_real_t get_f32(const uint8_t *p)
{
    const uint32_t u = get_u32(p);
    float f;
    memcpy(&f, &u, sizeof(f));
    return (fs_real_t)f;
}

/* ---------------------------------------------------------------- data identifiers */

/* The identity DIDs (software version, format versions); their length, 0 for another DID. */
static uint16_t did_identity(uint16_t did, uint8_t *buf)
{
    switch (did) {
    case DID_SW_VERSION: {
        const uint16_t n = (uint16_t)strlen(APP_SW_VERSION);
        memcpy(buf, APP_SW_VERSION, n);
        return n;
    }
    case DID_VERSIONS:
        buf[0] = APP_PROTO_VERSION_MAJOR;
        buf[1] = APP_PROTO_VERSION_MINOR;
        buf[2] = SKILL_FORMAT_VERSION;
        put_u16(&buf[3], DMP_MAX_KERNELS);
        buf[5] = APP_N_SLOTS;
        return 6u;
    default: return 0u;
    }
}

/* The configuration DIDs (gains, limits, communication, object); their length, 0 for another. */
static uint16_t did_config(const app_t *app, uint16_t did, uint8_t *buf)
{
    switch (did) {
    case DID_GAINS_X:
    case DID_GAINS_Y: {
        const pfc_axis_gains_t *g = &app->cfg.gains[did - DID_GAINS_X];
        put_f32(&buf[0], g->m_d_kg);
        put_f32(&buf[4], g->k_d_Nspm);
        put_f32(&buf[8], g->k_p_Npm);
        put_f32(&buf[12], g->k_f);
        put_f32(&buf[16], g->k_i_per_s);
        return 20u;
    }
    case DID_LIMITS_X:
    case DID_LIMITS_Y: {
        const lim_axis_t *l = &app->saf_cfg.lim.axis[did - DID_LIMITS_X];
        put_f32(&buf[0], l->force_max_N);
        put_f32(&buf[4], l->slew_max_N);
        put_f32(&buf[8], l->pos_min_m);
        put_f32(&buf[12], l->pos_max_m);
        put_f32(&buf[16], l->vel_max_mps);
        put_f32(&buf[20], l->contact_force_max_N);
        return 24u;
    }
    case DID_COMM:
        buf[0] = app->cfg.telemetry_period_ms;
        put_u16(&buf[1], app->saf_cfg.wdg.timeout_ms);
        return 3u;
    case DID_OBJECT: {
        const exec_object_t *o = &app->cfg.exec.object;
        buf[0] = app->cfg.exec.use_model;
        put_f32(&buf[1], o->m_v_kg);
        put_f32(&buf[5], o->d_v_Nspm);
        put_f32(&buf[9], o->k1_Npm);
        put_f32(&buf[13], o->k2_Npm);
        put_f32(&buf[17], o->layer_depth_m);
        put_f32(&buf[21], o->surface_m);
        return 25u;
    }
    default: return 0u;
    }
}

/* The slot directory: the count, then per slot valid, length, CRC, kernels, T, end policy. */
static uint16_t did_slot_dir(const app_t *app, uint8_t *buf)
{
    uint16_t n = 1u;
    buf[0] = APP_N_SLOTS;
    for (uint16_t s = 0; s < APP_N_SLOTS; s++) {
        uint8_t *e = &buf[n];
        memset(e, 0, SLOT_DIR_ENTRY);
        if (app->slot_valid[s]) {
            const skill_t *sk = &app->slot_skill[s];
            e[0] = 1u;
            put_u32(&e[1], app->slot_len[s]);
            put_u32(&e[5], app->slot_crc[s]); /* the image's own CRC-32 field */
            put_u16(&e[9], sk->dmp.n_kernels);
            put_f32(&e[11], sk->dmp.duration_s);
            e[15] = (uint8_t)sk->end_policy;
        }
        n = (uint16_t)(n + SLOT_DIR_ENTRY);
    }
    return n;
}

/* The status DIDs (slots, last transfer, device state, fault causes); length, 0 for another. */
static uint16_t did_status(const app_t *app, uint16_t did, uint8_t *buf)
{
    switch (did) {
    case DID_SLOT_DIR: return did_slot_dir(app, buf);
    case DID_LAST_TRANSFER: put_u16(buf, app->last_transfer_status); return 2u;
    case DID_DEVICE_STATE:
        buf[0] = (uint8_t)app->state;
        put_u16(&buf[1], app->saf_out.fault_code);
        buf[3] = app->active_slot;
        buf[4] = app->seq_step;
        put_u32(&buf[5], app->tick);
        return 9u;
    case DID_STIFFNESS_MAX: put_f32(buf, app->cfg.stiffness_max_Npm); return 4u;
    case DID_FAULT_CAUSES: /* what blocks a clear: the causes still present at the last tick */
        put_u32(&buf[0], app->saf.flt.latched_mask);
        put_u32(&buf[4], app->saf.cause_mask);
        return 8u;
    case DID_MOTION_KEY:
        memcpy(buf, app->secoc_dev_nonce, SECOC_NONCE_LEN);
        buf[SECOC_NONCE_LEN] = app->secoc.keyed ? 1u : 0u;
        return SECOC_NONCE_LEN + 1u;
    case DID_AUTH_STATS: secoc_stats_encode(&app->secoc, buf); return SECOC_STATS_LEN;
    default: return 0u;
    }
}

static uint8_t read_did(void *ctx, uint16_t did, uint8_t *out, uint16_t cap, uint16_t *len)
{
    app_t *app = ctx;
    uint8_t buf[8u + APP_N_SLOTS * SLOT_DIR_ENTRY];
    if (did == FWU_DID_STATUS) {
        return fwu_uds_read_did(&app->fwu, out, cap, len);
    }
    uint16_t n = did_identity(did, buf);
    n = n != 0u ? n : did_config(app, did, buf);
    n = n != 0u ? n : did_status(app, did, buf);
    if (n == 0u) {
        return UDS_NRC_REQUEST_OUT_OF_RANGE;
    }
    if (n > cap) {
        return UDS_NRC_RESPONSE_TOO_LONG;
    }
    memcpy(out, buf, n);
    *len = n;
    return UDS_NRC_OK;
}

static bool finite_all(const fs_real_t *v, unsigned n)
{
    for (unsigned i = 0; i < n; i++) {
        if (!fs_isfinite(v[i])) {
            return false;
        }
    }
    return true;
}

/* DID_GAINS_X/Y: m_d, k_d, k_p, k_f, k_i (float32), accepted when the gains validate. */
static uint8_t write_gains(app_t *app, uint16_t did, const uint8_t *d, uint16_t len)
{
    if (len != 20u) {
        return UDS_NRC_INCORRECT_LENGTH;
    }
    pfc_config_t pc;
    pfc_default_config(&pc);
    pc.gains[0] = app->cfg.gains[0];
    pc.gains[1] = app->cfg.gains[1];
    pfc_axis_gains_t *g = &pc.gains[did - DID_GAINS_X];
    g->m_d_kg = get_f32(&d[0]);
    g->k_d_Nspm = get_f32(&d[4]);
    g->k_p_Npm = get_f32(&d[8]);
    g->k_f = get_f32(&d[12]);
    g->k_i_per_s = get_f32(&d[16]);
    if (pfc_config_validate(&pc) != FS_OK) {
        return UDS_NRC_REQUEST_OUT_OF_RANGE;
    }
    app->cfg.gains[did - DID_GAINS_X] = *g;
    return UDS_NRC_OK;
}

/* DID_LIMITS_X/Y: six float32 limits, accepted when the safety configuration validates. */
static uint8_t write_limits(app_t *app, uint16_t did, const uint8_t *d, uint16_t len)
{
    if (len != 24u) {
        return UDS_NRC_INCORRECT_LENGTH;
    }
    saf_config_t sc = app->saf_cfg;
    lim_axis_t *l = &sc.lim.axis[did - DID_LIMITS_X];
    fs_real_t v[6];
    for (unsigned i = 0; i < 6u; i++) {
        v[i] = get_f32(&d[4u * i]);
    }
    if (!finite_all(v, 6u)) {
        return UDS_NRC_REQUEST_OUT_OF_RANGE;
    }
    l->force_max_N = v[0];
    l->slew_max_N = v[1];
    l->pos_min_m = v[2];
    l->pos_max_m = v[3];
    l->vel_max_mps = v[4];
    l->contact_force_max_N = v[5];
    if (saf_config_validate(&sc) != SAF_OK) {
        return UDS_NRC_REQUEST_OUT_OF_RANGE;
    }
    app->saf_cfg = sc;
    app->cfg.saf = sc;
    return UDS_NRC_OK;
}

/* DID_COMM: telemetry period (ms, > 0) and host timeout (ms, the watchdog's range). */
static uint8_t write_comm(app_t *app, const uint8_t *d, uint16_t len)
{
    if (len != 3u) {
        return UDS_NRC_INCORRECT_LENGTH;
    }
    saf_config_t sc = app->saf_cfg;
    sc.wdg.timeout_ms = get_u16(&d[1]);
    if (d[0] == 0u || saf_config_validate(&sc) != SAF_OK) {
        return UDS_NRC_REQUEST_OUT_OF_RANGE;
    }
    app->cfg.telemetry_period_ms = d[0];
    app->saf_cfg = sc;
    app->cfg.saf = sc;
    return UDS_NRC_OK;
}

/* DID_OBJECT: use the model (0/1), then m_v, d_v, k1, k2, layer depth, surface (float32). */
/* DID_STIFFNESS_MAX: the highest nominal skill stiffness accepted, finite in (0, 1e8] N/m. */
static uint8_t write_stiffness_max(app_t *app, const uint8_t *d, uint16_t len)
{
    if (len != 4u) {
        return UDS_NRC_INCORRECT_LENGTH;
    }
    const fs_real_t k = get_f32(d);
    if (!fs_isfinite(k) || !(k > FS_R(0.0)) || k > (fs_real_t)SKCHK_STIFFNESS_MAX_NPM) {
        return UDS_NRC_REQUEST_OUT_OF_RANGE;
    }
    app->cfg.stiffness_max_Npm = k;
    return UDS_NRC_OK;
}

static uint8_t write_object(app_t *app, const uint8_t *d, uint16_t len)
{
    if (len != 25u || d[0] > 1u) {
        return len != 25u ? UDS_NRC_INCORRECT_LENGTH : UDS_NRC_REQUEST_OUT_OF_RANGE;
    }
    fs_real_t v[6];
    for (unsigned i = 0; i < 6u; i++) {
        v[i] = get_f32(&d[1u + 4u * i]);
    }
    if (!finite_all(v, 6u) || v[0] < FS_R(0.0) || v[1] < FS_R(0.0) || v[2] <= FS_R(0.0) ||
        v[3] <= FS_R(0.0) || v[4] < FS_R(0.0)) {
        return UDS_NRC_REQUEST_OUT_OF_RANGE;
    }
    exec_object_t *o = &app->cfg.exec.object;
    app->cfg.exec.use_model = d[0];
    o->m_v_kg = v[0];
    o->d_v_Nspm = v[1];
    o->k1_Npm = v[2];
    o->k2_Npm = v[3];
    o->layer_depth_m = v[4];
    o->surface_m = v[5];
    return UDS_NRC_OK;
}

static uint8_t write_did(void *ctx, uint16_t did, const uint8_t *d, uint16_t len)
{
    app_t *app = ctx;
    if (app->uds.unlocked_level != UDS_SEC_LEVEL_WRITE) {
        return UDS_NRC_SECURITY_ACCESS_DENIED; /* settings: level 1 (not the firmware level) */
    }
    if (did == DID_MOTION_KEY) {
        return app_motion_key(app, d, len); /* also in FAULT: a host resynchronises to clear it */
    }
    if (app->state != APP_IDLE) {
        return UDS_NRC_CONDITIONS_NOT_CORRECT; /* configuration changes only while idle */
    }
    switch (did) {
    case DID_GAINS_X:
    case DID_GAINS_Y: return write_gains(app, did, d, len);
    case DID_LIMITS_X:
    case DID_LIMITS_Y: return write_limits(app, did, d, len);
    case DID_COMM: return write_comm(app, d, len);
    case DID_OBJECT: return write_object(app, d, len);
    case DID_STIFFNESS_MAX: return write_stiffness_max(app, d, len);
    default: return UDS_NRC_REQUEST_OUT_OF_RANGE; /* read-only or unknown */
    }
}

/* ---------------------------------------------------------------- routines */

/* A start request of RUN_SKILL (slot, goal and time scale in 1/1000, end policy) or
 * RUN_SEQUENCE (end policy, then per step: slot, goal, time in 1/1000, duration in ms). */
static uint8_t routine_run_start(app_t *app, uint16_t rid, const uint8_t *d, uint16_t len)
{
    uint8_t slots[EXEC_MAX_STEPS];
    fs_real_t g[EXEC_MAX_STEPS], ts[EXEC_MAX_STEPS], dur[EXEC_MAX_STEPS];
    uint8_t n = 0u;
    uint8_t end = 0u;
    fs_real_t ps[EXEC_MAX_STEPS];
    for (uint8_t i = 0; i < EXEC_MAX_STEPS; i++) {
        ps[i] = FS_R(1.0);
    }
    if (rid == UDS_RID_RUN_SKILL) {
        /* slot, goal scale, time scale, end [, path scale]: 6 or 8 bytes */
        if (len != 6u && len != 8u) {
            return UDS_NRC_INCORRECT_LENGTH;
        }
        slots[0] = d[0];
        g[0] = (fs_real_t)get_u16(&d[1]) * FS_R(0.001);
        ts[0] = (fs_real_t)get_u16(&d[3]) * FS_R(0.001);
        dur[0] = FS_R(0.0);
        end = d[5];
        if (len == 8u) {
            ps[0] = (fs_real_t)get_u16(&d[6]) * FS_R(0.001);
        }
        n = 1u;
    } else {
        if (len < 10u || (len - 1u) % 9u != 0u || (len - 1u) / 9u > EXEC_MAX_STEPS) {
            return UDS_NRC_INCORRECT_LENGTH;
        }
        end = d[0];
        n = (uint8_t)((len - 1u) / 9u);
        for (uint8_t i = 0; i < n; i++) {
            const uint8_t *s = &d[1u + 9u * i];
            slots[i] = s[0];
            g[i] = (fs_real_t)get_u16(&s[1]) * FS_R(0.001);
            ts[i] = (fs_real_t)get_u16(&s[3]) * FS_R(0.001);
            dur[i] = (fs_real_t)get_u32(&s[5]) * FS_R(0.001);
        }
    }
    return app_start_sequence(app, slots, g, ts, dur, ps, n, end);
}

/* RUN_SKILL / RUN_SEQUENCE: start, stop, or the results (state, step, done, fault code). */
static uint8_t routine_run(app_t *app, uint8_t sub, uint16_t rid, const uint8_t *d, uint16_t len,
                           uint8_t *out, uint16_t *out_len)
{
    if (sub == UDS_ROUTINE_START) {
        if (app->uds.unlocked_level != UDS_SEC_LEVEL_WRITE) {
            return UDS_NRC_SECURITY_ACCESS_DENIED; /* motion: the unlocked host session only */
        }
        return routine_run_start(app, rid, d, len);
    }
    if (sub == UDS_ROUTINE_STOP) {
        if (app->state != APP_EXECUTE) {
            return UDS_NRC_REQUEST_SEQUENCE_ERROR;
        }
        (void)app_event(app, APP_EV_STOP);
        return UDS_NRC_OK;
    }
    out[0] = (uint8_t)app->state;
    out[1] = app->seq_step;
    out[2] = app->exec_done ? 1u : 0u;
    put_u16(&out[3], app->saf_out.fault_code);
    *out_len = 5u;
    return UDS_NRC_OK;
}

/* SELF_TEST: the configurations, the skill storage and the sensors; out = pass/fail, code. */
static uint8_t routine_self_test(const app_t *app, uint8_t sub, uint8_t *out, uint16_t *out_len)
{
    if (sub == UDS_ROUTINE_STOP) {
        return UDS_NRC_SUBFUNCTION_NOT_SUPPORTED;
    }
    uint16_t code = 0u;
    pfc_config_t pc;
    pfc_default_config(&pc);
    pc.gains[0] = app->cfg.gains[0];
    pc.gains[1] = app->cfg.gains[1];
    if (saf_config_validate(&app->saf_cfg) != SAF_OK) {
        code = 1u;
    } else if (pfc_config_validate(&pc) != FS_OK) {
        code = (uint16_t)pfc_config_validate(&pc);
    } else if (!app->nvm_ok) {
        code = NVM_ERR_GEOMETRY;
    } else if (!fs_isfinite(app->sens.pos_m[0]) || !fs_isfinite(app->sens.pos_m[1]) ||
               !fs_isfinite(app->sens.force_contact_N[0])) {
        code = FLT_SENSOR_NAN;
    }
    out[0] = (uint8_t)(code == 0u ? 0u : 1u);
    put_u16(&out[1], code);
    *out_len = 3u;
    return UDS_NRC_OK;
}

/* CLEAR_FAULTS: accepted in FAULT once no cause persists. */
static uint8_t routine_clear_faults(app_t *app, uint8_t sub)
{
    if (sub != UDS_ROUTINE_START) {
        return UDS_NRC_SUBFUNCTION_NOT_SUPPORTED;
    }
    if (app->state != APP_FAULT) {
        return UDS_NRC_REQUEST_SEQUENCE_ERROR;
    }
    if (app_clear_faults(app) != FLT_NONE) {
        return UDS_NRC_CONDITIONS_NOT_CORRECT; /* a cause persists */
    }
    return UDS_NRC_OK;
}

/* ERASE_SLOT (slot 1..APP_N_SLOTS): write level unlocked, only while idle. */
static uint8_t routine_erase_slot(app_t *app, uint8_t sub, const uint8_t *d, uint16_t len)
{
    if (sub != UDS_ROUTINE_START) {
        return UDS_NRC_SUBFUNCTION_NOT_SUPPORTED;
    }
    if (len != 1u) {
        return UDS_NRC_INCORRECT_LENGTH;
    }
    if (d[0] < 1u || d[0] > APP_N_SLOTS) {
        return UDS_NRC_REQUEST_OUT_OF_RANGE;
    }
    if (app->uds.unlocked_level != UDS_SEC_LEVEL_WRITE) {
        return UDS_NRC_SECURITY_ACCESS_DENIED;
    }
    if (app->state != APP_IDLE || !app->nvm_ok) {
        return UDS_NRC_CONDITIONS_NOT_CORRECT; /* slots change only while idle */
    }
    if (nvm_erase_slot(&app->nvm, (uint16_t)(d[0] - 1u)) != NVM_OK) {
        return UDS_NRC_PROGRAMMING_FAILURE;
    }
    app->slot_valid[d[0] - 1u] = false;
    return UDS_NRC_OK;
}

static uint8_t routine(void *ctx, uint8_t sub, uint16_t rid, const uint8_t *d, uint16_t len,
                       uint8_t *out, uint16_t cap, uint16_t *out_len)
{
    app_t *app = ctx;
    if (fwu_uds_owns_rid(rid)) {
        if (rid == FWU_RID_CONFIRM && fwu_uds_authorised(&app->uds) && !app->fw_self_test_ok) {
            *out_len = 0u;
            return UDS_NRC_CONDITIONS_NOT_CORRECT; /* only an image that passed its self-test */
        }
        return fwu_uds_routine(&app->fwu, &app->uds, sub, rid, d, len, out, cap, out_len);
    }
    *out_len = 0u;
    if (cap < 8u) {
        return UDS_NRC_RESPONSE_TOO_LONG;
    }
    switch (rid) {
    case UDS_RID_RUN_SKILL:
    case UDS_RID_RUN_SEQUENCE: return routine_run(app, sub, rid, d, len, out, out_len);
    case UDS_RID_SELF_TEST: return routine_self_test(app, sub, out, out_len);
    case UDS_RID_CLEAR_FAULTS: return routine_clear_faults(app, sub);
    case UDS_RID_ERASE_SLOT: return routine_erase_slot(app, sub, d, len);
    default: return UDS_NRC_REQUEST_OUT_OF_RANGE;
    }
}

/* ---------------------------------------------------------------- session, reset, security */

static uint8_t session_allowed(void *ctx, uint8_t session)
{
    app_t *app = ctx;
    if (session == UDS_SESSION_PROGRAMMING && app->state != APP_IDLE) {
        return UDS_NRC_CONDITIONS_NOT_CORRECT;
    }
    return UDS_NRC_OK;
}

static uint8_t ecu_reset(void *ctx, uint8_t type)
{
    app_t *app = ctx;
    (void)type;
    return (app->state == APP_TEACH || app->state == APP_EXECUTE) ? UDS_NRC_CONDITIONS_NOT_CORRECT
                                                                  : UDS_NRC_OK;
}

static void reset_now(void *ctx, uint8_t type)
{
    (void)ctx;
    hal_request_reset(type);
}

static uint8_t security_seed(void *ctx, uint8_t level, uint8_t *seed, uint16_t cap, uint16_t *len)
{
    app_t *app = ctx;
    const sec_config_t *cfg = app_sec_config(app, level);
    if (cfg == NULL) {
        return UDS_NRC_SUBFUNCTION_NOT_SUPPORTED;
    }
    if (cap < SEC_SEED_LEN) {
        return UDS_NRC_RESPONSE_TOO_LONG;
    }
    /* the state is shared by the levels: a seed of another level is never "already unlocked" */
    if (app->uds.unlocked_level != level) {
        sec_lock(&app->sec);
    }
    const sec_nrc_t nrc = sec_request_seed(cfg, &app->sec, app->now_ms, seed);
    app_sec_persist(app); /* a lockout that ended clears the stored counter */
    if (nrc != SEC_NRC_NONE) {
        return (uint8_t)nrc;
    }
    *len = SEC_SEED_LEN;
    return UDS_NRC_OK;
}

static uint8_t security_key(void *ctx, uint8_t level, const uint8_t *key, uint16_t len)
{
    app_t *app = ctx;
    const sec_config_t *cfg = app_sec_config(app, level);
    if (cfg == NULL) {
        return UDS_NRC_SUBFUNCTION_NOT_SUPPORTED;
    }
    const uint8_t nrc = (uint8_t)sec_send_key(cfg, &app->sec, app->now_ms, key, len);
    app_sec_persist(app); /* the wrong-key counter survives reset and power-up */
    return nrc;
}

/* ---------------------------------------------------------------- transfers */

static uint8_t download_begin(void *ctx, uint32_t addr, uint32_t size)
{
    app_t *app = ctx;
    app->fw_xfer = addr == FWU_DOWNLOAD_ADDRESS;
    if (app->fw_xfer) {
        if (!fwu_uds_authorised(&app->uds)) {
            return UDS_NRC_SECURITY_ACCESS_DENIED; /* firmware: level 3 only */
        }
        return app->state == APP_IDLE ? fwu_uds_download_begin(&app->fwu, &app->uds, size)
                                      : UDS_NRC_CONDITIONS_NOT_CORRECT;
    }
    if (addr < 1u || addr > APP_N_SLOTS || size < SKILL_HEADER_SIZE_V2 + SKILL_CRC_SIZE ||
        size > APP_IMAGE_MAX) {
        return UDS_NRC_REQUEST_OUT_OF_RANGE;
    }
    if (app->uds.unlocked_level != UDS_SEC_LEVEL_WRITE) {
        return UDS_NRC_SECURITY_ACCESS_DENIED;
    }
    if (app->state != APP_IDLE) {
        return UDS_NRC_CONDITIONS_NOT_CORRECT; /* slots change only while idle */
    }
    if (!app->nvm_ok) {
        return UDS_NRC_UPLOAD_DOWNLOAD_NOT_ACCEPTED;
    }
    app->xfer_slot = addr;
    app->xfer_size = size;
    app->last_transfer_status = 0xFFFFu; /* in progress */
    return UDS_NRC_OK;
}

static uint8_t download_data(void *ctx, uint32_t offset, const uint8_t *d, uint16_t len)
{
    app_t *app = ctx;
    if (app->fw_xfer) {
        return fwu_uds_download_data(&app->fwu, &app->uds, offset, d, len);
    }
    if (offset + len > app->xfer_size) {
        return UDS_NRC_TRANSFER_SUSPENDED;
    }
    memcpy(&app->image[offset], d, len);
    return UDS_NRC_OK;
}

/* One tick's slice of a download's commit (app->commit_stage): false while it goes on; true once
 * done, *st FS_OK when the skill passed every check and the flash write is done (its result in
 * app->writer.status), or the refusal. */
static bool commit_slice(app_t *app, fs_status_t *st)
{
    *st = FS_OK;
    switch (app->commit_stage) {
    case APP_COMMIT_PARSE:
        if (!skill_parse_run(&app->parser, APP_COMMIT_UNITS_PER_TICK)) {
            return false;
        }
        *st = app->parser.status;
        app->commit_stage = APP_COMMIT_PARAMS;
        return *st != FS_OK;
    case APP_COMMIT_PARAMS:
        *st = skchk_params(&app->staging);
        if (*st == FS_OK) {
            *st = skchk_stiffness(&app->staging, app->cfg.stiffness_max_Npm);
        }
        if (*st != FS_OK) {
            return true;
        }
        skchk_begin(&app->check, &app->staging, FS_R(0.001), app->cfg.saf.lim.axis[0].force_max_N);
        app->check.path_max_m = app->cfg.saf.lim.axis[1].pos_max_m -
                                app->cfg.saf.lim.axis[1].pos_min_m;
        app->commit_stage = APP_COMMIT_CHECK;
        return false;
    case APP_COMMIT_CHECK:
        if (!skchk_run(&app->check, APP_CHECK_STEPS_PER_TICK)) {
            return false;
        }
        *st = app->check.status; /* 222/223/225: slot unchanged */
        if (*st != FS_OK) {
            return true;
        }
        (void)nvm_write_begin(&app->writer, &app->nvm, (uint16_t)(app->xfer_slot - 1u), app->image,
                              app->xfer_size); /* its argument errors end the write at once */
        app->commit_stage = APP_COMMIT_WRITE;
        return false;
    default: return nvm_write_run(&app->writer, APP_COMMIT_FLASH_UNITS_PER_TICK);
    }
}

static uint8_t download_end(void *ctx, uint32_t *crc_out)
{
    app_t *app = ctx;
    if (app->fw_xfer) {
        return fwu_uds_download_end(&app->fwu, &app->uds, crc_out);
    }
    const uint16_t slot = (uint16_t)(app->xfer_slot - 1u);
    if (app->state != APP_IDLE || app->uds.unlocked_level != UDS_SEC_LEVEL_WRITE) {
        /* a skill started (or security dropped) since RequestDownload: commit refused, the slot
         * keeps what it holds; nothing changes while a skill runs */
        app->checking = false;
        app->last_transfer_status = 0xFFFEu;
        return app->state != APP_IDLE ? UDS_NRC_CONDITIONS_NOT_CORRECT
                                      : UDS_NRC_SECURITY_ACCESS_DENIED;
    }
    if (!app->checking) {
        /* the commit, a bounded slice a tick (0x78 meanwhile): parse, parameters, rollout, write */
        skill_parse_begin(&app->parser, app->image, app->xfer_size, &app->staging);
        app->checking = true;
        app->commit_stage = APP_COMMIT_PARSE;
    }
    fs_status_t st = FS_OK;
    if (!commit_slice(app, &st)) {
        return UDS_NRC_RESPONSE_PENDING;
    }
    app->checking = false;
    if (st != FS_OK) {
        app->last_transfer_status = (uint16_t)st; /* e.g. 204 CRC, 223 peak: the old skill stays */
        return UDS_NRC_PROGRAMMING_FAILURE;
    }
    const nvm_status_t ns = app->writer.status;
    if (ns != NVM_OK) {
        app->last_transfer_status = (uint16_t)ns;
        app_slots_reload(app); /* whatever storage holds now */
        return UDS_NRC_PROGRAMMING_FAILURE;
    }
    /* swap into the slot cache: UDS runs at the start of a tick and downloads only in IDLE */
    app->slot_skill[slot] = app->staging;
    app->slot_valid[slot] = true;
    app->slot_peak_N[slot] = app->check.peak_N;
    app->slot_path_m[slot] = app->check.path_peak_m;
    app->last_transfer_status = 0u;
    *crc_out = app->parser.crc; /* the image's CRC-32, checked by the parse */
    app->slot_crc[slot] = *crc_out;
    app->slot_len[slot] = app->xfer_size;
    return UDS_NRC_OK;
}

static void transfer_abort(void *ctx)
{
    app_t *app = ctx;
    if (app->fw_xfer) {
        fwu_abort(&app->fwu);
    }
    if (app->last_transfer_status == 0xFFFFu) {
        app->last_transfer_status = 0xFFFEu; /* interrupted: nothing was written */
    }
    app->checking = false; /* a commit in progress ends with the transfer */
    app->xfer_size = 0u;
}

static uint8_t upload_begin(void *ctx, uint32_t addr, uint32_t size)
{
    app_t *app = ctx;
    if (addr < 1u || addr > APP_N_SLOTS || !app->nvm_ok) {
        return UDS_NRC_REQUEST_OUT_OF_RANGE;
    }
    uint32_t len = 0u;
    if (nvm_read(&app->nvm, (uint16_t)(addr - 1u), app->image, sizeof(app->image), &len) !=
        NVM_OK) {
        return UDS_NRC_UPLOAD_DOWNLOAD_NOT_ACCEPTED; /* empty slot */
    }
    if (size != len) {
        return UDS_NRC_REQUEST_OUT_OF_RANGE;
    }
    app->xfer_size = len;
    return UDS_NRC_OK;
}

static uint8_t upload_data(void *ctx, uint32_t offset, uint8_t *out, uint16_t len)
{
    app_t *app = ctx;
    if (offset + len > app->xfer_size) {
        return UDS_NRC_REQUEST_OUT_OF_RANGE;
    }
    memcpy(out, &app->image[offset], len);
    return UDS_NRC_OK;
}

void app_uds_bind(app_t *app, uds_app_t *out)
{
    memset(out, 0, sizeof(*out));
    out->ctx = app;
    out->read_did = read_did;
    out->write_did = write_did;
    out->routine = routine;
    out->session_allowed = session_allowed;
    out->ecu_reset = ecu_reset;
    out->reset_now = reset_now;
    out->security_seed = security_seed;
    out->security_key = security_key;
    out->download_begin = download_begin;
    out->download_data = download_data;
    out->download_end = download_end;
    out->transfer_abort = transfer_abort;
    out->upload_begin = upload_begin;
    out->upload_data = upload_data;
}

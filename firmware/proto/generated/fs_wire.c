/* Codecs of the device's UDS payloads (see fs_wire.h).
 * generated from firmware/base/wire.toml by tools/gen_codes.py; do not edit. */
#include "fs_wire.h"

#include <math.h>
#include <string.h>

static uint32_t get_be(const uint8_t *p, unsigned n)
{
    uint32_t v = 0u;
    for (unsigned i = 0; i < n; i++) {
        v = (v << 8) | p[i];
    }
    return v;
}

static void put_be(uint8_t *p, uint32_t v, unsigned n)
{
    for (unsigned i = 0; i < n; i++) {
        p[i] = (uint8_t)(v >> (8u * (n - 1u - i)));
    }
}

static float get_f32(const uint8_t *p)
{
    const uint32_t u = get_be(p, 4u);
    float f;
    memcpy(&f, &u, sizeof(f));
    return f;
}

static void put_f32(uint8_t *p, float f)
{
    uint32_t u;
    memcpy(&u, &f, sizeof(u));
    put_be(p, u, 4u);
}

static int versions_in_range(const fs_wire_versions_t *v)
{
    (void)v;
    return 1;
}

proto_status_t fs_wire_versions_unpack(fs_wire_versions_t *v, const uint8_t *d, uint16_t len)
{
    if (len != FS_WIRE_VERSIONS_LEN) {
        return PROTO_ERR_WIRE_LENGTH;
    }
    fs_wire_versions_t t;
    memset(&t, 0, sizeof(t));
    t.proto_major = (uint8_t)get_be(&d[0u], 1u);
    t.proto_minor = (uint8_t)get_be(&d[1u], 1u);
    t.skill_format = (uint8_t)get_be(&d[2u], 1u);
    t.max_kernels = (uint16_t)get_be(&d[3u], 2u);
    t.slots = (uint8_t)get_be(&d[5u], 1u);
    if (!versions_in_range(&t)) {
        return PROTO_ERR_WIRE_RANGE;
    }
    *v = t;
    return PROTO_OK;
}

uint16_t fs_wire_versions_pack(const fs_wire_versions_t *v, uint8_t *out, uint16_t cap)
{
    const unsigned n = 6u;
    if (!versions_in_range(v) || n > cap) {
        return 0u;
    }
    put_be(&out[0u], v->proto_major, 1u);
    put_be(&out[1u], v->proto_minor, 1u);
    put_be(&out[2u], v->skill_format, 1u);
    put_be(&out[3u], v->max_kernels, 2u);
    put_be(&out[5u], v->slots, 1u);
    return (uint16_t)n;
}

static int gains_in_range(const fs_wire_gains_t *v)
{
    (void)v;
    return 1;
}

proto_status_t fs_wire_gains_unpack(fs_wire_gains_t *v, const uint8_t *d, uint16_t len)
{
    if (len != FS_WIRE_GAINS_LEN) {
        return PROTO_ERR_WIRE_LENGTH;
    }
    fs_wire_gains_t t;
    memset(&t, 0, sizeof(t));
    t.m_d_kg = get_f32(&d[0u]);
    t.k_d_Nspm = get_f32(&d[4u]);
    t.k_p_Npm = get_f32(&d[8u]);
    t.k_f = get_f32(&d[12u]);
    t.k_i_per_s = get_f32(&d[16u]);
    if (!gains_in_range(&t)) {
        return PROTO_ERR_WIRE_RANGE;
    }
    *v = t;
    return PROTO_OK;
}

uint16_t fs_wire_gains_pack(const fs_wire_gains_t *v, uint8_t *out, uint16_t cap)
{
    const unsigned n = 20u;
    if (!gains_in_range(v) || n > cap) {
        return 0u;
    }
    put_f32(&out[0u], v->m_d_kg);
    put_f32(&out[4u], v->k_d_Nspm);
    put_f32(&out[8u], v->k_p_Npm);
    put_f32(&out[12u], v->k_f);
    put_f32(&out[16u], v->k_i_per_s);
    return (uint16_t)n;
}

static int limits_in_range(const fs_wire_limits_t *v)
{
    return isfinite(v->force_max_N) &&
           isfinite(v->slew_max_N) &&
           isfinite(v->pos_min_m) &&
           isfinite(v->pos_max_m) &&
           isfinite(v->vel_max_mps) &&
           isfinite(v->contact_force_max_N);
}

proto_status_t fs_wire_limits_unpack(fs_wire_limits_t *v, const uint8_t *d, uint16_t len)
{
    if (len != FS_WIRE_LIMITS_LEN) {
        return PROTO_ERR_WIRE_LENGTH;
    }
    fs_wire_limits_t t;
    memset(&t, 0, sizeof(t));
    t.force_max_N = get_f32(&d[0u]);
    t.slew_max_N = get_f32(&d[4u]);
    t.pos_min_m = get_f32(&d[8u]);
    t.pos_max_m = get_f32(&d[12u]);
    t.vel_max_mps = get_f32(&d[16u]);
    t.contact_force_max_N = get_f32(&d[20u]);
    if (!limits_in_range(&t)) {
        return PROTO_ERR_WIRE_RANGE;
    }
    *v = t;
    return PROTO_OK;
}

uint16_t fs_wire_limits_pack(const fs_wire_limits_t *v, uint8_t *out, uint16_t cap)
{
    const unsigned n = 24u;
    if (!limits_in_range(v) || n > cap) {
        return 0u;
    }
    put_f32(&out[0u], v->force_max_N);
    put_f32(&out[4u], v->slew_max_N);
    put_f32(&out[8u], v->pos_min_m);
    put_f32(&out[12u], v->pos_max_m);
    put_f32(&out[16u], v->vel_max_mps);
    put_f32(&out[20u], v->contact_force_max_N);
    return (uint16_t)n;
}

static int comm_in_range(const fs_wire_comm_t *v)
{
    return v->telemetry_period_ms >= 1u;
}

proto_status_t fs_wire_comm_unpack(fs_wire_comm_t *v, const uint8_t *d, uint16_t len)
{
    if (len != FS_WIRE_COMM_LEN) {
        return PROTO_ERR_WIRE_LENGTH;
    }
    fs_wire_comm_t t;
    memset(&t, 0, sizeof(t));
    t.telemetry_period_ms = (uint8_t)get_be(&d[0u], 1u);
    t.host_timeout_ms = (uint16_t)get_be(&d[1u], 2u);
    if (!comm_in_range(&t)) {
        return PROTO_ERR_WIRE_RANGE;
    }
    *v = t;
    return PROTO_OK;
}

uint16_t fs_wire_comm_pack(const fs_wire_comm_t *v, uint8_t *out, uint16_t cap)
{
    const unsigned n = 3u;
    if (!comm_in_range(v) || n > cap) {
        return 0u;
    }
    put_be(&out[0u], v->telemetry_period_ms, 1u);
    put_be(&out[1u], v->host_timeout_ms, 2u);
    return (uint16_t)n;
}

static int object_in_range(const fs_wire_object_t *v)
{
    return v->use_model <= 1u &&
           isfinite(v->m_v_kg) &&
           v->m_v_kg >= 0.0f &&
           isfinite(v->d_v_Nspm) &&
           v->d_v_Nspm >= 0.0f &&
           isfinite(v->k1_Npm) &&
           v->k1_Npm > 0.0f &&
           isfinite(v->k2_Npm) &&
           v->k2_Npm > 0.0f &&
           isfinite(v->layer_depth_m) &&
           v->layer_depth_m >= 0.0f &&
           isfinite(v->surface_m);
}

proto_status_t fs_wire_object_unpack(fs_wire_object_t *v, const uint8_t *d, uint16_t len)
{
    if (len != FS_WIRE_OBJECT_LEN) {
        return PROTO_ERR_WIRE_LENGTH;
    }
    fs_wire_object_t t;
    memset(&t, 0, sizeof(t));
    t.use_model = (uint8_t)get_be(&d[0u], 1u);
    t.m_v_kg = get_f32(&d[1u]);
    t.d_v_Nspm = get_f32(&d[5u]);
    t.k1_Npm = get_f32(&d[9u]);
    t.k2_Npm = get_f32(&d[13u]);
    t.layer_depth_m = get_f32(&d[17u]);
    t.surface_m = get_f32(&d[21u]);
    if (!object_in_range(&t)) {
        return PROTO_ERR_WIRE_RANGE;
    }
    *v = t;
    return PROTO_OK;
}

uint16_t fs_wire_object_pack(const fs_wire_object_t *v, uint8_t *out, uint16_t cap)
{
    const unsigned n = 25u;
    if (!object_in_range(v) || n > cap) {
        return 0u;
    }
    put_be(&out[0u], v->use_model, 1u);
    put_f32(&out[1u], v->m_v_kg);
    put_f32(&out[5u], v->d_v_Nspm);
    put_f32(&out[9u], v->k1_Npm);
    put_f32(&out[13u], v->k2_Npm);
    put_f32(&out[17u], v->layer_depth_m);
    put_f32(&out[21u], v->surface_m);
    return (uint16_t)n;
}

static int band_in_range(const fs_wire_band_t *v)
{
    return v->outside <= 1u;
}

proto_status_t fs_wire_band_unpack(fs_wire_band_t *v, const uint8_t *d, uint16_t len)
{
    if (len != FS_WIRE_BAND_LEN) {
        return PROTO_ERR_WIRE_LENGTH;
    }
    fs_wire_band_t t;
    memset(&t, 0, sizeof(t));
    t.checked_ms = (uint32_t)get_be(&d[0u], 4u);
    t.outside_ms = (uint32_t)get_be(&d[4u], 4u);
    t.longest_ms = (uint32_t)get_be(&d[8u], 4u);
    t.max_widths = (uint16_t)get_be(&d[12u], 2u);
    t.first_ms = (uint32_t)get_be(&d[14u], 4u);
    t.outside = (uint8_t)get_be(&d[18u], 1u);
    t.stop_ms = (uint16_t)get_be(&d[19u], 2u);
    if (!band_in_range(&t)) {
        return PROTO_ERR_WIRE_RANGE;
    }
    *v = t;
    return PROTO_OK;
}

uint16_t fs_wire_band_pack(const fs_wire_band_t *v, uint8_t *out, uint16_t cap)
{
    const unsigned n = 21u;
    if (!band_in_range(v) || n > cap) {
        return 0u;
    }
    put_be(&out[0u], v->checked_ms, 4u);
    put_be(&out[4u], v->outside_ms, 4u);
    put_be(&out[8u], v->longest_ms, 4u);
    put_be(&out[12u], v->max_widths, 2u);
    put_be(&out[14u], v->first_ms, 4u);
    put_be(&out[18u], v->outside, 1u);
    put_be(&out[19u], v->stop_ms, 2u);
    return (uint16_t)n;
}

static int stiffness_max_in_range(const fs_wire_stiffness_max_t *v)
{
    return isfinite(v->stiffness_max_Npm) &&
           v->stiffness_max_Npm > 0.0f &&
           v->stiffness_max_Npm <= 100000000.0f;
}

proto_status_t fs_wire_stiffness_max_unpack(fs_wire_stiffness_max_t *v, const uint8_t *d, uint16_t len)
{
    if (len != FS_WIRE_STIFFNESS_MAX_LEN) {
        return PROTO_ERR_WIRE_LENGTH;
    }
    fs_wire_stiffness_max_t t;
    memset(&t, 0, sizeof(t));
    t.stiffness_max_Npm = get_f32(&d[0u]);
    if (!stiffness_max_in_range(&t)) {
        return PROTO_ERR_WIRE_RANGE;
    }
    *v = t;
    return PROTO_OK;
}

uint16_t fs_wire_stiffness_max_pack(const fs_wire_stiffness_max_t *v, uint8_t *out, uint16_t cap)
{
    const unsigned n = 4u;
    if (!stiffness_max_in_range(v) || n > cap) {
        return 0u;
    }
    put_f32(&out[0u], v->stiffness_max_Npm);
    return (uint16_t)n;
}

static int slot_entry_in_range(const fs_wire_slot_entry_t *v)
{
    return v->valid <= 1u;
}

proto_status_t fs_wire_slot_entry_unpack(fs_wire_slot_entry_t *v, const uint8_t *d, uint16_t len)
{
    if (len != FS_WIRE_SLOT_ENTRY_LEN) {
        return PROTO_ERR_WIRE_LENGTH;
    }
    fs_wire_slot_entry_t t;
    memset(&t, 0, sizeof(t));
    t.valid = (uint8_t)get_be(&d[0u], 1u);
    t.length = (uint32_t)get_be(&d[1u], 4u);
    t.crc32 = (uint32_t)get_be(&d[5u], 4u);
    t.n_kernels = (uint16_t)get_be(&d[9u], 2u);
    t.duration_s = get_f32(&d[11u]);
    t.end = (uint8_t)get_be(&d[15u], 1u);
    if (!slot_entry_in_range(&t)) {
        return PROTO_ERR_WIRE_RANGE;
    }
    *v = t;
    return PROTO_OK;
}

uint16_t fs_wire_slot_entry_pack(const fs_wire_slot_entry_t *v, uint8_t *out, uint16_t cap)
{
    const unsigned n = 16u;
    if (!slot_entry_in_range(v) || n > cap) {
        return 0u;
    }
    put_be(&out[0u], v->valid, 1u);
    put_be(&out[1u], v->length, 4u);
    put_be(&out[5u], v->crc32, 4u);
    put_be(&out[9u], v->n_kernels, 2u);
    put_f32(&out[11u], v->duration_s);
    put_be(&out[15u], v->end, 1u);
    return (uint16_t)n;
}

static int slot_dir_in_range(const fs_wire_slot_dir_t *v)
{
    if (v->n_entries > 8u) {
        return 0;
    }
    for (unsigned i = 0; i < v->n_entries; i++) {
        if (!slot_entry_in_range(&v->entries[i])) {
            return 0;
        }
    }
    return v->count <= 8u;
}

proto_status_t fs_wire_slot_dir_unpack(fs_wire_slot_dir_t *v, const uint8_t *d, uint16_t len)
{
    if (len < FS_WIRE_SLOT_DIR_LEN_MIN || len > FS_WIRE_SLOT_DIR_LEN_MAX || (len - 1u) % 16u != 0u) {
        return PROTO_ERR_WIRE_LENGTH;
    }
    fs_wire_slot_dir_t t;
    memset(&t, 0, sizeof(t));
    t.count = (uint8_t)get_be(&d[0u], 1u);
    t.n_entries = (uint8_t)((len - 1u) / 16u);
    for (unsigned i = 0; i < t.n_entries; i++) {
        const unsigned at = 1u + 16u * i;
        t.entries[i].valid = (uint8_t)get_be(&d[at + 0u], 1u);
        t.entries[i].length = (uint32_t)get_be(&d[at + 1u], 4u);
        t.entries[i].crc32 = (uint32_t)get_be(&d[at + 5u], 4u);
        t.entries[i].n_kernels = (uint16_t)get_be(&d[at + 9u], 2u);
        t.entries[i].duration_s = get_f32(&d[at + 11u]);
        t.entries[i].end = (uint8_t)get_be(&d[at + 15u], 1u);
    }
    if (!slot_dir_in_range(&t)) {
        return PROTO_ERR_WIRE_RANGE;
    }
    *v = t;
    return PROTO_OK;
}

uint16_t fs_wire_slot_dir_pack(const fs_wire_slot_dir_t *v, uint8_t *out, uint16_t cap)
{
    const unsigned n = 1u + 16u * (unsigned)v->n_entries;
    if (!slot_dir_in_range(v) || n > cap) {
        return 0u;
    }
    put_be(&out[0u], v->count, 1u);
    for (unsigned i = 0; i < v->n_entries; i++) {
        const unsigned at = 1u + 16u * i;
        put_be(&out[at + 0u], v->entries[i].valid, 1u);
        put_be(&out[at + 1u], v->entries[i].length, 4u);
        put_be(&out[at + 5u], v->entries[i].crc32, 4u);
        put_be(&out[at + 9u], v->entries[i].n_kernels, 2u);
        put_f32(&out[at + 11u], v->entries[i].duration_s);
        put_be(&out[at + 15u], v->entries[i].end, 1u);
    }
    return (uint16_t)n;
}

static int last_transfer_in_range(const fs_wire_last_transfer_t *v)
{
    (void)v;
    return 1;
}

proto_status_t fs_wire_last_transfer_unpack(fs_wire_last_transfer_t *v, const uint8_t *d, uint16_t len)
{
    if (len != FS_WIRE_LAST_TRANSFER_LEN) {
        return PROTO_ERR_WIRE_LENGTH;
    }
    fs_wire_last_transfer_t t;
    memset(&t, 0, sizeof(t));
    t.status = (uint16_t)get_be(&d[0u], 2u);
    if (!last_transfer_in_range(&t)) {
        return PROTO_ERR_WIRE_RANGE;
    }
    *v = t;
    return PROTO_OK;
}

uint16_t fs_wire_last_transfer_pack(const fs_wire_last_transfer_t *v, uint8_t *out, uint16_t cap)
{
    const unsigned n = 2u;
    if (!last_transfer_in_range(v) || n > cap) {
        return 0u;
    }
    put_be(&out[0u], v->status, 2u);
    return (uint16_t)n;
}

static int device_state_in_range(const fs_wire_device_state_t *v)
{
    (void)v;
    return 1;
}

proto_status_t fs_wire_device_state_unpack(fs_wire_device_state_t *v, const uint8_t *d, uint16_t len)
{
    if (len != FS_WIRE_DEVICE_STATE_LEN) {
        return PROTO_ERR_WIRE_LENGTH;
    }
    fs_wire_device_state_t t;
    memset(&t, 0, sizeof(t));
    t.state = (uint8_t)get_be(&d[0u], 1u);
    t.fault = (uint16_t)get_be(&d[1u], 2u);
    t.slot = (uint8_t)get_be(&d[3u], 1u);
    t.step = (uint8_t)get_be(&d[4u], 1u);
    t.tick = (uint32_t)get_be(&d[5u], 4u);
    if (!device_state_in_range(&t)) {
        return PROTO_ERR_WIRE_RANGE;
    }
    *v = t;
    return PROTO_OK;
}

uint16_t fs_wire_device_state_pack(const fs_wire_device_state_t *v, uint8_t *out, uint16_t cap)
{
    const unsigned n = 9u;
    if (!device_state_in_range(v) || n > cap) {
        return 0u;
    }
    put_be(&out[0u], v->state, 1u);
    put_be(&out[1u], v->fault, 2u);
    put_be(&out[3u], v->slot, 1u);
    put_be(&out[4u], v->step, 1u);
    put_be(&out[5u], v->tick, 4u);
    return (uint16_t)n;
}

static int contact_wait_in_range(const fs_wire_contact_wait_t *v)
{
    return v->rate <= 1000u;
}

proto_status_t fs_wire_contact_wait_unpack(fs_wire_contact_wait_t *v, const uint8_t *d, uint16_t len)
{
    if (len != FS_WIRE_CONTACT_WAIT_LEN) {
        return PROTO_ERR_WIRE_LENGTH;
    }
    fs_wire_contact_wait_t t;
    memset(&t, 0, sizeof(t));
    t.hold_ms = (uint32_t)get_be(&d[0u], 4u);
    t.losses = (uint16_t)get_be(&d[4u], 2u);
    t.rate = (uint16_t)get_be(&d[6u], 2u);
    if (!contact_wait_in_range(&t)) {
        return PROTO_ERR_WIRE_RANGE;
    }
    *v = t;
    return PROTO_OK;
}

uint16_t fs_wire_contact_wait_pack(const fs_wire_contact_wait_t *v, uint8_t *out, uint16_t cap)
{
    const unsigned n = 8u;
    if (!contact_wait_in_range(v) || n > cap) {
        return 0u;
    }
    put_be(&out[0u], v->hold_ms, 4u);
    put_be(&out[4u], v->losses, 2u);
    put_be(&out[6u], v->rate, 2u);
    return (uint16_t)n;
}

static int fault_causes_in_range(const fs_wire_fault_causes_t *v)
{
    (void)v;
    return 1;
}

proto_status_t fs_wire_fault_causes_unpack(fs_wire_fault_causes_t *v, const uint8_t *d, uint16_t len)
{
    if (len != FS_WIRE_FAULT_CAUSES_LEN) {
        return PROTO_ERR_WIRE_LENGTH;
    }
    fs_wire_fault_causes_t t;
    memset(&t, 0, sizeof(t));
    t.latched_mask = (uint32_t)get_be(&d[0u], 4u);
    t.present_mask = (uint32_t)get_be(&d[4u], 4u);
    if (!fault_causes_in_range(&t)) {
        return PROTO_ERR_WIRE_RANGE;
    }
    *v = t;
    return PROTO_OK;
}

uint16_t fs_wire_fault_causes_pack(const fs_wire_fault_causes_t *v, uint8_t *out, uint16_t cap)
{
    const unsigned n = 8u;
    if (!fault_causes_in_range(v) || n > cap) {
        return 0u;
    }
    put_be(&out[0u], v->latched_mask, 4u);
    put_be(&out[4u], v->present_mask, 4u);
    return (uint16_t)n;
}

static int run_skill_in_range(const fs_wire_run_skill_t *v)
{
    return v->end <= 2u;
}

proto_status_t fs_wire_run_skill_unpack(fs_wire_run_skill_t *v, const uint8_t *d, uint16_t len)
{
    if (len != FS_WIRE_RUN_SKILL_LEN_MIN && len != FS_WIRE_RUN_SKILL_LEN_MAX) {
        return PROTO_ERR_WIRE_LENGTH;
    }
    fs_wire_run_skill_t t;
    memset(&t, 0, sizeof(t));
    t.slot = (uint8_t)get_be(&d[0u], 1u);
    t.goal_scale = (uint16_t)get_be(&d[1u], 2u);
    t.time_scale = (uint16_t)get_be(&d[3u], 2u);
    t.end = (uint8_t)get_be(&d[5u], 1u);
    if (len == FS_WIRE_RUN_SKILL_LEN_MAX) {
        t.has_path_scale = 1u;
        t.path_scale = (uint16_t)get_be(&d[6u], 2u);
    } else {
        t.path_scale = 1000u;
    }
    if (!run_skill_in_range(&t)) {
        return PROTO_ERR_WIRE_RANGE;
    }
    *v = t;
    return PROTO_OK;
}

uint16_t fs_wire_run_skill_pack(const fs_wire_run_skill_t *v, uint8_t *out, uint16_t cap)
{
    const unsigned n = 6u + (v->has_path_scale != 0u ? 2u : 0u);
    if (!run_skill_in_range(v) || n > cap) {
        return 0u;
    }
    put_be(&out[0u], v->slot, 1u);
    put_be(&out[1u], v->goal_scale, 2u);
    put_be(&out[3u], v->time_scale, 2u);
    put_be(&out[5u], v->end, 1u);
    if (v->has_path_scale != 0u) { put_be(&out[6u], v->path_scale, 2u); }
    return (uint16_t)n;
}

static int run_skill_band_in_range(const fs_wire_run_skill_band_t *v)
{
    return v->end <= 2u;
}

proto_status_t fs_wire_run_skill_band_unpack(fs_wire_run_skill_band_t *v, const uint8_t *d, uint16_t len)
{
    if (len != FS_WIRE_RUN_SKILL_BAND_LEN) {
        return PROTO_ERR_WIRE_LENGTH;
    }
    fs_wire_run_skill_band_t t;
    memset(&t, 0, sizeof(t));
    t.slot = (uint8_t)get_be(&d[0u], 1u);
    t.goal_scale = (uint16_t)get_be(&d[1u], 2u);
    t.time_scale = (uint16_t)get_be(&d[3u], 2u);
    t.end = (uint8_t)get_be(&d[5u], 1u);
    t.path_scale = (uint16_t)get_be(&d[6u], 2u);
    t.band_stop_ms = (uint16_t)get_be(&d[8u], 2u);
    if (!run_skill_band_in_range(&t)) {
        return PROTO_ERR_WIRE_RANGE;
    }
    *v = t;
    return PROTO_OK;
}

uint16_t fs_wire_run_skill_band_pack(const fs_wire_run_skill_band_t *v, uint8_t *out, uint16_t cap)
{
    const unsigned n = 10u;
    if (!run_skill_band_in_range(v) || n > cap) {
        return 0u;
    }
    put_be(&out[0u], v->slot, 1u);
    put_be(&out[1u], v->goal_scale, 2u);
    put_be(&out[3u], v->time_scale, 2u);
    put_be(&out[5u], v->end, 1u);
    put_be(&out[6u], v->path_scale, 2u);
    put_be(&out[8u], v->band_stop_ms, 2u);
    return (uint16_t)n;
}

static int run_periodic_in_range(const fs_wire_run_periodic_t *v)
{
    return v->end <= 2u;
}

proto_status_t fs_wire_run_periodic_unpack(fs_wire_run_periodic_t *v, const uint8_t *d, uint16_t len)
{
    if (len != FS_WIRE_RUN_PERIODIC_LEN_MIN && len != FS_WIRE_RUN_PERIODIC_LEN_MAX) {
        return PROTO_ERR_WIRE_LENGTH;
    }
    fs_wire_run_periodic_t t;
    memset(&t, 0, sizeof(t));
    t.slot = (uint8_t)get_be(&d[0u], 1u);
    t.goal_scale = (uint16_t)get_be(&d[1u], 2u);
    t.time_scale = (uint16_t)get_be(&d[3u], 2u);
    t.end = (uint8_t)get_be(&d[5u], 1u);
    t.path_scale = (uint16_t)get_be(&d[6u], 2u);
    t.cycles = (uint16_t)get_be(&d[8u], 2u);
    t.amplitude_scale = (uint16_t)get_be(&d[10u], 2u);
    if (len == FS_WIRE_RUN_PERIODIC_LEN_MAX) {
        t.has_band_stop_ms = 1u;
        t.band_stop_ms = (uint16_t)get_be(&d[12u], 2u);
    } else {
        t.band_stop_ms = 0u;
    }
    if (!run_periodic_in_range(&t)) {
        return PROTO_ERR_WIRE_RANGE;
    }
    *v = t;
    return PROTO_OK;
}

uint16_t fs_wire_run_periodic_pack(const fs_wire_run_periodic_t *v, uint8_t *out, uint16_t cap)
{
    const unsigned n = 12u + (v->has_band_stop_ms != 0u ? 2u : 0u);
    if (!run_periodic_in_range(v) || n > cap) {
        return 0u;
    }
    put_be(&out[0u], v->slot, 1u);
    put_be(&out[1u], v->goal_scale, 2u);
    put_be(&out[3u], v->time_scale, 2u);
    put_be(&out[5u], v->end, 1u);
    put_be(&out[6u], v->path_scale, 2u);
    put_be(&out[8u], v->cycles, 2u);
    put_be(&out[10u], v->amplitude_scale, 2u);
    if (v->has_band_stop_ms != 0u) { put_be(&out[12u], v->band_stop_ms, 2u); }
    return (uint16_t)n;
}

static int run_step_in_range(const fs_wire_run_step_t *v)
{
    (void)v;
    return 1;
}

proto_status_t fs_wire_run_step_unpack(fs_wire_run_step_t *v, const uint8_t *d, uint16_t len)
{
    if (len != FS_WIRE_RUN_STEP_LEN) {
        return PROTO_ERR_WIRE_LENGTH;
    }
    fs_wire_run_step_t t;
    memset(&t, 0, sizeof(t));
    t.slot = (uint8_t)get_be(&d[0u], 1u);
    t.goal_scale = (uint16_t)get_be(&d[1u], 2u);
    t.time_scale = (uint16_t)get_be(&d[3u], 2u);
    t.duration_s = (uint32_t)get_be(&d[5u], 4u);
    if (!run_step_in_range(&t)) {
        return PROTO_ERR_WIRE_RANGE;
    }
    *v = t;
    return PROTO_OK;
}

uint16_t fs_wire_run_step_pack(const fs_wire_run_step_t *v, uint8_t *out, uint16_t cap)
{
    const unsigned n = 9u;
    if (!run_step_in_range(v) || n > cap) {
        return 0u;
    }
    put_be(&out[0u], v->slot, 1u);
    put_be(&out[1u], v->goal_scale, 2u);
    put_be(&out[3u], v->time_scale, 2u);
    put_be(&out[5u], v->duration_s, 4u);
    return (uint16_t)n;
}

static int run_sequence_in_range(const fs_wire_run_sequence_t *v)
{
    if (v->n_steps < 1u || v->n_steps > 8u) {
        return 0;
    }
    for (unsigned i = 0; i < v->n_steps; i++) {
        if (!run_step_in_range(&v->steps[i])) {
            return 0;
        }
    }
    return v->end <= 2u;
}

proto_status_t fs_wire_run_sequence_unpack(fs_wire_run_sequence_t *v, const uint8_t *d, uint16_t len)
{
    if (len < FS_WIRE_RUN_SEQUENCE_LEN_MIN || len > FS_WIRE_RUN_SEQUENCE_LEN_MAX || (len - 1u) % 9u != 0u) {
        return PROTO_ERR_WIRE_LENGTH;
    }
    fs_wire_run_sequence_t t;
    memset(&t, 0, sizeof(t));
    t.end = (uint8_t)get_be(&d[0u], 1u);
    t.n_steps = (uint8_t)((len - 1u) / 9u);
    for (unsigned i = 0; i < t.n_steps; i++) {
        const unsigned at = 1u + 9u * i;
        t.steps[i].slot = (uint8_t)get_be(&d[at + 0u], 1u);
        t.steps[i].goal_scale = (uint16_t)get_be(&d[at + 1u], 2u);
        t.steps[i].time_scale = (uint16_t)get_be(&d[at + 3u], 2u);
        t.steps[i].duration_s = (uint32_t)get_be(&d[at + 5u], 4u);
    }
    if (!run_sequence_in_range(&t)) {
        return PROTO_ERR_WIRE_RANGE;
    }
    *v = t;
    return PROTO_OK;
}

uint16_t fs_wire_run_sequence_pack(const fs_wire_run_sequence_t *v, uint8_t *out, uint16_t cap)
{
    const unsigned n = 1u + 9u * (unsigned)v->n_steps;
    if (!run_sequence_in_range(v) || n > cap) {
        return 0u;
    }
    put_be(&out[0u], v->end, 1u);
    for (unsigned i = 0; i < v->n_steps; i++) {
        const unsigned at = 1u + 9u * i;
        put_be(&out[at + 0u], v->steps[i].slot, 1u);
        put_be(&out[at + 1u], v->steps[i].goal_scale, 2u);
        put_be(&out[at + 3u], v->steps[i].time_scale, 2u);
        put_be(&out[at + 5u], v->steps[i].duration_s, 4u);
    }
    return (uint16_t)n;
}

static int run_results_in_range(const fs_wire_run_results_t *v)
{
    return v->done <= 1u;
}

proto_status_t fs_wire_run_results_unpack(fs_wire_run_results_t *v, const uint8_t *d, uint16_t len)
{
    if (len != FS_WIRE_RUN_RESULTS_LEN) {
        return PROTO_ERR_WIRE_LENGTH;
    }
    fs_wire_run_results_t t;
    memset(&t, 0, sizeof(t));
    t.state = (uint8_t)get_be(&d[0u], 1u);
    t.step = (uint8_t)get_be(&d[1u], 1u);
    t.done = (uint8_t)get_be(&d[2u], 1u);
    t.fault = (uint16_t)get_be(&d[3u], 2u);
    if (!run_results_in_range(&t)) {
        return PROTO_ERR_WIRE_RANGE;
    }
    *v = t;
    return PROTO_OK;
}

uint16_t fs_wire_run_results_pack(const fs_wire_run_results_t *v, uint8_t *out, uint16_t cap)
{
    const unsigned n = 5u;
    if (!run_results_in_range(v) || n > cap) {
        return 0u;
    }
    put_be(&out[0u], v->state, 1u);
    put_be(&out[1u], v->step, 1u);
    put_be(&out[2u], v->done, 1u);
    put_be(&out[3u], v->fault, 2u);
    return (uint16_t)n;
}

static int self_test_in_range(const fs_wire_self_test_t *v)
{
    return v->status <= 1u;
}

proto_status_t fs_wire_self_test_unpack(fs_wire_self_test_t *v, const uint8_t *d, uint16_t len)
{
    if (len != FS_WIRE_SELF_TEST_LEN) {
        return PROTO_ERR_WIRE_LENGTH;
    }
    fs_wire_self_test_t t;
    memset(&t, 0, sizeof(t));
    t.status = (uint8_t)get_be(&d[0u], 1u);
    t.code = (uint16_t)get_be(&d[1u], 2u);
    if (!self_test_in_range(&t)) {
        return PROTO_ERR_WIRE_RANGE;
    }
    *v = t;
    return PROTO_OK;
}

uint16_t fs_wire_self_test_pack(const fs_wire_self_test_t *v, uint8_t *out, uint16_t cap)
{
    const unsigned n = 3u;
    if (!self_test_in_range(v) || n > cap) {
        return 0u;
    }
    put_be(&out[0u], v->status, 1u);
    put_be(&out[1u], v->code, 2u);
    return (uint16_t)n;
}

static int erase_slot_in_range(const fs_wire_erase_slot_t *v)
{
    return v->slot >= 1u &&
           v->slot <= 8u;
}

proto_status_t fs_wire_erase_slot_unpack(fs_wire_erase_slot_t *v, const uint8_t *d, uint16_t len)
{
    if (len != FS_WIRE_ERASE_SLOT_LEN) {
        return PROTO_ERR_WIRE_LENGTH;
    }
    fs_wire_erase_slot_t t;
    memset(&t, 0, sizeof(t));
    t.slot = (uint8_t)get_be(&d[0u], 1u);
    if (!erase_slot_in_range(&t)) {
        return PROTO_ERR_WIRE_RANGE;
    }
    *v = t;
    return PROTO_OK;
}

uint16_t fs_wire_erase_slot_pack(const fs_wire_erase_slot_t *v, uint8_t *out, uint16_t cap)
{
    const unsigned n = 1u;
    if (!erase_slot_in_range(v) || n > cap) {
        return 0u;
    }
    put_be(&out[0u], v->slot, 1u);
    return (uint16_t)n;
}

static int motion_key_in_range(const fs_wire_motion_key_t *v)
{
    return v->keyed <= 1u;
}

proto_status_t fs_wire_motion_key_unpack(fs_wire_motion_key_t *v, const uint8_t *d, uint16_t len)
{
    if (len != FS_WIRE_MOTION_KEY_LEN) {
        return PROTO_ERR_WIRE_LENGTH;
    }
    fs_wire_motion_key_t t;
    memset(&t, 0, sizeof(t));
    memcpy(t.nonce, &d[0u], 16u);
    t.keyed = (uint8_t)get_be(&d[16u], 1u);
    t.confirm = (uint32_t)get_be(&d[17u], 4u);
    if (!motion_key_in_range(&t)) {
        return PROTO_ERR_WIRE_RANGE;
    }
    *v = t;
    return PROTO_OK;
}

uint16_t fs_wire_motion_key_pack(const fs_wire_motion_key_t *v, uint8_t *out, uint16_t cap)
{
    const unsigned n = 21u;
    if (!motion_key_in_range(v) || n > cap) {
        return 0u;
    }
    memcpy(&out[0u], v->nonce, 16u);
    put_be(&out[16u], v->keyed, 1u);
    put_be(&out[17u], v->confirm, 4u);
    return (uint16_t)n;
}

static int motion_key_write_in_range(const fs_wire_motion_key_write_t *v)
{
    (void)v;
    return 1;
}

proto_status_t fs_wire_motion_key_write_unpack(fs_wire_motion_key_write_t *v, const uint8_t *d, uint16_t len)
{
    if (len != FS_WIRE_MOTION_KEY_WRITE_LEN) {
        return PROTO_ERR_WIRE_LENGTH;
    }
    fs_wire_motion_key_write_t t;
    memset(&t, 0, sizeof(t));
    memcpy(t.nonce, &d[0u], 16u);
    if (!motion_key_write_in_range(&t)) {
        return PROTO_ERR_WIRE_RANGE;
    }
    *v = t;
    return PROTO_OK;
}

uint16_t fs_wire_motion_key_write_pack(const fs_wire_motion_key_write_t *v, uint8_t *out, uint16_t cap)
{
    const unsigned n = 16u;
    if (!motion_key_write_in_range(v) || n > cap) {
        return 0u;
    }
    memcpy(&out[0u], v->nonce, 16u);
    return (uint16_t)n;
}

static int auth_stats_in_range(const fs_wire_auth_stats_t *v)
{
    return v->keyed <= 1u;
}

proto_status_t fs_wire_auth_stats_unpack(fs_wire_auth_stats_t *v, const uint8_t *d, uint16_t len)
{
    if (len != FS_WIRE_AUTH_STATS_LEN) {
        return PROTO_ERR_WIRE_LENGTH;
    }
    fs_wire_auth_stats_t t;
    memset(&t, 0, sizeof(t));
    t.accepted = (uint32_t)get_be(&d[0u], 4u);
    t.wrong_mac = (uint32_t)get_be(&d[4u], 4u);
    t.replayed = (uint32_t)get_be(&d[8u], 4u);
    t.no_key = (uint32_t)get_be(&d[12u], 4u);
    t.discarded = (uint32_t)get_be(&d[16u], 4u);
    t.last_refusal = (uint16_t)get_be(&d[20u], 2u);
    t.keyed = (uint8_t)get_be(&d[22u], 1u);
    t.fv_command = (uint32_t)get_be(&d[23u], 4u);
    t.fv_heartbeat = (uint32_t)get_be(&d[27u], 4u);
    t.foreign_writes = (uint32_t)get_be(&d[31u], 4u);
    if (!auth_stats_in_range(&t)) {
        return PROTO_ERR_WIRE_RANGE;
    }
    *v = t;
    return PROTO_OK;
}

uint16_t fs_wire_auth_stats_pack(const fs_wire_auth_stats_t *v, uint8_t *out, uint16_t cap)
{
    const unsigned n = 35u;
    if (!auth_stats_in_range(v) || n > cap) {
        return 0u;
    }
    put_be(&out[0u], v->accepted, 4u);
    put_be(&out[4u], v->wrong_mac, 4u);
    put_be(&out[8u], v->replayed, 4u);
    put_be(&out[12u], v->no_key, 4u);
    put_be(&out[16u], v->discarded, 4u);
    put_be(&out[20u], v->last_refusal, 2u);
    put_be(&out[22u], v->keyed, 1u);
    put_be(&out[23u], v->fv_command, 4u);
    put_be(&out[27u], v->fv_heartbeat, 4u);
    put_be(&out[31u], v->foreign_writes, 4u);
    return (uint16_t)n;
}

static int fwu_status_in_range(const fs_wire_fwu_status_t *v)
{
    return v->on_test <= 1u;
}

proto_status_t fs_wire_fwu_status_unpack(fs_wire_fwu_status_t *v, const uint8_t *d, uint16_t len)
{
    if (len != FS_WIRE_FWU_STATUS_LEN) {
        return PROTO_ERR_WIRE_LENGTH;
    }
    fs_wire_fwu_status_t t;
    memset(&t, 0, sizeof(t));
    t.running_version = (uint32_t)get_be(&d[0u], 4u);
    t.running_slot = (uint8_t)get_be(&d[4u], 1u);
    t.on_test = (uint8_t)get_be(&d[5u], 1u);
    t.active_slot = (uint8_t)get_be(&d[6u], 1u);
    t.test_slot = (uint8_t)get_be(&d[7u], 1u);
    t.path = (uint8_t)get_be(&d[8u], 1u);
    t.target = (uint8_t)get_be(&d[9u], 1u);
    t.last_refusal = (uint16_t)get_be(&d[10u], 2u);
    t.received_version = (uint32_t)get_be(&d[12u], 4u);
    t.phase = (uint8_t)get_be(&d[16u], 1u);
    if (!fwu_status_in_range(&t)) {
        return PROTO_ERR_WIRE_RANGE;
    }
    *v = t;
    return PROTO_OK;
}

uint16_t fs_wire_fwu_status_pack(const fs_wire_fwu_status_t *v, uint8_t *out, uint16_t cap)
{
    const unsigned n = 17u;
    if (!fwu_status_in_range(v) || n > cap) {
        return 0u;
    }
    put_be(&out[0u], v->running_version, 4u);
    put_be(&out[4u], v->running_slot, 1u);
    put_be(&out[5u], v->on_test, 1u);
    put_be(&out[6u], v->active_slot, 1u);
    put_be(&out[7u], v->test_slot, 1u);
    put_be(&out[8u], v->path, 1u);
    put_be(&out[9u], v->target, 1u);
    put_be(&out[10u], v->last_refusal, 2u);
    put_be(&out[12u], v->received_version, 4u);
    put_be(&out[16u], v->phase, 1u);
    return (uint16_t)n;
}

static int transfer_exit_in_range(const fs_wire_transfer_exit_t *v)
{
    (void)v;
    return 1;
}

proto_status_t fs_wire_transfer_exit_unpack(fs_wire_transfer_exit_t *v, const uint8_t *d, uint16_t len)
{
    if (len != FS_WIRE_TRANSFER_EXIT_LEN) {
        return PROTO_ERR_WIRE_LENGTH;
    }
    fs_wire_transfer_exit_t t;
    memset(&t, 0, sizeof(t));
    t.crc32 = (uint32_t)get_be(&d[0u], 4u);
    if (!transfer_exit_in_range(&t)) {
        return PROTO_ERR_WIRE_RANGE;
    }
    *v = t;
    return PROTO_OK;
}

uint16_t fs_wire_transfer_exit_pack(const fs_wire_transfer_exit_t *v, uint8_t *out, uint16_t cap)
{
    const unsigned n = 4u;
    if (!transfer_exit_in_range(v) || n > cap) {
        return 0u;
    }
    put_be(&out[0u], v->crc32, 4u);
    return (uint16_t)n;
}

static int mark_test_in_range(const fs_wire_mark_test_t *v)
{
    return v->options <= 1u;
}

proto_status_t fs_wire_mark_test_unpack(fs_wire_mark_test_t *v, const uint8_t *d, uint16_t len)
{
    if (len != FS_WIRE_MARK_TEST_LEN_MIN && len != FS_WIRE_MARK_TEST_LEN_MAX) {
        return PROTO_ERR_WIRE_LENGTH;
    }
    fs_wire_mark_test_t t;
    memset(&t, 0, sizeof(t));
    if (len == FS_WIRE_MARK_TEST_LEN_MAX) {
        t.has_options = 1u;
        t.options = (uint8_t)get_be(&d[0u], 1u);
    } else {
        t.options = 0u;
    }
    if (!mark_test_in_range(&t)) {
        return PROTO_ERR_WIRE_RANGE;
    }
    *v = t;
    return PROTO_OK;
}

uint16_t fs_wire_mark_test_pack(const fs_wire_mark_test_t *v, uint8_t *out, uint16_t cap)
{
    const unsigned n = 0u + (v->has_options != 0u ? 1u : 0u);
    if (!mark_test_in_range(v) || n > cap) {
        return 0u;
    }
    if (v->has_options != 0u) { put_be(&out[0u], v->options, 1u); }
    return (uint16_t)n;
}

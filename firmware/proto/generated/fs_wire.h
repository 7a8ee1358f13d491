/* Codecs of the device's UDS payloads (DIDs, routine start and results; docs/protocol.md):
 * big-endian, float32 for reals, scaled fields as counts of FS_WIRE_SCALE. An unpack checks
 * the length and every field's range and changes *v only when both are right; a pack
 * refuses a field outside its range.
 * generated from firmware/base/wire.toml by tools/gen_codes.py; do not edit. */
#ifndef FS_WIRE_H
#define FS_WIRE_H

#include <stdint.h>
#include "fs_wire_const.h"
#include "proto_status.h"

/** The value of a scaled field's count in the real type T: count * FS_WIRE_SCALE computed in T. */
#define FS_WIRE_REAL(T, count) ((T)(count) * (T)FS_WIRE_SCALE)

/* The records, for code that handles each the same way: X(name) per record. */
#define FS_WIRE_RECORDS(X) X(versions) X(gains) X(limits) X(comm) X(object) X(band) X(stiffness_max) X(slot_entry) X(slot_dir) X(last_transfer) X(device_state) X(contact_wait) X(fault_causes) X(run_skill) X(run_skill_band) X(run_periodic) X(run_step) X(run_sequence) X(run_results) X(self_test) X(erase_slot) X(motion_key) X(motion_key_write) X(auth_stats) X(fwu_status) X(transfer_exit) X(mark_test)

#define FS_WIRE_VERSIONS_LEN 6u
/** DID_VERSIONS: protocol and format versions. */
typedef struct {
    uint8_t proto_major;
    uint8_t proto_minor;
    uint8_t skill_format;
    uint16_t max_kernels;
    uint8_t slots;
} fs_wire_versions_t;
/** Unpack len bytes: PROTO_OK, PROTO_ERR_WIRE_LENGTH or PROTO_ERR_WIRE_RANGE (v unchanged). */
proto_status_t fs_wire_versions_unpack(fs_wire_versions_t *v, const uint8_t *d, uint16_t len);
/** Pack into out (cap bytes): the length, 0 if it does not fit or a field is out of range. */
uint16_t fs_wire_versions_pack(const fs_wire_versions_t *v, uint8_t *out, uint16_t cap);

#define FS_WIRE_GAINS_LEN 20u
/** DID_GAINS_X / DID_GAINS_Y: controller gains of one axis (validated by pfc_config_validate). */
typedef struct {
    float m_d_kg; /* kg */
    float k_d_Nspm; /* N s/m */
    float k_p_Npm; /* N/m */
    float k_f;
    float k_i_per_s; /* 1/s */
} fs_wire_gains_t;
/** Unpack len bytes: PROTO_OK, PROTO_ERR_WIRE_LENGTH or PROTO_ERR_WIRE_RANGE (v unchanged). */
proto_status_t fs_wire_gains_unpack(fs_wire_gains_t *v, const uint8_t *d, uint16_t len);
/** Pack into out (cap bytes): the length, 0 if it does not fit or a field is out of range. */
uint16_t fs_wire_gains_pack(const fs_wire_gains_t *v, uint8_t *out, uint16_t cap);

#define FS_WIRE_LIMITS_LEN 24u
/** DID_LIMITS_X / DID_LIMITS_Y: safety limits of one axis (validated by saf_config_validate). */
typedef struct {
    float force_max_N; /* N */
    float slew_max_N; /* N per tick */
    float pos_min_m; /* m */
    float pos_max_m; /* m */
    float vel_max_mps; /* m/s */
    float contact_force_max_N; /* N */
} fs_wire_limits_t;
/** Unpack len bytes: PROTO_OK, PROTO_ERR_WIRE_LENGTH or PROTO_ERR_WIRE_RANGE (v unchanged). */
proto_status_t fs_wire_limits_unpack(fs_wire_limits_t *v, const uint8_t *d, uint16_t len);
/** Pack into out (cap bytes): the length, 0 if it does not fit or a field is out of range. */
uint16_t fs_wire_limits_pack(const fs_wire_limits_t *v, uint8_t *out, uint16_t cap);

#define FS_WIRE_COMM_LEN 3u
/** DID_COMM: telemetry period in TEACH/EXECUTE and host-silence timeout. */
typedef struct {
    uint8_t telemetry_period_ms; /* ms */
    uint16_t host_timeout_ms; /* ms */
} fs_wire_comm_t;
/** Unpack len bytes: PROTO_OK, PROTO_ERR_WIRE_LENGTH or PROTO_ERR_WIRE_RANGE (v unchanged). */
proto_status_t fs_wire_comm_unpack(fs_wire_comm_t *v, const uint8_t *d, uint16_t len);
/** Pack into out (cap bytes): the length, 0 if it does not fit or a field is out of range. */
uint16_t fs_wire_comm_pack(const fs_wire_comm_t *v, uint8_t *out, uint16_t cap);

#define FS_WIRE_OBJECT_LEN 25u
/** DID_OBJECT: the object model of the execution reference. */
typedef struct {
    uint8_t use_model;
    float m_v_kg; /* kg */
    float d_v_Nspm; /* N s/m */
    float k1_Npm; /* N/m */
    float k2_Npm; /* N/m */
    float layer_depth_m; /* m */
    float surface_m; /* m */
} fs_wire_object_t;
/** Unpack len bytes: PROTO_OK, PROTO_ERR_WIRE_LENGTH or PROTO_ERR_WIRE_RANGE (v unchanged). */
proto_status_t fs_wire_object_unpack(fs_wire_object_t *v, const uint8_t *d, uint16_t len);
/** Pack into out (cap bytes): the length, 0 if it does not fit or a field is out of range. */
uint16_t fs_wire_object_pack(const fs_wire_object_t *v, uint8_t *out, uint16_t cap);

#define FS_WIRE_BAND_LEN 21u
/** The count of band.max_widths for a value v of the real type T (nearest step, 0..65535). */
#define FS_WIRE_BAND_MAX_WIDTHS_COUNT(T, v) ((uint16_t)(!((v) > (T)0.0) ? 0u : ((v) >= (T)65.535) ? 65535u : (uint32_t)((v) * (T)FS_WIRE_SCALE_STEPS + (T)0.5)))
/** DID_BAND: the demonstrated band's check of the running or last execution. */
typedef struct {
    uint32_t checked_ms; /* ms */
    uint32_t outside_ms; /* ms */
    uint32_t longest_ms; /* ms */
    uint16_t max_widths; /* count of FS_WIRE_SCALE */
    uint32_t first_ms; /* ms */
    uint8_t outside;
    uint16_t stop_ms; /* ms */
} fs_wire_band_t;
/** Unpack len bytes: PROTO_OK, PROTO_ERR_WIRE_LENGTH or PROTO_ERR_WIRE_RANGE (v unchanged). */
proto_status_t fs_wire_band_unpack(fs_wire_band_t *v, const uint8_t *d, uint16_t len);
/** Pack into out (cap bytes): the length, 0 if it does not fit or a field is out of range. */
uint16_t fs_wire_band_pack(const fs_wire_band_t *v, uint8_t *out, uint16_t cap);

#define FS_WIRE_STIFFNESS_MAX_LEN 4u
/** DID_STIFFNESS_MAX: the highest nominal skill stiffness the device accepts. */
typedef struct {
    float stiffness_max_Npm; /* N/m */
} fs_wire_stiffness_max_t;
/** Unpack len bytes: PROTO_OK, PROTO_ERR_WIRE_LENGTH or PROTO_ERR_WIRE_RANGE (v unchanged). */
proto_status_t fs_wire_stiffness_max_unpack(fs_wire_stiffness_max_t *v, const uint8_t *d, uint16_t len);
/** Pack into out (cap bytes): the length, 0 if it does not fit or a field is out of range. */
uint16_t fs_wire_stiffness_max_pack(const fs_wire_stiffness_max_t *v, uint8_t *out, uint16_t cap);

#define FS_WIRE_SLOT_ENTRY_LEN 16u
/** one slot of DID_SLOT_DIR (all zero for an empty slot). */
typedef struct {
    uint8_t valid;
    uint32_t length; /* bytes */
    uint32_t crc32;
    uint16_t n_kernels;
    float duration_s; /* s */
    uint8_t end;
} fs_wire_slot_entry_t;
/** Unpack len bytes: PROTO_OK, PROTO_ERR_WIRE_LENGTH or PROTO_ERR_WIRE_RANGE (v unchanged). */
proto_status_t fs_wire_slot_entry_unpack(fs_wire_slot_entry_t *v, const uint8_t *d, uint16_t len);
/** Pack into out (cap bytes): the length, 0 if it does not fit or a field is out of range. */
uint16_t fs_wire_slot_entry_pack(const fs_wire_slot_entry_t *v, uint8_t *out, uint16_t cap);

#define FS_WIRE_SLOT_DIR_LEN_MIN 1u
#define FS_WIRE_SLOT_DIR_LEN_MAX 129u
/** DID_SLOT_DIR: the slot directory. */
typedef struct {
    uint8_t count;
    uint8_t n_entries; /* 0..8 */
    fs_wire_slot_entry_t entries[8];
} fs_wire_slot_dir_t;
/** Unpack len bytes: PROTO_OK, PROTO_ERR_WIRE_LENGTH or PROTO_ERR_WIRE_RANGE (v unchanged). */
proto_status_t fs_wire_slot_dir_unpack(fs_wire_slot_dir_t *v, const uint8_t *d, uint16_t len);
/** Pack into out (cap bytes): the length, 0 if it does not fit or a field is out of range. */
uint16_t fs_wire_slot_dir_pack(const fs_wire_slot_dir_t *v, uint8_t *out, uint16_t cap);

#define FS_WIRE_LAST_TRANSFER_LEN 2u
/** DID_LAST_TRANSFER: status of the last download (0 ok, a code, TRANSFER_*). */
typedef struct {
    uint16_t status;
} fs_wire_last_transfer_t;
/** Unpack len bytes: PROTO_OK, PROTO_ERR_WIRE_LENGTH or PROTO_ERR_WIRE_RANGE (v unchanged). */
proto_status_t fs_wire_last_transfer_unpack(fs_wire_last_transfer_t *v, const uint8_t *d, uint16_t len);
/** Pack into out (cap bytes): the length, 0 if it does not fit or a field is out of range. */
uint16_t fs_wire_last_transfer_pack(const fs_wire_last_transfer_t *v, uint8_t *out, uint16_t cap);

#define FS_WIRE_DEVICE_STATE_LEN 9u
/** DID_DEVICE_STATE: state, latched fault, active slot, sequence step, tick. */
typedef struct {
    uint8_t state;
    uint16_t fault;
    uint8_t slot;
    uint8_t step;
    uint32_t tick;
} fs_wire_device_state_t;
/** Unpack len bytes: PROTO_OK, PROTO_ERR_WIRE_LENGTH or PROTO_ERR_WIRE_RANGE (v unchanged). */
proto_status_t fs_wire_device_state_unpack(fs_wire_device_state_t *v, const uint8_t *d, uint16_t len);
/** Pack into out (cap bytes): the length, 0 if it does not fit or a field is out of range. */
uint16_t fs_wire_device_state_pack(const fs_wire_device_state_t *v, uint8_t *out, uint16_t cap);

#define FS_WIRE_CONTACT_WAIT_LEN 8u
/** The count of contact_wait.rate for a value v of the real type T (nearest step, 0..1000). */
#define FS_WIRE_CONTACT_WAIT_RATE_COUNT(T, v) ((uint16_t)(!((v) > (T)0.0) ? 0u : ((v) >= (T)1.0) ? 1000u : (uint32_t)((v) * (T)FS_WIRE_SCALE_STEPS + (T)0.5)))
/** DID_CONTACT_WAIT: the contact wait of the running or last execution. */
typedef struct {
    uint32_t hold_ms; /* ms */
    uint16_t losses;
    uint16_t rate; /* count of FS_WIRE_SCALE */
} fs_wire_contact_wait_t;
/** Unpack len bytes: PROTO_OK, PROTO_ERR_WIRE_LENGTH or PROTO_ERR_WIRE_RANGE (v unchanged). */
proto_status_t fs_wire_contact_wait_unpack(fs_wire_contact_wait_t *v, const uint8_t *d, uint16_t len);
/** Pack into out (cap bytes): the length, 0 if it does not fit or a field is out of range. */
uint16_t fs_wire_contact_wait_pack(const fs_wire_contact_wait_t *v, uint8_t *out, uint16_t cap);

#define FS_WIRE_FAULT_CAUSES_LEN 8u
/** DID_FAULT_CAUSES: latched faults and the causes present at the last tick (bit n: fault 500 + n). */
typedef struct {
    uint32_t latched_mask;
    uint32_t present_mask;
} fs_wire_fault_causes_t;
/** Unpack len bytes: PROTO_OK, PROTO_ERR_WIRE_LENGTH or PROTO_ERR_WIRE_RANGE (v unchanged). */
proto_status_t fs_wire_fault_causes_unpack(fs_wire_fault_causes_t *v, const uint8_t *d, uint16_t len);
/** Pack into out (cap bytes): the length, 0 if it does not fit or a field is out of range. */
uint16_t fs_wire_fault_causes_pack(const fs_wire_fault_causes_t *v, uint8_t *out, uint16_t cap);

#define FS_WIRE_RUN_SKILL_LEN_MIN 6u
#define FS_WIRE_RUN_SKILL_LEN_MAX 8u
/** The count of run_skill.goal_scale for a value v of the real type T (nearest step, 0..65535). */
#define FS_WIRE_RUN_SKILL_GOAL_SCALE_COUNT(T, v) ((uint16_t)(!((v) > (T)0.0) ? 0u : ((v) >= (T)65.535) ? 65535u : (uint32_t)((v) * (T)FS_WIRE_SCALE_STEPS + (T)0.5)))
/** The count of run_skill.time_scale for a value v of the real type T (nearest step, 0..65535). */
#define FS_WIRE_RUN_SKILL_TIME_SCALE_COUNT(T, v) ((uint16_t)(!((v) > (T)0.0) ? 0u : ((v) >= (T)65.535) ? 65535u : (uint32_t)((v) * (T)FS_WIRE_SCALE_STEPS + (T)0.5)))
/** The count of run_skill.path_scale for a value v of the real type T (nearest step, 0..65535). */
#define FS_WIRE_RUN_SKILL_PATH_SCALE_COUNT(T, v) ((uint16_t)(!((v) > (T)0.0) ? 0u : ((v) >= (T)65.535) ? 65535u : (uint32_t)((v) * (T)FS_WIRE_SCALE_STEPS + (T)0.5)))
/** RID_RUN_SKILL start: one skill (end 0 the skill's own, 1 hold, 2 release). */
typedef struct {
    uint8_t slot;
    uint16_t goal_scale; /* count of FS_WIRE_SCALE */
    uint16_t time_scale; /* count of FS_WIRE_SCALE */
    uint8_t end;
    uint16_t path_scale; /* count of FS_WIRE_SCALE */
    uint8_t has_path_scale; /* 0: absent (unpack: the default 1) */
} fs_wire_run_skill_t;
/** Unpack len bytes: PROTO_OK, PROTO_ERR_WIRE_LENGTH or PROTO_ERR_WIRE_RANGE (v unchanged). */
proto_status_t fs_wire_run_skill_unpack(fs_wire_run_skill_t *v, const uint8_t *d, uint16_t len);
/** Pack into out (cap bytes): the length, 0 if it does not fit or a field is out of range. */
uint16_t fs_wire_run_skill_pack(const fs_wire_run_skill_t *v, uint8_t *out, uint16_t cap);

#define FS_WIRE_RUN_SKILL_BAND_LEN 10u
/** The count of run_skill_band.goal_scale for a value v of the real type T (nearest step, 0..65535). */
#define FS_WIRE_RUN_SKILL_BAND_GOAL_SCALE_COUNT(T, v) ((uint16_t)(!((v) > (T)0.0) ? 0u : ((v) >= (T)65.535) ? 65535u : (uint32_t)((v) * (T)FS_WIRE_SCALE_STEPS + (T)0.5)))
/** The count of run_skill_band.time_scale for a value v of the real type T (nearest step, 0..65535). */
#define FS_WIRE_RUN_SKILL_BAND_TIME_SCALE_COUNT(T, v) ((uint16_t)(!((v) > (T)0.0) ? 0u : ((v) >= (T)65.535) ? 65535u : (uint32_t)((v) * (T)FS_WIRE_SCALE_STEPS + (T)0.5)))
/** The count of run_skill_band.path_scale for a value v of the real type T (nearest step, 0..65535). */
#define FS_WIRE_RUN_SKILL_BAND_PATH_SCALE_COUNT(T, v) ((uint16_t)(!((v) > (T)0.0) ? 0u : ((v) >= (T)65.535) ? 65535u : (uint32_t)((v) * (T)FS_WIRE_SCALE_STEPS + (T)0.5)))
/** RID_RUN_SKILL start with a band stop time: run_skill's fields with the path scale, then the ms outside the demonstrated band (consecutive) that stop the run with FLT_BAND (0: report only; the device tells the starts by their length). */
typedef struct {
    uint8_t slot;
    uint16_t goal_scale; /* count of FS_WIRE_SCALE */
    uint16_t time_scale; /* count of FS_WIRE_SCALE */
    uint8_t end;
    uint16_t path_scale; /* count of FS_WIRE_SCALE */
    uint16_t band_stop_ms; /* ms */
} fs_wire_run_skill_band_t;
/** Unpack len bytes: PROTO_OK, PROTO_ERR_WIRE_LENGTH or PROTO_ERR_WIRE_RANGE (v unchanged). */
proto_status_t fs_wire_run_skill_band_unpack(fs_wire_run_skill_band_t *v, const uint8_t *d, uint16_t len);
/** Pack into out (cap bytes): the length, 0 if it does not fit or a field is out of range. */
uint16_t fs_wire_run_skill_band_pack(const fs_wire_run_skill_band_t *v, uint8_t *out, uint16_t cap);

#define FS_WIRE_RUN_PERIODIC_LEN_MIN 12u
#define FS_WIRE_RUN_PERIODIC_LEN_MAX 14u
/** The count of run_periodic.goal_scale for a value v of the real type T (nearest step, 0..65535). */
#define FS_WIRE_RUN_PERIODIC_GOAL_SCALE_COUNT(T, v) ((uint16_t)(!((v) > (T)0.0) ? 0u : ((v) >= (T)65.535) ? 65535u : (uint32_t)((v) * (T)FS_WIRE_SCALE_STEPS + (T)0.5)))
/** The count of run_periodic.time_scale for a value v of the real type T (nearest step, 0..65535). */
#define FS_WIRE_RUN_PERIODIC_TIME_SCALE_COUNT(T, v) ((uint16_t)(!((v) > (T)0.0) ? 0u : ((v) >= (T)65.535) ? 65535u : (uint32_t)((v) * (T)FS_WIRE_SCALE_STEPS + (T)0.5)))
/** The count of run_periodic.path_scale for a value v of the real type T (nearest step, 0..65535). */
#define FS_WIRE_RUN_PERIODIC_PATH_SCALE_COUNT(T, v) ((uint16_t)(!((v) > (T)0.0) ? 0u : ((v) >= (T)65.535) ? 65535u : (uint32_t)((v) * (T)FS_WIRE_SCALE_STEPS + (T)0.5)))
/** The count of run_periodic.amplitude_scale for a value v of the real type T (nearest step, 0..65535). */
#define FS_WIRE_RUN_PERIODIC_AMPLITUDE_SCALE_COUNT(T, v) ((uint16_t)(!((v) > (T)0.0) ? 0u : ((v) >= (T)65.535) ? 65535u : (uint32_t)((v) * (T)FS_WIRE_SCALE_STEPS + (T)0.5)))
/** RID_RUN_SKILL start of a periodic skill: run_skill's fields with the path scale, then the periods to run (0: until stopped) and the stroke's amplitude scale, optionally the band stop time (the device tells the two starts by their length). */
typedef struct {
    uint8_t slot;
    uint16_t goal_scale; /* count of FS_WIRE_SCALE */
    uint16_t time_scale; /* count of FS_WIRE_SCALE */
    uint8_t end;
    uint16_t path_scale; /* count of FS_WIRE_SCALE */
    uint16_t cycles;
    uint16_t amplitude_scale; /* count of FS_WIRE_SCALE */
    uint16_t band_stop_ms; /* ms */
    uint8_t has_band_stop_ms; /* 0: absent (unpack: the default 0) */
} fs_wire_run_periodic_t;
/** Unpack len bytes: PROTO_OK, PROTO_ERR_WIRE_LENGTH or PROTO_ERR_WIRE_RANGE (v unchanged). */
proto_status_t fs_wire_run_periodic_unpack(fs_wire_run_periodic_t *v, const uint8_t *d, uint16_t len);
/** Pack into out (cap bytes): the length, 0 if it does not fit or a field is out of range. */
uint16_t fs_wire_run_periodic_pack(const fs_wire_run_periodic_t *v, uint8_t *out, uint16_t cap);

#define FS_WIRE_RUN_STEP_LEN 9u
/** The count of run_step.goal_scale for a value v of the real type T (nearest step, 0..65535). */
#define FS_WIRE_RUN_STEP_GOAL_SCALE_COUNT(T, v) ((uint16_t)(!((v) > (T)0.0) ? 0u : ((v) >= (T)65.535) ? 65535u : (uint32_t)((v) * (T)FS_WIRE_SCALE_STEPS + (T)0.5)))
/** The count of run_step.time_scale for a value v of the real type T (nearest step, 0..65535). */
#define FS_WIRE_RUN_STEP_TIME_SCALE_COUNT(T, v) ((uint16_t)(!((v) > (T)0.0) ? 0u : ((v) >= (T)65.535) ? 65535u : (uint32_t)((v) * (T)FS_WIRE_SCALE_STEPS + (T)0.5)))
/** The count of run_step.duration_s for a value v of the real type T (nearest step, 0..4294967295). */
#define FS_WIRE_RUN_STEP_DURATION_S_COUNT(T, v) ((uint32_t)(!((v) > (T)0.0) ? 0u : ((v) >= (T)4294967.295) ? 4294967295u : (uint32_t)((v) * (T)FS_WIRE_SCALE_STEPS + (T)0.5)))
/** one step of a RUN_SEQUENCE start (duration 0: the skill's T times its time scale). */
typedef struct {
    uint8_t slot;
    uint16_t goal_scale; /* count of FS_WIRE_SCALE */
    uint16_t time_scale; /* count of FS_WIRE_SCALE */
    uint32_t duration_s; /* count of FS_WIRE_SCALE s */
} fs_wire_run_step_t;
/** Unpack len bytes: PROTO_OK, PROTO_ERR_WIRE_LENGTH or PROTO_ERR_WIRE_RANGE (v unchanged). */
proto_status_t fs_wire_run_step_unpack(fs_wire_run_step_t *v, const uint8_t *d, uint16_t len);
/** Pack into out (cap bytes): the length, 0 if it does not fit or a field is out of range. */
uint16_t fs_wire_run_step_pack(const fs_wire_run_step_t *v, uint8_t *out, uint16_t cap);

#define FS_WIRE_RUN_SEQUENCE_LEN_MIN 10u
#define FS_WIRE_RUN_SEQUENCE_LEN_MAX 73u
/** RID_RUN_SEQUENCE start: the end policy, then 1..SEQUENCE_STEPS_MAX steps. */
typedef struct {
    uint8_t end;
    uint8_t n_steps; /* 1..8 */
    fs_wire_run_step_t steps[8];
} fs_wire_run_sequence_t;
/** Unpack len bytes: PROTO_OK, PROTO_ERR_WIRE_LENGTH or PROTO_ERR_WIRE_RANGE (v unchanged). */
proto_status_t fs_wire_run_sequence_unpack(fs_wire_run_sequence_t *v, const uint8_t *d, uint16_t len);
/** Pack into out (cap bytes): the length, 0 if it does not fit or a field is out of range. */
uint16_t fs_wire_run_sequence_pack(const fs_wire_run_sequence_t *v, uint8_t *out, uint16_t cap);

#define FS_WIRE_RUN_RESULTS_LEN 5u
/** RID_RUN_SKILL / RID_RUN_SEQUENCE results. */
typedef struct {
    uint8_t state;
    uint8_t step;
    uint8_t done;
    uint16_t fault;
} fs_wire_run_results_t;
/** Unpack len bytes: PROTO_OK, PROTO_ERR_WIRE_LENGTH or PROTO_ERR_WIRE_RANGE (v unchanged). */
proto_status_t fs_wire_run_results_unpack(fs_wire_run_results_t *v, const uint8_t *d, uint16_t len);
/** Pack into out (cap bytes): the length, 0 if it does not fit or a field is out of range. */
uint16_t fs_wire_run_results_pack(const fs_wire_run_results_t *v, uint8_t *out, uint16_t cap);

#define FS_WIRE_SELF_TEST_LEN 3u
/** RID_SELF_TEST results: 0 pass / 1 fail, the first failing check's code. */
typedef struct {
    uint8_t status;
    uint16_t code;
} fs_wire_self_test_t;
/** Unpack len bytes: PROTO_OK, PROTO_ERR_WIRE_LENGTH or PROTO_ERR_WIRE_RANGE (v unchanged). */
proto_status_t fs_wire_self_test_unpack(fs_wire_self_test_t *v, const uint8_t *d, uint16_t len);
/** Pack into out (cap bytes): the length, 0 if it does not fit or a field is out of range. */
uint16_t fs_wire_self_test_pack(const fs_wire_self_test_t *v, uint8_t *out, uint16_t cap);

#define FS_WIRE_ERASE_SLOT_LEN 1u
/** RID_ERASE_SLOT start. */
typedef struct {
    uint8_t slot;
} fs_wire_erase_slot_t;
/** Unpack len bytes: PROTO_OK, PROTO_ERR_WIRE_LENGTH or PROTO_ERR_WIRE_RANGE (v unchanged). */
proto_status_t fs_wire_erase_slot_unpack(fs_wire_erase_slot_t *v, const uint8_t *d, uint16_t len);
/** Pack into out (cap bytes): the length, 0 if it does not fit or a field is out of range. */
uint16_t fs_wire_erase_slot_pack(const fs_wire_erase_slot_t *v, uint8_t *out, uint16_t cap);

#define FS_WIRE_MOTION_KEY_LEN 21u
/** DID_MOTION_KEY read: the device nonce of the motion key in use (zeros before any), whether a key is established, and the key's confirmation (the first 4 bytes of AES-CMAC(key, SECOC_CONFIRM_LABEL) big-endian, 0 without a key): a host whose own key gives another value re-establishes the session. */
typedef struct {
    uint8_t nonce[16];
    uint8_t keyed;
    uint32_t confirm;
} fs_wire_motion_key_t;
/** Unpack len bytes: PROTO_OK, PROTO_ERR_WIRE_LENGTH or PROTO_ERR_WIRE_RANGE (v unchanged). */
proto_status_t fs_wire_motion_key_unpack(fs_wire_motion_key_t *v, const uint8_t *d, uint16_t len);
/** Pack into out (cap bytes): the length, 0 if it does not fit or a field is out of range. */
uint16_t fs_wire_motion_key_pack(const fs_wire_motion_key_t *v, uint8_t *out, uint16_t cap);

#define FS_WIRE_MOTION_KEY_WRITE_LEN 16u
/** DID_MOTION_KEY write: the host nonce of a new host session. */
typedef struct {
    uint8_t nonce[16];
} fs_wire_motion_key_write_t;
/** Unpack len bytes: PROTO_OK, PROTO_ERR_WIRE_LENGTH or PROTO_ERR_WIRE_RANGE (v unchanged). */
proto_status_t fs_wire_motion_key_write_unpack(fs_wire_motion_key_write_t *v, const uint8_t *d, uint16_t len);
/** Pack into out (cap bytes): the length, 0 if it does not fit or a field is out of range. */
uint16_t fs_wire_motion_key_write_pack(const fs_wire_motion_key_write_t *v, uint8_t *out, uint16_t cap);

#define FS_WIRE_AUTH_STATS_LEN 35u
/** DID_AUTH_STATS: authenticated host frames accepted and refused, the last refusal's code, the freshness values last accepted, UDS writes refused because the other tester owns the session. */
typedef struct {
    uint32_t accepted;
    uint32_t wrong_mac;
    uint32_t replayed;
    uint32_t no_key;
    uint32_t discarded;
    uint16_t last_refusal;
    uint8_t keyed;
    uint32_t fv_command;
    uint32_t fv_heartbeat;
    uint32_t foreign_writes;
} fs_wire_auth_stats_t;
/** Unpack len bytes: PROTO_OK, PROTO_ERR_WIRE_LENGTH or PROTO_ERR_WIRE_RANGE (v unchanged). */
proto_status_t fs_wire_auth_stats_unpack(fs_wire_auth_stats_t *v, const uint8_t *d, uint16_t len);
/** Pack into out (cap bytes): the length, 0 if it does not fit or a field is out of range. */
uint16_t fs_wire_auth_stats_pack(const fs_wire_auth_stats_t *v, uint8_t *out, uint16_t cap);

#define FS_WIRE_FWU_STATUS_LEN 17u
/** DID_FWU_STATUS: the update status (fwu_status): the running image's version (0 when none runs), its slot, whether it runs on test (not confirmed yet), the active slot, the slot marked for a test boot, the boot path, the device's target id, the last refusal's code, the received image's version, the update phase. */
typedef struct {
    uint32_t running_version;
    uint8_t running_slot;
    uint8_t on_test;
    uint8_t active_slot;
    uint8_t test_slot;
    uint8_t path;
    uint8_t target;
    uint16_t last_refusal;
    uint32_t received_version;
    uint8_t phase;
} fs_wire_fwu_status_t;
/** Unpack len bytes: PROTO_OK, PROTO_ERR_WIRE_LENGTH or PROTO_ERR_WIRE_RANGE (v unchanged). */
proto_status_t fs_wire_fwu_status_unpack(fs_wire_fwu_status_t *v, const uint8_t *d, uint16_t len);
/** Pack into out (cap bytes): the length, 0 if it does not fit or a field is out of range. */
uint16_t fs_wire_fwu_status_pack(const fs_wire_fwu_status_t *v, uint8_t *out, uint16_t cap);

#define FS_WIRE_TRANSFER_EXIT_LEN 4u
/** RequestTransferExit's positive answer after a download: the CRC-32 of the received image (the host compares its own). */
typedef struct {
    uint32_t crc32;
} fs_wire_transfer_exit_t;
/** Unpack len bytes: PROTO_OK, PROTO_ERR_WIRE_LENGTH or PROTO_ERR_WIRE_RANGE (v unchanged). */
proto_status_t fs_wire_transfer_exit_unpack(fs_wire_transfer_exit_t *v, const uint8_t *d, uint16_t len);
/** Pack into out (cap bytes): the length, 0 if it does not fit or a field is out of range. */
uint16_t fs_wire_transfer_exit_pack(const fs_wire_transfer_exit_t *v, uint8_t *out, uint16_t cap);

#define FS_WIRE_MARK_TEST_LEN_MIN 0u
#define FS_WIRE_MARK_TEST_LEN_MAX 1u
/** FWU_RID_MARK_TEST start: the options (bit 0: allow a downgrade, FWU_OPT_ALLOW_DOWNGRADE); absent: none. */
typedef struct {
    uint8_t options;
    uint8_t has_options; /* 0: absent (unpack: the default 0) */
} fs_wire_mark_test_t;
/** Unpack len bytes: PROTO_OK, PROTO_ERR_WIRE_LENGTH or PROTO_ERR_WIRE_RANGE (v unchanged). */
proto_status_t fs_wire_mark_test_unpack(fs_wire_mark_test_t *v, const uint8_t *d, uint16_t len);
/** Pack into out (cap bytes): the length, 0 if it does not fit or a field is out of range. */
uint16_t fs_wire_mark_test_pack(const fs_wire_mark_test_t *v, uint8_t *out, uint16_t cap);

#endif /* FS_WIRE_H */

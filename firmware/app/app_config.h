/* Configuring and driving the device from inside its process (the simulator, tests): the
 * configuration app_config_t, the HostCommand modes, a run request to the one motion path, the
 * host session's motion key, and read-only views of the device state. Everything else of app_t
 * stays private to firmware/app (app_internal.h). A port's main needs only app.h.
 *
 *     app_config_default(&cfg);
 *     cfg.render_carriage = 1u;        (any field below, before app_init)
 *     app_t *app = app_device();
 *     app_init(app, &cfg);
 *     ... app_tick(app, false); app_run_start(app, &req); app_state(app) ... */
#ifndef APP_CONFIG_H
#define APP_CONFIG_H

#include <stdbool.h>
#include <stdint.h>
#include "app.h"
#include "boot.h"
#include "fs_exec.h"
#include "fs_real.h"
#include "fs_wire_const.h"
#include "pfc.h"
#include "saf.h"
#include "skill.h"

#define APP_TICK_US FS_TICK_US            /* the tick period (wire.toml) */
#define APP_TICK_S ((fs_real_t)FS_TICK_S) /* the same in seconds, the control law's dt */

/** HostCommand.Mode values. */
typedef enum {
    APP_CMD_NONE = 0,
    APP_CMD_IDLE = 1,
    APP_CMD_TEACH = 2,
    APP_CMD_EXECUTE = 3,
    APP_CMD_CLEAR_FAULT = 4,
    APP_CMD_RUN_OPTIONS = 5 /* time scale and end policy of the EXECUTE that follows */
} app_cmd_mode_t;

/** Device configuration (factory defaults from app_config_default, changed by UDS writes). */
struct app_config {
    uint8_t node;                     /* 0..PROTO_NODE_MAX: ids = base + node */
    uint8_t render_carriage;          /* 1: render m_d by admittance (real carriage); 0: the
                                          drive is dynamics-compensated (ideal plant) */
    pfc_axis_gains_t gains[PFC_AXES]; /* TEACH rendering (m_d) and the y axis */
    exec_config_t exec;               /* object model, phase stopping (gains come from the skill) */
    exec_render_cfg_t render;
    saf_config_t saf;
    fs_real_t vel_cutoff_Hz;
    uint8_t telemetry_period_ms; /* in TEACH/EXECUTE and through a fault, 1..255 */
    fs_real_t stiffness_max_Npm; /* skills stiffer than this are refused (227), DID 0x0140 */
    uint8_t uds_tx_dl;           /* UDS ISO-TP frames: 8 classic CAN (default), 64 CAN FD */
    bool uds_brs;                /* CAN FD: bit-rate switch in the data phase */
};

/** The default skill stiffness limit (DID 0x0140, 227 above it) of a drive: the highest nominal
 *  stiffness at which both stiff HIL profiles track within 5 % RMS without a fault
 *  (bench/stiffness/stiffness_limit.py, docs/hil.md): FS_STIFFNESS_MAX_NPM for a
 *  dynamics-compensated drive (render_carriage 0), FS_STIFFNESS_MAX_RENDERED_NPM for a carriage
 *  rendered by admittance (render_carriage 1; 13-15 % at 1e5 N/m). */
fs_real_t app_stiffness_max_default_Npm(uint8_t render_carriage);

/** Where a run request came from (HostCommand frame, UDS routine, or the simulator itself). */
typedef enum {
    APP_RUN_FROM_COMMAND = 0,
    APP_RUN_FROM_ROUTINE = 1,
    APP_RUN_FROM_LOCAL = 2
} app_run_source_t;

/** One step of a run: slot 1..APP_N_SLOTS, goal and time scale, duration_s (<= 0: the skill's
 *  T*time_scale) and path scale (the y path of a skill with a y DMP; 1: as demonstrated). */
typedef struct {
    uint8_t slot;
    fs_real_t goal_scale;
    fs_real_t time_scale;
    fs_real_t duration_s;
    fs_real_t path_scale;
    fs_real_t amplitude_scale; /* a periodic skill's stroke scale */
    uint16_t cycles; /* a periodic skill's periods when duration_s is 0 (0: until stopped) */
} app_run_step_t;

/** A request to start motion, decoded from any source (app_run.c). */
typedef struct {
    app_run_source_t source;
    uint8_t n_steps; /* 1..EXEC_MAX_STEPS */
    uint8_t end;     /* 0 each skill's own end policy, 1 hold, 2 release */
    /* ms outside the demonstrated band (consecutive) that stop the run with FLT_BAND; 0: the
     * check only reports (DID_BAND, the telemetry's BandOutside) */
    uint16_t band_stop_ms;
    app_run_step_t step[EXEC_MAX_STEPS];
} app_run_request_t;

/** Start a run: app_run_authorize, then the end policy and step count (0x31), the state (IDLE,
 *  no commit running: 0x22), each step's slot, scales, stiffness, force and path limits (0x31,
 *  the check's code 224-227 in last_run_status), then EXECUTE. Returns a UDS NRC (0 started). */
uint8_t app_run_start(app_t *app, const app_run_request_t *req);

/** Establish the motion key of a host session from its nonce at once (the simulator's and the
 *  tests' own host session; the DID 0x0302 write runs it in slices). Returns a UDS NRC (0 ok). */
uint8_t app_motion_key(app_t *app, const uint8_t *host_nonce, uint16_t len);

/** The count of ticks since app_init. */
uint32_t app_tick_count(const app_t *app);

/** The skill's force reference f_hat of the last tick (N, 0 outside EXECUTE). */
fs_real_t app_force_ref_N(const app_t *app);

/** The cached skill of slot 1..FS_SLOT_COUNT, NULL for an empty slot. */
const skill_t *app_slot_skill(const app_t *app, uint8_t slot);

/** The CRC-32 field of slot 1..FS_SLOT_COUNT's image, 0 for an empty slot. */
uint32_t app_slot_crc(const app_t *app, uint8_t slot);

/** The bootloader's view of the firmware slots (the running slot, its header, its state). */
const boot_t *app_boot(const app_t *app);

/** The firmware slots' flash layout the device was started with. */
const boot_config_t *app_boot_config(const app_t *app);

/** The check's code of the last start request (0, or 224-227 of a refused step). */
uint16_t app_last_run_status(const app_t *app);

/** The count of frames the device could not queue (it keeps counting: a pointer for monitors). */
const uint32_t *app_tx_dropped(const app_t *app);

/** The device nonce of the motion key in use (SECOC_NONCE_LEN bytes). */
const uint8_t *app_motion_nonce(const app_t *app);

/** True while a UDS transfer or a request answered 0x78 (a commit) runs. */
bool app_transfer_busy(const app_t *app);

/** True when the active (or last) download is a firmware image, not a skill. */
bool app_transfer_is_firmware(const app_t *app);

#endif /* APP_CONFIG_H */

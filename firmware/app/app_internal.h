/* The device application's internals (the public surface is app.h): the whole device state
 * app_t, its configuration app_config_t and the functions its own modules (app.c, app_uds.c)
 * share. Included by firmware/app and by white-box users (the simulator, tests, fuzzers);
 * tools/check_layers.py keeps every other firmware module on app.h.
 *
 * The device application: state machine BOOT -> IDLE -> TEACH | EXECUTE -> FAULT
 * (latched), the 1 kHz tick, the cyclic frames of forceskill.dbc (status, telemetry, emergency;
 * host command and heartbeat with E2E checks) and the UDS server on ISO-TP with its device hooks
 * (app_uds.c: data identifiers, routines, skill download/upload into slots).
 * Hardware only through hal.h. No heap; everything lives in app_t (one static instance).
 *
 * Per tick (app_tick): CAN rx (bounded) -> UDS -> sensors -> commands/state -> control
 * (TEACH: render m_d; EXECUTE: fs_exec sequence) -> safety supervisor (limits, faults, safe
 * stop) -> actuator -> emergency/status/telemetry frames. */
#ifndef APP_INTERNAL_H
#define APP_INTERNAL_H

#include <stdbool.h>
#include <stdint.h>
#include "app.h"
#include "app_sm.h"
#include "e2e.h"
#include "fs_exec.h"
#include "fs_wire.h"
#include "hal.h"
#include "isotp.h"
#include "nvm.h"
#include "boot_fls_window.h"
#include "fwu.h"
#include "saf.h"
#include "sec_access.h"
#include "secoc.h"
#include "skill.h"
#include "skill_check.h"
#include "uds.h"

#define APP_TICK_US FS_TICK_US            /* the tick period (wire.toml) */
#define APP_TICK_S ((fs_real_t)FS_TICK_S) /* the same in seconds, the control law's dt */
#define APP_N_SLOTS NVM_MAX_SLOTS         /* UDS/CAN slot numbers 1..APP_N_SLOTS */
#define APP_RX_FRAMES_PER_TICK 64u        /* bounded CAN drain per tick */
/* Transmit places kept for emergency and status frames: telemetry and ISO-TP (UDS) frames are
 * queued only while more than this many are free, so a backlog of them (bus flooded by frames
 * of higher priority) never keeps a safety frame out of the queue. */
#define APP_TX_RESERVE 8u
#define APP_RESET_TX_WAIT_MS 100u /* ECUReset: longest wait for the response to leave */
#define APP_STATUS_PERIOD_MS 10u
#define APP_IDLE_TELEMETRY_PERIOD_MS 100u
#define APP_IMAGE_MAX SKILL_IMAGE_MAX
#define APP_SW_VERSION "forceskill-fw 0.1.0"
#define APP_PROTO_VERSION_MAJOR 3u /* 3: the frames' MAC is AES-CMAC (docs/protocol.md) */
#define APP_PROTO_VERSION_MINOR 0u
#define APP_SEC_LEVELS 2u /* SecurityAccess levels 1 and 3, one secret each */
#define APP_TESTERS 2u    /* UDS tester ids: UDS_REQUEST(_2) -> UDS_RESPONSE(_2) */
/* DMP steps of a downloaded skill's own rollout (skill_check.h) per tick while the commit waits:
 * on the M4F 100 steps are ~55,000 instructions (docs/cortex-m.md), within the 168,000-cycle tick
 * of an idle device; a 17 s skill takes 0.17 s. A port whose float is in software defines fewer
 * (the M3 image: 8, ~90,000 instructions). */
#ifndef APP_CHECK_STEPS_PER_TICK
#define APP_CHECK_STEPS_PER_TICK 100u
#endif
/* Units of the downloaded image's parse (skill_parse_run: one kernel's value, 32 bytes of the
 * CRC) per tick while the commit waits: on the M4F a unit is at most ~450 instructions, so 12
 * keep such a tick near 6,000; N = 50 takes ~20 ticks, N = 256 ~110. */
#ifndef APP_COMMIT_UNITS_PER_TICK
#define APP_COMMIT_UNITS_PER_TICK 12u
#endif
/* Units of the slot's flash write (nvm_write_run: the erase, the commit word, or 256 bytes of
 * the CRC, programming, read-back or final scan, each at most ~3,500 instructions on the M4F)
 * per tick while the commit waits. */
#ifndef APP_COMMIT_FLASH_UNITS_PER_TICK
#define APP_COMMIT_FLASH_UNITS_PER_TICK 2u
#endif


/* SHA-256 rounds per tick of a SecurityAccess key check or a motion key derivation (four
 * compressions of 64 rounds, answered 0x78 first): ~80 instructions a round on both images
 * plus the wipes of a stage change, at most 1,775 a tick with 8 (bench/qemu_mac_cost.sh); 32
 * ticks in all. */
#ifndef APP_SEC_ROUNDS_PER_TICK
#define APP_SEC_ROUNDS_PER_TICK 8u
#endif
/* MAC verifications (secoc_verify: one AES-128 block, ~1,000 instructions; two for a frame that
 * fails, its replay check) per tick; the authenticated frame beyond them waits for the next tick
 * (app_t.held), so a flood of forged frames costs at most ~2,000 instructions a tick. One keeps
 * an EXECUTE tick with a genuine frame within the M4F's 3,000 (bench/qemu_tick.sh); the host
 * sends ~110 authenticated frames a second. */
#ifndef APP_MAC_PER_TICK
#define APP_MAC_PER_TICK 1u
#endif

/** The stages of a skill download's commit (one per tick at least, app_uds.c). */
enum {
    APP_COMMIT_PARSE = 0, /* skill_parse_run, APP_COMMIT_UNITS_PER_TICK units a tick */
    APP_COMMIT_PARAMS,    /* skchk_params, skchk_stiffness, skchk_begin */
    APP_COMMIT_CHECK,     /* the rollout, APP_CHECK_STEPS_PER_TICK steps a tick */
    APP_COMMIT_WRITE      /* the slot's flash record, APP_COMMIT_FLASH_UNITS_PER_TICK units a
                             tick, then the slot cache */
};

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
    uint8_t telemetry_period_ms; /* in TEACH/EXECUTE, 1..255 */
    fs_real_t stiffness_max_Npm; /* skills stiffer than this are refused (227), DID 0x0140 */
};

/** The whole device. */
struct app {
    app_config_t cfg;
    app_state_t state;
    uint32_t tick;
    uint64_t now_us;
    uint32_t now_ms;
    uint64_t ms_base_us; /* app_now_ms: a whole millisecond (a multiple of 1,000 us) ... */
    uint32_t ms_base_ms; /* ... and its count, so the tick divides 32 bits, not 64 */
    /* CAN */
    e2e_rx_t rx_command;
    e2e_rx_t rx_heartbeat;
    uint8_t tx_counter_status;
    uint8_t tx_counter_emcy;
    uint8_t host_period_ms; /* telemetry period requested by the host heartbeat */
    bool host_frame;        /* a valid host frame this tick */
    uint32_t e2e_errors;
    uint32_t tx_dropped;
    secoc_t secoc;                            /* authenticated host frames (motion key) */
    uint8_t secoc_dev_nonce[SECOC_NONCE_LEN]; /* the device nonce of the key in use */
    sec_hmac_job_t motion_job;                /* the derivation of the next key, in slices */
    bool motion_keying;                       /* motion_job runs (DID 0x0302 answered 0x78) */
    can_frame_t held;                         /* an authenticated frame beyond APP_MAC_PER_TICK */
    uint8_t held_ch;                          /* its channel + 1, 0: none */
    uint32_t run_opts_fv;                     /* freshness value of the last RUN_OPTIONS ... */
    uint16_t run_opts_time;                   /* ... its time scale (1/1000) and end policy */
    uint8_t run_opts_end;
    /* UDS on ISO-TP, one link per tester id (UDS_REQUEST, UDS_REQUEST_2) */
    isotp_link_t tp[APP_TESTERS];
    uint8_t uds_from;     /* the tester of the request served last or pending */
    uint8_t uds_next;     /* the tester asked first next tick (the two take turns) */
    uint8_t uds_owner;    /* tester + 1 that unlocked the session, 0 while locked */
    uint32_t uds_foreign; /* writes refused because another tester owns the session (558) */
    uds_server_t uds;
    uint8_t uds_resp[ISOTP_MAX_PAYLOAD];
    uint32_t reset_since_ms; /* ECUReset accepted at (its response leaves first) */
    sec_config_t
        sec_cfg[APP_SEC_LEVELS]; /* [0] level 1 (skills, settings), [1] level 3 (firmware) */
    sec_state_t sec;             /* one attempt counter for both levels */
    nvm_t sec_nvm;               /* attempt record (hal_sec_flash), kept across resets */
    bool sec_nvm_ok;
    uint8_t sec_saved[SEC_RECORD_LEN]; /* the record as last stored */
    /* storage */
    nvm_t nvm;
    bool nvm_ok;
    skill_t slot_skill[APP_N_SLOTS]; /* parsed copy of each valid slot */
    bool slot_valid[APP_N_SLOTS];
    uint32_t slot_crc[APP_N_SLOTS]; /* CRC-32 field of each valid image */
    uint32_t slot_len[APP_N_SLOTS];
    uint8_t image[APP_IMAGE_MAX]; /* transfer scratch (download staging / upload) */
    uint32_t xfer_slot;
    uint32_t xfer_size;
    uint16_t last_transfer_status;      /* fs_status / nvm status of the last download */
    uint16_t last_run_status;           /* fs_status of the last start request's scale check */
    skill_t staging;                    /* validation target of a download */
    skill_parser_t parser;              /* the parse of staging, spread over ticks */
    skchk_t check;                      /* output check of staging, spread over ticks */
    nvm_writer_t writer;                /* the slot's flash write, spread over ticks */
    bool checking;                      /* a download's commit runs (UDS 0x78 sent): no start */
    uint8_t commit_stage;               /* APP_COMMIT_*: the commit's stage while checking */
    fs_real_t slot_peak_N[APP_N_SLOTS]; /* peak |f_hat| of each valid slot at goal scale 1 */
    fs_real_t slot_path_m[APP_N_SLOTS]; /* extent max|p| of each valid slot's y path (0: none) */
    /* firmware update (firmware/boot, docs/update.md) */
    boot_fls_window_t fw_w_state, fw_w_slots;
    fls_dev_t fw_state_dev, fw_slots_dev;
    nvm_t fw_state_nvm;
    boot_config_t boot_cfg;
    boot_t boot;
    fwu_t fwu;
    bool fw_xfer;         /* the active download is a firmware image */
    bool fw_self_test_ok; /* the running image passed its self-test (boot tick) */
    /* control */
    exec_state_t exec;
    exec_config_t exec_run_cfg;
    exec_render_t rend[PFC_AXES];
    exec_vel_t vel[PFC_AXES];
    hal_sensors_t sens;
    fs_real_t vel_mps[PFC_AXES];
    fs_real_t force_req_N[PFC_AXES];
    fs_real_t force_out_N[PFC_AXES];
    fs_real_t force_hat_N;
    uint8_t active_slot;
    uint8_t seq_step;
    bool exec_done;
    saf_config_t saf_cfg;
    saf_state_t saf;
    saf_output_t saf_out;
    bool actuator_enabled;
    bool overrun;
    uint32_t teach_ticks;  /* ticks since TEACH started */
    uint64_t next_tick_us; /* app_poll: when the next tick is due */
};

/** A new firmware image on its test boot: run the self-test and confirm it (boot_confirm);
 *  true if confirmed or not on test. Called once, on the first tick. */
bool app_fw_self_test_and_confirm(app_t *app);

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
} app_run_step_t;

/** A request to start motion, decoded from any source (app_run.c). */
typedef struct {
    app_run_source_t source;
    uint8_t n_steps; /* 1..EXEC_MAX_STEPS */
    uint8_t end;     /* 0 each skill's own end policy, 1 hold, 2 release */
    app_run_step_t step[EXEC_MAX_STEPS];
} app_run_request_t;

/** The authorisation of a run request, the first check of every start whatever its source: the
 *  one place a MAC and freshness check of the request sits. Today every request passes (a run
 *  needs no SecurityAccess level, docs/protocol.md). Returns a UDS NRC (0 authorised). */
uint8_t app_run_authorize(const app_t *app, const app_run_request_t *req);

/** Start a run: app_run_authorize, then the end policy and step count (0x31), the state (IDLE,
 *  no commit running: 0x22), each step's slot, scales, stiffness, force and path limits (0x31,
 *  the check's code 224-227 in last_run_status), then EXECUTE. Returns a UDS NRC (0 started). */
uint8_t app_run_start(app_t *app, const app_run_request_t *req);

/** The default skill stiffness limit (DID 0x0140, 227 above it) of a drive: the highest nominal
 *  stiffness at which both stiff HIL profiles track within 5 % RMS without a fault
 *  (bench/stiffness/stiffness_limit.py, docs/hil.md): FS_STIFFNESS_MAX_NPM for a
 *  dynamics-compensated drive (render_carriage 0), FS_STIFFNESS_MAX_RENDERED_NPM for a carriage
 *  rendered by admittance (render_carriage 1; 13-15 % at 1e5 N/m). */
fs_real_t app_stiffness_max_default_Npm(uint8_t render_carriage);

/** Handle the UDS hooks (app_uds.c): fills an uds_app_t bound to app. */
void app_uds_bind(app_t *app, uds_app_t *out);

/** Apply a state machine event (app_sm_next): the only place the device state changes; runs the
 *  entry actions of the new state. Returns true if the state changed. */
bool app_event(app_t *app, app_event_t ev);

/** Clear the latched faults (host command or RoutineControl): FLT_NONE and IDLE when cleared,
 *  else the first fault whose cause persists (the device stays in FAULT). */
flt_code_t app_clear_faults(app_t *app);

/** Reload slot caches from storage (boot, after a download or erase). */
void app_slots_reload(app_t *app);

/** SecurityAccess config of a level (1 or 3); NULL for any other level. */
const sec_config_t *app_sec_config(const app_t *app, uint8_t level);

/** Begin the motion key of a host session from its nonce (DID 0x0302 write): forgets the key
 *  in use, draws the device nonce, starts the derivation from the level-1 secret. Returns
 *  UDS_NRC_RESPONSE_PENDING (app_motion_key_run finishes it) or a refusal's NRC. */
uint8_t app_motion_key_begin(app_t *app, const uint8_t *host_nonce, uint16_t len);

/** Up to rounds SHA-256 rounds of the derivation begun: UDS_NRC_RESPONSE_PENDING while it runs,
 *  then 0 with the key in use. */
uint8_t app_motion_key_run(app_t *app, uint32_t rounds);

/** Begin and finish at once (the simulator's and the tests' own host session). A UDS NRC. */
uint8_t app_motion_key(app_t *app, const uint8_t *host_nonce, uint16_t len);

/** Store the SecurityAccess attempt record if it changed (after every seed/key request). */
void app_sec_persist(app_t *app);

#endif /* APP_INTERNAL_H */

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
 * Per tick (app_tick), the control path first: sensors -> control (TEACH: render m_d; EXECUTE:
 * fs_exec sequence) -> safety supervisor (limits, faults, safe stop) -> actuator -> a run's
 * start slice -> CAN rx (bounded; commands act from the next tick) -> UDS and the jobs' slices
 * -> emergency/status/telemetry frames. */
#ifndef APP_INTERNAL_H
#define APP_INTERNAL_H

#include <stdbool.h>
#include <stdint.h>
#include "app.h"
#include "app_config.h"
#include "app_fw.h"
#include "app_sec.h"
#include "app_sm.h"
#include "e2e.h"
#include "fs_budget.h" /* the per-tick budgets (APP_*_PER_TICK, SLOTS_*) */
#include "fs_exec.h"
#include "fs_job.h"
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
#include "slots.h"
#include "uds.h"

#define APP_N_SLOTS SLOTS_N /* UDS/CAN slot numbers 1..APP_N_SLOTS */
/* Transmit places kept for emergency and status frames: telemetry and ISO-TP (UDS) frames are
 * queued only while more than this many are free, so a backlog of them (bus flooded by frames
 * of higher priority) never keeps a safety frame out of the queue. */
#define APP_TX_RESERVE 8u
#define APP_RESET_TX_WAIT_MS 100u /* ECUReset: longest wait for the response to leave */
#define APP_STATUS_PERIOD_MS 10u
#define APP_IDLE_TELEMETRY_PERIOD_MS 100u
/* in FAULT the telemetry keeps the host's rate for the stop ramp and this long after it (a
 * host that records the ramp gets its end), then while host frames keep coming */
#define APP_FAULT_TELEMETRY_TAIL_MS 20u
#define APP_IMAGE_MAX SLOTS_IMAGE_MAX
#define APP_SW_VERSION "forceskill-fw 0.1.0"
#define APP_PROTO_VERSION_MAJOR 4u /* 4: commands fresh in time (docs/protocol.md) */
#define APP_PROTO_VERSION_MINOR 0u
#define APP_TESTERS UDS_TESTERS /* UDS tester ids: UDS_REQUEST(_2) -> UDS_RESPONSE(_2) */
/* Authenticated host frames waiting for their MAC check, in arrival order (a full queue drops its
 * oldest), and how long one may wait: a frame still unverified this long after its arrival is
 * dropped unverified (counted), the newer ones go first. */
#define APP_MAC_QUEUE_LEN 8u
#define APP_MAC_STALE_MS 40u
/* A command (TEACH, RUN_OPTIONS, EXECUTE, CLEAR_FAULT) is acted on only if it arrived within this
 * long of the previous authenticated host frame the device accepted (the host's heartbeat comes
 * every 10 ms), and never after a later heartbeat that carries a newer command freshness. A stop
 * (IDLE, from any node), a UDS fault clear or run stop and a new motion key end the reference:
 * the next command needs a heartbeat after them. docs/protocol.md "Freshness in time". */
#define APP_CMD_FRESH_MS 50u
/** Authenticated host frames waiting for their MAC check (a ring, oldest at head). */
typedef struct {
    uint8_t data[APP_MAC_QUEUE_LEN][E2E_FRAME_LEN];
    uint32_t arrival_ms[APP_MAC_QUEUE_LEN];
    uint8_t ch[APP_MAC_QUEUE_LEN];
    uint8_t head;
    uint8_t count;
} app_mac_queue_t;

/** The whole device. */
/** The cyclic frames' counters and what the host's authenticated frames left (app.c). */
typedef struct {
    uint8_t tx_counter_status;
    uint8_t tx_counter_emcy;
    uint8_t host_period_ms; /* telemetry period requested by the host heartbeat */
    bool host_frame;        /* an authenticated host frame was accepted this tick ... */
    uint32_t host_frame_ms; /* ... and the newest one's arrival time (the silence watchdog's) */
    uint32_t host_seen_ms;  /* arrival of the last host frame acted on: commands' reference */
    bool host_seen;         /* host_seen_ms holds (APP_CMD_FRESH_MS) */
    uint32_t e2e_errors;
    uint32_t stale_commands; /* authenticated commands refused as late (APP_CMD_FRESH_MS) */
    uint32_t tx_dropped;
} app_bus_t;

/** Control and execution: the executor, the rendered drive, the run in progress (app_run.c). */
typedef struct {
    uint32_t teach_ticks; /* ticks since TEACH started */
    exec_state_t exec;
    exec_config_t exec_run_cfg;
    exec_render_t rend[PFC_AXES];
    exec_vel_t vel[PFC_AXES];
    /* the tick's sensors in the executor's and the safety layer's units, converted once a
     * tick (the fixed-point build's integers), and its request there */
    exec_sample_t sample;
    uint8_t active_slot;
    uint8_t seq_step;
    bool exec_done;
    fs_job_t start;        /* a run's start (exec_start_run, a slice a tick, no force) */
    uint8_t run_start_nrc; /* its outcome for a pending RUN_SKILL/RUN_SEQUENCE start (0x78) */
    uint16_t band_stop_ms; /* the run's band stop time (app_run_request_t), 0: report only */
    uint32_t causes;       /* this tick's fault causes for the safety layer: FLT_SKILL_INVALID (a
                      * saturated exec_tick, FS_ERR_FIXED_OVERFLOW), FLT_BAND */
    uint32_t exec_saturated_ticks; /* ticks whose exec_tick saturated, since power-up */
    uint16_t last_run_status;      /* fs_status of the last start request's scale check */
} app_ctl_t;

/** Authenticated host frames: their MAC checks and what the accepted ones left (app.c). */
typedef struct {
    secoc_t secoc;               /* the MACs under the motion key */
    secoc_job_t mac_job;         /* the MAC verification in flight */
    uint32_t mac_job_arrival_ms; /* its frame's arrival */
    app_mac_queue_t macq;        /* frames waiting for it, oldest first */
    uint32_t mac_dropped;        /* frames dropped unverified (full or stale) */
    bool mac_ran;                /* this tick verified a frame's MAC */
    uint32_t run_opts_fv;        /* freshness value of the last RUN_OPTIONS ... */
    uint16_t run_opts_time;      /* ... its time scale (1/1000) and end policy */
    uint8_t run_opts_end;
} app_auth_t;

/** UDS on ISO-TP, one link per tester id (UDS_REQUEST, UDS_REQUEST_2), and the server (app.c's
 *  service, app_uds.c's hooks); the server's answers are built in the tester's link. */
typedef struct {
    uint8_t uds_from;      /* the tester of the request served last or pending */
    uint8_t uds_next;      /* the tester asked first next tick (the two take turns) */
    bool uds_request_turn; /* a new request before the pending one's slice next tick */
    /* the long work a request answered 0x78 began: its next slice and, once done, the answer
     * (set by the hook that began it; the UDS server's resume calls it) */
    uint8_t (*pending)(app_t *app);
    uint8_t uds_owner;       /* tester + 1 that unlocked the session, 0 while locked */
    uint32_t uds_foreign;    /* writes refused because another tester owns the session (558) */
    uint32_t reset_since_ms; /* ECUReset accepted at (its response leaves first) */
    uint8_t tp_held; /* tester + 1 whose request buffer a TransferData block's slices read */
    uint64_t seed_sent_us[APP_TESTERS]; /* when each tester was last sent a seed */
    uint32_t tp_frames;                 /* ISO-TP frames queued this tick (budget a tick) */
    uds_server_t uds;
    isotp_link_t tp[APP_TESTERS]; /* last: their buffers are large */
} app_diag_t;

/** The whole device: the tick's values first (within a load's immediate offset of the start),
 *  then the modules, the large and cold ones last. */
struct app {
    app_config_t cfg;
    app_state_t state;
    uint32_t tick;
    uint64_t now_us;
    uint32_t now_ms;
    hal_sensors_t sens;
    fs_real_t vel_mps[PFC_AXES];
    fs_real_t force_req_N[PFC_AXES];
    fs_real_t force_out_N[PFC_AXES];
    exec_nmeas_force_t force_hat; /* the executor's f_hat in the layer's units (Q16.16 in the
                                   * fixed-point build: a float only where it is read) */
    app_bus_t bus;
    saf_output_t saf_out;
    bool actuator_enabled;
    bool overrun;
    app_ctl_t ctl;
    uint32_t fault_fast_until_ms; /* in FAULT: the telemetry at the host's rate until then */
    saf_config_t saf_cfg;
    saf_state_t saf;
    app_auth_t auth;
    app_diag_t diag;
    app_sec_t sec;         /* SecurityAccess, its record, the motion key (app_sec.h) */
    slots_t slots;         /* the skill store: slot cache, transfer buffer, a download's commit */
    app_fw_t fw;           /* firmware update (app_fw.h, docs/update.md) */
    uint64_t next_tick_us; /* app_poll: when the next tick is due */
};

/** A new firmware image on its test boot: run the self-test and confirm it (boot_confirm);
 *  true if confirmed or not on test. Called once, on the first tick. */
bool app_fw_self_test_and_confirm(app_t *app);

/** The authorisation of a run request, the first check of every start whatever its source: the
 *  one place a MAC and freshness check of the request sits. Today every request passes (a run
 *  needs no SecurityAccess level, docs/protocol.md). Returns a UDS NRC (0 authorised). */
uint8_t app_run_authorize(const app_t *app, const app_run_request_t *req);

/** True from a run's acceptance until its start's slices are done (app_run_start_step). */
static inline bool app_run_starting(const app_t *app)
{
    return fs_job_running(&app->ctl.start);
}

/** One slice of an accepted run's start (exec_start_run), after the tick's actuator write (the
 *  control commands no force meanwhile); a refusal ends the run (last_run_status). */
void app_run_start_step(app_t *app);

/** End every command sent before now (a stop, a UDS fault clear or run stop, a new motion key):
 *  the next HostCommand is acted on only after an authenticated heartbeat arrived after this. */
void app_commands_void(app_t *app);

/** True if app_sec_store_step has work (a record being written or waiting) and the tick is not
 *  one that noted a change: the tick calls it only then. Inline: asked every tick. */
static inline bool app_sec_store_pending(const app_t *app)
{
    const app_sec_store_t *r = &app->sec.store;
    return (fs_job_running(&r->job) || r->dirty) && r->noted_tick != app->tick;
}

/** Handle the UDS hooks (app_uds.c): fills an uds_app_t bound to app. */
void app_uds_bind(app_t *app, uds_app_t *out);

/** Apply a state machine event (app_sm_next): the only place the device state changes; runs the
 *  entry actions of the new state. Returns true if the state changed. */
bool app_event(app_t *app, app_event_t ev);

/** Clear the latched faults (host command or RoutineControl): FLT_NONE and IDLE when cleared,
 *  else the first fault whose cause persists (the device stays in FAULT). */
flt_code_t app_clear_faults(app_t *app);

#endif /* APP_INTERNAL_H */

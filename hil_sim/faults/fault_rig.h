/* Lockstep HIL rig for fault injection (docs/safety.md "HIL fault injection"): the FULL device
 * application (firmware/app: state machine, saf_ supervisor, nvm skill bank, UDS) on the host
 * port's simulated CAN backend (hal_can_sim.c), coupled every 1 ms to hil_sim's plant, object
 * and sensor models, with the host side scripted in C. Host frames (E2E-protected heartbeats,
 * commands, UDS on ISO-TP) enter the device through hal_sim_can_deliver, the path `hil_sim
 * serve` uses; device frames leave through hal_sim_can_tx_peek/pop. The device is scheduled
 * by app_poll on the HAL time source, so a late tick is a real overrun. Deterministic for a
 * seed (the only non-deterministic input is the SecurityAccess seed, which does not change
 * the outcome). One rig at a time: the HAL of the host port is global. */
#ifndef FAULT_RIG_H
#define FAULT_RIG_H

#include <stdbool.h>
#include <stdint.h>

#include "app_config.h"
#include "isotp.h"
#include "sim_couple.h"
#include "sim_model.h"
#include "sim_rng.h"
#include "sim_scenario.h"

#define RIG_MAX_EMCY 16u
#define RIG_HB_PERIOD_MS 10u /* the host heartbeat period (forceskill host default) */

/** Sensor/actuator/bus injections applied by rig_step (all off when zero/false). */
typedef struct {
    bool force_nan;     /* tip force reads NaN */
    double force_add_N; /* added to the tip force reading */
    bool force_stuck;   /* tip force repeats stuck_value_N */
    double stuck_value_N;
    double encoder_add_m; /* added to the x encoder reading */
    double act_limit_N;   /* > 0: the actuator saturates at +-act_limit_N */
    bool corrupt_host;    /* host frames arrive with one bit flipped (E2E fails) */
    double drop_p;        /* each host frame is lost with this probability (seeded) */
    uint32_t stall_ticks; /* the device does not get the CPU for this many ticks */
} rig_inject_t;

/** One emergency frame seen by the host. */
typedef struct {
    uint16_t code;
    uint32_t dev_tick; /* the frame's tick field */
    uint64_t rx_tick;  /* rig tick at which it reached the host */
} rig_emcy_t;

/** The rig. */
typedef struct {
    sim_scenario_t sc;
    sim_axis_t ax[2];
    sim_drive_t drv[2];
    sim_rng_t rng_sens;
    sim_sample_t ring[SIM_COUPLE_RING]; /* sensor pipeline (delay_samples) */
    uint64_t n_tick;                    /* simulated ms since the rig started */
    app_config_t cfg;
    app_t *app; /* app_device(): one device per process */
    /* host */
    bool heartbeat_on;
    secoc_t host; /* the host's session (motion key, freshness values), new at every boot */
    uint64_t last_host_tick; /* tick of the last host frame delivered to the device */
    isotp_link_t tester;     /* UDS client (ISO-TP, ids swapped) */
    /* injections and observations */
    rig_inject_t inj;
    rig_emcy_t emcy[RIG_MAX_EMCY];
    uint32_t n_emcy;
    uint16_t status_fault; /* last DeviceStatus: fault code, state */
    uint8_t status_state;
    uint32_t e2e_bad_rx;   /* device frames failing the host's E2E check */
    sim_rng_t rng_faults;  /* frame loss draws */
    uint32_t host_dropped; /* host frames lost by injection */
    double contact_max_N;  /* largest true contact force since rig_init */
    double cmd_N[2];       /* this tick's actuator command (after enable) */
    bool act_enable;
    bool ran; /* app_poll ran a tick this rig tick */
} rig_t;

/** Build the device from a plant scenario (hil_sim scenario file, EXECUTE part unused) over a
 *  freshly erased flash; the device is not booted yet (rig_flash_skill, then rig_boot). */
void rig_init(rig_t *r, const sim_scenario_t *sc);

/** Factory-program slot (0-based) with a skill image through the storage (nvm_write). 0 ok. */
int rig_flash_skill(rig_t *r, uint16_t slot, const uint8_t *img, uint32_t len);

/** Power the device up (app_init: storage scan, UDS, security; the host CAN queues reset). */
void rig_boot(rig_t *r);

/** One simulated millisecond: host frames due, sensors (with injections), app_poll, device
 *  frames to the host, actuator, plant substeps. */
void rig_step(rig_t *r);

/** Run n ticks. */
void rig_run(rig_t *r, uint32_t n);

/** Send a HostCommand (mode APP_CMD_*, slot 1.., goal/time scale, end 0 skill/1 hold/2 release). */
void rig_command(rig_t *r, uint8_t mode, uint8_t slot, double goal_scale, double time_scale,
                 uint8_t end);

/** One UDS request/response through ISO-TP, running the rig until the answer (response
 *  pending 0x78 skipped) or timeout_ms; returns the response length (0 on timeout). */
uint16_t rig_uds(rig_t *r, const uint8_t *req, uint16_t len, uint8_t *resp, uint16_t cap,
                 uint32_t timeout_ms);

/** Programming session + SecurityAccess level 1 (waits out the boot delay). 0 ok. */
int rig_uds_unlock(rig_t *r);

/** Programming session + SecurityAccess of level (1 or 3) with its secret. 0 ok. */
int rig_uds_unlock_level(rig_t *r, uint8_t level);

/** A download as rig_uds_download, to the memory address addr (a slot 1.., or
 *  FWU_DOWNLOAD_ADDRESS for a firmware image). */
uint8_t rig_uds_download_to(rig_t *r, uint32_t addr, const uint8_t *img, uint32_t len);

/** RequestDownload/TransferData/RequestTransferExit of an image into slot (1-based); returns
 *  the final NRC (0 = positive response to RequestTransferExit, 0xFF = no answer). */
uint8_t rig_uds_download(rig_t *r, uint8_t slot, const uint8_t *img, uint32_t len);

/** CRC-32 of the whole slot flash region and each slot's directory (valid, seq, crc, length). */
uint32_t rig_flash_crc(void);

/** Read slot (0-based) through a fresh storage scan; *len = 0 when empty. 0 ok. */
int rig_read_slot(uint16_t slot, uint8_t *buf, uint32_t cap, uint32_t *len);

/** requestSeed at level, waited out (100 ms at a time, 4 s at most) while it answers 0x37; the
 *  last answer into resp, its length returned. */
uint16_t rig_uds_seed(rig_t *r, uint8_t level, uint8_t *resp, uint16_t cap);

/** Read a whole file of at most cap bytes into buf; -1 when it cannot be read, is longer or
 *  empty, else 0 with *len its length. */
int rig_read_file(const char *path, uint8_t *buf, uint32_t cap, uint32_t *len);

#endif /* FAULT_RIG_H */

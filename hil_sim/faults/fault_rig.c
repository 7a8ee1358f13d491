/* Lockstep fault-injection rig (see fault_rig.h). The device <-> plant coupling is
 * sim_couple.h, the steps of hil_sim/bus/serve.c's sim_tick: sensors sampled at t with the
 * pipeline delay, the device's tick, the actuator held over the plant substeps; in IDLE/BOOT
 * and once a fault has disabled the actuator the simulated drive parks the handle. */
#include "fault_rig.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "e2e.h"
#include "fls_ram.h"
#include "fs_dbc.h"
#include "hal_host.h"
#include "nvm.h"
#include "proto_ids.h"
#include "sec_access.h"
#include "sec_sha256.h"
#include "uds.h"


static bool tester_send(void *ctx, const can_frame_t *f)
{
    (void)ctx;
    return hal_sim_can_deliver(f); /* UDS frames do not feed the host-silence watchdog */
}

void rig_init(rig_t *r, const sim_scenario_t *sc)
{
    memset(r, 0, sizeof(*r));
    r->app = app_device();
    r->sc = *sc;
    hal_host_init();
    hal_host_flash_erase();
    hal_sim_can_reset();
    hal_host_set_time_us(0u);

    sim_couple_plant_init(&r->sc, r->ax, r->drv);
    sim_rng_seed(&r->rng_sens, sc->seed ^ 0x5EB5C0DEDA7A5EEDull);
    sim_rng_seed(&r->rng_faults, sc->seed ^ 0xFA17FA17FA17FA17ull);
    sim_couple_device_config(sc, &r->cfg); /* the scenario's controller, as hil_sim serve */

    isotp_config_t tc;
    isotp_config_default(&tc, PROTO_ID_UDS_REQUEST(r->cfg.node),
                         PROTO_ID_UDS_RESPONSE(r->cfg.node));
    isotp_init(&r->tester, &tc, tester_send, r);
}

int rig_flash_skill(rig_t *r, uint16_t slot, const uint8_t *img, uint32_t len)
{
    (void)r;
    nvm_t n;
    if (nvm_init(&n, hal_flash()) != NVM_OK) {
        return -1;
    }
    return nvm_write(&n, slot, img, len) == NVM_OK ? 0 : -1;
}

void rig_boot(rig_t *r)
{
    hal_sim_can_reset();
    hal_host_set_time_us(r->n_tick * 1000u);
    app_init(r->app, &r->cfg);
    (void)sim_couple_host_session(r->app, &r->host); /* a new session after every power-up */
}

static void deliver_host(rig_t *r, can_frame_t *f)
{
    if (r->inj.drop_p > 0.0 && sim_rng_uniform(&r->rng_faults) < r->inj.drop_p) {
        r->host_dropped++;
        return;
    }
    if (r->inj.corrupt_host) {
        f->data[2] ^= 0x10u; /* a bit error the CAN CRC missed: the E2E CRC-8 catches it */
    }
    (void)hal_sim_can_deliver(f);
    if (!r->inj.corrupt_host) {
        r->last_host_tick = r->n_tick;
    }
}

static void send_heartbeat(rig_t *r)
{
    can_frame_t f;
    sim_couple_heartbeat_frame(&r->host, r->cfg.node, 10u, &f);
    deliver_host(r, &f);
}

void rig_command(rig_t *r, uint8_t mode, uint8_t slot, double goal_scale, double time_scale,
                 uint8_t end)
{
    can_frame_t f[2];
    const unsigned n = sim_couple_command_frames(&r->host, r->cfg.node, mode, slot, goal_scale,
                                                 time_scale, end, f);
    for (unsigned i = 0; i < n && i < 2u; i++) {
        deliver_host(r, &f[i]);
    }
}

static void host_receive(rig_t *r)
{
    can_frame_t f;
    const uint64_t now_us = r->n_tick * 1000u;
    while (hal_sim_can_tx_peek(&f)) {
        hal_sim_can_tx_pop();
        const uint32_t node = r->cfg.node;
        if (f.id == PROTO_ID_UDS_RESPONSE(node)) {
            isotp_on_frame(&r->tester, &f, now_us);
        } else if (f.id == PROTO_ID_EMERGENCY(node) || f.id == PROTO_ID_STATUS(node)) {
            e2e_rx_t rx; /* the counter is not followed here; the CRC is checked */
            e2e_rx_reset(&rx);
            if (e2e_check(&rx, &f) != PROTO_OK) {
                r->e2e_bad_rx++;
                continue;
            }
            if (f.id == PROTO_ID_EMERGENCY(node)) {
                struct fs_dbc_emergency_t m;
                if (fs_dbc_emergency_unpack(&m, f.data, f.len) == 0 && r->n_emcy < RIG_MAX_EMCY) {
                    r->emcy[r->n_emcy].code = m.fault_code;
                    r->emcy[r->n_emcy].dev_tick = m.tick;
                    r->emcy[r->n_emcy].rx_tick = r->n_tick;
                    r->n_emcy++;
                }
            } else {
                struct fs_dbc_device_status_t s;
                if (fs_dbc_device_status_unpack(&s, f.data, f.len) == 0) {
                    r->status_fault = s.fault_code;
                    r->status_state = s.state;
                }
            }
        }
    }
}

void rig_step(rig_t *r)
{
    const sim_scenario_t *sc = &r->sc;
    const uint64_t now_us = r->n_tick * 1000u;
    hal_host_set_time_us(now_us);

    /* host: heartbeat due, UDS client */
    if (r->heartbeat_on && r->n_tick % RIG_HB_PERIOD_MS == 0u) {
        send_heartbeat(r);
    }
    isotp_poll(&r->tester, now_us);

    /* sensors sampled now (injections act on the physical sensor), seen delay_samples later */
    sim_sample_t smp;
    sim_couple_sample(sc, r->ax, r->drv, &r->rng_sens, &smp);
    smp.x_m += r->inj.encoder_add_m;
    smp.contact_N += r->inj.force_add_N;
    if (r->inj.force_stuck) {
        smp.contact_N = r->inj.stuck_value_N;
    }
    if (r->inj.force_nan) {
        smp.contact_N = NAN;
    }
    hal_sensors_t hs;
    sim_couple_to_hal(sim_couple_delay(r->ring, r->n_tick, sc->delay_samples, &smp), &hs);
    hal_host_set_sensors(&hs);

    /* the device: its scheduler on the HAL clock (a stalled CPU misses ticks) */
    r->ran = false;
    if (r->inj.stall_ticks > 0u) {
        r->inj.stall_ticks--;
    } else {
        r->ran = app_poll(r->app);
    }
    uint8_t reset_type = 0u;
    if (hal_host_take_reset(&reset_type)) {
        rig_boot(r);
    }
    host_receive(r);

    /* actuator */
    const bool enable = sim_couple_actuate(sc, r->app, r->drv, r->cmd_N);
    r->act_enable = enable;
    for (int a = 0; a < 2; a++) {
        if (r->inj.act_limit_N > 0.0) {
            const double lim = r->inj.act_limit_N;
            const double fa = r->drv[a].force_cmd_N;
            r->drv[a].force_cmd_N = fa > lim ? lim : (fa < -lim ? -lim : fa);
        }
        r->drv[a].force_ext_N = 0.0;
        r->drv[a].hand_damping_Nspm = 0.0;
    }
    sim_couple_advance(sc, r->ax, r->drv, sim_couple_parked(app_state(r->app), enable));
    if (r->ax[0].contact_N > r->contact_max_N) {
        r->contact_max_N = r->ax[0].contact_N;
    }
    r->n_tick++;
}

void rig_run(rig_t *r, uint32_t n)
{
    for (uint32_t i = 0; i < n; i++) {
        rig_step(r);
    }
}

uint16_t rig_uds(rig_t *r, const uint8_t *req, uint16_t len, uint8_t *resp, uint16_t cap,
                 uint32_t timeout_ms)
{
    if (isotp_send(&r->tester, req, len, r->n_tick * 1000u) != PROTO_OK) {
        return 0u;
    }
    for (uint32_t i = 0; i < timeout_ms; i++) {
        rig_step(r);
        const uint8_t *data = NULL;
        const uint16_t n = isotp_rx_peek(&r->tester, &data);
        if (n == 0u) {
            continue;
        }
        const bool pending = n >= 3u && data[0] == UDS_NEGATIVE_RESPONSE && data[2] == 0x78u;
        uint16_t out = 0u;
        if (!pending) {
            out = n > cap ? cap : n;
            memcpy(resp, data, out);
        }
        isotp_rx_release(&r->tester);
        if (!pending) {
            return out;
        }
    }
    return 0u;
}

int rig_uds_unlock(rig_t *r)
{
    return rig_uds_unlock_level(r, UDS_SEC_LEVEL_WRITE);
}

uint16_t rig_uds_seed(rig_t *r, uint8_t level, uint8_t *resp, uint16_t cap)
{
    const uint8_t rs[2] = {UDS_SID_SECURITY, level};
    uint16_t n = 0u;
    for (int attempt = 0; attempt < 40; attempt++) {
        n = rig_uds(r, rs, 2u, resp, cap, 200u);
        if (!(n == 3u && resp[0] == UDS_NEGATIVE_RESPONSE &&
              resp[2] == UDS_NRC_DELAY_NOT_EXPIRED)) {
            break;
        }
        rig_run(r, 100u); /* SecurityAccess's power-up or wrong-key delay */
    }
    return n;
}

int rig_uds_unlock_level(rig_t *r, uint8_t level)
{
    uint8_t resp[64];
    const uint8_t dsc[2] = {UDS_SID_DSC, UDS_SESSION_PROGRAMMING};
    if (rig_uds(r, dsc, 2u, resp, sizeof resp, 200u) < 2u || resp[0] != 0x50u) {
        return -1;
    }
    const uint16_t n = rig_uds_seed(r, level, resp, sizeof resp);
    if (n != 2u + SEC_SEED_LEN || resp[0] != 0x67u) {
        return -2;
    }
    uint8_t secret_len = 0u;
    const uint8_t *secret = hal_device_secret(level, &secret_len);
    uint8_t mac[SEC_SHA256_LEN];
    sec_hmac_sha256(secret, secret_len, &resp[2], SEC_SEED_LEN, mac);
    uint8_t sk[2u + SEC_KEY_LEN];
    sk[0] = UDS_SID_SECURITY;
    sk[1] = (uint8_t)(level + 1u);
    memcpy(&sk[2], mac, SEC_KEY_LEN);
    const uint16_t k = rig_uds(r, sk, (uint16_t)sizeof sk, resp, sizeof resp, 200u);
    return (k >= 2u && resp[0] == 0x67u) ? 0 : -3;
}

uint8_t rig_uds_download(rig_t *r, uint8_t slot, const uint8_t *img, uint32_t len)
{
    return rig_uds_download_to(r, slot, img, len);
}

uint8_t rig_uds_download_to(rig_t *r, uint32_t addr, const uint8_t *img, uint32_t len)
{
    static uint8_t buf[ISOTP_MAX_PAYLOAD];
    uint8_t resp[64];
    uint8_t rd[UDS_REQ_DOWNLOAD_LEN];
    uint16_t n = rig_uds(r, rd, uds_request_download(rd, addr, len), resp, sizeof resp, 500u);
    if (n == 0u) {
        return 0xFFu;
    }
    if (resp[0] != 0x74u) {
        return n >= 3u ? resp[2] : 0xFEu;
    }
    uint32_t pos = 0u;
    uint8_t counter = 1u;
    while (pos < len) {
        uint32_t chunk = len - pos;
        if (chunk > 1024u) {
            chunk = 1024u;
        }
        buf[0] = UDS_SID_TRANSFER_DATA;
        buf[1] = counter;
        memcpy(&buf[2], &img[pos], chunk);
        n = rig_uds(r, buf, (uint16_t)(2u + chunk), resp, sizeof resp, 1000u);
        if (n == 0u) {
            return 0xFFu;
        }
        if (resp[0] != 0x76u) {
            return n >= 3u ? resp[2] : 0xFEu;
        }
        pos += chunk;
        counter++;
    }
    const uint8_t te[1] = {UDS_SID_TRANSFER_EXIT};
    n = rig_uds(r, te, 1u, resp, sizeof resp, 2000u);
    if (n == 0u) {
        return 0xFFu;
    }
    return resp[0] == 0x77u ? 0u : (n >= 3u ? resp[2] : 0xFEu);
}

uint32_t rig_flash_crc(void)
{
    const fls_dev_t *dev = hal_flash();
    uint8_t buf[512];
    uint32_t crc = 0u;
    const uint32_t total = dev->sector_size * dev->sector_count;
    for (uint32_t a = 0u; a < total; a += (uint32_t)sizeof buf) {
        if (dev->read(dev->ctx, a, buf, (uint32_t)sizeof buf) != 0) {
            return 0u;
        }
        crc = nvm_crc32(crc, buf, (uint32_t)sizeof buf);
    }
    return crc;
}

int rig_read_slot(uint16_t slot, uint8_t *buf, uint32_t cap, uint32_t *len)
{
    nvm_t n;
    *len = 0u;
    if (nvm_init(&n, hal_flash()) != NVM_OK) {
        return -1;
    }
    const nvm_status_t st = nvm_read(&n, slot, buf, cap, len);
    if (st == NVM_ERR_EMPTY) {
        *len = 0u;
        return 0;
    }
    return st == NVM_OK ? 0 : -1;
}

int rig_read_file(const char *path, uint8_t *buf, uint32_t cap, uint32_t *len)
{
    FILE *f = fopen(path, "rb");
    if (f == NULL) {
        return -1;
    }
    const size_t n = fread(buf, 1, cap, f);
    const int bad = ferror(f) || !feof(f);
    fclose(f);
    *len = (uint32_t)n;
    return bad || n == 0u ? -1 : 0;
}

/* Cost image of the authenticated frames (bench/qemu_mac_cost.sh): each operation of
 * firmware/security once between the count markers, in this order:
 *   1 verify_ok      secoc_verify of a genuine frame (the per-frame cost: one AES-CMAC block)
 *   2 verify_bad     secoc_verify of a frame with a wrong MAC at a freshness value above 256
 *                    (the refusal with its replay check: two blocks; the worst case)
 *   3 protect        secoc_protect (the sender's MAC of a frame)
 *   4 set_key        secoc_set_key (AES key schedule and CMAC subkeys)
 *   5 hmac_oneshot   one HMAC-SHA256 of a 16-byte seed under a 32-byte secret (what a sendKey's
 *                    check or a key derivation would cost in one tick: four SHA-256 compressions)
 *   6 hmac_slice_max the largest of the calls of sec_hmac_job_run with APP_ROUNDS rounds that
 *                    compute the same HMAC in slices (the application's APP_SEC_ROUNDS_PER_TICK);
 *                    the number of calls follows as slices */
#include <string.h>

#include "cm_port.h"
#include "cm_semihost.h"
#include "sec_sha256.h"
#include "secoc.h"

#define APP_ROUNDS 8u /* app_internal.h APP_SEC_ROUNDS_PER_TICK */

static secoc_t dev, host;
static sec_hmac_job_t job;

int main(void)
{
    static const uint8_t secret[32] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16};
    static const uint8_t dn[SECOC_NONCE_LEN] = {0xA5};
    static const uint8_t hn[SECOC_NONCE_LEN] = {0x5A};
    uint8_t key[SECOC_KEY_LEN];
    secoc_derive_key(secret, sizeof secret, dn, hn, key);
    secoc_init(&dev);
    secoc_set_key(&dev, key);
    secoc_init(&host);
    secoc_set_key(&host, key);
    dev.fv[SECOC_CH_HEARTBEAT] = 1000u;
    host.fv[SECOC_CH_HEARTBEAT] = 1000u;
    can_frame_t f;
    memset(&f, 0, sizeof f);
    f.id = 0x110u;
    f.len = 8u;
    f.data[0] = 10u;
    (void)secoc_protect(&host, &f, SECOC_CH_HEARTBEAT);
    volatile int ok = 1;
    cm_port_mark_begin();
    const sec_status_t a = secoc_verify(&dev, &f, SECOC_CH_HEARTBEAT);
    cm_port_mark_end();
    ok &= a == SEC_OK;
    (void)secoc_protect(&host, &f, SECOC_CH_HEARTBEAT);
    f.data[SECOC_MAC_OFFSET] ^= 1u;
    cm_port_mark_begin();
    const sec_status_t b = secoc_verify(&dev, &f, SECOC_CH_HEARTBEAT);
    cm_port_mark_end();
    ok &= b == SEC_ERR_MAC;
    cm_port_mark_begin();
    (void)secoc_protect(&host, &f, SECOC_CH_HEARTBEAT);
    cm_port_mark_end();
    cm_port_mark_begin();
    secoc_set_key(&dev, key);
    cm_port_mark_end();
    uint8_t one[SEC_SHA256_LEN], sliced[SEC_SHA256_LEN];
    cm_port_mark_begin();
    sec_hmac_sha256(secret, sizeof secret, dn, SECOC_NONCE_LEN, one);
    cm_port_mark_end();
    (void)sec_hmac_job_begin(&job, secret, sizeof secret, dn, SECOC_NONCE_LEN);
    bool done = false;
    while (!done) {
        cm_port_mark_begin();
        done = sec_hmac_job_run(&job, APP_ROUNDS, sliced);
        cm_port_mark_end();
    }
    ok &= memcmp(one, sliced, sizeof one) == 0;
    sh_puts(ok ? "mac_cost done\n" : "mac_cost FAILED\n");
    return 0;
}

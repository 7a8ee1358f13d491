/* hal.h on qemu's MPS2 boards: CAN over SLCAN, time, flash, random, keys, reset, watchdog
 * (see cm_port.h). Sensors and actuator: the sample and the command the main loop exchanges
 * with the board's plant (cm_plant.h, cm_port_sensors, cm_port_actuator). */
#include <string.h>

#include "boot_cm_flash.h"
#include "cm_board.h"
#include "cm_devinfo.h"
#include "cm_port.h"
#include "cm_slcan.h"
#include "cm_uart.h"
#include "hal.h"
#include "sec_aes.h"
#include "sec_sha256.h"
#include "cm_semihost.h"

#define CM_CAN_RX_QUEUE 256u /* received frames (power of two); overflow drops the newest */

/* The SLCAN text of the host waits in the UART's receive ring (cm_uart.c: the RX interrupt only
 * stores bytes). The port's loop parses it after the tick (cm_port_end_tick: the emulated CAN
 * controller's work, which a board with a CAN peripheral does in hardware), complete frames into
 * g_rx, each command's reply (z, or BEL) to the UART; hal_can_receive only copies a frame out of
 * g_rx, at most CM_PORT_RX_FRAMES_PER_TICK a tick. */
void SysTick_Handler(void);
void NMI_Handler(void);

static slcan_t g_slcan;
static can_frame_t g_rx[CM_CAN_RX_QUEUE];
static uint32_t g_rx_head, g_rx_tail; /* both written outside interrupts */
static uint32_t g_rx_dropped;
static uint32_t g_rx_taken; /* frames hal_can_receive returned this tick */
/* the transmit queue, its indices beside each other: one address for both in hal_can_send */
static struct {
    uint32_t head, tail;
    can_frame_t q[CM_PORT_TX_QUEUE];
} g_tx;
static volatile uint32_t g_ms; /* SysTick count since power-up */
static volatile uint32_t g_pending;
static volatile uint32_t g_busy;
static volatile uint32_t g_overruns;
static volatile uint32_t g_missed;
static volatile uint32_t g_skipped;
static uint32_t g_ms0;      /* g_ms when the ticks started */
static uint64_t g_host_us0; /* host time then (0: no pacing) */
static bool g_reset_requested;
static boot_cm_flash_t g_skill_fl, g_fw_fl, g_sec_fl;
static fls_dev_t g_skill_dev, g_fw_dev, g_sec_dev;
/* random: AES-128 in counter mode (the shape of SP 800-90A's CTR_DRBG) keyed from the seed */
static uint8_t g_pool[SEC_SHA256_LEN]; /* SHA-256 of the seed: key (16 bytes), counter (16) */
static sec_aes128_t g_drbg;
/* The emulated TRNG's FIFO (hal_random): two blocks drawn ahead, refilled after the tick. */
#define CM_RNG_FIFO_LEN (2u * SEC_AES_BLOCK)
static uint8_t g_rng_fifo[CM_RNG_FIFO_LEN];
static uint32_t g_rng_count;
static void rng_refill(void);

/* development key of the image tag (host/forceskill/model/fwimage.py DEV_KEY, docs/update.md) */
static const uint8_t g_fw_key[32] = {
    0x40, 0x41, 0x42, 0x43, 0x44, 0x45, 0x46, 0x47, 0x48, 0x49, 0x4a, 0x4b, 0x4c, 0x4d, 0x4e, 0x4f,
    0x50, 0x51, 0x52, 0x53, 0x54, 0x55, 0x56, 0x57, 0x58, 0x59, 0x5a, 0x5b, 0x5c, 0x5d, 0x5e, 0x5f};

void SysTick_Handler(void)
{
    g_ms = g_ms + 1u;
    if (g_busy != 0u) {
        g_missed = 1u; /* the running tick took longer than its period: an overrun */
    } else if (g_pending != 0u) {
        g_skipped = g_skipped + 1u; /* two SysTicks while the core slept: qemu caught up with
                                       host time (icount sleep), not the code's overrun */
    }
    g_pending = 1u;
}

void NMI_Handler(void)
{
    /* first watchdog expiry: stop feeding; the second expiry resets the board */
    for (;;) {
        __asm__ volatile("wfi");
    }
}

/* The SLCAN text received so far: complete frame commands into g_rx, each command's reply to
 * the UART (port loop, after the tick). */
static void can_rx_parse(void)
{
    uint8_t buf[CM_PORT_RX_CHUNK];
    uint32_t n;
    /* a chunk holds at most CM_PORT_RX_CHUNK commands: read one only with that much room, so a
     * backlog waits in the ring (and then in the UART and the host's socket), none is dropped */
    while (CM_CAN_RX_QUEUE - (g_rx_head - g_rx_tail) >= CM_PORT_RX_CHUNK &&
           (n = cm_uart_read(buf, CM_PORT_RX_CHUNK)) != 0u) {
        for (uint32_t i = 0u; i < n; i++) {
            if (slcan_take(&g_slcan, buf[i])) {
                continue; /* a character of the line: all but the line's end */
            }
            char reply[SLCAN_REPLY_MAX];
            uint32_t reply_len;
            can_frame_t f;
            if (slcan_feed(&g_slcan, buf[i], &f, reply, &reply_len)) {
                if (g_rx_head - g_rx_tail < CM_CAN_RX_QUEUE) {
                    g_rx[g_rx_head % CM_CAN_RX_QUEUE] = f;
                    g_rx_head++;
                } else {
                    g_rx_dropped++; /* as a CAN controller's receive overrun */
                }
            }
            if (reply_len > 0u) {
                (void)cm_uart_write(reply, reply_len);
            }
        }
    }
}

void cm_port_init(const uint8_t *seed, uint32_t seed_len)
{
    slcan_init(&g_slcan);
    g_rx_head = g_rx_tail = 0u;
    g_rx_dropped = 0u;
    g_tx.head = g_tx.tail = 0u;
    cm_uart_init();
    boot_cm_flash_init(&g_skill_fl, &g_skill_dev, CM_FLASH_SKILL_ADDR, CM_FLASH_SKILL_SECTOR,
                       CM_FLASH_SKILL_SECTORS);
    boot_cm_flash_init(&g_fw_fl, &g_fw_dev, CM_FLASH_FW_ADDR, CM_FLASH_FW_SECTOR,
                       CM_FLASH_FW_SECTORS);
    boot_cm_flash_init(&g_sec_fl, &g_sec_dev, CM_FLASH_SEC_ADDR, CM_FLASH_SEC_SECTOR, 2u);
    sec_sha256(seed, seed_len, g_pool);
    sec_aes128_init(&g_drbg, g_pool);
    g_rng_count = 0u;
    rng_refill();
    rng_refill();
}

void cm_port_start_ticks(bool pace)
{
    g_ms0 = g_ms;
    g_host_us0 = pace ? sh_host_elapsed_us() : 0u;
    CM_WDG_LOCK = CM_WDG_UNLOCK_KEY;
    CM_WDG_LOAD = CM_CORE_CLOCK_HZ / 1000u * CM_PORT_WDG_TIMEOUT_MS;
    CM_WDG_CTRL = CM_WDG_CTRL_INTEN_RESEN;
    CM_WDG_LOCK = 0u;
    CM_SCB_SHPR3 = (CM_SCB_SHPR3 & 0x00FFFFFFu) | 0x80000000u;
    CM_SYST_RVR = CM_CORE_CLOCK_HZ / CM_PORT_TICK_HZ - 1u;
    CM_SYST_CVR = 0u;
    CM_SYST_CSR = CM_SYST_CSR_ENABLE_TICKINT_CLK;
    cm_uart_rx_budget(CM_PORT_RX_BYTES_PER_TICK); /* the first period's (cm_port_end_tick) */
}

bool cm_port_wait_tick(void)
{
    /* pacing: the board's clock follows its instructions (qemu -icount, idle time skipped), so
     * while the device is ahead of the host's clock, the SysTick is held (it does not count the
     * instructions of this wait) until the host has caught up */
    const uint64_t due_us = (uint64_t)(g_ms - g_ms0) * 1000u;
    if (g_host_us0 != 0u && sh_host_elapsed_us() - g_host_us0 < due_us) {
        CM_SYST_CSR = 0u;
        while (sh_host_elapsed_us() - g_host_us0 < due_us) {
            /* between two looks at the host's clock, CM_PORT_PACE_SPIN iterations without a
             * semihosting call: each call takes qemu's global lock, which the I/O thread
             * needs to hand the UART its received bytes */
            for (volatile uint32_t n = 0u; n < CM_PORT_PACE_SPIN; n = n + 1u) {
            }
        }
        CM_SYST_CSR = CM_SYST_CSR_ENABLE_TICKINT_CLK;
    }
    while (g_pending == 0u) {
        __asm__ volatile("wfi");
    }
    __asm__ volatile("cpsid i" ::: "memory");
    g_pending = 0u;
    g_busy = 1u;
    const bool missed = g_missed != 0u;
    g_missed = 0u;
    __asm__ volatile("cpsie i" ::: "memory");
    cm_uart_rx_cap(CM_PORT_RX_BYTES_IN_TICK); /* the baud rate's bytes while the tick runs */
    g_rx_taken = 0u;
    if (missed) {
        g_overruns = g_overruns + 1u;
    }
    return missed;
}

/* Frames of the transmit queue to the UART as SLCAN text: at most budget frames. */
static void can_tx_drain(uint32_t budget)
{
    for (uint32_t n = 0u; n < budget && g_tx.tail != g_tx.head; n++) {
        char text[SLCAN_FRAME_TEXT_MAX];
        const uint32_t len = slcan_encode(&g_tx.q[g_tx.tail % CM_PORT_TX_QUEUE], text);
        if (g_slcan.open && !cm_uart_write(text, len)) {
            return; /* the host does not read: retry next tick */
        }
        g_tx.tail++;
    }
}

void cm_port_end_tick(void)
{
    can_tx_drain(CM_PORT_TX_FRAMES_PER_TICK);
    can_rx_parse();
    /* the next period's receive budget from now, after the tick: bytes that waited for it are
     * taken in the slack before the next tick, not in bulk inside it */
    cm_uart_rx_budget(CM_PORT_RX_BYTES_PER_TICK);
    rng_refill();
    CM_WDG_LOCK = CM_WDG_UNLOCK_KEY;
    CM_WDG_INTCLR = 1u; /* reload the watchdog */
    CM_WDG_LOCK = 0u;
    if (g_reset_requested) {
        __asm__ volatile("dsb" ::: "memory");
        CM_SCB_AIRCR = CM_SCB_AIRCR_SYSRESETREQ;
        for (;;) {
            __asm__ volatile("wfi");
        }
    }
    g_busy = 0u;
}

/* The millisecond count and SysTick's current value read as one pair (read again when the
 * SysTick interrupt moved the count in between). */
static void systick_sample(uint32_t *ms, uint32_t *cvr)
{
    do {
        *ms = g_ms;
        *cvr = CM_SYST_CVR;
    } while (*ms != g_ms);
}

uint32_t cm_port_cycles(void)
{
    uint32_t ms;
    uint32_t cvr;
    systick_sample(&ms, &cvr);
    return ms * (CM_SYST_RVR + 1u) + (CM_SYST_RVR - cvr);
}

uint32_t cm_port_overruns(void)
{
    return g_overruns;
}

uint32_t cm_port_skipped(void)
{
    return g_skipped;
}

/* ---- CAN over SLCAN ---- */

/* hal_can_send with at most limit frames already queued (hal_can_send: CM_PORT_TX_QUEUE - 1). */
static inline bool can_send_within(const can_frame_t *frame, uint32_t limit)
{
    if (frame->id > CAN_STD_ID_MASK || frame->len > CAN_CLASSIC_MAX_LEN ||
        (frame->flags & CAN_FRAME_FD) != 0u) {
        return true; /* not a classic frame (SLCAN carries no other): nothing to send */
    }
    if (!g_slcan.open) {
        return true; /* no adapter listening: the frame is lost */
    }
    const uint32_t head = g_tx.head;
    if (head - g_tx.tail > limit) {
        return false;
    }
    g_tx.q[head % CM_PORT_TX_QUEUE] = *frame;
    g_tx.head = head + 1u;
    return true;
}

bool hal_can_send(const can_frame_t *frame)
{
    return can_send_within(frame, CM_PORT_TX_QUEUE - 1u);
}

uint32_t hal_can_tx_free(void)
{
    return CM_PORT_TX_QUEUE - (g_tx.head - g_tx.tail);
}

bool hal_can_send_bulk(const can_frame_t *frame, uint32_t keep)
{
    /* more than keep places free after it: at most CM_PORT_TX_QUEUE - 1 - keep frames queued
     * (one test of the queue's fill, the telemetry's two frames a tick pass here) */
    return keep < CM_PORT_TX_QUEUE && can_send_within(frame, CM_PORT_TX_QUEUE - 1u - keep);
}

bool hal_can_receive(can_frame_t *frame)
{
    const uint32_t t = g_rx_tail;
    if (t == g_rx_head || g_rx_taken >= CM_PORT_RX_FRAMES_PER_TICK) {
        return false; /* none, or this tick's share taken: the rest wait for the next tick */
    }
    *frame = g_rx[t % CM_CAN_RX_QUEUE];
    g_rx_tail = t + 1u;
    g_rx_taken++;
    return true;
}

uint32_t cm_port_rx_dropped(void)
{
    return g_rx_dropped;
}

bool hal_can_bus_off(void)
{
    return false;
}

bool hal_can_tx_idle(void)
{
    return g_tx.tail == g_tx.head && cm_uart_tx_empty();
}

/* ---- time ---- */

uint64_t hal_time_us_ms(uint32_t *now_ms)
{
    uint32_t ms;
    uint32_t cvr;
    systick_sample(&ms, &cvr);
    const uint32_t per_us = CM_CORE_CLOCK_HZ / 1000000u;
    const uint32_t sub_us = (CM_SYST_RVR - cvr) / per_us;
    *now_ms = ms; /* the SysTick count: below it less than 1,000 us */
    return (uint64_t)ms * 1000u + (uint64_t)(sub_us < 1000u ? sub_us : 999u);
}

uint64_t hal_time_us(void)
{
    uint32_t ms;
    return hal_time_us_ms(&ms);
}

/* ---- platform ---- */

/* One block of the board's random stream: the board has no entropy source, so AES-128 of a
 * 128-bit counter under the key drawn from the seed `hil_sim pil` passes at start (from the
 * host's getrandom), the SysTick phase of each call mixed into the counter; ~700 instructions (a
 * SHA-256 chain cost ~10,000 a call). */
static void rng_block(uint8_t out[SEC_AES_BLOCK])
{
    uint8_t *ctr = &g_pool[SEC_AES128_KEY_LEN];
    const uint32_t phase = CM_SYST_CVR;
    for (uint32_t i = 0u; i < 4u; i++) {
        ctr[i] ^= (uint8_t)(phase >> (8u * i));
    }
    uint32_t carry = 1u; /* bytes 4..15: a counter, +1 a block, the same instructions whatever
                            its value (the boot's instructions do not depend on the seed) */
    for (uint32_t i = SEC_AES_BLOCK; i-- > 4u;) {
        const uint32_t v = ctr[i] + carry;
        ctr[i] = (uint8_t)v;
        carry = v >> 8;
    }
    sec_aes128_encrypt(&g_drbg, ctr, out);
}

/* A block into the FIFO if it has room for one: after the tick, as a TRNG peripheral fills its
 * FIFO beside the core, so a seed drawn in a tick costs a copy, not an encryption. */
static void rng_refill(void)
{
    if (g_rng_count + SEC_AES_BLOCK <= CM_RNG_FIFO_LEN) {
        rng_block(&g_rng_fifo[g_rng_count]);
        g_rng_count += SEC_AES_BLOCK;
    }
}

int hal_random(uint8_t *buf, uint32_t len)
{
    uint32_t done = 0u;
    while (done < len) {
        if (g_rng_count == 0u) { /* drawn faster than refilled: a block now */
            rng_refill();
        }
        const uint32_t n = (len - done < g_rng_count) ? len - done : g_rng_count;
        const uint32_t from = g_rng_count - n; /* the FIFO's newest bytes first */
        memcpy(&buf[done], &g_rng_fifo[from], n);
        memset(&g_rng_fifo[from], 0, n); /* a byte is given once */
        g_rng_count = from;
        done += n;
    }
    return 0;
}

const fls_dev_t *hal_flash(void)
{
    return &g_skill_dev;
}

const fls_dev_t *hal_fw_flash(void)
{
    return &g_fw_dev;
}

uint32_t hal_fw_slot_sectors(void)
{
    return CM_FLASH_FW_SLOT_SECTORS;
}

const uint8_t *hal_fw_key(uint8_t *len)
{
    *len = (uint8_t)sizeof(g_fw_key);
    return g_fw_key;
}

static uint32_t devinfo_u32(const volatile uint8_t *p)
{
    return (uint32_t)p[0] | ((uint32_t)p[1] << 8) | ((uint32_t)p[2] << 16) | ((uint32_t)p[3] << 24);
}

const uint8_t *hal_device_secret(uint8_t level, uint8_t *len)
{
    /* from the device-unique area (cm_devinfo.h); unknown level or unprovisioned board: 0 */
    const volatile uint8_t *d = (const volatile uint8_t *)(uintptr_t)CM_DEVINFO_ADDR;
    const uint32_t i = level == 1u ? 0u : (level == 3u ? 1u : CM_DEVINFO_LEVELS);
    *len = 0u;
    if (i >= CM_DEVINFO_LEVELS || devinfo_u32(d) != CM_DEVINFO_MAGIC ||
        devinfo_u32(&d[4]) != CM_DEVINFO_VERSION) {
        return (const uint8_t *)(uintptr_t)CM_DEVINFO_ADDR;
    }
    const uint32_t off = CM_DEVINFO_SECRET_OFF(i);
    const uint8_t n = d[off];
    if (n >= 1u && n <= CM_DEVINFO_SECRET_MAX) {
        *len = n;
    }
    return (const uint8_t *)(uintptr_t)(CM_DEVINFO_ADDR + off + 1u);
}

const fls_dev_t *hal_sec_flash(void)
{
    return &g_sec_dev;
}

void hal_request_reset(uint8_t type)
{
    (void)type;
    g_reset_requested = true;
}

/* ---- sensors and actuator: what the main loop exchanges with the plant ---- */

static hal_sensors_t g_sens;
static bool g_act_enable;
static fs_real_t g_act_force_N[HAL_AXES];

hal_sensors_t *cm_port_sensors(void)
{
    return &g_sens;
}

bool cm_port_actuator(fs_real_t force_N[HAL_AXES])
{
    for (uint32_t i = 0u; i < HAL_AXES; i++) {
        force_N[i] = g_act_force_N[i];
    }
    return g_act_enable;
}

void hal_sensors_read(hal_sensors_t *out)
{
    *out = g_sens;
}

void hal_actuator_enable(bool enable)
{
    g_act_enable = enable;
    if (!enable) {
        for (uint32_t i = 0u; i < HAL_AXES; i++) {
            g_act_force_N[i] = FS_R(0.0);
        }
    }
}

void hal_actuator_force(const fs_real_t force_N[HAL_AXES])
{
    if (g_act_enable) {
        for (uint32_t i = 0u; i < HAL_AXES; i++) {
            g_act_force_N[i] = force_N[i];
        }
    }
}

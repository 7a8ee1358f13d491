/* Host port, common part (see hal_host.h). */
#define _GNU_SOURCE
#include "hal_host.h"

#include <string.h>
#include <sys/random.h>
#include <time.h>

#include "fls_ram.h"

static struct {
    bool manual_time;
    uint64_t t_us;
    hal_sensors_t sens;
    bool act_enable;
    fs_real_t act_force_N[HAL_AXES];
    uint8_t secret[2][64]; /* level 1, level 3 */
    uint8_t secret_len[2];
    bool reset_requested;
    uint8_t reset_type;
} g;

static fls_ram_t g_fls;
static fls_dev_t g_dev;
static uint8_t g_flash_mem[HAL_HOST_FLASH_SECTOR * HAL_HOST_FLASH_SECTORS];
static bool g_flash_ready;
static fls_ram_t g_fw_fls;
static fls_dev_t g_fw_dev;
static uint8_t g_fw_mem[HAL_HOST_FW_SECTOR * HAL_HOST_FW_SECTORS];
static bool g_fw_ready;
static fls_ram_t g_sec_fls;
static fls_dev_t g_sec_dev;
static uint8_t g_sec_mem[HAL_HOST_SEC_SECTOR * 2u];
/* development key of the image tag (host/forceskill/model/fwimage.py DEV_KEY, docs/update.md) */
static const uint8_t g_fw_key[32] = {
    0x40, 0x41, 0x42, 0x43, 0x44, 0x45, 0x46, 0x47, 0x48, 0x49, 0x4a, 0x4b, 0x4c, 0x4d, 0x4e, 0x4f,
    0x50, 0x51, 0x52, 0x53, 0x54, 0x55, 0x56, 0x57, 0x58, 0x59, 0x5a, 0x5b, 0x5c, 0x5d, 0x5e, 0x5f};

/* Power-cut injection (hal_host_flash_cut_after): every region's erase and program go through
 * these shims, counted in one sequence; the fls_ram device stays each region's ctx. */
static fls_dev_t g_raw[HAL_HOST_FLASH_REGIONS]; /* fls_ram's own functions, per region */
static struct {
    uint32_t ops;  /* operations since hal_host_flash_erase */
    uint32_t left; /* operations before the cut, while armed */
    bool armed, cut;
    hal_host_flash_op_t log[HAL_HOST_FLASH_LOG];
} g_cut;

static int region_of(const void *ctx)
{
    for (int k = 0; k < (int)HAL_HOST_FLASH_REGIONS; k++) {
        if (g_raw[k].ctx == ctx) {
            return k;
        }
    }
    return -1;
}

/* True if the power is still on for one more operation (then counted and logged). */
static bool op_allowed(int region, uint8_t kind, uint32_t addr, uint32_t len)
{
    if (region < 0 || g_cut.cut) {
        return false;
    }
    if (g_cut.armed) {
        if (g_cut.left == 0u) {
            g_cut.cut = true; /* the power is gone: this and every later operation fail */
            return false;
        }
        g_cut.left--;
    }
    if (g_cut.ops < HAL_HOST_FLASH_LOG) {
        const hal_host_flash_op_t o = {(uint8_t)region, kind, addr, len};
        g_cut.log[g_cut.ops] = o;
    }
    g_cut.ops++;
    return true;
}

static int shim_erase(void *ctx, uint32_t sector)
{
    const int k = region_of(ctx);
    if (!op_allowed(k, 0u, k < 0 ? 0u : sector * g_raw[k].sector_size, 0u)) {
        return -1;
    }
    return g_raw[k].erase(ctx, sector);
}

static int shim_program(void *ctx, uint32_t addr, const uint8_t *data, uint32_t len)
{
    const int k = region_of(ctx);
    if (!op_allowed(k, 1u, addr, len)) {
        return -1;
    }
    return g_raw[k].program(ctx, addr, data, len);
}

static void shim(fls_dev_t *dev, unsigned region)
{
    g_raw[region] = *dev;
    dev->erase = shim_erase;
    dev->program = shim_program;
}

void hal_host_flash_cut_after(uint32_t n)
{
    g_cut.armed = true;
    g_cut.left = n;
    g_cut.cut = false;
}

bool hal_host_flash_cut(void)
{
    return g_cut.cut;
}

void hal_host_flash_power_on(void)
{
    g_cut.armed = false;
    g_cut.cut = false;
}

uint32_t hal_host_flash_ops(void)
{
    return g_cut.ops;
}

const hal_host_flash_op_t *hal_host_flash_op(uint32_t i)
{
    return i < g_cut.ops && i < HAL_HOST_FLASH_LOG ? &g_cut.log[i] : NULL;
}

void hal_host_fw_flash_erase(void)
{
    memset(g_fw_mem, 0xFF, sizeof(g_fw_mem));
    fls_ram_init(&g_fw_fls, &g_fw_dev, g_fw_mem, HAL_HOST_FW_SECTOR, HAL_HOST_FW_SECTORS, 4u);
    shim(&g_fw_dev, HAL_HOST_REGION_FIRMWARE);
    g_fw_ready = true;
}

void hal_host_init(void)
{
    memset(&g, 0, sizeof(g));
    g.secret_len[0] = (uint8_t)strlen(HAL_HOST_SECRET_DEFAULT);
    memcpy(g.secret[0], HAL_HOST_SECRET_DEFAULT, g.secret_len[0]);
    g.secret_len[1] = (uint8_t)strlen(HAL_HOST_FW_SECRET_DEFAULT);
    memcpy(g.secret[1], HAL_HOST_FW_SECRET_DEFAULT, g.secret_len[1]);
    if (!g_flash_ready) {
        hal_host_flash_erase();
    }
}

void hal_host_flash_erase(void)
{
    memset(g_flash_mem, 0xFF, sizeof(g_flash_mem));
    fls_ram_init(&g_fls, &g_dev, g_flash_mem, HAL_HOST_FLASH_SECTOR, HAL_HOST_FLASH_SECTORS, 4u);
    shim(&g_dev, HAL_HOST_REGION_SLOTS);
    memset(g_sec_mem, 0xFF, sizeof(g_sec_mem));
    fls_ram_init(&g_sec_fls, &g_sec_dev, g_sec_mem, HAL_HOST_SEC_SECTOR, 2u, 4u);
    shim(&g_sec_dev, HAL_HOST_REGION_SECURITY);
    g_flash_ready = true;
    g_cut.ops = 0u;
}

void hal_host_set_time_us(uint64_t t_us)
{
    g.manual_time = true;
    g.t_us = t_us;
}

uint64_t hal_time_us(void)
{
    if (g.manual_time) {
        return g.t_us;
    }
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (uint64_t)ts.tv_sec * 1000000u + (uint64_t)ts.tv_nsec / 1000u;
}

uint64_t hal_time_us_ms(uint32_t *now_ms)
{
    const uint64_t us = hal_time_us();
    *now_ms = (uint32_t)(us / 1000u);
    return us;
}

void hal_host_set_sensors(const hal_sensors_t *s)
{
    g.sens = *s;
}

void hal_sensors_read(hal_sensors_t *out)
{
    *out = g.sens;
}

void hal_actuator_enable(bool enable)
{
    g.act_enable = enable;
    if (!enable) {
        g.act_force_N[0] = FS_R(0.0);
        g.act_force_N[1] = FS_R(0.0);
    }
}

void hal_actuator_force(const fs_real_t force_N[HAL_AXES])
{
    if (g.act_enable) {
        g.act_force_N[0] = force_N[0];
        g.act_force_N[1] = force_N[1];
    }
}

void hal_host_get_actuator(bool *enable, fs_real_t force_N[HAL_AXES])
{
    *enable = g.act_enable;
    force_N[0] = g.act_force_N[0];
    force_N[1] = g.act_force_N[1];
}

int hal_random(uint8_t *buf, uint32_t len)
{
    uint32_t done = 0u;
    while (done < len) {
        const ssize_t n = getrandom(buf + done, len - done, 0);
        if (n <= 0) {
            return -1;
        }
        done += (uint32_t)n;
    }
    return 0;
}

const fls_dev_t *hal_flash(void)
{
    if (!g_flash_ready) {
        hal_host_flash_erase();
    }
    return &g_dev;
}

const fls_dev_t *hal_fw_flash(void)
{
    if (!g_fw_ready) {
        hal_host_fw_flash_erase();
    }
    return &g_fw_dev;
}

uint32_t hal_fw_slot_sectors(void)
{
    return HAL_HOST_FW_SLOT_SECTORS;
}

const uint8_t *hal_fw_key(uint8_t *len)
{
    *len = (uint8_t)sizeof(g_fw_key);
    return g_fw_key;
}

/* index of a level's secret: 0 for level 1, 1 for level 3, -1 otherwise */
static int secret_index(uint8_t level)
{
    return level == 1u ? 0 : (level == 3u ? 1 : -1);
}

void hal_host_set_secret(uint8_t level, const uint8_t *secret, uint8_t len)
{
    const int i = secret_index(level);
    if (i < 0) {
        return;
    }
    if (len > sizeof(g.secret[0])) {
        len = (uint8_t)sizeof(g.secret[0]);
    }
    memcpy(g.secret[i], secret, len);
    g.secret_len[i] = len;
}

const uint8_t *hal_device_secret(uint8_t level, uint8_t *len)
{
    const int i = secret_index(level);
    *len = i < 0 ? 0u : g.secret_len[i];
    return i < 0 ? g.secret[0] : g.secret[i];
}

const fls_dev_t *hal_sec_flash(void)
{
    if (!g_flash_ready) {
        hal_host_flash_erase();
    }
    return &g_sec_dev;
}

void hal_request_reset(uint8_t type)
{
    g.reset_requested = true;
    g.reset_type = type;
}

bool hal_host_take_reset(uint8_t *type)
{
    if (!g.reset_requested) {
        return false;
    }
    g.reset_requested = false;
    *type = g.reset_type;
    return true;
}

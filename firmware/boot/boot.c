/* Bootloader decision logic (boot.h). */
#include "boot.h"
#include "boot_verify.h"

#include <stddef.h>
#include <string.h>

static void wr_u32(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)v;
    p[1] = (uint8_t)(v >> 8);
    p[2] = (uint8_t)(v >> 16);
    p[3] = (uint8_t)(v >> 24);
}

static uint32_t rd_u32(const uint8_t *p)
{
    return (uint32_t)p[0] | ((uint32_t)p[1] << 8) | ((uint32_t)p[2] << 16) | ((uint32_t)p[3] << 24);
}

static void state_fresh(boot_state_t *s)
{
    s->active_slot = BOOT_SLOT_NONE;
    s->test_slot = BOOT_SLOT_NONE;
    s->test_attempts = 0u;
    s->confirmed = 0u;
    s->test_flags = 0u;
    s->active_version = 0u;
}

static bool slot_ok(uint8_t s)
{
    return s < BOOT_SLOT_COUNT;
}

void boot_state_encode(const boot_state_t *s, uint8_t out[BOOT_STATE_LEN])
{
    out[0] = BOOT_STATE_VERSION;
    out[1] = s->active_slot;
    out[2] = s->test_slot;
    out[3] = s->test_attempts;
    out[4] = s->confirmed;
    out[5] = s->test_flags;
    out[6] = 0u;
    out[7] = 0u;
    wr_u32(&out[8], s->active_version);
    wr_u32(&out[12], 0u);
}

bool boot_state_decode(const uint8_t in[BOOT_STATE_LEN], boot_state_t *s)
{
    if (in[0] != BOOT_STATE_VERSION || (!slot_ok(in[1]) && in[1] != BOOT_SLOT_NONE) ||
        (!slot_ok(in[2]) && in[2] != BOOT_SLOT_NONE) || in[3] > 1u) {
        return false;
    }
    s->active_slot = in[1];
    s->test_slot = in[2];
    s->test_attempts = in[3];
    s->confirmed = in[4] != 0u ? 1u : 0u;
    s->test_flags = in[5];
    s->active_version = rd_u32(&in[8]);
    return true;
}

bool boot_state_load(const boot_config_t *cfg, boot_state_t *s)
{
    uint8_t buf[BOOT_STATE_LEN];
    uint32_t len = 0u;
    if (nvm_read(cfg->state_nvm, cfg->state_slot, buf, (uint32_t)sizeof buf, &len) == NVM_OK &&
        len == BOOT_STATE_LEN && boot_state_decode(buf, s)) {
        return true;
    }
    state_fresh(s);
    return false;
}

boot_status_t boot_state_store(const boot_config_t *cfg, const boot_state_t *s)
{
    uint8_t buf[BOOT_STATE_LEN];
    boot_state_encode(s, buf);
    return nvm_write(cfg->state_nvm, cfg->state_slot, buf, BOOT_STATE_LEN) == NVM_OK
               ? BOOT_OK
               : BOOT_ERR_FLASH;
}

boot_status_t boot_slot_verify(const boot_config_t *cfg, uint8_t slot, boot_image_header_t *out)
{
    if (cfg == NULL || out == NULL || !slot_ok(slot)) {
        return BOOT_ERR_ARG;
    }
    return boot_image_verify(cfg->app_dev, cfg->slot_addr[slot], cfg->slot_size, cfg->target_id,
                             cfg->key, cfg->key_len, out);
}

boot_status_t boot_check_candidate(const boot_t *b, const boot_image_header_t *h, uint8_t flags)
{
    const boot_config_t *cfg = b->cfg;
    const bool have_running = slot_ok(b->running_slot);
    if (have_running && h->fw_version < b->running.fw_version &&
        (flags & BOOT_FLAG_ALLOW_DOWNGRADE) == 0u) {
        return BOOT_ERR_DOWNGRADE;
    }
    return boot_image_check_data(h, cfg->skill_min, cfg->skill_max, cfg->config_min,
                                 cfg->config_max);
}

/* Start slot s (already verified into *h). */
static void run(boot_t *b, uint8_t s, const boot_image_header_t *h, boot_path_t path)
{
    b->running_slot = s;
    b->running = *h;
    b->path = path;
}

/* A pending test image: try it once (the attempt recorded before the jump), or drop it after
 * a refusal or an unconfirmed earlier try. Returns true when it runs (b->path says why not). */
static bool try_test_image(boot_t *b, const boot_config_t *cfg, boot_status_t act_st,
                           const boot_image_header_t *act)
{
    boot_state_t *s = &b->state;
    const uint8_t t = s->test_slot;
    boot_image_header_t h;
    if (s->test_attempts != 0u || t == s->active_slot) {
        /* booted once and never confirmed (or nonsense): revert */
        b->path = BOOT_PATH_REVERTED;
        s->test_slot = BOOT_SLOT_NONE;
        s->test_attempts = 0u;
        s->test_flags = 0u;
        return false;
    }
    boot_status_t st = boot_slot_verify(cfg, t, &h);
    if (st == BOOT_OK) {
        /* downgrade is judged against the active image */
        b->running_slot = act_st == BOOT_OK ? s->active_slot : BOOT_SLOT_NONE;
        b->running = *act;
        st = boot_check_candidate(b, &h, s->test_flags);
        b->running_slot = BOOT_SLOT_NONE;
    }
    if (st != BOOT_OK) {
        b->refusal = st;
        b->path = BOOT_PATH_TEST_REFUSED;
        s->test_slot = BOOT_SLOT_NONE;
        s->test_flags = 0u;
        return false;
    }
    s->test_attempts = 1u; /* recorded BEFORE the jump: one try only */
    if (boot_state_store(cfg, s) == BOOT_OK) {
        b->test_boot = 1u;
        run(b, t, &h, BOOT_PATH_TEST);
        return true;
    }
    /* could not record the attempt: do not risk an unbounded test loop */
    s->test_attempts = 0u;
    b->refusal = BOOT_ERR_FLASH;
    b->path = BOOT_PATH_TEST_REFUSED;
    return false;
}

/* Recovery / first boot: the best image that verifies, other than the active slot (highest
 * version, A on a tie) into *best_h; its slot, or BOOT_SLOT_NONE. */
static uint8_t best_image(const boot_config_t *cfg, uint8_t active, boot_image_header_t *best_h)
{
    uint8_t best = BOOT_SLOT_NONE;
    boot_image_header_t h;
    memset(best_h, 0, sizeof *best_h);
    for (uint8_t i = 0u; i < BOOT_SLOT_COUNT; i++) {
        if (i == active) {
            continue;
        }
        boot_status_t st = boot_slot_verify(cfg, i, &h);
        if (st == BOOT_OK) {
            st = boot_image_check_data(&h, cfg->skill_min, cfg->skill_max, cfg->config_min,
                                       cfg->config_max);
        }
        if (st == BOOT_OK && (best == BOOT_SLOT_NONE || h.fw_version > best_h->fw_version)) {
            best = i;
            *best_h = h;
        }
    }
    return best;
}

boot_status_t boot_select(boot_t *b, const boot_config_t *cfg)
{
    if (b == NULL || cfg == NULL) {
        return BOOT_ERR_ARG;
    }
    b->cfg = cfg;
    b->running_slot = BOOT_SLOT_NONE;
    b->test_boot = 0u;
    b->path = BOOT_PATH_NONE;
    b->refusal = BOOT_OK;
    const bool had_record = boot_state_load(cfg, &b->state);
    boot_state_t *s = &b->state;

    /* The active image's header (for the downgrade rule), if it verifies. */
    boot_image_header_t act;
    memset(&act, 0, sizeof act);
    boot_status_t act_st = slot_ok(s->active_slot) ? boot_slot_verify(cfg, s->active_slot, &act)
                                                   : BOOT_ERR_NO_IMAGE;
    if (slot_ok(s->test_slot) && try_test_image(b, cfg, act_st, &act)) {
        return BOOT_OK;
    }

    const boot_path_t why = b->path;
    if (act_st == BOOT_OK) {
        if (why != BOOT_PATH_NONE) {
            (void)boot_state_store(cfg, s); /* test dropped; if this write fails, the next
                                                 reset decides the same way again */
        }
        run(b, s->active_slot, &act, why == BOOT_PATH_NONE ? BOOT_PATH_ACTIVE : why);
        return BOOT_OK;
    }
    if (slot_ok(s->active_slot) && b->refusal == BOOT_OK) {
        b->refusal = act_st;
    }
    boot_image_header_t best_h;
    const uint8_t best = best_image(cfg, s->active_slot, &best_h);
    if (best == BOOT_SLOT_NONE) {
        return BOOT_ERR_NO_IMAGE;
    }
    s->active_slot = best;
    s->active_version = best_h.fw_version;
    s->confirmed = 1u; /* an image that booted before, or the factory image */
    s->test_slot = BOOT_SLOT_NONE;
    s->test_attempts = 0u;
    (void)boot_state_store(cfg, s);
    run(b, best, &best_h, had_record ? BOOT_PATH_RECOVERED : BOOT_PATH_FIRST);
    return BOOT_OK;
}

boot_status_t boot_confirm(boot_t *b)
{
    if (b == NULL || b->cfg == NULL) {
        return BOOT_ERR_ARG;
    }
    if (!b->test_boot) {
        return BOOT_OK;
    }
    boot_state_t s = b->state;
    s.active_slot = b->running_slot;
    s.active_version = b->running.fw_version;
    s.confirmed = 1u;
    s.test_slot = BOOT_SLOT_NONE;
    s.test_attempts = 0u;
    s.test_flags = 0u;
    const boot_status_t st = boot_state_store(b->cfg, &s);
    if (st == BOOT_OK) {
        b->state = s;
        b->test_boot = 0u;
    }
    return st;
}

boot_status_t boot_confirm_slot(const boot_config_t *cfg, uint8_t slot)
{
    if (cfg == NULL || !slot_ok(slot)) {
        return BOOT_ERR_ARG;
    }
    boot_state_t s;
    if (!boot_state_load(cfg, &s) || s.test_slot != slot || s.test_attempts != 1u) {
        return BOOT_OK;
    }
    boot_image_header_t h;
    const boot_status_t st = boot_slot_verify(cfg, slot, &h);
    if (st != BOOT_OK) {
        return st;
    }
    s.active_slot = slot;
    s.active_version = h.fw_version;
    s.confirmed = 1u;
    s.test_slot = BOOT_SLOT_NONE;
    s.test_attempts = 0u;
    s.test_flags = 0u;
    return boot_state_store(cfg, &s);
}

boot_status_t boot_mark_test(boot_t *b, uint8_t slot, uint8_t flags)
{
    if (b == NULL || b->cfg == NULL || !slot_ok(slot)) {
        return BOOT_ERR_ARG;
    }
    if (b->test_boot) {
        return FWU_ERR_TEST_PENDING;
    }
    if (slot == b->running_slot) {
        return BOOT_ERR_ARG;
    }
    boot_image_header_t h;
    boot_status_t st = boot_slot_verify(b->cfg, slot, &h);
    if (st == BOOT_OK) {
        st = boot_check_candidate(b, &h, flags);
    }
    if (st != BOOT_OK) {
        return st;
    }
    boot_state_t s = b->state;
    s.test_slot = slot;
    s.test_attempts = 0u;
    s.test_flags = flags & BOOT_FLAG_ALLOW_DOWNGRADE;
    st = boot_state_store(b->cfg, &s);
    if (st == BOOT_OK) {
        b->state = s;
    }
    return st;
}

uint8_t boot_inactive_slot(const boot_t *b)
{
    if (slot_ok(b->running_slot)) {
        return (uint8_t)(1u - b->running_slot);
    }
    return 0u;
}

/* Skill bank with a tick-boundary swap: see nvm_bank.h. */
#include "nvm_bank.h"

#include <stddef.h>

void nvm_bank_init(nvm_bank_t *b)
{
    if (b == NULL) {
        return;
    }
    b->active = 0u;
    b->has_active = 0u;
    b->pending = 0u;
    b->active_slot = 0u;
    b->pending_slot = 0u;
}

nvm_status_t nvm_bank_stage(nvm_bank_t *b, const nvm_t *n, uint16_t slot, uint8_t *scratch,
                            uint32_t cap, fs_status_t *parse_status)
{
    if (parse_status != NULL) {
        *parse_status = FS_OK;
    }
    if (b == NULL || n == NULL || scratch == NULL) {
        return NVM_ERR_NULL_ARG;
    }
    /* Withdraw any staged skill before overwriting its buffer: the tick (which may interrupt
     * this function) then never swaps in a half-written buffer. */
    b->pending = 0u;
    uint32_t len = 0u;
    nvm_status_t s = nvm_read(n, slot, scratch, cap, &len);
    if (s != NVM_OK) {
        return s;
    }
    skill_t *dst = &b->buf[(b->active + 1u) & 1u];
    const fs_status_t ps = skill_parse(scratch, len, dst);
    if (parse_status != NULL) {
        *parse_status = ps;
    }
    if (ps != FS_OK) {
        return NVM_ERR_PAYLOAD;
    }
    b->pending_slot = slot;
    b->pending = 1u;
    return NVM_OK;
}

bool nvm_bank_tick(nvm_bank_t *b, bool idle)
{
    if (b == NULL || b->pending == 0u || !idle) {
        return false;
    }
    b->active = (uint8_t)((b->active + 1u) & 1u);
    b->active_slot = b->pending_slot;
    b->has_active = 1u;
    b->pending = 0u;
    return true;
}

const skill_t *nvm_bank_active(const nvm_bank_t *b)
{
    if (b == NULL || b->has_active == 0u) {
        return NULL;
    }
    return &b->buf[b->active];
}

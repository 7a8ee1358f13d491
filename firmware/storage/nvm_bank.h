/* Skill bank: the active skill and a staged one, swapped at a tick boundary (moteus-style
 * pointer swap). Loading (flash read + skill_parse) happens outside the tick; the tick only
 * calls nvm_bank_tick, which is constant time. Built twice like the core (double / float). */
#ifndef NVM_BANK_H
#define NVM_BANK_H

#include <stdbool.h>
#include <stdint.h>
#include "nvm.h"
#include "skill.h"

#ifdef FS_REAL_FLOAT
#define nvm_bank_init nvm_bank_init_f32
#define nvm_bank_stage nvm_bank_stage_f32
#define nvm_bank_tick nvm_bank_tick_f32
#define nvm_bank_active nvm_bank_active_f32
#endif

/** Two skill buffers and a pointer: a new skill is loaded into the inactive buffer outside the
 *  tick, and becomes active only at a tick boundary while idle (moteus-style swap). */
typedef struct {
    skill_t buf[2];
    uint8_t active;     /* index of the active buffer */
    uint8_t has_active; /* a skill is active */
    uint8_t pending;    /* buf[!active] holds a validated skill waiting for the swap */
    uint16_t active_slot;
    uint16_t pending_slot;
} nvm_bank_t;

/** Empty bank. */
void nvm_bank_init(nvm_bank_t *b);

/** Read slot from storage, validate it with skill_parse into the inactive buffer and mark it
 *  pending (scratch: cap bytes of working memory for the image). On any error the active skill
 *  is untouched and nothing is pending. *parse_status gets skill_parse's result (may be NULL). */
nvm_status_t nvm_bank_stage(nvm_bank_t *b, const nvm_t *n, uint16_t slot, uint8_t *scratch,
                            uint32_t cap, fs_status_t *parse_status);

/** Call at the start of a tick: if a skill is pending and idle is true, make it active. Returns
 *  true if a swap happened. Constant time (a pointer/index swap). */
bool nvm_bank_tick(nvm_bank_t *b, bool idle);

/** The active skill, or NULL if none. */
const skill_t *nvm_bank_active(const nvm_bank_t *b);

#endif /* NVM_BANK_H */

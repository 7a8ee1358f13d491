/* Fault list: latching, first-fault reporting, emergency-frame queue and guarded clearing.
 * A fault latches on flt_raise and stays latched until flt_clear_request succeeds, which it
 * does only while none of the latched faults' causes is present. Clearing never resumes a
 * skill: the state machine goes to IDLE and waits for a new command.
 * Pure state over an explicit struct: no I/O, bounded work. */
#ifndef FLT_H
#define FLT_H

#include <stdbool.h>
#include <stdint.h>
#include "flt_codes.h"

/** Payload data of one emergency frame (the CAN layer adds counter and CRC-8). */
typedef struct {
    uint16_t code;         /* the fault that latched (5xx) */
    uint8_t n_latched;     /* number of faults latched after this one */
    uint32_t latched_mask; /* FLT_BIT of every latched fault */
    uint32_t tick;         /* control tick at which it latched */
} flt_emcy_t;

/** Fault state. */
typedef struct {
    uint32_t latched_mask; /* FLT_BIT of every latched fault */
    uint16_t first_code;   /* first fault since the last clear (status frame), 0 if none */
    uint32_t first_tick;   /* tick at which first_code latched */
    uint32_t raise_count[FLT_COUNT]; /* times each fault latched since flt_init (diagnostics) */
    flt_emcy_t emcy[FLT_COUNT];      /* FIFO of emergency frames not yet sent */
    uint8_t emcy_head;
    uint8_t emcy_len;
} flt_state_t;

/** Clear all faults and the emergency queue. */
void flt_init(flt_state_t *st);

/** Latch code at tick; returns true if it was not latched before (an emergency frame is then
 *  queued). FLT_NONE and codes outside the list are ignored (false). */
bool flt_raise(flt_state_t *st, flt_code_t code, uint32_t tick);

/** True while any fault is latched (the actuator must be ramping down or disabled). Inline:
 *  the supervisor asks every tick. */
static inline bool flt_active(const flt_state_t *st)
{
    return st != 0 && st->latched_mask != 0u;
}

/** Code for the status frame: the first fault latched since the last clear, 0 if none. */
static inline uint16_t flt_active_code(const flt_state_t *st)
{
    return (st == 0) ? 0u : st->first_code;
}

/** True if this particular code is latched. */
bool flt_is_latched(const flt_state_t *st, flt_code_t code);

/** Clear request: cause_present_mask has FLT_BIT set for every cause still present now.
 *  Refused (returns the lowest latched code whose cause is present; nothing is cleared) if any
 *  latched fault's cause persists; otherwise clears all and returns FLT_NONE. */
flt_code_t flt_clear_request(flt_state_t *st, uint32_t cause_present_mask);

/** True if an emergency frame is queued. Inline: the application asks every tick. */
static inline bool flt_emcy_pending(const flt_state_t *st)
{
    return st->emcy_len != 0u;
}

/** Copy the next queued emergency frame into *out without removing it; false if none. */
bool flt_emcy_peek(const flt_state_t *st, flt_emcy_t *out);

/** Pop the next queued emergency frame into *out; false if the queue is empty. */
bool flt_emcy_pop(flt_state_t *st, flt_emcy_t *out);

/** Short constant name of a code ("HOST_SILENCE"), "NONE" or "UNKNOWN". */
const char *flt_name(uint16_t code);

#endif /* FLT_H */

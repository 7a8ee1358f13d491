/* Fault list: see flt.h. */
#include "flt.h"

#include <stddef.h>

void flt_init(flt_state_t *st)
{
    if (st == NULL) {
        return;
    }
    st->latched_mask = 0u;
    st->first_code = 0u;
    st->first_tick = 0u;
    for (uint32_t i = 0u; i < FLT_COUNT; i++) {
        st->raise_count[i] = 0u;
        st->emcy[i].code = 0u;
        st->emcy[i].n_latched = 0u;
        st->emcy[i].latched_mask = 0u;
        st->emcy[i].tick = 0u;
    }
    st->emcy_head = 0u;
    st->emcy_len = 0u;
}

static uint8_t popcount32(uint32_t x)
{
    uint8_t n = 0u;
    while (x != 0u) {
        x &= x - 1u;
        n++;
    }
    return n;
}

bool flt_raise(flt_state_t *st, flt_code_t code, uint32_t tick)
{
    const uint32_t bit = FLT_BIT(code);
    if (st == NULL || bit == 0u || (st->latched_mask & bit) != 0u) {
        return false;
    }
    st->latched_mask |= bit;
    st->raise_count[(uint32_t)code - FLT_CODE_FIRST]++;
    if (st->first_code == 0u) {
        st->first_code = (uint16_t)code;
        st->first_tick = tick;
    }
    /* A fault latches at most once between clears, and the queue holds FLT_COUNT entries, so
     * it cannot overflow before the next clear; the guard keeps that true if the queue is never
     * drained across several clears (the oldest frame is then dropped). */
    if (st->emcy_len == FLT_COUNT) {
        st->emcy_head = (uint8_t)((st->emcy_head + 1u) % FLT_COUNT);
        st->emcy_len--;
    }
    const uint32_t idx = ((uint32_t)st->emcy_head + st->emcy_len) % FLT_COUNT;
    st->emcy[idx].code = (uint16_t)code;
    st->emcy[idx].latched_mask = st->latched_mask;
    st->emcy[idx].n_latched = popcount32(st->latched_mask);
    st->emcy[idx].tick = tick;
    st->emcy_len++;
    return true;
}

bool flt_is_latched(const flt_state_t *st, flt_code_t code)
{
    const uint32_t bit = FLT_BIT(code);
    return st != NULL && bit != 0u && (st->latched_mask & bit) != 0u;
}

flt_code_t flt_clear_request(flt_state_t *st, uint32_t cause_present_mask)
{
    if (st == NULL) {
        return FLT_NONE;
    }
    const uint32_t persisting = st->latched_mask & cause_present_mask;
    if (persisting != 0u) {
        for (uint32_t i = 0u; i < FLT_COUNT; i++) {
            if ((persisting & (1u << i)) != 0u) {
                return (flt_code_t)(FLT_CODE_FIRST + i);
            }
        }
    }
    st->latched_mask = 0u;
    st->first_code = 0u;
    st->first_tick = 0u;
    return FLT_NONE;
}

bool flt_emcy_peek(const flt_state_t *st, flt_emcy_t *out)
{
    if (st == NULL || out == NULL || st->emcy_len == 0u) {
        return false;
    }
    *out = st->emcy[st->emcy_head];
    return true;
}

bool flt_emcy_pop(flt_state_t *st, flt_emcy_t *out)
{
    if (st == NULL || out == NULL || st->emcy_len == 0u) {
        return false;
    }
    *out = st->emcy[st->emcy_head];
    st->emcy_head = (uint8_t)((st->emcy_head + 1u) % FLT_COUNT);
    st->emcy_len--;
    return true;
}

const char *flt_name(uint16_t code)
{
    static const char *const names[FLT_COUNT] = {
        "HOST_SILENCE",  "BUS_OFF",        "SENSOR_NAN",   "SENSOR_RANGE",
        "SENSOR_STUCK",  "SENSOR_SPIKE",   "ENCODER_JUMP", "FORCE_LIMIT",
        "SLEW_LIMIT",    "WORKSPACE",      "VELOCITY",     "TICK_OVERRUN",
        "SKILL_INVALID", "CMD_NOT_FINITE", "STORAGE",      "BAND",
    };
    if (code == 0u) {
        return "NONE";
    }
    if (code >= FLT_CODE_FIRST && code < FLT_CODE_FIRST + FLT_COUNT) {
        return names[code - FLT_CODE_FIRST];
    }
    return "UNKNOWN";
}

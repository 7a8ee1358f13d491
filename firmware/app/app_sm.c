#include "app_sm.h"

#include <stdint.h>

/* One row per state, one column per event (app_event_t order). */
static const uint8_t k_next[APP_STATE_COUNT][APP_EVENT_COUNT] = {
    /*               BOOTED     STOP       TEACH        EXECUTE        FAULT      CLEARED */
    [APP_BOOT] = {APP_IDLE, APP_BOOT, APP_BOOT, APP_BOOT, APP_FAULT, APP_BOOT},
    [APP_IDLE] = {APP_IDLE, APP_IDLE, APP_TEACH, APP_EXECUTE, APP_FAULT, APP_IDLE},
    [APP_TEACH] = {APP_TEACH, APP_IDLE, APP_TEACH, APP_TEACH, APP_FAULT, APP_TEACH},
    [APP_EXECUTE] = {APP_EXECUTE, APP_IDLE, APP_EXECUTE, APP_EXECUTE, APP_FAULT, APP_EXECUTE},
    [APP_FAULT] = {APP_FAULT, APP_FAULT, APP_FAULT, APP_FAULT, APP_FAULT, APP_IDLE},
};

app_state_t app_sm_next(app_state_t state, app_event_t ev)
{
    if ((uint32_t)state >= APP_STATE_COUNT || (uint32_t)ev >= APP_EVENT_COUNT) {
        return state;
    }
    return (app_state_t)k_next[state][ev];
}

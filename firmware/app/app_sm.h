/* The device state machine as a table: BOOT -> IDLE -> TEACH | EXECUTE -> IDLE, any state ->
 * FAULT (latched) -> IDLE only when the faults are cleared. app_sm_next is pure; the application
 * assigns its state only through it (app_event, app.c), which also runs the entry actions. */
#ifndef APP_SM_H
#define APP_SM_H

/** Device states (DeviceStatus.State in the DBC). */
typedef enum {
    APP_BOOT = 0,
    APP_IDLE = 1,
    APP_TEACH = 2,
    APP_EXECUTE = 3,
    APP_FAULT = 4
} app_state_t;

#define APP_STATE_COUNT 5u

/** What can move the device from one state to another. */
typedef enum {
    APP_EV_BOOTED = 0,  /* start-up finished (first tick) */
    APP_EV_STOP = 1,    /* host command IDLE, or RoutineControl stop of a running skill */
    APP_EV_TEACH = 2,   /* host command TEACH */
    APP_EV_EXECUTE = 3, /* a skill or sequence was accepted and started */
    APP_EV_FAULT = 4,   /* the safety supervisor latched a fault (safe stop running) */
    APP_EV_CLEARED = 5  /* every latched fault was cleared */
} app_event_t;

#define APP_EVENT_COUNT 6u

/** The state after ev in state (the same state when ev does not apply there); an unknown state
 *  or event gives state unchanged. */
app_state_t app_sm_next(app_state_t state, app_event_t ev);

#endif /* APP_SM_H */

/* The device state machine (app_sm_next) against the state chart written out edge by edge. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "app_sm.h"

typedef struct {
    app_state_t from;
    app_event_t ev;
    app_state_t to;
} edge_t;

/* Every transition that changes the state; any other (state, event) pair keeps the state. */
static const edge_t k_edges[] = {
    {APP_BOOT, APP_EV_BOOTED, APP_IDLE},    {APP_BOOT, APP_EV_FAULT, APP_FAULT},
    {APP_IDLE, APP_EV_TEACH, APP_TEACH},    {APP_IDLE, APP_EV_EXECUTE, APP_EXECUTE},
    {APP_IDLE, APP_EV_FAULT, APP_FAULT},    {APP_TEACH, APP_EV_STOP, APP_IDLE},
    {APP_TEACH, APP_EV_FAULT, APP_FAULT},   {APP_EXECUTE, APP_EV_STOP, APP_IDLE},
    {APP_EXECUTE, APP_EV_FAULT, APP_FAULT}, {APP_FAULT, APP_EV_CLEARED, APP_IDLE},
};

static app_state_t chart(app_state_t s, app_event_t ev)
{
    for (size_t i = 0; i < sizeof(k_edges) / sizeof(k_edges[0]); i++) {
        if (k_edges[i].from == s && k_edges[i].ev == ev) {
            return k_edges[i].to;
        }
    }
    return s;
}

static void test_every_pair_follows_the_chart(void **st)
{
    (void)st;
    for (uint32_t s = 0; s < APP_STATE_COUNT; s++) {
        for (uint32_t e = 0; e < APP_EVENT_COUNT; e++) {
            assert_int_equal(app_sm_next((app_state_t)s, (app_event_t)e),
                             chart((app_state_t)s, (app_event_t)e));
        }
    }
}

static void test_fault_is_left_only_by_clearing(void **st)
{
    (void)st;
    for (uint32_t e = 0; e < APP_EVENT_COUNT; e++) {
        const app_state_t to = app_sm_next(APP_FAULT, (app_event_t)e);
        assert_int_equal(to, e == APP_EV_CLEARED ? APP_IDLE : APP_FAULT);
    }
    for (uint32_t s = 0; s < APP_STATE_COUNT; s++) {
        assert_int_equal(app_sm_next((app_state_t)s, APP_EV_FAULT), APP_FAULT);
    }
}

static void test_motion_starts_only_from_idle(void **st)
{
    (void)st;
    for (uint32_t s = 0; s < APP_STATE_COUNT; s++) {
        const app_state_t t = app_sm_next((app_state_t)s, APP_EV_TEACH);
        const app_state_t x = app_sm_next((app_state_t)s, APP_EV_EXECUTE);
        assert_true(t != APP_TEACH || s == APP_IDLE || s == APP_TEACH);
        assert_true(x != APP_EXECUTE || s == APP_IDLE || s == APP_EXECUTE);
    }
}

static void test_unknown_state_or_event_changes_nothing(void **st)
{
    (void)st;
    assert_int_equal(app_sm_next((app_state_t)7, APP_EV_BOOTED), 7);
    assert_int_equal(app_sm_next(APP_IDLE, (app_event_t)APP_EVENT_COUNT), APP_IDLE);
    assert_int_equal(app_sm_next(APP_BOOT, (app_event_t)-1), APP_BOOT);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_every_pair_follows_the_chart),
        cmocka_unit_test(test_fault_is_left_only_by_clearing),
        cmocka_unit_test(test_motion_starts_only_from_idle),
        cmocka_unit_test(test_unknown_state_or_event_changes_nothing),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

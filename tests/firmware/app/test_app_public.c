/* The application's public surface (app.h) as a port's main uses it: the one static instance,
 * factory configuration, init and the 1 kHz scheduler on the host port's clock. Only app.h and
 * the port's own header: the device's fields stay out of sight. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "app.h"
#include "hal_host.h"

static void test_a_main_boots_the_device_to_idle(void **state)
{
    (void)state;
    hal_host_init();
    hal_host_set_time_us(0u);
    app_t *app = app_device();
    assert_ptr_equal(app, app_device()); /* one instance */
    app_config_default(app_device_config());
    app_init(app, app_device_config());
    assert_int_equal(app_state(app), APP_BOOT);
    uint32_t ticks = 0u;
    for (uint64_t t_us = 0u; t_us <= 5000u; t_us += 250u) {
        hal_host_set_time_us(t_us);
        ticks += app_poll(app) ? 1u : 0u;
    }
    /* the first tick is due 1 ms after init: one per boundary 1..5 ms; the first leaves BOOT */
    assert_int_equal(ticks, 5u);
    assert_int_equal(app_state(app), APP_IDLE);
    assert_int_equal(app_fault_code(app), 0u);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_a_main_boots_the_device_to_idle),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

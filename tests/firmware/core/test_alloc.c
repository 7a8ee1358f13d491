/* Zero allocation and bounded work per step: this executable is linked with
 * -Wl,--wrap=malloc,--wrap=calloc,--wrap=realloc,--wrap=free, so every call to those from the
 * test or from fs_core goes through the counting wrappers below. A 17 000-step rollout (17 s at
 * 1 kHz, N = 50) must call none of them, and the kernels summed per step stay under a fixed bound. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <cmocka.h>

#include "core_test_util.h"
#include "dmp.h"

/* Same bound as test_forcing.c (about 7 neighbours within sqrt(46) sigma; 9 at worst). */
#define ACTIVE_BOUND 9u

static unsigned long alloc_calls;

void *__real_malloc(size_t size);
void *__real_calloc(size_t n, size_t size);
void *__real_realloc(void *p, size_t size);
void __real_free(void *p);
void *__wrap_malloc(size_t size);
void *__wrap_calloc(size_t n, size_t size);
void *__wrap_realloc(void *p, size_t size);
void __wrap_free(void *p);

void *__wrap_malloc(size_t size)
{
    alloc_calls++;
    return __real_malloc(size);
}

void *__wrap_calloc(size_t n, size_t size)
{
    alloc_calls++;
    return __real_calloc(n, size);
}

void *__wrap_realloc(void *p, size_t size)
{
    alloc_calls++;
    return __real_realloc(p, size);
}

void __wrap_free(void *p)
{
    alloc_calls++;
    __real_free(p);
}

static tu_skill_desc_t desc;
static dmp_model_t model;

/* The wrappers really are in the path: a malloc/free pair here counts 2. */
static void test_wrappers_count(void **state)
{
    (void)state;
    const unsigned long before = alloc_calls;
    void *volatile p = malloc(16);
    assert_non_null(p);
    free(p);
    assert_int_equal(alloc_calls - before, 2);
}

static void test_rollout_no_alloc_bounded_work(void **state)
{
    (void)state;
    tu_default_desc(&desc, 50, 280.0, 17.0);
    assert_int_equal(tu_model_from_desc(&desc, &model), FS_OK);
    dmp_state_t s;
    const dmp_run_t run = {1.0, 1.0};
    dmp_coupling_t cpl = {0.0, 0.0};
    uint16_t active_max = 0;
    double f_max = 0.0;
    const unsigned long before = alloc_calls;
    dmp_state_reset(&s);
    for (long n = 0; n < 17000; n++) {
        const uint16_t active = dmp_active_kernels(&model, s.u);
        active_max = (active > active_max) ? active : active_max;
        cpl.phase_slowdown = dmp_phase_stop_factor((double)(n % 100) * 0.01, 0.1);
        const double f = dmp_step(&model, &s, &run, &cpl);
        f_max = fmax(f_max, fabs(f));
    }
    const unsigned long calls = alloc_calls - before;
    printf("17000-step rollout (N=50): %lu allocator calls, max kernels summed per step %u, "
           "max |f_hat| %.3f N\n", calls, active_max, f_max);
    assert_int_equal(calls, 0);
    assert_true(active_max <= ACTIVE_BOUND);
    assert_true(f_max > 0.0 && isfinite(f_max));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_wrappers_count),
        cmocka_unit_test(test_rollout_no_alloc_bounded_work),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

/* The long-work mechanism (fs_job.h) on a job whose trace is known: where each call resumes,
 * that a wait is tested at once, that locals do not need to survive, that an ended job starts
 * over and that a reset one does too. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "fs_job.h"

typedef struct {
    fs_job_t job;
    uint32_t slices; /* slices of the loop done */
    uint32_t needed; /* slices the loop takes */
    int gate;        /* the wait's condition */
    char trace[32];  /* one letter per piece of work, in order */
    uint32_t n;
} demo_t;

static void mark(demo_t *d, char c)
{
    d->trace[d->n++] = c;
    d->trace[d->n] = '\0';
}

static fs_job_status_t demo_job(demo_t *d)
{
    FS_JOB_BEGIN(&d->job);
    mark(d, 'a');
    FS_JOB_YIELD(&d->job);
    mark(d, 'b');
    while (d->slices < d->needed) {
        d->slices++;
        mark(d, 'l');
        FS_JOB_YIELD(&d->job);
    }
    FS_JOB_WAIT_UNTIL(&d->job, d->gate != 0);
    mark(d, 'z');
    FS_JOB_END(&d->job);
}

static void test_resumes_where_it_yielded(void **state)
{
    (void)state;
    demo_t d = {{0u}, 0u, 2u, 0, {0}, 0u};
    assert_false(fs_job_running(&d.job));
    assert_int_equal(demo_job(&d), FS_JOB_PENDING); /* a */
    assert_true(fs_job_running(&d.job));
    assert_int_equal(demo_job(&d), FS_JOB_PENDING); /* b l */
    assert_int_equal(demo_job(&d), FS_JOB_PENDING); /* l */
    assert_int_equal(demo_job(&d), FS_JOB_PENDING); /* the loop ends, the gate is shut */
    assert_int_equal(demo_job(&d), FS_JOB_PENDING); /* still shut: nothing done */
    assert_string_equal(d.trace, "abll");
    d.gate = 1;
    assert_int_equal(demo_job(&d), FS_JOB_DONE);
    assert_string_equal(d.trace, "abllz");
    assert_false(fs_job_running(&d.job));
}

static void test_an_open_wait_does_not_yield(void **state)
{
    (void)state;
    demo_t d = {{0u}, 0u, 0u, 1, {0}, 0u};
    assert_int_equal(demo_job(&d), FS_JOB_PENDING);
    assert_int_equal(demo_job(&d), FS_JOB_DONE); /* b, no loop, the gate open: z in one call */
    assert_string_equal(d.trace, "abz");
}

static void test_ended_or_reset_starts_over(void **state)
{
    (void)state;
    demo_t d = {{0u}, 0u, 0u, 1, {0}, 0u};
    while (demo_job(&d) == FS_JOB_PENDING) {
    }
    assert_int_equal(demo_job(&d), FS_JOB_PENDING); /* a again */
    fs_job_reset(&d.job);
    assert_int_equal(demo_job(&d), FS_JOB_PENDING); /* a again */
    assert_string_equal(d.trace, "abzaa");
    d.job.at = 1u; /* a resume point the job does not have: it starts over */
    assert_int_equal(demo_job(&d), FS_JOB_PENDING);
    assert_string_equal(d.trace, "abzaaa");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_resumes_where_it_yielded),
        cmocka_unit_test(test_an_open_wait_does_not_yield),
        cmocka_unit_test(test_ended_or_reset_starts_over),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

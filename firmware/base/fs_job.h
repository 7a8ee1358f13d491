/* Long work in a tick's share: the one mechanism the firmware uses for every piece of work
 * longer than a tick may spend on it (key checks and derivations, a record's flash write, a
 * run's start, ...).
 *
 * A job is a function written as straight-line code that returns at its yield points and,
 * called again, goes on after the yield it left at (a protothread: the resume point is the
 * yield's line number, kept in the job's fs_job_t; the idea of Contiki's protothreads). Its
 * locals do not survive a yield: what must, lives in the job's own state struct. Between two
 * yields a job does at most one slice of work, sized so the slice fits the tick's budget beside
 * the control path (bench/qemu_tick.sh measures the tick's instructions); the calling module
 * decides how many slices a tick (its knobs sit with the other per-tick budgets, app_config.h).
 *
 *   fs_job_status_t key_job(key_t *k)
 *   {
 *       FS_JOB_BEGIN(&k->job);
 *       start(k);
 *       FS_JOB_YIELD(&k->job);             // next call resumes here
 *       while (!hash_step(k)) {
 *           FS_JOB_YIELD(&k->job);
 *       }
 *       FS_JOB_END(&k->job);               // FS_JOB_DONE; the next call starts over
 *   }
 *
 * No yield inside a `switch` of the job's own (its case labels would mix with the job's), and
 * one yield a line. A resume point the job does not know (its state overwritten) starts it over. */
#ifndef FS_JOB_H
#define FS_JOB_H

#include <stdbool.h>
#include <stdint.h>

/** A job's resume point: 0 before its first call and after it ended (fs_job_reset). */
typedef struct {
    uint16_t at;
} fs_job_t;

/** What a job's call returns: it yielded (call again, in a later tick) or it ended. */
typedef enum {
    FS_JOB_PENDING = 0,
    FS_JOB_DONE = 1
} fs_job_status_t;

/** Forget where a job was: its next call starts at FS_JOB_BEGIN (a job abandoned or restarted). */
static inline void fs_job_reset(fs_job_t *j)
{
    j->at = 0u;
}

/** True while a job has yielded and not ended. */
static inline bool fs_job_running(const fs_job_t *j)
{
    return j->at != 0u;
}

/** The job's first statement. */
#define FS_JOB_BEGIN(j) \
    switch ((j)->at) {  \
    default:            \
    case 0u:

/** End this call; the next call goes on after this point. */
#define FS_JOB_YIELD(j)               \
    do {                              \
        (j)->at = (uint16_t)__LINE__; \
        return FS_JOB_PENDING;        \
    case __LINE__:;                   \
    } while (0)

/** Yield until cond holds (tested at once, then once a call). */
#define FS_JOB_WAIT_UNTIL(j, cond) \
    while (!(cond)) {              \
        FS_JOB_YIELD(j);           \
    }

/** End the job now, from anywhere in it (e.g. a refusal): FS_JOB_DONE, the next call starts over. */
#define FS_JOB_EXIT(j)      \
    do {                    \
        (j)->at = 0u;       \
        return FS_JOB_DONE; \
    } while (0)

/** The job's last statement: returns FS_JOB_DONE, and the next call starts over. */
#define FS_JOB_END(j) \
    }                 \
    (j)->at = 0u;     \
    return FS_JOB_DONE

#endif /* FS_JOB_H */

/* SPDX-License-Identifier: MIT */
/* The pool of threads a scene keeps (src/engine/parallel.c): after ttd_pool_tasks returns, every
 * task of the call has run exactly once and its writes are visible to the caller, whether the
 * pool's threads were spinning (calls back to back), asleep (a pause longer than their spin
 * between calls) or not yet started, on 2, 3 and all threads, and a pool destroyed right after a
 * call ends its threads. Counted by the tasks themselves, checked against the task count. */
#define _POSIX_C_SOURCE 200809L
#include <stdatomic.h>
#include <stdint.h>
#include <stdlib.h>
#include <time.h>

#include "engine/parallel.h"
#include "test_macros.h"

enum { MAX_TASKS = 97 };

typedef struct job {
    atomic_int runs[MAX_TASKS]; /* how many times each task ran */
    int value[MAX_TASKS];       /* a plain write per task, read by the caller after the call */
    int round;
    long slow_us; /* a pool thread's task sleeps this long: the caller outlasts its spin and blocks */
} job;

static void pause_us(long us)
{
    struct timespec t = {0, us * 1000};
    nanosleep(&t, NULL);
}

static void task(void *ctx, size_t k, int worker)
{
    job *J = ctx;
    if (J->slow_us && worker != 0)
        pause_us(J->slow_us);
    atomic_fetch_add_explicit(&J->runs[k], 1, memory_order_relaxed);
    J->value[k] = J->round * 1000 + (int)k;
}

/* rounds calls on one pool, task counts 0..MAX_TASKS in a fixed mix; every pause_every-th call
 * after a pause of pause us (0: none); tasks on pool threads sleep slow_us */
static int run_rounds_slow(ttd_pool *p, int threads, int rounds, int pause_every, long pause, long slow_us)
{
    static job J;
    J.slow_us = slow_us;
    for (int r = 0; r < rounds; ++r) {
        const size_t n = (size_t)((r * 37 + 11) % (MAX_TASKS + 1));
        for (size_t k = 0; k < MAX_TASKS; ++k) {
            atomic_store_explicit(&J.runs[k], 0, memory_order_relaxed);
            J.value[k] = -1;
        }
        J.round = r;
        if (pause_every && r % pause_every == 0)
            pause_us(pause);
        ttd_pool_tasks(p, n, threads, task, &J);
        for (size_t k = 0; k < MAX_TASKS; ++k) {
            const int want = k < n;
            ENSURE_MSG(atomic_load_explicit(&J.runs[k], memory_order_relaxed) == want,
                       "threads %d, call %d of %zu tasks: task %zu ran %d times", threads, r, n, k,
                       atomic_load_explicit(&J.runs[k], memory_order_relaxed));
            ENSURE_MSG(J.value[k] == (want ? r * 1000 + (int)k : -1), "threads %d, call %d: task %zu wrote %d",
                       threads, r, k, J.value[k]);
        }
    }
    return 0;
}

static int run_rounds(ttd_pool *p, int threads, int rounds, int pause_every, long pause)
{
    return run_rounds_slow(p, threads, rounds, pause_every, pause, 0);
}

static int calls_back_to_back(void)
{
    const int threads[3] = {2, 3, 0};
    for (int t = 0; t < 3; ++t) {
        ttd_pool *p = ttd_pool_create();
        ENSURE(p != NULL);
        const int bad = run_rounds(p, threads[t], 3000, 0, 0);
        ttd_pool_destroy(p);
        ENSURE(bad == 0);
    }
    return 0;
}

/* a pause of 1 ms, longer than the threads' spin (0.2 ms): they block and are woken */
static int calls_after_sleeps(void)
{
    ttd_pool *p = ttd_pool_create();
    ENSURE(p != NULL);
    const int bad = run_rounds(p, 2, 300, 3, 1000);
    ttd_pool_destroy(p);
    ENSURE(bad == 0);
    return 0;
}

/* a pool grown to 8 threads, then calls that want 2 (the others must stay out and not be waited
 * for), then 8 again */
static int fewer_threads_than_the_pool(void)
{
    ttd_pool *p = ttd_pool_create();
    ENSURE(p != NULL);
    int bad = run_rounds(p, 8, 50, 0, 0);
    bad |= run_rounds(p, 2, 1000, 0, 0);
    bad |= run_rounds(p, 8, 50, 0, 0);
    ttd_pool_destroy(p);
    ENSURE(bad == 0);
    return 0;
}

/* tasks on the pool's threads that take 0.5 ms, longer than the caller's spin: the caller sleeps
 * and the last thread out wakes it */
static int caller_sleeps(void)
{
    ttd_pool *p = ttd_pool_create();
    ENSURE(p != NULL);
    const int bad = run_rounds_slow(p, 2, 60, 0, 0, 500);
    ttd_pool_destroy(p);
    ENSURE(bad == 0);
    return 0;
}

/* pools made, used once or a few times and destroyed at once, some while their threads spin */
static int destroyed_after_calls(void)
{
    for (int i = 0; i < 200; ++i) {
        ttd_pool *p = ttd_pool_create();
        ENSURE(p != NULL);
        const int bad = run_rounds(p, 2 + i % 2, 1 + i % 3, 0, 0);
        ttd_pool_destroy(p);
        ENSURE(bad == 0);
    }
    ttd_pool_destroy(NULL);
    return 0;
}

int main(int argc, char **argv)
{
    TEST_MAIN_BEGIN(argc, argv);
    RUN_TEST(calls_back_to_back);
    RUN_TEST(calls_after_sleeps);
    RUN_TEST(destroyed_after_calls);
    RUN_TEST(fewer_threads_than_the_pool);
    RUN_TEST(caller_sleeps);
    TEST_MAIN_END();
}

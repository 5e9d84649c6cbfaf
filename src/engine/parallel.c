/* SPDX-License-Identifier: MIT */
/* The parallel-for of engine/parallel.h: blocks claimed from an atomic counter by the calling
 * thread and by threads started for this call only. */
#define _POSIX_C_SOURCE 200809L

#include "engine/parallel.h"

#include <pthread.h>
#include <stdatomic.h>
#include <unistd.h>

typedef struct ttd_pfor {
    atomic_size_t next; /* the next unclaimed block */
    size_t nblocks;
    ttd_block_fn fn;
    void *ctx;
} ttd_pfor;

typedef struct ttd_pfor_worker {
    ttd_pfor *job;
    int index;
} ttd_pfor_worker;

static void ttd_pfor_run(ttd_pfor *job, int worker)
{
    for (;;) {
        size_t b = atomic_fetch_add_explicit(&job->next, 1, memory_order_relaxed);
        if (b >= job->nblocks)
            return;
        job->fn(job->ctx, b, worker);
    }
}

static void *ttd_pfor_thread(void *arg)
{
    ttd_pfor_worker *w = arg;
    ttd_pfor_run(w->job, w->index);
    return NULL;
}

int ttd_parallel_cores(void)
{
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n < 1 ? 1 : (n > TTD_MAX_WORKERS ? TTD_MAX_WORKERS : (int)n);
}

int ttd_parallel_workers(size_t nblocks, int threads)
{
    /* Small batches first: they never ask the OS for the core count (a file read on Linux). */
    size_t by_work = nblocks / TTD_MIN_BLOCKS_PER_WORKER;
    if (by_work < 2 || threads == 1)
        return 1;
    size_t w = threads > 0 ? (size_t)threads : (size_t)ttd_parallel_cores();
    if (w > TTD_MAX_WORKERS)
        w = TTD_MAX_WORKERS;
    return (int)(w < by_work ? w : by_work);
}

static void ttd_parallel_run(size_t nblocks, int workers, ttd_block_fn fn, void *ctx)
{
    if (workers <= 1) { /* no counter to share: a single pair or pose pays nothing for threads */
        for (size_t b = 0; b < nblocks; ++b)
            fn(ctx, b, 0);
        return;
    }
    ttd_pfor job = {.nblocks = nblocks, .fn = fn, .ctx = ctx};
    atomic_init(&job.next, 0);
    pthread_t tid[TTD_MAX_WORKERS];
    ttd_pfor_worker args[TTD_MAX_WORKERS];
    int started = 0;
    /* A thread that fails to start leaves its index unused; the blocks still get done. */
    for (int i = 1; i < workers; ++i) {
        args[started] = (ttd_pfor_worker){.job = &job, .index = i};
        if (pthread_create(&tid[started], NULL, ttd_pfor_thread, &args[started]) == 0)
            ++started;
    }
    ttd_pfor_run(&job, 0);
    for (int i = 0; i < started; ++i)
        pthread_join(tid[i], NULL);
}

void ttd_parallel_for(size_t nblocks, int threads, ttd_block_fn fn, void *ctx)
{
    ttd_parallel_run(nblocks, ttd_parallel_workers(nblocks, threads), fn, ctx);
}

int ttd_parallel_task_workers(size_t ntasks, int threads)
{
    if (ntasks < 2 || threads == 1)
        return 1;
    size_t w = threads > 0 ? (size_t)threads : (size_t)ttd_parallel_cores();
    if (w > ntasks)
        w = ntasks;
    return (int)(w > TTD_MAX_WORKERS ? TTD_MAX_WORKERS : w);
}

void ttd_parallel_tasks(size_t ntasks, int threads, ttd_block_fn fn, void *ctx)
{
    ttd_parallel_run(ntasks, ttd_parallel_task_workers(ntasks, threads), fn, ctx);
}

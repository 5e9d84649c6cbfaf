/* SPDX-License-Identifier: MIT */
/* The parallel-for of engine/parallel.h: blocks claimed from an atomic counter by the calling
 * thread and by threads started for this call only, or by a pool's threads. */
#define _POSIX_C_SOURCE 200809L

#include "engine/parallel.h"

#include <pthread.h>
#include <stdatomic.h>
#include <stdint.h>
#include <stdlib.h>
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

/* ---- a pool of threads kept between calls ------------------------------------------------- */

/* A job is posted by bumping `gen` under the mutex; threads 1 .. want - 1 of the pool (pool
 * thread k is worker k + 1) take part, the others go back to waiting. The caller, worker 0, runs
 * its share and then waits until `busy` (the taking part still running) is 0, so the job, on the
 * caller's stack, outlives every use. A thread spins briefly on `gen` before it blocks: steps of
 * a simulation come back to back, and a wake-up through the scheduler costs tens of
 * microseconds on a busy machine. */
struct ttd_pool {
    pthread_mutex_t mu;
    pthread_cond_t wake, done;
    pthread_t tid[TTD_MAX_WORKERS];
    int nthreads;
    int quit;
    _Atomic uint64_t gen; /* the job's number */
    ttd_pfor *job;
    int want;             /* workers of the job, the caller included */
    atomic_int busy;      /* pool threads of the job still running it */
};

typedef struct ttd_pool_start {
    ttd_pool *pool;
    int index;            /* the thread's worker index (its slot + 1) */
    uint64_t gen;         /* the job number when it started: it waits for the next */
} ttd_pool_start;

/* Spins before blocking: about 10-20 microseconds of pause instructions. */
#define TTD_POOL_SPIN 256

static void ttd_pool_relax(void)
{
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();
#endif
}

static void *ttd_pool_thread(void *arg)
{
    ttd_pool_start st = *(ttd_pool_start *)arg;
    free(arg);
    ttd_pool *p = st.pool;
    uint64_t seen = st.gen;
    for (;;) {
        for (int i = 0; i < TTD_POOL_SPIN && atomic_load_explicit(&p->gen, memory_order_acquire) == seen; ++i)
            ttd_pool_relax();
        pthread_mutex_lock(&p->mu);
        while (!p->quit && atomic_load_explicit(&p->gen, memory_order_relaxed) == seen)
            pthread_cond_wait(&p->wake, &p->mu);
        if (p->quit) {
            pthread_mutex_unlock(&p->mu);
            return NULL;
        }
        seen = atomic_load_explicit(&p->gen, memory_order_relaxed);
        ttd_pfor *job = p->job;
        const int part = st.index < p->want;
        pthread_mutex_unlock(&p->mu);
        if (!part)
            continue;
        ttd_pfor_run(job, st.index);
        if (atomic_fetch_sub_explicit(&p->busy, 1, memory_order_acq_rel) == 1) {
            pthread_mutex_lock(&p->mu);
            pthread_cond_signal(&p->done);
            pthread_mutex_unlock(&p->mu);
        }
    }
}

ttd_pool *ttd_pool_create(void)
{
    ttd_pool *p = calloc(1, sizeof *p);
    if (p == NULL)
        return NULL;
    if (pthread_mutex_init(&p->mu, NULL) != 0) {
        free(p);
        return NULL;
    }
    if (pthread_cond_init(&p->wake, NULL) != 0) {
        pthread_mutex_destroy(&p->mu);
        free(p);
        return NULL;
    }
    if (pthread_cond_init(&p->done, NULL) != 0) {
        pthread_cond_destroy(&p->wake);
        pthread_mutex_destroy(&p->mu);
        free(p);
        return NULL;
    }
    atomic_init(&p->gen, 0);
    atomic_init(&p->busy, 0);
    return p;
}

void ttd_pool_destroy(ttd_pool *p)
{
    if (p == NULL)
        return;
    pthread_mutex_lock(&p->mu);
    p->quit = 1;
    pthread_cond_broadcast(&p->wake);
    pthread_mutex_unlock(&p->mu);
    for (int i = 0; i < p->nthreads; ++i)
        pthread_join(p->tid[i], NULL);
    pthread_cond_destroy(&p->done);
    pthread_cond_destroy(&p->wake);
    pthread_mutex_destroy(&p->mu);
    free(p);
}

/* Starts threads until the pool has `need` (or one fails to start); returns how many it has. */
static int ttd_pool_grow(ttd_pool *p, int need)
{
    while (p->nthreads < need) {
        ttd_pool_start *st = malloc(sizeof *st);
        if (st == NULL)
            break;
        *st = (ttd_pool_start){p, p->nthreads + 1, atomic_load(&p->gen)};
        if (pthread_create(&p->tid[p->nthreads], NULL, ttd_pool_thread, st) != 0) {
            free(st);
            break;
        }
        p->nthreads++;
    }
    return p->nthreads;
}

void ttd_pool_tasks(ttd_pool *p, size_t ntasks, int threads, ttd_block_fn fn, void *ctx)
{
    int workers = ttd_parallel_task_workers(ntasks, threads);
    if (p == NULL || workers <= 1) {
        ttd_parallel_run(ntasks, workers, fn, ctx);
        return;
    }
    /* a thread that fails to start leaves its index unused; the blocks still get done */
    const int have = ttd_pool_grow(p, workers - 1);
    workers = have + 1 < workers ? have + 1 : workers;
    ttd_pfor job = {.nblocks = ntasks, .fn = fn, .ctx = ctx};
    atomic_init(&job.next, 0);
    if (workers > 1) {
        pthread_mutex_lock(&p->mu);
        p->job = &job;
        p->want = workers;
        atomic_store_explicit(&p->busy, workers - 1, memory_order_relaxed);
        atomic_fetch_add_explicit(&p->gen, 1, memory_order_release);
        pthread_cond_broadcast(&p->wake);
        pthread_mutex_unlock(&p->mu);
    }
    ttd_pfor_run(&job, 0);
    if (workers > 1) {
        for (int i = 0; i < TTD_POOL_SPIN && atomic_load_explicit(&p->busy, memory_order_acquire) > 0; ++i)
            ttd_pool_relax();
        pthread_mutex_lock(&p->mu);
        while (atomic_load_explicit(&p->busy, memory_order_acquire) > 0)
            pthread_cond_wait(&p->done, &p->mu);
        pthread_mutex_unlock(&p->mu);
    }
}

/* SPDX-License-Identifier: MIT */
/* The parallel-for of engine/parallel.h: blocks claimed from an atomic counter by the calling
 * thread and by threads started for this call only, or by a pool's threads. */
#define _POSIX_C_SOURCE 200809L

#include "engine/parallel.h"

#include <pthread.h>
#include <stdatomic.h>
#include <stdint.h>
#include <stdlib.h>
#include <time.h>
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

/* Worker threads run mesh walks whose working set lives on the stack (tens of KiB, query_impl.h's
 * qwork): ask for at least 1 MiB where the platform's default is smaller (musl's is 128 KiB), and
 * keep a larger default (glibc's 8 MiB). NULL (the default attributes) when that cannot be set. */
enum { TTD_WORKER_STACK = 1 << 20 };

static int ttd_thread_start(pthread_t *tid, void *(*fn)(void *), void *arg)
{
    pthread_attr_t attr;
    if (pthread_attr_init(&attr) != 0)
        return pthread_create(tid, NULL, fn, arg);
    size_t size = 0;
    int have = 1;
    if (pthread_attr_getstacksize(&attr, &size) != 0 || size < TTD_WORKER_STACK)
        have = pthread_attr_setstacksize(&attr, TTD_WORKER_STACK) == 0;
    const int rc = pthread_create(tid, have ? &attr : NULL, fn, arg);
    pthread_attr_destroy(&attr);
    return rc;
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
        if (ttd_thread_start(&tid[started], ttd_pfor_thread, &args[started]) == 0)
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

/* A job is posted by bumping `gen` under the mutex (for the threads blocked on `wake`); threads
 * 1 .. want - 1 of the pool (pool thread k is worker k + 1) may take part, the others go back to
 * waiting. A thread takes part by counting itself into `entry` with one compare-and-swap that
 * also checks the job's number there, unless the caller has closed the job: the caller, worker 0,
 * runs its share, closes the job (the CLOSED bit) and then waits only for the threads that
 * entered before that to finish (`finished`), so the job, on the caller's stack, outlives every
 * use, and a query shorter than a thread's wake-up never waits for one that has not woken yet.
 * A thread spins (pause, about TTD_POOL_SPIN_NS) on `gen` before it blocks: steps of a
 * simulation and a scene's queries come back to back, and a wake-up through the scheduler costs
 * tens of microseconds (more for a virtual machine's idle core), which was most of the second
 * thread's loss on a query of half a millisecond (docs/scene-speed.md, section 13). A spinning
 * thread enters without the mutex: taking it as the job was posted found it held (the caller
 * broadcasts under it) and slept in the kernel, the wake-up the spin is there to avoid (section 14). */
struct ttd_pool {
    pthread_mutex_t mu;
    pthread_cond_t wake, done;
    pthread_t tid[TTD_MAX_WORKERS];
    int nthreads;
    atomic_int quit;
    _Atomic uint64_t gen; /* the job's number */
    _Atomic(ttd_pfor *) job;
    atomic_int want;      /* workers of the job, the caller included */
    _Atomic uint64_t entry; /* the job's number (low 32 bits) << 32 | CLOSED once the caller is done |
                             * pool threads that took the job */
    atomic_uint finished; /* pool threads that took the job and are done with it */
    atomic_int sleeping;  /* the caller waits on `done` (past its spin) */
};

#define TTD_POOL_CLOSED 0x80000000u
#define TTD_POOL_COUNT 0x7fffffffu

typedef struct ttd_pool_start {
    ttd_pool *pool;
    int index;            /* the thread's worker index (its slot + 1) */
    uint64_t gen;         /* the job number when it started: it waits for the next */
} ttd_pool_start;

/* How long a thread spins before it blocks, in nanoseconds of the monotonic clock: idle pool
 * threads burn at most this much CPU after each job; a waiting caller as much before it sleeps. */
#define TTD_POOL_SPIN_NS 200000

static void ttd_pool_relax(void)
{
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();
#endif
}

/* The monotonic clock in nanoseconds, -1 without one (then no spinning). */
static int64_t ttd_pool_now(void)
{
    struct timespec t;
    if (clock_gettime(CLOCK_MONOTONIC, &t) != 0)
        return -1;
    return (int64_t)t.tv_sec * 1000000000 + t.tv_nsec;
}

/* Spins until *x != v or about TTD_POOL_SPIN_NS have passed; the clock is read every 64 pauses. */
static void ttd_pool_spin_gen(_Atomic uint64_t *x, uint64_t v)
{
    const int64_t t0 = ttd_pool_now();
    for (int64_t t = t0; t >= 0 && t - t0 <= TTD_POOL_SPIN_NS; t = ttd_pool_now())
        for (int i = 0; i < 64; ++i) {
            if (atomic_load_explicit(x, memory_order_acquire) != v)
                return;
            ttd_pool_relax();
        }
}

/* Spins until *x >= v or about TTD_POOL_SPIN_NS have passed. */
static void ttd_pool_spin_count(atomic_uint *x, unsigned v)
{
    const int64_t t0 = ttd_pool_now();
    for (int64_t t = t0; t >= 0 && t - t0 <= TTD_POOL_SPIN_NS; t = ttd_pool_now())
        for (int i = 0; i < 64; ++i) {
            if (atomic_load_explicit(x, memory_order_acquire) >= v)
                return;
            ttd_pool_relax();
        }
}

static void *ttd_pool_thread(void *arg)
{
    ttd_pool_start st = *(ttd_pool_start *)arg;
    free(arg);
    ttd_pool *p = st.pool;
    uint64_t seen = st.gen;
    for (;;) {
        ttd_pool_spin_gen(&p->gen, seen);
        if (atomic_load_explicit(&p->gen, memory_order_acquire) == seen) {
            pthread_mutex_lock(&p->mu);
            while (!atomic_load_explicit(&p->quit, memory_order_relaxed) &&
                   atomic_load_explicit(&p->gen, memory_order_relaxed) == seen)
                pthread_cond_wait(&p->wake, &p->mu);
            pthread_mutex_unlock(&p->mu);
        }
        if (atomic_load_explicit(&p->quit, memory_order_acquire))
            return NULL;
        seen = atomic_load_explicit(&p->gen, memory_order_acquire);
        /* count in only while `entry` still holds this job's number, open: the caller cannot
         * post the next job (and reset the counts) before the threads counted in are done */
        uint64_t e = atomic_load_explicit(&p->entry, memory_order_acquire);
        /* a thread the job does not want stays out (the caller would wait for it, and its
         * compare-and-swap would contend with the others'): `want` is stored before `entry`
         * (release), so an entry with this job's number shows this job's `want` or a later one's,
         * and a later job's number makes the compare-and-swap below fail anyway */
        if ((uint32_t)(e >> 32) == (uint32_t)seen &&
            st.index >= atomic_load_explicit(&p->want, memory_order_relaxed))
            continue;
        int in = 0;
        while (!in && (uint32_t)(e >> 32) == (uint32_t)seen && !(e & TTD_POOL_CLOSED))
            in = atomic_compare_exchange_weak_explicit(&p->entry, &e, e + 1, memory_order_acq_rel,
                                                       memory_order_acquire);
        if (!in)
            continue;
        if (st.index < atomic_load_explicit(&p->want, memory_order_relaxed))
            ttd_pfor_run(atomic_load_explicit(&p->job, memory_order_relaxed), st.index);
        /* the caller, still spinning, reads `finished` and needs no signal; taking the mutex for
         * one would meet the caller posting its next job under it. Both sequentially consistent:
         * the caller sets `sleeping` and then reads `finished`, so one of them sees the other. */
        atomic_fetch_add_explicit(&p->finished, 1, memory_order_seq_cst);
        if (atomic_load_explicit(&p->sleeping, memory_order_seq_cst)) {
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
    atomic_init(&p->quit, 0);
    atomic_init(&p->gen, 0);
    atomic_init(&p->job, NULL);
    atomic_init(&p->want, 0);
    atomic_init(&p->entry, 0);
    atomic_init(&p->finished, 0);
    atomic_init(&p->sleeping, 0);
    return p;
}

void ttd_pool_destroy(ttd_pool *p)
{
    if (p == NULL)
        return;
    pthread_mutex_lock(&p->mu);
    atomic_store_explicit(&p->quit, 1, memory_order_release);
    atomic_fetch_add_explicit(&p->gen, 1, memory_order_release); /* ends the threads' spins */
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
        if (ttd_thread_start(&p->tid[p->nthreads], ttd_pool_thread, st) != 0) {
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
        atomic_store_explicit(&p->job, &job, memory_order_relaxed);
        atomic_store_explicit(&p->want, workers, memory_order_relaxed);
        atomic_store_explicit(&p->finished, 0, memory_order_relaxed);
        const uint64_t gen = atomic_load_explicit(&p->gen, memory_order_relaxed) + 1;
        /* the job, its workers and the zero count are published by this release; gen after it,
         * so a thread that sees the new gen finds the entry open */
        atomic_store_explicit(&p->entry, (uint64_t)(uint32_t)gen << 32, memory_order_release);
        atomic_store_explicit(&p->gen, gen, memory_order_release);
        pthread_mutex_unlock(&p->mu);
        /* after the unlock: a thread woken under it would block at once on the held mutex. A
         * sleeper cannot miss the job: it reads gen under the mutex before it waits */
        pthread_cond_broadcast(&p->wake);
    }
    ttd_pfor_run(&job, 0);
    if (workers > 1) {
        /* close the job: a thread not in by now finds it closed and leaves it alone */
        const unsigned in =
            (unsigned)(atomic_fetch_or_explicit(&p->entry, TTD_POOL_CLOSED, memory_order_acq_rel) & TTD_POOL_COUNT);
        ttd_pool_spin_count(&p->finished, in);
        if (atomic_load_explicit(&p->finished, memory_order_acquire) < in) {
            pthread_mutex_lock(&p->mu);
            atomic_store_explicit(&p->sleeping, 1, memory_order_seq_cst);
            while (atomic_load_explicit(&p->finished, memory_order_seq_cst) < in)
                pthread_cond_wait(&p->done, &p->mu);
            atomic_store_explicit(&p->sleeping, 0, memory_order_relaxed);
            pthread_mutex_unlock(&p->mu);
        }
    }
}

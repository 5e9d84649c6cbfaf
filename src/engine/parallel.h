/* SPDX-License-Identifier: MIT */
/* A small parallel-for over blocks (Box2D's b2ParallelFor idea, on pthreads).
 *
 * ttd_parallel_for(nblocks, threads, fn, ctx) calls fn(ctx, block, worker) once for every
 * block in [0, nblocks). Workers claim blocks one at a time from an atomic counter, so a slow
 * block does not hold up the others; the calling thread is worker 0 and returns when every
 * block is done. worker is in [0, ttd_parallel_workers(nblocks, threads)) and stable for the
 * thread that runs it, so fn may keep per-worker scratch indexed by it. Which worker runs
 * which block varies from run to run: fn must make each block's result depend on the block
 * alone, and then the output does not depend on the thread count. ttd_parallel_for and
 * ttd_parallel_tasks start threads per call (no global state); ttd_pool_tasks runs on the threads
 * of a pool that an object keeps between calls (a scene's: a simulator queries it every step, and
 * starting threads per call cost more than a short query's work). If a thread cannot be started
 * the others do its share. */
#ifndef TTD_ENGINE_PARALLEL_H
#define TTD_ENGINE_PARALLEL_H

#include <stddef.h>

/// Most workers one call uses.
#define TTD_MAX_WORKERS 256
/// Fewest blocks per worker: a thread costs tens of microseconds to start, a block a few.
#define TTD_MIN_BLOCKS_PER_WORKER 8

typedef void (*ttd_block_fn)(void *ctx, size_t block, int worker);

/// Online cores (at least 1).
int ttd_parallel_cores(void);
/// Workers a call with these arguments uses: threads (0 = every online core), capped by
/// TTD_MAX_WORKERS and by nblocks / TTD_MIN_BLOCKS_PER_WORKER, at least 1.
int ttd_parallel_workers(size_t nblocks, int threads);
/// Runs fn on every block; see the top of this file.
void ttd_parallel_for(size_t nblocks, int threads, ttd_block_fn fn, void *ctx);
/// Workers ttd_parallel_tasks uses: threads (0 = every online core), capped by ntasks and
/// TTD_MAX_WORKERS, at least 1.
int ttd_parallel_task_workers(size_t ntasks, int threads);
/// ttd_parallel_for for tasks that are each long enough to pay for a thread (a subtree of a mesh
/// build, a query pose): ttd_parallel_task_workers(ntasks, threads) workers.
void ttd_parallel_tasks(size_t ntasks, int threads, ttd_block_fn fn, void *ctx);

/// Worker threads kept between calls: none at first; a call that wants more starts them, and
/// between calls they spin for about 0.2 ms, then wait, blocked. A call waits only for the
/// threads that joined it before its caller ran out of tasks. Owned by one object whose calls do
/// not overlap (a scene).
typedef struct ttd_pool ttd_pool;
/// An empty pool (no thread yet), or NULL when out of memory.
ttd_pool *ttd_pool_create(void);
/// Ends the pool's threads and frees it (NULL is fine). No call may be running on it.
void ttd_pool_destroy(ttd_pool *pool);
/// ttd_parallel_tasks on the pool's threads (started as needed; NULL: threads per call as
/// ttd_parallel_tasks): the same workers, indices and guarantees.
void ttd_pool_tasks(ttd_pool *pool, size_t ntasks, int threads, ttd_block_fn fn, void *ctx);

#endif /* TTD_ENGINE_PARALLEL_H */

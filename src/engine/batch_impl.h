/* SPDX-License-Identifier: MIT */
/* The batch engine, precision-generic: engine/batch_d.c and engine/batch_f.c compile it once
 * each (see there for TTD_UBITS, TTD_EXP_BITS, TTD_RUNNER and TTD_RUNNER_MAKE).
 *
 * A batch is cut into blocks of TTD_BLOCK_PAIRS pairs, and each block goes
 *
 *     source  ->  runner  ->  sink
 *
 * The source yields the block's pairs as two contiguous arrays of finite coordinates: the
 * caller's own memory when it can (all 18n coordinates finite and aligned: almost every
 * block), otherwise the worker's scratch (allocated on first need, bounded by the block size),
 * into which it copies byte-wise (any alignment) or gathers mesh triangles, replacing a pair
 * with NaN/inf by a harmless placeholder. The runner is the method's kernel (engine/runner.h).
 * The sink hands the kernel the caller's output arrays, or scratch where they are not aligned
 * or where results are needed only for the not-converged flag, then overwrites a placeholder's
 * outputs with NaN and TTD_PAIR_NONFINITE and copies scratch back.
 *
 * Nothing here starts threads: engine_run schedules whole blocks on ttd_parallel_for, and as
 * block boundaries do not depend on the thread count, neither do the results. */

typedef struct scratch {
    real s[9 * TTD_BLOCK_PAIRS];
    real t[9 * TTD_BLOCK_PAIRS];
    real dist[TTD_BLOCK_PAIRS];
    ttd_result res[TTD_BLOCK_PAIRS];
    unsigned char bad[TTD_BLOCK_PAIRS];
} scratch;

/* One block on its way from the source through the runner to the sink. */
typedef struct block {
    size_t i0, m;          /* pairs [i0, i0 + m) of the batch */
    const real *s, *t;     /* from the source: 9m finite coordinates each */
    int any_bad;           /* some pair was replaced by the placeholder (scratch bad[] says which) */
    real *d;               /* from the sink: where the kernel writes distances (or NULL) */
    ttd_result *r;         /* and results (or NULL) */
} block;

/* Fills b->s, b->t and b->any_bad for pairs [b->i0, b->i0 + b->m); returns 0 when it needed
 * scratch and none could be had (TTD_BATCH_NOMEM is then set). */
typedef int (*source_fill_fn)(const void *src, block *b, scratch **slot, atomic_uint *bits);

/* The flat source: the caller's two arrays of 9n coordinates, as bytes. */
typedef struct flat_source {
    const unsigned char *s, *t;
    int aligned;
} flat_source;

/* The indexed source: triangle pairs[2i] of m1 against pairs[2i+1] of m2 (indices checked). */
typedef struct indexed_source {
    const engine_mesh *m1, *m2;
    const unsigned char *pairs;
} indexed_source;

/* The sink: the caller's outputs, as bytes; either may be NULL. */
typedef struct array_sink {
    unsigned char *distance, *results;
    int dist_aligned, res_aligned;
    int need_flags; /* results are needed for TTD_PAIR_NOT_CONVERGED */
} array_sink;

typedef struct job {
    size_t n;
    source_fill_fn fill;
    const void *src;
    TTD_RUNNER run;
    array_sink sink;
    atomic_uint bits; /* TTD_BATCH_* seen by any block */
    scratch *scratch[TTD_MAX_WORKERS];
} job;

/* Non-zero when any of count reals at p (any alignment) is NaN or inf. The exponent field
 * of such a value is all ones, so adding one to it carries into the sign bit of the masked
 * word: an OR of and-add words, without compares, that compilers vectorise with baseline
 * SSE2. Eight accumulators keep the loop from waiting on one OR chain. */
static int any_nonfinite(const unsigned char *p, size_t count)
{
    const TTD_UBITS exp_bits = TTD_EXP_BITS, exp_lsb = TTD_EXP_BITS & (TTD_UBITS)(~TTD_EXP_BITS + 1);
    TTD_UBITS acc[8] = {0}, u[8], all = 0;
    size_t k = 0;
    for (; k + 8 <= count; k += 8) {
        memcpy(u, p + k * sizeof u[0], sizeof u);
        for (int j = 0; j < 8; ++j)
            acc[j] |= (u[j] & exp_bits) + exp_lsb;
    }
    for (; k < count; ++k) {
        memcpy(u, p + k * sizeof u[0], sizeof u[0]);
        acc[0] |= (u[0] & exp_bits) + exp_lsb;
    }
    for (int j = 0; j < 8; ++j)
        all |= acc[j];
    return (int)(all >> (8 * sizeof all - 1));
}

/* The worker's scratch, allocated on first need. */
static scratch *need_scratch(scratch **slot, atomic_uint *bits)
{
    if (*slot == NULL) {
        *slot = malloc(sizeof(scratch));
        if (*slot == NULL)
            atomic_fetch_or(bits, TTD_BATCH_NOMEM);
    }
    return *slot;
}

/* The block's pairs are in scratch and some has NaN/inf: mark each such pair and replace it
 * by a pair far from degenerate and from touching, so that every method handles it quickly;
 * the sink overwrites its outputs. */
static void replace_nonfinite(scratch *sc, size_t m, atomic_uint *bits)
{
    static const real ph_s[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    static const real ph_t[9] = {(real)0.25, (real)0.25, 1, 1, (real)0.25, 2, (real)0.25, 1, 2};
    for (size_t i = 0; i < m; ++i) {
        sc->bad[i] = (unsigned char)(any_nonfinite((const unsigned char *)(sc->s + 9 * i), 9) ||
                                     any_nonfinite((const unsigned char *)(sc->t + 9 * i), 9));
        if (sc->bad[i]) {
            memcpy(sc->s + 9 * i, ph_s, sizeof ph_s);
            memcpy(sc->t + 9 * i, ph_t, sizeof ph_t);
        }
    }
    atomic_fetch_or(bits, TTD_BATCH_NONFINITE);
}

static int flat_fill(const void *p, block *b, scratch **slot, atomic_uint *bits)
{
    const flat_source *src = p;
    const size_t off = 9 * b->i0 * sizeof(real);
    b->any_bad = any_nonfinite(src->s + off, 9 * b->m) || any_nonfinite(src->t + off, 9 * b->m);
    if (!b->any_bad && src->aligned) {
        b->s = (const real *)(const void *)(src->s + off);
        b->t = (const real *)(const void *)(src->t + off);
        return 1;
    }
    scratch *sc = need_scratch(slot, bits);
    if (sc == NULL)
        return 0;
    memcpy(sc->s, src->s + off, 9 * b->m * sizeof(real));
    memcpy(sc->t, src->t + off, 9 * b->m * sizeof(real));
    if (b->any_bad)
        replace_nonfinite(sc, b->m, bits);
    b->s = sc->s;
    b->t = sc->t;
    return 1;
}

/* Copies the 9 coordinates of triangle tri of mesh into out (indices already checked). */
static void gather(const engine_mesh *mesh, uint32_t tri, real *out)
{
    const unsigned char *tris = (const unsigned char *)mesh->tris;
    const unsigned char *verts = (const unsigned char *)mesh->verts;
    for (size_t k = 0; k < 3; ++k) {
        size_t v = ttd_load_u32(tris, 3 * (size_t)tri + k);
        memcpy(out + 3 * k, verts + 3 * v * sizeof(real), 3 * sizeof(real));
    }
}

static int indexed_fill(const void *p, block *b, scratch **slot, atomic_uint *bits)
{
    const indexed_source *src = p;
    scratch *sc = need_scratch(slot, bits);
    if (sc == NULL)
        return 0;
    for (size_t i = 0; i < b->m; ++i) {
        gather(src->m1, ttd_load_u32(src->pairs, 2 * (b->i0 + i)), sc->s + 9 * i);
        gather(src->m2, ttd_load_u32(src->pairs, 2 * (b->i0 + i) + 1), sc->t + 9 * i);
    }
    b->any_bad = any_nonfinite((const unsigned char *)sc->s, 9 * b->m) ||
                 any_nonfinite((const unsigned char *)sc->t, 9 * b->m);
    if (b->any_bad)
        replace_nonfinite(sc, b->m, bits);
    b->s = sc->s;
    b->t = sc->t;
    return 1;
}

/* Points b->d and b->r at the caller's arrays where they are aligned, at scratch otherwise (and
 * b->r at scratch when only the flags are wanted); returns 0 when scratch could not be had. */
static int sink_prepare(const array_sink *k, block *b, scratch **slot, atomic_uint *bits)
{
    const int d_direct = k->distance == NULL || k->dist_aligned;
    const int r_direct = k->results != NULL ? k->res_aligned : !k->need_flags;
    scratch *sc = d_direct && r_direct ? NULL : need_scratch(slot, bits);
    if (!(d_direct && r_direct) && sc == NULL)
        return 0;
    b->d = NULL;
    b->r = NULL;
    if (k->distance)
        b->d = k->dist_aligned ? (real *)(void *)(k->distance + b->i0 * sizeof(real)) : sc->dist;
    if (k->results)
        b->r = k->res_aligned ? (ttd_result *)(void *)(k->results + b->i0 * sizeof(ttd_result)) : sc->res;
    else if (k->need_flags)
        b->r = sc->res;
    return 1;
}

/* After the kernel: placeholders' outputs become NaN, not-converged pairs are reported, and
 * outputs written to scratch go to the caller. */
static void sink_finish(const array_sink *k, const block *b, scratch *sc, atomic_uint *bits)
{
    if (b->any_bad) {
        const real nan = (real)NAN;
        for (size_t i = 0; i < b->m; ++i) {
            if (!sc->bad[i])
                continue;
            if (b->d)
                b->d[i] = nan;
            if (b->r) {
                ttd_result *r = &b->r[i];
                r->distance = nan;
                for (int c = 0; c < 3; ++c)
                    r->p[c] = r->q[c] = r->bary_p[c] = r->bary_q[c] = nan;
                r->flags = TTD_PAIR_NONFINITE;
                r->feature_p = r->feature_q = 0;
                r->iterations = 0;
            }
        }
    }
    if (b->r && k->need_flags)
        for (size_t i = 0; i < b->m; ++i)
            if (b->r[i].flags & TTD_PAIR_NOT_CONVERGED) {
                atomic_fetch_or(bits, TTD_BATCH_NOT_CONVERGED);
                break;
            }
    if (sc != NULL && b->d == sc->dist)
        memcpy(k->distance + b->i0 * sizeof(real), sc->dist, b->m * sizeof(real));
    if (sc != NULL && k->results && b->r == sc->res)
        memcpy(k->results + b->i0 * sizeof(ttd_result), sc->res, b->m * sizeof(ttd_result));
}

/* One block: source -> runner -> sink. */
static void run_block(void *ctx, size_t blockno, int worker)
{
    job *j = ctx;
    if (atomic_load_explicit(&j->bits, memory_order_relaxed) & TTD_BATCH_NOMEM)
        return;
    block b = {.i0 = blockno * TTD_BLOCK_PAIRS};
    b.m = j->n - b.i0 < TTD_BLOCK_PAIRS ? j->n - b.i0 : TTD_BLOCK_PAIRS;
    scratch **slot = &j->scratch[worker];
    if (!j->fill(j->src, &b, slot, &j->bits) || !sink_prepare(&j->sink, &b, slot, &j->bits))
        return;
    const ttd_out out = {b.d, NULL, b.r};
    j->run.fn(b.m, b.s, b.t, &j->run.params, (real)INFINITY, &out);
    sink_finish(&j->sink, &b, *slot, &j->bits);
}

/* Runs every block of j on the configured threads and turns the bits into a status. The caller
 * set n, the source and the sink's arrays; everything else is set here. */
static ttd_status engine_run(const ttd_engine_config *cfg, job *j)
{
    j->run = TTD_RUNNER_MAKE(cfg);
    j->sink.need_flags = j->run.need_flags;
    j->sink.dist_aligned = ((uintptr_t)j->sink.distance % _Alignof(real)) == 0;
    j->sink.res_aligned = ((uintptr_t)j->sink.results % _Alignof(ttd_result)) == 0;
    atomic_init(&j->bits, 0u);
    const size_t nblocks = (j->n + TTD_BLOCK_PAIRS - 1) / TTD_BLOCK_PAIRS;
    const int workers = ttd_parallel_workers(nblocks, cfg->threads);
    for (int w = 0; w < workers; ++w)
        j->scratch[w] = NULL;
    ttd_parallel_for(nblocks, workers, run_block, j);
    for (int w = 0; w < workers; ++w)
        free(j->scratch[w]);
    return ttd_batch_status(atomic_load(&j->bits));
}

static ttd_status engine_batch(const ttd_engine_config *cfg, size_t n, const real *s, const real *t,
                               real *distance, ttd_result *results)
{
    const flat_source src = {
        .s = (const unsigned char *)s,
        .t = (const unsigned char *)t,
        .aligned = ((uintptr_t)s % _Alignof(real)) == 0 && ((uintptr_t)t % _Alignof(real)) == 0,
    };
    job j = {.n = n, .fill = flat_fill, .src = &src};
    j.sink.distance = (unsigned char *)distance;
    j.sink.results = (unsigned char *)results;
    return engine_run(cfg, &j);
}

/* The index check before an indexed run: every pair's triangle indices and their vertex
 * indices in range, one block at a time. */
typedef struct index_check {
    const indexed_source *src;
    size_t n;
    atomic_uint bad;
} index_check;

static void check_block(void *ctx, size_t blockno, int worker)
{
    (void)worker;
    index_check *c = ctx;
    if (atomic_load_explicit(&c->bad, memory_order_relaxed))
        return;
    const engine_mesh *m1 = c->src->m1, *m2 = c->src->m2;
    const unsigned char *tris1 = (const unsigned char *)m1->tris, *tris2 = (const unsigned char *)m2->tris;
    const size_t i0 = blockno * TTD_BLOCK_PAIRS;
    const size_t i1 = c->n - i0 < TTD_BLOCK_PAIRS ? c->n : i0 + TTD_BLOCK_PAIRS;
    for (size_t i = i0; i < i1; ++i) {
        uint32_t a = ttd_load_u32(c->src->pairs, 2 * i), b = ttd_load_u32(c->src->pairs, 2 * i + 1);
        int ok = a < m1->nt && b < m2->nt;
        for (size_t k = 0; ok && k < 3; ++k)
            ok = ttd_load_u32(tris1, 3 * (size_t)a + k) < m1->nv && ttd_load_u32(tris2, 3 * (size_t)b + k) < m2->nv;
        if (!ok) {
            atomic_store(&c->bad, 1u);
            return;
        }
    }
}

static ttd_status engine_indexed(const ttd_engine_config *cfg, const engine_mesh *m1, const engine_mesh *m2,
                                 size_t n, const uint32_t *pairs, real *distance, ttd_result *results)
{
    const indexed_source src = {.m1 = m1, .m2 = m2, .pairs = (const unsigned char *)pairs};
    index_check check = {.src = &src, .n = n};
    atomic_init(&check.bad, 0u);
    const size_t nblocks = (n + TTD_BLOCK_PAIRS - 1) / TTD_BLOCK_PAIRS;
    ttd_parallel_for(nblocks, ttd_parallel_workers(nblocks, cfg->threads), check_block, &check);
    if (atomic_load(&check.bad))
        return TTD_ERR_INDEX_OUT_OF_RANGE;
    job j = {.n = n, .fill = indexed_fill, .src = &src};
    j.sink.distance = (unsigned char *)distance;
    j.sink.results = (unsigned char *)results;
    return engine_run(cfg, &j);
}

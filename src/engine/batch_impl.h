/* SPDX-License-Identifier: MIT */
/* The batch engine, precision-generic: engine/batch_d.c and engine/batch_f.c compile it once
 * each (see there for TTD_UBITS, TTD_EXP_BITS, TTD_KERNEL_FN, TTD_DISPATCH_KERNEL).
 *
 * Each block of TTD_BLOCK_PAIRS pairs goes one of two ways. The fast way, taken by almost
 * every block: all 18n coordinates finite, every pointer aligned for its type, and no flags
 * needed beyond what the caller asked for; the kernel then reads and writes the caller's
 * arrays directly. Otherwise the block goes through the worker's scratch (allocated on first
 * need, bounded by the block size): inputs are copied byte-wise (so any alignment is fine),
 * a pair with NaN/inf is replaced by a harmless placeholder pair, the kernel runs, and the
 * placeholder's outputs are overwritten with NaN and TTD_PAIR_NONFINITE. The block boundaries
 * do not depend on the thread count, so neither do the results. */

typedef struct ttd_scratch {
    real s[9 * TTD_BLOCK_PAIRS];
    real t[9 * TTD_BLOCK_PAIRS];
    real dist[TTD_BLOCK_PAIRS];
    ttd_result res[TTD_BLOCK_PAIRS];
    unsigned char bad[TTD_BLOCK_PAIRS];
} ttd_scratch;

typedef struct ttd_bjob {
    TTD_KERNEL_FN fn;
    const ttd_params *prm;
    size_t n;
    int need_flags;                /* results are needed for TTD_PAIR_NOT_CONVERGED */
    int mesh_check;                /* mesh: this pass only checks indices */
    const unsigned char *s, *t;    /* plain batch: the caller's coordinates, as bytes */
    int in_aligned;
    const engine_mesh *m1, *m2; /* mesh batch */
    const unsigned char *pairs;
    unsigned char *distance, *results; /* the caller's outputs, as bytes; either may be NULL */
    int dist_aligned, res_aligned;
    atomic_uint bits;              /* TTD_BATCH_* seen by any block */
    ttd_scratch *scratch[TTD_MAX_WORKERS];
} ttd_bjob;

/* Non-zero when any of count reals at p (any alignment) is NaN or inf. The exponent field
 * of such a value is all ones, so adding one to it carries into the sign bit of the masked
 * word: an OR of and-add words, without compares, that compilers vectorise with baseline
 * SSE2. Eight accumulators keep the loop from waiting on one OR chain. */
static int ttd_any_nonfinite(const unsigned char *p, size_t count)
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

static ttd_scratch *ttd_get_scratch(ttd_bjob *j, int worker)
{
    if (j->scratch[worker] == NULL) {
        j->scratch[worker] = malloc(sizeof(ttd_scratch));
        if (j->scratch[worker] == NULL)
            atomic_fetch_or(&j->bits, TTD_BATCH_NOMEM);
    }
    return j->scratch[worker];
}

/* Mesh check pass: every pair's triangle indices and their vertex indices in range. */
static int ttd_mesh_block_ok(const ttd_bjob *j, size_t i0, size_t m)
{
    const unsigned char *tris1 = (const unsigned char *)j->m1->tris;
    const unsigned char *tris2 = (const unsigned char *)j->m2->tris;
    for (size_t i = i0; i < i0 + m; ++i) {
        uint32_t a = ttd_load_u32(j->pairs, 2 * i), b = ttd_load_u32(j->pairs, 2 * i + 1);
        if (a >= j->m1->nt || b >= j->m2->nt)
            return 0;
        for (size_t k = 0; k < 3; ++k)
            if (ttd_load_u32(tris1, 3 * (size_t)a + k) >= j->m1->nv ||
                ttd_load_u32(tris2, 3 * (size_t)b + k) >= j->m2->nv)
                return 0;
    }
    return 1;
}

/* Copies the 9 coordinates of triangle tri of mesh into out (indices already checked). */
static void ttd_gather(const engine_mesh *mesh, uint32_t tri, real *out)
{
    const unsigned char *tris = (const unsigned char *)mesh->tris;
    const unsigned char *verts = (const unsigned char *)mesh->verts;
    for (size_t k = 0; k < 3; ++k) {
        size_t v = ttd_load_u32(tris, 3 * (size_t)tri + k);
        memcpy(out + 3 * k, verts + 3 * v * sizeof(real), 3 * sizeof(real));
    }
}

static void ttd_block(void *ctx, size_t block, int worker)
{
    ttd_bjob *j = ctx;
    const unsigned stop = TTD_BATCH_NOMEM | TTD_BATCH_BAD_INDEX;
    if (atomic_load_explicit(&j->bits, memory_order_relaxed) & stop)
        return;
    const size_t i0 = block * TTD_BLOCK_PAIRS;
    const size_t m = j->n - i0 < TTD_BLOCK_PAIRS ? j->n - i0 : TTD_BLOCK_PAIRS;
    if (j->mesh_check) {
        if (!ttd_mesh_block_ok(j, i0, m))
            atomic_fetch_or(&j->bits, TTD_BATCH_BAD_INDEX);
        return;
    }

    const size_t in_off = 9 * i0 * sizeof(real);
    int any_bad = 0;
    if (j->m1 == NULL)
        any_bad = ttd_any_nonfinite(j->s + in_off, 9 * m) ||
                  ttd_any_nonfinite(j->t + in_off, 9 * m);
    const int fast = j->m1 == NULL && !any_bad && j->in_aligned &&
                     (j->distance == NULL || j->dist_aligned) &&
                     (j->results != NULL ? j->res_aligned : !j->need_flags);
    if (fast) {
        /* Aligned, finite and nothing to add: the kernel works on the caller's arrays. */
        real *d = j->distance ? (real *)(void *)(j->distance + i0 * sizeof(real)) : NULL;
        ttd_result *r = j->results ? (ttd_result *)(void *)(j->results + i0 * sizeof(ttd_result)) : NULL;
        j->fn(m, (const real *)(const void *)(j->s + in_off), (const real *)(const void *)(j->t + in_off),
              j->prm, d, r);
        if (r && j->need_flags)
            for (size_t i = 0; i < m; ++i)
                if (r[i].flags & TTD_PAIR_NOT_CONVERGED) {
                    atomic_fetch_or(&j->bits, TTD_BATCH_NOT_CONVERGED);
                    break;
                }
        return;
    }

    ttd_scratch *sc = ttd_get_scratch(j, worker);
    if (sc == NULL)
        return;
    if (j->m1 == NULL) {
        memcpy(sc->s, j->s + in_off, 9 * m * sizeof(real));
        memcpy(sc->t, j->t + in_off, 9 * m * sizeof(real));
    } else {
        for (size_t i = 0; i < m; ++i) {
            ttd_gather(j->m1, ttd_load_u32(j->pairs, 2 * (i0 + i)), sc->s + 9 * i);
            ttd_gather(j->m2, ttd_load_u32(j->pairs, 2 * (i0 + i) + 1), sc->t + 9 * i);
        }
        any_bad = ttd_any_nonfinite((const unsigned char *)sc->s, 9 * m) ||
                  ttd_any_nonfinite((const unsigned char *)sc->t, 9 * m);
    }
    if (any_bad) {
        /* A pair far from degenerate and from touching, so that every method handles it
         * quickly; its outputs are overwritten below. */
        static const real ph_s[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
        static const real ph_t[9] = {(real)0.25, (real)0.25, 1, 1, (real)0.25, 2, (real)0.25, 1, 2};
        for (size_t i = 0; i < m; ++i) {
            sc->bad[i] = (unsigned char)(ttd_any_nonfinite((const unsigned char *)(sc->s + 9 * i), 9) ||
                                         ttd_any_nonfinite((const unsigned char *)(sc->t + 9 * i), 9));
            if (sc->bad[i]) {
                memcpy(sc->s + 9 * i, ph_s, sizeof ph_s);
                memcpy(sc->t + 9 * i, ph_t, sizeof ph_t);
            }
        }
        atomic_fetch_or(&j->bits, TTD_BATCH_NONFINITE);
    }

    real *d = NULL;
    ttd_result *r = NULL;
    if (j->distance)
        d = j->dist_aligned ? (real *)(void *)(j->distance + i0 * sizeof(real)) : sc->dist;
    if (j->results)
        r = j->res_aligned ? (ttd_result *)(void *)(j->results + i0 * sizeof(ttd_result)) : sc->res;
    else if (j->need_flags)
        r = sc->res;
    j->fn(m, sc->s, sc->t, j->prm, d, r);

    if (any_bad) {
        const real nan = (real)NAN;
        for (size_t i = 0; i < m; ++i) {
            if (!sc->bad[i])
                continue;
            if (d)
                d[i] = nan;
            if (r) {
                r[i].distance = nan;
                for (int k = 0; k < 3; ++k)
                    r[i].p[k] = r[i].q[k] = r[i].bary_p[k] = r[i].bary_q[k] = nan;
                r[i].flags = TTD_PAIR_NONFINITE;
                r[i].feature_p = r[i].feature_q = 0;
                r[i].iterations = 0;
            }
        }
    }
    if (r && j->need_flags)
        for (size_t i = 0; i < m; ++i)
            if (r[i].flags & TTD_PAIR_NOT_CONVERGED) {
                atomic_fetch_or(&j->bits, TTD_BATCH_NOT_CONVERGED);
                break;
            }
    if (d == sc->dist)
        memcpy(j->distance + i0 * sizeof(real), sc->dist, m * sizeof(real));
    if (j->results && r == sc->res)
        memcpy(j->results + i0 * sizeof(ttd_result), sc->res, m * sizeof(ttd_result));
}

/* Runs the blocks and turns the bits into a status. The caller set n, the inputs (s/t or
 * m1/m2/pairs) and the outputs; everything else is set here. */
static ttd_status ttd_run(const ttd_engine_config *cfg, ttd_bjob *j)
{
    j->fn = TTD_DISPATCH_KERNEL(cfg->isa, cfg->method);
    j->prm = &cfg->params;
    j->need_flags = ttd_method_traits_of(cfg->method)->may_not_converge;
    j->mesh_check = 0;
    j->dist_aligned = ((uintptr_t)j->distance % _Alignof(real)) == 0;
    j->res_aligned = ((uintptr_t)j->results % _Alignof(ttd_result)) == 0;
    atomic_init(&j->bits, 0u);

    const size_t nblocks = (j->n + TTD_BLOCK_PAIRS - 1) / TTD_BLOCK_PAIRS;
    const int workers = ttd_parallel_workers(nblocks, cfg->threads);
    for (int w = 0; w < workers; ++w)
        j->scratch[w] = NULL;
    if (j->m1 != NULL) {
        j->mesh_check = 1;
        ttd_parallel_for(nblocks, workers, ttd_block, j);
        j->mesh_check = 0;
    }
    if (!(atomic_load(&j->bits) & TTD_BATCH_BAD_INDEX))
        ttd_parallel_for(nblocks, workers, ttd_block, j);
    for (int w = 0; w < workers; ++w)
        free(j->scratch[w]);
    return ttd_batch_status(atomic_load(&j->bits));
}

static ttd_status engine_batch(const ttd_engine_config *cfg, size_t n, const real *s,
                                     const real *t, real *distance, ttd_result *results)
{
    ttd_bjob j;
    j.n = n;
    j.s = (const unsigned char *)s;
    j.t = (const unsigned char *)t;
    j.in_aligned = ((uintptr_t)s % _Alignof(real)) == 0 && ((uintptr_t)t % _Alignof(real)) == 0;
    j.m1 = j.m2 = NULL;
    j.pairs = NULL;
    j.distance = (unsigned char *)distance;
    j.results = (unsigned char *)results;
    return ttd_run(cfg, &j);
}

static ttd_status engine_mesh_run(const ttd_engine_config *cfg, const engine_mesh *m1,
                                    const engine_mesh *m2, size_t n, const uint32_t *pairs,
                                    real *distance, ttd_result *results)
{
    ttd_bjob j;
    j.n = n;
    j.s = j.t = NULL;
    j.in_aligned = 1;
    j.m1 = m1;
    j.m2 = m2;
    j.pairs = (const unsigned char *)pairs;
    j.distance = (unsigned char *)distance;
    j.results = (unsigned char *)results;
    return ttd_run(cfg, &j);
}

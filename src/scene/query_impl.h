/* SPDX-License-Identifier: MIT */
/* The scene queries, precision-generic: scene/query_d.c and query_f.c compile this once each.
 *
 * A query sweeps the bodies' world boxes for the eligible pairs that may come within its margin
 * (scene/scene.c), then hands each such body pair to the mesh traversal (mesh/mesh.h) with both
 * bodies' world poses: the tree works in body i's frame, the exact kernel on both triangles moved
 * into the world, as a brute force over all triangle pairs in the world frame would. Body pairs
 * are spread over the threads, each walked by one thread (one pair's answer does not depend on
 * which), and their answers are joined in (i, j) order: results do not depend on the threads.
 * docs/scenes.md has the design. */

/* the bodies' helpers, then the manifold's reduction and normals, which stand on them alone;
 * the walk below hands them each body pair's contacts */
#include "scene/body_impl.h"
#include "scene/manifold_impl.h"

/* ---- collide and distance: one mesh query per body pair ------------------------------------ */

typedef struct pair_job {
    const ttd_engine_config *cfg; /* one thread */
    struct ttd_scene *s;
    const scene_pair *pairs;
    int mode;                     /* MODE_COLLIDE or MODE_DISTANCE */
    real limit;                   /* the margin, or the distance's bound */
    ttd_collision *hit;           /* collide: one per pair */
    ttd_mesh_result *dist;        /* distance: one per pair */
    /* the closest pair alone: the bound falls to the best distance so far (its bits: distances
     * are >= 0, so their bit patterns order as they do), and no pair after the first at
     * distance 0 is needed (pairs come in (i, j) order: that one is the answer) */
    int closest_only;
    _Atomic uint64_t best_bits;
    atomic_size_t first_zero;
    atomic_int nomem;
} pair_job;

/* *x = min(*x, v), atomically. */
static void atomic_min_size(atomic_size_t *x, size_t v)
{
    size_t old = atomic_load(x);
    while (v < old && !atomic_compare_exchange_weak(x, &old, v))
        ;
}

static uint64_t real_bits(real x)
{
    double d = (double)x;
    uint64_t b;
    memcpy(&b, &d, sizeof b);
    return b;
}

static real bits_real(uint64_t b)
{
    double d;
    memcpy(&d, &b, sizeof d);
    return (real)d;
}

enum { MODE_COLLIDE, MODE_DISTANCE };

/* Body pair p's distance if at most bound (else a result beyond it), solids included: one inside
 * the other is at distance 0 (at the inner body's vertex). */
static ttd_status pair_distance(const ttd_engine_config *one, const struct ttd_scene *s, const scene_pair *p,
                                real bound, ttd_mesh_result *r)
{
    const double defect = pair_defect(s, p->i, p->j);
    const ttd_status st = TTD_QUERY(distance)(one, s->body[p->i].mesh, s->body[p->j].mesh, 1, body_pose(s, p->j),
                                              body_pose(s, p->i), &defect, bound, 0, r);
    real at[3];
    int side;
    if (st == TTD_OK && !(r->distance == 0) && solid_pair(s, p->i, p->j) && (side = solid_nested(s, p->i, p->j, at))) {
        r->distance = 0;
        memcpy(r->p, at, sizeof r->p);
        memcpy(r->q, at, sizeof r->q);
        r->tri_a = side == 2 ? 0 : UINT32_MAX;
        r->tri_b = side == 1 ? 0 : UINT32_MAX;
        r->flags = TTD_MESH_INTERSECTING | TTD_MESH_CONTAINED;
    }
    return st;
}

static void pair_task(void *ctx, size_t k, int worker)
{
    (void)worker;
    pair_job *J = ctx;
    const scene_pair *p = &J->pairs[k];
    const struct ttd_mesh *a = J->s->body[p->i].mesh, *b = J->s->body[p->j].mesh;
    const double defect = pair_defect(J->s, p->i, p->j);
    ttd_status st;
    if (J->mode == MODE_COLLIDE && J->closest_only && k > atomic_load_explicit(&J->first_zero, memory_order_relaxed)) {
        J->hit[k] = (ttd_collision){0, UINT32_MAX, UINT32_MAX, 0, 0}; /* after a touching pair: not needed */
        st = TTD_OK;
    } else if (J->mode == MODE_COLLIDE) {
        st = TTD_QUERY(collide)(J->cfg, a, b, 1, body_pose(J->s, p->j), body_pose(J->s, p->i), &defect, J->limit,
                                &J->hit[k]);
        real at[3];
        int side;
        if (st == TTD_OK && !J->hit[k].hit && solid_pair(J->s, p->i, p->j) && (side = solid_nested(J->s, p->i, p->j, at))) {
            J->hit[k].hit = 1; /* one solid inside the other: the inner body's triangle 0 */
            J->hit[k].tri_a = side == 2 ? 0 : UINT32_MAX;
            J->hit[k].tri_b = side == 1 ? 0 : UINT32_MAX;
        }
        if (st == TTD_OK && J->closest_only && J->hit[k].hit) {
            atomic_min_size(&J->first_zero, k);
        }
    } else if (J->closest_only && k > atomic_load_explicit(&J->first_zero, memory_order_relaxed)) {
        J->dist[k].distance = (real)INFINITY; /* after a pair at 0: not needed */
        J->dist[k].node_tests = 0;
        J->dist[k].pair_tests = 0;
        st = TTD_OK;
    } else {
        const real bound = J->closest_only ? bits_real(atomic_load(&J->best_bits)) : J->limit;
        st = pair_distance(J->cfg, J->s, p, bound, &J->dist[k]);
        const real d = J->dist[k].distance;
        if (st == TTD_OK && J->closest_only && d <= bound) {
            uint64_t old = atomic_load(&J->best_bits);
            const uint64_t mine = real_bits(d);
            while (mine < old && !atomic_compare_exchange_weak(&J->best_bits, &old, mine))
                ;
            if (d == 0) {
                atomic_min_size(&J->first_zero, k);
            }
        }
    }
    if (st != TTD_OK)
        atomic_store(&J->nomem, 1);
}

static ttd_status run_pairs(const ttd_engine_config *cfg, pair_job *J, size_t n)
{
    const ttd_engine_config one = one_thread(cfg);
    J->cfg = &one;
    atomic_init(&J->best_bits, real_bits(J->limit));
    atomic_init(&J->first_zero, SIZE_MAX);
    atomic_init(&J->nomem, 0);
    ttd_pool_tasks(J->s->pool, n, cfg->threads, pair_task, J);
    if (atomic_load(&J->nomem))
        return TTD_ERR_OUT_OF_MEMORY;
    ttd_scene_stats *t = &J->s->stats;
    t->body_pairs += n;
    for (size_t k = 0; k < n; ++k) {
        t->node_tests += J->mode == MODE_COLLIDE ? J->hit[k].node_tests : J->dist[k].node_tests;
        t->pair_tests += J->mode == MODE_COLLIDE ? J->hit[k].pair_tests : J->dist[k].pair_tests;
    }
    return TTD_OK;
}

static ttd_status query_collide(const ttd_engine_config *cfg, struct ttd_scene *s, real margin, ttd_scene_array *out)
{
    out->count = 0;
    s->stats = (ttd_scene_stats){0};
    scene_pair *pairs;
    size_t n;
    if (!ttd_scene_sweep_on(s, cfg->threads, (double)margin, NULL, &pairs, &n))
        return TTD_ERR_OUT_OF_MEMORY;
    pair_job J = {.s = s, .pairs = pairs, .mode = MODE_COLLIDE, .limit = margin};
    J.hit = malloc((n ? n : 1) * sizeof *J.hit);
    ttd_status st = J.hit == NULL ? TTD_ERR_OUT_OF_MEMORY : run_pairs(cfg, &J, n);
    size_t hits = 0;
    for (size_t k = 0; st == TTD_OK && k < n; ++k)
        hits += J.hit[k].hit != 0;
    if (st == TTD_OK && !array_reserve(out, hits, sizeof(ttd_scene_hit)))
        st = TTD_ERR_OUT_OF_MEMORY;
    for (size_t k = 0; st == TTD_OK && k < n; ++k)
        if (J.hit[k].hit)
            ((ttd_scene_hit *)out->data)[out->count++] =
                (ttd_scene_hit){pairs[k].i, pairs[k].j, J.hit[k].tri_a, J.hit[k].tri_b};
    free(J.hit);
    free(pairs);
    s->stats.results = out->count;
    if (st != TTD_OK)
        s->stats = (ttd_scene_stats){0};
    return st;
}

/* ---- contacts: every pair within the margin, per body pair ---------------------------------- */

/* A contact's place in its body pair's order, and where it is in the walk's order. */
typedef struct sort_item {
    uint64_t key; /* tri_i * (triangles of j) + tri_j */
    size_t at;
} sort_item;

/* Sorts x[0..n) by key, stably, with y as scratch; the result is in x or y, returned. A radix
 * sort, a byte of the key at a time up to the largest key's bytes (3 passes on the pile's
 * icospheres): the comparison sort it replaces, with a call per comparison, was 7.5% of the
 * pile's contact query (docs/scene-speed.md). */
static sort_item *radix_sort(sort_item *x, sort_item *y, size_t n, uint64_t largest)
{
    for (int shift = 0; shift < 64 && (largest >> shift) != 0; shift += 8) {
        size_t count[257] = {0};
        for (size_t k = 0; k < n; ++k)
            count[((x[k].key >> shift) & 255) + 1]++;
        if (count[((x[0].key >> shift) & 255) + 1] == n)
            continue; /* one digit: this pass would not move anything */
        for (int d = 0; d < 256; ++d)
            count[d + 1] += count[d];
        for (size_t k = 0; k < n; ++k)
            y[count[(x[k].key >> shift) & 255]++] = x[k];
        sort_item *t = x;
        x = y;
        y = t;
    }
    return x;
}

/* What a scene keeps between its contact and manifold queries (s->scratch; docs/scenes.md section
 * 9, docs/scene-buffers.md): per worker, the memory it used for its body pairs, and per body pair
 * where its contacts and points went. Made and freed every query, these left glibc a free heap top
 * above its trim threshold: every query gave the pages back and faulted them in again (the sliver
 * tower: 21 brk calls and 939 faults a query). A query resets the fill marks alone: every pair
 * writes what it reads (its contacts, then its points), and the manifold's scratch already
 * serves many pairs a query. */
typedef struct scratch_worker {
    ttd_mesh_contacts set;      /* the walk's contacts of the pair at hand */
    ttd_scene_contact *block;   /* the contacts of the pairs this worker walked this query, a pair
                                 * after another (a pair keeps its offset: the block may move); a
                                 * manifold gives a pair's room back once the pair is reduced */
    size_t used, cap;
    size_t peak;                /* the most of the block this query held at once */
    sort_item *sort;            /* the radix sort's items and scratch, 2 per contact */
    size_t sort_cap;
    manifold_work mw;
    ttd_scene_array part;       /* the points of the pairs this worker reduced this query */
} scratch_worker;

typedef struct scratch_pair {
    const ttd_scene_contact *found; /* its contacts (none: NULL), once the walks are done */
    size_t at, n;                   /* their offset in their walker's block, their number */
    int by;                         /* their walker */
    int red_by;                     /* manifold: the worker that reduced it, */
    size_t red_at, red_n;           /* its first point in that worker's part, its points */
    size_t out;                     /* contacts: its first contact in the caller's array */
    uint64_t tests[2];              /* node tests and pair tests */
} scratch_pair;

typedef struct query_scratch {
    scratch_worker *w;
    int nw;                 /* workers made: the most a query has used */
    scratch_pair *pair;
    size_t pair_cap;
    int thin;               /* queries in a row that used under a quarter of the blocks held */
} query_scratch;

static void scratch_worker_free(scratch_worker *w)
{
    TTD_CONTACTS_FREE(&w->set);
    free(w->block);
    free(w->sort);
    manifold_work_free(&w->mw);
    free(w->part.data);
    memset(w, 0, sizeof *w);
}

/* The bytes of the workers' contact blocks (scene/scene.h, ttd_scene_scratch_held). */
static size_t scratch_held(const void *p)
{
    const query_scratch *q = p;
    size_t held = 0;
    for (int k = 0; k < q->nw; ++k)
        held += q->w[k].cap * sizeof(ttd_scene_contact);
    return held;
}

static void scratch_free(void *p)
{
    query_scratch *q = p;
    for (int k = 0; q != NULL && k < q->nw; ++k)
        scratch_worker_free(&q->w[k]);
    if (q != NULL) {
        free(q->w);
        free(q->pair);
    }
    free(q);
}

/* The scene's scratch with room for `workers` workers and n body pairs, the workers' fill marks
 * reset; NULL out of memory (what the scene held stays, for the destroy). */
static query_scratch *scratch_get(struct ttd_scene *s, int workers, size_t n)
{
    query_scratch *q = s->scratch;
    if (q == NULL) {
        if ((q = calloc(1, sizeof *q)) == NULL)
            return NULL;
        s->scratch = q;
        s->scratch_free = scratch_free;
        s->scratch_held = scratch_held;
    }
    if (workers > q->nw) {
        scratch_worker *w = realloc(q->w, (size_t)workers * sizeof *w);
        if (w == NULL)
            return NULL;
        memset(w + q->nw, 0, (size_t)(workers - q->nw) * sizeof *w);
        q->w = w;
        q->nw = workers;
    }
    if (n > q->pair_cap) {
        const size_t cap = n > 2 * q->pair_cap ? n : 2 * q->pair_cap;
        scratch_pair *p = realloc(q->pair, cap * sizeof *p);
        if (p == NULL)
            return NULL;
        q->pair = p;
        q->pair_cap = cap;
    }
    for (int k = 0; k < q->nw; ++k) {
        q->w[k].used = 0;
        q->w[k].peak = 0;
        q->w[k].part.count = 0;
    }
    return q;
}

/* After a query: the scratch freed when it has been far larger than the queries' need for
 * SCRATCH_THIN_QUERIES queries in a row (the contact blocks, most of it, measure it; the rest is
 * per pair or per worker, the largest pair's). So it holds memory for the largest query of a
 * recent run of queries, not for the largest ever; blocks of SCRATCH_SMALL contacts or fewer in
 * all are kept (scene/scene.h: a worker's first block is 1,024 contacts, and a small scene's would
 * be freed and made again every few queries). */
static void scratch_done(struct ttd_scene *s)
{
    query_scratch *q = s->scratch;
    if (q == NULL)
        return;
    size_t used = 0, held = 0;
    for (int k = 0; k < q->nw; ++k) {
        used += q->w[k].peak;
        held += q->w[k].cap;
    }
    q->thin = held > SCRATCH_SMALL && 4 * used < held ? q->thin + 1 : 0;
    if (q->thin >= SCRATCH_THIN_QUERIES) {
        scratch_free(q);
        s->scratch = NULL;
    }
}

/* The contacts of body pair p within margin, sorted by (tri_i, tri_j), appended to w's block: at
 * *at, *n of them (the block may move: an offset, not a pointer); with walk_order, in the walk's
 * order (a manifold's pair that is not a pair of solids: its reduction orders its points itself
 * by a total order, the questions of step 0 too, so it gives the same bits from contacts in any
 * order; the sort was a few percent of the contacts' cost). */
static int pair_contacts(const ttd_engine_config *cfg, struct ttd_scene *s, const scene_pair *p, real margin,
                         int walk_order, scratch_worker *w, size_t *at, size_t *n, uint64_t tests[2])
{
    *at = w->used;
    *n = 0;
    ttd_mesh_contacts *set = &w->set;
    const double defect = pair_defect(s, p->i, p->j);
    /* one walk from the root: this pair's contacts are sorted below, and the pairs spread over
     * the threads, so the mesh query's cut into sub-walks (for an order independent of the
     * thread count) would buy nothing */
    if (TTD_QUERY(contacts_walk)(cfg, s->body[p->i].mesh, s->body[p->j].mesh, body_pose(s, p->j), body_pose(s, p->i),
                                 defect, margin, set, tests) != TTD_OK)
        return 0;
    const size_t m = set->count;
    if (m == 0)
        return 1;
    if (m > w->cap - w->used) {
        ttd_scene_contact *b = array_grow(w->block, &w->cap, w->used + m, sizeof *b, 1024);
        if (b == NULL)
            return 0;
        w->block = b;
    }
    ttd_scene_contact *v = w->block + w->used;
    const sort_item *sorted = NULL;
    if (!walk_order) {
        if (2 * m > w->sort_cap) {
            sort_item *o = realloc(w->sort, 2 * m * sizeof *o);
            if (o == NULL)
                return 0;
            w->sort = o;
            w->sort_cap = 2 * m;
        }
        const uint64_t ntj = (uint64_t)s->body[p->j].mesh->nt;
        for (size_t k = 0; k < m; ++k)
            w->sort[k] = (sort_item){(uint64_t)set->pairs[k].tri_a * ntj + set->pairs[k].tri_b, k};
        sorted = radix_sort(w->sort, w->sort + m, m, (uint64_t)s->body[p->i].mesh->nt * ntj - 1);
    }
    for (size_t k = 0; k < m; ++k) {
        const ttd_mesh_contact *c = &set->pairs[sorted != NULL ? sorted[k].at : k];
        v[k].i = p->i;
        v[k].j = p->j;
        v[k].tri_i = c->tri_a;
        v[k].tri_j = c->tri_b;
        v[k].distance = c->distance;
        memcpy(v[k].p, c->p, sizeof v[k].p);
        memcpy(v[k].q, c->q, sizeof v[k].q);
    }
    w->used += m;
    w->peak = w->used > w->peak ? w->used : w->peak;
    *n = m;
    return 1;
}

typedef struct contact_job {
    const ttd_engine_config *cfg;
    struct ttd_scene *s;
    const scene_pair *pairs;
    real margin;
    query_scratch *q;
    int walk_order;               /* a manifold's: pairs not of solids in the walk's order (pair_contacts) */
    atomic_int nomem;
    struct reduce_job *reduce;    /* a manifold's: each pair reduced in its task, its contacts' room given back */
} contact_job;

static int reduce_found(struct reduce_job *R, size_t k, int worker, scratch_pair *r, scratch_worker *w);

static void contact_task(void *ctx, size_t k, int worker)
{
    contact_job *J = ctx;
    const scene_pair *p = &J->pairs[k];
    scratch_pair *r = &J->q->pair[k];
    scratch_worker *w = &J->q->w[worker];
    r->by = worker;
    if (!pair_contacts(J->cfg, J->s, p, J->margin, J->walk_order && !solid_pair(J->s, p->i, p->j), w, &r->at, &r->n,
                       r->tests))
        atomic_store(&J->nomem, 1);
    else if (J->reduce != NULL) {
        /* reduced at once, while the pair's contacts are in the cache (read back after every
         * pair's walk, they came from memory: the pile's 37 MB), and their room given back, so
         * that the next pair's contacts go where these were */
        if (!reduce_found(J->reduce, k, worker, r, w))
            atomic_store(&J->nomem, 1);
        w->used = r->at;
        r->n = 0;
    }
}

/* Every eligible body pair within a margin and its contacts: pairs[0..n), with pair[k].found and
 * pair[k].n for pair k (sorted by triangles), in the scene's scratch (valid until its next query). */
typedef struct pair_contacts_set {
    scene_pair *pairs;
    size_t n;
    query_scratch *q;
    scratch_pair *pair;
} pair_contacts_set;

/* Frees what the set owns (the pairs: the contacts are the scene's), then lets the scene judge
 * the scratch's size. */
static void pair_contacts_free(struct ttd_scene *s, pair_contacts_set *c)
{
    free(c->pairs);
    scratch_done(s);
}

/* The set of every eligible body pair's contacts within margin (the caller frees it with
 * pair_contacts_free, whatever the status); walk_order: see contact_job. */
static ttd_status contacts_run(const ttd_engine_config *cfg, struct ttd_scene *s, real margin, int walk_order,
                               struct reduce_job *reduce, pair_contacts_set *c);

static ttd_status all_contacts(const ttd_engine_config *cfg, struct ttd_scene *s, real margin, int walk_order,
                               pair_contacts_set *c)
{
    *c = (pair_contacts_set){NULL, 0, NULL, NULL};
    s->stats = (ttd_scene_stats){0};
    if (!ttd_scene_sweep_on(s, cfg->threads, (double)margin, NULL, &c->pairs, &c->n))
        return TTD_ERR_OUT_OF_MEMORY;
    return contacts_run(cfg, s, margin, walk_order, NULL, c);
}

/* The walks of the pairs c->pairs[0..c->n) (swept), into c; with reduce, each pair reduced in its
 * task (reduce_found) and its contacts not kept (pair[k].n 0). */
static ttd_status contacts_run(const ttd_engine_config *cfg, struct ttd_scene *s, real margin, int walk_order,
                               struct reduce_job *reduce, pair_contacts_set *c)
{
    const ttd_engine_config one = one_thread(cfg);
    const int workers = ttd_parallel_task_workers(c->n, cfg->threads);
    query_scratch *q = scratch_get(s, workers, c->n);
    if (q == NULL)
        return TTD_ERR_OUT_OF_MEMORY;
    contact_job J = {&one, s, c->pairs, margin, q, walk_order, 0, reduce};
    atomic_init(&J.nomem, 0);
    ttd_pool_tasks(s->pool, c->n, cfg->threads, contact_task, &J);
    if (atomic_load(&J.nomem))
        return TTD_ERR_OUT_OF_MEMORY;
    s->stats.body_pairs = c->n;
    for (size_t k = 0; k < c->n; ++k) {
        scratch_pair *r = &q->pair[k];
        r->found = r->n ? q->w[r->by].block + r->at : NULL;
        s->stats.node_tests += r->tests[0];
        s->stats.pair_tests += r->tests[1];
    }
    c->q = q;
    c->pair = q->pair;
    return TTD_OK;
}

/* Copies body pairs' contacts into the caller's array at their offsets, a pair per task: on the
 * threads, as a serial copy of the pile's 33 MB would hold the second thread up. */
typedef struct join_job {
    const pair_contacts_set *c;
    ttd_scene_contact *dst;
} join_job;

static void join_task(void *ctx, size_t k, int worker)
{
    (void)worker;
    const join_job *J = ctx;
    const scratch_pair *r = &J->c->pair[k];
    if (r->n)
        memcpy(J->dst + r->out, r->found, r->n * sizeof(ttd_scene_contact));
}

static ttd_status query_contacts(const ttd_engine_config *cfg, struct ttd_scene *s, real margin,
                                 ttd_scene_array *out)
{
    out->count = 0;
    pair_contacts_set c;
    ttd_status st = all_contacts(cfg, s, margin, 0, &c);
    size_t total = 0;
    for (size_t k = 0; st == TTD_OK && k < c.n; ++k) {
        c.pair[k].out = total;
        total += c.pair[k].n;
    }
    if (st == TTD_OK && !array_reserve(out, total, sizeof(ttd_scene_contact)))
        st = TTD_ERR_OUT_OF_MEMORY;
    if (st == TTD_OK) {
        join_job J = {&c, out->data};
        /* a copy under 64 KB (a few microseconds) on the caller alone: a job on the pool costs
         * more than its half */
        ttd_pool_tasks(s->pool, c.n, total * sizeof(ttd_scene_contact) < 65536 ? 1 : cfg->threads, join_task, &J);
        out->count = total;
    }
    pair_contacts_free(s, &c);
    s->stats.results = out->count;
    if (st != TTD_OK)
        s->stats = (ttd_scene_stats){0};
    return st;
}

/* ---- contacts counted: query_contacts' number, no contact held --------------------------------- */

typedef struct count_job {
    const ttd_engine_config *cfg;
    struct ttd_scene *s;
    const scene_pair *pairs;
    real margin;
    size_t *counts;   /* per pair: its contacts; summed in pair order after the walks */
    uint64_t *tests;  /* per pair: node tests and pair tests */
    atomic_int nomem;
} count_job;

static void count_task(void *ctx, size_t k, int worker)
{
    (void)worker;
    count_job *J = ctx;
    const scene_pair *p = &J->pairs[k];
    if (TTD_QUERY(contacts_walk_count)(J->cfg, J->s->body[p->i].mesh, J->s->body[p->j].mesh, body_pose(J->s, p->j),
                                       body_pose(J->s, p->i), pair_defect(J->s, p->i, p->j), J->margin,
                                       &J->counts[k], J->tests + 2 * k) != TTD_OK)
        atomic_store(&J->nomem, 1);
}

/* The number of contacts query_contacts would give, into *count: each body pair's walk counts its
 * pairs instead of holding them (memory: a count and two test counters per body pair). The same
 * body pairs and the same walks, so the same number on any thread count. */
static ttd_status query_contacts_count(const ttd_engine_config *cfg, struct ttd_scene *s, real margin, size_t *count)
{
    *count = 0;
    scene_pair *pairs;
    size_t n;
    if (!ttd_scene_sweep(s, (double)margin, NULL, &pairs, &n))
        return TTD_ERR_OUT_OF_MEMORY;
    const ttd_engine_config one = one_thread(cfg);
    count_job J = {&one, s, pairs, margin, calloc(n ? n : 1, sizeof(size_t)), calloc(2 * (n ? n : 1), sizeof(uint64_t)),
                   0};
    atomic_init(&J.nomem, J.counts == NULL || J.tests == NULL);
    if (!atomic_load(&J.nomem))
        ttd_pool_tasks(s->pool, n, cfg->threads, count_task, &J);
    const ttd_status st = atomic_load(&J.nomem) ? TTD_ERR_OUT_OF_MEMORY : TTD_OK;
    s->stats = (ttd_scene_stats){0};
    if (st == TTD_OK) {
        s->stats.body_pairs = n;
        for (size_t k = 0; k < n; ++k) {
            *count += J.counts[k];
            s->stats.node_tests += J.tests[2 * k];
            s->stats.pair_tests += J.tests[2 * k + 1];
        }
        s->stats.results = *count;
    }
    free(J.counts);
    free(J.tests);
    free(pairs);
    return st;
}

/* ---- manifolds: each body pair's contacts reduced to a few points --------------------------- */

/* Body pairs' reductions on the threads: each worker appends to its own array with its own
 * scratch, and the pairs' points are joined in pair order afterwards, so the answer does not
 * depend on the threads. */
typedef struct reduce_job {
    const struct ttd_scene *s;
    const ttd_engine_config *one;
    const pair_contacts_set *c;
    real margin;
    size_t max_points;
} reduce_job;

/* Pair k's reduction, in its walk's task (contact_task), from its contacts in w's block, into
 * w's points; 0 out of memory. */
static int reduce_found(reduce_job *J, size_t k, int worker, scratch_pair *r, scratch_worker *w)
{
    const scene_pair *p = &J->c->pairs[k];
    ttd_scene_array *part = &w->part;
    r->red_by = worker;
    r->red_at = part->count;
    r->red_n = 0;
    if (r->n == 0 && !solid_pair(J->s, p->i, p->j))
        return 1;
    if (!reduce_pair(J->s, J->one, p, r->n ? w->block + r->at : NULL, r->n, J->margin, J->max_points, &w->mw, part))
        return 0;
    r->red_n = part->count - r->red_at;
    return 1;
}

static ttd_status query_manifold(const ttd_engine_config *cfg, struct ttd_scene *s, real margin, size_t max_points,
                                 ttd_scene_array *out)
{
    out->count = 0;
    pair_contacts_set c = {NULL, 0, NULL, NULL};
    const ttd_engine_config one = one_thread(cfg);
    s->stats = (ttd_scene_stats){0};
    ttd_status st = ttd_scene_sweep_on(s, cfg->threads, (double)margin, NULL, &c.pairs, &c.n) ? TTD_OK : TTD_ERR_OUT_OF_MEMORY;
    /* the meshes' edge information, made on their first manifold (mesh/mesh.h), before the
     * threads read it: for every pair swept, as the reductions run in the walks' tasks */
    for (size_t k = 0; st == TTD_OK && k < c.n; ++k)
        if (ttd_mesh_edges_get(s->body[c.pairs[k].i].mesh) == NULL || ttd_mesh_edges_get(s->body[c.pairs[k].j].mesh) == NULL)
            st = TTD_ERR_OUT_OF_MEMORY;
    reduce_job J = {s, &one, &c, margin, max_points};
    if (st == TTD_OK)
        st = contacts_run(cfg, s, margin, 1, &J, &c);
    size_t total = 0;
    for (size_t k = 0; st == TTD_OK && k < c.n; ++k)
        total += c.pair[k].red_n;
    if (st == TTD_OK && !array_reserve(out, total, sizeof(ttd_scene_point)))
        st = TTD_ERR_OUT_OF_MEMORY;
    for (size_t k = 0; st == TTD_OK && k < c.n; ++k) {
        const scratch_pair *r = &c.pair[k];
        if (r->red_n) {
            memcpy((ttd_scene_point *)out->data + out->count, (const ttd_scene_point *)c.q->w[r->red_by].part.data + r->red_at,
                   r->red_n * sizeof(ttd_scene_point));
            out->count += r->red_n;
        }
    }
    pair_contacts_free(s, &c);
    s->stats.results = out->count;
    if (st != TTD_OK) {
        out->count = 0;
        s->stats = (ttd_scene_stats){0};
    }
    return st;
}

/* ---- distance: the closest body pair, and each body's nearest ------------------------------ */

static ttd_scene_contact no_contact(uint32_t i)
{
    ttd_scene_contact c = {i, UINT32_MAX, UINT32_MAX, UINT32_MAX, (real)INFINITY, {0, 0, 0}, {0, 0, 0}};
    return c;
}

/* The record of body pair p at its minimum d, with its smallest pair of triangles at d (as body
 * `first` sees it: its own triangle first), from the contacts within d. */
static int pair_record(const ttd_engine_config *cfg, struct ttd_scene *s, const scene_pair *p, real d, uint32_t first,
                       ttd_scene_contact *rec)
{
    scratch_worker w = {0}; /* one pair's: not the scene's, which a query's contacts may be in */
    size_t at, n;
    const ttd_engine_config one = one_thread(cfg);
    uint64_t tests[2];
    const int ok = pair_contacts(&one, s, p, d, 0, &w, &at, &n, tests);
    const ttd_scene_contact *v = n ? w.block + at : NULL;
    const int swap = first != p->i;
    size_t best = n;
    for (size_t k = 0; ok && k < n; ++k) {
        if (v[k].distance != d)
            continue;
        if (best == n)
            best = k;
        else if (swap && (v[k].tri_j < v[best].tri_j || (v[k].tri_j == v[best].tri_j && v[k].tri_i < v[best].tri_i)))
            best = k;
        /* not swapped: v is sorted by (tri_i, tri_j), the first at d is the smallest */
    }
    if (ok && best < n) {
        *rec = v[best];
        if (swap) {
            *rec = (ttd_scene_contact){p->j, p->i, v[best].tri_j, v[best].tri_i, d, {0, 0, 0}, {0, 0, 0}};
            memcpy(rec->p, v[best].q, sizeof rec->p);
            memcpy(rec->q, v[best].p, sizeof rec->q);
        }
    }
    scratch_worker_free(&w);
    if (!ok)
        return 0;
    if (best == n) { /* no triangle pair at d: one solid inside the other (else cannot happen) */
        real at3[3];
        const int side = d == 0 && solid_pair(s, p->i, p->j) ? solid_nested(s, p->i, p->j, at3) : 0;
        if (side == 0)
            return 0;
        const uint32_t ti = side == 2 ? 0 : UINT32_MAX, tj = side == 1 ? 0 : UINT32_MAX;
        *rec = swap ? (ttd_scene_contact){p->j, p->i, tj, ti, 0, {0, 0, 0}, {0, 0, 0}}
                    : (ttd_scene_contact){p->i, p->j, ti, tj, 0, {0, 0, 0}, {0, 0, 0}};
        memcpy(rec->p, at3, sizeof rec->p);
        memcpy(rec->q, at3, sizeof rec->q);
    }
    return 1;
}

/* Box tests the scan below may spend per present body before it leaves the rest to the sweep. */
#define FIRST_TOUCH_BUDGET 32

/* The closest pair alone, where bodies touch: the first touching pair in (i, j) order is the
 * answer. Bodies are taken in id order, each against the later bodies whose world boxes meet its
 * own (a pass over the boxes, so in j order), collided at 0 in that order, and the first that
 * touches is the answer: in a packed scene it comes within the first bodies, found without
 * sorting the whole scene (the sweep at 0 over the pile's 1,000 bodies was 87% of its distance
 * query, docs/scene-speed.md). Every touching pair has meeting boxes, so none before it is
 * skipped. Gives up after FIRST_TOUCH_BUDGET box tests per body (a scene whose first bodies touch
 * nothing: the sweep then does it all). Returns 1 with *pair, 0 when no pair touches (*gave_up
 * 0) or it gave up (*gave_up 1), -1 out of memory. */
static int first_touching(const ttd_engine_config *cfg, struct ttd_scene *s, scene_pair *pair, int *gave_up)
{
    const ttd_engine_config one = one_thread(cfg);
    const size_t nb = s->nbody;
    size_t budget = FIRST_TOUCH_BUDGET * (s->present > 1 ? s->present : 1);
    *gave_up = 0;
    for (size_t i = 0; i < nb; ++i) {
        if (s->body[i].mesh == NULL)
            continue;
        if (budget < nb - i) {
            *gave_up = 1;
            return 0;
        }
        budget -= nb - i;
        const double *bi = s->box + 6 * i;
        for (size_t j = i + 1; j < nb; ++j) {
            const double *bj = s->box + 6 * j;
            if (s->body[j].mesh == NULL || !(bj[0] <= bi[3] && bj[3] >= bi[0] && bj[1] <= bi[4] && bj[4] >= bi[1] &&
                                              bj[2] <= bi[5] && bj[5] >= bi[2]) ||
                !ttd_scene_eligible(s, (uint32_t)i, (uint32_t)j))
                continue;
            const double defect = pair_defect(s, (uint32_t)i, (uint32_t)j);
            ttd_collision hit;
            if (TTD_QUERY(collide)(&one, s->body[i].mesh, s->body[j].mesh, 1, body_pose(s, (uint32_t)j),
                                   body_pose(s, (uint32_t)i), &defect, 0, &hit) != TTD_OK)
                return -1;
            s->stats.body_pairs++;
            s->stats.node_tests += hit.node_tests;
            s->stats.pair_tests += hit.pair_tests;
            if (hit.hit) {
                *pair = (scene_pair){(uint32_t)i, (uint32_t)j};
                return 1;
            }
        }
    }
    return 0;
}

/* ---- each body's nearest, best first ------------------------------------------------------ */

/* A lower bound on the distance between bodies x and y from their world boxes (which hold the
 * triangles the kernel measures, section 4 of docs/mesh-queries.md): the boxes' gap, scaled by
 * its largest axis (no overflow or underflow of squares), then lowered by 2^-20 of itself, more
 * than the roundings here and a float distance's own (so it stays below a computed distance). */
static double box_gap(const struct ttd_scene *s, uint32_t x, uint32_t y)
{
    const double *a = s->box + 6 * (size_t)x, *b = s->box + 6 * (size_t)y;
    double g[3], big = 0;
    for (int k = 0; k < 3; ++k) {
        const double u = b[k] - a[3 + k], v = a[k] - b[3 + k];
        g[k] = u > v ? u : v;
        g[k] = g[k] > 0 ? g[k] : 0;
        big = g[k] > big ? g[k] : big;
    }
    if (!(big > 0))
        return 0;
    double q = 0;
    for (int k = 0; k < 3; ++k)
        q += (g[k] / big) * (g[k] / big);
    return big * sqrt(q) * (1 - 0x1p-20);
}

typedef struct nearest_cand {
    double gap;
    uint32_t id;
} nearest_cand;

static int cand_cmp(const void *x, const void *y)
{
    const nearest_cand *a = x, *b = y;
    return a->gap < b->gap ? -1 : a->gap > b->gap ? 1 : (a->id > b->id) - (a->id < b->id);
}

/* Neighbours in the sweep's order tried for a first bound, on each side. */
#define NEAREST_SEED 8

typedef struct nearest_job {
    const ttd_engine_config *one;
    const struct ttd_scene *s;
    const uint32_t *todo;   /* the bodies asked */
    const uint32_t *pos;    /* each present body's place in s->order */
    double widest;          /* the widest box along the sweep's axis */
    real *best;             /* per body id: its nearest distance (in: the bound), */
    uint32_t *partner;      /* and its partner (UINT32_MAX: none) */
    nearest_cand **cand;    /* per worker: room for every body */
    uint64_t *tests;        /* per body asked: body pairs, node tests, pair tests */
    atomic_int nomem;
} nearest_job;

/* Body i's nearest, its partner the smallest id at that distance: the bodies whose boxes are
 * within the best distance so far (scanned out from i in the sweep's order while the axis alone
 * allows it), measured in the order of their boxes' gaps, each with the best so far as bound; a
 * first bound from the closest-looking of i's neighbours in that order. */
static void nearest_task(void *ctx, size_t t, int worker)
{
    nearest_job *J = ctx;
    const struct ttd_scene *s = J->s;
    const uint32_t i = J->todo[t], at = J->pos[i];
    const int ax = s->axis;
    const double lo = s->box[6 * (size_t)i + (size_t)ax], hi = s->box[6 * (size_t)i + 3 + (size_t)ax];
    real best = J->best[i];
    uint32_t partner = J->partner[i];
    uint64_t *tests = J->tests + 3 * t;
    nearest_cand *c = J->cand[worker];
    size_t n = 0;
    /* the seed: the neighbour with the smallest gap, measured without a bound (the bound given) */
    uint32_t seed = UINT32_MAX;
    double seed_gap = HUGE_VAL;
    for (size_t k = at > NEAREST_SEED ? at - NEAREST_SEED : 0; k < s->norder && k <= (size_t)at + NEAREST_SEED; ++k) {
        const uint32_t j = s->order[k];
        if (j == i || !ttd_scene_eligible(s, i, j))
            continue;
        const double g = box_gap(s, i, j);
        if (g < seed_gap || (g == seed_gap && j < seed)) {
            seed_gap = g;
            seed = j;
        }
    }
    for (int pass = 0; pass < 2; ++pass) {
        if (pass == 1) { /* every body whose box may come within best, from both sides (the
                          * reach above best by more than the roundings of the gaps and of a
                          * float distance) */
            const double reach = (double)best * (1 + 0x1p-20);
            for (size_t k = (size_t)at + 1; k < s->norder; ++k) {
                const uint32_t j = s->order[k];
                if (!(s->box[6 * (size_t)j + (size_t)ax] - hi <= reach))
                    break; /* the order's lower ends only grow */
                const double g = box_gap(s, i, j);
                if (j != seed && g <= (double)best && ttd_scene_eligible(s, i, j))
                    c[n++] = (nearest_cand){g, j};
            }
            for (size_t k = at; k-- > 0;) {
                const uint32_t j = s->order[k];
                if (!(lo - (s->box[6 * (size_t)j + (size_t)ax] + J->widest) <= reach))
                    break; /* no box to the left reaches further than its lower end + widest */
                const double g = box_gap(s, i, j);
                if (j != seed && g <= (double)best && ttd_scene_eligible(s, i, j))
                    c[n++] = (nearest_cand){g, j};
            }
            qsort(c, n, sizeof *c, cand_cmp);
        } else if (seed != UINT32_MAX && seed_gap <= (double)best) {
            c[n++] = (nearest_cand){seed_gap, seed};
        }
        for (size_t k = 0; k < n; ++k) {
            const uint32_t j = c[k].id;
            /* a distance at least gap: better only below best, or at it with a smaller id */
            if (c[k].gap > (double)best)
                break;
            if (c[k].gap == (double)best && j > partner)
                continue;
            const scene_pair p = {i < j ? i : j, i < j ? j : i};
            ttd_mesh_result r;
            if (pair_distance(J->one, s, &p, best, &r) != TTD_OK) {
                atomic_store(&J->nomem, 1);
                return;
            }
            tests[0]++;
            tests[1] += r.node_tests;
            tests[2] += r.pair_tests;
            const real d = r.distance;
            if (d < best || (d == best && j < partner)) {
                best = d;
                partner = j;
            }
        }
        n = 0;
    }
    J->best[i] = best;
    J->partner[i] = partner;
}

/* Bodies todo[0..n)'s nearest (best[], partner[] hold each one's bound and partner so far), on
 * the threads, each body independently: the same answer on every thread count. Needs the sweep's
 * order made (a sweep of this query). */
static ttd_status nearest_rest(const ttd_engine_config *cfg, struct ttd_scene *s, const uint32_t *todo, size_t n,
                               real *best, uint32_t *partner)
{
    const int workers = ttd_parallel_task_workers(n, cfg->threads);
    const ttd_engine_config one = one_thread(cfg);
    uint32_t *pos = malloc((s->nbody ? s->nbody : 1) * sizeof *pos);
    nearest_job J = {&one, s, todo, pos, 0, best, partner, calloc((size_t)workers + 1, sizeof(nearest_cand *)),
                     calloc(3 * (n ? n : 1), sizeof(uint64_t)), 0};
    atomic_init(&J.nomem, pos == NULL || J.cand == NULL || J.tests == NULL);
    for (int w = 0; !atomic_load(&J.nomem) && w < workers; ++w)
        if ((J.cand[w] = malloc((s->norder ? s->norder : 1) * sizeof(nearest_cand))) == NULL)
            atomic_store(&J.nomem, 1);
    for (size_t k = 0; !atomic_load(&J.nomem) && k < s->norder; ++k) {
        const uint32_t id = s->order[k];
        pos[id] = (uint32_t)k;
        const double w = s->box[6 * (size_t)id + 3 + (size_t)s->axis] - s->box[6 * (size_t)id + (size_t)s->axis];
        J.widest = w > J.widest ? w : J.widest;
    }
    if (!atomic_load(&J.nomem))
        ttd_pool_tasks(s->pool, n, cfg->threads, nearest_task, &J);
    for (size_t k = 0; J.tests != NULL && k < n; ++k) {
        s->stats.body_pairs += J.tests[3 * k];
        s->stats.node_tests += J.tests[3 * k + 1];
        s->stats.pair_tests += J.tests[3 * k + 2];
    }
    const ttd_status st = atomic_load(&J.nomem) ? TTD_ERR_OUT_OF_MEMORY : TTD_OK;
    for (int w = 0; J.cand != NULL && w < workers; ++w)
        free(J.cand[w]);
    free(J.cand);
    free(J.tests);
    free(pos);
    return st;
}

static ttd_status query_distance(const ttd_engine_config *cfg, struct ttd_scene *s, real upper_bound,
                                 ttd_scene_contact *closest, ttd_scene_contact *nearest)
{
    *closest = no_contact(UINT32_MAX);
    s->stats = (ttd_scene_stats){0};
    const size_t nb = s->nbody;
    for (size_t id = 0; nearest != NULL && id < nb; ++id)
        nearest[id] = no_contact((uint32_t)id);
    /* nearest[] of the present bodies still open (beyond every margin tried) */
    unsigned char *open = nearest != NULL ? calloc(nb ? nb : 1, 1) : NULL;
    real *best = nearest != NULL ? malloc((nb ? nb : 1) * sizeof *best) : NULL;
    uint32_t *partner = nearest != NULL ? malloc((nb ? nb : 1) * sizeof *partner) : NULL;
    if (nearest != NULL && (open == NULL || best == NULL || partner == NULL)) {
        free(open);
        free(best);
        free(partner);
        return TTD_ERR_OUT_OF_MEMORY;
    }
    size_t nopen = 0;
    for (size_t id = 0; nearest != NULL && id < nb; ++id) {
        open[id] = s->body[id].mesh != NULL;
        nopen += open[id];
        best[id] = (real)INFINITY;
        partner[id] = UINT32_MAX;
    }
    /* margins: the bound, or growing ones until the answers are inside (every body pair within a
     * margin is examined, so a minimum at or below it is the minimum over all pairs) */
    const double extent = ttd_scene_extent(s);
    double margin = isfinite((double)upper_bound) ? (double)upper_bound : 1e-3 * extent;
    ttd_status st = TTD_OK;
    int closest_done = s->present < 2;
    real cbest = (real)INFINITY;
    size_t cpair_i = SIZE_MAX;
    scene_pair cpair = {0, 0};
    /* the closest pair alone: touching bodies are found sooner by collision at 0, which stops at
     * its first pair within 0, than by distance; the first touching pair in (i, j) order is the
     * answer, and no pair after it is needed */
    int gave_up = 1;
    if (nearest == NULL && !closest_done) {
        const int f = first_touching(cfg, s, &cpair, &gave_up);
        if (f < 0)
            return TTD_ERR_OUT_OF_MEMORY;
        if (f > 0) {
            cbest = 0;
            cpair_i = 0;
            closest_done = 1;
        }
    }
    if (nearest == NULL && !closest_done && gave_up) {
        scene_pair *pairs;
        size_t n;
        if (!ttd_scene_sweep(s, 0, NULL, &pairs, &n))
            return TTD_ERR_OUT_OF_MEMORY;
        pair_job J = {.s = s, .pairs = pairs, .mode = MODE_COLLIDE, .limit = 0, .closest_only = 1};
        J.hit = malloc((n ? n : 1) * sizeof *J.hit);
        st = J.hit == NULL ? TTD_ERR_OUT_OF_MEMORY : run_pairs(cfg, &J, n);
        const size_t z = atomic_load(&J.first_zero);
        if (st == TTD_OK && z < n) {
            cbest = 0;
            cpair = pairs[z];
            cpair_i = z;
            closest_done = 1;
        }
        free(J.hit);
        free(pairs);
    }
    while (st == TTD_OK && !(closest_done && nopen == 0)) {
        const size_t open_before = nopen;
        const int last = isfinite((double)upper_bound) || !(margin < extent) || !(margin > 0);
        const double m = last && !isfinite((double)upper_bound) ? HUGE_VAL : margin;
        scene_pair *pairs;
        size_t n;
        if (!ttd_scene_sweep(s, m, closest_done ? open : NULL, &pairs, &n)) {
            st = TTD_ERR_OUT_OF_MEMORY;
            break;
        }
        pair_job J = {.s = s, .pairs = pairs, .mode = MODE_DISTANCE,
                      .limit = isfinite(m) ? (real)m : (real)INFINITY, .closest_only = nearest == NULL};
        J.dist = malloc((n ? n : 1) * sizeof *J.dist);
        st = J.dist == NULL ? TTD_ERR_OUT_OF_MEMORY : run_pairs(cfg, &J, n);
        for (size_t k = 0; st == TTD_OK && k < n; ++k) {
            const real d = J.dist[k].distance;
            if (!(d <= J.limit))
                continue;
            if (!closest_done && d < cbest) { /* pairs come in (i, j) order: ties keep the first */
                cbest = d;
                cpair = pairs[k];
                cpair_i = k;
            }
            for (int side = 0; nearest != NULL && side < 2; ++side) {
                const uint32_t me = side ? pairs[k].j : pairs[k].i, other = side ? pairs[k].i : pairs[k].j;
                if (open[me] && (d < best[me] || (d == best[me] && other < partner[me]))) {
                    best[me] = d;
                    partner[me] = other;
                }
            }
        }
        free(J.dist);
        free(pairs);
        if (st != TTD_OK)
            break;
        if (cpair_i != SIZE_MAX)
            closest_done = 1;
        for (size_t id = 0; nearest != NULL && id < nb; ++id)
            if (open[id] && best[id] <= (real)m) {
                open[id] = 0;
                --nopen;
            }
        if (last || (closest_done && nopen == 0))
            break;
        if (nearest != NULL && 2 * (open_before - nopen) < open_before) {
            /* a margin that settled fewer than half the bodies still open: the rest get their
             * nearest best first (the margins grow by 4 and measure every pair within them
             * again, a sparse scene's last margins nearly every pair), then the closest pair
             * from them: the smallest id at the smallest distance and its partner, which comes
             * later (an earlier one would be at that distance too) */
            uint32_t *todo = malloc((nopen ? nopen : 1) * sizeof *todo);
            size_t nt = 0;
            for (size_t id = 0; todo != NULL && id < nb; ++id)
                if (open[id])
                    todo[nt++] = (uint32_t)id;
            st = todo == NULL ? TTD_ERR_OUT_OF_MEMORY : nearest_rest(cfg, s, todo, nt, best, partner);
            free(todo);
            for (size_t id = 0; st == TTD_OK && !closest_done && id < nb; ++id)
                if (partner[id] != UINT32_MAX && (cpair_i == SIZE_MAX || best[id] < cbest)) {
                    cbest = best[id];
                    cpair = (scene_pair){(uint32_t)id < partner[id] ? (uint32_t)id : partner[id],
                                         (uint32_t)id < partner[id] ? partner[id] : (uint32_t)id};
                    cpair_i = 0;
                }
            break;
        }
        margin *= 4;
    }
    if (st == TTD_OK && cpair_i != SIZE_MAX && !pair_record(cfg, s, &cpair, cbest, cpair.i, closest))
        st = TTD_ERR_OUT_OF_MEMORY;
    for (size_t id = 0; st == TTD_OK && nearest != NULL && id < nb; ++id) {
        if (partner[id] == UINT32_MAX)
            continue;
        const uint32_t o = partner[id];
        const scene_pair p = {id < o ? (uint32_t)id : o, id < o ? o : (uint32_t)id};
        if (!pair_record(cfg, s, &p, best[id], (uint32_t)id, &nearest[id]))
            st = TTD_ERR_OUT_OF_MEMORY;
    }
    free(open);
    free(best);
    free(partner);
    s->stats.results = st == TTD_OK && cpair_i != SIZE_MAX;
    if (st != TTD_OK)
        s->stats = (ttd_scene_stats){0};
    return st;
}

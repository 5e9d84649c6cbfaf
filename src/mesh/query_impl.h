/* SPDX-License-Identifier: MIT */
/* The mesh queries, precision-generic: mesh/query_d.c and query_f.c compile this once each and
 * write out the entries of mesh/mesh.h.
 *
 * One traversal serves every query: a depth-first walk over pairs (box of a, box of b), each
 * pair an item on a stack. An item whose bound exceeds the query's limit is dropped. Otherwise
 * the larger box is opened (a triangle's box never is): one node test (core/kernels.h) bounds
 * the other box against all of its children at once, the children within the limit are pushed,
 * nearest last so that it is walked first. Two triangles make a candidate pair; candidates are
 * gathered (b's triangle moved into a's frame by the caller's pose, as a brute force would) and
 * handed to the exact kernel in batches, with the limit as its bound:
 *   - minimum distance: the limit is the best distance so far (over 1 + rel_tol), falling as
 *     batches come back; small batches keep it fresh;
 *   - collision: the margin, and the walk stops at the first pair within it;
 *   - contacts: the margin; every pair within it is kept, with its points.
 * A self query (one mesh against itself: self-contacts and self-collision) is the same walk with
 * b = a under the identity, from the root's box against itself: an item of a box against itself
 * opens into its children against themselves and every two of its children (expand_self), and
 * a candidate pair is ordered (the smaller triangle first) and filtered by the vertices its two
 * triangles share (queue_pair).
 * Each pose is walked by one thread, in an order fixed by the meshes and the pose; a contact
 * query on one pose is cut into a fixed list of sub-walks, run on any threads and joined in list
 * order. So results do not depend on the thread count, and as every row's node test and exact
 * kernel give the same bits, not on the instruction set either.
 *
 * Rounding: a bound is computed from rounded boxes, rotations and products, and the kernel
 * from b's vertices moved by the caller's pose, rounded. Items are dropped only when their bound
 * exceeds the limit by delta = (64 eps + 4 d) S, where S bounds every magnitude involved (the
 * distance between the meshes' origins, twice their radii, and how far from the coordinate
 * origin the meshes and the pose's translation are) and d is how far the pose's R is from a
 * rotation. That covers the bounds' rounding, the boxes' own (their extents are rounded), the
 * pose's and the exact kernel's, so that no pair the exact method would have reported is ever
 * skipped. */

/* A box of one side: slot `slot` of node `node`. */
typedef struct item {
    int32_t an, bn;   /* a's box: nodes_a[an] slot as; b's likewise */
    int32_t as, bs;
    real lb2;         /* squared lower bound on the distance between the two boxes */
} item;

/* One side of a query. */
typedef struct side {
    const ttd_node *nodes;
    const real *verts;
    const uint32_t *tris;
} side;

enum { MODE_DISTANCE, MODE_COLLIDE, MODE_CONTACTS };

/* Candidates per kernel call: few for the minimum and collision (the bound falls as they come
 * back; a leaf's pairs go as soon as they fill a vector of the widest row), many for contacts
 * (nothing falls; fewer calls). Fixed numbers, not the row's lane count: which pairs are
 * tested, and so which of equally near pairs is reported, must not depend on the instruction
 * set. */
#define BATCH_MIN 16
#define BATCH_LEAF 8
#define BATCH_MAX 128

/* The most items one opening writes: a box against itself gives its children against themselves
 * and every two of them (expand_self); any other opening, at most the children. */
#define EXPAND_MAX (TTD_NODE_WIDTH * (TTD_NODE_WIDTH + 1) / 2)

/* A self query's bits (qctx.self): set for every self query, and whether pairs that share one
 * vertex are kept (TTD_SELF_SHARED_VERTEX). */
#define SELF_QUERY 1u
#define SELF_SHARED 2u

/* What a queued candidate computes: the two triangles, or (a self query's pair that shares one
 * vertex) one triangle's edge opposite that vertex against the other triangle. */
enum { ENTRY_PAIR, ENTRY_EDGE_A, ENTRY_EDGE_B };

/* What is shared by every walk of one pose. */
typedef struct qpose {
    side a, b;
    real r[9], t[3];   /* b's frame about its origin -> a's frame about its origin */
    real ri[9], ti[3]; /* and back */
    real pose[12];     /* the caller's pose: b's coordinates -> a's frame (or the world's) */
    real pose_a[12];   /* with has_a: a's coordinates -> the world (scenes); else a stays put */
    int has_a;
    unsigned self;     /* a self query (qctx.self): b is a, under the identity */
    real delta;        /* the rounding margin of the bounds */
} qpose;

/* What one query needs beyond its poses. */
typedef struct qctx {
    const struct ttd_mesh *ma, *mb;
    ttd_node_test_fn node_test;
    TTD_KERNEL_FN kernel;
    int threads;
    unsigned self;     /* 0, or SELF_QUERY (ma == mb) with SELF_SHARED or not */
    ttd_isa isa;       /* the row's (self-contacts by the grid take the double row's screens) */
    ttd_node_within_fn node_within;
} qctx;

/* A contact found, before it is copied into the caller's set. */
typedef ttd_contact contact;

/* A growable list of contacts: chunks of doubling size, never copied while it grows (a contact
 * query may find millions of pairs: copying on growth would touch twice the memory, and fresh
 * memory is what such a query spends its time on), or, with one worker, the caller's set
 * itself (`direct`), whose memory a caller that reuses its set has already touched. */
#define CLIST_CHUNKS 40
#define CLIST_FIRST 256

typedef struct clist {
    contact *chunk[CLIST_CHUNKS]; /* chunk c holds CLIST_FIRST << c contacts */
    int nchunks;
    size_t n;                     /* contacts in all */
    size_t in_last;               /* contacts in the last chunk */
    ttd_contacts *direct;         /* when not NULL: append to this set instead */
    int count_only;               /* only count them (n), holding none: the *_count queries */
} clist;

/* A thread's working memory, reused across the walks it runs. */
/* Items a walk holds without allocating (most walks need fewer). */
#define STACK_INLINE 256
/* Triangles kept moved by the pose, per side (direct-mapped by triangle index; a power of 2): all
 * of them for a contact walk (the pile's: 64 slots moved 0.41M triangles, 256 0.36M), the first
 * MOVED_SLOTS_SHORT for the other walks, many of them short, which clear their keys each time. */
#define MOVED_SLOTS 256
#define MOVED_SLOTS_SHORT 64
/* Node-test views of boxes kept per walk (direct-mapped by box; a power of 2): all of them for the
 * minimum's best-first walk, which meets a box again long after (a far pose's views were
 * recomputed for 386 of 625 node tests with 32), the first QUERY_SLOTS_SHORT for the other walks,
 * many of them short, which clear their keys each time. */
#define QUERY_SLOTS 256
#define QUERY_SLOTS_SHORT 32

typedef struct qwork {
    /* workers' qwork lie side by side and are written all the time: a cache line each */
    _Alignas(64) item *stack;        /* inline, or on the heap once it outgrew it */
    size_t cap;
    item inline_stack[STACK_INLINE];
    item *deferred;                  /* the minimum's first phase: items left for the second */
    size_t ndef, defcap;
    int nb;                          /* candidates waiting for the kernel */
    uint32_t ta[BATCH_MAX], tb[BATCH_MAX];
    uint8_t kind[BATCH_MAX];         /* ENTRY_*: what each computes */
    uint32_t shared[BATCH_MAX];      /* ENTRY_EDGE_*: the vertex the two triangles share */
    real s[9 * BATCH_MAX], t[9 * BATCH_MAX];
    real dist[BATCH_MAX], pts[6 * BATCH_MAX];
    /* The walk's triangles as the kernel sees them (b's moved by the pose; a's by a's pose in
     * scenes), kept for the walk: a contact walk meets one triangle with many of the other
     * side's in a row, and moving it again for every pair (three vertex gathers, 27 products)
     * was 14% of a large contact query. The same bits whichever way they are reached. */
    uint32_t moved_key[2][MOVED_SLOTS]; /* triangle index, or UINT32_MAX: empty */
    real moved[2][MOVED_SLOTS][9];
    /* Boxes as the node test sees them, with the other side's frame mapped in. A best-first walk
     * opens items in bound order, so that one box meets the other side's nodes far apart in
     * time: keeping only the last view recomputed it for 94% of the node tests (far bunny
     * poses), at a third of the node test's own instructions. */
    uint64_t query_key[QUERY_SLOTS]; /* (node * 8 + slot) * 2 + side, or UINT64_MAX: empty */
    ttd_box_query query[QUERY_SLOTS];
    unsigned query_mask;             /* slots in use - 1 */
    unsigned moved_mask;             /* moved-triangle slots in use - 1 */
    int nomem;
} qwork;

/* One walk's state and results. */
typedef struct walk {
    int mode;
    real limit;        /* the kernel's bound: best so far, or the margin */
    real limit2;       /* an item is dropped when its lb2 exceeds this */
    real gate2;        /* and deferred to the second phase when it exceeds this (the minimum) */
    int ordered;       /* children come nearest last (depth-first walks) */
    int cutting;       /* a contact query's pose being cut into sub-walks: pairs stay items */
    int any_order;     /* contacts for a caller that sorts them (query_contacts_walk): no walk order */
    real rel;          /* 1 + rel_tol (distance) */
    int found, hit;    /* distance: some pair within the bound; collide: a witness */
    uint32_t ta, tb;   /* the pair */
    uint32_t node_tests;
    uint64_t pair_tests;
    clist *out;        /* contacts */
    int bound_adapt;   /* self-contacts by the grid: the kernel's bound is left out (skip_bound)
                          after a batch that recorded half of its entries or more */
    int skip_bound;
} walk;

/* The items' limit from the kernel's bound. */
static void walk_set_limit(walk *w, const qpose *P, real limit)
{
    w->limit = limit;
    const real l = (limit + P->delta) / w->rel;
    /* floored: a bound that underflows (tiny meshes) carries an absolute error of a few
     * subnormals, which the relative margin delta does not cover; below the floor nothing is
     * dropped */
    const real floor2 = 64 * TTD_REAL_MIN;
    w->limit2 = l * l > floor2 ? l * l : floor2;
}

/* n workers' memory, its arrays allocated as they are needed. */
static void qwork_init(qwork *W)
{
    W->stack = W->inline_stack;
    W->cap = STACK_INLINE;
    W->deferred = NULL;
    W->ndef = W->defcap = 0;
    W->nb = W->nomem = 0;
    W->query_mask = QUERY_SLOTS_SHORT - 1;
    W->moved_mask = MOVED_SLOTS_SHORT - 1;
}

static void qwork_release(qwork *W)
{
    if (W->stack != W->inline_stack)
        free(W->stack);
    free(W->deferred);
}

/* n workers' memory; one worker (a single pose, the common call) uses `one`, no allocation. */
static qwork *qwork_new(int n, qwork *one)
{
    qwork *W = n == 1 ? one : aligned_alloc(_Alignof(qwork), (size_t)n * sizeof *W);
    for (int i = 0; W != NULL && i < n; ++i)
        qwork_init(&W[i]);
    return W;
}

static void qwork_free(qwork *W, int n, qwork *one)
{
    for (int i = 0; W != NULL && i < n; ++i)
        qwork_release(&W[i]);
    if (W != one)
        free(W);
}

static int grow_stack(qwork *W, size_t need)
{
    if (need <= W->cap)
        return 1;
    size_t cap = 2 * W->cap;
    while (cap < need)
        cap *= 2;
    item *s = malloc(cap * sizeof *s);
    if (s == NULL) {
        W->nomem = 1;
        return 0;
    }
    memcpy(s, W->stack, W->cap * sizeof *s);
    if (W->stack != W->inline_stack)
        free(W->stack);
    W->stack = s;
    W->cap = cap;
    return 1;
}

static int defer_item(qwork *W, const item *it)
{
    if (W->ndef == W->defcap) {
        const size_t cap = W->defcap ? 2 * W->defcap : 2048; /* a near pose sets aside 600-1,000: no copy */
        item *v = realloc(W->deferred, cap * sizeof *v);
        if (v == NULL) {
            W->nomem = 1;
            return 0;
        }
        W->deferred = v;
        W->defcap = cap;
    }
    W->deferred[W->ndef++] = *it;
    return 1;
}

/* Whether item a comes before item b in the second phase: the smaller bound first, then by the
 * boxes, a total order, so that the walk is the same on every platform. */
static int item_before(const item *a, const item *b)
{
    if (a->lb2 != b->lb2)
        return a->lb2 < b->lb2;
    const int32_t ka[4] = {a->an, a->as, a->bn, a->bs}, kb[4] = {b->an, b->as, b->bn, b->bs};
    for (int i = 0; i < 4; ++i)
        if (ka[i] != kb[i])
            return ka[i] < kb[i];
    return 0;
}

/* A binary heap of n items in h, the first by item_before on top. */
static void heap_up(item *h, size_t i)
{
    const item x = h[i];
    while (i > 0 && item_before(&x, &h[(i - 1) / 2])) {
        h[i] = h[(i - 1) / 2];
        i = (i - 1) / 2;
    }
    h[i] = x;
}

static void heap_down(item *h, size_t n, size_t i)
{
    const item x = h[i];
    for (;;) {
        size_t c = 2 * i + 1;
        if (c >= n)
            break;
        if (c + 1 < n && item_before(&h[c + 1], &h[c]))
            ++c;
        if (!item_before(&h[c], &x))
            break;
        h[i] = h[c];
        i = c;
    }
    h[i] = x;
}

static int clist_push(clist *l, const contact *c)
{
    if (l->count_only) {
        ++l->n;
        return 1;
    }
    if (l->direct != NULL) {
        ttd_contacts *o = l->direct;
        if (o->count == o->capacity) {
            const size_t cap = o->capacity ? 2 * o->capacity : 1024;
            void *v = o->pairs;
            if (ttd_big_grow(&v, o->count * sizeof *o->pairs, cap * sizeof *o->pairs) != 0)
                return 0;
            o->pairs = v;
            o->capacity = cap;
        }
        o->pairs[o->count++] = *c;
        return 1;
    }
    if (l->nchunks == 0 || l->in_last == (size_t)CLIST_FIRST << (l->nchunks - 1)) {
        if (l->nchunks == CLIST_CHUNKS)
            return 0;
        contact *v = ttd_big_alloc(((size_t)CLIST_FIRST << l->nchunks) * sizeof *v);
        if (v == NULL)
            return 0;
        l->chunk[l->nchunks++] = v;
        l->in_last = 0;
    }
    l->chunk[l->nchunks - 1][l->in_last++] = *c;
    ++l->n;
    return 1;
}

/* Copies list l to dst (l->n contacts) and frees its chunks. */
static void clist_drain(clist *l, contact *dst)
{
    for (int c = 0; c < l->nchunks; ++c) {
        const size_t m = c + 1 < l->nchunks ? (size_t)CLIST_FIRST << c : l->in_last;
        if (dst != NULL)
            memcpy(dst, l->chunk[c], m * sizeof *dst);
        dst += dst != NULL ? m : 0;
        free(l->chunk[c]);
    }
    l->nchunks = 0;
    l->n = l->in_last = 0;
}

/* x -> pose x, per coordinate ((r0 x + r1 y) + r2 z) + t (the order ttd/ttd.h documents). */
static void pose_apply(const real p[12], const real x[3], real out[3])
{
    for (int i = 0; i < 3; ++i)
        out[i] = ((p[4 * i] * x[0] + p[4 * i + 1] * x[1]) + p[4 * i + 2] * x[2]) + p[4 * i + 3];
}

/* Vertex v of a as the kernel sees it: the caller's coordinates, or moved by a's pose (scenes),
 * exactly as a brute force in the world frame would. */
static void side_vertex(const qpose *P, uint32_t v, real out[3])
{
    if (P->has_a)
        pose_apply(P->pose_a, P->a.verts + 3 * (size_t)v, out);
    else
        memcpy(out, P->a.verts + 3 * (size_t)v, 3 * sizeof(real));
}

/* The node test's view of box (node n, slot j) of side X, with Y's frame mapped in by (r, t). */
static void box_query(const ttd_node *node, int j, const real r[9], const real t[3], ttd_box_query *q)
{
    real u[9], d[3];
    for (int i = 0; i < 9; ++i)
        u[i] = node->u[i][j];
    for (int i = 0; i < 3; ++i) {
        q->e[i] = node->e[i][j];
        d[i] = t[i] - node->c[i][j];
    }
    for (int i = 0; i < 3; ++i) {
        for (int k = 0; k < 3; ++k)
            q->m[3 * i + k] = (u[3 * i] * r[k] + u[3 * i + 1] * r[3 + k]) + u[3 * i + 2] * r[6 + k];
        q->v[i] = (u[3 * i] * d[0] + u[3 * i + 1] * d[1]) + u[3 * i + 2] * d[2];
    }
}

static real box_size(const ttd_node *node, int j)
{
    return node->e[0][j] + node->e[1][j] + node->e[2][j];
}

#if defined(__GNUC__)
#define WALK_INLINE inline __attribute__((always_inline))
#define WALK_NOINLINE __attribute__((noinline))
#else
#define WALK_INLINE inline
#define WALK_NOINLINE
#endif

/* Fills the cache's slot m with triangle tri of one side, moved (moved_triangle's miss). */
static WALK_NOINLINE void moved_fill(const qpose *P, qwork *W, int side_b, uint32_t tri, real *m)
{
    const uint32_t *ix = (side_b ? P->b.tris : P->a.tris) + 3 * (size_t)tri;
    for (int k = 0; k < 3; ++k) {
        if (side_b && !P->self) /* a self query's b is a as given, not moved by the identity */
            pose_apply(P->pose, P->b.verts + 3 * (size_t)ix[k], m + 3 * k);
        else
            side_vertex(P, ix[k], m + 3 * k);
    }
    W->moved_key[side_b][tri & W->moved_mask] = tri;
}

/* Triangle tri of b (side 1) moved by the pose, or of a (side 0) as side_vertex gives it, into
 * out[9], through the walk's cache of moved triangles. Inlined with the miss out of line: most
 * calls hit, and a call with the miss's saved registers was most of a hit's 45 instructions. */
static WALK_INLINE void moved_triangle(const qpose *P, qwork *W, int side_b, uint32_t tri, real out[9])
{
    const unsigned slot = tri & W->moved_mask;
    real *m = W->moved[side_b][slot];
    if (W->moved_key[side_b][slot] != tri)
        moved_fill(P, W, side_b, tri, m);
    memcpy(out, m, 9 * sizeof(real));
}

/* The moved-triangle slots a walk of this mode uses (before its pose_forget). */
static void moved_slots(qwork *W, int mode)
{
    W->moved_mask = (mode == MODE_CONTACTS ? MOVED_SLOTS : MOVED_SLOTS_SHORT) - 1;
}

/* A walk's pose may differ from the last walk's on this thread: the moved triangles and the
 * boxes' views go. */
static void pose_forget(qwork *W)
{
    for (int sd = 0; sd < 2; ++sd)
        memset(W->moved_key[sd], 0xff, ((size_t)W->moved_mask + 1) * sizeof W->moved_key[0][0]);
    memset(W->query_key, 0xff, ((size_t)W->query_mask + 1) * sizeof W->query_key[0]);
}

/* The node test's view of box (node n, slot j) of one side, with the other side's frame mapped
 * in, through the walk's cache. */
static const ttd_box_query *walk_box_query(const qpose *P, qwork *W, int side_b, int32_t n, int j)
{
    /* a self query's two sides are one mesh under the identity, (r, t) = (ri, ti) = (I, +0): a
     * box's view is the same bits from either side, so it is kept once */
    side_b = P->self ? 0 : side_b;
    const uint64_t key = ((uint64_t)n * TTD_NODE_WIDTH + (uint64_t)j) * 2 + (uint64_t)side_b; /* exact: no two boxes share it */
    const unsigned slot = (((uint32_t)key * 2654435761u) >> 24) & W->query_mask; /* Knuth's multiplier */
    ttd_box_query *q = &W->query[slot];
    if (W->query_key[slot] != key) {
        if (side_b)
            box_query(P->b.nodes + n, j, P->ri, P->ti, q);
        else
            box_query(P->a.nodes + n, j, P->r, P->t, q);
        W->query_key[slot] = key;
    }
    return q;
}

/* The vertex indices of triangle x (distinct ones) that triangle y has too: how many, and the last
 * in *v. */
static int shared_vertices(const uint32_t *x, const uint32_t *y, uint32_t *v)
{
    int n = 0;
    for (int k = 0; k < 3; ++k) {
        if ((k > 0 && x[k] == x[0]) || (k > 1 && x[k] == x[1]))
            continue;
        if (x[k] == y[0] || x[k] == y[1] || x[k] == y[2]) {
            ++n;
            *v = x[k];
        }
    }
    return n;
}

/* Whether triangle ix has a vertex other than v. */
static int has_other_vertex(const uint32_t *ix, uint32_t v)
{
    return ix[0] != v || ix[1] != v || ix[2] != v;
}

/* Triangle ix's edge opposite its vertex v, as the degenerate triangle the kernel takes: its
 * vertices other than v (by index) in their order, the last repeated: (r0, r1, r1), or (r0, r0,
 * r0) when one is left. tri holds the triangle's coordinates and gets the edge's. */
static void opposite_edge(const uint32_t *ix, uint32_t v, real tri[9])
{
    real keep[9];
    int n = 0;
    for (int k = 0; k < 3; ++k)
        if (ix[k] != v)
            memcpy(keep + 3 * n++, tri + 3 * k, 3 * sizeof(real));
    for (int k = 0; k < 3; ++k)
        memcpy(tri + 3 * k, keep + 3 * (k < n ? k : n - 1), 3 * sizeof(real));
}

/* Sends the waiting candidates through the kernel and acts on the answers. */
static void flush(const qctx *C, const qpose *P, qwork *W, walk *w)
{
    const int n = W->nb;
    if (n == 0)
        return;
    W->nb = 0;
    for (int i = 0; i < n; ++i) {
        moved_triangle(P, W, 0, W->ta[i], W->s + 9 * i);
        moved_triangle(P, W, 1, W->tb[i], W->t + 9 * i);
        if (!P->self) /* two meshes: pairs only, whose kind may be left unwritten */
            continue;
        if (W->kind[i] == ENTRY_EDGE_A)
            opposite_edge(P->a.tris + 3 * (size_t)W->ta[i], W->shared[i], W->s + 9 * i);
        else if (W->kind[i] == ENTRY_EDGE_B)
            opposite_edge(P->b.tris + 3 * (size_t)W->tb[i], W->shared[i], W->t + 9 * i);
    }
    const ttd_params prm = {0, 0, 1};
    const ttd_out out = {W->dist, w->mode == MODE_CONTACTS ? W->pts : NULL, NULL};
    /* Without a bound the kernel computes every lane in place instead of screening them by a
     * lower bound first: a lane the screen would rule out is farther than the limit either way,
     * and the others get the same bits, so only the time changes (where nearly every candidate
     * is a contact, the screen rules out almost none: docs/mesh-queries.md, issue 36's eighth
     * session). */
    C->kernel((size_t)n, W->s, W->t, &prm, w->skip_bound ? (real)INFINITY : w->limit, &out);
    w->pair_tests += (uint64_t)n;
    int kept = 0;
    ttd_contacts *o = w->out != NULL && !w->out->count_only ? w->out->direct : NULL;
    if (w->mode == MODE_CONTACTS && !P->self && o != NULL && o->capacity - o->count >= (size_t)n) {
        /* a two-mesh contact walk into a set with room for the whole batch (a scene's pair):
         * every pair is written at the set's end and kept by the count, without a branch on its
         * distance, which about half the pairs pass (a mispredicted one: docs/scene-speed.md 18);
         * the same records in the same order as clist_push's */
        contact *c = o->pairs + o->count;
        for (int i = 0; i < n; ++i) {
            const real d = W->dist[i];
            c->tri_a = W->ta[i];
            c->tri_b = W->tb[i];
            c->distance = d;
            for (int k = 0; k < 3; ++k) {
                c->p[k] = W->pts[6 * i + k];
                c->q[k] = d == 0 ? c->p[k] : W->pts[6 * i + 3 + k];
            }
            c += d <= w->limit;
        }
        kept = (int)(c - (o->pairs + o->count));
        o->count += (size_t)kept;
        if (w->bound_adapt)
            w->skip_bound = 2 * kept >= n;
        return;
    }
    for (int i = 0; i < n; ++i) {
        real d = W->dist[i];
        int at = i; /* the entry whose points are the pair's */
        if (P->self && W->kind[i] == ENTRY_EDGE_A && w->mode == MODE_CONTACTS) {
            /* a pair sharing a vertex: its two entries, the nearer (the first when as near) */
            ++i;
            if (W->dist[i] < d) {
                d = W->dist[i];
                at = i;
            }
        }
        if (w->mode == MODE_DISTANCE) {
            if (d < w->limit || (!w->found && d <= w->limit)) {
                w->found = 1;
                w->ta = W->ta[i];
                w->tb = W->tb[i];
                walk_set_limit(w, P, d);
            }
        } else if (d <= w->limit) {
            if (w->mode == MODE_COLLIDE) {
                w->hit = 1;
                w->ta = W->ta[i];
                w->tb = W->tb[i];
                return;
            }
            contact c = {.tri_a = W->ta[i], .tri_b = W->tb[i], .distance = d};
            for (int k = 0; k < 3; ++k) {
                c.p[k] = W->pts[6 * at + k];
                c.q[k] = d == 0 ? c.p[k] : W->pts[6 * at + 3 + k];
            }
            if (!clist_push(w->out, &c)) {
                W->nomem = 1;
                return;
            }
            ++kept;
        }
    }
    if (w->bound_adapt)
        w->skip_bound = 2 * kept >= n;
}

static void queue_entry(qwork *W, int kind, int32_t ta, int32_t tb, uint32_t shared)
{
    W->ta[W->nb] = (uint32_t)ta;
    W->tb[W->nb] = (uint32_t)tb;
    W->kind[W->nb] = (uint8_t)kind;
    W->shared[W->nb++] = shared;
}

/* Queues candidate pair (a's triangle ta, b's tb), sending the queue through the kernel when it
 * is full. A self query orders the pair (the smaller triangle first, as a brute force over i < j
 * computes it) and keeps it by the vertices the two share (by index): none, the pair; one, with
 * SELF_SHARED and another vertex on each triangle, two entries, each triangle's edge opposite the
 * shared vertex against the other triangle (the pair's distance away from that vertex, the
 * nearer of the two); more, nothing (an edge or the whole triangle in common). */
/* What a self query computes for its triangles ia, ib (vertex indices): SELF_NONE, nothing (an
 * edge or more in common, or one vertex without SELF_SHARED or with a triangle that has no other
 * vertex); SELF_PAIR, the two triangles; SELF_EDGES, each one's edge opposite the shared vertex
 * *v against the other. */
enum { SELF_NONE, SELF_PAIR, SELF_EDGES };

static int self_kind(unsigned self, const uint32_t *ia, const uint32_t *ib, uint32_t *v)
{
    int any = 0; /* the common case first, without branches: no vertex in common */
    for (int k = 0; k < 3; ++k)
        any |= (ia[k] == ib[0]) | (ia[k] == ib[1]) | (ia[k] == ib[2]);
    if (!any)
        return SELF_PAIR;
    if (!(self & SELF_SHARED))
        return SELF_NONE;
    const int n = shared_vertices(ia, ib, v);
    if (n == 0)
        return SELF_PAIR;
    return n == 1 && (self & SELF_SHARED) && has_other_vertex(ia, *v) && has_other_vertex(ib, *v) ? SELF_EDGES
                                                                                                  : SELF_NONE;
}

/* Queues a self query's pair ta < tb of kind SELF_PAIR or SELF_EDGES (shared vertex v); sends the
 * queue through the kernel when it is full. */
static void queue_self(const qctx *C, const qpose *P, qwork *W, walk *w, int32_t ta, int32_t tb, int kind, uint32_t v)
{
    if (kind == SELF_PAIR) {
        queue_entry(W, ENTRY_PAIR, ta, tb, 0);
    } else {
        if (W->nb + 2 > BATCH_MAX) /* the two entries in one batch */
            flush(C, P, W, w);
        queue_entry(W, ENTRY_EDGE_A, ta, tb, v);
        queue_entry(W, ENTRY_EDGE_B, ta, tb, v);
    }
    if (W->nb >= (w->mode == MODE_CONTACTS ? BATCH_MAX : BATCH_MIN))
        flush(C, P, W, w);
}

static void queue_pair(const qctx *C, const qpose *P, qwork *W, walk *w, int32_t ta, int32_t tb)
{
    if (P->self) {
        if (ta > tb) {
            const int32_t t = ta;
            ta = tb;
            tb = t;
        }
        uint32_t v = 0;
        const int kind = self_kind(P->self, P->a.tris + 3 * (size_t)ta, P->b.tris + 3 * (size_t)tb, &v);
        if (kind != SELF_NONE)
            queue_self(C, P, W, w, ta, tb, kind, v);
        return;
    }
    queue_entry(W, ENTRY_PAIR, ta, tb, 0);
    if (W->nb >= (w->mode == MODE_CONTACTS ? BATCH_MAX : BATCH_MIN))
        flush(C, P, W, w);
}

/* Item it with the opened side's box replaced by child j of node `node`, at bound lb2. */
static item child_item(const item *it, int open_b, int32_t node, int j, real lb2)
{
    item c = *it;
    if (open_b) {
        c.bn = node;
        c.bs = j;
    } else {
        c.an = node;
        c.as = j;
    }
    c.lb2 = lb2;
    return c;
}

/* Opens the larger box of item it (it is within the limit) and writes the children within the
 * limit to dst; returns how many. A pair of triangles is queued for the kernel instead.
 * In a depth-first phase the children come nearest last (deepest overlap last among
 * overlapping ones), so that the nearest is walked first, and those past the gate are set
 * aside; a leaf facing a triangle queues its pairs at once, and for the minimum and collision
 * the queue goes to the kernel as soon as it fills a vector, so that the next items meet a
 * fresh limit. In the best-first phase the children come unordered: the heap orders them. */
/* ---- self queries: a leaf against itself ---------------------------------------------------
 * A leaf's triangles are neighbours: most of its pairs share a vertex, which the rule of
 * docs/mesh-queries.md section 3b drops whatever their distance. So a leaf against itself first
 * finds, by vertex indices, which of triangle i's pairs (i, j > i) can count (self_kind), and
 * makes the node test of triangle i's box against the leaf only when one can (on the benchmark's
 * folded sheet a quarter of the rows need none: docs/mesh-queries.md section 6). */

/* Queues the pairs (ti, t[j]) of row `bits` (bit j) whose node test lanes are within the limit,
 * each ordered (the smaller index first) and of kind kind[j] (shared vertex v[j]). */
static void queue_row(const qctx *C, const qpose *P, qwork *W, walk *w, int32_t ti, const int32_t *t, unsigned bits,
                      const real *lb2, const uint8_t *kind, const uint32_t *v)
{
    for (int j = 0; j < TTD_NODE_WIDTH && !w->hit; ++j)
        if ((bits >> j & 1u) && lb2[j] <= w->limit2)
            queue_self(C, P, W, w, ti < t[j] ? ti : t[j], ti < t[j] ? t[j] : ti, kind[j], v[j]);
}

/* A self query's leaf (node c, whose children are triangles) against itself: its pairs i < j. */
static void self_leaf(const qctx *C, const qpose *P, qwork *W, walk *w, int32_t c)
{
    const ttd_node *y = P->a.nodes + c;
    int32_t t[TTD_NODE_WIDTH];
    const int k = y->count;
    for (int i = 0; i < k; ++i)
        t[i] = -1 - y->child[i];
    for (int i = 0; i + 1 < k && !w->hit; ++i) {
        uint8_t kind[TTD_NODE_WIDTH];
        uint32_t v[TTD_NODE_WIDTH];
        unsigned row = 0;
        const uint32_t *ia = P->a.tris + 3 * (size_t)t[i];
        for (int j = i + 1; j < k; ++j) {
            kind[j] = (uint8_t)self_kind(P->self, ia, P->a.tris + 3 * (size_t)t[j], &v[j]);
            row |= (unsigned)(kind[j] != SELF_NONE) << j;
        }
        if (row == 0)
            continue;
        real lb2[TTD_NODE_WIDTH], sep[TTD_NODE_WIDTH];
        C->node_test(walk_box_query(P, W, 0, c, i), y, lb2, sep);
        ++w->node_tests;
        queue_row(C, P, W, w, t[i], t, row, lb2, kind, v);
    }
}

/* Opens a self query's item of one box against itself: its children against themselves (as
 * items; a triangle against itself is no pair) and every two of its children within the limit,
 * each pair of children once, found by one node test of each child against the others. A leaf
 * (outside the cutting of a contact query into sub-walks, where pairs stay items) is self_leaf's. */
static int expand_self(const qctx *C, const qpose *P, qwork *W, walk *w, const item *it, item *dst)
{
    const int32_t c = P->a.nodes[it->an].child[it->as];
    if (c < 0)
        return 0;
    if (!w->cutting && P->a.nodes[c].child[0] < 0) {
        self_leaf(C, P, W, w, c);
        return 0;
    }
    const ttd_node *y = P->b.nodes + c;
    int n = 0;
    for (int i = 0; i < y->count; ++i) {
        if (y->child[i] >= 0)
            dst[n++] = (item){c, c, i, i, 0};
        if (i + 1 == y->count)
            break;
        real lb2[TTD_NODE_WIDTH], sep[TTD_NODE_WIDTH];
        C->node_test(walk_box_query(P, W, 0, c, i), y, lb2, sep);
        ++w->node_tests;
        for (int j = i + 1; j < y->count; ++j)
            if (lb2[j] <= w->limit2)
                dst[n++] = (item){c, c, i, j, lb2[j]};
    }
    return n;
}

/* The lanes j < count of a node test whose bound is not past lim (bit j): the same test as a
 * branch per lane, without the branch, which which lanes pass (2 of 8 on the pile) made a
 * mispredicted one (docs/scene-speed.md 18). */
static WALK_INLINE unsigned lanes_within(const real *lb2, int count, real lim)
{
    unsigned m = 0;
    for (int j = 0; j < TTD_NODE_WIDTH; ++j)
        m |= (unsigned)!(lb2[j] > lim) << j;
    return m & ((1u << count) - 1u);
}

/* The node test of an item's opening and its lanes within the limit (lanes_within's mask): a
 * scene pair's contacts (any_order) take both from node_within, which compares in the vector
 * registers (docs/scene-speed.md 20); the same bounds and the same mask. */
static WALK_INLINE unsigned walk_node_test(const qctx *C, const walk *w, const ttd_box_query *q, const ttd_node *y,
                                           real *lb2, real *sep)
{
    if (w->any_order)
        return C->node_within(q, y, w->limit2, lb2, sep) & ((1u << y->count) - 1u);
    C->node_test(q, y, lb2, sep);
    return lanes_within(lb2, y->count, w->limit2);
}

/* A leaf (node `node` of side b when open_b, else of a) facing triangle t0 of the other side, with
 * the node test's bounds lb2 of its triangles: its pairs within the gate go straight to the
 * queue (item it: the leaf's slot and the triangle's). */
/* inlined into its two callers, as the code it was cut from was (an out-of-line call per leaf
 * opening cost the collision walk more than the change saved) */
static WALK_INLINE void leaf_facing_triangle(const qctx *C, const qpose *P, qwork *W, walk *w, const item *it,
                                             int open_b, int32_t t0, int32_t node, const real *lb2, unsigned within)
{
    const ttd_node *y = (open_b ? P->b.nodes : P->a.nodes) + node;
    if (!P->self && w->mode == MODE_CONTACTS && W->nb + TTD_NODE_WIDTH <= BATCH_MAX) {
        /* a two-mesh contact walk (gate at infinity, limit fixed) with room for the whole row:
         * every lane's pair written, only its two triangles (a two-mesh flush reads no kind),
         * and kept by the count, without a loop that ends on how many lanes pass (about 2 of 8,
         * in no pattern: docs/scene-speed.md 20); the same pairs in the same order, and the
         * batch full at the same pair */
        uint32_t *fixed = open_b ? W->ta : W->tb, *var = open_b ? W->tb : W->ta;
        int32_t child[TTD_NODE_WIDTH]; /* read before the stores, which may alias it as far as C knows */
        memcpy(child, y->child, sizeof child);
        int nb = W->nb;
        for (int j = 0; j < TTD_NODE_WIDTH; ++j) {
            fixed[nb] = (uint32_t)t0;
            var[nb] = (uint32_t)(-1 - child[j]);
            nb += (int)(within >> j & 1u);
        }
        W->nb = nb;
        if (nb >= BATCH_MAX)
            flush(C, P, W, w);
        return;
    }
    for (unsigned m = within; m != 0; m &= m - 1) {
        const int j = __builtin_ctz(m);
        /* the minimum's limit falls as the queue goes through the kernel, so its lanes are
         * asked again as the lane loop asked them (the other walks' limit stays) */
        if (w->mode == MODE_DISTANCE && lb2[j] > w->limit2)
            continue;
        if (lb2[j] > w->gate2) {
            const item c = child_item(it, open_b, node, j, lb2[j]);
            defer_item(W, &c);
            continue;
        }
        const int32_t t = -1 - y->child[j];
        queue_pair(C, P, W, w, open_b ? t0 : t, open_b ? t : t0);
    }
    if (w->mode != MODE_CONTACTS && W->nb >= BATCH_LEAF)
        flush(C, P, W, w);
}

/* A leaf pair's second step, for the depth-first contact and collision walks of two meshes: an
 * item of two leaves opened the leaf of side b (open_b) or a, whose triangles within the limit
 * are the items dst[0..n) facing leaf `other` of the other side. Each opens that leaf now, in the
 * order the stack would pop them and under the walk's checks between two items, instead of going
 * through the stack: the same node tests and pairs in the same order, without an item's push,
 * pop and opening (docs/scene-speed.md 12). */
static void leaf_pair_rest(const qctx *C, const qpose *P, qwork *W, walk *w, int open_b, int32_t other,
                           const item *dst, int n)
{
    const ttd_node *y = (open_b ? P->a.nodes : P->b.nodes) + other;
    for (int k = n - 1; k >= 0 && !W->nomem && !w->hit && !(w->found && w->limit == 0); --k) {
        const item *c = &dst[k];
        if (c->lb2 > w->limit2)
            continue;
        /* c's triangle (side b when open_b) against the other side's leaf */
        real lb2[TTD_NODE_WIDTH], sep[TTD_NODE_WIDTH];
        const ttd_box_query *q = open_b ? walk_box_query(P, W, 1, c->bn, c->bs) : walk_box_query(P, W, 0, c->an, c->as);
        const unsigned within = walk_node_test(C, w, q, y, lb2, sep);
        ++w->node_tests;
        const int32_t t0 = open_b ? -1 - P->b.nodes[c->bn].child[c->bs] : -1 - P->a.nodes[c->an].child[c->as];
        leaf_facing_triangle(C, P, W, w, c, !open_b, t0, other, lb2, within);
    }
}

static int expand(const qctx *C, const qpose *P, qwork *W, walk *w, const item *it, item *dst)
{
    /* it may be dst[0] (walk_stack's popped slot): read first, field by field (docs/scene-speed.md 18) */
    const item cur = *it;
    it = &cur;
    if (P->self && it->an == it->bn && it->as == it->bs)
        return expand_self(C, P, W, w, it, dst);
    const ttd_node *na = P->a.nodes + it->an, *nb = P->b.nodes + it->bn;
    const int32_t ca = na->child[it->as], cb = nb->child[it->bs];
    if (ca < 0 && cb < 0) {
        queue_pair(C, P, W, w, -1 - ca, -1 - cb);
        return 0;
    }
    const int open_b = ca < 0 || (cb >= 0 && box_size(nb, it->bs) > box_size(na, it->as));
    real lb2[TTD_NODE_WIDTH], sep[TTD_NODE_WIDTH];
    const ttd_node *y = open_b ? P->b.nodes + cb : P->a.nodes + ca;
    const ttd_box_query *q = open_b ? walk_box_query(P, W, 0, it->an, it->as) : walk_box_query(P, W, 1, it->bn, it->bs);
    const unsigned within = walk_node_test(C, w, q, y, lb2, sep);
    ++w->node_tests;
    if (!w->cutting && y->child[0] < 0 && (open_b ? ca : cb) < 0) {
        leaf_facing_triangle(C, P, W, w, it, open_b, open_b ? -1 - ca : -1 - cb, open_b ? cb : ca, lb2, within);
        return 0;
    }
    /* walk order: nearest first, and among overlapping boxes the deepest overlap first */
    real key[TTD_NODE_WIDTH];
    int n = 0;
    /* a self query's contacts come in the walk's order whatever it is (it depends on the mesh
     * alone), and a scene's pair sorts its own: no nearest-first ordering there, and the
     * children within the limit are written without a branch per child (each is written, and
     * kept by the count: dst has room for EXPAND_MAX) */
    if (!w->ordered || (P->self && w->mode == MODE_CONTACTS) || w->any_order) {
        for (int j = 0; j < y->count; ++j) {
            dst[n] = child_item(it, open_b, open_b ? cb : ca, j, lb2[j]);
            n += (int)(within >> j & 1u);
        }
    } else for (unsigned m = within; m != 0; m &= m - 1) {
        const int j = __builtin_ctz(m);
        const item c = child_item(it, open_b, open_b ? cb : ca, j, lb2[j]);
        if (c.lb2 > w->gate2) {
            defer_item(W, &c);
            continue;
        }
        /* insertion by decreasing key: the first to walk ends last, on top of the stack */
        const real kj = lb2[j] > 0 ? lb2[j] : sep[j];
        int at = n++;
        while (at > 0 && key[at - 1] < kj) {
            dst[at] = dst[at - 1];
            key[at] = key[at - 1];
            --at;
        }
        dst[at] = c;
        key[at] = kj;
    }
    const int32_t other = open_b ? ca : cb;
    if (w->ordered && w->mode != MODE_DISTANCE && !P->self && !w->cutting && y->child[0] < 0 && other >= 0 &&
        (open_b ? P->a.nodes : P->b.nodes)[other].child[0] < 0) {
        leaf_pair_rest(C, P, W, w, open_b, other, dst, n);
        return 0;
    }
    return n;
}

/* The depth-first walk from the items on the stack, until it is empty (or a collision is found,
 * or the minimum is 0). */
static void walk_stack(const qctx *C, const qpose *P, qwork *W, walk *w, size_t top)
{
    w->ordered = 1;
    while (top > 0 && !W->nomem && !w->hit && !(w->found && w->limit == 0)) {
        /* the popped item is not copied whole: expand reads its fields, each from the store
         * that wrote it (a copy's 16-byte load spanned three stores and could not be
         * forwarded, docs/scene-speed.md 18), and its children overwrite it */
        if (W->stack[--top].lb2 > w->limit2)
            continue;
        if (!grow_stack(W, top + EXPAND_MAX))
            return;
        top += (size_t)expand(C, P, W, w, W->stack + top, W->stack + top);
    }
    flush(C, P, W, w);
}

/* Whether both boxes of item it are a triangle or a leaf (a node of triangles). */
static int item_small(const qpose *P, const item *it)
{
    const int32_t ca = P->a.nodes[it->an].child[it->as], cb = P->b.nodes[it->bn].child[it->bs];
    return (ca < 0 || P->a.nodes[ca].child[0] < 0) && (cb < 0 || P->b.nodes[cb].child[0] < 0);
}

/* The minimum's second phase: best first. The item with the smallest bound is opened next, so
 * that no item is opened whose bound exceeds the distance the walk ends with, except while
 * candidate pairs wait in the queue; the walk ends when the smallest bound left exceeds the
 * limit. The set-aside items start the heap. */
static void walk_best_first(const qctx *C, const qpose *P, qwork *W, walk *w)
{
    item *h = W->deferred;
    size_t n = W->ndef;
    for (size_t i = 1; i < n; ++i)
        heap_up(h, i);
    item kids[EXPAND_MAX];
    while (n > 0 && !W->nomem && h[0].lb2 <= w->limit2 && !(w->found && w->limit == 0)) {
        /* the top stays in place while it is opened (nothing below touches the heap in this
         * phase): its first child to enter the heap replaces it, saving a sift; as the order
         * is total, the items leave the heap in the same order either way */
        const item it = h[0];
        int replaced = 0;
        w->ordered = 0;
        const int m = expand(C, P, W, w, &it, kids);
        size_t top = 0;
        for (int j = 0; j < m; ++j) {
            if (item_small(P, &kids[j])) {
                /* nearest last: on top of the stack */
                size_t at = top++;
                while (at > 0 && W->stack[at - 1].lb2 < kids[j].lb2) {
                    W->stack[at] = W->stack[at - 1];
                    --at;
                }
                W->stack[at] = kids[j];
                continue;
            }
            if (!replaced) {
                h[0] = kids[j];
                heap_down(h, n, 0);
                replaced = 1;
                continue;
            }
            W->ndef = n;
            if (!defer_item(W, &kids[j]))
                return;
            h = W->deferred;
            heap_up(h, n++);
        }
        if (!replaced) {
            h[0] = h[--n];
            heap_down(h, n, 0);
        }
        if (top > 0)
            walk_stack(C, P, W, w, top);
    }
    W->ndef = 0;
    flush(C, P, W, w);
}

/* The minimum's first limit when the first phase found nothing (rel_tol 0 only): one greedy
 * descent from the least set-aside item, opening the larger box as expand does and following
 * the child of least key (its bound, or its overlap depth where that is 0), to a triangle facing
 * a leaf or a triangle; that row's pairs through the kernel, the least distance as the limit,
 * not as found. A limit at or above the minimum drops only items whose pairs are all farther,
 * and the items left keep their order: the first pair at the minimum in the walk's order is
 * still the one returned (docs/kernel-speed.md 7.2). */
static void greedy_limit(const qctx *C, const qpose *P, qwork *W, walk *w)
{
    if (W->ndef == 0 || W->nb != 0)
        return;
    size_t best = 0;
    for (size_t i = 1; i < W->ndef; ++i)
        if (item_before(&W->deferred[i], &W->deferred[best]))
            best = i;
    item it = W->deferred[best];
    for (;;) {
        const ttd_node *na = P->a.nodes + it.an, *nb = P->b.nodes + it.bn;
        const int32_t ca = na->child[it.as], cb = nb->child[it.bs];
        if (ca < 0 && cb < 0) {
            queue_entry(W, ENTRY_PAIR, -1 - ca, -1 - cb, 0);
            break;
        }
        const int open_b = ca < 0 || (cb >= 0 && box_size(nb, it.bs) > box_size(na, it.as));
        real lb2[TTD_NODE_WIDTH], sep[TTD_NODE_WIDTH];
        const ttd_node *y = open_b ? P->b.nodes + cb : P->a.nodes + ca;
        const ttd_box_query *q = open_b ? walk_box_query(P, W, 0, it.an, it.as) : walk_box_query(P, W, 1, it.bn, it.bs);
        C->node_test(q, y, lb2, sep);
        ++w->node_tests;
        if (y->child[0] < 0 && (open_b ? ca : cb) < 0) {
            const int32_t t0 = open_b ? -1 - ca : -1 - cb;
            for (int j = 0; j < y->count; ++j) {
                const int32_t t = -1 - y->child[j];
                queue_entry(W, ENTRY_PAIR, open_b ? t0 : t, open_b ? t : t0, 0);
            }
            break;
        }
        int jb = 0;
        real kb = lb2[0] > 0 ? lb2[0] : sep[0];
        for (int j = 1; j < y->count; ++j) {
            const real kj = lb2[j] > 0 ? lb2[j] : sep[j];
            if (kj < kb) {
                kb = kj;
                jb = j;
            }
        }
        it = child_item(&it, open_b, open_b ? cb : ca, jb, lb2[jb]);
    }
    const int n = W->nb;
    W->nb = 0;
    for (int i = 0; i < n; ++i) {
        moved_triangle(P, W, 0, W->ta[i], W->s + 9 * i);
        moved_triangle(P, W, 1, W->tb[i], W->t + 9 * i);
    }
    const ttd_params prm = {0, 0, 1};
    const ttd_out out = {W->dist, NULL, NULL};
    C->kernel((size_t)n, W->s, W->t, &prm, w->limit, &out);
    w->pair_tests += (uint64_t)n;
    real d = w->limit;
    for (int i = 0; i < n; ++i)
        d = W->dist[i] < d ? W->dist[i] : d;
    if (d < w->limit)
        walk_set_limit(w, P, d);
}

/* Drops the set-aside items past the limit before the heap is built: the best-first walk would
 * never open them (its limit only falls), and most of a near pose's are. */
static void drop_deferred(qwork *W, const walk *w)
{
    size_t m = 0;
    for (size_t i = 0; i < W->ndef; ++i)
        if (W->deferred[i].lb2 <= w->limit2)
            W->deferred[m++] = W->deferred[i];
    W->ndef = m;
}

/* The walk from item root. The minimum walks in two phases: first only boxes that overlap, as a
 * collision test would (where meshes cross, that finds a crossing pair quickly, and the
 * distance is 0; otherwise the overlapping region is where the nearest pairs are likely to be),
 * setting aside every other item within the limit; then those, best first. Both phases
 * together open no item the plain walk would have dropped. */
static void walk_run(const qctx *C, const qpose *P, qwork *W, walk *w, const item *root)
{
    if (!grow_stack(W, 64))
        return;
    W->query_mask = (w->mode == MODE_DISTANCE || w->mode == MODE_CONTACTS ? QUERY_SLOTS : QUERY_SLOTS_SHORT) - 1;
    moved_slots(W, w->mode);
    pose_forget(W);
    W->ndef = 0;
    W->stack[0] = *root;
    walk_stack(C, P, W, w, 1);
    if (w->mode != MODE_DISTANCE || W->nomem || (w->found && w->limit == 0))
        return;
    w->gate2 = (real)INFINITY;
    if (!w->found && w->rel == 1)
        greedy_limit(C, P, W, w);
    drop_deferred(W, w);
    walk_best_first(C, P, W, w);
}

/* The pose's frames and rounding margin. pose maps b into a's frame; or, with pose_a (scenes),
 * both map into the world: then the tree works in a's frame with b's pose relative to a's, R_a^T
 * R_b and R_a^T (t_b - t_a) in double, and the kernel in the world. defect covers how far from
 * a rotation the (relative) R is. */
static void qpose_make(const qctx *C, const real pose[12], const real *pose_a, double defect, qpose *P)
{
    const struct ttd_mesh *ma = C->ma, *mb = C->mb;
    P->a = (side){(const ttd_node *)ma->nodes, (const real *)ma->verts, ma->tris};
    P->b = (side){(const ttd_node *)mb->nodes, (const real *)mb->verts, mb->tris};
    memcpy(P->pose, pose, sizeof P->pose);
    P->has_a = pose_a != NULL;
    P->self = C->self;
    /* b's pose in a's frame, [r | tb] */
    double r[9], tb[3], world = 0;
    for (int i = 0; i < 3; ++i) {
        tb[i] = (double)pose[4 * i + 3];
        for (int k = 0; k < 3; ++k)
            r[3 * i + k] = (double)pose[4 * i + k];
    }
    if (pose_a != NULL) {
        memcpy(P->pose_a, pose_a, sizeof P->pose_a);
        double rr[9], tr[3], ta2 = 0;
        for (int i = 0; i < 3; ++i) {
            tr[i] = 0;
            for (int k = 0; k < 3; ++k) {
                double x = 0;
                for (int j = 0; j < 3; ++j)
                    x += (double)pose_a[4 * j + i] * r[3 * j + k];
                rr[3 * i + k] = x;
                tr[i] += (double)pose_a[4 * k + i] * (tb[k] - (double)pose_a[4 * k + 3]);
            }
            ta2 += (double)pose_a[4 * i + 3] * (double)pose_a[4 * i + 3];
        }
        memcpy(r, rr, sizeof r);
        memcpy(tb, tr, sizeof tb);
        world = sqrt(ta2); /* the kernel's coordinates are as far out as a's translation more */
    }
    /* x_a - o_a = R (x_b - o_b) + (R o_b + t - o_a), in double */
    double t[3], tn = 0;
    for (int i = 0; i < 3; ++i) {
        t[i] = tb[i] - ma->origin[i];
        for (int k = 0; k < 3; ++k)
            t[i] += r[3 * i + k] * mb->origin[k];
        tn += t[i] * t[i];
    }
    for (int i = 0; i < 3; ++i) {
        P->t[i] = (real)t[i];
        /* back: x_b - o_b = R^T (x_a - o_a) - R^T t */
        double ti = 0;
        for (int k = 0; k < 3; ++k) {
            P->r[3 * i + k] = (real)r[3 * i + k];
            P->ri[3 * i + k] = (real)r[3 * k + i];
            ti -= r[3 * k + i] * t[k];
        }
        P->ti[i] = (real)ti;
    }
    /* the bounds' magnitudes, and the kernel's: it works on the caller's coordinates, b's moved by
     * the pose, whose rounding grows with how far from the origin the meshes sit */
    double oa = 0, ob = 0, tc = 0;
    for (int i = 0; i < 3; ++i) {
        oa += ma->origin[i] * ma->origin[i];
        ob += mb->origin[i] * mb->origin[i];
        tc += (double)pose[4 * i + 3] * (double)pose[4 * i + 3];
    }
    const double S = sqrt(tn) + 2 * (ma->radius + mb->radius) + sqrt(oa) + sqrt(ob) + sqrt(tc) + world;
    P->delta = (real)((64 * (double)TTD_REAL_EPS + 4 * defect) * S);
}

/* Whether the meshes' bounding spheres are farther apart than the limit: then no pair can be
 * within it, and the walk is not needed (a far pose of a collision or contact query). */
static int spheres_apart(const qctx *C, const qpose *P, const walk *w)
{
    double t2 = 0;
    for (int i = 0; i < 3; ++i)
        t2 += (double)P->t[i] * (double)P->t[i];
    const double gap = sqrt(t2) - (C->ma->radius + C->mb->radius) - (double)P->delta;
    return gap > 0 && gap * gap > (double)w->limit2;
}

static item root_item(void)
{
    item it = {0, 0, 0, 0, 0};
    return it;
}

static void walk_init(walk *w, int mode, const qpose *P, real limit, real rel_tol)
{
    memset(w, 0, sizeof *w);
    w->mode = mode;
    w->rel = 1 + rel_tol;
    w->ta = w->tb = UINT32_MAX;
    walk_set_limit(w, P, limit);
    w->gate2 = mode == MODE_DISTANCE ? 0 : (real)INFINITY;
}

static qctx qctx_make(const ttd_engine_config *cfg, const struct ttd_mesh *a, const struct ttd_mesh *b)
{
    const TTD_ROW *row = TTD_DISPATCH_ROW(cfg->isa);
    qctx C = {a, b, row->node_test, TTD_DISPATCH_KERNEL(cfg->isa, TTD_METHOD_EXACT), cfg->threads, 0, cfg->isa,
              row->node_within};
    return C;
}

/* ---- minimum distance and collision: one walk per pose, poses over the threads ------------ */

typedef struct pose_job {
    const qctx *C;
    const real *poses;
    const real *poses_a;   /* NULL, or a's poses too (scenes) */
    const double *defects;
    int mode;
    real limit, rel_tol;
    void *out;             /* ttd_mesh_result[] or ttd_collision[] */
    qwork *work;           /* one per worker */
    atomic_int nomem;
} pose_job;

/* The full result of the minimum's pair (the kernel again, with results). */
static void distance_result(const qctx *C, const qpose *P, const walk *w, ttd_mesh_result *r)
{
    memset(r, 0, sizeof *r);
    r->node_tests = w->node_tests;
    r->pair_tests = w->pair_tests;
    if (!w->found) {
        r->distance = (real)INFINITY;
        r->tri_a = r->tri_b = UINT32_MAX;
        r->flags = TTD_MESH_ABOVE_BOUND;
        return;
    }
    real s[9], t[9];
    const uint32_t *ia = P->a.tris + 3 * (size_t)w->ta, *ib = P->b.tris + 3 * (size_t)w->tb;
    for (int k = 0; k < 3; ++k) {
        side_vertex(P, ia[k], s + 3 * k);
        pose_apply(P->pose, P->b.verts + 3 * (size_t)ib[k], t + 3 * k);
    }
    ttd_result full;
    const ttd_params prm = {0, 0, 1};
    const ttd_out out = {NULL, NULL, &full};
    C->kernel(1, s, t, &prm, (real)INFINITY, &out);
    r->distance = full.distance;
    r->tri_a = w->ta;
    r->tri_b = w->tb;
    r->feature_a = full.feature_p;
    r->feature_b = full.feature_q;
    for (int k = 0; k < 3; ++k) {
        r->p[k] = full.p[k];
        r->q[k] = full.distance == 0 ? full.p[k] : full.q[k];
    }
    r->flags = full.distance == 0 ? TTD_MESH_INTERSECTING : 0;
}

static void pose_task(void *ctx, size_t i, int worker)
{
    pose_job *J = ctx;
    qwork *W = &J->work[worker];
    if (atomic_load_explicit(&J->nomem, memory_order_relaxed))
        return;
    qpose P;
    qpose_make(J->C, J->poses + 12 * i, J->poses_a ? J->poses_a + 12 * i : NULL, J->defects[i], &P);
    walk w;
    walk_init(&w, J->mode, &P, J->limit, J->rel_tol);
    const item root = root_item();
    if (!spheres_apart(J->C, &P, &w))
        walk_run(J->C, &P, W, &w, &root);
    if (W->nomem) {
        atomic_store(&J->nomem, 1);
        return;
    }
    if (J->mode == MODE_DISTANCE) {
        distance_result(J->C, &P, &w, (ttd_mesh_result *)J->out + i);
    } else {
        ttd_collision *c = (ttd_collision *)J->out + i;
        c->hit = (uint32_t)w.hit;
        c->tri_a = w.ta;
        c->tri_b = w.tb;
        c->node_tests = w.node_tests;
        c->pair_tests = w.pair_tests;
    }
}

static ttd_status run_poses(const qctx *C, size_t k, const real *poses, const real *poses_a, const double *defects,
                            int mode, real limit, real rel_tol, void *out)
{
    const int workers = ttd_parallel_task_workers(k, C->threads);
    qwork one;
    pose_job J = {C, poses, poses_a, defects, mode, limit, rel_tol, out, qwork_new(workers, &one), 0};
    atomic_init(&J.nomem, J.work == NULL);
    if (J.work != NULL)
        ttd_parallel_tasks(k, C->threads, pose_task, &J);
    qwork_free(J.work, workers, &one);
    return atomic_load(&J.nomem) ? TTD_ERR_OUT_OF_MEMORY : TTD_OK;
}

static ttd_status query_distance(const ttd_engine_config *cfg, const struct ttd_mesh *a, const struct ttd_mesh *b,
                                 size_t k, const real *poses, const real *poses_a, const double *defects,
                                 real upper_bound, real rel_tol, ttd_mesh_result *out)
{
    const qctx C = qctx_make(cfg, a, b);
    return run_poses(&C, k, poses, poses_a, defects, MODE_DISTANCE, upper_bound, rel_tol, out);
}

static ttd_status query_collide(const ttd_engine_config *cfg, const struct ttd_mesh *a, const struct ttd_mesh *b,
                                size_t k, const real *poses, const real *poses_a, const double *defects, real margin,
                                ttd_collision *out)
{
    const qctx C = qctx_make(cfg, a, b);
    return run_poses(&C, k, poses, poses_a, defects, MODE_COLLIDE, margin, 0, out);
}

/* ---- contacts: a fixed list of sub-walks per pose ----------------------------------------- */

/* Sub-walks a pose is cut into (when the pairs within the margin allow). */
#define CONTACT_TASKS 256

typedef struct contact_pose {
    qpose P;
    item *tasks;
    size_t ntasks;
    clist *lists;     /* one per task */
} contact_pose;

/* The size of item it's boxes: a proxy for the work below it (their children and pairs). */
static real item_size(const qpose *P, const item *it)
{
    return box_size(P->a.nodes + it->an, it->as) + box_size(P->b.nodes + it->bn, it->bs);
}

/* Cuts the walk from the root into sub-walks: in rounds, opens every item at least half as large
 * as the largest (in place: its children replace it, in order), until there are CONTACT_TASKS
 * items or nothing left to open (pairs of triangles are not opened). The work sits where the
 * meshes come close, a small part of the top-level pairs: opening the largest first splits it
 * where it is, so that the sub-walks spread over the threads. Rounds keep the cut linear in
 * the list (picking one largest item at a time took a quarter of a small mesh's contact
 * query). The list depends on the meshes and the pose alone. */
static int contact_tasks(const qctx *C, qwork *W, contact_pose *cp, walk *w)
{
    const size_t cap = CONTACT_TASKS + EXPAND_MAX;
    item *list = malloc(2 * cap * sizeof *list);
    real *size = malloc(2 * cap * sizeof *size); /* -1: a pair of triangles */
    if (list == NULL || size == NULL) {
        free(list);
        free(size);
        return 0;
    }
    item *next = list + cap;
    real *nsize = size + cap;
    size_t n = 0;
    list[n] = root_item();
    size[n++] = cp->P.a.nodes[0].child[0] < 0 && cp->P.b.nodes[0].child[0] < 0 ? -1 : 0;
    while (n < CONTACT_TASKS) {
        real largest = -1;
        for (size_t i = 0; i < n; ++i)
            largest = size[i] > largest ? size[i] : largest;
        if (largest < 0)
            break;
        size_t m = 0; /* next's items; with the n - i - 1 not yet seen, the list's new length */
        for (size_t i = 0; i < n; ++i) {
            if (!(size[i] >= largest / 2 && m + (n - i) < CONTACT_TASKS)) {
                next[m] = list[i];
                nsize[m++] = size[i];
                continue;
            }
            const int k = expand(C, &cp->P, W, w, &list[i], next + m);
            for (int j = 0; j < k; ++j, ++m) {
                const item *it = &next[m];
                const int pair = cp->P.a.nodes[it->an].child[it->as] < 0 && cp->P.b.nodes[it->bn].child[it->bs] < 0;
                nsize[m] = pair ? -1 : item_size(&cp->P, it);
            }
        }
        item *ti = list;
        list = next;
        next = ti;
        real *ts = size;
        size = nsize;
        nsize = ts;
        n = m;
    }
    /* list is one of the two halves of the block; keep the block, moving the tasks to its start */
    item *block = list < next ? list : next;
    if (list != block)
        memmove(block, list, n * sizeof *list);
    free(size < nsize ? size : nsize);
    cp->tasks = block;
    cp->ntasks = n;
    cp->lists = calloc(n ? n : 1, sizeof(clist));
    return cp->lists != NULL;
}

typedef struct contact_job {
    const qctx *C;
    contact_pose *cp;      /* one per pose */
    const real *poses;
    const real *poses_a;   /* NULL, or a's poses too (scenes) */
    const double *defects;
    real margin;
    size_t pose;           /* the pose whose tasks run in parallel (one pose), or SIZE_MAX */
    qwork *work;
    ttd_contacts *direct;  /* one worker: every task appends to the caller's set, in order */
    atomic_int nomem;
    int count_only;        /* the lists count their pairs and hold none */
} contact_job;

static void contact_task_run(const contact_job *J, contact_pose *cp, size_t i, qwork *W)
{
    walk w;
    walk_init(&w, MODE_CONTACTS, &cp->P, J->margin, 0);
    w.out = &cp->lists[i];
    walk_run(J->C, &cp->P, W, &w, &cp->tasks[i]);
}

/* Prepares pose i's tasks (walks nothing else). */
static int contact_pose_prepare(contact_job *J, size_t i, qwork *W)
{
    contact_pose *cp = &J->cp[i];
    qpose_make(J->C, J->poses + 12 * i, J->poses_a ? J->poses_a + 12 * i : NULL, J->defects[i], &cp->P);
    walk w;
    walk_init(&w, MODE_CONTACTS, &cp->P, J->margin, 0);
    w.cutting = 1;
    moved_slots(W, MODE_CONTACTS);
    pose_forget(W);
    if (!contact_tasks(J->C, W, cp, &w))
        return 0;
    for (size_t t = 0; J->count_only && t < cp->ntasks; ++t)
        cp->lists[t].count_only = 1;
    if (J->direct != NULL) { /* one worker: the poses come in order */
        J->direct->pose_start[i] = J->direct->count;
        for (size_t t = 0; t < cp->ntasks; ++t)
            cp->lists[t].direct = J->direct;
    }
    return 1;
}

/* One pose per task: prepare it and run its tasks in order. */
static void contact_pose_task(void *ctx, size_t i, int worker)
{
    contact_job *J = ctx;
    qwork *W = &J->work[worker];
    if (atomic_load_explicit(&J->nomem, memory_order_relaxed))
        return;
    if (!contact_pose_prepare(J, i, W)) {
        atomic_store(&J->nomem, 1);
        return;
    }
    for (size_t t = 0; t < J->cp[i].ntasks && !W->nomem; ++t)
        contact_task_run(J, &J->cp[i], t, W);
    if (W->nomem)
        atomic_store(&J->nomem, 1);
}

/* One task of the one pose per task. */
static void contact_sub_task(void *ctx, size_t t, int worker)
{
    contact_job *J = ctx;
    qwork *W = &J->work[worker];
    if (atomic_load_explicit(&J->nomem, memory_order_relaxed))
        return;
    contact_task_run(J, &J->cp[J->pose], t, W);
    if (W->nomem)
        atomic_store(&J->nomem, 1);
}

/* Room for k + 1 pose offsets in the caller's set. */
static int contacts_offsets(ttd_contacts *out, size_t k)
{
    if (k + 1 > out->pose_capacity) {
        size_t *ps = realloc(out->pose_start, (k + 1) * sizeof *ps);
        if (ps == NULL)
            return 0;
        out->pose_start = ps;
        out->pose_capacity = k + 1;
    }
    return 1;
}

/* Moves every pose's lists, in pose and task order, into the caller's set. */
static int contacts_join(const contact_job *J, size_t k, ttd_contacts *out)
{
    size_t total = 0;
    for (size_t i = 0; i < k; ++i)
        for (size_t t = 0; t < J->cp[i].ntasks; ++t)
            total += J->cp[i].lists[t].n;
    if (total > out->capacity) { /* nothing in it is kept: a new array, on huge pages if large */
        contact *v = ttd_big_alloc(total * sizeof *v);
        if (v == NULL)
            return 0;
        free(out->pairs);
        out->pairs = v;
        out->capacity = total;
    }
    size_t at = 0;
    for (size_t i = 0; i < k; ++i) {
        out->pose_start[i] = at;
        for (size_t t = 0; t < J->cp[i].ntasks; ++t) {
            clist *l = &J->cp[i].lists[t];
            const size_t n = l->n;
            /* an empty set may have no array yet: no pointer arithmetic on NULL */
            clist_drain(l, n > 0 ? out->pairs + at : NULL);
            at += n;
        }
    }
    out->count = at;
    return 1;
}

/* The contacts of k poses into out; or, with counts (out NULL), only each pose's number of pairs
 * into counts[0 .. k): the same walks, whose lists count instead of holding the pairs, so that
 * counting millions of pairs takes no memory for them. */
static ttd_status run_contacts(const qctx *Cq, size_t k, const real *poses, const real *poses_a, const double *defects,
                               real margin, ttd_contacts *out, size_t *counts)
{
    const qctx C = *Cq;
    if (out != NULL) {
        out->count = 0;
        out->poses = 0;
        if (!contacts_offsets(out, k))
            return TTD_ERR_OUT_OF_MEMORY;
    }
    /* one pose: its tasks over the threads; several: the poses over the threads */
    const size_t ntask_guess = k == 1 ? CONTACT_TASKS : k;
    const int workers = ttd_parallel_task_workers(ntask_guess, C.threads);
    qwork one;
    contact_job J = {&C, calloc(k, sizeof(contact_pose)), poses, poses_a, defects, margin, SIZE_MAX,
                     qwork_new(workers, &one), workers == 1 && counts == NULL ? out : NULL, 0, counts != NULL};
    atomic_init(&J.nomem, J.cp == NULL || J.work == NULL);
    if (!atomic_load(&J.nomem)) {
        if (k == 1) {
            J.pose = 0;
            if (!contact_pose_prepare(&J, 0, &J.work[0]) || J.work[0].nomem)
                atomic_store(&J.nomem, 1);
            else
                ttd_parallel_tasks(J.cp[0].ntasks, C.threads, contact_sub_task, &J);
        } else {
            ttd_parallel_tasks(k, C.threads, contact_pose_task, &J);
        }
    }
    /* one worker walked the poses and their tasks in order, into the set; several: join */
    int ok = !atomic_load(&J.nomem);
    if (ok && counts != NULL) {
        for (size_t i = 0; i < k; ++i) {
            counts[i] = 0;
            for (size_t t = 0; t < J.cp[i].ntasks; ++t)
                counts[i] += J.cp[i].lists[t].n;
        }
    } else if (ok) {
        ok = J.direct != NULL || contacts_join(&J, k, out);
    }
    for (size_t i = 0; J.cp != NULL && i < k; ++i) {
        for (size_t t = 0; J.cp[i].lists != NULL && t < J.cp[i].ntasks; ++t)
            clist_drain(&J.cp[i].lists[t], NULL);
        free(J.cp[i].lists);
        free(J.cp[i].tasks);
    }
    qwork_free(J.work, workers, &one);
    free(J.cp);
    if (counts != NULL)
        return ok ? TTD_OK : TTD_ERR_OUT_OF_MEMORY;
    if (!ok) {
        out->count = 0;
        return TTD_ERR_OUT_OF_MEMORY;
    }
    out->pose_start[k] = out->count;
    out->poses = k;
    return TTD_OK;
}

static ttd_status query_contacts(const ttd_engine_config *cfg, const struct ttd_mesh *a, const struct ttd_mesh *b,
                                 size_t k, const real *poses, const real *poses_a, const double *defects, real margin,
                                 ttd_contacts *out)
{
    const qctx C = qctx_make(cfg, a, b);
    return run_contacts(&C, k, poses, poses_a, defects, margin, out, NULL);
}

static ttd_status query_contacts_count(const ttd_engine_config *cfg, const struct ttd_mesh *a, const struct ttd_mesh *b,
                                       size_t k, const real *poses, const double *defects, real margin, size_t *counts)
{
    const qctx C = qctx_make(cfg, a, b);
    return run_contacts(&C, k, poses, NULL, defects, margin, NULL, counts);
}

/* ---- self queries: one mesh against itself ------------------------------------------------ */

static const real identity_pose[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
static const double no_defect = 0;

#include "mesh/self_grid_impl.h"

static qctx self_ctx(const ttd_engine_config *cfg, const struct ttd_mesh *m, unsigned shared)
{
    qctx C = qctx_make(cfg, m, m);
    C.self = SELF_QUERY | (shared ? SELF_SHARED : 0);
    return C;
}

static ttd_status query_self_contacts(const ttd_engine_config *cfg, const struct ttd_mesh *m, real margin,
                                      unsigned shared, ttd_contacts *out)
{
    const qctx C = self_ctx(cfg, m, shared);
    const int st = self_grid_contacts(&C, margin, out, NULL);
    return st >= 0 ? (ttd_status)st : run_contacts(&C, 1, identity_pose, NULL, &no_defect, margin, out, NULL);
}

static ttd_status query_self_contacts_walk(const ttd_engine_config *cfg, const struct ttd_mesh *m, real margin,
                                           unsigned shared, ttd_contacts *out)
{
    const qctx C = self_ctx(cfg, m, shared);
    return run_contacts(&C, 1, identity_pose, NULL, &no_defect, margin, out, NULL);
}

static ttd_status query_self_contacts_count(const ttd_engine_config *cfg, const struct ttd_mesh *m, real margin,
                                            unsigned shared, size_t *count)
{
    const qctx C = self_ctx(cfg, m, shared);
    const int st = self_grid_contacts(&C, margin, NULL, count);
    return st >= 0 ? (ttd_status)st : run_contacts(&C, 1, identity_pose, NULL, &no_defect, margin, NULL, count);
}

static ttd_status query_self_collide(const ttd_engine_config *cfg, const struct ttd_mesh *m, real margin,
                                     unsigned shared, ttd_collision *out)
{
    const qctx C = self_ctx(cfg, m, shared);
    return run_poses(&C, 1, identity_pose, NULL, &no_defect, MODE_COLLIDE, margin, 0, out);
}

/* One pose's contacts walked from the root on the calling thread, straight into out, in the
 * walk's order: for a caller that sorts them (a scene sorts each body pair's contacts by
 * triangles, and spreads body pairs over the threads itself). The cut into sub-walks above is
 * what makes the order of query_contacts independent of the thread count; on the pile of 1,000
 * icospheres it cost a scene a quarter of its contact query (256 lists allocated and zeroed per
 * body pair, the walk's caches reset per sub-walk, kernel calls of 4 pairs: docs/scene-speed.md). */
/* The walk of query_contacts_walk into list l (the caller's set, or a count); 0 when out of
 * memory. */
static int walk_contacts_into(const ttd_engine_config *cfg, const struct ttd_mesh *a, const struct ttd_mesh *b,
                              const real *pose, const real *pose_a, double defect, real margin, clist *l,
                              uint64_t tests[2])
{
    const qctx C = qctx_make(cfg, a, b);
    qwork W;
    qwork_init(&W);
    qpose P;
    qpose_make(&C, pose, pose_a, defect, &P);
    walk w;
    walk_init(&w, MODE_CONTACTS, &P, margin, 0);
    w.out = l;
    w.any_order = 1; /* the same set whatever the order, which the caller sorts (or counts) */
    if (!spheres_apart(&C, &P, &w)) {
        const item root = root_item();
        walk_run(&C, &P, &W, &w, &root);
    }
    tests[0] = w.node_tests;
    tests[1] = w.pair_tests;
    qwork_release(&W);
    return !W.nomem;
}

static ttd_status query_contacts_walk(const ttd_engine_config *cfg, const struct ttd_mesh *a, const struct ttd_mesh *b,
                                      const real *pose, const real *pose_a, double defect, real margin,
                                      ttd_contacts *out, uint64_t tests[2])
{
    out->count = 0;
    out->poses = 0;
    tests[0] = tests[1] = 0;
    if (!contacts_offsets(out, 1))
        return TTD_ERR_OUT_OF_MEMORY;
    clist l;
    memset(&l, 0, sizeof l);
    l.direct = out;
    out->pose_start[0] = 0;
    if (!walk_contacts_into(cfg, a, b, pose, pose_a, defect, margin, &l, tests)) {
        out->count = 0;
        return TTD_ERR_OUT_OF_MEMORY;
    }
    out->pose_start[1] = out->count;
    out->poses = 1;
    return TTD_OK;
}

/* query_contacts_walk's number of contacts alone, into *count: the pairs are counted, not held. */
static ttd_status query_contacts_walk_count(const ttd_engine_config *cfg, const struct ttd_mesh *a,
                                            const struct ttd_mesh *b, const real *pose, const real *pose_a,
                                            double defect, real margin, size_t *count, uint64_t tests[2])
{
    clist l;
    memset(&l, 0, sizeof l);
    l.count_only = 1;
    *count = 0;
    tests[0] = tests[1] = 0;
    if (!walk_contacts_into(cfg, a, b, pose, pose_a, defect, margin, &l, tests))
        return TTD_ERR_OUT_OF_MEMORY;
    *count = l.n;
    return TTD_OK;
}

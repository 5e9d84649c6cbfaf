/* SPDX-License-Identifier: MIT */
/* The closest point of a mesh to each of many points (points/points.h), precision-generic:
 * closest_d.c and closest_f.c compile it with `real`, `ttd_point_result`, the row type and the
 * scalar reference of their precision. docs/points.md has the design, the rounding margin and the
 * measurements behind it.
 *
 * One point is one walk, depth first with the nearest child first, over the mesh's hierarchy: a
 * node is opened with one point-node test (its up to 8 child boxes in the lanes) and, when it has
 * triangle children, one kernel call that measures all of them exactly (a prepared block, the
 * lanes over the triangles). The best distance so far, plus the rounding margin delta, is the
 * limit a box must come within to be opened. Every triangle at the final distance lies in boxes
 * within the limit, so the walk meets all of them and keeps the smallest index: the brute force's
 * answer, bit for bit (the kernel's distances are the reference's). A batch goes in spatial order,
 * each walk's limit seeded by the previous point's answer (ttd_points_order, closest_one); the
 * points are dealt to the threads in fixed blocks of that order, so a point's walk depends on its
 * batch but not on which thread runs it, and its answer on neither. */

/* Points per block of the parallel loop. */
#define CLOSEST_BLOCK 64
/* Batches of at least this many points go in spatial order (the sort costs three passes over 1,024
 * counters: a few walks; so the fuzzer's batches of up to 48 points reach it too). */
#define CLOSEST_SORTED 32
/* Deepest stack a walk needs: at most 7 siblings wait per level of a tree of depth <= 16. */
#define CLOSEST_STACK 128

typedef struct closest_job {
    const struct ttd_mesh *m;
    const ttd_points_data *pd;
    const TTD_ROW *row;
    ttd_point_node_fn node; /* the float row's node test */
    const real *points;
    size_t n;
    real upper_bound;
    ttd_point_result *out;
    const size_t *order; /* the points in spatial (Morton) order, or NULL: input order */
} closest_job;

/* A node waiting to be walked, and its key (the node test's lb2 or depth) when pushed. */
typedef struct citem {
    int32_t node;
    float key;
} citem;

/* A walk's state: the best triangle so far (its distance, index, block and slot, and the
 * candidate the kernel chose there), the limit, the margin, and the squared limit a box's computed
 * squared distance (in the walk nodes' float frame) must not exceed to be opened. */
typedef struct cbest {
    real d;
    uint32_t t;
    int32_t node, blk, j;
    real par[3];
    double lim, delta, scale;
    float lim2f;
} cbest;

/* The node test's squared limit: ((lim + delta) scale)^2 rounded up to float (scale: the walk nodes'
 * scale times their axes' stretch times 1 + 8 eps_f, for the test's relative rounding), at
 * least 2^-100 (below it the float squares' underflow is not covered) and at most FLT_MAX (an
 * empty slot's +inf is never within). docs/points.md, section 3. */
static void closest_limit(cbest *B)
{
    const double x = (B->lim + B->delta) * B->scale;
    double x2 = x * x * (1 + 4 * DBL_EPSILON);
    x2 = x2 > 0x1p-100 ? x2 : 0x1p-100;
    x2 = x2 < (double)FLT_MAX ? x2 : (double)FLT_MAX;
    float r = (float)x2;
    if ((double)r < x2) { /* the next float up: r is positive, finite and below FLT_MAX here */
        uint32_t bits;
        memcpy(&bits, &r, sizeof r);
        ++bits;
        memcpy(&r, &bits, sizeof r);
    }
    B->lim2f = r;
}

/* Measures the triangles of walk node y (its block, the slots in tm) and keeps the best: the
 * smallest distance within the bound, ties to the smallest triangle. */
static void closest_measure(const closest_job *J, const real P[3], int32_t node, unsigned tm, real ub, cbest *B)
{
    const ttd_pnode *y = &J->pd->pnodes[node];
    real d[TTD_NODE_WIDTH], par[3][TTD_NODE_WIDTH];
    J->row->point_block(P, (const real *)J->pd->blocks + (size_t)y->block * TTD_PT_ROWS * TTD_PT_LANES, d, par);
    int better = 0;
    for (; tm; tm &= tm - 1) {
        const int j = __builtin_ctz(tm);
        if (!(d[j] <= B->d && d[j] <= ub))
            continue;
        const uint32_t t = (uint32_t)(-1 - y->child[j]);
        if (d[j] < B->d || t < B->t) {
            B->d = d[j];
            B->t = t;
            B->node = node;
            B->blk = y->block;
            B->j = j;
            for (int k = 0; k < 3; ++k)
                B->par[k] = par[k][j];
            better = 1;
        }
    }
    if (better) {
        B->lim = (double)B->d;
        closest_limit(B);
    }
}

/* Writes a point's result for a point with no triangle within the bound, or a NaN point. */
static void closest_none(ttd_point_result *r, real distance, uint8_t flags)
{
    r->distance = distance;
    for (int c = 0; c < 3; ++c)
        r->point[c] = r->bary[c] = (real)NAN;
    r->triangle = UINT32_MAX;
    r->feature = 0;
    r->flags = flags;
}

/* The closest point of P into r. *seed: a walk node whose triangles are measured first (the
 * previous point's winner's, in spatial order: their distances start the limit near the answer, so
 * the first descent already prunes), or -1; it gets this point's winner's node. Only the limit
 * depends on it: every triangle within the final limit is still measured, so the answer (ties to
 * the smallest index) is the same bits; the counts of tests depend on it. */
static void closest_one(const closest_job *J, const real P[3], ttd_point_result *r, int32_t *seed)
{
    const struct ttd_mesh *m = J->m;
    const ttd_points_data *pd = J->pd;
    const ttd_pnode *pn = pd->pnodes;
    if (!(isfinite(P[0]) && isfinite(P[1]) && isfinite(P[2]))) {
        memset(r, 0, sizeof *r);
        closest_none(r, (real)NAN, TTD_POINT_NONFINITE);
        return;
    }
    /* the point in the walk nodes' frame (relative to the mesh's origin, scaled, clamped to
     * [-2^60, 2^60]: every box lies within [-1, 1], so the clamp only brings the point nearer to
     * all of them), and the margin delta = 64 eps S + 16 eps_f S, S bounding every magnitude of the
     * walk (docs/points.md, section 3) */
    float pf[3];
    double s2 = 0;
    for (int c = 0; c < 3; ++c) {
        const double x = (double)P[c] - m->origin[c];
        double xs = x * pd->scale;
        xs = xs < -0x1p60 ? -0x1p60 : (xs > 0x1p60 ? 0x1p60 : xs);
        pf[c] = (float)xs;
        s2 += x * x;
    }
    const real ub = J->upper_bound;
    const double S = sqrt(s2) + m->radius;
    cbest B = {(real)INFINITY, UINT32_MAX, -1, -1, 0, {0, 0, 0}, (double)ub,
               (64 * (double)TTD_REAL_EPS + 16 * (double)FLT_EPSILON) * S, pd->scale * pd->stretch * (1 + 8 * (double)FLT_EPSILON), 0};
    closest_limit(&B);
    uint32_t node_tests = 0, tri_tests = 0;
    const int32_t seeded = *seed;
    int32_t skip = -1; /* a seed node of triangles only: measured whole, so never walked into */
    if (seeded >= 0) {
        closest_measure(J, P, seeded, pn[seeded].tmask, ub, &B);
        tri_tests += pn[seeded].ntri;
        skip = pn[seeded].ntri == pn[seeded].nslots ? seeded : -1;
    }
    citem stack[CLOSEST_STACK];
    int sp = 0;
    /* Depth first, the nearest child first (boxes that hold the point by how deep they hold it);
     * the other children within the limit wait on the stack with their bounds, and are dropped
     * when the walk comes back to them beyond the limit. */
    int32_t node = 0; /* node 0 holds the root's box (or the mesh's one triangle) */
    for (;;) {
        const ttd_pnode *y = &pn[node];
        float key[TTD_NODE_WIDTH];
        const unsigned within = J->node(pf, y, B.lim2f, key);
        ++node_tests;
        if ((within & y->tmask) && node != seeded) {
            closest_measure(J, P, node, y->tmask, ub, &B);
            tri_tests += y->ntri;
        }
        int jbest = -1;
        float best = INFINITY;
        for (unsigned nm = within & ~y->tmask; nm; nm &= nm - 1) {
            const int j = __builtin_ctz(nm);
            if (key[j] > B.lim2f || y->child[j] == skip)
                continue;
            if (key[j] < best) {
                if (jbest >= 0 && sp < CLOSEST_STACK)
                    stack[sp++] = (citem){y->child[jbest], best};
                best = key[j];
                jbest = j;
            } else if (sp < CLOSEST_STACK) {
                stack[sp++] = (citem){y->child[j], key[j]};
            }
        }
        if (jbest >= 0) {
            node = y->child[jbest];
            continue;
        }
        while (sp > 0 && stack[sp - 1].key > B.lim2f)
            --sp;
        if (sp == 0)
            break;
        node = stack[--sp].node;
    }
    r->node_tests = node_tests;
    r->triangle_tests = tri_tests;
    r->reserved = 0;
    if (B.t == UINT32_MAX) {
        closest_none(r, (real)INFINITY, TTD_POINT_ABOVE_BOUND);
        return;
    }
    *seed = B.node;
    /* the winner's point and weights from the candidate the kernel chose (the reference's code) */
    const real *f = (const real *)pd->blocks + (size_t)B.blk * TTD_PT_ROWS * TTD_PT_LANES + B.j;
    POINT_REBUILD(f, TTD_PT_LANES, (int)B.par[0], B.par[1], B.par[2], r->point, r->bary);
    r->distance = B.d;
    r->triangle = B.t;
    r->feature = (uint8_t)((r->bary[0] > 0 ? 1u : 0u) | (r->bary[1] > 0 ? 2u : 0u) | (r->bary[2] > 0 ? 4u : 0u));
    r->flags = f[TTD_PT_INN * TTD_PT_LANES] > 0 ? 0 : TTD_POINT_DEGENERATE;
}

/* Points i0 .. i1 - 1 against a mesh of a few triangles (ttd_points_data.tiny): 8 points at a
 * time, one per lane, against every triangle in index order, each point keeping the smallest
 * distance within the bound (ties to the smallest triangle): the brute force itself. */
static void closest_tiny(const closest_job *J, size_t i0, size_t i1)
{
    const struct ttd_mesh *m = J->m;
    const real *tiny = (const real *)J->pd->tiny;
    const real ub = J->upper_bound;
    for (size_t g = i0; g < i1; g += TTD_NODE_WIDTH) {
        const int cnt = (int)(i1 - g < TTD_NODE_WIDTH ? i1 - g : TTD_NODE_WIDTH);
        real P[3][TTD_NODE_WIDTH], best[TTD_NODE_WIDTH], bq[3][TTD_NODE_WIDTH], bw[3][TTD_NODE_WIDTH];
        uint32_t bt[TTD_NODE_WIDTH];
        int finite[TTD_NODE_WIDTH];
        for (int i = 0; i < TTD_NODE_WIDTH; ++i) {
            const real *p = J->points + 3 * (g + (size_t)(i < cnt ? i : 0));
            /* x - x is 0 for a finite x, NaN for an infinite or NaN one; a NaN point's lane measures
             * the origin (its result is NaN) */
            finite[i] = (p[0] - p[0] == 0) & (p[1] - p[1] == 0) & (p[2] - p[2] == 0);
            for (int c = 0; c < 3; ++c)
                P[c][i] = finite[i] ? p[c] : (real)0;
            best[i] = (real)INFINITY;
            bt[i] = UINT32_MAX;
        }
        for (uint32_t t = 0; t < (uint32_t)m->nt; ++t) {
            real d[TTD_NODE_WIDTH], q[3][TTD_NODE_WIDTH], w[3][TTD_NODE_WIDTH];
            J->row->point_lanes(tiny + (size_t)t * TTD_PT_COUNT, (const real(*)[TTD_NODE_WIDTH])P, d, q, w);
            for (int i = 0; i < cnt; ++i)
                if (d[i] < best[i] && d[i] <= ub) {
                    best[i] = d[i];
                    bt[i] = t;
                    for (int c = 0; c < 3; ++c) {
                        bq[c][i] = q[c][i];
                        bw[c][i] = w[c][i];
                    }
                }
        }
        for (int i = 0; i < cnt; ++i) {
            ttd_point_result *r = &J->out[g + (size_t)i];
            if (!finite[i]) {
                memset(r, 0, sizeof *r);
                closest_none(r, (real)NAN, TTD_POINT_NONFINITE);
                continue;
            }
            r->node_tests = 0;
            r->triangle_tests = (uint32_t)m->nt;
            r->reserved = 0;
            if (bt[i] == UINT32_MAX) {
                closest_none(r, (real)INFINITY, TTD_POINT_ABOVE_BOUND);
                continue;
            }
            const real *f = tiny + (size_t)bt[i] * TTD_PT_COUNT;
            for (int c = 0; c < 3; ++c) {
                r->point[c] = bq[c][i];
                r->bary[c] = bw[c][i];
            }
            r->distance = best[i];
            r->triangle = bt[i];
            r->feature = (uint8_t)((r->bary[0] > 0 ? 1u : 0u) | (r->bary[1] > 0 ? 2u : 0u) | (r->bary[2] > 0 ? 4u : 0u));
            r->flags = f[TTD_PT_INN] > 0 ? 0 : TTD_POINT_DEGENERATE;
        }
    }
}

static void closest_block(void *ctx, size_t b, int worker)
{
    (void)worker;
    const closest_job *J = ctx;
    const size_t i1 = (b + 1) * CLOSEST_BLOCK < J->n ? (b + 1) * CLOSEST_BLOCK : J->n;
    if (J->pd->tiny != NULL) {
        closest_tiny(J, b * CLOSEST_BLOCK, i1);
        return;
    }
    int32_t seed = -1; /* each block starts afresh: a point's answer does not depend on the threads */
    for (size_t i = b * CLOSEST_BLOCK; i < i1; ++i) {
        const size_t k = J->order != NULL ? J->order[i] : i;
        if (J->order == NULL)
            seed = -1; /* points in input order are not near each other */
        closest_one(J, J->points + 3 * k, &J->out[k], &seed);
    }
}


static ttd_status closest_run(const ttd_engine_config *cfg, const struct ttd_mesh *m, size_t n, const real *points,
                              real upper_bound, ttd_point_result *out)
{
    const ttd_points_data *pd = ttd_points_data_get(m, cfg->threads);
    if (pd == NULL)
        return TTD_ERR_OUT_OF_MEMORY;
    /* a batch large enough to share nodes goes in spatial order (a few radix passes a point) */
    size_t *order = pd->tiny == NULL && n >= CLOSEST_SORTED ? ttd_points_order(m, pd, n, points, (int)sizeof(real)) : NULL;
    closest_job J = {m, pd, TTD_DISPATCH_ROW(cfg->isa), ttd_dispatch_row_f(cfg->isa)->point_node, points, n, upper_bound, out,
                     order};
    ttd_parallel_for((n + CLOSEST_BLOCK - 1) / CLOSEST_BLOCK, cfg->threads, closest_block, &J);
    free(order);
    return TTD_OK;
}

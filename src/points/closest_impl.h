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
 * answer, bit for bit (the kernel's distances are the reference's). Points are dealt to the
 * threads in fixed blocks; a point's walk does not depend on which thread runs it. */

/* Points per block of the parallel loop. */
#define CLOSEST_BLOCK 64
/* Deepest stack a walk needs: at most 7 siblings wait per level of a tree of depth <= 16. */
#define CLOSEST_STACK 128

typedef struct closest_job {
    const struct ttd_mesh *m;
    const ttd_points_data *pd;
    const TTD_ROW *row;
    const real *points;
    size_t n;
    real upper_bound;
    ttd_point_result *out;
} closest_job;

typedef struct citem {
    int32_t node;
    real lb2;
} citem;

/* A walk's state: the best triangle so far (its distance, index, block and slot, and the
 * candidate the kernel chose there), the limit, the margin and the squared limit. */
typedef struct cbest {
    real d;
    uint32_t t;
    int32_t blk, j;
    real par[3];
    double lim, delta, lim2;
    real lim2r; /* lim2 in the query's precision, rounded up: lb2 <= lim2r iff lb2 <= lim2 */
} cbest;

/* The squared limit a box's computed squared bound must not exceed to be opened: (lim + delta)^2
 * rounded up, at least 64 REAL_MIN (below it the bounds' own underflow is not covered). */
static void closest_limit(cbest *B)
{
    const double x = (B->lim + B->delta) * (1 + 4 * DBL_EPSILON);
    const double x2 = x * x * (1 + 4 * DBL_EPSILON);
    B->lim2 = x2 > 64 * (double)TTD_REAL_MIN ? x2 : 64 * (double)TTD_REAL_MIN;
    real r = (real)B->lim2;
    if ((double)r < B->lim2)
        r = TTD_NEXTUP(r);
    B->lim2r = r;
}

/* Measures the triangles of block blk (the slots in tm of node y) and keeps the best: the
 * smallest distance within the bound, ties to the smallest triangle. */
static void closest_measure(const closest_job *J, const real P[3], const ttd_node *y, int32_t blk, unsigned tm,
                            real ub, cbest *B)
{
    real d[TTD_NODE_WIDTH], par[3][TTD_NODE_WIDTH];
    J->row->point_block(P, (const real *)J->pd->blocks + (size_t)blk * TTD_PT_ROWS * TTD_PT_LANES, d, par);
    int better = 0;
    for (; tm; tm &= tm - 1) {
        const int j = __builtin_ctz(tm);
        if (!(d[j] <= B->d && d[j] <= ub))
            continue;
        const uint32_t t = (uint32_t)(-1 - y->child[j]);
        if (d[j] < B->d || t < B->t) {
            B->d = d[j];
            B->t = t;
            B->blk = blk;
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

static void closest_one(const closest_job *J, const real P[3], ttd_point_result *r)
{
    const struct ttd_mesh *m = J->m;
    const ttd_node *nodes = m->nodes;
    const ttd_points_data *pd = J->pd;
    if (!(isfinite(P[0]) && isfinite(P[1]) && isfinite(P[2]))) {
        memset(r, 0, sizeof *r);
        r->distance = (real)NAN;
        for (int c = 0; c < 3; ++c)
            r->point[c] = r->bary[c] = (real)NAN;
        r->triangle = UINT32_MAX;
        r->flags = TTD_POINT_NONFINITE;
        return;
    }
    /* the point in the tree's frame (relative to the mesh's origin) and the margin delta =
     * 64 eps S, S bounding every magnitude of the walk (docs/points.md, section 3) */
    real pt[3];
    double s2 = 0;
    for (int c = 0; c < 3; ++c) {
        const double x = (double)P[c] - m->origin[c];
        pt[c] = (real)x;
        s2 += x * x;
    }
    const real ub = J->upper_bound;
    cbest B = {(real)INFINITY, UINT32_MAX, -1, 0, {0, 0, 0}, (double)ub,
               64 * (double)TTD_REAL_EPS * (sqrt(s2) + m->radius), 0, 0};
    closest_limit(&B);
    uint32_t node_tests = 0, tri_tests = 0;
    citem stack[CLOSEST_STACK];
    int sp = 0;
    /* node 0 holds the root's box alone: the walk starts at its child (or measures the mesh's one
     * triangle) */
    if (nodes[0].child[0] < 0) {
        closest_measure(J, P, &nodes[0], pd->block_of[0], 1u, ub, &B);
        tri_tests = 1;
    } else {
        stack[sp++] = (citem){nodes[0].child[0], 0};
    }
    while (sp > 0) {
        const citem it = stack[--sp];
        if (it.lb2 > B.lim2r)
            continue;
        const ttd_node *y = &nodes[it.node];
        real lb2[TTD_NODE_WIDTH];
        const unsigned live = pd->live_mask[it.node], tmask = pd->tri_mask[it.node];
        const unsigned within = J->row->point_node(pt, y, B.lim2r, lb2) & live;
        ++node_tests;
        if (within & tmask) {
            closest_measure(J, P, y, pd->block_of[it.node], tmask, ub, &B);
            tri_tests += (uint32_t)__builtin_popcount(tmask);
        }
        /* the node children still within the limit, the nearest pushed last (walked first) */
        int idx[TTD_NODE_WIDTH], k = 0;
        for (unsigned nm = within & ~tmask; nm; nm &= nm - 1) {
            const int j = __builtin_ctz(nm);
            if (lb2[j] > B.lim2r)
                continue;
            int at = k++;
            while (at > 0 && lb2[idx[at - 1]] < lb2[j]) {
                idx[at] = idx[at - 1];
                --at;
            }
            idx[at] = j;
        }
        for (int i = 0; i < k && sp < CLOSEST_STACK; ++i)
            stack[sp++] = (citem){y->child[idx[i]], lb2[idx[i]]};
        if (k > 0) /* the next node walked: its boxes' first lines on their way */
            for (int l = 0; l < (int)sizeof(ttd_node); l += 128)
                __builtin_prefetch((const char *)&nodes[stack[sp - 1].node] + l);
    }
    r->node_tests = node_tests;
    r->triangle_tests = tri_tests;
    r->reserved = 0;
    if (B.t == UINT32_MAX) {
        r->distance = (real)INFINITY;
        for (int c = 0; c < 3; ++c)
            r->point[c] = r->bary[c] = (real)NAN;
        r->triangle = UINT32_MAX;
        r->feature = 0;
        r->flags = TTD_POINT_ABOVE_BOUND;
        return;
    }
    /* the winner's point and weights from the candidate the kernel chose (the reference's code) */
    const real *f = (const real *)pd->blocks + (size_t)B.blk * TTD_PT_ROWS * TTD_PT_LANES + B.j;
    POINT_REBUILD(f, TTD_PT_LANES, (int)B.par[0], B.par[1], B.par[2], r->point, r->bary);
    r->distance = B.d;
    r->triangle = B.t;
    r->feature = (uint8_t)((r->bary[0] > 0 ? 1u : 0u) | (r->bary[1] > 0 ? 2u : 0u) | (r->bary[2] > 0 ? 4u : 0u));
    r->flags = f[TTD_PT_INN * TTD_PT_LANES] > 0 ? 0 : TTD_POINT_DEGENERATE;
}

static void closest_block(void *ctx, size_t b, int worker)
{
    (void)worker;
    const closest_job *J = ctx;
    const size_t i1 = (b + 1) * CLOSEST_BLOCK < J->n ? (b + 1) * CLOSEST_BLOCK : J->n;
    for (size_t i = b * CLOSEST_BLOCK; i < i1; ++i)
        closest_one(J, J->points + 3 * i, &J->out[i]);
}

static ttd_status closest_run(const ttd_engine_config *cfg, const struct ttd_mesh *m, size_t n, const real *points,
                              real upper_bound, ttd_point_result *out)
{
    const ttd_points_data *pd = ttd_points_data_get(m, cfg->threads);
    if (pd == NULL)
        return TTD_ERR_OUT_OF_MEMORY;
    closest_job J = {m, pd, TTD_DISPATCH_ROW(cfg->isa), points, n, upper_bound, out};
    ttd_parallel_for((n + CLOSEST_BLOCK - 1) / CLOSEST_BLOCK, cfg->threads, closest_block, &J);
    return TTD_OK;
}

/* SPDX-License-Identifier: MIT */
/* Self-contacts by a grid of leaves (precision-generic; included by mesh/query_impl.h, whose
 * queue and kernel calls it shares). docs/mesh-queries.md, section 3b and issue 36's notes.
 *
 * The walk of query_impl.h meets every pair of a mesh's triangles at the node where their paths
 * part; on a sheet most of its node tests show that neighbours are neighbours (5.5 a triangle,
 * about 130 ns each). Here the tree's leaves are only groups of 8 nearby triangles:
 *   1. every triangle's axis-aligned box (its vertices' minima, and their maxima raised by the
 *      limit L = margin + the walk's rounding margin) and vertex indices, 8 lanes per leaf;
 *   2. the leaves' boxes counted into a uniform grid whose cell, per axis, is at least the
 *      largest box of the leaves in cells plus L, so that two such leaves within L of each other
 *      lie in one cell or two neighbouring ones; each leaf meets itself, the leaves after it in
 *      its cell, and those of the 13 cells after its own (half of its 26 neighbours); leaves
 *      larger than 4 times the mean stay out of the cells and meet every leaf;
 *   3. two leaves whose boxes are within L screen their triangles 8 at a time (the row's
 *      self_screen: box and vertex-index comparisons); the pairs left go to the exact kernel by
 *      the walk's queue (queue_entry, queue_self), as the walk's do, so each pair's distance and
 *      points are the same bits.
 * Rounding: the screen compares exact minima with fl(max + L); where the exact gap between two
 * boxes on an axis is at most L, lo <= max + L exactly, so lo <= fl(max + L) (rounding is
 * monotone): no pair the walk would give the kernel within L is dropped, and L covers what the
 * kernel's rounding needs (the walk's delta). The set is the brute force's; its order is the
 * grid's (cells, then leaves, then triangles), fixed by the mesh. Cells are cut into a fixed
 * list of runs, each with its own list, joined in order: the thread count changes nothing.
 * Where one leaf's box is so large that the grid would put most leaves together, the caller
 * keeps the walk (self_grid_make returns 0). */

/* A self query's arrays, kept with the mesh between queries (ttd_mesh.self_scratch): a query on a
 * 100k-triangle mesh needs about 18 MB of them, and fresh memory each time cost it the clearing
 * of every page. Taken by one query at a time (an atomic exchange; a query that finds none, as
 * when two run at once, makes its own and keeps or frees it after); freed with the mesh by its
 * first member. What a query leaves in them is not read by the next, with one exception: the
 * groups' triangle ids (tri) and vertex indices (blk[g].ix), which depend on the triangles alone,
 * are written by the first query after the scratch is made (topo_filled) and read by later ones;
 * so self_fill must never write ix, and nothing may reorder blk or tri. */
typedef struct self_scratch {
    void (*free_fn)(void *);
    size_t cap_g, cap_c;       /* leaves and cells they hold */
    ttd_self_block *blk;
    int32_t (*tri)[TTD_NODE_WIDTH];
    double *sbox;
    uint32_t *order, *cell;
    double (*gbox)[6];
    double *ext;               /* per leaf: its largest side with L */
    uint32_t *start;
    /* The groups (below, self_topo_make): made by the first self query from the triangles alone,
     * which no refit changes, so kept for the mesh's life. */
    int32_t (*topo)[TTD_NODE_WIDTH]; /* group g's triangles, -1 past its count */
    size_t ntopo;              /* groups in topo */
    int topo_state;            /* 0 not made yet; 1 the groups are used; -1 the tree's leaves are */
    int topo_filled;           /* with groups: tri and blk's ix (the triangles and their vertex
                                  indices, which no refit changes) hold them already */
} self_scratch;

static void self_scratch_free(void *p)
{
    self_scratch *S = p;
    if (S == NULL)
        return;
    free(S->blk);
    free(S->tri);
    free(S->sbox);
    free(S->order);
    free(S->cell);
    free(S->gbox);
    free(S->ext);
    free(S->start);
    free(S->topo);
    free(S);
}

/* The mesh's scratch (its arrays sized by self_scratch_room), or NULL out of memory. */
static self_scratch *self_scratch_take(const struct ttd_mesh *mesh)
{
    struct ttd_mesh *m = (struct ttd_mesh *)(uintptr_t)mesh; /* a cache, not a change to the mesh */
    self_scratch *S = __atomic_exchange_n((self_scratch **)&m->self_scratch, NULL, __ATOMIC_ACQ_REL);
    if (S == NULL && (S = calloc(1, sizeof *S)) != NULL)
        S->free_fn = self_scratch_free;
    return S;
}

/* Room in S for ng groups: 1, or 0 out of memory (S freed). */
static int self_scratch_room(self_scratch *S, size_t ng)
{
    if (S->cap_g >= ng)
        return 1;
    S->topo_filled = 0;
    free(S->blk), free(S->tri), free(S->sbox), free(S->order), free(S->cell), free(S->gbox), free(S->ext);
    const size_t n = ng ? ng : 1;
    S->blk = ttd_big_alloc(n * sizeof *S->blk);
    S->tri = malloc(n * sizeof *S->tri);
    S->sbox = ttd_big_alloc(6 * (n + TTD_NODE_WIDTH) * sizeof *S->sbox);
    S->order = malloc(n * sizeof *S->order);
    S->cell = malloc(n * sizeof *S->cell);
    S->gbox = malloc(n * sizeof *S->gbox);
    S->ext = malloc(n * sizeof *S->ext);
    S->cap_g = n;
    if (!S->blk || !S->tri || !S->sbox || !S->order || !S->cell || !S->gbox || !S->ext) {
        self_scratch_free(S);
        return 0;
    }
    return 1;
}

/* Groups of up to 8 triangles that share vertices (issue 36): the tree's leaves group triangles
 * by the rank of their centroids, which on a sheet spreads a leaf over 6 to 9 quads, so that a
 * leaf's box, raised by the margin, meets about 23 others; 8 triangles grown breadth-first over
 * shared vertices are a patch about 2 x 2 quads wide, whose box meets about 8. Each group starts
 * at the first triangle not yet grouped and takes triangles that share a vertex with one already
 * in it, nearest in the breadth-first order first, in index order around each vertex, until it
 * has 8 or no ungrouped neighbour is left. Made from the triangles alone (refits keep it), so the
 * groups, like the leaves, depend on the mesh alone; any grouping gives the same pairs (only the
 * work and the records' order depend on it). Around each vertex a cursor skips the triangles
 * grouped already and at most TOPO_LOOK more are looked at per visit, so a vertex shared by many
 * triangles costs no more than its own list over the whole making. Where the groups come out
 * short (triangles with few neighbours: a soup), more than 5 in 4 of a full grouping's count,
 * the tree's leaves are kept. 1 done (S->topo_state set), 0 out of memory. */
#define TOPO_LOOK 32

static int self_topo_make(const uint32_t *tris, size_t nt, size_t nv, self_scratch *S)
{
    size_t *off = calloc(nv + 1, sizeof *off), *cur = malloc((nv ? nv : 1) * sizeof *cur);
    uint32_t *inc = malloc((nt ? 3 * nt : 1) * sizeof *inc);
    int32_t *grp = malloc((nt ? nt : 1) * sizeof *grp), *mark = malloc((nt ? nt : 1) * sizeof *mark);
    int32_t(*topo)[TTD_NODE_WIDTH] = malloc((nt ? nt : 1) * sizeof *topo); /* at most nt groups */
    int ok = off && cur && inc && grp && mark && topo;
    size_t ng = 0;
    if (ok) {
        for (size_t i = 0; i < 3 * nt; ++i) /* the triangles around each vertex, in index order */
            off[tris[i] + 1]++;
        for (size_t v = 0; v < nv; ++v)
            off[v + 1] += off[v];
        memcpy(cur, off, nv * sizeof *cur);
        for (size_t i = 0; i < 3 * nt; ++i)
            inc[cur[tris[i]]++] = (uint32_t)(i / 3);
        memcpy(cur, off, nv * sizeof *cur);
        for (size_t t = 0; t < nt; ++t)
            grp[t] = mark[t] = -1;
        for (size_t seed = 0; seed < nt; ++seed) {
            if (grp[seed] >= 0)
                continue;
            int32_t q[TTD_NODE_WIDTH]; /* the group's queue: its members, then those waiting */
            int qh = 0, qn = 1;
            q[0] = (int32_t)seed;
            mark[seed] = (int32_t)ng;
            while (qh < qn) {
                const uint32_t t = (uint32_t)q[qh++];
                grp[t] = (int32_t)ng;
                for (int k = 0; k < 3 && qn < TTD_NODE_WIDTH; ++k) {
                    const uint32_t v = tris[3 * (size_t)t + k];
                    while (cur[v] < off[v + 1] && grp[inc[cur[v]]] >= 0)
                        cur[v]++;
                    for (size_t i = cur[v], e = 0; i < off[v + 1] && e < TOPO_LOOK && qn < TTD_NODE_WIDTH; ++i, ++e) {
                        const uint32_t u = inc[i];
                        if (grp[u] < 0 && mark[u] != (int32_t)ng) {
                            mark[u] = (int32_t)ng;
                            q[qn++] = (int32_t)u;
                        }
                    }
                }
            }
            for (int k = 0; k < TTD_NODE_WIDTH; ++k)
                topo[ng][k] = k < qn ? q[k] : -1;
            ++ng;
        }
    }
    free(off), free(cur), free(inc), free(grp), free(mark);
    if (!ok) {
        free(topo);
        return 0;
    }
    const size_t full = (nt + TTD_NODE_WIDTH - 1) / TTD_NODE_WIDTH;
    if (4 * ng > 5 * full) {
        free(topo);
        S->topo_state = -1;
        return 1;
    }
    S->topo = topo;
    S->ntopo = ng;
    S->topo_state = 1;
    return 1;
}

/* Gives the scratch back to the mesh (or frees it where another query's is there already). */
static void self_scratch_give(const struct ttd_mesh *mesh, self_scratch *S)
{
    struct ttd_mesh *m = (struct ttd_mesh *)(uintptr_t)mesh;
    void *none = NULL;
    if (S != NULL && !__atomic_compare_exchange_n(&m->self_scratch, &none, (void *)S, 0, __ATOMIC_ACQ_REL, __ATOMIC_ACQUIRE))
        self_scratch_free(S);
}

/* A self query's grid. Every box is in double, for both precisions (float coordinates convert
 * exactly, and L is rounded up in double as in real). */
typedef struct self_grid {
    size_t ngroups;
    ttd_self_block *blk;       /* per leaf: its triangles' boxes and indices (lanes) */
    int32_t (*tri)[TTD_NODE_WIDTH]; /* per leaf: its triangles, -1 past its count */
    double *sbox;              /* the leaves' boxes in the grid's order, one array per bound:
                                  lo x, y, z, raised hi x, y, z, each ngroups + 8 (padding) */
    uint32_t *start;           /* ncells + 1: cell c's leaves are order[start[c] .. start[c+1]) */
    uint32_t *order;
    size_t dim[3], ncells;
    size_t nsmall;             /* leaves in cells: positions [0, nsmall) of order; the large
                                  leaves after them, each tested against every leaf */
    ttd_self_screen_fn screen; /* the row's, or NULL: the scalar loops */
    ttd_box_list_fn list;      /* the row's, or NULL: box_list_scalar */
    self_scratch *S;           /* where the arrays are */
} self_grid;

/* The scalar row's screens (core/kernels.h): the same comparisons one lane at a time. */
static unsigned self_screen_scalar(const ttd_self_block *g, const ttd_self_block *h, int same,
                                   uint16_t out[TTD_NODE_WIDTH])
{
    unsigned found = 0;
    for (int i = 0; i < TTD_NODE_WIDTH; ++i) {
        unsigned n = 0, s = 0;
        out[i] = 0;
        if (same && i == TTD_NODE_WIDTH - 1) /* no lane after it (as the rows') */
            continue;
        int row = 1; /* triangle i near h's leaf box */
        for (int c = 0; c < 3; ++c)
            row &= (h->box[c] <= g->hi[c][i]) & (g->lo[c][i] <= h->box[3 + c]);
        if (!row)
            continue;
        for (int j = same ? i + 1 : 0; j < TTD_NODE_WIDTH; ++j) {
            int near = 1, share = 0;
            for (int c = 0; c < 3; ++c) {
                near &= (h->lo[c][j] <= g->hi[c][i]) & (g->lo[c][i] <= h->hi[c][j]);
                share |= (h->ix[c][j] == g->ix[0][i]) | (h->ix[c][j] == g->ix[1][i]) | (h->ix[c][j] == g->ix[2][i]);
            }
            int diag = 1; /* the diagonal screen (pairs sharing a vertex: self_grid_leaves) */
            for (int d = 0; d < 6; ++d)
                diag &= (h->dg[d][j] <= g->dg[6 + d][i]) & (g->dg[d][i] <= h->dg[6 + d][j]);
            n |= (unsigned)(near & !share & diag) << j;
            s |= (unsigned)(near & share) << j;
        }
        out[i] = (uint16_t)(n | s << 8);
        found |= (unsigned)(n != 0) << i | (unsigned)(s != 0) << (8 + i);
    }
    return found;
}

static unsigned box_screen_scalar(const double *const lo[3], const double *const hi[3], const double q[6])
{
    unsigned n = 0;
    for (int j = 0; j < TTD_NODE_WIDTH; ++j)
        n |= (unsigned)((lo[0][j] <= q[3]) & (q[0] <= hi[0][j]) & (lo[1][j] <= q[4]) & (q[1] <= hi[1][j]) &
                        (lo[2][j] <= q[5]) & (q[2] <= hi[2][j]))
             << j;
    return n;
}

/* The scalar row's box_list (core/kernels.h): box_screen_scalar's loop over up to 64 boxes. */
static unsigned box_list_scalar(const double *b, size_t c, unsigned n, const double q[6], uint8_t at[64])
{
    unsigned k = 0;
    for (unsigned r = 0; r < n; r += TTD_NODE_WIDTH) {
        const double *const lo[3] = {b + r, b + c + r, b + 2 * c + r};
        const double *const hi[3] = {b + 3 * c + r, b + 4 * c + r, b + 5 * c + r};
        unsigned m = box_screen_scalar(lo, hi, q);
        if (n - r < TTD_NODE_WIDTH)
            m &= (1u << (n - r)) - 1;
        for (; m != 0; m &= m - 1)
            at[k++] = (uint8_t)(r + (unsigned)__builtin_ctz(m));
    }
    return k;
}

/* The diagonal screen: whether two triangles are farther apart than the limit along one of the six
 * directions x +- y, x +- z, y +- z (in self_screen, from each triangle's projections made once
 * per query by self_fill): the boxes' screen passes in-plane neighbours of a sheet whose
 * quads are split along a diagonal (five a triangle, 0.7 to 1.4 edges apart), which the exact
 * kernel would then compute in full. Along d = (e_a +- e_b) / sqrt 2 two triangles' projections
 * are at most their distance apart; so the test drops a pair only when the gap of the unscaled
 * projections exceeds R = 1.5 L >= sqrt 2 L + 0.086 L, where 0.086 L >= 0.086 delta = 5.5 eps S
 * (delta = 64 eps S, S >= every coordinate's magnitude) covers the rounding of a +- b (eps S each)
 * and of the comparison's sum. In double for both precisions. */

/* The scalar row's self_fill (core/kernels.h): a leaf's boxes and diagonal projections, a lane at a
 * time, in the row's order of operations. */
static void self_fill_scalar(const double v[9][TTD_NODE_WIDTH], double L, double R, ttd_self_block *b)
{
    double(*dg)[TTD_NODE_WIDTH] = b->dg;
    for (int j = 0; j < TTD_NODE_WIDTH; ++j) {
        for (int c = 0; c < 3; ++c) {
            const double x0 = v[c][j], x1 = v[3 + c][j], x2 = v[6 + c][j];
            double mn = x0 < x1 ? x0 : x1, mx = x1 > x0 ? x1 : x0;
            mn = x2 < mn ? x2 : mn;
            mx = x2 > mx ? x2 : mx;
            b->lo[c][j] = mn;
            b->hi[c][j] = mx + L;
        }
        for (int k = 0; k < 3; ++k) {
            const double x = v[3 * k][j], y = v[3 * k + 1][j], z = v[3 * k + 2][j];
            const double p[6] = {x + y, x - y, x + z, x - z, y + z, y - z};
            for (int d = 0; d < 6; ++d) {
                dg[d][j] = k == 0 || p[d] < dg[d][j] ? p[d] : dg[d][j];
                dg[6 + d][j] = k == 0 || p[d] > dg[6 + d][j] ? p[d] : dg[6 + d][j];
            }
        }
        for (int d = 0; d < 6; ++d)
            dg[6 + d][j] += R;
    }
}

/* The diagonal screen between lane i of leaf g and lane j of leaf h: whether they are apart. */
static int diag_apart(const self_grid *G, uint32_t g, int i, uint32_t h, int j)
{
    const double *a = &G->blk[g].dg[0][i], *b = &G->blk[h].dg[0][j]; /* direction d at [d * 8] */
    int apart = 0;
    for (int d = 0; d < 6; ++d)
        apart |= (b[d * TTD_NODE_WIDTH] > a[(6 + d) * TTD_NODE_WIDTH]) | (a[d * TTD_NODE_WIDTH] > b[(6 + d) * TTD_NODE_WIDTH]);
    return apart;
}

/* Leaf tests per leaf above which the grid is no better than the walk (one huge leaf box makes
 * cells that hold most of the mesh). */
#define SELF_GRID_WORK 256

/* Builds G for the mesh of P at limit L (double): 1 done, 0 the walk is better (or L is not
 * finite), -1 out of memory. */
static int self_grid_make(const qpose *P, const struct ttd_mesh *mesh, double L, const ttd_kernels_d *row,
                          self_grid *G)
{
    memset(G, 0, sizeof *G);
    G->screen = row != NULL ? row->self_screen : NULL;
    G->list = row != NULL ? row->box_list : NULL;
    if (!isfinite(L))
        return 0;
    const size_t nnodes = mesh->nnodes;
    self_scratch *S = G->S = self_scratch_take(mesh);
    if (S == NULL)
        return -1;
    if (S->topo_state == 0 && !self_topo_make(mesh->tris, mesh->nt, mesh->nv, S)) {
        self_scratch_free(S);
        G->S = NULL;
        return -1;
    }
    const int topo = S->topo_state > 0;
    size_t ng = topo ? S->ntopo : 0;
    for (size_t n = 0; !topo && n < nnodes; ++n) /* a group: a node's triangle children (a leaf's) */
        for (int j = 0; j < P->a.nodes[n].count; ++j)
            if (P->a.nodes[n].child[j] < 0) {
                ++ng;
                break;
            }
    G->ngroups = ng;
    if (!self_scratch_room(S, ng)) {
        G->S = NULL;
        return -1;
    }
    G->blk = S->blk;
    G->tri = S->tri;
    G->sbox = S->sbox;
    G->order = S->order;
    double(*gbox)[6] = S->gbox;
    uint32_t *cell = S->cell;
    double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL}, sum = 0;
    const ttd_self_fill_fn fill = row != NULL && row->self_fill != NULL ? row->self_fill : self_fill_scalar;
    size_t g = 0;
    /* the groups' triangles and vertex indices are the mesh's: written by its first query only */
    const int fixed = topo && S->topo_filled;
    for (size_t n = 0; n < (topo ? ng : nnodes); ++n) { /* group n, or node n's triangles */
        const ttd_node *y = topo ? NULL : P->a.nodes + n;
        int k = 0;
        ttd_self_block *b = &G->blk[g];
        if (g + 4 < ng) { /* the block written 4 groups on: its lines' loads for the stores started */
            const char *x = (const char *)&G->blk[g + 4];
#pragma GCC unroll 24
            for (size_t o = 0; o < sizeof *b; o += 64)
                __builtin_prefetch(x + o, 1);
            __builtin_prefetch(x + sizeof *b - 1, 1);
        }
        double v[9][TTD_NODE_WIDTH]; /* the leaf's vertices, lanes (vertex k, coordinate c at 3 k + c) */
        for (int j = 0; j < (topo ? TTD_NODE_WIDTH : y->count); ++j) {
            if (topo ? S->topo[n][j] < 0 : y->child[j] >= 0)
                continue;
            const uint32_t t = topo ? (uint32_t)S->topo[n][j] : (uint32_t)(-1 - y->child[j]);
            const uint32_t *ix = P->a.tris + 3 * (size_t)t;
            for (int q = 0; q < 3; ++q) {
                const real *x = P->a.verts + 3 * (size_t)ix[q];
                v[3 * q][k] = (double)x[0], v[3 * q + 1][k] = (double)x[1], v[3 * q + 2][k] = (double)x[2];
            }
            if (!fixed) {
                G->tri[g][k] = (int32_t)t;
                for (int q = 0; q < 3; ++q)
                    b->ix[q][k] = (double)ix[q], b->iv[q][k] = ix[q];
            }
            ++k;
        }
        if (k == 0)
            continue;
        const int live = k;
        for (; k < TTD_NODE_WIDTH; ++k) /* empty lanes: any finite numbers, replaced below */
            for (int q = 0; q < 9; ++q)
                v[q][k] = 0;
        fill((const double(*)[TTD_NODE_WIDTH])v, L, 1.5 * L, b);
        for (k = live; k < TTD_NODE_WIDTH; ++k) { /* empty lanes: never near */
            G->tri[g][k] = -1;
            for (int d = 0; d < 12; ++d)
                b->dg[d][k] = 0;
            for (int c = 0; c < 3; ++c) {
                b->lo[c][k] = HUGE_VAL;
                b->hi[c][k] = -HUGE_VAL;
                b->ix[c][k] = -1;
                b->iv[c][k] = UINT32_MAX;
            }
        }
        double *gb = gbox[g]; /* the leaf's box: its lanes' (the empty ones' are +-inf) */
        for (int c = 0; c < 3; ++c) {
            double mn = b->lo[c][0], mx = b->hi[c][0];
            for (int j = 1; j < TTD_NODE_WIDTH; ++j) {
                mn = b->lo[c][j] < mn ? b->lo[c][j] : mn;
                mx = b->hi[c][j] > mx ? b->hi[c][j] : mx;
            }
            gb[c] = mn, gb[3 + c] = mx;
        }
        memcpy(b->box, gb, sizeof b->box);
        double e = 0; /* the leaf's extent with L: its largest side */
        for (int c = 0; c < 3; ++c) {
            e = gb[3 + c] - gb[c] > e ? gb[3 + c] - gb[c] : e;
            lo[c] = gb[c] < lo[c] ? gb[c] : lo[c];
            hi[c] = gb[c] > hi[c] ? gb[c] : hi[c];
        }
        S->ext[g] = e;
        sum += e;
        ++g;
    }
    S->topo_filled = topo;
    /* Leaves up to 4 times the mean extent go into cells as wide as the largest of them; two of
     * them within L on axis c have low corners at most that apart, and a cell a little wider
     * keeps their cells' indices within 1 despite the rounding of (lo - lo_min) / h. The larger
     * leaves (a few, where a refitted tree has stretched ones) are each tested against all. */
    const double cut = 4 * sum / (double)(ng ? ng : 1);
    double hc[3] = {0, 0, 0}; /* per axis: the largest side of the leaves in cells */
    size_t nbig = 0;
    for (size_t i = 0; i < ng; ++i) {
        if (S->ext[i] > cut) {
            ++nbig;
            continue;
        }
        for (int c = 0; c < 3; ++c)
            hc[c] = gbox[i][3 + c] - gbox[i][c] > hc[c] ? gbox[i][3 + c] - gbox[i][c] : hc[c];
    }
    G->nsmall = ng - nbig;
    double h[3];
    G->ncells = ttd_grid_cells(hc, lo, hi, ng, h, G->dim);
    if (G->ncells == 0)
        return 0;
    if (S->cap_c < G->ncells + 2) {
        free(S->start);
        S->start = malloc((G->ncells + 2) * sizeof *S->start);
        S->cap_c = S->start ? G->ncells + 2 : 0;
        if (S->start == NULL)
            return -1;
    }
    G->start = S->start;
    memset(G->start, 0, (G->ncells + 2) * sizeof *G->start);
    for (size_t i = 0; i < ng; ++i) {
        if (S->ext[i] > cut)
            continue;
        size_t at = 0;
        for (int c = 2; c >= 0; --c) {
            size_t q = (size_t)floor((gbox[i][c] - lo[c]) / h[c]);
            q = q < G->dim[c] ? q : G->dim[c] - 1;
            at = at * G->dim[c] + q;
        }
        cell[i] = (uint32_t)at;
        G->start[at + 2]++;
    }
    for (size_t c = 0; c < G->ncells; ++c)
        G->start[c + 2] += G->start[c + 1];
    for (size_t i = 0, big = G->nsmall; i < ng; ++i) /* start[c + 1] runs through cell c, then is its end */
        G->order[S->ext[i] > cut ? big++ : G->start[cell[i] + 1]++] = (uint32_t)i;
    const size_t stride = ng + TTD_NODE_WIDTH;
    for (size_t p = 0; p < stride; ++p)
        for (int c = 0; c < 6; ++c)
            G->sbox[c * stride + p] = p < ng ? gbox[G->order[p]][c] : c < 3 ? (double)INFINITY : -(double)INFINITY;
    /* the work: each leaf's tests against its cell and the 13 after it, estimated by the cells'
     * counts; past SELF_GRID_WORK a leaf, the walk */
    double work = 0;
    for (size_t z = 0; z < G->dim[2]; ++z)
        for (size_t y = 0; y < G->dim[1]; ++y)
            for (size_t x = 0; x < G->dim[0]; ++x) {
                const size_t c = (z * G->dim[1] + y) * G->dim[0] + x;
                const double nc = (double)(G->start[c + 1] - G->start[c]);
                if (nc == 0)
                    continue;
                double around = 0;
                for (int dz = 0; dz <= 1; ++dz)
                    for (int dy = dz ? -1 : 0; dy <= 1; ++dy)
                        for (int dx = dz || dy ? -1 : 1; dx <= 1; ++dx) {
                            if (x + (size_t)dx >= G->dim[0] || y + (size_t)dy >= G->dim[1] || z + (size_t)dz >= G->dim[2])
                                continue; /* (size_t)-1 wraps past the end too */
                            const size_t d = ((z + (size_t)dz) * G->dim[1] + (y + (size_t)dy)) * G->dim[0] + x + (size_t)dx;
                            around += (double)(G->start[d + 1] - G->start[d]);
                        }
                work += nc * (around + (nc + 1) / 2);
            }
    work += (double)nbig * (double)ng / TTD_NODE_WIDTH; /* the large leaves' row calls */
    return work <= SELF_GRID_WORK * (double)ng + 1024 ? 1 : 0;
}

/* Leaves g and h (g <= h; their boxes near): their triangle pairs near by the screen (for g == h,
 * i < j), queued. */
static void self_grid_leaves(const qctx *C, const qpose *P, qwork *W, walk *w, const self_grid *G, uint32_t g,
                             uint32_t h)
{
    uint16_t near[TTD_NODE_WIDTH];
    const unsigned keep = P->self & SELF_SHARED ? 0xFFFFu : 0xFFu;
    unsigned rows = G->screen ? G->screen(&G->blk[g], &G->blk[h], g == h, near)
                              : self_screen_scalar(&G->blk[g], &G->blk[h], g == h, near);
    rows &= keep; /* the rows with a pair kept (on a sheet most near rows have only pairs sharing a
                     vertex, which a query without SELF_SHARED drops) */
    rows = (rows | rows >> 8) & 0xFFu;
    for (; rows != 0 && !w->hit; rows &= rows - 1) {
        const int i = __builtin_ctz(rows);
        const int32_t ti = G->tri[g][i];
        for (unsigned m = near[i] & keep; m != 0; m &= m - 1) {
            const int bit = __builtin_ctz(m), j = bit & 7;
            const int32_t tj = G->tri[h][j], ta = ti < tj ? ti : tj, tb = ti < tj ? tj : ti;
            if (bit < 8) { /* a pair sharing no vertex, screened: queue_self's first case, inline */
                queue_entry(W, ENTRY_PAIR, ta, tb, 0);
                if (W->nb >= BATCH_MAX) /* the grid's walks are MODE_CONTACTS */
                    flush(C, P, W, w);
                continue;
            }
            uint32_t v = 0;
            const int kind = self_kind(P->self, P->a.tris + 3 * (size_t)ta, P->a.tris + 3 * (size_t)tb, &v);
            if (kind != SELF_NONE && !diag_apart(G, g, i, h, j)) /* the screen did bits 0-7's */
                queue_self(C, P, W, w, ta, tb, kind, v);
        }
    }
}

/* A leaf's block (22 cache lines) is read from memory or the last-level cache by its first
 * screen: its loads are started as soon as the leaf is known (docs/mesh-queries.md, issue 36's
 * eighth session). */
static inline void self_block_prefetch(const ttd_self_block *b)
{
    const char *x = (const char *)b;
#pragma GCC unroll 24
    for (size_t k = 0; k < sizeof *b; k += 64)
        __builtin_prefetch(x + k);
    __builtin_prefetch(x + sizeof *b - 1);
}

#define SELF_NEAR_HITS 32

/* Leaf g against the *nh leaves of hit, in their order; empties hit. */
static inline __attribute__((always_inline)) void self_grid_hits(const qctx *C, const qpose *P, qwork *W, walk *w,
                                                                 const self_grid *G, uint32_t g, const uint32_t *hit, int *nh)
{
    for (int k = 0; k < *nh; ++k) /* the leaf pair as (smaller, larger) so that g == h is the only self case */
        self_grid_leaves(C, P, W, w, G, g < hit[k] ? g : hit[k], g < hit[k] ? hit[k] : g);
    *nh = 0;
}

/* Leaf g (at grid position p) against n leaves whose boxes are near its own, 64 a row call (box_list): their
 * boxes in the 6 arrays at b, c apart (lo x, y, z, raised hi x, y, z; readable 8 past n), their
 * leaves in id. A cell's run of the grid (b = sbox + q0, c its stride, id = order + q0) and the
 * gathered list of its 13 neighbouring cells take this one loop. */
static inline __attribute__((always_inline)) void self_grid_near(const qctx *C, const qpose *P, qwork *W, walk *w, const self_grid *G, uint32_t p,
                           const double *b, size_t c, const uint32_t *id, size_t n)
{
    const size_t stride = G->ngroups + TTD_NODE_WIDTH;
    const double *s = G->sbox;
    const double q[6] = {s[p], s[stride + p], s[2 * stride + p], s[3 * stride + p], s[4 * stride + p], s[5 * stride + p]};
    const uint32_t g = G->order[p];
    uint32_t hit[SELF_NEAR_HITS]; /* the leaves found, their blocks' loads started */
    int nh = 0;
    for (size_t r = 0; r < n; r += 64) { /* 64 boxes a row call (box_list) */
        uint8_t at[64];
        const unsigned cn = n - r < 64 ? (unsigned)(n - r) : 64;
        const unsigned k = G->list ? G->list(b + r, c, cn, q, at) : box_list_scalar(b + r, c, cn, q, at);
        for (unsigned e = 0; e < k; ++e) {
            hit[nh] = id[r + at[e]];
            self_block_prefetch(&G->blk[hit[nh]]);
            if (++nh == SELF_NEAR_HITS)
                self_grid_hits(C, P, W, w, G, g, hit, &nh);
        }
    }
    self_grid_hits(C, P, W, w, G, g, hit, &nh);
}

/* Leaf at grid position p against the leaves at positions [q0, q1). */
static void self_grid_range(const qctx *C, const qpose *P, qwork *W, walk *w, const self_grid *G, uint32_t p,
                            uint32_t q0, uint32_t q1)
{
    self_grid_near(C, P, W, w, G, p, G->sbox + q0, G->ngroups + TTD_NODE_WIDTH, G->order + q0, q1 - q0);
}

/* Units [u0, u1) into w's list: unit u < ncells is cell u, whose leaves meet their neighbours; a
 * unit past them is a large leaf (position nsmall + u - ncells), which meets every leaf in a cell
 * and the large leaves from itself on. A cell's leaves meet the rest of their cell, then the
 * leaves of the 13 cells after it, gathered once a cell into one list in the cells' order (so the
 * pairs come in the order of a run at a time, with fewer and fuller row calls). */
static void self_grid_cells(const qctx *C, const qpose *P, qwork *W, walk *w, const self_grid *G, size_t u0, size_t u1)
{
    const size_t X = G->dim[0], Y = G->dim[1], Z = G->dim[2], stride = G->ngroups + TTD_NODE_WIDTH;
    double *nb = NULL; /* the gathered boxes: 6 arrays of cap (lo x, y, z, raised hi x, y, z) */
    uint32_t *id = NULL; /* their leaves */
    size_t cap = 0;
    for (size_t c = u0; c < u1 && c < G->ncells && !W->nomem && !w->hit; ++c) {
        if (G->start[c] == G->start[c + 1])
            continue;
        const size_t x = c % X, y = c / X % Y, z = c / (X * Y);
        size_t d[13], nd = 0, n = 0;
        for (int dz = 0; dz <= 1; ++dz)
            for (int dy = dz ? -1 : 0; dy <= 1; ++dy)
                for (int dx = dz || dy ? -1 : 1; dx <= 1; ++dx) {
                    if (x + (size_t)dx >= X || y + (size_t)dy >= Y || z + (size_t)dz >= Z)
                        continue;
                    d[nd] = ((z + (size_t)dz) * Y + (y + (size_t)dy)) * X + x + (size_t)dx;
                    n += G->start[d[nd] + 1] - G->start[d[nd]];
                    ++nd;
                }
        if (n + TTD_NODE_WIDTH > cap) {
            free(nb), free(id);
            cap = 2 * (n + TTD_NODE_WIDTH);
            nb = malloc(6 * cap * sizeof *nb);
            id = malloc(cap * sizeof *id);
            if (nb == NULL || id == NULL) {
                W->nomem = 1;
                break;
            }
        }
        size_t k = 0;
        for (size_t e = 0; e < nd; ++e)
            for (uint32_t r = G->start[d[e]]; r < G->start[d[e] + 1]; ++r, ++k) {
                for (int b = 0; b < 6; ++b)
                    nb[(size_t)b * cap + k] = G->sbox[(size_t)b * stride + r];
                id[k] = G->order[r];
            }
        for (; k < n + TTD_NODE_WIDTH; ++k) /* padding: never near */
            for (int b = 0; b < 6; ++b)
                nb[(size_t)b * cap + k] = b < 3 ? (double)INFINITY : -(double)INFINITY;
        for (uint32_t p = G->start[c]; p < G->start[c + 1] && !W->nomem && !w->hit; ++p) {
            if (p + 1 < G->start[c + 1]) /* the next leaf's own block, read by all its screens */
                self_block_prefetch(&G->blk[G->order[p + 1]]);
            self_grid_range(C, P, W, w, G, p, p, G->start[c + 1]); /* itself, then the rest of its cell */
            self_grid_near(C, P, W, w, G, p, nb, cap, id, n);
        }
    }
    free(nb);
    free(id);
    for (size_t u = u1 > G->ncells ? (u0 > G->ncells ? u0 : G->ncells) : u1; u < u1 && !W->nomem && !w->hit; ++u) {
        const uint32_t p = (uint32_t)(G->nsmall + (u - G->ncells));
        self_grid_range(C, P, W, w, G, p, 0, (uint32_t)G->nsmall);
        self_grid_range(C, P, W, w, G, p, p, (uint32_t)G->ngroups);
    }
    flush(C, P, W, w);
}

/* Runs of cells, each one task with its own list (joined in order). */
#define SELF_GRID_TASKS 64

typedef struct self_grid_job {
    const qctx *C;
    const qpose *P;
    const self_grid *G;
    real margin;
    size_t cut[SELF_GRID_TASKS + 1]; /* task t: units [cut[t], cut[t + 1]) (self_grid_cells) */
    clist *lists;
    qwork *work;
    atomic_int nomem;
} self_grid_job;

static void self_grid_task(void *ctx, size_t t, int worker)
{
    self_grid_job *J = ctx;
    qwork *W = &J->work[worker];
    if (atomic_load_explicit(&J->nomem, memory_order_relaxed))
        return;
    W->moved_mask = MOVED_SLOTS_SHORT - 1; /* the grid's cells meet few triangles each: not measured with more */
    pose_forget(W);
    walk w;
    walk_init(&w, MODE_CONTACTS, J->P, J->margin, 0);
    w.bound_adapt = 1;
    w.out = &J->lists[t];
    self_grid_cells(J->C, J->P, W, &w, J->G, J->cut[t], J->cut[t + 1]);
    if (W->nomem)
        atomic_store(&J->nomem, 1);
}

/* Self-contacts (out) or their count (count) by the grid: TTD_OK, TTD_ERR_OUT_OF_MEMORY, or -1
 * when the walk should answer instead (nothing written). */
static int self_grid_contacts(const qctx *C, real margin, ttd_contacts *out, size_t *count)
{
    qpose P;
    qpose_make(C, identity_pose, NULL, no_defect, &P);
    self_grid G;
    /* L: the walk's limit with its rounding margin, rounded up in double */
    const double L = ((double)margin + (double)P.delta) * (1 + 0x1p-50);
    const int made = self_grid_make(&P, C->ma, L, ttd_dispatch_row_d(C->isa), &G);
    if (made <= 0) {
        self_scratch_give(C->ma, G.S);
        return made == 0 ? -1 : TTD_ERR_OUT_OF_MEMORY;
    }
    self_grid_job J = {C, &P, &G, margin, {0}, NULL, NULL, 0};
    /* runs of about equal numbers of leaves, cut at cells */
    size_t nt = 0;
    for (size_t t = 1; t <= SELF_GRID_TASKS; ++t) {
        const size_t want = G.ngroups * t / SELF_GRID_TASKS;
        const size_t units = G.ncells + (G.ngroups - G.nsmall);
        size_t c = J.cut[nt]; /* the leaves before unit c: start[c], or nsmall + (c - ncells) */
        while (c < units && (c < G.ncells ? G.start[c] : G.nsmall + (c - G.ncells)) < want)
            ++c;
        if (t == SELF_GRID_TASKS)
            c = units;
        if (c > J.cut[nt])
            J.cut[++nt] = c;
    }
    const int workers = ttd_parallel_task_workers(nt, C->threads);
    qwork one;
    J.work = qwork_new(workers, &one);
    J.lists = calloc(nt ? nt : 1, sizeof *J.lists);
    atomic_init(&J.nomem, J.work == NULL || J.lists == NULL);
    if (out != NULL) {
        out->count = 0;
        out->poses = 0;
        if (!contacts_offsets(out, 1))
            atomic_store(&J.nomem, 1);
    }
    if (!atomic_load(&J.nomem)) {
        for (size_t t = 0; t < nt; ++t) {
            J.lists[t].count_only = out == NULL;
            J.lists[t].direct = workers == 1 && out != NULL ? out : NULL;
        }
        if (out != NULL)
            out->pose_start[0] = 0;
        ttd_parallel_tasks(nt, C->threads, self_grid_task, &J);
    }
    int ok = !atomic_load(&J.nomem);
    size_t total = 0;
    for (size_t t = 0; ok && t < nt; ++t)
        total += J.lists[t].n;
    if (ok && count != NULL) {
        *count = total;
    } else if (ok && workers > 1) { /* join the lists in task order */
        if (total > out->capacity) {
            contact *v = ttd_big_alloc(total * sizeof *v);
            if (v == NULL) {
                ok = 0;
            } else {
                free(out->pairs);
                out->pairs = v;
                out->capacity = total;
            }
        }
        size_t at = 0;
        for (size_t t = 0; ok && t < nt; ++t) {
            const size_t n = J.lists[t].n;
            clist_drain(&J.lists[t], n > 0 ? out->pairs + at : NULL);
            at += n;
        }
        out->count = at;
    }
    for (size_t t = 0; J.lists != NULL && t < nt; ++t)
        clist_drain(&J.lists[t], NULL);
    free(J.lists);
    qwork_free(J.work, workers, &one);
    self_scratch_give(C->ma, G.S);
    if (!ok) {
        if (out != NULL)
            out->count = 0;
        return TTD_ERR_OUT_OF_MEMORY;
    }
    if (out != NULL) {
        out->pose_start[1] = out->count;
        out->poses = 1;
    }
    return TTD_OK;
}

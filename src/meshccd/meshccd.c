/* SPDX-License-Identifier: MIT */
/* Continuous collision of deforming meshes (meshccd.h; docs/ccd.md, section 10).
 *
 * 1. Boxes: each vertex's swept box (its two ends), widened by delta; each triangle's, the join
 *    of its vertices'. All exact (min and max), the widening rounded outward (sweep_tree.h).
 * 2. Broad phase: a hierarchy over b's widened triangle boxes (over the mesh's own, self); each
 *    leaf of a's tree, by its triangles' unwidened boxes, walks it; in a self query a uniform grid
 *    of groups of 8 triangles grown over shared vertices (grid_make), or where that does poorly the
 *    tree walked against itself (pairs of nodes): each unordered pair of triangles once. A triangle
 *    pair whose boxes do not overlap is more than delta apart along an axis at every t, and so is
 *    every pair of their primitives. Self: a triangle pair that shares no vertex is first tried
 *    whole by the concave-gap proof that precedes each primitive search (apart_cheaply, here
 *    tri_pair_apart over the six points; 8 pairs at a time in the ISA row's lanes where it has
 *    them, the same bits): proved, none of its 15 sub-queries can come within delta, and the pair
 *    ends there (most pairs of a sheet do).
 * 3. Primitive pairs, each once: a vertex-face or edge-edge pair belongs to several triangle
 *    pairs (a vertex to every triangle around it, an edge to two); it is queried only from its
 *    owner, the smallest triangle pair (by index) that holds it and that the rule keeps. The
 *    owner's boxes hold the primitives' boxes, so whenever the primitives' boxes overlap, the
 *    owner is a candidate of step 2: nothing is lost, nothing repeated, and no sort is needed.
 * 4. Narrow phase: the primitive query of src/ccd/ (ttd_ccd_query) over all of [0, 1], its answer
 *    a function of the pair's numbers alone; each worker keeps the hits at or before its earliest
 *    + TTD_CCD_DEFAULT_T_TOL; at the end the earliest of all, the hits within the tolerance of it,
 *    sorted. So the result does not depend on the threads or on the order of the walk. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The leaves' box tests in SSE2 registers where the compiler has them (every x86-64);
 * MESHCCD_SCALAR_LEAVES keeps the plain loop (a test builds it so, against the same brute force). */
#if defined(__SSE2__) && !defined(MESHCCD_SCALAR_LEAVES)
#define MESHCCD_SSE2_LEAVES 1
#include <emmintrin.h>
#endif

#include "ccd/ccd.h"
#include "core/grid_cells.h"
#include "core/kernels.h"
#include "engine/dispatch.h"
#include "engine/parallel.h"
#include "meshccd/meshccd.h"
#include "meshccd/sweep_tree.h"

/* The self query's broad phase: -1 the grid of groups where it does better than the tree (the
 * library's), 1 the grid wherever it can be made, 0 the tree always (tests build both). */
#ifndef MESHCCD_GRID
#define MESHCCD_GRID -1
#endif

enum { MCCD_BLOCK_LEAVES = 16, MCCD_STACK = 128 };
_Static_assert(SWEEP_LEAF_SELF == TTD_NODE_WIDTH, "a self leaf's boxes are one leaf_screen call");

/* Called after each primitive search with its query and answer: nothing in the library;
 * bench/mesh_ccd_searches.c, which compiles this file into itself, records and times them. */
#ifndef MESHCCD_SEARCHED
#define MESHCCD_SEARCHED(kind, x0, x1, prm, r) ((void)0)
#endif

/* Per-triangle slot flags. */
#define FIRST_V(k) (1u << (k))        /* slot k's vertex index does not appear in an earlier slot */
#define FIRST_E(k) (1u << (3 + (k)))  /* edge k (slot k to k + 1) is not an earlier slot's edge */
#define OWN_V(k) (1u << (6 + (k)))    /* and the triangle is the smallest that holds that vertex */
#define OWN_E(k) (1u << (9 + (k)))    /* and the smallest that holds that edge */

/* What one side's primitives need. */
typedef struct side_data {
    const meshccd_side *s;
    sweep_box *vbox, *vwide;   /* per vertex: swept box, and widened by delta (vbox at delta 0) */
    sweep_box *tbox, *twide;   /* per triangle (twide is tbox at delta 0: widening by 0 is exact) */
    double *vmag;              /* per vertex: its largest coordinate magnitude at t = 0 and t = 1 */
    uint32_t *vt_start;        /* nv + 1: vertex v's triangles are vt_list[vt_start[v] .. vt_start[v+1]) */
    uint32_t *vt_list;         /* ascending (a triangle twice where it repeats the vertex) */
    uint16_t *flags;           /* per triangle; NULL where made per pair (tri_flags) */
} side_data;

static void side_free(side_data *d)
{
    if (d->vwide != d->vbox)
        free(d->vwide);
    if (d->twide != d->tbox)
        free(d->twide);
    free(d->vbox);
    free(d->tbox);
    free(d->vmag);
    free(d->vt_start);
    free(d->vt_list);
    free(d->flags);
    memset(d, 0, sizeof *d);
}

static int tri_has(const uint32_t *t, uint32_t v)
{
    return t[0] == v || t[1] == v || t[2] == v;
}

/* Whether triangle t has an edge between p and q: both among its vertices, and p twice when
 * p == q (a zero-length edge of a triangle that repeats a vertex). */
static int tri_has_edge(const uint32_t *t, uint32_t p, uint32_t q)
{
    if (p != q)
        return tri_has(t, p) && tri_has(t, q);
    return (t[0] == p) + (t[1] == p) + (t[2] == p) >= 2;
}

/* Triangle t's slot flags (FIRST_V .. OWN_E), from the vertex-triangle lists. */
static unsigned tri_flags(const side_data *d, size_t t)
{
    const uint32_t *tr = d->s->tris + 3 * t;
    unsigned f = 0;
    for (int k = 0; k < 3; ++k) {
        int first = 1;
        for (int j = 0; j < k; ++j)
            first &= tr[j] != tr[k];
        if (first) {
            f |= FIRST_V(k);
            if (d->vt_list[d->vt_start[tr[k]]] == t)
                f |= OWN_V(k);
        }
        const uint32_t p = tr[k], q = tr[(k + 1) % 3];
        first = 1;
        for (int j = 0; j < k; ++j) {
            const uint32_t r = tr[j], w = tr[(j + 1) % 3];
            first &= !((r == p && w == q) || (r == q && w == p));
        }
        if (first) {
            f |= FIRST_E(k);
            int own = 1;
            for (uint32_t m = d->vt_start[p]; m < d->vt_start[p + 1] && d->vt_list[m] < t; ++m)
                own &= !tri_has_edge(d->s->tris + 3 * (size_t)d->vt_list[m], p, q);
            if (own)
                f |= OWN_E(k);
        }
    }
    return f;
}

static int side_make(const meshccd_side *s, double delta, int want_flags, side_data *d)
{
    memset(d, 0, sizeof *d);
    d->s = s;
    d->vbox = malloc(s->nv * sizeof *d->vbox);
    d->vwide = delta == 0 ? d->vbox : malloc(s->nv * sizeof *d->vwide);
    d->tbox = malloc(s->nt * sizeof *d->tbox);
    d->twide = delta == 0 ? d->tbox : malloc(s->nt * sizeof *d->twide);
    d->vmag = malloc(s->nv * sizeof *d->vmag);
    d->vt_start = calloc(s->nv + 1, sizeof *d->vt_start);
    d->vt_list = malloc(3 * s->nt * sizeof *d->vt_list);
    d->flags = want_flags ? malloc(s->nt * sizeof *d->flags) : NULL;
    if (!d->vbox || !d->vwide || !d->tbox || !d->twide || !d->vmag || !d->vt_start || !d->vt_list ||
        (want_flags && !d->flags)) {
        side_free(d);
        return -1;
    }
    for (size_t v = 0; v < s->nv; ++v) {
        sweep_point_box(s->x0 + 3 * v, s->x1 + 3 * v, &d->vbox[v]);
        double m = 0;
        for (int k = 0; k < 3; ++k) {
            m = fabs(d->vbox[v].lo[k]) > m ? fabs(d->vbox[v].lo[k]) : m;
            m = fabs(d->vbox[v].hi[k]) > m ? fabs(d->vbox[v].hi[k]) : m;
        }
        d->vmag[v] = m;
        if (delta != 0) {
            d->vwide[v] = d->vbox[v];
            sweep_box_widen(&d->vwide[v], delta);
        }
    }
    const uint32_t *T = s->tris;
    for (size_t t = 0; t < s->nt; ++t) {
        d->tbox[t] = d->vbox[T[3 * t]];
        for (int k = 1; k < 3; ++k)
            sweep_box_join(&d->tbox[t], &d->vbox[T[3 * t + k]]);
        if (delta != 0) {
            d->twide[t] = d->vwide[T[3 * t]];
            for (int k = 1; k < 3; ++k)
                sweep_box_join(&d->twide[t], &d->vwide[T[3 * t + k]]);
        }
    }
    /* vertex -> triangles, ascending */
    for (size_t i = 0; i < 3 * s->nt; ++i)
        ++d->vt_start[T[i] + 1];
    for (size_t v = 0; v < s->nv; ++v)
        d->vt_start[v + 1] += d->vt_start[v];
    uint32_t *fill = malloc(s->nv * sizeof *fill);
    if (fill == NULL) {
        side_free(d);
        return -1;
    }
    memcpy(fill, d->vt_start, s->nv * sizeof *fill);
    for (size_t i = 0; i < 3 * s->nt; ++i)
        d->vt_list[fill[T[i]]++] = (uint32_t)(i / 3);
    free(fill);
    /* slot flags: made here where most triangle pairs take the per-primitive path (two meshes,
     * self with the shared-vertex pairs); else per pair when it needs them (tri_flags), since the
     * whole-pair proof leaves few pairs to that path (docs/ccd-speed.md, change 8) */
    if (d->flags != NULL)
        for (size_t t = 0; t < s->nt; ++t)
            d->flags[t] = (uint16_t)tri_flags(d, t);
    return 0;
}

/* The query's shared state. */
typedef struct job {
    side_data *a, *b; /* b == a for a self query */
    int self;
    unsigned shared;  /* self: TTD_SELF_SHARED_VERTEX keeps triangle pairs that share one vertex */
    sweep_tree tree;  /* over b's widened triangle boxes */
    sweep_tree qtree; /* two meshes: over a's unwidened boxes, whose leaves group the walks */
    uint32_t *leaves; /* the leaves of the query side's tree (qtree, or tree in a self query) */
    size_t nleaves;
    ttd_ccd_params params;
    struct worker *workers;
    int nworkers;
    struct node_pair *tasks; /* self: the walk's starting pairs, shared out among the workers */
    size_t ntasks;
    double *pb[6], *pw[6]; /* self: the triangles' boxes (lo x, y, z, hi x, y, z), and widened, as
                            * columns in the tree's order (pw is pb at delta 0), read in turn at the
                            * leaves; SWEEP_LEAF_SELF entries of padding after the last */
    uint32_t *ptri;          /* self: the triangles' vertex indices in the columns' order */
    const uint32_t *porder;  /* self: the columns' triangles (the tree's order, or the groups') */
    /* self, by the grid (grid_make): ng groups of up to SWEEP_LEAF_SELF triangles, group g's at
     * columns 8 g .. 8 g + gn[g]; their widened boxes' joins gbox; the small groups in cells
     * (cell c's: gorder[gstart[c] .. gstart[c + 1]), nsmall in all), the large ones after them */
    int grid;
    size_t ng, nsmall, ncells, gdim[3];
    uint8_t *gn;
    sweep_box *gbox;
    uint32_t *gtri, *gstart, *gorder;
    ttd_tri_apart_at_fn apart; /* self: the whole-pair proof in lanes (the row's), or NULL: scalar */
    ttd_leaf_screen_fn lscreen; /* self: a pair of leaves' box tests on the row, or NULL: leaf_mask */
} job;

/* Two nodes of the tree, a == b or a's range of the order before b's. */
typedef struct node_pair {
    uint32_t a, b;
} node_pair;

typedef struct worker {
    ttd_mesh_ccd_pair *hits;
    size_t n, cap;
    double best;      /* the earliest toi this worker has seen */
    uint64_t tri_pairs, queries, searches;
    struct node_pair *stack; /* the self walk's pairs of nodes still to visit */
    size_t stack_cap;
    int oom;
    /* self, with J->apart: disjoint triangle pairs waiting for the proof in lanes, by their six
     * vertex indices (core/kernels.h, tri_apart_at: the proof reads the points itself); lanes
     * past nq hold an earlier pair's indices, or 0 (the workers are made zeroed), valid vertices */
    int nq;
    uint32_t qv[6 * TTD_NODE_WIDTH];
    uint32_t qa[TTD_NODE_WIDTH], qb[TTD_NODE_WIDTH];
    const uint32_t *qta[TTD_NODE_WIDTH], *qtb[TTD_NODE_WIDTH];
} worker;


/* Keeps a hit when it is at or before the worker's earliest + the tolerance; the list is thinned
 * to that window before it grows. */
static void keep_hit(worker *w, const ttd_mesh_ccd_pair *h)
{
    if (h->toi > w->best + TTD_CCD_DEFAULT_T_TOL)
        return;
    if (h->toi < w->best)
        w->best = h->toi;
    if (w->n == w->cap) {
        size_t m = 0;
        const double lim = w->best + TTD_CCD_DEFAULT_T_TOL;
        for (size_t i = 0; i < w->n; ++i)
            if (w->hits[i].toi <= lim)
                w->hits[m++] = w->hits[i];
        w->n = m;
        if (w->n >= w->cap / 2) {
            const size_t cap = w->cap ? 2 * w->cap : 64;
            ttd_mesh_ccd_pair *p = realloc(w->hits, cap * sizeof *p);
            if (p == NULL) {
                w->oom = 1;
                return;
            }
            w->hits = p;
            w->cap = cap;
        }
    }
    w->hits[w->n++] = *h;
}

/* A cheap proof that a primitive pair stays more than delta apart over the whole step: for a
 * fixed direction n, the gap g(t) = min over the first set of n.x(t) - max over the second (or
 * the other way round) is concave in t (each n.x(t) is linear), so g > delta |n| at t = 0 and
 * t = 1 proves it for every t between (docs/ccd.md, section 3, whose argument this is). Any n
 * gives a valid bound, so n's own rounding does not matter. The dot products of n with input
 * points err by at most 3.01 u sum |n_k x_k| <= 3.01 u |n|_1 S each (S the largest coordinate),
 * a gap by twice that plus its own rounding: 8 u |n|_1 S + 2 u |g| covers it with the rounding of
 * the bound itself, and 2^-1000 products that underflow. */
static int gap_proves(const double n[3], int na, int np, const double *const *x0, const double *const *x1, double S,
                      double delta)
{
    const double u = 0x1p-53;
    const double n1 = fabs(n[0]) + fabs(n[1]) + fabs(n[2]);
    /* |n.x| <= n1 S: below 2^1000 no dot product overflows; above it one could be inf - inf =
     * NaN, which the minima below pass over, so a point would drop out of its set unseen */
    if (!(n1 > 0) || !isfinite(n1) || !(n1 * S < 0x1p1000))
        return 0;
    /* (at delta 0: 0, or NaN, which proves nothing, where |n|^2 overflows, as delta |n| would give) */
    const double nn = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
    const double need = delta != 0 ? delta * sqrt(nn) * (1 + 0x1p-40) : 0 * nn;
    const double base = 8 * u * n1 * S + 0x1p-1000;
    int ok_pos = 1, ok_neg = 1; /* first set above the second along n, or below */
    for (int t = 0; t < 2; ++t) {
        const double *const *y = t ? x1 : x0;
        double amin = HUGE_VAL, amax = -HUGE_VAL, bmin = HUGE_VAL, bmax = -HUGE_VAL;
        for (int i = 0; i < np; ++i) {
            const double d = n[0] * y[i][0] + n[1] * y[i][1] + n[2] * y[i][2];
            if (i < na) {
                amin = d < amin ? d : amin;
                amax = d > amax ? d : amax;
            } else {
                bmin = d < bmin ? d : bmin;
                bmax = d > bmax ? d : bmax;
            }
        }
        const double gp = amin - bmax, gn = bmin - amax;
        ok_pos &= gp - (base + 2 * u * fabs(gp)) > need;
        ok_neg &= gn - (base + 2 * u * fabs(gn)) > need;
        if (!ok_pos && !ok_neg)
            return 0;
    }
    return 1;
}

static void cross3(const double a[3], const double b[3], double r[3])
{
    r[0] = a[1] * b[2] - a[2] * b[1];
    r[1] = a[2] * b[0] - a[0] * b[2];
    r[2] = a[0] * b[1] - a[1] * b[0];
}

/* e x (w x e): w's part perpendicular to e (e times |e|^2). */
static void perp3(const double e[3], const double w[3], double r[3])
{
    double c[3];
    cross3(w, e, c);
    cross3(e, c, r);
}

/* Directions tried, from the positions at t = 0 and then at t = 1: the face's normal
 * (vertex-face) or the edges' cross product (edge-edge), and the directions within the face's
 * plane that separate a vertex beyond one of its edges (each edge's perpendicular towards the
 * vertex), or an edge beside the other (each edge's perpendicular towards the other's first
 * point): neighbours in one flat layer of a sheet, coplanar, are separated by the second kind. */
static int apart_cheaply(int na, const double x0[12], const double x1[12], double delta)
{
    double S = 0;
    for (int i = 0; i < 12; ++i) {
        const double m = fabs(x0[i]) > fabs(x1[i]) ? fabs(x0[i]) : fabs(x1[i]);
        S = m > S ? m : S;
    }
    const double *p0[4], *p1[4];
    for (int i = 0; i < 4; ++i)
        p0[i] = x0 + 3 * i, p1[i] = x1 + 3 * i;
    for (int end = 0; end < 2; ++end) {
        const double *x = end ? x1 : x0;
        double e1[3], e2[3], n[3];
        for (int k = 0; k < 3; ++k) {
            /* vertex-face: the face's two edges from its first vertex; edge-edge: the two edges */
            e1[k] = na == 1 ? x[6 + k] - x[3 + k] : x[3 + k] - x[k];
            e2[k] = na == 1 ? x[9 + k] - x[3 + k] : x[9 + k] - x[6 + k];
        }
        cross3(e1, e2, n);
        if (gap_proves(n, na, 4, p0, p1, S, delta))
            return 1;
        if (na == 1) {
            for (int j = 0; j < 3; ++j) {
                const double *f = x + 3 + 3 * j, *g = x + 3 + 3 * ((j + 1) % 3);
                double e[3], w[3], m[3];
                for (int k = 0; k < 3; ++k)
                    e[k] = g[k] - f[k], w[k] = x[k] - f[k];
                perp3(e, w, m);
                if (gap_proves(m, na, 4, p0, p1, S, delta))
                    return 1;
            }
        } else {
            double w[3], m[3];
            for (int k = 0; k < 3; ++k)
                w[k] = x[6 + k] - x[k];
            perp3(e1, w, m);
            if (gap_proves(m, na, 4, p0, p1, S, delta))
                return 1;
            for (int k = 0; k < 3; ++k)
                w[k] = -w[k];
            perp3(e2, w, m);
            if (gap_proves(m, na, 4, p0, p1, S, delta))
                return 1;
        }
    }
    return 0;
}

/* The same proof for a whole triangle pair (points x[0 .. 3) one triangle, x[3 .. 6) the other, at
 * t = 0 and t = 1; S the largest coordinate magnitude among them): a direction along which the
 * two triangles stay more than delta apart at both ends holds every primitive pair of theirs
 * apart over the step (each primitive's points are among its triangle's), so none of their 15
 * sub-queries can come within delta. The directions, from the positions at t = 0 and then at
 * t = 1: the perpendicular of each triangle's edges within its own plane (neighbours in one flat
 * piece, the most common pair of a sheet: two disjoint triangles in a plane have an edge whose
 * line separates them), then each triangle's normal (layers one above another). */
static int tri_pair_apart(const double *const x0[6], const double *const x1[6], double S, double delta)
{
    for (int end = 0; end < 2; ++end) {
        const double *const *x = end ? x1 : x0;
        /* The edge most likely to separate first: the one facing the other triangle, opposite
         * the vertex that lies furthest back along d, the difference of the two vertex sums
         * (the centroids' times 3). Only the order of the directions changes, not which are
         * tried, so what is proved is the same; on the folding sheet the first direction tried
         * proves most pairs (docs/ccd-speed.md). */
        double d[3];
        for (int k = 0; k < 3; ++k)
            d[k] = (x[3][k] + x[4][k] + x[5][k]) - (x[0][k] + x[1][k] + x[2][k]);
        double e[2][3][3]; /* e[s][j]: edge j of triangle s, from its vertex j to j + 1 */
        for (int sd = 0; sd < 2; ++sd) {
            for (int j = 0; j < 3; ++j)
                for (int k = 0; k < 3; ++k)
                    e[sd][j][k] = x[3 * sd + (j + 1) % 3][k] - x[3 * sd + j][k];
            /* the vertex furthest back: least along d for the first triangle, most for the second */
            const double sg = sd ? -1.0 : 1.0;
            int back = 0;
            double best = HUGE_VAL;
            for (int i = 0; i < 3; ++i) {
                const double *v = x[3 * sd + i];
                const double a = sg * (v[0] * d[0] + v[1] * d[1] + v[2] * d[2]);
                if (a < best) {
                    best = a;
                    back = i;
                }
            }
            for (int jj = 0; jj < 3; ++jj) {
                /* edge back + 1 (the one opposite vertex back), then back, then back + 2: on the
                 * folding sheet the third proves more pairs than the second (docs/ccd-speed.md) */
                const int j = (back + 1 + 2 * jj) % 3;
                double m[3];
                /* within the plane: the edge's perpendicular towards the triangle's third vertex */
                perp3(e[sd][j], e[sd][(j + 2) % 3], m);
                if (gap_proves(m, 3, 6, x0, x1, S, delta))
                    return 1;
            }
        }
        for (int sd = 0; sd < 2; ++sd) {
            double n[3];
            cross3(e[sd][0], e[sd][1], n);
            if (gap_proves(n, 3, 6, x0, x1, S, delta))
                return 1;
        }
    }
    return 0;
}

int meshccd_tri_apart(const double *const x0[6], const double *const x1[6], double S, double delta)
{
    return tri_pair_apart(x0, x1, S, delta);
}

/* Runs one primitive query: points pa[0 .. na) of side P, pb[0 .. 4 - na) of side Q. */
static void query(const job *J, worker *w, uint32_t kind, const side_data *P, const uint32_t *pa, int na,
                  const side_data *Q, const uint32_t *pb, const uint32_t ida[2], const uint32_t idb[2])
{
    double x0[12], x1[12];
    for (int i = 0; i < 4; ++i) {
        const side_data *S = i < na ? P : Q;
        const uint32_t v = i < na ? pa[i] : pb[i - na];
        memcpy(x0 + 3 * i, S->s->x0 + 3 * (size_t)v, 3 * sizeof(double));
        memcpy(x1 + 3 * i, S->s->x1 + 3 * (size_t)v, 3 * sizeof(double));
    }
    /* Searched up to the worker's earliest + the tolerance only: a pair that comes later cannot
     * be reported (the final earliest is no later), and one that comes sooner gets the answer
     * of a full search (ccd.h, t_stop), so the result does not depend on the order of the walk. */
    ++w->queries;
    if (apart_cheaply(na, x0, x1, J->params.delta))
        return;
    ++w->searches;
    ttd_ccd_params prm = J->params;
    prm.t_stop = w->best + TTD_CCD_DEFAULT_T_TOL;
    ttd_ccd_result r;
    ttd_ccd_query(na == 1 ? TTD_CCD_VF : TTD_CCD_EE, x0, x1, &prm, &r);
    MESHCCD_SEARCHED(na == 1 ? TTD_CCD_VF : TTD_CCD_EE, x0, x1, &prm, &r);
    if (!r.hit)
        return;
    ttd_mesh_ccd_pair h;
    h.toi = r.toi;
    h.gap = r.gap;
    h.kind = kind;
    h.flags = r.flags & TTD_CCD_BUDGET;
    h.a[0] = ida[0];
    h.a[1] = ida[1];
    h.b[0] = idb[0];
    h.b[1] = idb[1];
    keep_hit(w, &h);
}

static void edge_of(const uint32_t *tr, int k, uint32_t e[2])
{
    const uint32_t p = tr[k], q = tr[(k + 1) % 3];
    e[0] = p < q ? p : q;
    e[1] = p < q ? q : p;
}

/* The join of the edge's two vertex boxes (written field by field: a struct copy became a slow
 * rep movs here). */
static void edge_box(const sweep_box *vb, const uint32_t e[2], sweep_box *out)
{
    const sweep_box *p = &vb[e[0]], *q = &vb[e[1]];
    for (int k = 0; k < 3; ++k) {
        out->lo[k] = p->lo[k] < q->lo[k] ? p->lo[k] : q->lo[k];
        out->hi[k] = p->hi[k] > q->hi[k] ? p->hi[k] : q->hi[k];
    }
}

/* ---- two meshes ---- */

static void pair_two(const job *J, worker *w, uint32_t ta, uint32_t tb)
{
    const side_data *A = J->a, *B = J->b;
    const uint32_t *TA = A->s->tris + 3 * (size_t)ta, *TB = B->s->tris + 3 * (size_t)tb;
    const unsigned fa = A->flags[ta], fb = B->flags[tb];
    const uint32_t none = UINT32_MAX;
    ++w->tri_pairs;
    for (int k = 0; k < 3; ++k)
        if ((fa & OWN_V(k)) && sweep_overlap(&A->vbox[TA[k]], &B->twide[tb])) {
            const uint32_t ida[2] = {TA[k], none}, idb[2] = {tb, none};
            query(J, w, TTD_MESH_CCD_VF, A, &TA[k], 1, B, TB, ida, idb);
        }
    for (int k = 0; k < 3; ++k)
        if ((fb & OWN_V(k)) && sweep_overlap(&A->tbox[ta], &B->vwide[TB[k]])) {
            const uint32_t ida[2] = {ta, none}, idb[2] = {TB[k], none};
            query(J, w, TTD_MESH_CCD_FV, B, &TB[k], 1, A, TA, ida, idb);
        }
    for (int i = 0; i < 3; ++i) {
        if (!(fa & OWN_E(i)))
            continue;
        uint32_t ea[2];
        sweep_box boxa;
        edge_of(TA, i, ea);
        edge_box(A->vbox, ea, &boxa);
        for (int j = 0; j < 3; ++j) {
            if (!(fb & OWN_E(j)))
                continue;
            uint32_t eb[2];
            sweep_box boxb;
            edge_of(TB, j, eb);
            edge_box(B->vwide, eb, &boxb);
            if (sweep_overlap(&boxa, &boxb))
                query(J, w, TTD_MESH_CCD_EE, A, ea, 2, B, eb, ea, eb);
        }
    }
}

/* ---- one mesh ---- */

/* Distinct vertices (by index) that triangles t and u share. */
static int shared_count(const uint32_t *t, const uint32_t *u)
{
    int c = 0;
    for (int k = 0; k < 3; ++k) {
        int first = 1;
        for (int j = 0; j < k; ++j)
            first &= t[j] != t[k];
        c += first && tri_has(u, t[k]);
    }
    return c;
}

/* Whether triangles a and b (their vertex indices) have an index in common: nine comparisons. */
static inline int common_index(const uint32_t *a, const uint32_t *b)
{
    return (a[0] == b[0]) | (a[0] == b[1]) | (a[0] == b[2]) | (a[1] == b[0]) | (a[1] == b[1]) | (a[1] == b[2]) |
           (a[2] == b[0]) | (a[2] == b[1]) | (a[2] == b[2]);
}

/* Whether the self rule keeps the pair of triangles a and b (their vertex indices; not the same
 * triangle; any: whether they have an index in common): 0 no, 1 yes and they share no vertex, 2
 * yes and they share one (the shared-vertex rule). */
static inline int eligible_tris(const job *J, const uint32_t *a, const uint32_t *b, int any)
{
    if (!any)
        return 1;
    if (!J->shared)
        return 0; /* an index in common is a vertex in common: shared_count would be 1 or more */
    const int c = shared_count(a, b);
    return c == 0 ? 1 : c == 1 ? 2 : 0;
}

/* Whether the self rule keeps the triangle pair (t, u). */
static int eligible(const job *J, uint32_t t, uint32_t u)
{
    if (t == u)
        return 0;
    const uint32_t *T = J->a->s->tris;
    const uint32_t *a = T + 3 * (size_t)t, *b = T + 3 * (size_t)u;
    return eligible_tris(J, a, b, common_index(a, b));
}

/* Whether tv owns vertex v (not in f) against triangle f: no smaller triangle around v is one
 * the rule pairs with f (tv itself is; the list is ascending). */
static int owns_vf(const job *J, uint32_t v, uint32_t f, uint32_t tv)
{
    const side_data *A = J->a;
    for (uint32_t m = A->vt_start[v]; m < A->vt_start[v + 1] && A->vt_list[m] < tv; ++m)
        if (eligible(J, A->vt_list[m], f))
            return 0;
    return 1;
}

/* Whether the triangle pair me = (min, max) owns two edges that share no vertex: no triangle pair
 * (t around e, u around g) that the rule keeps is smaller, as (min, max) = min * 2^32 + max. */
static int owns_ee(const job *J, const uint32_t e[2], const uint32_t g[2], uint64_t me)
{
    const side_data *A = J->a;
    const uint32_t *T = A->s->tris;
    for (uint32_t m = A->vt_start[e[0]]; m < A->vt_start[e[0] + 1]; ++m) {
        const uint32_t t = A->vt_list[m];
        if (!tri_has_edge(T + 3 * (size_t)t, e[0], e[1]))
            continue;
        for (uint32_t n = A->vt_start[g[0]]; n < A->vt_start[g[0] + 1]; ++n) {
            const uint32_t u = A->vt_list[n];
            const uint64_t key = t < u ? ((uint64_t)t << 32 | u) : ((uint64_t)u << 32 | t);
            if (key >= me)
                continue;
            if (tri_has_edge(T + 3 * (size_t)u, g[0], g[1]) && eligible(J, t, u))
                return 0;
        }
    }
    return 1;
}

/* Triangle pair ta < tb, kept by the rule, not proved apart whole: its primitive pairs that it
 * owns. TA, TB its vertex indices (the caller's copies in the tree's order, at hand: one random
 * read less per pair). */
static void pair_prims(const job *J, worker *w, uint32_t ta, uint32_t tb, const uint32_t *TA, const uint32_t *TB)
{
    const side_data *A = J->a;
    const uint32_t none = UINT32_MAX;
    const unsigned fa = A->flags ? A->flags[ta] : tri_flags(A, ta), fb = A->flags ? A->flags[tb] : tri_flags(A, tb);
    /* vertices of one against the other's face */
    for (int side = 0; side < 2; ++side) {
        const uint32_t *TV = side ? TB : TA, *TF = side ? TA : TB;
        const uint32_t tv = side ? tb : ta, tf = side ? ta : tb;
        const unsigned fv = side ? fb : fa;
        for (int k = 0; k < 3; ++k) {
            const uint32_t v = TV[k];
            if (!(fv & FIRST_V(k)) || tri_has(TF, v) || !sweep_overlap(&A->vbox[v], &A->twide[tf]) ||
                !sweep_overlap(&A->tbox[tf], &A->vwide[v]))
                continue;
            if (!owns_vf(J, v, tf, tv))
                continue;
            const uint32_t ida[2] = {v, none}, idb[2] = {tf, none};
            query(J, w, TTD_MESH_CCD_VF, A, &TV[k], 1, A, TF, ida, idb);
        }
    }
    /* edges against edges (tb's edges and boxes made once) */
    const uint64_t me = (uint64_t)ta << 32 | tb;
    uint32_t eb[3][2];
    sweep_box rawb[3], wideb[3];
    for (int j = 0; j < 3; ++j) {
        edge_of(TB, j, eb[j]);
        edge_box(A->vbox, eb[j], &rawb[j]);
        edge_box(A->vwide, eb[j], &wideb[j]);
    }
    for (int i = 0; i < 3; ++i) {
        if (!(fa & FIRST_E(i)))
            continue;
        uint32_t ea[2];
        sweep_box boxa, widea;
        edge_of(TA, i, ea);
        edge_box(A->vbox, ea, &boxa);
        edge_box(A->vwide, ea, &widea);
        for (int j = 0; j < 3; ++j) {
            if (!(fb & FIRST_E(j)))
                continue;
            const uint32_t *g = eb[j];
            if (ea[0] == g[0] || ea[0] == g[1] || ea[1] == g[0] || ea[1] == g[1])
                continue;
            if (!sweep_overlap(&boxa, &wideb[j]) || !sweep_overlap(&rawb[j], &widea) || !owns_ee(J, ea, g, me))
                continue;
            /* the smaller edge (by its vertex indices) first */
            const int swap = g[0] < ea[0] || (g[0] == ea[0] && g[1] < ea[1]);
            if (swap)
                query(J, w, TTD_MESH_CCD_EE, A, g, 2, A, ea, g, ea);
            else
                query(J, w, TTD_MESH_CCD_EE, A, ea, 2, A, g, ea, g);
        }
    }
}

/* The waiting pairs through the proof in lanes; those it does not prove, to the primitives. */
static void flush_pairs(const job *J, worker *w)
{
    const int n = w->nq;
    if (n == 0)
        return;
    w->nq = 0;
    const meshccd_side *X = J->a->s;
    unsigned left = ~J->apart(n, w->qv, X->x0, X->x1, J->a->vmag, J->params.delta) & ((2u << (n - 1)) - 1);
    for (; left != 0; left &= left - 1) {
        const int i = __builtin_ctz(left);
        pair_prims(J, w, w->qa[i], w->qb[i], w->qta[i], w->qtb[i]);
    }
}

/* Triangle pair ta < tb, kept by the rule (disjoint: sharing no vertex); TA, TB their vertex
 * indices (as pair_prims's). A disjoint pair is first tried whole (tri_pair_apart), in lanes
 * where the row has them: it waits in the worker's queue by its six vertex indices (which pairs
 * the lanes prove is what the scalar proof proves, and the answer does not depend on the order in
 * which pairs reach the primitive searches: t_stop's promise, ccd.h). */
static void pair_self_rest(const job *J, worker *w, uint32_t ta, uint32_t tb, const uint32_t *TA, const uint32_t *TB,
                           int disjoint);
static inline void pair_self(const job *J, worker *w, uint32_t ta, uint32_t tb, const uint32_t *TA, const uint32_t *TB,
                             int disjoint)
{
    ++w->tri_pairs;
    if (disjoint && J->apart != NULL) { /* the queue's path inline (most pairs), the rest a call */
        const int n = w->nq;
        for (int i = 0; i < 3; ++i) {
            w->qv[i * TTD_NODE_WIDTH + n] = TA[i];
            w->qv[(3 + i) * TTD_NODE_WIDTH + n] = TB[i];
        }
        w->qa[n] = ta;
        w->qb[n] = tb;
        w->qta[n] = TA;
        w->qtb[n] = TB;
        if (++w->nq == TTD_NODE_WIDTH)
            flush_pairs(J, w);
        return;
    }
    pair_self_rest(J, w, ta, tb, TA, TB, disjoint);
}

static void pair_self_rest(const job *J, worker *w, uint32_t ta, uint32_t tb, const uint32_t *TA, const uint32_t *TB,
                           int disjoint)
{
    const side_data *A = J->a;
    if (disjoint) { /* (two triangles with a vertex in common are never apart) */
        const double *x0[6], *x1[6]; /* the six points where they are (a copy costs more) */
        double S = 0;
        for (int i = 0; i < 6; ++i) {
            const size_t v = i < 3 ? TA[i] : TB[i - 3];
            x0[i] = A->s->x0 + 3 * v;
            x1[i] = A->s->x1 + 3 * v;
            S = A->vmag[v] > S ? A->vmag[v] : S;
        }
        if (tri_pair_apart(x0, x1, S, J->params.delta))
            return;
    }
    pair_prims(J, w, ta, tb, TA, TB);
}

/* ---- the walk ---- */

/* Two meshes: the triangles of a at positions [gb, ge) of qorder (a leaf of a's tree), by their
 * unwidened boxes, against the tree of b's widened boxes. One walk serves the whole leaf: its box
 * first, then each triangle at the tree's leaves. (The tree's depth is at most 32, so the stack
 * holds at most 2 per level.) */
static void walk_group(const job *J, worker *w, const uint32_t *qorder, uint32_t gb, uint32_t ge)
{
    const sweep_box *tbox = J->a->tbox, *twide = J->b->twide;
    const sweep_tree *t = &J->tree;
    sweep_box R = tbox[qorder[gb]];
    for (uint32_t k = gb + 1; k < ge; ++k)
        sweep_box_join(&R, &tbox[qorder[k]]);
    uint32_t stack[MCCD_STACK];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const sweep_node *nd = &t->nodes[stack[--top]];
        if (!sweep_overlap(&R, &nd->box))
            continue;
        if (nd->left != 0) {
            stack[top++] = nd->left + 1;
            stack[top++] = nd->left;
            continue;
        }
        for (uint32_t kq = gb; kq < ge; ++kq) {
            const uint32_t q = qorder[kq];
            if (!sweep_overlap(&tbox[q], &nd->box))
                continue;
            for (uint32_t k = nd->begin; k < nd->end; ++k) {
                const uint32_t u = t->order[k];
                if (sweep_overlap(&tbox[q], &twide[u]))
                    pair_two(J, w, q, u);
            }
        }
    }
}

/* ---- the self walk: the tree against itself ---- */

/* Which of the up to SWEEP_LEAF_SELF boxes k = kb, kb + 1, ... of the columns W overlap the box q
 * (lo[3], hi[3]), as bits 0, 1, ...: a fixed count of comparisons without branches, which the
 * compiler lays out in vector registers (about half the leaf tests pass, so a branch per test
 * mispredicts); the caller masks off the padding. Exact (comparisons of the same doubles as
 * sweep_overlap). */
static inline unsigned leaf_mask(const double *const W[6], uint32_t kb, const double q[6])
{
    unsigned m = 0;
#if MESHCCD_SSE2_LEAVES
    /* two boxes a register (SSE2 is in every x86-64); the same comparisons, bit for bit */
    __m128d ql[3], qh[3];
    for (int c = 0; c < 3; ++c) {
        ql[c] = _mm_set1_pd(q[c]);
        qh[c] = _mm_set1_pd(q[3 + c]);
    }
    for (int i = 0; i < SWEEP_LEAF_SELF; i += 2) {
        const uint32_t k = kb + (uint32_t)i;
        __m128d ok = _mm_and_pd(_mm_cmple_pd(ql[0], _mm_loadu_pd(W[3] + k)), _mm_cmple_pd(_mm_loadu_pd(W[0] + k), qh[0]));
        for (int c = 1; c < 3; ++c)
            ok = _mm_and_pd(ok, _mm_and_pd(_mm_cmple_pd(ql[c], _mm_loadu_pd(W[3 + c] + k)),
                                           _mm_cmple_pd(_mm_loadu_pd(W[c] + k), qh[c])));
        m |= (unsigned)_mm_movemask_pd(ok) << i;
    }
    return m;
#else
    for (int i = 0; i < SWEEP_LEAF_SELF; ++i) {
        const uint32_t k = kb + (uint32_t)i;
        const int ok = (q[0] <= W[3][k]) & (W[0][k] <= q[3]) & (q[1] <= W[4][k]) & (W[1][k] <= q[4]) &
                       (q[2] <= W[5][k]) & (W[2][k] <= q[5]);
        m |= (unsigned)ok << i;
    }
    return m;
#endif
}

/* Triangle pair (kq, k) of the self walk, by its places in the tree's order, whose boxes overlap;
 * any: whether they have an index in common. To pair_self if the rule keeps it. */
static inline void leaf_pair_kept(const job *J, worker *w, uint32_t kq, uint32_t k, int any)
{
    const uint32_t *TQ = J->ptri + 3 * (size_t)kq, *TU = J->ptri + 3 * (size_t)k;
    const int kept = eligible_tris(J, TQ, TU, any);
    if (kept) {
        const uint32_t qi = J->porder[kq], u = J->porder[k];
        if (qi < u)
            pair_self(J, w, qi, u, TQ, TU, kept == 1);
        else
            pair_self(J, w, u, qi, TU, TQ, kept == 1);
    }
}

/* Row kq of a pair of leaves against the lanes k = kb + (bits of m) of the other, in order: the
 * rule's index test, common_index's, in a register where SSE2 is: the other triangle's indices
 * (and one of padding: the copy in the tree's order has one more) against each of kq's, which are
 * broadcast once for the row. */
static inline void leaf_row_pairs(const job *J, worker *w, uint32_t kq, uint32_t kb, unsigned m)
{
#if MESHCCD_SSE2_LEAVES
    const uint32_t *TQ = J->ptri + 3 * (size_t)kq;
    const __m128i q0 = _mm_set1_epi32((int)TQ[0]), q1 = _mm_set1_epi32((int)TQ[1]), q2 = _mm_set1_epi32((int)TQ[2]);
    for (; m != 0; m &= m - 1) {
        const uint32_t k = kb + (uint32_t)__builtin_ctz(m);
        const __m128i u = _mm_loadu_si128((const __m128i *)(const void *)(J->ptri + 3 * (size_t)k));
        const __m128i eq = _mm_or_si128(_mm_or_si128(_mm_cmpeq_epi32(u, q0), _mm_cmpeq_epi32(u, q1)),
                                        _mm_cmpeq_epi32(u, q2));
        leaf_pair_kept(J, w, kq, k, (_mm_movemask_ps(_mm_castsi128_ps(eq)) & 7) != 0);
    }
#else
    for (; m != 0; m &= m - 1) {
        const uint32_t k = kb + (uint32_t)__builtin_ctz(m);
        leaf_pair_kept(J, w, kq, k, common_index(J->ptri + 3 * (size_t)kq, J->ptri + 3 * (size_t)k));
    }
#endif
}

/* Two runs of the columns (a tree's leaves, or the grid's groups), ka .. ka + na and kb .. kb + nb
 * (1 to SWEEP_LEAF_SELF each), the same run (same) or disjoint; box: a box that holds the second
 * run's widened boxes. Each triangle q of the first against each triangle u of the second (after q
 * in a run against itself), by the same tests as walk_group's (so the same triangle pairs), u
 * ascending. */
static void run_pair_self(const job *J, worker *w, uint32_t ka, uint32_t na, uint32_t kb, uint32_t nb, int same,
                          const sweep_box *box)
{
    const double *const *P = (const double *const *)J->pb, *const *W = (const double *const *)J->pw;
    const int wide = J->pw[0] != J->pb[0]; /* at delta 0 the two tests are one (the test is symmetric) */
    const unsigned all = (2u << (nb - 1)) - 1;
    if (J->lscreen != NULL) {
        /* the whole pair of runs in one call of the row (a's rows against b's lanes; the same
         * comparisons as the loop below, so the same bits): a row near a lane is near b's box */
        const double *const ra[6] = {P[0] + ka, P[1] + ka, P[2] + ka, P[3] + ka, P[4] + ka, P[5] + ka};
        const double *const rw[6] = {W[0] + kb, W[1] + kb, W[2] + kb, W[3] + kb, W[4] + kb, W[5] + kb};
        uint8_t m8[TTD_NODE_WIDTH];
        unsigned rows = J->lscreen(ra, (int)na, rw, m8);
        if (wide && rows) {
            const double *const rwa[6] = {W[0] + ka, W[1] + ka, W[2] + ka, W[3] + ka, W[4] + ka, W[5] + ka};
            const double *const rp[6] = {P[0] + kb, P[1] + kb, P[2] + kb, P[3] + kb, P[4] + kb, P[5] + kb};
            uint8_t w8[TTD_NODE_WIDTH];
            J->lscreen(rwa, (int)na, rp, w8);
            for (uint32_t i = 0; i < na; ++i)
                m8[i] &= w8[i];
        }
        for (; rows != 0; rows &= rows - 1) {
            const int i = __builtin_ctz(rows);
            unsigned m = m8[i] & all;
            if (same)
                m &= ~((2u << i) - 1); /* u after q only */
            leaf_row_pairs(J, w, ka + (uint32_t)i, kb, m);
        }
        return;
    }
    for (uint32_t kq = ka; kq < ka + na; ++kq) {
        const double q[6] = {P[0][kq], P[1][kq], P[2][kq], P[3][kq], P[4][kq], P[5][kq]};
        if (!(q[0] <= box->hi[0] && box->lo[0] <= q[3] && q[1] <= box->hi[1] && box->lo[1] <= q[4] &&
              q[2] <= box->hi[2] && box->lo[2] <= q[5]))
            continue;
        unsigned m = leaf_mask(W, kb, q) & all;
        if (same)
            m &= ~((2u << (kq - kb)) - 1); /* u after q only */
        if (wide && m) {
            const double qw[6] = {W[0][kq], W[1][kq], W[2][kq], W[3][kq], W[4][kq], W[5][kq]};
            m &= leaf_mask(P, kb, qw);
        }
        leaf_row_pairs(J, w, kq, kb, m);
    }
}

/* Two leaves of the tree, a == b or a before b in the order. */
static void leaf_pair_self(const job *J, worker *w, const sweep_node *a, const sweep_node *b)
{
    run_pair_self(J, w, a->begin, a->end - a->begin, b->begin, b->end - b->begin, a == b, &b->box);
}

/* Pushes (a, b) on the worker's stack, grown as needed; 0, or -1 out of memory. */
static int push_pair(worker *w, size_t *top, uint32_t a, uint32_t b)
{
    if (*top == w->stack_cap) {
        const size_t cap = w->stack_cap ? 2 * w->stack_cap : 256;
        node_pair *p = realloc(w->stack, cap * sizeof *p);
        if (p == NULL) {
            w->oom = 1;
            return -1;
        }
        w->stack = p;
        w->stack_cap = cap;
    }
    w->stack[(*top)++] = (node_pair){a, b};
    return 0;
}

/* What a pair of nodes becomes: a == b splits into (l, l), (l, r), (r, r); two others whose boxes
 * overlap, into the larger's children against the other (a's before b's in the order still).
 * Returns how many pairs it wrote to out[0 .. 3), or -1 for a pair of leaves to test. A pair of
 * nodes whose (widened) boxes do not overlap holds no triangle pair that walk_group would test:
 * a triangle's own box lies inside its widened box, which lies inside its nodes'. */
static int split_pair(const sweep_tree *t, node_pair p, node_pair out[3])
{
    const sweep_node *a = &t->nodes[p.a], *b = &t->nodes[p.b];
    if (p.a == p.b) {
        if (a->left == 0)
            return -1;
        out[0] = (node_pair){a->left, a->left};
        out[1] = (node_pair){a->left, a->left + 1};
        out[2] = (node_pair){a->left + 1, a->left + 1};
        return 3;
    }
    if (!sweep_overlap(&a->box, &b->box))
        return 0;
    if (a->left == 0 && b->left == 0)
        return -1;
    if (b->left == 0 || (a->left != 0 && a->end - a->begin >= b->end - b->begin)) {
        out[0] = (node_pair){a->left, p.b};
        out[1] = (node_pair){a->left + 1, p.b};
    } else {
        out[0] = (node_pair){p.a, b->left};
        out[1] = (node_pair){p.a, b->left + 1};
    }
    return 2;
}

/* The walk below one starting pair, depth first. Each pair of distinct nodes is tested before it
 * is pushed, and two inner nodes split both at once into their four children's pairs (the pairs
 * of a node and the other's parent that a one-sided split visits are skipped: a pair of boxes that
 * overlaps lies inside such a pair, which then overlaps too). So the pairs of leaves reached are
 * split_pair's, those whose boxes overlap, and their triangle pairs the same; only their order
 * differs, which the answer does not depend on (pair_self). */
static void walk_self(const job *J, worker *w, node_pair start)
{
    const sweep_node *N = J->tree.nodes;
    size_t top = 0;
    if ((start.a == start.b || sweep_overlap(&N[start.a].box, &N[start.b].box)) &&
        push_pair(w, &top, start.a, start.b) != 0)
        return;
    while (top > 0) {
        const node_pair p = w->stack[--top];
        const sweep_node *a = &N[p.a], *b = &N[p.b];
        const uint32_t al = a->left, bl = b->left;
        if (al == 0 && bl == 0) {
            leaf_pair_self(J, w, a, b);
            continue;
        }
        /* children pushed last first, so that they are visited as split_pair orders them */
        int fail = 0;
        if (p.a == p.b) {
            fail |= push_pair(w, &top, al + 1, al + 1);
            if (sweep_overlap(&N[al].box, &N[al + 1].box))
                fail |= push_pair(w, &top, al, al + 1);
            fail |= push_pair(w, &top, al, al);
        } else if (al != 0 && bl != 0) {
            for (int i = 3; i >= 0; --i) {
                const uint32_t x = al + (uint32_t)(i >> 1), y = bl + (uint32_t)(i & 1);
                if (sweep_overlap(&N[x].box, &N[y].box))
                    fail |= push_pair(w, &top, x, y);
            }
        } else if (al != 0) {
            for (int i = 1; i >= 0; --i)
                if (sweep_overlap(&N[al + (uint32_t)i].box, &b->box))
                    fail |= push_pair(w, &top, al + (uint32_t)i, p.b);
        } else {
            for (int i = 1; i >= 0; --i)
                if (sweep_overlap(&a->box, &N[bl + (uint32_t)i].box))
                    fail |= push_pair(w, &top, p.a, bl + (uint32_t)i);
        }
        if (fail)
            return;
    }
    if (J->apart != NULL)
        flush_pairs(J, w);
}

/* The starting pairs of the self walk: the pairs of the walk's first levels, split (in order,
 * breadth first) until both nodes of each hold at most SELF_TASK_TRIS triangles or are leaves;
 * the workers share them out (their order does not matter to the result). 0, or -1 out of memory. */
enum { SELF_TASK_TRIS = 256 };
static int self_tasks(job *J)
{
    const sweep_tree *t = &J->tree;
    size_t cap = 64, n = 0, head = 0;
    node_pair *q = malloc(cap * sizeof *q);
    if (q == NULL)
        return -1;
    q[n++] = (node_pair){0, 0};
    size_t done = 0; /* q[0 .. done) are final tasks, q[head .. n) still to look at */
    while (head < n) {
        const node_pair p = q[head++];
        const sweep_node *a = &t->nodes[p.a], *b = &t->nodes[p.b];
        node_pair kids[3];
        int nk;
        if ((a->end - a->begin <= SELF_TASK_TRIS && b->end - b->begin <= SELF_TASK_TRIS) ||
            (nk = split_pair(t, p, kids)) < 0) {
            q[done++] = p; /* done <= head - 1: no entry still to look at is overwritten */
            continue;
        }
        if (n + (size_t)nk > cap) {
            cap *= 2;
            node_pair *g = realloc(q, cap * sizeof *g);
            if (g == NULL) {
                free(q);
                return -1;
            }
            q = g;
        }
        for (int i = 0; i < nk; ++i)
            q[n++] = kids[i];
    }
    J->tasks = q;
    J->ntasks = done;
    return 0;
}

enum { SELF_BLOCK_TASKS = 4 };

static void run_self_block(void *ctx, size_t block, int wi)
{
    job *J = ctx;
    worker *w = &J->workers[wi];
    const size_t end = (block + 1) * SELF_BLOCK_TASKS < J->ntasks ? (block + 1) * SELF_BLOCK_TASKS : J->ntasks;
    for (size_t i = block * SELF_BLOCK_TASKS; i < end && !w->oom; ++i)
        walk_self(J, w, J->tasks[i]);
}

/* The leaves of a tree (node indices), in order. */
static size_t tree_leaves(const sweep_tree *t, uint32_t *out)
{
    uint32_t stack[MCCD_STACK];
    int top = 0;
    size_t n = 0;
    stack[top++] = 0;
    while (top > 0) {
        const uint32_t i = stack[--top];
        if (t->nodes[i].left != 0) {
            stack[top++] = t->nodes[i].left + 1;
            stack[top++] = t->nodes[i].left;
        } else {
            out[n++] = i;
        }
    }
    return n;
}

static void run_block(void *ctx, size_t block, int wi)
{
    job *J = ctx;
    worker *w = &J->workers[wi];
    if (w->oom)
        return;
    const sweep_tree *qt = &J->qtree;
    const size_t end = (block + 1) * MCCD_BLOCK_LEAVES < J->nleaves ? (block + 1) * MCCD_BLOCK_LEAVES : J->nleaves;
    for (size_t i = block * MCCD_BLOCK_LEAVES; i < end; ++i) {
        const sweep_node *leaf = &qt->nodes[J->leaves[i]];
        walk_group(J, w, qt->order, leaf->begin, leaf->end);
    }
}

/* ---- the self query by a grid of groups (docs/ccd-speed.md, ninth session) ---- */

/* The tree's leaves group triangles by the rank of their centroids, which on a sheet spreads a
 * leaf over 6 to 9 quads whose boxes meet about 23 leaves; 8 triangles grown over shared vertices
 * are a patch of about 2 x 2 quads, whose box meets about 8 (as self-contacts' groups,
 * docs/mesh-queries.md section 3b). Each group starts at the first triangle not yet grouped and
 * takes those that share a vertex with one in it, in the breadth-first order and index order
 * around each vertex, until it has 8 or none is left; around a vertex a cursor skips the grouped
 * triangles and at most GROUP_LOOK more are looked at a visit. Any grouping gives the same
 * triangle pairs (every pair whose boxes overlap, once); only the work depends on it. gtri: 8 a
 * group (UINT32_MAX past its count gn). cur: nv, mark: nt (int32), done: nt zeroed. */
enum { GROUP_LOOK = 32 };
static size_t ccd_groups(const side_data *d, uint32_t *gtri, uint8_t *gn, uint32_t *cur, int32_t *mark,
                         uint8_t *done)
{
    const uint32_t *T = d->s->tris, *vs = d->vt_start, *vl = d->vt_list;
    const size_t nt = d->s->nt;
    memcpy(cur, vs, d->s->nv * sizeof *cur);
    for (size_t t = 0; t < nt; ++t)
        mark[t] = -1;
    size_t ng = 0;
    for (size_t seed = 0; seed < nt; ++seed) {
        if (done[seed])
            continue;
        uint32_t *q = gtri + SWEEP_LEAF_SELF * ng;
        int qh = 0, qn = 1;
        q[0] = (uint32_t)seed;
        mark[seed] = (int32_t)ng;
        while (qh < qn) {
            const uint32_t t = q[qh++];
            done[t] = 1;
            for (int k = 0; k < 3 && qn < SWEEP_LEAF_SELF; ++k) {
                const uint32_t v = T[3 * (size_t)t + k];
                while (cur[v] < vs[v + 1] && done[vl[cur[v]]])
                    cur[v]++;
                for (uint32_t i = cur[v], e = 0; i < vs[v + 1] && e < GROUP_LOOK && qn < SWEEP_LEAF_SELF; ++i, ++e) {
                    const uint32_t u = vl[i];
                    if (!done[u] && mark[u] != (int32_t)ng) {
                        mark[u] = (int32_t)ng;
                        q[qn++] = u;
                    }
                }
            }
        }
        gn[ng] = (uint8_t)qn;
        for (int j = qn; j < SWEEP_LEAF_SELF; ++j)
            q[j] = UINT32_MAX;
        ++ng;
    }
    return ng;
}

/* Group pairs a group's box tests may reach, a group, above which the tree walks instead (a few
 * huge groups put most of the mesh in a few cells). */
#define GRID_WORK 256

/* The grid of J (self): groups, their columns, boxes and cells. 1 made, 0 the tree is better (or
 * a box is not finite), -1 out of memory. */
static int grid_make(job *J)
{
    const side_data *A = J->a;
    const size_t nt = A->s->nt, nv = A->s->nv;
    J->gtri = malloc(SWEEP_LEAF_SELF * nt * sizeof *J->gtri);
    J->gn = malloc(nt * sizeof *J->gn);
    uint32_t *cur = malloc((nv ? nv : 1) * sizeof *cur);
    int32_t *mark = malloc(nt * sizeof *mark);
    uint8_t *done = calloc(nt, 1);
    if (J->gtri == NULL || J->gn == NULL || cur == NULL || mark == NULL || done == NULL) {
        free(cur), free(mark), free(done);
        return -1;
    }
    const size_t ng = J->ng = ccd_groups(A, J->gtri, J->gn, cur, mark, done);
    free(cur), free(mark), free(done);
#if MESHCCD_GRID < 0
    /* groups short (more than 5 in 4 of a full grouping's count: a soup of unconnected triangles,
     * whose tree leaves group them better): the tree */
    if (4 * ng > 5 * ((nt + SWEEP_LEAF_SELF - 1) / SWEEP_LEAF_SELF))
        return 0;
#endif
    J->porder = J->gtri;
    const size_t cols = SWEEP_LEAF_SELF * (ng + 1); /* + a group of padding: the rows read 8 lanes */
    const int wide = J->params.delta != 0;
    J->pb[0] = malloc(6 * cols * sizeof(double));
    J->pw[0] = wide ? malloc(6 * cols * sizeof(double)) : J->pb[0];
    J->ptri = calloc(3 * cols + 1, sizeof *J->ptri); /* + 1: leaf_row_pairs reads one more */
    J->gbox = malloc((ng ? ng : 1) * sizeof *J->gbox);
    J->gorder = malloc((ng ? ng : 1) * sizeof *J->gorder);
    uint32_t *cell = malloc((ng ? ng : 1) * sizeof *cell);
    double *ext = malloc((ng ? ng : 1) * sizeof *ext);
    if (J->pb[0] == NULL || J->pw[0] == NULL || J->ptri == NULL || J->gbox == NULL || J->gorder == NULL ||
        cell == NULL || ext == NULL) {
        free(cell), free(ext);
        return -1;
    }
    for (int c = 1; c < 6; ++c) {
        J->pb[c] = J->pb[0] + c * cols;
        J->pw[c] = J->pw[0] + c * cols;
    }
    /* the columns in the groups' order (padding lanes never near: lo +inf, hi -inf), the groups'
     * boxes (joins of their widened boxes), their largest sides */
    double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL}, sum = 0;
    for (size_t g = 0; g <= ng; ++g)
        for (int j = 0; j < SWEEP_LEAF_SELF; ++j) {
            const size_t k = SWEEP_LEAF_SELF * g + (size_t)j;
            const uint32_t t = g < ng ? J->gtri[k] : UINT32_MAX;
            if (t == UINT32_MAX) {
                for (int c = 0; c < 3; ++c) {
                    J->pb[c][k] = J->pw[c][k] = HUGE_VAL;
                    J->pb[3 + c][k] = J->pw[3 + c][k] = -HUGE_VAL;
                }
                continue;
            }
            const sweep_box *b = &A->tbox[t], *bw = &A->twide[t];
            for (int c = 0; c < 3; ++c) {
                J->pb[c][k] = b->lo[c];
                J->pb[3 + c][k] = b->hi[c];
            }
            if (wide)
                for (int c = 0; c < 3; ++c) {
                    J->pw[c][k] = bw->lo[c];
                    J->pw[3 + c][k] = bw->hi[c];
                }
            memcpy(J->ptri + 3 * k, A->s->tris + 3 * (size_t)t, 3 * sizeof *J->ptri);
            if (j == 0)
                J->gbox[g] = *bw;
            else
                sweep_box_join(&J->gbox[g], bw);
        }
    for (size_t g = 0; g < ng; ++g) {
        const sweep_box *b = &J->gbox[g];
        double e = 0;
        for (int c = 0; c < 3; ++c) {
            e = b->hi[c] - b->lo[c] > e ? b->hi[c] - b->lo[c] : e;
            lo[c] = b->lo[c] < lo[c] ? b->lo[c] : lo[c];
            hi[c] = b->lo[c] > hi[c] ? b->lo[c] : hi[c];
        }
        ext[g] = e;
        sum += e;
    }
    /* groups up to 4 times the mean side go into cells as wide as the largest of them on each axis
     * (two whose boxes overlap have low corners at most that apart: cells within 1 of each other;
     * a cell a little wider covers the rounding of (lo - lo_min) / h); the larger meet every group */
    const double cut = 4 * sum / (double)(ng ? ng : 1);
    double side[3] = {0, 0, 0}, h[3];
    size_t nbig = 0;
    for (size_t g = 0; g < ng; ++g) {
        if (ext[g] > cut) {
            ++nbig;
            continue;
        }
        for (int c = 0; c < 3; ++c)
            side[c] = J->gbox[g].hi[c] - J->gbox[g].lo[c] > side[c] ? J->gbox[g].hi[c] - J->gbox[g].lo[c] : side[c];
    }
    J->nsmall = ng - nbig;
    J->ncells = isfinite(sum) ? ttd_grid_cells(side, lo, hi, ng, h, J->gdim) : 0;
    if (J->ncells == 0) {
        free(cell), free(ext);
        return 0;
    }
    J->gstart = calloc(J->ncells + 2, sizeof *J->gstart);
    if (J->gstart == NULL) {
        free(cell), free(ext);
        return -1;
    }
    uint32_t *S = J->gstart;
    for (size_t g = 0; g < ng; ++g) {
        if (ext[g] > cut)
            continue;
        size_t at = 0;
        for (int c = 2; c >= 0; --c) {
            size_t q = (size_t)floor((J->gbox[g].lo[c] - lo[c]) / h[c]);
            q = q < J->gdim[c] ? q : J->gdim[c] - 1;
            at = at * J->gdim[c] + q;
        }
        cell[g] = (uint32_t)at;
        S[at + 2]++;
    }
    for (size_t c = 0; c < J->ncells; ++c)
        S[c + 2] += S[c + 1];
    for (size_t g = 0, big = J->nsmall; g < ng; ++g) /* S[c + 1] runs through cell c, then is its end */
        J->gorder[ext[g] > cut ? big++ : S[cell[g] + 1]++] = (uint32_t)g;
    free(cell), free(ext);
    /* the work: each group's box tests against its cell and the 13 after it */
    const size_t X = J->gdim[0], Y = J->gdim[1], Z = J->gdim[2];
    double work = 0;
    for (size_t c = 0; c < J->ncells; ++c) {
        const double nc = (double)(S[c + 1] - S[c]);
        if (nc == 0)
            continue;
        const size_t x = c % X, y = c / X % Y, z = c / (X * Y);
        double around = 0;
        for (int dz = 0; dz <= 1; ++dz)
            for (int dy = dz ? -1 : 0; dy <= 1; ++dy)
                for (int dx = dz || dy ? -1 : 1; dx <= 1; ++dx)
                    if (x + (size_t)dx < X && y + (size_t)dy < Y && z + (size_t)dz < Z) /* -1 wraps past */
                        around += (double)(S[((z + (size_t)dz) * Y + y + (size_t)dy) * X + x + (size_t)dx + 1] -
                                           S[((z + (size_t)dz) * Y + y + (size_t)dy) * X + x + (size_t)dx]);
        work += nc * (around + (nc + 1) / 2);
    }
    work += (double)nbig * (double)ng;
    return MESHCCD_GRID > 0 || work <= GRID_WORK * (double)ng + 1024 ? 1 : 0;
}

/* Groups g and h (whose boxes overlap, g == h or not): their triangle pairs. */
static inline void grid_pair(const job *J, worker *w, uint32_t g, uint32_t h)
{
    run_pair_self(J, w, SWEEP_LEAF_SELF * g, J->gn[g], SWEEP_LEAF_SELF * h, J->gn[h], g == h, &J->gbox[h]);
}

/* Group at position p of gorder against those at positions [q0, q1) whose boxes overlap its own. */
static void grid_range(const job *J, worker *w, uint32_t p, uint32_t q0, uint32_t q1)
{
    const uint32_t g = J->gorder[p];
    const sweep_box *b = &J->gbox[g];
    for (uint32_t q = q0; q < q1; ++q) {
        const uint32_t h = J->gorder[q];
        if (sweep_overlap(b, &J->gbox[h]))
            grid_pair(J, w, g, h);
    }
}

enum { GRID_BLOCK_UNITS = 64 };

/* Units [block * GRID_BLOCK_UNITS, ...): unit u < ncells is cell u, whose groups meet themselves,
 * the rest of their cell and the 13 cells after it (so each pair of groups in cells once); a
 * unit past them is a large group, which meets every group in a cell and the large ones from
 * itself on. */
static void run_grid_block(void *ctx, size_t block, int wi)
{
    job *J = ctx;
    worker *w = &J->workers[wi];
    const size_t X = J->gdim[0], Y = J->gdim[1], Z = J->gdim[2], units = J->ncells + (J->ng - J->nsmall);
    const uint32_t *S = J->gstart;
    const size_t u0 = block * GRID_BLOCK_UNITS, u1 = u0 + GRID_BLOCK_UNITS < units ? u0 + GRID_BLOCK_UNITS : units;
    for (size_t c = u0; c < u1 && c < J->ncells && !w->oom; ++c) {
        if (S[c] == S[c + 1])
            continue;
        const size_t x = c % X, y = c / X % Y, z = c / (X * Y);
        size_t d[13];
        int nd = 0;
        for (int dz = 0; dz <= 1; ++dz)
            for (int dy = dz ? -1 : 0; dy <= 1; ++dy)
                for (int dx = dz || dy ? -1 : 1; dx <= 1; ++dx)
                    if (x + (size_t)dx < X && y + (size_t)dy < Y && z + (size_t)dz < Z) {
                        const size_t e = ((z + (size_t)dz) * Y + y + (size_t)dy) * X + x + (size_t)dx;
                        if (S[e] != S[e + 1])
                            d[nd++] = e;
                    }
        for (uint32_t p = S[c]; p < S[c + 1]; ++p) {
            grid_pair(J, w, J->gorder[p], J->gorder[p]);
            grid_range(J, w, p, p + 1, S[c + 1]);
            for (int e = 0; e < nd; ++e)
                grid_range(J, w, p, S[d[e]], S[d[e] + 1]);
        }
    }
    for (size_t u = u1 > J->ncells ? (u0 > J->ncells ? u0 : J->ncells) : u1; u < u1 && !w->oom; ++u) {
        const uint32_t p = (uint32_t)(J->nsmall + (u - J->ncells));
        grid_range(J, w, p, 0, (uint32_t)J->nsmall);
        grid_range(J, w, p, p, (uint32_t)J->ng);
    }
    if (J->apart != NULL)
        flush_pairs(J, w);
}


/* Frees what grid_make made (the columns too). */
static void grid_drop(job *J)
{
    if (J->pw[0] != J->pb[0])
        free(J->pw[0]);
    free(J->pb[0]);
    free(J->ptri);
    free(J->gtri);
    free(J->gn);
    free(J->gbox);
    free(J->gorder);
    free(J->gstart);
    memset(J->pb, 0, sizeof J->pb);
    memset(J->pw, 0, sizeof J->pw);
    J->ptri = J->gtri = J->gorder = J->gstart = NULL;
    J->gn = NULL;
    J->gbox = NULL;
    J->porder = NULL;
    J->grid = 0;
}

static int pair_cmp(const void *x, const void *y)
{
    const ttd_mesh_ccd_pair *p = x, *q = y;
    if (p->toi != q->toi)
        return p->toi < q->toi ? -1 : 1;
    if (p->kind != q->kind)
        return p->kind < q->kind ? -1 : 1;
    const uint32_t kp[4] = {p->a[0], p->a[1], p->b[0], p->b[1]}, kq[4] = {q->a[0], q->a[1], q->b[0], q->b[1]};
    for (int i = 0; i < 4; ++i)
        if (kp[i] != kq[i])
            return kp[i] < kq[i] ? -1 : 1;
    return 0;
}

ttd_status ttd_meshccd_run(int threads, ttd_isa isa, const meshccd_side *a, const meshccd_side *b, double delta,
                           unsigned shared, ttd_mesh_ccd_result *out)
{
    memset(out, 0, sizeof *out);
    out->toi = HUGE_VAL;
    side_data da, db;
    job J;
    memset(&J, 0, sizeof J);
    J.self = b == NULL;
    J.shared = shared & TTD_SELF_SHARED_VERTEX;
    J.params = ttd_ccd_default_params();
    J.params.delta = delta;
    const ttd_kernels_d *row = ttd_dispatch_row_d(isa);
    J.apart = J.self && row != NULL ? row->tri_apart_at : NULL;
#if !defined(MESHCCD_SCALAR_LEAVES)
    J.lscreen = J.self && row != NULL ? row->leaf_screen : NULL;
#endif
    if (side_make(a, delta, !J.self || J.shared, &da) != 0)
        return TTD_ERR_OUT_OF_MEMORY;
    if (!J.self && side_make(b, delta, 1, &db) != 0) {
        side_free(&da);
        return TTD_ERR_OUT_OF_MEMORY;
    }
    J.a = &da;
    J.b = J.self ? &da : &db;
    ttd_status st = TTD_OK;
    if (J.self && MESHCCD_GRID != 0) { /* the grid of groups where it does better than the tree */
        const int made = grid_make(&J);
        if (made < 0) {
            st = TTD_ERR_OUT_OF_MEMORY;
            goto done;
        }
        if (made == 0)
            grid_drop(&J);
        J.grid = made;
    }
    if (!J.grid && sweep_tree_build(J.b->twide, J.b->s->nt, J.self ? SWEEP_LEAF_SELF : SWEEP_LEAF, &J.tree) != 0) {
        st = TTD_ERR_OUT_OF_MEMORY;
        goto done;
    }
    if (!J.self && sweep_tree_build(J.a->tbox, a->nt, SWEEP_LEAF, &J.qtree) != 0) {
        st = TTD_ERR_OUT_OF_MEMORY;
        goto done;
    }
    size_t blocks;
    if (J.grid) {
        blocks = (J.ncells + (J.ng - J.nsmall) + GRID_BLOCK_UNITS - 1) / GRID_BLOCK_UNITS;
    } else if (J.self) {
        /* the tree against itself from the pairs of its first levels */
        const size_t nt = a->nt;
        const size_t cols = nt + SWEEP_LEAF_SELF; /* padding: leaf_mask reads a whole leaf's width */
        J.pb[0] = calloc(6 * cols, sizeof(double));
        J.pw[0] = delta == 0 ? J.pb[0] : calloc(6 * cols, sizeof(double));
        J.ptri = calloc(3 * nt + 1, sizeof *J.ptri); /* + 1: leaf_row_pairs reads one more */
        J.porder = J.tree.order;
        if (J.pb[0] == NULL || J.pw[0] == NULL || J.ptri == NULL || self_tasks(&J) != 0) {
            st = TTD_ERR_OUT_OF_MEMORY;
            goto done;
        }
        for (int c = 1; c < 6; ++c) {
            J.pb[c] = J.pb[0] + c * cols;
            J.pw[c] = J.pw[0] + c * cols;
        }
        const int wide = J.pw[0] != J.pb[0]; /* at delta 0 they are one array */
        for (size_t k = 0; k < nt; ++k) {
            const uint32_t t = J.tree.order[k];
            for (int c = 0; c < 3; ++c) {
                J.pb[c][k] = da.tbox[t].lo[c];
                J.pb[3 + c][k] = da.tbox[t].hi[c];
            }
            if (wide)
                for (int c = 0; c < 3; ++c) {
                    J.pw[c][k] = da.twide[t].lo[c];
                    J.pw[3 + c][k] = da.twide[t].hi[c];
                }
            memcpy(J.ptri + 3 * k, a->tris + 3 * (size_t)t, 3 * sizeof *J.ptri);
        }
        blocks = (J.ntasks + SELF_BLOCK_TASKS - 1) / SELF_BLOCK_TASKS;
    } else {
        /* a walk of b's tree from each leaf of a's */
        J.leaves = malloc(J.qtree.nnodes * sizeof *J.leaves);
        if (J.leaves == NULL) {
            st = TTD_ERR_OUT_OF_MEMORY;
            goto done;
        }
        J.nleaves = tree_leaves(&J.qtree, J.leaves);
        blocks = (J.nleaves + MCCD_BLOCK_LEAVES - 1) / MCCD_BLOCK_LEAVES;
    }
    const int nw = ttd_parallel_workers(blocks, threads);
    J.workers = calloc((size_t)nw, sizeof *J.workers);
    J.nworkers = J.workers != NULL ? nw : 0;
    if (J.workers == NULL) {
        st = TTD_ERR_OUT_OF_MEMORY;
        goto done;
    }
    for (int i = 0; i < nw; ++i)
        J.workers[i].best = HUGE_VAL;
    ttd_parallel_for(blocks, threads, J.grid ? run_grid_block : J.self ? run_self_block : run_block, &J);
    /* the earliest over the workers, then their hits within the tolerance of it */
    double best = HUGE_VAL;
    size_t total = 0;
    for (int i = 0; i < nw; ++i) {
        const worker *w = &J.workers[i];
        if (w->oom)
            st = TTD_ERR_OUT_OF_MEMORY;
        best = w->best < best ? w->best : best;
        out->triangle_pairs += w->tri_pairs;
        out->queries += w->queries;
        out->searches += w->searches;
        total += w->n;
    }
    if (st != TTD_OK)
        goto done;
    if (total > 0) {
        out->pairs = malloc(total * sizeof *out->pairs);
        if (out->pairs == NULL) {
            st = TTD_ERR_OUT_OF_MEMORY;
            goto done;
        }
        const double lim = best + TTD_CCD_DEFAULT_T_TOL;
        for (int i = 0; i < nw; ++i)
            for (size_t k = 0; k < J.workers[i].n; ++k)
                if (J.workers[i].hits[k].toi <= lim) {
                    out->pairs[out->count] = J.workers[i].hits[k];
                    out->flags |= out->pairs[out->count].flags;
                    ++out->count;
                }
        qsort(out->pairs, out->count, sizeof *out->pairs, pair_cmp);
    }
    out->toi = best;
done:
    if (J.workers != NULL) {
        for (int i = 0; i < J.nworkers; ++i) {
            free(J.workers[i].hits);
            free(J.workers[i].stack);
        }
        free(J.workers);
    }
    if (st != TTD_OK) {
        free(out->pairs);
        memset(out, 0, sizeof *out);
        out->toi = HUGE_VAL;
    }
    sweep_tree_free(&J.tree);
    sweep_tree_free(&J.qtree);
    free(J.leaves);
    free(J.tasks);
    grid_drop(&J); /* (the columns, made by the grid or the tree's path) */
    side_free(&da);
    if (!J.self)
        side_free(&db);
    return st;
}

/* SPDX-License-Identifier: MIT */
/* Building a mesh's hierarchy (mesh/mesh.h).
 *
 * Shape: a node with at most TTD_NODE_WIDTH triangles takes them as its children (a leaf); a
 * larger one deals its leaves (ceil(n / 8) of them, full) evenly to up to 8 children, and
 * orders its triangles into those groups by splitting the list of groups in halves, each time
 * at the matching rank of the centroids along the longest side of their bounding box. Each
 * group is a child (a triangle when alone, a node otherwise). As the group sizes depend on the
 * triangle count alone, so does every subtree's node count: node indices are laid out in
 * pre-order before anything is built, and the top subtrees are then built in parallel into
 * their own index ranges, with the same result on any number of threads.
 *
 * Bounds: an oriented box per child. A triangle's box has its longest edge and its normal as
 * axes, so that it is flat: against a nearly parallel neighbour the node test's bound is then
 * nearly the true distance, which is what keeps the candidate pairs of a query few (a box
 * around a triangle in the mesh's axes is as thick as the triangle is wide). A subtree's box has
 * the principal axes of its triangles' area (the covariance of the surface, Gottschalk's OBB
 * fit), with the extents of every vertex below it. All of this is computed in double; a float
 * mesh rounds the axes and centre to float and then recomputes the extents against the rounded
 * axes, rounded up, so that its boxes still hold every vertex. */
#define _POSIX_C_SOURCE 200809L
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "engine/parallel.h"
#include "mesh/memory.h"
#include "mesh/mesh.h"

/* An oriented box in double while building: centre (relative to the mesh origin), axes (row i =
 * axis i), half extents. */
typedef struct obb {
    double c[3], u[9], e[3];
} obb;

typedef struct builder {
    const struct ttd_mesh *mesh;
    int threads;          /* for the top of the tree (ttd_engine_config.threads) */
    double *pts;          /* 9 nt: each triangle's vertices relative to the origin, in double */
    double *cen;          /* 3 nt triangle centroids, relative */
    float *mom;           /* 10 nt triangle area moments (tri_moments), in float: they only
                           * choose the axes, and the extents are exact about any axes */
    uint32_t *idx;        /* the triangles in hierarchy order, as positions in the arrays above */
    uint32_t *order;      /* the triangle at each position (Morton order of the centroids) */
    const double *vrel;   /* while preparing: 3 nv vertices relative to the origin */
} builder;

/* A subtree to build: triangles idx[lo, hi) into node `node` (pre-order index). */
typedef struct subtree {
    size_t lo, hi;
    int32_t node;
} subtree;

/* A triangle's vertices. Each level of the build reads every triangle: one contiguous record
 * per triangle instead of three indirect vertex loads keeps that from waiting on memory. */
static void tri_vertices(const builder *B, uint32_t t, double p[3][3])
{
    memcpy(p, B->pts + 9 * (size_t)t, 9 * sizeof(double));
}

/* min and max for numbers that are not NaN (libm's fmin/fmax are calls) */
static double dmin(double a, double b)
{
    return a < b ? a : b;
}

static double dmax(double a, double b)
{
    return a > b ? a : b;
}

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void cross3(const double a[3], const double b[3], double out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

/* a / |a| into out; 0 when a is 0 (or so small that its square vanishes). */
static int normalize3(const double a[3], double out[3])
{
    const double m = dmax(fabs(a[0]), dmax(fabs(a[1]), fabs(a[2])));
    if (!(m > 0))
        return 0;
    const double im = 1 / m; /* reciprocals: a near-unit vector is all a box axis needs */
    const double b[3] = {a[0] * im, a[1] * im, a[2] * im};
    const double in = 1 / sqrt(dot3(b, b));
    for (int i = 0; i < 3; ++i)
        out[i] = b[i] * in;
    return 1;
}

/* Completes axes u[0] (unit) to an orthonormal frame: u[1] perpendicular, u[2] = u[0] x u[1]. */
static void complete_frame(double u[9])
{
    const double *a = u;
    /* the coordinate axis least aligned with a, made perpendicular to it */
    int m = 0;
    if (fabs(a[1]) < fabs(a[m])) m = 1;
    if (fabs(a[2]) < fabs(a[m])) m = 2;
    double w[3] = {0, 0, 0};
    w[m] = 1;
    const double d = dot3(w, a);
    double p[3] = {w[0] - d * a[0], w[1] - d * a[1], w[2] - d * a[2]};
    normalize3(p, u + 3);
    cross3(u, u + 3, u + 6);
}

/* A triangle's axes: its longest edge and its normal (flat box); a segment's: its direction; a
 * point's: the coordinate axes. */
static void triangle_axes(double p[3][3], double u[9])
{
    double e[3][3], len[3];
    for (int i = 0; i < 3; ++i) {
        for (int c = 0; c < 3; ++c)
            e[i][c] = p[(i + 1) % 3][c] - p[i][c];
        len[i] = dot3(e[i], e[i]);
    }
    int k = 0;
    if (len[1] > len[k]) k = 1;
    if (len[2] > len[k]) k = 2;
    if (!normalize3(e[k], u)) {
        static const double id[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
        memcpy(u, id, sizeof id);
        return;
    }
    double n[3];
    cross3(e[k], e[(k + 2) % 3], n);
    if (normalize3(n, u + 6)) {
        cross3(u + 6, u, u + 3);
        normalize3(u + 3, u + 3);
        return;
    }
    complete_frame(u);
}

/* Eigenvectors of the symmetric 3x3 matrix a (destroyed) by cyclic Jacobi rotations, as the rows
 * of u, largest eigenvalue first. */
static void eigen_sym3(double a[3][3], double u[9])
{
    double v[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    for (int sweep = 0; sweep < 50; ++sweep) {
        const double off = fabs(a[0][1]) + fabs(a[0][2]) + fabs(a[1][2]);
        const double diag = fabs(a[0][0]) + fabs(a[1][1]) + fabs(a[2][2]);
        /* axes to 1e-9: a box is fitted to its vertices about whatever axes it gets, so
         * further sweeps would only tilt it by less than that */
        if (!(off > 1e-9 * diag))
            break;
        for (int p = 0; p < 2; ++p)
            for (int q = p + 1; q < 3; ++q) {
                if (a[p][q] == 0)
                    continue;
                const double theta = (a[q][q] - a[p][p]) / (2 * a[p][q]);
                const double t = (theta >= 0 ? 1.0 : -1.0) / (fabs(theta) + sqrt(theta * theta + 1));
                const double c = 1 / sqrt(t * t + 1), s = t * c;
                for (int k = 0; k < 3; ++k) { /* columns p, q of a */
                    const double akp = a[k][p], akq = a[k][q];
                    a[k][p] = c * akp - s * akq;
                    a[k][q] = s * akp + c * akq;
                }
                for (int k = 0; k < 3; ++k) { /* rows p, q */
                    const double apk = a[p][k], aqk = a[q][k];
                    a[p][k] = c * apk - s * aqk;
                    a[q][k] = s * apk + c * aqk;
                }
                for (int k = 0; k < 3; ++k) {
                    const double vkp = v[k][p], vkq = v[k][q];
                    v[k][p] = c * vkp - s * vkq;
                    v[k][q] = s * vkp + c * vkq;
                }
            }
    }
    int order[3] = {0, 1, 2};
    for (int i = 0; i < 3; ++i)
        for (int j = i + 1; j < 3; ++j)
            if (a[order[j]][order[j]] > a[order[i]][order[i]]) {
                const int t = order[i];
                order[i] = order[j];
                order[j] = t;
            }
    for (int i = 0; i < 2; ++i) {
        const double col[3] = {v[0][order[i]], v[1][order[i]], v[2][order[i]]};
        normalize3(col, u + 3 * i);
    }
    /* the third axis exactly perpendicular to the first two (they are to rounding) */
    double w[3];
    cross3(u, u + 3, w);
    normalize3(w, u + 6);
    cross3(u + 6, u, u + 3);
    normalize3(u + 3, u + 3);
}

/* Upper-triangle entries (xx, xy, xz, yy, yz, zz) of a symmetric 3x3 matrix. */
static const int sym_r[6] = {0, 0, 0, 1, 1, 2}, sym_c[6] = {0, 1, 2, 1, 2, 2};

/* A triangle's area moments, once per build (each level sums them): its area a, a g (g its
 * centroid) and the second moment of a uniform triangle, a (9 g g^T + sum p p^T) / 12, as 6
 * entries. */
static void tri_moments(double p[3][3], const double g[3], float mom[10])
{
    double e1[3], e2[3], x[3];
    for (int c = 0; c < 3; ++c) {
        e1[c] = p[1][c] - p[0][c];
        e2[c] = p[2][c] - p[0][c];
    }
    cross3(e1, e2, x);
    const double a = 0.5 * sqrt(dot3(x, x));
    mom[0] = (float)a;
    for (int c = 0; c < 3; ++c)
        mom[1 + c] = (float)(a * g[c]);
    for (int k = 0; k < 6; ++k) {
        const int r = sym_r[k], c = sym_c[k];
        mom[4 + k] = (float)(a / 12 * (9 * g[r] * g[c] + p[0][r] * p[0][c] + p[1][r] * p[1][c] + p[2][r] * p[2][c]));
    }
}

/* Principal axes of the surface of triangles idx[lo, hi): eigenvectors of the covariance of
 * their area; of their vertices when their area is 0. */
static void surface_axes(const builder *B, size_t lo, size_t hi, double u[9])
{
    double m[10] = {0};
    for (size_t i = lo; i < hi; ++i) {
        const float *t = B->mom + 10 * (size_t)B->idx[i];
        for (int k = 0; k < 10; ++k)
            m[k] += (double)t[k];
    }
    if (!(m[0] > 0)) { /* no area at all: the vertices' covariance */
        for (int k = 0; k < 10; ++k)
            m[k] = 0;
        for (size_t i = lo; i < hi; ++i) {
            double p[3][3];
            tri_vertices(B, B->idx[i], p);
            for (int v = 0; v < 3; ++v) {
                m[0] += 1;
                for (int c = 0; c < 3; ++c)
                    m[1 + c] += p[v][c];
                for (int k = 0; k < 6; ++k)
                    m[4 + k] += p[v][sym_r[k]] * p[v][sym_c[k]];
            }
        }
    }
    double cov[3][3];
    for (int k = 0; k < 6; ++k) {
        const int r = sym_r[k], c = sym_c[k];
        cov[r][c] = cov[c][r] = m[4 + k] / m[0] - (m[1 + r] / m[0]) * (m[1 + c] / m[0]);
    }
    eigen_sym3(cov, u);
}

/* The box with axes u around the vertices of triangles idx[lo, hi): centre and extents from
 * the range of their projections. */
static void fit_extents(const builder *B, size_t lo, size_t hi, obb *b)
{
    /* the bounds in locals, not an array the compiler keeps in memory: this loop is a fifth of
     * a build (every vertex of every triangle, on every level) */
    const double *u = b->u;
    double mn0 = INFINITY, mn1 = INFINITY, mn2 = INFINITY, mx0 = -INFINITY, mx1 = -INFINITY, mx2 = -INFINITY;
    for (size_t i = lo; i < hi; ++i) {
        const double *p = B->pts + 9 * (size_t)B->idx[i];
        for (int k = 0; k < 9; k += 3) {
            const double d0 = u[0] * p[k] + u[1] * p[k + 1] + u[2] * p[k + 2];
            const double d1 = u[3] * p[k] + u[4] * p[k + 1] + u[5] * p[k + 2];
            const double d2 = u[6] * p[k] + u[7] * p[k + 1] + u[8] * p[k + 2];
            mn0 = dmin(mn0, d0);
            mx0 = dmax(mx0, d0);
            mn1 = dmin(mn1, d1);
            mx1 = dmax(mx1, d1);
            mn2 = dmin(mn2, d2);
            mx2 = dmax(mx2, d2);
        }
    }
    const double mn[3] = {mn0, mn1, mn2}, mx[3] = {mx0, mx1, mx2};
    for (int c = 0; c < 3; ++c)
        b->c[c] = 0;
    for (int a = 0; a < 3; ++a) {
        const double mid = 0.5 * (mn[a] + mx[a]);
        b->e[a] = 0.5 * (mx[a] - mn[a]);
        for (int c = 0; c < 3; ++c)
            b->c[c] += mid * b->u[3 * a + c];
    }
}

static void fit_box(const builder *B, size_t lo, size_t hi, obb *b)
{
    if (hi - lo == 1) {
        double p[3][3];
        tri_vertices(B, B->idx[lo], p);
        triangle_axes(p, b->u);
    } else {
        surface_axes(B, lo, hi, b->u);
    }
    fit_extents(B, lo, hi, b);
}

/* Stores box b in slot j of node n, with child `child`. A double mesh stores it as it is; a
 * float mesh rounds axes and centre to float, then takes the extents of the vertices about the
 * rounded centre along the rounded axes, rounded up, so the stored box still holds them. */
static void store_box(const builder *B, int32_t n, int j, const obb *b, int32_t child, size_t lo, size_t hi)
{
    const struct ttd_mesh *m = B->mesh;
    if (m->bytes == 8) {
        ttd_node_d *node = (ttd_node_d *)m->nodes + n;
        for (int i = 0; i < 3; ++i) {
            node->c[i][j] = b->c[i];
            node->e[i][j] = b->e[i];
        }
        for (int i = 0; i < 9; ++i)
            node->u[i][j] = b->u[i];
        node->child[j] = child;
        return;
    }
    ttd_node_f *node = (ttd_node_f *)m->nodes + n;
    double uf[9], cf[3], e[3] = {0, 0, 0};
    for (int i = 0; i < 9; ++i)
        uf[i] = (double)(float)b->u[i];
    for (int i = 0; i < 3; ++i)
        cf[i] = (double)(float)b->c[i];
    for (size_t i = lo; i < hi; ++i) {
        double p[3][3];
        tri_vertices(B, B->idx[i], p);
        for (int k = 0; k < 3; ++k) {
            const double r[3] = {p[k][0] - cf[0], p[k][1] - cf[1], p[k][2] - cf[2]};
            for (int a = 0; a < 3; ++a)
                e[a] = dmax(e[a], fabs(dot3(uf + 3 * a, r)));
        }
    }
    for (int i = 0; i < 3; ++i) {
        node->c[i][j] = (float)cf[i];
        /* one float ulp up, and a relative double margin for the products above */
        node->e[i][j] = nextafterf((float)(e[i] * (1 + 8 * DBL_EPSILON)), INFINITY);
    }
    for (int i = 0; i < 9; ++i)
        node->u[i][j] = (float)uf[i];
    node->child[j] = child;
}

/* ---- shape ---------------------------------------------------------------------------- */

/* The groups a node of n > TTD_NODE_WIDTH triangles splits into: its leaves (ceil(n / 8) groups
 * of at most 8 triangles) dealt as evenly as possible to at most 8 children, each child a
 * whole number of full leaves but the last. So leaves are full and nodes have 8 children
 * wherever the count allows: the node test always bounds 8 boxes, empty slots are wasted work.
 * Returns the number of groups; g[j] is group j's triangle count. */
static int group_sizes(size_t n, size_t g[8])
{
    const size_t leaves = (n + TTD_NODE_WIDTH - 1) / TTD_NODE_WIDTH;
    if (leaves <= TTD_NODE_WIDTH) {
        /* children are leaves: n triangles dealt into `leaves` groups of nearly equal size */
        for (size_t j = 0; j < leaves; ++j)
            g[j] = n / leaves + (j < n % leaves ? 1 : 0);
        return (int)leaves;
    }
    size_t rest = n;
    for (size_t j = 0; j < 8; ++j) {
        const size_t lj = leaves / 8 + (j < leaves % 8 ? 1 : 0);
        g[j] = lj * TTD_NODE_WIDTH < rest ? lj * TTD_NODE_WIDTH : rest;
        rest -= g[j];
    }
    return 8;
}

/* Nodes of the subtree over n triangles (n >= 2; a lone triangle is a child, not a node). */
static size_t count_nodes(size_t n)
{
    if (n <= TTD_NODE_WIDTH)
        return 1;
    size_t g[8], total = 1;
    const int ng = group_sizes(n, g);
    for (int j = 0; j < ng; ++j)
        if (g[j] > 1)
            total += count_nodes(g[j]);
    return total;
}

/* Reorders idx[lo, hi) so that idx[k] holds the triangle whose centroid coordinate `axis` would
 * be there in sorted order, none larger before it and none smaller after (quickselect with a
 * three-way partition, which keeps runs of equal coordinates, common in grids, linear; the
 * pivot comes from a hash of the range, so the result is deterministic). */
static void select_kth(builder *B, size_t lo, size_t hi, size_t k, int axis)
{
    uint32_t *idx = B->idx;
    const double *cen = B->cen;
    while (hi - lo > 1) {
        uint64_t h = (uint64_t)lo * 0x9E3779B97F4A7C15ull ^ (uint64_t)hi * 0xBF58476D1CE4E5B9ull;
        h ^= h >> 31;
        const double pivot = cen[3 * (size_t)idx[lo + (size_t)(h % (hi - lo))] + axis];
        size_t lt = lo, i = lo, gt = hi;
        while (i < gt) {
            const double x = cen[3 * (size_t)idx[i] + axis];
            if (x < pivot) {
                const uint32_t t = idx[lt];
                idx[lt++] = idx[i];
                idx[i++] = t;
            } else if (x > pivot) {
                const uint32_t t = idx[--gt];
                idx[gt] = idx[i];
                idx[i] = t;
            } else {
                ++i;
            }
        }
        /* [lo, lt) < pivot, [lt, gt) == pivot, [gt, hi) > pivot */
        if (k < lt)
            hi = lt;
        else if (k >= gt)
            lo = gt;
        else
            return;
    }
}

/* Splits idx[lo, hi) at rank lo + k along the longest side of its centroids' box. */
static void split_at(builder *B, size_t lo, size_t hi, size_t k)
{
    double mn[3] = {INFINITY, INFINITY, INFINITY}, mx[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t i = lo; i < hi; ++i)
        for (int c = 0; c < 3; ++c) {
            mn[c] = dmin(mn[c], B->cen[3 * (size_t)B->idx[i] + c]);
            mx[c] = dmax(mx[c], B->cen[3 * (size_t)B->idx[i] + c]);
        }
    int axis = 0;
    for (int c = 1; c < 3; ++c)
        if (mx[c] - mn[c] > mx[axis] - mn[axis])
            axis = c;
    select_kth(B, lo, hi, lo + k, axis);
}

/* Orders idx[lo, hi) into groups g[0..ng) by halving the list of groups: the first half of the
 * groups' triangles from the second along the longest side, and again within each half. */
static void split_groups(builder *B, size_t lo, const size_t *g, int ng)
{
    if (ng < 2)
        return;
    const int h = (ng + 1) / 2;
    size_t left = 0, all = 0;
    for (int j = 0; j < ng; ++j) {
        all += g[j];
        if (j < h)
            left += g[j];
    }
    split_at(B, lo, lo + all, left);
    split_groups(B, lo, g, h);
    split_groups(B, lo + left, g + h, ng - h);
}

/* The boxes of groups g[0..ng) starting at idx[lo]; at the top of the tree (parallel), one
 * group per task. */
typedef struct group_job {
    const builder *B;
    size_t lo[8], hi[8];
    obb *boxes;
} group_job;

static void fit_group(void *ctx, size_t j, int worker)
{
    (void)worker;
    group_job *G = ctx;
    fit_box(G->B, G->lo[j], G->hi[j], &G->boxes[j]);
}

static void fit_groups(const builder *B, size_t lo, const size_t *g, int ng, obb *boxes, int parallel)
{
    group_job G = {.B = B, .boxes = boxes};
    for (int j = 0; j < ng; ++j) {
        G.lo[j] = lo;
        G.hi[j] = lo + g[j];
        lo += g[j];
    }
    if (parallel)
        ttd_parallel_tasks((size_t)ng, B->threads, fit_group, &G);
    else
        for (int j = 0; j < ng; ++j)
            fit_group(&G, (size_t)j, 0);
}

/* Builds node n over idx[lo, hi). Children that are subtrees get the indices after n in
 * pre-order; when `defer` is given, they are listed there instead of being built (the top of
 * the tree, whose subtrees are then built in parallel). Returns the nodes used. */
static size_t build_node(builder *B, int32_t n, size_t lo, size_t hi, subtree *defer, size_t *ndefer)
{
    const size_t count = hi - lo;
    int32_t next = n + 1;
    size_t g[8] = {0};
    int ng = 0;
    if (count <= TTD_NODE_WIDTH) {
        for (size_t j = 0; j < count; ++j)
            g[ng++] = 1;
    } else {
        ng = group_sizes(count, g);
        split_groups(B, lo, g, ng);
    }
    obb boxes[8];
    fit_groups(B, lo, g, ng, boxes, defer != NULL);
    size_t at = lo;
    for (int j = 0; j < ng; ++j) {
        const obb b = boxes[j];
        if (g[j] == 1) {
            store_box(B, n, j, &b, -1 - (int32_t)B->order[B->idx[at]], at, at + 1);
        } else {
            store_box(B, n, j, &b, next, at, at + g[j]);
            if (defer) {
                defer[(*ndefer)++] = (subtree){at, at + g[j], next};
            } else {
                build_node(B, next, at, at + g[j], NULL, NULL);
            }
            next += (int32_t)count_nodes(g[j]);
        }
        at += g[j];
    }
    /* unused slots hold zeros (the node test reads all of them) */
    const obb none = {{0, 0, 0}, {0, 0, 0, 0, 0, 0, 0, 0, 0}, {0, 0, 0}};
    for (int j = ng; j < TTD_NODE_WIDTH; ++j)
        store_box(B, n, j, &none, 0, lo, lo);
    if (B->mesh->bytes == 8)
        ((ttd_node_d *)B->mesh->nodes)[n].count = (int32_t)ng;
    else
        ((ttd_node_f *)B->mesh->nodes)[n].count = (int32_t)ng;
    return (size_t)(next - n);
}

static void build_subtree(void *ctx, size_t i, int worker)
{
    (void)worker;
    void **c = ctx;
    builder *B = c[0];
    const subtree *t = (const subtree *)c[1] + i;
    build_node(B, t->node, t->lo, t->hi, NULL, NULL);
}

/* ---- the mesh --------------------------------------------------------------------------- */

/* Triangles per block of the preparation pass. */
#define PREP_BLOCK 4096

/* Each position's triangle's vertices, centroid and moments, for block b of positions. */
static void prepare_triangles(void *ctx, size_t b, int worker)
{
    (void)worker;
    builder *B = ctx;
    const uint32_t *tris = B->mesh->tris;
    const size_t i1 = (b + 1) * PREP_BLOCK < B->mesh->nt ? (b + 1) * PREP_BLOCK : B->mesh->nt;
    for (size_t i = b * PREP_BLOCK; i < i1; ++i) {
        const size_t t = B->order[i];
        double p[3][3];
        B->idx[i] = (uint32_t)i;
        for (int k = 0; k < 3; ++k)
            memcpy(p[k], B->vrel + 3 * (size_t)tris[3 * t + (size_t)k], 3 * sizeof(double));
        memcpy(B->pts + 9 * i, p, sizeof p);
        for (int c = 0; c < 3; ++c)
            B->cen[3 * i + c] = (p[0][c] + p[1][c] + p[2][c]) / 3;
        tri_moments(p, B->cen + 3 * i, B->mom + 10 * i);
    }
}

/* 10 bits of x in every third bit. */
static uint32_t spread3(uint32_t x)
{
    x &= 0x3ffu;
    x = (x | (x << 16)) & 0x030000ffu;
    x = (x | (x << 8)) & 0x0300f00fu;
    x = (x | (x << 4)) & 0x030c30c3u;
    x = (x | (x << 2)) & 0x09249249u;
    return x;
}

/* The triangles in Morton order of their centroids (1024 cells per axis of the vertices' box),
 * ties in index order: the splits below then find a node's triangles close together in memory,
 * which at a million triangles decides the build's speed more than its arithmetic. Radix sort
 * of (code, index) pairs. Returns 0 on allocation failure. */
static int morton_order(builder *B, const double lo[3], const double hi[3])
{
    const size_t nt = B->mesh->nt;
    const uint32_t *tris = B->mesh->tris;
    uint64_t *key = ttd_big_alloc(nt * sizeof *key), *tmp = ttd_big_alloc(nt * sizeof *tmp);
    if (!key || !tmp) {
        free(key);
        free(tmp);
        return 0;
    }
    double scale[3];
    for (int c = 0; c < 3; ++c)
        scale[c] = hi[c] > lo[c] ? 1023.0 / (hi[c] - lo[c]) : 0;
    for (size_t t = 0; t < nt; ++t) {
        uint32_t code = 0;
        for (int c = 0; c < 3; ++c) {
            double g = 0;
            for (int k = 0; k < 3; ++k)
                g += B->vrel[3 * (size_t)tris[3 * t + (size_t)k] + (size_t)c];
            const double q = (g / 3 - lo[c]) * scale[c];
            code |= spread3(q > 0 ? (uint32_t)(q < 1023 ? q : 1023) : 0u) << c;
        }
        key[t] = (uint64_t)code << 32 | (uint64_t)t;
    }
    for (int shift = 32; shift < 64; shift += 8) { /* LSD radix sort on the code's bytes */
        size_t count[257] = {0};
        for (size_t t = 0; t < nt; ++t)
            ++count[((key[t] >> shift) & 0xffu) + 1];
        for (int d = 0; d < 256; ++d)
            count[d + 1] += count[d];
        for (size_t t = 0; t < nt; ++t)
            tmp[count[(key[t] >> shift) & 0xffu]++] = key[t];
        uint64_t *sw = key;
        key = tmp;
        tmp = sw;
    }
    for (size_t t = 0; t < nt; ++t)
        B->order[t] = (uint32_t)key[t];
    free(key);
    free(tmp);
    return 1;
}

void ttd_mesh_free(struct ttd_mesh *mesh)
{
    if (mesh == NULL)
        return;
    free(mesh->verts);
    free(mesh->tris);
    free(mesh->nodes);
    free(mesh);
}

ttd_status ttd_mesh_build(const ttd_engine_config *cfg, int bytes, const void *verts, size_t nv,
                          const uint32_t *tris, size_t nt, struct ttd_mesh **out)
{
    *out = NULL;
    struct ttd_mesh *m = calloc(1, sizeof *m);
    builder B = {.mesh = m, .threads = cfg->threads};
    double *vrel = NULL;
    subtree *defer = NULL;
    if (m == NULL)
        goto nomem;
    m->bytes = bytes;
    m->nv = nv;
    m->nt = nt;
    /* nodes: the root's box holder (node 0) and the tree from node 1 when there is more than
     * one triangle */
    m->nnodes = 1 + (nt > 1 ? count_nodes(nt) : 0);
    const size_t node_bytes = bytes == 8 ? sizeof(ttd_node_d) : sizeof(ttd_node_f);
    const size_t nodes_size = (m->nnodes * node_bytes + 63) / 64 * 64;
    m->verts = ttd_big_alloc(3 * nv * (size_t)bytes);
    m->tris = ttd_big_alloc(3 * nt * sizeof(uint32_t));
    m->nodes = ttd_big_alloc(nodes_size);
    vrel = ttd_big_alloc(3 * nv * sizeof(double));
    B.cen = ttd_big_alloc(3 * nt * sizeof(double));
    B.idx = ttd_big_alloc(nt * sizeof(uint32_t));
    B.pts = ttd_big_alloc(9 * nt * sizeof(double));
    B.mom = ttd_big_alloc(10 * nt * sizeof(float));
    B.order = ttd_big_alloc(nt * sizeof(uint32_t));
    if (!m->verts || !m->tris || !m->nodes || !vrel || !B.cen || !B.idx || !B.pts || !B.mom || !B.order)
        goto nomem;
    memcpy(m->verts, verts, 3 * nv * (size_t)bytes);
    memcpy(m->tris, tris, 3 * nt * sizeof(uint32_t));
    memset(m->nodes, 0, node_bytes); /* node 0: the root's box, slot 0 only */

    /* origin: the centre of the vertices' bounding box; radius: how far the farthest vertex is */
    double mn[3] = {INFINITY, INFINITY, INFINITY}, mx[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t i = 0; i < 3 * nv; ++i) {
        const double x = bytes == 8 ? ((const double *)verts)[i] : (double)((const float *)verts)[i];
        vrel[i] = x;
        mn[i % 3] = dmin(mn[i % 3], x);
        mx[i % 3] = dmax(mx[i % 3], x);
    }
    for (int c = 0; c < 3; ++c)
        m->origin[c] = 0.5 * mn[c] + 0.5 * mx[c]; /* halves first: no overflow near DBL_MAX */
    double r2 = 0;
    for (size_t i = 0; i < nv; ++i) {
        double d2 = 0;
        for (int c = 0; c < 3; ++c) {
            vrel[3 * i + c] -= m->origin[c];
            d2 += vrel[3 * i + c] * vrel[3 * i + c];
        }
        r2 = dmax(r2, d2);
    }
    m->radius = sqrt(r2) * (1 + 4 * DBL_EPSILON);
    B.vrel = vrel;
    double vlo[3], vhi[3];
    for (int c = 0; c < 3; ++c) {
        vlo[c] = mn[c] - m->origin[c];
        vhi[c] = mx[c] - m->origin[c];
    }
    if (!morton_order(&B, vlo, vhi))
        goto nomem;
    ttd_parallel_for((nt + PREP_BLOCK - 1) / PREP_BLOCK, cfg->threads, prepare_triangles, &B);
    free(vrel);
    vrel = NULL;

    /* node 0, slot 0: the root's box around everything, with the tree (or the triangle) below */
    obb root;
    fit_box(&B, 0, nt, &root);
    store_box(&B, 0, 0, &root, nt > 1 ? 1 : -1, 0, nt);
    if (bytes == 8)
        ((ttd_node_d *)m->nodes)[0].count = 1;
    else
        ((ttd_node_f *)m->nodes)[0].count = 1;
    if (nt > 1) {
        /* The top node's split in this thread and its boxes in parallel, then its subtrees
         * (8) in parallel; with more than 8 workers, one level more first (64 subtrees). */
        defer = malloc(64 * sizeof *defer);
        subtree *level = malloc(8 * sizeof *level);
        if (!defer || !level) {
            free(level);
            goto nomem;
        }
        size_t nlevel = 0, ndefer = 0;
        build_node(&B, 1, 0, nt, level, &nlevel);
        if (ttd_parallel_task_workers(64, cfg->threads) > 8) {
            for (size_t i = 0; i < nlevel; ++i)
                build_node(&B, level[i].node, level[i].lo, level[i].hi, defer, &ndefer);
        } else {
            memcpy(defer, level, nlevel * sizeof *level);
            ndefer = nlevel;
        }
        free(level);
        void *ctx[2] = {&B, defer};
        ttd_parallel_tasks(ndefer, cfg->threads, build_subtree, ctx);
    }
    free(defer);
    free(B.cen);
    free(B.idx);
    free(B.pts);
    free(B.mom);
    free(B.order);
    *out = m;
    return TTD_OK;
nomem:
    free(defer);
    free(vrel);
    if (m) {
        free(B.cen);
        free(B.idx);
        free(B.pts);
        free(B.mom);
        free(B.order);
    }
    ttd_mesh_free(m);
    return TTD_ERR_OUT_OF_MEMORY;
}

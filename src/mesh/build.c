/* SPDX-License-Identifier: MIT */
/* Building a mesh's hierarchy (mesh/mesh.h), in two passes over the triangles.
 *
 * Shape: a node with at most TTD_NODE_WIDTH triangles takes them as its children (a leaf); a
 * larger one deals its leaves (ceil(n / 8) of them, full) evenly to up to 8 children, and
 * orders its triangles into those groups by splitting the list of groups in halves, each time
 * at the matching rank of the centroids along the longest side of their bounding box. Each
 * group is a child (a triangle when alone, a node otherwise). As the group sizes depend on the
 * triangle count alone, so does every subtree's node count: node indices are laid out in
 * pre-order before anything is built, and the top subtrees are built in parallel into their own
 * index ranges, with the same result on any number of threads. The splits permute an array of
 * 16-byte records (centroid, triangle) in place, so that a node's triangles are a contiguous
 * run of them: every pass reads memory in order.
 *
 * Bounds, once the order is known: each triangle's vertices are copied into that order, one
 * array per coordinate, and the boxes are fitted bottom-up, each node's over a contiguous run of
 * those arrays. A triangle's box has its longest edge and its normal as axes, so that it is
 * flat: against a nearly parallel neighbour the node test's bound is then nearly the true
 * distance, which is what keeps the candidate pairs of a query few (a box around a triangle in
 * the mesh's axes is as thick as the triangle is wide). A subtree's box has the principal axes
 * of its triangles' area (the covariance of the surface, Gottschalk's OBB fit; the area moments
 * are summed up the tree, children to parent), with the extents of every vertex below it. All
 * of this is computed in double; a float mesh rounds the axes and centre to float and then
 * recomputes the extents against the rounded axes, rounded up, so that its boxes still hold
 * every vertex.
 *
 * Measured on the 1M-triangle torus (docs/mesh-queries.md): the build's time is memory, not
 * arithmetic; hence the contiguous runs, and the large arrays on huge pages (mesh/memory.h). */
#define _POSIX_C_SOURCE 200809L
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "core/vec3.h"
#include "engine/dispatch.h"
#include "engine/parallel.h"
#include "mesh/memory.h"
#include "mesh/mesh.h"

/* An oriented box in double while building: centre (relative to the mesh origin), axes (row i =
 * axis i), half extents. */
typedef struct obb {
    double c[3], u[9], e[3];
} obb;

/* A triangle while the shape is decided: its centroid relative to the origin, scaled to the
 * mesh's radius and rounded to float (the splits only compare centroids; 16 bytes a record
 * halves the memory they move), and its index, which breaks ties: no two records compare equal. */
typedef struct trirec {
    float c[3];
    uint32_t t;
} trirec;

/* A triangle's area moments (tri_moments), and sums of them. */
typedef struct moments {
    double m[10];
} moments;

typedef struct builder {
    const struct ttd_mesh *mesh;
    int threads;          /* for the top of the tree (ttd_engine_config.threads) */
    const double *vrel;   /* 3 nv vertices relative to the origin */
    trirec *rec;          /* shape pass: the triangles, permuted into hierarchy order */
    double unit;          /* a power of two near 1 / radius: the records' scale */
    uint32_t *ord;        /* bounds pass: the triangle at each position of that order */
    double *p[9];         /* bounds pass: p[3k + c][i] = coordinate c of vertex k of ord[i] */
    int refit;            /* the shape is kept (a refit): the shape pass only lists subtrees */
} builder;

/* A subtree: positions [lo, hi) into node `node` (pre-order index). */
typedef struct subtree {
    size_t lo, hi;
    int32_t node;
} subtree;

/* Subtrees built in parallel: the top node's (8), or with more than 8 workers one level more
 * (64). The levels above them are done in the calling thread (their boxes' fits in parallel). */
static int parallel_depth(int threads)
{
    return ttd_parallel_task_workers(64, threads) > 8 ? 2 : 1;
}

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

/* a / |a| into out; 0 when a is 0 (or so small that its square vanishes). */
static int normalize3(const double a[3], double out[3])
{
    const double d = dot3(a, a);
    if (d > 0x1p-900 && d < 0x1p900) { /* the common case: no scaling needed */
        const double in = 1 / sqrt(d);
        for (int i = 0; i < 3; ++i)
            out[i] = a[i] * in;
        return 1;
    }
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
    ttd_cross3(u, u + 3, u + 6);
}

/* u[6..8] (unit) made perpendicular to u[0..2] (unit) by Gram-Schmidt, twice: one pass leaves
 * an error of eps over the sine of their angle, the second brings it to a few eps ("twice is
 * enough"). Returns 0 when the two are too close to parallel for the result to mean anything
 * (the normal of a needle or of a collinear triangle can be mostly rounding error). */
static int orthogonalize(double u[9])
{
    for (int pass = 0; pass < 2; ++pass) {
        const double d = dot3(u, u + 6);
        double w[3];
        for (int c = 0; c < 3; ++c)
            w[c] = u[6 + c] - d * u[c];
        if (!(dot3(w, w) > 0.0625) || !normalize3(w, u + 6))
            return 0;
    }
    return 1;
}

/* A triangle's axes: its longest edge and its normal (flat box); a segment's: its direction; a
 * point's: the coordinate axes. The frame is orthonormal to a few eps whatever the triangle:
 * the computed normal of a thin triangle is not perpendicular to its edge (its cross product
 * is mostly rounding), so it is made so, or replaced by any perpendicular direction. A box only
 * has to hold its triangle (fit_extents sees to that about any axes); orthonormal axes are what
 * the node test's bound assumes (docs/mesh-queries.md, section 4). *area2 gets twice the
 * triangle's area (the length of its edges' cross product, to rounding; 0 when it has none to
 * speak of): the normal u[6..8] times it is its oriented normal, the same way round for every
 * triangle (each takes -(p1 - p0) x (p2 - p0) in its vertices' order). */
static void triangle_axes(double p[3][3], double u[9], double *area2)
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
    *area2 = 0;
    if (!normalize3(e[k], u)) {
        static const double id[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
        memcpy(u, id, sizeof id);
        return;
    }
    double n[3];
    ttd_cross3(e[k], e[(k + 2) % 3], n);
    if (!normalize3(n, u + 6)) {
        complete_frame(u);
        return;
    }
    *area2 = dot3(n, u + 6); /* |n|, twice the area, to rounding: a refit's sums (fitsum) */
    /* the common case, a triangle that is not thin: the computed normal is perpendicular to the
     * edge within 2 eps already, and so is their cross product, of length 1 within 3 u; the
     * frame is orthonormal to 2 eps as it is (half of a refit's time was these square roots) */
    if (fabs(dot3(u, u + 6)) <= 2 * DBL_EPSILON) {
        ttd_cross3(u + 6, u, u + 3);
        return;
    }
    if (orthogonalize(u)) {
        ttd_cross3(u + 6, u, u + 3);
        normalize3(u + 3, u + 3);
        return;
    }
    *area2 = 0; /* the normal was rounding noise */
    complete_frame(u);
}

/* Eigenvectors of the symmetric 3x3 matrix a (destroyed) by cyclic Jacobi rotations, as the rows
 * of u, largest eigenvalue first. start (rows: unit, orthonormal to a few eps) or NULL: the
 * rotations start from those axes instead of the coordinate axes (a refit starts from a box's
 * axes before its triangles moved, which are near the new ones: a sweep or none instead of three
 * or four), and where they need none, they are the answer as they are, in their order. */
static void eigen_sym3(double a[3][3], double u[9], const double *start)
{
    double v[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    if (start != NULL) { /* a <- S a S^T, v <- S^T */
        double t[3][3];
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                t[i][j] = 0;
                for (int k = 0; k < 3; ++k)
                    t[i][j] += a[i][k] * start[3 * j + k];
                v[i][j] = start[3 * j + i];
            }
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                a[i][j] = 0;
                for (int k = 0; k < 3; ++k)
                    a[i][j] += start[3 * i + k] * t[k][j];
            }
    }
    for (int sweep = 0; sweep < 50; ++sweep) {
        const double off = fabs(a[0][1]) + fabs(a[0][2]) + fabs(a[1][2]);
        const double diag = fabs(a[0][0]) + fabs(a[1][1]) + fabs(a[2][2]);
        /* axes to about 1e-6 (1e-3 from a start: a refit's box turns with its triangles, and
         * its axes are the last fit's unless they moved by more): a box is fitted to its
         * vertices about whatever axes it gets, so further sweeps would only tilt it by less
         * than that */
        if (!(off > (start ? 1e-3 : 1e-6) * diag)) {
            if (start != NULL && sweep == 0) { /* the start's axes still do, as they are */
                memcpy(u, start, 9 * sizeof *u);
                return;
            }
            break;
        }
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
    ttd_cross3(u, u + 3, w);
    normalize3(w, u + 6);
    ttd_cross3(u + 6, u, u + 3);
    normalize3(u + 3, u + 3);
}

/* Upper-triangle entries (xx, xy, xz, yy, yz, zz) of a symmetric 3x3 matrix. */

/* Upper-triangle entries (xx, xy, xz, yy, yz, zz) of a symmetric 3x3 matrix. */
static const int sym_r[6] = {0, 0, 0, 1, 1, 2}, sym_c[6] = {0, 1, 2, 1, 2, 2};

/* A triangle's area moments: its area a, a g (g its centroid) and the second moment of a
 * uniform triangle, a (9 g g^T + sum p p^T) / 12, as 6 entries. */
static void tri_moments(double p[3][3], moments *mo)
{
    double e1[3], e2[3], x[3], g[3];
    for (int c = 0; c < 3; ++c) {
        e1[c] = p[1][c] - p[0][c];
        e2[c] = p[2][c] - p[0][c];
        g[c] = (p[0][c] + p[1][c] + p[2][c]) / 3;
    }
    ttd_cross3(e1, e2, x);
    const double a = 0.5 * sqrt(dot3(x, x));
    double *m = mo->m;
    m[0] = a;
    for (int c = 0; c < 3; ++c)
        m[1 + c] = a * g[c];
    for (int k = 0; k < 6; ++k) {
        const int r = sym_r[k], c = sym_c[k];
        m[4 + k] = a / 12 * (9 * g[r] * g[c] + p[0][r] * p[0][c] + p[1][r] * p[1][c] + p[2][r] * p[2][c]);
    }
}

/* The vertices of the triangle at position i of the hierarchy order. */
static void pos_vertices(const builder *B, size_t i, double p[3][3])
{
    for (int k = 0; k < 3; ++k)
        for (int c = 0; c < 3; ++c)
            p[k][c] = B->p[3 * k + c][i];
}

/* Principal axes of the surface of positions [lo, hi) from its area moments m: eigenvectors of
 * the covariance of the area; of the vertices when the area is 0 (start: as eigen_sym3's). */
static void surface_axes(const builder *B, size_t lo, size_t hi, const moments *mo, const double *start, double u[9])
{
    double m[10];
    memcpy(m, mo->m, sizeof m);
    if (!(m[0] > 0)) { /* no area at all: the vertices' covariance */
        for (int k = 0; k < 10; ++k)
            m[k] = 0;
        for (size_t i = lo; i < hi; ++i) {
            double p[3][3];
            pos_vertices(B, i, p);
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
    eigen_sym3(cov, u, start);
}

/* Box b's centre and extents (its axes b->u) from the range [mn[a], mx[a]] of its vertices'
 * projections on each axis (fit_extents; a refit's leaf_span in lanes gives the same range). */
static void span_extents(const double mn[3], const double mx[3], double radius, obb *b)
{
    for (int c = 0; c < 3; ++c)
        b->c[c] = 0;
    for (int a = 0; a < 3; ++a) {
        const double mid = 0.5 * (mn[a] + mx[a]);
        for (int c = 0; c < 3; ++c)
            b->c[c] += mid * b->u[3 * a + c];
    }
    const double c1 = fabs(b->c[0]) + fabs(b->c[1]) + fabs(b->c[2]);
    const double slack = 4 * DBL_EPSILON * (2 * radius + c1);
    for (int a = 0; a < 3; ++a) {
        const double pc = dot3(b->u + 3 * a, b->c);
        b->e[a] = dmax(mx[a] - pc, pc - mn[a]) + slack;
    }
}

/* The box with axes b->u around the vertices of positions [lo, hi): centre and extents from the
 * range of their projections. Every level of the tree runs this over every vertex: the
 * coordinates are read in order, one array each, and the bounds kept in locals.
 *
 * The box is the set {x : |u_a . (x - c)| <= e_a, a = 0, 1, 2} (three slabs), and it holds every
 * vertex, and so its triangles, about any axes, once the extents cover the rounding (u = eps/2,
 * the unit roundoff; docs/mesh-queries.md, section 4): a computed projection u_a . x (three
 * products, two sums, no FMA, |u_a| within eps of 1) is within gamma_3 (1 + eps) |x|_1 < 3.01 u
 * |x|_1 of the exact one, with |v|_1 <= sqrt(3) |v|_2 < 2 radius for a vertex and |c|_1 for the
 * centre; so |u_a . (v - c)| <= max(mx - u_a.c, u_a.c - mn) + 3.01 u (2 radius + |c|_1). The
 * subtraction and the sum below round by at most u (2 radius + |c|_1) (1 + 9 u) each. The
 * slack, 8 u (2 radius + |c|_1) computed, covers all three. */
static void fit_extents(const builder *B, size_t lo, size_t hi, obb *b)
{
    const double *u = b->u;
    double mn0 = HUGE_VAL, mn1 = HUGE_VAL, mn2 = HUGE_VAL, mx0 = -HUGE_VAL, mx1 = -HUGE_VAL, mx2 = -HUGE_VAL;
    for (int k = 0; k < 3; ++k) {
        const double *x = B->p[3 * k], *y = B->p[3 * k + 1], *z = B->p[3 * k + 2];
        for (size_t i = lo; i < hi; ++i) {
            const double d0 = u[0] * x[i] + u[1] * y[i] + u[2] * z[i];
            const double d1 = u[3] * x[i] + u[4] * y[i] + u[5] * z[i];
            const double d2 = u[6] * x[i] + u[7] * y[i] + u[8] * z[i];
            mn0 = dmin(mn0, d0);
            mx0 = dmax(mx0, d0);
            mn1 = dmin(mn1, d1);
            mx1 = dmax(mx1, d1);
            mn2 = dmin(mn2, d2);
            mx2 = dmax(mx2, d2);
        }
    }
    const double mn[3] = {mn0, mn1, mn2}, mx[3] = {mx0, mx1, mx2};
    span_extents(mn, mx, B->mesh->radius, b);
}

/* The box of triangle p (vertices relative to the origin; radius: the mesh's): its axes
 * (triangle_axes), centre and extents computed exactly as fit_extents computes them for one
 * triangle (the same operations in the same order), without going through a builder's arrays: a
 * refit calls it for every triangle, and gives the build's bits. */
static void triangle_fit(double p[3][3], double radius, obb *b, double *area2)
{
    triangle_axes(p, b->u, area2);
    const double *u = b->u;
    double mn[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, mx[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    for (int k = 0; k < 3; ++k)
        for (int a = 0; a < 3; ++a) {
            const double d = u[3 * a] * p[k][0] + u[3 * a + 1] * p[k][1] + u[3 * a + 2] * p[k][2];
            mn[a] = dmin(mn[a], d);
            mx[a] = dmax(mx[a], d);
        }
    for (int c = 0; c < 3; ++c)
        b->c[c] = 0;
    for (int a = 0; a < 3; ++a) {
        const double mid = 0.5 * (mn[a] + mx[a]);
        for (int c = 0; c < 3; ++c)
            b->c[c] += mid * u[3 * a + c];
    }
    const double c1 = fabs(b->c[0]) + fabs(b->c[1]) + fabs(b->c[2]);
    const double slack = 4 * DBL_EPSILON * (2 * radius + c1);
    for (int a = 0; a < 3; ++a) {
        const double pc = dot3(u + 3 * a, b->c);
        b->e[a] = dmax(mx[a] - pc, pc - mn[a]) + slack;
    }
}

/* The box of the triangle at position i, and its moments. */
static void triangle_box(const builder *B, size_t i, obb *b, moments *mo)
{
    double p[3][3];
    pos_vertices(B, i, p);
    double area2;
    triangle_fit(p, B->mesh->radius, b, &area2);
    tri_moments(p, mo);
}

/* x rounded to float, as a double. Through a volatile: gcc 12.2's SLP vectorizer drops the round
 * trip (double)(float)x at -O2 and above (store_box fitted a float box about its centre's double
 * bits, then stored the centre rounded: vertices fell outside by up to half a float ulp;
 * tests/test_mesh_boxes.c caught it). */
static double round_to_float(double x)
{
    volatile float f = (float)x;
    return (double)f;
}

/* Stores box b in slot j of node n, with child `child`. A double mesh stores it as it is; a
 * float mesh rounds axes and centre to float, then takes the extents of the vertices of
 * positions [lo, hi) about the rounded centre along the rounded axes, and rounds them up, so
 * that the stored box still holds them: with r = v - c and s = u_a . r computed in double (u
 * the unit roundoff of double), |u_a . (v - c)| <= |s| + (gamma_3 + u) |r|_1 (1 + u) <
 * |s| + 4.1 u |r|_1, and 8 u |r|_1 also covers the rounding of the sum. */
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
    double uf[9], cf[3], e[3] = {0, 0, 0}, r1 = 0;
    for (int i = 0; i < 9; ++i)
        uf[i] = round_to_float(b->u[i]);
    for (int i = 0; i < 3; ++i)
        cf[i] = round_to_float(b->c[i]);
    for (size_t i = lo; i < hi; ++i) {
        double p[3][3];
        pos_vertices(B, i, p);
        for (int k = 0; k < 3; ++k) {
            const double r[3] = {p[k][0] - cf[0], p[k][1] - cf[1], p[k][2] - cf[2]};
            r1 = dmax(r1, fabs(r[0]) + fabs(r[1]) + fabs(r[2]));
            for (int a = 0; a < 3; ++a)
                e[a] = dmax(e[a], fabs(dot3(uf + 3 * a, r)));
        }
    }
    for (int i = 0; i < 3; ++i) {
        const double ed = e[i] + 4 * DBL_EPSILON * r1;
        float ef = (float)ed;
        if ((double)ef < ed) /* rounded up */
            ef = nextafterf(ef, INFINITY);
        node->c[i][j] = (float)cf[i];
        node->e[i][j] = ef;
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
    size_t g[8], total = 1, last = 0, below = 0;
    const int ng = group_sizes(n, g);
    for (int j = 0; j < ng; ++j)
        if (g[j] > 1) {
            if (g[j] != last) /* groups are dealt evenly: one or two sizes, each counted once */
                below = count_nodes(g[j]), last = g[j];
            total += below;
        }
    return total;
}

/* Node n over count triangles: its groups' sizes g and, for each group, the node it becomes
 * (-1: a lone triangle, a child of n itself). Returns the number of groups. */
static int node_groups(size_t count, int32_t n, size_t g[8], int32_t child[8])
{
    int ng;
    if (count <= TTD_NODE_WIDTH) {
        ng = (int)count;
        for (int j = 0; j < ng; ++j)
            g[j] = 1;
    } else {
        ng = group_sizes(count, g);
    }
    int32_t next = n + 1;
    for (int j = 0; j < ng; ++j) {
        child[j] = g[j] > 1 ? next : -1;
        if (g[j] > 1)
            next += (int32_t)count_nodes(g[j]);
    }
    return ng;
}

/* Whether record a comes before record b along axis: by the coordinate, then the index. */
static int rec_before(const trirec *a, const trirec *b, int axis)
{
    return (a->c[axis] < b->c[axis]) | ((a->c[axis] == b->c[axis]) & (a->t < b->t));
}

/* A deterministic position in [lo, hi) for pivot sample s (a hash of the range). */
static size_t sample_at(size_t lo, size_t hi, uint64_t s)
{
    uint64_t h = (uint64_t)lo * 0x9E3779B97F4A7C15ull ^ (uint64_t)hi * 0xBF58476D1CE4E5B9ull ^ s * 0x94D049BB133111EBull;
    h ^= h >> 31;
    return lo + (size_t)(h % (hi - lo));
}

/* Reorders rec[lo, hi) so that rec[k] holds the record that sorted order along `axis` would put
 * there, none after it before it and none before it after (quickselect: the median of three
 * sampled records as the pivot, and a partition without branches on the data, which on
 * centroids in no particular order would mispredict every other record). */
static void select_kth(trirec *rec, size_t lo, size_t hi, size_t k, int axis)
{
    while (hi - lo > 1) {
        size_t s0 = sample_at(lo, hi, 0), s1 = sample_at(lo, hi, 1), s2 = sample_at(lo, hi, 2), t;
        if (rec_before(&rec[s1], &rec[s0], axis))
            t = s0, s0 = s1, s1 = t;
        if (rec_before(&rec[s2], &rec[s1], axis))
            s1 = rec_before(&rec[s2], &rec[s0], axis) ? s0 : s2;
        /* the pivot to the end; [lo, store) before it, [store, i) not */
        trirec x = rec[s1];
        rec[s1] = rec[hi - 1];
        rec[hi - 1] = x;
        const trirec pivot = x;
        size_t store = lo;
        for (size_t i = lo; i + 1 < hi; ++i) {
            x = rec[i];
            rec[i] = rec[store];
            rec[store] = x;
            store += (size_t)rec_before(&x, &pivot, axis);
        }
        rec[hi - 1] = rec[store];
        rec[store] = pivot;
        if (k == store)
            return;
        if (k < store)
            hi = store;
        else
            lo = store + 1;
    }
}

/* Splits rec[lo, hi) at rank lo + k along the longest side of its centroids' box. */
static void split_at(trirec *rec, size_t lo, size_t hi, size_t k)
{
    float mn[3] = {INFINITY, INFINITY, INFINITY}, mx[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t i = lo; i < hi; ++i)
        for (int c = 0; c < 3; ++c) {
            mn[c] = rec[i].c[c] < mn[c] ? rec[i].c[c] : mn[c];
            mx[c] = rec[i].c[c] > mx[c] ? rec[i].c[c] : mx[c];
        }
    int axis = 0;
    for (int c = 1; c < 3; ++c)
        if (mx[c] - mn[c] > mx[axis] - mn[axis])
            axis = c;
    select_kth(rec, lo, hi, lo + k, axis);
}

/* Orders rec[lo, ...) into groups g[0..ng) by halving the list of groups: the first half of the
 * groups' triangles from the second along the longest side, and again within each half. */
static void split_groups(trirec *rec, size_t lo, const size_t *g, int ng)
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
    split_at(rec, lo, lo + all, left);
    split_groups(rec, lo, g, h);
    split_groups(rec, lo + left, g + h, ng - h);
}

/* The shape of node n over rec[lo, hi): its groups ordered, then its subtrees', down to
 * `depth` levels below n, where the subtrees are listed in `defer` instead (depth < 0: to the
 * leaves). */
static void shape(builder *B, int32_t n, size_t lo, size_t hi, int depth, subtree *defer, size_t *ndefer)
{
    size_t g[8];
    int32_t child[8];
    const int ng = node_groups(hi - lo, n, g, child);
    if (hi - lo > TTD_NODE_WIDTH && !B->refit)
        split_groups(B->rec, lo, g, ng);
    size_t at = lo;
    for (int j = 0; j < ng; ++j) {
        if (child[j] >= 0) {
            if (depth == 1)
                defer[(*ndefer)++] = (subtree){at, at + g[j], child[j]};
            else
                shape(B, child[j], at, at + g[j], depth - 1, defer, ndefer);
        }
        at += g[j];
    }
}

static void shape_task(void *ctx, size_t i, int worker)
{
    (void)worker;
    void **c = ctx;
    const subtree *t = (const subtree *)c[1] + i;
    shape(c[0], t->node, t->lo, t->hi, -1, NULL, NULL);
}

/* ---- bounds ------------------------------------------------------------------------------ */

/* The box of a group of positions [lo, hi) (two triangles or more) from its moments. */
static void group_box(const builder *B, size_t lo, size_t hi, const moments *mo, obb *b)
{
    surface_axes(B, lo, hi, mo, NULL, b->u);
    fit_extents(B, lo, hi, b);
}

/* Writes node n's count and zeros in its unused slots (the node test reads all of them). */
static void finish_node(const builder *B, int32_t n, int ng)
{
    const obb none = {{0, 0, 0}, {0, 0, 0, 0, 0, 0, 0, 0, 0}, {0, 0, 0}};
    for (int j = ng; j < TTD_NODE_WIDTH; ++j)
        store_box(B, n, j, &none, 0, 0, 0);
    if (B->mesh->bytes == 8)
        ((ttd_node_d *)B->mesh->nodes)[n].count = (int32_t)ng;
    else
        ((ttd_node_f *)B->mesh->nodes)[n].count = (int32_t)ng;
}

static void moments_add(moments *sum, const moments *x)
{
    for (int k = 0; k < 10; ++k)
        sum->m[k] += x->m[k];
}

/* The boxes of node n over positions [lo, hi) and of its whole subtree, children first; *sum
 * gets the moments of all its triangles. */
static void bound(const builder *B, int32_t n, size_t lo, size_t hi, moments *sum)
{
    size_t g[8];
    int32_t child[8];
    const int ng = node_groups(hi - lo, n, g, child);
    memset(sum, 0, sizeof *sum);
    size_t at = lo;
    for (int j = 0; j < ng; ++j) {
        obb b;
        moments mo;
        if (child[j] < 0) {
            triangle_box(B, at, &b, &mo);
            store_box(B, n, j, &b, -1 - (int32_t)B->ord[at], at, at + 1);
        } else {
            bound(B, child[j], at, at + g[j], &mo);
            group_box(B, at, at + g[j], &mo, &b);
            store_box(B, n, j, &b, child[j], at, at + g[j]);
        }
        moments_add(sum, &mo);
        at += g[j];
    }
    finish_node(B, n, ng);
}

/* The parallel bounds pass: the subtrees listed by the shape pass, each with its moments. */
typedef struct bound_job {
    const builder *B;
    const subtree *list;
    moments *mo;
} bound_job;

static void bound_task(void *ctx, size_t i, int worker)
{
    (void)worker;
    const bound_job *J = ctx;
    bound(J->B, J->list[i].node, J->list[i].lo, J->list[i].hi, &J->mo[i]);
}

/* The boxes of one node's groups from their moments, in parallel (the top of the tree, where
 * each group is a large part of the mesh). */
typedef struct group_job {
    const builder *B;
    size_t lo[8], hi[8];
    const moments *mo[8];
    obb box[8];
} group_job;

static void group_task(void *ctx, size_t j, int worker)
{
    (void)worker;
    group_job *G = ctx;
    if (G->hi[j] - G->lo[j] == 1) {
        moments unused;
        triangle_box(G->B, G->lo[j], &G->box[j], &unused);
    } else {
        group_box(G->B, G->lo[j], G->hi[j], G->mo[j], &G->box[j]);
    }
}

/* bound() for the levels above the listed subtrees, whose moments come from `done` in list
 * order (*next counts them), with each node's group boxes fitted in parallel. */
static void bound_top(const builder *B, int32_t n, size_t lo, size_t hi, int depth, const moments *done,
                      size_t *next, moments *sum)
{
    size_t g[8];
    int32_t child[8];
    const int ng = node_groups(hi - lo, n, g, child);
    moments mo[8];
    group_job G = {.B = B};
    memset(sum, 0, sizeof *sum);
    size_t at = lo;
    for (int j = 0; j < ng; ++j) {
        if (child[j] < 0) {
            double p[3][3];
            pos_vertices(B, at, p);
            tri_moments(p, &mo[j]);
        } else if (depth == 1) {
            mo[j] = done[(*next)++];
        } else {
            bound_top(B, child[j], at, at + g[j], depth - 1, done, next, &mo[j]);
        }
        G.lo[j] = at;
        G.hi[j] = at + g[j];
        G.mo[j] = &mo[j];
        moments_add(sum, &mo[j]);
        at += g[j];
    }
    ttd_parallel_tasks((size_t)ng, B->threads, group_task, &G);
    for (int j = 0; j < ng; ++j)
        store_box(B, n, j, &G.box[j], child[j] >= 0 ? child[j] : -1 - (int32_t)B->ord[G.lo[j]], G.lo[j], G.hi[j]);
    finish_node(B, n, ng);
}

/* ---- the mesh --------------------------------------------------------------------------- */

/* Triangles per block of the preparation passes. */
#define PREP_BLOCK 4096

/* Triangle t's record: its centroid (relative to the origin) and index, for block b. */
static void prepare_records(void *ctx, size_t b, int worker)
{
    (void)worker;
    builder *B = ctx;
    const uint32_t *tris = B->mesh->tris;
    const size_t i1 = (b + 1) * PREP_BLOCK < B->mesh->nt ? (b + 1) * PREP_BLOCK : B->mesh->nt;
    for (size_t t = b * PREP_BLOCK; t < i1; ++t) {
        trirec *r = &B->rec[t];
        for (int c = 0; c < 3; ++c) {
            double s = 0;
            for (int k = 0; k < 3; ++k)
                s += B->vrel[3 * (size_t)tris[3 * t + (size_t)k] + (size_t)c];
            r->c[c] = (float)(s / 3 * B->unit);
        }
        r->t = (uint32_t)t;
    }
}

/* The vertices of the triangle at each position, in hierarchy order, for block b. */
static void prepare_vertices(void *ctx, size_t b, int worker)
{
    (void)worker;
    builder *B = ctx;
    const uint32_t *tris = B->mesh->tris;
    const size_t i1 = (b + 1) * PREP_BLOCK < B->mesh->nt ? (b + 1) * PREP_BLOCK : B->mesh->nt;
    for (size_t i = b * PREP_BLOCK; i < i1; ++i) {
        const size_t t = B->ord[i];
        for (int k = 0; k < 3; ++k)
            for (int c = 0; c < 3; ++c)
                B->p[3 * k + c][i] = B->vrel[3 * (size_t)tris[3 * t + (size_t)k] + (size_t)c];
    }
}

static void refit_scratch_free(void *scratch);

void ttd_mesh_free(struct ttd_mesh *mesh)
{
    if (mesh == NULL)
        return;
    if (mesh->points != NULL) /* its first member frees it (src/points/points.h) */
        (*(void (**)(void *))mesh->points)(mesh->points);
    if (mesh->self_scratch != NULL) /* likewise (mesh/self_grid_impl.h) */
        (*(void (**)(void *))mesh->self_scratch)(mesh->self_scratch);
    free(mesh->verts);
    free(mesh->tris);
    free(mesh->nodes);
    free(mesh->leaf_vix);
    refit_scratch_free(mesh->refit_scratch);
    if (mesh->edges != NULL) {
        ttd_mesh_edges_free(mesh->edges);
        free(mesh->edges);
    }
    free(mesh);
}

const ttd_mesh_edges *ttd_mesh_edges_get(const struct ttd_mesh *mesh)
{
    /* a cache of what the immutable mesh determines, not a change to it */
    struct ttd_mesh *m = (struct ttd_mesh *)(uintptr_t)mesh;
    ttd_mesh_edges *e = __atomic_load_n(&m->edges, __ATOMIC_ACQUIRE);
    if (e != NULL)
        return e;
    e = malloc(sizeof *e);
    if (e == NULL || !ttd_mesh_edges_build(m->bytes, m->verts, m->nv, m->tris, m->nt, e)) {
        free(e);
        return NULL;
    }
    ttd_mesh_edges *expected = NULL;
    if (!__atomic_compare_exchange_n(&m->edges, &expected, e, 0, __ATOMIC_ACQ_REL, __ATOMIC_ACQUIRE)) {
        ttd_mesh_edges_free(e); /* another thread made it first: the same arrays */
        free(e);
        return expected;
    }
    return e;
}

/* place's passes over vertices of type T (double or float): the range of each coordinate into
 * mn, mx (and, with COPY, the vertices into m->verts as they are read); then, with the origin o,
 * the largest |x - o| of any coordinate into *big (and x - o into vrel unless NULL). One loop per
 * precision, the coordinates unrolled: a branch on the precision and an index modulo 3 per
 * coordinate were most of place's instructions (a 10th of a refit). */
#define PLACE_RANGE(T, COPY)                                                                       \
    do {                                                                                           \
        const T *v = verts;                                                                        \
        T *to = m->verts;                                                                          \
        for (size_t i = 0; i < nv; ++i)                                                            \
            for (int c = 0; c < 3; ++c) {                                                          \
                const T y = v[3 * i + (size_t)c];                                                  \
                const double x = (double)y;                                                        \
                if (COPY)                                                                          \
                    to[3 * i + (size_t)c] = y;                                                     \
                mn[c] = dmin(mn[c], x);                                                            \
                mx[c] = dmax(mx[c], x);                                                            \
            }                                                                                      \
    } while (0)
#define PLACE_BIG(T)                                                                               \
    do {                                                                                           \
        const T *v = verts;                                                                        \
        for (size_t i = 0; i < nv; ++i)                                                            \
            for (int c = 0; c < 3; ++c) {                                                          \
                const double d = (double)v[3 * i + (size_t)c] - m->origin[c];                      \
                if (vrel != NULL)                                                                  \
                    vrel[3 * i + (size_t)c] = d;                                                   \
                big = dmax(big, fabs(d));                                                          \
            }                                                                                      \
    } while (0)
#define PLACE_R2(T)                                                                                \
    do {                                                                                           \
        const T *v = verts;                                                                        \
        for (size_t i = 0; i < nv; ++i) {                                                          \
            double d2 = 0;                                                                         \
            for (int c = 0; c < 3; ++c) {                                                          \
                const double x = (double)v[3 * i + (size_t)c];                                     \
                const double d = scale > 0 ? (x - m->origin[c]) * scale : ldexp(x - m->origin[c], -e); \
                d2 += d * d;                                                                       \
            }                                                                                      \
            r2 = dmax(r2, d2);                                                                     \
        }                                                                                          \
    } while (0)

/* PLACE_R2(double) where scale > 0, two vertices a step on SSE2 (the same products and sums; the
 * largest of sums of squares, +0 or more, does not depend on the order they are compared in) */
static double place_r2(const double *v, size_t nv, const double o[3], double scale)
{
    double r2 = 0;
    size_t i = 0;
#if defined(__SSE2__)
    const __m128d s = _mm_set1_pd(scale), zero = _mm_setzero_pd();
    const __m128d o01 = _mm_setr_pd(o[0], o[1]), o20 = _mm_setr_pd(o[2], o[0]), o12 = _mm_setr_pd(o[1], o[2]);
    __m128d best = zero;
    for (; i + 2 <= nv; i += 2) {
        const double *x = v + 3 * i;
        const __m128d a = _mm_mul_pd(_mm_sub_pd(_mm_loadu_pd(x), o01), s);     /* d of x0, y0 */
        const __m128d b = _mm_mul_pd(_mm_sub_pd(_mm_loadu_pd(x + 2), o20), s); /* z0, x1 */
        const __m128d c = _mm_mul_pd(_mm_sub_pd(_mm_loadu_pd(x + 4), o12), s); /* y1, z1 */
        const __m128d a2 = _mm_mul_pd(a, a), b2 = _mm_mul_pd(b, b), c2 = _mm_mul_pd(c, c);
        const __m128d dx = _mm_shuffle_pd(a2, b2, 2), dy = _mm_shuffle_pd(a2, c2, 1), dz = _mm_shuffle_pd(b2, c2, 2);
        best = _mm_max_pd(best, _mm_add_pd(_mm_add_pd(_mm_add_pd(zero, dx), dy), dz));
    }
    double lanes[2];
    _mm_storeu_pd(lanes, best);
    r2 = dmax(lanes[0], lanes[1]);
#endif
    for (; i < nv; ++i) {
        double d2 = 0;
        for (int c = 0; c < 3; ++c) {
            const double d = (v[3 * i + (size_t)c] - o[c]) * scale;
            d2 += d * d;
        }
        r2 = dmax(r2, d2);
    }
    return r2;
}

/* The origin (the centre of the vertices' bounding box) and radius (how far the farthest vertex
 * is, rounded up) of a mesh, and its vertices relative to the origin into vrel (unless NULL).
 * With copy, verts is also copied into m->verts by the range's pass (a refit: a memcpy before it
 * read the vertices once more, 2% of a refit's instructions at 10k triangles). */
static void place(struct ttd_mesh *m, const void *verts, double *vrel, int copy)
{
    const size_t nv = m->nv;
    double mn[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, mx[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    if (m->bytes == 8 && copy)
        PLACE_RANGE(double, 1);
    else if (m->bytes == 8)
        PLACE_RANGE(double, 0);
    else if (copy)
        PLACE_RANGE(float, 1);
    else
        PLACE_RANGE(float, 0);
    for (int c = 0; c < 3; ++c)
        m->origin[c] = 0.5 * mn[c] + 0.5 * mx[c]; /* halves first: no overflow near DBL_MAX */
    double big = 0;
    if (vrel == NULL) {
        /* the largest |x - origin| without a pass: x - origin rounds monotonically in x, so its
         * extremes are those of the range's ends (the loop's bits) */
        for (int c = 0; c < 3; ++c)
            big = dmax(big, dmax(fabs(mx[c] - m->origin[c]), fabs(mn[c] - m->origin[c])));
    } else if (m->bytes == 8) {
        PLACE_BIG(double);
    } else {
        PLACE_BIG(float);
    }
    /* the squares at unit scale (a power of two, exact): below about 1e-154 they would underflow
     * (a radius of 0 collapsed a scene's world boxes to points, and its broad phase lost every
     * pair, at 1e-163) */
    int e = 0;
    if (big > 0)
        frexp(big, &e);
    /* x * 2^-e is ldexp(x, -e) (one correctly rounded product) without a library call per
     * coordinate (they were 5% of a refit); 2^-e overflows only for a subnormal big */
    const double scale = e >= -1023 ? ldexp(1.0, -e) : 0;
    double r2 = 0;
    if (m->bytes == 8 && scale > 0)
        r2 = place_r2(verts, nv, m->origin, scale);
    else if (m->bytes == 8)
        PLACE_R2(double);
    else
        PLACE_R2(float);
    m->radius = ldexp(sqrt(r2), e) * (1 + 4 * DBL_EPSILON);
}
#undef PLACE_RANGE
#undef PLACE_BIG
#undef PLACE_R2

/* The boxes, bottom-up, from the vertices in hierarchy order (B->p): the subtrees the shape
 * pass listed in parallel (their moments into done), then the levels above them, then the root's
 * box in node 0, slot 0. */
static void bounds_pass(const builder *B, const subtree *list, size_t nlist, moments *done, int depth)
{
    const struct ttd_mesh *m = B->mesh;
    const size_t nt = m->nt;
    obb root;
    moments all;
    if (nt > 1) {
        bound_job J = {B, list, done};
        ttd_parallel_tasks(nlist, B->threads, bound_task, &J);
        size_t next = 0;
        bound_top(B, 1, 0, nt, depth, done, &next, &all);
        group_box(B, 0, nt, &all, &root);
    } else {
        triangle_box(B, 0, &root, &all);
    }
    /* node 0, slot 0: the root's box around everything, with the tree (or the triangle) below */
    store_box(B, 0, 0, &root, nt > 1 ? 1 : -1, 0, nt);
    if (m->bytes == 8)
        ((ttd_node_d *)m->nodes)[0].count = 1;
    else
        ((ttd_node_f *)m->nodes)[0].count = 1;
}

/* Slot j of node n: its child and half extents (in double). */
static int32_t slot_child(const struct ttd_mesh *m, size_t n, int j)
{
    return m->bytes == 8 ? ((const ttd_node_d *)m->nodes)[n].child[j] : ((const ttd_node_f *)m->nodes)[n].child[j];
}

static int slot_count(const struct ttd_mesh *m, size_t n)
{
    return m->bytes == 8 ? ((const ttd_node_d *)m->nodes)[n].count : ((const ttd_node_f *)m->nodes)[n].count;
}

/* A box's surface area over 2 (half extents e). */
static double half_area(const double e[3])
{
    return 4 * (e[0] * e[1] + e[1] * e[2] + e[2] * e[0]);
}

/* The tree's quality measure (docs/mesh-queries.md, section 2b): the surface areas of every
 * subtree's box (the root's included) summed, over those of every triangle's box. What a query
 * pays for is boxes that hold more space than their triangles need: refitting a tree whose
 * triangles moved far from where it grouped them grows its boxes, and this ratio with them,
 * while the triangles' own boxes depend on the geometry alone (flat: each about twice its
 * triangle's area), so that a geometry whose fresh tree has thick boxes (a crumpled sheet) is
 * not held against one whose fresh tree has thin ones. Each node's slots summed in slot order
 * (node_areas), the nodes' sums in node order (quality_of gives the same bits); 0 when the
 * triangles have no area at all. */
/* Node n's part of the measure: its slots' box areas (half_area) summed in slot order, those of
 * subtrees into a[0], those of triangles into a[1]; one loop per precision (a branch on the
 * precision per slot and per extent was most of the measure's time). A refit takes each node's
 * part as it stores the node's boxes, while they are in cache (a pass over every node after the
 * refit re-read a fifth of the tree); the build by tree_quality. */
#define NODE_AREAS(T)                                                                              \
    do {                                                                                           \
        const T *nd = (const T *)m->nodes + n;                                                     \
        for (int j = 0; j < nd->count; ++j) {                                                      \
            const double e[3] = {(double)nd->e[0][j], (double)nd->e[1][j], (double)nd->e[2][j]};   \
            a[nd->child[j] >= 0 ? 0 : 1] += half_area(e);                                          \
        }                                                                                          \
    } while (0)

static void node_areas(const struct ttd_mesh *m, size_t n, double a[2])
{
    a[0] = a[1] = 0;
    if (m->bytes == 8)
        NODE_AREAS(ttd_node_d);
    else
        NODE_AREAS(ttd_node_f);
}
#undef NODE_AREAS

/* node_areas of a leaf (every slot a triangle): the same sums without a branch per slot, the
 * areas of all 8 lanes first (the lanes past count hold zeros, and are not summed) */
#define LEAF_AREAS(T)                                                                              \
    do {                                                                                           \
        const T *nd = (const T *)m->nodes + n;                                                     \
        count = nd->count;                                                                         \
        for (int j = 0; j < TTD_NODE_WIDTH; ++j) {                                                 \
            const double e[3] = {(double)nd->e[0][j], (double)nd->e[1][j], (double)nd->e[2][j]};   \
            h[j] = half_area(e);                                                                   \
        }                                                                                          \
    } while (0)

static void leaf_areas(const struct ttd_mesh *m, size_t n, double a[2])
{
    double h[TTD_NODE_WIDTH];
    int count;
    if (m->bytes == 8)
        LEAF_AREAS(ttd_node_d);
    else
        LEAF_AREAS(ttd_node_f);
    a[0] = a[1] = 0;
    for (int j = 0; j < count; ++j)
        a[1] += h[j];
}
#undef LEAF_AREAS

/* The measure from every node's part (node_areas), summed in node order: the same bits however
 * the parts were made (by the build, by a refit on any number of threads). */
static double quality_of(const double (*area)[2], size_t nnodes)
{
    double sub = 0, tri = 0;
    for (size_t n = 0; n < nnodes; ++n) {
        sub += area[n][0];
        tri += area[n][1];
    }
    return tri > 0 ? sub / tri : 0;
}

static double tree_quality(const struct ttd_mesh *m)
{
    double sub = 0, tri = 0;
    for (size_t n = 0; n < m->nnodes; ++n) {
        double a[2];
        node_areas(m, n, a);
        sub += a[0];
        tri += a[1];
    }
    return tri > 0 ? sub / tri : 0;
}

ttd_status ttd_mesh_build(const ttd_engine_config *cfg, int bytes, const void *verts, size_t nv,
                          const uint32_t *tris, size_t nt, struct ttd_mesh **out)
{
    *out = NULL;
    struct ttd_mesh *m = calloc(1, sizeof *m);
    builder B = {.mesh = m, .threads = cfg->threads};
    double *vrel = NULL, *pts = NULL;
    subtree *list = NULL;
    moments *done = NULL;
    if (m == NULL)
        goto nomem;
    m->bytes = bytes;
    m->nv = nv;
    m->nt = nt;
    /* nodes: the root's box holder (node 0) and the tree from node 1 when there is more than
     * one triangle */
    m->nnodes = 1 + (nt > 1 ? count_nodes(nt) : 0);
    const size_t node_bytes = bytes == 8 ? sizeof(ttd_node_d) : sizeof(ttd_node_f);
    m->verts = ttd_big_alloc(3 * nv * (size_t)bytes);
    m->tris = ttd_big_alloc(3 * nt * sizeof(uint32_t));
    m->nodes = ttd_big_alloc(m->nnodes * node_bytes);
    vrel = ttd_big_alloc(3 * nv * sizeof(double));
    B.rec = ttd_big_alloc(nt * sizeof *B.rec);
    B.ord = ttd_big_alloc(nt * sizeof *B.ord);
    list = malloc(64 * sizeof *list);
    done = malloc(64 * sizeof *done);
    if (!m->verts || !m->tris || !m->nodes || !vrel || !B.rec || !B.ord || !list || !done)
        goto nomem;
    memcpy(m->verts, verts, 3 * nv * (size_t)bytes);
    memcpy(m->tris, tris, 3 * nt * sizeof(uint32_t));
    memset(m->nodes, 0, node_bytes); /* node 0: the root's box, slot 0 only */
    place(m, verts, vrel, 0);
    B.vrel = vrel;
    int e;
    frexp(m->radius, &e);
    B.unit = m->radius > 0 ? ldexp(1.0, -e) : 1.0;

    /* shape: the top levels in this thread, then their subtrees in parallel */
    const size_t blocks = (nt + PREP_BLOCK - 1) / PREP_BLOCK;
    ttd_parallel_for(blocks, cfg->threads, prepare_records, &B);
    const int depth = parallel_depth(cfg->threads);
    size_t nlist = 0;
    if (nt > 1) {
        shape(&B, 1, 0, nt, depth, list, &nlist);
        void *ctx[2] = {&B, list};
        ttd_parallel_tasks(nlist, cfg->threads, shape_task, ctx);
    }
    for (size_t i = 0; i < nt; ++i)
        B.ord[i] = B.rec[i].t;
    free(B.rec);
    B.rec = NULL;

    /* bounds: the vertices in that order, then the listed subtrees in parallel, then the top */
    pts = ttd_big_alloc(9 * nt * sizeof(double));
    if (pts == NULL)
        goto nomem;
    for (int k = 0; k < 9; ++k)
        B.p[k] = pts + (size_t)k * nt;
    ttd_parallel_for(blocks, cfg->threads, prepare_vertices, &B);
    free(vrel);
    vrel = NULL;
    bounds_pass(&B, list, nlist, done, depth);
    m->quality = m->quality_built = tree_quality(m);
    free(pts);
    free(B.ord);
    free(list);
    free(done);
    *out = m;
    return TTD_OK;
nomem:
    free(vrel);
    free(pts);
    free(list);
    free(done);
    free(B.rec);
    free(B.ord);
    ttd_mesh_free(m);
    return TTD_ERR_OUT_OF_MEMORY;
}

/* ---- refit: new vertex positions, the same triangles -------------------------------------- */

/* A refit keeps the tree's shape (which triangles lie below which box) and fits every box again,
 * bottom-up (docs/mesh-queries.md, section 2b):
 *   - a triangle's box from its vertices exactly as the build fits it (triangle_fit: a refit to
 *     unchanged vertices gives the build's bits there); on the SIMD rows a leaf's 8 triangles at
 *     once, one per lane (tri_fit, simd/kernel_trifit.h: the same bits), with their terms of the
 *     leaf's sums (fitsum_terms, summed by fitsum_leaf in a fixed order);
 *   - a leaf's (a node of triangles) from its vertices, about axes found from its triangles' sums
 *     (refit_axes) and its axes before the move; a node's slots' axes at once, one per lane, on
 *     the SIMD rows (leaf_axes, simd/kernel_trifit.h: the same bits), refit_node's middle pass;
 *   - a larger subtree's likewise, around its children's boxes instead of its vertices (a few
 *     corners per child instead of a pass over every vertex below it).
 * The sums a parent's axes need (fitsum) are the triangles' normals and the vertices' moments,
 * which cost a few products a triangle: the build's area moments and Jacobi rotations per leaf
 * were most of a refit (docs/mesh-queries.md, section 6, where the lanes' round is measured). */

/* A subtree's sums for its box's axes: its triangles' normals (cross products of their edges,
 * oriented by their vertices' order: twice their areas) summed, with the sum of their lengths,
 * and its triangles' vertices' moments (three per triangle: the count, the sums of x and of
 * x x^T, the last as sym_r / sym_c's 6 entries), all relative to the mesh's origin. */
typedef struct fitsum {
    double n[3], nlen;
    double m[10];
} fitsum;

static void fitsum_add(fitsum *sum, const fitsum *x)
{
    for (int k = 0; k < 3; ++k)
        sum->n[k] += x->n[k];
    sum->nlen += x->nlen;
    for (int k = 0; k < 10; ++k)
        sum->m[k] += x->m[k];
}

/* Adds triangle p's normal (unit normal u, twice its area area2: triangle_axes's) and its
 * vertices' moments to *s. */
static void fitsum_triangle(fitsum *s, double p[3][3], const double u[3], double area2)
{
    for (int k = 0; k < 3; ++k)
        s->n[k] += area2 * u[k];
    s->nlen += area2;
    s->m[0] += 3;
    for (int v = 0; v < 3; ++v) {
        for (int c = 0; c < 3; ++c)
            s->m[1 + c] += p[v][c];
        for (int k = 0; k < 6; ++k)
            s->m[4 + k] += p[v][sym_r[k]] * p[v][sym_c[k]];
    }
}

/* A leaf's sums (fitsum) are summed in a fixed order that lanes can follow: each triangle's terms
 * first (terms[q][i], triangle i: its oriented normal area2 u and area2, q = 0..3; its vertices'
 * sum, q = 4..6, and moments, q = 7..12, each over its three vertices in order), then each term
 * over the leaf's 8 slots by pairs, ((0+1) + (2+3)) + ((4+5) + (6+7)), empty slots +0. The SIMD
 * rows compute the terms in lanes with the fit (simd/kernel_trifit.h, the same operations); the
 * scalar row and the triangles the lanes leave out compute them here. Summed one triangle after
 * another instead, with 16 chains of dependent additions through memory, the sums were a third
 * of a refit once the boxes were fitted in lanes (docs/mesh-queries.md, section 6). */
static void fitsum_terms(double terms[13][TTD_NODE_WIDTH], int i, double *const p9[9], const double u[3], double area2,
                         int vertices)
{
    for (int q = 0; q < 3; ++q)
        terms[q][i] = area2 * u[q];
    terms[3][i] = area2;
    if (!vertices)
        return;
    double v[3][3];
    for (int k = 0; k < 3; ++k)
        for (int c = 0; c < 3; ++c)
            v[k][c] = p9[3 * k + c][i];
    for (int q = 0; q < 3; ++q)
        terms[4 + q][i] = v[0][q] + v[1][q] + v[2][q];
    for (int q = 0; q < 6; ++q) {
        const int r = sym_r[q], c = sym_c[q];
        terms[7 + q][i] = v[0][r] * v[0][c] + v[1][r] * v[1][c] + v[2][r] * v[2][c];
    }
}

/* The leaf's sums from its count triangles' terms (fitsum_terms), in the order described there. */
static fitsum fitsum_leaf(double terms[13][TTD_NODE_WIDTH], int count)
{
    double x[14];
    if (count < TTD_NODE_WIDTH)
        for (int q = 0; q < 13; ++q)
            for (int i = count; i < TTD_NODE_WIDTH; ++i)
                terms[q][i] = 0;
#if defined(__SSE2__) && TTD_NODE_WIDTH == 8
    /* two terms at once (q, q + 1): the pairs' sums by unpacks, then the same additions in the
     * same order (one term at a time these were 6% of a refit's instructions) */
    for (int q = 0; q < 13; q += 2) {
        const double *t = terms[q], *w = terms[q < 12 ? q + 1 : q];
        __m128d s[4];
        for (int i = 0; i < 4; ++i) {
            const __m128d a = _mm_loadu_pd(t + 2 * i), b = _mm_loadu_pd(w + 2 * i);
            s[i] = _mm_add_pd(_mm_unpacklo_pd(a, b), _mm_unpackhi_pd(a, b)); /* (t[2i] + t[2i+1], w's) */
        }
        _mm_storeu_pd(x + q, _mm_add_pd(_mm_add_pd(s[0], s[1]), _mm_add_pd(s[2], s[3])));
    }
#else
    for (int q = 0; q < 13; ++q) {
        const double *t = terms[q];
        x[q] = ((t[0] + t[1]) + (t[2] + t[3])) + ((t[4] + t[5]) + (t[6] + t[7]));
    }
#endif
    fitsum s;
    for (int k = 0; k < 3; ++k)
        s.n[k] = x[k];
    s.nlen = x[3];
    s.m[0] = 3.0 * count;
    for (int k = 0; k < 9; ++k)
        s.m[1 + k] = x[4 + k];
    return s;
}

/* A patch counts as nearly flat for refit_axes when its normals' sum is at least this part of
 * their lengths' sum (for two equal halves, normals within about 50 degrees of each other). */
#define REFIT_FLAT 0.9

/* A refitted box's axes from its subtree's sums, starting from its axes before the move (old:
 * unit rows, orthonormal to a few eps); any axes are valid (the extents hold the vertices about
 * whatever axes they get), these make the box tight. A nearly flat patch (REFIT_FLAT) takes its
 * normals' sum as an axis and, across it, the principal axes of its vertices in that plane: the
 * old first axis made perpendicular to the normal (Gram-Schmidt twice), then turned by one
 * Jacobi rotation of the 2x2 covariance, which diagonalises it. Anything else (a curved patch, a
 * soup of facing triangles, no area) takes the principal axes of its vertices by Jacobi
 * rotations from the old axes (eigen_sym3). Either way the axes are closed as eigen_sym3 closes
 * them: orthonormal to a few eps. */
static void refit_axes(const fitsum *s, const double old[9], double u[9])
{
    double cov[3][3];
    const double k = s->m[0];
    for (int q = 0; q < 6; ++q) {
        const int r = sym_r[q], c = sym_c[q];
        cov[r][c] = cov[c][r] = s->m[4 + q] / k - (s->m[1 + r] / k) * (s->m[1 + c] / k);
    }
    double f[9];
    const int flat = s->nlen > 0 && dot3(s->n, s->n) >= REFIT_FLAT * REFIT_FLAT * s->nlen * s->nlen;
    if (!flat || !normalize3(s->n, f)) {
        eigen_sym3(cov, u, old);
        return;
    }
    /* f[0..2]: the normal; f[6..8]: the old first axis (or second) made perpendicular to it */
    memcpy(f + 6, old, 3 * sizeof *f);
    if (!orthogonalize(f)) {
        memcpy(f + 6, old + 3, 3 * sizeof *f);
        if (!orthogonalize(f)) {
            complete_frame(f);
            memcpy(f + 6, f + 3, 3 * sizeof *f);
        }
    }
    double a[3], b[3];
    memcpy(a, f + 6, sizeof a);
    ttd_cross3(f, a, b);
    double ca[3], cb[3];
    for (int i = 0; i < 3; ++i) {
        ca[i] = cov[i][0] * a[0] + cov[i][1] * a[1] + cov[i][2] * a[2];
        cb[i] = cov[i][0] * b[0] + cov[i][1] * b[1] + cov[i][2] * b[2];
    }
    double vaa = dot3(a, ca), vbb = dot3(b, cb);
    const double vab = dot3(a, cb);
    if (vab != 0) {
        const double theta = (vbb - vaa) / (2 * vab);
        const double t = (theta >= 0 ? 1.0 : -1.0) / (fabs(theta) + sqrt(theta * theta + 1));
        const double c = 1 / sqrt(t * t + 1), sn = t * c;
        for (int i = 0; i < 3; ++i) {
            const double ai = a[i], bi = b[i];
            a[i] = c * ai - sn * bi;
            b[i] = sn * ai + c * bi;
        }
        vaa -= t * vab;
        vbb += t * vab;
    }
    /* the larger spread first, as eigen_sym3 orders them; then closed as it closes them */
    normalize3(vaa >= vbb ? a : b, u);
    normalize3(vaa >= vbb ? b : a, u + 3);
    double w[3];
    ttd_cross3(u, u + 3, w);
    normalize3(w, u + 6);
    ttd_cross3(u + 6, u, u + 3);
    normalize3(u + 3, u + 3);
}

/* The refit's scratch, kept with the mesh (m->refit_scratch) from its first refit on, through
 * rebuilds (sized again where the node count differs), freed with the mesh: each node's subtree
 * sums (written before its parent reads them) and part of the measure (written for every node by
 * every refit), and the list of the subtrees refitted in parallel; it carries nothing from one
 * refit to the next. Allocated afresh by every refit, its pages were faulted in again each time
 * (520 faults a refit at 1M triangles: docs/mesh-queries.md, section 6). */
typedef struct refit_scratch {
    size_t nnodes;     /* the tree it was made for */
    fitsum *sums;      /* per node */
    double (*area)[2]; /* per node */
    subtree list[64];
} refit_scratch;

static void refit_scratch_free(void *scratch)
{
    refit_scratch *S = scratch;
    if (S == NULL)
        return;
    free(S->sums);
    free(S->area);
    free(S);
}

/* m's scratch for a tree of m->nnodes nodes (made on the first call, kept after): NULL out of
 * memory, m unchanged. */
static refit_scratch *refit_scratch_get(struct ttd_mesh *m)
{
    refit_scratch *S = m->refit_scratch;
    if (S != NULL && S->nnodes == m->nnodes)
        return S;
    S = malloc(sizeof *S);
    if (S == NULL)
        return NULL;
    S->nnodes = m->nnodes;
    S->sums = ttd_big_alloc(m->nnodes * sizeof *S->sums);
    S->area = ttd_big_alloc(m->nnodes * sizeof *S->area);
    if (S->sums == NULL || S->area == NULL) {
        refit_scratch_free(S);
        return NULL;
    }
    refit_scratch_free(m->refit_scratch);
    m->refit_scratch = S;
    return S;
}

typedef struct refit {
    const struct ttd_mesh *mesh;
    ttd_tri_fit_fn tri_fit; /* the ISA's lane fit of a leaf's triangles' boxes, or NULL (scalar) */
    ttd_leaf_span_fn leaf_span; /* the ISA's lane range of a leaf's vertices, or NULL (scalar) */
    ttd_leaf_axes_fn leaf_axes; /* the ISA's lane axes of up to 8 leaves, or NULL (scalar) */
    ttd_box_span_fn box_span;   /* the ISA's lane pass of store_box_of_boxes, or NULL (scalar) */
    fitsum *sums;         /* per node: its subtree's sums, once the node is refitted */
    double (*area)[2];    /* per node: its part of the tree's measure (node_areas) */
    subtree *list;        /* the subtrees refitted in parallel (room for 64) */
} refit;

/* A local builder over up to 8 triangles (a leaf, or one triangle): their vertices relative to
 * the origin, one array per coordinate as the build keeps them, so that the build's box
 * functions run on the same numbers. */
typedef struct local_tris {
    builder B;
    double p[9][TTD_NODE_WIDTH];
} local_tris;

#define GATHER(T)                                                                                  \
    do {                                                                                           \
        const T *v = m->verts;                                                                     \
        for (int i = 0; i < count; ++i)                                                            \
            for (int k = 0; k < 3; ++k) {                                                          \
                const T *x = v + 3 * (size_t)ix[3 * i + k];                                        \
                for (int c = 0; c < 3; ++c) /* as place() computes vrel */                         \
                    L->p[3 * k + c][i] = (double)x[c] - o[c];                                      \
            }                                                                                      \
    } while (0)

/* The vertices of count triangles whose vertex indices are ix[0..3 count) (three a triangle, in
 * order: a leaf's from m->leaf_vix, a lone triangle's from m->tris). */
static void gather(const struct ttd_mesh *m, local_tris *L, const uint32_t *ix, int count)
{
    /* the builder's fields that its box functions read (the mesh, the positions), no others */
    L->B.mesh = m;
    for (int k = 0; k < 9; ++k)
        L->B.p[k] = L->p[k];
    const double o[3] = {m->origin[0], m->origin[1], m->origin[2]};
    if (m->bytes == 8) {
#if defined(__SSE2__)
        /* x and y in one load and subtraction (the same differences), z alone */
        const double *v = m->verts;
        const __m128d oxy = _mm_setr_pd(o[0], o[1]);
        for (int i = 0; i < count; ++i)
            for (int k = 0; k < 3; ++k) {
                const double *x = v + 3 * (size_t)ix[3 * i + k];
                const __m128d d = _mm_sub_pd(_mm_loadu_pd(x), oxy);
                _mm_storel_pd(&L->p[3 * k][i], d);
                _mm_storeh_pd(&L->p[3 * k + 1][i], d);
                L->p[3 * k + 2][i] = x[2] - o[2];
            }
#else
        GATHER(double);
#endif
    } else {
        GATHER(float);
    }
    for (int k = 0; k < 9; ++k) /* lanes past the last triangle: defined numbers for tri_fit */
        for (int i = count; i < TTD_NODE_WIDTH; ++i)
            L->p[k][i] = 0;
}
#undef GATHER

/* The vertex indices of every leaf's triangles, 24 a node (TTD_NODE_WIDTH triangles of 3), in
 * slot order at the leaf's node index: the refit reads a leaf's from here, in the order it walks
 * the nodes, instead of m->tris through each leaf's children, whose lines the triangles' order
 * scatters (waiting on them was a fifth of a refit's node work on a tree out of cache:
 * docs/mesh-queries.md, section 6). The entries of nodes that are not leaves are left unset.
 * NULL out of memory. */
static uint32_t *leaf_indices(const struct ttd_mesh *m)
{
    uint32_t *vix = ttd_big_alloc(m->nnodes * 3 * TTD_NODE_WIDTH * sizeof *vix);
    if (vix == NULL)
        return NULL;
    for (size_t n = 0; n < m->nnodes; ++n) {
        const int count = slot_count(m, n);
        if (count == 0 || slot_child(m, n, 0) >= 0)
            continue;
        for (int i = 0; i < count; ++i) {
            const uint32_t t = (uint32_t)(-1 - slot_child(m, n, i));
            for (int k = 0; k < 3; ++k)
                vix[3 * TTD_NODE_WIDTH * n + 3 * (size_t)i + (size_t)k] = m->tris[3 * (size_t)t + (size_t)k];
        }
    }
    return vix;
}

/* Child slot j of node n read back in double (the stored values, exactly). */
static void slot_box(const struct ttd_mesh *m, size_t n, int j, obb *b)
{
    for (int i = 0; i < 3; ++i) {
        b->c[i] = m->bytes == 8 ? ((const ttd_node_d *)m->nodes)[n].c[i][j] : (double)((const ttd_node_f *)m->nodes)[n].c[i][j];
        b->e[i] = m->bytes == 8 ? ((const ttd_node_d *)m->nodes)[n].e[i][j] : (double)((const ttd_node_f *)m->nodes)[n].e[i][j];
    }
    for (int i = 0; i < 9; ++i)
        b->u[i] = m->bytes == 8 ? ((const ttd_node_d *)m->nodes)[n].u[i][j] : (double)((const ttd_node_f *)m->nodes)[n].u[i][j];
}

/* Stores in slot j of node n the box with axes u0 (unit rows, double) around the boxes in the
 * slots of node c, so that it holds every vertex they hold. A child box Y (centre y, axes the rows
 * y_b of W, extents f) is {y + W^-1 s : |s_b| <= f_b}. With G = W W^T - I, every entry within g,
 * W^-1 = W^T (I + G)^-1, so |W^-1 s - W^T s| <= |W| |G| / (1 - |G|) |s| <= 8 g |f|_1 for g < 1/6
 * (|G| <= 3 g; the builder's frames are orthonormal to a few eps, tests/test_mesh_boxes.c). Hence,
 * along an axis u_a of the new box (centre c),
 *     |u_a . (x - c)| <= |u_a . (y - c)| + sum_b |u_a . y_b| f_b + |u_a| 8 g |f|_1.
 * Each computed term is within a few u (double's unit roundoff) of its magnitude: y - c and its
 * dot with u_a within 4.1 u |y - c|_1, each |u_a . y_b| f_b within 6.2 u f_b, g's own error
 * within 4 u; the slack 16 u (|y - c|_1 + |f|_1) covers them with the sums, and |u_a| <= 1 + eps
 * is folded into 8 (g + 4 u) (1 + 2^-20). A float mesh rounds the axes and centre to float first
 * and the extents up. */
static void store_box_of_boxes(const struct ttd_mesh *m, int32_t n, int j, const double u0[9], int32_t c,
                               ttd_box_span_fn box_span)
{
    const int f32 = m->bytes == 4;
    const int count = slot_count(m, (size_t)c);
    double u[9], lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    double spread[TTD_NODE_WIDTH][3], slack[TTD_NODE_WIDTH];
    obb y[TTD_NODE_WIDTH];
    for (int i = 0; i < 9; ++i)
        u[i] = f32 ? round_to_float(u0[i]) : u0[i];
    if (!f32 && box_span != NULL) {
        /* the loop below in lanes, one child a lane (simd/kernel_trifit.h: the same bits) */
        const ttd_node_d *cn = (const ttd_node_d *)m->nodes + c;
        double sp[3][TTD_NODE_WIDTH];
        box_span((const double(*)[TTD_NODE_WIDTH])cn->c, (const double(*)[TTD_NODE_WIDTH])cn->u,
                 (const double(*)[TTD_NODE_WIDTH])cn->e, count, u, lo, hi, sp, slack);
        for (int k = 0; k < count; ++k)
            for (int a = 0; a < 3; ++a) {
                y[k].c[a] = cn->c[a][k];
                spread[k][a] = sp[a][k];
            }
    }
    for (int k = 0; k < (!f32 && box_span != NULL ? 0 : count); ++k) {
        slot_box(m, (size_t)c, k, &y[k]);
        double g = 0;
        for (int a = 0; a < 3; ++a)
            for (int b = a; b < 3; ++b)
                g = dmax(g, fabs(dot3(y[k].u + 3 * a, y[k].u + 3 * b) - (a == b ? 1.0 : 0.0)));
        const double f1 = y[k].e[0] + y[k].e[1] + y[k].e[2];
        const double skew = 8 * (g + 2 * DBL_EPSILON) * (1 + 0x1p-20) * f1;
        slack[k] = skew + 8 * DBL_EPSILON * f1;
        for (int a = 0; a < 3; ++a) {
            double r = 0;
            for (int b = 0; b < 3; ++b)
                r += fabs(dot3(u + 3 * a, y[k].u + 3 * b)) * y[k].e[b];
            spread[k][a] = r;
            const double p = dot3(u + 3 * a, y[k].c);
            lo[a] = dmin(lo[a], p - r - slack[k]);
            hi[a] = dmax(hi[a], p + r + slack[k]);
        }
    }
    /* the centre: the middle of the children's range along each axis (any centre would hold them) */
    obb b = {{0, 0, 0}, {0}, {0, 0, 0}};
    memcpy(b.u, u, sizeof u);
    for (int a = 0; a < 3; ++a)
        for (int i = 0; i < 3; ++i)
            b.c[i] += 0.5 * (lo[a] + hi[a]) * u[3 * a + i];
    for (int i = 0; i < 3; ++i)
        b.c[i] = f32 ? round_to_float(b.c[i]) : b.c[i];
    for (int k = 0; k < count; ++k) {
        const double d[3] = {y[k].c[0] - b.c[0], y[k].c[1] - b.c[1], y[k].c[2] - b.c[2]};
        const double d1 = fabs(d[0]) + fabs(d[1]) + fabs(d[2]);
        for (int a = 0; a < 3; ++a)
            b.e[a] = dmax(b.e[a], fabs(dot3(u + 3 * a, d)) + spread[k][a] + slack[k] + 8 * DBL_EPSILON * d1);
    }
    if (!f32) {
        ttd_node_d *node = (ttd_node_d *)m->nodes + n;
        for (int i = 0; i < 3; ++i) {
            node->c[i][j] = b.c[i];
            node->e[i][j] = b.e[i];
        }
        for (int i = 0; i < 9; ++i)
            node->u[i][j] = b.u[i];
        return;
    }
    ttd_node_f *node = (ttd_node_f *)m->nodes + n;
    for (int i = 0; i < 3; ++i) {
        float ef = (float)b.e[i];
        if ((double)ef < b.e[i]) /* rounded up */
            ef = nextafterf(ef, INFINITY);
        node->c[i][j] = (float)b.c[i];
        node->e[i][j] = ef;
    }
    for (int i = 0; i < 9; ++i)
        node->u[i][j] = (float)b.u[i];
}

/* Refits slot j of node n, a lone triangle, from its vertices, and returns its sums. */
static fitsum refit_slot(const refit *R, int32_t n, int j)
{
    const struct ttd_mesh *m = R->mesh;
    const int32_t c = slot_child(m, (size_t)n, j);
    const uint32_t t = (uint32_t)(-1 - c);
    local_tris L;
    obb b;
    double p[3][3], area2;
    fitsum sum;
    memset(&sum, 0, sizeof sum);
    gather(m, &L, m->tris + 3 * (size_t)t, 1);
    pos_vertices(&L.B, 0, p);
    triangle_fit(p, m->radius, &b, &area2);
    fitsum_triangle(&sum, p, b.u + 6, area2);
    store_box(&L.B, n, j, &b, c, 0, 1);
    return sum;
}

/* A leaf's part of a refit before its own axes: its triangles' boxes (in lanes where the ISA has
 * them, the same bits as triangle_fit; a full leaf of a double mesh takes them straight into its
 * node) and its sums. L keeps its vertices for its own extents (leaf_store). */
static fitsum leaf_fit(const refit *R, int32_t c, local_tris *L)
{
    const struct ttd_mesh *m = R->mesh;
    const int count = slot_count(m, (size_t)c);
    gather(m, L, m->leaf_vix + 3 * TTD_NODE_WIDTH * (size_t)c, count);
    const double *const *pl = (const double *const *)L->B.p;
    ttd_node_d *leaf = m->bytes == 8 && count == TTD_NODE_WIDTH ? (ttd_node_d *)m->nodes + c : NULL;
    double U[9][TTD_NODE_WIDTH], C[3][TTD_NODE_WIDTH], E[3][TTD_NODE_WIDTH], T[13][TTD_NODE_WIDTH];
    double(*u)[TTD_NODE_WIDTH] = leaf != NULL ? leaf->u : U;
    unsigned lanes = 0;
    obb b;
    if (R->tri_fit != NULL)
        lanes = R->tri_fit(pl, count, m->radius, u, leaf != NULL ? leaf->c : C, leaf != NULL ? leaf->e : E, T);
    for (int i = 0; i < count; ++i) {
        if (lanes >> i & 1) {
            if (leaf != NULL)
                continue; /* stored already */
            for (int k = 0; k < 3; ++k) {
                b.c[k] = C[k][i];
                b.e[k] = E[k][i];
            }
            for (int k = 0; k < 9; ++k)
                b.u[k] = U[k][i];
        } else {
            double area2, p[3][3];
            pos_vertices(&L->B, (size_t)i, p);
            triangle_fit(p, m->radius, &b, &area2);
            /* the lanes' vertex terms hold whatever the fit did (a row without lanes: none) */
            fitsum_terms(T, i, L->B.p, b.u + 6, area2, R->tri_fit == NULL);
        }
        store_box(&L->B, c, i, &b, slot_child(m, (size_t)c, i), (size_t)i, (size_t)i + 1);
    }
    return fitsum_leaf(T, count);
}

/* The rest of a leaf's refit: its box about axes u (from refit_axes or leaf_axes) around its
 * vertices, stored in slot j of node n. */
static void leaf_store(const refit *R, int32_t n, int j, int32_t c, const local_tris *L, const double u[9])
{
    const struct ttd_mesh *m = R->mesh;
    const int count = slot_count(m, (size_t)c);
    obb b;
    memcpy(b.u, u, sizeof b.u);
    if (R->leaf_span != NULL) {
        double mn[3], mx[3];
        R->leaf_span((const double *const *)L->B.p, count, b.u, mn, mx);
        span_extents(mn, mx, m->radius, &b);
    } else {
        fit_extents(&L->B, 0, (size_t)count, &b);
    }
    store_box(&L->B, n, j, &b, c, 0, (size_t)count);
}

/* Refits every slot of node n (its children refitted already, but for its leaves) into sum[j],
 * each slot's subtree's sums, in three passes: each slot's sums (a leaf's from its triangles,
 * whose boxes leaf_fit refits; a larger subtree's kept by its node); every slot's axes, eight at
 * once in lanes where the ISA has them (leaf_axes: the same bits as refit_axes, which does the
 * slots it leaves out and the scalar row's); then each slot's box (a leaf's around its vertices,
 * leaf_store; a larger subtree's around its children's boxes). A lone triangle by refit_slot. */
static void refit_node(const refit *R, int32_t n, fitsum sum[TTD_NODE_WIDTH])
{
    const struct ttd_mesh *m = R->mesh;
    const int count = slot_count(m, (size_t)n);
    local_tris L[TTD_NODE_WIDTH];
    double S[14][TTD_NODE_WIDTH], old[9][TTD_NODE_WIDTH], u[9][TTD_NODE_WIDTH];
    int32_t child[TTD_NODE_WIDTH];
    unsigned boxes = 0, leaves = 0;
    /* the slots' axes before the move (every lane's: those holding no box are set below), read
     * before the leaves are fitted: read after the first leaf's fit, their 9 lines were a first
     * touch of the node that waited alone (12% of refit_node's samples at 100k) */
    if (m->bytes == 8) {
        memcpy(old, ((const ttd_node_d *)m->nodes)[n].u, sizeof old); /* every lane: a fixed copy */
    } else {
        for (int k = 0; k < 9; ++k)
            for (int j = 0; j < TTD_NODE_WIDTH; ++j)
                old[k][j] = (double)((const ttd_node_f *)m->nodes)[n].u[k][j];
    }
    for (int j = 0; j < count; ++j) {
        child[j] = slot_child(m, (size_t)n, j);
        if (child[j] < 0) {
            sum[j] = refit_slot(R, n, j);
            continue;
        }
        boxes |= 1u << j;
        if (slot_child(m, (size_t)child[j], 0) < 0) {
            leaves |= 1u << j;
            sum[j] = leaf_fit(R, child[j], &L[j]);
            leaf_areas(m, (size_t)child[j], R->area[child[j]]);
        } else {
            sum[j] = R->sums[child[j]];
        }
        for (int k = 0; k < 3; ++k)
            S[k][j] = sum[j].n[k];
        S[3][j] = sum[j].nlen;
        for (int k = 0; k < 10; ++k)
            S[4 + k][j] = sum[j].m[k];
    }
    if (boxes != 0) {
        /* defined numbers in the lanes no box fills (a count of 1 where refit_axes divides by
         * it): set here, lane by lane, instead of clearing the array first (1.3% of a refit);
         * old holds the node's rows in every lane, finite numbers already */
        for (int j = 0; j < TTD_NODE_WIDTH; ++j)
            if (!(boxes >> j & 1))
                for (int k = 0; k < 14; ++k)
                    S[k][j] = k == 4 ? 1.0 : 0.0;
        const unsigned lanes = R->leaf_axes != NULL ? R->leaf_axes((const double(*)[TTD_NODE_WIDTH])S,
                                                                   (const double(*)[TTD_NODE_WIDTH])old, boxes, u)
                                                    : 0;
        for (int j = 0; j < count; ++j) {
            if (!(boxes >> j & 1))
                continue;
            double uj[9];
            if (lanes >> j & 1) {
                for (int k = 0; k < 9; ++k)
                    uj[k] = u[k][j];
            } else {
                double oj[9];
                for (int k = 0; k < 9; ++k)
                    oj[k] = old[k][j];
                refit_axes(&sum[j], oj, uj);
            }
            if (leaves >> j & 1)
                leaf_store(R, n, j, child[j], &L[j], uj);
            else
                store_box_of_boxes(m, n, j, uj, child[j], R->box_span);
        }
    }
    node_areas(m, (size_t)n, R->area[n]);
}

/* Asks for the nodes below node n (by index) before they are needed: refit_nodes goes down the
 * indices, and the next node it refits, with its leaves, lies just below n (pre-order puts a
 * node's leaves right after it; the bottom nodes hold 2.7 leaves on average, so about 4 KB).
 * Fetched as the refit reached them, a node's first lines (its leaves' children, its axes) had
 * been a fifth of its time on a tree out of cache (docs/mesh-queries.md, section 6). */
#define REFIT_AHEAD 4096
static void node_prefetch(const struct ttd_mesh *m, size_t n)
{
    const size_t at = n * (m->bytes == 8 ? sizeof(ttd_node_d) : sizeof(ttd_node_f));
    for (size_t k = 64; k <= REFIT_AHEAD && k <= at; k += 64)
        __builtin_prefetch((const char *)m->nodes + (at - k), 1, 3);
    /* and the leaves' vertex indices of the 8 nodes below (leaf_indices: 96 bytes a node) */
    const size_t vat = n * 3 * TTD_NODE_WIDTH * sizeof *m->leaf_vix;
    for (size_t k = 64; k <= 8 * 3 * TTD_NODE_WIDTH * sizeof *m->leaf_vix && k <= vat; k += 64)
        __builtin_prefetch((const char *)m->leaf_vix + (vat - k), 0, 3);
}
#undef REFIT_AHEAD

/* Refits the slots of the nodes first..last-1 that are not leaves, the last first (pre-order:
 * children after their parent), keeping each node's sums; skips the nodes of the first nlist
 * listed subtrees (the top of the tree, refitted after them). */
static void refit_nodes(const refit *R, size_t first, size_t last, size_t nlist)
{
    size_t next = nlist; /* the listed subtree below the current node, from the last */
    size_t end[64];      /* past each listed subtree's last node (count_nodes once each) */
    for (size_t i = 0; i < nlist; ++i)
        end[i] = (size_t)R->list[i].node + count_nodes(R->list[i].hi - R->list[i].lo);
    for (size_t n = last; n-- > first;) {
        while (next > 0 && (size_t)R->list[next - 1].node > n)
            --next;
        if (next > 0) {
            const subtree *t = &R->list[next - 1];
            if (n < end[next - 1]) { /* inside a listed subtree: done */
                n = (size_t)t->node;
                continue;
            }
        }
        if (slot_child(R->mesh, n, 0) < 0)
            continue; /* a leaf: its parent refits it */
        fitsum sum, slot[TTD_NODE_WIDTH];
        memset(&sum, 0, sizeof sum);
        node_prefetch(R->mesh, n);
        refit_node(R, (int32_t)n, slot);
        for (int j = 0; j < slot_count(R->mesh, n); ++j)
            fitsum_add(&sum, &slot[j]);
        R->sums[n] = sum;
    }
}

static void refit_task(void *ctx, size_t i, int worker)
{
    (void)worker;
    const refit *R = ctx;
    const subtree *t = &R->list[i];
    refit_nodes(R, (size_t)t->node, (size_t)t->node + count_nodes(t->hi - t->lo), 0);
}

/* Rebuilds m's hierarchy from its vertices (a fresh build, whose contents, everything derived
 * included, m takes, keeping its counters and the closed flag, which depends on the triangles
 * alone; the old contents are freed with the fresh mesh's struct). Out of memory, m keeps its
 * refitted tree, which is valid: a rebuild only makes the queries faster. */
static void rebuild(const ttd_engine_config *cfg, struct ttd_mesh *m)
{
    struct ttd_mesh *fresh;
    if (ttd_mesh_build(cfg, m->bytes, m->verts, m->nv, m->tris, m->nt, &fresh) != TTD_OK)
        return;
    struct ttd_mesh old = *m;
    *m = *fresh;
    m->generation = old.generation;
    m->rebuilds = old.rebuilds + 1;
    m->closed = old.closed;
    m->self_scratch = old.self_scratch; /* arrays only: sized again by the next self query */
    old.self_scratch = NULL;
    m->refit_scratch = old.refit_scratch; /* no state: sized again by the next refit */
    old.refit_scratch = NULL;
    *fresh = old;
    ttd_mesh_free(fresh);
}

/* The hierarchy's boxes, bottom-up over its kept shape: the subtrees the build would build in
 * parallel, in parallel, then the nodes above them, then the root's slot. */
static void refit_boxes(const ttd_engine_config *cfg, struct ttd_mesh *m, refit *R)
{
    size_t nlist = 0;
    if (m->nt > 1) {
        builder B = {.mesh = m, .refit = 1};
        shape(&B, 1, 0, m->nt, parallel_depth(cfg->threads), R->list, &nlist); /* lists them, in order */
        ttd_parallel_tasks(nlist, cfg->threads, refit_task, R);
        refit_nodes(R, 1, m->nnodes, nlist);
    }
    fitsum root[TTD_NODE_WIDTH];
    refit_node(R, 0, root); /* node 0's one slot: the root's box */
}

/* Everything derived from the vertex positions, recomputed after they moved, in this order:
 *   1. place: the origin and the radius (the boxes' frame, the spheres, the rounding margin);
 *   2. refit_boxes: the hierarchy's boxes;
 *   3. the measure that decides a rebuild (ttd_mesh_refit), from the nodes' parts refit_boxes
 *      took (quality_of: tree_quality's bits);
 *   4. the edge information (mesh/edges.c: flat, convex and concave edges, corners, flat pieces,
 *      welded places, normals: all from the positions) is dropped, for the next manifold to make
 *      again from the new positions (ttd_mesh_edges_get): a refit that no manifold follows does
 *      not pay for it, and dropping cannot run out of memory.
 * The point queries' data (src/points/, per node and per triangle) is refreshed by the API entry
 * after this (ttd_points_data_refresh: mesh/ does not include points/). A rebuild
 * (ttd_mesh_build) recomputes it all by itself. What depends on the triangles alone (the closed
 * flag, mesh/solid.c) stays as it is. */
static void refit_derived(const ttd_engine_config *cfg, struct ttd_mesh *m, const void *verts, refit *R)
{
    place(m, verts, NULL, 1); /* and the copy into m->verts */
    refit_boxes(cfg, m, R);
    m->quality = quality_of((const double(*)[2])R->area, m->nnodes);
    if (m->edges != NULL) {
        ttd_mesh_edges_free(m->edges);
        free(m->edges);
        m->edges = NULL;
    }
}

ttd_status ttd_mesh_refit(const ttd_engine_config *cfg, struct ttd_mesh *m, const void *verts)
{
    /* everything is allocated before the mesh changes: out of memory, it is as it was (the
     * scratch and leaf_vix, made for this tree, may stay: the next refit uses them) */
    const ttd_kernels_d *row = ttd_dispatch_row_d(cfg->isa);
    if (m->leaf_vix == NULL) /* the first refit (of this tree) */
        m->leaf_vix = leaf_indices(m);
    refit_scratch *S = refit_scratch_get(m);
    if (S == NULL || m->leaf_vix == NULL)
        return TTD_ERR_OUT_OF_MEMORY;
    refit R = {m, row != NULL ? row->tri_fit : NULL, row != NULL ? row->leaf_span : NULL,
               row != NULL ? row->leaf_axes : NULL, row != NULL ? row->box_span : NULL, S->sums, S->area, S->list};
    m->generation++; /* the vertices are copied by refit_derived's place */
    refit_derived(cfg, m, verts, &R);
    if (m->quality > TTD_MESH_REBUILD_RATIO * m->quality_built)
        rebuild(cfg, m);
    return TTD_OK;
}

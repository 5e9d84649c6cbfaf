/* SPDX-License-Identifier: MIT */
/* A mesh's point data (points/points.h): prepared triangle blocks and winding-number moments,
 * computed from the hierarchy and the vertices by one function (points_compute), made on first use
 * and kept in the mesh. */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/point_layout.h"
#include "engine/parallel.h"
#include "mesh/memory.h"
#include "points/points.h"
#include "scalar/scalar.h"

static void points_free(void *p)
{
    ttd_points_data *pd = p;
    if (pd == NULL)
        return;
    free(pd->pnodes);
    free(pd->rnodes);
    free(pd->blocks);
    free(pd->tiny);
    free(pd->moments);
    ttd_points_caps_free(pd->caps);
    free(pd);
}

/* The child array and count of node n, either precision. */
static const int32_t *node_child(const struct ttd_mesh *m, size_t n, int *count)
{
    if (m->bytes == 8) {
        const ttd_node_d *x = (const ttd_node_d *)m->nodes + n;
        *count = x->count;
        return x->child;
    }
    const ttd_node_f *x = (const ttd_node_f *)m->nodes + n;
    *count = x->count;
    return x->child;
}

/* Vertex k of triangle t, in double, relative to the mesh's origin when rel is set. */
static void tri_vertex(const struct ttd_mesh *m, size_t t, int k, int rel, double out[3])
{
    const size_t v = m->tris[3 * t + (size_t)k];
    for (int c = 0; c < 3; ++c) {
        const double x = m->bytes == 8 ? ((const double *)m->verts)[3 * v + (size_t)c]
                                       : (double)((const float *)m->verts)[3 * v + (size_t)c];
        out[c] = rel ? x - m->origin[c] : x;
    }
}

/* Slot j of mesh node n (either precision) as the walk's float box, scaled by `scale`, into y; its
 * axes' norm bound into *stretch (the largest so far).
 *
 * The mesh's box holds its vertices as the tree sees them (docs/mesh-queries.md, 4.1): |u_a . (x -
 * c)| <= e_a for every vertex x below it, in exact arithmetic, with axes orthonormal to a few eps of
 * the mesh's precision. Scaled (exactly, a power of two), with the centre rounded to c' = c +
 * gamma and the axes to u'_a = u_a + eps_a (both differences exact in double), for such an x:
 *     |u'_a . (x - c')| <= e_a + |u_a| |gamma| + |eps_a| (|x - c| + |gamma|),
 * and |x - c| <= (1 + eta) |e| (eta <= 8 eps, test_mesh_boxes). The extent stored is that bound,
 * formed in double with a relative slack for its own rounding and rounded up to float. */
static void slot_box(const struct ttd_mesh *m, size_t n, int j, double scale, ttd_pnode *y, double *stretch)
{
    double c[3], u[9], e[3];
    for (int k = 0; k < 3; ++k) {
        c[k] = m->bytes == 8 ? ((const ttd_node_d *)m->nodes)[n].c[k][j] : (double)((const ttd_node_f *)m->nodes)[n].c[k][j];
        e[k] = m->bytes == 8 ? ((const ttd_node_d *)m->nodes)[n].e[k][j] : (double)((const ttd_node_f *)m->nodes)[n].e[k][j];
    }
    for (int k = 0; k < 9; ++k)
        u[k] = m->bytes == 8 ? ((const ttd_node_d *)m->nodes)[n].u[k][j] : (double)((const ttd_node_f *)m->nodes)[n].u[k][j];
    const double eta = 8 * (m->bytes == 8 ? DBL_EPSILON : (double)FLT_EPSILON);
    double g2 = 0, ee = 0;
    for (int k = 0; k < 3; ++k) {
        volatile float cf = (float)(c[k] * scale); /* the rounding must happen (docs/mesh-queries.md, 4.1) */
        y->c[k][j] = cf;
        const double gk = (double)y->c[k][j] - c[k] * scale;
        g2 += gk * gk;
        ee += e[k] * scale * e[k] * scale;
    }
    const double gamma = sqrt(g2) * (1 + 1e-12), span = sqrt(ee) * (1 + eta) * (1 + 1e-12);
    double uf[9];
    for (int a = 0; a < 3; ++a) {
        double d2 = 0, n2 = 0;
        for (int k = 0; k < 3; ++k) {
            volatile float x = (float)u[3 * a + k];
            y->u[3 * a + k][j] = x;
            uf[3 * a + k] = (double)y->u[3 * a + k][j];
            const double dk = uf[3 * a + k] - u[3 * a + k];
            d2 += dk * dk;
            n2 += u[3 * a + k] * u[3 * a + k];
        }
        const double ext = (e[a] * scale + sqrt(n2) * (1 + 1e-12) * gamma + sqrt(d2) * (1 + 1e-12) * (span + gamma)) *
                           (1 + 1e-12);
        y->e[a][j] = ttd_float_up(ext);
    }
    /* |U'| <= sqrt(1 + |U' U'^T - I|_F), the Gram matrix's error formed in double (its own rounding,
     * near 1e-16, is far below the float axes' 1e-7) */
    double f2 = 0;
    for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) {
            const double g = uf[3 * a] * uf[3 * b] + uf[3 * a + 1] * uf[3 * b + 1] + uf[3 * a + 2] * uf[3 * b + 2] - (a == b);
            f2 += g * g;
        }
    const double st = sqrt(1 + sqrt(f2) * (1 + 1e-6)) * (1 + 1e-12);
    *stretch = st > *stretch ? st : *stretch;
}

typedef struct prep_job {
    const struct ttd_mesh *m;
    ttd_points_data *pd;
    double *stretch; /* per block of nodes: the largest axes' norm bound there */
} prep_job;

#define PREP_NODES 256 /* nodes per block of the parallel preparation */

/* The walk nodes' boxes and the prepared blocks of nodes [256 b, 256 b + 256). */
static void prepare_blocks(void *ctx, size_t b, int worker)
{
    (void)worker;
    const prep_job *J = ctx;
    const struct ttd_mesh *m = J->m;
    const ttd_points_data *pd = J->pd;
    const size_t n1 = (b + 1) * PREP_NODES < pd->nnodes ? (b + 1) * PREP_NODES : pd->nnodes;
    double stretch = 1;
    for (size_t n = b * PREP_NODES; n < n1; ++n)
        for (int j = 0; j < TTD_NODE_WIDTH; ++j)
            if ((uint32_t)j < pd->pnodes[n].nslots)
                slot_box(m, n, j, pd->scale, &pd->pnodes[n], &stretch);
    J->stretch[b] = stretch;
    for (size_t n = b * PREP_NODES; n < n1; ++n) {
        const int32_t blk = pd->pnodes[n].block;
        if (blk < 0)
            continue;
        int count;
        const int32_t *child = node_child(m, n, &count);
        int first = 0; /* a slot without a triangle gets a copy of the node's first triangle */
        while (child[first] >= 0)
            ++first;
        for (int j = 0; j < TTD_NODE_WIDTH; ++j) {
            const int src = j < count && child[j] < 0 ? j : first;
            const size_t t = (size_t)(-1 - child[src]);
            const size_t off = (size_t)blk * TTD_PT_ROWS * TTD_PT_LANES + (size_t)j;
            if (m->bytes == 8) {
                double v[9];
                for (int k = 0; k < 9; ++k)
                    v[k] = ((const double *)m->verts)[3 * (size_t)m->tris[3 * t + (size_t)(k / 3)] + (size_t)(k % 3)];
                ttd_point_prepare_d(v, (double *)pd->blocks + off, TTD_PT_LANES);
                ((double *)pd->blocks)[off + (size_t)TTD_PT_COUNT * TTD_PT_LANES] = 0;
            } else {
                float v[9];
                for (int k = 0; k < 9; ++k)
                    v[k] = ((const float *)m->verts)[3 * (size_t)m->tris[3 * t + (size_t)(k / 3)] + (size_t)(k % 3)];
                ttd_point_prepare_f(v, (float *)pd->blocks + off, TTD_PT_LANES);
                ((float *)pd->blocks)[off + (size_t)TTD_PT_COUNT * TTD_PT_LANES] = 0;
            }
        }
    }
}

/* Slot j of ray node y holds triangle t: its box from the vertices as the tree sees them (minus the
 * origin, rounded to double), scaled (exactly) and rounded outward. */
static void triangle_rbox(const struct ttd_mesh *m, double scale, size_t t, ttd_rnode *y, int j)
{
    double v[3][3];
    for (int k = 0; k < 3; ++k)
        tri_vertex(m, t, k, 1, v[k]);
    for (int c = 0; c < 3; ++c) {
        const double lo = fmin(fmin(v[0][c], v[1][c]), v[2][c]), hi = fmax(fmax(v[0][c], v[1][c]), v[2][c]);
        y->lo[c][j] = ttd_float_down(lo * scale);
        y->hi[c][j] = ttd_float_up(hi * scale);
    }
}

/* Slot j of ray node y holds node x: the union of x's boxes (exact in float). */
static void node_rbox(const ttd_rnode *x, ttd_rnode *y, int j)
{
    for (int c = 0; c < 3; ++c) {
        float lo = INFINITY, hi = -INFINITY;
        for (int i = 0; i < TTD_NODE_WIDTH; ++i) {
            lo = x->lo[c][i] < lo ? x->lo[c][i] : lo;
            hi = x->hi[c][i] > hi ? x->hi[c][i] : hi;
        }
        y->lo[c][j] = lo;
        y->hi[c][j] = hi;
    }
}

/* A slot this much smaller than the mesh (in the walk's frame, where the mesh's radius is about 1)
 * has moments whose powers may leave the range of doubles (its polar moment, a fourth power, below
 * 2^-1000): its remainder's bound is made +inf, so that the walk always opens it (and its ancestors)
 * and measures its triangles exactly (points/winding.c). */
#define WM_TINY 0x1p-200

/* The moments of triangle t (relative to the origin, times scale: the walk's frame, where powers
 * of the mesh's size neither overflow nor underflow at any scale of the coordinate range) into
 * w[f * TTD_NODE_WIDTH] (slot j's base). */
static void triangle_moments(const struct ttd_mesh *m, double scale, size_t t, double *w)
{
    double v[3][3], e1[3], e2[3], n[3];
    for (int k = 0; k < 3; ++k) {
        tri_vertex(m, t, k, 1, v[k]);
        for (int c = 0; c < 3; ++c)
            v[k][c] *= scale; /* a power of two: exact */
    }
    for (int c = 0; c < 3; ++c) {
        e1[c] = v[1][c] - v[0][c];
        e2[c] = v[2][c] - v[0][c];
    }
    n[0] = 0.5 * (e1[1] * e2[2] - e1[2] * e2[1]);
    n[1] = 0.5 * (e1[2] * e2[0] - e1[0] * e2[2]);
    n[2] = 0.5 * (e1[0] * e2[1] - e1[1] * e2[0]);
    double r2 = 0;
    for (int c = 0; c < 3; ++c) {
        w[(WM_N + c) * TTD_NODE_WIDTH] = n[c];
        w[(WM_C + c) * TTD_NODE_WIDTH] = (v[0][c] + v[1][c] + v[2][c]) / 3;
    }
    for (int k = 0; k < 3; ++k) {
        double d2 = 0;
        for (int c = 0; c < 3; ++c) {
            const double d = v[k][c] - w[(WM_C + c) * TTD_NODE_WIDTH];
            d2 += d * d;
        }
        r2 = d2 > r2 ? d2 : r2;
    }
    for (int i = 0; i < 9; ++i) /* the first moment about the centroid vanishes */
        w[(WM_M + i) * TTD_NODE_WIDTH] = 0;
    const double area = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    w[WM_AREA * TTD_NODE_WIDTH] = area;
    w[WM_RADIUS * TTD_NODE_WIDTH] = sqrt(r2) * (1 + 1e-12);
    /* the polar moment about the stored centre g': (A / 12) (|v0 - g'|^2 + |v1 - g'|^2 + |v2 - g'|^2)
     * is it about the exact centroid g plus A |g - g'|^2 / 4, against A |g - g'|^2 about g': the
     * difference, with |g - g'| below 2 eps |v|_max per coordinate, is added */
    double s = 0, big = 0;
    for (int k = 0; k < 3; ++k)
        for (int c = 0; c < 3; ++c) {
            const double d = v[k][c] - w[(WM_C + c) * TTD_NODE_WIDTH];
            s += d * d;
            big = fmax(big, fabs(v[k][c]));
        }
    const double off = 2 * DBL_EPSILON * big;
    w[WM_I * TTD_NODE_WIDTH] = (area / 12 * s + area * 3 * off * off) * (1 + 1e-12);
    /* A triangle below 2^-20 of its distance from the origin has vertices whose shift to it rounded
     * by up to 2^-33 of its size or more (all of it, below 2^-53): its moments describe another
     * triangle, and the remainder bound says nothing of the difference. A cube 2^-137 the size of
     * a mesh beside it came out flat here (moments 0, bound 0), and a point near it got its side
     * of |w| = 1/2 wrong, proven (the point fuzzer's tiny boxes). Such a triangle is measured
     * exactly instead (its solid angle from the mesh's own coordinates), as a tiny slot is. */
    if (!(w[WM_RADIUS * TTD_NODE_WIDTH] >= WM_TINY) || !(w[WM_RADIUS * TTD_NODE_WIDTH] >= 0x1p-20 * big))
        w[WM_I * TTD_NODE_WIDTH] = HUGE_VAL;
}

/* The moments of node c's slots summed into one slot (w, stride TTD_NODE_WIDTH): the area vectors
 * and areas add, the centre is the area-weighted mean (the plain mean without area), the second
 * moments move to it (M += (c_i - pc) n_i^T), and the radius holds every child's ball. */
static void node_moments(const double *moments, size_t c, int count, double *w)
{
    const double *x = moments + c * WM_COUNT * TTD_NODE_WIDTH;
#define X(f, j) x[(size_t)(f) * TTD_NODE_WIDTH + (size_t)(j)]
#define W(f) w[(size_t)(f) * TTD_NODE_WIDTH]
    double area = 0, pc[3] = {0, 0, 0}, mean[3] = {0, 0, 0};
    for (int j = 0; j < count; ++j) {
        area += X(WM_AREA, j);
        for (int k = 0; k < 3; ++k) {
            pc[k] += X(WM_AREA, j) * X(WM_C + k, j);
            mean[k] += X(WM_C + k, j) / count;
        }
    }
    for (int k = 0; k < 3; ++k)
        pc[k] = area > 0 ? pc[k] / area : mean[k];
    double radius = 0, M[9] = {0}, N[3] = {0}, polar = 0;
    for (int j = 0; j < count; ++j) {
        double d[3], d2 = 0;
        for (int k = 0; k < 3; ++k) {
            d[k] = X(WM_C + k, j) - pc[k];
            d2 += d[k] * d[k];
            N[k] += X(WM_N + k, j);
        }
        /* the parallel axis theorem (about any centre); d's rounding (below 2 eps |c_j| per
         * coordinate) is added */
        const double off = 2 * DBL_EPSILON * (fabs(X(WM_C, j)) + fabs(X(WM_C + 1, j)) + fabs(X(WM_C + 2, j)));
        polar += X(WM_I, j) + X(WM_AREA, j) * (d2 + 2 * sqrt(d2) * off * 1.8 + 3 * off * off);
        for (int a = 0; a < 3; ++a)
            for (int b = 0; b < 3; ++b)
                M[3 * a + b] += X(WM_M + 3 * a + b, j) + d[a] * X(WM_N + b, j);
        const double r = sqrt(d2) + X(WM_RADIUS, j);
        radius = r > radius ? r : radius;
    }
    for (int k = 0; k < 3; ++k) {
        W(WM_N + k) = N[k];
        W(WM_C + k) = pc[k];
    }
    for (int i = 0; i < 9; ++i)
        W(WM_M + i) = M[i];
    W(WM_AREA) = area;
    W(WM_RADIUS) = radius * (1 + 1e-12); /* covers the rounding of the sums above */
    W(WM_I) = radius >= WM_TINY ? polar * (1 + 1e-12) : HUGE_VAL;
#undef X
#undef W
}

/* The winding-number moments of every slot, bottom-up (a node's children come after it in the
 * pre-order numbering, so a reverse pass sees them first). */
static void moments_compute(const struct ttd_mesh *m, double scale, double *moments)
{
    for (size_t n = m->nnodes; n-- > 0;) {
        int count;
        const int32_t *child = node_child(m, n, &count);
        double *w = moments + n * WM_COUNT * TTD_NODE_WIDTH;
        memset(w, 0, WM_COUNT * TTD_NODE_WIDTH * sizeof *w);
        for (int j = 0; j < count; ++j) {
            if (child[j] < 0) {
                triangle_moments(m, scale, (size_t)(-1 - child[j]), w + j);
            } else {
                int cc;
                (void)node_child(m, (size_t)child[j], &cc);
                node_moments(moments, (size_t)child[j], cc, w + j);
            }
        }
    }
}

/* Everything, from the hierarchy and the vertices: the blocks in parallel, then the ray boxes
 * bottom-up, and the moments where a winding walk has made them (moments_get). */
static int points_compute(const struct ttd_mesh *m, ttd_points_data *pd, int threads)
{
    /* the walk nodes' scale: the power of two at or above the radius (at least 2^-1000) */
    int e;
    (void)frexp(m->radius, &e);
    pd->scale = ldexp(1.0, -(e < -1000 ? -1000 : e));
    const size_t nb = (pd->nnodes + PREP_NODES - 1) / PREP_NODES;
    prep_job J = {m, pd, malloc(nb * sizeof(double))};
    if (J.stretch == NULL)
        return -1;
    ttd_parallel_for(nb, threads, prepare_blocks, &J);
    for (size_t t = 0; pd->tiny != NULL && t < m->nt; ++t) {
        if (m->bytes == 8) {
            double v[9];
            for (int k = 0; k < 9; ++k)
                v[k] = ((const double *)m->verts)[3 * (size_t)m->tris[3 * t + (size_t)(k / 3)] + (size_t)(k % 3)];
            ttd_point_prepare_d(v, (double *)pd->tiny + t * TTD_PT_COUNT, 1);
        } else {
            float v[9];
            for (int k = 0; k < 9; ++k)
                v[k] = ((const float *)m->verts)[3 * (size_t)m->tris[3 * t + (size_t)(k / 3)] + (size_t)(k % 3)];
            ttd_point_prepare_f(v, (float *)pd->tiny + t * TTD_PT_COUNT, 1);
        }
    }
    pd->coord_max = 0;
    for (size_t i = 0; i < 3 * m->nv; ++i) {
        const double x = fabs(m->bytes == 8 ? ((const double *)m->verts)[i] : (double)((const float *)m->verts)[i]);
        pd->coord_max = x > pd->coord_max ? x : pd->coord_max;
    }
    pd->stretch = 1;
    for (size_t b = 0; b < nb; ++b)
        pd->stretch = J.stretch[b] > pd->stretch ? J.stretch[b] : pd->stretch;
    free(J.stretch);
    for (size_t n = pd->nnodes; n-- > 0;) {
        int count;
        const int32_t *child = node_child(m, n, &count);
        ttd_rnode *y = &pd->rnodes[n];
        for (int j = 0; j < TTD_NODE_WIDTH; ++j) {
            y->child[j] = j < count ? child[j] : 0;
            for (int c = 0; c < 3; ++c) {
                y->lo[c][j] = INFINITY;
                y->hi[c][j] = -INFINITY;
            }
        }
        for (int j = 0; j < count; ++j) {
            if (child[j] < 0)
                triangle_rbox(m, pd->scale, (size_t)(-1 - child[j]), y, j);
            else
                node_rbox(&pd->rnodes[child[j]], y, j);
        }
    }
    if (pd->moments != NULL)
        moments_compute(m, pd->scale, pd->moments);
    return 0;
}

const double *ttd_points_moments(const struct ttd_mesh *mesh, const ttd_points_data *pd)
{
    /* a cache of what the mesh determines, as the point data itself */
    ttd_points_data *p = (ttd_points_data *)(uintptr_t)pd;
    double *w = __atomic_load_n(&p->moments, __ATOMIC_ACQUIRE);
    if (w != NULL)
        return w;
    w = ttd_big_alloc(mesh->nnodes * WM_COUNT * TTD_NODE_WIDTH * sizeof(double));
    if (w == NULL)
        return NULL;
    moments_compute(mesh, pd->scale, w);
    double *expected = NULL;
    if (!__atomic_compare_exchange_n(&p->moments, &expected, w, 0, __ATOMIC_ACQ_REL, __ATOMIC_ACQUIRE)) {
        free(w); /* another thread made them first: the same numbers */
        return expected;
    }
    return w;
}

static ttd_points_data *points_make(const struct ttd_mesh *m, int threads)
{
    ttd_points_data *pd = calloc(1, sizeof *pd);
    if (pd == NULL)
        return NULL;
    pd->destroy = points_free;
    pd->bytes = m->bytes;
    pd->nnodes = m->nnodes;
    pd->pnodes = ttd_big_alloc(m->nnodes * sizeof *pd->pnodes);
    pd->rnodes = ttd_big_alloc(m->nnodes * sizeof *pd->rnodes);
    if (pd->pnodes == NULL || pd->rnodes == NULL)
        goto fail;

    for (size_t n = 0; n < m->nnodes; ++n) {
        int count;
        const int32_t *child = node_child(m, n, &count);
        ttd_pnode *y = &pd->pnodes[n];
        memset(y, 0, sizeof *y);
        unsigned mask = 0;
        y->nslots = (uint32_t)count;
        for (int j = 0; j < TTD_NODE_WIDTH; ++j) {
            for (int a = 0; a < 3; ++a) /* an unused slot: no point is within it */
                y->e[a][j] = -INFINITY;
            if (j < count) {
                y->child[j] = child[j];
                mask |= (unsigned)(child[j] < 0) << j;
            }
        }
        y->tmask = mask;
        y->ntri = (uint32_t)__builtin_popcount(mask);
        y->block = mask ? (int32_t)pd->nblocks++ : -1;
    }

    pd->blocks = ttd_big_alloc(pd->nblocks * TTD_PT_ROWS * TTD_PT_LANES * (size_t)m->bytes);
    if (m->nt <= TTD_POINTS_TINY && (pd->tiny = malloc(m->nt * TTD_PT_COUNT * (size_t)m->bytes)) == NULL)
        goto fail;
    if (pd->blocks == NULL)
        goto fail;
    if (points_compute(m, pd, threads) != 0)
        goto fail;
    (void)ttd_mesh_closed(m); /* the winding number's choice (points/ray.c), kept in the mesh */
    return pd;
fail:
    points_free(pd);
    return NULL;
}

const ttd_points_data *ttd_points_data_get(const struct ttd_mesh *mesh, int threads)
{
    /* a cache of what the immutable mesh determines, not a change to it */
    struct ttd_mesh *m = (struct ttd_mesh *)(uintptr_t)mesh;
    ttd_points_data *pd = __atomic_load_n((ttd_points_data **)&m->points, __ATOMIC_ACQUIRE);
    if (pd != NULL)
        return pd;
    pd = points_make(m, threads);
    if (pd == NULL)
        return NULL;
    void *expected = NULL;
    if (!__atomic_compare_exchange_n(&m->points, &expected, pd, 0, __ATOMIC_ACQ_REL, __ATOMIC_ACQUIRE)) {
        points_free(pd); /* another thread made it first: the same data */
        return expected;
    }
    return pd;
}

void ttd_points_data_refresh(struct ttd_mesh *mesh, int threads)
{
    if (mesh->points != NULL) { /* the caps' apexes and boundary follow the vertices: made again on use */
        ttd_points_data *pd = mesh->points;
        ttd_points_caps_free(pd->caps);
        pd->caps = NULL;
    }
    if (mesh->points != NULL && points_compute(mesh, mesh->points, threads) != 0) {
        /* out of memory: drop the point data (the next point query makes it again) */
        ttd_points_data *pd = mesh->points;
        mesh->points = NULL;
        points_free(pd);
    }
}

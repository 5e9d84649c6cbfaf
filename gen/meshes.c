/* SPDX-License-Identifier: MIT */
/* Mesh generators and poses (see meshes.h). Subdivision shares each edge's midpoint through a
 * small open-addressing table keyed by the edge's two vertex indices; the midpoint's index is
 * given when the edge is first met in triangle order, so the numbering never depends on the
 * table's layout. The icosahedron's faces are found rather than listed: the vertex triples at
 * mutual edge length, oriented outward by the sign of their determinant. */
#include "meshes.h"

#include "pairs.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void ttd_gen_mesh_free(ttd_gen_mesh *m)
{
    if (!m)
        return;
    free(m->verts);
    free(m->tris);
    memset(m, 0, sizeof *m);
}

/// Allocates room for nv vertices and nt triangles; *m zeroed on failure.
static int mesh_alloc(ttd_gen_mesh *m, size_t nv, size_t nt)
{
    memset(m, 0, sizeof *m);
    if (nv == 0 || nt == 0 || nv > SIZE_MAX / (3 * sizeof(double)) || nt > SIZE_MAX / (3 * sizeof(uint32_t)))
        return -1;
    m->verts = malloc(3 * nv * sizeof(double));
    m->tris = malloc(3 * nt * sizeof(uint32_t));
    if (!m->verts || !m->tris) {
        ttd_gen_mesh_free(m);
        return -1;
    }
    m->nv = nv;
    m->nt = nt;
    return 0;
}

/// A well-formed mesh: arrays present, counts non-zero, every index below nv.
static int mesh_valid(const ttd_gen_mesh *m)
{
    if (!m || !m->verts || !m->tris || m->nv == 0 || m->nt == 0 || m->nv > UINT32_MAX)
        return 0;
    for (size_t k = 0; k < 3 * m->nt; ++k)
        if (m->tris[k] >= m->nv)
            return 0;
    return 1;
}

int ttd_gen_mesh_copy(const ttd_gen_mesh *in, ttd_gen_mesh *out)
{
    if (!out)
        return -1;
    if (!in || !in->verts || !in->tris || in == out || mesh_alloc(out, in->nv, in->nt) != 0) {
        memset(out, 0, sizeof *out);
        return -1;
    }
    memcpy(out->verts, in->verts, 3 * in->nv * sizeof(double));
    memcpy(out->tris, in->tris, 3 * in->nt * sizeof(uint32_t));
    return 0;
}

/// A mesh from literal arrays.
static int mesh_from(ttd_gen_mesh *out, const double *v, size_t nv, const uint32_t *t, size_t nt)
{
    if (!out)
        return -1;
    if (mesh_alloc(out, nv, nt) != 0)
        return -1;
    memcpy(out->verts, v, 3 * nv * sizeof(double));
    memcpy(out->tris, t, 3 * nt * sizeof(uint32_t));
    return 0;
}

/* ---- edge midpoints ------------------------------------------------------------------ */

/// Open addressing from an edge (lower index << 32 | higher index) to its midpoint's index.
typedef struct edge_table {
    uint64_t *keys;
    uint32_t *vals;
    size_t mask;
} edge_table;

#define EDGE_EMPTY UINT64_MAX /* no edge has it: indices stay below UINT32_MAX */

static int edge_table_init(edge_table *e, size_t edges)
{
    size_t cap = 16;
    while (cap < 2 * edges) {
        if (cap > SIZE_MAX / 4 / sizeof(uint64_t))
            return -1;
        cap *= 2;
    }
    e->keys = malloc(cap * sizeof *e->keys);
    e->vals = malloc(cap * sizeof *e->vals);
    e->mask = cap - 1;
    if (!e->keys || !e->vals) {
        free(e->keys);
        free(e->vals);
        return -1;
    }
    for (size_t k = 0; k < cap; ++k)
        e->keys[k] = EDGE_EMPTY;
    return 0;
}

static void edge_table_free(edge_table *e)
{
    free(e->keys);
    free(e->vals);
}

/// The slot of edge (a, b): where it is, or the empty slot where it goes.
static size_t edge_slot(const edge_table *e, uint32_t a, uint32_t b, uint64_t *key)
{
    *key = a < b ? ((uint64_t)a << 32 | b) : ((uint64_t)b << 32 | a);
    size_t h = (size_t)((*key * 0x9E3779B97F4A7C15ull) >> 17) & e->mask;
    while (e->keys[h] != EDGE_EMPTY && e->keys[h] != *key)
        h = (h + 1) & e->mask;
    return h;
}

/// One 4:1 split of (v, nv, t, nt) into out; spherical pushes the new vertices to radius 1.
static int split_once(const double *v, size_t nv, const uint32_t *t, size_t nt, int spherical,
                      ttd_gen_mesh *out)
{
    memset(out, 0, sizeof *out);
    if (nt > SIZE_MAX / 4 / (3 * sizeof(uint32_t)))
        return -1;
    /* at most one new vertex per triangle side; more than UINT32_MAX is caught when adding */
    size_t cap_v = 3 * nt > UINT32_MAX - nv ? UINT32_MAX : nv + 3 * nt;
    edge_table e;
    if (edge_table_init(&e, 3 * nt) != 0)
        return -1;
    if (mesh_alloc(out, cap_v, 4 * nt) != 0) {
        edge_table_free(&e);
        return -1;
    }
    memcpy(out->verts, v, 3 * nv * sizeof(double));
    size_t n = nv;
    for (size_t f = 0; f < nt; ++f) {
        uint32_t c[3], m[3];
        for (int k = 0; k < 3; ++k)
            c[k] = t[3 * f + (size_t)k];
        for (int k = 0; k < 3; ++k) {
            uint32_t a = c[k], b = c[(k + 1) % 3];
            uint64_t key;
            size_t h = edge_slot(&e, a, b, &key);
            if (e.keys[h] == key) {
                m[k] = e.vals[h];
                continue;
            }
            if (n >= cap_v) { /* 2^32 - 1 vertices reached */
                edge_table_free(&e);
                ttd_gen_mesh_free(out);
                return -1;
            }
            const double *pa = v + 3 * (size_t)a, *pb = v + 3 * (size_t)b;
            double *q = out->verts + 3 * n;
            if (spherical) {
                double x = pa[0] + pb[0], y = pa[1] + pb[1], z = pa[2] + pb[2];
                double inv = 1.0 / sqrt(x * x + y * y + z * z);
                q[0] = x * inv; q[1] = y * inv; q[2] = z * inv;
            } else {
                for (int d = 0; d < 3; ++d)
                    q[d] = 0.5 * pa[d] + 0.5 * pb[d];
            }
            e.keys[h] = key;
            e.vals[h] = (uint32_t)n;
            m[k] = (uint32_t)n++;
        }
        /* m[0] = ab, m[1] = bc, m[2] = ca */
        const uint32_t quad[12] = {c[0], m[0], m[2], m[0], c[1], m[1], m[2], m[1], c[2], m[0], m[1], m[2]};
        memcpy(out->tris + 12 * f, quad, sizeof quad);
    }
    edge_table_free(&e);
    double *shrunk = realloc(out->verts, 3 * n * sizeof(double));
    if (shrunk)
        out->verts = shrunk;
    out->nv = n;
    return 0;
}

/// levels splits of in into out (out may alias in).
static int split_levels(const ttd_gen_mesh *in, int levels, int spherical, ttd_gen_mesh *out)
{
    ttd_gen_mesh cur, next;
    if (ttd_gen_mesh_copy(in, &cur) != 0)
        return -1;
    for (int l = 0; l < levels; ++l) {
        int rc = split_once(cur.verts, cur.nv, cur.tris, cur.nt, spherical, &next);
        ttd_gen_mesh_free(&cur);
        if (rc != 0)
            return -1;
        cur = next;
    }
    if (out == in)
        ttd_gen_mesh_free(out);
    *out = cur;
    return 0;
}

int ttd_gen_subdivide(const ttd_gen_mesh *in, int levels, ttd_gen_mesh *out)
{
    if (!out)
        return -1;
    if (!mesh_valid(in) || levels < 0 || levels > 16) {
        if (out != in)
            memset(out, 0, sizeof *out);
        return -1;
    }
    if (split_levels(in, levels, 0, out) != 0) {
        if (out != in)
            memset(out, 0, sizeof *out);
        return -1;
    }
    return 0;
}

/* ---- closed surfaces ----------------------------------------------------------------- */

static double det3(const double *a, const double *b, const double *c)
{
    return a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
           a[2] * (b[0] * c[1] - b[1] * c[0]);
}

static double dist2(const double *a, const double *b)
{
    double x = a[0] - b[0], y = a[1] - b[1], z = a[2] - b[2];
    return x * x + y * y + z * z;
}

/// The icosahedron on the unit sphere.
static int icosahedron(ttd_gen_mesh *out)
{
    const double g = 0.5 * (1.0 + sqrt(5.0)); /* golden ratio */
    double v[36];
    int n = 0;
    /* the cyclic permutations of (0, +-1, +-g) */
    for (int axis = 0; axis < 3; ++axis)
        for (int s1 = -1; s1 <= 1; s1 += 2)
            for (int s2 = -1; s2 <= 1; s2 += 2) {
                double p[3];
                p[axis] = 0.0;
                p[(axis + 1) % 3] = s1;
                p[(axis + 2) % 3] = s2 * g;
                memcpy(v + 3 * n++, p, sizeof p);
            }
    /* Edges have squared length 4 (before scaling); the next closest pairs 4 g^2 ~ 10.5. */
    uint32_t t[60];
    int nt = 0;
    for (uint32_t i = 0; i < 12; ++i)
        for (uint32_t j = i + 1; j < 12; ++j)
            for (uint32_t k = j + 1; k < 12; ++k) {
                const double *a = v + 3 * i, *b = v + 3 * j, *c = v + 3 * k;
                if (dist2(a, b) > 6 || dist2(b, c) > 6 || dist2(a, c) > 6)
                    continue;
                /* outward: det(a, b, c) > 0 for a face of a convex body around the origin */
                int flip = det3(a, b, c) < 0;
                t[3 * nt] = i;
                t[3 * nt + 1] = flip ? k : j;
                t[3 * nt + 2] = flip ? j : k;
                ++nt;
            }
    if (nt != 20)
        return -1;
    const double inv = 1.0 / sqrt(1.0 + g * g);
    for (int k = 0; k < 36; ++k)
        v[k] *= inv;
    return mesh_from(out, v, 12, t, 20);
}

int ttd_gen_icosphere(int level, ttd_gen_mesh *out)
{
    if (!out)
        return -1;
    memset(out, 0, sizeof *out);
    if (level < 0 || level > 10)
        return -1;
    ttd_gen_mesh ico;
    if (icosahedron(&ico) != 0)
        return -1;
    int rc = split_levels(&ico, level, 1, out);
    ttd_gen_mesh_free(&ico);
    return rc;
}

int ttd_gen_torus(double R, double r, size_t nu, size_t nv, ttd_gen_mesh *out)
{
    if (!out)
        return -1;
    memset(out, 0, sizeof *out);
    if (!(r > 0) || !(R > r) || !isfinite(R) || nu < 3 || nv < 3 || nu > UINT32_MAX / nv)
        return -1;
    size_t n = nu * nv;
    if (n > SIZE_MAX / 2 || mesh_alloc(out, n, 2 * n) != 0)
        return -1;
    double *cb = malloc(2 * nv * sizeof(double));
    if (!cb) {
        ttd_gen_mesh_free(out);
        return -1;
    }
    const double two_pi = 6.283185307179586476925286766559;
    for (size_t j = 0; j < nv; ++j) {
        double b = two_pi * (double)j / (double)nv;
        cb[2 * j] = cos(b);
        cb[2 * j + 1] = sin(b);
    }
    for (size_t i = 0; i < nu; ++i) {
        double a = two_pi * (double)i / (double)nu, ca = cos(a), sa = sin(a);
        for (size_t j = 0; j < nv; ++j) {
            double rho = R + r * cb[2 * j];
            double *p = out->verts + 3 * (i * nv + j);
            p[0] = rho * ca;
            p[1] = rho * sa;
            p[2] = r * cb[2 * j + 1];
        }
    }
    free(cb);
    /* d/da x d/db points outward, so (i,j) (i+1,j) (i+1,j+1) is counter-clockwise from outside */
    uint32_t *t = out->tris;
    for (size_t i = 0; i < nu; ++i) {
        size_t i1 = (i + 1) % nu;
        for (size_t j = 0; j < nv; ++j) {
            size_t j1 = (j + 1) % nv;
            uint32_t a = (uint32_t)(i * nv + j), b = (uint32_t)(i1 * nv + j);
            uint32_t c = (uint32_t)(i1 * nv + j1), d = (uint32_t)(i * nv + j1);
            t[0] = a; t[1] = b; t[2] = c;
            t[3] = a; t[4] = c; t[5] = d;
            t += 6;
        }
    }
    return 0;
}

/* ---- small meshes -------------------------------------------------------------------- */

int ttd_gen_mesh_triangle(ttd_gen_mesh *out)
{
    static const double v[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    static const uint32_t t[] = {0, 1, 2};
    return mesh_from(out, v, 3, t, 1);
}

int ttd_gen_mesh_tetrahedron(ttd_gen_mesh *out)
{
    static const double v[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    static const uint32_t t[] = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
    return mesh_from(out, v, 4, t, 4);
}

/* The cube's faces as quads (a, b, c, d), counter-clockwise from outside, vertex x + 2y + 4z;
 * each becomes (a, b, c) and (a, c, d). */
static const uint32_t cube_quads[6][4] = {
    {0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5},
};

static void cube_corner(uint32_t k, double *p)
{
    p[0] = (double)(k & 1);
    p[1] = (double)((k >> 1) & 1);
    p[2] = (double)((k >> 2) & 1);
}

int ttd_gen_mesh_cube(ttd_gen_mesh *out)
{
    double v[24];
    uint32_t t[36];
    for (uint32_t k = 0; k < 8; ++k)
        cube_corner(k, v + 3 * k);
    for (int f = 0; f < 6; ++f) {
        const uint32_t *q = cube_quads[f];
        const uint32_t tri[6] = {q[0], q[1], q[2], q[0], q[2], q[3]};
        memcpy(t + 6 * f, tri, sizeof tri);
    }
    return mesh_from(out, v, 8, t, 12);
}

int ttd_gen_mesh_duplicate_vertices(ttd_gen_mesh *out)
{
    double v[72];
    uint32_t t[36];
    for (uint32_t f = 0; f < 6; ++f) {
        for (uint32_t k = 0; k < 4; ++k)
            cube_corner(cube_quads[f][k], v + 3 * (4 * f + k));
        const uint32_t b = 4 * f, tri[6] = {b, b + 1, b + 2, b, b + 2, b + 3};
        memcpy(t + 6 * f, tri, sizeof tri);
    }
    return mesh_from(out, v, 24, t, 12);
}

int ttd_gen_mesh_degenerate(ttd_gen_mesh *out)
{
    static const double v[] = {
        0, 0, 0,   1, 0, 0,   0, 1, 0,          /* 0-2: a plain triangle */
        2, 0, 0,                                /* 3: on the x axis with 0 and 1 */
        0, 1, 0,                                /* 4: the coordinates of 2 again */
        0, 0, 1,   1, 0, 1,   1, 1e-10, 1,      /* 5-7: a needle */
        0, 0, 2,   1, 0, 2,   0.5, 1e-10, 2,    /* 8-10: a flat cap */
    };
    static const uint32_t t[] = {
        0, 1, 2,   /* plain */
        0, 0, 2,   /* repeated index: a segment */
        1, 1, 1,   /* a point */
        0, 1, 3,   /* collinear */
        0, 2, 4,   /* two distinct vertices at the same place */
        5, 6, 7,   /* needle */
        8, 9, 10,  /* cap */
    };
    return mesh_from(out, v, 11, t, 7);
}

int ttd_gen_mesh_nonmanifold(ttd_gen_mesh *out)
{
    static const double v[] = {0, 0, 0, 1, 0, 0, 0.5, 1, 0, 0.5, -0.5, 0.75, 0.5, -0.5, -0.75};
    static const uint32_t t[] = {0, 1, 2, 1, 0, 3, 0, 1, 4};
    return mesh_from(out, v, 5, t, 3);
}

/* An nx x ny grid of square quads of edge 1/nx (vertex (i, j) = index j*(nx+1) + i at (i/nx, j/nx, 0)),
 * each split along its diagonal from (i, j) to (i+1, j+1): ttd_gen_grid's layout for any width. */
static int grid_rect(size_t nx, size_t ny, ttd_gen_mesh *out)
{
    const size_t w = nx + 1, h = ny + 1;
    if (nx < 1 || ny < 1 || nx >= 65535 || ny >= 65535 || w * h >= ((size_t)1 << 32))
        return -1;
    if (mesh_alloc(out, w * h, 2 * nx * ny) != 0)
        return -1;
    for (size_t j = 0; j < h; ++j)
        for (size_t i = 0; i < w; ++i) {
            double *p = out->verts + 3 * (j * w + i);
            p[0] = (double)i / (double)nx;
            p[1] = (double)j / (double)nx;
            p[2] = 0.0;
        }
    uint32_t *t = out->tris;
    for (size_t j = 0; j < ny; ++j)
        for (size_t i = 0; i < nx; ++i) {
            uint32_t a = (uint32_t)(j * w + i), b = a + 1, c = (uint32_t)((j + 1) * w + i + 1), d = c - 1;
            t[0] = a; t[1] = b; t[2] = c;
            t[3] = a; t[4] = c; t[5] = d;
            t += 6;
        }
    return 0;
}

int ttd_gen_grid(size_t n, ttd_gen_mesh *out)
{
    if (!out)
        return -1;
    memset(out, 0, sizeof *out);
    return grid_rect(n, n, out);
}

int ttd_gen_folded_sheet(size_t n, int layers, double gap, double t, ttd_gen_mesh *out)
{
    return ttd_gen_folded_strip(n, n, layers, gap, t, out);
}

int ttd_gen_folded_strip(size_t nx, size_t ny, int layers, double gap, double t, ttd_gen_mesh *out)
{
    if (!out)
        return -1;
    memset(out, 0, sizeof *out);
    if (layers < 1 || layers > 64 || !(gap >= 0) || !(t >= 0 && t <= 2) || !isfinite(gap) ||
        grid_rect(nx, ny, out) != 0)
        return -1;
    /* the path in the xz-plane: layers flat runs of length a joined by arcs of radius r turning by
     * theta, left and right in turn; arc length x along it */
    const double pi = 3.14159265358979323846, theta = pi * t, r = 0.5 * gap;
    const double arc = r * theta, a = (1.0 - (double)(layers - 1) * arc) / (double)layers;
    if (!(a > 0)) {
        ttd_gen_mesh_free(out);
        return -1;
    }
    const size_t w = nx + 1;
    for (size_t i = 0; i < w; ++i) {
        double s = (double)i / (double)nx, x = 0, z = 0, phi = 0;
        for (int k = 0; k < layers; ++k) {
            const double run = s < a || k == layers - 1 ? s : a;
            x += run * cos(phi);
            z += run * sin(phi);
            s -= run;
            if (s <= 0 || k == layers - 1)
                break;
            /* the arc: about its centre, a quarter-turn from the direction on the turning side */
            const double side = k % 2 == 0 ? 1.0 : -1.0, turn = s < arc ? s / r : theta;
            const double cx = x - side * r * sin(phi), cz = z + side * r * cos(phi);
            phi += side * turn;
            x = cx + side * r * sin(phi);
            z = cz - side * r * cos(phi);
            s -= s < arc ? s : arc;
            if (s <= 0)
                break;
        }
        for (size_t j = 0; j <= ny; ++j) {
            double *p = out->verts + 3 * (j * w + i);
            p[0] = x;
            p[2] = z;
        }
    }
    return 0;
}

/* ---- operations ---------------------------------------------------------------------- */

int ttd_gen_mesh_bounds(const ttd_gen_mesh *m, double lo[3], double hi[3])
{
    if (!m || !m->verts || m->nv == 0 || !lo || !hi)
        return -1;
    for (int d = 0; d < 3; ++d)
        lo[d] = hi[d] = m->verts[d];
    for (size_t k = 1; k < m->nv; ++k)
        for (int d = 0; d < 3; ++d) {
            double x = m->verts[3 * k + (size_t)d];
            if (x < lo[d]) lo[d] = x;
            if (x > hi[d]) hi[d] = x;
        }
    return 0;
}

int ttd_gen_normalize(ttd_gen_mesh *m)
{
    double lo[3], hi[3];
    if (ttd_gen_mesh_bounds(m, lo, hi) != 0)
        return -1;
    for (size_t k = 0; k < 3 * m->nv; ++k)
        if (!isfinite(m->verts[k]))
            return -1;
    double c[3], e[3], big = 0;
    for (int d = 0; d < 3; ++d) {
        c[d] = 0.5 * lo[d] + 0.5 * hi[d];
        e[d] = hi[d] - lo[d];
        if (e[d] > big)
            big = e[d];
    }
    if (!(big > 0) || !isfinite(big))
        return -1;
    /* the diagonal scaled by the largest extent first, so that its square cannot overflow */
    double s0 = e[0] / big, s1 = e[1] / big, s2 = e[2] / big;
    double diag = big * sqrt(s0 * s0 + s1 * s1 + s2 * s2);
    if (!isfinite(diag))
        return -1;
    for (size_t k = 0; k < m->nv; ++k)
        for (int d = 0; d < 3; ++d) {
            double *x = m->verts + 3 * k + d;
            *x = (*x - c[d]) / diag;
        }
    return 0;
}

static void apply_pose(const double pose[12], const double *x, double *y)
{
    double a = x[0], b = x[1], c = x[2];
    for (int r = 0; r < 3; ++r)
        y[r] = pose[4 * r] * a + pose[4 * r + 1] * b + pose[4 * r + 2] * c + pose[4 * r + 3];
}

int ttd_gen_mesh_transform(const ttd_gen_mesh *in, const double pose[12], ttd_gen_mesh *out)
{
    if (!out)
        return -1;
    if (!in || !in->verts || !in->tris || !pose) {
        if (out != in)
            memset(out, 0, sizeof *out);
        return -1;
    }
    if (out != in && ttd_gen_mesh_copy(in, out) != 0)
        return -1;
    for (size_t k = 0; k < out->nv; ++k)
        apply_pose(pose, out->verts + 3 * k, out->verts + 3 * k);
    return 0;
}

/* ---- poses --------------------------------------------------------------------------- */

/// The pose of (seed, i), leaving rng ready for further draws. The quaternion is uniform in
/// the unit 4-ball (so its direction is uniform on the sphere: a uniform rotation); the matrix
/// is its homogeneous form divided by its squared norm, which needs no normalised quaternion
/// and keeps R^T R within a few ulps of I (normalising first, as ttd_gen_rng_rotation does,
/// carries the normalisation's rounding into every entry: 2.4e-15 measured).
static void pose_draw(ttd_gen_rng *rng, double scale, double pose[12])
{
    double w, x, y, z, n2;
    do {
        w = 2.0 * ttd_gen_rng_uniform(rng) - 1.0;
        x = 2.0 * ttd_gen_rng_uniform(rng) - 1.0;
        y = 2.0 * ttd_gen_rng_uniform(rng) - 1.0;
        z = 2.0 * ttd_gen_rng_uniform(rng) - 1.0;
        n2 = w * w + x * x + y * y + z * z;
    } while (!(n2 > 1e-4 && n2 <= 1.0));
    const double m[9] = {
        (w * w + x * x) - (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y),
        2 * (x * y + w * z), (w * w + y * y) - (x * x + z * z), 2 * (y * z - w * x),
        2 * (x * z - w * y), 2 * (y * z + w * x), (w * w + z * z) - (x * x + y * y),
    };
    for (int r = 0; r < 3; ++r) {
        pose[4 * r] = m[3 * r] / n2;
        pose[4 * r + 1] = m[3 * r + 1] / n2;
        pose[4 * r + 2] = m[3 * r + 2] / n2;
    }
    for (int r = 0; r < 3; ++r)
        pose[4 * r + 3] = scale * (2.0 * ttd_gen_rng_uniform(rng) - 1.0);
}

void ttd_gen_pose(uint64_t seed, uint64_t i, double scale, double pose[12])
{
    if (!pose)
        return;
    ttd_gen_rng rng = ttd_gen_rng_make(seed, i);
    pose_draw(&rng, scale, pose);
}

int ttd_gen_pose_gap(const ttd_gen_mesh *a, const ttd_gen_mesh *b, uint64_t seed, uint64_t i,
                     const double dir[3], double gap, double pose[12])
{
    if (!a || !b || !a->verts || !b->verts || a->nv == 0 || b->nv == 0 || !pose || !isfinite(gap))
        return -1;
    ttd_gen_rng rng = ttd_gen_rng_make(seed, i);
    double p[12], u[3];
    pose_draw(&rng, 0.0, p);
    if (dir) {
        double n2 = dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2];
        if (!(n2 > 0) || !isfinite(n2))
            return -1;
        double inv = 1.0 / sqrt(n2);
        for (int d = 0; d < 3; ++d)
            u[d] = dir[d] * inv;
    } else {
        for (;;) { /* uniform in the ball, then onto the sphere */
            for (int d = 0; d < 3; ++d)
                u[d] = 2.0 * ttd_gen_rng_uniform(&rng) - 1.0;
            double n2 = u[0] * u[0] + u[1] * u[1] + u[2] * u[2];
            if (n2 > 1e-4 && n2 <= 1.0) {
                double inv = 1.0 / sqrt(n2);
                for (int d = 0; d < 3; ++d)
                    u[d] *= inv;
                break;
            }
        }
    }
    /* a's box centre and its support along u */
    const double inf = (double)INFINITY;
    double alo[3], ahi[3], blo[3] = {inf, inf, inf}, bhi[3] = {-inf, -inf, -inf}, h = -inf;
    if (ttd_gen_mesh_bounds(a, alo, ahi) != 0)
        return -1;
    for (size_t k = 0; k < a->nv; ++k) {
        const double *x = a->verts + 3 * k;
        double s = u[0] * x[0] + u[1] * x[1] + u[2] * x[2];
        if (s > h)
            h = s;
    }
    /* b rotated: its box, then its centre moved onto a's */
    for (size_t k = 0; k < b->nv; ++k) {
        double y[3];
        apply_pose(p, b->verts + 3 * k, y);
        for (int d = 0; d < 3; ++d) {
            if (y[d] < blo[d]) blo[d] = y[d];
            if (y[d] > bhi[d]) bhi[d] = y[d];
        }
    }
    for (int d = 0; d < 3; ++d)
        p[4 * d + 3] = (0.5 * alo[d] + 0.5 * ahi[d]) - (0.5 * blo[d] + 0.5 * bhi[d]);
    double l = inf;
    for (size_t k = 0; k < b->nv; ++k) {
        double y[3];
        apply_pose(p, b->verts + 3 * k, y);
        double s = u[0] * y[0] + u[1] * y[1] + u[2] * y[2];
        if (s < l)
            l = s;
    }
    double shift = h - l + gap;
    for (int d = 0; d < 3; ++d)
        p[4 * d + 3] += shift * u[d];
    for (int k = 0; k < 12; ++k)
        if (!isfinite(p[k]))
            return -1;
    memcpy(pose, p, sizeof p);
    return 0;
}

/* SPDX-License-Identifier: MIT */
/* Welding: vertices within a tolerance become one (ttd_mesh_weld_d/f, include/ttd/ttd.h).
 *
 * The classes are the connected pieces of the graph "u and v within tol" (chained merges), so
 * they do not depend on the vertices' order. Steps:
 *  1. sort the vertices by value (x, then y, then z; -0 equals +0) and make each run of equal
 *     points one unique point (exact duplicates, STL's usual case, cost nothing more);
 *  2. for tol > 0, put the unique points in a grid of cubes of side h and compare each with the
 *     points of the cubes near its own, joining classes in a union-find whose root is the
 *     smaller unique point, so a class's root is its lexicographically smallest point.
 * The grid: with h = 0.577 tol a cube's diagonal (sqrt(3) h) is shorter than tol, so the points
 * of one cube are one class without a test, and two points within tol lie at most 2 cubes apart
 * on each axis; a pair of cubes already in one class is skipped whole, so a tolerance larger
 * than the mesh costs linear time, not quadratic. The cube index floor(x / h) must be exact
 * enough: when h would be below 2^-40 of the largest coordinate (a tolerance of a few ulps),
 * h is that instead (times 1 + 2^-10, so rounding cannot push two points within tol 2 cubes
 * apart), points in one cube are compared pairwise and neighbours are 1 cube apart. */
#include "io/weld.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ttd/ttd.h"

/* ---- the predicate: the definition ttd.h states ----------------------------------------- */

static int within(const double *a, const double *b, double tol)
{
    double d[3] = {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
    if (tol == 0)
        return d[0] == 0 && d[1] == 0 && d[2] == 0;
    if (!(fabs(d[0]) <= tol && fabs(d[1]) <= tol && fabs(d[2]) <= tol))
        return 0; /* also an overflowed difference */
    double x = d[0] / tol, y = d[1] / tol, z = d[2] / tol;
    return x * x + y * y + z * z <= 1.0;
}

/* ---- a stable merge sort of uint32 indices by a comparison with context ------------------- */

typedef int (*cmp_fn)(const void *ctx, uint32_t a, uint32_t b);

static void merge_sort(uint32_t *a, uint32_t *tmp, size_t n, cmp_fn cmp, const void *ctx)
{
    for (size_t w = 1; w < n; w *= 2) {
        for (size_t lo = 0; lo < n; lo += 2 * w) {
            size_t mid = lo + w < n ? lo + w : n, hi = lo + 2 * w < n ? lo + 2 * w : n;
            size_t i = lo, j = mid, k = lo;
            while (i < mid && j < hi)
                tmp[k++] = cmp(ctx, a[j], a[i]) < 0 ? a[j++] : a[i++];
            while (i < mid)
                tmp[k++] = a[i++];
            while (j < hi)
                tmp[k++] = a[j++];
        }
        memcpy(a, tmp, n * sizeof *a);
    }
}

static int cmp_point(const void *ctx, uint32_t a, uint32_t b)
{
    const double *v = ctx, *p = v + 3 * (size_t)a, *q = v + 3 * (size_t)b;
    for (int k = 0; k < 3; ++k) {
        if (p[k] < q[k])
            return -1;
        if (p[k] > q[k])
            return 1;
    }
    return a < b ? -1 : a > b;
}

typedef struct cell_ctx {
    const int64_t *key; /* 3 per unique point */
} cell_ctx;

static int cmp_cell(const void *ctx, uint32_t a, uint32_t b)
{
    const int64_t *k = ((const cell_ctx *)ctx)->key, *p = k + 3 * (size_t)a, *q = k + 3 * (size_t)b;
    for (int d = 0; d < 3; ++d) {
        if (p[d] != q[d])
            return p[d] < q[d] ? -1 : 1;
    }
    return a < b ? -1 : a > b;
}

/* ---- union-find with the smaller index as root -------------------------------------------- */

static uint32_t find(uint32_t *parent, uint32_t x)
{
    while (parent[x] != x) {
        parent[x] = parent[parent[x]];
        x = parent[x];
    }
    return x;
}

static void unite(uint32_t *parent, uint32_t a, uint32_t b)
{
    a = find(parent, a);
    b = find(parent, b);
    if (a < b)
        parent[b] = a;
    else if (b < a)
        parent[a] = b;
}

/* ---- the cells' hash table: cell -> its run in the cell order ----------------------------- */

static uint64_t cell_hash(const int64_t *k)
{
    uint64_t h = 0x9E3779B97F4A7C15ull;
    for (int d = 0; d < 3; ++d) {
        h = (h ^ (uint64_t)k[d]) * 0xBF58476D1CE4E5B9ull;
        h ^= h >> 31;
    }
    return h;
}

int ttd_weld_classes(const double *v, size_t nv, double tol, uint32_t *map, uint32_t *rep, size_t *nclasses)
{
    int rc = -1;
    uint32_t *order = malloc(nv * sizeof *order), *tmp = malloc(nv * sizeof *tmp);
    uint32_t *uid = malloc(nv * sizeof *uid), *first = malloc(nv * sizeof *first);
    uint32_t *parent = NULL, *cells = NULL, *table = NULL, *run_start = NULL;
    int64_t *key = NULL;
    if (!order || !tmp || !uid || !first)
        goto done;
    /* 1. unique points in lexicographic order; first[u] its smallest old index */
    for (size_t i = 0; i < nv; ++i)
        order[i] = (uint32_t)i;
    merge_sort(order, tmp, nv, cmp_point, v);
    size_t nu = 0;
    for (size_t s = 0; s < nv; ++s) {
        const double *p = v + 3 * (size_t)order[s];
        if (s == 0 || !within(p, v + 3 * (size_t)order[s - 1], 0))
            first[nu++] = order[s]; /* sorted by (value, index): the run's first is its smallest index */
        uid[order[s]] = (uint32_t)(nu - 1);
    }
    parent = malloc((nu ? nu : 1) * sizeof *parent);
    if (!parent)
        goto done;
    for (size_t u = 0; u < nu; ++u)
        parent[u] = (uint32_t)u;
    /* 2. the grid over unique points */
    double maxabs = 0;
    for (size_t i = 0; i < 3 * nv; ++i)
        maxabs = fmax(maxabs, fabs(v[i]));
    if (tol > 0 && nu > 1) {
        const double floor_h = ldexp(maxabs, -40);
        const int coarse = 0.577 * tol < floor_h; /* tolerance of a few ulps: see above */
        const double h = coarse ? floor_h * (1 + ldexp(1, -10)) : 0.577 * tol;
        const int reach = coarse ? 1 : 2;
        key = malloc(3 * nu * sizeof *key);
        cells = malloc(nu * sizeof *cells);
        run_start = malloc((nu + 1) * sizeof *run_start);
        if (!key || !cells || !run_start)
            goto done;
        for (size_t u = 0; u < nu; ++u) {
            for (int d = 0; d < 3; ++d)
                key[3 * u + (size_t)d] = (int64_t)floor(v[3 * (size_t)first[u] + (size_t)d] / h);
            cells[u] = (uint32_t)u;
        }
        cell_ctx cc = {key};
        merge_sort(cells, tmp, nu, cmp_cell, &cc);
        size_t nc = 0; /* runs of one cell: cells[run_start[c] .. run_start[c + 1]) */
        for (size_t s = 0; s < nu; ++s)
            if (s == 0 || memcmp(key + 3 * (size_t)cells[s], key + 3 * (size_t)cells[s - 1], 3 * sizeof *key) != 0)
                run_start[nc++] = (uint32_t)s;
        run_start[nc] = (uint32_t)nu;
        size_t tcap = 16;
        while (tcap < 2 * nc)
            tcap *= 2;
        table = malloc(tcap * sizeof *table);
        if (!table)
            goto done;
        for (size_t t = 0; t < tcap; ++t)
            table[t] = UINT32_MAX;
        for (size_t c = 0; c < nc; ++c) {
            size_t t = cell_hash(key + 3 * (size_t)cells[run_start[c]]) & (tcap - 1);
            while (table[t] != UINT32_MAX)
                t = (t + 1) & (tcap - 1);
            table[t] = (uint32_t)c;
        }
        for (size_t c = 0; c < nc; ++c) {
            const uint32_t s0 = run_start[c], s1 = run_start[c + 1];
            const int64_t *kc = key + 3 * (size_t)cells[s0];
            if (!coarse) { /* one cube is one class */
                for (uint32_t s = s0 + 1; s < s1; ++s)
                    unite(parent, cells[s0], cells[s]);
            } else {
                for (uint32_t s = s0; s < s1; ++s)
                    for (uint32_t r = s + 1; r < s1; ++r)
                        if (within(v + 3 * (size_t)first[cells[s]], v + 3 * (size_t)first[cells[r]], tol))
                            unite(parent, cells[s], cells[r]);
            }
            /* the neighbour cubes after this one in (dx, dy, dz) order: each pair of cubes once */
            for (int dx = 0; dx <= reach; ++dx)
                for (int dy = dx ? -reach : 0; dy <= reach; ++dy)
                    for (int dz = (dx || dy) ? -reach : 1; dz <= reach; ++dz) {
                        int64_t kn[3] = {kc[0] + dx, kc[1] + dy, kc[2] + dz};
                        size_t t = cell_hash(kn) & (tcap - 1);
                        uint32_t n = UINT32_MAX;
                        for (; table[t] != UINT32_MAX; t = (t + 1) & (tcap - 1))
                            if (memcmp(key + 3 * (size_t)cells[run_start[table[t]]], kn, sizeof kn) == 0) {
                                n = table[t];
                                break;
                            }
                        if (n == UINT32_MAX)
                            continue;
                        const uint32_t r0 = run_start[n], r1 = run_start[n + 1];
                        for (uint32_t s = s0; s < s1; ++s) {
                            if (!coarse && find(parent, cells[s]) == find(parent, cells[r0]))
                                break; /* the two cubes are one class already */
                            for (uint32_t r = r0; r < r1; ++r)
                                if (within(v + 3 * (size_t)first[cells[s]], v + 3 * (size_t)first[cells[r]], tol))
                                    unite(parent, cells[s], cells[r]);
                        }
                    }
        }
    }
    /* 3. new indices by each class's smallest old index; the representative is the class's
     * root, its lexicographically smallest unique point */
    for (size_t u = 0; u < nu; ++u)
        tmp[u] = UINT32_MAX; /* class root -> new index */
    size_t n = 0;
    for (size_t i = 0; i < nv; ++i) {
        uint32_t root = find(parent, uid[i]);
        if (tmp[root] == UINT32_MAX) {
            tmp[root] = (uint32_t)n;
            rep[n++] = first[root];
        }
        map[i] = tmp[root];
    }
    *nclasses = n;
    rc = 0;
done:
    free(order);
    free(tmp);
    free(uid);
    free(first);
    free(parent);
    free(key);
    free(cells);
    free(table);
    free(run_start);
    return rc;
}

/* ---- the public entries ------------------------------------------------------------------- */

/* Checks, classes, the triangles; the caller writes the vertices from rep (either precision). */
static ttd_status weld_common(const double *v, size_t nv, const uint32_t *tris, size_t nt, double tol,
                              uint32_t *tris_out, size_t *nt_out, uint32_t *map, uint32_t *rep, size_t *nclasses)
{
    for (size_t i = 0; i < 3 * nt; ++i)
        if (tris[i] >= nv)
            return TTD_ERR_INDEX_OUT_OF_RANGE;
    if (ttd_weld_classes(v, nv, tol, map, rep, nclasses) != 0)
        return TTD_ERR_OUT_OF_MEMORY;
    size_t k = 0;
    for (size_t t = 0; t < nt; ++t) {
        uint32_t a = map[tris[3 * t]], b = map[tris[3 * t + 1]], c = map[tris[3 * t + 2]];
        if (a == b || b == c || a == c)
            continue; /* collapsed: dropped */
        tris_out[3 * k] = a;
        tris_out[3 * k + 1] = b;
        tris_out[3 * k + 2] = c;
        ++k;
    }
    *nt_out = k;
    return TTD_OK;
}

static ttd_status weld_args(const void *verts, size_t nv, const uint32_t *tris, size_t nt, double tol,
                            const void *verts_out, const size_t *nv_out, const uint32_t *tris_out, const size_t *nt_out)
{
    if (!verts || !verts_out || !nv_out || !nt_out || (nt > 0 && (!tris || !tris_out)))
        return TTD_ERR_NULL_POINTER;
    if (nv == 0)
        return TTD_ERR_EMPTY;
    if (!(tol >= 0) || !isfinite(tol))
        return TTD_ERR_BAD_OPTIONS;
    if (nv > UINT32_MAX || nv > SIZE_MAX / (3 * sizeof(double)) || nt > SIZE_MAX / (3 * sizeof(uint32_t)))
        return TTD_ERR_TOO_LARGE;
    return TTD_OK;
}

ttd_status ttd_mesh_weld_d(const double *verts, size_t nv, const uint32_t *tris, size_t nt, double tolerance,
                           double *verts_out, size_t *nv_out, uint32_t *tris_out, size_t *nt_out, uint32_t *vertex_map)
{
    ttd_status st = weld_args(verts, nv, tris, nt, tolerance, verts_out, nv_out, tris_out, nt_out);
    if (st != TTD_OK)
        return st;
    for (size_t i = 0; i < 3 * nv; ++i)
        if (!isfinite(verts[i]))
            return TTD_ERR_NONFINITE_MESH;
    uint32_t *map = malloc(nv * sizeof *map), *rep = malloc(nv * sizeof *rep);
    double *w = malloc(3 * nv * sizeof *w);
    size_t n = 0;
    st = map && rep && w ? weld_common(verts, nv, tris, nt, tolerance, tris_out, nt_out, map, rep, &n)
                         : TTD_ERR_OUT_OF_MEMORY;
    if (st == TTD_OK) {
        for (size_t j = 0; j < n; ++j)
            for (int d = 0; d < 3; ++d)
                w[3 * j + (size_t)d] = verts[3 * (size_t)rep[j] + (size_t)d] + 0.0; /* -0 becomes +0 */
        memcpy(verts_out, w, 3 * n * sizeof *w);
        *nv_out = n;
        if (vertex_map)
            memcpy(vertex_map, map, nv * sizeof *map);
    }
    free(map);
    free(rep);
    free(w);
    return st;
}

ttd_status ttd_mesh_weld_f(const float *verts, size_t nv, const uint32_t *tris, size_t nt, float tolerance,
                           float *verts_out, size_t *nv_out, uint32_t *tris_out, size_t *nt_out, uint32_t *vertex_map)
{
    ttd_status st = weld_args(verts, nv, tris, nt, (double)tolerance, verts_out, nv_out, tris_out, nt_out);
    if (st != TTD_OK)
        return st;
    for (size_t i = 0; i < 3 * nv; ++i)
        if (!isfinite(verts[i]))
            return TTD_ERR_NONFINITE_MESH;
    /* the same classes on the floats' exact double values */
    uint32_t *map = malloc(nv * sizeof *map), *rep = malloc(nv * sizeof *rep);
    double *w = malloc(3 * nv * sizeof *w);
    size_t n = 0;
    if (map && rep && w) {
        for (size_t i = 0; i < 3 * nv; ++i)
            w[i] = (double)verts[i];
        st = weld_common(w, nv, tris, nt, (double)tolerance, tris_out, nt_out, map, rep, &n);
    } else {
        st = TTD_ERR_OUT_OF_MEMORY;
    }
    if (st == TTD_OK) {
        float *tmpf = malloc(3 * n * sizeof *tmpf);
        if (!tmpf) {
            st = TTD_ERR_OUT_OF_MEMORY;
        } else {
            for (size_t j = 0; j < n; ++j)
                for (int d = 0; d < 3; ++d)
                    tmpf[3 * j + (size_t)d] = verts[3 * (size_t)rep[j] + (size_t)d] + 0.0f;
            memcpy(verts_out, tmpf, 3 * n * sizeof *tmpf);
            free(tmpf);
            *nv_out = n;
            if (vertex_map)
                memcpy(vertex_map, map, nv * sizeof *map);
        }
    }
    free(map);
    free(rep);
    free(w);
    return st;
}

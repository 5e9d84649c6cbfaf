/* SPDX-License-Identifier: MIT */
/* Candidate pairs by bounding boxes (see mesh_pairs.h). a's triangles that reach the region
 * where the two meshes' boxes overlap (b's enlarged by the margin) go into a uniform grid over
 * that region (cells listed in one array, counting sort); each triangle of b then looks up the
 * cells its enlarged box covers, and a stamp per triangle of a keeps a pair that several cells
 * share from being listed twice. Cells are about the size of an average triangle of a, so a
 * box covers a few cells. */
#include "mesh_pairs.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/// The grid: dims cells per axis over [lo, lo + dims h), cell lists in CSR form.
typedef struct grid {
    double lo[3], h;
    size_t dims[3];
    size_t *start; /* cell c holds tri[start[c] .. start[c+1]) */
    uint32_t *tri;
} grid;

static int mesh_ok(const ttd_gen_mesh *m)
{
    if (!m || !m->verts || !m->tris || m->nv == 0 || m->nt == 0 || m->nt >= UINT32_MAX)
        return 0;
    for (size_t k = 0; k < 3 * m->nt; ++k)
        if (m->tris[k] >= m->nv)
            return 0;
    for (size_t k = 0; k < 3 * m->nv; ++k)
        if (!isfinite(m->verts[k]))
            return 0;
    return 1;
}

static void tri_box(const ttd_gen_mesh *m, size_t i, double lo[3], double hi[3])
{
    for (int c = 0; c < 3; ++c) {
        lo[c] = hi[c] = m->verts[3 * (size_t)m->tris[3 * i] + (size_t)c];
        for (int v = 1; v < 3; ++v) {
            const double x = m->verts[3 * (size_t)m->tris[3 * i + (size_t)v] + (size_t)c];
            lo[c] = x < lo[c] ? x : lo[c];
            hi[c] = x > hi[c] ? x : hi[c];
        }
    }
}

/// The cells [c0, c1] a box covers on each axis, clipped to the grid; 0 when it misses it.
static int cell_range(const grid *g, const double lo[3], const double hi[3], size_t c0[3], size_t c1[3])
{
    for (int c = 0; c < 3; ++c) {
        const double top = g->lo[c] + g->h * (double)g->dims[c];
        if (hi[c] < g->lo[c] || lo[c] > top)
            return 0;
        const double last = (double)(g->dims[c] - 1);
        double f0 = floor((lo[c] - g->lo[c]) / g->h), f1 = floor((hi[c] - g->lo[c]) / g->h);
        f0 = f0 < 0 ? 0 : (f0 > last ? last : f0);
        f1 = f1 > last ? last : (f1 < f0 ? f0 : f1);
        c0[c] = (size_t)f0;
        c1[c] = (size_t)f1;
    }
    return 1;
}

/// The number of cells of the range, and cell k of it (x fastest).
static size_t range_cells(const size_t c0[3], const size_t c1[3])
{
    return (c1[0] - c0[0] + 1) * (c1[1] - c0[1] + 1) * (c1[2] - c0[2] + 1);
}

static size_t range_cell(const grid *g, const size_t c0[3], const size_t c1[3], size_t k)
{
    const size_t nx = c1[0] - c0[0] + 1, ny = c1[1] - c0[1] + 1;
    const size_t x = c0[0] + k % nx, y = c0[1] + (k / nx) % ny, z = c0[2] + k / (nx * ny);
    return (z * g->dims[1] + y) * g->dims[0] + x;
}

static int cmp_u32(const void *x, const void *y)
{
    const uint32_t a = *(const uint32_t *)x, b = *(const uint32_t *)y;
    return (a > b) - (a < b);
}

int ttd_gen_mesh_pairs(const ttd_gen_mesh *a, const ttd_gen_mesh *b, double margin, size_t max_pairs,
                       uint32_t **pairs, size_t *n)
{
    if (!pairs || !n)
        return -1;
    *pairs = NULL;
    *n = 0;
    if (!mesh_ok(a) || !mesh_ok(b) || !(margin >= 0) || !isfinite(margin))
        return -1;
    double alo[3], ahi[3], blo[3], bhi[3], lo[3], hi[3];
    if (ttd_gen_mesh_bounds(a, alo, ahi) != 0 || ttd_gen_mesh_bounds(b, blo, bhi) != 0)
        return -1;
    for (int c = 0; c < 3; ++c) {
        lo[c] = fmax(alo[c], blo[c] - margin);
        hi[c] = fmin(ahi[c], bhi[c] + margin);
        if (lo[c] > hi[c])
            return 0; /* the meshes are farther apart than margin on this axis */
    }
    /* cell size: the mean largest extent of a's triangles, at least 1/128 of the region */
    double ext = 0;
    for (size_t i = 0; i < a->nt; ++i) {
        double tl[3], th[3];
        tri_box(a, i, tl, th);
        ext += fmax(th[0] - tl[0], fmax(th[1] - tl[1], th[2] - tl[2]));
    }
    ext /= (double)a->nt;
    double span = fmax(hi[0] - lo[0], fmax(hi[1] - lo[1], hi[2] - lo[2]));
    grid g;
    memset(&g, 0, sizeof g);
    g.h = fmax(fmax(ext, margin), span / 128);
    if (!(g.h > 0))
        g.h = 1;
    size_t cells = 1;
    for (int c = 0; c < 3; ++c) {
        g.lo[c] = lo[c];
        g.dims[c] = (size_t)floor((hi[c] - lo[c]) / g.h) + 1;
        cells *= g.dims[c];
    }
    uint32_t *stamp = calloc(a->nt, sizeof *stamp), *found = malloc(a->nt * sizeof *found);
    g.start = calloc(cells + 1, sizeof *g.start);
    uint32_t *out = NULL;
    size_t cap = 0, count = 0;
    int rc = -1;
    if (!stamp || !found || !g.start)
        goto done;
    /* counting sort of a's triangles into the cells their boxes cover */
    for (int pass = 0; pass < 2; ++pass) {
        for (size_t i = 0; i < a->nt; ++i) {
            double tl[3], th[3];
            size_t c0[3], c1[3];
            tri_box(a, i, tl, th);
            if (!cell_range(&g, tl, th, c0, c1))
                continue;
            for (size_t k = 0, nk = range_cells(c0, c1); k < nk; ++k) {
                const size_t cell = range_cell(&g, c0, c1, k);
                if (pass == 0)
                    g.start[cell + 1]++;
                else
                    g.tri[g.start[cell]++] = (uint32_t)i;
            }
        }
        if (pass == 0) {
            for (size_t c = 0; c < cells; ++c)
                g.start[c + 1] += g.start[c];
            g.tri = malloc((g.start[cells] ? g.start[cells] : 1) * sizeof *g.tri);
            if (!g.tri)
                goto done;
        } else { /* the fill moved every start to the next cell's: shift back */
            memmove(g.start + 1, g.start, cells * sizeof *g.start);
            g.start[0] = 0;
        }
    }
    for (size_t j = 0; j < b->nt; ++j) {
        double tl[3], th[3];
        size_t c0[3], c1[3], nf = 0;
        tri_box(b, j, tl, th);
        for (int c = 0; c < 3; ++c) {
            tl[c] -= margin;
            th[c] += margin;
        }
        if (!cell_range(&g, tl, th, c0, c1))
            continue;
        for (size_t q = 0, nq = range_cells(c0, c1); q < nq; ++q) {
            const size_t cell = range_cell(&g, c0, c1, q);
            for (size_t k = g.start[cell]; k < g.start[cell + 1]; ++k) {
                const uint32_t i = g.tri[k];
                if (stamp[i] == (uint32_t)j + 1)
                    continue;
                stamp[i] = (uint32_t)j + 1;
                double al[3], ah[3];
                tri_box(a, i, al, ah);
                if (al[0] <= th[0] && tl[0] <= ah[0] && al[1] <= th[1] && tl[1] <= ah[1] && al[2] <= th[2] &&
                    tl[2] <= ah[2])
                    found[nf++] = i;
            }
        }
        if (!nf)
            continue;
        qsort(found, nf, sizeof *found, cmp_u32);
        if (count + nf > max_pairs)
            goto done;
        if (count + nf > cap) {
            size_t nc = cap ? 2 * cap : 4096;
            while (nc < count + nf)
                nc *= 2;
            uint32_t *grown = realloc(out, 2 * nc * sizeof *out);
            if (!grown)
                goto done;
            out = grown;
            cap = nc;
        }
        for (size_t k = 0; k < nf; ++k) {
            out[2 * (count + k)] = found[k];
            out[2 * (count + k) + 1] = (uint32_t)j;
        }
        count += nf;
    }
    rc = 0;
done:
    free(stamp);
    free(found);
    free(g.start);
    free(g.tri);
    if (rc == 0) {
        *pairs = out;
        *n = count;
    } else {
        free(out);
    }
    return rc;
}

void ttd_gen_mesh_pair_coords(const ttd_gen_mesh *a, const ttd_gen_mesh *b, const uint32_t *pairs, size_t n,
                              double *s, double *t)
{
    for (size_t k = 0; k < n; ++k)
        for (int v = 0; v < 3; ++v)
            for (int c = 0; c < 3; ++c) {
                s[9 * k + 3 * (size_t)v + (size_t)c] =
                    a->verts[3 * (size_t)a->tris[3 * (size_t)pairs[2 * k] + (size_t)v] + (size_t)c];
                t[9 * k + 3 * (size_t)v + (size_t)c] =
                    b->verts[3 * (size_t)b->tris[3 * (size_t)pairs[2 * k + 1] + (size_t)v] + (size_t)c];
            }
}

/* SPDX-License-Identifier: MIT */
/* The brute force of the self queries (ttd_mesh_self_contacts_d/f), written from the header's
 * rules alone: over every pair i < j of one mesh's triangles, the vertices two triangles share
 * counted as sets of indices; none: the exact method on (T_i, T_j) through ttd_batch_d/f; exactly
 * one, v, and each triangle another vertex (shared): the smaller of (E_i, T_j) and (T_i, E_j), E
 * the triangle's vertices other than v in their order, the last repeated, E_i's when equal;
 * otherwise the pair does not count. Shared by tests/test_mesh_self.c and the mesh fuzzer
 * (tests/meshfuzz/). */
#ifndef TTD_TESTS_SELF_BRUTE_H
#define TTD_TESTS_SELF_BRUTE_H

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "ttd/ttd.h"

/* One pair's answer: distance and points (p on i, q on j); d = +inf when the pair does not count. */
typedef struct spair {
    uint32_t i, j;
    double d;
    double p[3], q[3];
} spair;

/* How many distinct indices of x are in y; the last such in *v. */
static inline int count_shared(const uint32_t x[3], const uint32_t y[3], uint32_t *v)
{
    uint32_t seen[3];
    int ns = 0, n = 0;
    for (int k = 0; k < 3; ++k) {
        int dup = 0;
        for (int q = 0; q < ns; ++q)
            dup |= seen[q] == x[k];
        if (dup)
            continue;
        seen[ns++] = x[k];
        if (x[k] == y[0] || x[k] == y[1] || x[k] == y[2]) {
            ++n;
            *v = x[k];
        }
    }
    return n;
}

/* Triangle t's coordinates (double), or its edge opposite vertex v (vertices other than v in
 * order, the last repeated); returns how many vertices other than v it has. */
static inline int tri_coords(const double *verts, const uint32_t t[3], int edge, uint32_t v, double out[9])
{
    int n = 0;
    for (int k = 0; k < 3; ++k)
        if (!edge || t[k] != v)
            memcpy(out + 3 * n++, verts + 3 * (size_t)t[k], 3 * sizeof(double));
    for (int k = n; k < 3 && n > 0; ++k)
        memcpy(out + 3 * k, out + 3 * (n - 1), 3 * sizeof(double));
    return n;
}

/* Every counting pair (i < j, in row-major order) of the mesh of nt triangles tris over verts
 * (3 doubles a vertex; computed in float when fl, the coordinates then rounded to float). */
static inline spair *brute_self(const double *verts, const uint32_t *tris, size_t nt, int fl, int shared, size_t *count)
{
    size_t cap = nt * (nt - 1) / 2 * (shared ? 2 : 1) + 1, n = 0, np = 0;
    double *s = malloc(9 * cap * sizeof *s), *t = malloc(9 * cap * sizeof *t);
    uint8_t *kind = malloc(cap);
    spair *out = malloc((nt * (nt - 1) / 2 + 1) * sizeof *out);
    if (!s || !t || !kind || !out)
        abort();
    for (size_t i = 0; i < nt; ++i)
        for (size_t j = i + 1; j < nt; ++j) {
            const uint32_t *ti = tris + 3 * i, *tj = tris + 3 * j;
            uint32_t v = 0;
            const int k = count_shared(ti, tj, &v);
            if (k == 0) {
                tri_coords(verts, ti, 0, 0, s + 9 * n);
                tri_coords(verts, tj, 0, 0, t + 9 * n);
                kind[n++] = 0;
            } else if (k == 1 && shared) {
                double e[9];
                if (tri_coords(verts, ti, 1, v, e) == 0 || tri_coords(verts, tj, 1, v, e) == 0)
                    continue;
                tri_coords(verts, ti, 1, v, s + 9 * n);
                tri_coords(verts, tj, 0, 0, t + 9 * n);
                kind[n++] = 1;
                tri_coords(verts, ti, 0, 0, s + 9 * n);
                tri_coords(verts, tj, 1, v, t + 9 * n);
                kind[n++] = 2;
            } else {
                continue;
            }
            out[np].i = (uint32_t)i;
            out[np++].j = (uint32_t)j;
        }
    if (!fl) {
        ttd_result_d *r = malloc((n + 1) * sizeof *r);
        if (!r || (n > 0 && ttd_batch_d(NULL, n, s, t, NULL, r) != TTD_OK))
            abort();
        for (size_t e = 0, p = 0; e < n; ++p) {
            const ttd_result_d *best = &r[e];
            if (kind[e] == 1 && r[e + 1].distance < best->distance)
                best = &r[e + 1];
            e += kind[e] == 1 ? 2 : 1;
            out[p].d = best->distance;
            memcpy(out[p].p, best->p, sizeof out[p].p);
            memcpy(out[p].q, best->distance == 0 ? best->p : best->q, sizeof out[p].q);
        }
        free(r);
    } else {
        float *sf = malloc((9 * n + 1) * sizeof *sf), *tf = malloc((9 * n + 1) * sizeof *tf);
        ttd_result_f *r = malloc((n + 1) * sizeof *r);
        if (!sf || !tf || !r)
            abort();
        for (size_t x = 0; x < 9 * n; ++x) {
            sf[x] = (float)s[x];
            tf[x] = (float)t[x];
        }
        if (n > 0 && ttd_batch_f(NULL, n, sf, tf, NULL, r) != TTD_OK)
            abort();
        for (size_t e = 0, p = 0; e < n; ++p) {
            const ttd_result_f *best = &r[e];
            if (kind[e] == 1 && r[e + 1].distance < best->distance)
                best = &r[e + 1];
            e += kind[e] == 1 ? 2 : 1;
            out[p].d = (double)best->distance;
            for (int c = 0; c < 3; ++c) {
                out[p].p[c] = (double)best->p[c];
                out[p].q[c] = (double)(best->distance == 0 ? best->p[c] : best->q[c]);
            }
        }
        free(sf);
        free(tf);
        free(r);
    }
    free(s);
    free(t);
    free(kind);
    *count = np;
    return out;
}

#endif /* TTD_TESTS_SELF_BRUTE_H */

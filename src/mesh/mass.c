/* SPDX-License-Identifier: MIT */
/* A closed mesh's mass properties (docs/mass-properties.md): volume, area, centre and inertia of
 * the solid it bounds, of uniform density.
 *
 * The divergence theorem turns each integral over the solid into one over its surface, and a
 * triangle's share is that of the tetrahedron it makes with a reference point o: for the
 * tetrahedron (o, a, b, c), with a, b, c taken relative to o,
 *     V = det(a, b, c) / 6,   int x dV = V (a + b + c) / 4,
 *     int x x^T dV = V / 20 (a a^T + b b^T + c c^T + s s^T),  s = a + b + c.
 * Summed over a closed surface the tetrahedra outside cancel, whatever o is; o is the centre of
 * the vertices' box, so that the terms are of the size of the mesh, not of where it sits. The
 * coordinates relative to o are scaled by a power of two to about 1 (no square or fifth power
 * overflows or underflows), the scale put back at the end by exact multiplications. Every sum
 * is compensated (Neumaier's: the rounding error of each addition kept and added at the end), so
 * a quantity is its terms' exact sum to about one rounding of the largest of them, whatever the
 * number of triangles. */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "mesh/mass.h"
#include "mesh/mesh.h"

/* A compensated sum. */
typedef struct csum {
    double s, c;
} csum;

static void csum_add(csum *x, double v)
{
    const double t = x->s + v;
    x->c += fabs(x->s) >= fabs(v) ? (x->s - t) + v : (v - t) + x->s;
    x->s = t;
}

static double csum_get(const csum *x)
{
    return x->s + x->c;
}

static int u64_cmp(const void *x, const void *y)
{
    const uint64_t a = *(const uint64_t *)x, b = *(const uint64_t *)y;
    return (a > b) - (a < b);
}

/* Whether every edge between two places runs once each way (edges within one place, of
 * triangles without area there, are left out): 1, 0, or -1 out of memory. */
static int closed_by_place(const struct ttd_mesh *m, const ttd_mesh_edges *E)
{
    uint64_t *e = malloc(3 * m->nt * sizeof *e + 1);
    if (e == NULL)
        return -1;
    size_t n = 0;
    for (size_t t = 0; t < m->nt; ++t)
        for (int k = 0; k < 3; ++k) {
            const uint64_t u = E->weld[m->tris[3 * t + (size_t)k]], v = E->weld[m->tris[3 * t + (size_t)(k + 1) % 3]];
            if (u != v)
                e[n++] = u << 32 | v;
        }
    qsort(e, n, sizeof *e, u64_cmp);
    int closed = 1;
    for (size_t i = 0; i < n && closed; ++i) {
        const uint64_t rev = (e[i] & 0xffffffffu) << 32 | e[i] >> 32;
        closed = !(i + 1 < n && e[i + 1] == e[i]) && bsearch(&rev, e, n, sizeof *e, u64_cmp) != NULL;
    }
    free(e);
    return closed;
}

static double vertex_coord(const struct ttd_mesh *m, size_t v, int r)
{
    return m->bytes == 8 ? ((const double *)m->verts)[3 * v + (size_t)r]
                         : (double)((const float *)m->verts)[3 * v + (size_t)r];
}

ttd_status ttd_mesh_mass_compute(const struct ttd_mesh *m, double density, ttd_mass_properties *out)
{
    const ttd_mesh_edges *E = ttd_mesh_edges_get(m);
    if (E == NULL)
        return TTD_ERR_OUT_OF_MEMORY;
    const int closed = closed_by_place(m, E);
    if (closed < 0)
        return TTD_ERR_OUT_OF_MEMORY;
    if (!closed)
        return TTD_ERR_MESH_NOT_CLOSED;
    /* o: the centre of the vertices' box; the scale 2^-ex brings the largest offset to [0.5, 1) */
    double lo[3], hi[3], o[3], far = 0;
    for (int r = 0; r < 3; ++r) {
        lo[r] = hi[r] = vertex_coord(m, 0, r);
        for (size_t v = 1; v < m->nv; ++v) {
            const double x = vertex_coord(m, v, r);
            lo[r] = x < lo[r] ? x : lo[r];
            hi[r] = x > hi[r] ? x : hi[r];
        }
        o[r] = 0.5 * lo[r] + 0.5 * hi[r];
        far = fmax(far, fmax(hi[r] - o[r], o[r] - lo[r]));
    }
    int ex = 0;
    if (far > 0)
        frexp(far, &ex);
    csum vol = {0, 0}, area = {0, 0}, first[3] = {{0, 0}}, second[6] = {{0, 0}}; /* xx yy zz xy yz zx */
    for (size_t t = 0; t < m->nt; ++t) {
        double p[3][3];
        for (int k = 0; k < 3; ++k)
            for (int r = 0; r < 3; ++r)
                p[k][r] = ldexp(vertex_coord(m, m->tris[3 * t + (size_t)k], r) - o[r], -ex);
        const double *a = p[0], *b = p[1], *c = p[2];
        const double bc[3] = {b[1] * c[2] - b[2] * c[1], b[2] * c[0] - b[0] * c[2], b[0] * c[1] - b[1] * c[0]};
        const double V = (a[0] * bc[0] + a[1] * bc[1] + a[2] * bc[2]) / 6;
        const double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        const double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
        csum_add(&area, 0.5 * sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]));
        csum_add(&vol, V);
        const double s[3] = {a[0] + b[0] + c[0], a[1] + b[1] + c[1], a[2] + b[2] + c[2]};
        for (int r = 0; r < 3; ++r)
            csum_add(&first[r], V * s[r] / 4);
        static const int ia[6] = {0, 1, 2, 0, 1, 2}, ib[6] = {0, 1, 2, 1, 2, 0};
        for (int q = 0; q < 6; ++q) {
            const int x = ia[q], y = ib[q];
            const double sum = a[x] * a[y] + b[x] * b[y] + c[x] * c[y] + s[x] * s[y];
            csum_add(&second[q], V * sum / 20);
        }
    }
    const double V = csum_get(&vol); /* at scale 2^-ex */
    ttd_mass_properties r;
    r.volume = ldexp(V, 3 * ex);
    r.area = ldexp(csum_get(&area), 2 * ex);
    r.mass = density * fabs(r.volume);
    if (!(V != 0)) {
        for (int k = 0; k < 3; ++k)
            r.center[k] = (double)NAN;
        for (int k = 0; k < 9; ++k)
            r.inertia[k] = (double)NAN;
        *out = r;
        return TTD_OK;
    }
    /* the centre g (scaled, relative to o); the second moments about it: C - V g g^T */
    double g[3], C[3][3];
    for (int k = 0; k < 3; ++k)
        g[k] = csum_get(&first[k]) / V;
    static const int ia[6] = {0, 1, 2, 0, 1, 2}, ib[6] = {0, 1, 2, 1, 2, 0};
    for (int q = 0; q < 6; ++q) {
        const int x = ia[q], y = ib[q];
        /* the shift subtracted inside the compensated sum: its rounding too is kept */
        csum c = second[q];
        csum_add(&c, -V * g[x] * g[y]);
        C[x][y] = C[y][x] = csum_get(&c);
    }
    /* inertia = density (tr(C) I - C), with the volume's sign taken out (an inward mesh's
     * integrals are all negated) */
    const double sign = V < 0 ? -1 : 1;
    for (int x = 0; x < 3; ++x) {
        r.center[x] = o[x] + ldexp(g[x], ex);
        for (int y = 0; y < 3; ++y) /* I_xx = C_yy + C_zz (not tr C - C_xx: no cancellation), I_xy = -C_xy */
            r.inertia[3 * x + y] =
                density * sign * ldexp(x == y ? C[(x + 1) % 3][(x + 1) % 3] + C[(x + 2) % 3][(x + 2) % 3] : -C[x][y], 5 * ex);
    }
    *out = r;
    return TTD_OK;
}

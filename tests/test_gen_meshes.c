/* SPDX-License-Identifier: MIT */
/* The mesh generators and poses of gen/meshes.h, against properties computed here
 * independently: the Euler characteristic and edge-manifoldness from a sorted edge list (not
 * the generators' hash table), orientation from the signed volume, areas and volumes against
 * closed forms (the icosahedron's, the torus's), midpoints found by brute force, rotations
 * checked for R^T R = I and det R = +1, the gap pose checked against the meshes' supports and
 * against ttd's exact mesh distance, and bit-for-bit determinism. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "meshes.h"
#include "test_macros.h"
#include "ttd/ttd.h"

/* ---- independent mesh measures ------------------------------------------------------- */

/// Edge counts from a sorted list of directed edges.
typedef struct edge_stats {
    size_t edges;          ///< distinct undirected edges
    size_t boundary;       ///< undirected edges in exactly 1 triangle
    size_t nonmanifold;    ///< undirected edges in 3 or more triangles
    size_t twice_directed; ///< directed edges that occur more than once (inconsistent orientation)
} edge_stats;

static int cmp_u64(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return (x > y) - (x < y);
}

static edge_stats edges_of(const ttd_gen_mesh *m)
{
    edge_stats s = {0, 0, 0, 0};
    size_t n = 3 * m->nt;
    uint64_t *und = malloc(n * sizeof *und), *dir = malloc(n * sizeof *dir);
    if (!und || !dir) {
        free(und);
        free(dir);
        s.edges = SIZE_MAX;
        return s;
    }
    for (size_t f = 0; f < m->nt; ++f)
        for (int k = 0; k < 3; ++k) {
            uint64_t a = m->tris[3 * f + (size_t)k], b = m->tris[3 * f + (size_t)(k + 1) % 3];
            dir[3 * f + (size_t)k] = a << 32 | b;
            und[3 * f + (size_t)k] = a < b ? (a << 32 | b) : (b << 32 | a);
        }
    qsort(und, n, sizeof *und, cmp_u64);
    qsort(dir, n, sizeof *dir, cmp_u64);
    for (size_t i = 0; i < n;) {
        size_t j = i;
        while (j < n && und[j] == und[i])
            ++j;
        ++s.edges;
        if (j - i == 1) ++s.boundary;
        if (j - i >= 3) ++s.nonmanifold;
        i = j;
    }
    for (size_t i = 1; i < n; ++i)
        if (dir[i] == dir[i - 1])
            ++s.twice_directed;
    free(und);
    free(dir);
    return s;
}

/// Closed, every edge in exactly two triangles, consistently oriented, V - E + F == chi.
static int check_closed_manifold(const ttd_gen_mesh *m, long chi)
{
    edge_stats s = edges_of(m);
    ENSURE(s.edges != SIZE_MAX);
    ENSURE_MSG(s.boundary == 0 && s.nonmanifold == 0, "boundary %zu, non-manifold %zu", s.boundary, s.nonmanifold);
    ENSURE(2 * s.edges == 3 * m->nt); /* with the above: every edge in exactly two triangles */
    ENSURE_MSG(s.twice_directed == 0, "%zu directed edges repeated", s.twice_directed);
    long euler = (long)m->nv - (long)s.edges + (long)m->nt;
    ENSURE_MSG(euler == chi, "V - E + F = %ld - %zu + %zu = %ld, expected %ld", (long)m->nv, s.edges, m->nt, euler, chi);
    return 0;
}

static void cross(const double *a, const double *b, double *c)
{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}

static void tri_normal(const ttd_gen_mesh *m, size_t f, double n[3])
{
    const double *a = m->verts + 3 * m->tris[3 * f], *b = m->verts + 3 * m->tris[3 * f + 1],
                 *c = m->verts + 3 * m->tris[3 * f + 2];
    double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    cross(u, v, n);
}

static double area(const ttd_gen_mesh *m)
{
    double s = 0;
    for (size_t f = 0; f < m->nt; ++f) {
        double n[3];
        tri_normal(m, f, n);
        s += 0.5 * sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    }
    return s;
}

/// Signed volume: sum of the tetrahedra (origin, a, b, c).
static double volume(const ttd_gen_mesh *m)
{
    double s = 0;
    for (size_t f = 0; f < m->nt; ++f) {
        const double *a = m->verts + 3 * m->tris[3 * f], *b = m->verts + 3 * m->tris[3 * f + 1],
                     *c = m->verts + 3 * m->tris[3 * f + 2];
        double n[3];
        cross(b, c, n);
        s += (a[0] * n[0] + a[1] * n[1] + a[2] * n[2]) / 6.0;
    }
    return s;
}

static int indices_in_range(const ttd_gen_mesh *m)
{
    for (size_t k = 0; k < 3 * m->nt; ++k)
        if (m->tris[k] >= m->nv)
            return 0;
    return 1;
}

static const double pi = 3.14159265358979323846;

/* ---- closed surfaces ----------------------------------------------------------------- */

static int icosphere_topology_and_radius(void)
{
    for (int level = 0; level <= 5; ++level) {
        ttd_gen_mesh m;
        ENSURE(ttd_gen_icosphere(level, &m) == 0);
        size_t f = (size_t)20 << (2 * level);
        ENSURE_MSG(m.nt == f && m.nv == f / 2 + 2, "level %d: %zu vertices, %zu triangles", level, m.nv, m.nt);
        ENSURE(indices_in_range(&m));
        if (check_closed_manifold(&m, 2)) return 1;
        double worst = 0;
        for (size_t k = 0; k < m.nv; ++k) {
            const double *p = m.verts + 3 * k;
            worst = fmax(worst, fabs(sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) - 1.0));
        }
        ENSURE_MSG(worst <= 4e-16, "level %d: radius off by %.3g", level, worst);
        /* outward: every triangle's normal points away from the centre, volume positive */
        for (size_t t = 0; t < m.nt; ++t) {
            double n[3];
            tri_normal(&m, t, n);
            const double *a = m.verts + 3 * m.tris[3 * t];
            ENSURE(n[0] * a[0] + n[1] * a[1] + n[2] * a[2] > 0);
        }
        double v = volume(&m);
        ENSURE(v > 0 && v < 4.0 / 3.0 * pi);
        if (level == 0) {
            /* the icosahedron inscribed in the unit sphere: edge a = 4 / sqrt(10 + 2 sqrt 5),
             * volume (5/12)(3 + sqrt 5) a^3, area 5 sqrt 3 a^2 */
            double a = 4.0 / sqrt(10.0 + 2.0 * sqrt(5.0));
            ENSURE_NEAR(v, 5.0 / 12.0 * (3.0 + sqrt(5.0)) * a * a * a, 1e-14);
            ENSURE_NEAR(area(&m), 5.0 * sqrt(3.0) * a * a, 1e-14);
        }
        if (level == 5) { /* edges ~1/30 long: within 1e-3 (relative) of 4 pi/3 and 4 pi (5.4e-4, 3.0e-4 measured) */
            ENSURE_NEAR(v, 4.0 / 3.0 * pi, 1e-3 * 4.0 / 3.0 * pi);
            ENSURE_NEAR(area(&m), 4.0 * pi, 1e-3 * 4.0 * pi);
        }
        ttd_gen_mesh_free(&m);
    }
    return 0;
}

static int icosphere_levels_nest(void)
{
    /* level L keeps level L-1's vertices, in order, bit for bit */
    ttd_gen_mesh a, b;
    ENSURE(ttd_gen_icosphere(2, &a) == 0 && ttd_gen_icosphere(3, &b) == 0);
    ENSURE(b.nv > a.nv && memcmp(a.verts, b.verts, 3 * a.nv * sizeof(double)) == 0);
    ENSURE(b.nt == 1280);
    ttd_gen_mesh_free(&a);
    ttd_gen_mesh_free(&b);
    return 0;
}

static int torus_topology_and_volume(void)
{
    const size_t sizes[][2] = {{3, 3}, {4, 7}, {64, 32}, {400, 200}};
    for (size_t s = 0; s < sizeof sizes / sizeof sizes[0]; ++s) {
        size_t nu = sizes[s][0], nv = sizes[s][1];
        double R = 2.0, r = 0.5;
        ttd_gen_mesh m;
        ENSURE(ttd_gen_torus(R, r, nu, nv, &m) == 0);
        ENSURE(m.nt == 2 * nu * nv && m.nv == nu * nv && indices_in_range(&m));
        if (check_closed_manifold(&m, 0)) return 1;
        double worst = 0; /* every vertex on the smooth torus */
        for (size_t k = 0; k < m.nv; ++k) {
            const double *p = m.verts + 3 * k;
            double rho = sqrt(p[0] * p[0] + p[1] * p[1]) - R;
            worst = fmax(worst, fabs(sqrt(rho * rho + p[2] * p[2]) - r));
        }
        ENSURE_MSG(worst < 1e-15, "off the torus by %.3g", worst);
        double v = volume(&m), smooth = 2 * pi * pi * R * r * r;
        ENSURE(v > 0 && v < smooth);
        if (nu >= 64) {
            /* The inscribed polyhedron misses O(h^2) of the volume: about (2pi/n)^2/6 relative
             * for each direction's chords (0.0016 + 0.0064 at 64 x 32). */
            double rel = (smooth - v) / smooth;
            double bound = (2 * pi / (double)nu) * (2 * pi / (double)nu) / 3 + (2 * pi / (double)nv) * (2 * pi / (double)nv) / 3;
            ENSURE_MSG(rel < bound, "%zu x %zu: volume deficit %.3g, bound %.3g", nu, nv, rel, bound);
        }
        /* outward: the normal of every triangle points away from the tube's centre circle */
        for (size_t t = 0; t < m.nt; ++t) {
            double n[3];
            tri_normal(&m, t, n);
            const double *a = m.verts + 3 * m.tris[3 * t];
            double rho = sqrt(a[0] * a[0] + a[1] * a[1]);
            double out[3] = {a[0] - R * a[0] / rho, a[1] - R * a[1] / rho, a[2]};
            ENSURE(n[0] * out[0] + n[1] * out[1] + n[2] * out[2] > 0);
        }
        ttd_gen_mesh_free(&m);
    }
    return 0;
}

static int torus_million(void)
{
    /* the benchmark's size: 1000 x 500, a million triangles */
    ttd_gen_mesh m;
    ENSURE(ttd_gen_torus(1.0, 0.3, 1000, 500, &m) == 0);
    ENSURE(m.nt == 1000000 && m.nv == 500000 && indices_in_range(&m));
    if (check_closed_manifold(&m, 0)) return 1;
    ttd_gen_mesh_free(&m);
    return 0;
}

/* ---- small meshes -------------------------------------------------------------------- */

static int small_closed_meshes(void)
{
    ttd_gen_mesh m;
    ENSURE(ttd_gen_mesh_tetrahedron(&m) == 0);
    ENSURE(m.nv == 4 && m.nt == 4);
    if (check_closed_manifold(&m, 2)) return 1;
    ENSURE_NEAR(volume(&m), 1.0 / 6.0, 1e-16);
    ttd_gen_mesh_free(&m);

    ENSURE(ttd_gen_mesh_cube(&m) == 0);
    ENSURE(m.nv == 8 && m.nt == 12);
    if (check_closed_manifold(&m, 2)) return 1;
    ENSURE_NEAR(volume(&m), 1.0, 1e-15);
    ENSURE(area(&m) == 6.0); /* twelve halves, exactly */
    /* every triangle lies in a face of the cube and its normal points out of that face */
    for (size_t t = 0; t < m.nt; ++t) {
        double n[3];
        tri_normal(&m, t, n);
        const double *a = m.verts + 3 * m.tris[3 * t];
        int axis = n[0] != 0 ? 0 : n[1] != 0 ? 1 : 2;
        ENSURE(n[(axis + 1) % 3] == 0 && n[(axis + 2) % 3] == 0);
        ENSURE((a[axis] == 1.0 && n[axis] > 0) || (a[axis] == 0.0 && n[axis] < 0));
    }
    ttd_gen_mesh cube = m;

    ENSURE(ttd_gen_mesh_duplicate_vertices(&m) == 0);
    ENSURE(m.nv == 24 && m.nt == 12);
    edge_stats s = edges_of(&m);
    ENSURE(s.boundary == 24); /* topologically six separate squares */
    /* the same triangles as the cube, coordinate for coordinate */
    for (size_t t = 0; t < 12; ++t)
        for (int k = 0; k < 3; ++k)
            ENSURE(memcmp(m.verts + 3 * m.tris[3 * t + (size_t)k], cube.verts + 3 * cube.tris[3 * t + (size_t)k],
                          3 * sizeof(double)) == 0);
    size_t same = 0; /* pairs of distinct vertices at the same place: 8 corners x C(3,2) */
    for (size_t i = 0; i < m.nv; ++i)
        for (size_t j = i + 1; j < m.nv; ++j)
            same += memcmp(m.verts + 3 * i, m.verts + 3 * j, 3 * sizeof(double)) == 0;
    ENSURE(same == 24);
    ttd_gen_mesh_free(&m);
    ttd_gen_mesh_free(&cube);

    ENSURE(ttd_gen_mesh_triangle(&m) == 0);
    ENSURE(m.nv == 3 && m.nt == 1 && area(&m) == 0.5);
    ttd_gen_mesh_free(&m);
    return 0;
}

static int trouble_meshes(void)
{
    ttd_gen_mesh m;
    ENSURE(ttd_gen_mesh_degenerate(&m) == 0);
    ENSURE(indices_in_range(&m));
    int repeated = 0, point = 0, collinear = 0, same_place = 0, needle = 0, cap = 0;
    for (size_t t = 0; t < m.nt; ++t) {
        const uint32_t *i = m.tris + 3 * t;
        const double *a = m.verts + 3 * i[0], *b = m.verts + 3 * i[1], *c = m.verts + 3 * i[2];
        double n[3];
        tri_normal(&m, t, n);
        int zero = n[0] == 0 && n[1] == 0 && n[2] == 0;
        if (i[0] == i[1] && i[1] == i[2]) ++point;
        else if (i[0] == i[1] || i[1] == i[2] || i[0] == i[2]) ++repeated;
        else if (memcmp(a, b, 24) == 0 || memcmp(b, c, 24) == 0 || memcmp(a, c, 24) == 0) same_place += zero;
        else if (zero) ++collinear;
        else {
            double e[3] = {sqrt((b[0] - a[0]) * (b[0] - a[0]) + (b[1] - a[1]) * (b[1] - a[1]) + (b[2] - a[2]) * (b[2] - a[2])),
                           sqrt((c[0] - b[0]) * (c[0] - b[0]) + (c[1] - b[1]) * (c[1] - b[1]) + (c[2] - b[2]) * (c[2] - b[2])),
                           sqrt((a[0] - c[0]) * (a[0] - c[0]) + (a[1] - c[1]) * (a[1] - c[1]) + (a[2] - c[2]) * (a[2] - c[2]))};
            double lo = fmin(e[0], fmin(e[1], e[2])), hi = fmax(e[0], fmax(e[1], e[2]));
            double twice_area = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
            if (lo < 1e-9) ++needle;                            /* a tiny edge */
            else if (twice_area / (hi * hi) < 1e-9) ++cap;      /* no tiny edge, tiny height */
        }
    }
    ENSURE(repeated == 1 && point == 1 && collinear == 1 && same_place == 1 && needle == 1 && cap == 1);

    ttd_gen_mesh_free(&m);
    ENSURE(ttd_gen_mesh_nonmanifold(&m) == 0);
    edge_stats s = edges_of(&m);
    ENSURE(s.nonmanifold == 1 && s.boundary == 6);
    ttd_gen_mesh_free(&m);

    ENSURE(ttd_gen_grid(7, &m) == 0);
    ENSURE(m.nv == 64 && m.nt == 98 && indices_in_range(&m));
    ENSURE_NEAR(area(&m), 1.0, 1e-15);
    s = edges_of(&m);
    ENSURE(s.boundary == 28 && s.nonmanifold == 0 && s.twice_directed == 0);
    ENSURE((long)m.nv - (long)s.edges + (long)m.nt == 1); /* a disc */
    for (size_t t = 0; t < m.nt; ++t) {
        double n[3];
        tri_normal(&m, t, n);
        ENSURE(n[0] == 0 && n[1] == 0 && n[2] > 0);
    }
    ttd_gen_mesh_free(&m);
    return 0;
}

/* ---- subdivision and normalisation --------------------------------------------------- */

static int subdivide_keeps_surface(void)
{
    ttd_gen_mesh base[3];
    ENSURE(ttd_gen_icosphere(1, &base[0]) == 0);
    ENSURE(ttd_gen_torus(3.0, 1.0, 12, 8, &base[1]) == 0);
    ENSURE(ttd_gen_mesh_cube(&base[2]) == 0);
    for (int b = 0; b < 3; ++b) {
        double a0 = area(&base[b]), v0 = volume(&base[b]);
        long chi = b == 1 ? 0 : 2;
        ttd_gen_mesh m;
        ENSURE(ttd_gen_subdivide(&base[b], 3, &m) == 0);
        ENSURE(m.nt == 64 * base[b].nt && indices_in_range(&m));
        if (check_closed_manifold(&m, chi)) return 1;
        ENSURE_NEAR(area(&m), a0, 1e-13 * a0);
        ENSURE_NEAR(volume(&m), v0, 1e-13 * fabs(v0));
        ENSURE(memcmp(m.verts, base[b].verts, 3 * base[b].nv * sizeof(double)) == 0);
        ttd_gen_mesh_free(&m);
    }
    /* one level: every new vertex is the midpoint of an old edge, found by brute force, and
     * the counts are V + E and 4F */
    ttd_gen_mesh m;
    ENSURE(ttd_gen_subdivide(&base[1], 1, &m) == 0);
    edge_stats s = edges_of(&base[1]);
    ENSURE(m.nv == base[1].nv + s.edges && m.nt == 4 * base[1].nt);
    for (size_t k = base[1].nv; k < m.nv; ++k) {
        int found = 0;
        for (size_t t = 0; t < base[1].nt && !found; ++t)
            for (int e = 0; e < 3 && !found; ++e) {
                const double *p = base[1].verts + 3 * base[1].tris[3 * t + (size_t)e];
                const double *q = base[1].verts + 3 * base[1].tris[3 * t + (size_t)(e + 1) % 3];
                const double *x = m.verts + 3 * k;
                found = x[0] == 0.5 * p[0] + 0.5 * q[0] && x[1] == 0.5 * p[1] + 0.5 * q[1] && x[2] == 0.5 * p[2] + 0.5 * q[2];
            }
        ENSURE_MSG(found, "vertex %zu is no edge's midpoint", k);
    }
    ttd_gen_mesh_free(&m);
    /* in place, zero levels, and meshes that are not manifold */
    ttd_gen_mesh c;
    ENSURE(ttd_gen_mesh_copy(&base[2], &c) == 0);
    ENSURE(ttd_gen_subdivide(&c, 2, &c) == 0 && c.nt == 192);
    ENSURE(ttd_gen_subdivide(&c, 0, &m) == 0 && m.nt == 192 && memcmp(m.verts, c.verts, 3 * c.nv * sizeof(double)) == 0);
    ttd_gen_mesh_free(&m);
    ttd_gen_mesh_free(&c);
    ENSURE(ttd_gen_mesh_nonmanifold(&c) == 0);
    ENSURE(ttd_gen_subdivide(&c, 1, &m) == 0 && m.nt == 12 && m.nv == 5 + 7);
    ttd_gen_mesh_free(&m);
    ttd_gen_mesh_free(&c);
    ENSURE(ttd_gen_mesh_degenerate(&c) == 0);
    double a0 = area(&c);
    ENSURE(ttd_gen_subdivide(&c, 2, &m) == 0 && m.nt == 16 * c.nt && indices_in_range(&m));
    ENSURE_NEAR(area(&m), a0, 1e-14);
    ttd_gen_mesh_free(&m);
    ttd_gen_mesh_free(&c);
    for (int b = 0; b < 3; ++b)
        ttd_gen_mesh_free(&base[b]);
    return 0;
}

static int normalize_box(void)
{
    ttd_gen_mesh m;
    ENSURE(ttd_gen_torus(5.0, 2.0, 30, 20, &m) == 0);
    double lo[3], hi[3], e[3];
    ENSURE(ttd_gen_mesh_bounds(&m, lo, hi) == 0);
    for (size_t k = 0; k < m.nv; ++k) { /* move it far off and stretch it */
        m.verts[3 * k] = 1e6 + 3 * m.verts[3 * k];
        m.verts[3 * k + 2] -= 7e5;
    }
    e[0] = 3 * (hi[0] - lo[0]); e[1] = hi[1] - lo[1]; e[2] = hi[2] - lo[2];
    double old_diag = sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
    ENSURE(ttd_gen_normalize(&m) == 0);
    ENSURE(ttd_gen_mesh_bounds(&m, lo, hi) == 0);
    double diag = sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) + (hi[2] - lo[2]) * (hi[2] - lo[2]));
    ENSURE_NEAR(diag, 1.0, 1e-11);
    /* translated by 1e6 with extents ~40: centre and shape hold to about 1e6 eps / 40 */
    for (int d = 0; d < 3; ++d) {
        ENSURE_NEAR(0.5 * (lo[d] + hi[d]), 0.0, 1e-11);
        ENSURE_NEAR(hi[d] - lo[d], e[d] / old_diag, 1e-11);
    }
    ttd_gen_mesh_free(&m);

    ENSURE(ttd_gen_icosphere(2, &m) == 0); /* centred already: exact to a few ulps */
    for (size_t k = 0; k < 3 * m.nv; ++k) m.verts[k] = 3.0 * m.verts[k] + 0.25;
    ENSURE(ttd_gen_normalize(&m) == 0 && ttd_gen_mesh_bounds(&m, lo, hi) == 0);
    diag = sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) + (hi[2] - lo[2]) * (hi[2] - lo[2]));
    ENSURE_NEAR(diag, 1.0, 1e-15);
    for (int d = 0; d < 3; ++d)
        ENSURE_NEAR(0.5 * (lo[d] + hi[d]), 0.0, 1e-16);
    ttd_gen_mesh_free(&m);

    /* huge and tiny coordinates: the diagonal's square would overflow or underflow */
    ENSURE(ttd_gen_mesh_cube(&m) == 0);
    for (size_t k = 0; k < 3 * m.nv; ++k) m.verts[k] *= 1e300;
    ENSURE(ttd_gen_normalize(&m) == 0 && ttd_gen_mesh_bounds(&m, lo, hi) == 0);
    ENSURE_NEAR(hi[0] - lo[0], 1.0 / sqrt(3.0), 1e-15);
    for (size_t k = 0; k < 3 * m.nv; ++k) m.verts[k] *= 1e-300;
    ENSURE(ttd_gen_normalize(&m) == 0 && ttd_gen_mesh_bounds(&m, lo, hi) == 0);
    ENSURE_NEAR(hi[2] - lo[2], 1.0 / sqrt(3.0), 1e-15);
    /* refused: a point, a NaN, an overflowing box */
    for (size_t k = 0; k < 3 * m.nv; ++k) m.verts[k] = 2.0;
    ENSURE(ttd_gen_normalize(&m) == -1 && m.verts[0] == 2.0);
    m.verts[4] = (double)NAN;
    ENSURE(ttd_gen_normalize(&m) == -1);
    m.verts[4] = 2.0;
    m.verts[0] = -1e308; m.verts[3] = 1e308; /* the x extent overflows */
    ENSURE(ttd_gen_normalize(&m) == -1 && m.verts[3] == 1e308);
    m.verts[0] = 0.0; /* extents 1e308 and 2: a finite diagonal, no overflow on the way */
    ENSURE(ttd_gen_normalize(&m) == 0 && ttd_gen_mesh_bounds(&m, lo, hi) == 0);
    ENSURE_NEAR(hi[0] - lo[0], 1.0, 1e-15);
    ttd_gen_mesh_free(&m);
    return 0;
}

/* ---- poses --------------------------------------------------------------------------- */

static int poses_are_rotations(void)
{
    double mean[9] = {0};
    const int n = 20000;
    for (int i = 0; i < n; ++i) {
        double p[12];
        ttd_gen_pose(42, (uint64_t)i, 3.0, p);
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c) {
                double s = 0;
                for (int k = 0; k < 3; ++k) s += p[4 * k + r] * p[4 * k + c];
                ENSURE_NEAR(s, r == c ? 1.0 : 0.0, 1e-15);
                mean[3 * r + c] += p[4 * r + c] / n;
            }
        double det = p[0] * (p[5] * p[10] - p[6] * p[9]) - p[1] * (p[4] * p[10] - p[6] * p[8]) + p[2] * (p[4] * p[9] - p[5] * p[8]);
        ENSURE_NEAR(det, 1.0, 1e-15);
        for (int r = 0; r < 3; ++r)
            ENSURE(p[4 * r + 3] >= -3.0 && p[4 * r + 3] < 3.0);
    }
    /* uniform rotations average to the zero matrix; each entry has variance 1/3, so its mean
     * over n has standard deviation 1/sqrt(3n) = 0.004; allow 5 of them */
    for (int k = 0; k < 9; ++k)
        ENSURE_MSG(fabs(mean[k]) < 5.0 / sqrt(3.0 * n), "mean entry %d = %.4f", k, mean[k]);
    return 0;
}

static int determinism(void)
{
    double p[12], q[12];
    ttd_gen_pose(7, 123, 1.0, p);
    ttd_gen_pose(7, 123, 1.0, q);
    ENSURE(memcmp(p, q, sizeof p) == 0);
    ttd_gen_pose(7, 124, 1.0, q);
    ENSURE(memcmp(p, q, sizeof p) != 0);
    ttd_gen_pose(8, 123, 1.0, q);
    ENSURE(memcmp(p, q, sizeof p) != 0);
    ttd_gen_pose(7, 123, 0.0, q); /* the rotation does not depend on the scale */
    for (int r = 0; r < 3; ++r)
        ENSURE(memcmp(p + 4 * r, q + 4 * r, 3 * sizeof(double)) == 0 && q[4 * r + 3] == 0.0);

    ttd_gen_mesh a, b;
    ENSURE(ttd_gen_icosphere(3, &a) == 0 && ttd_gen_icosphere(3, &b) == 0);
    ENSURE(a.nv == b.nv && memcmp(a.verts, b.verts, 3 * a.nv * sizeof(double)) == 0 &&
           memcmp(a.tris, b.tris, 3 * a.nt * sizeof(uint32_t)) == 0);
    ttd_gen_mesh sa, sb;
    ENSURE(ttd_gen_subdivide(&a, 2, &sa) == 0 && ttd_gen_subdivide(&b, 2, &sb) == 0);
    ENSURE(sa.nv == sb.nv && memcmp(sa.verts, sb.verts, 3 * sa.nv * sizeof(double)) == 0 &&
           memcmp(sa.tris, sb.tris, 3 * sa.nt * sizeof(uint32_t)) == 0);
    double g1[12], g2[12];
    ENSURE(ttd_gen_pose_gap(&a, &sa, 5, 9, NULL, 0.01, g1) == 0 && ttd_gen_pose_gap(&b, &sb, 5, 9, NULL, 0.01, g2) == 0);
    ENSURE(memcmp(g1, g2, sizeof g1) == 0);
    ttd_gen_mesh_free(&a);
    ttd_gen_mesh_free(&b);
    ttd_gen_mesh_free(&sa);
    ttd_gen_mesh_free(&sb);
    return 0;
}

/// The exact minimum distance between two meshes by brute force over every triangle pair.
static double mesh_distance(const ttd_gen_mesh *a, const ttd_gen_mesh *b)
{
    size_t n = a->nt * b->nt;
    double *s = malloc(9 * n * sizeof(double)), *t = malloc(9 * n * sizeof(double)), *d = malloc(n * sizeof(double));
    double best = (double)NAN;
    if (s && t && d) {
        for (size_t i = 0; i < a->nt; ++i)
            for (size_t j = 0; j < b->nt; ++j)
                for (int k = 0; k < 3; ++k) {
                    memcpy(s + 9 * (i * b->nt + j) + 3 * k, a->verts + 3 * a->tris[3 * i + (size_t)k], 3 * sizeof(double));
                    memcpy(t + 9 * (i * b->nt + j) + 3 * k, b->verts + 3 * b->tris[3 * j + (size_t)k], 3 * sizeof(double));
                }
        ttd_options opt = ttd_default_options();
        if (ttd_batch_d(&opt, n, s, t, d, NULL) == TTD_OK) {
            best = (double)INFINITY;
            for (size_t k = 0; k < n; ++k)
                best = fmin(best, d[k]);
        }
    }
    free(s);
    free(t);
    free(d);
    return best;
}

static int pose_at_gap(void)
{
    ttd_gen_mesh a, b, moved;
    ENSURE(ttd_gen_icosphere(1, &a) == 0 && ttd_gen_torus(2.0, 0.7, 12, 8, &b) == 0);
    ENSURE(ttd_gen_normalize(&a) == 0 && ttd_gen_normalize(&b) == 0);
    const double gaps[] = {1.0, 0.01, 0.002, 0.0, -0.05};
    const double axis[3] = {0, 0, 2};
    for (int g = 0; g < 5; ++g)
        for (uint64_t i = 0; i < 6; ++i) {
            double pose[12];
            const double *dir = i % 2 ? axis : NULL;
            ENSURE(ttd_gen_pose_gap(&a, &b, 11, i, dir, gaps[g], pose) == 0);
            /* the rotation is pose i's */
            double p[12];
            ttd_gen_pose(11, i, 1.0, p);
            for (int r = 0; r < 3; ++r)
                ENSURE(memcmp(p + 4 * r, pose + 4 * r, 3 * sizeof(double)) == 0);
            ENSURE(ttd_gen_mesh_transform(&b, pose, &moved) == 0);
            /* the direction: the given axis, or found as the one along which the supports are
             * gap apart (recover it from the translation of the box centres) */
            double u[3] = {0, 0, 1};
            if (!dir) {
                double alo[3], ahi[3], blo[3], bhi[3];
                ENSURE(ttd_gen_mesh_bounds(&a, alo, ahi) == 0);
                ttd_gen_mesh rot;
                double r0[12];
                memcpy(r0, pose, sizeof r0);
                r0[3] = r0[7] = r0[11] = 0;
                ENSURE(ttd_gen_mesh_transform(&b, r0, &rot) == 0 && ttd_gen_mesh_bounds(&rot, blo, bhi) == 0);
                double n2 = 0;
                for (int d = 0; d < 3; ++d) {
                    u[d] = pose[4 * d + 3] - (0.5 * (alo[d] + ahi[d]) - 0.5 * (blo[d] + bhi[d]));
                    n2 += u[d] * u[d];
                }
                ttd_gen_mesh_free(&rot);
                ENSURE(n2 > 0);
                for (int d = 0; d < 3; ++d) u[d] /= sqrt(n2);
            }
            double h = -(double)INFINITY, l = (double)INFINITY;
            for (size_t k = 0; k < a.nv; ++k)
                h = fmax(h, u[0] * a.verts[3 * k] + u[1] * a.verts[3 * k + 1] + u[2] * a.verts[3 * k + 2]);
            for (size_t k = 0; k < moved.nv; ++k)
                l = fmin(l, u[0] * moved.verts[3 * k] + u[1] * moved.verts[3 * k + 1] + u[2] * moved.verts[3 * k + 2]);
            ENSURE_MSG(fabs(l - h - gaps[g]) < 1e-14, "gap %g, pose %d: slab gap %.17g", gaps[g], (int)i, l - h);
            if (gaps[g] > 0) {
                double d = mesh_distance(&a, &moved);
                ENSURE_MSG(d >= gaps[g] * (1 - 1e-9) && d < gaps[g] + 0.5, "gap %g: distance %.17g", gaps[g], d);
            }
            ttd_gen_mesh_free(&moved);
        }
    double pose[12];
    ENSURE(ttd_gen_pose_gap(&a, &b, 1, 2, (const double[3]){0, 0, 0}, 0.1, pose) == -1);
    ENSURE(ttd_gen_pose_gap(&a, &b, 1, 2, NULL, (double)NAN, pose) == -1);
    ttd_gen_mesh_free(&a);
    ttd_gen_mesh_free(&b);
    return 0;
}

static int bad_arguments(void)
{
    ttd_gen_mesh m = {0}, c;
    ENSURE(ttd_gen_icosphere(-1, &m) == -1 && m.verts == NULL && m.nt == 0);
    ENSURE(ttd_gen_icosphere(11, &m) == -1 && m.verts == NULL);
    ENSURE(ttd_gen_icosphere(0, NULL) == -1);
    ENSURE(ttd_gen_torus(1.0, 1.0, 10, 10, &m) == -1);
    ENSURE(ttd_gen_torus(1.0, 0.0, 10, 10, &m) == -1);
    ENSURE(ttd_gen_torus((double)NAN, 0.5, 10, 10, &m) == -1);
    ENSURE(ttd_gen_torus(1.0, 0.5, 2, 10, &m) == -1);
    ENSURE(ttd_gen_torus(1.0, 0.5, (size_t)1 << 20, (size_t)1 << 20, &m) == -1);
    ENSURE(ttd_gen_grid(0, &m) == -1 && ttd_gen_grid(70000, &m) == -1);
    ENSURE(ttd_gen_subdivide(NULL, 1, &m) == -1);
    ENSURE(ttd_gen_mesh_cube(&c) == 0);
    ENSURE(ttd_gen_subdivide(&c, -1, &m) == -1 && m.verts == NULL);
    c.tris[5] = 8; /* out of range */
    ENSURE(ttd_gen_subdivide(&c, 1, &m) == -1 && m.verts == NULL);
    ttd_gen_mesh_free(&c);
    ENSURE(ttd_gen_normalize(NULL) == -1 && ttd_gen_normalize(&m) == -1);
    ttd_gen_mesh_free(NULL);
    return 0;
}

/* The folded strip: a square strip is the folded sheet, bit for bit; a 7-layer strip folded flat
 * has its layers gap apart (every vertex at one of 7 heights away from the folds, those heights
 * gap apart); bad sizes are refused. */
static int folded_strip(void)
{
    ttd_gen_mesh a, b;
    ENSURE(ttd_gen_folded_sheet(12, 3, 0.02, 0.9, &a) == 0 && ttd_gen_folded_strip(12, 12, 3, 0.02, 0.9, &b) == 0);
    ENSURE(a.nv == b.nv && a.nt == b.nt && memcmp(a.verts, b.verts, 3 * a.nv * sizeof *a.verts) == 0 &&
           memcmp(a.tris, b.tris, 3 * a.nt * sizeof *a.tris) == 0);
    ttd_gen_mesh_free(&a);
    ttd_gen_mesh_free(&b);
    const size_t nx = 595, ny = 85;
    const double gap = 0.75 / (double)nx;
    ENSURE(ttd_gen_folded_strip(nx, ny, 7, gap, 1.0, &a) == 0);
    ENSURE(a.nt == 101150 && a.nv == (nx + 1) * (ny + 1));
    int on_layer = 0;
    for (size_t i = 0; i < a.nv; ++i) {
        const double z = a.verts[3 * i + 2], k = z / gap; /* layer k at height k gap */
        if (fabs(k - floor(k + 0.5)) < 1e-6)
            ++on_layer;
        ENSURE(a.verts[3 * i + 1] == (double)(i / (nx + 1)) / (double)nx);
    }
    ENSURE(on_layer > (int)(0.9 * (double)a.nv));
    ttd_gen_mesh_free(&a);
    ENSURE(ttd_gen_folded_strip(0, 5, 2, 0.1, 1.0, &a) == -1 && ttd_gen_folded_strip(5, 0, 2, 0.1, 1.0, &a) == -1);
    ENSURE(ttd_gen_folded_strip(65535, 2, 2, 0.1, 1.0, &a) == -1 && ttd_gen_folded_strip(4, 4, 2, 10.0, 1.0, &a) == -1);
    return 0;
}

int main(int argc, char **argv)
{
    TEST_MAIN_BEGIN(argc, argv);
    RUN_TEST(icosphere_topology_and_radius);
    RUN_TEST(icosphere_levels_nest);
    RUN_TEST(torus_topology_and_volume);
    RUN_TEST(torus_million);
    RUN_TEST(small_closed_meshes);
    RUN_TEST(trouble_meshes);
    RUN_TEST(subdivide_keeps_surface);
    RUN_TEST(normalize_box);
    RUN_TEST(poses_are_rotations);
    RUN_TEST(determinism);
    RUN_TEST(pose_at_gap);
    RUN_TEST(bad_arguments);
    RUN_TEST(folded_strip);
    TEST_MAIN_END();
}

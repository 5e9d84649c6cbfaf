/* SPDX-License-Identifier: MIT */
/* ttd_mesh_mass_properties_d/_f (docs/mass-properties.md; issue 32, item 5), against references
 * that do not share its formulas:
 *   - boxes a x b x c, faces cut 1 x 1 and 3 x 3, centred anywhere (to 1e6 away) and at scales
 *     1e-100 to 1e100, turned by a general rotation: volume abc, area 2(ab + bc + ca), the centre,
 *     inertia R diag(m (b^2 + c^2) / 12, ...) R^T, each to a few ulps of its size, in double and
 *     float; wound inward: the volume -abc, the rest the same; without shared vertices (an STL
 *     file's): the same;
 *   - icospheres of levels 1 to 6: volume and inertia between those of the balls inside and
 *     around them (the polyhedron holds the ball of its faces' smallest distance from the centre
 *     and lies in the unit ball, and the integrals grow with the domain), the gaps shrinking
 *     4-fold a level; tori (R 1, r 0.3) of 16 x 8 to 256 x 128 segments: volume and both moments
 *     converge to 2 pi^2 R r^2, m (R^2 + 3 r^2 / 4), m (R^2 / 2 + 5 r^2 / 8), the error at least
 *     3-fold smaller per doubling and below 1e-3 at the finest;
 *   - refusals: a box with a face reversed or missing, NULL pointers, density 0, -1, NaN, inf,
 *     the other precision's mesh; *out untouched;
 *   - two SolidWorks parts' STL (tests/data/cad) against SolidWorks's figures for the parts,
 *     within a tolerance derived from the tessellation (cad_parts, below).
 * Exact rational references over random tetrahedra and boxes: python/tests/test_mass.py. */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "boxes.h"
#include "meshes.h"
#include "test_macros.h"
#include <ttd/meshfile.h>
#include <ttd/ttd.h>

static const double PI = 3.14159265358979323846;

static ttd_status mass(int bytes, const ttd_mesh *m, double density, ttd_mass_properties *out)
{
    return bytes == 8 ? ttd_mesh_mass_properties_d(m, density, out) : ttd_mesh_mass_properties_f(m, density, out);
}

/* A rotation from the unit quaternion along (1, 2, 3) by angle t. */
static void rotation(double t, double R[9])
{
    const double l = sqrt(14.0), s = sin(t / 2);
    const double w = cos(t / 2), x = s / l, y = 2 * s / l, z = 3 * s / l;
    const double M[9] = {1 - 2 * (y * y + z * z), 2 * (x * y - w * z),     2 * (x * z + w * y),
                         2 * (x * y + w * z),     1 - 2 * (x * x + z * z), 2 * (y * z - w * x),
                         2 * (x * z - w * y),     2 * (y * z + w * x),     1 - 2 * (x * x + y * y)};
    memcpy(R, M, sizeof M);
}

static int boxes_analytic(void)
{
    static const double dims[][3] = {{1, 1, 1}, {3, 1, 0.6}, {0.25, 2, 0.125}, {40, 0.5, 1}};
    static const double centres[][3] = {{0, 0, 0}, {0.3, -2, 5}, {1e6, -1e6, 3e5}};
    static const double scales[] = {1, 1e-50, 1e50, 1e-30};
    size_t cases = 0;
    double worst = 0;
    for (int bytes = 8; bytes >= 4; bytes -= 4)
        for (size_t di = 0; di < 4; ++di)
            for (int cut = 1; cut <= 3; cut += 2)
                for (size_t ci = 0; ci < 3; ++ci)
                    for (size_t si = 0; si < 4; ++si)
                        for (int turned = 0; turned < 2; ++turned)
                            for (int inward = 0; inward < 2; ++inward) {
                                if (bytes == 4 && (si == 1 || si == 2 || ci == 2))
                                    continue; /* float's range and digits */
                                const double sc = scales[si], a = dims[di][0] * sc, b = dims[di][1] * sc,
                                             c = dims[di][2] * sc;
                                test_box B;
                                ENSURE(test_box_make(a, b, c, cut, &B) == 0);
                                double R[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
                                if (turned)
                                    rotation(0.7, R);
                                double ctr[3];
                                for (int r = 0; r < 3; ++r)
                                    ctr[r] = centres[ci][r] * sc;
                                for (size_t v = 0; v < B.nv; ++v) {
                                    double x[3];
                                    for (int r = 0; r < 3; ++r)
                                        x[r] = R[3 * r] * B.v[3 * v] + R[3 * r + 1] * B.v[3 * v + 1] +
                                               R[3 * r + 2] * B.v[3 * v + 2] + ctr[r];
                                    memcpy(B.v + 3 * v, x, sizeof x);
                                }
                                if (inward)
                                    for (size_t t = 0; t < B.nt; ++t) {
                                        const uint32_t s = B.t[3 * t + 1];
                                        B.t[3 * t + 1] = B.t[3 * t + 2];
                                        B.t[3 * t + 2] = s;
                                    }
                                ttd_mesh *m = test_mesh_of(bytes, B.v, B.nv, B.t, B.nt);
                                ENSURE(m != NULL);
                                const double rho = 2.5;
                                ttd_mass_properties p;
                                ENSURE(mass(bytes, m, rho, &p) == TTD_OK);
                                /* the float mesh's box is the one its rounded vertices make: allow
                                 * their rounding (a few float ulps of the coordinates' size) */
                                const double eps = bytes == 8 ? 64 * DBL_EPSILON : 64 * (double)FLT_EPSILON;
                                const double far = fmax(fabs(ctr[0]), fmax(fabs(ctr[1]), fabs(ctr[2]))) + a + b + c;
                                /* exact vertices (double, dyadic sides, not turned, cut 1, scale 1): a
                                 * few ulps; else the vertices are rounded at the size of their
                                 * coordinates, and the box they make is the analytic one only to that */
                                const int exact = bytes == 8 && !turned && si == 0 && cut == 1 && di != 1;
                                const double rel_v = exact ? eps : eps * far / fmin(a, fmin(b, c));
                                const double V = a * b * c, M = rho * V;
                                char what[160];
                                snprintf(what, sizeof what, "%s box %g x %g x %g cut %d at (%g, %g, %g)%s%s",
                                         bytes == 8 ? "double" : "float", a, b, c, cut, ctr[0], ctr[1], ctr[2],
                                         turned ? " turned" : "", inward ? " inward" : "");
                                ENSURE_MSG(fabs(p.volume - (inward ? -V : V)) <= rel_v * V, "%s: volume %.17g", what,
                                           p.volume);
                                ENSURE_MSG(fabs(p.mass - M) <= rel_v * M, "%s: mass %.17g", what, p.mass);
                                const double A = 2 * (a * b + b * c + c * a);
                                ENSURE_MSG(fabs(p.area - A) <= rel_v * A, "%s: area %.17g, want %.17g", what, p.area, A);
                                for (int r = 0; r < 3; ++r)
                                    ENSURE_MSG(fabs(p.center[r] - ctr[r]) <= eps * far, "%s: centre %d %.17g", what, r,
                                               p.center[r]);
                                const double D[3] = {M * (b * b + c * c) / 12, M * (a * a + c * c) / 12,
                                                     M * (a * a + b * b) / 12};
                                const double big = fmax(D[0], fmax(D[1], D[2]));
                                for (int x = 0; x < 3; ++x)
                                    for (int y = 0; y < 3; ++y) {
                                        double want = 0; /* (R D R^T)_xy */
                                        for (int k = 0; k < 3; ++k)
                                            want += R[3 * x + k] * D[k] * R[3 * y + k];
                                        const double err = fabs(p.inertia[3 * x + y] - want) / big;
                                        worst = bytes == 8 && ci < 2 ? fmax(worst, err) : worst;
                                        ENSURE_MSG(err <= 10 * rel_v,
                                                   "%s: inertia %d %d %.17g, want %.17g", what, x, y,
                                                   p.inertia[3 * x + y], want);
                                    }
                                ttd_mesh_destroy(m);
                                test_box_free(&B);
                                ++cases;
                            }
    printf("  %zu boxes: volume, mass, area, centre, inertia R D R^T (worst inertia error in double near the "
           "origin: %.2g of the largest moment)\n", cases, worst);
    return 0;
}

static int boxes_unshared_and_refused(void)
{
    test_box B;
    ENSURE(test_box_make(3, 1, 0.6, 1, &B) == 0);
    ttd_mesh *m = test_mesh_of(8, B.v, B.nv, B.t, B.nt);
    ENSURE(m != NULL);
    ttd_mass_properties want, got;
    ENSURE(ttd_mesh_mass_properties_d(m, 1, &want) == TTD_OK);
    /* every triangle its own three vertices */
    double *v = malloc(9 * B.nt * sizeof *v);
    uint32_t *t = malloc(3 * B.nt * sizeof *t);
    ENSURE(v != NULL && t != NULL);
    for (size_t k = 0; k < 3 * B.nt; ++k) {
        memcpy(v + 3 * k, B.v + 3 * (size_t)B.t[k], 3 * sizeof *v);
        t[k] = (uint32_t)k;
    }
    ttd_mesh *u = test_mesh_of(8, v, 3 * B.nt, t, B.nt);
    ENSURE(u != NULL);
    ENSURE(ttd_mesh_mass_properties_d(u, 1, &got) == TTD_OK);
    ENSURE(memcmp(&got, &want, sizeof got) == 0);
    ttd_mesh_destroy(u);
    /* one triangle reversed: not closed by orientation; one missing: open */
    const uint32_t s = B.t[1];
    B.t[1] = B.t[2];
    B.t[2] = s;
    ttd_mesh *flip = test_mesh_of(8, B.v, B.nv, B.t, B.nt), *open = test_mesh_of(8, B.v, B.nv, B.t + 3, B.nt - 1);
    ENSURE(flip != NULL && open != NULL);
    memset(&got, 0x5a, sizeof got);
    ttd_mass_properties untouched;
    memcpy(&untouched, &got, sizeof got);
    ENSURE(ttd_mesh_mass_properties_d(flip, 1, &got) == TTD_ERR_MESH_NOT_CLOSED);
    ENSURE(ttd_mesh_mass_properties_d(open, 1, &got) == TTD_ERR_MESH_NOT_CLOSED);
    ENSURE(ttd_mesh_mass_properties_d(NULL, 1, &got) == TTD_ERR_NULL_POINTER);
    ENSURE(ttd_mesh_mass_properties_d(m, 1, NULL) == TTD_ERR_NULL_POINTER);
    const double bad[] = {0, -1, NAN, INFINITY, -INFINITY};
    for (int k = 0; k < 5; ++k)
        ENSURE(ttd_mesh_mass_properties_d(m, bad[k], &got) == TTD_ERR_BAD_OPTIONS);
    ENSURE(ttd_mesh_mass_properties_f(m, 1, &got) == TTD_ERR_PRECISION_MISMATCH);
    ENSURE(memcmp(&got, &untouched, sizeof got) == 0);
    ttd_mesh *mf = test_mesh_of(4, B.v, B.nv, B.t, B.nt);
    ENSURE(mf != NULL && ttd_mesh_mass_properties_d(mf, 1, &got) == TTD_ERR_PRECISION_MISMATCH);
    ttd_mesh_destroy(mf);
    ttd_mesh_destroy(flip);
    ttd_mesh_destroy(open);
    ttd_mesh_destroy(m);
    free(v);
    free(t);
    test_box_free(&B);
    printf("  a box without shared vertices: the same bits; a face reversed or missing, NULL, bad densities, the "
           "other precision: refused, *out untouched\n");
    return 0;
}

static int sphere_between_balls(void)
{
    double prev_gap = 0;
    for (int level = 1; level <= 6; ++level) {
        ttd_gen_mesh g;
        ENSURE(ttd_gen_icosphere(level, &g) == 0);
        /* rho: the faces' smallest distance from the centre (the polyhedron holds that ball) */
        double rho = 1;
        for (size_t t = 0; t < g.nt; ++t) {
            const double *a = g.verts + 3 * (size_t)g.tris[3 * t], *b = g.verts + 3 * (size_t)g.tris[3 * t + 1],
                         *c = g.verts + 3 * (size_t)g.tris[3 * t + 2];
            const double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
            const double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
            rho = fmin(rho, fabs(test_dot(n, a)) / sqrt(test_dot(n, n)));
        }
        ttd_mesh *m = test_mesh_of(8, g.verts, g.nv, g.tris, g.nt);
        ENSURE(m != NULL);
        ttd_mass_properties p;
        ENSURE(ttd_mesh_mass_properties_d(m, 1, &p) == TTD_OK);
        const double Vin = 4 * PI / 3 * rho * rho * rho, Vout = 4 * PI / 3;
        const double Iin = 0.4 * Vin * rho * rho, Iout = 0.4 * Vout;
        const double slack = 1e-12;
        ENSURE_MSG(p.volume >= Vin * (1 - slack) && p.volume <= Vout * (1 + slack), "level %d: volume %.17g not in [%.17g, %.17g]",
                   level, p.volume, Vin, Vout);
        for (int k = 0; k < 3; ++k) {
            ENSURE_MSG(p.inertia[4 * k] >= Iin * (1 - slack) && p.inertia[4 * k] <= Iout * (1 + slack),
                       "level %d: moment %d %.17g not in [%.17g, %.17g]", level, k, p.inertia[4 * k], Iin, Iout);
            ENSURE(fabs(p.center[k]) <= 1e-14);
        }
        const double gap = Vout - p.volume;
        if (level > 1)
            ENSURE_MSG(gap < prev_gap / 3, "level %d: volume error %.3g, before %.3g", level, gap, prev_gap);
        prev_gap = gap;
        printf("  icosphere level %d (%zu triangles): volume %.12f (ball %.12f, inner ball %.12f), moment %.12f\n", level,
               g.nt, p.volume, Vout, Vin, p.inertia[0]);
        ttd_mesh_destroy(m);
        ttd_gen_mesh_free(&g);
    }
    return 0;
}

static int torus_converges(void)
{
    const double R = 1, r = 0.3;
    const double V = 2 * PI * PI * R * r * r;
    double prev[3] = {0, 0, 0};
    for (size_t nu = 16; nu <= 256; nu *= 2) {
        ttd_gen_mesh g;
        ENSURE(ttd_gen_torus(R, r, nu, nu / 2, &g) == 0);
        ttd_mesh *m = test_mesh_of(8, g.verts, g.nv, g.tris, g.nt);
        ENSURE(m != NULL);
        ttd_mass_properties p;
        ENSURE(ttd_mesh_mass_properties_d(m, 1, &p) == TTD_OK);
        /* against the smooth torus of the same density */
        const double err[3] = {fabs(p.volume - V) / V,
                               fabs(p.inertia[8] - V * (R * R + 0.75 * r * r)) / (V * (R * R + 0.75 * r * r)),
                               fabs(p.inertia[0] - V * (0.5 * R * R + 0.625 * r * r)) / (V * (0.5 * R * R + 0.625 * r * r))};
        for (int k = 0; k < 3; ++k)
            if (nu > 16)
                ENSURE_MSG(err[k] < prev[k] / 3, "torus %zu x %zu: error %d %.3g, before %.3g", nu, nu / 2, k, err[k], prev[k]);
        memcpy(prev, err, sizeof err);
        printf("  torus %zu x %zu: relative errors volume %.2e, I_zz %.2e, I_xx %.2e\n", nu, nu / 2, err[0], err[1], err[2]);
        ttd_mesh_destroy(m);
        ttd_gen_mesh_free(&g);
    }
    ENSURE(prev[0] < 1e-3 && prev[1] < 1e-3 && prev[2] < 1e-3);
    return 0;
}

/* Two parts exported from SolidWorks as STL, against the mass properties SolidWorks reported for
 * the exact parts (tests/data/cad/README.md: source, licence, units). The figures are of the CAD
 * solids, the mesh's are of the chords between its vertices, so they may differ by the
 * tessellation's error; the tolerance is derived from the mesh itself (docs/mass-properties.md):
 * every edge whose faces' normals turn by less than 20 degrees (these files' smooth turns are at
 * most 15, their CAD edges at least 30) lies on a curved surface, which over the face beside it
 * bulges by the sagitta h = (c / 2) tan(theta / 4) of an arc of angle theta over the face's chord
 * c (its height over the edge). With h_f, theta_f the largest over a face's smooth edges:
 *   volume: the solid and the mesh differ only within slabs h_f thick over the curved faces,
 *     dV = sum A_f h_f (plus the float rounding of the vertices, u |x|max per unit area);
 *   area: an arc is longer than its chord by (theta / 2) / sin(theta / 2), so the part's area
 *     exceeds the mesh's by about dA = sum A_f ((theta_f / 2) / sin(theta_f / 2) - 1); allowed
 *     2 dA (doubly curved corners add to it), and the part's must be the larger;
 *   centre: g moves by (dS - g dV) / V', |dS - g dV| <= dV (r + h), r the farthest vertex from g;
 *   inertia about the centre: rho dV (r + h)^2 about g, plus M' |dg|^2 for the centre's move;
 * each plus half a unit of the figure's last printed digit. */
typedef struct cad_part {
    const char *file;
    double density, mass, area, center[3], moments[3], p_yz; /* p_yz: SolidWorks's, +integral yz dm */
    double printed;                                           /* the figures' last printed digit */
} cad_part;

static const cad_part CAD_PARTS[] = {
    {"angle_block.STL", 0.036127, 0.041358, 9.388587, {0, 0.436105, -0.599006}, {0.008312, 0.012823, 0.009005},
     0.000807, 1e-6},
    {"idler_riser.STL", 0.09754366, 0.14522859, 18.13860637, {1.25, 1.21830489, 0.20084261},
     {0.12108243, 0.09131981, 0.2057651}, 0.00013893, 1e-8},
};

static int edge_cmp(const void *a, const void *b)
{
    const uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return x < y ? -1 : x > y;
}

/* dV, dA, the largest sagitta and the number of curved faces of closed mesh (v, t) as above. */
static int tessellation_error(const double *v, const uint32_t *t, size_t nt, double *dV, double *dA, double *hmax,
                             size_t *curved)
{
    /* (directed edge a << 32 | b, its face) pairs, sorted by edge: each edge's twin by bsearch */
    uint64_t *e = malloc(2 * 3 * nt * sizeof *e);
    double *h = calloc(nt, sizeof *h), *th = calloc(nt, sizeof *th);
    ENSURE(e != NULL && h != NULL && th != NULL);
    for (size_t f = 0; f < nt; ++f)
        for (int k = 0; k < 3; ++k) {
            e[2 * (3 * f + k)] = (uint64_t)t[3 * f + k] << 32 | t[3 * f + (k + 1) % 3];
            e[2 * (3 * f + k) + 1] = f;
        }
    qsort(e, 3 * nt, 2 * sizeof *e, edge_cmp);
    double umax = 0;
    for (size_t c = 0; c < 3 * nt; ++c)
        for (int k = 0; k < 3; ++k)
            umax = fmax(umax, fabs(v[3 * (size_t)t[c] + (size_t)k]));
    for (size_t f = 0; f < nt; ++f) {
        const double *a = v + 3 * (size_t)t[3 * f], *b = v + 3 * (size_t)t[3 * f + 1], *c = v + 3 * (size_t)t[3 * f + 2];
        const double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        const double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
        const double n2 = sqrt(test_dot(n, n));
        for (int k = 0; k < 3; ++k) {
            const uint32_t p = t[3 * f + k], q = t[3 * f + (k + 1) % 3];
            const uint64_t rev[2] = {(uint64_t)q << 32 | p, 0};
            const uint64_t *hit = bsearch(rev, e, 3 * nt, 2 * sizeof *e, edge_cmp);
            ENSURE(hit != NULL); /* closed: the mass properties accepted it */
            const size_t g = (size_t)hit[1];
            const double *x = v + 3 * (size_t)t[3 * g], *y = v + 3 * (size_t)t[3 * g + 1], *z = v + 3 * (size_t)t[3 * g + 2];
            const double g1[3] = {y[0] - x[0], y[1] - x[1], y[2] - x[2]}, g2[3] = {z[0] - x[0], z[1] - x[1], z[2] - x[2]};
            const double m[3] = {g1[1] * g2[2] - g1[2] * g2[1], g1[2] * g2[0] - g1[0] * g2[2], g1[0] * g2[1] - g1[1] * g2[0]};
            const double cosang = test_dot(n, m) / (n2 * sqrt(test_dot(m, m)));
            const double theta = acos(fmax(-1.0, fmin(1.0, cosang)));
            if (theta >= 20 * PI / 180)
                continue; /* a CAD edge */
            const double pq[3] = {v[3 * (size_t)q] - v[3 * (size_t)p], v[3 * (size_t)q + 1] - v[3 * (size_t)p + 1],
                                  v[3 * (size_t)q + 2] - v[3 * (size_t)p + 2]};
            const double chord = n2 / sqrt(test_dot(pq, pq)); /* the face's height over pq */
            h[f] = fmax(h[f], chord / 2 * tan(theta / 4));
            th[f] = fmax(th[f], theta);
        }
    }
    *dV = *dA = *hmax = 0;
    *curved = 0;
    for (size_t f = 0; f < nt; ++f) {
        const double *a = v + 3 * (size_t)t[3 * f], *b = v + 3 * (size_t)t[3 * f + 1], *c = v + 3 * (size_t)t[3 * f + 2];
        const double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        const double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
        const double A = sqrt(test_dot(n, n)) / 2;
        *dV += A * (h[f] + umax * (double)FLT_EPSILON / 2);
        if (th[f] > 0)
            *dA += A * (th[f] / 2 / sin(th[f] / 2) - 1);
        *hmax = fmax(*hmax, h[f]);
        *curved += h[f] > 0;
    }
    free(e);
    free(h);
    free(th);
    return 0;
}

static int cad_parts(void)
{
    for (size_t k = 0; k < sizeof CAD_PARTS / sizeof *CAD_PARTS; ++k) {
        const cad_part *P = &CAD_PARTS[k];
        char path[512], err[256];
        snprintf(path, sizeof path, "%s/%s", TTD_CAD_DATA, P->file);
        ttd_meshfile f;
        ENSURE_MSG(ttd_meshfile_read(path, TTD_MESHFILE_FLOAT, &f, err, sizeof err) == 0, "%s", err);
        /* the exporter's copies of a corner differ by up to 5e-16 (its shortest edge: 1.1e-3) */
        size_t dropped = 1;
        ENSURE_MSG(ttd_meshfile_weld(&f, 1e-9, &dropped, err, sizeof err) == 0, "%s", err);
        ENSURE(dropped == 0);
        ttd_mesh *md = NULL, *mf = NULL;
        ENSURE(ttd_mesh_create_d(NULL, f.verts, f.nv, f.tris, f.nt, &md) == TTD_OK);
        ENSURE(ttd_mesh_create_f(NULL, f.verts_f, f.nv, f.tris, f.nt, &mf) == TTD_OK);
        ttd_mass_properties p, pf;
        ENSURE(ttd_mesh_mass_properties_d(md, P->density, &p) == TTD_OK);
        ENSURE(ttd_mesh_mass_properties_f(mf, P->density, &pf) == TTD_OK);
        /* an STL's coordinates are floats: the float mesh holds the same vertices, computed in double */
        ENSURE(memcmp(&p, &pf, sizeof p) == 0);
        double dV, dA, hmax;
        size_t curved;
        ENSURE(tessellation_error(f.verts, f.tris, f.nt, &dV, &dA, &hmax, &curved) == 0);
        double r = 0;
        for (size_t i = 0; i < f.nv; ++i) {
            const double d[3] = {f.verts[3 * i] - p.center[0], f.verts[3 * i + 1] - p.center[1],
                                 f.verts[3 * i + 2] - p.center[2]};
            r = fmax(r, sqrt(test_dot(d, d)));
        }
        const double half = P->printed / 2, rho = P->density;
        const double tol_m = rho * dV + half, tol_a = 2 * dA + half;
        const double dg = dV * (r + hmax) / (fabs(p.volume) - dV), tol_g = dg + half;
        const double tol_i = rho * dV * (r + hmax) * (r + hmax) + (p.mass + rho * dV) * dg * dg + half;
        printf("  %s: %zu triangles (%zu on curved surfaces, sagitta up to %.3g)\n", P->file, f.nt, curved, hmax);
        printf("    mass %.9g, SolidWorks %.9g: %+.3g (allowed %.3g)\n", p.mass, P->mass, p.mass - P->mass, tol_m);
        printf("    volume %.9g, SolidWorks (mass / density) %.9g: %+.3g (allowed %.3g)\n", p.volume, P->mass / rho,
               p.volume - P->mass / rho, tol_m / rho);
        printf("    area %.9g, SolidWorks %.9g: %+.3g (expected -%.3g from the chords, allowed -%.3g)\n", p.area, P->area,
               p.area - P->area, dA, tol_a);
        ENSURE_MSG(fabs(p.mass - P->mass) <= tol_m, "%s: mass %.9g, SolidWorks %.9g", P->file, p.mass, P->mass);
        /* the volume SolidWorks's mass and density imply */
        ENSURE_MSG(fabs(p.volume - P->mass / rho) <= tol_m / rho, "%s: volume %.9g, SolidWorks %.9g", P->file, p.volume,
                   P->mass / rho);
        ENSURE_MSG(P->area - p.area >= -half && P->area - p.area <= tol_a, "%s: area %.9g, SolidWorks %.9g", P->file,
                   p.area, P->area);
        double worst_g = 0, worst_i = 0;
        for (int i = 0; i < 3; ++i) {
            worst_g = fmax(worst_g, fabs(p.center[i] - P->center[i]));
            ENSURE_MSG(fabs(p.center[i] - P->center[i]) <= tol_g, "%s: centre %d %.9g, SolidWorks %.9g", P->file, i,
                       p.center[i], P->center[i]);
            for (int j = 0; j < 3; ++j) {
                /* the tensor: the moments on the diagonal, minus SolidWorks's products off it */
                const double want = i == j ? P->moments[i] : (i + j == 3 ? -P->p_yz : 0.0);
                worst_i = fmax(worst_i, fabs(p.inertia[3 * i + j] - want));
                ENSURE_MSG(fabs(p.inertia[3 * i + j] - want) <= tol_i, "%s: inertia %d %d %.9g, SolidWorks %.9g", P->file,
                           i, j, p.inertia[3 * i + j], want);
            }
        }
        printf("    centre (%.9g, %.9g, %.9g): off by up to %.3g (allowed %.3g)\n", p.center[0], p.center[1], p.center[2],
               worst_g, tol_g);
        printf("    inertia diagonal (%.9g, %.9g, %.9g), yz %.9g: off by up to %.3g (allowed %.3g)\n", p.inertia[0],
               p.inertia[4], p.inertia[8], p.inertia[5], worst_i, tol_i);
        ttd_mesh_destroy(md);
        ttd_mesh_destroy(mf);
        ttd_meshfile_free(&f);
    }
    return 0;
}

int main(int argc, char **argv)
{
    TEST_MAIN_BEGIN(argc, argv);
    RUN_TEST(boxes_analytic);
    RUN_TEST(boxes_unshared_and_refused);
    RUN_TEST(sphere_between_balls);
    RUN_TEST(torus_converges);
    RUN_TEST(cad_parts);
    TEST_MAIN_END();
}

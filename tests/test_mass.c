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
 *     the other precision's mesh; *out untouched.
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

int main(int argc, char **argv)
{
    TEST_MAIN_BEGIN(argc, argv);
    RUN_TEST(boxes_analytic);
    RUN_TEST(boxes_unshared_and_refused);
    RUN_TEST(sphere_between_balls);
    RUN_TEST(torus_converges);
    TEST_MAIN_END();
}

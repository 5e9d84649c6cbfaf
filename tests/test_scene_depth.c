/* SPDX-License-Identifier: MIT */
/* Depth for every interpenetration of solids (docs/scenes.md, section 5b; issue 32, item 1): two
 * solid boxes overlapping, with or without a vertex of either inside the other, against the
 * penetration depth by separating axes written here (the 15 axes of two boxes: each box's face
 * normals and the cross products of their edges; the depth is the smallest overlap of the
 * boxes' projections, its axis the separating direction):
 *   - crossing square rods 2 x 0.1 x 0.1 at right angles, sunk 0.02 to 0.08 into each other
 *     (no vertex of either inside the other), turned about z by 0 to 60 degrees and tilted about
 *     x by up to 0.2 rad; a box sunk face first into a bigger one (its vertices inside); a box
 *     nested inside another;
 *   - the manifold (K = 0 and 4) has a point below 0 wherever the depth is above 0; no point
 *     deeper than the depth (a point inside the other at distance d from its surface must move
 *     at least d to leave it, so d <= the depth, each point a real pair of points);
 *   - boxes are convex: in every case the deepest point's |d| is the depth, and its normal a
 *     separating direction (body 1 clears body 0 by moving the depth along it; docs/scenes.md
 *     5b, the convex pairs' point);
 * double and float. The code before this test gave the crossing rods no point below 0, and the
 * code before the convex pairs' point 0.39 of the depth (rods sunk 0.08) and 0.55 (nested). */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "boxes.h"
#include "test_macros.h"
#include <ttd/ttd.h>

/* A box: centre, axes (columns of R), half sides. */
typedef struct obb {
    double c[3], R[9], h[3];
} obb;

/* The penetration depth of two boxes by separating axes and its axis (unit, from a towards b);
 * 0 where they are apart. */
static double sat_depth(const obb *a, const obb *b, double axis[3])
{
    double ax[15][3];
    int n = 0;
    for (int k = 0; k < 3; ++k) {
        for (int r = 0; r < 3; ++r) {
            ax[n][r] = a->R[3 * r + k];
            ax[n + 1][r] = b->R[3 * r + k];
        }
        n += 2;
    }
    for (int k = 0; k < 3; ++k)
        for (int l = 0; l < 3; ++l) {
            const double u[3] = {a->R[k], a->R[3 + k], a->R[6 + k]}, v[3] = {b->R[l], b->R[3 + l], b->R[6 + l]};
            double w[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
            const double len = sqrt(test_dot(w, w));
            if (len < 1e-9)
                continue;
            for (int r = 0; r < 3; ++r)
                ax[n][r] = w[r] / len;
            ++n;
        }
    double best = INFINITY;
    for (int q = 0; q < n; ++q) {
        double ra = 0, rb = 0;
        for (int k = 0; k < 3; ++k) {
            ra += a->h[k] * fabs(a->R[k] * ax[q][0] + a->R[3 + k] * ax[q][1] + a->R[6 + k] * ax[q][2]);
            rb += b->h[k] * fabs(b->R[k] * ax[q][0] + b->R[3 + k] * ax[q][1] + b->R[6 + k] * ax[q][2]);
        }
        const double d[3] = {b->c[0] - a->c[0], b->c[1] - a->c[1], b->c[2] - a->c[2]};
        const double dist = test_dot(d, ax[q]);
        const double overlap = ra + rb - fabs(dist);
        if (overlap < best) {
            best = overlap;
            for (int r = 0; r < 3; ++r)
                axis[r] = dist < 0 ? -ax[q][r] : ax[q][r];
        }
    }
    return best > 0 ? best : 0;
}

/* R = Rz(yaw) Rx(tilt). */
static void rot(double yaw, double tilt, double R[9])
{
    const double cz = cos(yaw), sz = sin(yaw), cx = cos(tilt), sx = sin(tilt);
    const double M[9] = {cz, -sz * cx, sz * sx, sz, cz * cx, -cz * sx, 0, sx, cx};
    memcpy(R, M, sizeof M);
}

/* The manifold of solid boxes a and b; the smallest distance, its normal, the count of points
 * below 0 and their number. */
static int run(int bytes, const obb *A, const obb *B, size_t K, double *dmin, double nrm[3], size_t *neg, size_t *count)
{
    test_box ba, bb;
    if (test_box_make(2 * A->h[0], 2 * A->h[1], 2 * A->h[2], 1, &ba) || test_box_make(2 * B->h[0], 2 * B->h[1], 2 * B->h[2], 1, &bb))
        return 1;
    ttd_scene *s = NULL;
    ttd_mesh *ma = NULL, *mb = NULL;
    const obb *o[2] = {A, B};
    test_box *tb[2] = {&ba, &bb};
    ttd_mesh **mm[2] = {&ma, &mb};
    int rc = (bytes == 8 ? ttd_scene_create_d(&s) : ttd_scene_create_f(&s)) != TTD_OK;
    for (int k = 0; k < 2 && !rc; ++k) {
        double P[12];
        for (int r = 0; r < 3; ++r) {
            P[4 * r] = o[k]->R[3 * r];
            P[4 * r + 1] = o[k]->R[3 * r + 1];
            P[4 * r + 2] = o[k]->R[3 * r + 2];
            P[4 * r + 3] = o[k]->c[r];
        }
        uint32_t id;
        if (bytes == 8) {
            rc = ttd_mesh_create_d(NULL, tb[k]->v, tb[k]->nv, tb[k]->t, tb[k]->nt, mm[k]) != TTD_OK ||
                 ttd_scene_add_d(s, *mm[k], P, &id) != TTD_OK;
        } else {
            float vf[3 * 64], pf[12];
            for (size_t q = 0; q < 3 * tb[k]->nv; ++q)
                vf[q] = (float)tb[k]->v[q];
            for (int q = 0; q < 12; ++q)
                pf[q] = (float)P[q];
            rc = ttd_mesh_create_f(NULL, vf, tb[k]->nv, tb[k]->t, tb[k]->nt, mm[k]) != TTD_OK ||
                 ttd_scene_add_f(s, *mm[k], pf, &id) != TTD_OK;
        }
        rc = rc || ttd_scene_set_solid(s, id, 1) != TTD_OK;
    }
    ttd_scene_array arr = {0};
    if (!rc)
        rc = (bytes == 8 ? ttd_scene_manifold_d(NULL, s, 0.005, K, &arr) : ttd_scene_manifold_f(NULL, s, 0.005f, K, &arr)) != TTD_OK;
    *dmin = INFINITY;
    *neg = 0;
    *count = rc ? 0 : arr.count;
    for (size_t q = 0; !rc && q < arr.count; ++q) {
        double d, n[3];
        if (bytes == 8) {
            const ttd_scene_point_d *p = (const ttd_scene_point_d *)arr.data + q;
            d = p->distance;
            memcpy(n, p->normal, sizeof n);
        } else {
            const ttd_scene_point_f *p = (const ttd_scene_point_f *)arr.data + q;
            d = p->distance;
            for (int r = 0; r < 3; ++r)
                n[r] = p->normal[r];
        }
        *neg += d < 0;
        if (d < *dmin) {
            *dmin = d;
            memcpy(nrm, n, 3 * sizeof *n);
        }
    }
    ttd_scene_array_free(&arr);
    ttd_scene_destroy(s);
    ttd_mesh_destroy(ma);
    ttd_mesh_destroy(mb);
    test_box_free(&ba);
    test_box_free(&bb);
    return rc;
}

/* How far b must move along unit n to clear a: h_a(n) + h_b(-n). */
static double box_overlap_along(const obb *a, const obb *b, const double n[3])
{
    double ra = 0, rb = 0;
    for (int k = 0; k < 3; ++k) {
        ra += a->h[k] * fabs(a->R[k] * n[0] + a->R[3 + k] * n[1] + a->R[6 + k] * n[2]);
        rb += b->h[k] * fabs(b->R[k] * n[0] + b->R[3 + k] * n[1] + b->R[6 + k] * n[2]);
    }
    const double d[3] = {b->c[0] - a->c[0], b->c[1] - a->c[1], b->c[2] - a->c[2]};
    return ra + rb - test_dot(d, n);
}

static int check_case(const char *what, const obb *A, const obb *B, size_t *cases)
{
    double axis[3] = {0, 0, 1};
    const double pd = sat_depth(A, B, axis);
    for (int bytes = 8; bytes >= 4; bytes -= 4)
        for (size_t K = 0; K <= 4; K += 4) {
            double dmin, n[3];
            size_t neg, count;
            ENSURE(run(bytes, A, B, K, &dmin, n, &neg, &count) == 0);
            const double tol = bytes == 8 ? 1e-9 : 1e-5;
            ENSURE_MSG(neg > 0, "%s, %s, K %zu: depth %.6g by separating axes, no point below 0 (%zu points, deepest %.6g)",
                       what, bytes == 8 ? "double" : "float", K, pd, count, dmin);
            ENSURE_MSG(-dmin <= pd + tol, "%s, %s, K %zu: a point %.9g deep, deeper than the depth %.9g", what,
                       bytes == 8 ? "double" : "float", K, -dmin, pd);
            /* convex solids: the deepest point is the penetration depth, its normal a separating
               direction (b clears a by moving the depth along it) */
            ENSURE_MSG(fabs(-dmin - pd) <= tol, "%s, %s, K %zu: deepest %.12g, depth %.12g", what,
                       bytes == 8 ? "double" : "float", K, -dmin, pd);
            const double along = box_overlap_along(A, B, n);
            ENSURE_MSG(fabs(along - pd) <= (bytes == 8 ? 1e-9 : 1e-5),
                       "%s, %s, K %zu: normal (%.6g, %.6g, %.6g), b clears a by %.12g along it, depth %.12g (axis "
                       "(%.6g, %.6g, %.6g))",
                       what, bytes == 8 ? "double" : "float", K, n[0], n[1], n[2], along, pd, axis[0], axis[1], axis[2]);
            if (bytes == 8 && K == 4)
                printf("  %-44s depth %.6f, deepest point %.6f (%zu of %zu points below 0)\n", what, pd, -dmin, neg, count);
            ++*cases;
        }
    return 0;
}

static int crossing_rods(void)
{
    size_t cases = 0;
    static const double sinks[] = {0.02, 0.03, 0.04, 0.06, 0.08};
    static const double yaws[] = {0, 30, 60};
    static const double tilts[] = {0, 0.05, 0.2};
    for (size_t si = 0; si < 5; ++si)
        for (size_t yi = 0; yi < 3; ++yi)
            for (size_t ti = 0; ti < 3; ++ti) {
                obb A = {{0, 0, 0}, {1, 0, 0, 0, 1, 0, 0, 0, 1}, {1, 0.05, 0.05}};
                obb B = {{0.01, -0.02, 0.1 - sinks[si]}, {0}, {0.05, 1, 0.05}};
                rot(yaws[yi] * 3.14159265358979323846 / 180, tilts[ti], B.R);
                char what[96];
                snprintf(what, sizeof what, "rods crossing, sunk %g, turned %g deg, tilted %g", sinks[si], yaws[yi], tilts[ti]);
                ENSURE(check_case(what, &A, &B, &cases) == 0);
            }
    printf("  %zu cases\n", cases);
    return 0;
}

static int sunk_and_nested(void)
{
    size_t cases = 0;
    obb A = {{0, 0, 0}, {1, 0, 0, 0, 1, 0, 0, 0, 1}, {0.5, 0.5, 0.5}};
    for (int k = 0; k < 3; ++k) {
        const double s = 0.05 + 0.05 * k;
        obb B = {{0.05, -0.05, 0.5 + 0.25 - s}, {1, 0, 0, 0, 1, 0, 0, 0, 1}, {0.25, 0.2, 0.25}};
        char what[64];
        snprintf(what, sizeof what, "box sunk %g face first", s);
        ENSURE(check_case(what, &A, &B, &cases) == 0);
        rot(0.4, 0.1, B.R);
        snprintf(what, sizeof what, "box sunk %g, turned and tilted", s);
        ENSURE(check_case(what, &A, &B, &cases) == 0);
    }
    obb B = {{0.05, 0, 0.02}, {0}, {0.2, 0.1, 0.15}};
    rot(0.3, 0.2, B.R);
    ENSURE(check_case("box nested inside", &A, &B, &cases) == 0);
    printf("  %zu cases\n", cases);
    return 0;
}

/* Two unit cubes in one solid mesh, at x in [0, 1] and [3, 4], and a cube of side 0.6 at x in
 * [0.9, 1.5]: every edge of the first mesh is convex, but it is two pieces, so its depth is not
 * its hull's (0.8, along y or z): the penetration is 0.1 along x. No point deeper than that, one
 * below 0. The code that took every convex-edged mesh as one convex body put a point at -0.8. */
static int two_pieces(void)
{
    test_box cube, small;
    ENSURE(test_box_make(1, 1, 1, 1, &cube) == 0 && test_box_make(0.6, 0.6, 0.6, 1, &small) == 0);
    double v[2 * 3 * 8], vb[3 * 8];
    uint32_t t[2 * 3 * 12];
    ENSURE(cube.nv == 8 && cube.nt == 12);
    for (int piece = 0; piece < 2; ++piece) {
        for (size_t q = 0; q < 8; ++q)
            for (int r = 0; r < 3; ++r)
                v[24 * piece + 3 * q + (size_t)r] = cube.v[3 * q + (size_t)r] + (r == 0 ? 0.5 + 3 * piece : 0);
        for (size_t q = 0; q < 36; ++q)
            t[36 * piece + q] = cube.t[q] + 8u * (uint32_t)piece;
    }
    for (size_t q = 0; q < 8; ++q)
        for (int r = 0; r < 3; ++r)
            vb[3 * q + (size_t)r] = small.v[3 * q + (size_t)r] + (r == 0 ? 1.2 : 0);
    for (size_t K = 0; K <= 4; K += 4) {
        ttd_scene *s = NULL;
        ttd_mesh *ma = NULL, *mb = NULL;
        const double id[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
        uint32_t ia, ib;
        ENSURE(ttd_scene_create_d(&s) == TTD_OK);
        ENSURE(ttd_mesh_create_d(NULL, v, 16, t, 24, &ma) == TTD_OK && ttd_mesh_create_d(NULL, vb, 8, small.t, 12, &mb) == TTD_OK);
        ENSURE(ttd_scene_add_d(s, ma, id, &ia) == TTD_OK && ttd_scene_add_d(s, mb, id, &ib) == TTD_OK);
        ENSURE(ttd_scene_set_solid(s, ia, 1) == TTD_OK && ttd_scene_set_solid(s, ib, 1) == TTD_OK);
        ttd_scene_array arr = {0};
        ENSURE(ttd_scene_manifold_d(NULL, s, 0.005, K, &arr) == TTD_OK);
        double dmin = INFINITY;
        for (size_t q = 0; q < arr.count; ++q)
            dmin = fmin(dmin, ((const ttd_scene_point_d *)arr.data)[q].distance);
        ENSURE_MSG(dmin < 0 && -dmin <= 0.1 + 1e-12, "K %zu: deepest point %.9g, the penetration 0.1 (%zu points)", K, -dmin,
                   arr.count);
        printf("  two cubes in one mesh against a smaller one, K %zu: deepest point %.6f (penetration 0.1), %zu points\n", K, -dmin,
               arr.count);
        ttd_scene_array_free(&arr);
        ttd_scene_destroy(s);
        ttd_mesh_destroy(ma);
        ttd_mesh_destroy(mb);
    }
    test_box_free(&cube);
    test_box_free(&small);
    return 0;
}

int main(int argc, char **argv)
{
    TEST_MAIN_BEGIN(argc, argv);
    RUN_TEST(crossing_rods);
    RUN_TEST(sunk_and_nested);
    RUN_TEST(two_pieces);
    TEST_MAIN_END();
}

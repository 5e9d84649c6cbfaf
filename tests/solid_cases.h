/* SPDX-License-Identifier: MIT */
/* Solid pairs that are not both convex, placed in world coordinates, shared by the tests of the
 * faces' deepest points (test_scene_depth_faces.c) and of contact regions (test_scene_regions.c):
 * a ring (torus R 0.6, r 0.25, 576 triangles) with a plate through its tube, a rod through its
 * tube, a box sunk into its top; an L prism with a cube in its inner corner; two L beams crossing.
 * Header-only, static functions; make_*(bytes, variant, a, b) builds the pair rounded to the
 * precision (bytes 4: float), 0 on success. */
#ifndef TTD_TESTS_SOLID_CASES_H
#define TTD_TESTS_SOLID_CASES_H

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "boxes.h"
#include "pairs.h"

#define PI 3.14159265358979323846

typedef struct body {
    double *v;
    uint32_t *t;
    size_t nv, nt;
} body;

static inline void body_free(body *b)
{
    free(b->v);
    free(b->t);
    memset(b, 0, sizeof *b);
}

/* Turn by R (row-major) and move by c, then round to the precision (4: float). */
static inline void body_place(body *b, const double R[9], const double c[3], int bytes)
{
    for (size_t k = 0; k < b->nv; ++k) {
        double *x = b->v + 3 * k, y[3];
        for (int r = 0; r < 3; ++r)
            y[r] = R[3 * r] * x[0] + R[3 * r + 1] * x[1] + R[3 * r + 2] * x[2] + c[r];
        for (int r = 0; r < 3; ++r)
            x[r] = bytes == 4 ? (double)(float)y[r] : y[r];
    }
}

static inline int body_box(double a, double bb, double c, body *out)
{
    test_box t;
    if (test_box_make(a, bb, c, 1, &t)) {
        test_box_free(&t);
        return 1;
    }
    out->v = t.v;
    out->t = t.t;
    out->nv = t.nv;
    out->nt = t.nt;
    return 0;
}

static inline int body_torus(double R, double r, body *out)
{
    ttd_gen_mesh m;
    if (ttd_gen_torus(R, r, 24, 12, &m))
        return 1;
    out->v = m.verts;
    out->t = m.tris;
    out->nv = m.nv;
    out->nt = m.nt;
    return 0;
}

/* An L-shaped prism: the polygon (0,0) (w+a,0) (w+a,w) (w,w) (w,w+a) (0,w+a) in x, y (arms of
 * width w reaching a beyond the corner), from z = 0 to z = h; its inner corner edge (w, w) is
 * concave. */
static inline int body_ell(double w, double a, double h, body *out)
{
    const double P[6][2] = {{0, 0}, {w + a, 0}, {w + a, w}, {w, w}, {w, w + a}, {0, w + a}};
    out->nv = 12;
    out->nt = 20;
    out->v = malloc(3 * out->nv * sizeof *out->v);
    out->t = malloc(3 * out->nt * sizeof *out->t);
    if (out->v == NULL || out->t == NULL)
        return 1;
    for (int k = 0; k < 6; ++k)
        for (int z = 0; z < 2; ++z) {
            double *x = out->v + 3 * (2 * k + z);
            x[0] = P[k][0];
            x[1] = P[k][1];
            x[2] = z ? h : 0;
        }
    size_t n = 0;
    /* caps: the fan from corner 0 covers the L (corner 3 is the reflex one; every fan triangle
     * (0, k, k+1) lies inside it) */
    for (int k = 1; k < 5; ++k) {
        const uint32_t top[3] = {0 + 1, (uint32_t)(2 * k + 1), (uint32_t)(2 * (k + 1) + 1)};
        const uint32_t bot[3] = {0, (uint32_t)(2 * (k + 1)), (uint32_t)(2 * k)};
        memcpy(out->t + 3 * n++, top, sizeof top);
        memcpy(out->t + 3 * n++, bot, sizeof bot);
    }
    for (int k = 0; k < 6; ++k) {
        const uint32_t a0 = (uint32_t)(2 * k), a1 = (uint32_t)(2 * ((k + 1) % 6));
        const uint32_t s1[3] = {a0, a1, a1 + 1}, s2[3] = {a0, a1 + 1, a0 + 1};
        memcpy(out->t + 3 * n++, s1, sizeof s1);
        memcpy(out->t + 3 * n++, s2, sizeof s2);
    }
    return 0;
}

static inline void rot_axis(int axis, double ang, double R[9])
{
    const double c = cos(ang), s = sin(ang);
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    memset(R, 0, 9 * sizeof *R);
    R[3 * axis + axis] = 1;
    R[3 * u + u] = c;
    R[3 * u + v] = -s;
    R[3 * v + u] = s;
    R[3 * v + v] = c;
}

static inline void mat_mul(const double A[9], const double B[9], double C[9])
{
    for (int r = 0; r < 3; ++r)
        for (int k = 0; k < 3; ++k)
            C[3 * r + k] = A[3 * r] * B[k] + A[3 * r + 1] * B[3 + k] + A[3 * r + 2] * B[6 + k];
}

static inline double body_radius(const body *b)
{
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY}, c[3], r = 0;
    for (size_t k = 0; k < b->nv; ++k)
        for (int q = 0; q < 3; ++q) {
            lo[q] = fmin(lo[q], b->v[3 * k + q]);
            hi[q] = fmax(hi[q], b->v[3 * k + q]);
        }
    for (int q = 0; q < 3; ++q)
        c[q] = 0.5 * (lo[q] + hi[q]);
    for (size_t k = 0; k < b->nv; ++k) {
        double d2 = 0;
        for (int q = 0; q < 3; ++q)
            d2 += (b->v[3 * k + q] - c[q]) * (b->v[3 * k + q] - c[q]);
        r = fmax(r, sqrt(d2));
    }
    return r;
}

/* A plate 2 x 2 x 0.04 through the tube of a ring standing on its side (R 0.6, r 0.25). */
static inline int make_plate_ring(int bytes, int variant, body *a, body *b)
{
    if (body_torus(0.6, 0.25, a) || body_box(2, 2, 0.04, b))
        return 1;
    double R[9], T[9], Rt[9];
    rot_axis(1, PI / 2, R);
    rot_axis(0, 0.13 * variant, T);
    mat_mul(T, R, Rt);
    const double c[3] = {0.01 * variant, 0.02, 0.003 * variant}, z[3] = {0, 0, 0};
    body_place(a, Rt, c, bytes);
    double Q[9];
    rot_axis(2, 0.2 * variant, Q);
    body_place(b, Q, z, bytes);
    return 0;
}

/* A rod 0.24 x 0.24 x 2 along z through the tube of a ring lying flat. */
static inline int make_rod_ring(int bytes, int variant, body *a, body *b)
{
    if (body_torus(0.6, 0.25, a) || body_box(0.24, 0.24, 2, b))
        return 1;
    double R[9], I[9];
    rot_axis(0, 0.05 * variant, R);
    rot_axis(2, 0, I);
    const double c[3] = {0.6 + 0.01 * variant, 0.02 * variant, 0}, z[3] = {0, 0, 0};
    body_place(a, I, z, bytes);
    body_place(b, R, c, bytes);
    return 0;
}

/* A box 0.3 on a side sunk 0.05 face first into the top of a ring lying flat. */
static inline int make_box_ring_top(int bytes, int variant, body *a, body *b)
{
    if (body_torus(0.6, 0.25, a) || body_box(0.3, 0.3, 0.3, b))
        return 1;
    double R[9], I[9];
    rot_axis(2, 0.3 * variant, R);
    rot_axis(2, 0, I);
    const double c[3] = {0.6, 0.03 * variant, 0.25 + 0.15 - 0.05}, z[3] = {0, 0, 0};
    body_place(a, I, z, bytes);
    body_place(b, R, c, bytes);
    return 0;
}

/* A cube 0.6 turned 45 degrees about z, its edge pressed 0.1 into an L prism's inner corner. */
static inline int make_cube_corner(int bytes, int variant, body *a, body *b)
{
    if (body_ell(1, 1, 1, a) || body_box(0.6, 0.6, 0.6, b))
        return 1;
    double R[9], T[9], Rt[9], I[9];
    rot_axis(2, PI / 4 + 0.05 * variant, R);
    rot_axis(0, 0.1 * variant, T);
    mat_mul(T, R, Rt);
    rot_axis(2, 0, I);
    const double off = (0.3 * sqrt(2.0) - 0.1) / sqrt(2.0);
    const double c[3] = {1 + off, 1 + off, 0.5}, z[3] = {0, 0, 0};
    body_place(a, I, z, bytes);
    body_place(b, Rt, c, bytes);
    return 0;
}

/* Two L-shaped beams (arms 0.1 wide reaching 0.2 beyond the corner, 2 long) crossing at right
 * angles, sunk 0.04 into each other edge on. */
static inline int make_beams(int bytes, int variant, body *a, body *b)
{
    if (body_ell(0.1, 0.2, 2, a) || body_ell(0.1, 0.2, 2, b))
        return 1;
    double Ra[9], Rb[9], T[9], Rbt[9];
    rot_axis(1, PI / 2, Ra); /* beam a along x */
    rot_axis(0, -PI / 2, Rb); /* beam b along y */
    rot_axis(2, 0.15 * variant, T);
    mat_mul(T, Rb, Rbt);
    const double ca[3] = {-1, 0, 0}, cb[3] = {0.05, -1, -0.3 + 0.04};
    body_place(a, Ra, ca, bytes);
    body_place(b, Rbt, cb, bytes);
    return 0;
}

/* The manifold of solids a and b (world vertices, identity poses, margin 0.005) at K into arr
 * (free it with ttd_scene_array_free), id[] the two bodies' ids; 0 on success. */
static inline int solid_pair_manifold(int bytes, const body *a, const body *b, size_t K, ttd_scene_array *arr,
                                      uint32_t id[2])
{
    ttd_mesh *ma = test_mesh_of(bytes, a->v, a->nv, a->t, a->nt), *mb = test_mesh_of(bytes, b->v, b->nv, b->t, b->nt);
    ttd_scene *s = NULL;
    int rc = ma == NULL || mb == NULL || (bytes == 8 ? ttd_scene_create_d(&s) : ttd_scene_create_f(&s)) != TTD_OK;
    static const double I[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
    static const float If[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
    for (int k = 0; k < 2 && !rc; ++k) {
        ttd_mesh *m = k ? mb : ma;
        rc = (bytes == 8 ? ttd_scene_add_d(s, m, I, &id[k]) : ttd_scene_add_f(s, m, If, &id[k])) != TTD_OK ||
             ttd_scene_set_solid(s, id[k], 1) != TTD_OK;
    }
    if (!rc)
        rc = (bytes == 8 ? ttd_scene_manifold_d(NULL, s, 0.005, K, arr) : ttd_scene_manifold_f(NULL, s, 0.005f, K, arr)) !=
             TTD_OK;
    ttd_scene_destroy(s);
    ttd_mesh_destroy(ma);
    ttd_mesh_destroy(mb);
    return rc;
}

#endif

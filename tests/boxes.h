/* SPDX-License-Identifier: MIT */
/* Boxes for the scene and mass tests: a box of sides a x b x c centred at the origin, faces wound
 * outward, each face cut n x n into squares of two triangles (n = 1: 12 triangles), vertices
 * shared by index; poses turned about z; the closest point of a triangle to a point (Ericson's
 * regions, written here, independent of the library); a polygon clipped by a convex one; a ttd mesh of such vertices in double or
 * float. Header-only, static functions. */
#ifndef TTD_TESTS_BOXES_H
#define TTD_TESTS_BOXES_H

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <ttd/ttd.h>

typedef struct test_box {
    double *v;   /* 3 nv */
    uint32_t *t; /* 3 nt */
    size_t nv, nt;
} test_box;

static inline uint32_t test_box_vertex(test_box *b, const double x[3])
{
    for (size_t k = 0; k < b->nv; ++k)
        if (memcmp(b->v + 3 * k, x, 3 * sizeof *x) == 0)
            return (uint32_t)k;
    memcpy(b->v + 3 * b->nv, x, 3 * sizeof *x);
    return (uint32_t)b->nv++;
}

/* The box; 0, or 1 out of memory. */
static inline int test_box_make(double a, double bb, double c, int n, test_box *b)
{
    const double h[3] = {a / 2, bb / 2, c / 2};
    const size_t nt = 12 * (size_t)n * (size_t)n;
    b->v = malloc(3 * 3 * nt * sizeof *b->v);
    b->t = malloc(3 * nt * sizeof *b->t);
    b->nv = b->nt = 0;
    if (b->v == NULL || b->t == NULL)
        return 1;
    for (int axis = 0; axis < 3; ++axis)
        for (int sgn = -1; sgn <= 1; sgn += 2) {
            /* u, v: the face's other axes, ordered so that u x v points along sgn * axis */
            const int u = (axis + 1) % 3, w = (axis + 2) % 3;
            const int U = sgn > 0 ? u : w, V = sgn > 0 ? w : u;
            for (int iu = 0; iu < n; ++iu)
                for (int iv = 0; iv < n; ++iv) {
                    uint32_t q[2][2];
                    for (int du = 0; du < 2; ++du)
                        for (int dv = 0; dv < 2; ++dv) {
                            double x[3];
                            x[axis] = sgn * h[axis];
                            x[U] = -h[U] + 2 * h[U] * ((double)(iu + du) / n); /* 1 exactly at the far edge */
                            x[V] = -h[V] + 2 * h[V] * ((double)(iv + dv) / n);
                            q[du][dv] = test_box_vertex(b, x);
                        }
                    const uint32_t tr[6] = {q[0][0], q[1][0], q[1][1], q[0][0], q[1][1], q[0][1]};
                    memcpy(b->t + 3 * b->nt, tr, sizeof tr);
                    b->nt += 2;
                }
        }
    return 0;
}

static inline void test_box_free(test_box *b)
{
    free(b->v);
    free(b->t);
    memset(b, 0, sizeof *b);
}

/* A pose turned by yaw about z, then moved to centre c. */
static inline void test_yaw_pose(double yaw, const double c[3], double pose[12])
{
    const double cs = cos(yaw), sn = sin(yaw);
    const double P[12] = {cs, -sn, 0, c[0], sn, cs, 0, c[1], 0, 0, 1, c[2]};
    memcpy(pose, P, sizeof P);
}

/* x moved by pose. */
static inline void test_pose_apply(const double pose[12], const double x[3], double out[3])
{
    for (int r = 0; r < 3; ++r)
        out[r] = pose[4 * r] * x[0] + pose[4 * r + 1] * x[1] + pose[4 * r + 2] * x[2] + pose[4 * r + 3];
}

static inline double test_dot(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* The point x of triangle (a, b, c) nearest p (Ericson, Real-Time Collision Detection 5.1.5). */
static inline void test_closest_on_triangle(const double p[3], const double a[3], const double b[3], const double c[3],
                                            double x[3])
{
    double ab[3], ac[3], ap[3], bp[3], cp[3];
    for (int r = 0; r < 3; ++r) {
        ab[r] = b[r] - a[r];
        ac[r] = c[r] - a[r];
        ap[r] = p[r] - a[r];
        bp[r] = p[r] - b[r];
        cp[r] = p[r] - c[r];
    }
    const double d1 = test_dot(ab, ap), d2 = test_dot(ac, ap), d3 = test_dot(ab, bp), d4 = test_dot(ac, bp);
    const double d5 = test_dot(ab, cp), d6 = test_dot(ac, cp);
    const double vc = d1 * d4 - d3 * d2, vb = d5 * d2 - d1 * d6, va = d3 * d6 - d5 * d4;
    if (d1 <= 0 && d2 <= 0)
        memcpy(x, a, 3 * sizeof *x);
    else if (d3 >= 0 && d4 <= d3)
        memcpy(x, b, 3 * sizeof *x);
    else if (d6 >= 0 && d5 <= d6)
        memcpy(x, c, 3 * sizeof *x);
    else if (vc <= 0 && d1 >= 0 && d3 <= 0)
        for (int r = 0; r < 3; ++r)
            x[r] = a[r] + d1 / (d1 - d3) * ab[r];
    else if (vb <= 0 && d2 >= 0 && d6 <= 0)
        for (int r = 0; r < 3; ++r)
            x[r] = a[r] + d2 / (d2 - d6) * ac[r];
    else if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
        for (int r = 0; r < 3; ++r)
            x[r] = b[r] + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c[r] - b[r]);
    else {
        const double den = 1 / (va + vb + vc), v = vb * den, w = vc * den;
        for (int r = 0; r < 3; ++r)
            x[r] = a[r] + ab[r] * v + ac[r] * w;
    }
}

/* The distance from p to triangle (a, b, c). */
static inline double test_point_triangle(const double p[3], const double a[3], const double b[3], const double c[3])
{
    double x[3];
    test_closest_on_triangle(p, a, b, c, x);
    const double d[3] = {p[0] - x[0], p[1] - x[1], p[2] - x[2]};
    return sqrt(test_dot(d, d));
}

/* Polygon a[0..na) (counter-clockwise, xy; any shape) clipped by convex polygon b[0..nb)
 * (counter-clockwise) by Sutherland-Hodgman into out; returns how many points (at most 128: the
 * clipping stops adding there, far beyond what the tests' polygons make). */
static inline size_t test_clip_polygon(const double (*a)[2], size_t na, const double (*b)[2], size_t nb,
                                       double (*out)[2])
{
    double cur[128][2], next[128][2];
    size_t nc = na < 128 ? na : 128;
    memcpy(cur, a, nc * sizeof *a);
    for (size_t e = 0; e < nb && nc > 0; ++e) {
        const double *p = b[e], *q = b[(e + 1) % nb];
        size_t nn = 0;
        for (size_t k = 0; k < nc && nn + 2 <= 128; ++k) {
            const double *x = cur[k], *y = cur[(k + 1) % nc];
            const double sx = (q[0] - p[0]) * (x[1] - p[1]) - (q[1] - p[1]) * (x[0] - p[0]);
            const double sy = (q[0] - p[0]) * (y[1] - p[1]) - (q[1] - p[1]) * (y[0] - p[0]);
            if (sx >= 0)
                memcpy(next[nn++], x, sizeof next[0]);
            if ((sx >= 0) != (sy >= 0)) {
                const double t = sx / (sx - sy);
                next[nn][0] = x[0] + t * (y[0] - x[0]);
                next[nn][1] = x[1] + t * (y[1] - x[1]);
                ++nn;
            }
        }
        memcpy(cur, next, nn * sizeof *next);
        nc = nn;
    }
    memcpy(out, cur, nc * sizeof *cur);
    return nc;
}

/* The distance from p to segment (a, b). */
static inline double test_point_segment(const double p[3], const double a[3], const double b[3])
{
    double ab[3], ap[3];
    for (int r = 0; r < 3; ++r) {
        ab[r] = b[r] - a[r];
        ap[r] = p[r] - a[r];
    }
    const double L = test_dot(ab, ab);
    double t = L > 0 ? test_dot(ab, ap) / L : 0;
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    const double d[3] = {ap[0] - t * ab[0], ap[1] - t * ab[1], ap[2] - t * ab[2]};
    return sqrt(test_dot(d, d));
}

/* A ttd mesh of v (3 nv doubles) and t: bytes 8 in double, 4 in float (v rounded to float); NULL
 * where it cannot be built. */
static inline ttd_mesh *test_mesh_of(int bytes, const double *v, size_t nv, const uint32_t *t, size_t nt)
{
    ttd_mesh *m = NULL;
    if (bytes == 8)
        return ttd_mesh_create_d(NULL, v, nv, t, nt, &m) == TTD_OK ? m : NULL;
    float *f = malloc(3 * nv * sizeof *f);
    if (f == NULL)
        return NULL;
    for (size_t k = 0; k < 3 * nv; ++k)
        f[k] = (float)v[k];
    if (ttd_mesh_create_f(NULL, f, nv, t, nt, &m) != TTD_OK)
        m = NULL;
    free(f);
    return m;
}

#endif /* TTD_TESTS_BOXES_H */

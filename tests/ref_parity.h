/* SPDX-License-Identifier: MIT */
/* An independent reference for a closed mesh's inside, written apart from the library: the parity
 * of a random ray's crossings, in long double (what ray-parity readers such as trimesh and Open3D
 * answer; orientation plays no part). For the point tests; header-only, static functions. */
#ifndef TTD_TESTS_REF_PARITY_H
#define TTD_TESTS_REF_PARITY_H

#include <math.h>
#include <stddef.h>

#include "meshes.h"
#include "pairs.h"

/* Whether the ray x + s dir (s > 0) crosses triangle (a, b, c), in long double (Moller-Trumbore):
 * 1, 0, or -1 when it passes within 1e-9 of an edge or vertex, or lies in its plane (ambiguous:
 * the caller picks another direction). */
static inline int ray_crosses(const double x[3], const long double dir[3], const double *a, const double *b,
                              const double *c)
{
    long double e1[3], e2[3], s[3], h[3], q[3];
    for (int k = 0; k < 3; ++k) {
        e1[k] = (long double)b[k] - a[k];
        e2[k] = (long double)c[k] - a[k];
        s[k] = (long double)x[k] - a[k];
    }
    h[0] = dir[1] * e2[2] - dir[2] * e2[1];
    h[1] = dir[2] * e2[0] - dir[0] * e2[2];
    h[2] = dir[0] * e2[1] - dir[1] * e2[0];
    const long double det = e1[0] * h[0] + e1[1] * h[1] + e1[2] * h[2];
    if (fabsl(det) < 1e-15L)
        return -1;
    const long double u = (s[0] * h[0] + s[1] * h[1] + s[2] * h[2]) / det;
    q[0] = s[1] * e1[2] - s[2] * e1[1];
    q[1] = s[2] * e1[0] - s[0] * e1[2];
    q[2] = s[0] * e1[1] - s[1] * e1[0];
    const long double v = (dir[0] * q[0] + dir[1] * q[1] + dir[2] * q[2]) / det;
    const long double t = (e2[0] * q[0] + e2[1] * q[1] + e2[2] * q[2]) / det;
    const long double tol = 1e-9L;
    if (u < -tol || v < -tol || u + v > 1 + tol || t < -tol)
        return 0;
    if (u < tol || v < tol || u + v > 1 - tol || t < tol)
        return -1;
    return 1;
}

/* Inside m by a ray's crossing parity from x (another random direction where one is ambiguous). */
static inline int parity_inside(const ttd_gen_mesh *m, const double x[3], ttd_gen_rng *r)
{
    for (;;) {
        long double dir[3];
        for (int k = 0; k < 3; ++k)
            dir[k] = (long double)ttd_gen_rng_uniform(r) - 0.5L;
        int crossings = 0, ok = 1;
        for (size_t t = 0; t < m->nt && ok; ++t) {
            const int c = ray_crosses(x, dir, m->verts + 3 * m->tris[3 * t], m->verts + 3 * m->tris[3 * t + 1],
                                      m->verts + 3 * m->tris[3 * t + 2]);
            if (c < 0)
                ok = 0;
            crossings += c > 0;
        }
        if (ok)
            return crossings & 1;
    }
}

#endif /* TTD_TESTS_REF_PARITY_H */

/* SPDX-License-Identifier: MIT */
/* Solids: whether a mesh is closed, and on which side of a closed mesh a point lies (mesh/mesh.h).
 *
 * The inside test is the generalized winding number (Jacobson, Kavan and Sorkine-Hornung 2013):
 * the signed solid angles of the triangles seen from the point, summed, over 4 pi. For a closed
 * mesh it is an integer (0 outside; +-1 inside a simple solid, the sign its orientation's) that
 * rounding moves by far less than 1/2 wherever the point is not within rounding of the surface,
 * and the queries only ask it about points whose distance to the surface they have found to be
 * positive. Unlike a ray's parity it has no bad directions (a ray through an edge or a vertex).
 * It costs one pass over the triangles; the queries ask it once or twice per pose, and only
 * when the meshes' bounding spheres nest. */
#include <float.h>
#include <math.h>
#include <stdlib.h>

#include "mesh/mesh.h"

static int edge_cmp(const void *x, const void *y)
{
    const uint64_t a = *(const uint64_t *)x, b = *(const uint64_t *)y;
    return (a > b) - (a < b);
}

/* Closed: the sorted directed edges hold no repeat, and each one's reverse. */
static int compute_closed(const struct ttd_mesh *m)
{
    const size_t ne = 3 * m->nt;
    uint64_t *e = malloc(ne * sizeof *e);
    if (e == NULL)
        return -1;
    for (size_t t = 0; t < m->nt; ++t)
        for (int k = 0; k < 3; ++k) {
            const uint64_t u = m->tris[3 * t + (size_t)k], v = m->tris[3 * t + (size_t)(k + 1) % 3];
            e[3 * t + (size_t)k] = u << 32 | v;
        }
    qsort(e, ne, sizeof *e, edge_cmp);
    int closed = 1;
    for (size_t i = 0; i < ne && closed; ++i) {
        const uint64_t rev = (e[i] & 0xffffffffu) << 32 | e[i] >> 32;
        if ((e[i] >> 32) == (e[i] & 0xffffffffu) || (i + 1 < ne && e[i + 1] == e[i]) ||
            !bsearch(&rev, e, ne, sizeof *e, edge_cmp))
            closed = 0;
    }
    free(e);
    return closed;
}

int ttd_mesh_closed(const struct ttd_mesh *mesh)
{
    /* a cache of a property of the immutable mesh, not a change to it */
    int *flag = (int *)(uintptr_t)&mesh->closed;
    int c = __atomic_load_n(flag, __ATOMIC_ACQUIRE);
    if (c == 0) {
        const int r = compute_closed(mesh);
        if (r < 0)
            return -1; /* out of memory: not kept, asked again next time */
        c = r ? 1 : 2;
        __atomic_store_n(flag, c, __ATOMIC_RELEASE);
    }
    return c == 1;
}

double ttd_mesh_solid_angle(const struct ttd_mesh *m, size_t t, const double x[3])
{
    double a[3][3], len[3];
    for (int k = 0; k < 3; ++k) {
        const size_t v = m->tris[3 * t + (size_t)k];
        for (int c = 0; c < 3; ++c) {
            const double p = m->bytes == 8 ? ((const double *)m->verts)[3 * v + (size_t)c]
                                           : (double)((const float *)m->verts)[3 * v + (size_t)c];
            a[k][c] = p - x[c];
        }
        len[k] = sqrt(a[k][0] * a[k][0] + a[k][1] * a[k][1] + a[k][2] * a[k][2]);
    }
    /* the angle does not depend on the scale: work at unit scale, so that the products
     * below neither overflow nor underflow anywhere in the coordinate range */
    const double sc = fmax(len[0], fmax(len[1], len[2]));
    if (!(sc > 0))
        return 0; /* x is the (point) triangle itself: no angle */
    for (int k = 0; k < 3; ++k) {
        len[k] /= sc;
        for (int c = 0; c < 3; ++c)
            a[k][c] /= sc;
    }
    /* Van Oosterom and Strackee: tan(omega / 2) = det / (|a||b||c| + (a.b)|c| + (a.c)|b| + (b.c)|a|) */
    const double det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
                       a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
                       a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
    const double ab = a[0][0] * a[1][0] + a[0][1] * a[1][1] + a[0][2] * a[1][2];
    const double ac = a[0][0] * a[2][0] + a[0][1] * a[2][1] + a[0][2] * a[2][2];
    const double bc = a[1][0] * a[2][0] + a[1][1] * a[2][1] + a[1][2] * a[2][2];
    const double den = len[0] * len[1] * len[2] + ab * len[2] + ac * len[1] + bc * len[0];
    return 2 * atan2(det, den);
}

double ttd_mesh_winding(const struct ttd_mesh *m, const double x[3])
{
    double sum = 0;
    for (size_t t = 0; t < m->nt; ++t)
        sum += ttd_mesh_solid_angle(m, t, x);
    return sum / (4 * 3.14159265358979323846);
}

/* ---- orientation (ttd_mesh_orientation) ----------------------------------------------------- */

/* Every undirected edge on exactly two triangles, none from a vertex to itself: a surface without
 * boundary, whichever way its triangles run. 1, 0, or -1 out of memory. */
static int two_sided(const struct ttd_mesh *m)
{
    const size_t ne = 3 * m->nt;
    uint64_t *e = malloc(ne * sizeof *e);
    if (e == NULL)
        return -1;
    int ok = 1;
    for (size_t t = 0; t < m->nt; ++t)
        for (int k = 0; k < 3; ++k) {
            const uint64_t u = m->tris[3 * t + (size_t)k], v = m->tris[3 * t + (size_t)(k + 1) % 3];
            ok &= u != v;
            e[3 * t + (size_t)k] = u < v ? u << 32 | v : v << 32 | u;
        }
    qsort(e, ne, sizeof *e, edge_cmp);
    for (size_t i = 0; i < ne && ok; i += 2)
        ok = i + 1 < ne && e[i + 1] == e[i] && (i + 2 >= ne || e[i + 2] != e[i]);
    free(e);
    return ok;
}

/* The sign of the volume the triangles enclose, by the divergence theorem: the sum of det(A, B, C)
 * over the triangles, relative to the mesh's origin and scaled by a power of two to unit size (no
 * product overflows), summed with its rounding compensated. +1 or -1 where the sum exceeds a bound
 * on its rounding (every term's, 16 eps of |A| |B| |C|, Hadamard's bound on the determinant, and
 * the products' underflow), 0 where it does not (a closed mesh that encloses no volume). */
static int volume_sign(const struct ttd_mesh *m)
{
    int ex;
    frexp(m->radius > 0 ? m->radius : 1, &ex);
    double sum = 0, comp = 0, bound = 0;
    for (size_t t = 0; t < m->nt; ++t) {
        double a[3][3], len[3];
        for (int k = 0; k < 3; ++k) {
            const size_t v = m->tris[3 * t + (size_t)k];
            for (int c = 0; c < 3; ++c) {
                const double p = m->bytes == 8 ? ((const double *)m->verts)[3 * v + (size_t)c]
                                               : (double)((const float *)m->verts)[3 * v + (size_t)c];
                a[k][c] = ldexp(p - m->origin[c], -ex); /* the difference within 1 ulp; then exact */
            }
            len[k] = sqrt(a[k][0] * a[k][0] + a[k][1] * a[k][1] + a[k][2] * a[k][2]);
        }
        const double det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
                           a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
                           a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
        /* the vertices' own rounding (the difference from the origin, 1 ulp each) is in the bound */
        bound += 16 * DBL_EPSILON * len[0] * len[1] * len[2] + 16 * DBL_MIN;
        const double s2 = sum + det, bb = s2 - sum; /* two-sum */
        comp += (sum - (s2 - bb)) + (det - bb);
        sum = s2;
    }
    const double v = sum + comp;
    bound = bound * (1 + 1e-10) + 2 * DBL_EPSILON * fabs(v);
    return v > bound ? 1 : v < -bound ? -1 : 0;
}

ttd_orientation ttd_mesh_orientation_of(const struct ttd_mesh *m)
{
    const int closed = ttd_mesh_closed(m);
    if (closed < 0)
        return (ttd_orientation)-1;
    if (!closed) {
        const int two = two_sided(m);
        return two < 0 ? (ttd_orientation)-1 : two ? TTD_ORIENTATION_INCONSISTENT : TTD_ORIENTATION_OPEN;
    }
    const int v = volume_sign(m);
    return v > 0 ? TTD_ORIENTATION_OUTWARD : v < 0 ? TTD_ORIENTATION_INWARD : TTD_ORIENTATION_FLAT;
}

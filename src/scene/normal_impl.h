/* SPDX-License-Identifier: MIT */
/* Contact normals that belong to the bodies (docs/scenes.md, section 5), precision-generic:
 * scene/query_d.c and query_f.c include it before scene/query_impl.h.
 *
 * A contact is a triangle pair with its exact closest points p (on body i) and q (on body j).
 * Where each point lies on its triangle, with the mesh's edge information (mesh/edges.h), says
 * which feature of its body it lies on, and that feature's normal cone: the outward directions
 * in which the body has nothing near the point.
 *   - a face: the inside of a triangle, an edge between coplanar triangles, a vertex inside a
 *     flat part, or anything that is not a convex piece of a closed surface (a concave edge, a
 *     boundary, a saddle): the cone is the triangle's own normal;
 *   - a real convex edge: the directions perpendicular to it between its two faces' normals;
 *   - a corner: the directions that make an obtuse angle with every edge leaving it;
 *   - nothing (a triangle without area): every direction.
 * The normal, from i towards j (rule_normal):
 *   1. a face on one side only: that face's normal;
 *   2. faces on both sides: where they are opposite within TTD_FLAT_ANGLE, their mean (a face
 *      resting on a face); otherwise the one along which the two triangles are farther apart (a
 *      separating-axis test on the pair, as a simulator's face contact would pick);
 *   3. otherwise (edges, corners, nothing): the direction nearest the preferred one u within the
 *      cones of both sides (i's cone and the opposite of j's), where they meet; where they do not
 *      meet, case 2 on the triangles' own normals.
 * u is the direction from p to q where they differ, else from i's world box's centre to j's,
 * else +z. Each case gives the negated normal when i and j swap; the roles are also put in a
 * fixed order (by the triangles' world coordinates) before the rule runs, so that even its ties
 * are symmetric. Every vector is formed at unit scale (scaled by a power of two first), so that
 * tiny and huge scenes get the normals of the same scene at size 1.
 *
 * The points of solids inside each other (a vertex of one body inside the other, its closest
 * point on the other's surface; docs/scenes.md, section 5b) fit the same rule: the inside
 * point's side is nothing, the surface point's side its feature (contact_side), u the direction
 * from the inside point to the surface one, out of the other body. */

#ifndef TTD_SCENE_NORMAL_IMPL_H
#define TTD_SCENE_NORMAL_IMPL_H

#include "core/vec3.h"
#include "scene/body_impl.h"

/* A barycentric weight this close to 0 is 0: the world coordinates' rounding (relative to the
 * triangle, for coordinates up to about 1e6 times its size in double, 1e3 in float). */
#ifdef TTD_PRECISION_DOUBLE
#define FEATURE_TOL 0x1p-30
#else
#define FEATURE_TOL 0x1p-16
#endif
/* A direction is in a cone when it is within CONE_TOL of each side (the rounding of the
 * candidate directions, which are formed in double from the same constraint vectors). Where the
 * two sides' cones meet only in a ray (a corner resting on a corner, an edge on an edge), a tilt
 * far below anything a face would notice (1e-6 rad after one step of a simulated stack) parts
 * them; cones that miss each other by less than the flat angle (CONE_LOOSE, sin TTD_FLAT_ANGLE:
 * what the edge information already calls flat) then count as meeting, before the rule falls
 * back to the triangles' own faces. */
#define CONE_TOL 0x1p-40
#define CONE_LOOSE 1e-3

enum { SIDE_FREE, SIDE_FACE, SIDE_CONE };

/* One side of a contact: its feature's kind and normal cone. */
typedef struct body_feature {
    int kind;
    int on[3];                   /* the triangle's vertices the point's feature spans */
    uint32_t id, tri;            /* the body and its triangle */
    double v[3][3];              /* the triangle in the world (double) */
    int has_normal;              /* the triangle has a normal (n) */
    double area;                 /* log2 of the area of its flat piece (mesh/edges.h) */
    double n[3];                 /* the triangle's unit normal (outward by its winding) */
    int ncon, neq;               /* SIDE_CONE: v . g[k] <= 0, and = 0 for the first neq */
    double g[TTD_CORNER_MAX][3]; /* unit */
} body_feature;

/* x 2^e: ldexp's bits (one rounding, where the result is subnormal) by a product with 2^e
 * where that is a normal number (ldexp is a call into libm), ldexp beyond. */
static double scale2(double x, int e)
{
    if (e < -1022 || e > 1023)
        return ldexp(x, e);
    const uint64_t bits = (uint64_t)(e + 1023) << 52;
    double f;
    memcpy(&f, &bits, sizeof f);
    return x * f;
}

/* fmax(a, b)'s value inline (libm's fmax is a call on the baseline ISA): the other operand where
 * one is NaN, else the larger. Called here on non-negative operands only (|x| and maxima of
 * them, from +0), so no zeros of two signs to order. */
static inline double max_nn(double a, double b)
{
    return a != a ? b : b > a ? b : a;
}

/* frexp(x, &e)'s e, from x's bits where x is a normal number (frexp is a call into libm): x =
 * 1.f 2^(b - 1023) = 0.1f 2^(b - 1022), b its biased exponent; frexp itself beyond. */
static inline int frexp_e(double x)
{
    uint64_t u;
    memcpy(&u, &x, sizeof u);
    const int b = (int)(u >> 52 & 0x7ff);
    if (b == 0 || b == 0x7ff) {
        int e;
        frexp(x, &e);
        return e;
    }
    return b - 1022;
}

/* a / |a| into out, formed at unit scale; 0 when a is 0. */
static int unit3(const double a[3], double out[3])
{
    const double d = a[0] * a[0] + a[1] * a[1] + a[2] * a[2];
    if (d > 0x1p-900 && d < 0x1p900) { /* no scaling needed: the same bits as with it (powers of two) */
        const double len = sqrt(d);
        for (int r = 0; r < 3; ++r)
            out[r] = a[r] / len;
        return 1;
    }
    const double m = max_nn(fabs(a[0]), max_nn(fabs(a[1]), fabs(a[2])));
    if (!(m > 0) || !isfinite(m))
        return 0;
    const int e = frexp_e(m);
    double b[3];
    for (int r = 0; r < 3; ++r)
        b[r] = scale2(a[r], -e);
    const double len = sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
    for (int r = 0; r < 3; ++r)
        out[r] = b[r] / len;
    return 1;
}

static double dot3d(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* The scene's name for core/vec3.h's ttd_cross3 (the manifold's files call it too). */
static void cross3d(const double a[3], const double b[3], double out[3])
{
    ttd_cross3(a, b, out);
}

/* Vertex v of body id's mesh in the world, as the kernel sees it. */
static void world_vertex(const struct ttd_scene *s, uint32_t id, uint32_t v, double out[3])
{
    const struct ttd_mesh *m = s->body[id].mesh;
    const real *src = (const real *)m->verts + 3 * (size_t)v, *pose = body_pose(s, id);
    for (int r = 0; r < 3; ++r)
        out[r] = (double)(((pose[4 * r] * src[0] + pose[4 * r + 1] * src[1]) + pose[4 * r + 2] * src[2]) + pose[4 * r + 3]);
}

/* Triangle tri of body id in the world, as the kernel sees it (9 reals). */
static void world_triangle(const struct ttd_scene *s, uint32_t id, uint32_t tri, real x[9])
{
    const struct ttd_mesh *m = s->body[id].mesh;
    const real *v = (const real *)m->verts, *pose = body_pose(s, id);
    for (int k = 0; k < 3; ++k) {
        const real *src = v + 3 * (size_t)m->tris[3 * (size_t)tri + (size_t)k];
        for (int r = 0; r < 3; ++r)
            x[3 * k + r] = ((pose[4 * r] * src[0] + pose[4 * r + 1] * src[1]) + pose[4 * r + 2] * src[2]) + pose[4 * r + 3];
    }
}

/* The cross product of triangle v's edges from v[0], formed at unit scale (the edges scaled by a
 * power of two), into cr, and the edges' squared lengths at that scale into e11, e22; the
 * triangle's extent (its largest coordinate difference) into *extent. 0 when it has no extent. */
static int unit_cross(const double v[3][3], double cr[3], double *e11, double *e22, double *extent)
{
    double e1[3], e2[3], m = 0;
    for (int r = 0; r < 3; ++r) {
        e1[r] = v[1][r] - v[0][r];
        e2[r] = v[2][r] - v[0][r];
        m = max_nn(m, max_nn(fabs(e1[r]), fabs(e2[r])));
    }
    *extent = m;
    if (!(m > 0) || !isfinite(m))
        return 0;
    const int ex = frexp_e(m);
    for (int r = 0; r < 3; ++r) {
        e1[r] = scale2(e1[r], -ex);
        e2[r] = scale2(e2[r], -ex);
    }
    cross3d(e1, e2, cr);
    *e11 = dot3d(e1, e1);
    *e22 = dot3d(e2, e2);
    return 1;
}

/* Barycentric weights of x in triangle v (double), formed at unit scale; 0 when v has no area. */
static int weights_in(const double v[3][3], const double x[3], double w[3])
{
    double e1[3], e2[3], d[3], m = 0;
    for (int r = 0; r < 3; ++r) {
        e1[r] = v[1][r] - v[0][r];
        e2[r] = v[2][r] - v[0][r];
        d[r] = x[r] - v[0][r];
        m = max_nn(m, max_nn(fabs(e1[r]), fabs(e2[r])));
    }
    if (!(m > 0) || !isfinite(m))
        return 0;
    const int ex = frexp_e(m);
    for (int r = 0; r < 3; ++r) {
        e1[r] = scale2(e1[r], -ex);
        e2[r] = scale2(e2[r], -ex);
        d[r] = scale2(d[r], -ex);
    }
    double cr[3], c1[3], c2[3];
    cross3d(e1, e2, cr);
    const double a2 = dot3d(cr, cr);
    if (!(a2 > 0))
        return 0;
    cross3d(d, e2, c1);
    cross3d(e1, d, c2);
    w[1] = dot3d(c1, cr) / a2;
    w[2] = dot3d(c2, cr) / a2;
    w[0] = 1 - w[1] - w[2];
    return 1;
}

/* Adds the constraint v . (to - from) <= 0 (or = 0) to f. */
static void add_constraint(body_feature *f, const double from[3], const double to[3])
{
    const double d[3] = {to[0] - from[0], to[1] - from[1], to[2] - from[2]};
    if (f->ncon < TTD_CORNER_MAX && unit3(d, f->g[f->ncon]))
        f->ncon++;
}

/* Triangle tri of body id as a side: its world vertices (x, or from the mesh when NULL) and its
 * unit normal where it has one; no feature yet (SIDE_FREE). */
static void side_triangle(const struct ttd_scene *s, uint32_t id, uint32_t tri, const real *x, body_feature *f)
{
    f->kind = SIDE_FREE;
    f->ncon = f->neq = 0;
    f->has_normal = 0;
    f->id = id;
    f->tri = tri;
    const struct ttd_mesh *mesh = s->body[id].mesh;
    const ttd_mesh_edges *E = ttd_mesh_edges_made(mesh);
    f->area = E->piece_area[E->piece[tri]];
    for (int k = 0; k < 3; ++k) {
        if (x != NULL)
            for (int r = 0; r < 3; ++r)
                f->v[k][r] = (double)x[3 * k + r];
        else
            world_vertex(s, id, mesh->tris[3 * (size_t)tri + (size_t)k], f->v[k]);
    }
    double cr[3], e11, e22, m;
    if (!unit_cross((const double (*)[3])f->v, cr, &e11, &e22, &m))
        return;
    const double area = sqrt(dot3d(cr, cr));
    if (!(area > 64 * DBL_EPSILON * sqrt(e11 * e22)))
        return; /* no area: no normal, no feature */
    f->has_normal = 1;
    const int out = E->inward && s->body[id].solid; /* a solid of an inward mesh: outward is the other way */
    for (int r = 0; r < 3; ++r)
        f->n[r] = (out ? -cr[r] : cr[r]) / area;
}

/* f's feature from the vertices of its triangle that it spans (on): a face, or the cone of a
 * real convex edge or of a corner. f holds its triangle (side_triangle, with a normal). */
static void side_feature(const struct ttd_scene *s, body_feature *f, const int on[3])
{
    const struct ttd_mesh *mesh = s->body[f->id].mesh;
    ttd_mesh_edges view;
    const ttd_mesh_edges *E = ttd_mesh_edges_seen(ttd_mesh_edges_made(mesh), s->body[f->id].solid, &view);
    const uint32_t *tri = mesh->tris + 3 * (size_t)f->tri;
    for (int k = 0; k < 3; ++k)
        f->on[k] = on[k];
    f->kind = SIDE_FACE;
    f->ncon = f->neq = 0;
    const int n_on = on[0] + on[1] + on[2];
    if (n_on == 2) {
        const int k = !on[2] ? 0 : !on[0] ? 1 : 2; /* the edge from vertex k to k + 1 */
        if (ttd_edge_class(E, f->tri, k) != TTD_EDGE_CONVEX)
            return;
        const uint32_t u = E->across[3 * (size_t)f->tri + (size_t)k];
        const uint32_t a = E->weld[tri[k]], b = E->weld[tri[(k + 1) % 3]];
        uint32_t far = mesh->tris[3 * (size_t)u];
        for (int t = 0; t < 3; ++t) {
            const uint32_t vt = mesh->tris[3 * (size_t)u + (size_t)t];
            if (E->weld[vt] != a && E->weld[vt] != b)
                far = vt;
        }
        double xf[3];
        world_vertex(s, f->id, far, xf);
        f->kind = SIDE_CONE;
        add_constraint(f, f->v[k], f->v[(k + 1) % 3]); /* perpendicular to the edge */
        f->neq = f->ncon;
        add_constraint(f, f->v[k], f->v[(k + 2) % 3]); /* away from its two faces */
        add_constraint(f, f->v[k], xf);
    } else if (n_on == 1) {
        const int k = on[0] ? 0 : on[1] ? 1 : 2;
        if (ttd_vertex_class(E, f->tri, k) != TTD_VERTEX_CORNER)
            return;
        const uint32_t w = E->weld[tri[k]];
        f->kind = SIDE_CONE;
        for (uint32_t r = E->ring_start[w]; r < E->ring_start[w + 1]; ++r) {
            const uint32_t u = E->ring[r];
            for (int t = 0; t < 3; ++t)
                if (E->weld[mesh->tris[3 * (size_t)u + (size_t)t]] == w) { /* every edge leaving it, once */
                    double xn[3];
                    world_vertex(s, f->id, mesh->tris[3 * (size_t)u + (size_t)((t + 1) % 3)], xn);
                    add_constraint(f, f->v[k], xn);
                }
        }
    }
}

/* The point of triangle v nearest x (double), as weights w (Ericson's regions, at the scale
 * 2^-ex about v[0]); its squared distance at that scale, or -1 when v has no extent. */
static double closest_in_triangle(const double v[3][3], const double x[3], int ex, double w[3])
{
    double ab[3], ac[3], ap[3], bp[3], cp[3];
    for (int r = 0; r < 3; ++r) {
        ab[r] = scale2(v[1][r] - v[0][r], -ex);
        ac[r] = scale2(v[2][r] - v[0][r], -ex);
        ap[r] = scale2(x[r] - v[0][r], -ex);
        bp[r] = ap[r] - ab[r];
        cp[r] = ap[r] - ac[r];
    }
    const double d1 = dot3d(ab, ap), d2 = dot3d(ac, ap), d3 = dot3d(ab, bp), d4 = dot3d(ac, bp);
    const double d5 = dot3d(ab, cp), d6 = dot3d(ac, cp);
    const double vc = d1 * d4 - d3 * d2, vb = d5 * d2 - d1 * d6, va = d3 * d6 - d5 * d4;
    if (d1 <= 0 && d2 <= 0) {
        w[0] = 1, w[1] = 0, w[2] = 0;
    } else if (d3 >= 0 && d4 <= d3) {
        w[0] = 0, w[1] = 1, w[2] = 0;
    } else if (vc <= 0 && d1 >= 0 && d3 <= 0) {
        const double t = d1 / (d1 - d3);
        w[0] = 1 - t, w[1] = t, w[2] = 0;
    } else if (d6 >= 0 && d5 <= d6) {
        w[0] = 0, w[1] = 0, w[2] = 1;
    } else if (vb <= 0 && d2 >= 0 && d6 <= 0) {
        const double t = d2 / (d2 - d6);
        w[0] = 1 - t, w[1] = 0, w[2] = t;
    } else if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) {
        const double t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        w[0] = 0, w[1] = 1 - t, w[2] = t;
    } else {
        const double den = va + vb + vc;
        if (!(den > 0) || !isfinite(den))
            return -1;
        w[1] = vb / den;
        w[2] = vc / den;
        w[0] = 1 - w[1] - w[2];
    }
    double q[3];
    for (int r = 0; r < 3; ++r)
        q[r] = w[1] * ab[r] + w[2] * ac[r] - ap[r];
    return dot3d(q, q);
}

/* Where a face side f stands against the other point x (d > 0). FACE_APPLIES: the foot of x on
 * f's plane lies inside the flat part of the body around the contact (f's triangle and the
 * triangles of its flat piece around its feature's vertices), not on its rim. FACE_RIM: otherwise, and *rim is the body's feature at the point of that flat part
 * nearest the foot (a real convex edge or a corner: a cone; a concave or open edge or a saddle:
 * a face): the contact's closest point stopped at an edge the body does not have, or the other
 * point lies beyond the face, and the face does not speak for it. A point inside f's triangle
 * is its own foot. */
enum { FACE_APPLIES, FACE_RIM };
static int face_rim(const struct ttd_scene *s, const body_feature *f, const double x[3], body_feature *rim)
{
    if (f->on[0] && f->on[1] && f->on[2])
        return FACE_APPLIES;
    double foot[3], rel[3];
    for (int r = 0; r < 3; ++r)
        rel[r] = x[r] - f->v[0][r];
    const double h = dot3d(rel, f->n); /* x's height above the plane */
    for (int r = 0; r < 3; ++r)
        foot[r] = x[r] - h * f->n[r];
    const struct ttd_mesh *mesh = s->body[f->id].mesh;
    const ttd_mesh_edges *E = ttd_mesh_edges_made(mesh);
    double m = 0; /* one scale for every candidate: f's triangle's */
    for (int k = 1; k < 3; ++k)
        for (int r = 0; r < 3; ++r)
            m = max_nn(m, fabs(f->v[k][r] - f->v[0][r]));
    int ex = 0;
    if (m > 0 && isfinite(m))
        ex = frexp_e(m);
    double best = HUGE_VAL, best_w[3] = {1, 0, 0};
    uint32_t best_t = f->tri;
    for (int k = -1; k < 3; ++k) { /* f's triangle, then the rings of its feature's vertices */
        if (k >= 0 && !f->on[k])
            continue;
        const uint32_t w = k >= 0 ? E->weld[mesh->tris[3 * (size_t)f->tri + (size_t)k]] : 0;
        const uint32_t r0 = k >= 0 ? E->ring_start[w] : 0, r1 = k >= 0 ? E->ring_start[w + 1] : 1;
        for (uint32_t r = r0; r < r1; ++r) {
            const uint32_t t = k >= 0 ? E->ring[r] : f->tri;
            if (k >= 0 && t == f->tri)
                continue;
            double v[3][3], wt[3];
            if (E->piece[t] != E->piece[f->tri])
                continue; /* not part of the flat piece */
            for (int c = 0; c < 3; ++c)
                world_vertex(s, f->id, mesh->tris[3 * (size_t)t + (size_t)c], v[c]);
            const double d2 = closest_in_triangle((const double (*)[3])v, foot, ex, wt);
            if (d2 >= 0 && d2 < best) {
                best = d2;
                best_t = t;
                memcpy(best_w, wt, sizeof wt);
            }
        }
    }
    /* the nearest point inside a triangle, on a flat edge or at a flat vertex (the flat part
     * goes on there): the face applies; on a rim: the rim's feature */
    int on[3];
    for (int c = 0; c < 3; ++c)
        on[c] = !(best_w[c] <= FEATURE_TOL);
    const int n_on = on[0] + on[1] + on[2];
    if (n_on == 3 || (n_on == 2 && ttd_edge_class(E, best_t, !on[2] ? 0 : !on[0] ? 1 : 2) == TTD_EDGE_FLAT) ||
        (n_on == 1 && ttd_vertex_class(E, best_t, on[0] ? 0 : on[1] ? 1 : 2) == TTD_VERTEX_FLAT))
        return FACE_APPLIES;
    side_triangle(s, f->id, best_t, NULL, rim);
    if (rim->has_normal)
        side_feature(s, rim, on);
    else
        *rim = *f;
    return FACE_RIM;
}

/* The side of a contact on triangle tri of body id (x: the triangle in the world) at point pt:
 * its feature (snapped: a barycentric weight within FEATURE_TOL of 0 is 0, so a point on an
 * edge up to the world coordinates' rounding is on the edge) and its normal cone. */
static void contact_side(const struct ttd_scene *s, uint32_t id, uint32_t tri, const real x[9], const real pt[3],
                         body_feature *f)
{
    side_triangle(s, id, tri, x, f);
    double p[3], w[3];
    for (int r = 0; r < 3; ++r)
        p[r] = (double)pt[r];
    if (!f->has_normal || !weights_in((const double (*)[3])f->v, p, w))
        return;
    int on[3];
    for (int k = 0; k < 3; ++k)
        on[k] = !(w[k] <= FEATURE_TOL);
    side_feature(s, f, on);
}

/* Whether unit v lies in the cone of constraints g[0..n) (the first neq equalities), to tol. */
static int in_cone(const double (*g)[3], int n, int neq, const double v[3], double tol)
{
    for (int k = 0; k < n; ++k) {
        const double x = dot3d(v, g[k]);
        if (k < neq ? !(fabs(x) <= tol) : !(x <= tol))
            return 0;
    }
    return 1;
}

/* beyond_best: whether candidate c of cone_nearest, made unit by unit3 (v), surely has dot3d(u, v)
 * <= best (unit u; best >= 1/2), so that it cannot be kept, from p = dot3d(u, c) and d = dot3d(c,
 * c).
 * Only where unit3 takes its unscaled path: d, unit3's own sum, in (2^-900, 2^900), so S = |c| >
 * 2^-450 and underflow's absolute errors (2^-1075 an operation) are far below e S. With e = 2^-53
 * and P = u . c exactly: d = S^2 (1 + 3.01 e at most), len = sqrt(d) rounded = S (1 + l), |l| <=
 * 2.51 e; v_r = c_r / len (1 + d_r), |d_r| <= e; with the dot's rounding (3 e) and |u| <= 1 +
 * 3.6 e, dot3d(u, v) <= (P + 4.1 e S) / len. Where the computed p (within 3.1 e S of P) is <= 0,
 * dot3d(u, v) <= 7.3 e < best. Else, with q = best - 2^-40 (rounded: within 1.01 e), p p <=
 * (q q) d as computed gives p <= q S (1 + 3.02 e), so P + 4.1 e S <= S (best - 2^-40 + 11.3 e)
 * and dot3d(u, v) <= (best - 2^-40 + 11.3 e) / (1 - 2.51 e) < best. */
/* The screen on (1); 0 only in a test's build (tests/CMakeLists.txt, ttd_manifold_no_screen), whose
 * answers must be the same bits. */
#ifndef NORMAL_CONE_SCREEN
#define NORMAL_CONE_SCREEN 1
#endif
/* beyond_best (where d is in range, p <= 0 or p p <= (q q) d) for candidate c (p, d) in bit 0 and
 * for -c (-p, d) in bit 1 at once: the two share d, its range test and p p (the same
 * bits: rounding is symmetric), so each is asked once a pair of cross candidates. */
static unsigned beyond_best_pair(double p, double d, double best)
{
    if (!(d > 0x1p-900 && d < 0x1p900))
        return 0;
    const double q = best - 0x1p-40;
    const int far = p * p <= (q * q) * d;
    return (unsigned)(p <= 0 || far) | (unsigned)(-p <= 0 || far) << 1;
}

/* The unit direction nearest u in the polyhedral cone of g[0..n): u itself, or on a side (u
 * projected onto a constraint's plane), or on an edge (where two planes meet): whichever of
 * these lies in the cone and is nearest u (the first of equals, in this order). 0 when the
 * cone holds no direction. */
static int cone_nearest(const double (*g)[3], int n, int neq, const double u[3], double tol, double out[3])
{
    double best = -HUGE_VAL;
    int found = 0;
    for (int k = -1; k < n; ++k)
        for (int l = k; l < n; ++l) {
            double c[2][3];
            int nc = 1;
            if (k < 0 && l < 0) {
                memcpy(c[0], u, sizeof c[0]);
            } else if (k < 0 || l == k) {
                if (k < 0)
                    continue;
                const double x = dot3d(u, g[k]);
                for (int r = 0; r < 3; ++r)
                    c[0][r] = u[r] - x * g[k][r];
            } else {
                cross3d(g[k], g[l], c[0]);
                for (int r = 0; r < 3; ++r)
                    c[1][r] = -c[0][r];
                nc = 2;
            }
            /* c[0]'s p and d for beyond_best; c[1] = -c[0]'s are -p and d, exactly */
            unsigned beyond = 0;
            if (NORMAL_CONE_SCREEN && best >= 0.5)
                beyond = beyond_best_pair(dot3d(u, c[0]), dot3d(c[0], c[0]), best);
            for (int t = 0; t < nc; ++t) {
                double v[3];
                if (beyond >> t & 1)
                    continue;
                if (!unit3(c[t], v))
                    continue;
                /* kept when in the cone and nearer u than the best: the nearness first, as it is
                 * cheaper and most candidates fail it once u or a near one is in (in_cone reads
                 * and writes nothing else, so the same candidate is kept) */
                const double x = dot3d(u, v);
                if (x > best && in_cone(g, n, neq, v, tol)) {
                    best = x;
                    memcpy(out, v, sizeof v);
                    found = 1;
                }
            }
        }
    return found;
}

/* Two faces, a on body i and b on body j (outward unit normals; log2 of their flat pieces'
 * areas ai, aj), of triangles ti and tj (9 coordinates each, about a common origin at a common
 * scale): opposite within TTD_FLAT_ANGLE, their mean (a face resting on a face); otherwise the
 * face of the larger flat piece (a small facet of a curved body against a floor: the floor's,
 * whatever the floor's triangles), and between pieces of one area the normal along which the
 * two triangles are farther apart (min over tj of n . y minus max over ti of n . x); ties to
 * the mean, and the mean of equal normals to u. */
static void face_face(const double a[3], const double b[3], double ai, double aj, const double ti[9],
                      const double tj[9], const double u[3], double n[3])
{
    const double mean[3] = {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
    if (!(dot3d(a, b) <= -cos(TTD_FLAT_ANGLE))) {
        if (ai != aj) {
            for (int r = 0; r < 3; ++r)
                n[r] = ai > aj ? a[r] : -b[r];
            return;
        }
        double sep[2];
        for (int side = 0; side < 2; ++side) {
            const double nn[3] = {side ? -b[0] : a[0], side ? -b[1] : a[1], side ? -b[2] : a[2]};
            double lo = HUGE_VAL, hi = -HUGE_VAL;
            for (int k = 0; k < 3; ++k) {
                lo = fmin(lo, dot3d(nn, tj + 3 * k));
                hi = fmax(hi, dot3d(nn, ti + 3 * k));
            }
            sep[side] = lo - hi;
        }
        if (sep[0] != sep[1]) {
            for (int r = 0; r < 3; ++r)
                n[r] = sep[0] > sep[1] ? a[r] : -b[r];
            return;
        }
    }
    if (!unit3(mean, n))
        memcpy(n, u, 3 * sizeof *n);
}

/* rule_normal's case 2 on the triangles' own normals, or u. */
static void own_faces(const body_feature *fi, const body_feature *fj, const double ti[9], const double tj[9],
                      const double u[3], double n[3])
{
    if (fi->has_normal && fj->has_normal) {
        face_face(fi->n, fj->n, fi->area, fj->area, ti, tj, u, n);
    } else if (fi->has_normal || fj->has_normal) {
        for (int r = 0; r < 3; ++r)
            n[r] = fi->has_normal ? fi->n[r] : -fj->n[r];
    } else {
        memcpy(n, u, 3 * sizeof *n);
    }
}

/* The normal from body i towards body j of a contact with sides fi and fj, preferred direction
 * u (unit), triangles ti and tj for the face-face test (as face_face takes them). ai, aj: whether
 * each side's face applies (face_applies; 1 where the side is not a face). */
static void rule_normal(const body_feature *fi, const body_feature *fj, int ai, int aj, const double u[3],
                        const double ti[9], const double tj[9], double n[3])
{
    const int face_i = fi->kind == SIDE_FACE && ai, face_j = fj->kind == SIDE_FACE && aj;
    if (face_i && face_j) {
        face_face(fi->n, fj->n, fi->area, fj->area, ti, tj, u, n);
    } else if (face_i || face_j) {
        for (int r = 0; r < 3; ++r)
            n[r] = face_i ? fi->n[r] : -fj->n[r];
    } else if (fi->kind == SIDE_CONE || fj->kind == SIDE_CONE) {
        /* i's cone and the opposite of j's, equalities first, with the faces that do not apply
         * as their normals where that meets the other cone; without them where it does not;
         * then the same with cones that miss each other by less than the flat angle */
        for (int attempt = 0; attempt < 4; ++attempt) {
            const int with_faces = !(attempt & 1);
            const double tol = attempt < 2 ? CONE_TOL : CONE_LOOSE;
            double g[2 * TTD_CORNER_MAX + 4][3];
            int ng = 0, neq = 0;
            for (int pass = 0; pass < 2; ++pass) {
                for (int side = 0; side < 2; ++side) {
                    const body_feature *f = side ? fj : fi;
                    const double sg = side ? -1 : 1;
                    if (f->kind == SIDE_CONE) {
                        for (int k = pass ? f->neq : 0; k < (pass ? f->ncon : f->neq); ++k, ++ng)
                            for (int r = 0; r < 3; ++r)
                                g[ng][r] = sg * f->g[k][r];
                    } else if (f->kind == SIDE_FACE && with_faces) {
                        /* the ray of n: perpendicular to two directions across it (equalities),
                         * on n's side (an inequality) */
                        double a[3] = {0, 0, 0}, b[3];
                        const int m = fabs(f->n[0]) <= fabs(f->n[1]) && fabs(f->n[0]) <= fabs(f->n[2]) ? 0
                                      : fabs(f->n[1]) <= fabs(f->n[2])                                  ? 1
                                                                                                        : 2;
                        a[m] = 1;
                        cross3d(f->n, a, b);
                        unit3(b, b);
                        cross3d(f->n, b, a);
                        if (pass == 0) {
                            memcpy(g[ng++], a, sizeof a);
                            memcpy(g[ng++], b, sizeof b);
                        } else {
                            for (int r = 0; r < 3; ++r)
                                g[ng][r] = -sg * f->n[r];
                            ++ng;
                        }
                    }
                }
                if (pass == 0)
                    neq = ng;
            }
            if (cone_nearest((const double (*)[3])g, ng, neq, u, tol, n))
                return;
        }
        own_faces(fi, fj, ti, tj, u, n);
    } else {
        own_faces(fi, fj, ti, tj, u, n); /* faces that do not apply, or nothing: still the faces */
    }
}

/* Whether triangle x comes after y in the order of their coordinates. */
static int triangle_after(const real x[9], const real y[9])
{
    for (int k = 0; k < 9; ++k)
        if (x[k] != y[k])
            return x[k] > y[k];
    return 0;
}

/* The normal of contact c, from body i towards body j (docs/scenes.md, section 5). inside: -1,
 * or which of c's points is a vertex of one solid inside the other (0: p, body i's; 1: q, body
 * j's; c's distance negative): that side has no feature, and the normal comes out of the other
 * body at its surface point (5b). */
static void contact_normal(const struct ttd_scene *s, const ttd_scene_contact *c, int inside, double n[3])
{
    real tri[2][9];
    world_triangle(s, c->i, c->tri_i, tri[0]);
    world_triangle(s, c->j, c->tri_j, tri[1]);
    /* u: from p to q (inside: from q to p, out of the other body), else between the world boxes'
     * centres, else +z */
    double u[3], d[3];
    for (int r = 0; r < 3; ++r)
        d[r] = c->distance < 0 ? (double)c->p[r] - (double)c->q[r] : (double)c->q[r] - (double)c->p[r];
    if (!(c->distance != 0 && unit3(d, u))) {
        const double *bi = s->box + 6 * (size_t)c->i, *bj = s->box + 6 * (size_t)c->j;
        for (int r = 0; r < 3; ++r)
            d[r] = (0.5 * bj[r] + 0.5 * bj[3 + r]) - (0.5 * bi[r] + 0.5 * bi[3 + r]);
        if (!unit3(d, u)) {
            u[0] = u[1] = 0;
            u[2] = 1;
        }
    }
    /* the roles in a fixed order: a the side whose triangle comes first */
    const int swap = triangle_after(tri[0], tri[1]);
    const uint32_t id[2] = {swap ? c->j : c->i, swap ? c->i : c->j};
    const uint32_t t[2] = {swap ? c->tri_j : c->tri_i, swap ? c->tri_i : c->tri_j};
    const real *x[2] = {tri[swap], tri[!swap]}, *pt[2] = {swap ? c->q : c->p, swap ? c->p : c->q};
    body_feature f[2];
    for (int k = 0; k < 2; ++k) {
        contact_side(s, id[k], t[k], x[k], pt[k], &f[k]);
        if (inside >= 0 && k == (swap ? !inside : inside)) { /* a point inside the other solid: nothing */
            f[k].kind = SIDE_FREE;
            f[k].has_normal = 0;
            f[k].ncon = f[k].neq = 0;
        }
    }
    /* the triangles about a's point, at one scale, for the face-face test */
    double tt[2][9], m = 0;
    for (int k = 0; k < 2; ++k)
        for (int l = 0; l < 9; ++l) {
            tt[k][l] = (double)x[k][l] - (double)pt[0][l % 3];
            m = max_nn(m, fabs(tt[k][l]));
        }
    if (m > 0 && isfinite(m)) {
        const int ex = frexp_e(m);
        for (int k = 0; k < 2; ++k)
            for (int l = 0; l < 9; ++l)
                tt[k][l] = scale2(tt[k][l], -ex);
    }
    double ua[3];
    for (int r = 0; r < 3; ++r)
        ua[r] = swap ? -u[r] : u[r];
    /* a face side whose face does not speak for the contact becomes its rim's feature */
    int applies[2] = {1, 1};
    if (c->distance > 0)
        for (int k = 0; k < 2; ++k)
            if (f[k].kind == SIDE_FACE) {
                double other[3];
                body_feature rim;
                for (int r = 0; r < 3; ++r)
                    other[r] = (double)pt[!k][r];
                if (face_rim(s, &f[k], other, &rim) == FACE_RIM) {
                    f[k] = rim;
                    applies[k] = 0;
                }
            }
    rule_normal(&f[0], &f[1], applies[0], applies[1], ua, tt[0], tt[1], n);
    if (swap)
        for (int r = 0; r < 3; ++r)
            n[r] = -n[r];
}

#endif /* TTD_SCENE_NORMAL_IMPL_H */

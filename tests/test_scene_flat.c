/* SPDX-License-Identifier: MIT */
/* Flat contact in a manifold (docs/scenes.md, section 5, step 0): where two planar flat pieces lie
 * face on face above distance 0, their triangle pairs' closest points are not points of the
 * manifold; the corners of the pieces' overlap stand for them. Checked against references
 * written here, independent of the library's edge information:
 *   - prisms (a box in four triangulations: two triangles a face, a centre vertex, faces cut
 *     4 x 4 with the inner points moved in the face's plane, slivers fanned from a corner; an
 *     L-shaped prism, whose face is not convex) resting, turned and tilted, on a box or on
 *     another prism: every corner of the overlap polygon (the upper piece's outline projected on
 *     the lower face, clipped by it: Sutherland-Hodgman, written here) is a point of K = 0;
 *     every point's distance is |point_i - point_j| and no more than the distance from either of
 *     its points to the other body (a closest-point function written here); the deepest point
 *     of K = 0 and of K = 4 is the bodies' distance (brute force over every vertex-triangle and
 *     edge-edge pair); no point lies strictly inside both faces (the old rule gave the triangle
 *     pairs' closest points there);
 *   - a floor whose top is one flat piece but not planar (a bump, every edge within the flat
 *     angle): its contacts are points, and the deepest point, inside the piece, is kept. */
#define _POSIX_C_SOURCE 200809L
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "boxes.h"
#include "test_macros.h"
#include <ttd/ttd.h>

#define MARGIN 0.01
#define PI 3.14159265358979323846

/* ---- meshes: prisms over a face triangulation ----------------------------------------------- */

typedef struct pmesh {
    double *v;   /* 3 nv */
    uint32_t *t; /* 3 nt */
    size_t nv, nt;
    /* the bottom face's outline (counter-clockwise seen from above, local xy) */
    double outline[64][2];
    size_t nout;
} pmesh;

static void pm_vertex(pmesh *m, double x, double y, double z)
{
    m->v = realloc(m->v, 3 * (m->nv + 1) * sizeof *m->v);
    m->v[3 * m->nv] = x;
    m->v[3 * m->nv + 1] = y;
    m->v[3 * m->nv + 2] = z;
    m->nv++;
}

static void pm_tri(pmesh *m, uint32_t a, uint32_t b, uint32_t c)
{
    m->t = realloc(m->t, 3 * (m->nt + 1) * sizeof *m->t);
    m->t[3 * m->nt] = a;
    m->t[3 * m->nt + 1] = b;
    m->t[3 * m->nt + 2] = c;
    m->nt++;
}

/* A prism of height h over the face of nf points f (2D) and triangles ft (counter-clockwise,
 * nft), whose boundary is the chain ch[0..nch) (counter-clockwise); the top face's height at
 * each point is h + bump * (1 - |f|^2) (bump 0: a prism). */
static void prism(pmesh *m, const double (*f)[2], size_t nf, const uint32_t *ft, size_t nft, const uint32_t *ch,
                  size_t nch, double h, double bump)
{
    memset(m, 0, sizeof *m);
    for (size_t k = 0; k < nf; ++k)
        pm_vertex(m, f[k][0], f[k][1], 0);
    for (size_t k = 0; k < nf; ++k) {
        int rim = 0; /* the rim stays at h */
        for (size_t c = 0; c < nch; ++c)
            rim |= ch[c] == k;
        pm_vertex(m, f[k][0], f[k][1], rim ? h : h + bump * (1 - f[k][0] * f[k][0] - f[k][1] * f[k][1]));
    }
    for (size_t k = 0; k < nft; ++k) {
        pm_tri(m, ft[3 * k], ft[3 * k + 2], ft[3 * k + 1]); /* the bottom, facing down */
        pm_tri(m, (uint32_t)nf + ft[3 * k], (uint32_t)nf + ft[3 * k + 1], (uint32_t)nf + ft[3 * k + 2]);
    }
    for (size_t c = 0; c < nch; ++c) {
        const uint32_t a = ch[c], b = ch[(c + 1) % nch];
        pm_tri(m, a, b, (uint32_t)nf + b);
        pm_tri(m, a, (uint32_t)nf + b, (uint32_t)nf + a);
    }
    m->nout = nch < 64 ? nch : 64;
    for (size_t c = 0; c < m->nout; ++c) {
        m->outline[c][0] = f[ch[c]][0];
        m->outline[c][1] = f[ch[c]][1];
    }
}

enum { BOX_PLAIN, BOX_CENTRE, BOX_CUT, BOX_SLIVER, BOX_KINDS };
static const char *box_name[BOX_KINDS] = {"plain", "centre vertex", "cut 4 x 4", "slivers"};

/* A box W x D x H (local: [-W/2, W/2] x [-D/2, D/2] x [0, H]) in triangulation kind; cut: the
 * inner points moved in the face by up to 0.15 of a cell (seed). bump: the top's bump. */
static void box_mesh(pmesh *m, int kind, double W, double D, double H, unsigned seed, double bump)
{
    double f[64][2];
    uint32_t ft[3 * 64], ch[64];
    size_t nf = 0, nft = 0, nch = 0;
    const double x0 = -W / 2, y0 = -D / 2;
    if (kind == BOX_CUT) {
        const int n = 4;
        srand(seed);
        for (int j = 0; j <= n; ++j)
            for (int i = 0; i <= n; ++i) {
                double jx = 0, jy = 0;
                if (i > 0 && i < n && j > 0 && j < n && bump == 0) {
                    jx = 0.15 * W / n * (2.0 * rand() / RAND_MAX - 1);
                    jy = 0.15 * D / n * (2.0 * rand() / RAND_MAX - 1);
                }
                f[nf][0] = x0 + W * i / n + jx;
                f[nf][1] = y0 + D * j / n + jy;
                ++nf;
            }
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                const uint32_t a = (uint32_t)(j * (n + 1) + i), b = a + 1, c = a + (uint32_t)n + 2, d = a + (uint32_t)n + 1;
                if ((i + j) % 2) {
                    ft[3 * nft] = a, ft[3 * nft + 1] = b, ft[3 * nft + 2] = c, ++nft;
                    ft[3 * nft] = a, ft[3 * nft + 1] = c, ft[3 * nft + 2] = d, ++nft;
                } else {
                    ft[3 * nft] = a, ft[3 * nft + 1] = b, ft[3 * nft + 2] = d, ++nft;
                    ft[3 * nft] = b, ft[3 * nft + 1] = c, ft[3 * nft + 2] = d, ++nft;
                }
            }
        for (int i = 0; i < n; ++i)
            ch[nch++] = (uint32_t)i;
        for (int j = 0; j < n; ++j)
            ch[nch++] = (uint32_t)(j * (n + 1) + n);
        for (int i = n; i > 0; --i)
            ch[nch++] = (uint32_t)(n * (n + 1) + i);
        for (int j = n; j > 0; --j)
            ch[nch++] = (uint32_t)(j * (n + 1));
    } else {
        /* the outline: each side cut into s pieces (slivers: 6) */
        const int s = kind == BOX_SLIVER ? 6 : 1;
        const double c[4][2] = {{x0, y0}, {-x0, y0}, {-x0, -y0}, {x0, -y0}};
        for (int e = 0; e < 4; ++e)
            for (int k = 0; k < s; ++k) {
                f[nf][0] = c[e][0] + (c[(e + 1) % 4][0] - c[e][0]) * k / s;
                f[nf][1] = c[e][1] + (c[(e + 1) % 4][1] - c[e][1]) * k / s;
                ch[nch++] = (uint32_t)nf++;
            }
        if (kind == BOX_CENTRE) {
            f[nf][0] = f[nf][1] = 0;
            for (size_t k = 0; k < nch; ++k)
                ft[3 * nft] = (uint32_t)nf, ft[3 * nft + 1] = ch[k], ft[3 * nft + 2] = ch[(k + 1) % nch], ++nft;
            ++nf;
        } else { /* a fan from the first corner */
            for (size_t k = 1; k + 1 < nch; ++k)
                ft[3 * nft] = ch[0], ft[3 * nft + 1] = ch[k], ft[3 * nft + 2] = ch[k + 1], ++nft;
        }
    }
    prism(m, (const double (*)[2])f, nf, ft, nft, ch, nch, H, bump);
}

/* An L prism of height H: the face [0, 2a] x [0, a] and [0, a] x [0, 2a], moved by (-a, -a);
 * fanned from its inner corner (the face is not convex; every point of it sees that corner),
 * each side cut into s pieces. */
static void l_mesh(pmesh *m, double a, double H, int s)
{
    const double c[6][2] = {{0, 0}, {2 * a, 0}, {2 * a, a}, {a, a}, {a, 2 * a}, {0, 2 * a}};
    double f[64][2];
    uint32_t ft[3 * 64], ch[64];
    size_t nf = 0, nft = 0, nch = 0, inner = 0;
    for (int e = 0; e < 6; ++e)
        for (int k = 0; k < s; ++k) {
            if (e == 3 && k == 0)
                inner = nf;
            f[nf][0] = c[e][0] + (c[(e + 1) % 6][0] - c[e][0]) * k / s - a;
            f[nf][1] = c[e][1] + (c[(e + 1) % 6][1] - c[e][1]) * k / s - a;
            ch[nch++] = (uint32_t)nf++;
        }
    for (size_t k = 0; k < nch; ++k) {
        const size_t k1 = (k + 1) % nch;
        if (k == inner || k1 == inner)
            continue;
        ft[3 * nft] = (uint32_t)inner, ft[3 * nft + 1] = ch[k], ft[3 * nft + 2] = ch[k1], ++nft;
    }
    prism(m, (const double (*)[2])f, nf, ft, nft, ch, nch, H, 0);
}

/* ---- references ----------------------------------------------------------------------------- */

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* The distance between segments p1q1 and p2q2 (Ericson 5.1.9). */
static double segment_distance(const double p1[3], const double q1[3], const double p2[3], const double q2[3])
{
    double d1[3], d2[3], r[3];
    for (int k = 0; k < 3; ++k) {
        d1[k] = q1[k] - p1[k];
        d2[k] = q2[k] - p2[k];
        r[k] = p1[k] - p2[k];
    }
    const double a = dot3(d1, d1), e = dot3(d2, d2), f = dot3(d2, r);
    double s, t;
    if (a <= 0 && e <= 0) {
        s = t = 0;
    } else if (a <= 0) {
        s = 0;
        t = fmin(fmax(f / e, 0), 1);
    } else {
        const double c = dot3(d1, r);
        if (e <= 0) {
            t = 0;
            s = fmin(fmax(-c / a, 0), 1);
        } else {
            const double b = dot3(d1, d2), den = a * e - b * b;
            s = den != 0 ? fmin(fmax((b * f - c * e) / den, 0), 1) : 0;
            t = (b * s + f) / e;
            if (t < 0) {
                t = 0;
                s = fmin(fmax(-c / a, 0), 1);
            } else if (t > 1) {
                t = 1;
                s = fmin(fmax((b - c) / a, 0), 1);
            }
        }
    }
    double x[3];
    for (int k = 0; k < 3; ++k)
        x[k] = (p1[k] + d1[k] * s) - (p2[k] + d2[k] * t);
    return sqrt(dot3(x, x));
}

/* World triangles of a mesh under a pose (3 x 4, row-major). */
static double *world(const pmesh *m, const double pose[12])
{
    double *w = malloc(9 * m->nt * sizeof *w);
    for (size_t t = 0; t < m->nt; ++t)
        for (int k = 0; k < 3; ++k) {
            const double *x = m->v + 3 * (size_t)m->t[3 * t + (size_t)k];
            for (int r = 0; r < 3; ++r)
                w[9 * t + 3 * (size_t)k + (size_t)r] =
                    ((pose[4 * r] * x[0] + pose[4 * r + 1] * x[1]) + pose[4 * r + 2] * x[2]) + pose[4 * r + 3];
        }
    return w;
}

/* The distance from p to the triangles w[0..nt). */
static double point_body(const double p[3], const double *w, size_t nt)
{
    double best = INFINITY;
    for (size_t t = 0; t < nt; ++t) {
        double c[3];
        test_closest_on_triangle(p, w + 9 * t, w + 9 * t + 3, w + 9 * t + 6, c);
        const double d[3] = {p[0] - c[0], p[1] - c[1], p[2] - c[2]};
        best = fmin(best, sqrt(dot3(d, d)));
    }
    return best;
}

/* The distance between two bodies that do not cross: over every triangle pair, the least of its
 * six vertex-triangle and nine edge-edge distances. */
static double body_body(const double *a, size_t na, const double *b, size_t nb)
{
    double best = INFINITY;
    for (size_t s = 0; s < na; ++s)
        for (size_t t = 0; t < nb; ++t) {
            const double *x = a + 9 * s, *y = b + 9 * t;
            for (int k = 0; k < 3; ++k) {
                double c[3], d[3];
                test_closest_on_triangle(x + 3 * k, y, y + 3, y + 6, c);
                for (int r = 0; r < 3; ++r)
                    d[r] = x[3 * k + r] - c[r];
                best = fmin(best, sqrt(dot3(d, d)));
                test_closest_on_triangle(y + 3 * k, x, x + 3, x + 6, c);
                for (int r = 0; r < 3; ++r)
                    d[r] = y[3 * k + r] - c[r];
                best = fmin(best, sqrt(dot3(d, d)));
                for (int l = 0; l < 3; ++l)
                    best = fmin(best, segment_distance(x + 3 * k, x + 3 * ((k + 1) % 3), y + 3 * l, y + 3 * ((l + 1) % 3)));
            }
        }
    return best;
}

/* Whether local point x (2D) lies inside polygon o[0..n) (counter-clockwise) farther than tol
 * from its boundary (crossing parity, then the distance to each side). */
static int strictly_inside(const double (*o)[2], size_t n, const double x[2], double tol)
{
    int in = 0;
    for (size_t e = 0; e < n; ++e) {
        const double *p = o[e], *q = o[(e + 1) % n];
        if ((p[1] > x[1]) != (q[1] > x[1]) && x[0] < p[0] + (x[1] - p[1]) / (q[1] - p[1]) * (q[0] - p[0]))
            in = !in;
        const double d[2] = {q[0] - p[0], q[1] - p[1]}, w[2] = {x[0] - p[0], x[1] - p[1]};
        const double L = d[0] * d[0] + d[1] * d[1];
        const double t = fmin(fmax((d[0] * w[0] + d[1] * w[1]) / L, 0), 1);
        if (hypot(w[0] - t * d[0], w[1] - t * d[1]) <= tol)
            return 0;
    }
    return in;
}

/* A mesh's radius: from the centre of its vertices' box to the farthest vertex. */
static double radius(const pmesh *m)
{
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY}, r = 0;
    for (size_t v = 0; v < m->nv; ++v)
        for (int k = 0; k < 3; ++k) {
            lo[k] = fmin(lo[k], m->v[3 * v + (size_t)k]);
            hi[k] = fmax(hi[k], m->v[3 * v + (size_t)k]);
        }
    for (size_t v = 0; v < m->nv; ++v) {
        double d[3];
        for (int k = 0; k < 3; ++k)
            d[k] = m->v[3 * v + (size_t)k] - (0.5 * lo[k] + 0.5 * hi[k]);
        r = fmax(r, sqrt(dot3(d, d)));
    }
    return r;
}

/* Rotation: yaw about z after a tilt by angle t about the horizontal axis at angle b; then the
 * translation c. */
static void make_pose(double yaw, double t, double b, const double c[3], double pose[12])
{
    const double ax[3] = {cos(b), sin(b), 0};
    double T[9], Z[9] = {cos(yaw), -sin(yaw), 0, sin(yaw), cos(yaw), 0, 0, 0, 1};
    const double ct = cos(t), st = sin(t);
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            const double K[9] = {0, -ax[2], ax[1], ax[2], 0, -ax[0], -ax[1], ax[0], 0};
            T[3 * i + j] = (i == j ? ct : 0) + st * K[3 * i + j] + (1 - ct) * ax[i] * ax[j];
        }
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j)
            pose[4 * i + j] = T[3 * i] * Z[j] + T[3 * i + 1] * Z[3 + j] + T[3 * i + 2] * Z[6 + j];
        pose[4 * i + 3] = c[i];
    }
}

typedef struct wpoint {
    double pi[3], pj[3], x[3], d;
    uint32_t i, j, ti, tj;
} wpoint;

static size_t manifold(ttd_scene *s, size_t K, wpoint **out)
{
    ttd_scene_array a = {0};
    *out = NULL;
    if (ttd_scene_manifold_d(NULL, s, MARGIN, K, &a) != TTD_OK)
        return SIZE_MAX;
    *out = malloc((a.count + 1) * sizeof **out);
    for (size_t q = 0; q < a.count; ++q) {
        const ttd_scene_point_d *p = (const ttd_scene_point_d *)a.data + q;
        wpoint w = {{0}, {0}, {0}, p->distance, p->i, p->j, p->tri_i, p->tri_j};
        memcpy(w.pi, p->point_i, sizeof w.pi);
        memcpy(w.pj, p->point_j, sizeof w.pj);
        memcpy(w.x, p->point, sizeof w.x);
        (*out)[q] = w;
    }
    const size_t n = a.count;
    ttd_scene_array_free(&a);
    return n;
}

/* One case: the upper mesh resting on the lower one's top face (local z = H0 of the lower) at gap
 * g above its lowest bottom point, turned, tilted, shifted; the checks of the file's comment. */
static int rest_case(const char *what, const pmesh *lo, double H0, const double lo_pose[12], const pmesh *up, double yaw,
                     double tilt, double tilt_axis, double sx, double sy, double g, size_t *corners, size_t *flat_points)
{
    double pose[12];
    const double c0[3] = {0, 0, 0};
    make_pose(yaw, tilt, tilt_axis, c0, pose);
    double zmin = INFINITY;
    for (size_t k = 0; k < up->nout; ++k)
        zmin = fmin(zmin, pose[8] * up->outline[k][0] + pose[9] * up->outline[k][1]);
    pose[3] = lo_pose[3] + sx;
    pose[7] = lo_pose[7] + sy;
    pose[11] = lo_pose[11] + H0 + g - zmin;
    /* the overlap: the upper outline projected (world xy), clipped by the lower's (convex) */
    double a[64][2], b[64][2], region[128][2];
    for (size_t k = 0; k < up->nout; ++k)
        for (int r = 0; r < 2; ++r)
            a[k][r] = pose[4 * r] * up->outline[k][0] + pose[4 * r + 1] * up->outline[k][1] + pose[4 * r + 3];
    for (size_t k = 0; k < lo->nout; ++k)
        for (int r = 0; r < 2; ++r)
            b[k][r] = lo_pose[4 * r] * lo->outline[k][0] + lo_pose[4 * r + 1] * lo->outline[k][1] + lo_pose[4 * r + 3];
    size_t nr = test_clip_polygon((const double (*)[2])a, up->nout, (const double (*)[2])b, lo->nout, region);
    /* its corners: the clipping also leaves points where the outline runs straight on (a cut
     * rim's points, the clip polygon's own points on a side), which are not corners */
    for (int again = 1; again && nr > 3;) {
        again = 0;
        for (size_t k = 0; k < nr && nr > 3; ++k) {
            const double *p = region[(k + nr - 1) % nr], *x = region[k], *q = region[(k + 1) % nr];
            const double cr = (x[0] - p[0]) * (q[1] - x[1]) - (x[1] - p[1]) * (q[0] - x[0]);
            if (fabs(cr) <= 1e-12 * hypot(x[0] - p[0], x[1] - p[1]) * hypot(q[0] - x[0], q[1] - x[1]) + 1e-24) {
                memmove(region[k], region[k + 1], (nr - k - 1) * sizeof region[0]);
                --nr;
                again = 1;
            }
        }
    }
    ENSURE_MSG(nr >= 3, "%s: no overlap", what);
    ttd_mesh *m[2];
    ENSURE(ttd_mesh_create_d(NULL, lo->v, lo->nv, lo->t, lo->nt, &m[0]) == TTD_OK);
    ENSURE(ttd_mesh_create_d(NULL, up->v, up->nv, up->t, up->nt, &m[1]) == TTD_OK);
    ttd_scene *s;
    uint32_t id;
    ENSURE(ttd_scene_create_d(&s) == TTD_OK);
    ENSURE(ttd_scene_add_d(s, m[0], lo_pose, &id) == TTD_OK && ttd_scene_add_d(s, m[1], pose, &id) == TTD_OK);
    double *w0 = world(lo, lo_pose), *w1 = world(up, pose);
    const double dist = body_body(w0, lo->nt, w1, up->nt);
    wpoint *p0, *p4;
    const size_t n0 = manifold(s, 0, &p0), n4 = manifold(s, 4, &p4);
    ENSURE(n0 != SIZE_MAX && n4 != SIZE_MAX && n0 >= 1 && n4 >= 1);
    /* the deepest point is the bodies' distance, at K = 0 and K = 4 */
    double d0 = INFINITY, d4 = INFINITY;
    for (size_t q = 0; q < n0; ++q)
        d0 = fmin(d0, p0[q].d);
    for (size_t q = 0; q < n4; ++q)
        d4 = fmin(d4, p4[q].d);
    ENSURE_MSG(fabs(d0 - dist) <= 1e-12 && fabs(d4 - dist) <= 1e-12, "%s: deepest %.17g (K = 4: %.17g), bodies %.17g",
               what, d0, d4, dist);
    /* every corner of the overlap among K = 0's points (a crossing's points lie off the
     * projections' crossing by up to the gap times the tilt over the sine of the angle between
     * the edges: the cases keep that angle at 15 degrees or more) */
    const double merge = 1e-3 * fmin(radius(lo), radius(up)); /* step 2's merge tolerance */
    const double tol = 1e-9 + 16 * MARGIN * fabs(tilt) + merge;
    for (size_t c = 0; c < nr; ++c) {
        double best = INFINITY;
        for (size_t q = 0; q < n0; ++q)
            best = fmin(best, fmin(hypot(p0[q].pi[0] - region[c][0], p0[q].pi[1] - region[c][1]),
                                   hypot(p0[q].pj[0] - region[c][0], p0[q].pj[1] - region[c][1])));
        ENSURE_MSG(best <= tol, "%s: the overlap's corner (%.17g, %.17g) is %.3g from every K = 0 point", what,
                   region[c][0], region[c][1], best);
        /* a vertex's corner: a point at the vertex, at its distance to the other body */
        for (int side = 0; side < 2; ++side) {
            const pmesh *pm = side ? up : lo;
            const double *P = side ? pose : lo_pose;
            for (size_t k = 0; k < pm->nout; ++k) {
                const double v[3] = {pm->outline[k][0], pm->outline[k][1], side ? 0 : H0};
                double x[3];
                for (int r = 0; r < 3; ++r)
                    x[r] = ((P[4 * r] * v[0] + P[4 * r + 1] * v[1]) + P[4 * r + 2] * v[2]) + P[4 * r + 3];
                if (hypot(x[0] - region[c][0], x[1] - region[c][1]) > 1e-9)
                    continue;
                const double dv = point_body(x, side ? w0 : w1, side ? lo->nt : up->nt);
                /* its point, or one within the merge tolerance as deep or deeper (step 2) */
                double got = INFINITY;
                for (size_t q = 0; q < n0; ++q) {
                    const double *y = side ? p0[q].pj : p0[q].pi;
                    const double at = hypot(hypot(y[0] - x[0], y[1] - x[1]), y[2] - x[2]);
                    if (at <= 1e-12 || (at <= merge && p0[q].d <= dv + 1e-12))
                        got = fmin(got, at <= 1e-12 ? p0[q].d : dv);
                }
                ENSURE_MSG(fabs(got - dv) <= 1e-12, "%s: the vertex (%.17g, %.17g, %.17g) at %.17g from the other body: "
                           "its point at %.17g", what, x[0], x[1], x[2], dv, got);
                ++*flat_points;
            }
        }
    }
    *corners += nr;
    /* each point: its distance, no nearer body point; none strictly inside both faces */
    for (size_t q = 0; q < n0; ++q) {
        const wpoint *x = &p0[q];
        const double e[3] = {x->pi[0] - x->pj[0], x->pi[1] - x->pj[1], x->pi[2] - x->pj[2]};
        ENSURE_MSG(fabs(sqrt(dot3(e, e)) - x->d) <= 1e-12, "%s: point %zu: |pi - pj| %.17g, d %.17g", what, q,
                   sqrt(dot3(e, e)), x->d);
        /* local coordinates of each point on its body's face */
        double li[3], lj[3];
        for (int r = 0; r < 3; ++r) {
            li[r] = 0;
            lj[r] = 0;
            for (int k = 0; k < 3; ++k) {
                li[r] += lo_pose[4 * k + r] * (x->pi[k] - lo_pose[4 * k + 3]);
                lj[r] += pose[4 * k + r] * (x->pj[k] - pose[4 * k + 3]);
            }
        }
        const int in_i = fabs(li[2] - H0) <= 1e-9 && strictly_inside((const double (*)[2])lo->outline, lo->nout, li, 1e-9);
        const int in_j = fabs(lj[2]) <= 1e-9 && strictly_inside((const double (*)[2])up->outline, up->nout, lj, 1e-9);
        ENSURE_MSG(!(in_i && in_j), "%s: K = 0 point %zu (%.17g, %.17g, %.17g) d %.17g lies inside both faces", what, q,
                   x->x[0], x->x[1], x->x[2], x->d);
        /* both points on the bodies: neither nearer the other body than d */
        const double di = point_body(x->pi, w1, up->nt), dj = point_body(x->pj, w0, lo->nt);
        ENSURE_MSG(di <= x->d + 1e-12 && dj <= x->d + 1e-12, "%s: point %zu at %.17g: its points %.17g, %.17g from the "
                   "other body", what, q, x->d, di, dj);
    }
    free(p0);
    free(p4);
    free(w0);
    free(w1);
    ttd_scene_destroy(s);
    ttd_mesh_destroy(m[0]);
    ttd_mesh_destroy(m[1]);
    return 0;
}

static void pm_free(pmesh *m)
{
    free(m->v);
    free(m->t);
}

static double urand(void)
{
    return (double)rand() / RAND_MAX;
}

/* Boxes on boxes, every pair of triangulations, turned (15 to 75 degrees from the lower's sides,
 * or not at all) and tilted by up to 0.004 rad (the whole face within the margin), shifted so
 * that the upper overhangs or not; and L prisms on boxes. */
static int flat_overlap_corners(void)
{
    size_t cases = 0, corners = 0, flat_points = 0;
    pmesh lower[BOX_KINDS], upper[BOX_KINDS], ell[2];
    for (int k = 0; k < BOX_KINDS; ++k) {
        box_mesh(&lower[k], k, 3, 2, 0.5, 7u + (unsigned)k, 0);
        box_mesh(&upper[k], k, 1.2, 0.7, 0.4, 19u + (unsigned)k, 0);
    }
    l_mesh(&ell[0], 0.4, 0.3, 1);
    l_mesh(&ell[1], 0.4, 0.3, 5);
    srand(12345);
    for (int kl = 0; kl < BOX_KINDS; ++kl)
        for (int ku = 0; ku < BOX_KINDS + 2; ++ku)
            for (int rep = 0; rep < 12; ++rep) {
                const pmesh *up = ku < BOX_KINDS ? &upper[ku] : &ell[ku - BOX_KINDS];
                const double lo_yaw = 2 * PI * urand();
                double lo_pose[12];
                const double c[3] = {4 * urand() - 2, 4 * urand() - 2, urand()};
                make_pose(lo_yaw, 0, 0, c, lo_pose);
                const double yaw = lo_yaw + (rep % 3 == 0 ? 0 : (15 + 60 * urand()) * PI / 180);
                const double tilt = rep % 4 == 0 ? 0 : 0.004 * urand(), axis = 2 * PI * urand();
                const double g = 1e-4 + 3e-3 * urand();
                /* shifted within the lower face, or hanging over its side */
                /* the shift in the lower's frame: its centre over the lower face */
                const double reach = rep % 2 ? 1.2 : 0.6, ang = 2 * PI * urand();
                const double lx = reach * cos(ang), ly = 0.6 * reach * sin(ang);
                const double sx = cos(lo_yaw) * lx - sin(lo_yaw) * ly, sy = sin(lo_yaw) * lx + cos(lo_yaw) * ly;
                char what[200];
                snprintf(what, sizeof what, "%s on %s, case %d (yaw %.3g, tilt %.3g, gap %.3g, shift %.3g, %.3g)",
                         ku < BOX_KINDS ? box_name[ku] : ku == BOX_KINDS ? "L" : "L cut", box_name[kl], rep,
                         yaw - lo_yaw, tilt, g, sx, sy);
                if (rest_case(what, &lower[kl], 0.5, lo_pose, up, yaw, tilt, axis, sx, sy, g, &corners, &flat_points))
                    return 1;
                ++cases;
            }
    for (int k = 0; k < BOX_KINDS; ++k) {
        pm_free(&lower[k]);
        pm_free(&upper[k]);
    }
    pm_free(&ell[0]);
    pm_free(&ell[1]);
    printf("  %zu prisms resting on boxes: all %zu corners of the overlaps at K = 0, the deepest point the bodies' "
           "distance, no point inside both faces, the %zu vertices among the corners at their distance to the other "
           "body\n", cases, corners, flat_points);
    return 0;
}

/* A floor whose top is one flat piece that is not planar (a bump of 2e-4 over a 2 x 2 top cut
 * 4 x 4: every edge within the flat angle) under a box: the deepest point lies at the bump's
 * top, inside the piece, where no corner is; it must be kept (the contacts of a piece that is
 * not planar are points). */
static int bent_piece_keeps_contacts(void)
{
    pmesh floor_m, box_m;
    box_mesh(&floor_m, BOX_CUT, 2, 2, 0.5, 3u, 2e-4);
    box_mesh(&box_m, BOX_PLAIN, 0.8, 0.8, 0.3, 5u, 0);
    /* the bump's top is the floor's highest point: the box rests 1e-3 above it */
    const double lo_pose[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
    const double pose[12] = {1, 0, 0, 0.05, 0, 1, 0, 0.03, 0, 0, 1, 0.5 + 2e-4 + 1e-3};
    ttd_mesh *m[2];
    ENSURE(ttd_mesh_create_d(NULL, floor_m.v, floor_m.nv, floor_m.t, floor_m.nt, &m[0]) == TTD_OK);
    ENSURE(ttd_mesh_create_d(NULL, box_m.v, box_m.nv, box_m.t, box_m.nt, &m[1]) == TTD_OK);
    ttd_scene *s;
    uint32_t id;
    ENSURE(ttd_scene_create_d(&s) == TTD_OK);
    ENSURE(ttd_scene_add_d(s, m[0], lo_pose, &id) == TTD_OK && ttd_scene_add_d(s, m[1], pose, &id) == TTD_OK);
    double *w0 = world(&floor_m, lo_pose), *w1 = world(&box_m, pose);
    const double dist = body_body(w0, floor_m.nt, w1, box_m.nt);
    ENSURE_NEAR(dist, 1e-3, 1e-12);
    for (size_t K = 0; K <= 4; K += 4) {
        wpoint *p;
        const size_t n = manifold(s, K, &p);
        ENSURE(n != SIZE_MAX && n >= 1);
        double d = INFINITY;
        for (size_t q = 0; q < n; ++q)
            d = fmin(d, p[q].d);
        ENSURE_MSG(fabs(d - dist) <= 1e-12, "K = %zu: deepest %.17g, bodies %.17g", K, d, dist);
        free(p);
    }
    free(w0);
    free(w1);
    ttd_scene_destroy(s);
    ttd_mesh_destroy(m[0]);
    ttd_mesh_destroy(m[1]);
    pm_free(&floor_m);
    pm_free(&box_m);
    printf("  a box over a bump of a floor's flat piece: the deepest point, inside the piece, kept\n");
    return 0;
}

int main(int argc, char **argv)
{
    TEST_MAIN_BEGIN(argc, argv);
    RUN_TEST(flat_overlap_corners);
    RUN_TEST(bent_piece_keeps_contacts);
    TEST_MAIN_END();
}

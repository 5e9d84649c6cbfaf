/* SPDX-License-Identifier: MIT */
/* The exact ray count of points/ray.c (its comment says how it is made exact), per point, in one
 * source for the CPU (points/ray.c includes it) and the device (src/gpu/gpu_signed_impl.h):
 * every function TTD_RAY_FN (static inline, plus __host__ __device__ under nvcc), no recursion,
 * no allocation, fixed arrays whose bounds hold by construction (an exact sum has at most 192
 * terms) and a walk stack of RAY_STACK nodes whose overflow is reported (-1), as the CPU always
 * did.
 *
 * The mesh is read through ttd_ray_mesh (its ray nodes, vertices and triangles, and the numbers of
 * its point data the count uses). The node test is a function pointer on the CPU (the float row's
 * ray_node, an exact mask of comparisons: every row gives the same bits); an includer that cannot
 * call one (the device) defines TTD_RAY_NODE(fn, lo, hi, k, sigma, y) and TTD_RAY_NODE_ARG first. */
#ifndef TTD_POINTS_RAY_IMPL_H
#define TTD_POINTS_RAY_IMPL_H

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "core/point_layout.h"
#include "points/point_math.h"

#ifdef __CUDACC__
#define TTD_RAY_FN static inline __host__ __device__
#else
#define TTD_RAY_FN static inline
#endif

/* The exact fallbacks (expansions of up to 192 terms), seldom run: out of line on the device, so
 * that the common path (the rounded signs with their error bounds) keeps its registers. */
#ifdef __CUDACC__
#define TTD_RAY_COLD static __host__ __device__ __noinline__
#else
#define TTD_RAY_COLD static
#endif

#ifndef TTD_RAY_NODE
#include "core/kernels.h"
#define TTD_RAY_NODE(fn, lo, hi, k, sigma, y) (fn)(lo, hi, k, sigma, y)
#define TTD_RAY_NODE_ARG ttd_ray_node_fn
#endif

#ifdef __CUDA_ARCH__
#define TTD_RAY_CTZ(x) (__ffs((int)(x)) - 1)
#else
#define TTD_RAY_CTZ(x) __builtin_ctz(x)
#endif

/* What the count reads of a mesh and its point data (struct ttd_mesh, ttd_points_data). */
typedef struct ttd_ray_mesh {
    const ttd_rnode *rnodes; /* the ray walk's nodes */
    const void *verts;       /* 3 nv reals, double when bytes is 8, else float */
    const uint32_t *tris;
    int bytes;
    double origin[3];
    double radius;
    double scale;            /* the walk nodes' frame: (x - origin) scale */
    double coord_max;        /* the largest vertex coordinate's magnitude */
} ttd_ray_mesh;

/* ---- exact signs of sums of products ------------------------------------------------------ */

/* a + b = *s + *e exactly (Knuth's two-sum). */
TTD_RAY_FN void two_sum(double a, double b, double *s, double *e)
{
    const double x = a + b, bv = x - a, av = x - bv;
    *s = x;
    *e = (a - av) + (b - bv);
}

/* A list of doubles whose exact sum's sign is wanted, and whether a product underflowed (then
 * its error term is not exact). */
typedef struct xsum {
    double t[200];
    int n, bad;
} xsum;

/* a b - p exactly for p = a b rounded (fma is exact). Not inlined on the device: the PTX check
 * (tests/gpu_ptx.cmake) bounds the device code's FMAs to catch contraction, and this one, exact by
 * design, then appears once instead of once per unrolled use. */
#ifdef __CUDACC__
static __host__ __device__ __noinline__ double ray_prod_err(double a, double b, double p)
#else
static inline double ray_prod_err(double a, double b, double p)
#endif
{
    return fma(a, b, -p);
}

/* Appends a b exactly: its rounded value and its error. */
TTD_RAY_FN void xs_prod(xsum *x, double a, double b)
{
    const double p = a * b;
    if (a != 0 && b != 0 && !(fabs(p) >= 0x1p-900))
        x->bad = 1; /* the error term may have lost bits below the subnormal range */
    x->t[x->n++] = p;
    x->t[x->n++] = ray_prod_err(a, b, p);
}

/* The sign of the exact sum (Shewchuk's grow-expansion with zero elimination: the components stay
 * nonoverlapping and increasing, so the last one's sign is the sum's). */
TTD_RAY_COLD int xs_sign(const xsum *x)
{
    double h[200];
    int m = 0;
    for (int i = 0; i < x->n; ++i) {
        double q = x->t[i];
        int k = 0;
        for (int j = 0; j < m; ++j) {
            double s, e;
            two_sum(q, h[j], &s, &e);
            q = s;
            if (e != 0)
                h[k++] = e;
        }
        if (q != 0)
            h[k++] = q;
        m = k;
    }
    return m == 0 ? 0 : (h[m - 1] > 0 ? 1 : -1);
}

/* The exact terms of orient(q, a, b) = (a0 - q0)(b1 - q1) - (a1 - q1)(b0 - q0) appended to x,
 * times f (f = 1: the orientation itself; else each term times f's two parts, for the plane). */
TTD_RAY_COLD void orient_terms(xsum *x, const double q[2], const double a[2], const double b[2], const double *f)
{
    double d[4][2];
    two_sum(a[0], -q[0], &d[0][0], &d[0][1]);
    two_sum(b[1], -q[1], &d[1][0], &d[1][1]);
    two_sum(a[1], -q[1], &d[2][0], &d[2][1]);
    two_sum(b[0], -q[0], &d[3][0], &d[3][1]);
    for (int side = 0; side < 2; ++side) {
        const double *u = d[2 * side], *v = d[2 * side + 1];
        for (int i = 0; i < 2; ++i)
            for (int j = 0; j < 2; ++j) {
                xsum one;
                one.n = 0;
                one.bad = 0;
                xs_prod(&one, side ? -u[i] : u[i], v[j]);
                x->bad |= one.bad;
                for (int k = 0; k < 2; ++k) {
                    if (f == NULL) {
                        x->t[x->n++] = one.t[k];
                    } else {
                        xs_prod(x, one.t[k], f[0]);
                        xs_prod(x, one.t[k], f[1]);
                    }
                }
            }
    }
}

/* The power of two orient2 scales (q, a, b) up by first, or 0: a point within 2^-200 of both
 * vertices (at the walk's scale) but far from others of its triangle is scaled up (exact, the same
 * sign), so that the products of their differences stay far above the subnormal range. */
TTD_RAY_FN int orient2_scale(const double q[2], const double a[2], const double b[2])
{
    const double dm = ttd_max_nn(ttd_max_nn(fabs(a[0] - q[0]), fabs(b[1] - q[1])),
                                 ttd_max_nn(fabs(a[1] - q[1]), fabs(b[0] - q[0])));
    if (dm > 0 && dm < 0x1p-200) {
        const double big = ttd_max_nn(ttd_max_nn(fabs(q[0]), fabs(q[1])),
                                      ttd_max_nn(ttd_max_nn(fabs(a[0]), fabs(a[1])), ttd_max_nn(fabs(b[0]), fabs(b[1]))));
        int em, eb;
        (void)frexp(dm, &em);
        (void)frexp(big, &eb);
        const int f = -em < 1000 - eb ? -em : 1000 - eb;
        if (f > 0)
            return f;
    }
    return 0;
}

/* orient2 once the scale is settled. */
TTD_RAY_FN int orient2_scaled(const double q[2], const double a[2], const double b[2], double *val, double *perm, int *bad)
{
    const double l = (a[0] - q[0]) * (b[1] - q[1]), r = (a[1] - q[1]) * (b[0] - q[0]), det = l - r;
    *val = det;
    *perm = fabs(l) + fabs(r);
    /* the rounding of the two differences, the products and the subtraction: below 3.3e-16 perm
     * (Shewchuk's ccwerrboundA), taken twice */
    const double bound = 4 * DBL_EPSILON * *perm;
    if (*perm >= 0x1p-900 && det > bound) /* (below, the products may have underflowed) */
        return 1;
    if (*perm >= 0x1p-900 && det < -bound)
        return -1;
    xsum x;
    x.n = 0;
    x.bad = 0;
    orient_terms(&x, q, a, b, NULL);
    if (x.bad) {
        /* a term below the subnormal range (differences of very different sizes, such as a point
         * 1e-170 from a vertex of a unit triangle): all three scaled up by a power of two that
         * keeps them below 2^500 (exact, the same sign) and the terms formed again */
        const double big = ttd_max_nn(ttd_max_nn(fabs(q[0]), fabs(q[1])),
                                      ttd_max_nn(ttd_max_nn(fabs(a[0]), fabs(a[1])), ttd_max_nn(fabs(b[0]), fabs(b[1]))));
        int eb;
        (void)frexp(big, &eb);
        if (500 - eb > 0) {
            const int f = 500 - eb;
            const double qs[2] = {ldexp(q[0], f), ldexp(q[1], f)}, as[2] = {ldexp(a[0], f), ldexp(a[1], f)},
                         bs[2] = {ldexp(b[0], f), ldexp(b[1], f)};
            x.n = 0;
            x.bad = 0;
            orient_terms(&x, qs, as, bs, NULL);
        }
    }
    *bad |= x.bad;
    const int s = xs_sign(&x);
    if (s != 0)
        return s;
    *val = 0;
    /* exactly zero: the coefficients of eps ((a1 - b1)) and of eps^2 ((b0 - a0)) */
    if (a[1] != b[1])
        return a[1] > b[1] ? 1 : -1;
    if (a[0] != b[0])
        return b[0] > a[0] ? 1 : -1;
    return 0;
}

/* The orientation of (q, a, b) in 2D: its value in double (*val) and the sum of its two products'
 * magnitudes (*perm, for the plane's error bound), and its exact sign, the point moved by (eps,
 * eps^2) where it is zero (simulation of simplicity). The three are scaled up first where
 * orient2_scale says (*val and *perm scaled back after), as often as it says: once at most, since
 * after one scale either the differences are of unit size or the largest coordinate is 2^1000
 * (so the loop below is the one level of recursion it replaces, with no recursion on the device). */
TTD_RAY_FN int orient2(const double q[2], const double a[2], const double b[2], double *val, double *perm, int *bad)
{
    double qs[2] = {q[0], q[1]}, as[2] = {a[0], a[1]}, bs[2] = {b[0], b[1]};
    int fs[4], depth = 0;
    while (depth < 4) {
        const int f = orient2_scale(qs, as, bs);
        if (f <= 0)
            break;
        for (int c = 0; c < 2; ++c) {
            qs[c] = ldexp(qs[c], f);
            as[c] = ldexp(as[c], f);
            bs[c] = ldexp(bs[c], f);
        }
        fs[depth++] = f;
    }
    const int sg = orient2_scaled(qs, as, bs, val, perm, bad);
    while (depth > 0) {
        const int f = fs[--depth];
        *val = ldexp(*val, -2 * f);
        *perm = ldexp(*perm, -2 * f);
    }
    return sg;
}

/* ---- one triangle against the ray -------------------------------------------------------- */

/* The ray from p along sigma e_k against triangle v (3 vertices): +-1, its crossing counted with
 * the orientation of the triangle along the ray, or 0. */
TTD_RAY_FN int ray_triangle(const double p[3], int k, int sigma, const double v[3][3], int *bad)
{
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    const double q[2] = {p[i], p[j]};
    double w[3][2];
    for (int t = 0; t < 3; ++t) {
        w[t][0] = v[t][i];
        w[t][1] = v[t][j];
    }
    /* o[t]: the orientation of q against the edge opposite vertex t (its barycentric weight) */
    double o[3], perm[3];
    int s[3];
    for (int t = 0; t < 3; ++t) {
        s[t] = orient2(q, w[(t + 1) % 3], w[(t + 2) % 3], &o[t], &perm[t], bad);
        if (s[t] == 0 || s[t] != s[0])
            return 0;
    }
    /* ahead: sign(sum o_t (v_t,k - p_k)) = sign(hit - p_k) times s[0] (the o_t add up to the
     * projected area, of sign s[0]) */
    double val = 0, mag = 0, dk[3];
    for (int t = 0; t < 3; ++t) {
        dk[t] = v[t][k] - p[k];
        val += o[t] * dk[t];
        mag += perm[t] * fabs(dk[t]);
    }
    int side;
    const double bound = 8 * DBL_EPSILON * mag;
    if (mag >= 0x1p-800 && val > bound) {
        side = 1;
    } else if (mag >= 0x1p-800 && val < -bound) {
        side = -1;
    } else {
        xsum x;
        /* as orient2's: where a term falls below the subnormal range, everything scaled up by a
         * power of two that keeps it below 2^330 (products of three below 2^1000) and formed again */
        double big = 0;
        for (int t = 0; t < 3; ++t)
            for (int c = 0; c < 3; ++c)
                big = ttd_max_nn(big, ttd_max_nn(fabs(v[t][c]), fabs(p[c])));
        int eb;
        (void)frexp(big, &eb);
        for (int attempt = 0; attempt < 2; ++attempt) {
            const int sc = attempt == 0 ? 0 : 330 - eb;
            if (attempt == 1 && sc <= 0)
                break;
            const double qs[2] = {ldexp(q[0], sc), ldexp(q[1], sc)}, pk = ldexp(p[k], sc);
            x.n = 0;
            x.bad = 0;
            for (int t = 0; t < 3; ++t) {
                double f[2];
                two_sum(ldexp(v[t][k], sc), -pk, &f[0], &f[1]);
                const double ws[2][2] = {{ldexp(w[(t + 1) % 3][0], sc), ldexp(w[(t + 1) % 3][1], sc)},
                                         {ldexp(w[(t + 2) % 3][0], sc), ldexp(w[(t + 2) % 3][1], sc)}};
                orient_terms(&x, qs, ws[0], ws[1], f);
            }
            if (!x.bad)
                break;
        }
        *bad |= x.bad;
        side = xs_sign(&x);
    }
    /* hit - p_k has the sign side * s[0]; crossed when that is sigma's (0: on the plane, behind) */
    if (side * s[0] != sigma)
        return 0;
    return sigma * s[0];
}

/* ray_triangle with the point and the triangle scaled up by a power of two (exact: no sign
 * changes) where they lie within 2^-100 of one another at the walk's scale, so that the products
 * of their differences stay far above the subnormal range: a part of the mesh 2^-1000 the size of
 * the rest is counted exactly too (coordinates are kept below 2^1000). */
TTD_RAY_FN int ray_triangle_local(const double p[3], int k, int sigma, const double v[3][3], int *bad)
{
    double m = 0, big = 0;
    for (int c = 0; c < 3; ++c) {
        big = ttd_max_nn(big, fabs(p[c]));
        for (int t = 0; t < 3; ++t) {
            m = ttd_max_nn(m, fabs(v[t][c] - p[c]));
            big = ttd_max_nn(big, fabs(v[t][c]));
        }
    }
    if (!(m > 0 && m < 0x1p-100))
        return ray_triangle(p, k, sigma, v, bad);
    int em, eb;
    (void)frexp(m, &em);
    (void)frexp(big, &eb);
    const int f = -em < 1000 - eb ? -em : 1000 - eb;
    if (f <= 0)
        return ray_triangle(p, k, sigma, v, bad);
    double ps[3], vs[3][3];
    for (int c = 0; c < 3; ++c) {
        ps[c] = ldexp(p[c], f);
        for (int t = 0; t < 3; ++t)
            vs[t][c] = ldexp(v[t][c], f);
    }
    return ray_triangle(ps, k, sigma, (const double(*)[3])vs, bad);
}

/* ---- the walk ----------------------------------------------------------------------------- */

#define RAY_STACK 256

/* The ray's axis k and sense sigma for x: where x leaves the mesh's box soonest. */
TTD_RAY_FN void ttd_ray_direction(const ttd_ray_mesh *m, const double x[3], int *k, int *sigma)
{
    const ttd_rnode *rn = m->rnodes;
    double xs[3];
    for (int c = 0; c < 3; ++c)
        xs[c] = (x[c] - m->origin[c]) * m->scale;
    /* the axis and sense along which the point leaves the mesh's box soonest */
    *k = 0;
    *sigma = 1;
    double best = HUGE_VAL;
    for (int c = 0; c < 3; ++c)
        for (int sg = 1; sg >= -1; sg -= 2) {
            const double exit = sg > 0 ? (double)rn[0].hi[c][0] - xs[c] : xs[c] - (double)rn[0].lo[c][0];
            const double e = exit > 0 ? exit : 0;
            if (e < best) {
                best = e;
                *k = c;
                *sigma = sg;
            }
        }
}

/* The signed count of the crossings of the ray x + s sigma e_k, s > 0, into *w: 0, or -1 where it
 * cannot be made exact (products below the subnormal range, or the walk's stack full). */
TTD_RAY_FN int ttd_ray_count(const ttd_ray_mesh *m, TTD_RAY_NODE_ARG ray_node, const double x[3], int k, int sigma, int *w)
{
    const ttd_rnode *rn = m->rnodes;
    /* the point in the walk's frame, and the margin m = 2 eps (|x - origin| + radius) scale that
     * covers the rounding of the point's and the vertices' shift to the origin */
    double xs[3], s2 = 0;
    for (int c = 0; c < 3; ++c) {
        const double d = x[c] - m->origin[c];
        xs[c] = d * m->scale;
        s2 += d * d;
    }
    const double margin = 2 * DBL_EPSILON * (sqrt(s2) + m->radius) * m->scale * (1 + 1e-9);
    float lo[3], hi[3];
    for (int c = 0; c < 3; ++c) {
        double a = xs[c] - margin, b = xs[c] + margin;
        a = a < -0x1p60 ? -0x1p60 : (a > 0x1p60 ? 0x1p60 : a);
        b = b < -0x1p60 ? -0x1p60 : (b > 0x1p60 ? 0x1p60 : b);
        lo[c] = ttd_float_down(a);
        hi[c] = ttd_float_up(b);
    }
    /* Signs do not change under a power-of-two scale: the coordinates are kept within 2^+-300, so
     * that no product of three differences overflows (the scale is 1 unless the mesh or the point
     * lies beyond, and a coordinate the scale would push into the subnormal range is reported). */
    double big = m->coord_max;
    for (int c = 0; c < 3; ++c)
        big = fabs(x[c]) > big ? fabs(x[c]) : big;
    int e = 0;
    if (big > 0x1p300 || (big > 0 && big < 0x1p-300))
        (void)frexp(big, &e);
    double xe[3];
    int bad = 0;
    for (int c = 0; c < 3; ++c) {
        xe[c] = e != 0 ? ldexp(x[c], -e) : x[c];
        bad |= xe[c] != 0 && fabs(xe[c]) < 0x1p-1000;
    }
    int count = 0;
    int32_t stack[RAY_STACK];
    int sp = 0;
    stack[sp++] = 0;
    while (sp > 0) {
        const ttd_rnode *y = &rn[stack[--sp]];
        /* the slots whose boxes meet the ray's tube: across it, and ahead along sigma e_k */
        unsigned hit = TTD_RAY_NODE(ray_node, lo, hi, k, sigma, y);
        for (; hit; hit &= hit - 1) {
            const int s = TTD_RAY_CTZ(hit);
            const int32_t ch = y->child[s];
            if (ch >= 0) {
                if (sp == RAY_STACK)
                    return -1;
                stack[sp++] = ch;
                continue;
            }
            const size_t t = (size_t)(-1 - ch);
            double v[3][3];
            for (int a = 0; a < 3; ++a) {
                const size_t vi = m->tris[3 * t + (size_t)a];
                for (int c = 0; c < 3; ++c) {
                    v[a][c] = m->bytes == 8 ? ((const double *)m->verts)[3 * vi + (size_t)c]
                                            : (double)((const float *)m->verts)[3 * vi + (size_t)c];
                    if (e != 0) {
                        v[a][c] = ldexp(v[a][c], -e);
                        bad |= v[a][c] != 0 && fabs(v[a][c]) < 0x1p-1000;
                    }
                }
            }
            count += ray_triangle_local(xe, k, sigma, (const double(*)[3])v, &bad);
        }
    }
    if (bad)
        return -1;
    *w = count;
    return 0;
}

/* ttd_ray_count along ttd_ray_direction's ray: a closed mesh's winding number about x. */
TTD_RAY_FN int ttd_ray_winding(const ttd_ray_mesh *m, TTD_RAY_NODE_ARG ray_node, const double x[3], int *w)
{
    int k, sigma;
    ttd_ray_direction(m, x, &k, &sigma);
    return ttd_ray_count(m, ray_node, x, k, sigma, w);
}

#endif /* TTD_POINTS_RAY_IMPL_H */

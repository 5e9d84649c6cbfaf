/* SPDX-License-Identifier: MIT */
/* The scalar reference of continuous collision (ccd/ccd.h; the argument in docs/ccd.md), one source
 * for the CPU (ccd.c wraps it as ttd_ccd_query / ttd_ccd_screen) and the device (src/gpu/gpu_ccd.cu,
 * one query a CUDA thread): every function TTDW_FN (__host__ __device__ under nvcc, static inline in
 * C), nothing allocated, no recursion, the interval stack and the expansions bounded; no table at
 * file scope (device code cannot read host data): the point-pair tables are function-local.
 *
 * Both primitives are convex hulls of moving points, A(t) and B(t). For any direction n, the
 * separation of their projections,
 *     g_n(t) = min over a in A of n.a(t) - max over b in B of n.b(t),
 * bounds the distance from below: dist(t) >= g_n(t) / |n|. Each n.a(t) is linear in t, so the min
 * is concave, the max convex, and g_n concave: its minimum over a time interval [ta, tb] is
 * min(g_n(ta), g_n(tb)). So two evaluations at the ends, with their rounding error bounded,
 * certify dist > delta over the whole interval whenever min(g_n(ta), g_n(tb)) > delta |n|. The
 * direction is the one between the closest points at the interval's middle (computed in plain
 * double: any n gives a valid bound, a good one a tight bound; at the middle it equals the
 * distance, and near a minimum of the distance it loses only O(h^2)).
 *
 * The search bisects [0, t_max] depth first, earliest half first: an interval certified apart is
 * dropped, one shorter than t_tol that is not is the hit, and its start is toi. Every time before
 * toi was certified apart, so toi is never later than the true first time of contact. */
#ifndef TTD_CCD_CCD_SEARCH_IMPL_H
#define TTD_CCD_CCD_SEARCH_IMPL_H

#include <float.h>
#include <math.h>
#include <string.h>

#include "ccd/ccd.h"
#include "ccd/ccd_exact_impl.h"

/* The search's defaults (ttd_ccd_default_params). */
TTDW_FN ttd_ccd_params ccd_params_default(void)
{
    ttd_ccd_params p = {0.0, 1.0, TTD_CCD_DEFAULT_T_TOL, TTD_CCD_DEFAULT_MAX_EVALS, HUGE_VAL};
    return p;
}

/* u: the unit roundoff of double. */
#define U_ROUND 0x1p-53 /* (undefined at the end of the file) */

TTDW_FN double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

TTDW_FN void sub3(double r[3], const double a[3], const double b[3])
{
    r[0] = a[0] - b[0];
    r[1] = a[1] - b[1];
    r[2] = a[2] - b[2];
}

TTDW_FN void cross3(double r[3], const double a[3], const double b[3])
{
    r[0] = a[1] * b[2] - a[2] * b[1];
    r[1] = a[2] * b[0] - a[0] * b[2];
    r[2] = a[0] * b[1] - a[1] * b[0];
}

/* The query's state: the motions, the positions at the ends of the current interval. */
typedef struct ccd_state {
    int na;            /* points [0, na) are A, [na, 4) are B */
    double x0[4][3];   /* at t = 0 */
    double dx[4][3];   /* fl(x1 - x0) */
    double e_gap;      /* bound on the rounding error of a computed g_n, |n|_inf = 1, without the |g| term */
    const double *in0, *in1; /* the inputs, for the exact test */
    double ta, tb;     /* the interval being tested */
    double cand_n[3], cand_g; /* the exact test's direction for this interval, its rounded gap */
    double t_tol;      /* the search's resolution */
    int near_miss;     /* an exact contact condition proved a final interval free */
    int cond_cuts;     /* cuts made at a contact condition's root (cond_root), at most COND_CUTS */
    double cut_ta, cut_lo; /* the piece before the last such cut, where the conditions' exact test runs */
    int made[5];       /* whether poly[i] is formed: f, then the contact conditions */
    double last_t;     /* the last time f's exact sign was taken at, and that sign */
    int last_sign;
    ttd_ccd_xpoly poly[5];
} ccd_state;

/* Positions at time t: fl(x0 + fl(t fl(x1 - x0))); within 5 u S of the exact point for t in
 * [0, 1], S the largest coordinate magnitude (docs/ccd.md, section 3). */
TTDW_FN void positions(const ccd_state *s, double t, double x[4][3])
{
    for (int i = 0; i < 4; ++i)
        for (int k = 0; k < 3; ++k)
            x[i][k] = s->x0[i][k] + t * s->dx[i][k];
}

/* Closest points of a point p and a triangle abc (the Voronoi-region walk of Ericson's
 * "Real-Time Collision Detection", 5.1.5); the weights are clamped so q stays in the triangle up
 * to rounding even for a degenerate triangle. An edge region is taken only where its weight's
 * denominator is positive: it is zero where the edge's two ends are equal (d1 = d3 = 0 when
 * a = b), and 0/0 would put q at an end that need not be closest; the walk then goes on to the
 * regions of the other edges, which for a zero-area face are the segment (or point) it is. */
enum { R_A, R_B, R_C, R_AB, R_AC, R_BC, R_FACE };

TTDW_FN int closest_point_triangle(const double p[3], const double a[3], const double b[3],
                                  const double c[3], double q[3])
{
    double ab[3], ac[3], ap[3], bp[3], cp[3];
    sub3(ab, b, a);
    sub3(ac, c, a);
    sub3(ap, p, a);
    const double d1 = dot3(ab, ap), d2 = dot3(ac, ap);
    if (d1 <= 0 && d2 <= 0) {
        memcpy(q, a, sizeof(double) * 3);
        return R_A;
    }
    sub3(bp, p, b);
    const double d3 = dot3(ab, bp), d4 = dot3(ac, bp);
    if (d3 >= 0 && d4 <= d3) {
        memcpy(q, b, sizeof(double) * 3);
        return R_B;
    }
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0 && d1 - d3 > 0) {
        double v = d1 / (d1 - d3);
        v = v > 0 ? (v < 1 ? v : 1) : 0;
        for (int k = 0; k < 3; ++k)
            q[k] = a[k] + v * ab[k];
        return R_AB;
    }
    sub3(cp, p, c);
    const double d5 = dot3(ab, cp), d6 = dot3(ac, cp);
    if (d6 >= 0 && d5 <= d6) {
        memcpy(q, c, sizeof(double) * 3);
        return R_C;
    }
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0 && d2 - d6 > 0) {
        double w = d2 / (d2 - d6);
        w = w > 0 ? (w < 1 ? w : 1) : 0;
        for (int k = 0; k < 3; ++k)
            q[k] = a[k] + w * ac[k];
        return R_AC;
    }
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0 && (d4 - d3) + (d5 - d6) > 0) {
        double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        w = w > 0 ? (w < 1 ? w : 1) : 0;
        for (int k = 0; k < 3; ++k)
            q[k] = b[k] + w * (c[k] - b[k]);
        return R_BC;
    }
    const double sum = va + vb + vc;
    double v = sum > 0 ? vb / sum : 0, w = sum > 0 ? vc / sum : 0;
    v = v > 0 ? (v < 1 ? v : 1) : 0;
    w = w > 0 ? (w < 1 - v ? w : 1 - v) : 0;
    for (int k = 0; k < 3; ++k)
        q[k] = a[k] + v * ab[k] + w * ac[k];
    return R_FACE;
}

TTDW_FN double clamp01(double x)
{
    return x > 0 ? (x < 1 ? x : 1) : 0;
}

/* Closest points of segments p0p1 and q0q1 (Ericson, 5.1.9: the parameters clamped in turn;
 * zero-length and parallel segments handled by the same clamping); *sp, *tp the parameters. */
TTDW_FN void closest_segments(const double p0[3], const double p1[3], const double q0[3],
                             const double q1[3], double cp[3], double cq[3], double *sp, double *tp)
{
    double d1[3], d2[3], r[3];
    sub3(d1, p1, p0);
    sub3(d2, q1, q0);
    sub3(r, p0, q0);
    const double a = dot3(d1, d1), e = dot3(d2, d2), f = dot3(d2, r);
    double s, t;
    if (a <= 0 && e <= 0) {
        s = t = 0;
    } else if (a <= 0) {
        s = 0;
        t = clamp01(f / e);
    } else {
        const double c = dot3(d1, r);
        if (e <= 0) {
            t = 0;
            s = clamp01(-c / a);
        } else {
            const double b = dot3(d1, d2), denom = a * e - b * b;
            s = denom > 0 ? clamp01((b * f - c * e) / denom) : 0;
            t = (b * s + f) / e;
            if (t < 0) {
                t = 0;
                s = clamp01(-c / a);
            } else if (t > 1) {
                t = 1;
                s = clamp01((b - c) / a);
            }
        }
    }
    for (int k = 0; k < 3; ++k) {
        cp[k] = p0[k] + s * d1[k];
        cq[k] = q0[k] + t * d2[k];
    }
    *sp = s;
    *tp = t;
}

/* The part of p - u perpendicular to the line uv, times |v - u|^2: e x ((p - u) x e). Computed
 * from differences of the points, not of nearly equal closest points, so its direction stays
 * accurate when p is very near the line. */
TTDW_FN void perp(double n[3], const double p[3], const double u[3], const double v[3])
{
    double e[3], w[3], c[3];
    sub3(e, v, u);
    sub3(w, p, u);
    cross3(c, w, e);
    cross3(n, e, c);
}

TTDW_FN void negate3(double n[3])
{
    n[0] = -n[0];
    n[1] = -n[1];
    n[2] = -n[2];
}

/* Two directions from B toward A at positions x: n1 the closest points' difference (returned: its
 * length, the distance up to rounding) and n2 from the closest features (the face normal, an
 * edge's perpendicular, the edges' cross product), accurate where n1's rounding is not small
 * against the distance; n2 is zero where the features are two points, whose indices go to vv (else
 * -1). Any direction gives a valid bound; these give tight ones. */
TTDW_FN double directions(int na, double x[4][3], double n1[3], double n2[3], int vv[2])
{
    double ca[3], cb[3];
    n2[0] = n2[1] = n2[2] = 0;
    vv[0] = vv[1] = -1;
    if (na == TTD_CCD_VF) {
        memcpy(ca, x[0], sizeof ca);
        const int r = closest_point_triangle(x[0], x[1], x[2], x[3], cb);
        sub3(n1, ca, cb);
        if (r == R_FACE) {
            double ab[3], ac[3], ap[3];
            sub3(ab, x[2], x[1]);
            sub3(ac, x[3], x[1]);
            sub3(ap, x[0], x[1]);
            cross3(n2, ab, ac);
            if (dot3(n2, ap) < 0)
                negate3(n2);
        } else if (r == R_AB) {
            perp(n2, x[0], x[1], x[2]);
        } else if (r == R_AC) {
            perp(n2, x[0], x[1], x[3]);
        } else if (r == R_BC) {
            perp(n2, x[0], x[2], x[3]);
        } else {
            vv[0] = 0;
            vv[1] = 1 + r; /* R_A, R_B, R_C are 0, 1, 2 */
        }
    } else {
        double s, t;
        closest_segments(x[0], x[1], x[2], x[3], ca, cb, &s, &t);
        sub3(n1, ca, cb);
        const int s_in = s > 0 && s < 1, t_in = t > 0 && t < 1;
        if (s_in && t_in) {
            double ea[3], eb[3], w[3];
            sub3(ea, x[1], x[0]);
            sub3(eb, x[3], x[2]);
            sub3(w, x[0], x[2]);
            cross3(n2, ea, eb);
            /* Which side: a0 - b0 along the cross product (exact where the segments cross the
             * common normal's plane; n1 is too short to tell). */
            if (dot3(n2, w) < 0)
                negate3(n2);
        } else if (s_in) {
            /* B's endpoint against A's segment: from B toward A is minus the perpendicular. */
            perp(n2, t > 0 ? x[3] : x[2], x[0], x[1]);
            negate3(n2);
        } else if (t_in) {
            perp(n2, s > 0 ? x[1] : x[0], x[2], x[3]);
        } else {
            vv[0] = s > 0 ? 1 : 0;
            vv[1] = t > 0 ? 3 : 2;
        }
    }
    return sqrt(dot3(n1, n1));
}

/* The computed g_n at positions x, n with |n|_inf = 1. */
TTDW_FN double gap_along(int na, double x[4][3], const double n[3])
{
    double amin = HUGE_VAL, bmax = -HUGE_VAL;
    for (int i = 0; i < 4; ++i) {
        const double v = dot3(n, x[i]);
        if (i < na)
            amin = v < amin ? v : amin;
        else
            bmax = v > bmax ? v : bmax;
    }
    return amin - bmax;
}

/* ---- the exact test where the rounding bound cannot separate (delta = 0) ----------------------
 * n.(a(t) - b(t)), for doubles t and n and the exact linear motions, is a sum of products of two
 * or three doubles: each product is split into doubles that add up to it exactly (fma gives a
 * product's rounding error), and the sign of their sum is taken exactly by Shewchuk's
 * grow-expansion with zero elimination (the technique of src/points/ray.c). */

typedef struct xterms {
    double t[64];
    int n, bad;
} xterms;

/* Appends a b exactly (bad when the error term may have lost bits below the normal range). */
TTDW_FN void xt_prod(xterms *x, double a, double b)
{
    const double p = a * b;
    if (a != 0 && b != 0 && !(fabs(p) >= 0x1p-960))
        x->bad = 1;
    x->t[x->n++] = p;
    x->t[x->n++] = fma(a, b, -p);
}

TTDW_FN int xt_sign(const xterms *x)
{
    double h[64];
    int m = 0;
    for (int i = 0; i < x->n; ++i) {
        double q = x->t[i];
        int k = 0;
        for (int j = 0; j < m; ++j) {
            double sum, err;
            ccdx_two_sum(q, h[j], &sum, &err);
            q = sum;
            if (err != 0)
                h[k++] = err;
        }
        if (q != 0)
            h[k++] = q;
        m = k;
    }
    return m == 0 ? 0 : (h[m - 1] > 0 ? 1 : -1);
}

/* The exact sign of n.(a(t) - b(t)) for points ia (of A) and ib (of B) of the query's inputs x0,
 * x1; 2 when a product underflowed (the caller then does not rely on it). */
TTDW_FN int exact_side(const double x0[12], const double x1[12], int ia, int ib, double t, const double n[3])
{
    xterms x;
    x.n = 0;
    x.bad = 0;
    for (int k = 0; k < 3; ++k) {
        const double a0 = x0[3 * ia + k], a1 = x1[3 * ia + k], b0 = x0[3 * ib + k], b1 = x1[3 * ib + k];
        /* n a0 - n b0 + t n (a1 - a0 - b1 + b0), with t n = th + tl exactly. */
        const double th = t * n[k], tl = fma(t, n[k], -th);
        xt_prod(&x, n[k], a0);
        xt_prod(&x, -n[k], b0);
        const double c[4] = {a1, -a0, -b1, b0};
        for (int j = 0; j < 4; ++j) {
            xt_prod(&x, th, c[j]);
            xt_prod(&x, tl, c[j]);
        }
    }
    if (x.bad || (t != 0 && fabs(t) < 0x1p-900))
        return 2;
    /* First the compensated sum (Ogita, Rump and Oishi's Sum2): within u|sum| + gamma_{n-1}^2
     * sum|t_i| of the exact sum, which settles the sign unless the sum is within about 2^-94 of
     * the terms' size; the expansion only then. */
    double sum = 0, comp = 0, mag = 0;
    for (int i = 0; i < x.n; ++i) {
        double e;
        ccdx_two_sum(sum, x.t[i], &sum, &e);
        comp += e;
        mag += fabs(x.t[i]);
    }
    const double res = sum + comp, g = 64 * U_ROUND;
    if (fabs(res) > 4 * U_ROUND * fabs(res) + 4 * g * g * mag + 0x1p-1070)
        return res > 0 ? 1 : -1;
    return xt_sign(&x);
}

/* Whether every point of A lies strictly on n's positive side of every point of B at both t,
 * exactly: then A and B are disjoint over [ta, tb] (the argument at the top of this file). */
TTDW_FN int exact_separated(const double x0[12], const double x1[12], int na, double ta, double tb,
                           const double n[3])
{
    /* The pairs in the order of their rounded separation, the closest first: where the answer is
     * no, the first test usually says so. */
    double v[8];
    int ord[8], m = 0;
    for (int e = 0; e < 2; ++e)
        for (int ia = 0; ia < na; ++ia)
            for (int ib = na; ib < 4; ++ib) {
                const double t = e ? tb : ta;
                double d = 0;
                for (int k = 0; k < 3; ++k)
                    d += n[k] * ((x0[3 * ia + k] + t * (x1[3 * ia + k] - x0[3 * ia + k])) -
                                 (x0[3 * ib + k] + t * (x1[3 * ib + k] - x0[3 * ib + k])));
                int j = m++;
                for (; j > 0 && v[j - 1] > d; --j) {
                    v[j] = v[j - 1];
                    ord[j] = ord[j - 1];
                }
                v[j] = d;
                ord[j] = (e << 4) | (ia << 2) | ib;
            }
    for (int j = 0; j < m; ++j)
        if (exact_side(x0, x1, (ord[j] >> 2) & 3, ord[j] & 3, (ord[j] >> 4) ? tb : ta, n) != 1)
            return 0;
    return 1;
}

/* Whether dist > delta on all of the interval whose end positions are xa, xb, along n (any
 * finite nonzero vector). thr = delta times an upper bound of |n|_2 once n is scaled. */
TTDW_FN int separated_along(ccd_state *s, double xa[4][3], double xb[4][3],
                           const double n_in[3], double delta)
{
    const double m = fmax(fabs(n_in[0]), fmax(fabs(n_in[1]), fabs(n_in[2])));
    if (!(m > 0) || !isfinite(m))
        return 0;
    /* Scaled so that its largest component is exactly +-1: |n|_2 in [1, sqrt 3]. */
    const double n[3] = {n_in[0] / m, n_in[1] / m, n_in[2] / m};
    const double thr = delta > 0 ? delta * sqrt(dot3(n, n)) * (1 + 0x1p-44) : 0.0;
    const double ga = gap_along(s->na, xa, n), gb = gap_along(s->na, xb, n);
    /* Computed g within e_gap + 2u|g| of the exact g_n of the exact positions. */
    const double ea = s->e_gap + 0x1p-52 * fabs(ga), eb = s->e_gap + 0x1p-52 * fabs(gb);
    if (ga - ea > thr && gb - eb > thr)
        return 1;
    /* Within the rounding bound of separation at delta = 0: a candidate for the exact test, which
     * runs once an interval, on the direction whose rounded gap is largest. */
    const double g = fmin(ga, gb);
    if (delta == 0 && ga + ea > 0 && gb + eb > 0 && g > s->cand_g) {
        s->cand_g = g;
        memcpy(s->cand_n, n, sizeof n);
    }
    return 0;
}

/* For two points ia of A and ib of B: w(t) = a(t) - b(t) = w0 + t dw moves on a line, and
 * dw x (w0 x dw) is the direction of that line's nearest approach to 0, from the inputs (not from
 * rounded positions): the one direction that separates a point passing another within the
 * rounding of its positions (a vertex sliding past a vertex). */
TTDW_FN void pass_direction(const double x0[12], const double x1[12], int ia, int ib, double n[3])
{
    double w0[3], dw[3], c[3];
    for (int k = 0; k < 3; ++k) {
        w0[k] = x0[3 * ia + k] - x0[3 * ib + k];
        dw[k] = (x1[3 * ia + k] - x0[3 * ia + k]) - (x1[3 * ib + k] - x0[3 * ib + k]);
    }
    cross3(c, w0, dw);
    cross3(n, dw, c);
    if (!(dot3(n, n) > 0))
        memcpy(n, w0, sizeof w0);
}

/* ---- delta = 0: the four points never coplanar on the interval ----------------------------------
 * A contact (distance 0) makes the four points coplanar: the vertex lies in the face's plane, or
 * the two edges meet. Their coplanarity is f(t) = det(u, v, w) for three difference vectors, each
 * linear in t; on [ta, tb] (s in [0, 1]) f is a cubic whose Bernstein coefficients are the
 * trilinear form's values at the ends, averaged (its blossom). When all four have one strict sign,
 * f has no root there and the interval holds no contact. Computed from the end positions, with
 * the error bound of docs/ccd.md, section 3. */
TTDW_FN double det3(const double u[3], const double v[3], const double w[3])
{
    double c[3];
    cross3(c, u, v);
    return dot3(c, w);
}

/* What the rounded Bernstein coefficients of the coplanarity cubic f say about an interval. */
typedef struct cop_info {
    int never;    /* every coefficient beyond its rounding bound, one sign: f != 0, no contact */
    int undecided;/* no two coefficients of strict opposite signs: the exact test may prove it */
    int sgn;      /* then the sign a proof would have (0: either) */
    int change;   /* f(ta) and f(tb) of strict opposite signs: f has a root in the interval */
    int end_zero; /* f(ta) strict, f(tb) within its bound of 0 (maybe a root at tb) */
    double B[4];  /* the rounded Bernstein coefficients (a guess of f's first root: prefix_cut) */
} cop_info;

TTDW_FN void never_coplanar(int na, double xa[4][3], double xb[4][3], double S, cop_info *ci)
{
    memset(ci, 0, sizeof *ci);
    /* The difference vectors at both ends: VF (b - a, c - a, p - a), EE (a1 - a0, b0 - a0, b1 - a0). */
    static const int pick[2][4] = {{1, 2, 3, 0}, {0, 1, 2, 3}};
    const int *k = pick[na - 1];
    double w[2][3][3], V = 0;
    for (int e = 0; e < 2; ++e) {
        double(*x)[3] = e ? xb : xa;
        for (int j = 0; j < 3; ++j) {
            sub3(w[e][j], x[k[j + 1]], x[k[0]]);
            V = fmax(V, dot3(w[e][j], w[e][j]));
        }
    }
    /* Each component within 12uS of the exact difference (two positions within 5uS, one
     * subtraction); V bounds every vector's exact length. */
    const double ec = 12 * U_ROUND * S, en = 1.7321 * ec;
    V = sqrt(V) * (1 + 4 * U_ROUND) + en;
    if (!(V > 0x1p-300 && V < 0x1p300))
        return;
    const double err = (3 * en * V * V + 64 * U_ROUND * V * V * V) * (1 + 0x1p-40) + 0x1p-1000;
    double B[4];
    B[0] = det3(w[0][0], w[0][1], w[0][2]);
    B[3] = det3(w[1][0], w[1][1], w[1][2]);
    B[1] = (det3(w[1][0], w[0][1], w[0][2]) + det3(w[0][0], w[1][1], w[0][2]) + det3(w[0][0], w[0][1], w[1][2])) / 3;
    B[2] = (det3(w[1][0], w[1][1], w[0][2]) + det3(w[1][0], w[0][1], w[1][2]) + det3(w[0][0], w[1][1], w[1][2])) / 3;
    memcpy(ci->B, B, sizeof B);
    int pos = 1, neg = 1, any_pos = 0, any_neg = 0, sg[4];
    for (int i = 0; i < 4; ++i) {
        const double e = err + 0x1p-51 * fabs(B[i]);
        sg[i] = B[i] > e ? 1 : (B[i] < -e ? -1 : 0);
        pos &= sg[i] > 0;
        neg &= sg[i] < 0;
        any_pos |= sg[i] > 0;
        any_neg |= sg[i] < 0;
    }
    ci->never = pos || neg;
    ci->undecided = !ci->never && !(any_pos && any_neg);
    ci->sgn = any_neg ? -1 : (any_pos ? 1 : 0);
    ci->change = sg[0] * sg[3] < 0;
    ci->end_zero = sg[0] != 0 && sg[3] == 0;
}

/* ---- delta = 0: the contact conditions -----------------------------------------------------------
 * A contact also needs the vertex inside the face (each edge's condition
 * ((v_{i+1} - v_i) x (p - v_i)).((v1 - v0) x (v2 - v0)) >= 0), or the edges crossing (with
 * n = ea x eb: (eb x (a0 - b0)).n, (eb x (b0 - a1)).n, (ea x (a0 - b0)).n, (ea x (b1 - a0)).n all
 * >= 0), whenever the points are coplanar and the face has area or the edges are not parallel; a
 * strictly negative condition gives both. So one condition < 0 over the whole interval proves it
 * free of contact; all > 0 over it, with f changing sign there, prove a contact in it, and the first
 * contact there is f's first root. Each is (v0 x v1).(v2 x v3) of difference vectors (point pairs
 * below), a quartic in t. */
TTDW_FN const int (*ccd_form_pts(int na, int which))[2]
{
    /* [na - 1][which]: which 0 the coplanarity cubic f (cop), 1..4 the contact conditions; a
     * function-scope table, which device code can read (one at file scope it cannot). */
    static const int pts[2][5][4][2] = {
        {{{2, 1}, {3, 1}, {0, 1}, {0, 0}},
         {{2, 1}, {0, 1}, {2, 1}, {3, 1}}, {{3, 2}, {0, 2}, {2, 1}, {3, 1}}, {{1, 3}, {0, 3}, {2, 1}, {3, 1}}, {{0, 0}}},
        {{{1, 0}, {2, 0}, {3, 0}, {0, 0}},
         {{3, 2}, {0, 2}, {1, 0}, {3, 2}}, {{3, 2}, {2, 1}, {1, 0}, {3, 2}}, {{1, 0}, {0, 2}, {1, 0}, {3, 2}},
         {{1, 0}, {3, 0}, {1, 0}, {3, 2}}}};
    return pts[na - 1][which];
}

/* A condition's Bernstein coefficients on the interval in double from the rounded end positions
 * (B[j] the sum of the C(4, j) blossom values with j ends at tb: the quartic at s in [0, 1] is
 * sum B[j] s^j (1 - s)^(4 - j)), and *bound on each one's rounding error; 0 where none can be
 * bounded. The bound: each vector component within 21uS of the exact one (12uS, docs/ccd.md,
 * section 3), so |v| <= V and a value of the form moves by at most 4 (sqrt 3 21uS) V^3 from it,
 * plus 40uV^4 of rounding; a coefficient sums at most 6 values (5.01uV^4 more). */
TTDW_FN int condition_bern(const int pts[4][2], double xa[4][3], double xb[4][3], double S, double B[5], double *bound)
{
    double v[4][2][3], V = 0;
    for (int k = 0; k < 4; ++k)
        for (int e = 0; e < 2; ++e) {
            double(*x)[3] = e ? xb : xa;
            sub3(v[k][e], x[pts[k][0]], x[pts[k][1]]);
            V = fmax(V, dot3(v[k][e], v[k][e]));
        }
    V = sqrt(V) * (1 + 4 * U_ROUND) + 37 * U_ROUND * S;
    if (!(V < 0x1p200))
        return 0;
    *bound = (6 * (8 * 21 * U_ROUND * S * V * V * V + 48 * U_ROUND * V * V * V * V)) * (1 + 0x1p-40) + 0x1p-1000;
    double c01[2][2][3], c23[2][2][3];
    for (int j = 0; j < 5; ++j)
        B[j] = 0;
    for (int e0 = 0; e0 < 2; ++e0)
        for (int e1 = 0; e1 < 2; ++e1) {
            cross3(c01[e0][e1], v[0][e0], v[1][e1]);
            cross3(c23[e0][e1], v[2][e0], v[3][e1]);
        }
    for (int mask = 0; mask < 16; ++mask)
        B[ccdx_popcount4(mask)] +=
            dot3(c01[mask & 1][(mask >> 1) & 1], c23[(mask >> 2) & 1][(mask >> 3) & 1]);
    return 1;
}

/* A condition's sign on the interval by its rounded Bernstein coefficients (condition_bern): +1 when
 * all exceed their rounding bound (the condition is > 0 on the whole interval), -1 when none is
 * positive beyond it (it may be < 0 throughout: a candidate for the exact test), else 0. */
TTDW_FN int condition_sign(const int pts[4][2], double xa[4][3], double xb[4][3], double S)
{
    double B[5], bound;
    if (!condition_bern(pts, xa, xb, S, B, &bound))
        return 0;
    int pos = 1, mayneg = 1;
    for (int j = 0; j < 5; ++j) {
        pos &= B[j] > bound;
        mayneg &= B[j] <= bound;
    }
    return pos ? 1 : (mayneg ? -1 : 0);
}

/* The conditions' signs on the interval (condition_sign); returns 1 when all are > 0. */
TTDW_FN int conditions(int na, double xa[4][3], double xb[4][3], double S, int sign[4])
{
    const int nc = na == TTD_CCD_VF ? 3 : 4;
    int all = 1;
    for (int c = 0; c < nc; ++c) {
        sign[c] = condition_sign(ccd_form_pts(na, 1 + c), xa, xb, S);
        all &= sign[c] == 1;
    }
    for (int c = nc; c < 4; ++c)
        sign[c] = 0;
    return all;
}

/* The exact polynomial f (which 0) or contact condition which - 1, formed when first needed. */
TTDW_FN const ttd_ccd_xpoly *xpoly(ccd_state *s, int which)
{
    if (!s->made[which]) {
        if (which == 0)
            ccdx_xpoly_make(&s->poly[0], TTD_CCD_FORM_DET, ccd_form_pts(s->na, 0), s->in0, s->in1);
        else
            ccdx_xpoly_make(&s->poly[which], TTD_CCD_FORM_CROSS_DOT, ccd_form_pts(s->na, which), s->in0, s->in1);
        s->made[which] = 1;
    }
    return &s->poly[which];
}

/* f's exact sign at t (2: untrusted), remembered for the last t (the ends of nested intervals
 * repeat). */
TTDW_FN int f_sign_at(ccd_state *s, double t)
{
    if (t != s->last_t) {
        s->last_t = t;
        s->last_sign = ccdx_xpoly_sign_at(xpoly(s, 0), t);
    }
    return s->last_sign;
}

/* The first root of the cubic c0 + c1 t + c2 t^2 + c3 t^3 in [lo, hi] in double, approximately:
 * the pieces between the roots of its derivative in turn, the first whose ends differ in sign
 * bisected to the end. NAN if no piece changes sign. Only a guess: the caller checks it exactly. */
TTDW_FN double approx_first_root(const double c[4], double lo, double hi)
{
    double cut[4];
    int n = 0;
    const double A = 3 * c[3], B = 2 * c[2], C = c[1];
    if (A != 0) {
        const double disc = B * B - 4 * A * C;
        if (disc >= 0) {
            const double q = -0.5 * (B + copysign(sqrt(disc), B));
            if (q != 0) {
                cut[n++] = q / A;
                cut[n++] = C / q;
            }
        }
    } else if (B != 0) {
        cut[n++] = -C / B;
    }
    if (n == 2 && cut[0] > cut[1]) {
        const double t = cut[0];
        cut[0] = cut[1];
        cut[1] = t;
    }
    double pts[4];
    int np = 0;
    pts[np++] = lo;
    for (int i = 0; i < n; ++i)
        if (cut[i] > lo && cut[i] < hi)
            pts[np++] = cut[i];
    pts[np++] = hi;
    for (int i = 0; i + 1 < np; ++i) {
        double a = pts[i], b = pts[i + 1];
        double fa = ((c[3] * a + c[2]) * a + c[1]) * a + c[0];
        const double fb = ((c[3] * b + c[2]) * b + c[1]) * b + c[0];
        if (fa == 0)
            return a;
        if ((fa < 0) == (fb < 0) && fb != 0)
            continue;
        for (int it = 0; it < 200; ++it) {
            const double m = 0.5 * (a + b);
            if (!(m > a && m < b))
                break;
            const double fm = ((c[3] * m + c[2]) * m + c[1]) * m + c[0];
            if (fm != 0 && (fm < 0) == (fa < 0)) {
                a = m;
                fa = fm;
            } else {
                b = m;
            }
        }
        return b;
    }
    return (double)NAN;
}

/* In an interval [ta, tb] certain to hold a contact, whose first contact is f's first root there
 * (the conditions hold throughout): a root guessed in double and checked exactly gives toi at
 * once, in place of bisecting down to the tolerance. f(ta) nonzero; f has no root in [ta, lo]
 * (its Bernstein coefficients there, exactly) and has one in (lo, lo + t_tol] (f(lo + t_tol) not
 * of f(ta)'s sign, or zero_at_tb: f(tb) = 0 exactly with lo = tb - t_tol). Returns 1 with *toi = lo,
 * 0 where a check fails (the search then bisects). */
TTDW_FN int jump_to_root(ccd_state *s, double ta, double tb, int zero_at_tb, double *toi)
{
    const ttd_ccd_xpoly *P = xpoly(s, 0);
    if (P->bad)
        return 0;
    const int s0 = ccdx_xpoly_sign_at(P, ta);
    if (s0 != 1 && s0 != -1)
        return 0;
    double lo, hi;
    if (zero_at_tb) {
        hi = tb;
        lo = tb - s->t_tol;
    } else {
        const double r = approx_first_root(P->a, ta, tb);
        if (!(r >= ta && r <= tb))
            return 0;
        lo = r - 0.5 * s->t_tol;
        hi = lo + s->t_tol;
        if (hi > tb) {
            hi = tb;
            lo = tb - s->t_tol;
        }
    }
    while (hi - lo > s->t_tol)
        lo = nextafter(lo, hi);
    if (!(lo > ta && hi > lo))
        return 0;
    if (!zero_at_tb) {
        const int sh = ccdx_xpoly_sign_at(P, hi);
        if (sh == 2 || sh == s0)
            return 0;
    }
    if (ccdx_xpoly_sign(P, ta, lo, s0) != s0)
        return 0;
    *toi = lo;
    return 1;
}

/* The guess r of f's first root in (ta, tb], moved onto a sign change of f found exactly: f's exact
 * sign at r, then at r plus or minus 1, 4, 16, ... ulps until it differs from f(ta)'s, the bracket
 * then halved to at most t_tol / 2; returns its end b (f(b) not of f(ta)'s sign, f of that sign at a
 * point at most t_tol / 2 before b), so that the cut's piece [b - t_tol / 2, b + t_tol / 2] holds
 * the sign change. The guess rounded from f's coefficients is off by an ulp or two where f is
 * flat or has two roots close together, and a cut beside the root leaves a stretch starting at a
 * contact, which only halving to t_tol ends. r unchanged where f(ta) has no strict sign, an exact
 * sign is untrusted, or no change is found within 12 steps (the cut's order only: every
 * guarantee stands whatever r is). */
TTDW_FN double bracket_root(ccd_state *s, const ttd_ccd_xpoly *P, double ta, double tb, double r)
{
    if (!(r > ta && r <= tb))
        return r;
    const int s0 = ccdx_xpoly_sign_at(P, ta);
    if (s0 != 1 && s0 != -1)
        return r;
    const int sr = ccdx_xpoly_sign_at(P, r);
    if (sr == 2)
        return r;
    double a, b; /* f(a) of s0's sign, f(b) not */
    double step = nextafter(r, HUGE_VAL) - r;
    if (sr == s0) {
        a = r;
        for (int k = 0;; ++k) {
            if (k == 12 || a >= tb)
                return r;
            b = a + step < tb ? a + step : tb;
            const int sb = ccdx_xpoly_sign_at(P, b);
            if (sb == 2)
                return r;
            if (sb != s0)
                break;
            a = b;
            step *= 4;
        }
    } else {
        b = r;
        for (int k = 0;; ++k) {
            if (k == 12)
                return r;
            a = b - step > ta ? b - step : ta;
            const int sa = a == ta ? s0 : ccdx_xpoly_sign_at(P, a);
            if (sa == 2)
                return r;
            if (sa == s0)
                break;
            b = a;
            step *= 4;
        }
    }
    while (b - a > 0.5 * s->t_tol) {
        const double m = a + 0.5 * (b - a);
        if (!(m > a && m < b))
            break;
        const int sm = ccdx_xpoly_sign_at(P, m);
        if (sm == 2)
            return r;
        if (sm == s0)
            a = m;
        else
            b = m;
    }
    return b;
}

/* Where f changes sign on the interval (or may vanish at its end), its first root there guessed in
 * double and bracketed exactly (bracket_root); NAN otherwise. */
TTDW_FN double root_guess(ccd_state *s, const cop_info *ci, double ta, double tb)
{
    if (ci->never)
        return (double)NAN;
    if (!(ci->change || ci->end_zero)) {
        /* f too small for the rounded test (nearly coplanar motion): its exact signs. */
        if (!ci->undecided)
            return (double)NAN;
        const int s0 = f_sign_at(s, ta), s1 = f_sign_at(s, tb);
        if (s0 == 2 || s1 == 2 || s0 == 0 || !(s1 == 0 || s1 == -s0))
            return (double)NAN;
    }
    const ttd_ccd_xpoly *P = xpoly(s, 0);
    if (P->bad)
        return (double)NAN;
    return bracket_root(s, P, ta, tb, approx_first_root(P->a, ta, tb));
}

/* The first root in (ta, tb] of the quartic c0 + c1 t + ... + c4 t^4 (negative at ta) guessed in double:
 * the first of 16 equal pieces whose end is not negative, bisected. NAN if none. Only a guess. */
TTDW_FN double approx_first_rise(const double c[5], double ta, double tb)
{
    double a = ta;
    for (int i = 1; i <= 16; ++i) {
        double b = i == 16 ? tb : ta + (tb - ta) * (i / 16.0);
        const double fb = (((c[4] * b + c[3]) * b + c[2]) * b + c[1]) * b + c[0];
        if (!(fb < 0)) {
            for (int it = 0; it < 80; ++it) {
                const double m = 0.5 * (a + b);
                if (!(m > a && m < b))
                    break;
                const double fm = (((c[4] * m + c[3]) * m + c[2]) * m + c[1]) * m + c[0];
                if (fm < 0)
                    a = m;
                else
                    b = m;
            }
            return b;
        }
        a = b;
    }
    return (double)NAN;
}

/* Where f is about 0 on the interval (no root of it to cut at; motion close to coplanar), the time
 * before which no contact can come: a contact needs every contact condition >= 0, so where some are
 * negative at ta (exactly), the latest of their first roots, guessed in double and bracketed exactly
 * (bracket_root); NAN where none is negative at ta or one has no root guessed in the interval. At
 * most COND_CUTS a query; the cut's order only (the conditions' exact test then runs on the piece
 * before the root, which that condition's sign proves: try_conditions). */
enum { COND_CUTS = 8 };
TTDW_FN double cond_root(ccd_state *s, double ta, double tb)
{
    if (s->cond_cuts >= COND_CUTS)
        return (double)NAN;
    ++s->cond_cuts;
    const int nc = s->na == TTD_CCD_VF ? 3 : 4;
    double r = (double)NAN;
    for (int c = 0; c < nc; ++c) {
        const ttd_ccd_xpoly *P = xpoly(s, 1 + c);
        if (P->bad)
            return (double)NAN;
        if (ccdx_xpoly_sign_at(P, ta) != -1)
            continue;
        const double rc = bracket_root(s, P, ta, tb, approx_first_rise(P->a, ta, tb));
        if (!(rc > ta && rc <= tb))
            return (double)NAN;
        r = r > rc ? r : rc;
    }
    return r;
}

/* Edge-edge: whether the edges are parallel throughout the interval and their lines stay apart, in
 * double: the conditions' common factor ea x eb within about its rounding of 0 at ta, tm and tb (it is
 * quadratic in t, so about 0 all along), and the offset of b0 from a's line, perpendicular to it,
 * farther than `near` from 0 on the segment between its values at ta and tb. Every condition is then
 * about 0 and no contact is near, so a cut at a condition's root (cond_root) forms their exact
 * quartics to save almost no interval (docs/ccd-speed.md, the parallel-edges family). Parallel
 * edges whose lines meet (sliding along one line, as one kept slow query does) keep the cut, which
 * finds the contact there. A guess: it decides whether cond_root is tried, the order only. */
TTDW_FN int parallel_apart(const ccd_state *s, double xa[4][3], double xb[4][3], double tm, double S, double near)
{
    if (s->na != TTD_CCD_EE)
        return 0;
    double xm[4][3], w[2][3];
    positions(s, tm, xm);
    for (int e = 0; e < 3; ++e) {
        double(*x)[3] = e == 0 ? xa : (e == 1 ? xm : xb);
        double u[3], v[3], n[3], r[3];
        sub3(u, x[1], x[0]);
        sub3(v, x[3], x[2]);
        cross3(n, u, v);
        const double lu = fmax(fabs(u[0]), fmax(fabs(u[1]), fabs(u[2])));
        const double lv = fmax(fabs(v[0]), fmax(fabs(v[1]), fabs(v[2])));
        const double ln = fmax(fabs(n[0]), fmax(fabs(n[1]), fabs(n[2])));
        const double uu = dot3(u, u);
        if (!(ln <= 64 * U_ROUND * S * (lu + lv)) || !(uu > 0))
            return 0;
        if (e != 1) {
            sub3(r, x[2], x[0]);
            const double c = dot3(r, u) / uu;
            for (int k = 0; k < 3; ++k)
                w[e / 2][k] = r[k] - c * u[k];
        }
    }
    /* The distance from 0 to the segment w[0] w[1]. */
    double dw[3];
    sub3(dw, w[1], w[0]);
    const double dd = dot3(dw, dw);
    const double c = dd > 0 ? clamp01(-dot3(w[0], dw) / dd) : 0;
    double q[3];
    for (int k = 0; k < 3; ++k)
        q[k] = w[0][k] + c * dw[k];
    return sqrt(dot3(q, q)) > near;
}

/* Whether the conditions' exact test runs on the interval being tested: a final one (it would
 * otherwise be the hit), every one once a near miss was proved, and the piece before a cut at a
 * condition's root (the stretch that condition's sign proves). */
TTDW_FN int try_conditions(const ccd_state *s)
{
    return s->tb - s->ta <= s->t_tol || s->near_miss || (s->ta == s->cut_ta && s->tb == s->cut_lo);
}

/* The exact proofs of an interval free of contact at delta = 0 (ccd_exact.c): the coplanarity cubic
 * of one strict sign (where the rounding bound left it undecided), or a contact condition negative
 * throughout (where the rounded one may be). */
TTDW_FN int exact_free(ccd_state *s, const cop_info *ci, const int csign[4])
{
    /* The conditions only on an interval that would otherwise be the hit, and, once one proved such
     * an interval free (a near miss: the primitives slide past each other), on every interval. */
    if (ci->undecided && !(ci->end_zero && f_sign_at(s, s->tb) == 0)) {
        const int r = ccdx_xpoly_sign(xpoly(s, 0), s->ta, s->tb, ci->sgn);
        if (r == 1 || r == -1)
            return 1;
    }
    if (csign == NULL || !try_conditions(s))
        return 0;
    for (int c = 0; c < 4; ++c)
        if (csign[c] == -1 &&
            ccdx_xpoly_sign(xpoly(s, 1 + c), s->ta, s->tb, -1) == -1) {
            s->near_miss = 1;
            return 1;
        }
    return 0;
}

/* The directions' tests of an interval (the middle's closest points and features, a vertex pair's
 * pass direction, the start's); *d the distance computed at the middle. */
TTDW_FN int directions_separate(ccd_state *s, double xa[4][3], double xb[4][3], double tm, double delta, double *d)
{
    double xm[4][3], n1[3], n2[3], n3[3];
    int vv[2];
    positions(s, tm, xm);
    s->cand_g = -HUGE_VAL;
    *d = directions(s->na, xm, n1, n2, vv);
    if (separated_along(s, xa, xb, n1, delta) || separated_along(s, xa, xb, n2, delta))
        return 1;
    if (vv[0] >= 0) {
        pass_direction(s->in0, s->in1, vv[0], vv[1], n3);
        if (separated_along(s, xa, xb, n3, delta))
            return 1;
    }
    /* The closest direction at an end serves where the middle's cannot (a crossing). */
    directions(s->na, xa, n1, n2, vv);
    return separated_along(s, xa, xb, n1, delta) || separated_along(s, xa, xb, n2, delta);
}

/* ---- the proved-free prefix (docs/ccd.md, section 3, "t_stop") ---------------------------------
 * Where f changes sign on [ta, tb], the cut at its first root (root_guess) forms f exactly and
 * brackets the root, and the piece before the root is then tested: exact work that a search with
 * t_stop (mesh CCD) wastes when the root lies after t_stop. So before it, the stretch [ta, c] up to
 * a point c before the root guessed in double from the rounded Bernstein coefficients is tried
 * with the cheap certified tests; proved, [0, c] is free of contact (every time before ta already
 * was), and no later step may report a hit before c - t_tol (free_to in ccd_query_one); a second
 * step [c, c2] closer to the root follows. The same where f is about 0 and the search would go on
 * to f's exact tests and a cut at a condition's root (cond_root): the stretch before a condition's
 * first rise guessed in double, proved by that condition's rounded coefficients or the same cheap
 * tests; where no rise is guessed, a quarter of the interval, then its first half. Every search
 * does these steps, with or without t_stop (they read no t_stop but to stop, push no interval and
 * leave the state the later steps read as it was), so the intervals and the answers do not depend
 * on t_stop; a search with t_stop stops once free_to - t_tol is past it. */

/* The prefix's guess: the fraction u of [ta, tb] where the cubic with Bernstein coefficients B on
 * [ta, tb] first changes sign from B[0]'s, in double: the first of 8 equal pieces whose end differs
 * in sign, bisected 8 times (1/2048 of the interval, far finer than the 1/8 kept back); u is the
 * last point found of B[0]'s sign. NAN where none is found. */
TTDW_FN double prefix_cut(const double B[4])
{
    const double a[4] = {B[0], 3 * (B[1] - B[0]), 3 * (B[2] - 2 * B[1] + B[0]), B[3] - 3 * B[2] + 3 * B[1] - B[0]};
    const int neg = a[0] < 0;
    double lo = 0, hi = (double)NAN;
    for (int i = 1; i <= 8; ++i) {
        const double u = i / 8.0, v = ((a[3] * u + a[2]) * u + a[1]) * u + a[0];
        if ((v < 0) != neg || v == 0) {
            hi = u;
            break;
        }
        lo = u;
    }
    if (!(hi > 0))
        return (double)NAN;
    for (int it = 0; it < 8; ++it) {
        const double m = 0.5 * (lo + hi), v = ((a[3] * m + a[2]) * m + a[1]) * m + a[0];
        if ((v < 0) == neg && v != 0)
            lo = m;
        else
            hi = m;
    }
    return lo;
}

/* The quartic sum B[j] s^j (1 - s)^(4 - j) (a condition's, condition_bern) at s, in double. */
TTDW_FN double bern4_at(const double B[5], double s)
{
    const double r = 1 - s;
    return (((B[0] * r + B[1] * s) * r + B[2] * s * s) * r + B[3] * s * s * s) * r + B[4] * s * s * s * s;
}

/* The prefix's guess before a cut at a condition's root (cond_root), where f is about 0: for each
 * contact condition that seems negative from ta on (its first rounded Bernstein coefficient not
 * above the rounding bound, and it or the second below minus the bound: the layers' edges are
 * often parallel at ta, where every condition is about 0), the fraction of [ta, tb] before its
 * first rise, guessed in double as in prefix_cut (1 where none of the 8 pieces' ends is >= 0); the
 * latest of them, as cond_root takes the latest root, and *which its condition. NAN where no
 * condition seems negative. Only a guess: prefix_free proves the stretch or not. */
TTDW_FN double cond_prefix_cut(int na, double xa[4][3], double xb[4][3], double S, int *which)
{
    const int nc = na == TTD_CCD_VF ? 3 : 4;
    double best = (double)NAN;
    for (int c = 0; c < nc; ++c) {
        double B[5], bound;
        if (!condition_bern(ccd_form_pts(na, 1 + c), xa, xb, S, B, &bound) || !(B[0] <= bound) ||
            !(B[0] < -bound || B[1] < -bound))
            continue;
        double lo = 0, hi = (double)NAN;
        for (int i = 1; i <= 8; ++i) {
            const double u = i / 8.0;
            if (!(bern4_at(B, u) < 0)) {
                hi = u;
                break;
            }
            lo = u;
        }
        if (hi > 0) {
            for (int it = 0; it < 8; ++it) {
                const double m = 0.5 * (lo + hi);
                if (bern4_at(B, m) < 0)
                    lo = m;
                else
                    hi = m;
            }
        }
        if (!(best >= lo)) {
            best = lo;
            *which = c;
        }
    }
    return best;
}

/* Whether [a, c] (positions xa, xc) is certified free of contact at delta = 0 without an exact
 * test: contact condition `which` (when >= 0) below minus its rounding bound in every rounded
 * Bernstein coefficient (< 0 throughout: no contact, docs/ccd.md section 3), f of one strict sign
 * (rounded), or a direction's test (directions_separate). s's candidate for the exact test is left
 * as found. */
TTDW_FN int prefix_free(ccd_state *s, double xa[4][3], double xc[4][3], double a, double c, double S, int which)
{
    if (which >= 0) {
        double B[5], bound;
        if (condition_bern(ccd_form_pts(s->na, 1 + which), xa, xc, S, B, &bound) && B[0] < -bound &&
            B[1] < -bound && B[2] < -bound && B[3] < -bound && B[4] < -bound)
            return 1;
    }
    cop_info ci;
    never_coplanar(s->na, xa, xc, S, &ci);
    if (ci.never)
        return 1;
    const double cand_g = s->cand_g, cand_n[3] = {s->cand_n[0], s->cand_n[1], s->cand_n[2]};
    double d;
    const int apart = directions_separate(s, xa, xc, 0.5 * (a + c), 0.0, &d);
    s->cand_g = cand_g;
    memcpy(s->cand_n, cand_n, sizeof cand_n);
    return apart;
}

/* The prefix's steps on [ta, tb]: [ta, c], then [c, c2] (where ta < c < c2 < tb), each tried by
 * prefix_free; returns the end of the stretch from ta proved free, free_to where none. Stops after
 * the first step where that already passes the search's stop (t_stop's promise: below). */
TTDW_FN double prefix_steps(ccd_state *s, double xa[4][3], double ta, double tb, double c, double c2, double S,
                            int which, double free_to, const ttd_ccd_params *p)
{
    if (!(c > ta && c < tb && c > free_to))
        return free_to;
    double xc[4][3], xd[4][3];
    positions(s, c, xc);
    if (!prefix_free(s, xa, xc, ta, c, S, which))
        return free_to;
    if (c - p->t_stop > 4 * p->t_tol || !(c2 > c && c2 < tb))
        return c;
    positions(s, c2, xd);
    return prefix_free(s, xc, xd, c, c2, S, which) ? c2 : c;
}

/* Whether a point of A and a point of B are equal in the 12 coordinates x (exactly): the primitives
 * touch there. */
TTDW_FN int points_coincide(int na, const double x[12])
{
    for (int i = 0; i < na; ++i)
        for (int j = na; j < 4; ++j)
            if (x[3 * i] == x[3 * j] && x[3 * i + 1] == x[3 * j + 1] && x[3 * i + 2] == x[3 * j + 2])
                return 1;
    return 0;
}

/* The query's state from its inputs: the motions, S (the largest coordinate magnitude) and e_gap. */
TTDW_FN double state_init(ccd_state *s, int kind, const double x0[12], const double x1[12], double t_tol)
{
    s->na = kind;
    s->in0 = x0;
    s->in1 = x1;
    s->t_tol = t_tol;
    s->near_miss = 0;
    s->cond_cuts = 0;
    s->cut_ta = s->cut_lo = (double)NAN;
    memset(s->made, 0, sizeof s->made);
    s->last_t = (double)NAN;
    s->last_sign = 2;
    double S = 0;
    for (int i = 0; i < 4; ++i)
        for (int k = 0; k < 3; ++k) {
            s->x0[i][k] = x0[3 * i + k];
            s->dx[i][k] = x1[3 * i + k] - x0[3 * i + k];
            S = fmax(S, fmax(fabs(x0[3 * i + k]), fabs(x1[3 * i + k])));
        }
    /* Positions within 5uS; a projection on n (|n_k| <= 1) adds 3.01u sum |n_k x_k| <= 9.1uS and
     * carries 3 x 5uS of position error: 25uS each, 50uS for the difference of two, rounded up
     * to 64uS; the absolute term covers products that underflow (docs/ccd.md, section 3). */
    s->e_gap = 64 * U_ROUND * S + 0x1p-1000;
    return S;
}

/* ttd_ccd_screen (ccd/ccd.h). */
TTDW_CALL int ccd_screen_one(int kind, const double x0[12], const double x1[12], double delta, double t_max)
{
    for (int i = 0; i < 12; ++i)
        if (!isfinite(x0[i]) || !isfinite(x1[i]))
            return 0;
    ccd_state s;
    const double S = state_init(&s, kind, x0, x1, TTD_CCD_DEFAULT_T_TOL);
    if (!(S < TTD_CCD_SCREEN_MAX))
        return 0;
    double xa[4][3], xb[4][3], xm[4][3], n1[3], n2[3];
    int vv[2];
    s.ta = 0.0;
    s.tb = t_max;
    s.cand_g = -HUGE_VAL;
    positions(&s, 0.0, xa);
    positions(&s, t_max, xb);
    if (delta == 0) {
        cop_info ci;
        never_coplanar(s.na, xa, xb, S, &ci);
        if (ci.never)
            return 1;
    }
    positions(&s, 0.5 * (0.0 + t_max), xm);
    directions(s.na, xm, n1, n2, vv);
    return separated_along(&s, xa, xb, n1, delta) || separated_along(&s, xa, xb, n2, delta);
}

/* The search's stack of open intervals (ccd_query_one): [a, b] pushed on top. */
TTDW_FN void push_interval(double *st_ta, double *st_tb, int *top, double a, double b)
{
    st_ta[*top] = a;
    st_tb[*top] = b;
    ++*top;
}

/* [a, b] split at m: the later piece pushed first, so that the earlier one is on top. */
TTDW_FN void push_split(double *st_ta, double *st_tb, int *top, double a, double m, double b)
{
    push_interval(st_ta, st_tb, top, m, b);
    push_interval(st_ta, st_tb, top, a, m);
}

/* ttd_ccd_query (ccd/ccd.h): the search of one query. */
TTDW_CALL void ccd_query_one(int kind, const double x0[12], const double x1[12], const ttd_ccd_params *p,
                           ttd_ccd_result *out)
{
    ccd_state s;
    const double S = state_init(&s, kind, x0, x1, p->t_tol);
    const double delta = p->delta;

    out->hit = 0;
    out->flags = 0;
    out->toi = HUGE_VAL;
    out->gap = HUGE_VAL;
    out->evals = 0;

    /* The stack of intervals still open, the earliest on top; each keeps its end positions. */
    enum { STACK = 128 };
    double st_ta[STACK], st_tb[STACK];
    double xa[4][3], xb[4][3], xm[4][3];
    int top = 0;
    st_ta[0] = 0.0;
    st_tb[0] = p->t_max;
    top = 1;
    /* A point of A on a point of B at t_max = 1, exactly (a vertex reaching a vertex at the end):
     * the contact there is certain, so the final interval [1 - t_tol, 1] is cut off at once and
     * [0, 1 - t_tol] searched first; reached, the final piece is the hit without a test (no test
     * could prove it free: it holds a contact). The answer is the one the halving would give. */
    double end_cert = (double)NAN;
    if (p->t_max == 1 && p->t_tol < 0.5 && points_coincide(s.na, x1)) {
        double lo = 1 - p->t_tol;
        while (1 - lo > p->t_tol)
            lo = nextafter(lo, 1.0);
        if (lo > 0 && lo < 1) {
            st_ta[0] = lo;
            st_tb[0] = 1;
            st_ta[1] = 0;
            st_tb[1] = lo;
            top = 2;
            end_cert = lo;
        }
    }
    int evals = 0, probes = 0, end_probes = 0;
    /* [0, free_to] proved free of contact by a prefix (prefix_free): an interval inside it that
     * is not proved again is dropped, not a hit, and a hit's toi is at least free_to, except a
     * contact's (jump_to_root, the final pieces), which lies after it and so starts after
     * free_to - t_tol. */
    double free_to = -HUGE_VAL;
    /* Prefixes tried where f is about 0 (below): at most 2 a query, since they serve a search with
     * t_stop at its first intervals; deeper down the whole search would pay for them alone. */
    enum { COND_PREFIXES = 2 };
    int cond_prefixes = 0;
    enum { PROBES = 2, END_PROBES = 2 };
    double cert_ta = 1, cert_tb = 0; /* an interval certain to hold a contact (none yet) */
    while (top > 0) {
        const double ta = st_ta[top - 1], tb = st_tb[top - 1];
        if (ta > p->t_stop)
            break; /* every open interval starts after t_stop (the earliest is on top) */
        if (evals >= p->max_evals) {
            /* Out of budget: answer hit at the earliest interval not yet separated. */
            out->hit = 1;
            out->flags |= TTD_CCD_BUDGET;
            out->toi = ta < free_to ? free_to : ta;
            positions(&s, 0.5 * (ta + tb), xm);
            double n1[3], n2[3];
            int vv[2];
            out->gap = directions(s.na, xm, n1, n2, vv);
            break;
        }
        --top;
        ++evals;
        s.ta = ta;
        s.tb = tb;
        positions(&s, ta, xa);
        positions(&s, tb, xb);
        const double tm = 0.5 * (ta + tb);
        if (ta == 0 && points_coincide(s.na, x0)) {
            /* A point of A on a point of B at t = 0, exactly: distance 0 <= delta there, so toi = 0,
             * the true first time, with nothing to search. */
            double n1[3], n2[3];
            int vv[2];
            out->hit = 1;
            out->toi = 0;
            out->gap = directions(s.na, xa, n1, n2, vv);
            break;
        }
        if (ta == end_cert && tb == 1) {
            double n1[3], n2[3];
            int vv[2];
            positions(&s, tm, xm);
            out->hit = 1;
            out->toi = ta;
            out->gap = directions(s.na, xm, n1, n2, vv);
            break;
        }
        double d = HUGE_VAL, root = (double)NAN;
        int from_cond = 0; /* root is a condition's (cond_root) */
        if (delta == 0) {
            cop_info ci;
            never_coplanar(s.na, xa, xb, S, &ci);
            if (ci.never)
                continue;
            if (ci.change && !(ta >= cert_ta && tb <= cert_tb)) {
                const double u = prefix_cut(ci.B);
                free_to = prefix_steps(&s, xa, ta, tb, ta + (tb - ta) * (0.875 * u), ta + (tb - ta) * (0.984375 * u), S,
                                       -1, free_to, p);
                if (free_to - p->t_stop > 4 * p->t_tol)
                    break; /* every hit would start after t_stop (t_stop's promise, ccd.h) */
            }
            if (ta >= cert_ta && tb <= cert_tb) {
                /* Inside a certified interval only f's roots matter. */
                if (exact_free(&s, &ci, NULL))
                    continue;
                root = root_guess(&s, &ci, ta, tb);
                goto split;
            }
            int csign[4] = {0, 0, 0, 0};
            if ((ci.change || (ci.end_zero && f_sign_at(&s, tb) == 0)) && conditions(s.na, xa, xb, S, csign)) {
                /* A contact in [ta, tb] for sure (f has a root there, the conditions hold
                 * throughout): the first one is f's first root; no direction can separate. */
                cert_ta = ta;
                cert_tb = tb;
                double toi;
                if (jump_to_root(&s, ta, tb, !ci.change, &toi)) {
                    out->hit = 1;
                    out->toi = toi;
                    double n1[3], n2[3], xt[4][3];
                    int vv[2];
                    positions(&s, toi, xt);
                    out->gap = directions(s.na, xt, n1, n2, vv);
                    break;
                }
                root = root_guess(&s, &ci, ta, tb);
                goto split;
            }
            if (directions_separate(&s, xa, xb, tm, delta, &d))
                continue;
            /* f about 0 (no root of it to cut at): the prefix before a condition's root, before the
             * exact work that a cut there (cond_root) or f's exact tests would do. */
            if (ci.undecided && !ci.end_zero && tb - ta > 4 * p->t_tol && cond_prefixes < COND_PREFIXES) {
                ++cond_prefixes;
                int which = -1;
                const double u = cond_prefix_cut(s.na, xa, xb, S, &which);
                if (u > 0)
                    free_to = prefix_steps(&s, xa, ta, tb, ta + (tb - ta) * (0.875 * u), ta + (tb - ta) * (0.984375 * u),
                                           S, which, free_to, p);
                else /* no root guessed (edges parallel at ta: every condition 0 there): a quarter, a half */
                    free_to = prefix_steps(&s, xa, ta, tb, ta + 0.25 * (tb - ta), tm, S, -1, free_to, p);
                if (free_to - p->t_stop > 4 * p->t_tol)
                    break; /* as above */
            }
            /* The candidate direction's exact test before the polynomials' (it needs no expansion
             * of f or of a condition formed, which the tests below may form for nothing). */
            if (s.cand_g > -HUGE_VAL && exact_separated(x0, x1, s.na, ta, tb, s.cand_n))
                continue;
            s.cand_g = -HUGE_VAL; /* tried */
            if (!(ci.change || ci.end_zero) && try_conditions(&s))
                conditions(s.na, xa, xb, S, csign); /* for the exact test: not formed above */
            if (exact_free(&s, &ci, csign))
                continue;
            root = root_guess(&s, &ci, ta, tb);
            if (!(root > ta && root <= tb) && ci.undecided && tb - ta > 4 * p->t_tol &&
                !parallel_apart(&s, xa, xb, tm, S, 4 * s.e_gap)) {
                root = cond_root(&s, ta, tb);
                from_cond = root > ta && root <= tb;
            }
        } else if (directions_separate(&s, xa, xb, tm, delta, &d)) {
            continue;
        }
        if (s.cand_g > -HUGE_VAL && exact_separated(x0, x1, s.na, ta, tb, s.cand_n))
            continue;
    split:
        if (tb - ta <= p->t_tol || !(tm > ta && tm < tb) || top + 2 > STACK) {
            if (tb <= free_to)
                continue; /* inside the proved prefix: free */
            out->hit = 1;
            out->toi = ta < free_to ? free_to : ta;
            if (d == HUGE_VAL) {
                double n1[3], n2[3];
                int vv[2];
                positions(&s, tm, xm);
                d = directions(s.na, xm, n1, n2, vv);
            }
            out->gap = d;
            break;
        }
        /* The distances at the ends where a probe may use them (below), in double. */
        const int may_probe = !(root > ta && root <= tb) && tb - ta > 4 * p->t_tol && top + 2 <= STACK;
        const double near = delta + 4 * s.e_gap;
        double d_ta = HUGE_VAL, d_tb = HUGE_VAL;
        if (may_probe && (probes < PROBES || end_probes < END_PROBES)) {
            double n1[3], n2[3];
            int vv[2];
            d_ta = directions(s.na, xa, n1, n2, vv);
            d_tb = directions(s.na, xb, n1, n2, vv);
        }
        /* Where the primitives seem in contact at tb (the distance there within the rounding bound:
         * a contact at the query's end, as when a vertex reaches a vertex at t = 1), tb's final
         * interval [tb - t_tol, tb] is cut off: the rest ends where the primitives are apart, so a
         * direction's exact test can prove it whole, or its later part, where halving toward tb
         * would take about 50 levels (two intervals each) to reach t_tol; at most END_PROBES a query
         * (the order of the pieces only). */
        if (may_probe && d_tb <= near && d_ta > near && end_probes < END_PROBES) {
            double lo = tb - p->t_tol;
            while (tb - lo > p->t_tol)
                lo = nextafter(lo, tb);
            if (lo > ta && lo < tb) {
                ++end_probes;
                push_split(st_ta, st_tb, &top, ta, lo, tb);
                continue;
            }
        }
        /* Where the primitives seem in contact at ta or all along (the distance at ta or at the
         * middle within the rounding bound, and no root to cut at), the contact is likely at ta
         * already: its final interval [ta, ta + t_tol] first, then the rest (at most PROBES a query;
         * the order only). */
        if (may_probe && (d <= 4 * s.e_gap || d_ta <= near) && probes < PROBES) {
            double hi = ta + p->t_tol;
            while (hi - ta > p->t_tol)
                hi = nextafter(hi, ta);
            if (hi > ta && hi < tb) {
                ++probes;
                push_split(st_ta, st_tb, &top, ta, hi, tb);
                continue;
            }
        }
        /* Where f seems to have a root, the interval is cut at it: [ta, lo], [lo, lo + t_tol] and
         * the rest, so that the stretch before the root is tried whole and the contact (or the near
         * miss) is met in one step rather than after bisecting to t_tol (the order, earliest on
         * top, and so every guarantee, is that of the halves). */
        if (root > ta && root <= tb && tb - ta > 4 * p->t_tol && top + 3 <= STACK) {
            double lo = root - 0.5 * p->t_tol, hi = lo + p->t_tol;
            if (hi >= tb) {
                hi = tb;
                lo = tb - p->t_tol;
            }
            while (hi - lo > p->t_tol)
                lo = nextafter(lo, hi);
            if (lo > ta && hi > lo) {
                if (hi < tb)
                    push_interval(st_ta, st_tb, &top, hi, tb);
                push_split(st_ta, st_tb, &top, ta, lo, hi);
                if (from_cond) {
                    s.cut_ta = ta;
                    s.cut_lo = lo;
                }
                continue;
            }
        }
        push_split(st_ta, st_tb, &top, ta, tm, tb); /* the halves */
    }
    out->evals = (uint32_t)evals;
}

#undef U_ROUND

#endif /* TTD_CCD_CCD_SEARCH_IMPL_H */

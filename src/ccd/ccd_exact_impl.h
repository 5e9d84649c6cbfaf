/* SPDX-License-Identifier: MIT */
/* Exact Bernstein signs of the search's polynomials (ccd_exact.h; docs/ccd.md, section 3), one
 * source for the CPU (ccd.c includes it through ccd_search_impl.h) and the device (src/gpu/gpu_ccd.cu):
 * every function TTDW_FN (__host__ __device__ under nvcc, static inline in C), nothing allocated, no
 * recursion, every array bounded (an expansion longer than TTD_CCD_XE_CAP terms marks the
 * polynomial bad, and its callers then take the untrusted answer 2: docs/ccd.md, section 14).
 *
 * A polynomial p(t) = F(v_0(t), ..., v_{m-1}(t)), F multilinear and each v_k affine in t, has on
 * [ta, tb] the Bernstein coefficients b_j = (1 / C(m, j)) sum over the sets K of j slots of
 * F(v_k(tb) for k in K, v_k(ta) otherwise) (the blossom), and p lies in their convex hull there.
 * So when all b_j have one strict sign, so has p on the whole interval. Each F(...) is a sum of
 * products of the inputs and the two doubles ta, tb, which is formed exactly as a floating-point
 * expansion (Shewchuk's nonoverlapping sums of doubles: each product split into two doubles by
 * fma, each sum by the error-free two_sum); its sign is the sign of its largest term. */
#ifndef TTD_CCD_CCD_EXACT_IMPL_H
#define TTD_CCD_CCD_EXACT_IMPL_H

#include <math.h>

#include "ccd/ccd_exact.h"

/* TTDW_FN: the qualifiers of functions that the CPU and a CUDA kernel share. */
#include "core/device_fn.h"
/* The search's large functions: called, not inlined, on the device (each inlined copy of a query's
 * search costs nvcc minutes and the thread's stack frame grows with it); static inline in C. */
#ifndef TTDW_CALL
#if defined(__CUDACC__)
#define TTDW_CALL static __host__ __device__ __noinline__
#else
#define TTDW_CALL static inline
#endif
#endif

/* The number of bits set in a 4-bit mask. */
TTDW_FN int ccdx_popcount4(int m)
{
    return (m & 1) + ((m >> 1) & 1) + ((m >> 2) & 1) + ((m >> 3) & 1);
}

/* An expansion: nonoverlapping doubles in increasing magnitude, their exact sum the value. */
enum { XE_CAP = TTD_CCD_XE_CAP };
typedef ttd_ccd_xe xe;

TTDW_FN void ccdx_two_sum(double a, double b, double *s, double *e)
{
    const double x = a + b, bv = x - a, av = x - bv;
    *s = x;
    *e = (a - av) + (b - bv);
}

/* x += q exactly (Shewchuk's grow-expansion with zero elimination, which keeps the expansion
 * nonoverlapping and ordered for any q). */
TTDW_FN void xe_grow(xe *x, double q)
{
    if (q == 0)
        return;
    if (!isfinite(q)) {
        x->bad = 1;
        return;
    }
    int k = 0;
    for (int j = 0; j < x->n; ++j) {
        double s, e;
        ccdx_two_sum(q, x->v[j], &s, &e);
        q = s;
        if (e != 0)
            x->v[k++] = e;
    }
    if (q != 0)
        x->v[k++] = q;
    x->n = k;
    if (k > XE_CAP) {
        x->bad = 1;
        x->n = XE_CAP;
    }
}

/* x += s a b exactly (s = +-1): each product of two terms split into two doubles by fma, exact
 * unless its rounding error falls below the normal range (then x is marked bad). */
TTDW_FN void xe_mul_acc(xe *x, const xe *a, const xe *b, double s)
{
    x->bad |= a->bad | b->bad;
    for (int i = 0; i < a->n; ++i)
        for (int j = 0; j < b->n; ++j) {
            const double ai = s * a->v[i], p = ai * b->v[j];
            if (!(fabs(p) >= 0x1p-960))
                x->bad = 1;
            xe_grow(x, fma(ai, b->v[j], -p));
            xe_grow(x, p);
        }
}

/* Rewrites x with fewer, non-adjacent terms and the same value (Shewchuk's compression: a sweep down
 * from the largest term, then one up, each with the error-free fast two-sum). */
TTDW_FN void xe_compress(xe *x)
{
    if (x->n < 2)
        return;
    double *e = x->v;
    const int n = x->n;
    double h[XE_CAP + 2];
    int bottom = n - 1;
    double Q = e[bottom];
    for (int i = n - 2; i >= 0; --i) {
        const double Qn = Q + e[i], q = e[i] - (Qn - Q);
        if (q != 0) {
            h[bottom--] = Qn;
            Q = q;
        } else {
            Q = Qn;
        }
    }
    int top = 0;
    for (int i = bottom + 1; i < n; ++i) {
        const double Qn = h[i] + Q, q = Q - (Qn - h[i]);
        if (q != 0)
            e[top++] = q;
        Q = Qn;
    }
    e[top++] = Q;
    x->n = top;
}

TTDW_FN void xe_add(xe *x, const xe *a)
{
    x->bad |= a->bad;
    for (int i = 0; i < a->n; ++i)
        xe_grow(x, a->v[i]);
}

TTDW_FN int xe_sign(const xe *x)
{
    return x->n == 0 ? 0 : (x->v[x->n - 1] > 0 ? 1 : -1);
}

/* r = s x exactly (r may not be x), compressed. */
TTDW_FN void xe_scale(xe *r, const xe *x, double s)
{
    r->n = 0;
    r->bad = x->bad;
    for (int i = 0; i < x->n; ++i) {
        const double p = x->v[i] * s;
        if (s != 0 && !(fabs(p) >= 0x1p-960))
            r->bad = 1;
        xe_grow(r, fma(x->v[i], s, -p));
        xe_grow(r, p);
    }
    xe_compress(r);
}

/* Point i minus point j as p + t q, exactly: p = x0_i - x0_j, q = x1_i - x0_i - x1_j + x0_j. */
TTDW_FN void diff_line(xe p[3], xe q[3], const double x0[12], const double x1[12], int i, int j)
{
    for (int k = 0; k < 3; ++k) {
        p[k].n = p[k].bad = q[k].n = q[k].bad = 0;
        xe_grow(&p[k], x0[3 * i + k]);
        xe_grow(&p[k], -x0[3 * j + k]);
        xe_grow(&q[k], x1[3 * i + k]);
        xe_grow(&q[k], -x0[3 * i + k]);
        xe_grow(&q[k], -x1[3 * j + k]);
        xe_grow(&q[k], x0[3 * j + k]);
        xe_compress(&q[k]);
    }
}

TTDW_FN void cross_x(xe r[3], const xe a[3], const xe b[3])
{
    for (int k = 0; k < 3; ++k) {
        const int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
        r[k].n = 0;
        r[k].bad = 0;
        xe_mul_acc(&r[k], &a[k1], &b[k2], 1.0);
        xe_mul_acc(&r[k], &a[k2], &b[k1], -1.0);
        xe_compress(&r[k]);
    }
}

TTDW_FN void dot_x(xe *r, const xe a[3], const xe b[3])
{
    r->n = 0;
    r->bad = 0;
    for (int k = 0; k < 3; ++k)
        xe_mul_acc(r, &a[k], &b[k], 1.0);
}

TTDW_CALL void ccdx_xpoly_make(ttd_ccd_xpoly *P, int form, const int pts[4][2], const double x0[12], const double x1[12])
{
    const int m = form == TTD_CCD_FORM_DET ? 3 : 4;
    P->deg = m;
    P->bad = 0;
    for (int j = 0; j <= 4; ++j)
        P->c[j].n = P->c[j].bad = 0;
    /* Degree-4 products of coordinates up to 2^200 stay far from overflow; below, products that
     * underflow mark the expansion bad. */
    for (int i = 0; i < 12; ++i)
        if (!(fabs(x0[i]) < 0x1p200 && fabs(x1[i]) < 0x1p200)) {
            P->bad = 1;
            return;
        }
    /* v_k(t) = p_k + t q_k; the form is multilinear, so the coefficient of t^j sums its values
     * over the choices of q in j of the slots. */
    xe v[4][2][3];
    for (int k = 0; k < m; ++k)
        diff_line(v[k][0], v[k][1], x0, x1, pts[k][0], pts[k][1]);
    xe c01[2][2][3], c23[2][2][3];
    for (int e0 = 0; e0 < 2; ++e0)
        for (int e1 = 0; e1 < 2; ++e1) {
            cross_x(c01[e0][e1], v[0][e0], v[1][e1]);
            if (m == 4)
                cross_x(c23[e0][e1], v[2][e0], v[3][e1]);
        }
    for (int mask = 0; mask < (1 << m); ++mask) {
        const int e0 = mask & 1, e1 = (mask >> 1) & 1, e2 = (mask >> 2) & 1, e3 = (mask >> 3) & 1;
        xe val;
        if (m == 3)
            dot_x(&val, c01[e0][e1], v[2][e2]);
        else
            dot_x(&val, c01[e0][e1], c23[e2][e3]);
        xe_add(&P->c[ccdx_popcount4(mask)], &val);
    }
    for (int j = 0; j <= 4; ++j) {
        xe_compress(&P->c[j]);
        P->bad |= P->c[j].bad;
        /* Summed from the smallest term up: within 2u of the exact coefficient (4u is used). */
        double sum = 0;
        for (int i = 0; i < P->c[j].n; ++i)
            sum += P->c[j].v[i];
        P->a[j] = sum;
    }
}

/* p(t)'s sign from the rounded coefficients where their error and Horner's rounding cannot change
 * it (4u |c_k| each, gamma_8 < 8.1u of sum |a_k| |t|^k for Horner, 32u used), else 0. */
TTDW_FN int approx_sign(const ttd_ccd_xpoly *P, double t)
{
    double v = P->a[P->deg], m = fabs(P->a[P->deg]);
    const double at = fabs(t);
    for (int k = P->deg - 1; k >= 0; --k) {
        v = v * t + P->a[k];
        m = m * at + fabs(P->a[k]);
    }
    const double bound = 32 * 0x1p-53 * m + 0x1p-1000;
    return v > bound ? 1 : (v < -bound ? -1 : 0);
}

/* r = p(t) exactly, by Horner's rule. */
TTDW_CALL void xpoly_value(const ttd_ccd_xpoly *P, double t, xe *r)
{
    *r = P->c[P->deg];
    for (int k = P->deg - 1; k >= 0; --k) {
        xe s;
        xe_scale(&s, r, t);
        xe_add(&s, &P->c[k]);
        xe_compress(&s);
        *r = s;
    }
}

TTDW_FN int ccdx_xpoly_sign_at(const ttd_ccd_xpoly *P, double t)
{
    if (P->bad)
        return 2;
    const int sa = approx_sign(P, t);
    if (sa != 0)
        return sa;
    xe r;
    xpoly_value(P, t, &r);
    return r.bad ? 2 : xe_sign(&r);
}

TTDW_CALL int ccdx_xpoly_sign(const ttd_ccd_xpoly *P, double ta, double tb, int want)
{
    if (P->bad)
        return 2;
    const int d = P->deg;
    /* b_0 = p(ta) and b_d = p(tb) first: they usually tell a "no". */
    const int s0 = ccdx_xpoly_sign_at(P, ta);
    if (s0 == 2)
        return 2;
    if (want == 0)
        want = s0; /* either sign: the one of p(ta) */
    if (want == 0 || s0 != want)
        return 0;
    const int s1 = ccdx_xpoly_sign_at(P, tb);
    if (s1 == 2)
        return 2;
    if (s1 != want)
        return 0;
    /* The Taylor coefficients at ta (repeated synthetic division), then of s -> p(ta + h s) on
     * [0, 1] (times h^k, h = tb - ta as two doubles), then the Bernstein coefficients
     * b_j = sum_k C(j,k) / C(d,k) a_k h^k, times L = 3 (d = 3) or 12 (d = 4) to keep the weights
     * integers. */
    double h, hl;
    ccdx_two_sum(tb, -ta, &h, &hl); /* h + hl = tb - ta exactly */
    xe a[5];
    for (int k = 0; k <= d; ++k)
        a[k] = P->c[k];
    for (int i = 0; i < d; ++i)
        for (int k = d - 1; k >= i; --k) {
            xe s;
            xe_scale(&s, &a[k + 1], ta);
            xe_add(&s, &a[k]);
            xe_compress(&s);
            a[k] = s;
        }
    for (int k = 1; k <= d; ++k)
        for (int i = 0; i < k; ++i) {
            xe s, sl;
            xe_scale(&s, &a[k], h);
            if (hl != 0) {
                xe_scale(&sl, &a[k], hl);
                xe_add(&s, &sl);
                xe_compress(&s);
            }
            a[k] = s;
        }
    const double binom[5][5] = {{1}, {1, 1}, {1, 2, 1}, {1, 3, 3, 1}, {1, 4, 6, 4, 1}};
    const double L = d == 3 ? 3 : 12;
    for (int j = 1; j < d; ++j) {
        xe b = {0, 0, {0}};
        for (int k = 0; k <= j; ++k) {
            xe s;
            xe_scale(&s, &a[k], L * binom[j][k] / binom[d][k]);
            xe_add(&b, &s);
        }
        if (b.bad)
            return 2;
        if (xe_sign(&b) != want)
            return 0;
    }
    return want;
}

#endif /* TTD_CCD_CCD_EXACT_IMPL_H */

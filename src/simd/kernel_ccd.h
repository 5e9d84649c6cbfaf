/* SPDX-License-Identifier: MIT */
/* The continuous-collision screen in lanes (core/kernels.h, ccd_screen; docs/ccd.md, section 11):
 * one query per lane, the certified tests that ccd/ccd.c's ttd_ccd_screen runs on a query's first
 * interval [0, t_max], computed with the same operations in the same order, so every row (and the
 * one-lane cuda-host row) proves exactly the queries that the scalar screen proves:
 *  - delta = 0: the coplanarity cubic's four Bernstein coefficients beyond their rounding bound,
 *    all of one sign (ccd.c's never_coplanar);
 *  - the separation of the projections along n1, the closest points' difference at t_max / 2, and
 *    along n2, the closest features' direction there (ccd.c's directions and separated_along).
 * Branches of the scalar code (the Voronoi regions of the point-triangle walk, the clamping cases
 * of the segments' closest points) are computed for every lane and merged in the scalar order of
 * priority. A proved lane's query has no contact (the batch writes its answer at once); the rest
 * go to the scalar search. Double rows only: both precisions' entries widen to double. */
#include <float.h>
#include <math.h>

#ifdef TTD_PRECISION_DOUBLE

typedef ttdw_vd ccdw3[3];

TTDW_FN void ccdw_sub(ccdw3 r, const ccdw3 a, const ccdw3 b)
{
    r[0] = a[0] - b[0];
    r[1] = a[1] - b[1];
    r[2] = a[2] - b[2];
}

TTDW_FN ttdw_vd ccdw_dot(const ccdw3 a, const ccdw3 b)
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

TTDW_FN void ccdw_cross(ccdw3 r, const ccdw3 a, const ccdw3 b)
{
    r[0] = a[1] * b[2] - a[2] * b[1];
    r[1] = a[2] * b[0] - a[0] * b[2];
    r[2] = a[0] * b[1] - a[1] * b[0];
}

TTDW_FN ttdw_vd ccdw_det(const ccdw3 u, const ccdw3 v, const ccdw3 w)
{
    ccdw3 c;
    ccdw_cross(c, u, v);
    return ccdw_dot(c, w);
}

/* m ? a : b for 3-vectors, into r. */
TTDW_FN void ccdw_sel3(ccdw3 r, ttdw_md m, const ccdw3 a, const ccdw3 b)
{
    for (int k = 0; k < 3; ++k)
        r[k] = ttdw_sel_d(m, a[k], b[k]);
}

/* x > 0 ? (x < 1 ? x : 1) : 0 (NaN gives 0, as in the scalar clamp). */
TTDW_FN ttdw_vd ccdw_clamp01(ttdw_vd x)
{
    const ttdw_vd one = ttdw_set1_d(1.0), zero = ttdw_zero_d();
    return ttdw_sel_d(ttdw_gt_d(x, zero), ttdw_sel_d(ttdw_lt_d(x, one), x, one), zero);
}

/* ccd.c's perp: e x ((p - u) x e), e = v - u. */
TTDW_FN void ccdw_perp(ccdw3 n, const ccdw3 p, const ccdw3 u, const ccdw3 v)
{
    ccdw3 e, w, c;
    ccdw_sub(e, v, u);
    ccdw_sub(w, p, u);
    ccdw_cross(c, w, e);
    ccdw_cross(n, e, c);
}

/* ccd.c's never_coplanar, its `never` alone. */
TTDW_FN ttdw_md ccdw_never_coplanar(int na, ccdw3 xa[4], ccdw3 xb[4], ttdw_vd S)
{
    static const int pick[2][4] = {{1, 2, 3, 0}, {0, 1, 2, 3}};
    const int *k = pick[na - 1];
    ccdw3 w[2][3];
    ttdw_vd V = ttdw_zero_d();
    for (int e = 0; e < 2; ++e)
        for (int j = 0; j < 3; ++j) {
            ccdw_sub(w[e][j], e ? xb[k[j + 1]] : xa[k[j + 1]], e ? xb[k[0]] : xa[k[0]]);
            V = ttdw_max_d(V, ccdw_dot(w[e][j], w[e][j]));
        }
    const ttdw_vd ec = ttdw_set1_d(12 * 0x1p-53) * S, en = ttdw_set1_d(1.7321) * ec;
    V = ttdw_sqrt_d(V) * ttdw_set1_d(1 + 4 * 0x1p-53) + en;
    const ttdw_md ok = ttdw_mand_d(ttdw_gt_d(V, ttdw_set1_d(0x1p-300)), ttdw_lt_d(V, ttdw_set1_d(0x1p300)));
    const ttdw_vd err = (ttdw_set1_d(3.0) * en * V * V + ttdw_set1_d(64 * 0x1p-53) * V * V * V) *
                            ttdw_set1_d(1 + 0x1p-40) +
                        ttdw_set1_d(0x1p-1000);
    ttdw_vd B[4];
    const ttdw_vd third = ttdw_set1_d(3.0);
    B[0] = ccdw_det(w[0][0], w[0][1], w[0][2]);
    B[3] = ccdw_det(w[1][0], w[1][1], w[1][2]);
    B[1] = (ccdw_det(w[1][0], w[0][1], w[0][2]) + ccdw_det(w[0][0], w[1][1], w[0][2]) +
            ccdw_det(w[0][0], w[0][1], w[1][2])) / third;
    B[2] = (ccdw_det(w[1][0], w[1][1], w[0][2]) + ccdw_det(w[1][0], w[0][1], w[1][2]) +
            ccdw_det(w[0][0], w[1][1], w[1][2])) / third;
    ttdw_md pos = ok, neg = ok;
    for (int i = 0; i < 4; ++i) {
        const ttdw_vd e = err + ttdw_set1_d(0x1p-51) * ttdw_abs_d(B[i]);
        pos = ttdw_mand_d(pos, ttdw_gt_d(B[i], e));
        neg = ttdw_mand_d(neg, ttdw_lt_d(B[i], -e));
    }
    return ttdw_mor_d(pos, neg);
}

/* ccd.c's directions at positions x: n1 (the closest points' difference) and n2 (zero where the
 * closest features are two points). */
TTDW_FN void ccdw_directions(int na, ccdw3 x[4], ccdw3 n1, ccdw3 n2)
{
    const ttdw_vd zero = ttdw_zero_d(), one = ttdw_set1_d(1.0);
    ccdw3 q, cand;
    if (na == 1) {
        /* closest_point_triangle(p = x0, a = x1, b = x2, c = x3): every region, then the first. */
        ccdw3 ab, ac, ap, bp, cp;
        ccdw_sub(ab, x[2], x[1]);
        ccdw_sub(ac, x[3], x[1]);
        ccdw_sub(ap, x[0], x[1]);
        const ttdw_vd d1 = ccdw_dot(ab, ap), d2 = ccdw_dot(ac, ap);
        ccdw_sub(bp, x[0], x[2]);
        const ttdw_vd d3 = ccdw_dot(ab, bp), d4 = ccdw_dot(ac, bp);
        ccdw_sub(cp, x[0], x[3]);
        const ttdw_vd d5 = ccdw_dot(ab, cp), d6 = ccdw_dot(ac, cp);
        const ttdw_vd vc = d1 * d4 - d3 * d2, vb = d5 * d2 - d1 * d6, va = d3 * d6 - d5 * d4;
        const ttdw_md rA = ttdw_mand_d(ttdw_le_d(d1, zero), ttdw_le_d(d2, zero));
        const ttdw_md rB = ttdw_mand_d(ttdw_ge_d(d3, zero), ttdw_le_d(d4, d3));
        const ttdw_md rAB = ttdw_mand_d(ttdw_mand_d(ttdw_le_d(vc, zero), ttdw_ge_d(d1, zero)),
                                        ttdw_mand_d(ttdw_le_d(d3, zero), ttdw_gt_d(d1 - d3, zero)));
        const ttdw_md rC = ttdw_mand_d(ttdw_ge_d(d6, zero), ttdw_le_d(d5, d6));
        const ttdw_md rAC = ttdw_mand_d(ttdw_mand_d(ttdw_le_d(vb, zero), ttdw_ge_d(d2, zero)),
                                        ttdw_mand_d(ttdw_le_d(d6, zero), ttdw_gt_d(d2 - d6, zero)));
        const ttdw_vd d43 = d4 - d3, d56 = d5 - d6;
        const ttdw_md rBC = ttdw_mand_d(ttdw_mand_d(ttdw_le_d(va, zero), ttdw_ge_d(d43, zero)),
                                        ttdw_mand_d(ttdw_ge_d(d56, zero), ttdw_gt_d(d43 + d56, zero)));
        /* The scalar walk takes the first region of A, B, AB, C, AC, BC, the face: here the face,
         * then each region from the last to the first, each overriding those after it. */
        const ttdw_vd sum = va + vb + vc;
        const ttdw_md spos = ttdw_gt_d(sum, zero);
        ttdw_vd v = ttdw_sel_d(spos, vb / sum, zero), w = ttdw_sel_d(spos, vc / sum, zero);
        v = ccdw_clamp01(v);
        const ttdw_vd rest = one - v;
        w = ttdw_sel_d(ttdw_gt_d(w, zero), ttdw_sel_d(ttdw_lt_d(w, rest), w, rest), zero);
        for (int k = 0; k < 3; ++k)
            q[k] = x[1][k] + v * ab[k] + w * ac[k];
        ccdw3 n2f, pAB, pAC, pBC;
        ccdw_cross(n2f, ab, ac);
        const ttdw_md flip = ttdw_lt_d(ccdw_dot(n2f, ap), zero);
        for (int k = 0; k < 3; ++k)
            n2[k] = ttdw_sel_d(flip, -n2f[k], n2f[k]);
        ccdw_perp(pAB, x[0], x[1], x[2]);
        ccdw_perp(pAC, x[0], x[1], x[3]);
        ccdw_perp(pBC, x[0], x[2], x[3]);
        const ccdw3 z = {zero, zero, zero};
        /* BC */
        const ttdw_vd wbc = ccdw_clamp01(d43 / (d43 + d56));
        for (int k = 0; k < 3; ++k)
            cand[k] = x[2][k] + wbc * (x[3][k] - x[2][k]);
        ccdw_sel3(q, rBC, cand, q);
        ccdw_sel3(n2, rBC, pBC, n2);
        /* AC */
        const ttdw_vd wac = ccdw_clamp01(d2 / (d2 - d6));
        for (int k = 0; k < 3; ++k)
            cand[k] = x[1][k] + wac * ac[k];
        ccdw_sel3(q, rAC, cand, q);
        ccdw_sel3(n2, rAC, pAC, n2);
        /* C */
        ccdw_sel3(q, rC, x[3], q);
        ccdw_sel3(n2, rC, z, n2);
        /* AB */
        const ttdw_vd vab = ccdw_clamp01(d1 / (d1 - d3));
        for (int k = 0; k < 3; ++k)
            cand[k] = x[1][k] + vab * ab[k];
        ccdw_sel3(q, rAB, cand, q);
        ccdw_sel3(n2, rAB, pAB, n2);
        /* B, A */
        ccdw_sel3(q, rB, x[2], q);
        ccdw_sel3(n2, rB, z, n2);
        ccdw_sel3(q, rA, x[1], q);
        ccdw_sel3(n2, rA, z, n2);
        ccdw_sub(n1, x[0], q);
        return;
    }
    /* closest_segments(p0 = x0, p1 = x1, q0 = x2, q1 = x3): the general case, then the special
     * cases over it in the scalar order reversed. */
    ccdw3 d1, d2, r, cq;
    ccdw_sub(d1, x[1], x[0]);
    ccdw_sub(d2, x[3], x[2]);
    ccdw_sub(r, x[0], x[2]);
    const ttdw_vd a = ccdw_dot(d1, d1), e = ccdw_dot(d2, d2), f = ccdw_dot(d2, r);
    const ttdw_vd c = ccdw_dot(d1, r), b = ccdw_dot(d1, d2), denom = a * e - b * b;
    ttdw_vd s = ttdw_sel_d(ttdw_gt_d(denom, zero), ccdw_clamp01((b * f - c * e) / denom), zero);
    ttdw_vd t = (b * s + f) / e;
    const ttdw_md tlo = ttdw_lt_d(t, zero), thi = ttdw_mandnot_d(ttdw_gt_d(t, one), tlo);
    s = ttdw_sel_d(tlo, ccdw_clamp01(-c / a), ttdw_sel_d(thi, ccdw_clamp01((b - c) / a), s));
    t = ttdw_sel_d(tlo, zero, ttdw_sel_d(thi, one, t));
    const ttdw_md a0 = ttdw_le_d(a, zero), e0 = ttdw_le_d(e, zero);
    /* e <= 0 (a > 0) */
    s = ttdw_sel_d(e0, ccdw_clamp01(-c / a), s);
    t = ttdw_sel_d(e0, zero, t);
    /* a <= 0 */
    s = ttdw_sel_d(a0, zero, s);
    t = ttdw_sel_d(a0, ttdw_sel_d(e0, zero, ccdw_clamp01(f / e)), t);
    for (int k = 0; k < 3; ++k) {
        cand[k] = x[0][k] + s * d1[k];
        cq[k] = x[2][k] + t * d2[k];
    }
    ccdw_sub(n1, cand, cq);
    const ttdw_md s_in = ttdw_mand_d(ttdw_gt_d(s, zero), ttdw_lt_d(s, one));
    const ttdw_md t_in = ttdw_mand_d(ttdw_gt_d(t, zero), ttdw_lt_d(t, one));
    ccdw3 nb, ps, pt, pe;
    /* both inside: the edges' cross product, from B toward A */
    ccdw_cross(nb, d1, d2);
    const ttdw_md flip = ttdw_lt_d(ccdw_dot(nb, r), zero);
    for (int k = 0; k < 3; ++k)
        nb[k] = ttdw_sel_d(flip, -nb[k], nb[k]);
    /* s inside: B's endpoint against A's segment, negated */
    ccdw_sel3(pe, ttdw_gt_d(t, zero), x[3], x[2]);
    ccdw_perp(ps, pe, x[0], x[1]);
    for (int k = 0; k < 3; ++k)
        ps[k] = -ps[k];
    /* t inside: A's endpoint against B's segment */
    ccdw_sel3(pe, ttdw_gt_d(s, zero), x[1], x[0]);
    ccdw_perp(pt, pe, x[2], x[3]);
    for (int k = 0; k < 3; ++k)
        n2[k] = ttdw_sel_d(s_in, ttdw_sel_d(t_in, nb[k], ps[k]), ttdw_sel_d(t_in, pt[k], zero));
}

/* ccd.c's gap_along: min over A's points of n.x minus max over B's. */
TTDW_FN ttdw_vd ccdw_gap_along(int na, ccdw3 x[4], const ccdw3 n)
{
    ttdw_vd amin = ttdw_set1_d(HUGE_VAL), bmax = ttdw_set1_d(-HUGE_VAL);
    for (int i = 0; i < 4; ++i) {
        const ttdw_vd v = ccdw_dot(n, x[i]);
        if (i < na)
            amin = ttdw_sel_d(ttdw_lt_d(v, amin), v, amin);
        else
            bmax = ttdw_sel_d(ttdw_gt_d(v, bmax), v, bmax);
    }
    return amin - bmax;
}

/* ccd.c's separated_along: the lanes where dist > delta on the interval along n_in. */
TTDW_FN ttdw_md ccdw_separated_along(int na, ccdw3 xa[4], ccdw3 xb[4], const ccdw3 n_in, ttdw_vd e_gap,
                                     double delta)
{
    const ttdw_vd m = ttdw_max_d(ttdw_abs_d(n_in[0]), ttdw_max_d(ttdw_abs_d(n_in[1]), ttdw_abs_d(n_in[2])));
    const ttdw_md ok = ttdw_mand_d(ttdw_gt_d(m, ttdw_zero_d()), ttdw_le_d(m, ttdw_set1_d(DBL_MAX)));
    ccdw3 n;
    for (int k = 0; k < 3; ++k)
        n[k] = n_in[k] / m;
    ttdw_vd thr = ttdw_zero_d();
    if (delta > 0)
        thr = ttdw_set1_d(delta) * ttdw_sqrt_d(ccdw_dot(n, n)) * ttdw_set1_d(1 + 0x1p-44);
    const ttdw_vd ga = ccdw_gap_along(na, xa, n), gb = ccdw_gap_along(na, xb, n);
    const ttdw_vd ea = e_gap + ttdw_set1_d(0x1p-52) * ttdw_abs_d(ga), eb = e_gap + ttdw_set1_d(0x1p-52) * ttdw_abs_d(gb);
    return ttdw_mand_d(ok, ttdw_mand_d(ttdw_gt_d(ga - ea, thr), ttdw_gt_d(gb - eb, thr)));
}

/* The row's entry: queries 0..count-1 (count <= TTD_NODE_WIDTH) of x0, x1 (12 reals a query, the
 * four points at t = 0 and t = 1); bit i of the result: query i proved free of contact. */
static unsigned ccd_screen(int na, int count, const double *x0, const double *x1, double delta, double t_max)
{
    unsigned proved = 0;
    for (int j = 0; j < count; j += TTDW_LANES_D) {
        double buf[2][12][TTDW_LANES_D] TTDW_ALIGN(64);
        for (int l = 0; l < TTDW_LANES_D; ++l)
            for (int i = 0; i < 12; ++i) {
                buf[0][i][l] = j + l < count ? x0[12 * (j + l) + i] : 0.0;
                buf[1][i][l] = j + l < count ? x1[12 * (j + l) + i] : 0.0;
            }
        ccdw3 p0[4], dx[4], xa[4], xb[4], xm[4];
        ttdw_vd S = ttdw_zero_d();
        ttdw_md fin = ttdw_mfirst_d(count - j);
        const ttdw_vd big = ttdw_set1_d(DBL_MAX);
        for (int i = 0; i < 4; ++i)
            for (int k = 0; k < 3; ++k) {
                const ttdw_vd a = ttdw_loadu_d(buf[0][3 * i + k]), b = ttdw_loadu_d(buf[1][3 * i + k]);
                p0[i][k] = a;
                dx[i][k] = b - a;
                fin = ttdw_mand_d(fin, ttdw_mand_d(ttdw_le_d(ttdw_abs_d(a), big), ttdw_le_d(ttdw_abs_d(b), big)));
                S = ttdw_max_d(S, ttdw_max_d(ttdw_abs_d(a), ttdw_abs_d(b)));
            }
        fin = ttdw_mand_d(fin, ttdw_lt_d(S, ttdw_set1_d(TTD_CCD_SCREEN_MAX)));
        if (ttdw_none_d(fin))
            continue;
        const ttdw_vd e_gap = ttdw_set1_d(64 * 0x1p-53) * S + ttdw_set1_d(0x1p-1000);
        const ttdw_vd ta = ttdw_zero_d(), tb = ttdw_set1_d(t_max), tm = ttdw_set1_d(0.5 * (0.0 + t_max));
        for (int i = 0; i < 4; ++i)
            for (int k = 0; k < 3; ++k) {
                xa[i][k] = p0[i][k] + ta * dx[i][k];
                xb[i][k] = p0[i][k] + tb * dx[i][k];
                xm[i][k] = p0[i][k] + tm * dx[i][k];
            }
        ttdw_md done = ttdw_mandnot_d(ttdw_mtrue_d(), fin);
        if (delta == 0)
            done = ttdw_mor_d(done, ccdw_never_coplanar(na, xa, xb, S));
        if (ttdw_any_d(ttdw_mnot_d(done))) {
            ccdw3 n1, n2;
            ccdw_directions(na, xm, n1, n2);
            done = ttdw_mor_d(done, ccdw_separated_along(na, xa, xb, n1, e_gap, delta));
            done = ttdw_mor_d(done, ccdw_separated_along(na, xa, xb, n2, e_gap, delta));
        }
        proved |= ttdw_mbits_d(ttdw_mand_d(done, fin)) << j;
    }
    return proved;
}

#define TTD_LANE_ROW_CCD_SCREEN .ccd_screen = ccd_screen,
#else
#define TTD_LANE_ROW_CCD_SCREEN
#endif

/* SPDX-License-Identifier: MIT */
/* The boxes of a leaf's triangles (core/kernels.h, tri_fit), one triangle per lane: the refit of
 * a deforming mesh (mesh/build.c, refit_slot) fits them here, 8 at a time, where the build fits
 * them one by one (triangle_fit). Read it next to triangle_axes and triangle_fit in mesh/build.c:
 * the same operations in the same order (no FMA; the build has -ffp-contract=off), so a lane's
 * box has that function's bits; and each triangle's terms of its leaf's sums (fitsum_terms there, the
 * same operations). Only the common case is done in lanes: edges and normal whose
 * squares are within [2^-900, 2^900] (normalize3 without its rescaling) and a normal
 * perpendicular to the longest edge within 2 eps (no Gram-Schmidt pass). A lane outside it is
 * left out of the returned mask, for the caller's scalar function, which handles every case.
 * Double rows only: the build fits in double for both precisions. */
#ifdef TTD_PRECISION_DOUBLE
#include <float.h>
#include <math.h>

TTDW_FN ttdw_vd trifit_dot3(const ttdw_vd a[3], const ttdw_vd b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

TTDW_FN void trifit_cross3(const ttdw_vd a[3], const ttdw_vd b[3], ttdw_vd out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

/* a < b ? a : b and a > b ? a : b, spelled out (dmin / dmax in mesh/build.c): the ISA's min and
 * max may differ from them on signed zeros */
TTDW_FN ttdw_vd trifit_min(ttdw_vd a, ttdw_vd b) { return ttdw_sel_d(ttdw_lt_d(a, b), a, b); }
TTDW_FN ttdw_vd trifit_max(ttdw_vd a, ttdw_vd b) { return ttdw_sel_d(ttdw_gt_d(a, b), a, b); }

static unsigned tri_fit(const double *const p[9], int count, double radius, double u[9][TTD_NODE_WIDTH],
                        double c[3][TTD_NODE_WIDTH], double e[3][TTD_NODE_WIDTH], double terms[13][TTD_NODE_WIDTH])
{
    unsigned done = 0;
    const ttdw_vd lo = ttdw_set1_d(0x1p-900), hi = ttdw_set1_d(0x1p900), one = ttdw_set1_d(1.0);
    const ttdw_vd perp = ttdw_set1_d(2 * DBL_EPSILON), half = ttdw_set1_d(0.5);
    const ttdw_vd r2 = ttdw_set1_d(2 * radius), eps4 = ttdw_set1_d(4 * DBL_EPSILON);
    for (int j = 0; j < TTD_NODE_WIDTH && j < count; j += TTDW_LANES_D) {
        ttdw_vd v[3][3], ed[3][3], len[3];
        for (int k = 0; k < 3; ++k)
            for (int q = 0; q < 3; ++q)
                v[k][q] = ttdw_loadu_d(p[3 * k + q] + j);
        for (int i = 0; i < 3; ++i) {
            for (int q = 0; q < 3; ++q)
                ed[i][q] = v[(i + 1) % 3][q] - v[i][q];
            len[i] = trifit_dot3(ed[i], ed[i]);
        }
        /* the longest edge (the first of equals) and the edge before it */
        ttdw_vd lk = len[0], ek[3], em[3];
        for (int q = 0; q < 3; ++q) {
            ek[q] = ed[0][q];
            em[q] = ed[2][q];
        }
        const ttdw_md k1 = ttdw_gt_d(len[1], lk);
        lk = ttdw_sel_d(k1, len[1], lk);
        for (int q = 0; q < 3; ++q) {
            ek[q] = ttdw_sel_d(k1, ed[1][q], ek[q]);
            em[q] = ttdw_sel_d(k1, ed[0][q], em[q]);
        }
        const ttdw_md k2 = ttdw_gt_d(len[2], lk);
        for (int q = 0; q < 3; ++q) {
            ek[q] = ttdw_sel_d(k2, ed[2][q], ek[q]);
            em[q] = ttdw_sel_d(k2, ed[1][q], em[q]);
        }
        /* normalize3 of the edge and of the normal, their common case */
        ttdw_vd a[3], n[3], w[3], b[3];
        const ttdw_vd de = trifit_dot3(ek, ek);
        ttdw_md ok = ttdw_mand_d(ttdw_gt_d(de, lo), ttdw_lt_d(de, hi));
        const ttdw_vd ie = one / ttdw_sqrt_d(de);
        for (int q = 0; q < 3; ++q)
            a[q] = ek[q] * ie;
        trifit_cross3(ek, em, n);
        const ttdw_vd dn = trifit_dot3(n, n);
        ok = ttdw_mand_d(ok, ttdw_mand_d(ttdw_gt_d(dn, lo), ttdw_lt_d(dn, hi)));
        const ttdw_vd in = one / ttdw_sqrt_d(dn);
        for (int q = 0; q < 3; ++q)
            w[q] = n[q] * in;
        const ttdw_vd ar = trifit_dot3(n, w);
        ok = ttdw_mand_d(ok, ttdw_le_d(ttdw_abs_d(trifit_dot3(a, w)), perp));
        trifit_cross3(w, a, b);
        const ttdw_vd *ax[3] = {a, b, w};
        /* the extents about those axes, as triangle_fit computes them */
        /* the range starts at the first vertex's projection: triangle_fit's min(HUGE_VAL, d) is d */
        ttdw_vd mn[3], mx[3], cc[3];
        for (int k = 0; k < 3; ++k)
            for (int t = 0; t < 3; ++t) {
                const ttdw_vd d = ax[t][0] * v[k][0] + ax[t][1] * v[k][1] + ax[t][2] * v[k][2];
                mn[t] = k == 0 ? d : trifit_min(mn[t], d);
                mx[t] = k == 0 ? d : trifit_max(mx[t], d);
            }
        for (int q = 0; q < 3; ++q)
            cc[q] = ttdw_zero_d();
        for (int t = 0; t < 3; ++t) {
            const ttdw_vd mid = half * (mn[t] + mx[t]);
            for (int q = 0; q < 3; ++q)
                cc[q] = cc[q] + mid * ax[t][q];
        }
        const ttdw_vd c1 = ttdw_abs_d(cc[0]) + ttdw_abs_d(cc[1]) + ttdw_abs_d(cc[2]);
        const ttdw_vd slack = eps4 * (r2 + c1);
        ttdw_vd ex[3];
        for (int t = 0; t < 3; ++t) {
            const ttdw_vd pc = trifit_dot3(ax[t], cc);
            ex[t] = trifit_max(mx[t] - pc, pc - mn[t]) + slack;
        }
        for (int t = 0; t < 3; ++t)
            for (int q = 0; q < 3; ++q)
                ttdw_storeu_d(u[3 * t + q] + j, ax[t][q]);
        for (int q = 0; q < 3; ++q) {
            ttdw_storeu_d(c[q] + j, cc[q]);
            ttdw_storeu_d(e[q] + j, ex[q]);
        }
        /* each triangle's terms of its leaf's sums (mesh/build.c, fitsum_terms: the same
         * operations): its oriented normal and twice its area, its vertices' sum and moments */
        for (int q = 0; q < 3; ++q)
            ttdw_storeu_d(terms[q] + j, ar * w[q]);
        ttdw_storeu_d(terms[3] + j, ar);
        for (int q = 0; q < 3; ++q)
            ttdw_storeu_d(terms[4 + q] + j, v[0][q] + v[1][q] + v[2][q]);
        static const int r6[6] = {0, 0, 0, 1, 1, 2}, c6[6] = {0, 1, 2, 1, 2, 2};
        for (int q = 0; q < 6; ++q)
            ttdw_storeu_d(terms[7 + q] + j, v[0][r6[q]] * v[0][c6[q]] + v[1][r6[q]] * v[1][c6[q]] + v[2][r6[q]] * v[2][c6[q]]);
        done |= ttdw_mbits_d(ok) << j;
    }
    return done & ((1u << (count < TTD_NODE_WIDTH ? count : TTD_NODE_WIDTH)) - 1u);
}

/* The range of the projections u_a . v (a = 0, 1, 2; three products, two sums, as
 * mesh/build.c's fit_extents computes them) over the vertices of triangles 0..count-1, into
 * mn[a], mx[a]: a leaf's box about its refitted axes. The minimum and maximum of a set do not
 * depend on the order it is read in (a zero's sign aside, which the extents' slack absorbs), so
 * these are fit_extents's bits. */
static void leaf_span(const double *const p[9], int count, const double u[9], double mn[3], double mx[3])
{
    ttdw_vd ua[9], lo[3], hi[3];
    for (int k = 0; k < 9; ++k)
        ua[k] = ttdw_set1_d(u[k]);
    if (count >= TTD_NODE_WIDTH) {
        /* a full leaf (most): every lane live, and the range starts at the first projection
         * (min(HUGE_VAL, d) is d): the loop below's bits without its blends */
        for (int j = 0; j < TTD_NODE_WIDTH; j += TTDW_LANES_D)
            for (int k = 0; k < 3; ++k) {
                const ttdw_vd x = ttdw_loadu_d(p[3 * k] + j), y = ttdw_loadu_d(p[3 * k + 1] + j), z = ttdw_loadu_d(p[3 * k + 2] + j);
                for (int a = 0; a < 3; ++a) {
                    const ttdw_vd d = ua[3 * a] * x + ua[3 * a + 1] * y + ua[3 * a + 2] * z;
                    lo[a] = j == 0 && k == 0 ? d : trifit_min(lo[a], d);
                    hi[a] = j == 0 && k == 0 ? d : trifit_max(hi[a], d);
                }
            }
        count = 0; /* the loop below does nothing */
    } else {
        for (int a = 0; a < 3; ++a) {
            lo[a] = ttdw_set1_d(HUGE_VAL);
            hi[a] = ttdw_set1_d(-HUGE_VAL);
        }
    }
    for (int j = 0; j < TTD_NODE_WIDTH && j < count; j += TTDW_LANES_D) {
        const ttdw_md live = ttdw_mfirst_d(count - j);
        for (int k = 0; k < 3; ++k) {
            const ttdw_vd x = ttdw_loadu_d(p[3 * k] + j), y = ttdw_loadu_d(p[3 * k + 1] + j), z = ttdw_loadu_d(p[3 * k + 2] + j);
            for (int a = 0; a < 3; ++a) {
                const ttdw_vd d = ua[3 * a] * x + ua[3 * a + 1] * y + ua[3 * a + 2] * z;
                lo[a] = ttdw_sel_d(live, trifit_min(lo[a], d), lo[a]);
                hi[a] = ttdw_sel_d(live, trifit_max(hi[a], d), hi[a]);
            }
        }
    }
    for (int a = 0; a < 3; ++a) {
        double l[TTDW_LANES_D], h[TTDW_LANES_D];
        ttdw_storeu_d(l, lo[a]);
        ttdw_storeu_d(h, hi[a]);
        mn[a] = l[0];
        mx[a] = h[0];
        for (int i = 1; i < TTDW_LANES_D; ++i) {
            mn[a] = l[i] < mn[a] ? l[i] : mn[a];
            mx[a] = h[i] > mx[a] ? h[i] : mx[a];
        }
    }
}

/* normalize3 of mesh/build.c in its common case (a squared length within (2^-900, 2^900)), lane
 * by lane; *ok loses the lanes outside it */
TTDW_FN void trifit_normalize3(const ttdw_vd a[3], ttdw_vd out[3], ttdw_md *ok)
{
    const ttdw_vd d = trifit_dot3(a, a);
    *ok = ttdw_mand_d(*ok, ttdw_mand_d(ttdw_gt_d(d, ttdw_set1_d(0x1p-900)), ttdw_lt_d(d, ttdw_set1_d(0x1p900))));
    const ttdw_vd in = ttdw_set1_d(1.0) / ttdw_sqrt_d(d);
    for (int q = 0; q < 3; ++q)
        out[q] = a[q] * in;
}

/* The axes of up to 8 leaves' boxes at once, one leaf per lane (bit i of live): mesh/build.c's
 * refit_axes in its flat case, the same operations in the same order (no FMA), so the same bits.
 * s[q][i] is leaf i's sums (build.c's fitsum: n[0..2], nlen, m[0..9]), old[k][i] its axes before
 * the move. A lane outside that case (a patch that is not flat, a normalisation that would need
 * rescaling, an old first axis within 75 degrees of the normal) is left out of the returned mask
 * for the caller's refit_axes, which handles every case. The flat case is a dependent chain of
 * seven square roots and divisions a leaf: one leaf at a time it ran at their latency (a quarter of
 * a refit); eight at a time at their throughput. */
static unsigned leaf_axes(const double s[14][TTD_NODE_WIDTH], const double old[9][TTD_NODE_WIDTH], unsigned live,
                          double u[9][TTD_NODE_WIDTH])
{
    static const int r6[6] = {0, 0, 0, 1, 1, 2}, c6[6] = {0, 1, 2, 1, 2, 2};
    unsigned done = 0;
    const ttdw_vd zero = ttdw_zero_d(), one = ttdw_set1_d(1.0);
    for (int j = 0; j < TTD_NODE_WIDTH; j += TTDW_LANES_D) {
        if ((live >> j & ((1u << TTDW_LANES_D) - 1u)) == 0)
            continue;
        ttdw_vd n[3], cov[3][3], f0[3], f6[3];
        for (int q = 0; q < 3; ++q)
            n[q] = ttdw_loadu_d(s[q] + j);
        const ttdw_vd nlen = ttdw_loadu_d(s[3] + j), k = ttdw_loadu_d(s[4] + j);
        for (int q = 0; q < 6; ++q) {
            const int r = r6[q], c = c6[q];
            cov[r][c] = cov[c][r] = ttdw_loadu_d(s[8 + q] + j) / k - (ttdw_loadu_d(s[5 + r] + j) / k) * (ttdw_loadu_d(s[5 + c] + j) / k);
        }
        const ttdw_vd flat2 = ttdw_set1_d(0.9 * 0.9); /* build.c's REFIT_FLAT squared */
        ttdw_md ok = ttdw_mand_d(ttdw_gt_d(nlen, zero), ttdw_ge_d(trifit_dot3(n, n), flat2 * nlen * nlen));
        trifit_normalize3(n, f0, &ok);
        for (int q = 0; q < 3; ++q)
            f6[q] = ttdw_loadu_d(old[q] + j);
        for (int pass = 0; pass < 2; ++pass) { /* orthogonalize */
            const ttdw_vd d = trifit_dot3(f0, f6);
            ttdw_vd w[3];
            for (int q = 0; q < 3; ++q)
                w[q] = f6[q] - d * f0[q];
            ok = ttdw_mand_d(ok, ttdw_gt_d(trifit_dot3(w, w), ttdw_set1_d(0.0625)));
            trifit_normalize3(w, f6, &ok);
        }
        ttdw_vd a[3], b[3], ca[3], cb[3];
        for (int q = 0; q < 3; ++q)
            a[q] = f6[q];
        trifit_cross3(f0, a, b);
        for (int i = 0; i < 3; ++i) {
            ca[i] = cov[i][0] * a[0] + cov[i][1] * a[1] + cov[i][2] * a[2];
            cb[i] = cov[i][0] * b[0] + cov[i][1] * b[1] + cov[i][2] * b[2];
        }
        ttdw_vd vaa = trifit_dot3(a, ca), vbb = trifit_dot3(b, cb);
        const ttdw_vd vab = trifit_dot3(a, cb);
        /* one Jacobi rotation where vab != 0 (computed in every lane, kept in those) */
        const ttdw_md rot = ttdw_mnot_d(ttdw_eq_d(vab, zero));
        const ttdw_vd theta = (vbb - vaa) / (ttdw_set1_d(2.0) * vab);
        const ttdw_vd sg = ttdw_sel_d(ttdw_ge_d(theta, zero), one, ttdw_set1_d(-1.0));
        const ttdw_vd t = sg / (ttdw_abs_d(theta) + ttdw_sqrt_d(theta * theta + one));
        const ttdw_vd c = one / ttdw_sqrt_d(t * t + one), sn = t * c;
        for (int q = 0; q < 3; ++q) {
            const ttdw_vd aq = a[q], bq = b[q];
            a[q] = ttdw_sel_d(rot, c * aq - sn * bq, aq);
            b[q] = ttdw_sel_d(rot, sn * aq + c * bq, bq);
        }
        vaa = ttdw_sel_d(rot, vaa - t * vab, vaa);
        vbb = ttdw_sel_d(rot, vbb + t * vab, vbb);
        /* the larger spread first, then closed as refit_axes closes them */
        const ttdw_md first = ttdw_ge_d(vaa, vbb);
        ttdw_vd x[3], y[3], u0[3], u3[3], u6[3], w[3];
        for (int q = 0; q < 3; ++q) {
            x[q] = ttdw_sel_d(first, a[q], b[q]);
            y[q] = ttdw_sel_d(first, b[q], a[q]);
        }
        trifit_normalize3(x, u0, &ok);
        trifit_normalize3(y, u3, &ok);
        trifit_cross3(u0, u3, w);
        trifit_normalize3(w, u6, &ok);
        trifit_cross3(u6, u0, w);
        trifit_normalize3(w, u3, &ok);
        for (int q = 0; q < 3; ++q) {
            ttdw_storeu_d(u[q] + j, u0[q]);
            ttdw_storeu_d(u[3 + q] + j, u3[q]);
            ttdw_storeu_d(u[6 + q] + j, u6[q]);
        }
        done |= ttdw_mbits_d(ok) << j;
    }
    return done & live;
}

/* The first pass of mesh/build.c's store_box_of_boxes for a double mesh, one child box a lane:
 * for the count boxes of a node's rows (centres yc, axes yu, extents ye) and the new box's axes
 * ua, each child's slack (its axes' defect g folded in) and spread along each new axis, and the
 * range [lo[a], hi[a]] of the children along the new axes, reduced over the children one after
 * another in slot order as that loop does: the same operations (no FMA), the same bits. A scalar
 * pass over 2.7 to 8 children was 10% of a refit's instructions. */
static void box_span(const double yc[3][TTD_NODE_WIDTH], const double yu[9][TTD_NODE_WIDTH],
                     const double ye[3][TTD_NODE_WIDTH], int count, const double ua[9], double lo[3], double hi[3],
                     double spread[3][TTD_NODE_WIDTH], double slack[TTD_NODE_WIDTH])
{
    double lk[3][TTD_NODE_WIDTH], hk[3][TTD_NODE_WIDTH];
    ttdw_vd u[9];
    for (int k = 0; k < 9; ++k)
        u[k] = ttdw_set1_d(ua[k]);
    const ttdw_vd zero = ttdw_zero_d(), one = ttdw_set1_d(1.0), eps2 = ttdw_set1_d(2 * DBL_EPSILON);
    const ttdw_vd eight = ttdw_set1_d(8.0), wide = ttdw_set1_d(1 + 0x1p-20), eps8 = ttdw_set1_d(8 * DBL_EPSILON);
    for (int j = 0; j < TTD_NODE_WIDTH && j < count; j += TTDW_LANES_D) {
        ttdw_vd w[9], c[3], e[3];
        for (int q = 0; q < 9; ++q)
            w[q] = ttdw_loadu_d(yu[q] + j);
        for (int q = 0; q < 3; ++q) {
            c[q] = ttdw_loadu_d(yc[q] + j);
            e[q] = ttdw_loadu_d(ye[q] + j);
        }
        ttdw_vd g = zero;
        for (int a = 0; a < 3; ++a)
            for (int b = a; b < 3; ++b) {
                const ttdw_vd d = w[3 * a] * w[3 * b] + w[3 * a + 1] * w[3 * b + 1] + w[3 * a + 2] * w[3 * b + 2];
                g = trifit_max(g, ttdw_abs_d(d - (a == b ? one : zero)));
            }
        const ttdw_vd f1 = e[0] + e[1] + e[2];
        const ttdw_vd skew = eight * (g + eps2) * wide * f1;
        const ttdw_vd sl = skew + eps8 * f1;
        ttdw_storeu_d(slack + j, sl);
        for (int a = 0; a < 3; ++a) {
            ttdw_vd r = zero;
            for (int b = 0; b < 3; ++b)
                r = r + ttdw_abs_d(u[3 * a] * w[3 * b] + u[3 * a + 1] * w[3 * b + 1] + u[3 * a + 2] * w[3 * b + 2]) * e[b];
            ttdw_storeu_d(spread[a] + j, r);
            const ttdw_vd p = u[3 * a] * c[0] + u[3 * a + 1] * c[1] + u[3 * a + 2] * c[2];
            ttdw_storeu_d(lk[a] + j, p - r - sl);
            ttdw_storeu_d(hk[a] + j, p + r + sl);
        }
    }
    for (int a = 0; a < 3; ++a) {
        lo[a] = HUGE_VAL;
        hi[a] = -HUGE_VAL;
        for (int k = 0; k < count; ++k) {
            lo[a] = lo[a] < lk[a][k] ? lo[a] : lk[a][k];
            hi[a] = hi[a] > hk[a][k] ? hi[a] : hk[a][k];
        }
    }
}

#define TTD_LANE_ROW_TRI_FIT .tri_fit = tri_fit, .leaf_span = leaf_span, .leaf_axes = leaf_axes, .box_span = box_span,
#else
#define TTD_LANE_ROW_TRI_FIT
#endif

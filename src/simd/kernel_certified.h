/* SPDX-License-Identifier: MIT */
/* The certified mode, one pair per lane: scalar/certified_impl.h's certified_pair with
 * every case computed in every lane and chosen by select, so that each lane performs the
 * scalar operations in the scalar order and rounds the same way. Read the two side by side;
 * the method and why its check certifies are in certified_impl.h and docs/certified-mode.md.
 *
 *  1. The penalty loop of kernel_penalty.h (kp_frame_of, kp_step, kp_finish), unchanged.
 *  2. The frame's six vertices (the penalty frame without its subnormal lift) and the exact
 *     kernel's per-triangle data (kx_tri_init).
 *  3. Per lane, the feature of each side from the penalty's clamped weights (masks), its
 *     vertex or edge picked by select; the closed-form solutions for vertex-edge, edge-vertex,
 *     edge-edge and the two face projections are all computed, and each lane selects its own.
 *  4. The check: feasible weights; the separating-plane bound from the six vertices' KKT
 *     multipliers and stationarity residuals within GAP of |p - q|; clear of contact. Where
 *     it fails in some lane, the clear crossings (certified contacts) are tried.
 *  5. Lanes that fail are not recomputed in place: their indices are collected over the block
 *     and the pairs are gathered, KC_CHUNK at a time, into a contiguous buffer that goes
 *     through kernel_exact (full vectors), then scattered back with TTD_PAIR_FALLBACK. Running
 *     the exact kernel on a whole group whenever one lane of it failed would cost a full exact
 *     group per failing lane at ~10% failures (random pairs that intersect). */

#define KC_CHUNK 64 /* fallback pairs gathered per exact-kernel call (stack: ~18 KB in double) */

/* x[i] with i picked per lane by the masks is0, is1 (else 2). */
static inline vreal kc_sel3(vmask is0, vmask is1, vreal x0, vreal x1, vreal x2)
{
    return vsel(is0, x0, vsel(is1, x1, x2));
}

/* scalar: cert_feature. The positive weights of w: exactly one (one), two (two) or three;
 * the vertex (v0, v1, else 2) of one, the edge (e0, e1, else 2) of two. */
typedef struct kc_feat {
    vmask one, two, three, v0, v1, e0, e1;
} kc_feat;

static inline kc_feat kc_feature_of(const vreal w[3])
{
    const vreal zero = vzero();
    const vmask z0 = vgt(w[0], zero), z1 = vgt(w[1], zero), z2 = vgt(w[2], zero);
    kc_feat f;
    f.three = mand(z0, mand(z1, z2));
    const vmask only0 = mandnot(mandnot(z0, z1), z2), only1 = mandnot(mandnot(z1, z0), z2);
    const vmask only2 = mandnot(mandnot(z2, z0), z1);
    f.one = mor(only0, mor(only1, only2));
    f.two = mnot(mor(f.one, f.three)); /* at least one weight is positive after clamping */
    f.v0 = z0;
    f.v1 = mandnot(z1, z0);
    f.e0 = mnot(z2);
    f.e1 = mandnot(z2, z0);
    return f;
}

/* scalar: the feature of a triangle without a face becomes its longest edge (k). */
static inline void kc_as_edge(kc_feat *f, const kx_tri *T)
{
    const vmask conv = mandnot(f->three, T->has_face);
    f->three = mandnot(f->three, conv);
    f->two = mor(f->two, conv);
    f->e0 = mor(mand(conv, T->is0), mandnot(f->e0, conv));
    f->e1 = mor(mand(conv, T->is1), mandnot(f->e1, conv));
}

/* scalar: cert_face_weights. P projected onto T's plane, as three barycentric weights:
 * c across the longest edge L, b along it corrected by c (the exact method's compensated
 * form, exact-method.md 3.3), a = 1 - b - c. Written here rather than taken from
 * kernel_exact.h so that it stays the scalar code's expression. */
static inline void kc_face_weights(const kx_tri *T, const vreal P[3], vreal w[3])
{
    vreal r[3], x[3];
    for (int i = 0; i < 3; ++i)
        r[i] = P[i] - T->vk[i];
    kx_cross(T->L, r, x);
    const vreal c = kx_dot(T->n, x) * T->inv_nn;
    const vreal b = (kx_dot(r, T->L) - c * T->ML) * T->inv_eek;
    const vreal a = vset1((real)1) - b - c;
    w[0] = kx_pick(T, a, c, b);
    w[1] = kx_pick(T, b, a, c);
    w[2] = kx_pick(T, c, b, a);
}

/* scalar: cert_combine. w0 v0 + w1 v1 + w2 v2. */
static inline void kc_combine(const kx_tri *T, const vreal w[3], vreal p[3])
{
    for (int c = 0; c < 3; ++c)
        p[c] = w[0] * T->v[0][c] + w[1] * T->v[1][c] + w[2] * T->v[2][c];
}

/* Edge weights (1 - s at the edge's start, s at its end), the edge picked by e0, e1. */
static inline void kc_edge_weights(vmask e0, vmask e1, vreal s, vreal w[3])
{
    const vreal zero = vzero(), a = vset1((real)1) - s;
    w[0] = vsel(e0, a, vsel(e1, zero, s));
    w[1] = vsel(e0, s, vsel(e1, a, zero));
    w[2] = vsel(e0, zero, vsel(e1, s, a));
}

/* Unit weight on the vertex picked by v0, v1. */
static inline void kc_vertex_weights(vmask v0, vmask v1, vreal w[3])
{
    const vreal zero = vzero(), one = vset1((real)1);
    w[0] = vsel(v0, one, zero);
    w[1] = vsel(mandnot(v1, v0), one, zero);
    w[2] = vsel(mor(v0, v1), zero, one);
}

static inline vreal kc_min(vreal a, vreal b)
{
    return vsel(vlt(a, b), a, b);
}

/* scalar: cert_cross_edge, for the edge picked per lane by e0, e1 (else 2). */
static inline vmask kc_cross_edge(const kx_tri *X, const kx_tri *Y, vmask e0, vmask e1,
                                           const vreal h[3], vreal nrm, vreal mw, vreal wx[3], vreal wy[3])
{
    const vreal h0 = kc_sel3(e0, e1, h[0], h[1], h[2]);
    const vreal h1 = kc_sel3(e0, e1, h[1], h[2], h[0]);
    const vreal tau = h0 / (h0 - h1);
    vreal xp[3];
    for (int c = 0; c < 3; ++c)
        xp[c] = kc_sel3(e0, e1, X->v[0][c], X->v[1][c], X->v[2][c]) +
                tau * kc_sel3(e0, e1, X->e[0][c], X->e[1][c], X->e[2][c]);
    kc_face_weights(Y, xp, wy);
    kc_edge_weights(e0, e1, tau, wx);
    return mand(mand(vge(wy[0] * nrm, mw), vge(wy[1] * nrm, mw)), vge(wy[2] * nrm, mw));
}

/* scalar: cert_crossing. The lanes where an edge of X crosses Y's face clearly (CROSS in
 * certified_tol.h): of the edges with clearly opposite heights, the first, else the last;
 * its weights in wx, the crossing point's in wy (lanes without a hit: unspecified). */
static inline vmask kc_crossing(const kx_tri *X, const kx_tri *Y, vreal wx[3], vreal wy[3])
{
#ifdef TTD_PRECISION_DOUBLE
    const vreal margin = vset1((real)TTD_CERT_CROSS_D);
#else
    const vreal margin = vset1((real)TTD_CERT_CROSS_F);
#endif
    vreal h[3];
    for (int i = 0; i < 3; ++i) {
        vreal r[3];
        for (int c = 0; c < 3; ++c)
            r[c] = X->v[i][c] - Y->vk[c];
        h[i] = kx_dot(Y->n, r);
    }
    const vreal nrm = vsqrt(Y->nn);
    const vreal mh = margin * nrm, mmh = -mh;
    const vreal mw = margin * vsqrt(kx_pick(Y, Y->ee[0], Y->ee[1], Y->ee[2]));
    vmask opp[3];
    for (int i = 0; i < 3; ++i) {
        const vreal h0 = h[i], h1 = h[(i + 1) % 3];
        opp[i] = mor(mand(vge(h0, mh), vle(h1, mmh)), mand(vle(h0, mmh), vge(h1, mh)));
    }
    const vmask any_edge = mand(mor(opp[0], mor(opp[1], opp[2])), Y->has_face);
    /* first: 0 if opp0, else 1 if opp1, else 2; last: 2 if opp2, else 1 if opp1, else 0 */
    const vmask f0 = opp[0], f1 = mandnot(opp[1], opp[0]);
    const vmask l1 = mandnot(opp[1], opp[2]), l0 = mnot(mor(opp[2], opp[1]));
    vreal wx2[3], wy2[3];
    const vmask hit1 = kc_cross_edge(X, Y, f0, f1, h, nrm, mw, wx, wy);
    const vmask hit2 = kc_cross_edge(X, Y, l0, l1, h, nrm, mw, wx2, wy2);
    for (int c = 0; c < 3; ++c) {
        wx[c] = vsel(hit1, wx[c], wx2[c]);
        wy[c] = vsel(hit1, wy[c], wy2[c]);
    }
    return mand(any_edge, mor(hit1, hit2));
}

/* kc_min on double lanes, for kc_check_d in both precisions */
static inline ttdw_vd kc_min_d(ttdw_vd a, ttdw_vd b)
{
    return ttdw_sel_d(ttdw_lt_d(a, b), a, b);
}

/* scalar: the end of cert_solve_check, in double for both precisions (the float kernel widens
 * its lanes into two halves). From the frame's vertices and the clamped weights: |p - q| in
 * nw, and the lanes where the separating-plane bound is within gap of it and above touch. */
static inline ttdw_md kc_check_d(ttdw_vd Sv[3][3], ttdw_vd Tv[3][3], const ttdw_vd wp[3],
                                 const ttdw_vd wq[3], double gap, double touch, ttdw_vd *nw)
{
    ttdw_vd p[3], q[3], w[3], ds[3], dt[3];
    for (int c = 0; c < 3; ++c) {
        p[c] = wp[0] * Sv[0][c] + wp[1] * Sv[1][c] + wp[2] * Sv[2][c];
        q[c] = wq[0] * Tv[0][c] + wq[1] * Tv[1][c] + wq[2] * Tv[2][c];
        w[c] = p[c] - q[c];
    }
    for (int i = 0; i < 3; ++i) {
        ttdw_vd a[3], b[3];
        for (int c = 0; c < 3; ++c) {
            a[c] = Sv[i][c] - p[c];
            b[c] = q[c] - Tv[i][c];
        }
        ds[i] = w[0] * a[0] + w[1] * a[1] + w[2] * a[2];
        dt[i] = w[0] * b[0] + w[1] * b[1] + w[2] * b[2];
    }
    /* half the multipliers of the active constraints and the residuals of the inactive
     * ones; the separation the planes normal to w prove is (|w|^2 + min ds + min dt) / |w| */
    const ttdw_vd ls = kc_min_d(kc_min_d(ds[0], ds[1]), ds[2]);
    const ttdw_vd lt = kc_min_d(kc_min_d(dt[0], dt[1]), dt[2]);
    const ttdw_vd ww = w[0] * w[0] + w[1] * w[1] + w[2] * w[2];
    *nw = ttdw_sqrt_d(ww);
    const ttdw_vd msum = ls + lt;
    return ttdw_mand_d(ttdw_ge_d(msum, ttdw_set1_d(-gap) * *nw), ttdw_gt_d(ww + msum, ttdw_set1_d(touch) * *nw));
}

/* scalar: the frame of certified_pair and cert_solve_check. From the group's input and
 * the penalty's clamped weights pw, qw: the certified weights wp, wq, the distance (input
 * scale) and the degenerate masks in o; returns the lanes that passed the check. */
static inline vmask kc_certify(const vreal Sin[9], const vreal Tin[9], const vreal pw[3],
                                        const vreal qw[3], vreal wp[3], vreal wq[3], kw_out *o)
{
    const vreal zero = vzero(), one = vset1((real)1), two = vset1((real)2);
    /* the penalty's frame without its subnormal lift (size_floor clamps e at emin, as the
     * scalar code does), all six vertices: for a pair of subnormal size the frame stays below
     * unit size, and such pairs, once small enough, fail the check and fall back */
    vreal m0 = zero;
    for (int k = 0; k < 9; ++k)
        m0 = vmax(m0, vmax(vabs(Sin[k]), vabs(Tin[k])));
    const vreal pre = vsel(vgt(m0, vset1(TTD_REAL_MAX * (real)0.125)), vset1((real)0.0625), one);
    kx_tri S, T;
    vreal size = zero;
    for (int k = 0; k < 3; ++k) {
        const vreal a = Sin[k] * pre;
        for (int i = 0; i < 3; ++i) {
            S.v[i][k] = Sin[3 * i + k] * pre - a;
            T.v[i][k] = Tin[3 * i + k] * pre - a;
            size = vmax(size, vmax(vabs(S.v[i][k]), vabs(T.v[i][k])));
        }
    }
#ifdef TTD_PRECISION_DOUBLE
    const real size_floor = 0x1p-1020; /* 2^(emin - 1), emin = DBL_MIN_EXP + 2 */
    const real feas = -TTD_CERT_FEAS_D, gap = TTD_CERT_GAP_D, touch = TTD_CERT_TOUCH_D;
#else
    const real size_floor = 0x1p-124f; /* 2^(emin - 1), emin = FLT_MIN_EXP + 2 */
    const real feas = -TTD_CERT_FEAS_F, gap = TTD_CERT_GAP_F, touch = TTD_CERT_TOUCH_F;
#endif
    const vreal half = vpow2(vmax(size, vset1(size_floor))); /* 2^(e-1) */
    const vreal scale = vset1((real)0.5) / half, unscale = half * two;
    for (int i = 0; i < 3; ++i)
        for (int k = 0; k < 3; ++k) {
            S.v[i][k] = S.v[i][k] * scale;
            T.v[i][k] = T.v[i][k] * scale;
        }
    kx_tri_init(&S);
    kx_tri_init(&T);

    /* features and the penalty's points */
    kc_feat fs = kc_feature_of(pw), ft = kc_feature_of(qw);
    /* a triangle without a face is its longest edge */
    kc_as_edge(&fs, &S);
    kc_as_edge(&ft, &T);
    vreal ppen[3], qpen[3], Xs[3], Xt[3], P[3], d1[3], Q[3], d2[3];
    kc_combine(&S, pw, ppen);
    kc_combine(&T, qw, qpen);
    for (int c = 0; c < 3; ++c) {
        Xs[c] = vsel(fs.one, kc_sel3(fs.v0, fs.v1, S.v[0][c], S.v[1][c], S.v[2][c]), ppen[c]);
        Xt[c] = vsel(ft.one, kc_sel3(ft.v0, ft.v1, T.v[0][c], T.v[1][c], T.v[2][c]), qpen[c]);
        P[c] = kc_sel3(fs.e0, fs.e1, S.v[0][c], S.v[1][c], S.v[2][c]);
        d1[c] = kc_sel3(fs.e0, fs.e1, S.e[0][c], S.e[1][c], S.e[2][c]);
        Q[c] = kc_sel3(ft.e0, ft.e1, T.v[0][c], T.v[1][c], T.v[2][c]);
        d2[c] = kc_sel3(ft.e0, ft.e1, T.e[0][c], T.e[1][c], T.e[2][c]);
    }
    const vreal ie1 = kc_sel3(fs.e0, fs.e1, S.inv_ee[0], S.inv_ee[1], S.inv_ee[2]);
    const vreal ie2 = kc_sel3(ft.e0, ft.e1, T.inv_ee[0], T.inv_ee[1], T.inv_ee[2]);
    /* the penalty's points as parameters on the edges */
    vreal r0[3], r1[3];
    for (int c = 0; c < 3; ++c) {
        r0[c] = ppen[c] - P[c];
        r1[c] = qpen[c] - Q[c];
    }
    const vreal pen_s = kx_dot(r0, d1) * ie1;
    const vreal pen_t = kx_dot(r1, d2) * ie2;

    /* edge-edge: the lines' stationary point; parallel lines start from the penalty's s */
    vreal n[3], w[3], x[3], r[3];
    kx_cross(d1, d2, n);
    const vreal nn = kx_dot(n, n);
    for (int c = 0; c < 3; ++c)
        w[c] = Q[c] - P[c];
    kx_cross(w, d2, x);
    const vreal d12 = kx_dot(d1, d2), wd1 = kx_dot(w, d1), wd2 = kx_dot(w, d2);
    const vmask nonpar = vge(nn, vset1(TTD_REAL_MIN));
    /* then the segments' closest pair: s clamped, t = projection of p(s) clamped, and s
     * again as the projection of q(t) where t was clamped or the lines are parallel */
    const vreal sc = kx_clamp01(vsel(nonpar, kx_dot(x, n) / nn, pen_s));
    const vreal tt = (sc * d12 - wd2) * ie2;
    const vreal t_ll = kx_clamp01(tt);
    const vmask tin = mand(vge(tt, zero), vle(tt, one));
    const vreal s_ll = vsel(mand(tin, nonpar), sc, kx_clamp01((t_ll * d12 + wd1) * ie1));
    /* vertex-edge both ways */
    for (int c = 0; c < 3; ++c)
        r[c] = Xt[c] - P[c];
    const vreal s_ve = kx_dot(r, d1) * ie1;
    for (int c = 0; c < 3; ++c)
        r[c] = Xs[c] - Q[c];
    const vreal t_ve = kx_dot(r, d2) * ie2;
    const vreal s = vsel(ft.two, s_ll, vsel(ft.one, s_ve, pen_s));
    const vreal t = vsel(fs.two, t_ll, vsel(fs.one, t_ve, pen_t));

    /* raw weights of each side */
    vreal vw[3], ew[3], fw[3], rp[3], rq[3];
    kc_vertex_weights(fs.v0, fs.v1, vw);
    kc_edge_weights(fs.e0, fs.e1, s, ew);
    kc_face_weights(&S, Xt, fw);
    for (int c = 0; c < 3; ++c)
        rp[c] = vsel(fs.one, vw[c], vsel(fs.two, ew[c], vsel(ft.three, pw[c], fw[c])));
    kc_vertex_weights(ft.v0, ft.v1, vw);
    kc_edge_weights(ft.e0, ft.e1, t, ew);
    kc_face_weights(&T, Xs, fw);
    for (int c = 0; c < 3; ++c)
        rq[c] = vsel(ft.one, vw[c], vsel(ft.two, ew[c], fw[c]));

    /* the check */
    const vreal vfeas = vset1(feas);
    vmask ok = mand(mand(vge(rp[0], vfeas), vge(rp[1], vfeas)), vge(rp[2], vfeas));
    ok = mand(ok, mand(mand(vge(rq[0], vfeas), vge(rq[1], vfeas)), vge(rq[2], vfeas)));
    kp_clamp_bary3(rp[0], rp[1], rp[2], wp);
    kp_clamp_bary3(rq[0], rq[1], rq[2], wq);
#ifdef TTD_PRECISION_DOUBLE
    vreal nw;
    ok = mand(ok, kc_check_d(S.v, T.v, wp, wq, gap, touch, &nw));
#else
    /* the check in double: each half of the float lanes widened (exactly) */
    ttdw_vd svl[3][3], svh[3][3], tvl[3][3], tvh[3][3], wpl[3], wph[3], wql[3], wqh[3], nwl, nwh;
    for (int i = 0; i < 3; ++i) {
        for (int c = 0; c < 3; ++c) {
            svl[i][c] = ttdw_f2d_lo(S.v[i][c]);
            svh[i][c] = ttdw_f2d_hi(S.v[i][c]);
            tvl[i][c] = ttdw_f2d_lo(T.v[i][c]);
            tvh[i][c] = ttdw_f2d_hi(T.v[i][c]);
        }
        wpl[i] = ttdw_f2d_lo(wp[i]);
        wph[i] = ttdw_f2d_hi(wp[i]);
        wql[i] = ttdw_f2d_lo(wq[i]);
        wqh[i] = ttdw_f2d_hi(wq[i]);
    }
    const ttdw_md okl = kc_check_d(svl, tvl, wpl, wql, (double)gap, (double)touch, &nwl);
    const ttdw_md okh = kc_check_d(svh, tvh, wph, wqh, (double)gap, (double)touch, &nwh);
    const ttdw_vd one_d = ttdw_set1_d(1.0), zero_d = ttdw_zero_d();
    const vreal okf = ttdw_d2f(ttdw_sel_d(okl, one_d, zero_d), ttdw_sel_d(okh, one_d, zero_d));
    ok = mand(ok, vgt(okf, vset1(0.5f)));
    const vreal nw = ttdw_d2f(nwl, nwh);
#endif
    /* where the check failed, a clear crossing is a certified contact (S's edges first) */
    vmask crossing = mnot(mtrue());
    if (many(mnot(ok))) {
        vreal xs_p[3], xs_q[3], xt_p[3], xt_q[3];
        const vmask cs = mandnot(kc_crossing(&S, &T, xs_p, xs_q), ok);
        const vmask ct = mandnot(mandnot(kc_crossing(&T, &S, xt_q, xt_p), ok), cs);
        for (int c = 0; c < 3; ++c) {
            wp[c] = vsel(cs, xs_p[c], vsel(ct, xt_p[c], wp[c]));
            wq[c] = vsel(cs, xs_q[c], vsel(ct, xt_q[c], wq[c]));
        }
        crossing = mor(cs, ct);
        ok = mor(ok, crossing);
    }
    o->distance = vsel(crossing, zero, nw) * unscale / pre;
    o->flags_int = mbits(crossing);
    o->flags_ds = mbits(mnot(S.has_face));
    o->flags_dt = mbits(mnot(T.has_face));
    return ok;
}

/* The failing pairs idx[0..nf) of the block through the exact kernel, their outputs written
 * over the certified ones, flagged, with the penalty's iteration count kept. */
static void kc_fallback(const size_t *idx, int nf, const real *s, const real *t, const ttd_params *prm,
                        const ttd_out *out)
{
    real bs[9 * KC_CHUNK], bt[9 * KC_CHUNK], bd[KC_CHUNK], bp[6 * KC_CHUNK];
    ttd_result br[KC_CHUNK];
    const ttd_out bout = {bd, out->points ? bp : NULL, out->results ? br : NULL};
    for (int j = 0; j < nf; ++j)
        for (int k = 0; k < 9; ++k) {
            bs[9 * j + k] = s[9 * idx[j] + k];
            bt[9 * j + k] = t[9 * idx[j] + k];
        }
    /* gcc 12 at -O2 warns that bs and bt may be read uninitialised: kernel_exact reads only
     * the nf pairs written above, which it cannot see (zeroing 2 x 9 KB per call would). */
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
    kernel_exact((size_t)nf, bs, bt, prm, (real)INFINITY, &bout);
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif
    for (int j = 0; j < nf; ++j) {
        if (out->distance)
            out->distance[idx[j]] = bd[j];
        if (out->points)
            memcpy(out->points + 6 * idx[j], bp + 6 * j, 6 * sizeof(real));
        if (out->results) {
            ttd_result *r = &out->results[idx[j]];
            const uint16_t its = r->iterations;
            *r = br[j];
            r->flags |= (uint32_t)TTD_PAIR_FALLBACK;
            r->iterations = its;
        }
    }
}

static void kernel_certified(size_t n, const real *s, const real *t, const ttd_params *prm, real bound,
                             const ttd_out *out)
{
    (void)bound;
    const kp_consts K = kp_consts_of(prm);
    size_t idx[KC_CHUNK];
    int nf = 0;
    for (size_t i0 = 0; i0 < n; i0 += TTDW_LANES) {
        const int live = n - i0 < (size_t)TTDW_LANES ? (int)(n - i0) : TTDW_LANES;
        vreal S[9], T[9];
        kw_load_group(s + 9 * i0, t + 9 * i0, live, S, T);
        /* 1. the penalty loop (kernel_penalty) */
        kp_frame F;
        kp_hf H;
        kp_state X;
        kp_frame_of(S, T, &F);
        kp_hf_of(&F, &H);
        kp_init(&X);
        vmask active = mfirst(live);
        vreal its = vzero();
        for (int it = 1; it <= prm->max_iterations && many(active); ++it) {
            its = vsel(active, vset1((real)it), its);
            const vmask done = kp_step(&K, &F, &H, &X, active);
            active = mandnot(active, done);
        }
        vreal pw[3], pq[3], wp[3], wq[3];
        (void)kp_finish(&F, &X, pw, pq);
        /* 2-4. solve on the active set and check */
        kw_out o;
        const vmask ok = kc_certify(S, T, pw, pq, wp, wq, &o);
        const vreal dist = o.distance;
        const unsigned ds = o.flags_ds, dt = o.flags_dt, in = o.flags_int;
        kp_points(S, T, wp, wq, &o);
        o.distance = dist;
        o.flags_ds = ds;
        o.flags_dt = dt;
        o.flags_int = in;
        o.iterations = its;
        o.flags_nc = 0;
        kw_store_group(&o, live, out, i0);
        /* 5. the failures of this group join the block's fallback list */
        const unsigned bad = ~mbits(ok);
        for (int i = 0; i < live; ++i) {
            if (!((bad >> i) & 1u))
                continue;
            idx[nf++] = i0 + (size_t)i;
            if (nf == KC_CHUNK) {
                kc_fallback(idx, nf, s, t, prm, out);
                nf = 0;
            }
        }
    }
    if (nf)
        kc_fallback(idx, nf, s, t, prm, out);
}

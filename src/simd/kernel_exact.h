/* SPDX-License-Identifier: MIT */
/* The exact method, one pair per lane: scalar/exact_impl.h's ttd_exact_pair with every
 * candidate computed in every lane and the closest kept by compare and select. Read it next
 * to the scalar file: the helpers carry the same names with kx_ for exact_, the candidates
 * come in the same order (so ties go to the same, earliest, candidate), and every distance
 * is computed with the same operations in the same order, so each lane's squared distance
 * is the scalar code's to the bit.
 *
 * What differs, and why:
 *  - The scalar code keeps the best candidate's points p, q and weights; here the best keeps
 *    its squared distance and weights only (7 selects per candidate instead of 13), and p, q
 *    are rebuilt at the end as the weighted sums of the vertices: the same points up to a
 *    few ulps of the pair's size.
 *  - The longest-edge index k of a triangle becomes three masks (is0, is1, is2) and the
 *    vectors that depend on it are selected.
 *  - "if (...) continue" becomes a mask; a pass whose mask is empty in every lane is skipped
 *    (Embree's `if (none(valid)) return`), which is where the speed comes from: on random
 *    pairs most edge-edge, vertex-face and crossing candidates are rejected by every lane.
 *  - Passes: vertex-edge, edge-edge, vertex-face, crossings, each reading the per-triangle
 *    data from memory (kx_tri) so that only one candidate's working set is live at a time. */

#ifndef TTD_EXACT_TOUCH_EPS
/* scalar: "a distance below 4 eps of the pair's extent is a contact" */
#define TTD_EXACT_TOUCH_EPS 4
#endif

typedef struct TTD_SFX(kx_tri) {
    vreal v[3][3];   /* vertices, normalised */
    vreal e[3][3];   /* e[i] = v[i+1] - v[i] */
    vreal ee[3];     /* |e[i]|^2 */
    vreal inv_ee[3]; /* 1/ee[i], 0 for a point-like edge */
    vmask is0, is1;  /* k == 0, k == 1 (k == 2 otherwise): the longest edge, first on ties */
    vreal vk[3];     /* v[k] */
    vreal L[3], M[3], n[3];
    vreal nn, inv_nn, ML, inv_eek; /* |n|^2, 1/nn or 0, dot(M, L), inv_ee[k] */
    vmask has_face;
} TTD_SFX(kx_tri);

typedef struct TTD_SFX(kx_best) {
    vreal d2;
    vreal wp[3], wq[3];
} TTD_SFX(kx_best);

static inline vreal TTD_SFX(kx_dot)(const vreal a[3], const vreal b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static inline void TTD_SFX(kx_cross)(const vreal a[3], const vreal b[3], vreal out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

/* scalar: exact_clamp01 */
static inline vreal TTD_SFX(kx_clamp01)(vreal x)
{
    const vreal zero = vzero(), one = vset1((real)1);
    return vsel(vlt(x, zero), zero, vsel(vgt(x, one), one, x));
}

/* k-indexed selection: x[k] */
static inline vreal TTD_SFX(kx_pick)(const TTD_SFX(kx_tri) *T, vreal x0, vreal x1, vreal x2)
{
    return vsel(T->is0, x0, vsel(T->is1, x1, x2));
}

#ifdef TTD_PRECISION_DOUBLE
/* scalar: exact_dop_d. a*b - c*d with Kahan's FMA trick. Without FMA (SSE2) the product
 * error comes from Dekker's split instead: the same value in all but rare last bits. */
static inline vreal TTD_SFX(kx_dop)(vreal a, vreal b, vreal c, vreal d)
{
    const vreal w = c * d;
#if TTDW_HAVE_FMA
    const vreal err = vfma(c, d, -w);
    const vreal f = vfma(a, b, -w);
    return f - err;
#else
    const vreal split = vset1(134217729.0); /* 2^27 + 1 */
    vreal t = c * split;
    const vreal ch = t - (t - c), cl = c - ch;
    t = d * split;
    const vreal dh = t - (t - d), dl = d - dh;
    const vreal err = ((ch * dh - w) + ch * dl + cl * dh) + cl * dl; /* c*d - w, exact */
    const vreal p = a * b;
    t = a * split;
    const vreal ah = t - (t - a), al = a - ah;
    t = b * split;
    const vreal bh = t - (t - b), bl = b - bh;
    const vreal perr = ((ah * bh - p) + ah * bl + al * bh) + al * bl; /* a*b - p, exact */
    return ((p - w) + perr) - err;
#endif
}

/* scalar: exact_cross_acc_d. Naive cross product; lanes whose |n|^2 is below 2^-20 |a|^2 |b|^2
 * (nearly parallel) take the FMA-compensated one. Returns |n|^2. */
static inline vreal TTD_SFX(kx_cross_acc)(const vreal a[3], const vreal b[3], vreal aa, vreal bb, vreal out[3])
{
    TTD_SFX(kx_cross)(a, b, out);
    vreal nn = TTD_SFX(kx_dot)(out, out);
    const vmask need = vlt(nn, vset1(0x1p-20) * aa * bb);
    if (many(need)) {
        out[0] = vsel(need, TTD_SFX(kx_dop)(a[1], b[2], a[2], b[1]), out[0]);
        out[1] = vsel(need, TTD_SFX(kx_dop)(a[2], b[0], a[0], b[2]), out[1]);
        out[2] = vsel(need, TTD_SFX(kx_dop)(a[0], b[1], a[1], b[0]), out[2]);
        nn = TTD_SFX(kx_dot)(out, out);
    }
    return nn;
}
#else
/* scalar: exact_cross_acc_f. Products of floats are exact in double: one double difference
 * per component, rounded to float. The float lanes are widened in two halves. */
static inline vreal TTD_SFX(kx_cross_acc)(const vreal a[3], const vreal b[3], vreal aa, vreal bb, vreal out[3])
{
    (void)aa;
    (void)bb;
    ttdw_vd al[3], ah[3], bl[3], bh[3];
    for (int c = 0; c < 3; ++c) {
        al[c] = ttdw_f2d_lo(a[c]);
        ah[c] = ttdw_f2d_hi(a[c]);
        bl[c] = ttdw_f2d_lo(b[c]);
        bh[c] = ttdw_f2d_hi(b[c]);
    }
    out[0] = ttdw_d2f(al[1] * bl[2] - al[2] * bl[1], ah[1] * bh[2] - ah[2] * bh[1]);
    out[1] = ttdw_d2f(al[2] * bl[0] - al[0] * bl[2], ah[2] * bh[0] - ah[0] * bh[2]);
    out[2] = ttdw_d2f(al[0] * bl[1] - al[1] * bl[0], ah[0] * bh[1] - ah[1] * bh[0]);
    return TTD_SFX(kx_dot)(out, out);
}
#endif

/* scalar: exact_tri_init. v[][] is filled by the caller. */
static inline void TTD_SFX(kx_tri_init)(TTD_SFX(kx_tri) *T)
{
    const vreal zero = vzero(), one = vset1((real)1), rmin = vset1(TTD_REAL_MIN);
    for (int i = 0; i < 3; ++i) {
        for (int c = 0; c < 3; ++c)
            T->e[i][c] = T->v[(i + 1) % 3][c] - T->v[i][c];
        T->ee[i] = TTD_SFX(kx_dot)(T->e[i], T->e[i]);
        T->inv_ee[i] = vsel(vge(T->ee[i], rmin), one / T->ee[i], zero);
    }
    /* k = 0; if (ee[1] > ee[k]) k = 1; if (ee[2] > ee[k]) k = 2; */
    const vmask k1 = vgt(T->ee[1], T->ee[0]);
    const vmask k2 = vgt(T->ee[2], vsel(k1, T->ee[1], T->ee[0]));
    T->is1 = mandnot(k1, k2);
    T->is0 = mnot(mor(k1, k2));
    for (int c = 0; c < 3; ++c) {
        T->L[c] = TTD_SFX(kx_pick)(T, T->e[0][c], T->e[1][c], T->e[2][c]);
        T->M[c] = -TTD_SFX(kx_pick)(T, T->e[2][c], T->e[0][c], T->e[1][c]); /* v[k+2] - v[k] */
        T->vk[c] = TTD_SFX(kx_pick)(T, T->v[0][c], T->v[1][c], T->v[2][c]);
    }
    const vreal eek = TTD_SFX(kx_pick)(T, T->ee[0], T->ee[1], T->ee[2]);
    const vreal eekm = TTD_SFX(kx_pick)(T, T->ee[2], T->ee[0], T->ee[1]);
    T->inv_eek = TTD_SFX(kx_pick)(T, T->inv_ee[0], T->inv_ee[1], T->inv_ee[2]);
    T->nn = TTD_SFX(kx_cross_acc)(T->L, T->M, eek, eekm, T->n);
    T->has_face = vge(T->nn, rmin);
    T->inv_nn = vsel(T->has_face, one / T->nn, zero);
    T->ML = TTD_SFX(kx_dot)(T->M, T->L);
}

/* scalar: exact_face_project. Weights w (T's vertex order), projected point q, height h;
 * returns the lanes whose projection is inside or on the face. */
static inline vmask TTD_SFX(kx_face_project)(const TTD_SFX(kx_tri) *T, const vreal P[3], vreal w[3],
                                              vreal q[3], vreal *h)
{
    const vreal zero = vzero();
    vreal r[3], x[3];
    for (int c = 0; c < 3; ++c)
        r[c] = P[c] - T->vk[c];
    TTD_SFX(kx_cross)(T->L, r, x);
    const vreal c_ = TTD_SFX(kx_dot)(T->n, x) * T->inv_nn;
    const vreal b = (TTD_SFX(kx_dot)(r, T->L) - c_ * T->ML) * T->inv_eek;
    const vreal a = vset1((real)1) - b - c_;
    /* w[k] = a, w[k+1] = b, w[k+2] = c */
    w[0] = TTD_SFX(kx_pick)(T, a, c_, b);
    w[1] = TTD_SFX(kx_pick)(T, b, a, c_);
    w[2] = TTD_SFX(kx_pick)(T, c_, b, a);
    for (int i = 0; i < 3; ++i)
        q[i] = T->vk[i] + b * T->L[i] + c_ * T->M[i];
    *h = TTD_SFX(kx_dot)(T->n, r);
    return mand(mand(T->has_face, vge(a, zero)), mand(vge(b, zero), vge(c_, zero)));
}

/* scalar: exact_consider. Keeps the candidate in the lanes of ok where it is strictly
 * closer. wx belongs to the triangle in role `swapped` (0: x on S). */
static inline void TTD_SFX(kx_consider)(TTD_SFX(kx_best) *best, vmask ok, vreal d2, const vreal wx[3],
                                        const vreal wy[3], int swapped)
{
    const vmask m = mand(ok, vlt(d2, best->d2));
    if (mnone(m))
        return;
    best->d2 = vsel(m, d2, best->d2);
    for (int i = 0; i < 3; ++i) {
        best->wp[i] = vsel(m, swapped ? wy[i] : wx[i], best->wp[i]);
        best->wq[i] = vsel(m, swapped ? wx[i] : wy[i], best->wq[i]);
    }
}

/* scalar: exact_vertex_edge. 9 candidates: each vertex of X against each edge of Y. */
static inline void TTD_SFX(kx_vertex_edge)(const TTD_SFX(kx_tri) *X, const TTD_SFX(kx_tri) *Y, int swapped,
                                           TTD_SFX(kx_best) *best, vmask live)
{
    const vreal zero = vzero(), one = vset1((real)1);
    for (int i = 0; i < 3; ++i) {
        const vreal wx[3] = {i == 0 ? one : zero, i == 1 ? one : zero, i == 2 ? one : zero};
        for (int j = 0; j < 3; ++j) {
            vreal r[3], d[3];
            for (int c = 0; c < 3; ++c)
                r[c] = X->v[i][c] - Y->v[j][c];
            const vreal t = TTD_SFX(kx_clamp01)(TTD_SFX(kx_dot)(r, Y->e[j]) * Y->inv_ee[j]);
            for (int c = 0; c < 3; ++c)
                d[c] = X->v[i][c] - (Y->v[j][c] + t * Y->e[j][c]);
            vreal wy[3];
            wy[j] = one - t;
            wy[(j + 1) % 3] = t;
            wy[(j + 2) % 3] = zero;
            TTD_SFX(kx_consider)(best, live, TTD_SFX(kx_dot)(d, d), wx, wy, swapped);
        }
    }
}

/* scalar: exact_edge_edge. 9 candidates: the stationary point of two edges' lines, where it
 * lies inside both segments (plain cross product for the normal, as in the scalar code). */
static inline void TTD_SFX(kx_edge_edge)(const TTD_SFX(kx_tri) *S, const TTD_SFX(kx_tri) *T,
                                         TTD_SFX(kx_best) *best, vmask live)
{
    const vreal zero = vzero(), one = vset1((real)1), rmin = vset1(TTD_REAL_MIN);
    for (int i = 0; i < 3; ++i) {
        const vreal *P = S->v[i], *d1 = S->e[i];
        for (int j = 0; j < 3; ++j) {
            const vreal *Q = T->v[j], *d2 = T->e[j];
            vreal n[3], w[3], x[3];
            TTD_SFX(kx_cross)(d1, d2, n);
            const vreal nn = TTD_SFX(kx_dot)(n, n);
            const vmask valid = mand(live, vge(nn, rmin)); /* parallel or a point: endpoints cover it */
            for (int c = 0; c < 3; ++c)
                w[c] = Q[c] - P[c];
            TTD_SFX(kx_cross)(w, d2, x);
            const vreal s = TTD_SFX(kx_dot)(x, n) / nn;
            const vreal sc = TTD_SFX(kx_clamp01)(s);
            const vreal t = (sc * TTD_SFX(kx_dot)(d1, d2) - TTD_SFX(kx_dot)(w, d2)) * T->inv_ee[j];
            const vmask ok = mand(mand(valid, mand(vge(s, zero), vle(s, one))), mand(vge(t, zero), vle(t, one)));
            if (mnone(ok))
                continue;
            vreal d[3];
            for (int c = 0; c < 3; ++c)
                d[c] = (P[c] + sc * d1[c]) - (Q[c] + t * d2[c]);
            vreal wp[3], wq[3];
            wp[i] = one - sc;
            wp[(i + 1) % 3] = sc;
            wp[(i + 2) % 3] = zero;
            wq[j] = one - t;
            wq[(j + 1) % 3] = t;
            wq[(j + 2) % 3] = zero;
            TTD_SFX(kx_consider)(best, ok, TTD_SFX(kx_dot)(d, d), wp, wq, 0);
        }
    }
}

/* scalar: exact_face. 3 vertex-face candidates (vertices of X over the face of Y); h gets
 * the vertices' heights for the crossings. */
static inline void TTD_SFX(kx_face)(const TTD_SFX(kx_tri) *X, const TTD_SFX(kx_tri) *Y, int swapped,
                                    TTD_SFX(kx_best) *best, vreal h[3], vmask live)
{
    const vreal zero = vzero(), one = vset1((real)1);
    for (int i = 0; i < 3; ++i) {
        vreal wy[3], q[3], d[3];
        const vmask inside = mand(live, TTD_SFX(kx_face_project)(Y, X->v[i], wy, q, &h[i]));
        if (mnone(inside))
            continue;
        const vreal wx[3] = {i == 0 ? one : zero, i == 1 ? one : zero, i == 2 ? one : zero};
        for (int c = 0; c < 3; ++c)
            d[c] = X->v[i][c] - q[c];
        TTD_SFX(kx_consider)(best, inside, TTD_SFX(kx_dot)(d, d), wx, wy, swapped);
    }
}

/* scalar: exact_crossings. 3 candidates: edges of X whose ends lie on opposite sides of Y's
 * plane, crossing it inside the face (distance 0). */
static inline void TTD_SFX(kx_crossings)(const TTD_SFX(kx_tri) *X, const TTD_SFX(kx_tri) *Y, int swapped,
                                         TTD_SFX(kx_best) *best, const vreal h[3], vmask live)
{
    const vreal zero = vzero(), one = vset1((real)1);
    const vmask face = mand(live, Y->has_face);
    if (mnone(face))
        return;
    for (int i = 0; i < 3; ++i) {
        const vreal h0 = h[i], h1 = h[(i + 1) % 3];
        const vmask sides = mor(mand(vlt(h0, zero), vgt(h1, zero)), mand(vgt(h0, zero), vlt(h1, zero)));
        const vmask ok = mand(face, sides);
        if (mnone(ok))
            continue;
        const vreal tau = h0 / (h0 - h1); /* no cancellation: opposite signs */
        vreal xp[3], wy[3], q[3], hx;
        for (int c = 0; c < 3; ++c)
            xp[c] = X->v[i][c] + tau * X->e[i][c];
        const vmask inside = mand(ok, TTD_SFX(kx_face_project)(Y, xp, wy, q, &hx));
        vreal wx[3];
        wx[i] = one - tau;
        wx[(i + 1) % 3] = tau;
        wx[(i + 2) % 3] = zero;
        TTD_SFX(kx_consider)(best, inside, zero, wx, wy, swapped);
    }
}

/* One group of W pairs: scalar ttd_exact_pair, steps 1-4. */
static inline void TTD_SFX(kx_group)(const vreal Sin[9], const vreal Tin[9], vmask live, TTD_SFX(kw_out) *out)
{
    const vreal zero = vzero(), one = vset1((real)1);
    /* 1. Normalise: halve twice near the overflow limit, translate to A, scale by 2^-e with
     * max |relative coordinate| = f 2^e, f in [0.5, 1). 2^-e is 0.5 / (m with its mantissa
     * cleared); the one product equals the scalar's two (f1, f2) wherever neither rounds,
     * i.e. except for coordinates below REAL_MIN of the pair's extent. */
    vreal m0 = zero;
    for (int i = 0; i < 9; ++i) {
        m0 = vmax(m0, vabs(Sin[i]));
        m0 = vmax(m0, vabs(Tin[i]));
    }
    const vreal pre = vsel(vgt(m0, vset1(TTD_REAL_MAX * (real)0.25)), vset1((real)0.25), one);
    vreal o[3], rel[18];
    for (int c = 0; c < 3; ++c)
        o[c] = Sin[c] * pre;
    vreal m = zero;
    for (int i = 0; i < 9; ++i) {
        rel[i] = Sin[i] * pre - o[i % 3];
        rel[9 + i] = Tin[i] * pre - o[i % 3];
        m = vmax(m, vmax(vabs(rel[i]), vabs(rel[9 + i])));
    }
#ifdef TTD_PRECISION_DOUBLE
    const real lift = 0x1p54, unlift = 0x1p-54;
#else
    const real lift = 0x1p25f, unlift = 0x1p-25f;
#endif
    const vmask tiny = vlt(m, vset1(TTD_REAL_MIN)), isz = veq(m, zero);
    const vreal up = vsel(tiny, vset1(lift), one);
    const vreal half = vpow2(m * up);                                   /* 2^(e-1) (lifted) */
    const vreal inv = vsel(isz, one, vset1((real)0.5) / half);          /* 2^-e (lifted) */
    const vreal g = vsel(isz, one, half * vset1((real)2) * vsel(tiny, vset1(unlift), one)); /* 2^e */
    TTD_SFX(kx_tri) S, T;
    for (int i = 0; i < 3; ++i)
        for (int c = 0; c < 3; ++c) {
            S.v[i][c] = rel[3 * i + c] * up * inv;
            T.v[i][c] = rel[9 + 3 * i + c] * up * inv;
        }
    TTD_SFX(kx_tri_init)(&S);
    TTD_SFX(kx_tri_init)(&T);

    /* 2. Candidates, in the scalar code's order. */
    TTD_SFX(kx_best) best;
    best.d2 = vset1(TTD_REAL_MAX);
    for (int i = 0; i < 3; ++i)
        best.wp[i] = best.wq[i] = i == 0 ? one : zero;
    TTD_SFX(kx_vertex_edge)(&S, &T, 0, &best, live);
    TTD_SFX(kx_vertex_edge)(&T, &S, 1, &best, live);
    TTD_SFX(kx_edge_edge)(&S, &T, &best, live);
    vreal hs[3], ht[3];
    TTD_SFX(kx_face)(&S, &T, 0, &best, hs, live);
    TTD_SFX(kx_face)(&T, &S, 1, &best, ht, live);
    TTD_SFX(kx_crossings)(&S, &T, 0, &best, hs, live);
    TTD_SFX(kx_crossings)(&T, &S, 1, &best, ht, live);

    /* 3. A distance within rounding of 0 is a contact. */
    vreal d = vsqrt(best.d2);
    const vmask touch = vle(d, vset1((real)TTD_EXACT_TOUCH_EPS * TTD_REAL_EPS));
    d = vsel(touch, zero, d);

    /* 4. Scale back, origin back; p and q from the weights. */
    const vreal unpre = one / pre;
    out->distance = d * g * unpre;
    for (int c = 0; c < 3; ++c) {
        const vreal p = best.wp[0] * S.v[0][c] + best.wp[1] * S.v[1][c] + best.wp[2] * S.v[2][c];
        const vreal q = best.wq[0] * T.v[0][c] + best.wq[1] * T.v[1][c] + best.wq[2] * T.v[2][c];
        out->p[c] = (p * g + o[c]) * unpre;
        out->q[c] = (q * g + o[c]) * unpre;
        out->bary_p[c] = best.wp[c];
        out->bary_q[c] = best.wq[c];
    }
    out->iterations = zero;
    out->flags_nc = 0;
    out->flags_int = mbits(touch);
    out->flags_ds = mbits(mnot(S.has_face));
    out->flags_dt = mbits(mnot(T.has_face));
}

static void TTD_SFX(kernel_exact)(size_t n, const real *s, const real *t, const ttd_params *prm,
                                  real *distance, ttd_result *results)
{
    (void)prm;
    for (size_t i0 = 0; i0 < n; i0 += TTDW_LANES) {
        const int live = n - i0 < (size_t)TTDW_LANES ? (int)(n - i0) : TTDW_LANES;
        vreal S[9], T[9];
        TTD_SFX(kw_load_group)(s + 9 * i0, t + 9 * i0, live, S, T);
        TTD_SFX(kw_out) o;
        TTD_SFX(kx_group)(S, T, mfirst(live), &o);
        TTD_SFX(kw_store_group)(&o, live, distance ? distance + i0 : NULL, results ? results + i0 : NULL);
    }
}

/* SPDX-License-Identifier: MIT */
/* The exact method, one pair per lane: scalar/exact_impl.h's exact_pair with every
 * candidate computed in every lane and the closest kept by compare and select. Read it next
 * to the scalar file: the helpers carry the same names with kx_ for exact_, the candidates
 * come in the same order with the same ids (so ties go to the same, earliest, candidate),
 * every d2 is computed with the same operations in the same order, and the winner's points
 * and weights are rebuilt from (id, u, v, w) with the scalar expressions: each lane's result
 * is meant to be the scalar code's to the bit, on every row: the one FMA, in the products'
 * errors of kx_dop, is exact, and the rows without FMA (SSE2, portable) compute the same exact
 * errors by Dekker's split (Kahan's shorter form, fma(a, b, -w) - err, rounded differently from
 * any FMA-free formula: 26 of 1e6 thin pairs differed on those rows before). The mesh queries
 * rely on it (src/mesh/query_impl.h); test_isa_kernels.c and the mesh fuzzer check it. The GPU
 * runs this file too, one lane per CUDA thread (simd/lanes_cuda.h, src/gpu/, docs/gpu.md).
 *
 * What differs, and why:
 *  - The longest-edge index k of a triangle becomes two masks (is0, is1) and the vectors that
 *    depend on it are selected; the rebuild's data-dependent choices (which vertex, edge or
 *    face, which triangle) are selects on the id.
 *  - No branch on the data. Keeping a candidate only in groups where some lane improves, and
 *    skipping edge-edge, vertex-face and crossing candidates that no lane accepts (Embree's
 *    `if (none(valid)) return`), was tried first and was 1.6-1.9x slower: those branches are
 *    unpredictable on random pairs, and each misprediction also empties the out-of-order
 *    window that overlaps the independent candidates (docs/simd.md, 7.1). What remains are
 *    branches that are predictable on the data they meet: the crossings when no lane's
 *    vertices straddle the other face's plane (separated pairs, as a mesh query produces) or
 *    no lane's other triangle has a face, the FMA cross product for nearly parallel face
 *    frames (double; rare), and the products by the pre-scale and the lift, skipped when no
 *    lane needs them (inputs near REAL_MAX or a subnormal extent; never on real data).
 *  - Shared work the scalar code recomputes: edge-edge takes dot(Q - P, d2) from the
 *    vertex-edge pass (an exact negation).
 *  - Three specialisations of the group, for what the call asks for (docs/simd.md 7.1b):
 *    distances only (no rebuild; the selection is a running minimum of d2, the same bits,
 *    docs/simd.md 7.1a); distances and points (the selection keeps a label and the
 *    parameters p and q need, and p and q are rebuilt without weights); full results.
 *  - A finite bound (core/kernels.h) is used: pairs whose cheap lower bound exceeds it are
 *    ruled out per lane before the exact work, the others gathered into full vectors
 *    (kx_screened).
 *  - Passes: vertex-edge, edge-edge, vertex-face, crossings, each reading the per-triangle
 *    data from memory (kx_tri) so that only one candidate's working set is live at a time. */

#include "core/exact_ids.h" /* candidate ids and the contact threshold, shared with the scalar code */

/* kx_group is inlined into each of the three loops (kx_run_*), so that each is specialised on
 * its constant mode (gcc 12 otherwise keeps one out-of-line copy and tests it at run time). */
#if defined(__GNUC__)
#define KX_GROUP_INLINE TTDW_FN __attribute__((always_inline))
#else
#define KX_GROUP_INLINE TTDW_FN
#endif

typedef struct kx_tri {
    vreal v[3][3];   /* vertices, normalised */
    vreal e[3][3];   /* e[i] = v[i+1] - v[i] */
    vreal ee[3];     /* |e[i]|^2 */
    vreal inv_ee[3]; /* 1/ee[i], 0 for a point-like edge */
    vmask is0, is1;  /* k == 0, k == 1 (k == 2 otherwise): the longest edge, first on ties */
    vreal vk[3];     /* v[k] */
    vreal L[3], M[3], n[3];
    vreal nn, inv_nn, ML, inv_eek; /* |n|^2, 1/nn or 0, dot(M, L), inv_ee[k] */
    vreal u[3];                    /* cross(n, L) / nn */
    vmask has_face;
} kx_tri;

/* What a call asks for; a constant in each specialisation of kx_group. */
enum {
    KX_DIST = 0,   /* distances only: d2 is a plain running minimum */
    KX_POINTS = 1, /* distances and p, q: the winner's label (KX_LBL) and the parameters p and q need */
    KX_FULL = 2    /* the whole result: the scalar id (TTD_EXACT_*) and every parameter */
};

/* Labels of the candidates in KX_POINTS mode: 9 cls + 3 a + b, where cls is the kind and a, b
 * the index of S's and T's vertex or edge (0 where the kind has none), chosen so that
 * kx_rebuild_points decodes them with a few roundings instead of a compare per id:
 *   cls 0 VE_S (vertex a of S, edge b of T)   1 VE_T (edge a of S, vertex b of T)
 *       2 EE (edges a, b)   3 VF_S (vertex a of S)   4 VF_T (vertex b of T)
 *       5 X_S (edge a of S through T's face)   6 X_T (edge b of T through S's face) */
#define KX_LBL(cls, a, b) (9 * (cls) + 3 * (a) + (b))

/* scalar: exact_best. The smallest d2 so far, the id of its candidate (TTD_EXACT_* in
 * scalar/exact_impl.h in KX_FULL mode, KX_LBL in KX_POINTS mode, as a real) and its
 * parameters. */
typedef struct kx_best {
    vreal d2, id, u, v, w;
    int mode;
} kx_best;

TTDW_FN vreal kx_dot(const vreal a[3], const vreal b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

TTDW_FN void kx_cross(const vreal a[3], const vreal b[3], vreal out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

/* scalar: exact_clamp01, x < 0 ? 0 : (x > 1 ? 1 : x). With x86's min(a, b) = a < b ? a : b and
 * max(a, b) = a > b ? a : b this is the same expression, signed zeros included (NEON's
 * min/max may turn a -0 into +0 here, nothing else); x is never NaN. Two instructions instead
 * of two compares and two selects. */
TTDW_FN vreal kx_clamp01(vreal x)
{
    return vmax(vzero(), vmin(vset1((real)1), x));
}

/* k-indexed selection: x[k] */
TTDW_FN vreal kx_pick(const kx_tri *T, vreal x0, vreal x1, vreal x2)
{
    return vsel(T->is0, x0, vsel(T->is1, x1, x2));
}

#ifdef TTD_PRECISION_DOUBLE
/* scalar: exact_prod_err_d. The rounding error of p = a*b, exactly, where |p| > 2^-900 (0
 * below): one FMA, or without FMA (SSE2, portable) Dekker's split, which is exact over the same
 * range, so every row gets the same bits. */
TTDW_FN vreal kx_prod_err(vreal a, vreal b, vreal p)
{
#if TTDW_HAVE_FMA
    const vreal err = vfma(a, b, -p);
#else
    const vreal split = vset1(134217729.0); /* 2^27 + 1 */
    vreal t = a * split;
    const vreal ah = t - (t - a), al = a - ah;
    t = b * split;
    const vreal bh = t - (t - b), bl = b - bh;
    const vreal err = ((ah * bh - p) + ah * bl + al * bh) + al * bl;
#endif
    return vsel(vlt(vset1(0x1p-900), vabs(p)), err, vzero());
}

/* scalar: exact_dop_d. a*b - c*d with both products' errors restored. */
TTDW_FN vreal kx_dop(vreal a, vreal b, vreal c, vreal d)
{
    const vreal p = a * b, w = c * d;
    return ((p - w) + kx_prod_err(a, b, p)) - kx_prod_err(c, d, w);
}

/* scalar: exact_cross_acc_d. Naive cross product; lanes whose |n|^2 is below 2^-20 |a|^2 |b|^2
 * (nearly parallel) take the FMA-compensated one. Returns |n|^2. */
TTDW_FN vreal kx_cross_acc(const vreal a[3], const vreal b[3], vreal aa, vreal bb, vreal out[3])
{
    kx_cross(a, b, out);
    vreal nn = kx_dot(out, out);
    const vmask need = vlt(nn, vset1(0x1p-20) * aa * bb);
    if (many(need)) {
        out[0] = vsel(need, kx_dop(a[1], b[2], a[2], b[1]), out[0]);
        out[1] = vsel(need, kx_dop(a[2], b[0], a[0], b[2]), out[1]);
        out[2] = vsel(need, kx_dop(a[0], b[1], a[1], b[0]), out[2]);
        nn = kx_dot(out, out);
    }
    return nn;
}
#else
/* scalar: exact_cross_acc_f. Products of floats are exact in double: one double difference
 * per component, rounded to float. The float lanes are widened in two halves. */
TTDW_FN vreal kx_cross_acc(const vreal a[3], const vreal b[3], vreal aa, vreal bb, vreal out[3])
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
    return kx_dot(out, out);
}
#endif

/* scalar: exact_tri_init. v[][] is filled by the caller. */
TTDW_FN void kx_tri_init(kx_tri *T)
{
    const vreal zero = vzero(), one = vset1((real)1), rmin = vset1(TTD_REAL_MIN);
    for (int i = 0; i < 3; ++i) {
        for (int c = 0; c < 3; ++c)
            T->e[i][c] = T->v[(i + 1) % 3][c] - T->v[i][c];
        T->ee[i] = kx_dot(T->e[i], T->e[i]);
        T->inv_ee[i] = vsel(vge(T->ee[i], rmin), one / T->ee[i], zero);
    }
    /* k = 0; if (ee[1] > ee[k]) k = 1; if (ee[2] > ee[k]) k = 2; */
    const vmask k1 = vgt(T->ee[1], T->ee[0]);
    const vmask k2 = vgt(T->ee[2], vsel(k1, T->ee[1], T->ee[0]));
    T->is1 = mandnot(k1, k2);
    T->is0 = mnot(mor(k1, k2));
    for (int c = 0; c < 3; ++c) {
        T->L[c] = kx_pick(T, T->e[0][c], T->e[1][c], T->e[2][c]);
        T->M[c] = -kx_pick(T, T->e[2][c], T->e[0][c], T->e[1][c]); /* v[k+2] - v[k] */
        T->vk[c] = kx_pick(T, T->v[0][c], T->v[1][c], T->v[2][c]);
    }
    const vreal eek = kx_pick(T, T->ee[0], T->ee[1], T->ee[2]);
    const vreal eekm = kx_pick(T, T->ee[2], T->ee[0], T->ee[1]);
    T->inv_eek = kx_pick(T, T->inv_ee[0], T->inv_ee[1], T->inv_ee[2]);
    T->nn = kx_cross_acc(T->L, T->M, eek, eekm, T->n);
    T->has_face = vge(T->nn, rmin);
    T->inv_nn = vsel(T->has_face, one / T->nn, zero);
    T->ML = kx_dot(T->M, T->L);
    kx_cross(T->n, T->L, T->u);
    for (int c = 0; c < 3; ++c)
        T->u[c] = T->u[c] * T->inv_nn;
}

/* scalar: exact_fc, exact_face_coords. P's face coordinates over T: c (weight of v[k+2]),
 * g = dot(P - v[k], L) and the height h. */
typedef struct kx_fc {
    vreal c, g, h;
} kx_fc;

TTDW_FN kx_fc kx_face_coords(const kx_tri *T, const vreal P[3])
{
    vreal r[3];
    for (int i = 0; i < 3; ++i)
        r[i] = P[i] - T->vk[i];
    kx_fc f;
    f.c = kx_dot(r, T->u); /* n . (L x r) / nn */
    f.g = kx_dot(r, T->L);
    f.h = kx_dot(T->n, r);
    return f;
}

/* scalar: exact_face_weights. b from (c, g), and the lanes whose point is inside or on the
 * face. */
TTDW_FN vmask kx_face_weights(const kx_tri *T, vreal c, vreal g, vreal *b)
{
    const vreal zero = vzero();
    const vreal bb = (g - c * T->ML) * T->inv_eek;
    const vreal aa = vset1((real)1) - bb - c;
    *b = bb;
    return mand(mand(T->has_face, vge(aa, zero)), mand(vge(bb, zero), vge(c, zero)));
}

/* scalar: exact_face_point. q = v[k] + b L + c M and its weights (w[k] = 1 - b - c). */
TTDW_FN void kx_face_point(const kx_tri *T, vreal b, vreal c, vreal q[3], vreal w[3])
{
    for (int i = 0; i < 3; ++i)
        q[i] = T->vk[i] + b * T->L[i] + c * T->M[i];
    const vreal a = vset1((real)1) - b - c;
    w[0] = kx_pick(T, a, c, b);
    w[1] = kx_pick(T, b, a, c);
    w[2] = kx_pick(T, c, b, a);
}

/* scalar: exact_keep. In the lanes of m (where d2 is strictly smaller), keep d2, the id (id in
 * KX_FULL mode, lbl in KX_POINTS mode) and the first np of u, v, w (np_pts of them in
 * KX_POINTS mode: a crossing's point needs only tau); the others are never read for it. */
TTDW_FN void kx_keep_m(kx_best *best, vmask m, vreal d2, int id, int lbl, int np, int np_pts, vreal u,
                       vreal v, vreal w)
{
    const int k = best->mode == KX_FULL ? np : np_pts;
    best->d2 = vsel(m, d2, best->d2);
    best->id = vsel(m, vset1((real)(best->mode == KX_FULL ? id : lbl)), best->id);
    best->u = vsel(m, u, best->u);
    if (k > 1)
        best->v = vsel(m, v, best->v);
    if (k > 2)
        best->w = vsel(m, w, best->w);
}

/* Distances only: min(d2, best) is d2 < best ? d2 : best on x86 (NEON differs only for
 * signed zeros and NaN, and d2 is a sum of squares or a square), so the compare folds into
 * the min. */
TTDW_FN void kx_keep(kx_best *best, vmask ok, vreal d2, int id, int lbl, int np, int np_pts, vreal u,
                     vreal v, vreal w)
{
    if (best->mode != KX_DIST)
        kx_keep_m(best, mand(ok, vlt(d2, best->d2)), d2, id, lbl, np, np_pts, u, v, w);
    else
        best->d2 = vmin(vsel(ok, d2, best->d2), best->d2);
}

/* kx_keep for a candidate that every lane offers (vertex-edge) */
TTDW_FN void kx_keep_all(kx_best *best, vreal d2, int id, int lbl, int np, vreal u, vreal v, vreal w)
{
    if (best->mode != KX_DIST)
        kx_keep_m(best, vlt(d2, best->d2), d2, id, lbl, np, np, u, v, w);
    else
        best->d2 = vmin(d2, best->d2);
}

/* scalar: exact_vertex_edge. 9 candidates: each vertex of X against each edge of Y (X is S
 * when id0 is TTD_EXACT_VE_S, else T). When rdot is given, rdot[3i + j] keeps
 * dot(X.v[i] - Y.v[j], Y.e[j]) for the edge-edge pass. */
TTDW_FN void kx_vertex_edge(const kx_tri *X, const kx_tri *Y, int id0,
                            kx_best *best, vreal *rdot)
{
    const vreal zero = vzero();
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            vreal r[3], d[3];
            for (int c = 0; c < 3; ++c)
                r[c] = X->v[i][c] - Y->v[j][c];
            const vreal re = kx_dot(r, Y->e[j]);
            if (rdot)
                rdot[3 * i + j] = re;
            const vreal t = kx_clamp01(re * Y->inv_ee[j]);
            for (int c = 0; c < 3; ++c)
                d[c] = r[c] - t * Y->e[j][c]; /* X.v[i] - (Y.v[j] + t e[j]) */
            const int lbl = id0 == TTD_EXACT_VE_S ? KX_LBL(0, i, j) : KX_LBL(1, j, i);
            kx_keep_all(best, kx_dot(d, d), id0 + 3 * i + j, lbl, 1, t, zero, zero);
        }
}

/* scalar: exact_edge_edge. 9 candidates: the stationary point of two edges' lines, where it
 * lies inside both segments (plain cross product for the normal, as in the scalar code). */
TTDW_FN void kx_edge_edge(const kx_tri *S, const kx_tri *T,
                          kx_best *best, const vreal rdot[9])
{
    const vreal zero = vzero(), one = vset1((real)1), rmin = vset1(TTD_REAL_MIN);
    for (int i = 0; i < 3; ++i) {
        const vreal *P = S->v[i], *d1 = S->e[i];
        for (int j = 0; j < 3; ++j) {
            const vreal *Q = T->v[j], *d2 = T->e[j];
            vreal n[3], w[3], x[3], d[3];
            kx_cross(d1, d2, n);
            const vreal nn = kx_dot(n, n);
            const vmask ok = vge(nn, rmin); /* parallel or a point: the endpoints cover it */
            for (int c = 0; c < 3; ++c)
                w[c] = Q[c] - P[c];
            kx_cross(w, d2, x);
            const vreal s = vsel(ok, kx_dot(x, n) / nn, -one);
            const vreal sc = kx_clamp01(s);
            /* scalar: sc dot(d1, d2) - dot(w, d2). dot(w, d2) is minus the vertex-edge dot of
             * S.v[i] on T's edge j, kept from that pass (w = -r, and negation is exact) */
            const vreal t = (sc * kx_dot(d1, d2) + rdot[3 * i + j]) * T->inv_ee[j];
            const vreal tc = kx_clamp01(t);
            /* s and t in [0, 1]: exactly when clamping leaves them unchanged (-0 included) */
            const vmask accept = mand(veq(s, sc), veq(t, tc));
            for (int c = 0; c < 3; ++c)
                d[c] = (sc * d1[c] - w[c]) - tc * d2[c]; /* (P + sc d1) - (Q + tc d2) */
            kx_keep(best, accept, kx_dot(d, d), TTD_EXACT_EE + 3 * i + j, KX_LBL(2, i, j), 2, 2, sc, tc, zero);
        }
    }
}

/* scalar: exact_vertex_face. 3 candidates: vertices of X over the face of Y; f gets the
 * vertices' face coordinates for the crossings. */
TTDW_FN void kx_vertex_face(const kx_tri *X, const kx_tri *Y, int id0,
                            kx_best *best, kx_fc f[3])
{
    for (int i = 0; i < 3; ++i) {
        vreal b;
        f[i] = kx_face_coords(Y, X->v[i]);
        const vreal c = f[i].c, h = f[i].h;
        const vmask inside = kx_face_weights(Y, c, f[i].g, &b);
        /* the squared distance to the plane, h^2 / |n|^2 */
        const int lbl = id0 == TTD_EXACT_VF_S ? KX_LBL(3, i, 0) : KX_LBL(4, 0, i);
        kx_keep(best, inside, (h * Y->inv_nn) * h, id0 + i, lbl, 2, 2, b, c, b);
    }
}

/* scalar: exact_crossings. 3 candidates: edges of X (whose vertices' face coordinates over Y
 * are f) with ends strictly on opposite sides of Y's plane, crossing it inside the face
 * (distance 0). The crossing's coordinates are the ends' interpolated with tau. */
TTDW_FN void kx_crossings(const kx_tri *Y, int id0, kx_best *best,
                          const kx_fc f[3])
{
    const vreal zero = vzero();
    /* Only a lane whose other triangle has a face and whose vertices lie strictly on both sides
     * of its plane can have a crossing: when no lane does, every candidate below is rejected
     * (the scalar code's `continue`), so the pass is skipped. Predictable either way: separated
     * pairs of a mesh query skip it in 80-95% of the groups, random pairs almost never. */
    const vmask below = mor(mor(vlt(f[0].h, zero), vlt(f[1].h, zero)), vlt(f[2].h, zero));
    const vmask above = mor(mor(vgt(f[0].h, zero), vgt(f[1].h, zero)), vgt(f[2].h, zero));
    if (mnone(mand(Y->has_face, mand(below, above))))
        return;
    for (int i = 0; i < 3; ++i) {
        const kx_fc f0 = f[i], f1 = f[(i + 1) % 3];
        const vreal h0 = f0.h, h1 = f1.h;
        const vmask opposite = mor(mand(vlt(h0, zero), vgt(h1, zero)), mand(vgt(h0, zero), vlt(h1, zero)));
        const vreal tau = h0 / (h0 - h1); /* no cancellation: opposite signs */
        const vreal c = f0.c + tau * (f1.c - f0.c);
        const vreal g = f0.g + tau * (f1.g - f0.g);
        vreal b;
        const vmask inside = mand(opposite, kx_face_weights(Y, c, g, &b));
        const int lbl = id0 == TTD_EXACT_X_S ? KX_LBL(5, i, 0) : KX_LBL(6, 0, i);
        kx_keep(best, inside, zero, id0 + i, lbl, 3, 1, tau, b, c);
    }
}

/* scalar: exact_edge_point, for the edge picked per lane by the masks e0, e1 (else edge 2). */
TTDW_FN void kx_edge_point_sel(const kx_tri *X, vmask e0, vmask e1, vreal t, vreal p[3],
                               vreal w[3])
{
    const vreal zero = vzero(), one = vset1((real)1);
    for (int c = 0; c < 3; ++c) {
        const vreal p0 = X->v[0][c] + t * X->e[0][c];
        const vreal p1 = X->v[1][c] + t * X->e[1][c];
        const vreal p2 = X->v[2][c] + t * X->e[2][c];
        p[c] = vsel(e0, p0, vsel(e1, p1, p2));
    }
    const vreal a = one - t;
    /* edge i: w[i] = 1 - t, w[i+1] = t */
    w[0] = vsel(e0, a, vsel(e1, zero, t));
    w[1] = vsel(e0, t, vsel(e1, a, zero));
    w[2] = vsel(e0, zero, vsel(e1, t, a));
}

/* scalar: exact_rebuild. p, q and their weights from (id, u, v, w), the scalar expressions
 * chosen per lane: for each side, a vertex, an edge point or a face point. */
TTDW_FN void kx_rebuild(const kx_best *best, const kx_tri *S,
                        const kx_tri *T, vreal p[3], vreal q[3], vreal wp[3], vreal wq[3])
{
    const vreal zero = vzero(), one = vset1((real)1), id = best->id;
#define KX_IN(lo, hi) mand(vge(id, vset1((real)(lo))), vlt(id, vset1((real)(hi))))
#define KX_IS(v_) veq(id, vset1((real)(v_)))
    const vmask ve_s = KX_IN(TTD_EXACT_VE_S, TTD_EXACT_VE_T), ve_t = KX_IN(TTD_EXACT_VE_T, TTD_EXACT_EE);
    const vmask ee = KX_IN(TTD_EXACT_EE, TTD_EXACT_VF_S), vf_s = KX_IN(TTD_EXACT_VF_S, TTD_EXACT_VF_T);
    const vmask vf_t = KX_IN(TTD_EXACT_VF_T, TTD_EXACT_X_S), x_s = KX_IN(TTD_EXACT_X_S, TTD_EXACT_X_T);
    /* Which vertex or edge of S (sv, se) and of T (tv, te) the id names:
     *   VE_S 3i+j: vertex i of S, edge j of T     VE_T 9+3j+i: vertex j of T, edge i of S
     *   EE 18+3i+j: edge i of S, edge j of T       VF_S 27+i: vertex i of S   VF_T 30+j: vertex j of T
     *   X_S 33+i: edge i of S                      X_T 36+j: edge j of T */
    vmask s0 = mnot(mtrue()), s1 = s0, t0 = s0, t1 = s0;
    for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) {
            const vmask m_ve_s = KX_IS(TTD_EXACT_VE_S + 3 * a + b), m_ve_t = KX_IS(TTD_EXACT_VE_T + 3 * a + b);
            const vmask m_ee = KX_IS(TTD_EXACT_EE + 3 * a + b);
            /* S index: a for VE_S and EE, b for VE_T; T index: b for VE_S and EE, a for VE_T */
            const vmask sa = mor(m_ve_s, m_ee), sb = m_ve_t, ta = m_ve_t, tb = mor(m_ve_s, m_ee);
            if (a == 0) { s0 = mor(s0, sa); t0 = mor(t0, ta); }
            if (a == 1) { s1 = mor(s1, sa); t1 = mor(t1, ta); }
            if (b == 0) { s0 = mor(s0, sb); t0 = mor(t0, tb); }
            if (b == 1) { s1 = mor(s1, sb); t1 = mor(t1, tb); }
        }
    for (int a = 0; a < 2; ++a) {
        if (a == 0) {
            s0 = mor(s0, mor(KX_IS(TTD_EXACT_VF_S), KX_IS(TTD_EXACT_X_S)));
            t0 = mor(t0, mor(KX_IS(TTD_EXACT_VF_T), KX_IS(TTD_EXACT_X_T)));
        } else {
            s1 = mor(s1, mor(KX_IS(TTD_EXACT_VF_S + 1), KX_IS(TTD_EXACT_X_S + 1)));
            t1 = mor(t1, mor(KX_IS(TTD_EXACT_VF_T + 1), KX_IS(TTD_EXACT_X_T + 1)));
        }
    }
#undef KX_IN
#undef KX_IS
    const vmask x_t = vge(id, vset1((real)TTD_EXACT_X_T));
    /* the candidate points on each side */
    vreal sv[3], se[3], sf[3], tv[3], te[3], tf[3], wsv[3], wse[3], wsf[3], wtv[3], wte[3], wtf[3];
    for (int c = 0; c < 3; ++c) {
        sv[c] = vsel(s0, S->v[0][c], vsel(s1, S->v[1][c], S->v[2][c]));
        tv[c] = vsel(t0, T->v[0][c], vsel(t1, T->v[1][c], T->v[2][c]));
        wsv[c] = vsel(c == 0 ? s0 : c == 1 ? mandnot(s1, s0) : mnot(mor(s0, s1)), one, zero);
        wtv[c] = vsel(c == 0 ? t0 : c == 1 ? mandnot(t1, t0) : mnot(mor(t0, t1)), one, zero);
    }
    /* edge parameters: u for VE (on Y), EE on S, and the crossings; v for EE on T */
    kx_edge_point_sel(S, s0, s1, best->u, se, wse);
    kx_edge_point_sel(T, t0, t1, vsel(ee, best->v, best->u), te, wte);
    /* face points: VF_T lands on S's face with (u, v), VF_S on T's with (u, v), a crossing of
     * S's edge on T's face with (v, w), of T's edge on S's face with (v, w) */
    const vmask face_uv_s = vf_t, face_uv_t = vf_s;
    kx_face_point(S, vsel(face_uv_s, best->u, best->v), vsel(face_uv_s, best->v, best->w), sf, wsf);
    kx_face_point(T, vsel(face_uv_t, best->u, best->v), vsel(face_uv_t, best->v, best->w), tf, wtf);
    /* p: vertex (VE_S, VF_S), edge point of S (VE_T, EE, X_S), face point of S (VF_T), the
     * crossing point on T's edge (X_T); q likewise, mirrored */
    const vmask p_vertex = mor(ve_s, vf_s), p_edge = mor(ve_t, mor(ee, x_s)), p_face = vf_t;
    const vmask q_vertex = mor(ve_t, vf_t), q_edge = mor(ve_s, mor(ee, x_t)), q_face = vf_s;
    for (int c = 0; c < 3; ++c) {
        p[c] = vsel(p_vertex, sv[c], vsel(p_edge, se[c], vsel(p_face, sf[c], te[c])));
        q[c] = vsel(q_vertex, tv[c], vsel(q_edge, te[c], vsel(q_face, tf[c], se[c])));
        /* weights: a crossing's other side has the face weights of the crossing point */
        wp[c] = vsel(p_vertex, wsv[c], vsel(p_edge, wse[c], wsf[c]));
        wq[c] = vsel(q_vertex, wtv[c], vsel(q_edge, wte[c], wtf[c]));
    }
}

/* x rounded to the nearest integer (|x| < 2^(mantissa bits - 1)): adding and removing 1.5 2^52
 * (2^23 in float) leaves only the integer part, as -ffp-contract=off keeps both roundings. */
TTDW_FN vreal kx_round(vreal x)
{
#ifdef TTD_PRECISION_DOUBLE
    const vreal magic = vset1(0x1.8p52);
#else
    const vreal magic = vset1(0x1.8p23f);
#endif
    return (x + magic) - magic;
}

/* x[i] for i in {0, 1, 2} picked per lane by the masks i0, i1 (else 2). */
TTDW_FN vreal kx_sel3(vmask i0, vmask i1, vreal x0, vreal x1, vreal x2)
{
    return vsel(i0, x0, vsel(i1, x1, x2));
}

/* The winner's p and q from its label (KX_LBL) and parameters, with the scalar code's
 * expressions (exact_rebuild): a vertex, an edge point v + t e, or a face point
 * (v[k] + b L) + c M on each side; a crossing is the edge point on both. Weights are not
 * computed: this is the KX_POINTS path. */
TTDW_FN void kx_rebuild_points(const kx_best *best, const kx_tri *S, const kx_tri *T, vreal p[3],
                               vreal q[3])
{
    const vreal u = best->u, v = best->v;
    /* label = 9 cls + 3 a + b with a, b in 0..2: each is an exact small integer */
    const vreal cls = kx_round((best->id - vset1((real)4)) * vset1((real)1 / (real)9));
    const vreal r = best->id - vset1((real)9) * cls;
    const vreal a = kx_round((r - vset1((real)1)) * vset1((real)1 / (real)3));
    const vreal b = r - vset1((real)3) * a;
    const vreal one = vset1((real)1), two = vset1((real)2);
    const vmask a0 = veq(a, vzero()), a1 = veq(a, one), b0 = veq(b, vzero()), b1 = veq(b, one);
    const vmask c0 = veq(cls, vzero()), c1 = veq(cls, one), c2 = veq(cls, two);
    const vmask c3 = veq(cls, vset1((real)3)), c4 = veq(cls, vset1((real)4)), c5 = veq(cls, vset1((real)5));
    const vmask c6 = veq(cls, vset1((real)6));
    /* p: S's vertex a (VE_S, VF_S), S's edge a at u (VE_T, EE, X_S), S's face (VF_T), T's
     * edge b at u (X_T); q: T's vertex b (VE_T, VF_T), T's edge b at u or (EE) v (VE_S, EE,
     * X_T), T's face (VF_S), S's edge a at u (X_S) */
    const vmask p_vertex = mor(c0, c3), p_edge = mor(mor(c1, c2), c5);
    const vmask q_vertex = mor(c1, c4), q_edge = mor(mor(c0, c2), c6);
    const vreal tq = vsel(c2, v, u);
    for (int c = 0; c < 3; ++c) {
        const vreal sa = kx_sel3(a0, a1, S->v[0][c], S->v[1][c], S->v[2][c]);
        const vreal tb = kx_sel3(b0, b1, T->v[0][c], T->v[1][c], T->v[2][c]);
        const vreal s_edge = sa + u * kx_sel3(a0, a1, S->e[0][c], S->e[1][c], S->e[2][c]);
        const vreal t_edge = tb + tq * kx_sel3(b0, b1, T->e[0][c], T->e[1][c], T->e[2][c]);
        const vreal s_face = (S->vk[c] + u * S->L[c]) + v * S->M[c];
        const vreal t_face = (T->vk[c] + u * T->L[c]) + v * T->M[c];
        p[c] = vsel(p_vertex, sa, vsel(p_edge, s_edge, vsel(c4, s_face, t_edge)));
        q[c] = vsel(q_vertex, tb, vsel(q_edge, t_edge, vsel(c3, t_face, s_edge)));
    }
}

/* One group of W pairs: scalar exact_pair, steps 1-4. mode is a constant at each call: with
 * KX_DIST (distances only) the winner is not rebuilt, and the compiler drops the selection's
 * id and parameters with it, leaving a running minimum of d2; with KX_POINTS only p and q are
 * rebuilt (no weights, features or flags). The distance is the same bits in every mode (the
 * minimum does not depend on which candidate attains it). */
KX_GROUP_INLINE void kx_group(const vreal Sin[9], const vreal Tin[9], kw_out *out, const int mode)
{
    const vreal zero = vzero(), one = vset1((real)1);
    /* 1. Normalise: halve twice near the overflow limit, translate to A, scale by 2^-e with
     * the pair's extent m (the largest side of the box around the six vertices, whatever
     * their order) = f 2^e, f in [0.5, 1). 2^-e is 0.5 / (m with its mantissa cleared); the
     * one product equals the scalar's two (f1, f2) wherever neither rounds, i.e. except for
     * coordinates below REAL_MIN of the pair's extent. */
    /* the box around the six vertices; its corners also give the largest |coordinate| */
    vreal lo[3], hi[3], m0 = zero;
    for (int c = 0; c < 3; ++c) {
        lo[c] = hi[c] = Sin[c];
        for (int i = 1; i < 6; ++i) {
            const vreal x = i < 3 ? Sin[3 * i + c] : Tin[3 * (i - 3) + c];
            lo[c] = vmin(lo[c], x);
            hi[c] = vmax(hi[c], x);
        }
        m0 = vmax(m0, vmax(vabs(lo[c]), vabs(hi[c])));
    }
    const vmask huge = vgt(m0, vset1(TTD_REAL_MAX * (real)0.25));
    const vreal pre = vsel(huge, vset1((real)0.25), one);
    /* Multiplying by pre = 1 is exact, so it is skipped when no lane needs the pre-scale (a
     * branch that real data never takes, hence predicted); likewise the lift below. */
    vreal sp[9], tp[9];
    for (int i = 0; i < 9; ++i) {
        sp[i] = Sin[i];
        tp[i] = Tin[i];
    }
    const int any_huge = many(huge);
    if (any_huge)
        for (int i = 0; i < 9; ++i) {
            sp[i] = Sin[i] * pre;
            tp[i] = Tin[i] * pre;
        }
    vreal o[3], rel[18];
    for (int c = 0; c < 3; ++c)
        o[c] = sp[c];
    for (int i = 0; i < 9; ++i) {
        rel[i] = sp[i] - o[i % 3];
        rel[9 + i] = tp[i] - o[i % 3];
    }
    /* the extent; the pre-scale is monotone, so the box scales with it */
    vreal m = zero;
    for (int c = 0; c < 3; ++c)
        m = vmax(m, any_huge ? hi[c] * pre - lo[c] * pre : hi[c] - lo[c]);
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
    if (many(tiny))
        for (int i = 0; i < 18; ++i)
            rel[i] = rel[i] * up;
    kx_tri S, T;
    for (int i = 0; i < 3; ++i)
        for (int c = 0; c < 3; ++c) {
            S.v[i][c] = rel[3 * i + c] * inv;
            T.v[i][c] = rel[9 + 3 * i + c] * inv;
        }
    kx_tri_init(&S);
    kx_tri_init(&T);

    /* 2. Candidates, in the scalar code's order and with its ids. */
    kx_best best;
    best.d2 = vset1(TTD_REAL_MAX);
    best.id = best.u = best.v = best.w = zero;
    best.mode = mode;
    kx_fc fs[3], ft[3]; /* S's vertices over T's face, and T's over S's */
    vreal rdot[9];               /* vertex-edge dots of S's vertices on T's edges */
    kx_vertex_edge(&S, &T, TTD_EXACT_VE_S, &best, rdot);
    kx_vertex_edge(&T, &S, TTD_EXACT_VE_T, &best, NULL);
    kx_edge_edge(&S, &T, &best, rdot);
    kx_vertex_face(&S, &T, TTD_EXACT_VF_S, &best, fs);
    kx_vertex_face(&T, &S, TTD_EXACT_VF_T, &best, ft);
    kx_crossings(&T, TTD_EXACT_X_S, &best, fs);
    kx_crossings(&S, TTD_EXACT_X_T, &best, ft);

    /* 3. A distance within rounding of 0 is a contact. */
    vreal d = vsqrt(best.d2);
    const vmask touch = vle(d, vset1((real)TTD_EXACT_TOUCH_EPS * TTD_REAL_EPS));
    d = vsel(touch, zero, d);

    /* 4. Scale back and add the origin back. */
    /* 1/pre is 4 or 1, exact; without a huge lane it is 1 and the clamps below change nothing
     * (every point lies in its triangle's box, within REAL_MAX/4 up to rounding), so both are
     * skipped: the same bits */
    const vreal unpre = vsel(huge, vset1((real)4), one);
    out->distance = any_huge ? d * g * unpre : d * g;
    if (mode == KX_POINTS) {
        vreal bp[3], bq[3];
        kx_rebuild_points(&best, &S, &T, bp, bq);
        const vreal big = vset1(TTD_REAL_MAX), mbig = vset1(-TTD_REAL_MAX);
        for (int c = 0; c < 3; ++c) {
            out->p[c] = bp[c] * g + o[c];
            out->q[c] = bq[c] * g + o[c];
            if (any_huge) {
                out->p[c] = vmin(vmax(out->p[c] * unpre, mbig), big);
                out->q[c] = vmin(vmax(out->q[c] * unpre, mbig), big);
            }
        }
    } else if (mode == KX_FULL) {
        vreal bp[3], bq[3], wp[3], wq[3];
        kx_rebuild(&best, &S, &T, bp, bq, wp, wq);
        /* a point within rounding of REAL_MAX can round past it: clamp, as the scalar code does */
        const vreal big = vset1(TTD_REAL_MAX), mbig = vset1(-TTD_REAL_MAX);
        for (int c = 0; c < 3; ++c) {
            out->p[c] = vmin(vmax((bp[c] * g + o[c]) * unpre, mbig), big);
            out->q[c] = vmin(vmax((bq[c] * g + o[c]) * unpre, mbig), big);
            out->bary_p[c] = wp[c];
            out->bary_q[c] = wq[c];
        }
    }
    out->iterations = zero;
    out->flags_nc = 0;
    out->flags_int = mbits(touch);
    out->flags_ds = mbits(mnot(S.has_face));
    out->flags_dt = mbits(mnot(T.has_face));
}

/* The three specialisations of the group loop over n pairs (n <= TTD_BLOCK_PAIRS); pad lanes
 * compute a harmless pair and are never stored. */
static TTD_DEVICE void kx_run_dist(size_t n, const real *s, const real *t, real *distance)
{
    for (size_t i0 = 0; i0 < n; i0 += TTDW_LANES) {
        const int live = n - i0 < (size_t)TTDW_LANES ? (int)(n - i0) : TTDW_LANES;
        vreal S[9], T[9];
        kw_load_group(s + 9 * i0, t + 9 * i0, live, S, T);
        kw_out o;
        kx_group(S, T, &o, KX_DIST);
        kw_store_distance(o.distance, live, distance + i0);
    }
}

/* idx: where not NULL, pair i's outputs go to index idx[i] of distance and points (kx_flush). */
static TTD_DEVICE void kx_run_points(size_t n, const real *s, const real *t, real *distance, real *points,
                                     const size_t *idx)
{
    for (size_t i0 = 0; i0 < n; i0 += TTDW_LANES) {
        const int live = n - i0 < (size_t)TTDW_LANES ? (int)(n - i0) : TTDW_LANES;
        vreal S[9], T[9];
        kw_load_group(s + 9 * i0, t + 9 * i0, live, S, T);
        kw_out o;
        kx_group(S, T, &o, KX_POINTS);
        if (idx)
            kw_store_points_at(&o, live, idx + i0, distance, points);
        else
            kw_store_points(&o, live, distance ? distance + i0 : NULL, points + 6 * i0);
    }
}

static TTD_DEVICE void kx_run_full(size_t n, const real *s, const real *t, const ttd_out *out)
{
    for (size_t i0 = 0; i0 < n; i0 += TTDW_LANES) {
        const int live = n - i0 < (size_t)TTDW_LANES ? (int)(n - i0) : TTDW_LANES;
        vreal S[9], T[9];
        kw_load_group(s + 9 * i0, t + 9 * i0, live, S, T);
        kw_out o;
        kx_group(S, T, &o, KX_FULL);
        kw_store_group(&o, live, out, i0);
    }
}

/* The pairs of out (offset 0) for n pairs, whichever outputs it names. */
static TTD_DEVICE void kx_run(size_t n, const real *s, const real *t, const ttd_out *out)
{
    if (out->results)
        kx_run_full(n, s, t, out);
    else if (out->points)
        kx_run_points(n, s, t, out->distance, out->points, NULL);
    else
        kx_run_dist(n, s, t, out->distance);
}

/* A lower bound on each lane's distance, cheap next to the exact method, for the early-out
 * against the caller's bound: the gap between the two triangles' projections on the line
 * through their centroids (a separating axis whenever the triangles are apart; over candidate
 * pairs of a mesh query at 0.2% to 1% of the mesh's size it rules out 87% to 95% of the pairs
 * farther than the margin, docs/simd.md 7.1b). Computed on the input coordinates: each
 * projection c.x rounds by at most 3 eps |c| |x| (and |x| <= sqrt(3) M, M = the largest
 * |coordinate|), so gap/|c| - 32 eps M is below the true gap of the stored axis c (any c
 * gives a valid bound). Lanes where M is outside [2^-500, 2^500] (2^-50, 2^50 in float), where
 * the products could overflow or lose bits to underflow, get -inf (never ruled out). The
 * scalar row uses scalar/exact_impl.h's exact_lower_bound, the same operations in the same
 * order: the rows rule out the same pairs with the same bits. */
TTDW_FN vreal kx_screen(const vreal S[9], const vreal T[9])
{
#ifdef TTD_PRECISION_DOUBLE
    const vreal lo = vset1(0x1p-500), hi = vset1(0x1p500);
#else
    const vreal lo = vset1(0x1p-50f), hi = vset1(0x1p50f);
#endif
    vreal c[3], m = vzero();
    for (int k = 0; k < 3; ++k)
        c[k] = ((T[k] + T[3 + k]) + T[6 + k]) - ((S[k] + S[3 + k]) + S[6 + k]);
    for (int k = 0; k < 9; ++k)
        m = vmax(m, vmax(vabs(S[k]), vabs(T[k])));
    vreal ps[3], pt[3];
    for (int i = 0; i < 3; ++i) {
        ps[i] = c[0] * S[3 * i] + c[1] * S[3 * i + 1] + c[2] * S[3 * i + 2];
        pt[i] = c[0] * T[3 * i] + c[1] * T[3 * i + 1] + c[2] * T[3 * i + 2];
    }
    const vreal smin = vmin(vmin(ps[0], ps[1]), ps[2]), smax = vmax(vmax(ps[0], ps[1]), ps[2]);
    const vreal tmin = vmin(vmin(pt[0], pt[1]), pt[2]), tmax = vmax(vmax(pt[0], pt[1]), pt[2]);
    const vreal gap = vmax(tmin - smax, smin - tmax);
    const vreal lb = gap / vsqrt(kx_dot(c, c)) - vset1((real)32 * TTD_REAL_EPS) * m;
    const vmask ok = mand(vge(m, lo), vle(m, hi));
    return vsel(ok, lb, vset1(-(real)INFINITY));
}

#define KX_CHUNK 64 /* pairs gathered per call of kx_run in the screened path (up to W more) */

/* Writes what a pair ruled out by the screen gets, for the live lanes of a group at pair i0 (the
 * lanes that are not ruled out are overwritten later): its lower bound (at least 0) as the
 * distance, NaN points, and in results the bound, NaN points and weights, no flags. */
static TTD_DEVICE void kx_write_far(const ttd_out *out, size_t i0, int live, vreal lb)
{
    const real nan = (real)NAN;
    lb = vmax(lb, vzero());
    if (out->distance)
        kw_store_distance(lb, live, out->distance + i0);
    if (out->points) {
        if (live == TTDW_LANES) { /* a whole group's 6 W reals by vectors: the same bytes */
            const vreal vnan = vset1(nan);
            for (int k = 0; k < 6; ++k)
                vstoreu(out->points + 6 * i0 + (size_t)k * TTDW_LANES, vnan);
        } else {
            for (size_t k = 0; k < 6 * (size_t)live; ++k)
                out->points[6 * i0 + k] = nan;
        }
    }
    if (out->results) {
        real buf[TTDW_LANES];
        vstoreu(buf, lb);
        for (int i = 0; i < live; ++i) {
            ttd_result *r = &out->results[i0 + (size_t)i];
            r->distance = buf[i];
            for (int k = 0; k < 3; ++k)
                r->p[k] = r->q[k] = r->bary_p[k] = r->bary_q[k] = nan;
            r->flags = 0;
            r->feature_p = r->feature_q = 0;
            r->iterations = 0;
        }
    }
}

/* Runs the nf gathered pairs of bs, bt and scatters their outputs to the indices idx of out. */
static TTD_DEVICE void kx_flush(int nf, const real *bs, const real *bt, const size_t *idx, const ttd_out *out)
{
    if (out->points && !out->results) {
        /* each lane's points and distance written straight to its index, not through a buffer
         * copied after: the same values to the same places */
        kx_run_points((size_t)nf, bs, bt, out->distance, out->points, idx);
        return;
    }
    real bd[KX_CHUNK + TTDW_LANES], bp[6 * (KX_CHUNK + TTDW_LANES)];
    ttd_result br[KX_CHUNK + TTDW_LANES];
    const ttd_out bout = {out->distance ? bd : NULL, out->points ? bp : NULL, out->results ? br : NULL};
    kx_run((size_t)nf, bs, bt, &bout);
    for (int j = 0; j < nf; ++j) {
        if (out->distance)
            out->distance[idx[j]] = bd[j];
        if (out->points)
            memcpy(out->points + 6 * idx[j], bp + 6 * j, 6 * sizeof(real));
        if (out->results)
            out->results[idx[j]] = br[j];
    }
}

/* The early-out for a finite bound: each group is screened (kx_screen); every live lane first
 * gets kx_write_far, and the lanes whose lower bound does not exceed bound are gathered,
 * KX_CHUNK at a time, into a contiguous buffer for the exact method (which overwrites their
 * outputs), so that the lanes that need it stay full. The gather copies every lane and keeps
 * the ones it needs by advancing its count, without a branch per lane (ruled-out lanes come
 * unpredictably). A group with nothing ruled out while nothing is pending runs in place; one
 * with everything ruled out copies nothing. */
static TTD_DEVICE void kx_screened(size_t n, const real *s, const real *t, real bound, const ttd_out *out)
{
    real bs[9 * (KX_CHUNK + TTDW_LANES)], bt[9 * (KX_CHUNK + TTDW_LANES)];
    size_t idx[KX_CHUNK + TTDW_LANES];
    int nf = 0;
    const vreal vb = vset1(bound);
    for (size_t i0 = 0; i0 < n; i0 += TTDW_LANES) {
        const int live = n - i0 < (size_t)TTDW_LANES ? (int)(n - i0) : TTDW_LANES;
        vreal S[9], T[9];
        kw_load_group(s + 9 * i0, t + 9 * i0, live, S, T);
        const vreal lb = kx_screen(S, T);
        const unsigned keep = ~mbits(vgt(lb, vb)) & mbits(mfirst(live));
        if (keep == mbits(mfirst(live)) && nf == 0) {
            ttd_out o = {out->distance ? out->distance + i0 : NULL, out->points ? out->points + 6 * i0 : NULL,
                         out->results ? out->results + i0 : NULL};
            kx_run((size_t)live, s + 9 * i0, t + 9 * i0, &o);
            continue;
        }
        kx_write_far(out, i0, live, lb);
        if (!keep)
            continue;
        for (int i = 0; i < live; ++i) {
            memcpy(bs + 9 * nf, s + 9 * (i0 + (size_t)i), 9 * sizeof(real));
            memcpy(bt + 9 * nf, t + 9 * (i0 + (size_t)i), 9 * sizeof(real));
            idx[nf] = i0 + (size_t)i;
            nf += (int)((keep >> i) & 1u);
        }
        if (nf >= KX_CHUNK) {
            kx_flush(nf, bs, bt, idx, out);
            nf = 0;
        }
    }
    if (nf)
        kx_flush(nf, bs, bt, idx, out);
}

static TTD_DEVICE void kernel_exact(size_t n, const real *s, const real *t, const ttd_params *prm, real bound,
                                    const ttd_out *out)
{
    (void)prm;
    if (bound < TTD_REAL_MAX)
        kx_screened(n, s, t, bound, out);
    else
        kx_run(n, s, t, out);
}

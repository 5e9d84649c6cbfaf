/* SPDX-License-Identifier: MIT */
/* The certified mode, precision-generic (certified_d.c and certified_f.c compile
 * it once each).
 *
 * 1. The optimised penalty method (ttd_penalty_pair_d/f) runs as usual.
 * 2. Its final weights say which of the six constraints a, b, c >= 0 (S) and g, d, f >= 0 (T)
 *    are active: a weight clamped to 0 is an active constraint. The vertices with a positive
 *    weight are the feature of each triangle (vertex, edge or face).
 * 3. The distance between the two features is solved exactly, in closed form, with the exact
 *    method's care (longest-edge face frame with an accurate normal, see exact-method.md 3.3):
 *      vertex-vertex   the two vertices;
 *      vertex-edge     the vertex projected onto the edge's line;
 *      vertex-face     the vertex projected onto the face's plane;
 *      edge-edge       the stationary point of the two lines, then clamped to the segments
 *                      (the segments' closest pair, for answers at an end of an edge);
 *                      parallel lines: the penalty's point on the first edge, projected
 *                      onto the second and back;
 *      edge-face, face-face: in 3D the closest pair of two features of total dimension >= 3 is
 *                      either not unique (parallel) or a crossing; the penalty's point on S
 *                      (on T for face-edge) is kept and projected onto the other face.
 * 4. The check. The solved weights must be feasible (>= -FEAS, then clamped onto the
 *    triangle). With w = p - q, the KKT multiplier of the active constraint "weight of
 *    vertex V_i of S >= 0" is 2 w.(V_i - p), that of T's vertex W_j is 2 w.(q - W_j); for the
 *    vertices inside the features the same expressions are the stationarity residuals (0 at
 *    an exact solution of step 3). The minima m_S, m_T over all six vertices give the
 *    certificate: the planes normal to w through the extreme vertices separate the
 *    triangles, so for ANY w
 *        true distance >= LB = (|w|^2 + m_S + m_T) / |w|,     true distance <= |w|,
 *    both up to the rounding of these few dot products and of p and q (~18 eps of double in
 *    the frame: this part runs in double for both precisions). The pair is accepted when
 *    |w| - LB <= GAP (the multipliers are non-negative and the residuals 0, up to GAP |w|
 *    together) and LB > TOUCH (certainly apart). Checking only the active constraints'
 *    multipliers and trusting the solve for the rest is not enough: for an edge nearly
 *    parallel to a face the objective is flat along the pair of features, and a residual
 *    below rounding let a point 4e-13 off pass (docs/certified-mode.md).
 * 5. Where the check fails, a clear crossing (cert_crossing, CROSS in certified_tol.h) is a
 *    certified contact: distance 0, flagged intersecting. Every other pair, touching ones
 *    included, goes to the exact method (ttd_exact_pair_d/f) and is flagged TTD_PAIR_FALLBACK. Correctness rests on
 *    the check alone: a wrong active set or an inaccurate solve only costs a fallback.
 *
 * The lane kernel (simd/kernel_certified.h) computes every case in every lane and selects;
 * this file computes only the lane's case, with the same expressions in the same order, so
 * that the two agree to the bit. Thresholds: core/certified_tol.h. */

/* One triangle in the frame with the exact method's per-triangle data (exact_tri_init). */
typedef struct cert_tri {
    real v[3][3], e[3][3], ee[3], inv_ee[3];
    int k;
    real L[3], M[3], n[3];
    real nn, inv_nn, ML;
    int has_face;
} cert_tri;

static real cert_dot(const real a[3], const real b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void cert_cross(const real a[3], const real b[3], real out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

/* exact_clamp01 */
static real cert_clamp01(real x)
{
    return x < (real)0 ? (real)0 : (x > (real)1 ? (real)1 : x);
}

static real cert_pos(real v)
{
    return (v + TTD_FABS(v)) * (real)0.5;
}

#ifdef TTD_PRECISION_DOUBLE
/* exact_impl.h's exact_dop_d and exact_cross_acc_d: the face normal accurate in direction
 * for slivers (Kahan's FMA difference of products when the naive one is unreliable). */
static double cert_dop(double a, double b, double c, double d)
{
    double w = c * d;
    double err = fma(c, d, -w);
    double f = fma(a, b, -w);
    return f - err;
}

static double cert_cross_acc(const double a[3], const double b[3], double aa, double bb, double out[3])
{
    cert_cross(a, b, out);
    double nn = cert_dot(out, out);
    if (nn < 0x1p-20 * aa * bb) {
        out[0] = cert_dop(a[1], b[2], a[2], b[1]);
        out[1] = cert_dop(a[2], b[0], a[0], b[2]);
        out[2] = cert_dop(a[0], b[1], a[1], b[0]);
        nn = cert_dot(out, out);
    }
    return nn;
}
#else
/* exact_cross_acc_f: float products are exact in double. */
static float cert_cross_acc(const float a[3], const float b[3], float aa, float bb, float out[3])
{
    (void)aa;
    (void)bb;
    out[0] = (float)((double)a[1] * (double)b[2] - (double)a[2] * (double)b[1]);
    out[1] = (float)((double)a[2] * (double)b[0] - (double)a[0] * (double)b[2]);
    out[2] = (float)((double)a[0] * (double)b[1] - (double)a[1] * (double)b[0]);
    return cert_dot(out, out);
}
#endif

/* exact_tri_init, on vertices already in the frame. */
static void cert_tri_init(cert_tri *T)
{
    for (int i = 0; i < 3; ++i) {
        for (int c = 0; c < 3; ++c)
            T->e[i][c] = T->v[(i + 1) % 3][c] - T->v[i][c];
        T->ee[i] = cert_dot(T->e[i], T->e[i]);
        T->inv_ee[i] = T->ee[i] >= TTD_REAL_MIN ? (real)1 / T->ee[i] : (real)0;
    }
    int k = 0;
    if (T->ee[1] > T->ee[k]) k = 1;
    if (T->ee[2] > T->ee[k]) k = 2;
    T->k = k;
    const int km = (k + 2) % 3;
    for (int c = 0; c < 3; ++c) {
        T->L[c] = T->e[k][c];
        T->M[c] = -T->e[km][c];
    }
    T->nn = cert_cross_acc(T->L, T->M, T->ee[k], T->ee[km], T->n);
    T->has_face = T->nn >= TTD_REAL_MIN;
    T->inv_nn = T->has_face ? (real)1 / T->nn : (real)0;
    T->ML = cert_dot(T->M, T->L);
}

/* The exact method's face projection (exact_face_coords, then exact_face_weights): the
 * weights of P's projection onto T's plane, against the longest edge (c across it, b along it
 * corrected by c), written as the three barycentric weights. b is exact_face_weights'
 * expression; c is taken in the per-point form n . (L x (P - v[k])) / nn, not as
 * dot(P - v[k], u) with the precomputed u = (n x L) / nn that exact_face_coords uses (the
 * same triple product, rounded differently; cert_tri has no u). A triangle without a face has
 * inv_nn = 0: c = 0 and the point lands on the longest edge's line, which the check then
 * judges like any other. */
static void cert_face_weights(const cert_tri *T, const real P[3], real w[3])
{
    const int k = T->k;
    real r[3], x[3];
    for (int i = 0; i < 3; ++i)
        r[i] = P[i] - T->v[k][i];
    cert_cross(T->L, r, x);
    const real cc = cert_dot(T->n, x) * T->inv_nn;
    const real bb = (cert_dot(r, T->L) - cc * T->ML) * T->inv_ee[k];
    const real aa = (real)1 - bb - cc;
    w[k] = aa;
    w[(k + 1) % 3] = bb;
    w[(k + 2) % 3] = cc;
}

/* Sum of weights times vertices, in the order w0 v0 + w1 v1 + w2 v2. */
static void cert_combine(const cert_tri *T, const real w[3], real p[3])
{
    for (int c = 0; c < 3; ++c)
        p[c] = w[0] * T->v[0][c] + w[1] * T->v[1][c] + w[2] * T->v[2][c];
}

/* kp_clamp_bary3's order: negative weights to 0, renormalised to sum 1. */
static void cert_clamp(const real x[3], real w[3])
{
    const real w0 = cert_pos(x[0]), w1 = cert_pos(x[1]), w2 = cert_pos(x[2]);
    const real sum = w0 + w1 + w2;
    const int pos = sum > 0;
    const real inv = (real)1 / (pos ? sum : (real)1);
    w[0] = pos ? w0 * inv : (real)1;
    w[1] = w1 * inv;
    w[2] = w2 * inv;
}

/* The feature of a weight triple: popcount of the positive weights, the vertex (1 bit) or the
 * edge (2 bits: edge i runs from v[i] to v[i+1], so the edge is the one after the missing
 * vertex). */
static void cert_feature(const real w[3], int *count, int *vertex, int *edge)
{
    const int z0 = w[0] > 0, z1 = w[1] > 0, z2 = w[2] > 0;
    *count = z0 + z1 + z2;
    *vertex = z0 ? 0 : (z1 ? 1 : 2);
    *edge = !z2 ? 0 : (!z0 ? 1 : 2);
}

/* Steps 3 and 4 for one pair in the frame: from the penalty's clamped weights pw, qw to the
 * solved, clamped weights wp, wq and |p - q| in the frame. Returns 1 when certified. */
static int cert_solve_check(const cert_tri *S, const cert_tri *T, const real pw[3],
                                     const real qw[3], real wp[3], real wq[3], real *dist)
{
    int ns, vi, ei, nt, vj, ej;
    cert_feature(pw, &ns, &vi, &ei);
    cert_feature(qw, &nt, &vj, &ej);
    /* A triangle without a face (collinear to far below rounding) is its longest edge. */
    if (ns == 3 && !S->has_face) {
        ns = 2;
        ei = S->k;
    }
    if (nt == 3 && !T->has_face) {
        nt = 2;
        ej = T->k;
    }
    real ppen[3], qpen[3], rp[3] = {0, 0, 0}, rq[3] = {0, 0, 0};
    cert_combine(S, pw, ppen);
    cert_combine(T, qw, qpen);
    /* the point of S projected onto T's face (a vertex, or the penalty's point), and back */
    const real *Xs = ns == 1 ? S->v[vi] : ppen;
    const real *Xt = nt == 1 ? T->v[vj] : qpen;
    const real *P = S->v[ei], *d1 = S->e[ei], *Q = T->v[ej], *d2 = T->e[ej];
    /* the penalty's points as parameters on the edges (their weights, up to rounding; for a
     * triangle taken as its longest edge, the projection) */
    real r0[3], r1[3];
    for (int c = 0; c < 3; ++c) {
        r0[c] = ppen[c] - P[c];
        r1[c] = qpen[c] - Q[c];
    }
    const real pen_s = cert_dot(r0, d1) * S->inv_ee[ei];
    const real pen_t = cert_dot(r1, d2) * T->inv_ee[ej];
    real s = 0, t = 0;
    if (ns == 2 && nt == 2) {
        /* edge-edge: exact_edge_edge's stationary point (s unclamped); parallel lines keep
         * the penalty's s */
        real n[3], w[3], x[3];
        cert_cross(d1, d2, n);
        const real nn = cert_dot(n, n);
        for (int c = 0; c < 3; ++c)
            w[c] = Q[c] - P[c];
        cert_cross(w, d2, x);
        const real d12 = cert_dot(d1, d2), wd1 = cert_dot(w, d1), wd2 = cert_dot(w, d2);
        s = nn >= TTD_REAL_MIN ? cert_dot(x, n) / nn : pen_s;
        /* The two segments' closest pair when the penalty's edges are right but the answer
         * sits at an end (nearly parallel edges, where the penalty cannot tell): s onto
         * [0, 1]; t, the projection of p(s), onto [0, 1]; when t was clamped or the lines are
         * parallel, s again as the projection of q(t) (for parallel lines p - q is then
         * normal to both). The check then tests the vertices left out. */
        const real sc = cert_clamp01(s);
        const real tt = (sc * d12 - wd2) * T->inv_ee[ej];
        t = cert_clamp01(tt);
        s = ((tt >= 0) & (tt <= 1) & (nn >= TTD_REAL_MIN)) ? sc
                                                         : cert_clamp01((t * d12 + wd1) * S->inv_ee[ei]);
    } else {
        if (ns == 2) {
            real r[3];
            for (int c = 0; c < 3; ++c)
                r[c] = Xt[c] - P[c];
            s = nt == 1 ? cert_dot(r, d1) * S->inv_ee[ei] : pen_s;
        }
        if (nt == 2) {
            real r[3];
            for (int c = 0; c < 3; ++c)
                r[c] = Xs[c] - Q[c];
            t = ns == 1 ? cert_dot(r, d2) * T->inv_ee[ej] : pen_t;
        }
    }
    /* raw weights of each side */
    if (ns == 1) {
        rp[vi] = 1;
    } else if (ns == 2) {
        rp[ei] = (real)1 - s;
        rp[(ei + 1) % 3] = s;
    } else if (nt == 3) {
        rp[0] = pw[0];
        rp[1] = pw[1];
        rp[2] = pw[2];
    } else {
        cert_face_weights(S, Xt, rp);
    }
    if (nt == 1) {
        rq[vj] = 1;
    } else if (nt == 2) {
        rq[ej] = (real)1 - t;
        rq[(ej + 1) % 3] = t;
    } else {
        cert_face_weights(T, Xs, rq);
    }
#ifdef TTD_PRECISION_DOUBLE
    const real feas = -TTD_CERT_FEAS_D, gap = TTD_CERT_GAP_D, touch = TTD_CERT_TOUCH_D;
#else
    const real feas = -TTD_CERT_FEAS_F, gap = TTD_CERT_GAP_F, touch = TTD_CERT_TOUCH_F;
#endif
    /* feasible (a NaN fails every compare) */
    int ok = (rp[0] >= feas) & (rp[1] >= feas) & (rp[2] >= feas) & (rq[0] >= feas) & (rq[1] >= feas) &
             (rq[2] >= feas);
    cert_clamp(rp, wp);
    cert_clamp(rq, wq);
    /* The check's arithmetic is in double for both precisions: in float, the rounding of p
     * and q and of these dot products (~18 float eps of the frame) would otherwise be most of
     * the error budget. The weights and vertices convert exactly. */
    double p[3], q[3], w[3], ds[3], dt[3];
    for (int c = 0; c < 3; ++c) {
        p[c] = (double)wp[0] * (double)S->v[0][c] + (double)wp[1] * (double)S->v[1][c] +
               (double)wp[2] * (double)S->v[2][c];
        q[c] = (double)wq[0] * (double)T->v[0][c] + (double)wq[1] * (double)T->v[1][c] +
               (double)wq[2] * (double)T->v[2][c];
        w[c] = p[c] - q[c];
    }
    for (int i = 0; i < 3; ++i) {
        double a[3], b[3];
        for (int c = 0; c < 3; ++c) {
            a[c] = (double)S->v[i][c] - p[c];
            b[c] = q[c] - (double)T->v[i][c];
        }
        ds[i] = w[0] * a[0] + w[1] * a[1] + w[2] * a[2]; /* half the multiplier of S's vertex i */
        dt[i] = w[0] * b[0] + w[1] * b[1] + w[2] * b[2]; /* half the multiplier of T's vertex i */
    }
    /* ds, dt: half the KKT multipliers of the constraints "weight of this vertex >= 0" for
     * the vertices outside the features (active), the stationarity residuals for those inside
     * (0 up to rounding when the solve is right). Their minima over all six vertices give
     * the separation that the planes normal to w through p and q prove:
     *     true distance >= (|w|^2 + min ds + min dt) / |w|. */
    double ls = ds[0] < ds[1] ? ds[0] : ds[1];
    ls = ls < ds[2] ? ls : ds[2];
    double lt = dt[0] < dt[1] ? dt[0] : dt[1];
    lt = lt < dt[2] ? lt : dt[2];
    const double ww = w[0] * w[0] + w[1] * w[1] + w[2] * w[2];
    const double nw = sqrt(ww);
    const double msum = ls + lt;
    ok &= (msum >= -(double)gap * nw) & (ww + msum > (double)touch * nw);
    *dist = (real)nw;
    return ok;
}

/* Edge i of X crossing Y's plane at tau = h0 / (h0 - h1): 1 when the crossing point lies
 * at least CROSS inside each edge line of Y, with the edge's weights in wx and the point's
 * in wy. */
static int cert_cross_edge(const cert_tri *X, const cert_tri *Y, int i, const real h[3],
                                    real nrm, real mw, real wx[3], real wy[3])
{
    const real h0 = h[i], h1 = h[(i + 1) % 3];
    const real tau = h0 / (h0 - h1);
    real xp[3], w[3];
    for (int c = 0; c < 3; ++c)
        xp[c] = X->v[i][c] + tau * X->e[i][c];
    cert_face_weights(Y, xp, w);
    if (!((w[0] * nrm >= mw) & (w[1] * nrm >= mw) & (w[2] * nrm >= mw)))
        return 0;
    wx[0] = wx[1] = wx[2] = 0;
    wx[i] = (real)1 - tau;
    wx[(i + 1) % 3] = tau;
    wy[0] = w[0];
    wy[1] = w[1];
    wy[2] = w[2];
    return 1;
}

/* A clear crossing of an edge of X through Y's face (certified_tol.h, CROSS). The edges whose
 * ends lie at least CROSS from Y's plane on opposite sides are at most two: the first and the
 * last of them in edge order are tried, in that order. Returns 1 with the edge's weights in
 * wx and the crossing point's weights in wy. */
static int cert_crossing(const cert_tri *X, const cert_tri *Y, real wx[3], real wy[3])
{
#ifdef TTD_PRECISION_DOUBLE
    const real margin = TTD_CERT_CROSS_D;
#else
    const real margin = TTD_CERT_CROSS_F;
#endif
    const int k = Y->k;
    real h[3];
    for (int i = 0; i < 3; ++i) {
        real r[3];
        for (int c = 0; c < 3; ++c)
            r[c] = X->v[i][c] - Y->v[k][c];
        h[i] = cert_dot(Y->n, r);
    }
    const real nrm = TTD_SQRT(Y->nn);
    const real mh = margin * nrm;                /* distance CROSS from the plane, times |n| */
    const real mw = margin * TTD_SQRT(Y->ee[k]); /* weight w_j |n| / |L| >= CROSS */
    int opp[3];
    for (int i = 0; i < 3; ++i) {
        const real h0 = h[i], h1 = h[(i + 1) % 3];
        opp[i] = ((h0 >= mh) & (h1 <= -mh)) | ((h0 <= -mh) & (h1 >= mh));
    }
    if (!(opp[0] | opp[1] | opp[2]) || !Y->has_face)
        return 0;
    const int first = opp[0] ? 0 : (opp[1] ? 1 : 2), last = opp[2] ? 2 : (opp[1] ? 1 : 0);
    return cert_cross_edge(X, Y, first, h, nrm, mw, wx, wy) ||
           cert_cross_edge(X, Y, last, h, nrm, mw, wx, wy);
}

static void certified_pair(const real s[9], const real t[9], const ttd_params *prm, ttd_result *r)
{
    ttd_result pen;
    scalar_penalty_pair(s, t, prm, &pen);

    /* The penalty method's frame (penalty_impl.h) without its subnormal lift, all six
     * vertices: A at 0, scaled by 2^-e (e from frexp of the largest relative coordinate,
     * clamped at emin instead), pre guarding the differences near REAL_MAX (its threshold
     * and factor as there, for the reasons given there). For a pair of subnormal size the
     * frame therefore stays below unit size, and the absolute thresholds (TOUCH, CROSS)
     * grow against the pair: such pairs fail the check and fall back to the exact method
     * (correct, only slower) once they are small enough (2,000 random pairs in double
     * scaled by 2^-1040: the intersecting ones, 11%, fall back; by 2^-1060, 82%; by
     * 2^-1070, all; unscaled, 0.1%). */
    real m0 = 0;
    for (int k = 0; k < 9; ++k) {
        if (TTD_FABS(s[k]) > m0) m0 = TTD_FABS(s[k]);
        if (TTD_FABS(t[k]) > m0) m0 = TTD_FABS(t[k]);
    }
    const real pre = m0 > TTD_REAL_MAX * (real)0.125 ? (real)0.0625 : (real)1;
    cert_tri S, T;
    real size = 0;
    for (int k = 0; k < 3; ++k) {
        const real a = s[k] * pre;
        for (int i = 0; i < 3; ++i) {
            S.v[i][k] = s[3 * i + k] * pre - a;
            T.v[i][k] = t[3 * i + k] * pre - a;
            if (TTD_FABS(S.v[i][k]) > size) size = TTD_FABS(S.v[i][k]);
            if (TTD_FABS(T.v[i][k]) > size) size = TTD_FABS(T.v[i][k]);
        }
    }
    int e = 0;
    (void)TTD_FREXP(size, &e);
    {
        const int emin = (int)sizeof(real) == (int)sizeof(double) ? DBL_MIN_EXP + 2 : FLT_MIN_EXP + 2;
        if (e < emin || !(size > 0)) e = emin; /* size 0: every vertex is A, any scale does */
    }
    const real scale = TTD_LDEXP((real)1, -e), unscale = TTD_LDEXP((real)1, e);
    for (int i = 0; i < 3; ++i)
        for (int k = 0; k < 3; ++k) {
            S.v[i][k] *= scale;
            T.v[i][k] *= scale;
        }
    cert_tri_init(&S);
    cert_tri_init(&T);

    real wp[3], wq[3], dist;
    int ok = cert_solve_check(&S, &T, pen.bary_p, pen.bary_q, wp, wq, &dist);
    int crossing = 0;
    if (!ok) {
        /* a clear crossing is a certified contact: distance 0, p and q the crossing point */
        crossing = cert_crossing(&S, &T, wp, wq) || cert_crossing(&T, &S, wq, wp);
        ok = crossing;
        dist = 0;
    }
    if (ok) {
        /* Vertices near +-REAL_MAX: the convex combination can round past it; clamped as
         * the lanes do (kp_points) and as the other methods do. */
        for (int k = 0; k < 3; ++k) {
            const real pk = wp[0] * s[k] + wp[1] * s[3 + k] + wp[2] * s[6 + k];
            const real qk = wq[0] * t[k] + wq[1] * t[3 + k] + wq[2] * t[6 + k];
            r->p[k] = pk > TTD_REAL_MAX ? TTD_REAL_MAX : (pk < -TTD_REAL_MAX ? -TTD_REAL_MAX : pk);
            r->q[k] = qk > TTD_REAL_MAX ? TTD_REAL_MAX : (qk < -TTD_REAL_MAX ? -TTD_REAL_MAX : qk);
            r->bary_p[k] = wp[k];
            r->bary_q[k] = wq[k];
        }
        r->distance = dist * unscale / pre;
        r->feature_p = (uint8_t)((wp[0] > 0) | ((wp[1] > 0) << 1) | ((wp[2] > 0) << 2));
        r->feature_q = (uint8_t)((wq[0] > 0) | ((wq[1] > 0) << 1) | ((wq[2] > 0) << 2));
        r->flags = (S.has_face ? 0u : (uint32_t)TTD_PAIR_DEGENERATE_S) |
                   (T.has_face ? 0u : (uint32_t)TTD_PAIR_DEGENERATE_T) |
                   (crossing ? (uint32_t)TTD_PAIR_INTERSECTING : 0u);
    } else {
        scalar_exact_pair(s, t, r);
        r->flags |= (uint32_t)TTD_PAIR_FALLBACK;
    }
    r->iterations = pen.iterations;
}

/* SPDX-License-Identifier: MIT */
/* Precision-generic body of the exact method (included by exact.c once per precision; see
 * common/precision.h). The distance is the minimum over a fixed list of candidate point
 * pairs, each a real point of S and a real point of T, so every candidate is an upper bound
 * and the true minimum is always among them up to rounding:
 *   18 vertex-edge (every vertex of one triangle against every edge of the other, clamped),
 *    9 edge-edge interior (line-line stationary point, accepted when inside both segments),
 *    6 vertex-face (a vertex whose projection falls inside the other face),
 *    6 edge-face crossings (an edge crossing the other face: distance 0).
 * Ties go to the earliest candidate in that order. Everything runs on coordinates
 * translated to A and scaled by a power of two to magnitude ~1, so no threshold below is
 * absolute. The method, the accuracy argument and notes for the SIMD port are in
 * docs/exact-method.md. Every name here carries TTD_SFX because this file is compiled twice
 * in one translation unit. */

/* One triangle in normalised coordinates, with what every candidate shares. */
typedef struct TTD_SFX(exact_tri) {
    real v[3][3];     /* vertices */
    real e[3][3];     /* edges e[i] = v[i+1] - v[i] */
    real ee[3];       /* |e[i]|^2 */
    real inv_ee[3];   /* 1/ee[i], 0 for an edge too short to divide by (a point) */
    /* Face frame: base vertex k = start of the longest edge, L = e[k], M = v[k+2] - v[k].
     * Barycentrics are solved against the longest edge so that a sliver's ill-conditioned
     * across-coordinate is compensated along L (see docs, "vertex-face"). */
    int k;
    real L[3], M[3];
    real n[3];        /* cross(L, M), computed accurately */
    real nn;          /* |n|^2 */
    real inv_nn;      /* 1/nn, 0 when there is no face */
    real ML;          /* dot(M, L) */
    int has_face;     /* nn is a normal number: the triangle has an area we can divide by */
} TTD_SFX(exact_tri);

/* The best candidate so far. */
typedef struct TTD_SFX(exact_best) {
    real d2;
    real p[3], q[3];
    real wp[3], wq[3];
} TTD_SFX(exact_best);

static real TTD_SFX(exact_dot)(const real a[3], const real b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void TTD_SFX(exact_sub)(const real a[3], const real b[3], real out[3])
{
    out[0] = a[0] - b[0];
    out[1] = a[1] - b[1];
    out[2] = a[2] - b[2];
}

static void TTD_SFX(exact_cross)(const real a[3], const real b[3], real out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

static real TTD_SFX(exact_clamp01)(real x)
{
    return x < (real)0 ? (real)0 : (x > (real)1 ? (real)1 : x);
}

#ifdef TTD_PRECISION_DOUBLE
/* a*b - c*d with Kahan's FMA trick: error within 1.5 ulp of the result even when the two
 * products nearly cancel (the normal of a sliver or of nearly parallel edges). */
static double exact_dop_d(double a, double b, double c, double d)
{
    double w = c * d;
    double err = fma(c, d, -w);   /* c*d - w, exact */
    double f = fma(a, b, -w);     /* a*b - w, rounded once */
    return f - err;
}

/* cross(a, b) to within a few ulps per component. Cheap path first: the naive cross product
 * is accurate in direction to about eps/sin(angle); only when the angle is small (|n|^2 below
 * 2^-20 |a|^2 |b|^2) is it redone with FMA. Returns |n|^2. */
static double exact_cross_acc_d(const double a[3], const double b[3], double aa, double bb,
                                    double out[3])
{
    exact_cross_d(a, b, out);
    double nn = exact_dot_d(out, out);
    if (nn < 0x1p-20 * aa * bb) {
        out[0] = exact_dop_d(a[1], b[2], a[2], b[1]);
        out[1] = exact_dop_d(a[2], b[0], a[0], b[2]);
        out[2] = exact_dop_d(a[0], b[1], a[1], b[0]);
        nn = exact_dot_d(out, out);
    }
    return nn;
}
#else
/* Float: products of floats are exact in double, so one double difference per component,
 * rounded to float, is accurate to 1 ulp whatever the angle. Returns |n|^2. */
static float exact_cross_acc_f(const float a[3], const float b[3], float aa, float bb,
                                   float out[3])
{
    (void)aa;
    (void)bb;
    out[0] = (float)((double)a[1] * (double)b[2] - (double)a[2] * (double)b[1]);
    out[1] = (float)((double)a[2] * (double)b[0] - (double)a[0] * (double)b[2]);
    out[2] = (float)((double)a[0] * (double)b[1] - (double)a[1] * (double)b[0]);
    return exact_dot_f(out, out);
}
#endif

static void TTD_SFX(exact_tri_init)(TTD_SFX(exact_tri) *T)
{
    for (int i = 0; i < 3; ++i) {
        TTD_SFX(exact_sub)(T->v[(i + 1) % 3], T->v[i], T->e[i]);
        T->ee[i] = TTD_SFX(exact_dot)(T->e[i], T->e[i]);
        /* Guard: an edge shorter than sqrt(REAL_MIN) of the pair's extent is a point. */
        T->inv_ee[i] = T->ee[i] >= TTD_REAL_MIN ? (real)1 / T->ee[i] : (real)0;
    }
    int k = 0;   /* longest edge, first on ties (a selection, not a decision tree) */
    if (T->ee[1] > T->ee[k]) k = 1;
    if (T->ee[2] > T->ee[k]) k = 2;
    T->k = k;
    int km = (k + 2) % 3;
    for (int c = 0; c < 3; ++c) {
        T->L[c] = T->e[k][c];
        T->M[c] = -T->e[km][c];   /* v[k+2] - v[k], exact negation */
    }
    T->nn = TTD_SFX(exact_cross_acc)(T->L, T->M, T->ee[k], T->ee[km], T->n);
    T->has_face = T->nn >= TTD_REAL_MIN;
    T->inv_nn = T->has_face ? (real)1 / T->nn : (real)0;
    T->ML = TTD_SFX(exact_dot)(T->M, T->L);
}

/* Projects point P onto the face of T. Writes the barycentric weights w (in T's vertex
 * order), the projected point q = v[k] + b L + c M (the same weights, so q lies on T up to
 * rounding) and the signed height h = dot(n, P - v[k]) (unnormalised; its sign is the side).
 * Returns whether the projection is inside or on the face. */
static int TTD_SFX(exact_face_project)(const TTD_SFX(exact_tri) *T, const real P[3], real w[3],
                                       real q[3], real *h)
{
    const int k = T->k;
    real r[3], x[3];
    TTD_SFX(exact_sub)(P, T->v[k], r);
    TTD_SFX(exact_cross)(T->L, r, x);
    /* c: across the longest edge; b: along it, corrected by c so that errors in c move q
     * only by c's error times the height over L (docs: consistent reconstruction). */
    real c = TTD_SFX(exact_dot)(T->n, x) * T->inv_nn;
    real b = (TTD_SFX(exact_dot)(r, T->L) - c * T->ML) * T->inv_ee[k];
    real a = (real)1 - b - c;
    w[k] = a;
    w[(k + 1) % 3] = b;
    w[(k + 2) % 3] = c;
    for (int i = 0; i < 3; ++i)
        q[i] = T->v[k][i] + b * T->L[i] + c * T->M[i];
    *h = TTD_SFX(exact_dot)(T->n, r);
    return T->has_face && a >= (real)0 && b >= (real)0 && c >= (real)0;
}

/* Keeps the candidate when strictly closer. x/wx belong to the triangle whose role is
 * `first` (0: x is on S; 1: x is on T, so the pair is stored swapped). */
static void TTD_SFX(exact_consider)(TTD_SFX(exact_best) *best, real d2, const real x[3],
                                    const real y[3], const real wx[3], const real wy[3], int swapped)
{
    if (!(d2 < best->d2))
        return;
    best->d2 = d2;
    for (int i = 0; i < 3; ++i) {
        best->p[i] = swapped ? y[i] : x[i];
        best->q[i] = swapped ? x[i] : y[i];
        best->wp[i] = swapped ? wy[i] : wx[i];
        best->wq[i] = swapped ? wx[i] : wy[i];
    }
}

/* 9 vertex-edge candidates: each vertex of X against each edge of Y, t clamped to [0,1]. */
static void TTD_SFX(exact_vertex_edge)(const TTD_SFX(exact_tri) *X, const TTD_SFX(exact_tri) *Y,
                                       int swapped, TTD_SFX(exact_best) *best)
{
    for (int i = 0; i < 3; ++i) {
        real wx[3] = {0, 0, 0};
        wx[i] = 1;
        for (int j = 0; j < 3; ++j) {
            real r[3], q[3], d[3];
            TTD_SFX(exact_sub)(X->v[i], Y->v[j], r);
            real t = TTD_SFX(exact_clamp01)(TTD_SFX(exact_dot)(r, Y->e[j]) * Y->inv_ee[j]);
            for (int c = 0; c < 3; ++c)
                q[c] = Y->v[j][c] + t * Y->e[j][c];
            TTD_SFX(exact_sub)(X->v[i], q, d);
            real d2 = TTD_SFX(exact_dot)(d, d);
            if (!(d2 < best->d2))   /* the common case: skip building the weights */
                continue;
            real wy[3] = {0, 0, 0};
            wy[j] = (real)1 - t;
            wy[(j + 1) % 3] = t;
            TTD_SFX(exact_consider)(best, d2, X->v[i], q, wx, wy, swapped);
        }
    }
}

/* 9 edge-edge interior candidates: the stationary point of the two lines, accepted when
 * both parameters lie in [0,1]. s from the normal n = cross(d1, d2), t as the projection of
 * p(s) onto the second line. The plain cross product is enough here: for nearly parallel
 * edges at gap D its direction error eps/sin moves p(s) along a direction in which the
 * distance grows only to second order (error ~ eps^2 D / sin^2), and where that is large the
 * endpoint candidates are within L^2 sin^2 / D; the smaller of the two is below eps L
 * (docs/exact-method.md, "edge-edge"). */
static void TTD_SFX(exact_edge_edge)(const TTD_SFX(exact_tri) *S, const TTD_SFX(exact_tri) *T,
                                     TTD_SFX(exact_best) *best)
{
    for (int i = 0; i < 3; ++i) {
        const real *P = S->v[i], *d1 = S->e[i];
        for (int j = 0; j < 3; ++j) {
            const real *Q = T->v[j], *d2 = T->e[j];
            real n[3], w[3], x[3];
            TTD_SFX(exact_cross)(d1, d2, n);
            real nn = TTD_SFX(exact_dot)(n, n);
            if (!(nn >= TTD_REAL_MIN))   /* parallel or a point: the endpoints cover it */
                continue;
            TTD_SFX(exact_sub)(Q, P, w);
            TTD_SFX(exact_cross)(w, d2, x);
            real s = TTD_SFX(exact_dot)(x, n) / nn;
            real sc = TTD_SFX(exact_clamp01)(s);
            real t = (sc * TTD_SFX(exact_dot)(d1, d2) - TTD_SFX(exact_dot)(w, d2)) * T->inv_ee[j];
            if (!(s >= (real)0 && s <= (real)1 && t >= (real)0 && t <= (real)1))
                continue;
            real p[3], q[3], d[3];
            for (int c = 0; c < 3; ++c) {
                p[c] = P[c] + sc * d1[c];
                q[c] = Q[c] + t * d2[c];
            }
            TTD_SFX(exact_sub)(p, q, d);
            real dd = TTD_SFX(exact_dot)(d, d);
            if (!(dd < best->d2))
                continue;
            real wp[3] = {0, 0, 0}, wq[3] = {0, 0, 0};
            wp[i] = (real)1 - sc;
            wp[(i + 1) % 3] = sc;
            wq[j] = (real)1 - t;
            wq[(j + 1) % 3] = t;
            TTD_SFX(exact_consider)(best, dd, p, q, wp, wq, 0);
        }
    }
}

/* 3 vertex-face candidates (vertices of X against the face of Y), then 3 edge-face crossings
 * (edges of X through the face of Y), sharing the vertices' signed heights. */
static void TTD_SFX(exact_face)(const TTD_SFX(exact_tri) *X, const TTD_SFX(exact_tri) *Y,
                                int swapped, TTD_SFX(exact_best) *best, real h[3])
{
    for (int i = 0; i < 3; ++i) {
        real wy[3], q[3], d[3];
        int inside = TTD_SFX(exact_face_project)(Y, X->v[i], wy, q, &h[i]);
        if (!inside)
            continue;
        real wx[3] = {0, 0, 0};
        wx[i] = 1;
        TTD_SFX(exact_sub)(X->v[i], q, d);
        TTD_SFX(exact_consider)(best, TTD_SFX(exact_dot)(d, d), X->v[i], q, wx, wy, swapped);
    }
}

static void TTD_SFX(exact_crossings)(const TTD_SFX(exact_tri) *X, const TTD_SFX(exact_tri) *Y,
                                     int swapped, TTD_SFX(exact_best) *best, const real h[3])
{
    if (!Y->has_face)
        return;
    for (int i = 0; i < 3; ++i) {
        real h0 = h[i], h1 = h[(i + 1) % 3];
        if (!((h0 < (real)0 && h1 > (real)0) || (h0 > (real)0 && h1 < (real)0)))
            continue;
        real tau = h0 / (h0 - h1);   /* no cancellation: opposite signs */
        real xp[3], wy[3], q[3], hx;
        for (int c = 0; c < 3; ++c)
            xp[c] = X->v[i][c] + tau * X->e[i][c];
        if (!TTD_SFX(exact_face_project)(Y, xp, wy, q, &hx))
            continue;
        real wx[3] = {0, 0, 0};
        wx[i] = (real)1 - tau;
        wx[(i + 1) % 3] = tau;
        TTD_SFX(exact_consider)(best, (real)0, xp, xp, wx, wy, swapped);
    }
}

static uint8_t TTD_SFX(exact_features)(const real w[3])
{
    return (uint8_t)((w[0] > (real)0 ? 1u : 0u) | (w[1] > (real)0 ? 2u : 0u) |
                     (w[2] > (real)0 ? 4u : 0u));
}

void TTD_SFX(ttd_exact_pair)(const real s[9], const real t[9], ttd_result *r)
{
    /* 1. Normalise. Inputs near the overflow limit are first halved twice (exact) so that
     * differences cannot overflow; then translate to A and scale by 2^-e so the largest
     * relative coordinate lies in [0.5, 1). The power is applied as two factors because
     * 2^-e alone may not be representable (e down to the subnormal range). */
    real m0 = 0;
    for (int i = 0; i < 9; ++i) {
        real a = TTD_FABS(s[i]), b = TTD_FABS(t[i]);
        m0 = a > m0 ? a : m0;
        m0 = b > m0 ? b : m0;
    }
    const real pre = m0 > TTD_REAL_MAX * (real)0.25 ? (real)0.25 : (real)1;
    const real o[3] = {s[0] * pre, s[1] * pre, s[2] * pre};
    real rel[18];
    real m = 0;
    for (int i = 0; i < 9; ++i) {
        rel[i] = s[i] * pre - o[i % 3];
        rel[9 + i] = t[i] * pre - o[i % 3];
    }
    for (int i = 0; i < 18; ++i) {
        real a = TTD_FABS(rel[i]);
        m = a > m ? a : m;
    }
    int e = 0;
    (void)TTD_FREXP(m, &e);   /* m == 0 gives e == 0: all vertices equal, still handled */
    const int e1 = e / 2, e2 = e - e / 2;
    const real f1 = TTD_LDEXP((real)1, -e1), f2 = TTD_LDEXP((real)1, -e2);

    TTD_SFX(exact_tri) S, T;
    for (int i = 0; i < 3; ++i)
        for (int c = 0; c < 3; ++c) {
            S.v[i][c] = rel[3 * i + c] * f1 * f2;
            T.v[i][c] = rel[9 + 3 * i + c] * f1 * f2;
        }
    TTD_SFX(exact_tri_init)(&S);
    TTD_SFX(exact_tri_init)(&T);

    /* 2. Candidates, in the fixed order that breaks ties. */
    TTD_SFX(exact_best) best;
    best.d2 = TTD_REAL_MAX;
    for (int i = 0; i < 3; ++i) {   /* placeholder, always beaten by the first candidate */
        best.p[i] = best.q[i] = S.v[0][i];
        best.wp[i] = best.wq[i] = (real)(i == 0);
    }
    TTD_SFX(exact_vertex_edge)(&S, &T, 0, &best);
    TTD_SFX(exact_vertex_edge)(&T, &S, 1, &best);
    TTD_SFX(exact_edge_edge)(&S, &T, &best);
    real hs[3], ht[3];   /* heights of S's vertices over T's plane, and of T's over S's */
    TTD_SFX(exact_face)(&S, &T, 0, &best, hs);
    TTD_SFX(exact_face)(&T, &S, 1, &best, ht);
    TTD_SFX(exact_crossings)(&S, &T, 0, &best, hs);
    TTD_SFX(exact_crossings)(&T, &S, 1, &best, ht);

    /* 3. Touching within rounding counts as touching: a distance below 4 eps of the pair's
     * extent (which is ~1 here) is what a contact computes to, not a gap. */
    real d = TTD_SQRT(best.d2);
    uint32_t flags = 0;
    if (!S.has_face) flags |= TTD_PAIR_DEGENERATE_S;
    if (!T.has_face) flags |= TTD_PAIR_DEGENERATE_T;
    if (d <= (real)4 * TTD_REAL_EPS) {
        d = 0;
        flags |= TTD_PAIR_INTERSECTING;
    }

    /* 4. Scale back and add the origin back. */
    const real g1 = TTD_LDEXP((real)1, e1), g2 = TTD_LDEXP((real)1, e2);
    const real unpre = (real)1 / pre;
    r->distance = d * g1 * g2 * unpre;
    for (int c = 0; c < 3; ++c) {
        r->p[c] = (best.p[c] * g1 * g2 + o[c]) * unpre;
        r->q[c] = (best.q[c] * g1 * g2 + o[c]) * unpre;
        r->bary_p[c] = best.wp[c];
        r->bary_q[c] = best.wq[c];
    }
    r->flags = flags;
    r->feature_p = TTD_SFX(exact_features)(best.wp);
    r->feature_q = TTD_SFX(exact_features)(best.wq);
    r->iterations = 0;
}

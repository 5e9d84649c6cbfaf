/* SPDX-License-Identifier: MIT */
/* Precision-generic body of the exact method (exact_d.c and exact_f.c compile it once each;
 * see core/precision.h). The distance is the minimum over a fixed list of candidate point
 * pairs, each a real point of S and a real point of T, so every candidate but the crossings
 * (which offer 0 unmeasured, see docs 3.1) is an upper bound, and the true minimum is always
 * among them up to rounding:
 *   18 vertex-edge (every vertex of one triangle against every edge of the other, clamped),
 *    9 edge-edge interior (line-line stationary point, accepted when inside both segments),
 *    6 vertex-face (a vertex whose projection falls inside the other face),
 *    6 edge-face crossings (an edge crossing the other face: distance 0).
 * Ties go to the earliest candidate in that order. Everything runs on coordinates
 * translated to A and scaled by a power of two to magnitude ~1, so no threshold below is
 * absolute. The method, the accuracy argument and notes for the SIMD port are in
 * docs/exact-method.md. */

#include <stdint.h>
#include <string.h>

/* One triangle in normalised coordinates, with what every candidate shares. */
typedef struct exact_tri {
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
    real u[3];        /* cross(n, L) / nn (0 without a face): the across-weight c of a point P
                       * is dot(P - v[k], u) = dot(n, cross(L, P - v[k])) / nn */
    int has_face;     /* nn is a normal number: the triangle has an area we can divide by */
} exact_tri;

static real exact_dot(const real a[3], const real b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void exact_sub(const real a[3], const real b[3], real out[3])
{
    out[0] = a[0] - b[0];
    out[1] = a[1] - b[1];
    out[2] = a[2] - b[2];
}

static void exact_cross(const real a[3], const real b[3], real out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

/* a < b ? a : b and a > b ? a : b, as the lanes' vmin and vmax on x86 */
static real exact_min(real a, real b)
{
    return a < b ? a : b;
}

static real exact_max(real a, real b)
{
    return a > b ? a : b;
}

static real exact_clamp01(real x)
{
    return x < (real)0 ? (real)0 : (x > (real)1 ? (real)1 : x);
}

#ifdef TTD_PRECISION_DOUBLE
/* The rounding error of the product p = a*b, exactly (p + error = a*b), where the product is
 * large enough for it to be representable (|p| > 2^-900; below, 0). The lane rows without FMA
 * (SSE2, portable) get the same bits from Dekker's split, which is exact over the same range:
 * so every row computes exact_dop alike, to the bit. */
static double exact_prod_err(double a, double b, double p)
{
    return fabs(p) > 0x1p-900 ? fma(a, b, -p) : 0.0;
}

/* a*b - c*d with both products' errors restored: within an ulp or two of the result even when
 * the two products nearly cancel (the normal of a sliver or of nearly parallel edges). (Kahan's
 * fma(a, b, -w) - err saves an operation, but a row without FMA cannot reproduce its bits.) */
static double exact_dop(double a, double b, double c, double d)
{
    const double p = a * b, w = c * d;
    return ((p - w) + exact_prod_err(a, b, p)) - exact_prod_err(c, d, w);
}

/* cross(a, b) to within a few ulps per component. Cheap path first: the naive cross product
 * is accurate in direction to about eps/sin(angle); only when the angle is small (|n|^2 below
 * 2^-20 |a|^2 |b|^2) is it redone with FMA. Returns |n|^2. */
static double exact_cross_acc(const double a[3], const double b[3], double aa, double bb,
                                    double out[3])
{
    exact_cross(a, b, out);
    double nn = exact_dot(out, out);
    if (nn < 0x1p-20 * aa * bb) {
        out[0] = exact_dop(a[1], b[2], a[2], b[1]);
        out[1] = exact_dop(a[2], b[0], a[0], b[2]);
        out[2] = exact_dop(a[0], b[1], a[1], b[0]);
        nn = exact_dot(out, out);
    }
    return nn;
}
#else
/* Float: products of floats are exact in double, so one double difference per component,
 * rounded to float, is accurate to 1 ulp whatever the angle. Returns |n|^2. */
static float exact_cross_acc(const float a[3], const float b[3], float aa, float bb,
                                   float out[3])
{
    (void)aa;
    (void)bb;
    out[0] = (float)((double)a[1] * (double)b[2] - (double)a[2] * (double)b[1]);
    out[1] = (float)((double)a[2] * (double)b[0] - (double)a[0] * (double)b[2]);
    out[2] = (float)((double)a[0] * (double)b[1] - (double)a[1] * (double)b[0]);
    return exact_dot(out, out);
}
#endif

/* exact_tri_init's edges: e, ee, inv_ee. */
static void exact_tri_edges(exact_tri *T)
{
    for (int i = 0; i < 3; ++i) {
        exact_sub(T->v[(i + 1) % 3], T->v[i], T->e[i]);
        T->ee[i] = exact_dot(T->e[i], T->e[i]);
        /* Guard: an edge shorter than sqrt(REAL_MIN) of the pair's extent is a point. */
        T->inv_ee[i] = T->ee[i] >= TTD_REAL_MIN ? (real)1 / T->ee[i] : (real)0;
    }
}

/* exact_tri_init's face frame, after exact_tri_edges. */
static void exact_tri_face(exact_tri *T)
{
    int k = 0;   /* longest edge, first on ties (a selection, not a decision tree) */
    if (T->ee[1] > T->ee[k]) k = 1;
    if (T->ee[2] > T->ee[k]) k = 2;
    T->k = k;
    int km = (k + 2) % 3;
    for (int c = 0; c < 3; ++c) {
        T->L[c] = T->e[k][c];
        T->M[c] = -T->e[km][c];   /* v[k+2] - v[k], exact negation */
    }
    T->nn = exact_cross_acc(T->L, T->M, T->ee[k], T->ee[km], T->n);
    T->has_face = T->nn >= TTD_REAL_MIN;
    T->inv_nn = T->has_face ? (real)1 / T->nn : (real)0;
    T->ML = exact_dot(T->M, T->L);
    exact_cross(T->n, T->L, T->u);
    for (int c = 0; c < 3; ++c)
        T->u[c] *= T->inv_nn;
}

static void exact_tri_init(exact_tri *T)
{
    exact_tri_edges(T);
    exact_tri_face(T);
}

/* The face coordinates of a point P relative to T: c = the weight of v[k+2] (across the
 * longest edge), g = dot(P - v[k], L) (along it, before the correction by c) and the signed
 * height h = dot(n, P - v[k]) (unnormalised; its sign is the side). All three are affine in
 * P, which is what lets a crossing interpolate them (exact_crossings). */
typedef struct exact_fc {
    real c, g, h;
} exact_fc;

static exact_fc exact_face_coords(const exact_tri *T, const real P[3])
{
    real r[3];
    exact_sub(P, T->v[T->k], r);
    exact_fc f;
    /* n . (L x r) / nn as r . u: the same triple product, one cross product per triangle
     * instead of one per point; its rounding is as small relative to |L| |r| / |n| (docs 3.3) */
    f.c = exact_dot(r, T->u);
    f.g = exact_dot(r, T->L);
    f.h = exact_dot(T->n, r);
    return f;
}

/* The weights b (of v[k+1]) and c (of v[k+2]) of a point with face coordinates (c, g), and
 * whether it is inside or on the face. b is computed after c and corrected by it, so that an
 * error in c moves the point only by that error times the height over L (docs: consistent
 * reconstruction). The point itself is exact_face_point(T, b, c), rebuilt from these weights
 * so that it lies on T up to rounding. */
static int exact_face_weights(const exact_tri *T, real c, real g, real *b)
{
    real bb = (g - c * T->ML) * T->inv_ee[T->k];
    real aa = (real)1 - bb - c;
    *b = bb;
    return T->has_face && aa >= (real)0 && bb >= (real)0 && c >= (real)0;
}

static void exact_face_point(const exact_tri *T, real b, real c, real q[3],
                                      real w[3])
{
    const int k = T->k;
    for (int i = 0; i < 3; ++i)
        q[i] = T->v[k][i] + b * T->L[i] + c * T->M[i];
    w[k] = (real)1 - b - c;
    w[(k + 1) % 3] = b;
    w[(k + 2) % 3] = c;
}

/* The point X.v[i] + t X.e[i] of edge i, and its weights. */
static void exact_edge_point(const exact_tri *X, int i, real t, real p[3],
                                      real w[3])
{
    for (int c = 0; c < 3; ++c)
        p[c] = X->v[i][c] + t * X->e[i][c];
    w[0] = w[1] = w[2] = 0;
    w[i] = (real)1 - t;
    w[(i + 1) % 3] = t;
}

/* The selection: the smallest d2 so far, which candidate gave it (id, numbered in the order
 * below) and that candidate's parameters. Points and weights are rebuilt once at the end
 * from these (exact_rebuild), with the same expressions, so they are the same bits. A
 * rejected candidate offers REAL_MAX, which never wins against the initial value. */
typedef struct exact_best {
    real d2;
    int id;
    real u, v, w;
} exact_best;

#include "core/exact_ids.h" /* candidate ids and the contact threshold, shared with the lanes */

static void exact_keep(exact_best *best, real d2, int id, real u, real v, real w)
{
    if (d2 < best->d2) {   /* strict: the first of equal candidates wins */
        best->d2 = d2;
        best->id = id;
        best->u = u;
        best->v = v;
        best->w = w;
    }
}

/* 9 vertex-edge candidates: each vertex of X against each edge of Y, t clamped to [0,1]. */
static void exact_vertex_edge(const exact_tri *X, const exact_tri *Y,
                                       int id0, exact_best *best)
{
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            real r[3], d[3];
            exact_sub(X->v[i], Y->v[j], r);
            real t = exact_clamp01(exact_dot(r, Y->e[j]) * Y->inv_ee[j]);
            for (int c = 0; c < 3; ++c)
                d[c] = r[c] - t * Y->e[j][c];   /* X.v[i] - (Y.v[j] + t e[j]) */
            exact_keep(best, exact_dot(d, d), id0 + 3 * i + j, t, 0, 0);
        }
}

/* 9 edge-edge interior candidates: the stationary point of the two lines, accepted when
 * both parameters lie in [0,1]. s from the normal n = cross(d1, d2), t as the projection of
 * p(s) onto the second line. The plain cross product is enough here: for nearly parallel
 * edges at gap D its direction error eps/sin moves p(s) along a direction in which the
 * distance grows only to second order (error ~ eps^2 D / sin^2), and where that is large the
 * endpoint candidates are within L^2 sin^2 / D; the smaller of the two is below eps L
 * (docs/exact-method.md, "edge-edge"). Parallel edges (nn below REAL_MIN) are rejected:
 * their endpoints cover them. This is one candidate, S's edge i against T's edge j, shared by
 * exact_edge_edge and exact_edge_edge_some so that both ask it with the same operations. */
static inline void exact_ee_candidate(const exact_tri *S, const exact_tri *T, int i, int j,
                                      exact_best *best)
{
    const real *P = S->v[i], *d1 = S->e[i];
    const real *Q = T->v[j], *d2 = T->e[j];
    real n[3], w[3], x[3], d[3];
    exact_cross(d1, d2, n);
    real nn = exact_dot(n, n);
    int ok = nn >= TTD_REAL_MIN;
    exact_sub(Q, P, w);
    exact_cross(w, d2, x);
    real s = ok ? exact_dot(x, n) / nn : (real)-1;
    real sc = exact_clamp01(s);
    real t = (sc * exact_dot(d1, d2) - exact_dot(w, d2)) * T->inv_ee[j];
    real tc = exact_clamp01(t);
    int accept = s >= (real)0 && s <= (real)1 && t >= (real)0 && t <= (real)1;
    for (int c = 0; c < 3; ++c)
        d[c] = (sc * d1[c] - w[c]) - tc * d2[c];   /* (P + sc d1) - (Q + tc d2) */
    real dd = accept ? exact_dot(d, d) : TTD_REAL_MAX;
    exact_keep(best, dd, TTD_EXACT_EE + 3 * i + j, sc, tc, 0);
}

static void exact_edge_edge(const exact_tri *S, const exact_tri *T,
                                     exact_best *best)
{
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            exact_ee_candidate(S, T, i, j, best);
}

/* 3 vertex-face candidates: vertices of X against the face of Y. Also returns the vertices'
 * face coordinates over Y (c, g and the height h), which the crossings reuse. */
static void exact_vertex_face(const exact_tri *X, const exact_tri *Y,
                                       int id0, exact_best *best, exact_fc f[3])
{
    for (int i = 0; i < 3; ++i) {
        real b;
        f[i] = exact_face_coords(Y, X->v[i]);
        const real c = f[i].c, h = f[i].h;
        int inside = exact_face_weights(Y, c, f[i].g, &b);
        /* The squared distance to the plane, h^2 / |n|^2, which is the distance to the face
         * point exact_face_point(Y, b, c) up to its in-plane rounding (eps |r|, docs 3.3).
         * h * inv_nn first: h^2 alone may underflow for a face near REAL_MIN in area. */
        exact_keep(best, inside ? (h * Y->inv_nn) * h : TTD_REAL_MAX, id0 + i, b, c, 0);
    }
}

/* 3 edge-face crossings: edge i of X (the triangle whose vertices f describes) whose ends
 * lie strictly on opposite sides of Y's plane crosses it at X = P0 + tau (P1 - P0); when that
 * point is inside Y's face the distance is 0. The crossing's face coordinates are those of
 * its ends interpolated with tau: c, g and h are affine in the point, so this is the
 * projection of X itself up to rounding, and h(X) = 0 by the choice of tau (docs 3.5). The
 * `continue` is a guard that only saves time: a lane port computes every crossing and masks
 * (kernel_exact.h skips the pass only when no lane's Y has a face). */
static void exact_crossings(const exact_tri *Y, int id0, exact_best *best,
                                     const exact_fc f[3])
{
    for (int i = 0; i < 3; ++i) {
        const exact_fc f0 = f[i], f1 = f[(i + 1) % 3];
        real h0 = f0.h, h1 = f1.h;
        int opposite = (h0 < (real)0 && h1 > (real)0) || (h0 > (real)0 && h1 < (real)0);
        if (!opposite || !Y->has_face)
            continue;
        real tau = h0 / (h0 - h1);   /* no cancellation: opposite signs */
        real c = f0.c + tau * (f1.c - f0.c);
        real g = f0.g + tau * (f1.g - f0.g);
        real b;
        int inside = exact_face_weights(Y, c, g, &b);
        exact_keep(best, inside ? (real)0 : TTD_REAL_MAX, id0 + i, tau, b, c);
    }
}

/* Rebuilds p, q and their weights from the winning candidate, with the expressions that
 * computed its d2. */
static void exact_rebuild(const exact_best *best, const exact_tri *S,
                                   const exact_tri *T, real p[3], real q[3], real wp[3],
                                   real wq[3])
{
    const int id = best->id;
    /* x/wx: the point of triangle X (the one whose vertex or edge the candidate names),
     * y/wy: the point of the other one; swapped when X is T. */
    const exact_tri *X = S, *Y = T;
    real x[3], y[3], wx[3], wy[3];
    int swapped = 0;
    if (id < TTD_EXACT_EE) {
        int k = id < TTD_EXACT_VE_T ? id : id - TTD_EXACT_VE_T;
        if (id >= TTD_EXACT_VE_T) { X = T; Y = S; swapped = 1; }
        int i = k / 3, j = k % 3;
        for (int c = 0; c < 3; ++c) {
            x[c] = X->v[i][c];
            wx[c] = (real)(c == i);
        }
        exact_edge_point(Y, j, best->u, y, wy);
    } else if (id < TTD_EXACT_VF_S) {
        int i = (id - TTD_EXACT_EE) / 3, j = (id - TTD_EXACT_EE) % 3;
        exact_edge_point(S, i, best->u, x, wx);
        exact_edge_point(T, j, best->v, y, wy);
    } else if (id < TTD_EXACT_X_S) {
        int i = (id - TTD_EXACT_VF_S) % 3;
        if (id >= TTD_EXACT_VF_T) { X = T; Y = S; swapped = 1; }
        for (int c = 0; c < 3; ++c) {
            x[c] = X->v[i][c];
            wx[c] = (real)(c == i);
        }
        exact_face_point(Y, best->u, best->v, y, wy);
    } else {
        int i = (id - TTD_EXACT_X_S) % 3;
        if (id >= TTD_EXACT_X_T) { X = T; Y = S; swapped = 1; }
        exact_edge_point(X, i, best->u, x, wx);
        real yq[3];
        exact_face_point(Y, best->v, best->w, yq, wy);
        for (int c = 0; c < 3; ++c)
            y[c] = x[c];   /* the crossing point, common to both: p == q exactly */
    }
    for (int c = 0; c < 3; ++c) {
        p[c] = swapped ? y[c] : x[c];
        q[c] = swapped ? x[c] : y[c];
        wp[c] = swapped ? wy[c] : wx[c];
        wq[c] = swapped ? wx[c] : wy[c];
    }
}

static uint8_t exact_features(const real w[3])
{
    return (uint8_t)((w[0] > (real)0 ? 1u : 0u) | (w[1] > (real)0 ? 2u : 0u) |
                     (w[2] > (real)0 ? 4u : 0u));
}

/* A closest point with a coordinate within rounding of REAL_MAX (a vertex there) can round
 * past it when it is rebuilt; the point lies in its triangle's bounding box, so REAL_MAX is
 * right to that rounding and keeps it finite. */
static real exact_clamp_max(real x)
{
    return x > TTD_REAL_MAX ? TTD_REAL_MAX : (x < -TTD_REAL_MAX ? -TTD_REAL_MAX : x);
}

/* 2^k, as TTD_LDEXP(1, k) gives it (exactly), made from its bits where it is a normal number:
 * ldexp is a call into libm, four a pair. */
static real exact_pow2(int k)
{
#ifdef TTD_PRECISION_DOUBLE
    if (k >= -1022 && k <= 1023) {
        const uint64_t bits = (uint64_t)(k + 1023) << 52;
        double x;
        memcpy(&x, &bits, sizeof x);
        return x;
    }
#else
    if (k >= -126 && k <= 127) {
        const uint32_t bits = (uint32_t)(k + 127) << 23;
        float x;
        memcpy(&x, &bits, sizeof x);
        return x;
    }
#endif
    return TTD_LDEXP((real)1, k);
}

/* exact_pair's frame: what step 4 scales back by */
typedef struct exact_frame {
    real pre, o[3];
    int e1, e2;
} exact_frame;

/* exact_pair's step 1: S's and T's vertices normalised (not yet prepared), and the frame to scale
 * back by. */
static void exact_normalise_v(const real s[9], const real t[9], exact_tri *S, exact_tri *T, exact_frame *F)
{
    /* 1. Normalise. Inputs near the overflow limit are first halved twice (exact) so that
     * differences cannot overflow; then translate to A and scale by 2^-e, 2^e the power of two
     * above the pair's extent m (the largest side of the box around all six vertices), so
     * that every relative coordinate lies in (-1, 1) and the largest beyond 1/4. m depends on
     * neither the order of the triangles nor that of their vertices, and so neither does the
     * contact snap's threshold (step 3), which is relative to it. The power is applied as two
     * factors because 2^-e alone may not be representable (e down to the subnormal range). */
    /* the box around the six vertices; its corners also give the largest |coordinate| */
    real lo[3], hi[3], m0 = 0;
    for (int c = 0; c < 3; ++c) {
        lo[c] = hi[c] = s[c];
        for (int i = 1; i < 6; ++i) {
            const real x = i < 3 ? s[3 * i + c] : t[3 * (i - 3) + c];
            lo[c] = exact_min(lo[c], x);
            hi[c] = exact_max(hi[c], x);
        }
        m0 = exact_max(m0, exact_max(TTD_FABS(lo[c]), TTD_FABS(hi[c])));
    }
    const real pre = m0 > TTD_REAL_MAX * (real)0.25 ? (real)0.25 : (real)1;
    const real o[3] = {s[0] * pre, s[1] * pre, s[2] * pre};
    real rel[18];
    for (int i = 0; i < 9; ++i) {
        rel[i] = s[i] * pre - o[i % 3];
        rel[9 + i] = t[i] * pre - o[i % 3];
    }
    real m = 0; /* the extent; the pre-scale is monotone, so the box scales with it */
    for (int c = 0; c < 3; ++c)
        m = exact_max(m, hi[c] * pre - lo[c] * pre);
    int e = 0;
    (void)TTD_FREXP(m, &e);   /* m == 0 gives e == 0: all vertices equal, still handled */
    const int e1 = e / 2, e2 = e - e / 2;
    const real f1 = exact_pow2(-e1), f2 = exact_pow2(-e2);

    for (int i = 0; i < 3; ++i)
        for (int c = 0; c < 3; ++c) {
            S->v[i][c] = rel[3 * i + c] * f1 * f2;
            T->v[i][c] = rel[9 + 3 * i + c] * f1 * f2;
        }
    F->pre = pre;
    for (int c = 0; c < 3; ++c)
        F->o[c] = o[c];
    F->e1 = e1;
    F->e2 = e2;
}

/* exact_pair's step 1 with both triangles prepared. */
static void exact_normalise(const real s[9], const real t[9], exact_tri *S, exact_tri *T, exact_frame *F)
{
    exact_normalise_v(s, t, S, T, F);
    exact_tri_init(S);
    exact_tri_init(T);
}

/* exact_pair's steps 3 and 4 on the winning candidate. */
static void exact_finish(const exact_best *best_in, const exact_tri *S, const exact_tri *T, const exact_frame *F,
                         ttd_result *r)
{
    const exact_best best = *best_in;
    const real pre = F->pre, *o = F->o;
    const int e1 = F->e1, e2 = F->e2;
    real bp[3], bq[3], wp[3], wq[3];
    exact_rebuild(&best, S, T, bp, bq, wp, wq);

    /* 3. Touching within rounding counts as touching: a distance below 4 eps of the pair's
     * extent (which is ~1 here) is what a contact computes to, not a gap. */
    real d = TTD_SQRT(best.d2);
    uint32_t flags = 0;
    if (!S->has_face) flags |= TTD_PAIR_DEGENERATE_S;
    if (!T->has_face) flags |= TTD_PAIR_DEGENERATE_T;
    if (d <= (real)TTD_EXACT_TOUCH_EPS * TTD_REAL_EPS) {
        d = 0;
        flags |= TTD_PAIR_INTERSECTING;
    }

    /* 4. Scale back and add the origin back. */
    const real g1 = exact_pow2(e1), g2 = exact_pow2(e2);
    const real unpre = (real)1 / pre;
    r->distance = d * g1 * g2 * unpre;
    for (int c = 0; c < 3; ++c) {
        r->p[c] = exact_clamp_max((bp[c] * g1 * g2 + o[c]) * unpre);
        r->q[c] = exact_clamp_max((bq[c] * g1 * g2 + o[c]) * unpre);
        r->bary_p[c] = wp[c];
        r->bary_q[c] = wq[c];
    }
    r->flags = flags;
    r->feature_p = exact_features(wp);
    r->feature_q = exact_features(wq);
    r->iterations = 0;
}

static void exact_pair(const real s[9], const real t[9], ttd_result *r)
{
    exact_tri S, T;
    exact_frame F;
    exact_normalise(s, t, &S, &T, &F);

    /* 2. Candidates, in the fixed order that breaks ties (ids in TTD_EXACT_*). */
    exact_best best = {TTD_REAL_MAX, 0, 0, 0, 0};
    exact_fc fs[3], ft[3];   /* S's vertices over T's face, and T's over S's */
    exact_vertex_edge(&S, &T, TTD_EXACT_VE_S, &best);
    exact_vertex_edge(&T, &S, TTD_EXACT_VE_T, &best);
    exact_edge_edge(&S, &T, &best);
    exact_vertex_face(&S, &T, TTD_EXACT_VF_S, &best, fs);
    exact_vertex_face(&T, &S, TTD_EXACT_VF_T, &best, ft);
    exact_crossings(&T, TTD_EXACT_X_S, &best, fs);
    exact_crossings(&S, TTD_EXACT_X_T, &best, ft);
    exact_finish(&best, &S, &T, &F, r);
}

/* ---- exact_pair with the candidates that cannot win left out ------------------------------ */
/* For triangles with repeated vertices (a vertex or an edge asked as a triangle, as the scene's
 * manifold asks them): the same result, every bit, as exact_pair. A candidate is left out only
 * where exact_pair's own selection could not take it: it computes the same bits as an earlier
 * candidate (its inputs are the same bits: a vertex equal to an earlier one of its triangle; an
 * edge whose start and vector equal an earlier edge's), and the strict comparison keeps the
 * first of equals; or it is rejected whatever it computes (REAL_MAX never wins): an edge-edge
 * candidate with an edge of zero length (its cross product is 0 or NaN, so s = -1), a vertex-face
 * candidate or crossing over a triangle without a face. A vertex left out of the vertex-face
 * candidates still gives its face coordinates to the crossings, as a copy of the earlier one's. */

static int exact_same3(const real a[3], const real b[3])
{
    return memcmp(a, b, 3 * sizeof(real)) == 0;
}

/* Bits of X: vertex i repeats an earlier vertex (vdup); edge i repeats an earlier edge, start
 * and vector (edup); edge i is 0 (ezero). */
static void exact_dups(const exact_tri *X, unsigned *vdup, unsigned *edup, unsigned *ezero)
{
    *vdup = *edup = *ezero = 0;
    for (int i = 1; i < 3; ++i)
        for (int j = 0; j < i; ++j) {
            if (exact_same3(X->v[i], X->v[j]))
                *vdup |= 1u << i;
            if (exact_same3(X->v[i], X->v[j]) && exact_same3(X->e[i], X->e[j]))
                *edup |= 1u << i;
        }
    for (int i = 0; i < 3; ++i)
        if (X->e[i][0] == 0 && X->e[i][1] == 0 && X->e[i][2] == 0)
            *ezero |= 1u << i;
}

/* exact_vertex_edge without X's repeated vertices (xs) and Y's repeated edges (ys). */
static void exact_vertex_edge_some(const exact_tri *X, const exact_tri *Y, int id0, exact_best *best, unsigned xs,
                                   unsigned ys)
{
    for (int i = 0; i < 3; ++i) {
        if (xs >> i & 1)
            continue;
        for (int j = 0; j < 3; ++j) {
            if (ys >> j & 1)
                continue;
            real r[3], d[3];
            exact_sub(X->v[i], Y->v[j], r);
            real t = exact_clamp01(exact_dot(r, Y->e[j]) * Y->inv_ee[j]);
            for (int c = 0; c < 3; ++c)
                d[c] = r[c] - t * Y->e[j][c];
            exact_keep(best, exact_dot(d, d), id0 + 3 * i + j, t, 0, 0);
        }
    }
}

/* exact_edge_edge without the edges of zero length (zs of S, zt of T). */
static void exact_edge_edge_some(const exact_tri *S, const exact_tri *T, exact_best *best, unsigned zs, unsigned zt)
{
    for (int i = 0; i < 3; ++i) {
        if (zs >> i & 1)
            continue;
        for (int j = 0; j < 3; ++j)
            if (!(zt >> j & 1))
                exact_ee_candidate(S, T, i, j, best);
    }
}

/* exact_vertex_face without X's repeated vertices (xs; their face coordinates copied from the
 * first equal vertex's), and nothing over a Y without a face (its crossings are skipped too). */
static void exact_vertex_face_some(const exact_tri *X, const exact_tri *Y, int id0, exact_best *best, exact_fc f[3],
                                   unsigned xs)
{
    if (!Y->has_face)
        return;
    for (int i = 0; i < 3; ++i) {
        if (xs >> i & 1) {
            for (int j = 0; j < i; ++j)
                if (exact_same3(X->v[i], X->v[j])) {
                    f[i] = f[j];
                    break;
                }
            continue;
        }
        real b;
        f[i] = exact_face_coords(Y, X->v[i]);
        const real c = f[i].c, h = f[i].h;
        int inside = exact_face_weights(Y, c, f[i].g, &b);
        exact_keep(best, inside ? (h * Y->inv_nn) * h : TTD_REAL_MAX, id0 + i, b, c, 0);
    }
}

/* X prepared as exact_tri_init prepares it, with its repeats (exact_dups). A triangle with a
 * repeated vertex (the same bits) gets no face frame: its nn is exactly 0, so it has no face, and
 * without one nothing below reads the frame (the vertex-face candidates and crossings over it are
 * not asked, exact_rebuild rebuilds none of them, exact_finish reads has_face). nn is 0: the edge
 * between the equal vertices is 0 and the other two are each other's exact negation (rounding is
 * symmetric), so L is the longer (first of equals) and M = -e[k+2] is either 0 or L itself; the
 * cross product of L with 0 is 0, and with L each component is a product minus the same product
 * (FMA's error terms, where exact_cross_acc redoes it, the same too). */
static void exact_tri_dups(exact_tri *X, unsigned *vdup, unsigned *edup, unsigned *ezero)
{
    exact_tri_edges(X);
    exact_dups(X, vdup, edup, ezero);
    if (*vdup == 0) {
        exact_tri_face(X);
        return;
    }
    X->k = 0;
    X->nn = 0;
    X->has_face = 0;
    X->inv_nn = 0;
}

static void exact_pair_dups(const real s[9], const real t[9], ttd_result *r)
{
    exact_tri S, T;
    exact_frame F;
    exact_normalise_v(s, t, &S, &T, &F);
    unsigned vs, es, zs, vt, et, zt;
    exact_tri_dups(&S, &vs, &es, &zs);
    exact_tri_dups(&T, &vt, &et, &zt);
    exact_best best = {TTD_REAL_MAX, 0, 0, 0, 0};
    exact_fc fs[3], ft[3];
    exact_vertex_edge_some(&S, &T, TTD_EXACT_VE_S, &best, vs, et);
    exact_vertex_edge_some(&T, &S, TTD_EXACT_VE_T, &best, vt, es);
    exact_edge_edge_some(&S, &T, &best, zs, zt);
    exact_vertex_face_some(&S, &T, TTD_EXACT_VF_S, &best, fs, vs);
    exact_vertex_face_some(&T, &S, TTD_EXACT_VF_T, &best, ft, vt);
    if (T.has_face)
        exact_crossings(&T, TTD_EXACT_X_S, &best, fs);
    if (S.has_face)
        exact_crossings(&S, TTD_EXACT_X_T, &best, ft);
    exact_finish(&best, &S, &T, &F, r);
}

/* A lower bound on the distance between S and T, for a caller that only cares about pairs
 * within a bound (core/kernels.h): the gap between the two triangles' projections on the line
 * through their centroids, gap/|c| - 32 eps M, M the largest |coordinate|. Each projection c.x
 * rounds by at most 3 eps |c| |x| <= 3 eps |c| sqrt(3) M, so this is below the true gap along
 * the stored c (any c gives a valid bound). Where M lies outside [2^-500, 2^500] (2^-50, 2^50
 * in float), products could overflow or lose bits to underflow: -inf, no bound. The lane
 * kernel's early-out (kx_screen) computes the same operations in the same order. Not part of
 * exact_pair: the scalar row (kernels.c) calls it before exact_pair when a bound is given. */
static real exact_lower_bound(const real s[9], const real t[9])
{
#ifdef TTD_PRECISION_DOUBLE
    const real lo = 0x1p-500, hi = 0x1p500;
#else
    const real lo = 0x1p-50f, hi = 0x1p50f;
#endif
    real c[3], m = 0;
    for (int k = 0; k < 3; ++k)
        c[k] = ((t[k] + t[3 + k]) + t[6 + k]) - ((s[k] + s[3 + k]) + s[6 + k]);
    for (int k = 0; k < 9; ++k) {
        const real a = TTD_FABS(s[k]), b = TTD_FABS(t[k]);
        const real ab = a > b ? a : b;
        m = m > ab ? m : ab;
    }
    if (!(m >= lo && m <= hi))
        return -(real)INFINITY;
    real ps[3], pt[3];
    for (int i = 0; i < 3; ++i) {
        ps[i] = c[0] * s[3 * i] + c[1] * s[3 * i + 1] + c[2] * s[3 * i + 2];
        pt[i] = c[0] * t[3 * i] + c[1] * t[3 * i + 1] + c[2] * t[3 * i + 2];
    }
    const real smin = exact_min(exact_min(ps[0], ps[1]), ps[2]), smax = exact_max(exact_max(ps[0], ps[1]), ps[2]);
    const real tmin = exact_min(exact_min(pt[0], pt[1]), pt[2]), tmax = exact_max(exact_max(pt[0], pt[1]), pt[2]);
    const real gap = exact_max(tmin - smax, smin - tmax);
    return gap / TTD_SQRT(exact_dot(c, c)) - (real)32 * TTD_REAL_EPS * m;
}

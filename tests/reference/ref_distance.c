/* SPDX-License-Identifier: MIT */
/* The high-precision reference distance: enumeration of the faces of the product polytope
 * S x T, each solved exactly in closed form (see ref_distance.h for why this is correct).
 *
 * Notation: a feature is a non-empty subset of a triangle's vertices (a bit mask 1..7). For the
 * pair (features FS of S, FT of T) with base vertices X0 in FS and Y0 in FT,
 *     P - Q = w0 + sum_i z_i c_i,   w0 = X0 - Y0,
 * where the columns c_i are X - X0 for the other vertices X of FS and -(Y - Y0) for the other
 * vertices Y of FT, and z_i are the weights of those vertices. Minimising |P - Q| over the
 * affine hulls is least squares in k = |FS| + |FT| - 2 unknowns:
 *   k = 0: |w0|;
 *   k = 1: z = -(w0.c)/(c.c), residual |w0 x c| / |c|;
 *   k = 2: n = c1 x c2, residual |w0.n| / |n|, z1 = -((w0 x c2).n)/|n|^2, z2 = -((c1 x w0).n)/|n|^2;
 *   k = 3: D = c1.(c2 x c3), residual 0, z by Cramer's rule with triple products.
 * The solution is a candidate when every weight of FS and of FT is in [0, 1] (within 1e-24). */
#include "ref_distance.h"

#include <float.h>
#include <math.h>
#include <string.h>
#if defined(TTD_REF_FLOAT128) || LDBL_MANT_DIG >= 113
#define QEPS ((ttd_qreal)0x1p-112)
#define QWEIGHT_TOL ((ttd_qreal)1e-24)
#else
#define QEPS ((ttd_qreal)LDBL_EPSILON)
#define QWEIGHT_TOL ((ttd_qreal)1e-14)
#endif
#ifdef TTD_REF_FLOAT128
#define QSQRT qsqrt
#else
#define QSQRT sqrtl
#endif

/// A system is singular when its determinant is below this multiple of eps times the product
/// of its columns' lengths: about 7 eps is the rounding noise of a triple product of exact
/// columns, and the smallest angle any generator makes (1e-10) is far above 64 eps.
#define SINGULAR_FACTOR 64

typedef struct qv3 {
    ttd_qreal x, y, z;
} qv3;

static qv3 qv_sub_d(const double *a, const double *b)
{
    qv3 r = {(ttd_qreal)a[0] - (ttd_qreal)b[0], (ttd_qreal)a[1] - (ttd_qreal)b[1],
             (ttd_qreal)a[2] - (ttd_qreal)b[2]};
    return r;
}
static qv3 qv_from_d(const double *a)
{
    qv3 r = {(ttd_qreal)a[0], (ttd_qreal)a[1], (ttd_qreal)a[2]};
    return r;
}
static qv3 qv_neg(qv3 a) { qv3 r = {-a.x, -a.y, -a.z}; return r; }
static qv3 qv_sub(qv3 a, qv3 b) { qv3 r = {a.x - b.x, a.y - b.y, a.z - b.z}; return r; }
static ttd_qreal qv_dot(qv3 a, qv3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static qv3 qv_cross(qv3 a, qv3 b)
{
    qv3 r = {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
    return r;
}
#ifdef TTD_REF_FLOAT128
/// sqrt in __float128 without libquadmath: scale by an even power of two into double's
/// comfortable range, start from the double sqrt (53 bits) and take two Newton steps (each
/// doubles the correct bits: 106, then past 113); the scaling is exact.
static ttd_qreal qsqrt(ttd_qreal x)
{
    if (!(x > 0)) return x == 0 ? x : (ttd_qreal)NAN;
    if (x - x != 0) return x; /* infinity */
    ttd_qreal up = 1;
    const ttd_qreal big = (ttd_qreal)0x1p600, small = (ttd_qreal)0x1p-600;
    while (x > big) { x *= small; up *= (ttd_qreal)0x1p300; }
    while (x < small) { x *= big; up *= (ttd_qreal)0x1p-300; }
    ttd_qreal y = (ttd_qreal)sqrt((double)x);
    y = (y + x / y) / 2;
    y = (y + x / y) / 2;
    return y * up;
}
#endif

static ttd_qreal qv_norm(qv3 a) { return QSQRT(qv_dot(a, a)); }
static ttd_qreal qabs(ttd_qreal x) { return x < 0 ? -x : x; }

/// The best candidate so far: value and the weights of the 3 + 3 vertices.
typedef struct best {
    int found;
    ttd_qreal value;
    ttd_qreal ws[3], wt[3];
} best;

static int popcount3(unsigned m) { return (int)(m & 1u) + (int)((m >> 1) & 1u) + (int)((m >> 2) & 1u); }

/// Solves the pair (ms of s, mt of t) and records it in b when feasible and better.
static void solve_pair(const double *s, const double *t, unsigned ms, unsigned mt, best *b)
{
    int vs[3], vt[3], ns = 0, nt = 0;
    for (int i = 0; i < 3; ++i) {
        if (ms & (1u << i)) vs[ns++] = i;
        if (mt & (1u << i)) vt[nt++] = i;
    }
    const int k = ns + nt - 2;
    if (k > 3) return; /* face-face: always singular in 3D */
    qv3 w0 = qv_sub_d(s + 3 * vs[0], t + 3 * vt[0]);
    qv3 c[3];
    int owner[3], vert[3]; /* column -> triangle (0 = s, 1 = t) and vertex index */
    int m = 0;
    for (int i = 1; i < ns; ++i, ++m) { c[m] = qv_sub_d(s + 3 * vs[i], s + 3 * vs[0]); owner[m] = 0; vert[m] = vs[i]; }
    for (int j = 1; j < nt; ++j, ++m) { c[m] = qv_neg(qv_sub_d(t + 3 * vt[j], t + 3 * vt[0])); owner[m] = 1; vert[m] = vt[j]; }

    ttd_qreal z[3] = {0, 0, 0}, value;
    const ttd_qreal tiny = (ttd_qreal)SINGULAR_FACTOR * QEPS;
    if (k == 0) {
        value = qv_norm(w0);
    } else if (k == 1) {
        ttd_qreal cc = qv_dot(c[0], c[0]);
        if (!(cc > 0)) return;
        z[0] = -qv_dot(w0, c[0]) / cc;
        value = qv_norm(qv_cross(w0, c[0])) / QSQRT(cc);
    } else if (k == 2) {
        qv3 n = qv_cross(c[0], c[1]);
        ttd_qreal nn = qv_dot(n, n);
        ttd_qreal scale = qv_dot(c[0], c[0]) * qv_dot(c[1], c[1]);
        if (!(nn > tiny * tiny * scale) || !(nn > 0)) return;
        z[0] = -qv_dot(qv_cross(w0, c[1]), n) / nn;
        z[1] = -qv_dot(qv_cross(c[0], w0), n) / nn;
        value = qabs(qv_dot(w0, n)) / QSQRT(nn);
    } else {
        qv3 n23 = qv_cross(c[1], c[2]);
        ttd_qreal det = qv_dot(c[0], n23);
        ttd_qreal scale = qv_norm(c[0]) * qv_norm(c[1]) * qv_norm(c[2]);
        if (!(qabs(det) > tiny * scale) || det == 0) return;
        z[0] = -qv_dot(w0, n23) / det;
        z[1] = -qv_dot(c[0], qv_cross(w0, c[2])) / det;
        z[2] = -qv_dot(c[0], qv_cross(c[1], w0)) / det;
        value = 0;
    }
    /* weights of each feature's vertices: the base vertex gets 1 - sum of the others */
    ttd_qreal ws[3] = {0, 0, 0}, wt[3] = {0, 0, 0}, rs = 1, rt = 1;
    for (int i = 0; i < k; ++i) {
        if (owner[i] == 0) { ws[vert[i]] = z[i]; rs -= z[i]; }
        else { wt[vert[i]] = z[i]; rt -= z[i]; }
    }
    ws[vs[0]] = rs;
    wt[vt[0]] = rt;
    for (int i = 0; i < 3; ++i)
        if (ws[i] < -QWEIGHT_TOL || wt[i] < -QWEIGHT_TOL) return;
    if (b->found && !(value < b->value)) return;
    b->found = 1;
    b->value = value;
    for (int i = 0; i < 3; ++i) {
        b->ws[i] = ws[i];
        b->wt[i] = wt[i];
    }
}

/// Minimum over all feature pairs whose vertices are within the masks sub_s and sub_t.
static void solve_all(const double *s, const double *t, unsigned sub_s, unsigned sub_t, best *b)
{
    b->found = 0;
    b->value = 0;
    for (unsigned ms = 1; ms < 8; ++ms) {
        if (ms & ~sub_s) continue;
        for (unsigned mt = 1; mt < 8; ++mt) {
            if (mt & ~sub_t) continue;
            if (popcount3(ms) + popcount3(mt) > 5) continue;
            solve_pair(s, t, ms, mt, b);
        }
    }
}

/// Clamps weights into the simplex (they may be off by 1e-24) and renormalises.
static void clamp_weights(ttd_qreal w[3])
{
    ttd_qreal sum = 0;
    for (int i = 0; i < 3; ++i) {
        if (w[i] < 0) w[i] = 0;
        if (w[i] > 1) w[i] = 1;
        sum += w[i];
    }
    for (int i = 0; i < 3; ++i) w[i] /= sum;
}

static qv3 combine(const double *tri, const ttd_qreal w[3])
{
    qv3 r = {0, 0, 0};
    for (int i = 0; i < 3; ++i) {
        r.x += w[i] * (ttd_qreal)tri[3 * i];
        r.y += w[i] * (ttd_qreal)tri[3 * i + 1];
        r.z += w[i] * (ttd_qreal)tri[3 * i + 2];
    }
    return r;
}

const char *ttd_ref_precision(void)
{
#if defined(TTD_REF_FLOAT128)
    return "__float128";
#elif LDBL_MANT_DIG >= 113
    return "long double (IEEE quad)";
#else
    return "long double (64-bit significand: weaker reference)";
#endif
}

double ttd_ref_epsilon(void) { return (double)QEPS / 2; }

void ttd_ref_distance(const double s[9], const double t[9], ttd_ref_result *out)
{
    best b;
    solve_all(s, t, 7u, 7u, &b); /* vertex-vertex always succeeds, so b.found */
    clamp_weights(b.ws);
    clamp_weights(b.wt);
    qv3 P = combine(s, b.ws), Q = combine(t, b.wt);
    out->distance_q = b.value;
    out->distance = (double)b.value;
    out->p[0] = (double)P.x; out->p[1] = (double)P.y; out->p[2] = (double)P.z;
    out->q[0] = (double)Q.x; out->q[1] = (double)Q.y; out->q[2] = (double)Q.z;
    out->feature_p = out->feature_q = 0;
    for (int i = 0; i < 3; ++i) {
        out->bary_p[i] = (double)b.ws[i];
        out->bary_q[i] = (double)b.wt[i];
        if (b.ws[i] > 0) out->feature_p |= 1u << i;
        if (b.wt[i] > 0) out->feature_q |= 1u << i;
    }
    /* Certificate: with r = P - Q, every X in S has r.X >= r.P + gs and every Y in T has
     * r.Y <= r.Q - gt (gs, gt the minima over vertices), so |X - Y| >= (|r|^2 + gs + gt)/|r|.
     * r and the vertex terms are formed from differences of input vertices (exact), so the
     * bound does not depend on where the pair sits; its rounding still grows like size^2/d,
     * because an error in the direction of a short r tilts the planes. */
    qv3 r = {0, 0, 0};
    for (int i = 0; i < 3; ++i) {
        qv3 a = qv_sub_d(s + 3 * i, t), c = qv_sub_d(t + 3 * i, t);
        r.x += b.ws[i] * a.x - b.wt[i] * c.x;
        r.y += b.ws[i] * a.y - b.wt[i] * c.y;
        r.z += b.ws[i] * a.z - b.wt[i] * c.z;
    }
    ttd_qreal rn = qv_norm(r);
    out->lower_bound = 0;
    if (b.value > 0 && rn > 0) {
        ttd_qreal gs = 0, gt = 0;
        for (int i = 0; i < 3; ++i) {
            ttd_qreal a = 0, c = 0; /* r.(X_i - P) and r.(Q - Y_i) */
            for (int j = 0; j < 3; ++j) {
                a += b.ws[j] * qv_dot(r, qv_sub_d(s + 3 * i, s + 3 * j));
                c += b.wt[j] * qv_dot(r, qv_sub_d(t + 3 * j, t + 3 * i));
            }
            if (i == 0 || a < gs) gs = a;
            if (i == 0 || c < gt) gt = c;
        }
        ttd_qreal lb = (rn * rn + gs + gt) / rn;
        out->lower_bound = lb > 0 ? (double)lb : 0.0;
    }
}

void ttd_ref_sub_distances(const double s[9], const double t[9], double out[15])
{
    best b;
    for (int i = 0; i < 3; ++i) {
        solve_all(s, t, 1u << i, 7u, &b);
        out[i] = (double)b.value;
        solve_all(s, t, 7u, 1u << i, &b);
        out[3 + i] = (double)b.value;
    }
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            unsigned es = (1u << i) | (1u << ((i + 1) % 3)), et = (1u << j) | (1u << ((j + 1) % 3));
            solve_all(s, t, es, et, &b);
            out[6 + 3 * i + j] = (double)b.value;
        }
}

double ttd_ref_point_triangle(const double x[3], const double tri[9])
{
    double pt[9];
    for (int i = 0; i < 9; ++i) pt[i] = x[i % 3];
    best b;
    solve_all(pt, tri, 1u, 7u, &b);
    return (double)b.value;
}

double ttd_ref_size(const double s[9], const double t[9])
{
    ttd_qreal m = 0;
    const double *tri[2] = {s, t};
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 3; ++i) {
            ttd_qreal l = qv_norm(qv_sub_d(tri[j] + 3 * i, tri[j] + 3 * ((i + 1) % 3)));
            if (l > m) m = l;
        }
    return (double)m;
}

/// The margin by which segment a-b crosses the interior of triangle tri, in units of size^3;
/// 0 when it does not strictly cross.
static ttd_qreal segment_crossing(const double *a, const double *b, const double *tri, ttd_qreal size3)
{
    qv3 A = qv_from_d(a), B = qv_from_d(b);
    qv3 V[3] = {qv_from_d(tri), qv_from_d(tri + 3), qv_from_d(tri + 6)};
    qv3 n = qv_cross(qv_sub(V[1], V[0]), qv_sub(V[2], V[0]));
    ttd_qreal ha = qv_dot(n, qv_sub(A, V[0])), hb = qv_dot(n, qv_sub(B, V[0]));
    if (!((ha > 0 && hb < 0) || (ha < 0 && hb > 0))) return 0;
    ttd_qreal m = qabs(ha) < qabs(hb) ? qabs(ha) : qabs(hb);
    qv3 ab = qv_sub(B, A);
    int sign = 0;
    for (int k = 0; k < 3; ++k) {
        ttd_qreal o = qv_dot(qv_cross(qv_sub(V[k], A), qv_sub(V[(k + 1) % 3], A)), ab);
        int sg = o > 0 ? 1 : (o < 0 ? -1 : 0);
        if (sg == 0 || (sign != 0 && sg != sign)) return 0;
        sign = sg;
        if (qabs(o) < m) m = qabs(o);
    }
    return m / size3;
}

double ttd_ref_intersection_margin(const double s[9], const double t[9])
{
    ttd_qreal size = (ttd_qreal)ttd_ref_size(s, t);
    if (!(size > 0)) return 0.0;
    ttd_qreal size3 = size * size * size, best_margin = 0;
    for (int i = 0; i < 3; ++i) {
        int j = (i + 1) % 3;
        ttd_qreal m1 = segment_crossing(s + 3 * i, s + 3 * j, t, size3);
        ttd_qreal m2 = segment_crossing(t + 3 * i, t + 3 * j, s, size3);
        if (m1 > best_margin) best_margin = m1;
        if (m2 > best_margin) best_margin = m2;
    }
    return (double)best_margin;
}

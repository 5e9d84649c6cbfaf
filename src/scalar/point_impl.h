/* SPDX-License-Identifier: MIT */
/* Precision-generic body of the exact distance from a point to a triangle, the reference of the
 * point queries (src/points/, docs/points.md). Included after exact_impl.h by exact_d.c and
 * exact_f.c, whose helpers it shares (the accurate cross product of nearly parallel edges).
 *
 * It is the exact method (docs/exact-method.md) for a triangle against a point: the distance is
 * the minimum over four candidates, each a real point of the triangle, so each is an upper bound
 * and the minimum is among them up to rounding:
 *   3 vertex-edge (the point against each edge, clamped to the edge: this covers the vertices),
 *   1 vertex-face (the point's projection, when it falls inside or on the face).
 * Ties go to the earliest. Unlike the pair method it normalises the triangle alone (origin at its
 * vertex 0, scaled by the power of two above its extent) so that everything that depends on the
 * triangle only is computed once (point_prepare, into core/point_layout.h's fields) and a query
 * point costs about sixty operations and one square root (point_eval). A point farther than
 * 2^400 (float: 2^40) of the triangle's extents is measured to vertex 0, which is within rounding
 * of the triangle there; a point triangle is measured to its point. */
#include "core/point_layout.h"

#ifdef TTD_PRECISION_DOUBLE
#define PT_FAR TTD_PT_FAR_D
#define PT_EMIN (-1000) /* s = 2^-e stays finite: triangles below 2^-1000 keep a smaller scale */
#define PT_EMAX 1000
#else
#define PT_FAR TTD_PT_FAR_F
#define PT_EMIN (-100)
#define PT_EMAX 100
#endif

/* Prepares triangle v (vertices A, B, C, 9 reals) into f, field i at f[i * stride]. */
static void point_prepare(const real v[9], real *f, size_t stride)
{
    real lo[3], hi[3], m = 0;
    for (int c = 0; c < 3; ++c) {
        lo[c] = exact_min(exact_min(v[c], v[3 + c]), v[6 + c]);
        hi[c] = exact_max(exact_max(v[c], v[3 + c]), v[6 + c]);
        m = exact_max(m, hi[c] - lo[c]);
    }
    int e = 0;
    (void)TTD_FREXP(m, &e);
    e = e < PT_EMIN ? PT_EMIN : (e > PT_EMAX ? PT_EMAX : e);
    const real s = m > 0 ? TTD_LDEXP((real)1, -e) : (real)0;
    const real g = m > 0 ? TTD_LDEXP((real)1, e) : (real)1;
    exact_tri T; /* only the fields exact_tri_init fills that do not need vertices */
    for (int i = 0; i < 3; ++i) {
        for (int c = 0; c < 3; ++c)
            T.e[i][c] = (v[3 * ((i + 1) % 3) + c] - v[3 * i + c]) * s;
        T.ee[i] = exact_dot(T.e[i], T.e[i]);
        T.inv_ee[i] = T.ee[i] >= TTD_REAL_MIN ? (real)1 / T.ee[i] : (real)0;
    }
    int k = 0; /* longest edge, first on ties */
    if (T.ee[1] > T.ee[k]) k = 1;
    if (T.ee[2] > T.ee[k]) k = 2;
    const int km = (k + 2) % 3;
    real L[3], M[3], n[3], u[3];
    for (int c = 0; c < 3; ++c) {
        L[c] = T.e[k][c];
        M[c] = -T.e[km][c];
    }
    const real nn = exact_cross_acc(L, M, T.ee[k], T.ee[km], n);
    const real inn = nn >= TTD_REAL_MIN ? (real)1 / nn : (real)0;
    exact_cross(n, L, u);
    for (int c = 0; c < 3; ++c) {
        f[(TTD_PT_V0 + c) * stride] = v[c];
        f[(TTD_PT_L + c) * stride] = L[c];
        f[(TTD_PT_U + c) * stride] = u[c] * inn;
        f[(TTD_PT_N + c) * stride] = n[c];
    }
    f[TTD_PT_S * stride] = s;
    f[TTD_PT_G * stride] = g;
    for (int i = 0; i < 3; ++i) {
        for (int c = 0; c < 3; ++c)
            f[(TTD_PT_E + 3 * i + c) * stride] = T.e[i][c];
        f[(TTD_PT_IEE + i) * stride] = T.inv_ee[i];
    }
    f[TTD_PT_K * stride] = (real)k;
    f[TTD_PT_ML * stride] = exact_dot(M, L);
    f[TTD_PT_IEEK * stride] = T.inv_ee[k];
    f[TTD_PT_INN * stride] = inn;
}

/* |(x, y, z)| without overflow or loss to underflow: scaled by the power of two below the largest
 * component, as the lanes' kw_norm3 (simd/kernel_common.h), to the bit. */
static real point_norm3(real x, real y, real z)
{
    const real m = exact_max(exact_max(TTD_FABS(x), TTD_FABS(y)), TTD_FABS(z));
    if (!(m > 0) || !(m <= TTD_REAL_MAX))
        return m;
#ifdef TTD_PRECISION_DOUBLE
    const real lift = 0x1p54, unlift = 0x1p-54;
#else
    const real lift = 0x1p25f, unlift = 0x1p-25f;
#endif
    const real up = m < TTD_REAL_MIN ? lift : (real)1;
    x *= up;
    y *= up;
    z *= up;
    int e;
    (void)TTD_FREXP(m * up, &e);
    const real half = TTD_LDEXP((real)1, e - 1), inv = (real)0.5 / half;
    x *= inv;
    y *= inv;
    z *= inv;
    real r = TTD_SQRT(x * x + y * y + z * z);
    r = r * half * (real)2;
    return r * (m < TTD_REAL_MIN ? unlift : (real)1);
}

/* What point_select chose: the candidate (0..2 an edge, clamped at t = u; 3 the face, weights b = u
 * and c = v of v[k+1] and v[k+2]; 4 vertex 0, for a point triangle or a far point) and its
 * parameters. The lanes (simd/kernel_point.h) return the same three numbers, so that the winner's
 * point is rebuilt by point_rebuild alone. */
enum { PT_EDGE0 = 0, PT_FACE = 3, PT_VERTEX = 4 };

/* The distance from P to the prepared triangle f and the candidate that gives it (*id, *u, *v).
 * The lane kernel computes the same operations in the same order. */
static real point_select(const real *f, size_t stride, const real P[3], int *id, real *u, real *v)
{
#define F(i) f[(size_t)(i) * stride]
    const real s = F(TTD_PT_S);
    real r0[3], far = 0;
    for (int c = 0; c < 3; ++c) {
        r0[c] = (P[c] - F(TTD_PT_V0 + c)) * s;
        far = exact_max(far, TTD_FABS(r0[c]));
    }
    *u = *v = 0;
    if (!(s > 0) || far > PT_FAR) { /* a point triangle, or a point far beyond its size */
        *id = PT_VERTEX;
        return point_norm3(P[0] - F(TTD_PT_V0), P[1] - F(TTD_PT_V0 + 1), P[2] - F(TTD_PT_V0 + 2));
    }
    /* the point from each vertex: w_0 = r0, w_1 = r0 - e_0, w_2 = r0 + e_2 */
    real wv[3][3];
    for (int c = 0; c < 3; ++c) {
        wv[0][c] = r0[c];
        wv[1][c] = r0[c] - F(TTD_PT_E + c);
        wv[2][c] = r0[c] + F(TTD_PT_E + 6 + c);
    }
    real best = TTD_REAL_MAX;
    *id = 0;
    for (int j = 0; j < 3; ++j) { /* the edges, clamped */
        const real e[3] = {F(TTD_PT_E + 3 * j), F(TTD_PT_E + 3 * j + 1), F(TTD_PT_E + 3 * j + 2)};
        const real t = exact_clamp01(exact_dot(wv[j], e) * F(TTD_PT_IEE + j));
        real d[3];
        for (int c = 0; c < 3; ++c)
            d[c] = wv[j][c] - t * e[c];
        const real d2 = exact_dot(d, d);
        if (d2 < best) {
            best = d2;
            *id = j;
            *u = t;
        }
    }
    { /* the face: the point's projection, when inside or on it */
        const int k = (int)F(TTD_PT_K);
        const real L[3] = {F(TTD_PT_L), F(TTD_PT_L + 1), F(TTD_PT_L + 2)};
        const real uu[3] = {F(TTD_PT_U), F(TTD_PT_U + 1), F(TTD_PT_U + 2)};
        const real n[3] = {F(TTD_PT_N), F(TTD_PT_N + 1), F(TTD_PT_N + 2)};
        const real inn = F(TTD_PT_INN);
        const real c = exact_dot(wv[k], uu), g = exact_dot(wv[k], L), h = exact_dot(n, wv[k]);
        const real b = (g - c * F(TTD_PT_ML)) * F(TTD_PT_IEEK);
        const real a = (real)1 - b - c;
        const int inside = inn > 0 && a >= 0 && b >= 0 && c >= 0;
        const real d2 = inside ? (h * inn) * h : TTD_REAL_MAX;
        if (d2 < best) {
            best = d2;
            *id = PT_FACE;
            *u = b;
            *v = c;
        }
    }
    return TTD_SQRT(best) * F(TTD_PT_G);
#undef F
}

/* The closest point q of candidate (id, u, v) of the prepared triangle f, and its vertices'
 * weights w. */
static void point_rebuild(const real *f, size_t stride, int id, real u, real v, real q[3], real w[3])
{
#define F(i) f[(size_t)(i) * stride]
    if (id == PT_VERTEX) {
        for (int c = 0; c < 3; ++c) {
            q[c] = F(TTD_PT_V0 + c);
            w[c] = (real)(c == 0);
        }
        return;
    }
    /* vertex j in the frame: v_0 = 0, v_1 = e_0, v_2 = -e_2 */
    real vj[3][3], x[3];
    for (int c = 0; c < 3; ++c) {
        vj[0][c] = 0;
        vj[1][c] = F(TTD_PT_E + c);
        vj[2][c] = -F(TTD_PT_E + 6 + c);
    }
    if (id < PT_FACE) {
        for (int c = 0; c < 3; ++c)
            x[c] = vj[id][c] + u * F(TTD_PT_E + 3 * id + c);
        w[id] = (real)1 - u;
        w[(id + 1) % 3] = u;
        w[(id + 2) % 3] = 0;
    } else {
        const int k = (int)F(TTD_PT_K);
        for (int c = 0; c < 3; ++c)
            x[c] = vj[k][c] + u * F(TTD_PT_L + c) + v * -F(TTD_PT_E + 3 * ((k + 2) % 3) + c);
        w[k] = (real)1 - u - v;
        w[(k + 1) % 3] = u;
        w[(k + 2) % 3] = v;
    }
    for (int c = 0; c < 3; ++c)
        q[c] = exact_clamp_max(x[c] * F(TTD_PT_G) + F(TTD_PT_V0 + c));
#undef F
}

/* The distance from P to the prepared triangle f, and with q and w not NULL its closest point
 * and the weights of its vertices there. */
static real point_eval(const real *f, size_t stride, const real P[3], real q[3], real w[3])
{
    int id;
    real u, v;
    const real d = point_select(f, stride, P, &id, &u, &v);
    if (q != NULL)
        point_rebuild(f, stride, id, u, v, q, w);
    return d;
}

/* The scalar row's point kernels (core/kernels.h): a loop over point_eval's distance, and (float
 * only) the walk's node test one child at a time with the lanes' operations (simd/kernel_point.h). */
static void point_block_scalar(const real P[3], const real *blk, real d[TTD_NODE_WIDTH], real par[3][TTD_NODE_WIDTH])
{
    for (int j = 0; j < TTD_NODE_WIDTH; ++j) {
        int id;
        d[j] = point_select(blk + j, TTD_PT_LANES, P, &id, &par[1][j], &par[2][j]);
        par[0][j] = (real)id;
    }
}

static void point_lanes_scalar(const real *f, const real P[3][TTD_NODE_WIDTH], real d[TTD_NODE_WIDTH],
                               real q[3][TTD_NODE_WIDTH], real w[3][TTD_NODE_WIDTH])
{
    for (int i = 0; i < TTD_NODE_WIDTH; ++i) {
        const real p[3] = {P[0][i], P[1][i], P[2][i]};
        real qi[3], wi[3];
        d[i] = point_eval(f, 1, p, qi, wi);
        for (int c = 0; c < 3; ++c) {
            q[c][i] = qi[c];
            w[c][i] = wi[c];
        }
    }
}

#ifndef TTD_PRECISION_DOUBLE
static unsigned point_node_scalar(const float p[3], const ttd_pnode *y, float lim2, float lb2[TTD_NODE_WIDTH])
{
    unsigned within = 0;
    for (int j = 0; j < TTD_NODE_WIDTH; ++j) {
        const float dx = p[0] - y->c[0][j], dy = p[1] - y->c[1][j], dz = p[2] - y->c[2][j];
        float s = 0, sep = 0;
        for (int a = 0; a < 3; ++a) {
            const float z = (y->u[3 * a][j] * dx + y->u[3 * a + 1][j] * dy) + y->u[3 * a + 2][j] * dz;
            const float gap = TTD_FABS(z) - y->e[a][j], g = exact_max(gap, 0.0f);
            s = a == 0 ? g * g : s + g * g;
            sep = a == 0 ? gap : exact_max(sep, gap);
        }
        lb2[j] = s > 0 ? s : sep;
        within |= (unsigned)(s <= lim2) << j;
    }
    return within;
}

static unsigned ray_node_scalar(const float lo[3], const float hi[3], int k, int sigma, const ttd_rnode *y)
{
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    unsigned hit = 0;
    for (int s = 0; s < TTD_NODE_WIDTH; ++s)
        hit |= (unsigned)((y->lo[i][s] <= hi[i]) & (y->hi[i][s] >= lo[i]) & (y->lo[j][s] <= hi[j]) & (y->hi[j][s] >= lo[j]) &
                          (sigma > 0 ? y->hi[k][s] >= lo[k] : y->lo[k][s] <= hi[k]))
               << s;
    return hit;
}
#endif

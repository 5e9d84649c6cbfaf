/* SPDX-License-Identifier: MIT */
/* Deterministic triangle-pair generators (see pairs.h for the families). Each pair is built
 * in a convenient local frame where its defining property (gap, angle, contact) is set by
 * construction, then moved: by a random rigid motion where rounding is harmless, or by exact
 * motions (axis permutations, sign flips, dyadic translations) where the property must survive
 * exactly (exact contacts, exact collinearity, exact parallelism). Finally the vertex order of
 * each triangle is permuted and the two triangles are swapped at random, so that no family
 * favours one vertex or one argument. */
#include "pairs.h"

#include <math.h>
#include <string.h>

static const char *const family_names[TTD_GEN_COUNT] = {
    "random", "paper", "far", "near_parallel_edges", "near_parallel_faces", "near_touching",
    "intersecting", "degenerate", "sliver", "scaled", "offset", "features",
};

/* ---- random numbers ------------------------------------------------------------------ */

static uint64_t splitmix64_next(uint64_t *x)
{
    uint64_t z = (*x += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

ttd_gen_rng ttd_gen_rng_make(uint64_t seed, uint64_t stream)
{
    uint64_t a = seed, b = stream ^ 0xD1B54A32D192ED03ull;
    ttd_gen_rng r;
    r.state = splitmix64_next(&a) ^ (splitmix64_next(&b) * 0xA24BAED4963EE407ull);
    return r;
}

uint64_t ttd_gen_rng_u64(ttd_gen_rng *r) { return splitmix64_next(&r->state); }

double ttd_gen_rng_uniform(ttd_gen_rng *r)
{
    return (double)(ttd_gen_rng_u64(r) >> 11) * (1.0 / 9007199254740992.0);
}

static double uni(ttd_gen_rng *r, double lo, double hi) { return lo + (hi - lo) * ttd_gen_rng_uniform(r); }

/// Uniform integer in [0, n).
static int irand(ttd_gen_rng *r, int n) { return (int)(ttd_gen_rng_u64(r) % (uint64_t)n); }

/// 10^k by exact multiplications (exact up to 1e22) or one correctly rounded division.
static double pow10i(int k)
{
    double p = 1.0;
    for (int i = 0; i < (k < 0 ? -k : k); ++i) p *= 10.0;
    return k < 0 ? 1.0 / p : p;
}

/// A value in [10^lo, 10^hi): uniform decade, uniform mantissa (no libm needed).
static double log_uniform(ttd_gen_rng *r, int lo, int hi)
{
    int k = lo + irand(r, hi - lo);
    return pow10i(k) * uni(r, 1.0, 10.0);
}

/// A small value in (10^-k / 2, 10^-k] with k uniform in 0..kmax.
static double small_value(ttd_gen_rng *r, int kmax)
{
    int k = irand(r, kmax + 1);
    return pow10i(-k) * uni(r, 0.5, 1.0);
}

static void unit_vector(ttd_gen_rng *r, double v[3])
{
    for (;;) {
        double x = uni(r, -1, 1), y = uni(r, -1, 1), z = uni(r, -1, 1);
        double n2 = x * x + y * y + z * z;
        if (n2 > 1e-4 && n2 <= 1.0) {
            double inv = 1.0 / sqrt(n2);
            v[0] = x * inv; v[1] = y * inv; v[2] = z * inv;
            return;
        }
    }
}

void ttd_gen_rng_rotation(ttd_gen_rng *r, double m[9])
{
    double w, x, y, z;
    for (;;) { /* uniform in the unit 4-ball, then onto the sphere: a uniform rotation */
        w = uni(r, -1, 1); x = uni(r, -1, 1); y = uni(r, -1, 1); z = uni(r, -1, 1);
        double n2 = w * w + x * x + y * y + z * z;
        if (n2 > 1e-4 && n2 <= 1.0) {
            double inv = 1.0 / sqrt(n2);
            w *= inv; x *= inv; y *= inv; z *= inv;
            break;
        }
    }
    m[0] = 1 - 2 * (y * y + z * z); m[1] = 2 * (x * y - w * z);     m[2] = 2 * (x * z + w * y);
    m[3] = 2 * (x * y + w * z);     m[4] = 1 - 2 * (x * x + z * z); m[5] = 2 * (y * z - w * x);
    m[6] = 2 * (x * z - w * y);     m[7] = 2 * (y * z + w * x);     m[8] = 1 - 2 * (x * x + y * y);
}

/* ---- moving pairs -------------------------------------------------------------------- */

static void set3(double *v, double x, double y, double z) { v[0] = x; v[1] = y; v[2] = z; }

/// Rotation m then translation tr, applied to the 3 vertices of both triangles.
static void rigid_motion(ttd_gen_rng *r, double *s, double *t, double tr_half)
{
    double m[9], tr[3];
    ttd_gen_rng_rotation(r, m);
    for (int k = 0; k < 3; ++k) tr[k] = uni(r, -tr_half, tr_half);
    double *tri[2] = {s, t};
    for (int j = 0; j < 2; ++j)
        for (int v = 0; v < 3; ++v) {
            double *p = tri[j] + 3 * v, x = p[0], y = p[1], z = p[2];
            for (int k = 0; k < 3; ++k) p[k] = m[3 * k] * x + m[3 * k + 1] * y + m[3 * k + 2] * z + tr[k];
        }
}

/// A multiple of 1/64 in [-h, h] (h a small integer): exact arithmetic stays exact on these.
static double grid(ttd_gen_rng *r, int h) { return (double)(irand(r, 128 * h + 1) - 64 * h) / 64.0; }

/// Axis permutation, sign flips and a dyadic translation: exact, so contacts stay exact.
static void exact_motion(ttd_gen_rng *r, double *s, double *t)
{
    static const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
    const int *pm = perms[irand(r, 6)];
    double sign[3], tr[3];
    for (int k = 0; k < 3; ++k) {
        sign[k] = irand(r, 2) ? -1.0 : 1.0;
        tr[k] = grid(r, 4);
    }
    double *tri[2] = {s, t};
    for (int j = 0; j < 2; ++j)
        for (int v = 0; v < 3; ++v) {
            double *p = tri[j] + 3 * v, q[3] = {p[0], p[1], p[2]};
            for (int k = 0; k < 3; ++k) p[k] = sign[k] * q[pm[k]] + tr[k];
        }
}

/// One of the 6 vertex orders of a triangle.
static void permute_vertices(ttd_gen_rng *r, double *tri)
{
    static const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
    const int *pm = perms[irand(r, 6)];
    double c[9];
    memcpy(c, tri, sizeof c);
    for (int v = 0; v < 3; ++v) memcpy(tri + 3 * v, c + 3 * pm[v], 3 * sizeof(double));
}

/// Random vertex orders and a random swap of the two triangles.
static void shuffle_pair(ttd_gen_rng *r, double *s, double *t)
{
    permute_vertices(r, s);
    permute_vertices(r, t);
    if (irand(r, 2)) {
        double c[9];
        memcpy(c, s, sizeof c);
        memcpy(s, t, sizeof c);
        memcpy(t, c, sizeof c);
    }
}

/* ---- families, one pair each --------------------------------------------------------- */

static void pair_random(ttd_gen_rng *r, double *s, double *t)
{
    double o[3];
    for (int k = 0; k < 9; ++k) s[k] = ttd_gen_rng_uniform(r);
    for (int k = 0; k < 3; ++k) o[k] = uni(r, -0.5, 0.5);
    for (int k = 0; k < 9; ++k) t[k] = ttd_gen_rng_uniform(r) + o[k % 3];
}

static void pair_paper(ttd_gen_rng *r, double *s, double *t)
{
    static const double ps[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    static const double pt[9] = {0.3, 0.3, 0.5, 1.0, 0.5, 1.2, 0.4, 1.1, 0.9};
    (void)r;
    memcpy(s, ps, sizeof ps);
    memcpy(t, pt, sizeof pt);
}

static void pair_far(ttd_gen_rng *r, double *s, double *t)
{
    double dir[3];
    for (int k = 0; k < 9; ++k) s[k] = uni(r, -0.5, 0.5);
    unit_vector(r, dir);
    double len = log_uniform(r, 1, 8);
    for (int k = 0; k < 9; ++k) t[k] = uni(r, -0.5, 0.5) + len * dir[k % 3];
}

static void pair_near_parallel_edges(ttd_gen_rng *r, double *s, double *t)
{
    int exact = irand(r, 12) == 0;
    double theta = exact ? 0.0 : small_value(r, 10);
    double gap = small_value(r, 6);
    double l1 = uni(r, 0.5, 1.5), l2 = uni(r, 0.5, 1.5);
    /* S: edge AB on the x axis, C in the quarter y <= 0, z < 0. */
    set3(s, 0, 0, 0);
    set3(s + 3, l1, 0, 0);
    set3(s + 6, uni(r, 0, l1), -uni(r, 0, 1), -uni(r, 0.2, 1));
    /* T: edge DE at height gap, direction (1, theta a, theta b), F above. */
    double a = uni(r, -1, 1), b = uni(r, -1, 1), n = sqrt(a * a + b * b);
    if (n == 0.0) { a = 1; n = 1; }
    double dx = 1.0, dy = theta * a / n, dz = theta * b / n;
    double x0 = uni(r, -0.4 * l2, l1 - 0.2);
    set3(t, x0, 0, gap);
    set3(t + 3, x0 + l2 * dx, l2 * dy, gap + l2 * dz);
    set3(t + 6, x0 + uni(r, 0, l2), uni(r, -1, 1), gap + uni(r, 0.2, 1));
    if (exact) exact_motion(r, s, t);
    else rigid_motion(r, s, t, 1.0);
    shuffle_pair(r, s, t);
}

static void pair_near_parallel_faces(ttd_gen_rng *r, double *s, double *t)
{
    int exact = irand(r, 12) == 0;
    double theta = exact ? 0.0 : small_value(r, 10);
    double gap = small_value(r, 6);
    double a = uni(r, -1, 1), b = uni(r, -1, 1), n = sqrt(a * a + b * b);
    if (n == 0.0) { a = 1; n = 1; }
    a *= theta / n; b *= theta / n;
    for (int v = 0; v < 3; ++v) {
        set3(s + 3 * v, ttd_gen_rng_uniform(r), ttd_gen_rng_uniform(r), 0.0);
        double x = ttd_gen_rng_uniform(r), y = ttd_gen_rng_uniform(r);
        set3(t + 3 * v, x, y, gap + a * (x - 0.5) + b * (y - 0.5));
    }
    if (exact) exact_motion(r, s, t);
    else rigid_motion(r, s, t, 1.0);
    shuffle_pair(r, s, t);
}

/// A random point inside triangle tri (barycentric weights bounded away from 0).
static void inner_point(ttd_gen_rng *r, const double *tri, double p[3])
{
    double u = uni(r, 0.1, 1), v = uni(r, 0.1, 1), w = uni(r, 0.1, 1), sum = u + v + w;
    for (int k = 0; k < 3; ++k) p[k] = (u * tri[k] + v * tri[3 + k] + w * tri[6 + k]) / sum;
}

static void pair_near_touching(ttd_gen_rng *r, double *s, double *t)
{
    double gap = small_value(r, 12);
    if (irand(r, 4) == 0) gap = -gap;
    /* S in the plane z = 0, a fat triangle. */
    set3(s, 0, 0, 0);
    set3(s + 3, uni(r, 0.8, 1.2), uni(r, -0.2, 0.2), 0);
    set3(s + 6, uni(r, -0.2, 0.8), uni(r, 0.8, 1.2), 0);
    double p[3], q[3];
    switch (irand(r, 4)) {
    case 0: /* vertex D over the interior of S, T above */
        inner_point(r, s, p);
        set3(t, p[0], p[1], gap);
        set3(t + 3, p[0] + uni(r, -0.5, 0.5), p[1] + uni(r, -0.5, 0.5), gap + uni(r, 0.3, 1));
        set3(t + 6, p[0] + uni(r, -0.5, 0.5), p[1] + uni(r, -0.5, 0.5), gap + uni(r, 0.3, 1));
        break;
    case 1: /* edge AB of S (tilted down to C) crossed by edge DE of T at height gap */
        set3(s, -0.5, 0, 0);
        set3(s + 3, 0.5, 0, 0);
        set3(s + 6, uni(r, -0.5, 0.5), uni(r, -1, 1), -uni(r, 0.3, 1));
        {
            double xc = uni(r, -0.3, 0.3), slope = uni(r, -0.5, 0.5);
            set3(t, xc - 0.5 * slope, -0.5, gap);
            set3(t + 3, xc + 0.5 * slope, 0.5, gap);
            set3(t + 6, uni(r, -0.5, 0.5), uni(r, -0.5, 0.5), gap + uni(r, 0.3, 1));
        }
        break;
    case 2: /* edge DE parallel to S, over its interior */
        inner_point(r, s, p);
        inner_point(r, s, q);
        set3(t, p[0], p[1], gap);
        set3(t + 3, q[0], q[1], gap);
        set3(t + 6, uni(r, 0, 1), uni(r, 0, 1), gap + uni(r, 0.3, 1));
        break;
    default: /* T parallel to S, inside its projection */
        for (int v = 0; v < 3; ++v) {
            inner_point(r, s, p);
            set3(t + 3 * v, p[0], p[1], gap);
        }
        break;
    }
    rigid_motion(r, s, t, 1.0);
    shuffle_pair(r, s, t);
}

/// A grid triangle with non-zero area.
static void grid_triangle(ttd_gen_rng *r, double *tri)
{
    for (;;) {
        for (int k = 0; k < 9; ++k) tri[k] = grid(r, 1);
        double e1[3], e2[3];
        for (int k = 0; k < 3; ++k) { e1[k] = tri[3 + k] - tri[k]; e2[k] = tri[6 + k] - tri[k]; }
        double cx = e1[1] * e2[2] - e1[2] * e2[1], cy = e1[2] * e2[0] - e1[0] * e2[2],
               cz = e1[0] * e2[1] - e1[1] * e2[0];
        if (cx * cx + cy * cy + cz * cz > 1e-2) return;
    }
}

static void pair_intersecting(ttd_gen_rng *r, double *s, double *t)
{
    double x[3], v[3];
    grid_triangle(r, s);
    grid_triangle(r, t);
    switch (irand(r, 7)) {
    case 0: /* pierce: DE passes through an interior point of S */
        for (int k = 0; k < 3; ++k) {
            x[k] = (s[k] + s[3 + k] + 2 * s[6 + k]) / 4;
            v[k] = grid(r, 1);
        }
        if (v[0] == 0 && v[1] == 0 && v[2] == 0) v[2] = 0.5;
        for (int k = 0; k < 3; ++k) { t[k] = x[k] - v[k]; t[3 + k] = x[k] + v[k]; }
        break;
    case 1: /* coplanar overlap: S and T in z = 0, D inside S */
        for (int j = 0; j < 3; ++j) { s[3 * j + 2] = 0; t[3 * j + 2] = 0; }
        s[0] = -1; s[1] = -1; s[3] = 1; s[4] = -1; s[6] = 0; s[7] = 1; /* fat, non-degenerate */
        for (int k = 0; k < 2; ++k) t[k] = (s[k] + s[3 + k] + 2 * s[6 + k]) / 4;
        break;
    case 2: /* edge through edge: DE crosses AB at its midpoint */
        for (int k = 0; k < 3; ++k) { x[k] = (s[k] + s[3 + k]) / 2; v[k] = grid(r, 1); }
        if (v[0] == 0 && v[1] == 0 && v[2] == 0) v[2] = 0.5;
        for (int k = 0; k < 3; ++k) { t[k] = x[k] - v[k]; t[3 + k] = x[k] + v[k]; }
        break;
    case 3: /* vertex on face */
        for (int k = 0; k < 3; ++k) t[k] = (s[k] + s[3 + k] + 2 * s[6 + k]) / 4;
        break;
    case 4: /* vertex on edge */
        for (int k = 0; k < 3; ++k) t[k] = (3 * s[k] + s[3 + k]) / 4;
        break;
    case 5: /* shared vertex */
        memcpy(t, s, 3 * sizeof(double));
        break;
    default: /* shared edge */
        memcpy(t, s, 6 * sizeof(double));
        break;
    }
    exact_motion(r, s, t);
    shuffle_pair(r, s, t);
}

/// Makes tri degenerate in one of three ways (kind 1..3), on the grid, exactly.
static void degenerate_triangle(ttd_gen_rng *r, double *tri, int kind)
{
    for (int k = 0; k < 9; ++k) tri[k] = grid(r, 1);
    if (kind == 1) { /* segment: C = A + (j/4)(B - A), exactly collinear */
        double lam = (double)(irand(r, 13) - 4) / 4.0;
        for (int k = 0; k < 3; ++k) tri[6 + k] = tri[k] + lam * (tri[3 + k] - tri[k]);
    } else if (kind == 2) { /* point */
        memcpy(tri + 3, tri, 3 * sizeof(double));
        memcpy(tri + 6, tri, 3 * sizeof(double));
    } else { /* two repeated vertices: a segment A-C */
        memcpy(tri + 3, tri, 3 * sizeof(double));
    }
}

static void pair_degenerate(ttd_gen_rng *r, double *s, double *t)
{
    degenerate_triangle(r, s, 1 + irand(r, 3));
    int kt = irand(r, 4);
    if (kt == 0) grid_triangle(r, t);
    else degenerate_triangle(r, t, kt);
    double o[3];
    for (int k = 0; k < 3; ++k) o[k] = grid(r, 1) / 2;
    for (int k = 0; k < 9; ++k) t[k] += o[k % 3];
    exact_motion(r, s, t);
    shuffle_pair(r, s, t);
}

/// A sliver around base point b: a needle or a flat cap of aspect ratio about eps.
static void sliver_triangle(ttd_gen_rng *r, double *tri, const double base[3])
{
    double eps = small_value(r, 10), u[3], w[3], b[3] = {base[0], base[1], base[2]};
    unit_vector(r, u);
    double len = uni(r, 0.5, 1.0);
    if (irand(r, 2)) { /* needle: B within eps of A, C far */
        unit_vector(r, w);
        for (int k = 0; k < 3; ++k) { tri[3 + k] = b[k] + eps * len * w[k]; tri[6 + k] = b[k] + len * u[k]; }
    } else { /* cap: C at height eps*len over the line AB */
        unit_vector(r, w);
        double dot = w[0] * u[0] + w[1] * u[1] + w[2] * u[2];
        for (int k = 0; k < 3; ++k) w[k] -= dot * u[k];
        double nw = sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
        if (nw == 0.0) { w[0] = -u[1]; w[1] = u[0]; w[2] = 0; nw = sqrt(w[0] * w[0] + w[1] * w[1]); }
        double along = uni(r, -0.2, 1.2);
        for (int k = 0; k < 3; ++k) {
            tri[3 + k] = b[k] + len * u[k];
            tri[6 + k] = b[k] + len * (along * u[k] + eps * w[k] / nw);
        }
    }
}

static void pair_sliver(ttd_gen_rng *r, double *s, double *t)
{
    pair_random(r, s, t);
    int which = irand(r, 3); /* 0: S only, 1: T only, 2: both */
    if (which != 1) sliver_triangle(r, s, s);
    if (which != 0) sliver_triangle(r, t, t);
    shuffle_pair(r, s, t);
}

static void pair_scaled(ttd_gen_rng *r, double *s, double *t)
{
    pair_random(r, s, t);
    double f = log_uniform(r, -6, 6);
    for (int k = 0; k < 9; ++k) { s[k] *= f; t[k] *= f; }
}

static void pair_offset(ttd_gen_rng *r, double *s, double *t)
{
    double dir[3];
    pair_random(r, s, t);
    unit_vector(r, dir);
    double len = log_uniform(r, 0, 6);
    for (int k = 0; k < 9; ++k) { s[k] += len * dir[k % 3]; t[k] += len * dir[k % 3]; }
}

/// Fills tri as a fat triangle in the plane z = 0 around the origin.
static void fat_triangle_z0(ttd_gen_rng *r, double *tri)
{
    set3(tri, uni(r, -0.6, -0.4), uni(r, -0.4, -0.2), 0);
    set3(tri + 3, uni(r, 0.4, 0.6), uni(r, -0.4, -0.2), 0);
    set3(tri + 6, uni(r, -0.1, 0.1), uni(r, 0.4, 0.6), 0);
}

/// Vertex v of apex (the others higher) over the interior of base (in z = 0), at height gap.
static void vertex_over_face(ttd_gen_rng *r, double *apex, int v, double *base, double gap)
{
    double p[3];
    fat_triangle_z0(r, base);
    inner_point(r, base, p);
    for (int k = 0; k < 3; ++k) {
        if (k == v) set3(apex + 3 * k, p[0], p[1], gap);
        else set3(apex + 3 * k, p[0] + uni(r, -0.5, 0.5), p[1] + uni(r, -0.5, 0.5), gap + uni(r, 0.3, 1));
    }
}

/* Pair i has feature pairing i mod 15 as its unique closest pair, labels preserved:
 * 0..2 vertex i of S to the face of T; 3..5 vertex i-3 of T to the face of S; 6..14 edge
 * (m-6)/3 of S (AB, BC, CA) to edge (m-6)%3 of T (DE, EF, FD), crossing. Gap in [1e-3, 1). */
static void pair_features(ttd_gen_rng *r, double *s, double *t, size_t i)
{
    int m = (int)(i % 15);
    double gap = log_uniform(r, -3, 0);
    if (m < 3) {
        vertex_over_face(r, s, m, t, gap);
    } else if (m < 6) {
        vertex_over_face(r, t, m - 3, s, gap);
    } else {
        int ei = (m - 6) / 3, ej = (m - 6) % 3;
        double xc = uni(r, -0.3, 0.3), slope = uni(r, -0.5, 0.5);
        set3(s + 3 * ei, -0.5, 0, 0);
        set3(s + 3 * ((ei + 1) % 3), 0.5, 0, 0);
        set3(s + 3 * ((ei + 2) % 3), uni(r, -0.5, 0.5), uni(r, -1, 1), -uni(r, 0.3, 1));
        set3(t + 3 * ej, xc - 0.5 * slope, -0.5, gap);
        set3(t + 3 * ((ej + 1) % 3), xc + 0.5 * slope, 0.5, gap);
        set3(t + 3 * ((ej + 2) % 3), uni(r, -0.5, 0.5), uni(r, -0.5, 0.5), gap + uni(r, 0.3, 1));
    }
    rigid_motion(r, s, t, 1.0);
}

typedef void (*pair_fn)(ttd_gen_rng *r, double *s, double *t);

static const pair_fn family_fns[TTD_GEN_COUNT] = {
    pair_random, pair_paper, pair_far, pair_near_parallel_edges, pair_near_parallel_faces,
    pair_near_touching, pair_intersecting, pair_degenerate, pair_sliver, pair_scaled, pair_offset,
    NULL, /* features: needs the pair index, called directly */
};

/* ---- entry points -------------------------------------------------------------------- */

size_t ttd_gen(ttd_gen_family f, uint64_t seed, size_t n, double *s, double *t)
{
    if ((int)f < 0 || f >= TTD_GEN_COUNT || !s || !t) return 0;
    for (size_t i = 0; i < n; ++i) {
        /* one stream per (family, seed, pair): prefixes are stable, pairs independent */
        ttd_gen_rng r = ttd_gen_rng_make(seed ^ ((uint64_t)(f + 1) << 56), (uint64_t)i);
        if (f == TTD_GEN_FEATURES) pair_features(&r, s + 9 * i, t + 9 * i, i);
        else family_fns[f](&r, s + 9 * i, t + 9 * i);
    }
    return n;
}

const char *ttd_gen_name(ttd_gen_family f)
{
    return ((int)f >= 0 && f < TTD_GEN_COUNT) ? family_names[f] : NULL;
}

int ttd_gen_family_from_name(const char *name)
{
    if (!name) return -1;
    for (int f = 0; f < TTD_GEN_COUNT; ++f)
        if (strcmp(name, family_names[f]) == 0) return f;
    return -1;
}

size_t ttd_gen_random(uint64_t seed, size_t n, double *s, double *t) { return ttd_gen(TTD_GEN_RANDOM, seed, n, s, t); }
size_t ttd_gen_paper(uint64_t seed, size_t n, double *s, double *t) { return ttd_gen(TTD_GEN_PAPER, seed, n, s, t); }
size_t ttd_gen_far(uint64_t seed, size_t n, double *s, double *t) { return ttd_gen(TTD_GEN_FAR, seed, n, s, t); }
size_t ttd_gen_near_parallel_edges(uint64_t seed, size_t n, double *s, double *t) { return ttd_gen(TTD_GEN_NEAR_PARALLEL_EDGES, seed, n, s, t); }
size_t ttd_gen_near_parallel_faces(uint64_t seed, size_t n, double *s, double *t) { return ttd_gen(TTD_GEN_NEAR_PARALLEL_FACES, seed, n, s, t); }
size_t ttd_gen_near_touching(uint64_t seed, size_t n, double *s, double *t) { return ttd_gen(TTD_GEN_NEAR_TOUCHING, seed, n, s, t); }
size_t ttd_gen_intersecting(uint64_t seed, size_t n, double *s, double *t) { return ttd_gen(TTD_GEN_INTERSECTING, seed, n, s, t); }
size_t ttd_gen_degenerate(uint64_t seed, size_t n, double *s, double *t) { return ttd_gen(TTD_GEN_DEGENERATE, seed, n, s, t); }
size_t ttd_gen_sliver(uint64_t seed, size_t n, double *s, double *t) { return ttd_gen(TTD_GEN_SLIVER, seed, n, s, t); }
size_t ttd_gen_scaled(uint64_t seed, size_t n, double *s, double *t) { return ttd_gen(TTD_GEN_SCALED, seed, n, s, t); }
size_t ttd_gen_offset(uint64_t seed, size_t n, double *s, double *t) { return ttd_gen(TTD_GEN_OFFSET, seed, n, s, t); }
size_t ttd_gen_features(uint64_t seed, size_t n, double *s, double *t) { return ttd_gen(TTD_GEN_FEATURES, seed, n, s, t); }

void ttd_gen_features_expected(size_t i, unsigned *feature_s, unsigned *feature_t)
{
    int m = (int)(i % 15);
    if (m < 3) { *feature_s = 1u << m; *feature_t = 7u; }
    else if (m < 6) { *feature_s = 7u; *feature_t = 1u << (m - 3); }
    else {
        int ei = (m - 6) / 3, ej = (m - 6) % 3;
        *feature_s = (1u << ei) | (1u << ((ei + 1) % 3));
        *feature_t = (1u << ej) | (1u << ((ej + 1) % 3));
    }
}

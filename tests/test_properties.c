/* SPDX-License-Identifier: MIT */
/* Properties the exact method (ttd_exact_pair_d, src/scalar/) must have whatever the pair,
 * checked on several generator families:
 *   - symmetry d(S,T) = d(T,S), and p, q exchanged where the closest pair is unique and well
 *     conditioned (closest_pair_kind: a vertex closest, or skew edges; touching, parallel and
 *     edge/face-against-face pairs skipped);
 *   - invariance under the 6 x 6 vertex orders;
 *   - invariance under random rigid motions (within the rounding of the moved input), under
 *     exact motions (axis permutations, sign flips), scaling by powers of 4 (exact, so the
 *     distance must scale bit for bit: no absolute thresholds),
 *     and dyadic translations by 2^20 of pairs on a dyadic grid (exact);
 *   - p and q on their triangles: weights >= 0, summing to 1, giving p and q; |p - q| = d;
 *   - d <= each of the 15 sub-distances (from the reference, tests/reference/);
 *   - d = 0 and the intersecting flag when the reference finds a robust crossing, d > 0 when
 *     the reference finds the pair separated by more than 1e-10 of its size;
 *   - a triangle with exactly zero area is flagged degenerate.
 *   - float: symmetry and the intersecting flag within the float target (1e-5 of size), p and q
 *     on their float-rounded triangles.
 * "Within rounding" is 1e-13 relative to max(d, size) unless said otherwise: an order below
 * the method's 1e-12 accuracy target. */
#include <float.h>
#include <math.h>
#include <stdlib.h>

#include "pairs.h"
#include "ref_distance.h"
#include "scalar/scalar.h"
#include "test_macros.h"

enum { PAIRS = 400 };
static const double ROUNDING = 1e-13;

static const ttd_gen_family families[] = {
    TTD_GEN_RANDOM, TTD_GEN_FAR, TTD_GEN_NEAR_PARALLEL_EDGES, TTD_GEN_NEAR_PARALLEL_FACES, TTD_GEN_NEAR_TOUCHING,
    TTD_GEN_INTERSECTING, TTD_GEN_DEGENERATE, TTD_GEN_SLIVER, TTD_GEN_SCALED,
};
enum { NFAM = sizeof families / sizeof families[0] };

static double dist(const double *s, const double *t)
{
    ttd_result_d r;
    ttd_exact_pair_d(s, t, &r);
    return r.distance;
}

static double ttd_ref_distance_value(const double *s, const double *t)
{
    ttd_ref_result r;
    ttd_ref_distance(s, t, &r);
    return r.distance;
}

static double pair_scale(const double *s, const double *t, double d)
{
    return fmax(ttd_ref_size(s, t), d);
}

/// Runs check(s, t, family) on PAIRS pairs of every family; reports the first failing pair.
static int for_each_pair(int (*check)(const double *s, const double *t), const char *what)
{
    double *s = malloc(9 * sizeof(double) * PAIRS), *t = malloc(9 * sizeof(double) * PAIRS);
    ENSURE(s && t);
    int failed = 0;
    for (int f = 0; f < (int)NFAM && !failed; ++f) {
        ttd_gen(families[f], 77, PAIRS, s, t);
        for (int i = 0; i < PAIRS; ++i)
            if (check(s + 9 * i, t + 9 * i)) {
                fprintf(stderr, "  %s fails on %s pair %d:\n", what, ttd_gen_name(families[f]), i);
                print_pair("input", s + 9 * i, t + 9 * i);
                failed = 1;
                break;
            }
    }
    free(s);
    free(t);
    return failed;
}

/* Whether the closest pair of (s, t) is unique, and well conditioned, so that p and q of both
 * argument orders can be compared: 0 when it may not be (skipped), 1 when a vertex is the
 * closest feature of one triangle, 2 when the closest features are two edges at an angle.
 * Detected from the reference's separation direction v = p - q (quad-accurate, rounded):
 * every closest pair has p - q = v, and p lies where S is lowest along v, q where T is
 * highest. A triangle's closest feature is its vertices within TAU of its extreme height.
 * - d <= 1e-6 of the pair's size (touching, intersecting, or v's direction uncertain): 0.
 * - one triangle's closest feature is a single vertex: unique (p is that vertex, q = p - v).
 * - both are edges with sin(angle) > 1e-3: unique (p and q can only move together along a
 *   direction parallel to both edges), conditioned by 1 / sin(angle).
 * - anything else (parallel edges, edge against face, face against face): 0, since p and q
 *   can slide together over the overlap. */
static int closest_pair_kind(const double *s, const double *t, double scale)
{
    ttd_ref_result ref;
    ttd_ref_distance(s, t, &ref);
    if (!(ref.distance > 1e-6 * scale))
        return 0;
    double v[3], n = 0;
    for (int k = 0; k < 3; ++k)
        v[k] = ref.p[k] - ref.q[k], n += v[k] * v[k];
    n = sqrt(n);
    const double tau = 1e-6 * scale;
    double hs[3], ht[3], smin = (double)INFINITY, tmax = -(double)INFINITY;
    for (int i = 0; i < 3; ++i) {
        hs[i] = (s[3 * i] * v[0] + s[3 * i + 1] * v[1] + s[3 * i + 2] * v[2]) / n;
        ht[i] = (t[3 * i] * v[0] + t[3 * i + 1] * v[1] + t[3 * i + 2] * v[2]) / n;
        smin = fmin(smin, hs[i]), tmax = fmax(tmax, ht[i]);
    }
    int ns = 0, nt = 0, es[2] = {0, 0}, et[2] = {0, 0};
    for (int i = 0; i < 3; ++i) {
        if (hs[i] - smin <= tau) es[ns < 2 ? ns : 1] = i, ++ns;
        if (tmax - ht[i] <= tau) et[nt < 2 ? nt : 1] = i, ++nt;
    }
    if (ns == 1 || nt == 1)
        return 1;
    if (ns != 2 || nt != 2)
        return 0;
    double a[3], b[3], c[3];
    for (int k = 0; k < 3; ++k)
        a[k] = s[3 * es[1] + k] - s[3 * es[0] + k], b[k] = t[3 * et[1] + k] - t[3 * et[0] + k];
    c[0] = a[1] * b[2] - a[2] * b[1], c[1] = a[2] * b[0] - a[0] * b[2], c[2] = a[0] * b[1] - a[1] * b[0];
    double sin_ab = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]) /
                    (sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]) * sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]));
    return sin_ab > 1e-3 ? 2 : 0;
}

static double sym_worst[3];
static int sym_count[3];

static int check_symmetry(const double *s, const double *t)
{
    ttd_result_d a, b;
    ttd_exact_pair_d(s, t, &a);
    ttd_exact_pair_d(t, s, &b);
    double scale = pair_scale(s, t, a.distance);
    ENSURE_NEAR(a.distance, b.distance, ROUNDING * scale);
    int kind = closest_pair_kind(s, t, scale);
    sym_count[kind]++;
    if (kind == 0)
        return 0;
    double dev = 0;
    for (int k = 0; k < 3; ++k)
        dev = fmax(dev, fmax(fabs(a.p[k] - b.q[k]), fabs(a.q[k] - b.p[k])));
    sym_worst[kind] = fmax(sym_worst[kind], dev / scale);
    ENSURE_MSG(dev <= ROUNDING * scale, "d(T,S)'s p, q are not d(S,T)'s q, p: off by %.3g of size (kind %d)",
               dev / scale, kind);
    return 0;
}
static int symmetry(void)
{
    int r = for_each_pair(check_symmetry, "symmetry");
    printf("  p, q exchanged: %d pairs vertex-closest (worst %.3g of size), %d skew edges (worst %.3g), %d skipped\n",
           sym_count[1], sym_worst[1], sym_count[2], sym_worst[2], sym_count[0]);
    return r;
}

static const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};

static void reorder(const double *in, double *out, const int pm[3])
{
    for (int v = 0; v < 3; ++v)
        for (int k = 0; k < 3; ++k) out[3 * v + k] = in[3 * pm[v] + k];
}

static int check_vertex_order(const double *s, const double *t)
{
    double d0 = dist(s, t), tol = ROUNDING * pair_scale(s, t, d0);
    for (int i = 0; i < 6; ++i)
        for (int j = 0; j < 6; ++j) {
            double s2[9], t2[9];
            reorder(s, s2, perms[i]);
            reorder(t, t2, perms[j]);
            ENSURE_NEAR(dist(s2, t2), d0, tol);
        }
    return 0;
}
static int vertex_order(void) { return for_each_pair(check_vertex_order, "vertex order"); }

static int check_rigid_motion(const double *s, const double *t)
{
    double d0 = dist(s, t), scale = pair_scale(s, t, d0), mag = 0;
    for (int k = 0; k < 9; ++k) mag = fmax(mag, fmax(fabs(s[k]), fabs(t[k])));
    uint64_t seed;
    memcpy(&seed, s, sizeof seed); /* a different motion for every pair, reproducibly */
    ttd_gen_rng r = ttd_gen_rng_make(seed, 1);
    for (int rep = 0; rep < 4; ++rep) {
        double m[9], tr[3], s2[9], t2[9];
        ttd_gen_rng_rotation(&r, m);
        for (int k = 0; k < 3; ++k) tr[k] = 2 * ttd_gen_rng_uniform(&r) - 1;
        for (int v = 0; v < 3; ++v)
            for (int k = 0; k < 3; ++k) {
                const double *x = s + 3 * v, *y = t + 3 * v;
                s2[3 * v + k] = m[3 * k] * x[0] + m[3 * k + 1] * x[1] + m[3 * k + 2] * x[2] + tr[k];
                t2[3 * v + k] = m[3 * k] * y[0] + m[3 * k + 1] * y[1] + m[3 * k + 2] * y[2] + tr[k];
            }
        /* the moved input is rounded: each vertex moves by up to ~4 eps (|x| + 1) */
        double tol = ROUNDING * scale + 16 * DBL_EPSILON * (mag + 1);
        ENSURE_NEAR(dist(s2, t2), d0, tol);
    }
    /* exact motions: axis permutation and sign flips */
    for (int p = 0; p < 6; ++p) {
        double sg[3] = {(p & 1) ? -1.0 : 1.0, (p & 2) ? -1.0 : 1.0, (p & 4) ? -1.0 : 1.0}, s2[9], t2[9];
        for (int v = 0; v < 3; ++v)
            for (int k = 0; k < 3; ++k) {
                s2[3 * v + k] = sg[k] * s[3 * v + perms[p][k]];
                t2[3 * v + k] = sg[k] * t[3 * v + perms[p][k]];
            }
        ENSURE_NEAR(dist(s2, t2), d0, ROUNDING * scale);
    }
    return 0;
}
static int rigid_motion(void) { return for_each_pair(check_rigid_motion, "rigid motion"); }

/* Scaling by 4^k is exact and commutes with every rounding, sqrt included, as long as
 * nothing underflows or overflows (true here: coordinates stay within 1e-13..1e14). So a
 * method without absolute thresholds returns exactly 2^(2k) d: the test demands bit equality,
 * which any hidden absolute epsilon breaks. */
static int check_scaling(const double *s, const double *t)
{
    double d0 = dist(s, t);
    const int ks[4] = {-10, -5, 5, 10};
    for (int i = 0; i < 4; ++i) {
        double f = ldexp(1.0, 2 * ks[i]), s2[9], t2[9];
        for (int k = 0; k < 9; ++k) { s2[k] = s[k] * f; t2[k] = t[k] * f; }
        double d1 = dist(s2, t2);
        ENSURE_MSG(d1 / f == d0, "scaled by 4^%d: %.17g, unscaled %.17g", ks[i], d1 / f, d0);
    }
    return 0;
}
static int scaling(void) { return for_each_pair(check_scaling, "scaling by 4^k"); }

/* Pairs on a dyadic grid (intersecting and degenerate families) translated by 2^20 in every
 * axis: exact, so the distance may change only by the method's rounding. */
static int translation_exact(void)
{
    double s[9 * PAIRS], t[9 * PAIRS];
    const ttd_gen_family grid_families[2] = {TTD_GEN_INTERSECTING, TTD_GEN_DEGENERATE};
    for (int f = 0; f < 2; ++f) {
        ttd_gen(grid_families[f], 78, PAIRS, s, t);
        for (int i = 0; i < PAIRS; ++i) {
            const double *a = s + 9 * i, *b = t + 9 * i;
            double d0 = dist(a, b), s2[9], t2[9];
            for (int k = 0; k < 9; ++k) {
                s2[k] = a[k] + 0x1p20;
                t2[k] = b[k] + 0x1p20;
                ENSURE(s2[k] - 0x1p20 == a[k] && t2[k] - 0x1p20 == b[k]); /* exact */
            }
            double d1 = dist(s2, t2), tol = ROUNDING * pair_scale(a, b, d0);
            if (!(fabs(d1 - d0) <= tol)) {
                fprintf(stderr, "  translation by 2^20 of %s pair %d: %.17g vs %.17g\n", ttd_gen_name(grid_families[f]),
                        i, d1, d0);
                print_pair("input", a, b);
                return 1;
            }
        }
    }
    return 0;
}

static int check_points_on_triangles(const double *s, const double *t)
{
    ttd_result_d r;
    ttd_exact_pair_d(s, t, &r);
    double scale = pair_scale(s, t, r.distance), mag = 0;
    for (int k = 0; k < 9; ++k) mag = fmax(mag, fmax(fabs(s[k]), fabs(t[k])));
    double tol = ROUNDING * scale + 8 * DBL_EPSILON * mag;
    double sp = 0, sq = 0;
    for (int k = 0; k < 3; ++k) {
        ENSURE(r.bary_p[k] >= 0 && r.bary_q[k] >= 0 && r.bary_p[k] <= 1 && r.bary_q[k] <= 1);
        sp += r.bary_p[k];
        sq += r.bary_q[k];
        ENSURE_NEAR(r.bary_p[0] * s[k] + r.bary_p[1] * s[3 + k] + r.bary_p[2] * s[6 + k], r.p[k], tol);
        ENSURE_NEAR(r.bary_q[0] * t[k] + r.bary_q[1] * t[3 + k] + r.bary_q[2] * t[6 + k], r.q[k], tol);
    }
    ENSURE_NEAR(sp, 1.0, 4 * DBL_EPSILON);
    ENSURE_NEAR(sq, 1.0, 4 * DBL_EPSILON);
    ENSURE(ttd_ref_point_triangle(r.p, s) <= tol);
    ENSURE(ttd_ref_point_triangle(r.q, t) <= tol);
    double dx = r.p[0] - r.q[0], dy = r.p[1] - r.q[1], dz = r.p[2] - r.q[2];
    ENSURE_NEAR(sqrt(dx * dx + dy * dy + dz * dz), r.distance, tol);
    /* feature bits: vertex i is in the feature exactly when its weight is non-zero */
    for (int k = 0; k < 3; ++k) {
        ENSURE(((r.feature_p >> k) & 1u) == (r.bary_p[k] != 0));
        ENSURE(((r.feature_q >> k) & 1u) == (r.bary_q[k] != 0));
    }
    return 0;
}
static int points_on_triangles(void) { return for_each_pair(check_points_on_triangles, "p, q on triangles"); }

static int check_sub_distances(const double *s, const double *t)
{
    double d = dist(s, t), sub[15];
    ttd_ref_sub_distances(s, t, sub);
    double tol = ROUNDING * pair_scale(s, t, d);
    for (int k = 0; k < 15; ++k) ENSURE_MSG(d <= sub[k] + tol, "d %.17g > sub-distance %d = %.17g", d, k, sub[k]);
    return 0;
}
static int below_sub_distances(void) { return for_each_pair(check_sub_distances, "d <= sub-distances"); }

static int check_intersection(const double *s, const double *t)
{
    ttd_result_d r;
    ttd_exact_pair_d(s, t, &r);
    ttd_ref_result ref;
    ttd_ref_distance(s, t, &ref);
    double size = ttd_ref_size(s, t);
    if (ttd_ref_intersection_margin(s, t) > 1e-6) { /* a crossing that survives perturbation */
        ENSURE_MSG(r.distance == 0.0, "robust crossing but d = %.17g", r.distance);
        ENSURE(r.flags & TTD_PAIR_INTERSECTING);
    }
    if (ref.distance > 1e-10 * size) {
        ENSURE_MSG(r.distance > 0.0, "separated by %.17g but d = 0", ref.distance);
        ENSURE(!(r.flags & TTD_PAIR_INTERSECTING));
    }
    if (r.flags & TTD_PAIR_INTERSECTING) ENSURE(r.distance == 0.0);
    return 0;
}
static int zero_exactly_when_intersecting(void)
{
    return for_each_pair(check_intersection, "d = 0 exactly when intersecting");
}

static int exact_zero_area(const double *x)
{
    double e1[3] = {x[3] - x[0], x[4] - x[1], x[5] - x[2]}, e2[3] = {x[6] - x[0], x[7] - x[1], x[8] - x[2]};
    return e1[1] * e2[2] - e1[2] * e2[1] == 0 && e1[2] * e2[0] - e1[0] * e2[2] == 0 &&
           e1[0] * e2[1] - e1[1] * e2[0] == 0;
}

/* Degenerate family: coordinates on a dyadic grid, so the area test above is exact. */
static int degenerate_flags(void)
{
    double s[9 * PAIRS], t[9 * PAIRS];
    ttd_gen(TTD_GEN_DEGENERATE, 79, PAIRS, s, t);
    for (int i = 0; i < PAIRS; ++i) {
        ttd_result_d r;
        ttd_exact_pair_d(s + 9 * i, t + 9 * i, &r);
        if (exact_zero_area(s + 9 * i)) ENSURE(r.flags & TTD_PAIR_DEGENERATE_S);
        if (exact_zero_area(t + 9 * i)) ENSURE(r.flags & TTD_PAIR_DEGENERATE_T);
        if (!exact_zero_area(s + 9 * i)) ENSURE(!(r.flags & TTD_PAIR_DEGENERATE_S));
        if (!exact_zero_area(t + 9 * i)) ENSURE(!(r.flags & TTD_PAIR_DEGENERATE_T));
    }
    return 0;
}

/* Float: the same symmetry and points-on-triangles properties on the float-rounded input. */
static int float_properties(void)
{
    double s[9 * PAIRS], t[9 * PAIRS];
    for (int f = 0; f < (int)NFAM; ++f) {
        ttd_gen(families[f], 80, PAIRS, s, t);
        for (int i = 0; i < PAIRS; ++i) {
            float a[9], b[9];
            double ad[9], bd[9];
            for (int k = 0; k < 9; ++k) {
                a[k] = (float)s[9 * i + k]; b[k] = (float)t[9 * i + k];
                ad[k] = (double)a[k]; bd[k] = (double)b[k];
            }
            ttd_result_f r1, r2;
            ttd_exact_pair_f(a, b, &r1);
            ttd_exact_pair_f(b, a, &r2);
            double scale = pair_scale(ad, bd, (double)r1.distance), mag = 0;
            for (int k = 0; k < 9; ++k) mag = fmax(mag, fmax(fabs(ad[k]), fabs(bd[k])));
            double tol = 1e-6 * scale + 8 * (double)FLT_EPSILON * mag;
            if (!(fabs((double)r1.distance - (double)r2.distance) <= 1e-5 * scale)) {
                ttd_ref_result ref;
                ttd_ref_distance(ad, bd, &ref);
                fprintf(stderr, "  float symmetry, %s pair %d: d(S,T) %.9g d(T,S) %.9g reference %.17g size %.3g\n",
                        ttd_gen_name(families[f]), i, (double)r1.distance, (double)r2.distance, ref.distance, scale);
                print_pair("input", ad, bd);
                return 1;
            }
            double p[3] = {(double)r1.p[0], (double)r1.p[1], (double)r1.p[2]};
            double q[3] = {(double)r1.q[0], (double)r1.q[1], (double)r1.q[2]};
            ENSURE_MSG(ttd_ref_point_triangle(p, ad) <= tol && ttd_ref_point_triangle(q, bd) <= tol,
                       "%s pair %d", ttd_gen_name(families[f]), i);
            for (int k = 0; k < 3; ++k) ENSURE(r1.bary_p[k] >= 0 && r1.bary_q[k] >= 0);
            /* flagged intersecting only within the float accuracy target of a contact */
            if (r1.flags & TTD_PAIR_INTERSECTING) {
                ENSURE(r1.distance == 0.0f);
                ENSURE_MSG(ttd_ref_distance_value(ad, bd) <= 1e-5 * scale, "%s pair %d", ttd_gen_name(families[f]), i);
            }
        }
    }
    return 0;
}

int main(int argc, char **argv)
{
    TEST_MAIN_BEGIN(argc, argv);
    RUN_TEST(symmetry);
    RUN_TEST(vertex_order);
    RUN_TEST(rigid_motion);
    RUN_TEST(scaling);
    RUN_TEST(translation_exact);
    RUN_TEST(points_on_triangles);
    RUN_TEST(below_sub_distances);
    RUN_TEST(zero_exactly_when_intersecting);
    RUN_TEST(degenerate_flags);
    RUN_TEST(float_properties);
    TEST_MAIN_END();
}

/* SPDX-License-Identifier: MIT */
/* ttd_exact_pair_dups_d/f, which the manifold's step 0 asks its vertex and edge questions with
 * (a vertex as a triangle (v, v, v), an edge as (a, b, b)), against the exact method itself:
 * every field of the result the same bits, on triangles with every pattern of repeated vertices
 * (and none), both orders, coordinates on a small grid (where candidates tie exactly, so the
 * first-of-equals choice is tested), random ones at scales from subnormal to 2^1000, needles
 * (a third vertex 1e-15 off the other two's midpoint), and vertices shared between the two
 * triangles. And step 0's two screens of edge questions (scene/edge_axis_impl.h,
 * scene/edges_miss_impl.h) against the same method: no corner wherever they screen one out. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "test_macros.h"
#include "scalar/scalar.h"

/* step 0's screen of edge questions on axis-aligned edges, once per precision */
#define real double
#define edge_axis edge_axis_d
#define edges_axis_apart edges_axis_apart_d
#include "scene/edge_axis_impl.h"
#undef real
#undef edge_axis
#undef edges_axis_apart
#define real float
#define edge_axis edge_axis_f
#define edges_axis_apart edges_axis_apart_f
#include "scene/edge_axis_impl.h"
#undef real
#undef edge_axis
#undef edges_axis_apart

/* step 0's screen of edge questions far from a corner, once per precision, with the dot product
 * of scene/normal_impl.h */
static double dot3d(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
#define real double
#define edges_miss edges_miss_d
#include "scene/edges_miss_impl.h"
#undef real
#undef edges_miss
#define real float
#define edges_miss edges_miss_f
#include "scene/edges_miss_impl.h"
#undef real
#undef edges_miss

static uint64_t rng = 0x9e3779b97f4a7c15ULL;
static uint64_t next_u64(void)
{
    rng ^= rng << 13;
    rng ^= rng >> 7;
    rng ^= rng << 17;
    return rng;
}
static double uniform(void) /* [0, 1) */
{
    return (double)(next_u64() >> 11) * 0x1p-53;
}

/* A point: on the grid {-2..2} / 2 (mode 0), or random in [-1, 1) times scale (modes 1, 2). */
static void point(double x[3], int mode, double scale)
{
    for (int r = 0; r < 3; ++r)
        x[r] = mode == 0 ? (double)((int)(next_u64() % 5) - 2) * 0.5 : (2 * uniform() - 1) * scale;
}

/* Triangle x with repeat pattern k: 0 (a, b, c), 1 (a, a, a), 2 (a, b, b), 3 (a, a, b), 4 (a, b, a).
 * share: the first vertex copied from other (when not NULL). */
static void triangle(double x[9], int k, int mode, double scale, const double *other)
{
    double v[3][3];
    for (int i = 0; i < 3; ++i)
        point(v[i], mode, scale);
    if (mode == 2) /* a needle: the third vertex 1e-15 (relative) off the first two's midpoint */
        for (int r = 0; r < 3; ++r)
            v[2][r] = 0.5 * (v[0][r] + v[1][r]) + (r == 0 ? 1e-15 * scale : 0.0);
    if (other != NULL)
        memcpy(v[0], other + 3 * (next_u64() % 3), sizeof v[0]);
    static const int pat[5][3] = {{0, 1, 2}, {0, 0, 0}, {0, 1, 1}, {0, 0, 1}, {0, 1, 0}};
    for (int i = 0; i < 3; ++i)
        memcpy(x + 3 * i, v[pat[k][i]], sizeof v[0]);
}

static int same_d(const ttd_result_d *a, const ttd_result_d *b)
{
    return memcmp(&a->distance, &b->distance, sizeof a->distance) == 0 && memcmp(a->p, b->p, sizeof a->p) == 0 &&
           memcmp(a->q, b->q, sizeof a->q) == 0 && memcmp(a->bary_p, b->bary_p, sizeof a->bary_p) == 0 &&
           memcmp(a->bary_q, b->bary_q, sizeof a->bary_q) == 0 && a->flags == b->flags &&
           a->feature_p == b->feature_p && a->feature_q == b->feature_q && a->iterations == b->iterations;
}

static int same_f(const ttd_result_f *a, const ttd_result_f *b)
{
    return memcmp(&a->distance, &b->distance, sizeof a->distance) == 0 && memcmp(a->p, b->p, sizeof a->p) == 0 &&
           memcmp(a->q, b->q, sizeof a->q) == 0 && memcmp(a->bary_p, b->bary_p, sizeof a->bary_p) == 0 &&
           memcmp(a->bary_q, b->bary_q, sizeof a->bary_q) == 0 && a->flags == b->flags &&
           a->feature_p == b->feature_p && a->feature_q == b->feature_q && a->iterations == b->iterations;
}

static int dups_same_bits(void)
{
    static const double scales[] = {1.0, 1e-7, 3e5, 0x1p-500, 0x1p500, 0x1p-1060, 0x1p1000};
    long n = 0, ties = 0;
    for (int mode = 0; mode < 3; ++mode)
        for (int sc = 0; sc < 7; ++sc)
            for (int ks = 0; ks < 5; ++ks)
                for (int kt = 0; kt < 5; ++kt)
                    for (int rep = 0; rep < 400; ++rep) {
                        const double scale = mode == 0 ? 1.0 : scales[sc];
                        double s[9], t[9];
                        triangle(t, kt, mode, scale, NULL);
                        triangle(s, ks, mode, scale, rep % 4 == 0 ? t : NULL);
                        for (int order = 0; order < 2; ++order) {
                            const double *a = order ? t : s, *b = order ? s : t;
                            ttd_result_d r0, r1;
                            memset(&r0, 0x5a, sizeof r0);
                            memset(&r1, 0x5a, sizeof r1);
                            ttd_exact_pair_d(a, b, &r0);
                            ttd_exact_pair_dups_d(a, b, &r1);
                            ENSURE_MSG(same_d(&r0, &r1), "double: patterns %d %d, mode %d, scale %g, case %d", ks,
                                       kt, mode, scale, rep);
                            /* float: the scales 2^-500, 2^500, 2^-1060 and 2^1000 brought to
                             * 2^-50, 2^50, 2^-140 (subnormal in float) and 2^100 */
                            const double to_f = sc == 3 ? 0x1p450 : sc == 4 ? 0x1p-450 : sc == 5 ? 0x1p920
                                              : sc == 6 ? 0x1p-900 : 1.0;
                            float af[9], bf[9];
                            for (int k = 0; k < 9; ++k) {
                                af[k] = (float)(a[k] * to_f);
                                bf[k] = (float)(b[k] * to_f);
                            }
                            ttd_result_f f0, f1;
                            memset(&f0, 0x5a, sizeof f0);
                            memset(&f1, 0x5a, sizeof f1);
                            ttd_exact_pair_f(af, bf, &f0);
                            ttd_exact_pair_dups_f(af, bf, &f1);
                            ENSURE_MSG(same_f(&f0, &f1), "float: patterns %d %d, mode %d, scale %g, case %d", ks, kt,
                                       mode, scale, rep);
                            ++n;
                            ties += r0.distance == 0;
                        }
                    }
    printf("  %ld pairs (double and float) the same bits, %ld of them touching\n", n, ties);
    return 0;
}

/* An axis-aligned segment as the manifold asks it, (a, b, b): along axis ax, its ends' coordinate
 * on each axis from a few values (so that ends and the other segment's coordinates tie exactly)
 * or, for half the segments, any, times scale, plus offset. */
static void axis_segment(double x[9], int ax, double scale, double offset)
{
    const int grid = next_u64() % 2; /* else any value in [-1, 1) */
    for (int r = 0; r < 3; ++r) {
        const double u = grid ? (double)((int)(next_u64() % 7) - 3) / 3 : 2 * uniform() - 1;
        x[r] = u * scale + offset;
        x[3 + r] = r == ax ? (double)((int)(next_u64() % 7) - 3) / 3 * scale + offset : x[r];
    }
    memcpy(x + 6, x + 3, 3 * sizeof *x);
}

/* Step 0's edge screen (scene/edge_axis_impl.h, edges_axis_apart): where it says no corner, the
 * exact method (exact_pair_dups, as corner_ask asks it) puts a closest point at an end of one
 * segment (corner_ask's test: both first weights strictly inside (0, 1)), in double and float,
 * near the origin and far from it; and the questions it leaves do find corners (so that a screen
 * too wide fails here). */
/* Whether the exact method puts the closest points of edges s and t (each (a, b, b)) inside
 * both, strictly (corner_ask's test: a corner). */
static int corner_d(const double s[9], const double t[9])
{
    ttd_result_d r;
    ttd_exact_pair_dups_d(s, t, &r);
    return r.bary_p[0] > 0 && r.bary_p[0] < 1 && r.bary_q[0] > 0 && r.bary_q[0] < 1;
}

/* The same in float, on s and t rounded (into sf and tf, for the screen to be asked the same). */
static int corner_f(const double s[9], const double t[9], float sf[9], float tf[9])
{
    for (int k = 0; k < 9; ++k) {
        sf[k] = (float)s[k];
        tf[k] = (float)t[k];
    }
    ttd_result_f f;
    ttd_exact_pair_dups_f(sf, tf, &f);
    return f.bary_p[0] > 0 && f.bary_p[0] < 1 && f.bary_q[0] > 0 && f.bary_q[0] < 1;
}

static int edge_axis_screen(void)
{
    static const double scales[] = {1.0, 1e-3, 0x1p-400, 0x1p400};
    static const double offsets[] = {0.0, 0.7, 1e6, -3e3};
    long screened = 0, left = 0, corners = 0;
    for (int sc = 0; sc < 4; ++sc)
        for (int of = 0; of < 4; ++of)
            for (int rep = 0; rep < 20000; ++rep) {
                const double scale = scales[sc], offset = offsets[of] * (sc == 3 ? 0x1p400 : 1.0);
                double s[9], t[9];
                axis_segment(s, (int)(next_u64() % 3), scale, offset);
                axis_segment(t, (int)(next_u64() % 3), scale, offset);
                if (rep % 8 == 0) /* the other's axis coordinate at an end of s */
                    for (int r = 0; r < 3; ++r)
                        if (s[r] != s[3 + r])
                            t[r] = t[3 + r] = t[6 + r] = s[3 * (int)(next_u64() % 2) + r];
                const int corner = corner_d(s, t);
                if (edges_axis_apart_d(s, t)) {
                    ENSURE_MSG(!corner, "double: scale %g, offset %g, case %d", scale, offset, rep);
                    ++screened;
                } else {
                    ++left;
                    corners += corner;
                }
                if (sc < 2 && (of == 0 || of == 1)) { /* float: the same segments */
                    float sf[9], tf[9];
                    const int fc = corner_f(s, t, sf, tf);
                    ENSURE_MSG(!(edges_axis_apart_f(sf, tf) && fc), "float: scale %g, offset %g, case %d", scale,
                               offset, rep);
                }
            }
    printf("  %ld edge questions screened (no corner), %ld left, %ld of those with a corner\n", screened, left,
           corners);
    ENSURE(screened > 0 && corners > 0);
    return 0;
}

/* edges_miss against the exact method itself: wherever it says no corner, the exact method
 * puts no pair of closest points inside both edges. Edge pairs whose lines' closest point on
 * the first edge lies 0.2% to 3% beyond an end (the screen's 1% in the middle of that) or
 * inside, the second edge's inside, at distances up to a few lengths, some near parallel; short
 * edges far from the origin (length 1e-3 at 1e11: about 70 ulps) and scales from 2^-400 to
 * 2^400; double, and float where the coordinates fit. */
static int edges_miss_screen(void)
{
    static const double scales[] = {1.0, 1e-3, 0x1p-400, 0x1p400};
    static const double offsets[] = {0.0, 1.0, 1e6, 1e11};
    long fired = 0, left = 0, corners = 0;
    for (int sc = 0; sc < 4; ++sc)
        for (int of = 0; of < 4; ++of)
            for (int rep = 0; rep < 20000; ++rep) {
                const double len = scales[sc], off = offsets[of] * len; /* in lengths */
                double s[9], t[9], u[3], v[3], n[3];
                for (int r = 0; r < 3; ++r) {
                    u[r] = len * (uniform() - 0.5);
                    v[r] = rep % 4 == 0 ? u[r] + 1e-4 * len * (uniform() - 0.5) : len * (uniform() - 0.5);
                }
                n[0] = u[1] * v[2] - u[2] * v[1];
                n[1] = u[2] * v[0] - u[0] * v[2];
                n[2] = u[0] * v[1] - u[1] * v[0];
                const double nl = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
                if (!(nl > 0))
                    continue;
                const double beyond = 0.002 + 0.028 * uniform();
                const double p = rep % 3 == 0 ? uniform() : rep % 3 == 1 ? 1 + beyond : -beyond;
                const double q = uniform(), h = 3 * len * uniform() / nl;
                for (int r = 0; r < 3; ++r) {
                    const double base = off * (2 * uniform() - 1);
                    s[r] = base;
                    s[3 + r] = s[6 + r] = base + u[r];
                    t[r] = base + p * u[r] + h * n[r] - q * v[r];
                    t[3 + r] = t[6 + r] = t[r] + v[r];
                }
                const int corner = corner_d(s, t);
                if (edges_miss_d(s, t)) {
                    ENSURE_MSG(!corner, "double: length %g, offset %g, case %d", len, off, rep);
                    ++fired;
                } else {
                    ++left;
                    corners += corner;
                }
                if (sc < 2 && of < 3) { /* float: the same edges rounded */
                    float sf[9], tf[9];
                    const int fc = corner_f(s, t, sf, tf);
                    ENSURE_MSG(!(edges_miss_f(sf, tf) && fc), "float: length %g, offset %g, case %d", len, off, rep);
                }
            }
    printf("  %ld edge pairs screened by edges_miss (no corner), %ld left, %ld of those with a corner\n", fired,
           left, corners);
    ENSURE(fired > 0 && corners > 0);
    return 0;
}

int main(int argc, char **argv)
{
    TEST_MAIN_BEGIN(argc, argv);
    RUN_TEST(dups_same_bits);
    RUN_TEST(edge_axis_screen);
    RUN_TEST(edges_miss_screen);
    TEST_MAIN_END();
}

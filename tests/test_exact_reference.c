/* SPDX-License-Identifier: MIT */
/* The exact method (ttd_exact_pair_d / _f, src/scalar/) against the independent __float128
 * reference (tests/reference/) on every generator family (gen/) and on mesh-like pairs (the
 * candidate pairs of a mesh query, tests/mesh_like_pairs.h); then every SIMD row this machine
 * runs, in each of its output paths (distances and points; full results), against the same
 * reference at the same tolerances.
 *
 * Errors are relative to max(reference distance, size of the pair), size = longest edge.
 * Double: |d - d_ref| <= 1e-12 of that. Float: the input is rounded to float first and the
 * reference is computed on the rounded input (what the float routine was given); error at
 * most 1e-5. In both: p and q lie on their triangles (reference point-triangle distance),
 * their barycentric weights are non-negative, sum to 1 and give p and q, and | |p-q| - d | is
 * small. Allowances for rounding p and q themselves grow with the coordinates' magnitude
 * (offset pairs), never the distance's. Prints the worst errors per family as a table and,
 * for every failure, the pair with %.17g coordinates. */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/kernels.h"
#include "isa_rows.h"
#include "mesh_like_pairs.h"
#include "pairs.h"
#include "ref_distance.h"
#include "scalar/scalar.h"
#include "test_macros.h"

enum { PAIRS_PER_FAMILY = 2000, MAX_REPORTS = 3 };

static const double DOUBLE_TOL = 1e-12;
static const double FLOAT_TOL = 1e-5;

static double max_abs9(const double *s, const double *t)
{
    double m = 0;
    for (int k = 0; k < 9; ++k) m = fmax(m, fmax(fabs(s[k]), fabs(t[k])));
    return m;
}

/// Worst errors seen in one family and precision.
typedef struct stats {
    double dist, off, pq, bary;
    int fails, nonfinite;
} stats;

/// Checks one result (already converted to double) against the reference ref of the pair; eps
/// is the unit roundoff of the precision under test, tol the distance tolerance; bp and bq may
/// be NULL (a path without weights).
static void check_with_ref(const char *family, const char *prec, int i, const double *s, const double *t,
                           const ttd_ref_result *refp, double d, const double p[3], const double q[3],
                           const double *bp, const double *bq, uint32_t flags, double eps, double tol, stats *st)
{
    const ttd_ref_result ref = *refp;
    double size = ttd_ref_size(s, t), scale = fmax(size, ref.distance);
    double mag = max_abs9(s, t);
    int finite = isfinite(d);
    for (int k = 0; k < 3; ++k) finite &= isfinite(p[k]) && isfinite(q[k]) && (!bp || (isfinite(bp[k]) && isfinite(bq[k])));
    if (!finite) {
        if (st->nonfinite++ < MAX_REPORTS) {
            fprintf(stderr, "  %s %s pair %d: non-finite output (d = %g)\n", family, prec, i, d);
            print_pair("input", s, t);
        }
        st->fails++;
        return;
    }
    if (scale == 0) { /* both triangles the same point */
        if (d != 0) st->fails++;
        return;
    }
    /* a reference weaker than quad (64-bit long double) is trusted only up to its certificate's
     * gap; in quad the gap is ~1e-30 and changes nothing */
    tol += fmax(0.0, ref.distance - ref.lower_bound) / scale;
    /* rounding p and q to the working precision moves them by about eps * magnitude */
    double round_allow = 8 * eps * (mag + scale) / scale;
    double err = fabs(d - ref.distance) / scale;
    double off = fmax(ttd_ref_point_triangle(p, s), ttd_ref_point_triangle(q, t)) / scale;
    double dx = p[0] - q[0], dy = p[1] - q[1], dz = p[2] - q[2];
    double pq = fabs(sqrt(dx * dx + dy * dy + dz * dz) - d) / scale;
    double bary = 0; /* weights: sign, sum, and agreement with the points */
    for (int k = 0; k < 3 && bp; ++k) {
        bary = fmax(bary, fmax(-bp[k], -bq[k]));
        double pk = bp[0] * s[k] + bp[1] * s[3 + k] + bp[2] * s[6 + k];
        double qk = bq[0] * t[k] + bq[1] * t[3 + k] + bq[2] * t[6 + k];
        bary = fmax(bary, fmax(fabs(pk - p[k]), fabs(qk - q[k])) / scale);
    }
    if (bp)
        bary = fmax(bary, fmax(fabs(bp[0] + bp[1] + bp[2] - 1), fabs(bq[0] + bq[1] + bq[2] - 1)));
    st->dist = fmax(st->dist, err);
    st->off = fmax(st->off, off);
    st->pq = fmax(st->pq, pq);
    st->bary = fmax(st->bary, bary);
    int bad = !(err <= tol) || !(off <= tol + round_allow) || !(pq <= tol + round_allow) ||
              !(bary <= tol + round_allow) || ((flags & TTD_PAIR_INTERSECTING) && d != 0);
    if (bad) {
        if (st->fails < MAX_REPORTS) {
            fprintf(stderr, "  %s %s pair %d: d %.17g ref %.17g (rel err %.3g), off-triangle %.3g, ||p-q|-d| %.3g, "
                            "weights %.3g, flags 0x%x\n",
                    family, prec, i, d, ref.distance, err, off, pq, bary, (unsigned)flags);
            print_pair("input", s, t);
        }
        st->fails++;
    }
}

/// check_with_ref with the reference computed here.
static void check_one(const char *family, const char *prec, int i, const double *s, const double *t, double d,
                      const double p[3], const double q[3], const double bp[3], const double bq[3], uint32_t flags,
                      double eps, double tol, stats *st)
{
    ttd_ref_result ref;
    ttd_ref_distance(s, t, &ref);
    check_with_ref(family, prec, i, s, t, &ref, d, p, q, bp, bq, flags, eps, tol, st);
}

/// The pairs of family f (TTD_GEN_COUNT: the mesh-like pairs).
static int family_pairs(int f, uint64_t seed, size_t n, double *s, double *t)
{
    if (f == TTD_GEN_COUNT)
        return mesh_like_pairs(seed, n, s, t);
    return ttd_gen((ttd_gen_family)f, seed, n, s, t) == n ? 0 : -1;
}

static const char *family_name(int f)
{
    return f == TTD_GEN_COUNT ? "mesh_like" : ttd_gen_name((ttd_gen_family)f);
}

static int exact_vs_reference(void)
{
    double *s = malloc(9 * sizeof(double) * PAIRS_PER_FAMILY), *t = malloc(9 * sizeof(double) * PAIRS_PER_FAMILY);
    ENSURE(s && t);
    int failed = 0;
    printf("exact method vs %s reference, %d pairs per family; errors relative to max(d, size)\n",
           ttd_ref_precision(), PAIRS_PER_FAMILY);
    printf("  %-20s | %9s %9s %9s %9s | %9s %9s %9s %9s | %s\n", "family", "d err", "off tri", "|pq|-d", "weights",
           "f d err", "f off", "f |pq|-d", "f weights", "fails d/f");
    for (int f = 0; f <= TTD_GEN_COUNT; ++f) {
        const char *name = family_name(f);
        ENSURE(family_pairs(f, 2024, PAIRS_PER_FAMILY, s, t) == 0);
        stats sd = {0, 0, 0, 0, 0, 0}, sf = {0, 0, 0, 0, 0, 0};
        for (int i = 0; i < PAIRS_PER_FAMILY; ++i) {
            const double *a = s + 9 * i, *b = t + 9 * i;
            ttd_result_d rd;
            ttd_exact_pair_d(a, b, &rd);
            check_one(name, "double", i, a, b, rd.distance, rd.p, rd.q, rd.bary_p, rd.bary_q, rd.flags,
                      DBL_EPSILON / 2, DOUBLE_TOL, &sd);
            /* float: the reference of the float-rounded input */
            float af[9], bf[9];
            double ar[9], br[9];
            for (int k = 0; k < 9; ++k) {
                af[k] = (float)a[k]; bf[k] = (float)b[k];
                ar[k] = (double)af[k]; br[k] = (double)bf[k];
            }
            ttd_result_f rf;
            ttd_exact_pair_f(af, bf, &rf);
            double p[3], q[3], bp[3], bq[3];
            for (int k = 0; k < 3; ++k) {
                p[k] = (double)rf.p[k]; q[k] = (double)rf.q[k]; bp[k] = (double)rf.bary_p[k]; bq[k] = (double)rf.bary_q[k];
            }
            check_one(name, "float", i, ar, br, (double)rf.distance, p, q, bp, bq, rf.flags, (double)FLT_EPSILON / 2, FLOAT_TOL,
                      &sf);
        }
        printf("  %-20s | %9.2e %9.2e %9.2e %9.2e | %9.2e %9.2e %9.2e %9.2e | %d/%d\n", name, sd.dist, sd.off, sd.pq,
               sd.bary, sf.dist, sf.off, sf.pq, sf.bary, sd.fails, sf.fails);
        fflush(stdout);
        if (sd.fails || sf.fails) failed = 1;
    }
    free(s);
    free(t);
    ENSURE(!failed);
    return 0;
}

enum { ROW_PAIRS = 400 };

/* One row's exact kernel on n pairs in one precision, in its points path (distances and
 * points) or its full path, each pair checked against refs. */
static void row_paths_d(ttd_kernel_d_fn fn, const char *family, const char *what, size_t n, const double *s,
                        const double *t, const ttd_ref_result *refs, stats *st)
{
    static double dist[ROW_PAIRS], pts[6 * ROW_PAIRS];
    static ttd_result_d res[ROW_PAIRS];
    const ttd_params prm = {0, 0, 0};
    const ttd_out_d po = {dist, pts, NULL}, fo = {NULL, NULL, res};
    fn(n, s, t, &prm, (double)INFINITY, &po);
    fn(n, s, t, &prm, (double)INFINITY, &fo);
    for (size_t i = 0; i < n; ++i) {
        check_with_ref(family, what, (int)i, s + 9 * i, t + 9 * i, &refs[i], dist[i], pts + 6 * i, pts + 6 * i + 3,
                       NULL, NULL, 0, DBL_EPSILON / 2, DOUBLE_TOL, st);
        check_with_ref(family, what, (int)i, s + 9 * i, t + 9 * i, &refs[i], res[i].distance, res[i].p, res[i].q,
                       res[i].bary_p, res[i].bary_q, res[i].flags, DBL_EPSILON / 2, DOUBLE_TOL, st);
    }
}

static void row_paths_f(ttd_kernel_f_fn fn, const char *family, const char *what, size_t n, const float *s,
                        const float *t, const double *sr, const double *tr, const ttd_ref_result *refs, stats *st)
{
    static float dist[ROW_PAIRS], pts[6 * ROW_PAIRS];
    static ttd_result_f res[ROW_PAIRS];
    const ttd_params prm = {0, 0, 0};
    const ttd_out_f po = {dist, pts, NULL}, fo = {NULL, NULL, res};
    fn(n, s, t, &prm, INFINITY, &po);
    fn(n, s, t, &prm, INFINITY, &fo);
    for (size_t i = 0; i < n; ++i) {
        double p[3], q[3], bp[3], bq[3], rp[3], rq[3];
        for (int k = 0; k < 3; ++k) {
            p[k] = (double)pts[6 * i + (size_t)k];
            q[k] = (double)pts[6 * i + 3 + (size_t)k];
            rp[k] = (double)res[i].p[k];
            rq[k] = (double)res[i].q[k];
            bp[k] = (double)res[i].bary_p[k];
            bq[k] = (double)res[i].bary_q[k];
        }
        check_with_ref(family, what, (int)i, sr + 9 * i, tr + 9 * i, &refs[i], (double)dist[i], p, q, NULL, NULL, 0,
                       (double)FLT_EPSILON / 2, FLOAT_TOL, st);
        check_with_ref(family, what, (int)i, sr + 9 * i, tr + 9 * i, &refs[i], (double)res[i].distance, rp, rq, bp, bq,
                       res[i].flags, (double)FLT_EPSILON / 2, FLOAT_TOL, st);
    }
}

/* Every row this machine runs, both precisions, both output paths that give points, against
 * the reference on every family and the mesh-like pairs (ROW_PAIRS each; the rows' agreement
 * with the scalar code on many more pairs is test_isa_kernels'). Prints each row's worst
 * distance error per precision. */
static int rows_vs_reference(void)
{
    static double s[9 * ROW_PAIRS], t[9 * ROW_PAIRS], sr[9 * ROW_PAIRS], tr[9 * ROW_PAIRS];
    static float sf[9 * ROW_PAIRS], tf[9 * ROW_PAIRS];
    static ttd_ref_result refd[ROW_PAIRS], reff[ROW_PAIRS];
    int failed = 0, rows = 0;
    stats worst_d[8], worst_f[8];
    memset(worst_d, 0, sizeof worst_d);
    memset(worst_f, 0, sizeof worst_f);
    for (int f = 0; f <= TTD_GEN_COUNT; ++f) {
        ENSURE(family_pairs(f, 77, ROW_PAIRS, s, t) == 0);
        for (size_t k = 0; k < 9 * (size_t)ROW_PAIRS; ++k) {
            sf[k] = (float)s[k];
            tf[k] = (float)t[k];
            sr[k] = (double)sf[k];
            tr[k] = (double)tf[k];
        }
        for (size_t i = 0; i < ROW_PAIRS; ++i) {
            ttd_ref_distance(s + 9 * i, t + 9 * i, &refd[i]);
            ttd_ref_distance(sr + 9 * i, tr + 9 * i, &reff[i]);
        }
        int r = 0;
        for (const isa_row *row = isa_rows; row->name && r < 8; ++row, ++r) {
            const char *why = "";
            if (!cpu_runs(row->name, &why))
                continue;
            char what[48];
            snprintf(what, sizeof what, "%s double", row->name);
            row_paths_d(row->d->fn[TTD_METHOD_EXACT], family_name(f), what, ROW_PAIRS, s, t, refd, &worst_d[r]);
            snprintf(what, sizeof what, "%s float", row->name);
            row_paths_f(row->f->fn[TTD_METHOD_EXACT], family_name(f), what, ROW_PAIRS, sf, tf, sr, tr, reff, &worst_f[r]);
            if (f == 0)
                ++rows;
        }
    }
    int r = 0;
    for (const isa_row *row = isa_rows; row->name && r < 8; ++row, ++r) {
        const char *why = "";
        if (!cpu_runs(row->name, &why))
            continue;
        printf("  %-8s points and full paths: worst d err %.2e (double), %.2e (float); fails %d/%d\n", row->name,
               worst_d[r].dist, worst_f[r].dist, worst_d[r].fails, worst_f[r].fails);
        failed |= worst_d[r].fails || worst_f[r].fails || worst_d[r].nonfinite || worst_f[r].nonfinite;
    }
    ENSURE(rows > 0 || isa_rows[0].name == NULL);
    ENSURE(!failed);
    return 0;
}

/* Each of the 15 feature pairings as the unique closest pair (features family): the exact
 * method names the constructed features and matches the reference. */
static int feature_pairings(void)
{
    enum { N = 15 * 40 };
    static double s[9 * N], t[9 * N];
    ttd_gen(TTD_GEN_FEATURES, 11, N, s, t);
    for (int i = 0; i < N; ++i) {
        unsigned es, et;
        ttd_gen_features_expected((size_t)i, &es, &et);
        ttd_result_d r;
        ttd_exact_pair_d(s + 9 * i, t + 9 * i, &r);
        ttd_ref_result ref;
        ttd_ref_distance(s + 9 * i, t + 9 * i, &ref);
        if (r.feature_p != es || r.feature_q != et ||
            !(fabs(r.distance - ref.distance) <= DOUBLE_TOL * fmax(ref.distance, ttd_ref_size(s + 9 * i, t + 9 * i)))) {
            fprintf(stderr, "  pairing %d: features %u/%u (want %u/%u), d %.17g ref %.17g\n", i % 15, r.feature_p,
                    r.feature_q, es, et, r.distance, ref.distance);
            print_pair("input", s + 9 * i, t + 9 * i);
            return 1;
        }
    }
    return 0;
}

/* The core issue's three examples, with their known answers. */
static int issue_examples(void)
{
    double s1[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0}, t1[9] = {0.2, 0.2, -1, 0.3, 0.2, 1, 0.2, 0.3, 1};
    double s2[9] = {0, 0, 0, 1e-4, 0, 0, 0, 1e-4, 0};
    double t2[9] = {2.5e-5, 2.5e-5, 1e-5, -1e-4, 2.5e-5, 2e-4, 2.5e-5, -1e-4, 2e-4};
    double s3[9] = {0.7, 0.3, 2.1, 1.1, 0.3, 2.1, 0.7, 1.2, 2.1}, t3[9] = {0, 1.5, 1.6, 0, 1.5, 1.1, 0.8, 1.5, 1.6};
    ttd_result_d r;
    ttd_exact_pair_d(s1, t1, &r);
    ENSURE(r.distance == 0.0);
    ENSURE(r.flags & TTD_PAIR_INTERSECTING);
    ENSURE_NEAR(r.p[2], 0.0, 1e-15);
    ENSURE_NEAR(r.q[2], 0.0, 1e-15);
    ttd_exact_pair_d(s2, t2, &r);
    ENSURE_NEAR(r.distance, 1e-5, 1e-17);
    ttd_exact_pair_d(s3, t3, &r);
    ENSURE_NEAR(r.distance, 0.58309518948453, 1e-14);
    ttd_result_f rf;
    float f1[9], g1[9];
    for (int k = 0; k < 9; ++k) { f1[k] = (float)s3[k]; g1[k] = (float)t3[k]; }
    ttd_exact_pair_f(f1, g1, &rf);
    ENSURE_NEAR(rf.distance, 0.58309518948453, 1e-6);
    return 0;
}

int main(int argc, char **argv)
{
    TEST_MAIN_BEGIN(argc, argv);
    RUN_TEST(issue_examples);
    RUN_TEST(feature_pairings);
    RUN_TEST(exact_vs_reference);
    RUN_TEST(rows_vs_reference);
    TEST_MAIN_END();
}

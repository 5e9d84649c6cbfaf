/* SPDX-License-Identifier: MIT */
/* The certified mode (ttd_certified_pair_d/f and the lane kernels of every ISA row the CPU
 * runs) against the independent __float128 reference (tests/reference/) on every generator
 * family (gen/), with the exact method's accuracy targets: double within 1e-12 of
 * max(d, size), float within 1e-5 (reference of the float-rounded input). Prints the fraction
 * of pairs that fell back to the exact method per family. Also: pairs built so that the check
 * must fail (the penalty stopped after one iteration, a penalty weight far too small) are
 * still exact, through the fallback; only clear crossings are certified as contacts, the
 * other contacts and the nearest misses go to the exact method; extreme magnitudes give
 * finite results. */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/defaults.h"
#include "core/kernels.h"
#include "pairs.h"
#include "ref_distance.h"
#include "scalar/scalar.h"
#include "isa_rows.h"
#include "test_macros.h"

enum { PAIRS_PER_FAMILY = 1000, FORCED_PAIRS = 300, MAX_REPORTS = 3 };

static const double DOUBLE_TOL = 1e-12;
static const double FLOAT_TOL = 1e-5;

static ttd_params default_params(void)
{
    ttd_params p = {TTD_DEFAULT_RHO, TTD_DEFAULT_TOL, TTD_DEFAULT_MAX_ITERATIONS};
    return p;
}

static double max_abs9(const double *s, const double *t)
{
    double m = 0;
    for (int k = 0; k < 9; ++k)
        m = fmax(m, fmax(fabs(s[k]), fabs(t[k])));
    return m;
}

typedef struct stats {
    double dist;      /* worst distance error, all pairs */
    double dist_cert; /* worst distance error of the pairs that passed the check */
    double off, pq, bary;
    int fails, fallback, n;
} stats;

/* One result (converted to double) against the reference: distance, points on their
 * triangles, weights, |p - q| = d; a certified pair (no FALLBACK flag) must be apart (not
 * flagged intersecting, d > 0). */
static void check_one(const char *family, const char *prec, int i, const double *s, const double *t, double d,
                      const double p[3], const double q[3], const double bp[3], const double bq[3], uint32_t flags,
                      double eps, double tol, stats *st)
{
    ttd_ref_result ref;
    ttd_ref_distance(s, t, &ref);
    const double size = ttd_ref_size(s, t), scale = fmax(size, ref.distance), mag = max_abs9(s, t);
    const int fell = (flags & TTD_PAIR_FALLBACK) != 0;
    st->n++;
    st->fallback += fell;
    int finite = isfinite(d);
    for (int k = 0; k < 3; ++k)
        finite &= isfinite(p[k]) && isfinite(q[k]) && isfinite(bp[k]) && isfinite(bq[k]);
    if (!finite || scale == 0) {
        if (!finite || d != 0) {
            if (st->fails++ < MAX_REPORTS) {
                fprintf(stderr, "  %s %s pair %d: d = %g (finite %d, scale %g)\n", family, prec, i, d, finite, scale);
                print_pair("input", s, t);
            }
        }
        return;
    }
    tol += fmax(0.0, ref.distance - ref.lower_bound) / scale;
    const double round_allow = 8 * eps * (mag + scale) / scale;
    const double err = fabs(d - ref.distance) / scale;
    const double off = fmax(ttd_ref_point_triangle(p, s), ttd_ref_point_triangle(q, t)) / scale;
    const double dx = p[0] - q[0], dy = p[1] - q[1], dz = p[2] - q[2];
    const double pq = fabs(sqrt(dx * dx + dy * dy + dz * dz) - d) / scale;
    double bary = 0;
    for (int k = 0; k < 3; ++k) {
        bary = fmax(bary, fmax(-bp[k], -bq[k]));
        const double pk = bp[0] * s[k] + bp[1] * s[3 + k] + bp[2] * s[6 + k];
        const double qk = bq[0] * t[k] + bq[1] * t[3 + k] + bq[2] * t[6 + k];
        bary = fmax(bary, fmax(fabs(pk - p[k]), fabs(qk - q[k])) / scale);
    }
    bary = fmax(bary, fmax(fabs(bp[0] + bp[1] + bp[2] - 1), fabs(bq[0] + bq[1] + bq[2] - 1)));
    st->dist = fmax(st->dist, err);
    if (!fell)
        st->dist_cert = fmax(st->dist_cert, err);
    st->off = fmax(st->off, off);
    st->pq = fmax(st->pq, pq);
    st->bary = fmax(st->bary, bary);
    const int bad = !(err <= tol) || !(off <= tol + round_allow) || !(pq <= tol + round_allow) ||
                    !(bary <= tol + round_allow) || ((flags & TTD_PAIR_INTERSECTING) && d != 0) ||
                    (!fell && !(flags & TTD_PAIR_INTERSECTING) && !(d > 0));
    if (bad) {
        if (st->fails < MAX_REPORTS) {
            fprintf(stderr,
                    "  %s %s pair %d: d %.17g ref %.17g (rel err %.3g), off-triangle %.3g, ||p-q|-d| %.3g, "
                    "weights %.3g, flags 0x%x\n",
                    family, prec, i, d, ref.distance, err, off, pq, bary, (unsigned)flags);
            print_pair("input", s, t);
        }
        st->fails++;
    }
}

static void round_pair(const double *a, const double *b, float af[9], float bf[9], double ar[9], double br[9])
{
    for (int k = 0; k < 9; ++k) {
        af[k] = (float)a[k];
        bf[k] = (float)b[k];
        ar[k] = (double)af[k];
        br[k] = (double)bf[k];
    }
}

/* Both precisions of the scalar certified code on every family, with the given parameters.
 * n pairs per family; prints one table row per family and returns the number of failing pairs. */
static int scalar_families(const ttd_params *prm, const char *title, int n)
{
    double *s = malloc(9 * sizeof(double) * (size_t)n), *t = malloc(9 * sizeof(double) * (size_t)n);
    if (!s || !t)
        return 1;
    int failed = 0;
    printf("certified (%s) vs %s reference, %d pairs per family; errors relative to max(d, size)\n", title,
           ttd_ref_precision(), n);
    printf("  %-20s | %9s %9s %9s %9s | %9s %9s %9s %9s | %s\n", "family", "d err", "certified", "off tri",
           "fallback", "f d err", "f cert.", "f off", "f fallbk", "fails d/f");
    for (int f = 0; f < TTD_GEN_COUNT; ++f) {
        const char *name = ttd_gen_name((ttd_gen_family)f);
        ttd_gen((ttd_gen_family)f, 2025, (size_t)n, s, t);
        stats sd, sf;
        memset(&sd, 0, sizeof sd);
        memset(&sf, 0, sizeof sf);
        for (int i = 0; i < n; ++i) {
            const double *a = s + 9 * i, *b = t + 9 * i;
            ttd_result_d rd;
            ttd_certified_pair_d(a, b, prm, &rd);
            check_one(name, "double", i, a, b, rd.distance, rd.p, rd.q, rd.bary_p, rd.bary_q, rd.flags,
                      DBL_EPSILON / 2, DOUBLE_TOL, &sd);
            float af[9], bf[9];
            double ar[9], br[9];
            round_pair(a, b, af, bf, ar, br);
            ttd_result_f rf;
            ttd_certified_pair_f(af, bf, prm, &rf);
            double p[3], q[3], bp[3], bq[3];
            for (int k = 0; k < 3; ++k) {
                p[k] = (double)rf.p[k];
                q[k] = (double)rf.q[k];
                bp[k] = (double)rf.bary_p[k];
                bq[k] = (double)rf.bary_q[k];
            }
            check_one(name, "float", i, ar, br, (double)rf.distance, p, q, bp, bq, rf.flags,
                      (double)FLT_EPSILON / 2, FLOAT_TOL, &sf);
        }
        printf("  %-20s | %9.2e %9.2e %9.2e %8.2f%% | %9.2e %9.2e %9.2e %8.2f%% | %d/%d\n", name, sd.dist,
               sd.dist_cert, sd.off, 100.0 * sd.fallback / sd.n, sf.dist, sf.dist_cert, sf.off,
               100.0 * sf.fallback / sf.n, sd.fails, sf.fails);
        fflush(stdout);
        failed += sd.fails + sf.fails;
    }
    free(s);
    free(t);
    return failed;
}

static int certified_vs_reference(void)
{
    const ttd_params prm = default_params();
    ENSURE(scalar_families(&prm, "defaults", PAIRS_PER_FAMILY) == 0);
    return 0;
}

/* The error bound of a certified (not fallen back) pair follows from the check's gap
 * (core/certified_tol.h): GAP plus ~18 double eps of the frame, whose unit is at most twice
 * the extent, which is at most 3 max(d, size). On nearly parallel edges and faces the objective is flat along the pair of
 * features, where a check that trusted the solve's stationarity let 4e-13 through (pair 3347
 * of near_parallel_faces, seed 7). */
static int certified_error_bound(void)
{
    enum { N = 4000 };
    const ttd_params prm = default_params();
    /* 6 (GAP + 32 eps of double): the frame's unit is at most twice the extent, the extent at
     * most 3 max(d, size), the check runs in double for both precisions; float adds the
     * rounding of the returned distance */
    const double bound_d = 6.0 * (0x1p-43 + 32 * DBL_EPSILON);
    const double bound_f = 6.0 * (0x1p-20 + 32 * DBL_EPSILON) + (double)FLT_EPSILON;
    double *s = malloc(9 * sizeof(double) * N), *t = malloc(9 * sizeof(double) * N);
    ENSURE(s && t);
    const ttd_gen_family fams[] = {TTD_GEN_NEAR_PARALLEL_FACES, TTD_GEN_NEAR_PARALLEL_EDGES};
    for (int f = 0; f < 2; ++f) {
        ttd_gen(fams[f], 7, N, s, t);
        double worst_d = 0, worst_f = 0;
        for (int i = 0; i < N; ++i) {
            const double *a = s + 9 * i, *b = t + 9 * i;
            ttd_result_d r;
            ttd_certified_pair_d(a, b, &prm, &r);
            if (!(r.flags & TTD_PAIR_FALLBACK)) {
                ttd_ref_result ref;
                ttd_ref_distance(a, b, &ref);
                const double e = fabs(r.distance - ref.distance) / fmax(ref.distance, ttd_ref_size(a, b));
                worst_d = fmax(worst_d, e);
                ENSURE_MSG(e <= bound_d, "%s double pair %d: error %.3g > %.3g", ttd_gen_name(fams[f]), i, e, bound_d);
            }
            float af[9], bf[9];
            double ar[9], br[9];
            round_pair(a, b, af, bf, ar, br);
            ttd_result_f rf;
            ttd_certified_pair_f(af, bf, &prm, &rf);
            if (!(rf.flags & TTD_PAIR_FALLBACK)) {
                ttd_ref_result ref;
                ttd_ref_distance(ar, br, &ref);
                const double e = fabs((double)rf.distance - ref.distance) / fmax(ref.distance, ttd_ref_size(ar, br));
                worst_f = fmax(worst_f, e);
                ENSURE_MSG(e <= bound_f, "%s float pair %d: error %.3g > %.3g", ttd_gen_name(fams[f]), i, e, bound_f);
            }
        }
        printf("  %s: worst certified error %.2e double (bound %.2e), %.2e float (bound %.2e)\n",
               ttd_gen_name(fams[f]), worst_d, bound_d, worst_f, bound_f);
    }
    free(s);
    free(t);
    return 0;
}

/* The penalty stopped after one Newton step: its active set is mostly wrong, so the check
 * must fail on most pairs, and every answer must still be exact (through the fallback). */
static int forced_fallback_one_iteration(void)
{
    ttd_params prm = default_params();
    prm.max_iterations = 1;
    ENSURE(scalar_families(&prm, "max_iterations = 1", FORCED_PAIRS) == 0);
    double s[9 * 400], t[9 * 400];
    ttd_gen(TTD_GEN_RANDOM, 3, 400, s, t);
    int fell = 0;
    for (int i = 0; i < 400; ++i) {
        ttd_result_d r;
        ttd_certified_pair_d(s + 9 * i, t + 9 * i, &prm, &r);
        fell += (r.flags & TTD_PAIR_FALLBACK) != 0;
        ENSURE(r.iterations == 1);
    }
    printf("  random, max_iterations = 1: %d of 400 fell back\n", fell);
    ENSURE(fell > 200);
    return 0;
}

/* A penalty weight far too small (rho 10, tol 1e-3): the penalty's answers are off by
 * ~1e-2, the check must catch every one that its exact solve does not repair. */
static int forced_fallback_weak_penalty(void)
{
    ttd_params prm = {10.0, 1e-3, 99};
    ENSURE(scalar_families(&prm, "rho 10, tol 1e-3", FORCED_PAIRS) == 0);
    return 0;
}

/* Contacts: a clear crossing is certified (distance 0, flagged, no fallback); touching, a
 * crossing near the other triangle's boundary and near misses closer than the check can
 * resolve go to the exact method. */
static int contacts(void)
{
    const ttd_params prm = default_params();
    const double S0[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    ttd_result_d r;
    /* the piercing pair: edge DE crosses S at (0.25, 0.2, 0), clearly inside */
    const double pierce[9] = {0.2, 0.2, -1, 0.3, 0.2, 1, 0.2, 0.3, 1};
    ttd_certified_pair_d(S0, pierce, &prm, &r);
    ENSURE(r.distance == 0.0 && (r.flags & TTD_PAIR_INTERSECTING) && !(r.flags & TTD_PAIR_FALLBACK));
    ENSURE_NEAR(r.p[0], 0.25, 1e-15);
    ENSURE_NEAR(r.p[1], 0.2, 1e-15);
    ENSURE_NEAR(r.q[2], 0.0, 1e-15);
    ttd_result_f rf;
    float sf[9], tf[9];
    for (int k = 0; k < 9; ++k) {
        sf[k] = (float)S0[k];
        tf[k] = (float)pierce[k];
    }
    ttd_certified_pair_f(sf, tf, &prm, &rf);
    ENSURE(rf.distance == 0.0f && (rf.flags & TTD_PAIR_INTERSECTING) && !(rf.flags & TTD_PAIR_FALLBACK));
    /* vertex D exactly on S's face, the rest above: touching, for the exact method */
    const double touch[9] = {0.2, 0.2, 0, 0.9, 0.3, 0.7, 0.3, 0.8, 0.6};
    ttd_certified_pair_d(S0, touch, &prm, &r);
    ENSURE(r.distance == 0.0 && (r.flags & TTD_PAIR_INTERSECTING) && (r.flags & TTD_PAIR_FALLBACK));
    /* an edge crossing S 1e-9 inside its edge AB: not clear, for the exact method */
    const double graze[9] = {0.5, 1e-9, -1, 0.5, 1e-9, 1, 0.5, -1, 0.5};
    ttd_certified_pair_d(S0, graze, &prm, &r);
    ENSURE(r.distance == 0.0 && (r.flags & TTD_PAIR_INTERSECTING) && (r.flags & TTD_PAIR_FALLBACK));
    /* near misses above the face: 1e-14 (below TOUCH: exact method) and 1e-8 (either way,
     * but right and not flagged) */
    const double miss14[9] = {0.2, 0.2, 1e-14, 0.9, 0.3, 0.7, 0.3, 0.8, 0.6};
    ttd_certified_pair_d(S0, miss14, &prm, &r);
    ENSURE((r.flags & TTD_PAIR_FALLBACK) && !(r.flags & TTD_PAIR_INTERSECTING));
    ENSURE_NEAR(r.distance, 1e-14, 1e-16);
    const double miss8[9] = {0.2, 0.2, 1e-8, 0.9, 0.3, 0.7, 0.3, 0.8, 0.6};
    ttd_certified_pair_d(S0, miss8, &prm, &r);
    ENSURE(!(r.flags & TTD_PAIR_INTERSECTING));
    ENSURE_NEAR(r.distance, 1e-8, 1e-16);
    /* the intersecting family: every pair 0 and flagged, by either path */
    double s[9 * 300], t[9 * 300];
    ttd_gen(TTD_GEN_INTERSECTING, 9, 300, s, t);
    int certified = 0;
    for (int i = 0; i < 300; ++i) {
        ttd_certified_pair_d(s + 9 * i, t + 9 * i, &prm, &r);
        ENSURE_MSG((r.flags & TTD_PAIR_INTERSECTING) && r.distance == 0.0, "intersecting pair %d: d %g flags 0x%x", i,
                   r.distance, (unsigned)r.flags);
        certified += !(r.flags & TTD_PAIR_FALLBACK);
    }
    printf("  intersecting family: %d of 300 certified as clear crossings\n", certified);
    /* the paper's pair: vertex D over S's face at 0.5, certified */
    const double pt[9] = {0.3, 0.3, 0.5, 1, 0.5, 1.2, 0.4, 1.1, 0.9};
    ttd_certified_pair_d(S0, pt, &prm, &r);
    ENSURE(!(r.flags & TTD_PAIR_FALLBACK));
    ENSURE_NEAR(r.distance, 0.5, 1e-16);
    ENSURE(r.feature_p == 7 && r.feature_q == 1);
    return 0;
}

/* Extreme magnitudes: finite outputs, and the answer scales exactly with a power of two. */
static int extreme_magnitudes(void)
{
    const ttd_params prm = default_params();
    double s[9 * 200], t[9 * 200];
    ttd_gen(TTD_GEN_RANDOM, 5, 200, s, t);
    const int exps[] = {-1070, -1000, -300, 300, 1000, 1020};
    for (int e = 0; e < (int)(sizeof exps / sizeof exps[0]); ++e)
        for (int i = 0; i < 200; ++i) {
            double a[9], b[9];
            for (int k = 0; k < 9; ++k) {
                a[k] = ldexp(s[9 * i + k], exps[e]);
                b[k] = ldexp(t[9 * i + k], exps[e]);
            }
            ttd_result_d r0, r;
            ttd_certified_pair_d(s + 9 * i, t + 9 * i, &prm, &r0);
            ttd_certified_pair_d(a, b, &prm, &r);
            ENSURE(isfinite(r.distance));
            for (int k = 0; k < 3; ++k)
                ENSURE(isfinite(r.p[k]) && isfinite(r.q[k]));
            if (exps[e] > -1000) /* above the subnormal range the scaling is exact */
                ENSURE_MSG(fabs(r.distance - ldexp(r0.distance, exps[e])) <= 1e-12 * ldexp(1.0, exps[e]),
                           "2^%d pair %d: %g vs %g", exps[e], i, r.distance, ldexp(r0.distance, exps[e]));
            float af[9], bf[9];
            for (int k = 0; k < 9; ++k) {
                af[k] = (float)ldexp(s[9 * i + k], exps[e] / 8);
                bf[k] = (float)ldexp(t[9 * i + k], exps[e] / 8);
            }
            ttd_result_f rf;
            ttd_certified_pair_f(af, bf, &prm, &rf);
            ENSURE(isfinite(rf.distance));
        }
    return 0;
}

/* ---------------------------------------------------------------------------------------- */
/* Every ISA row the CPU runs against the scalar certified code on the generator families.   */



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

/* Each row's certified kernels (both precisions, blocks of TTD_BLOCK_PAIRS, also with
 * max_iterations = 1 so that most lanes take the fallback path) against the scalar code:
 * distance within 8 eps of the pair's magnitude, flags and iterations equal; counts the
 * bit-identical results. */
static int rows_vs_scalar(void)
{
    enum { N = 600 };
    double *s = malloc(9 * sizeof(double) * N), *t = malloc(9 * sizeof(double) * N);
    float *sf = malloc(9 * sizeof(float) * N), *tf = malloc(9 * sizeof(float) * N);
    ttd_result_d *rd = malloc(N * sizeof *rd);
    ttd_result_f *rf = malloc(N * sizeof *rf);
    double *dd = malloc(N * sizeof *dd);
    float *df = malloc(N * sizeof *df);
    ENSURE(s && t && sf && tf && rd && rf && dd && df);
    int checked = 0;
    for (const isa_row *r = isa_rows; r->name; ++r) {
        const char *why = "";
        if (!cpu_runs(r->name, &why)) {
            printf("  skip %s: %s\n", r->name, why);
            continue;
        }
        ENSURE(r->d->fn[TTD_METHOD_CERTIFIED] != NULL && r->f->fn[TTD_METHOD_CERTIFIED] != NULL);
        for (int pass = 0; pass < 2; ++pass) {
            ttd_params prm = default_params();
            if (pass == 1)
                prm.max_iterations = 1;
            size_t total = 0, ident_d = 0, ident_f = 0, fb_d = 0, fb_f = 0;
            for (int f = 0; f < TTD_GEN_COUNT; ++f) {
                ttd_gen((ttd_gen_family)f, 31, N, s, t);
                for (int k = 0; k < 9 * N; ++k) {
                    sf[k] = (float)s[k];
                    tf[k] = (float)t[k];
                }
                for (size_t i0 = 0; i0 < N; i0 += TTD_BLOCK_PAIRS) {
                    const size_t m = N - i0 < TTD_BLOCK_PAIRS ? N - i0 : TTD_BLOCK_PAIRS;
                    run_kernel_d(r->d->fn[TTD_METHOD_CERTIFIED], m, s + 9 * i0, t + 9 * i0, &prm, dd + i0, rd + i0);
                    run_kernel_f(r->f->fn[TTD_METHOD_CERTIFIED], m, sf + 9 * i0, tf + 9 * i0, &prm, df + i0, rf + i0);
                }
                for (int i = 0; i < N; ++i) {
                    ttd_result_d wd;
                    ttd_result_f wf;
                    ttd_certified_pair_d(s + 9 * i, t + 9 * i, &prm, &wd);
                    ttd_certified_pair_f(sf + 9 * i, tf + 9 * i, &prm, &wf);
                    const double magd = max_abs9(s + 9 * i, t + 9 * i);
                    double magf = 0;
                    for (int k = 0; k < 9; ++k)
                        magf = fmax(magf, fmax(fabs((double)sf[9 * i + k]), fabs((double)tf[9 * i + k])));
                    ENSURE_MSG(fabs(rd[i].distance - wd.distance) <= 8 * DBL_EPSILON * magd && rd[i].flags == wd.flags &&
                                   rd[i].iterations == wd.iterations && dd[i] == rd[i].distance,
                               "%s double %s pair %d: %.17g vs %.17g, flags %x vs %x", r->name,
                               ttd_gen_name((ttd_gen_family)f), i, rd[i].distance, wd.distance, rd[i].flags, wd.flags);
                    ENSURE_MSG(fabs((double)rf[i].distance - (double)wf.distance) <= 8 * (double)FLT_EPSILON * magf &&
                                   rf[i].flags == wf.flags && rf[i].iterations == wf.iterations &&
                                   df[i] == rf[i].distance,
                               "%s float %s pair %d: %.9g vs %.9g, flags %x vs %x", r->name,
                               ttd_gen_name((ttd_gen_family)f), i, (double)rf[i].distance, (double)wf.distance,
                               rf[i].flags, wf.flags);
                    ident_d += (size_t)same_d(&rd[i], &wd);
                    ident_f += (size_t)same_f(&rf[i], &wf);
                    fb_d += (rd[i].flags & TTD_PAIR_FALLBACK) != 0;
                    fb_f += (rf[i].flags & TTD_PAIR_FALLBACK) != 0;
                    ++total;
                }
            }
            printf("  %s, max_iterations %d: %zu pairs; bit-identical to scalar: %zu double, %zu float; "
                   "fallback %.1f%% double, %.1f%% float\n",
                   r->name, prm.max_iterations, total, ident_d, ident_f, 100.0 * (double)fb_d / (double)total,
                   100.0 * (double)fb_f / (double)total);
            ++checked;
        }
    }
    printf("  %d row x pass combinations checked\n", checked);
    free(s);
    free(t);
    free(sf);
    free(tf);
    free(rd);
    free(rf);
    free(dd);
    free(df);
    return 0;
}

int main(int argc, char **argv)
{
    TEST_MAIN_BEGIN(argc, argv);
    RUN_TEST(contacts);
    RUN_TEST(extreme_magnitudes);
    RUN_TEST(certified_vs_reference);
    RUN_TEST(certified_error_bound);
    RUN_TEST(forced_fallback_one_iteration);
    RUN_TEST(forced_fallback_weak_penalty);
    RUN_TEST(rows_vs_scalar);
    TEST_MAIN_END();
}

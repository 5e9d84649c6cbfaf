/* SPDX-License-Identifier: MIT */
/* Every SIMD row (src/isa/<isa>.c) that is built and that this CPU runs, for every method it
 * implements and both precisions, against the scalar function of the same method
 * (src/scalar/scalar.h) on generated sets; plus the SPMD properties: a pair gives the same
 * bits alone and in any lane among any neighbours (NaN ones too), tails (n = 0, 1, W-1, W+1,
 * a full block), unaligned arrays, and nothing written past n. Rows the CPU cannot run are
 * skipped with a printed reason. The rows are called directly, as the engine calls them. */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/defaults.h"
#include "pairs.h"
#include "core/kernels.h"
#include "scalar/scalar.h"
#include "isa_rows.h"
#include "mesh_like_pairs.h"
#include "test_macros.h"

/* Families 0..6 are generated here; from GEN_LIBRARY_FIRST on they come from gen/pairs.h,
 * for the hard cases of the iterative methods (nearly flat valleys, contacts, slivers); the
 * last, GEN_MESH, is the candidate pairs of a mesh query (tests/mesh_like_pairs.h). */
enum { GEN_EXTREME = 6, GEN_LIBRARY_FIRST = 7, GEN_MESH = 11, GEN_FAMILIES = 12 };
static const ttd_gen_family gen_library_family[GEN_MESH - GEN_LIBRARY_FIRST] = {
    TTD_GEN_NEAR_PARALLEL_EDGES, TTD_GEN_NEAR_PARALLEL_FACES, TTD_GEN_NEAR_TOUCHING, TTD_GEN_SLIVER};

static const char *gen_family_name(int f)
{
    static const char *names[GEN_LIBRARY_FIRST] = {"random", "overlapping", "degenerate", "scaled", "far", "paper",
                                                   "extreme"};
    if (f == GEN_MESH)
        return "mesh_like";
    if (f >= GEN_LIBRARY_FIRST && f < GEN_MESH)
        return ttd_gen_name(gen_library_family[f - GEN_LIBRARY_FIRST]);
    return f >= 0 && f < GEN_LIBRARY_FIRST ? names[f] : "?";
}

/* Pair i of a family; depends only on (family, seed, i).
 *   random       vertices uniform in [0,1)^3, the second triangle shifted by [-0.5,0.5)^3
 *                (the benchmark's set; about 10% intersect)
 *   overlapping  the second triangle is the first moved by up to 1e-3: touching or crossing
 *   degenerate   the first triangle is a segment (C the exact midpoint of A and B, dyadic)
 *                or a point, the second random
 *   scaled       random pairs times 2^k, k in [-20, 20]
 *   far          random pairs 1000 apart
 *   paper        the paper's one pair, distance 0.5
 *   extreme      random pairs scaled by 2^k over the whole exponent range of the precision,
 *                subnormal to near REAL_MAX (applied by fill_d/fill_f after rounding) */
static void gen_pair(int family, uint64_t seed, size_t i, double s[9], double t[9])
{
    ttd_gen_rng st = ttd_gen_rng_make(seed ^ ((uint64_t)family << 56), (uint64_t)i); /* one stream per pair */
    for (int k = 0; k < 9; ++k) {
        s[k] = ttd_gen_rng_uniform(&st);
        t[k] = ttd_gen_rng_uniform(&st);
    }
    double off[3];
    for (int k = 0; k < 3; ++k)
        off[k] = ttd_gen_rng_uniform(&st) - 0.5;
    switch (family) {
    case 1:
        for (int k = 0; k < 9; ++k)
            t[k] = s[(k + 3) % 9] + 1e-3 * (ttd_gen_rng_uniform(&st) - 0.5);
        return;
    case 2:
        for (int k = 0; k < 6; ++k)
            s[k] = floor(s[k] * 64.0) / 64.0;
        for (int k = 0; k < 3; ++k)
            s[6 + k] = (i % 3 == 0) ? s[k] : 0.5 * (s[k] + s[3 + k]);
        if (i % 3 == 0)
            for (int k = 0; k < 3; ++k)
                s[3 + k] = s[k];
        break;
    case 3: {
        const double f = ldexp(1.0, (int)(ttd_gen_rng_u64(&st) % 41) - 20);
        for (int k = 0; k < 9; ++k) {
            s[k] *= f;
            t[k] = (t[k] + off[k % 3]) * f;
        }
        return;
    }
    case 4:
        for (int k = 0; k < 9; ++k)
            t[k] += 1000.0 * (k % 3 == 0);
        return;
    case 5: {
        static const double ps[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
        static const double pt[9] = {0.3, 0.3, 0.5, 1, 0.5, 1.2, 0.4, 1.1, 0.9};
        memcpy(s, ps, sizeof ps);
        memcpy(t, pt, sizeof pt);
        return;
    }
    default:
        break;
    }
    for (int k = 0; k < 9; ++k)
        t[k] += off[k % 3];
}

#define TTD_PRECISION_DOUBLE
#include "precision_open.h"
#include "isa_kernels_impl.h"
#include "precision_close.h"
#define TTD_PRECISION_FLOAT
#include "precision_open.h"
#include "isa_kernels_impl.h"
#include "precision_close.h"



static const char *method_names[TTD_METHOD_COUNT] = {"exact", "penalty", "penalty-ref", "barrier", "certified"};

/* How far a row may be from the scalar code, in units of eps times the pair's size. The
 * kernels repeat the scalar operations in the same order (no FMA where the scalar has none),
 * so they are expected to match to the bit; the margin only allows for a libm sqrt/fma that
 * is not correctly rounded. */
static const double method_ulps[TTD_METHOD_COUNT] = {8, 8, 8, 8, 8};

static ttd_params test_params(void)
{
    ttd_params p = {TTD_DEFAULT_RHO, TTD_DEFAULT_TOL, TTD_DEFAULT_MAX_ITERATIONS};
    return p;
}

static int rows_vs_scalar(void)
{
    const ttd_params prm = test_params();
    int checked = 0;
    for (const isa_row *r = isa_rows; r->name; ++r) {
        const char *why = "";
        if (!cpu_runs(r->name, &why)) {
            printf("  skip %s: %s\n", r->name, why);
            continue;
        }
        for (int m = 0; m < TTD_METHOD_COUNT; ++m) {
            char what[64];
            if (r->d->fn[m]) {
                snprintf(what, sizeof what, "%s %s double", r->name, method_names[m]);
                ENSURE(check_vs_scalar_d(what, r->d->fn[m], m, &prm, 3000, method_ulps[m]) == 0);
                ++checked;
            }
            if (r->f->fn[m]) {
                snprintf(what, sizeof what, "%s %s float", r->name, method_names[m]);
                ENSURE(check_vs_scalar_f(what, r->f->fn[m], m, &prm, 3000, method_ulps[m]) == 0);
                ++checked;
            }
        }
    }
    printf("  %d row x method x precision combinations checked\n", checked);
    return 0;
}

static int rows_lane_independence(void)
{
    const ttd_params prm = test_params();
    ttd_gen_rng st = ttd_gen_rng_make(5, 0);
    for (const isa_row *r = isa_rows; r->name; ++r) {
        const char *why = "";
        if (!cpu_runs(r->name, &why))
            continue;
        for (int m = 0; m < TTD_METHOD_COUNT; ++m) {
            char what[64];
            snprintf(what, sizeof what, "%s %s", r->name, method_names[m]);
            if (r->d->fn[m])
                ENSURE(check_lane_independence_d(what, r->d->fn[m], r->d->lanes, &prm, &st) == 0);
            if (r->f->fn[m])
                ENSURE(check_lane_independence_f(what, r->f->fn[m], r->f->lanes, &prm, &st) == 0);
        }
    }
    return 0;
}

static int rows_sizes_and_alignment(void)
{
    const ttd_params prm = test_params();
    for (const isa_row *r = isa_rows; r->name; ++r) {
        const char *why = "";
        if (!cpu_runs(r->name, &why))
            continue;
        ENSURE(r->d->lanes >= 1 && TTD_BLOCK_PAIRS % r->d->lanes == 0);
        ENSURE(r->f->lanes >= 1 && TTD_BLOCK_PAIRS % r->f->lanes == 0);
        for (int m = 0; m < TTD_METHOD_COUNT; ++m) {
            char what[64];
            snprintf(what, sizeof what, "%s %s", r->name, method_names[m]);
            if (r->d->fn[m])
                ENSURE(check_sizes_d(what, r->d->fn[m], r->d->lanes, &prm) == 0);
            if (r->f->fn[m])
                ENSURE(check_sizes_f(what, r->f->fn[m], r->f->lanes, &prm) == 0);
        }
    }
    return 0;
}

/* The exact kernel's early-out against the caller's bound (check_bound), on the scalar row and
 * every SIMD row (which must give the scalar row's bits on every bounded call); and that it does
 * rule pairs out: in the "far" family most pairs lie far beyond the bounds tried. */
static int rows_bound(void)
{
    const ttd_params prm = test_params();
    const ttd_kernel_d_fn ref_d = ttd_kernels_scalar_d.fn[TTD_METHOD_EXACT];
    const ttd_kernel_f_fn ref_f = ttd_kernels_scalar_f.fn[TTD_METHOD_EXACT];
    size_t out_d = 0, out_f = 0;
    ENSURE(check_bound_d("scalar exact double", ref_d, NULL, &prm, &out_d) == 0);
    ENSURE(check_bound_f("scalar exact float", ref_f, NULL, &prm, &out_f) == 0);
    printf("  scalar exact: bounded calls agree; \"far\" pairs ruled out by the early-out: %zu double, %zu float\n",
           out_d, out_f);
    ENSURE(out_d > 0 && out_f > 0);
    for (const isa_row *r = isa_rows; r->name; ++r) {
        const char *why = "";
        if (!cpu_runs(r->name, &why))
            continue;
        char what[64];
        snprintf(what, sizeof what, "%s exact double", r->name);
        ENSURE(check_bound_d(what, r->d->fn[TTD_METHOD_EXACT], ref_d, &prm, &out_d) == 0);
        snprintf(what, sizeof what, "%s exact float", r->name);
        ENSURE(check_bound_f(what, r->f->fn[TTD_METHOD_EXACT], ref_f, &prm, &out_f) == 0);
        printf("  %s exact: bounded calls agree, with the scalar row's bits; \"far\" pairs ruled out: %zu double, "
               "%zu float\n",
               r->name, out_d, out_f);
        ENSURE(out_d > 0 && out_f > 0);
    }
    return 0;
}

/* A thin pair i: needles (the third vertex 10^-w of the length off the long edge, w in 3..15,
 * or exactly on it: c = a + t (b - a) rounded) against needles nearly parallel to them (angles
 * 10^-4 .. 10^-14) at gaps 10^-1 .. 10^-15, or crossing: the face frames whose normals take the
 * compensated cross product (kx_dop), where the rows without FMA once rounded differently. */
static void thin_pair(ttd_gen_rng *st, double s[9], double t[9])
{
    double a[3], d[3], side[3];
    for (int k = 0; k < 3; ++k) {
        a[k] = ttd_gen_rng_uniform(st);
        d[k] = ttd_gen_rng_uniform(st) - 0.5;
        side[k] = ttd_gen_rng_uniform(st) - 0.5;
    }
    const double w = ttd_gen_rng_u64(st) % 4 == 0 ? 0 : pow(10, -(double)(3 + ttd_gen_rng_u64(st) % 13));
    const double tilt = pow(10, -(double)(4 + ttd_gen_rng_u64(st) % 11));
    const double gap = ttd_gen_rng_u64(st) % 5 == 0 ? 0 : pow(10, -(double)(1 + ttd_gen_rng_u64(st) % 15));
    const double f = ttd_gen_rng_uniform(st), g = ttd_gen_rng_uniform(st);
    for (int k = 0; k < 3; ++k) {
        s[k] = a[k];
        s[3 + k] = a[k] + d[k];
        s[6 + k] = a[k] + f * d[k] + w * side[k];
        /* the second: the first's long edge tilted, moved along `side` by the gap */
        t[k] = a[k] + 0.3 * d[k] + gap * side[k];
        t[3 + k] = t[k] + d[k] + tilt * side[(k + 1) % 3];
        t[6 + k] = t[k] + g * (t[3 + k] - t[k]) + w * side[(k + 2) % 3];
    }
}

/* The exact method through ttd_batch_d/f on every row this CPU runs, on thin pairs: whole
 * results bit for bit equal to the scalar row's (the promise the mesh queries rest on: rows
 * agree to the bit, so a query's answer does not depend on the instruction set). */
static int rows_bit_identical_on_thin_pairs(void)
{
    const size_t n = 1000000;
    double *s = malloc(9 * n * sizeof *s), *t = malloc(9 * n * sizeof *t);
    float *sf = malloc(9 * n * sizeof *sf), *tf = malloc(9 * n * sizeof *tf);
    ttd_result_d *want = malloc(n * sizeof *want), *got = malloc(n * sizeof *got);
    ttd_result_f *want_f = malloc(n * sizeof *want_f), *got_f = malloc(n * sizeof *got_f);
    ENSURE(s && t && sf && tf && want && got && want_f && got_f);
    ttd_gen_rng st = ttd_gen_rng_make(2026, 16);
    for (size_t i = 0; i < n; ++i)
        thin_pair(&st, s + 9 * i, t + 9 * i);
    for (size_t i = 0; i < 9 * n; ++i) {
        sf[i] = (float)s[i];
        tf[i] = (float)t[i];
    }
    ttd_options opt = ttd_default_options();
    opt.isa = TTD_ISA_SCALAR;
    ENSURE(ttd_batch_d(&opt, n, s, t, NULL, want) == TTD_OK);
    ENSURE(ttd_batch_f(&opt, n, sf, tf, NULL, want_f) == TTD_OK);
    int rows = 0;
    for (int isa = TTD_ISA_SCALAR + 1; isa < TTD_ISA_COUNT; ++isa) {
        if (!ttd_isa_available((ttd_isa)isa)) {
            printf("  %s: not available here\n", ttd_isa_name((ttd_isa)isa));
            continue;
        }
        opt.isa = (ttd_isa)isa;
        ENSURE(ttd_batch_d(&opt, n, s, t, NULL, got) == TTD_OK);
        ENSURE(ttd_batch_f(&opt, n, sf, tf, NULL, got_f) == TTD_OK);
        size_t diff_d = 0, diff_f = 0, first = n;
        for (size_t i = 0; i < n; ++i) {
            const int dd = memcmp(&got[i], &want[i], sizeof *got) != 0;
            diff_d += (size_t)dd;
            diff_f += (size_t)(memcmp(&got_f[i], &want_f[i], sizeof *got_f) != 0);
            if (dd && first == n)
                first = i;
        }
        printf("  %s: %zu thin pairs, results differing from the scalar row's bits: %zu double, %zu float\n",
               ttd_isa_name((ttd_isa)isa), n, diff_d, diff_f);
        ENSURE_MSG(diff_d == 0 && diff_f == 0, "%s: first double difference at pair %zu: %.17g, scalar %.17g",
                   ttd_isa_name((ttd_isa)isa), first, first < n ? got[first].distance : 0.0,
                   first < n ? want[first].distance : 0.0);
        ++rows;
    }
#ifdef TTD_HAVE_CUDA_HOST
    {
        /* the cuda-host row is not in the dispatcher: its kernel is called in blocks */
        const ttd_params prm = test_params();
        double *dist = malloc(n * sizeof *dist);
        float *dist_f = malloc(n * sizeof *dist_f);
        ENSURE(dist && dist_f);
        run_bounded_d(ttd_kernels_cuda_host_d.fn[TTD_METHOD_EXACT], n, s, t, &prm, (double)INFINITY, dist, NULL, got);
        run_bounded_f(ttd_kernels_cuda_host_f.fn[TTD_METHOD_EXACT], n, sf, tf, &prm, INFINITY, dist_f, NULL, got_f);
        size_t diff_d = 0, diff_f = 0;
        for (size_t i = 0; i < n; ++i) {
            diff_d += (size_t)(memcmp(&got[i], &want[i], sizeof *got) != 0 ||
                               memcmp(&dist[i], &want[i].distance, sizeof *dist) != 0);
            diff_f += (size_t)(memcmp(&got_f[i], &want_f[i], sizeof *got_f) != 0 ||
                               memcmp(&dist_f[i], &want_f[i].distance, sizeof *dist_f) != 0);
        }
        printf("  cuda-host: %zu thin pairs, results differing from the scalar row's bits: %zu double, %zu float\n",
               n, diff_d, diff_f);
        ENSURE(diff_d == 0 && diff_f == 0);
        ++rows;
        free(dist);
        free(dist_f);
    }
#endif
    printf("  %d rows besides the scalar one checked\n", rows);
    free(s);
    free(t);
    free(sf);
    free(tf);
    free(want);
    free(got);
    free(want_f);
    free(got_f);
    return 0;
}

/* The exact method on every row, whole results in every output path, against the scalar row's
 * bits on every family (the SPMD promise: the same operations in the same order), the
 * cuda-host row included: that is the CUDA device source (src/simd/lanes_cuda.h,
 * docs/gpu.md) compiled for the host, tested here on machines without a GPU. */
static int rows_exact_bits_on_families(void)
{
    const ttd_params prm = test_params();
    for (const isa_row *r = isa_rows; r->name; ++r) {
        const char *why = "";
        if (!cpu_runs(r->name, &why))
            continue;
        char what[64];
        size_t diff_d = 0, diff_f = 0;
        snprintf(what, sizeof what, "%s exact double", r->name);
        ENSURE(check_bits_d(what, r->d->fn[TTD_METHOD_EXACT], ttd_kernels_scalar_d.fn[TTD_METHOD_EXACT], &prm, 2000,
                            &diff_d) == 0);
        snprintf(what, sizeof what, "%s exact float", r->name);
        ENSURE(check_bits_f(what, r->f->fn[TTD_METHOD_EXACT], ttd_kernels_scalar_f.fn[TTD_METHOD_EXACT], &prm, 2000,
                            &diff_f) == 0);
        printf("  %s exact: %d families x 2000 pairs x 3 output paths, differing from the scalar row's bits: %zu "
               "double, %zu float\n",
               r->name, GEN_FAMILIES, diff_d, diff_f);
        ENSURE(diff_d == 0 && diff_f == 0);
    }
    return 0;
}

/* The mesh queries' node test on every row against the scalar row's, bit for bit
 * (simd/kernel_node.h: a traversal visits the same nodes on every row, and on the GPU). */
static int rows_node_test_bits(void)
{
    for (const isa_row *r = isa_rows; r->name; ++r) {
        const char *why = "";
        if (!cpu_runs(r->name, &why))
            continue;
        size_t diff_d = 0, diff_f = 0;
        ENSURE(check_node_bits_d(r->d->node_test, NULL, ttd_kernels_scalar_d.node_test, 20000, &diff_d) == 0);
        ENSURE(check_node_bits_f(r->f->node_test, NULL, ttd_kernels_scalar_f.node_test, 20000, &diff_f) == 0);
        printf("  %s node test: 20000 nodes x 8 children, differing from the scalar row's bits: %zu double, %zu "
               "float\n",
               r->name, diff_d, diff_f);
        ENSURE(diff_d == 0 && diff_f == 0);
        /* node_within: the same bounds, and the mask the walk takes instead of comparing them */
        ENSURE(check_node_bits_d(NULL, r->d->node_within, ttd_kernels_scalar_d.node_test, 20000, &diff_d) == 0);
        ENSURE(check_node_bits_f(NULL, r->f->node_within, ttd_kernels_scalar_f.node_test, 20000, &diff_f) == 0);
        printf("  %s node within: 20000 nodes x 8 children, bounds or mask differing from the scalar node test's: "
               "%zu double, %zu float\n",
               r->name, diff_d, diff_f);
        ENSURE(diff_d == 0 && diff_f == 0);
    }
    return 0;
}

int main(int argc, char **argv)
{
    TEST_MAIN_BEGIN(argc, argv);
    RUN_TEST(rows_vs_scalar);
    RUN_TEST(rows_bound);
    RUN_TEST(rows_lane_independence);
    RUN_TEST(rows_sizes_and_alignment);
    RUN_TEST(rows_bit_identical_on_thin_pairs);
    RUN_TEST(rows_exact_bits_on_families);
    RUN_TEST(rows_node_test_bits);
    TEST_MAIN_END();
}

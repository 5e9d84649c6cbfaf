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

int main(int argc, char **argv)
{
    TEST_MAIN_BEGIN(argc, argv);
    RUN_TEST(rows_vs_scalar);
    RUN_TEST(rows_bound);
    RUN_TEST(rows_lane_independence);
    RUN_TEST(rows_sizes_and_alignment);
    TEST_MAIN_END();
}

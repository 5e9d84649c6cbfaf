/* SPDX-License-Identifier: MIT */
/* gen/mesh_pairs.h, the broad-phase workload generator, against brute force: every pair of
 * triangles whose boxes come within the margin, in order of the second mesh's triangle and
 * then the first's, for meshes posed near, touching, overlapping and far apart; plus its
 * argument checks and its limit on the number of pairs. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "mesh_pairs.h"
#include "meshes.h"
#include "test_macros.h"

static void box(const ttd_gen_mesh *m, size_t i, double lo[3], double hi[3])
{
    for (int c = 0; c < 3; ++c) {
        lo[c] = (double)INFINITY;
        hi[c] = -(double)INFINITY;
        for (int v = 0; v < 3; ++v) {
            const double x = m->verts[3 * m->tris[3 * i + (size_t)v] + (size_t)c];
            lo[c] = fmin(lo[c], x);
            hi[c] = fmax(hi[c], x);
        }
    }
}

/* The list by brute force: all nt_a x nt_b box tests. */
static uint32_t *brute(const ttd_gen_mesh *a, const ttd_gen_mesh *b, double margin, size_t *n)
{
    uint32_t *out = malloc(2 * a->nt * b->nt * sizeof *out + 1);
    *n = 0;
    if (!out)
        return NULL;
    for (size_t j = 0; j < b->nt; ++j)
        for (size_t i = 0; i < a->nt; ++i) {
            double al[3], ah[3], bl[3], bh[3];
            box(a, i, al, ah);
            box(b, j, bl, bh);
            int hit = 1;
            for (int c = 0; c < 3; ++c)
                hit &= al[c] <= bh[c] + margin && bl[c] - margin <= ah[c];
            if (hit) {
                out[2 * *n] = (uint32_t)i;
                out[2 * *n + 1] = (uint32_t)j;
                ++*n;
            }
        }
    return out;
}

static int same_as_brute(const ttd_gen_mesh *a, const ttd_gen_mesh *b, double margin, size_t *count)
{
    uint32_t *got = NULL, *want;
    size_t ng = 0, nw = 0;
    ENSURE(ttd_gen_mesh_pairs(a, b, margin, (size_t)1 << 30, &got, &ng) == 0);
    want = brute(a, b, margin, &nw);
    ENSURE(want != NULL);
    ENSURE_MSG(ng == nw, "margin %g: %zu pairs, brute force %zu", margin, ng, nw);
    ENSURE(ng == 0 || memcmp(got, want, 2 * ng * sizeof *got) == 0);
    free(got);
    free(want);
    *count = ng;
    return 0;
}

static int against_brute_force(void)
{
    ttd_gen_mesh s = {NULL, 0, NULL, 0}, b = {NULL, 0, NULL, 0};
    ENSURE(ttd_gen_icosphere(2, &s) == 0 && ttd_gen_normalize(&s) == 0);
    static const double gaps[] = {0.05, 0.01, 0.0, -0.05, 2.0};
    static const double margins[] = {0.0, 0.01, 0.05};
    size_t total = 0;
    for (size_t g = 0; g < sizeof gaps / sizeof gaps[0]; ++g) {
        double pose[12];
        ENSURE(ttd_gen_pose_gap(&s, &s, 9, g, NULL, gaps[g], pose) == 0);
        ENSURE(ttd_gen_mesh_transform(&s, pose, &b) == 0);
        for (size_t k = 0; k < sizeof margins / sizeof margins[0]; ++k) {
            size_t n = 0;
            ENSURE(same_as_brute(&s, &b, margins[k], &n) == 0);
            total += n;
            if (gaps[g] > 1)
                ENSURE(n == 0); /* the copies are farther apart than any margin here */
        }
        ttd_gen_mesh_free(&b);
    }
    /* a mesh with itself: every triangle meets its neighbours (shared vertices: gap 0) */
    size_t self = 0;
    ENSURE(same_as_brute(&s, &s, 0.0, &self) == 0);
    ENSURE(self >= s.nt);
    /* different meshes, degenerate triangles included */
    ttd_gen_mesh d = {NULL, 0, NULL, 0}, grid = {NULL, 0, NULL, 0};
    ENSURE(ttd_gen_mesh_degenerate(&d) == 0 && ttd_gen_grid(7, &grid) == 0);
    size_t n = 0;
    ENSURE(same_as_brute(&d, &grid, 0.1, &n) == 0 && n > 0);
    ENSURE(same_as_brute(&grid, &d, 0.0, &n) == 0 && n > 0);
    printf("  %zu pairs over the posed spheres, %zu of the sphere with itself\n", total, self);
    ttd_gen_mesh_free(&s);
    ttd_gen_mesh_free(&d);
    ttd_gen_mesh_free(&grid);
    return 0;
}

static int bad_arguments_and_limit(void)
{
    ttd_gen_mesh s = {NULL, 0, NULL, 0};
    ENSURE(ttd_gen_icosphere(1, &s) == 0);
    uint32_t *pairs = (uint32_t *)&s; /* set to NULL on every failure */
    size_t n = 7;
    ENSURE(ttd_gen_mesh_pairs(NULL, &s, 0.0, 100, &pairs, &n) == -1 && pairs == NULL && n == 0);
    ENSURE(ttd_gen_mesh_pairs(&s, &s, -1.0, 100, &pairs, &n) == -1 && pairs == NULL);
    ENSURE(ttd_gen_mesh_pairs(&s, &s, (double)NAN, 100, &pairs, &n) == -1);
    ENSURE(ttd_gen_mesh_pairs(&s, &s, (double)INFINITY, 100, &pairs, &n) == -1);
    ENSURE(ttd_gen_mesh_pairs(&s, &s, 0.0, 100, NULL, &n) == -1);
    s.tris[4] = (uint32_t)s.nv; /* an index out of range */
    ENSURE(ttd_gen_mesh_pairs(&s, &s, 0.0, 100, &pairs, &n) == -1 && pairs == NULL);
    s.tris[4] = 0;
    s.verts[2] = (double)NAN;
    ENSURE(ttd_gen_mesh_pairs(&s, &s, 0.0, 100, &pairs, &n) == -1);
    ttd_gen_mesh_free(&s);
    ENSURE(ttd_gen_icosphere(1, &s) == 0);
    size_t all = 0;
    ENSURE(ttd_gen_mesh_pairs(&s, &s, 0.0, (size_t)1 << 30, &pairs, &all) == 0 && all > 10);
    free(pairs);
    ENSURE(ttd_gen_mesh_pairs(&s, &s, 0.0, all, &pairs, &n) == 0 && n == all);
    free(pairs);
    ENSURE(ttd_gen_mesh_pairs(&s, &s, 0.0, all - 1, &pairs, &n) == -1 && pairs == NULL && n == 0);
    ttd_gen_mesh_free(&s);
    return 0;
}

int main(int argc, char **argv)
{
    TEST_MAIN_BEGIN(argc, argv);
    RUN_TEST(against_brute_force);
    RUN_TEST(bad_arguments_and_limit);
    TEST_MAIN_END();
}

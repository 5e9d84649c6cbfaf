/* SPDX-License-Identifier: MIT */
/* The GPU's mesh pose queries (src/gpu/gpu_walk_impl.h, docs/gpu.md section 6) without a GPU: the
 * walk one CUDA thread runs, compiled for the host (tests/cuda_host/), on the CPU's own mesh
 * arrays, against the CPU's ttd_mesh_distance and ttd_mesh_collide, pose by pose, in double and
 * float: the distance's bits and flags; the whole record when the pair is the CPU's, and where
 * several pairs are equally near and the walk reports another, that pair's distance (the same
 * bits) and its points (the public batch's bits for it); the collision verdict, with a witness
 * within the margin; poses the CPU refuses refused. Each pose is walked in the walk's own order
 * and in another (the host's stand-in for the warp vote), with the same answers.
 *
 * Meshes: icospheres (1,280 and 20,480 triangles), a torus, a grid of slivers 1e-6 thin, ttd's
 * mesh of degenerate triangles, one triangle; poses far, near, touching (a gap of 0, and a grid
 * against its copy moved by exactly 1/4: every facing pair ties), crossing, random, and refused
 * ones (NaN, inf, a scale, a reflection, beyond the coordinate range). */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "meshes.h"
#include "ttd/ttd.h"
#include "ttd/ttd_gpu.h"
#include "cuda_host/cuda_host.h"
#include "mesh/mesh.h"
#include "test_macros.h"

typedef struct gw_case {
    const char *name;
    const ttd_gen_mesh *a, *b;
} gw_case;

typedef struct gw_stats {
    size_t poses, refused, above, same_pair, tie_pair, hits, same_witness, zero;
    uint64_t pairs_cpu, pairs_walk, nodes_cpu, nodes_walk; /* distance queries' work */
} gw_stats;

#define GW_REAL double
#define GW_SUF d
#include "gpu_walk_check_impl.h"
#undef GW_REAL
#undef GW_SUF
#define GW_REAL float
#define GW_SUF f
#include "gpu_walk_check_impl.h"
#undef GW_REAL
#undef GW_SUF

/* The walk's stack (GW_STACK, 256) holds 1 + 7 (h_a + h_b) items at most. */
static int fits_stack(int ha, int hb)
{
    return 1 + (TTD_NODE_WIDTH - 1) * (ha + hb) <= 256;
}

enum { MESHES = 6 };
static ttd_gen_mesh gm[MESHES];
static const char *gm_name[MESHES] = {"ico3", "ico5", "torus", "slivers", "degenerate", "triangle"};

static int make_meshes(void)
{
    if (gm[0].nt)
        return 0;
    ENSURE(ttd_gen_icosphere(3, &gm[0]) == 0 && ttd_gen_normalize(&gm[0]) == 0);
    ENSURE(ttd_gen_icosphere(5, &gm[1]) == 0 && ttd_gen_normalize(&gm[1]) == 0);
    ENSURE(ttd_gen_torus(0.4, 0.1, 48, 24, &gm[2]) == 0 && ttd_gen_normalize(&gm[2]) == 0);
    ENSURE(ttd_gen_grid(24, &gm[3]) == 0);
    for (size_t v = 0; v < gm[3].nv; ++v) /* slivers: the unit square squashed to 1e-6 in y */
        gm[3].verts[3 * v + 1] *= 1e-6;
    ENSURE(ttd_gen_mesh_degenerate(&gm[4]) == 0);
    ENSURE(ttd_gen_mesh_triangle(&gm[5]) == 0);
    return 0;
}

/* k poses of b next to a: gaps far to crossing, random rotations about a's centre, far ones,
 * and refused ones (the last 6). */
static size_t make_poses(const ttd_gen_mesh *a, const ttd_gen_mesh *b, uint64_t seed, size_t per, double *poses)
{
    static const double gaps[] = {1.0, 0.05, 0.01, 0.002, 0.0, -0.02, -0.05};
    size_t k = 0;
    for (size_t g = 0; g < sizeof gaps / sizeof *gaps; ++g)
        for (size_t i = 0; i < per; ++i)
            if (ttd_gen_pose_gap(a, b, seed + g, i, NULL, gaps[g], poses + 12 * k) == 0)
                ++k;
    for (size_t i = 0; i < per; ++i)
        ttd_gen_pose(seed + 100, i, 0.3, poses + 12 * k++);
    for (size_t i = 0; i < per / 4 + 1; ++i)
        ttd_gen_pose(seed + 200, i, 1e3, poses + 12 * k++);
    /* refused: NaN, inf, scaled by 2, a reflection, past the coordinate range (double and float) */
    double *p = poses + 12 * k;
    for (int r = 0; r < 6; ++r)
        ttd_gen_pose(seed + 300, (uint64_t)r, 0.1, p + 12 * r);
    p[0] = NAN;
    p[12 + 7] = INFINITY;
    for (int j = 0; j < 3; ++j)
        p[24 + j] *= 2, p[24 + 4 + j] *= 2, p[24 + 8 + j] *= 2;
    for (int j = 0; j < 3; ++j)
        p[36 + 4 * j] = -p[36 + 4 * j];
    p[48 + 3] = 0x1p600;
    p[60 + 11] = 0x1p70;
    return k + 6;
}

static int build(const ttd_gen_mesh *g, int single, ttd_mesh **m)
{
    if (!single)
        return ttd_mesh_create_d(NULL, g->verts, g->nv, g->tris, g->nt, m) == TTD_OK ? 0 : 1;
    float *v = malloc(3 * g->nv * sizeof *v);
    ENSURE(v != NULL);
    for (size_t i = 0; i < 3 * g->nv; ++i)
        v[i] = (float)g->verts[i];
    const ttd_status s = ttd_mesh_create_f(NULL, v, g->nv, g->tris, g->nt, m);
    free(v);
    return s == TTD_OK ? 0 : 1;
}

static int run_case(int ia, int ib, size_t per, int single, gw_stats *st)
{
    const gw_case c = {gm_name[ia], &gm[ia], &gm[ib]};
    ttd_mesh *ma = NULL, *mb = NULL;
    ENSURE(build(c.a, single, &ma) == 0 && build(c.b, single, &mb) == 0);
    const int ha = single ? ttd_cuda_host_mesh_height_f(ma) : ttd_cuda_host_mesh_height_d(ma);
    const int hb = single ? ttd_cuda_host_mesh_height_f(mb) : ttd_cuda_host_mesh_height_d(mb);
    ENSURE(fits_stack(ha, hb));
    double *poses = malloc(12 * (10 * per + 8) * sizeof *poses);
    ENSURE(poses != NULL);
    const size_t k = make_poses(c.a, c.b, 1000u * (uint64_t)ia + 37u * (uint64_t)ib, per, poses);
    gw_stats s0 = *st;
    int fail;
    /* upper bounds: none, and one most near poses are under and far ones over; margins 0 and small */
    if (single)
        fail = check_poses_f(&c, ma, mb, k, poses, INFINITY, 0, st) || check_poses_f(&c, ma, mb, k, poses, 0.02f, 0.004f, st);
    else
        fail = check_poses_d(&c, ma, mb, k, poses, INFINITY, 0, st) || check_poses_d(&c, ma, mb, k, poses, 0.02, 0.004, st);
    printf("  %-10s x %-10s %s (heights %d, %d): %zu pose queries, %zu refused, %zu above the bound, %zu at 0, "
           "%zu the CPU's pair, %zu another pair as near; %zu hits (%zu the CPU's witness); distance: node tests "
           "%.2fx the CPU's, pair tests %.2fx\n",
           gm_name[ia], gm_name[ib], single ? "float " : "double", ha, hb, st->poses - s0.poses, st->refused - s0.refused,
           st->above - s0.above, st->zero - s0.zero, st->same_pair - s0.same_pair, st->tie_pair - s0.tie_pair,
           st->hits - s0.hits, st->same_witness - s0.same_witness,
           (double)(st->nodes_walk - s0.nodes_walk) / (double)(st->nodes_cpu - s0.nodes_cpu + (st->nodes_cpu == s0.nodes_cpu)),
           (double)(st->pairs_walk - s0.pairs_walk) / (double)(st->pairs_cpu - s0.pairs_cpu + (st->pairs_cpu == s0.pairs_cpu)));
    free(poses);
    ttd_mesh_destroy(ma);
    ttd_mesh_destroy(mb);
    return fail;
}

/* The walk's constants are the CPU's: the coordinate range and the pose tolerance (a pose just
 * inside and one just outside it must be refused alike). */
static int walk_constants(void)
{
    ENSURE(ttd_mesh_range(8) == 0x1p508 && ttd_mesh_range(4) == 0x1p60);
    ENSURE(make_meshes() == 0);
    ttd_mesh *m = NULL;
    ENSURE(build(&gm[0], 0, &m) == 0);
    ttd_options opt = ttd_default_options();
    opt.threads = 1;
    for (int e = -8; e <= 8; ++e) { /* R = (1 + eps) I: defect about 2 eps around the tolerance */
        const double eps = 0.5e-6 * (1 + e / 16.0);
        double pose[12] = {1 + eps, 0, 0, 0, 0, 1 + eps, 0, 0, 0, 0, 1 + eps, 0.5};
        ttd_mesh_result_d want, got;
        const ttd_status s = ttd_mesh_distance_d(&opt, m, m, 1, pose, INFINITY, 0, &want);
        ttd_cuda_host_mesh_distance_d(m, m, 1, pose, INFINITY, 0, &got);
        ENSURE_MSG((s == TTD_ERR_BAD_POSE) == (got.flags == TTD_GPU_POSE_REFUSED), "eps %g: CPU %d, walk flags %u", eps, s,
                   (unsigned)got.flags);
        ENSURE(s != TTD_OK || memcmp(&got.distance, &want.distance, sizeof got.distance) == 0);
    }
    ttd_mesh_destroy(m);
    return 0;
}

static int walk_double(void)
{
    ENSURE(make_meshes() == 0);
    gw_stats st = {0};
    static const int pairs[][2] = {{0, 0}, {0, 2}, {2, 3}, {3, 2}, {4, 0}, {0, 4}, {1, 2}, {1, 1}, {5, 0}, {0, 5}, {5, 5}, {3, 3}};
    for (size_t p = 0; p < sizeof pairs / sizeof *pairs; ++p)
        ENSURE(run_case(pairs[p][0], pairs[p][1], pairs[p][0] == 1 || pairs[p][1] == 1 ? 3 : 8, 0, &st) == 0);
    printf("  double: %zu pose queries, 0 differing\n", st.poses);
    ENSURE(st.tie_pair > 0 && st.same_pair > 0 && st.above > 0 && st.zero > 0 && st.hits > 0 && st.refused > 0);
    return 0;
}

static int walk_float(void)
{
    ENSURE(make_meshes() == 0);
    gw_stats st = {0};
    static const int pairs[][2] = {{0, 0}, {0, 2}, {2, 3}, {4, 0}, {1, 2}, {5, 5}, {3, 3}};
    for (size_t p = 0; p < sizeof pairs / sizeof *pairs; ++p)
        ENSURE(run_case(pairs[p][0], pairs[p][1], pairs[p][0] == 1 || pairs[p][1] == 1 ? 2 : 5, 1, &st) == 0);
    printf("  float: %zu pose queries, 0 differing\n", st.poses);
    ENSURE(st.same_pair > 0 && st.zero > 0 && st.hits > 0 && st.refused > 0);
    return 0;
}

/* A grid against its copy moved by exactly 1/4 along its normal (and rotated by a quarter turn
 * about it, exactly): every facing pair is at 1/4, the CPU and the walk may report different
 * ones; the distance's bits must agree, and the walk's pair must be at exactly 1/4. */
static int walk_ties(void)
{
    ENSURE(make_meshes() == 0);
    ttd_gen_mesh g = {0};
    ENSURE(ttd_gen_grid(8, &g) == 0);
    const gw_case c = {"grid", &g, &g};
    ttd_mesh *m = NULL;
    ENSURE(build(&g, 0, &m) == 0);
    const double poses[24] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0.25, 0, -1, 0, 1, 1, 0, 0, 0, 0, 0, 1, 0.25};
    gw_stats st = {0};
    ENSURE(check_poses_d(&c, m, m, 2, poses, INFINITY, 0.25, &st) == 0);
    printf("  grid against its copy 1/4 above: %zu poses, %zu the CPU's pair, %zu another at 1/4\n", st.poses,
           st.same_pair, st.tie_pair);
    ENSURE(st.same_pair + st.tie_pair == 2 && st.hits == 2);
    ttd_mesh_destroy(m);
    ttd_gen_mesh_free(&g);
    return 0;
}

int main(int argc, char **argv)
{
    TEST_MAIN_BEGIN(argc, argv);
    RUN_TEST(walk_constants);
    RUN_TEST(walk_ties);
    RUN_TEST(walk_double);
    RUN_TEST(walk_float);
    for (int i = 0; i < MESHES; ++i)
        ttd_gen_mesh_free(&gm[i]);
    TEST_MAIN_END();
}

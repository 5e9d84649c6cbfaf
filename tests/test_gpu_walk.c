/* SPDX-License-Identifier: MIT */
#define _POSIX_C_SOURCE 200809L
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
 * ones (NaN, inf, a scale, a reflection, beyond the coordinate range).
 *
 * The C entries (ttd_gpu_mesh_*): without a usable GPU they say why (the stub: NOT_BUILT), and
 * refuse NULL arguments. With a GPU (built with CUDA, TTD_TEST_CUDA; scripts/test-gpu-device.sh):
 * walk_device runs TTD_GPU_WALK_POSES poses (default 20,000; the device script asks 1,000,000) of
 * a bunny-sized mesh (81,920 triangles, an icosphere with a rough surface) against itself through
 * ttd_gpu_mesh_distance/collide_d/f on device memory, against ttd_mesh_distance/collide on the
 * host's cores, with the checks above, and TTD_GPU_POINTS points (default 100,000; the script asks
 * 10,000,000) through ttd_gpu_points_closest_d/f against ttd_points_closest, whole results; it
 * prints poses/s and points/s of both (not asserted). */
#include <float.h>
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "boxes.h"
#include "meshes.h"
#include "ttd/ttd.h"
#include "ttd/ttd_gpu.h"
#include "cuda_host/cuda_host.h"
#include "mesh/mesh.h"
#include "test_macros.h"
#include "gpu_test_util.h"
#include <time.h>

#ifdef TTD_TEST_CUDA
#include <cuda_runtime.h>
#endif

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

/* g as a mesh in double, or in float (single: its vertices rounded to float). */
static int build(const ttd_gen_mesh *g, int single, ttd_mesh **m)
{
    *m = test_mesh_of(single ? 4 : 8, g->verts, g->nv, g->tris, g->nt);
    return *m != NULL ? 0 : 1;
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
    /* the record sizes python/ttd/cuda.py reads the device's results with */
    ENSURE(sizeof(ttd_mesh_result_d) == 80 && sizeof(ttd_mesh_result_f) == 56 && sizeof(ttd_collision) == 24);
    ENSURE(sizeof(ttd_point_result_d) == 72 && sizeof(ttd_point_result_f) == 44);
    ENSURE(offsetof(ttd_mesh_result_d, distance) == 0 && offsetof(ttd_collision, hit) == 0 &&
           offsetof(ttd_point_result_d, distance) == 0);
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

/* Poses per placement and case: TTD_GPU_WALK_PER (default 2; the counts in docs/gpu.md were run
 * with 4 to 8), so that scripts/test.sh stays short on a loaded 2-core machine. */
static size_t walk_per(size_t def)
{
    const char *e = getenv("TTD_GPU_WALK_PER");
    const size_t per = e ? (size_t)strtoull(e, NULL, 10) : 0;
    return per > 0 ? per : def;
}

static int walk_double(void)
{
    ENSURE(make_meshes() == 0);
    gw_stats st = {0};
    static const int pairs[][2] = {{0, 0}, {0, 2}, {2, 3}, {3, 2}, {4, 0}, {0, 4}, {1, 2}, {5, 0}, {0, 5}, {5, 5}, {3, 3}};
    for (size_t p = 0; p < sizeof pairs / sizeof *pairs; ++p)
        ENSURE(run_case(pairs[p][0], pairs[p][1], pairs[p][0] == 1 || pairs[p][1] == 1 ? 1 : walk_per(2), 0, &st) == 0);
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
        ENSURE(run_case(pairs[p][0], pairs[p][1], pairs[p][0] == 1 || pairs[p][1] == 1 ? 1 : walk_per(1), 1, &st) == 0);
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

/* ---- closest points (src/gpu/gpu_points_impl.h) ------------------------------------------- */

/* n points about mesh g: on its vertices (ties between the triangles that share them), near its
 * surface, in its box, far, and 2 non-finite; seeded. */
static void point_set(const ttd_gen_mesh *g, uint64_t seed, size_t n, double *p)
{
    uint64_t x = seed * 0x9e3779b97f4a7c15ull + 1;
    for (size_t i = 0; i < n; ++i) {
        double r[3];
        for (int c = 0; c < 3; ++c) {
            x ^= x << 13, x ^= x >> 7, x ^= x << 17;
            r[c] = (double)(x >> 11) * 0x1p-53 - 0.5;
        }
        const double *v = g->verts + 3 * ((x >> 20) % g->nv);
        for (int c = 0; c < 3; ++c) {
            switch (i % 5) {
            case 0: p[3 * i + c] = v[c]; break;                /* a vertex */
            case 1: p[3 * i + c] = v[c] + 0.01 * r[c]; break;  /* near */
            case 2: p[3 * i + c] = 1.2 * r[c]; break;          /* in the box */
            case 3: p[3 * i + c] = 1e3 * r[c]; break;          /* far */
            default: p[3 * i + c] = v[c] + 1e-9 * r[c]; break; /* touching */
            }
        }
    }
    p[3 * (n - 1)] = NAN;
    p[3 * (n - 2) + 1] = INFINITY;
}

#define SAME_FIELD(a, b, f) (memcmp(&(a).f, &(b).f, sizeof (a).f) == 0)
#define SAME_POINT(a, b)                                                                                            \
    (SAME_FIELD(a, b, distance) && SAME_FIELD(a, b, point) && SAME_FIELD(a, b, bary) && (a).triangle == (b).triangle && \
     (a).feature == (b).feature && (a).flags == (b).flags)

/* The device's closest-point walk on the host against ttd_points_closest_d/f, whole results (but
 * the counts of tests) bit for bit. */
static int points_closest(void)
{
    ENSURE(make_meshes() == 0);
    const size_t n = 2000;
    double *p = malloc(3 * n * sizeof *p);
    float *pf = malloc(3 * n * sizeof *pf);
    ttd_point_result_d *want = malloc(n * sizeof *want), *got = malloc(n * sizeof *got);
    ttd_point_result_f *want_f = malloc(n * sizeof *want_f), *got_f = malloc(n * sizeof *got_f);
    ENSURE(p && pf && want && got && want_f && got_f);
    ttd_options opt = ttd_default_options();
    opt.threads = 1;
    size_t total = 0, above = 0, degenerate = 0;
    for (int i = 0; i < MESHES; ++i) {
        ttd_mesh *md = NULL, *mf = NULL;
        ENSURE(build(&gm[i], 0, &md) == 0 && build(&gm[i], 1, &mf) == 0);
        point_set(&gm[i], 77u + (uint64_t)i, n, p);
        for (size_t k = 0; k < 3 * n; ++k)
            pf[k] = (float)p[k];
        static const double bounds[] = {INFINITY, 0.05, 0};
        for (int b = 0; b < 3; ++b) {
            const ttd_status sd = ttd_points_closest_d(&opt, md, n, p, NULL, bounds[b], want);
            const ttd_status sf = ttd_points_closest_f(&opt, mf, n, pf, NULL, (float)bounds[b], want_f);
            ENSURE(sd == TTD_ERR_NONFINITE_INPUT && sf == TTD_ERR_NONFINITE_INPUT);
            ENSURE(ttd_cuda_host_closest_d(md, n, p, bounds[b], got) == 0);
            ENSURE(ttd_cuda_host_closest_f(mf, n, pf, (float)bounds[b], got_f) == 0);
            for (size_t k = 0; k < n; ++k) {
                ENSURE_MSG(SAME_POINT(got[k], want[k]), "%s point %zu bound %g: walk %.17g (triangle %u), CPU %.17g (%u)",
                           gm_name[i], k, bounds[b], got[k].distance, got[k].triangle, want[k].distance, want[k].triangle);
                ENSURE_MSG(SAME_POINT(got_f[k], want_f[k]), "%s point %zu bound %g (float): walk %.9g (%u), CPU %.9g (%u)",
                           gm_name[i], k, bounds[b], (double)got_f[k].distance, got_f[k].triangle,
                           (double)want_f[k].distance, want_f[k].triangle);
                above += (want[k].flags & TTD_POINT_ABOVE_BOUND) != 0;
                degenerate += (want[k].flags & TTD_POINT_DEGENERATE) != 0;
            }
            total += 2 * n;
        }
        ttd_mesh_destroy(md);
        ttd_mesh_destroy(mf);
    }
    printf("  %zu closest points (6 meshes, vertices, near, in the box, far, touching, NaN/inf; bounds inf, 0.05, 0; "
           "double and float): 0 differing from ttd_points_closest (%zu above the bound, %zu on degenerate triangles "
           "in double)\n",
           total, above, degenerate);
    ENSURE(above > 0 && degenerate > 0);
    free(p);
    free(pf);
    free(want);
    free(got);
    free(want_f);
    free(got_f);
    return 0;
}

/* The entries without a usable GPU: NOT_BUILT from the stub, NO_DEVICE without a driver or GPU;
 * NULL arguments refused first. */
static int walk_entries_without_device(void)
{
    ttd_gpu_info info;
    const ttd_gpu_status st = ttd_gpu_query(&info);
    ttd_gpu_mesh *g = (ttd_gpu_mesh *)&info; /* must be overwritten */
    ENSURE(make_meshes() == 0);
    ttd_mesh *m = NULL;
    ENSURE(build(&gm[0], 0, &m) == 0);
    const double pose[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
    ttd_mesh_result_d r;
    ttd_collision c;
    ttd_gpu_mesh_free(NULL);
    if (st == TTD_GPU_ERR_NOT_BUILT) {
        ENSURE(ttd_gpu_mesh_upload(m, &g) == TTD_GPU_ERR_NOT_BUILT && g == NULL);
        ENSURE(ttd_gpu_mesh_distance_d(NULL, NULL, 1, pose, INFINITY, &r, NULL) == TTD_GPU_ERR_NOT_BUILT);
        ENSURE(ttd_gpu_mesh_collide_f(NULL, NULL, 1, NULL, 0, &c, NULL) == TTD_GPU_ERR_NOT_BUILT);
        ttd_point_result_d pr;
        ENSURE(ttd_gpu_points_closest_d(NULL, 1, pose, INFINITY, &pr, NULL) == TTD_GPU_ERR_NOT_BUILT);
        ENSURE(ttd_gpu_points_closest_f(NULL, 0, NULL, 0, NULL, NULL) == TTD_GPU_ERR_NOT_BUILT);
    } else {
        ENSURE(ttd_gpu_mesh_upload(m, NULL) == TTD_GPU_ERR_NULL_POINTER);
        ENSURE(ttd_gpu_mesh_upload(NULL, &g) == TTD_GPU_ERR_NULL_POINTER && g == NULL);
        ENSURE(ttd_gpu_mesh_distance_d(NULL, NULL, 1, pose, INFINITY, &r, NULL) == TTD_GPU_ERR_NULL_POINTER);
        ENSURE(ttd_gpu_mesh_collide_d(NULL, NULL, 1, pose, 0, &c, NULL) == TTD_GPU_ERR_NULL_POINTER);
        ENSURE(ttd_gpu_mesh_distance_f(NULL, NULL, 0, NULL, 0, NULL, NULL) == TTD_GPU_ERR_NULL_POINTER);
        ttd_point_result_d pr;
        ENSURE(ttd_gpu_points_closest_d(NULL, 1, pose, INFINITY, &pr, NULL) == TTD_GPU_ERR_NULL_POINTER);
        ENSURE(ttd_gpu_points_closest_f(NULL, 0, NULL, 0, NULL, NULL) == TTD_GPU_ERR_NULL_POINTER);
        if (st != TTD_GPU_OK) {
            ENSURE(ttd_gpu_mesh_upload(m, &g) == TTD_GPU_ERR_NO_DEVICE && g == NULL);
        }
#ifdef TTD_TEST_CUDA
        else { /* with a device: bad arguments on real meshes */
            ttd_gpu_mesh *ga = NULL, *gf = NULL;
            ttd_mesh *mf = NULL;
            ENSURE(build(&gm[0], 1, &mf) == 0);
            ENSURE(ttd_gpu_mesh_upload(m, &ga) == TTD_GPU_OK && ttd_gpu_mesh_upload(mf, &gf) == TTD_GPU_OK);
            double *dp;
            ttd_mesh_result_d *dr;
            ENSURE(cudaMalloc((void **)&dp, sizeof pose) == cudaSuccess && cudaMalloc((void **)&dr, sizeof *dr) == cudaSuccess);
            ENSURE(ttd_gpu_mesh_distance_d(ga, ga, 1, dp, -1, dr, NULL) == TTD_GPU_ERR_BAD_ARGUMENT);
            ENSURE(ttd_gpu_mesh_distance_d(ga, ga, 1, dp, NAN, dr, NULL) == TTD_GPU_ERR_BAD_ARGUMENT);
            ENSURE(ttd_gpu_mesh_distance_d(ga, gf, 1, dp, 1, dr, NULL) == TTD_GPU_ERR_BAD_ARGUMENT);
            ENSURE(ttd_gpu_mesh_distance_d(ga, ga, 1, pose, 1, dr, NULL) == TTD_GPU_ERR_NOT_DEVICE_MEMORY);
            ENSURE(ttd_gpu_mesh_distance_d(ga, ga, 0, dp, 1, dr, NULL) == TTD_GPU_OK);
            /* points: ga was uploaded before any point query (no point data); after one, accepted */
            ttd_point_result_d *dpr;
            ENSURE(cudaMalloc((void **)&dpr, sizeof *dpr) == cudaSuccess);
            ENSURE(ttd_gpu_points_closest_d(ga, 1, dp, INFINITY, dpr, NULL) == TTD_GPU_ERR_BAD_ARGUMENT);
            ttd_point_result_d hr;
            ENSURE(ttd_points_closest_d(NULL, m, 1, pose, NULL, INFINITY, &hr) == TTD_OK);
            ttd_gpu_mesh *gp = NULL;
            ENSURE(ttd_gpu_mesh_upload(m, &gp) == TTD_GPU_OK);
            ENSURE(ttd_gpu_points_closest_d(gp, 1, dp, -1, dpr, NULL) == TTD_GPU_ERR_BAD_ARGUMENT);
            ENSURE(ttd_gpu_points_closest_f(gp, 1, (const float *)dp, 1, (ttd_point_result_f *)dpr, NULL) ==
                   TTD_GPU_ERR_BAD_ARGUMENT);
            ENSURE(ttd_gpu_points_closest_d(gp, 1, pose, INFINITY, dpr, NULL) == TTD_GPU_ERR_NOT_DEVICE_MEMORY);
            ENSURE(ttd_gpu_points_closest_d(gp, 1, dp, INFINITY, dpr, NULL) == TTD_GPU_OK);
            ENSURE(cudaDeviceSynchronize() == cudaSuccess);
            cudaFree(dpr);
            ttd_gpu_mesh_free(gp);
            cudaFree(dp);
            cudaFree(dr);
            ttd_gpu_mesh_free(ga);
            ttd_gpu_mesh_free(gf);
            ttd_mesh_destroy(mf);
        }
#endif
    }
    printf("  %s: %s\n", ttd_gpu_status_string(st), st == TTD_GPU_OK ? info.name : info.message);
    ttd_mesh_destroy(m);
    return 0;
}

#ifdef TTD_TEST_CUDA
/* A bunny-sized mesh: an icosphere of 81,920 triangles, each vertex moved radially by up to 3%
 * (a fixed hash), normalized. */
static int rough_sphere(ttd_gen_mesh *g)
{
    ENSURE(ttd_gen_icosphere(6, g) == 0);
    for (size_t v = 0; v < g->nv; ++v) {
        const double f = 1 + 0.03 * ((double)((v * 2654435761u) % 1000u) / 1000.0 - 0.5);
        for (int k = 0; k < 3; ++k)
            g->verts[3 * v + k] *= f;
    }
    ENSURE(ttd_gen_normalize(g) == 0);
    return 0;
}

/* k poses, in precision `single` or not, through the device and the CPU; checks as check_poses_*
 * (bits of distance and flags, ties through the batch, collide verdicts), and poses/s. */
static int device_run(const gw_case *c, ttd_mesh *ma, size_t k, const double *posesd, int single)
{
    ttd_gpu_mesh *g = NULL;
    ENSURE(ttd_gpu_mesh_upload(ma, &g) == TTD_GPU_OK);
    const size_t rb = single ? sizeof(ttd_mesh_result_f) : sizeof(ttd_mesh_result_d), pb = single ? 4 : 8;
    void *hp = malloc(12 * k * pb), *want = malloc(k * rb), *got = malloc(k * rb);
    ttd_collision *cw = malloc(k * sizeof *cw), *cg = malloc(k * sizeof *cg);
    ENSURE(hp && want && got && cw && cg);
    for (size_t i = 0; i < 12 * k; ++i) {
        if (single)
            ((float *)hp)[i] = (float)posesd[i];
        else
            ((double *)hp)[i] = posesd[i];
    }
    void *dp, *dr, *dc;
    CU(cudaMalloc(&dp, 12 * k * pb));
    CU(cudaMalloc(&dr, k * rb));
    CU(cudaMalloc(&dc, k * sizeof *cg));
    CU(cudaMemcpy(dp, hp, 12 * k * pb, cudaMemcpyHostToDevice));
    cudaEvent_t e0, e1, e2;
    CU(cudaEventCreate(&e0));
    CU(cudaEventCreate(&e1));
    CU(cudaEventCreate(&e2));
    const float ub = INFINITY, mg = 0.002f;
    CU(cudaEventRecord(e0, NULL));
    ENSURE((single ? ttd_gpu_mesh_distance_f(g, g, k, dp, ub, dr, NULL)
                   : ttd_gpu_mesh_distance_d(g, g, k, dp, ub, dr, NULL)) == TTD_GPU_OK);
    CU(cudaEventRecord(e1, NULL));
    ENSURE((single ? ttd_gpu_mesh_collide_f(g, g, k, dp, mg, dc, NULL)
                   : ttd_gpu_mesh_collide_d(g, g, k, dp, mg, dc, NULL)) == TTD_GPU_OK);
    CU(cudaEventRecord(e2, NULL));
    CU(cudaEventSynchronize(e2));
    float msf_d = 0, msf_c = 0;
    CU(cudaEventElapsedTime(&msf_d, e0, e1));
    CU(cudaEventElapsedTime(&msf_c, e1, e2));
    const double ms_d = (double)msf_d, ms_c = (double)msf_c;
    CU(cudaMemcpy(got, dr, k * rb, cudaMemcpyDeviceToHost));
    CU(cudaMemcpy(cg, dc, k * sizeof *cg, cudaMemcpyDeviceToHost));
    ttd_options opt = ttd_default_options(); /* every core */
    const double t0 = seconds();
    ENSURE((single ? ttd_mesh_distance_f(&opt, ma, ma, k, hp, ub, 0, want)
                   : ttd_mesh_distance_d(&opt, ma, ma, k, hp, ub, 0, want)) == TTD_OK);
    const double t1 = seconds();
    ENSURE((single ? ttd_mesh_collide_f(&opt, ma, ma, k, hp, mg, cw) : ttd_mesh_collide_d(&opt, ma, ma, k, hp, mg, cw)) ==
           TTD_OK);
    const double t2 = seconds();
    size_t dist_diff = 0, flag_diff = 0, hit_diff = 0, ties = 0, tie_bad = 0, hits = 0;
    for (size_t i = 0; i < k; ++i) {
        double wd, gd;
        unsigned wf, gf;
        uint32_t wa, wb, ga, gb;
        if (single) {
            const ttd_mesh_result_f *w = (const ttd_mesh_result_f *)want + i, *x = (const ttd_mesh_result_f *)got + i;
            dist_diff += memcmp(&w->distance, &x->distance, sizeof w->distance) != 0;
            wd = w->distance, gd = x->distance, wf = w->flags, gf = x->flags, wa = w->tri_a, wb = w->tri_b, ga = x->tri_a,
            gb = x->tri_b;
        } else {
            const ttd_mesh_result_d *w = (const ttd_mesh_result_d *)want + i, *x = (const ttd_mesh_result_d *)got + i;
            dist_diff += memcmp(&w->distance, &x->distance, sizeof w->distance) != 0;
            wd = w->distance, gd = x->distance, wf = w->flags, gf = x->flags, wa = w->tri_a, wb = w->tri_b, ga = x->tri_a,
            gb = x->tri_b;
        }
        (void)gd;
        flag_diff += wf != gf;
        hit_diff += cw[i].hit != cg[i].hit;
        hits += cg[i].hit != 0;
        if (!(wf & TTD_MESH_ABOVE_BOUND) && (ga != wa || gb != wb)) {
            ++ties;
            if (single) {
                ttd_result_f r;
                ENSURE(pair_result_f(c, (const float *)hp + 12 * i, ga, gb, &r) == TTD_OK);
                tie_bad += r.distance != (float)wd;
            } else {
                ttd_result_d r;
                ENSURE(pair_result_d(c, (const double *)hp + 12 * i, ga, gb, &r) == TTD_OK);
                tie_bad += r.distance != wd;
            }
        }
    }
    printf("  %s, %zu poses: distance %zu differing bits, %zu differing flags (%zu pairs another equally near one, "
           "%zu of those not); collide (margin 0.002) %zu differing of %zu hits\n",
           single ? "float " : "double", k, dist_diff, flag_diff, ties, tie_bad, hit_diff, hits);
    printf("  %s poses/s: distance device %.3g, host (%d threads) %.3g: %.1fx; collide device %.3g, host %.3g: %.1fx\n",
           single ? "float " : "double", (double)k / (ms_d * 1e-3), opt.threads, (double)k / (t1 - t0),
           (t1 - t0) / (ms_d * 1e-3), (double)k / (ms_c * 1e-3), (double)k / (t2 - t1), (t2 - t1) / (ms_c * 1e-3));
    ENSURE(dist_diff == 0 && flag_diff == 0 && hit_diff == 0 && tie_bad == 0);
    cudaFree(dp);
    cudaFree(dr);
    cudaFree(dc);
    cudaEventDestroy(e0);
    cudaEventDestroy(e1);
    cudaEventDestroy(e2);
    free(hp);
    free(want);
    free(got);
    free(cw);
    free(cg);
    ttd_gpu_mesh_free(g);
    return 0;
}

/* n points near and far from g through ttd_gpu_points_closest on device memory against
 * ttd_points_closest on the host's cores: whole results bit for bit, and points/s. */
static int device_points(const ttd_gen_mesh *g, ttd_mesh *m, size_t n, int single)
{
    double *p = malloc(3 * n * sizeof *p);
    ENSURE(p != NULL);
    point_set(g, 99u, n, p);
    p[3 * (n - 1)] = 0.5, p[3 * (n - 2) + 1] = 0.25; /* no NaN here: the CPU call is then TTD_OK */
    const size_t pb = single ? 4 : 8, rb = single ? sizeof(ttd_point_result_f) : sizeof(ttd_point_result_d);
    void *hp = malloc(3 * n * pb), *want = malloc(n * rb), *got = malloc(n * rb);
    ENSURE(hp && want && got);
    for (size_t i = 0; i < 3 * n; ++i) {
        if (single)
            ((float *)hp)[i] = (float)p[i];
        else
            ((double *)hp)[i] = p[i];
    }
    ttd_options opt = ttd_default_options();
    ENSURE((single ? ttd_points_closest_f(&opt, m, 1, hp, NULL, INFINITY, want)
                   : ttd_points_closest_d(&opt, m, 1, hp, NULL, INFINITY, want)) == TTD_OK); /* the point data */
    ttd_gpu_mesh *gm_ = NULL;
    ENSURE(ttd_gpu_mesh_upload(m, &gm_) == TTD_GPU_OK);
    void *dp, *dr;
    CU(cudaMalloc(&dp, 3 * n * pb));
    CU(cudaMalloc(&dr, n * rb));
    CU(cudaMemcpy(dp, hp, 3 * n * pb, cudaMemcpyHostToDevice));
    cudaEvent_t e0, e1;
    CU(cudaEventCreate(&e0));
    CU(cudaEventCreate(&e1));
    CU(cudaEventRecord(e0, NULL));
    ENSURE((single ? ttd_gpu_points_closest_f(gm_, n, dp, INFINITY, dr, NULL)
                   : ttd_gpu_points_closest_d(gm_, n, dp, INFINITY, dr, NULL)) == TTD_GPU_OK);
    CU(cudaEventRecord(e1, NULL));
    CU(cudaEventSynchronize(e1));
    float msf = 0;
    CU(cudaEventElapsedTime(&msf, e0, e1));
    CU(cudaMemcpy(got, dr, n * rb, cudaMemcpyDeviceToHost));
    const double t0 = seconds();
    ENSURE((single ? ttd_points_closest_f(&opt, m, n, hp, NULL, INFINITY, want)
                   : ttd_points_closest_d(&opt, m, n, hp, NULL, INFINITY, want)) == TTD_OK);
    const double t1 = seconds();
    size_t diff = 0;
    for (size_t i = 0; i < n; ++i) {
        if (single) {
            const ttd_point_result_f *a = (const ttd_point_result_f *)got + i, *b = (const ttd_point_result_f *)want + i;
            diff += !SAME_POINT(*a, *b);
        } else {
            const ttd_point_result_d *a = (const ttd_point_result_d *)got + i, *b = (const ttd_point_result_d *)want + i;
            diff += !SAME_POINT(*a, *b);
        }
    }
    const double gps = (double)n / ((double)msf * 1e-3), cps = (double)n / (t1 - t0);
    printf("  %s closest points, %zu points: %zu differing results; points/s device %.3g, host (%d threads) %.3g: "
           "%.1fx\n", single ? "float " : "double", n, diff, gps, opt.threads, cps, gps / cps);
    ENSURE(diff == 0);
    cudaFree(dp);
    cudaFree(dr);
    cudaEventDestroy(e0);
    cudaEventDestroy(e1);
    ttd_gpu_mesh_free(gm_);
    free(p);
    free(hp);
    free(want);
    free(got);
    return 0;
}

static int walk_device(void)
{
    ttd_gpu_info info;
    if (ttd_gpu_query(&info) != TTD_GPU_OK) {
        printf("  skip: no usable GPU (%s)\n", info.message);
        return 0;
    }
    const char *env = getenv("TTD_GPU_WALK_POSES");
    const size_t k = env ? (size_t)strtoull(env, NULL, 10) : 20000;
    ENSURE(k >= 16);
    ttd_gen_mesh g = {0};
    ENSURE(rough_sphere(&g) == 0);
    const gw_case c = {"rough sphere", &g, &g};
    double *poses = malloc(12 * k * sizeof *poses);
    ENSURE(poses != NULL);
    /* a quarter each: near (gap 0.01), touching (0.002), crossing (-0.02), random about the centre */
    static const double gaps[] = {0.01, 0.002, -0.02};
    for (size_t i = 0; i < k; ++i)
        if (i % 4 == 3 || ttd_gen_pose_gap(&g, &g, 4242 + i % 4, i, NULL, gaps[i % 4], poses + 12 * i) != 0)
            ttd_gen_pose(4343, i, 0.5, poses + 12 * i);
    ttd_mesh *md = NULL, *mf = NULL;
    ENSURE(build(&g, 0, &md) == 0 && build(&g, 1, &mf) == 0);
    printf("  %s (%zu triangles) against itself on %s\n", c.name, g.nt, info.name);
    const char *envp = getenv("TTD_GPU_POINTS");
    const size_t np = envp ? (size_t)strtoull(envp, NULL, 10) : 100000;
    ENSURE(np >= 16);
    const int fail = device_run(&c, md, k, poses, 0) || device_run(&c, mf, k, poses, 1) ||
                     device_points(&g, md, np, 0) || device_points(&g, mf, np, 1);
    ttd_mesh_destroy(md);
    ttd_mesh_destroy(mf);
    free(poses);
    ttd_gen_mesh_free(&g);
    return fail;
}
#endif

int main(int argc, char **argv)
{
    TEST_MAIN_BEGIN(argc, argv);
    RUN_TEST(walk_constants);
    RUN_TEST(walk_entries_without_device);
#ifdef TTD_TEST_CUDA
    RUN_TEST(walk_device);
#endif
    RUN_TEST(walk_ties);
    RUN_TEST(points_closest);
    RUN_TEST(walk_double);
    RUN_TEST(walk_float);
    for (int i = 0; i < MESHES; ++i)
        ttd_gen_mesh_free(&gm[i]);
    TEST_MAIN_END();
}

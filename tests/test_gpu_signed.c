/* SPDX-License-Identifier: MIT */
#define _POSIX_C_SOURCE 200809L
/* Signed distances of points on the device (src/gpu/gpu_signed_impl.h; docs/gpu.md, section 6).
 *
 * Without a GPU (CI): the device code compiled for the host (tests/cuda_host/, the cuda-host row)
 * runs point by point on the CPU's point data and is compared with ttd_points_signed_distance_d/f
 * bit for bit (the signed distance's bits, and the whole result but the counts of tests, the
 * inside flag included) on closed meshes (icospheres wound outwards and inwards, a hollow shell
 * whose cavity is outside, a torus, an axis-aligned cube whose grid points send rays through its
 * edges and vertices, the cube at 2^-600 and 2^400), an open mesh whose boundary cancels by
 * coordinates (the cube with its vertices repeated per face) and a mesh of one triangle; points on
 * vertices, near, in the box, far, touching, on a grid, NaN and inf; bounds inf, 0.05 and 0. Since
 * the ray count is the CPU's own source (points/ray_impl.h), the sides are also checked against an
 * independent reference: the winding number as a plain sum of solid angles (mesh/solid.c), for
 * every point farther than 1e-6 from the surface. Meshes the device cannot sign as the CPU does
 * (open with a boundary) are refused; a point whose ray count cannot be made exact is refused
 * alone. With a GPU (TTD_TEST_CUDA; scripts/test-gpu-device.sh): the entries' argument checks on
 * real device meshes, and TTD_GPU_POINTS points (default 100,000) on an 81,920-triangle rough
 * sphere through ttd_gpu_points_signed_distance_d/f against the host's cores, bit for bit, with
 * points/s of both. */
#include <float.h>
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "boxes.h"
#include "meshes.h"
#include "ttd/ttd.h"
#include "ttd/ttd_gpu.h"
#include "cuda_host/cuda_host.h"
#include "mesh/mesh.h"
#include "test_macros.h"
#include "gpu_test_util.h"

#ifdef TTD_TEST_CUDA
#include <cuda_runtime.h>
#endif

#define SAME_FIELD(a, b, f) (memcmp(&(a).f, &(b).f, sizeof (a).f) == 0)
#define SAME_POINT(a, b)                                                                                            \
    (SAME_FIELD(a, b, distance) && SAME_FIELD(a, b, point) && SAME_FIELD(a, b, bary) && (a).triangle == (b).triangle && \
     (a).feature == (b).feature && (a).flags == (b).flags)

/* ---- meshes --------------------------------------------------------------------------------- */

enum { MESHES = 10 };
static ttd_gen_mesh gm[MESHES];
static const char *gm_name[MESHES] = {"ico3",        "ico3 inward", "shell",      "torus",    "cube",
                                      "cube 2^-600", "cube 2^400",  "cube dup",   "triangle", "grid (open)"};
/* the sign mode the device must choose (gpu_sign_mode.h): 2 the ray count, 1 unsigned, 0 refused */
static const int gm_mode[MESHES] = {2, 2, 2, 2, 2, 2, 2, 2, 1, 0};
/* meshes also run in float (the scaled cubes are outside float's range) */
static const int gm_float[MESHES] = {1, 1, 1, 1, 1, 0, 0, 1, 1, 1};
/* the power of two that takes a scaled cube back to the unit one, for the reference (its plain sum of
 * solid angles underflows at 2^-600) */
static const int gm_unscale[MESHES] = {0, 0, 0, 0, 0, 600, -400, 0, 0, 0};

static void reverse(ttd_gen_mesh *g)
{
    for (size_t t = 0; t < g->nt; ++t) {
        const uint32_t s = g->tris[3 * t + 1];
        g->tris[3 * t + 1] = g->tris[3 * t + 2];
        g->tris[3 * t + 2] = s;
    }
}

static void scale(ttd_gen_mesh *g, int e)
{
    for (size_t i = 0; i < 3 * g->nv; ++i)
        g->verts[i] = ldexp(g->verts[i], e);
}

/* two meshes as one (b's indices shifted) */
static int join(const ttd_gen_mesh *a, const ttd_gen_mesh *b, ttd_gen_mesh *out)
{
    out->nv = a->nv + b->nv;
    out->nt = a->nt + b->nt;
    out->verts = malloc(3 * out->nv * sizeof *out->verts);
    out->tris = malloc(3 * out->nt * sizeof *out->tris);
    ENSURE(out->verts && out->tris);
    memcpy(out->verts, a->verts, 3 * a->nv * sizeof *out->verts);
    memcpy(out->verts + 3 * a->nv, b->verts, 3 * b->nv * sizeof *out->verts);
    memcpy(out->tris, a->tris, 3 * a->nt * sizeof *out->tris);
    for (size_t i = 0; i < 3 * b->nt; ++i)
        out->tris[3 * a->nt + i] = b->tris[i] + (uint32_t)a->nv;
    return 0;
}

static int make_meshes(void)
{
    if (gm[0].nt)
        return 0;
    ENSURE(ttd_gen_icosphere(3, &gm[0]) == 0);
    ENSURE(ttd_gen_mesh_copy(&gm[0], &gm[1]) == 0);
    reverse(&gm[1]);
    /* a hollow shell: the unit sphere outwards, one of radius 1/2 inwards (the cavity: w = 0) */
    ttd_gen_mesh outer = {0}, inner = {0};
    ENSURE(ttd_gen_icosphere(2, &outer) == 0 && ttd_gen_icosphere(2, &inner) == 0);
    scale(&inner, -1);
    reverse(&inner);
    ENSURE(join(&outer, &inner, &gm[2]) == 0);
    ttd_gen_mesh_free(&outer);
    ttd_gen_mesh_free(&inner);
    ENSURE(ttd_gen_torus(0.4, 0.1, 48, 24, &gm[3]) == 0);
    ENSURE(ttd_gen_mesh_cube(&gm[4]) == 0);
    ENSURE(ttd_gen_mesh_cube(&gm[5]) == 0);
    scale(&gm[5], -600);
    ENSURE(ttd_gen_mesh_cube(&gm[6]) == 0);
    scale(&gm[6], 400);
    ENSURE(ttd_gen_mesh_duplicate_vertices(&gm[7]) == 0);
    ENSURE(ttd_gen_mesh_triangle(&gm[8]) == 0);
    ENSURE(ttd_gen_grid(8, &gm[9]) == 0);
    return 0;
}

/* g as a mesh in double, or in float (single: its vertices rounded to float). */
static int build(const ttd_gen_mesh *g, int single, ttd_mesh **m)
{
    *m = test_mesh_of(single ? 4 : 8, g->verts, g->nv, g->tris, g->nt);
    return *m != NULL ? 0 : 1;
}

/* ---- points ----------------------------------------------------------------------------------- */

/* n points about mesh g (of size about s, its box [lo, hi]): on a grid of quarters of the box
 * (faces, edges, vertices, and inside points whose rays run through edges), on vertices, near, in
 * the box, far, touching, one with a subnormal coordinate (its ray count cannot be made exact:
 * refused on the device), and NaN and inf; seeded. */
static size_t point_set(const ttd_gen_mesh *g, uint64_t seed, size_t n, double *p, size_t *subnormal)
{
    double lo[3], hi[3];
    ttd_gen_mesh_bounds(g, lo, hi);
    const double s = fmax(hi[0] - lo[0], fmax(hi[1] - lo[1], hi[2] - lo[2]));
    size_t k = 0;
    for (int i = -1; i <= 5 && k < n; ++i)
        for (int j = -1; j <= 5 && k < n; ++j)
            for (int l = -1; l <= 5 && k < n; ++l, ++k) {
                const int q[3] = {i, j, l};
                for (int c = 0; c < 3; ++c)
                    p[3 * k + c] = lo[c] + (hi[c] - lo[c]) * q[c] / 4;
            }
    uint64_t x = seed * 0x9e3779b97f4a7c15ull + 1;
    for (; k < n; ++k) {
        double r[3];
        for (int c = 0; c < 3; ++c) {
            x ^= x << 13, x ^= x >> 7, x ^= x << 17;
            r[c] = (double)(x >> 11) * 0x1p-53 - 0.5;
        }
        const double *v = g->verts + 3 * ((x >> 20) % g->nv);
        for (int c = 0; c < 3; ++c) {
            const double mid = (lo[c] + hi[c]) / 2;
            switch (k % 5) {
            case 0: p[3 * k + c] = v[c]; break;                      /* a vertex */
            case 1: p[3 * k + c] = v[c] + 0.01 * s * r[c]; break;    /* near */
            case 2: p[3 * k + c] = mid + 1.2 * s * r[c]; break;      /* in the box */
            case 3: p[3 * k + c] = mid + 1e3 * s * r[c]; break;      /* far */
            default: p[3 * k + c] = v[c] + 1e-9 * s * r[c]; break;   /* touching */
            }
        }
    }
    /* inside the box's middle, one coordinate subnormal: the ray count reports that it cannot be
     * exact (a coordinate below 2^-1000 after its scale) */
    *subnormal = n - 3;
    for (int c = 0; c < 3; ++c)
        p[3 * (n - 3) + c] = lo[c] + (hi[c] - lo[c]) * 0.3;
    p[3 * (n - 3) + 2] = 0x1p-1060;
    p[3 * (n - 1)] = NAN;
    p[3 * (n - 2) + 1] = INFINITY;
    return n;
}

/* ---- the host build of the device code against the CPU -------------------------------------- */

typedef struct sd_stats {
    size_t results, inside, refused, reference, above;
} sd_stats;

/* Point i's device answer (got, gd) against the CPU's (want, wd), in either precision. */
#define CHECK_ONE(i, got, want, gd, wd, label)                                                                     \
    do {                                                                                                       \
        if ((got).flags & TTD_GPU_POINT_SIDE_REFUSED) {                                                        \
            /* refused alone: signed distance NaN, the closest point still the CPU's */                      \
            ENSURE_MSG(isnan(gd), "%s point %zu: refused with a distance %g", label, i, (double)(gd));          \
            ENSURE_MSG((got).distance == (want).distance && (got).triangle == (want).triangle &&                  \
                           ((got).flags & ~(TTD_GPU_POINT_SIDE_REFUSED)) ==                                     \
                               ((want).flags & ~(unsigned)(TTD_POINT_INSIDE | TTD_POINT_SIGN_UNPROVEN)),         \
                       "%s point %zu: refused, its closest point not the CPU's", label, i);                    \
            ++st->refused;                                                                                     \
        } else {                                                                                               \
            ENSURE_MSG(SAME_POINT(got, want) && memcmp(&(gd), &(wd), sizeof(gd)) == 0,                          \
                       "%s point %zu: device %.17g (flags %u, triangle %u), CPU %.17g (flags %u, triangle %u)",     \
                       label, i, (double)(gd), (got).flags, (got).triangle, (double)(wd), (want).flags,             \
                       (want).triangle);                                                                       \
        }                                                                                                      \
    } while (0)

/* Every point of p on mesh g (built as md and mf) in both precisions, bounds inf, 0.05 s, 0. */
static int signed_case(int gi, ttd_mesh *md, ttd_mesh *mf, size_t n, const double *p, size_t subnormal, sd_stats *st)
{
    ttd_mesh *unit = NULL; /* the reference's mesh: md, or the unit cube for a scaled one */
    if (gm_unscale[gi] != 0)
        ENSURE(build(&gm[4], 0, &unit) == 0);
    const ttd_gen_mesh *g = &gm[gi];
    double lo[3], hi[3];
    ttd_gen_mesh_bounds(g, lo, hi);
    const double s = fmax(hi[0] - lo[0], fmax(hi[1] - lo[1], hi[2] - lo[2]));
    ttd_options opt = ttd_default_options();
    opt.threads = 1;
    double *wd = malloc(n * sizeof *wd), *gd = malloc(n * sizeof *gd);
    float *pf = malloc(3 * n * sizeof *pf), *wf = malloc(n * sizeof *wf), *gf = malloc(n * sizeof *gf);
    ttd_point_result_d *want = malloc(n * sizeof *want), *got = malloc(n * sizeof *got);
    ttd_point_result_f *want_f = malloc(n * sizeof *want_f), *got_f = malloc(n * sizeof *got_f);
    ENSURE(wd && gd && pf && wf && gf && want && got && want_f && got_f);
    for (size_t k = 0; gm_float[gi] && k < 3 * n; ++k) /* (the scaled cubes' points are past float's range) */
        pf[k] = (float)p[k];
    const double bounds[3] = {INFINITY, 0.05 * s, 0};
    for (int b = 0; b < 3; ++b) {
        /* the CPU first: it makes what the device's mode depends on (closedness, the caps) */
        ENSURE(ttd_points_signed_distance_d(&opt, md, n, p, NULL, bounds[b], wd, want) == TTD_ERR_NONFINITE_INPUT);
        const int mode = ttd_cuda_host_signed_d(md, n, p, bounds[b], gd, got);
        ENSURE_MSG(mode == gm_mode[gi], "%s: sign mode %d, expected %d", gm_name[gi], mode, gm_mode[gi]);
        if (mode == 0)
            break; /* refused: nothing computed */
        for (size_t i = 0; i < n; ++i) {
            CHECK_ONE(i, got[i], want[i], gd[i], wd[i], gm_name[gi]);
            ++st->results;
            st->inside += (want[i].flags & TTD_POINT_INSIDE) != 0;
            st->above += (want[i].flags & TTD_POINT_ABOVE_BOUND) != 0;
            /* the independent reference: the plain sum of solid angles, off the surface */
            if (b == 0 && mode == 2 && isfinite(want[i].distance) && want[i].distance > 1e-6 * s &&
                !(got[i].flags & TTD_GPU_POINT_SIDE_REFUSED)) {
                double x[3];
                for (int c = 0; c < 3; ++c)
                    x[c] = ldexp(p[3 * i + c], gm_unscale[gi]);
                const double w = ttd_mesh_winding(unit ? unit : md, x);
                ENSURE_MSG((fabs(w) >= 0.5) == ((want[i].flags & TTD_POINT_INSIDE) != 0),
                           "%s point %zu (%g %g %g): solid angles give w = %g, the count %s", gm_name[gi], i,
                           p[3 * i], p[3 * i + 1], p[3 * i + 2], w,
                           (want[i].flags & TTD_POINT_INSIDE) ? "inside" : "outside");
                ++st->reference;
            }
        }
        if (mode == 2 && s > 0.5 && s < 2) /* (a mesh at unit scale: scaled ones scale the point too) */
            ENSURE_MSG(got[subnormal].flags & TTD_GPU_POINT_SIDE_REFUSED, "%s: the subnormal point was not refused",
                       gm_name[gi]);
        /* the distance alone (results NULL on the CPU side: its own path) */
        ENSURE(ttd_points_signed_distance_d(&opt, md, n, p, NULL, bounds[b], wd, NULL) == TTD_ERR_NONFINITE_INPUT);
        for (size_t i = 0; i < n; ++i)
            if (!(got[i].flags & TTD_GPU_POINT_SIDE_REFUSED))
                ENSURE_MSG(memcmp(&gd[i], &wd[i], sizeof *gd) == 0, "%s point %zu: distance alone differs", gm_name[gi], i);
        if (!gm_float[gi])
            continue;
        ENSURE(ttd_points_signed_distance_f(&opt, mf, n, pf, NULL, (float)bounds[b], wf, want_f) ==
               TTD_ERR_NONFINITE_INPUT);
        ENSURE(ttd_cuda_host_signed_f(mf, n, pf, (float)bounds[b], gf, got_f) == gm_mode[gi]);
        for (size_t i = 0; i < n; ++i) {
            CHECK_ONE(i, got_f[i], want_f[i], gf[i], wf[i], gm_name[gi]);
            ++st->results;
        }
    }
    ttd_mesh_destroy(unit);
    free(wd);
    free(gd);
    free(pf);
    free(wf);
    free(gf);
    free(want);
    free(got);
    free(want_f);
    free(got_f);
    return 0;
}

static int signed_host(void)
{
    ENSURE(make_meshes() == 0);
    const size_t n = 1500;
    double *p = malloc(3 * n * sizeof *p);
    ENSURE(p != NULL);
    sd_stats st = {0};
    for (int i = 0; i < MESHES; ++i) {
        ttd_mesh *md = NULL, *mf = NULL;
        ENSURE_MSG(build(&gm[i], 0, &md) == 0, "%s", gm_name[i]);
        if (gm_float[i])
            ENSURE(build(&gm[i], 1, &mf) == 0);
        size_t subnormal;
        point_set(&gm[i], 31u + (uint64_t)i, n, p, &subnormal);
        const sd_stats before = st;
        ENSURE(signed_case(i, md, mf, n, p, subnormal, &st) == 0);
        printf("  %-12s %6zu triangles: %5zu results, %4zu inside, %zu refused points, %4zu against solid angles\n",
               gm_name[i], gm[i].nt, st.results - before.results, st.inside - before.inside,
               st.refused - before.refused, st.reference - before.reference);
        ttd_mesh_destroy(md);
        ttd_mesh_destroy(mf);
    }
    printf("  %zu signed distances (double and float, bounds inf, 0.05, 0): 0 differing from "
           "ttd_points_signed_distance; %zu inside, %zu above the bound, %zu sides checked against solid angles, "
           "%zu refused points (subnormal coordinates)\n",
           st.results, st.inside, st.above, st.reference, st.refused);
    ENSURE(st.inside > 0 && st.above > 0 && st.reference > 0 && st.refused > 0);
    free(p);
    return 0;
}

/* The shell's cavity is outside and its wall inside; the inward icosphere's inside is inside
 * (|w| = 1): the rule |w| >= 1/2, not w >= 1/2, and a count, not a parity. Points on the axes. */
static int signed_rules(void)
{
    ENSURE(make_meshes() == 0);
    static const double r[] = {0.0, 0.2, 0.3, 0.75, 0.9, 1.5};
    static const int in_shell[] = {0, 0, 0, 1, 1, 0}, in_ball[] = {1, 1, 1, 1, 1, 0};
    double p[3 * 6];
    for (int i = 0; i < 6; ++i)
        p[3 * i] = r[i], p[3 * i + 1] = 0.01, p[3 * i + 2] = 0.02;
    const int meshes[3] = {1, 2, 0};
    for (int m = 0; m < 3; ++m) {
        ttd_mesh *md = NULL;
        ENSURE(build(&gm[meshes[m]], 0, &md) == 0);
        double wd[6], gd[6];
        ttd_point_result_d want[6], got[6];
        ENSURE(ttd_points_signed_distance_d(NULL, md, 6, p, NULL, INFINITY, wd, want) == TTD_OK);
        ENSURE(ttd_cuda_host_signed_d(md, 6, p, INFINITY, gd, got) == 2);
        for (int i = 0; i < 6; ++i) {
            const int expect = meshes[m] == 2 ? in_shell[i] : in_ball[i];
            ENSURE_MSG(((got[i].flags & TTD_POINT_INSIDE) != 0) == expect && (gd[i] < 0) == expect,
                       "%s at r = %g: inside %d, expected %d", gm_name[meshes[m]], r[i],
                       (got[i].flags & TTD_POINT_INSIDE) != 0, expect);
            ENSURE(memcmp(&gd[i], &wd[i], sizeof *gd) == 0 && SAME_POINT(got[i], want[i]));
        }
        ttd_mesh_destroy(md);
    }
    return 0;
}

/* ---- the entries -------------------------------------------------------------------------------- */

static int signed_entries_without_device(void)
{
    ttd_gpu_info info;
    const ttd_gpu_status st = ttd_gpu_query(&info);
    const double pt[3] = {0, 0, 0};
    double d;
    ttd_point_result_d r;
    if (st == TTD_GPU_ERR_NOT_BUILT) {
        ENSURE(ttd_gpu_points_signed_distance_d(NULL, 1, pt, INFINITY, &d, &r, NULL) == TTD_GPU_ERR_NOT_BUILT);
        ENSURE(ttd_gpu_points_signed_distance_f(NULL, 0, NULL, 0, NULL, NULL, NULL) == TTD_GPU_ERR_NOT_BUILT);
    } else {
        ENSURE(ttd_gpu_points_signed_distance_d(NULL, 1, pt, INFINITY, &d, &r, NULL) == TTD_GPU_ERR_NULL_POINTER);
        ENSURE(ttd_gpu_points_signed_distance_f(NULL, 0, NULL, 0, NULL, NULL, NULL) == TTD_GPU_ERR_NULL_POINTER);
    }
    ENSURE(strstr(ttd_gpu_status_string(TTD_GPU_ERR_BAD_ARGUMENT), "side") != NULL);
    printf("  %s: %s\n", ttd_gpu_status_string(st), st == TTD_GPU_OK ? info.name : info.message);
    return 0;
}

#ifdef TTD_TEST_CUDA
/* The entries' checks on real device meshes. */
static int signed_entries_device(void)
{
    ENSURE(make_meshes() == 0);
    ttd_mesh *m = NULL, *open = NULL;
    ENSURE(build(&gm[0], 0, &m) == 0 && build(&gm[9], 0, &open) == 0);
    ttd_gpu_mesh *g0 = NULL, *g1 = NULL, *go = NULL;
    ENSURE(ttd_gpu_mesh_upload(m, &g0) == TTD_GPU_OK); /* before any point query: no point data */
    const double pt[3] = {0.1, 0.2, 0.3};
    double *dp, *dd;
    ttd_point_result_d *dr;
    CU(cudaMalloc((void **)&dp, sizeof pt));
    CU(cudaMalloc((void **)&dd, sizeof *dd));
    CU(cudaMalloc((void **)&dr, sizeof *dr));
    CU(cudaMemcpy(dp, pt, sizeof pt, cudaMemcpyHostToDevice));
    ENSURE(ttd_gpu_points_signed_distance_d(g0, 1, dp, INFINITY, dd, dr, NULL) == TTD_GPU_ERR_BAD_ARGUMENT);
    double hd;
    ttd_point_result_d hr;
    ENSURE(ttd_points_signed_distance_d(NULL, m, 1, pt, NULL, INFINITY, &hd, &hr) == TTD_OK);
    ENSURE(ttd_points_signed_distance_d(NULL, open, 1, pt, NULL, INFINITY, &hd, &hr) == TTD_OK);
    ENSURE(ttd_gpu_mesh_upload(m, &g1) == TTD_GPU_OK && ttd_gpu_mesh_upload(open, &go) == TTD_GPU_OK);
    ENSURE(ttd_gpu_points_signed_distance_d(go, 1, dp, INFINITY, dd, dr, NULL) == TTD_GPU_ERR_BAD_ARGUMENT);
    ENSURE(ttd_gpu_points_signed_distance_d(g1, 1, dp, -1, dd, dr, NULL) == TTD_GPU_ERR_BAD_ARGUMENT);
    ENSURE(ttd_gpu_points_signed_distance_d(g1, 1, dp, NAN, dd, dr, NULL) == TTD_GPU_ERR_BAD_ARGUMENT);
    ENSURE(ttd_gpu_points_signed_distance_f(g1, 1, (const float *)dp, 1, (float *)dd, NULL, NULL) ==
           TTD_GPU_ERR_BAD_ARGUMENT);
    ENSURE(ttd_gpu_points_signed_distance_d(g1, 1, dp, INFINITY, NULL, NULL, NULL) == TTD_GPU_ERR_NULL_POINTER);
    ENSURE(ttd_gpu_points_signed_distance_d(g1, 1, pt, INFINITY, dd, dr, NULL) == TTD_GPU_ERR_NOT_DEVICE_MEMORY);
    ENSURE(ttd_gpu_points_signed_distance_d(g1, 1, dp, INFINITY, &hd, NULL, NULL) == TTD_GPU_ERR_NOT_DEVICE_MEMORY);
    ENSURE(ttd_gpu_points_signed_distance_d(g1, 0, dp, INFINITY, dd, dr, NULL) == TTD_GPU_OK);
    ENSURE(ttd_gpu_points_signed_distance_d(g1, 1, dp, INFINITY, dd, NULL, NULL) == TTD_GPU_OK);
    ENSURE(ttd_gpu_points_signed_distance_d(g1, 1, dp, INFINITY, NULL, dr, NULL) == TTD_GPU_OK);
    CU(cudaDeviceSynchronize());
    double got;
    CU(cudaMemcpy(&got, dd, sizeof got, cudaMemcpyDeviceToHost));
    ENSURE(ttd_points_signed_distance_d(NULL, m, 1, pt, NULL, INFINITY, &hd, NULL) == TTD_OK);
    ENSURE(memcmp(&got, &hd, sizeof got) == 0 && got < 0);
    cudaFree(dp);
    cudaFree(dd);
    cudaFree(dr);
    ttd_gpu_mesh_free(g0);
    ttd_gpu_mesh_free(g1);
    ttd_gpu_mesh_free(go);
    ttd_mesh_destroy(m);
    ttd_mesh_destroy(open);
    return 0;
}

/* A bunny-sized closed mesh: an icosphere of 81,920 triangles, each vertex moved radially by up to
 * 3% (a fixed hash), normalized (test_gpu_walk's rough sphere). */
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

/* n points near and far from g through ttd_gpu_points_signed_distance on device memory against
 * ttd_points_signed_distance on the host's cores: distances and whole results bit for bit, and
 * points/s of both. */
static int device_signed(const ttd_gen_mesh *g, ttd_mesh *m, size_t n, int single)
{
    double *p = malloc(3 * n * sizeof *p);
    ENSURE(p != NULL);
    size_t subnormal;
    point_set(g, 99u, n, p, &subnormal);
    p[3 * (n - 1)] = 0.5, p[3 * (n - 2) + 1] = 0.25; /* no NaN here: the CPU call is then TTD_OK */
    p[3 * subnormal + 2] = 0.125;                     /* and no refused point */
    const size_t pb = single ? 4 : 8, rb = single ? sizeof(ttd_point_result_f) : sizeof(ttd_point_result_d);
    void *hp = malloc(3 * n * pb), *want = malloc(n * rb), *got = malloc(n * rb), *wd = malloc(n * pb),
         *gd = malloc(n * pb);
    ENSURE(hp && want && got && wd && gd);
    for (size_t i = 0; i < 3 * n; ++i) {
        if (single)
            ((float *)hp)[i] = (float)p[i];
        else
            ((double *)hp)[i] = p[i];
    }
    ttd_options opt = ttd_default_options();
    ENSURE((single ? ttd_points_signed_distance_f(&opt, m, 1, hp, NULL, INFINITY, wd, want)
                   : ttd_points_signed_distance_d(&opt, m, 1, hp, NULL, INFINITY, wd, want)) == TTD_OK);
    ttd_gpu_mesh *gm_ = NULL;
    ENSURE(ttd_gpu_mesh_upload(m, &gm_) == TTD_GPU_OK);
    void *dp, *dr, *dd;
    CU(cudaMalloc(&dp, 3 * n * pb));
    CU(cudaMalloc(&dr, n * rb));
    CU(cudaMalloc(&dd, n * pb));
    CU(cudaMemcpy(dp, hp, 3 * n * pb, cudaMemcpyHostToDevice));
    cudaEvent_t e0, e1, e2;
    CU(cudaEventCreate(&e0));
    CU(cudaEventCreate(&e1));
    CU(cudaEventCreate(&e2));
    CU(cudaEventRecord(e0, NULL));
    ENSURE((single ? ttd_gpu_points_signed_distance_f(gm_, n, dp, INFINITY, dd, NULL, NULL)
                   : ttd_gpu_points_signed_distance_d(gm_, n, dp, INFINITY, dd, NULL, NULL)) == TTD_GPU_OK);
    CU(cudaEventRecord(e1, NULL));
    ENSURE((single ? ttd_gpu_points_signed_distance_f(gm_, n, dp, INFINITY, NULL, dr, NULL)
                   : ttd_gpu_points_signed_distance_d(gm_, n, dp, INFINITY, NULL, dr, NULL)) == TTD_GPU_OK);
    CU(cudaEventRecord(e2, NULL));
    CU(cudaEventSynchronize(e2));
    float ms = 0;
    CU(cudaEventElapsedTime(&ms, e0, e1));
    CU(cudaMemcpy(got, dr, n * rb, cudaMemcpyDeviceToHost));
    CU(cudaMemcpy(gd, dd, n * pb, cudaMemcpyDeviceToHost));
    const double t0 = seconds();
    ENSURE((single ? ttd_points_signed_distance_f(&opt, m, n, hp, NULL, INFINITY, wd, NULL)
                   : ttd_points_signed_distance_d(&opt, m, n, hp, NULL, INFINITY, wd, NULL)) == TTD_OK);
    const double t1 = seconds();
    ENSURE((single ? ttd_points_signed_distance_f(&opt, m, n, hp, NULL, INFINITY, NULL, want)
                   : ttd_points_signed_distance_d(&opt, m, n, hp, NULL, INFINITY, NULL, want)) == TTD_OK);
    size_t diff = 0, inside = 0;
    for (size_t i = 0; i < n; ++i) {
        diff += memcmp((const char *)gd + i * pb, (const char *)wd + i * pb, pb) != 0;
        if (single) {
            const ttd_point_result_f *a = (const ttd_point_result_f *)got + i, *b = (const ttd_point_result_f *)want + i;
            diff += !SAME_POINT(*a, *b);
            inside += (b->flags & TTD_POINT_INSIDE) != 0;
        } else {
            const ttd_point_result_d *a = (const ttd_point_result_d *)got + i, *b = (const ttd_point_result_d *)want + i;
            diff += !SAME_POINT(*a, *b);
            inside += (b->flags & TTD_POINT_INSIDE) != 0;
        }
    }
    const double gps = (double)n / ((double)ms * 1e-3), cps = (double)n / (t1 - t0);
    printf("  %s signed distances, %zu points (%zu inside): %zu differing; points/s device %.3g, host (%d threads) "
           "%.3g: %.1fx\n",
           single ? "float " : "double", n, inside, diff, gps, opt.threads, cps, gps / cps);
    ENSURE(diff == 0 && inside > 0);
    cudaFree(dp);
    cudaFree(dr);
    cudaFree(dd);
    cudaEventDestroy(e0);
    cudaEventDestroy(e1);
    cudaEventDestroy(e2);
    ttd_gpu_mesh_free(gm_);
    free(p);
    free(hp);
    free(want);
    free(got);
    free(wd);
    free(gd);
    return 0;
}

static int signed_device(void)
{
    ttd_gpu_info info;
    if (ttd_gpu_query(&info) != TTD_GPU_OK) {
        printf("  skip: no usable GPU (%s)\n", info.message);
        return 0;
    }
    ENSURE(signed_entries_device() == 0);
    const char *envp = getenv("TTD_GPU_POINTS");
    const size_t np = envp ? (size_t)strtoull(envp, NULL, 10) : 100000;
    ENSURE(np >= 400);
    ttd_gen_mesh g = {0};
    ENSURE(rough_sphere(&g) == 0);
    ttd_mesh *md = NULL, *mf = NULL;
    ENSURE(build(&g, 0, &md) == 0 && build(&g, 1, &mf) == 0);
    printf("  rough sphere (%zu triangles) on %s\n", g.nt, info.name);
    const int fail = device_signed(&g, md, np, 0) || device_signed(&g, mf, np, 1);
    ttd_mesh_destroy(md);
    ttd_mesh_destroy(mf);
    ttd_gen_mesh_free(&g);
    return fail;
}
#endif

int main(int argc, char **argv)
{
    TEST_MAIN_BEGIN(argc, argv);
    RUN_TEST(signed_entries_without_device);
#ifdef TTD_TEST_CUDA
    RUN_TEST(signed_device);
#endif
    RUN_TEST(signed_rules);
    RUN_TEST(signed_host);
    for (int i = 0; i < MESHES; ++i)
        ttd_gen_mesh_free(&gm[i]);
    TEST_MAIN_END();
}

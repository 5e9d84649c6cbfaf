/* SPDX-License-Identifier: MIT */
/* Continuous collision on the device (src/gpu/gpu_ccd.cu; docs/ccd.md, section 14). The device runs
 * for each query what src/ccd/ccd_batch_impl.h says (the search of ccd_search_impl.h with the exact
 * expansions of ccd_exact_impl.h), the source the CPU compiles too. Here that per-thread body,
 * compiled for the host (tests/cuda_host/cuda_host_ccd.c), against the CPU batch entries
 * (ttd_ccd_vertex_face/edge_edge/triangles_d/f, which screen in SIMD lanes first), every output field
 * to the bit: the generated families of test_ccd_lanes (random, near-degenerate, coplanar motion,
 * parallel edges, touching at t = 0 and 1, scaled, offset, zero-length edges and zero-area faces, no
 * motion, coordinates near 2^400, non-finite, apart by the rounding bound), triangle pairs built on
 * them, and the kept sample queries of the CCD benchmark, at three separations, in double and float.
 * The C entries: without a usable GPU they say why, and refuse bad arguments first. With a GPU
 * (built with CUDA, TTD_TEST_CUDA; scripts/test-gpu-device.sh) `ccd_device` runs the same sets
 * through ttd_gpu_ccd_* on device memory against the CPU (TTD_GPU_CCD_N queries a family). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "cuda_host/cuda_host.h"
#include "test_macros.h"
#include "gpu_test_util.h"
#include "ttd/ttd.h"
#include "ttd/ttd_gpu.h"

#ifdef TTD_TEST_CUDA
#include <cuda_runtime.h>
#endif

#define TEST_RAND_SEED 0x6a09e667f3bcc909ull
#include "test_rand.h"
#include "ccd_families.h"

/* A batch in the entries' layout: a0/a1 the first primitives (na points a query), b0/b1 the second
 * (nb points), in double and in float (the doubles rounded to float). */
typedef struct ccd_arrays {
    int kind, na, nb;
    size_t n;
    double *a0, *b0, *a1, *b1;
    float *f[4];
} ccd_arrays;

/* Queries of 12 reals (kind 1, 2) or 18 (kind 3: triangle a's 9, then b's) into the layout. */
static ccd_arrays split(int kind, size_t n, const double *x0, const double *x1)
{
    ccd_arrays A = {kind, kind == 3 ? 3 : kind, kind == 3 ? 3 : 4 - kind, n, NULL, NULL, NULL, NULL, {NULL}};
    const size_t ra = 3 * (size_t)A.na, rb = 3 * (size_t)A.nb, per = ra + rb;
    A.a0 = malloc(n * ra * sizeof(double) + 8), A.a1 = malloc(n * ra * sizeof(double) + 8);
    A.b0 = malloc(n * rb * sizeof(double) + 8), A.b1 = malloc(n * rb * sizeof(double) + 8);
    for (size_t q = 0; q < n; ++q) {
        memcpy(A.a0 + ra * q, x0 + per * q, ra * sizeof(double));
        memcpy(A.a1 + ra * q, x1 + per * q, ra * sizeof(double));
        memcpy(A.b0 + rb * q, x0 + per * q + ra, rb * sizeof(double));
        memcpy(A.b1 + rb * q, x1 + per * q + ra, rb * sizeof(double));
    }
    double *d[4] = {A.a0, A.b0, A.a1, A.b1};
    for (int k = 0; k < 4; ++k) {
        const size_t m = n * ((k & 1) ? rb : ra);
        A.f[k] = malloc(m * sizeof(float) + 4);
        for (size_t i = 0; i < m; ++i)
            A.f[k][i] = (float)d[k][i];
    }
    return A;
}

static void free_arrays(ccd_arrays *A)
{
    free(A->a0), free(A->b0), free(A->a1), free(A->b1);
    for (int k = 0; k < 4; ++k)
        free(A->f[k]);
}

/* The CPU batch entry for A (default options: the best ISA, all cores). */
static ttd_status cpu_run(const ccd_arrays *A, int is_float, double delta, ttd_ccd_result *out)
{
    float *const *f = A->f;
    switch (A->kind) {
    case 1:
        return is_float ? ttd_ccd_vertex_face_f(NULL, A->n, f[0], f[1], f[2], f[3], delta, out)
                        : ttd_ccd_vertex_face_d(NULL, A->n, A->a0, A->b0, A->a1, A->b1, delta, out);
    case 2:
        return is_float ? ttd_ccd_edge_edge_f(NULL, A->n, f[0], f[1], f[2], f[3], delta, out)
                        : ttd_ccd_edge_edge_d(NULL, A->n, A->a0, A->b0, A->a1, A->b1, delta, out);
    default:
        return is_float ? ttd_ccd_triangles_f(NULL, A->n, f[0], f[1], f[2], f[3], delta, out)
                        : ttd_ccd_triangles_d(NULL, A->n, A->a0, A->b0, A->a1, A->b1, delta, out);
    }
}

static int same_result(const ttd_ccd_result *a, const ttd_ccd_result *b)
{
    return memcmp(&a->toi, &b->toi, sizeof a->toi) == 0 && memcmp(&a->gap, &b->gap, sizeof a->gap) == 0 &&
           a->hit == b->hit && a->flags == b->flags && a->sub == b->sub && a->evals == b->evals;
}

/* got against the CPU's want, query by query; counts compared queries and hits. */
static int compare(const char *name, const ccd_arrays *A, int is_float, double delta, const ttd_ccd_result *want,
                   const ttd_ccd_result *got, size_t *queries, size_t *hits)
{
    for (size_t q = 0; q < A->n; ++q) {
        ENSURE_MSG(same_result(&want[q], &got[q]),
                   "%s, kind %d, %s, delta %g, query %zu: CPU hit %u toi %a gap %a flags %u sub %u evals %u; "
                   "device source hit %u toi %a gap %a flags %u sub %u evals %u",
                   name, A->kind, is_float ? "float" : "double", delta, q, want[q].hit, want[q].toi, want[q].gap,
                   want[q].flags, want[q].sub, want[q].evals, got[q].hit, got[q].toi, got[q].gap, got[q].flags,
                   got[q].sub, got[q].evals);
        *hits += want[q].hit;
    }
    *queries += A->n;
    return 0;
}

/* The device source on the host (cuda-host) for A. */
static void host_run(const ccd_arrays *A, int is_float, double delta, ttd_ccd_result *out)
{
    if (is_float)
        ttd_cuda_host_ccd(A->kind, 1, A->n, A->f[0], A->f[1], A->f[2], A->f[3], delta, out);
    else
        ttd_cuda_host_ccd(A->kind, 0, A->n, A->a0, A->b0, A->a1, A->b1, delta, out);
}

/* Where a set is run: 0 the device source on the host, 1 the GPU library on a device. */
typedef int (*side_fn)(const ccd_arrays *A, int is_float, double delta, ttd_ccd_result *out);

static int host_side(const ccd_arrays *A, int is_float, double delta, ttd_ccd_result *out)
{
    host_run(A, is_float, delta, out);
    return 0;
}

/* One set on a side against the CPU, in double and float, at the given separations. */
static int check_set(const char *name, const ccd_arrays *A, side_fn side, const double *deltas, int nd,
                     size_t *queries, size_t *hits)
{
    ttd_ccd_result *want = malloc(A->n * sizeof *want), *got = malloc(A->n * sizeof *got);
    ENSURE(want != NULL && got != NULL);
    int bad = 0;
    for (int is_float = 0; is_float < 2 && !bad; ++is_float)
        for (int d = 0; d < nd && !bad; ++d) {
            const ttd_status st = cpu_run(A, is_float, deltas[d], want);
            ENSURE_MSG(st == TTD_OK || st == TTD_ERR_NONFINITE_INPUT, "%s: CPU status %d", name, (int)st);
            memset(got, 0xa5, A->n * sizeof *got);
            bad = side(A, is_float, deltas[d], got) != 0 ||
                  compare(name, A, is_float, deltas[d], want, got, queries, hits) != 0;
        }
    free(want), free(got);
    return bad;
}

/* Every family, vertex-face and edge-edge, and triangle pairs whose first two vertices each are a
 * family's edges (so parallel, touching and degenerate edges meet as sub-queries) and whose third
 * are random, through side against the CPU. n queries a family and kind. */
static int families(side_fn side, size_t n, size_t *queries, size_t *hits)
{
    for (int fam = 0; fam < F_COUNT; ++fam) {
        const double scale = fam == F_HUGE ? 0x1p399 : 1;
        const double deltas[3] = {0, 1e-3 * scale, 0.05 * scale};
        for (int kind = 1; kind <= 3; ++kind) {
            qset s = make_set(fam, kind == 3 ? 2 : kind, n);
            double *x0 = s.x0, *x1 = s.x1;
            if (kind == 3) { /* a = (e_a0, e_a1, c), b = (e_b0, e_b1, d) */
                x0 = malloc(n * 18 * sizeof(double));
                x1 = malloc(n * 18 * sizeof(double));
                for (size_t q = 0; q < n; ++q)
                    for (int t = 0; t < 2; ++t) {
                        for (int k = 0; k < 3; ++k)
                            for (int e = 0; e < 2; ++e) {
                                double *x = e ? x1 : x0;
                                const double *y = e ? s.x1 : s.x0;
                                x[18 * q + 9 * t + k] = y[12 * q + 6 * t + k];
                                x[18 * q + 9 * t + 3 + k] = y[12 * q + 6 * t + 3 + k];
                            }
                        for (int k = 0; k < 3; ++k) {
                            const double c = x0[18 * q + 9 * t + k] + 0.4 * scale * srand1();
                            x0[18 * q + 9 * t + 6 + k] = c;
                            x1[18 * q + 9 * t + 6 + k] = fam == F_STILL ? c : c + 0.3 * scale * srand1();
                        }
                    }
            }
            ccd_arrays A = split(kind, n, x0, x1);
            const size_t q0 = *queries, h0 = *hits;
            const int bad = check_set(family_name[fam], &A, side, deltas, 3, queries, hits);
            free_arrays(&A);
            if (kind == 3)
                free(x0), free(x1);
            free(s.x0), free(s.x1);
            if (bad)
                return 1;
            printf("  %-12s %-36s %6zu queries, %5zu hits: equal\n",
                   kind == 1 ? "vertex-face" : kind == 2 ? "edge-edge" : "triangles", family_name[fam],
                   *queries - q0, *hits - h0);
        }
    }
    return 0;
}

/* A sample file at separations 0 and 1e-4 (walk_csv's fn; ctx: the side and the counts). */
typedef struct samples_ctx {
    side_fn side;
    size_t queries, hits;
} samples_ctx;

static int samples_file(const char *path, const qset *s, void *ctx)
{
    samples_ctx *c = ctx;
    ccd_arrays A = split(s->kind, s->n, s->x0, s->x1);
    const double deltas[2] = {0, 1e-4};
    const int bad = check_set(path, &A, c->side, deltas, 2, &c->queries, &c->hits);
    free_arrays(&A);
    return bad;
}

static int samples(side_fn side)
{
    size_t files = 0;
    samples_ctx c = {side, 0, 0};
    ENSURE(walk_csv(TTD_CCD_DATA, samples_file, &c, &files) == 0);
    const size_t queries = c.queries, hits = c.hits;
    printf("  sample queries: %zu files, %zu answers (two separations, double and float), %zu hits: equal\n", files,
           queries, hits);
    ENSURE(files >= 20 && hits > queries / 50);
    return 0;
}

/* The device source compiled for the host against the CPU batch. */
static int host_families(void)
{
    size_t queries = 0, hits = 0;
    const char *env = getenv("TTD_GPU_CCD_HOST_N");
    ENSURE(families(host_side, env ? (size_t)strtoull(env, NULL, 10) : 300, &queries, &hits) == 0);
    printf("  %zu answers, %zu hits, every field equal to the CPU's\n", queries, hits);
    ENSURE(hits > queries / 20); /* the comparison covers contacts, not only free queries */
    return 0;
}

static int host_samples(void)
{
    return samples(host_side);
}

/* The entries without a usable GPU: NOT_BUILT from the stub; with CUDA, NULL arrays and bad
 * separations refused before any device is asked, n = 0 nothing, host arrays refused. */
static int ccd_entries_without_device(void)
{
    ttd_gpu_info info;
    const ttd_gpu_status st = ttd_gpu_query(&info);
    double x[9] = {0};
    float f[9] = {0};
    ttd_ccd_result r;
    if (st == TTD_GPU_ERR_NOT_BUILT) {
        ENSURE(ttd_gpu_ccd_vertex_face_d(1, x, x, x, x, 0, &r, NULL) == TTD_GPU_ERR_NOT_BUILT);
        ENSURE(ttd_gpu_ccd_vertex_face_f(1, f, f, f, f, 0, &r, NULL) == TTD_GPU_ERR_NOT_BUILT);
        ENSURE(ttd_gpu_ccd_edge_edge_d(1, x, x, x, x, 0, &r, NULL) == TTD_GPU_ERR_NOT_BUILT);
        ENSURE(ttd_gpu_ccd_edge_edge_f(0, NULL, NULL, NULL, NULL, NAN, NULL, NULL) == TTD_GPU_ERR_NOT_BUILT);
        ENSURE(ttd_gpu_ccd_triangles_d(1, x, x, x, x, 0, &r, NULL) == TTD_GPU_ERR_NOT_BUILT);
        ENSURE(ttd_gpu_ccd_triangles_f(1, f, f, f, f, 0, &r, NULL) == TTD_GPU_ERR_NOT_BUILT);
    } else {
        ENSURE(ttd_gpu_ccd_vertex_face_d(1, NULL, x, x, x, 0, &r, NULL) == TTD_GPU_ERR_NULL_POINTER);
        ENSURE(ttd_gpu_ccd_vertex_face_f(1, f, f, f, f, 0, NULL, NULL) == TTD_GPU_ERR_NULL_POINTER);
        ENSURE(ttd_gpu_ccd_edge_edge_d(1, x, x, NULL, x, 0, &r, NULL) == TTD_GPU_ERR_NULL_POINTER);
        ENSURE(ttd_gpu_ccd_triangles_f(0, f, f, f, NULL, 0, &r, NULL) == TTD_GPU_ERR_NULL_POINTER);
        ENSURE(ttd_gpu_ccd_vertex_face_d(1, x, x, x, x, -1, &r, NULL) == TTD_GPU_ERR_BAD_ARGUMENT);
        ENSURE(ttd_gpu_ccd_edge_edge_f(1, f, f, f, f, NAN, &r, NULL) == TTD_GPU_ERR_BAD_ARGUMENT);
        ENSURE(ttd_gpu_ccd_triangles_d(1, x, x, x, x, INFINITY, &r, NULL) == TTD_GPU_ERR_BAD_ARGUMENT);
        ENSURE(ttd_gpu_ccd_edge_edge_d(0, x, x, x, x, 0, &r, NULL) == TTD_GPU_OK);
        ENSURE(ttd_gpu_ccd_triangles_d(SIZE_MAX / 8, x, x, x, x, 0, &r, NULL) == TTD_GPU_ERR_NOT_DEVICE_MEMORY);
        /* host arrays: not device memory (with a device) or no device to ask (without) */
        const ttd_gpu_status h = ttd_gpu_ccd_vertex_face_d(1, x, x, x, x, 0, &r, NULL);
        ENSURE_MSG(h == (st == TTD_GPU_OK ? TTD_GPU_ERR_NOT_DEVICE_MEMORY : TTD_GPU_ERR_NO_DEVICE), "status %d",
                   (int)h);
    }
    /* what ttd.cuda.ccd_vertex_face / ccd_edge_edge read (python/ttd/cuda.py, CCDResultGPU) */
    ENSURE(sizeof(ttd_ccd_result) == 32 && offsetof(ttd_ccd_result, toi) == 0 && offsetof(ttd_ccd_result, hit) == 16);
    printf("  %s: %s\n", ttd_gpu_status_string(st), st == TTD_GPU_OK ? info.name : info.message);
    return 0;
}

#ifdef TTD_TEST_CUDA
/* The GPU library on a device: A's arrays copied to device memory, the entry, the records back. */
static int device_side(const ccd_arrays *A, int is_float, double delta, ttd_ccd_result *out)
{
    const size_t rs = is_float ? sizeof(float) : sizeof(double);
    const size_t m[4] = {A->n * 3 * (size_t)A->na, A->n * 3 * (size_t)A->nb, A->n * 3 * (size_t)A->na,
                         A->n * 3 * (size_t)A->nb};
    const void *h[4] = {A->a0, A->b0, A->a1, A->b1};
    void *dv[4] = {NULL, NULL, NULL, NULL};
    ttd_ccd_result *dr = NULL;
    int bad = 0;
    for (int k = 0; k < 4 && !bad; ++k)
        bad = cudaMalloc(&dv[k], m[k] * rs + 8) != cudaSuccess ||
              cudaMemcpy(dv[k], is_float ? (const void *)A->f[k] : h[k], m[k] * rs, cudaMemcpyHostToDevice) != cudaSuccess;
    bad = bad || cudaMalloc((void **)&dr, A->n * sizeof *dr) != cudaSuccess;
    ttd_gpu_status st = TTD_GPU_ERR_CUDA;
    if (!bad) {
        if (A->kind == 1)
            st = is_float ? ttd_gpu_ccd_vertex_face_f(A->n, dv[0], dv[1], dv[2], dv[3], delta, dr, NULL)
                          : ttd_gpu_ccd_vertex_face_d(A->n, dv[0], dv[1], dv[2], dv[3], delta, dr, NULL);
        else if (A->kind == 2)
            st = is_float ? ttd_gpu_ccd_edge_edge_f(A->n, dv[0], dv[1], dv[2], dv[3], delta, dr, NULL)
                          : ttd_gpu_ccd_edge_edge_d(A->n, dv[0], dv[1], dv[2], dv[3], delta, dr, NULL);
        else
            st = is_float ? ttd_gpu_ccd_triangles_f(A->n, dv[0], dv[1], dv[2], dv[3], delta, dr, NULL)
                          : ttd_gpu_ccd_triangles_d(A->n, dv[0], dv[1], dv[2], dv[3], delta, dr, NULL);
        bad = st != TTD_GPU_OK || cudaDeviceSynchronize() != cudaSuccess ||
              cudaMemcpy(out, dr, A->n * sizeof *dr, cudaMemcpyDeviceToHost) != cudaSuccess;
    }
    for (int k = 0; k < 4; ++k)
        cudaFree(dv[k]);
    cudaFree(dr);
    ENSURE_MSG(!bad, "device run: %s, %s", ttd_gpu_status_string(st), cudaGetErrorString(cudaGetLastError()));
    return 0;
}

/* Queries a second on the device (data resident, CUDA events) and on the host's cores (wall clock),
 * on n random vertex-face and edge-edge queries, double, separation 0. */
static int device_throughput(size_t n)
{
    for (int kind = 1; kind <= 2; ++kind) {
        qset s = make_set(F_RANDOM, kind, n);
        ccd_arrays A = split(kind, n, s.x0, s.x1);
        ttd_ccd_result *want = malloc(n * sizeof *want);
        double t0 = seconds();
        ENSURE(cpu_run(&A, 0, 0, want) == TTD_OK);
        const double host_s = seconds() - t0;
        void *dv[4];
        const void *h[4] = {A.a0, A.b0, A.a1, A.b1};
        const size_t m[4] = {n * 3 * (size_t)A.na, n * 3 * (size_t)A.nb, n * 3 * (size_t)A.na, n * 3 * (size_t)A.nb};
        ttd_ccd_result *dr;
        for (int k = 0; k < 4; ++k)
            ENSURE(cudaMalloc(&dv[k], m[k] * 8) == cudaSuccess &&
                   cudaMemcpy(dv[k], h[k], m[k] * 8, cudaMemcpyHostToDevice) == cudaSuccess);
        ENSURE(cudaMalloc((void **)&dr, n * sizeof *dr) == cudaSuccess);
        cudaEvent_t e0, e1;
        cudaEventCreate(&e0), cudaEventCreate(&e1);
        float best = 1e30f;
        for (int rep = 0; rep < 3; ++rep) {
            cudaEventRecord(e0, NULL);
            const ttd_gpu_status st = kind == 1 ? ttd_gpu_ccd_vertex_face_d(n, dv[0], dv[1], dv[2], dv[3], 0, dr, NULL)
                                                : ttd_gpu_ccd_edge_edge_d(n, dv[0], dv[1], dv[2], dv[3], 0, dr, NULL);
            cudaEventRecord(e1, NULL);
            ENSURE(st == TTD_GPU_OK && cudaEventSynchronize(e1) == cudaSuccess);
            float ms;
            cudaEventElapsedTime(&ms, e0, e1);
            best = ms < best ? ms : best;
        }
        ttd_ccd_result *got = malloc(n * sizeof *got);
        ENSURE(cudaMemcpy(got, dr, n * sizeof *dr, cudaMemcpyDeviceToHost) == cudaSuccess);
        size_t qs = 0, hs = 0;
        ENSURE(compare("throughput", &A, 0, 0, want, got, &qs, &hs) == 0);
        printf("  %s, %zu random queries: device %.3g queries/s (best of 3, events), host cores %.3g queries/s, "
               "%zu hits, equal\n", kind == 1 ? "vertex-face" : "edge-edge", n, (double)n / ((double)best * 1e-3), (double)n / host_s, hs);
        for (int k = 0; k < 4; ++k)
            cudaFree(dv[k]);
        cudaFree(dr);
        free(want), free(got);
        free_arrays(&A);
        free(s.x0), free(s.x1);
    }
    return 0;
}

static int ccd_device(void)
{
    ttd_gpu_info info;
    if (ttd_gpu_query(&info) != TTD_GPU_OK) {
        printf("  skip: no usable GPU (%s)\n", info.message);
        return 0;
    }
    const char *env = getenv("TTD_GPU_CCD_N");
    const size_t n = env ? (size_t)strtoull(env, NULL, 10) : 2000;
    ENSURE(n >= 16);
    printf("  on %s, %zu queries a family and kind\n", info.name, n);
    size_t queries = 0, hits = 0;
    ENSURE(families(device_side, n, &queries, &hits) == 0);
    printf("  %zu answers, %zu hits, every field equal to the CPU's\n", queries, hits);
    ENSURE(samples(device_side) == 0);
    return device_throughput(n < 100000 ? 100000 : n);
}
#endif

int main(int argc, char **argv)
{
    TEST_MAIN_BEGIN(argc, argv);
    RUN_TEST(ccd_entries_without_device);
    RUN_TEST(host_families);
    RUN_TEST(host_samples);
#ifdef TTD_TEST_CUDA
    RUN_TEST(ccd_device);
#endif
    TEST_MAIN_END();
}

/* SPDX-License-Identifier: MIT */
#define _POSIX_C_SOURCE 200809L
/* The GPU library (include/ttd/ttd_gpu.h, src/gpu/, docs/gpu.md).
 *
 * Everywhere: the statuses; the GPU batch's per-thread source (src/gpu/gpu_pair_impl.h over
 * src/simd/lanes_cuda.h) compiled for the host (tests/cuda_host/) against the CPU's ttd_batch,
 * whole results bit for bit on every generator family, pairs scaled over the whole exponent
 * range, and NaN/inf pairs; and, without a usable GPU, that the entry points say why (the stub:
 * TTD_GPU_ERR_NOT_BUILT; no driver or device: TTD_GPU_ERR_NO_DEVICE) and the device tests skip
 * with a message.
 *
 * With a GPU (built with CUDA, TTD_TEST_CUDA): the same pairs through ttd_gpu_batch_d/f on
 * device memory, whole results and distance-only, against the CPU bit for bit; the argument and
 * memory checks; and the device-resident distance-only throughput, printed (not asserted). */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "pairs.h"
#include "ttd/ttd.h"
#include "ttd/ttd_gpu.h"
#include "cuda_host/cuda_host.h"
#include "test_macros.h"

#ifdef TTD_TEST_CUDA
#include <cuda_runtime.h>
#endif

/* Pairs for the bit comparisons: every gen/pairs.h family (n each), then the random family
 * scaled by 2^k over the whole double exponent range (extreme: subnormal-sized to near
 * DBL_MAX; the float copies clamp the scale to float's range), then NaN and inf pairs. */
enum { FAM_N = 4000 };
static size_t pair_set(double **s_out, double **t_out, float **sf_out, float **tf_out)
{
    const size_t n = (size_t)(TTD_GEN_COUNT + 2) * FAM_N + 8;
    double *s = malloc(9 * n * sizeof *s), *t = malloc(9 * n * sizeof *t);
    float *sf = malloc(9 * n * sizeof *sf), *tf = malloc(9 * n * sizeof *tf);
    if (!s || !t || !sf || !tf)
        abort();
    for (int f = 0; f < TTD_GEN_COUNT; ++f)
        ttd_gen((ttd_gen_family)f, 2020u + (uint64_t)f, FAM_N, s + 9 * (size_t)f * FAM_N, t + 9 * (size_t)f * FAM_N);
    size_t i0 = (size_t)TTD_GEN_COUNT * FAM_N;
    ttd_gen(TTD_GEN_RANDOM, 99u, 2 * FAM_N, s + 9 * i0, t + 9 * i0);
    for (size_t i = 0; i < 9 * (i0 + 2 * FAM_N); ++i) {
        sf[i] = (float)s[i];
        tf[i] = (float)t[i];
    }
    for (size_t i = 0; i < 2 * FAM_N; ++i) {
        const int kd = -1060 + (int)((i * 2654435761u) % 2080u), kf = -160 + (int)((i * 2654435761u) % 285u);
        for (int c = 0; c < 9; ++c) {
            const size_t j = 9 * (i0 + i) + (size_t)c;
            sf[j] = ldexpf(sf[j], kf);
            tf[j] = ldexpf(tf[j], kf);
            s[j] = ldexp(s[j], kd);
            t[j] = ldexp(t[j], kd);
        }
    }
    i0 += 2 * FAM_N;
    ttd_gen(TTD_GEN_RANDOM, 7u, 8, s + 9 * i0, t + 9 * i0);
    for (size_t i = 0; i < 8; ++i) {
        double *x = (i % 2 ? t : s) + 9 * (i0 + i);
        x[i] = i < 4 ? (double)NAN : (i % 3 ? (double)INFINITY : -(double)INFINITY);
    }
    for (size_t i = 9 * i0; i < 9 * n; ++i) {
        sf[i] = (float)s[i];
        tf[i] = (float)t[i];
    }
    *s_out = s;
    *t_out = t;
    *sf_out = sf;
    *tf_out = tf;
    return n;
}

/* Pairs whose results (and distances, where given) differ from the CPU's in any bit. */
static size_t count_diff_d(size_t n, const ttd_result_d *want, const ttd_result_d *got, const double *dist)
{
    size_t diff = 0;
    for (size_t i = 0; i < n; ++i) {
        const int d = (got && memcmp(&got[i], &want[i], sizeof *got) != 0) ||
                      (dist && memcmp(&dist[i], &want[i].distance, sizeof *dist) != 0);
        if (d && diff == 0)
            fprintf(stderr, "  first difference at pair %zu: distance %.17g, CPU %.17g\n", i,
                    got ? got[i].distance : dist[i], want[i].distance);
        diff += (size_t)d;
    }
    return diff;
}

static size_t count_diff_f(size_t n, const ttd_result_f *want, const ttd_result_f *got, const float *dist)
{
    size_t diff = 0;
    for (size_t i = 0; i < n; ++i) {
        const int d = (got && memcmp(&got[i], &want[i], sizeof *got) != 0) ||
                      (dist && memcmp(&dist[i], &want[i].distance, sizeof *dist) != 0);
        if (d && diff == 0)
            fprintf(stderr, "  first difference at pair %zu: distance %.9g, CPU %.9g\n", i,
                    (double)(got ? got[i].distance : dist[i]), (double)want[i].distance);
        diff += (size_t)d;
    }
    return diff;
}

static int gpu_statuses(void)
{
    for (int s = TTD_GPU_OK; s <= TTD_GPU_ERR_CUDA; ++s) {
        const char *a = ttd_gpu_status_string((ttd_gpu_status)s);
        ENSURE(a && a[0]);
        for (int r = TTD_GPU_OK; r < s; ++r)
            ENSURE(strcmp(a, ttd_gpu_status_string((ttd_gpu_status)r)) != 0);
    }
    ENSURE(ttd_gpu_status_string((ttd_gpu_status)99) != NULL);
    ENSURE(ttd_gpu_query(NULL) == TTD_GPU_ERR_NULL_POINTER);
    ttd_gpu_info info;
    const ttd_gpu_status st = ttd_gpu_query(&info);
    ENSURE(st == TTD_GPU_OK || st == TTD_GPU_ERR_NOT_BUILT || st == TTD_GPU_ERR_NO_DEVICE);
    ENSURE((st == TTD_GPU_ERR_NOT_BUILT) == !info.built);
    ENSURE(st == TTD_GPU_OK ? info.device >= 0 && info.name[0] : info.message[0] != 0);
    printf("  %s\n", st == TTD_GPU_OK ? info.name : info.message);
    return 0;
}

/* The device source on the host: thread i's body (gpu_pair) for every i, against ttd_batch. */
static int gpu_source_on_host(void)
{
    double *s, *t;
    float *sf, *tf;
    const size_t n = pair_set(&s, &t, &sf, &tf);
    ttd_result_d *want = malloc(n * sizeof *want), *got = malloc(n * sizeof *got);
    ttd_result_f *want_f = malloc(n * sizeof *want_f), *got_f = malloc(n * sizeof *got_f);
    double *dist = malloc(n * sizeof *dist);
    float *dist_f = malloc(n * sizeof *dist_f);
    ENSURE(want && got && want_f && got_f && dist && dist_f);
    ttd_options opt = ttd_default_options();
    opt.isa = TTD_ISA_SCALAR;
    ENSURE(ttd_batch_d(&opt, n, s, t, NULL, want) == TTD_ERR_NONFINITE_INPUT);
    ENSURE(ttd_batch_f(&opt, n, sf, tf, NULL, want_f) == TTD_ERR_NONFINITE_INPUT);
    ttd_cuda_host_batch_d(n, s, t, NULL, got);
    ttd_cuda_host_batch_d(n, s, t, dist, NULL);
    ttd_cuda_host_batch_f(n, sf, tf, NULL, got_f);
    ttd_cuda_host_batch_f(n, sf, tf, dist_f, NULL);
    const size_t dd = count_diff_d(n, want, got, dist), df = count_diff_f(n, want_f, got_f, dist_f);
    printf("  %zu pairs (%d families, scaled, NaN/inf): differing from ttd_batch's bits: %zu double, %zu float\n", n,
           TTD_GEN_COUNT, dd, df);
    ENSURE(dd == 0 && df == 0);
    ENSURE(got[n - 1].flags == TTD_PAIR_NONFINITE && isnan(got[n - 1].distance));
    free(s);
    free(t);
    free(sf);
    free(tf);
    free(want);
    free(got);
    free(want_f);
    free(got_f);
    free(dist);
    free(dist_f);
    return 0;
}

/* Without a usable GPU the entry points say why, before touching any pointer. */
static int gpu_without_device(void)
{
    ttd_gpu_info info;
    const ttd_gpu_status st = ttd_gpu_query(&info);
    if (st == TTD_GPU_OK) {
        printf("  a GPU is usable: nothing to check here\n");
        return 0;
    }
    double s[9] = {0}, d[1];
    float sf[9] = {0}, df[1];
    const ttd_gpu_status bd = ttd_gpu_batch_d(1, s, s, d, NULL, NULL), bf = ttd_gpu_batch_f(1, sf, sf, df, NULL, NULL);
    if (st == TTD_GPU_ERR_NOT_BUILT) {
        ENSURE(bd == TTD_GPU_ERR_NOT_BUILT && bf == TTD_GPU_ERR_NOT_BUILT);
    } else {
        ENSURE(ttd_gpu_batch_d(1, NULL, s, d, NULL, NULL) == TTD_GPU_ERR_NULL_POINTER);
        ENSURE(ttd_gpu_batch_f(1, sf, sf, NULL, NULL, NULL) == TTD_GPU_ERR_NULL_POINTER);
        ENSURE(bd == TTD_GPU_ERR_NO_DEVICE && bf == TTD_GPU_ERR_NO_DEVICE);
    }
    printf("  skip the device tests: %s (%s)\n", ttd_gpu_status_string(st), info.message);
    return 0;
}

#ifdef TTD_TEST_CUDA
#define CU(x) ENSURE_MSG((x) == cudaSuccess, "%s", cudaGetErrorString(cudaGetLastError()))

static double seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* The pair set through ttd_gpu_batch_d/f on device memory, bit for bit against the CPU. */
static int gpu_device_bits(void)
{
    ttd_gpu_info info;
    if (ttd_gpu_query(&info) != TTD_GPU_OK) {
        printf("  skip: no usable GPU (%s)\n", info.message);
        return 0;
    }
    double *s, *t;
    float *sf, *tf;
    const size_t n = pair_set(&s, &t, &sf, &tf);
    ttd_result_d *want = malloc(n * sizeof *want), *got = malloc(n * sizeof *got);
    ttd_result_f *want_f = malloc(n * sizeof *want_f), *got_f = malloc(n * sizeof *got_f);
    double *dist = malloc(n * sizeof *dist);
    float *dist_f = malloc(n * sizeof *dist_f);
    ENSURE(want && got && want_f && got_f && dist && dist_f);
    ttd_options opt = ttd_default_options();
    ENSURE(ttd_batch_d(&opt, n, s, t, NULL, want) == TTD_ERR_NONFINITE_INPUT);
    ENSURE(ttd_batch_f(&opt, n, sf, tf, NULL, want_f) == TTD_ERR_NONFINITE_INPUT);
    double *ds, *dt, *dd;
    float *fs, *ft, *fd;
    ttd_result_d *dr;
    ttd_result_f *fr;
    CU(cudaMalloc((void **)&ds, 9 * n * sizeof *ds));
    CU(cudaMalloc((void **)&dt, 9 * n * sizeof *dt));
    CU(cudaMalloc((void **)&dd, n * sizeof *dd));
    CU(cudaMalloc((void **)&dr, n * sizeof *dr));
    CU(cudaMalloc((void **)&fs, 9 * n * sizeof *fs));
    CU(cudaMalloc((void **)&ft, 9 * n * sizeof *ft));
    CU(cudaMalloc((void **)&fd, n * sizeof *fd));
    CU(cudaMalloc((void **)&fr, n * sizeof *fr));
    CU(cudaMemcpy(ds, s, 9 * n * sizeof *ds, cudaMemcpyHostToDevice));
    CU(cudaMemcpy(dt, t, 9 * n * sizeof *dt, cudaMemcpyHostToDevice));
    CU(cudaMemcpy(fs, sf, 9 * n * sizeof *fs, cudaMemcpyHostToDevice));
    CU(cudaMemcpy(ft, tf, 9 * n * sizeof *ft, cudaMemcpyHostToDevice));
    /* full results (with distances), then distances alone */
    ENSURE(ttd_gpu_batch_d(n, ds, dt, NULL, dr, NULL) == TTD_GPU_OK);
    ENSURE(ttd_gpu_batch_f(n, fs, ft, NULL, fr, NULL) == TTD_GPU_OK);
    CU(cudaDeviceSynchronize());
    CU(cudaMemcpy(got, dr, n * sizeof *got, cudaMemcpyDeviceToHost));
    CU(cudaMemcpy(got_f, fr, n * sizeof *got_f, cudaMemcpyDeviceToHost));
    ENSURE(ttd_gpu_batch_d(n, ds, dt, dd, NULL, NULL) == TTD_GPU_OK);
    ENSURE(ttd_gpu_batch_f(n, fs, ft, fd, NULL, NULL) == TTD_GPU_OK);
    CU(cudaDeviceSynchronize());
    CU(cudaMemcpy(dist, dd, n * sizeof *dist, cudaMemcpyDeviceToHost));
    CU(cudaMemcpy(dist_f, fd, n * sizeof *dist_f, cudaMemcpyDeviceToHost));
    const size_t diff_d = count_diff_d(n, want, got, dist), diff_f = count_diff_f(n, want_f, got_f, dist_f);
    printf("  %s: %zu pairs, differing from the CPU's bits: %zu double, %zu float\n", info.name, n, diff_d, diff_f);
    /* the checks: host memory, NULL, n = 0 */
    ENSURE(ttd_gpu_batch_d(n, s, dt, dd, NULL, NULL) == TTD_GPU_ERR_NOT_DEVICE_MEMORY);
    ENSURE(ttd_gpu_batch_d(n, ds, dt, dist, NULL, NULL) == TTD_GPU_ERR_NOT_DEVICE_MEMORY);
    ENSURE(ttd_gpu_batch_f(n, fs, NULL, fd, NULL, NULL) == TTD_GPU_ERR_NULL_POINTER);
    ENSURE(ttd_gpu_batch_f(n, fs, ft, NULL, NULL, NULL) == TTD_GPU_ERR_NULL_POINTER);
    ENSURE(ttd_gpu_batch_d(0, ds, dt, dd, NULL, NULL) == TTD_GPU_OK);
    CU(cudaFree(ds));
    CU(cudaFree(dt));
    CU(cudaFree(dd));
    CU(cudaFree(dr));
    CU(cudaFree(fs));
    CU(cudaFree(ft));
    CU(cudaFree(fd));
    CU(cudaFree(fr));
    free(s);
    free(t);
    free(sf);
    free(tf);
    free(want);
    free(got);
    free(want_f);
    free(got_f);
    free(dist);
    free(dist_f);
    ENSURE(diff_d == 0 && diff_f == 0);
    return 0;
}

/* Device-resident random pairs, distances only: pairs per second on the GPU (best of 5), and
 * ttd_batch on every core of this machine for scale. Printed, not asserted (docs/gpu.md). */
static int gpu_device_throughput(void)
{
    ttd_gpu_info info;
    if (ttd_gpu_query(&info) != TTD_GPU_OK) {
        printf("  skip: no usable GPU (%s)\n", info.message);
        return 0;
    }
    const char *env = getenv("TTD_GPU_BENCH_PAIRS");
    const size_t n = env ? (size_t)strtoull(env, NULL, 10) : (size_t)1 << 22;
    double *s = malloc(9 * n * sizeof *s), *t = malloc(9 * n * sizeof *t), *dist = malloc(n * sizeof *dist);
    float *sf = malloc(9 * n * sizeof *sf), *tf = malloc(9 * n * sizeof *tf), *dist_f = malloc(n * sizeof *dist_f);
    ENSURE(s && t && dist && sf && tf && dist_f);
    ttd_gen(TTD_GEN_RANDOM, 1u, n, s, t);
    for (size_t i = 0; i < 9 * n; ++i) {
        sf[i] = (float)s[i];
        tf[i] = (float)t[i];
    }
    void *ds, *dt, *dd;
    CU(cudaMalloc(&ds, 9 * n * sizeof(double)));
    CU(cudaMalloc(&dt, 9 * n * sizeof(double)));
    CU(cudaMalloc(&dd, n * sizeof(double)));
    for (int prec = 0; prec < 2; ++prec) {
        const size_t rs = prec ? sizeof(float) : sizeof(double);
        CU(cudaMemcpy(ds, prec ? (const void *)sf : (const void *)s, 9 * n * rs, cudaMemcpyHostToDevice));
        CU(cudaMemcpy(dt, prec ? (const void *)tf : (const void *)t, 9 * n * rs, cudaMemcpyHostToDevice));
        cudaEvent_t a, b;
        CU(cudaEventCreate(&a));
        CU(cudaEventCreate(&b));
        float best = 1e30f;
        for (int rep = 0; rep < 6; ++rep) {
            CU(cudaEventRecord(a, NULL));
            const ttd_gpu_status st = prec ? ttd_gpu_batch_f(n, (const float *)ds, (const float *)dt, (float *)dd, NULL, NULL)
                                           : ttd_gpu_batch_d(n, (const double *)ds, (const double *)dt, (double *)dd, NULL, NULL);
            ENSURE(st == TTD_GPU_OK);
            CU(cudaEventRecord(b, NULL));
            CU(cudaEventSynchronize(b));
            float ms;
            CU(cudaEventElapsedTime(&ms, a, b));
            if (rep > 0 && ms < best) /* the first run loads the module */
                best = ms;
        }
        ttd_options opt = ttd_default_options();
        double cpu = 1e30;
        for (int rep = 0; rep < 3; ++rep) {
            const double t0 = seconds();
            ENSURE((prec ? ttd_batch_f(&opt, n, sf, tf, dist_f, NULL) : ttd_batch_d(&opt, n, s, t, dist, NULL)) == TTD_OK);
            const double el = seconds() - t0;
            cpu = el < cpu ? el : cpu;
        }
        printf("  %s, %s, %zu device-resident random pairs, distances: %.3g pairs/s (%.3f ms); ttd_batch on this "
               "machine's cores: %.3g pairs/s\n",
               info.name, prec ? "float" : "double", n, (double)n / (1e-3 * (double)best), (double)best,
               (double)n / cpu);
        CU(cudaEventDestroy(a));
        CU(cudaEventDestroy(b));
    }
    CU(cudaFree(ds));
    CU(cudaFree(dt));
    CU(cudaFree(dd));
    free(s);
    free(t);
    free(dist);
    free(sf);
    free(tf);
    free(dist_f);
    return 0;
}
#endif

int main(int argc, char **argv)
{
    TEST_MAIN_BEGIN(argc, argv);
    RUN_TEST(gpu_statuses);
    RUN_TEST(gpu_source_on_host);
    RUN_TEST(gpu_without_device);
#ifdef TTD_TEST_CUDA
    RUN_TEST(gpu_device_bits);
    RUN_TEST(gpu_device_throughput);
#else
    printf("  (built without CUDA: no device tests)\n");
#endif
    TEST_MAIN_END();
}

/* SPDX-License-Identifier: MIT */
/* The ISA rows this build has, and whether this CPU runs each, for the tests that call the
 * rows directly (test_isa_kernels.c, test_certified.c, test_lanes.c). Checked here with the
 * compiler's own CPU test, independently of the library's dispatcher. */
#ifndef TTD_TEST_ISA_ROWS_H
#define TTD_TEST_ISA_ROWS_H

#include <math.h>
#include <string.h>

#include "core/kernels.h"
#ifdef TTD_HAVE_CUDA_HOST
#include "cuda_host/cuda_host.h"
#endif

/* A row's kernel called as the batch engine calls it: distances and/or results, no bound. */
static inline void run_kernel_d(ttd_kernel_d_fn fn, size_t n, const double *s, const double *t,
                                const ttd_params *prm, double *distance, ttd_result_d *results)
{
    const ttd_out_d out = {distance, NULL, results};
    fn(n, s, t, prm, (double)INFINITY, &out);
}

static inline void run_kernel_f(ttd_kernel_f_fn fn, size_t n, const float *s, const float *t,
                                const ttd_params *prm, float *distance, ttd_result_f *results)
{
    const ttd_out_f out = {distance, NULL, results};
    fn(n, s, t, prm, INFINITY, &out);
}

/* Non-zero when this CPU runs isa; otherwise *why says what is missing. */
static inline int cpu_runs(const char *isa, const char **why)
{
#if defined(__x86_64__) || defined(__i386__)
    __builtin_cpu_init();
    if (!strcmp(isa, "sse2")) {
        *why = "no SSE2";
        return __builtin_cpu_supports("sse2");
    }
    if (!strcmp(isa, "avx2")) {
        *why = "no AVX2+FMA";
        return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
    }
    if (!strcmp(isa, "avx512")) {
        *why = "no AVX-512F/DQ/VL";
        return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq") &&
               __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx2") &&
               __builtin_cpu_supports("fma");
    }
#endif
#if defined(__aarch64__)
    if (!strcmp(isa, "neon"))
        return 1;
#endif
    if (!strcmp(isa, "portable")) /* baseline code of this target */
        return 1;
    if (!strcmp(isa, "cuda-host")) /* src/simd/lanes_cuda.h on the host: plain C */
        return 1;
    *why = "not this architecture";
    return 0;
}

/* Every SIMD row built in (TTD_HAVE_<ISA>), ended by a NULL name; and the test-only
 * "cuda-host" row (tests/cuda_host/: the CUDA lane vocabulary compiled for the host, one lane),
 * which the library's dispatcher does not have. */
typedef struct isa_row {
    const char *name;
    const ttd_kernels_d *d;
    const ttd_kernels_f *f;
} isa_row;

static const isa_row isa_rows[] = {
#ifdef TTD_HAVE_SSE2
    {"sse2", &ttd_kernels_sse2_d, &ttd_kernels_sse2_f},
#endif
#ifdef TTD_HAVE_AVX2
    {"avx2", &ttd_kernels_avx2_d, &ttd_kernels_avx2_f},
#endif
#ifdef TTD_HAVE_AVX512
    {"avx512", &ttd_kernels_avx512_d, &ttd_kernels_avx512_f},
#endif
#ifdef TTD_HAVE_NEON
    {"neon", &ttd_kernels_neon_d, &ttd_kernels_neon_f},
#endif
#ifdef TTD_HAVE_PORTABLE
    {"portable", &ttd_kernels_portable_d, &ttd_kernels_portable_f},
#endif
#ifdef TTD_HAVE_CUDA_HOST
    {"cuda-host", &ttd_kernels_cuda_host_d, &ttd_kernels_cuda_host_f},
#endif
    {NULL, NULL, NULL},
};

#endif /* TTD_TEST_ISA_ROWS_H */

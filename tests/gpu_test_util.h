/* SPDX-License-Identifier: MIT */
/* What the GPU tests (test_gpu*.c) share: a monotonic wall clock for their device timings and,
 * built with CUDA (TTD_TEST_CUDA), CU(x), which fails the current test with CUDA's last error
 * when a runtime call does not return cudaSuccess. The including file defines _POSIX_C_SOURCE
 * (clock_gettime) before its first include. */
#ifndef TTD_TESTS_GPU_TEST_UTIL_H
#define TTD_TESTS_GPU_TEST_UTIL_H

#include <time.h>

#include "test_macros.h"

#ifdef TTD_TEST_CUDA
#include <cuda_runtime.h>

#define CU(x) ENSURE_MSG((x) == cudaSuccess, "%s", cudaGetErrorString(cudaGetLastError()))
#endif

/* Seconds on the monotonic clock. */
static inline double seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

#endif /* TTD_TESTS_GPU_TEST_UTIL_H */

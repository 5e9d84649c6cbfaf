/* SPDX-License-Identifier: MIT */
/* The test-only "cuda-host" row (cuda_host_d.c, cuda_host_f.c): src/simd/lanes_cuda.h compiled
 * for the host, one lane. */
#ifndef TTD_TEST_CUDA_HOST_H
#define TTD_TEST_CUDA_HOST_H

#include "core/kernels.h"

extern const ttd_kernels_d ttd_kernels_cuda_host_d;
extern const ttd_kernels_f ttd_kernels_cuda_host_f;
int ttd_lanes_probe_cuda_host_d(int op, const double *a, const double *b, const double *c, double *out);
int ttd_lanes_probe_cuda_host_f(int op, const float *a, const float *b, const float *c, float *out);

#endif /* TTD_TEST_CUDA_HOST_H */

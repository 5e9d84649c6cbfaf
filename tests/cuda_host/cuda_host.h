/* SPDX-License-Identifier: MIT */
/* The test-only "cuda-host" row (cuda_host_d.c, cuda_host_f.c): src/simd/lanes_cuda.h compiled
 * for the host, one lane, and the GPU batch's per-thread body on it. */
#ifndef TTD_TEST_CUDA_HOST_H
#define TTD_TEST_CUDA_HOST_H

#include "core/kernels.h"

extern const ttd_kernels_d ttd_kernels_cuda_host_d;
extern const ttd_kernels_f ttd_kernels_cuda_host_f;
int ttd_lanes_probe_cuda_host_d(int op, const double *a, const double *b, const double *c, double *out);
int ttd_lanes_probe_cuda_host_f(int op, const float *a, const float *b, const float *c, float *out);
/* What the GPU batch (src/gpu/) runs, thread i for pair i, run here by a loop over i: the one
 * source (src/gpu/gpu_pair_impl.h) compiled for the host. */
void ttd_cuda_host_batch_d(size_t n, const double *s, const double *t, double *distance, ttd_result_d *results);
void ttd_cuda_host_batch_f(size_t n, const float *s, const float *t, float *distance, ttd_result_f *results);

#endif /* TTD_TEST_CUDA_HOST_H */

/* SPDX-License-Identifier: MIT */
/* Between the GPU library's translation units: the launchers of gpu_d.cu / gpu_f.cu, called by
 * gpu_api.cu after its checks. Each returns a cudaError_t as an int (0: launched). */
#ifndef TTD_GPU_INTERNAL_H
#define TTD_GPU_INTERNAL_H

#include <stddef.h>

#include "core/kernels.h"

#ifdef __cplusplus
extern "C" {
#endif

int ttd_gpu_launch_exact_d(size_t n, const double *s, const double *t, double *distance, ttd_result_d *results,
                           void *stream);
int ttd_gpu_launch_exact_f(size_t n, const float *s, const float *t, float *distance, ttd_result_f *results,
                           void *stream);
/* k node tests (query q[i] against node y[i]); lb2 and sep get 8k reals, child j of test i at 8i + j */
int ttd_gpu_launch_node_d(size_t k, const ttd_box_query_d *q, const ttd_node_d *y, double *lb2, double *sep,
                          void *stream);
int ttd_gpu_launch_node_f(size_t k, const ttd_box_query_f *q, const ttd_node_f *y, float *lb2, float *sep,
                          void *stream);

/* 0 (cudaSuccess) when the current device runs the kernels built here, else the cudaError_t of
 * cudaFuncGetAttributes on one of them (no kernel image for the device, no driver, ...) */
int ttd_gpu_kernel_loads(void);

/* registers a thread of the distance-only exact kernel (0 when they cannot be read), and the
 * launch configuration the kernels were built with */
int ttd_gpu_kernel_registers_d(void);
int ttd_gpu_kernel_registers_f(void);
int ttd_gpu_block_threads(void);
int ttd_gpu_min_blocks(void);

#ifdef __cplusplus
}
#endif

#endif /* TTD_GPU_INTERNAL_H */

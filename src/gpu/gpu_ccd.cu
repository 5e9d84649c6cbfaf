/* SPDX-License-Identifier: MIT */
/* Continuous collision of moving primitives on the device (issue 33; docs/ccd.md, section 14):
 * one query a CUDA thread, running what the CPU batch runs for it (src/ccd/ccd_batch_impl.h, over
 * the search ccd_search_impl.h and the exact expansions ccd_exact_impl.h: one source), so each
 * answer is the CPU's, bit for bit. Built with the GPU library's floating-point flags
 * (-fmad=false -prec-div=true -prec-sqrt=true -ftz=false: src/gpu/CMakeLists.txt), so each
 * operation rounds as on the CPU; the search's explicit fma() calls are exact products' errors. */
#include <stddef.h>
#include <stdint.h>

#include <cuda_runtime.h>

#include "ccd/ccd_batch_impl.h"
#include "gpu/gpu_internal.h"

#ifndef TTD_GPU_BLOCK
#define TTD_GPU_BLOCK 128
#endif

/* The queries of a pair kind (TTD_CCD_VF, TTD_CCD_EE) or of triangles (kind 3): one query a
 * thread, a grid-stride loop for grids past the launch limit. Two kernels, so that the pair
 * queries do not carry the triangles' 15 sub-queries in their stack frame. */
__global__ void __launch_bounds__(TTD_GPU_BLOCK) gpu_ccd_pair_kernel(int kind, int is_float, size_t n, const void *a0,
                                                                    const void *b0, const void *a1, const void *b1,
                                                                    double delta, ttd_ccd_result *out)
{
    const size_t stride = (size_t)gridDim.x * blockDim.x;
    for (size_t i = (size_t)blockIdx.x * blockDim.x + threadIdx.x; i < n; i += stride)
        ccdb_query_pair(kind, is_float, a0, b0, a1, b1, i, delta, &out[i]);
}

__global__ void __launch_bounds__(TTD_GPU_BLOCK) gpu_ccd_tri_kernel(int is_float, size_t n, const void *a0,
                                                                   const void *b0, const void *a1, const void *b1,
                                                                   double delta, ttd_ccd_result *out)
{
    const size_t stride = (size_t)gridDim.x * blockDim.x;
    for (size_t i = (size_t)blockIdx.x * blockDim.x + threadIdx.x; i < n; i += stride)
        ccdb_query_triangles(is_float, a0, b0, a1, b1, i, delta, &out[i]);
}

extern "C" int ttd_gpu_launch_ccd(int kind, int is_float, size_t n, const void *a0, const void *b0, const void *a1,
                                  const void *b1, double delta, ttd_ccd_result *out, void *stream)
{
    const size_t blocks = (n + TTD_GPU_BLOCK - 1) / TTD_GPU_BLOCK;
    const unsigned grid = blocks > 1u << 30 ? 1u << 30 : (unsigned)blocks; /* as gpu_grid */
    cudaStream_t st = (cudaStream_t)stream;
    if (kind == 3)
        gpu_ccd_tri_kernel<<<grid, TTD_GPU_BLOCK, 0, st>>>(is_float, n, a0, b0, a1, b1, delta, out);
    else
        gpu_ccd_pair_kernel<<<grid, TTD_GPU_BLOCK, 0, st>>>(kind, is_float, n, a0, b0, a1, b1, delta, out);
    return (int)cudaGetLastError();
}

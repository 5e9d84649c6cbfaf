/* SPDX-License-Identifier: MIT */
/* The "cuda-host" row in double, for the tests only: the lane-generic kernels compiled by the host C
 * compiler through the CUDA lane vocabulary (simd/lanes_cuda.h: one lane, a real per "vector", a
 * bool per mask), the same source that src/gpu/ compiles as device code with nvcc. CI has no GPU
 * and may have no nvcc; this row is how it tests that source (tests/isa_rows.h lists it, so
 * test_isa_kernels and test_lanes hold it to every other row's contract, and test_isa_kernels
 * requires the scalar row's bits of it). Not part of the library: the dispatcher never sees it. */
#define TTDW_USE_CUDA 1
#define TTD_PRECISION_DOUBLE
#include "simd/kernels_all.h"
#include "gpu/gpu_pair_impl.h"
#include "cuda_host.h"

const ttd_kernels_d ttd_kernels_cuda_host_d = TTD_LANE_ROW(TTD_ISA_SCALAR);

int ttd_lanes_probe_cuda_host_d(int op, const double *a, const double *b, const double *c, double *out)
{
    return lanes_probe(op, a, b, c, out);
}

void ttd_cuda_host_batch_d(size_t n, const double *s, const double *t, double *distance, ttd_result_d *results)
{
    for (size_t i = 0; i < n; ++i) /* what thread i of src/gpu/'s kernel runs */
        gpu_pair(i, s, t, distance, results);
}

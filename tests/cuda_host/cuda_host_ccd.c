/* SPDX-License-Identifier: MIT */
/* The device's continuous collision (src/gpu/gpu_ccd.cu) compiled for the host: what thread i of its
 * kernels runs for query i (ccd/ccd_batch_impl.h over the search and the exact expansions), run here
 * by a loop. test_gpu_ccd holds it to the CPU batch, bit for bit. */
#include "ccd/ccd_batch_impl.h"
#include "cuda_host.h"

void ttd_cuda_host_ccd(int kind, int is_float, size_t n, const void *a0, const void *b0, const void *a1,
                       const void *b1, double delta, ttd_ccd_result *out)
{
    for (size_t i = 0; i < n; ++i) /* what thread i of gpu_ccd.cu's kernels runs */
        ccdb_query(kind, is_float, a0, b0, a1, b1, i, delta, &out[i]);
}

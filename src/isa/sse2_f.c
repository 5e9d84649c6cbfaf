/* SPDX-License-Identifier: MIT */
/* The SSE2 row in float: the lane-generic kernels (src/simd/kernel_*.h) compiled with this
 * file's flags (src/CMakeLists.txt). Nothing here but the choice of lane header and precision
 * and the two exported names; the engine calls the row only when the CPU supports it. */
#define TTDW_USE_SSE2 1
#define TTD_PRECISION_FLOAT
#include "simd/kernels_all.h"

const ttd_kernels_f ttd_kernels_sse2_f = TTD_LANE_ROW(TTD_ISA_SSE2);

int ttd_lanes_probe_sse2_f(int op, const float *a, const float *b, const float *c, float *out)
{
    return lanes_probe(op, a, b, c, out);
}

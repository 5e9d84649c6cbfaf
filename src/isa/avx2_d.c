/* SPDX-License-Identifier: MIT */
/* The AVX2+FMA row in double: the lane-generic kernels (src/simd/kernel_*.h) compiled with this
 * file's flags (src/CMakeLists.txt). Nothing here but the choice of lane header and precision
 * and the two exported names; the engine calls the row only when the CPU supports it. */
#define TTDW_USE_AVX2 1
#define TTD_PRECISION_DOUBLE
#include "simd/kernels_all.h"

const ttd_kernels_d ttd_kernels_avx2_d = TTD_LANE_ROW(TTD_ISA_AVX2);

int ttd_lanes_probe_avx2_d(int op, const double *a, const double *b, const double *c, double *out)
{
    return lanes_probe(op, a, b, c, out);
}

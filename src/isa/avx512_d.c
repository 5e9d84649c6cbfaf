/* SPDX-License-Identifier: MIT */
/* The AVX-512F/DQ row in double: the lane-generic kernels (src/simd/kernel_*.h) compiled with this
 * file's flags (src/CMakeLists.txt). Nothing here but the choice of lane header and precision
 * and the two exported names; the engine calls the row only when the CPU supports it. */
#define TTDW_USE_AVX512 1
#define TTD_PRECISION_DOUBLE
#include "simd/kernels_all.h"

const ttd_kernels_d ttd_kernels_avx512_d = TTD_LANE_ROW(TTD_ISA_AVX512);

int ttd_lanes_probe_avx512_d(int op, const double *a, const double *b, const double *c, double *out)
{
    return lanes_probe(op, a, b, c, out);
}

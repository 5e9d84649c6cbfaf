/* SPDX-License-Identifier: MIT */
/* The portable row in double: the lane-generic kernels (src/simd/kernel_*.h) on GCC/clang vector
 * extensions (simd/lanes_portable.h), compiled with the baseline flags of any target. Nothing
 * here but the choice of lane header and precision and the two exported names. */
#define TTDW_USE_PORTABLE 1
#define TTD_PRECISION_DOUBLE
#include "simd/kernels_all.h"

const ttd_kernels_d ttd_kernels_portable_d = TTD_LANE_ROW(TTD_ISA_PORTABLE);

int ttd_lanes_probe_portable_d(int op, const double *a, const double *b, const double *c, double *out)
{
    return lanes_probe(op, a, b, c, out);
}

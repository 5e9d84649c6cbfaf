/* SPDX-License-Identifier: MIT */
/* The SSE2 (the x86-64 baseline) row: the lane-generic kernels (src/simd/kernel_*.h) compiled once per
 * precision with this file's flags (src/CMakeLists.txt). Nothing here but the choice of lane
 * header and the table row; the engine calls the row only when the CPU supports it. */
#define TTDW_USE_SSE2 1
#include "simd/lanes.h"

#define TTD_PRECISION_DOUBLE
#define TTD_PROBE_NAME ttd_lanes_probe_sse2_d
#include "simd/kernels_all.h"

#define TTD_PRECISION_FLOAT
#define TTD_PROBE_NAME ttd_lanes_probe_sse2_f
#include "simd/kernels_all.h"

const ttd_isa_kernels ttd_kernels_sse2 = TTD_ISA_ROW(TTD_ISA_SSE2);

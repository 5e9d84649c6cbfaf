/* SPDX-License-Identifier: MIT */
/* Every lane kernel and the lane probe for one precision. An ISA file (src/isa/<isa>.c)
 * includes simd/lanes.h once, then this file twice: with TTD_PRECISION_DOUBLE and
 * TTD_PROBE_NAME ttd_lanes_probe_<isa>_d, then the same for float. TTD_ISA_ROW(isa) then
 * builds the table row from the static kernels. */
#include "core/defaults.h"
#include "core/certified_tol.h"
#include "core/kernels.h"
#include "simd/probe.h"
#include <stdint.h>
#include "core/precision.h"
#include "simd/lanes_precision.h"

#include "simd/kernel_common.h"
#include "simd/kernel_penalty_ref.h"
#include "simd/kernel_penalty.h"
#include "simd/kernel_exact.h"
#include "simd/kernel_certified.h"
#include "simd/probe_impl.h"

#include "simd/lanes_precision_end.h"
#include "core/precision_end.h"
#undef TTD_PROBE_NAME

#ifndef TTD_ISA_ROW
/* Methods without a lane kernel here are NULL: the engine uses the scalar row for them. */
#define TTD_ISA_ROW(isa_enum)                                                                  \
    {                                                                                          \
        .isa = (isa_enum), .lanes_f = TTDW_LANES_F, .lanes_d = TTDW_LANES_D,                   \
        .d = {[TTD_METHOD_EXACT] = kernel_exact_d,                                             \
              [TTD_METHOD_PENALTY] = kernel_penalty_d,                                         \
              [TTD_METHOD_PENALTY_REFERENCE] = kernel_penalty_ref_d,                           \
              [TTD_METHOD_CERTIFIED] = kernel_certified_d},                                    \
        .f = {[TTD_METHOD_EXACT] = kernel_exact_f,                                             \
              [TTD_METHOD_PENALTY] = kernel_penalty_f,                                         \
              [TTD_METHOD_PENALTY_REFERENCE] = kernel_penalty_ref_f,                           \
              [TTD_METHOD_CERTIFIED] = kernel_certified_f},                                    \
    }
#endif

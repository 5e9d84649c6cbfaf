/* SPDX-License-Identifier: MIT */
/* Every lane kernel and the lane probe, for one instruction set and one precision. A row file
 * (src/isa/<isa>_d.c or <isa>_f.c) defines TTDW_USE_<ISA> and TTD_PRECISION_<DOUBLE|FLOAT>,
 * includes this file once, and then writes out its two exported names: the table row
 * ttd_kernels_<isa>_<p> = TTD_LANE_ROW(TTD_ISA_<ISA>) and the probe ttd_lanes_probe_<isa>_<p>,
 * a call of lanes_probe. */
#include <stdint.h>
#include <string.h>

#include "core/precision.h"
#include "core/certified_tol.h"
#include "core/defaults.h"
#include "core/kernels.h"
#include "core/point_layout.h"
#include "simd/lanes.h"
#include "simd/lanes_precision.h"
#include "simd/probe.h"

#include "simd/kernel_common.h"
#include "simd/kernel_penalty_ref.h"
#include "simd/kernel_penalty.h"
#include "simd/kernel_exact.h"
#include "simd/kernel_certified.h"
#include "simd/kernel_node.h"
#include "simd/kernel_point.h"
#include "simd/kernel_trifit.h"
#include "simd/kernel_selfscreen.h"
#include "simd/kernel_ccd.h"
#include "simd/kernel_tri_apart.h"
#include "simd/probe_impl.h"

/* Methods without a lane kernel (the barrier method) are NULL: the engine uses the scalar row
 * for them. */
#define TTD_LANE_ROW(isa_enum)                                                                 \
    {                                                                                          \
        .isa = (isa_enum), .lanes = TTDW_LANES,                                                \
        .fn = {[TTD_METHOD_EXACT] = kernel_exact,                                              \
               [TTD_METHOD_PENALTY] = kernel_penalty,                                          \
               [TTD_METHOD_PENALTY_REFERENCE] = kernel_penalty_ref,                            \
               [TTD_METHOD_CERTIFIED] = kernel_certified},                                     \
        .node_test = node_test, .node_within = node_within,                                    \
        TTD_LANE_ROW_POINT_NODE                                                                 \
        TTD_LANE_ROW_TRI_FIT                                                                    \
        TTD_LANE_ROW_SELF_SCREEN                                                                \
        TTD_LANE_ROW_CCD_SCREEN                                                                 \
        TTD_LANE_ROW_TRI_APART                                                                  \
        .point_block = point_block, .point_lanes = point_lanes,                                \
    }
#ifdef TTD_PRECISION_DOUBLE
#define TTD_LANE_ROW_POINT_NODE
#else
#define TTD_LANE_ROW_POINT_NODE .point_node = point_node, .ray_node = ray_node,
#endif

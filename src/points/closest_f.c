/* SPDX-License-Identifier: MIT */
/* The closest-point query in float: points/closest_impl.h compiled for this precision, and its
 * entry (points/points.h) written out. */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define TTD_PRECISION_FLOAT
#include "core/precision.h"
#include "core/point_layout.h"
#include "engine/dispatch.h"
#include "engine/parallel.h"
#include "points/points.h"
#include "scalar/scalar.h"

typedef ttd_point_result_f ttd_point_result;
#define TTD_ROW ttd_kernels_f
#define TTD_DISPATCH_ROW ttd_dispatch_row_f
#define POINT_REBUILD ttd_point_rebuild_f
#define TTD_NEXTUP(x) nextafterf(x, INFINITY)
#include "points/closest_impl.h"

ttd_status ttd_points_query_closest_f(const ttd_engine_config *cfg, const struct ttd_mesh *mesh, size_t n,
                                      const float *points, float upper_bound, ttd_point_result_f *results)
{
    return closest_run(cfg, mesh, n, points, upper_bound, results);
}

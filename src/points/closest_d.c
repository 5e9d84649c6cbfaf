/* SPDX-License-Identifier: MIT */
/* The closest-point query in double: points/closest_impl.h compiled for this precision, and its
 * entry (points/points.h) written out. */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define TTD_PRECISION_DOUBLE
#include "core/precision.h"
#include "core/point_layout.h"
#include "engine/dispatch.h"
#include "engine/parallel.h"
#include "points/points.h"
#include "scalar/scalar.h"

typedef ttd_point_result_d ttd_point_result;
#define TTD_ROW ttd_kernels_d
#define TTD_DISPATCH_ROW ttd_dispatch_row_d
#define POINT_REBUILD ttd_point_rebuild_d
#define TTD_NEXTUP(x) nextafter(x, INFINITY)
#include "points/closest_impl.h"

ttd_status ttd_points_query_closest_d(const ttd_engine_config *cfg, const struct ttd_mesh *mesh, size_t n,
                                      const double *points, double upper_bound, ttd_point_result_d *results)
{
    return closest_run(cfg, mesh, n, points, upper_bound, results);
}

/* SPDX-License-Identifier: MIT */
/* ttd_exact_pair_d: the exact method in double (the code is precision-generic, in
 * exact_impl.h; the method and its accuracy argument in docs/exact-method.md). */
#define TTD_PRECISION_DOUBLE
#include "core/precision.h"
#include "scalar/scalar.h"
#include "scalar/exact_impl.h"
#include "scalar/point_impl.h"

void ttd_exact_pair_d(const double s[9], const double t[9], ttd_result_d *r)
{
    exact_pair(s, t, r);
}

void ttd_exact_pair_dups_d(const double s[9], const double t[9], ttd_result_d *r)
{
    exact_pair_dups(s, t, r);
}

double ttd_exact_lower_bound_d(const double s[9], const double t[9])
{
    return exact_lower_bound(s, t);
}

void ttd_point_prepare_d(const double v[9], double *f, size_t stride)
{
    point_prepare(v, f, stride);
}

double ttd_point_eval_d(const double *f, size_t stride, const double p[3], double q[3], double w[3])
{
    return point_eval(f, stride, p, q, w);
}

void ttd_point_rebuild_d(const double *f, size_t stride, int id, double u, double v, double q[3], double w[3])
{
    point_rebuild(f, stride, id, u, v, q, w);
}

void ttd_point_lanes_scalar_d(const double *f, const double P[3][TTD_NODE_WIDTH], double d[TTD_NODE_WIDTH],
                               double q[3][TTD_NODE_WIDTH], double w[3][TTD_NODE_WIDTH])
{
    point_lanes_scalar(f, P, d, q, w);
}

void ttd_point_block_scalar_d(const double p[3], const double *block, double d[TTD_NODE_WIDTH],
                                double par[3][TTD_NODE_WIDTH])
{
    point_block_scalar(p, block, d, par);
}

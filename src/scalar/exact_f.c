/* SPDX-License-Identifier: MIT */
/* ttd_exact_pair_f: the exact method in float (the code is precision-generic, in
 * exact_impl.h; the method and its accuracy argument in docs/exact-method.md). */
#define TTD_PRECISION_FLOAT
#include "core/precision.h"
#include "scalar/scalar.h"
#include "scalar/exact_impl.h"
#include "scalar/point_impl.h"

void ttd_exact_pair_f(const float s[9], const float t[9], ttd_result_f *r)
{
    exact_pair(s, t, r);
}

void ttd_exact_pair_dups_f(const float s[9], const float t[9], ttd_result_f *r)
{
    exact_pair_dups(s, t, r);
}

float ttd_exact_lower_bound_f(const float s[9], const float t[9])
{
    return exact_lower_bound(s, t);
}

void ttd_point_prepare_f(const float v[9], float *f, size_t stride)
{
    point_prepare(v, f, stride);
}

float ttd_point_eval_f(const float *f, size_t stride, const float p[3], float q[3], float w[3])
{
    return point_eval(f, stride, p, q, w);
}

void ttd_point_rebuild_f(const float *f, size_t stride, int id, float u, float v, float q[3], float w[3])
{
    point_rebuild(f, stride, id, u, v, q, w);
}

void ttd_point_lanes_scalar_f(const float *f, const float P[3][TTD_NODE_WIDTH], float d[TTD_NODE_WIDTH],
                               float q[3][TTD_NODE_WIDTH], float w[3][TTD_NODE_WIDTH])
{
    point_lanes_scalar(f, P, d, q, w);
}

void ttd_point_block_scalar_f(const float p[3], const float *block, float d[TTD_NODE_WIDTH],
                                float par[3][TTD_NODE_WIDTH])
{
    point_block_scalar(p, block, d, par);
}

unsigned ttd_ray_node_scalar(const float lo[3], const float hi[3], int k, int sigma, const ttd_rnode *y)
{
    return ray_node_scalar(lo, hi, k, sigma, y);
}

unsigned ttd_point_node_scalar(const float p[3], const ttd_pnode *y, float lim2, float lb2[TTD_NODE_WIDTH])
{
    return point_node_scalar(p, y, lim2, lb2);
}

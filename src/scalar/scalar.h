/* SPDX-License-Identifier: MIT */
/* The scalar reference methods, one pair at a time, plain C. Every SIMD kernel is tested
 * against these, and these against independent references (tests/). s and t are 9
 * coordinates each; r receives every field of the result (flags only from the kernel set
 * listed in core/kernels.h). Inputs must be finite; any magnitude is fine. */
#ifndef TTD_SCALAR_SCALAR_H
#define TTD_SCALAR_SCALAR_H

#include "core/kernels.h"

void ttd_exact_pair_d(const double s[9], const double t[9], ttd_result_d *r);
void ttd_exact_pair_f(const float s[9], const float t[9], ttd_result_f *r);
/* The same, every bit, with the candidates that cannot win left out: cheaper where a triangle
 * repeats a vertex (a point or a segment asked as a triangle, as the scene's manifold asks). */
void ttd_exact_pair_dups_d(const double s[9], const double t[9], ttd_result_d *r);
void ttd_exact_pair_dups_f(const float s[9], const float t[9], ttd_result_f *r);

/* A lower bound on the pair's distance (or -inf), cheap next to the exact method: what the exact
 * kernels rule pairs out with when the caller gives a bound (core/kernels.h; exact_impl.h). */
double ttd_exact_lower_bound_d(const double s[9], const double t[9]);
float ttd_exact_lower_bound_f(const float s[9], const float t[9]);

void ttd_penalty_pair_d(const double s[9], const double t[9], const ttd_params *prm, ttd_result_d *r);
void ttd_penalty_pair_f(const float s[9], const float t[9], const ttd_params *prm, ttd_result_f *r);

void ttd_penalty_ref_pair_d(const double s[9], const double t[9], const ttd_params *prm, ttd_result_d *r);
void ttd_penalty_ref_pair_f(const float s[9], const float t[9], const ttd_params *prm, ttd_result_f *r);

void ttd_barrier_pair_d(const double s[9], const double t[9], const ttd_params *prm, ttd_result_d *r);
void ttd_barrier_pair_f(const float s[9], const float t[9], const ttd_params *prm, ttd_result_f *r);

/* The certified mode: the penalty iterations, then the exact solution on the final active
 * set, checked for optimality; a pair that fails the check is computed by ttd_exact_pair_d/f and
 * flagged TTD_PAIR_FALLBACK (docs/certified-mode.md). */
void ttd_certified_pair_d(const double s[9], const double t[9], const ttd_params *prm, ttd_result_d *r);
void ttd_certified_pair_f(const float s[9], const float t[9], const ttd_params *prm, ttd_result_f *r);

/* The mesh queries' node test, one child at a time (core/kernels.h). */
void ttd_node_test_scalar_d(const ttd_box_query_d *x, const ttd_node_d *y, double lb2[TTD_NODE_WIDTH],
                            double sep[TTD_NODE_WIDTH]);
void ttd_node_test_scalar_f(const ttd_box_query_f *x, const ttd_node_f *y, float lb2[TTD_NODE_WIDTH],
                            float sep[TTD_NODE_WIDTH]);
unsigned ttd_node_within_scalar_d(const ttd_box_query_d *x, const ttd_node_d *y, double lim2, double lb2[TTD_NODE_WIDTH],
                              double sep[TTD_NODE_WIDTH]);
unsigned ttd_node_within_scalar_f(const ttd_box_query_f *x, const ttd_node_f *y, float lim2, float lb2[TTD_NODE_WIDTH],
                              float sep[TTD_NODE_WIDTH]);

/* The exact distance from a point to a triangle (scalar/point_impl.h, the point queries'
 * reference): the triangle v (9 reals) prepared once into f (core/point_layout.h's fields, field i
 * at f[i * stride]), then any number of points measured against it; q and w, when not NULL, get
 * the closest point and its weights. */
void ttd_point_prepare_d(const double v[9], double *f, size_t stride);
void ttd_point_prepare_f(const float v[9], float *f, size_t stride);
double ttd_point_eval_d(const double *f, size_t stride, const double p[3], double q[3], double w[3]);
float ttd_point_eval_f(const float *f, size_t stride, const float p[3], float q[3], float w[3]);
/* The closest point and weights of candidate (id, u, v) of a prepared triangle, as the point
 * kernels return it (core/kernels.h). */
void ttd_point_rebuild_d(const double *f, size_t stride, int id, double u, double v, double q[3], double w[3]);
void ttd_point_rebuild_f(const float *f, size_t stride, int id, float u, float v, float q[3], float w[3]);
/* The scalar row's point kernels (core/kernels.h). */
void ttd_point_lanes_scalar_d(const double *f, const double P[3][TTD_NODE_WIDTH], double d[TTD_NODE_WIDTH],
                               double q[3][TTD_NODE_WIDTH], double w[3][TTD_NODE_WIDTH]);
void ttd_point_block_scalar_d(const double p[3], const double *block, double d[TTD_NODE_WIDTH],
                              double par[3][TTD_NODE_WIDTH]);
void ttd_point_lanes_scalar_f(const float *f, const float P[3][TTD_NODE_WIDTH], float d[TTD_NODE_WIDTH],
                               float q[3][TTD_NODE_WIDTH], float w[3][TTD_NODE_WIDTH]);
void ttd_point_block_scalar_f(const float p[3], const float *block, float d[TTD_NODE_WIDTH], float par[3][TTD_NODE_WIDTH]);
struct ttd_pnode;
struct ttd_rnode;
unsigned ttd_ray_node_scalar(const float lo[3], const float hi[3], int k, int sigma, const struct ttd_rnode *y);
unsigned ttd_point_node_scalar(const float p[3], const struct ttd_pnode *y, float lim2, float lb2[TTD_NODE_WIDTH]);

/* Precision-generic code (the scalar _impl.h files, one precision per translation unit) calls the other
 * methods of its own precision by these names. */
#if defined(TTD_PRECISION_DOUBLE)
#define scalar_exact_pair ttd_exact_pair_d
#define scalar_penalty_pair ttd_penalty_pair_d
#elif defined(TTD_PRECISION_FLOAT)
#define scalar_exact_pair ttd_exact_pair_f
#define scalar_penalty_pair ttd_penalty_pair_f
#endif

#endif /* TTD_SCALAR_SCALAR_H */

/* SPDX-License-Identifier: MIT */
/* The scalar ISA row: each kernel is a loop over the per-pair functions of scalar/scalar.h.
 * It is the reference every SIMD row is tested against, and the fallback for entries an ISA
 * does not provide. */
#include <float.h>
#include <math.h>

#include "scalar/scalar.h"

/* One loop per (method, precision). The per-pair functions fill a whole result; the loop
 * copies out what the engine asked for. */
#define TTD_SCALAR_LOOP(name, real, result, out_t, call)                                      \
    static void name(size_t n, const real *s, const real *t, const ttd_params *prm, real bound, \
                     const out_t *out)                                                        \
    {                                                                                         \
        (void)prm;                                                                            \
        (void)bound; /* used by the exact method's call only */                              \
        for (size_t i = 0; i < n; ++i) {                                                      \
            result r;                                                                         \
            call;                                                                             \
            if (out->distance)                                                                \
                out->distance[i] = r.distance;                                                \
            if (out->points)                                                                  \
                for (int k = 0; k < 3; ++k) {                                                 \
                    out->points[6 * i + k] = r.p[k];                                          \
                    out->points[6 * i + 3 + k] = r.q[k];                                      \
                }                                                                             \
            if (out->results)                                                                 \
                out->results[i] = r;                                                          \
        }                                                                                     \
    }

/* The exact method with the caller's bound used: a pair whose lower bound exceeds a finite
 * bound gets that bound (at least 0) as its distance, NaN points and weights and no flags,
 * as from the lane rows (simd/kernel_exact.h, the same lower bound to the bit). */
#define TTD_SCALAR_EXACT(name, real, result, bound_fn, pair_fn, REAL_MAX_)                     \
    static void name##_pair(const real *s, const real *t, real bound, result *r)               \
    {                                                                                         \
        const real lb = bound < REAL_MAX_ ? bound_fn(s, t) : (real)0;                         \
        if (!(bound < REAL_MAX_ && lb > bound)) {                                             \
            pair_fn(s, t, r);                                                                 \
            return;                                                                           \
        }                                                                                     \
        const real nan = (real)NAN;                                                           \
        r->distance = lb > 0 ? lb : (real)0;                                                  \
        for (int k = 0; k < 3; ++k)                                                           \
            r->p[k] = r->q[k] = r->bary_p[k] = r->bary_q[k] = nan;                            \
        r->flags = 0;                                                                         \
        r->feature_p = r->feature_q = 0;                                                      \
        r->iterations = 0;                                                                    \
    }

TTD_SCALAR_EXACT(ttd_scalar_exact_d, double, ttd_result_d, ttd_exact_lower_bound_d, ttd_exact_pair_d, DBL_MAX)
TTD_SCALAR_EXACT(ttd_scalar_exact_f, float, ttd_result_f, ttd_exact_lower_bound_f, ttd_exact_pair_f, FLT_MAX)
TTD_SCALAR_LOOP(ttd_scalar_exact_d, double, ttd_result_d, ttd_out_d, ttd_scalar_exact_d_pair(s + 9 * i, t + 9 * i, bound, &r))
TTD_SCALAR_LOOP(ttd_scalar_exact_f, float, ttd_result_f, ttd_out_f, ttd_scalar_exact_f_pair(s + 9 * i, t + 9 * i, bound, &r))
TTD_SCALAR_LOOP(ttd_scalar_penalty_d, double, ttd_result_d, ttd_out_d, ttd_penalty_pair_d(s + 9 * i, t + 9 * i, prm, &r))
TTD_SCALAR_LOOP(ttd_scalar_penalty_f, float, ttd_result_f, ttd_out_f, ttd_penalty_pair_f(s + 9 * i, t + 9 * i, prm, &r))
TTD_SCALAR_LOOP(ttd_scalar_penalty_ref_d, double, ttd_result_d, ttd_out_d, ttd_penalty_ref_pair_d(s + 9 * i, t + 9 * i, prm, &r))
TTD_SCALAR_LOOP(ttd_scalar_penalty_ref_f, float, ttd_result_f, ttd_out_f, ttd_penalty_ref_pair_f(s + 9 * i, t + 9 * i, prm, &r))
TTD_SCALAR_LOOP(ttd_scalar_barrier_d, double, ttd_result_d, ttd_out_d, ttd_barrier_pair_d(s + 9 * i, t + 9 * i, prm, &r))
TTD_SCALAR_LOOP(ttd_scalar_barrier_f, float, ttd_result_f, ttd_out_f, ttd_barrier_pair_f(s + 9 * i, t + 9 * i, prm, &r))
TTD_SCALAR_LOOP(ttd_scalar_certified_d, double, ttd_result_d, ttd_out_d, ttd_certified_pair_d(s + 9 * i, t + 9 * i, prm, &r))
TTD_SCALAR_LOOP(ttd_scalar_certified_f, float, ttd_result_f, ttd_out_f, ttd_certified_pair_f(s + 9 * i, t + 9 * i, prm, &r))

const ttd_kernels_d ttd_kernels_scalar_d = {
    .isa = TTD_ISA_SCALAR,
    .lanes = 1,
    .fn = {[TTD_METHOD_EXACT] = ttd_scalar_exact_d,
           [TTD_METHOD_PENALTY] = ttd_scalar_penalty_d,
           [TTD_METHOD_PENALTY_REFERENCE] = ttd_scalar_penalty_ref_d,
           [TTD_METHOD_BARRIER] = ttd_scalar_barrier_d,
           [TTD_METHOD_CERTIFIED] = ttd_scalar_certified_d},
    .node_test = ttd_node_test_scalar_d,
    .node_within = ttd_node_within_scalar_d,
    .point_block = ttd_point_block_scalar_d,
    .point_lanes = ttd_point_lanes_scalar_d,
};

const ttd_kernels_f ttd_kernels_scalar_f = {
    .isa = TTD_ISA_SCALAR,
    .lanes = 1,
    .fn = {[TTD_METHOD_EXACT] = ttd_scalar_exact_f,
           [TTD_METHOD_PENALTY] = ttd_scalar_penalty_f,
           [TTD_METHOD_PENALTY_REFERENCE] = ttd_scalar_penalty_ref_f,
           [TTD_METHOD_BARRIER] = ttd_scalar_barrier_f,
           [TTD_METHOD_CERTIFIED] = ttd_scalar_certified_f},
    .node_test = ttd_node_test_scalar_f,
    .node_within = ttd_node_within_scalar_f,
    .point_node = ttd_point_node_scalar,
    .ray_node = ttd_ray_node_scalar,
    .point_block = ttd_point_block_scalar_f,
    .point_lanes = ttd_point_lanes_scalar_f,
};

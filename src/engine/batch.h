/* SPDX-License-Identifier: MIT */
/* The batch engine: splits n pairs into blocks of TTD_BLOCK_PAIRS and sends each block from a
 * pair source (the caller's arrays, or indexed meshes) through the block runner (runner.h) to
 * the caller's outputs, on the worker threads (parallel.h); keeps NaN/inf away from the
 * kernels. The public entry points (src/api/) check the arguments and options and then call
 * these. The code is engine/batch_impl.h. */
#ifndef TTD_ENGINE_BATCH_H
#define TTD_ENGINE_BATCH_H

#include <stdint.h>
#include "core/kernels.h"

/// What a batch runs, resolved from ttd_options by the API.
typedef struct ttd_engine_config {
    ttd_isa isa;                ///< the chosen instruction set, built and supported
    ttd_method method;
    ttd_params params;
    int threads;                ///< 0 = every online core
} ttd_engine_config;

/// One indexed mesh: nv vertices (3 coordinates each), nt triangles (3 vertex indices each).
typedef struct ttd_mesh_d {
    const double *verts;
    size_t nv;
    const uint32_t *tris;
    size_t nt;
} ttd_mesh_d;

/// ttd_mesh_d in single precision.
typedef struct ttd_mesh_f {
    const float *verts;
    size_t nv;
    const uint32_t *tris;
    size_t nt;
} ttd_mesh_f;

/// n > 0 pairs, pointers checked by the caller (distance or results may be NULL, not both).
/// Returns TTD_OK, TTD_WARN_NOT_CONVERGED, TTD_ERR_NONFINITE_INPUT (when both happen) or
/// TTD_ERR_OUT_OF_MEMORY.
ttd_status ttd_engine_batch_d(const ttd_engine_config *cfg, size_t n, const double *s,
                              const double *t, double *distance, ttd_result_d *results);
ttd_status ttd_engine_batch_f(const ttd_engine_config *cfg, size_t n, const float *s,
                              const float *t, float *distance, ttd_result_f *results);

/// The mesh entry: first checks every index (TTD_ERR_INDEX_OUT_OF_RANGE, nothing written),
/// then gathers each block's triangles into per-worker scratch and runs the same kernels.
ttd_status ttd_engine_mesh_d(const ttd_engine_config *cfg, const ttd_mesh_d *m1,
                             const ttd_mesh_d *m2, size_t n, const uint32_t *pairs,
                             double *distance, ttd_result_d *results);
ttd_status ttd_engine_mesh_f(const ttd_engine_config *cfg, const ttd_mesh_f *m1,
                             const ttd_mesh_f *m2, size_t n, const uint32_t *pairs,
                             float *distance, ttd_result_f *results);

#endif /* TTD_ENGINE_BATCH_H */

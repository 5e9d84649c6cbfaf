/* SPDX-License-Identifier: MIT */
/* The checks every public entry makes before it computes (api.c), shared by the pair entries
 * (api.c), the mesh entries (mesh_api.c) and the scene entries (scene_api.c), so that both answer bad input the same way and in
 * the same order. */
#ifndef TTD_API_PREPARE_H
#define TTD_API_PREPARE_H

#include <stddef.h>

#include "engine/batch.h"

/// Non-zero when count elements of per x size bytes cannot exist in one object.
int ttd_too_large(size_t count, size_t per, size_t size);

/// The checks, in this order: pointers (TTD_ERR_NULL_POINTER), options (TTD_ERR_BAD_OPTIONS),
/// n == 0 (TTD_ERR_EMPTY), sizes (TTD_ERR_TOO_LARGE), the instruction set
/// (TTD_ERR_ISA_UNAVAILABLE). The caller says whether its pointers are there and whether its
/// arrays could exist; on TTD_OK, cfg is ready for the engine.
ttd_status ttd_prepare(const ttd_options *opt, int pointers_ok, size_t n, int too_large, ttd_engine_config *cfg);

struct ttd_mesh;
/// The pose checks of every mesh and scene query (mesh_api.c): each of k poses (12 reals of bytes
/// each) finite, R^T R - I within TTD_POSE_TOLERANCE, det R > 0 (TTD_ERR_BAD_POSE), and b moved
/// by it within the coordinate range (TTD_ERR_COORDINATE_RANGE). Fills defects[i] (when not NULL)
/// with max |R^T R - I|; on a refused pose, *bad is its index.
ttd_status ttd_check_poses(const struct ttd_mesh *b, size_t k, const void *poses, int bytes, double *defects,
                           size_t *bad);

struct ttd_scene;
/// The checks of every scene query (scene_api.c): pointers, options (the exact method), the
/// precision, the margin or bound (>= 0; +inf only where inf_ok); then the bodies whose meshes
/// moved get their poses checked and boxes recomputed.
ttd_status ttd_scene_query_prepare(const ttd_options *opt, struct ttd_scene *s, int out_ok, int bytes, double limit,
                                   int inf_ok, ttd_engine_config *cfg);

#endif /* TTD_API_PREPARE_H */

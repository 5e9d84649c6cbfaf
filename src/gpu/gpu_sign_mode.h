/* SPDX-License-Identifier: MIT */
/* How the device decides the side of a point for a mesh (gpu_signed_impl.h), chosen on the host
 * from what the CPU already knows of the mesh: read by the upload (gpu_mesh.c) and by the host
 * build of the device code (tests/cuda_host/), so both choose alike. C only (reads
 * mesh/mesh.h's and points/points.h's structs). */
#ifndef TTD_GPU_SIGN_MODE_H
#define TTD_GPU_SIGN_MODE_H

#include "mesh/mesh.h"
#include "points/points.h"

enum {
    /* the side cannot be decided on the device as the CPU decides it: no point data, closedness
     * not known yet, or an open mesh whose caps are not known or have triangles (its winding
     * number is then a sum of solid angles through atan2, whose last bits differ between
     * glibc and CUDA: docs/gpu.md, section 6); the entry refuses the mesh */
    TTD_GPU_SIGN_NONE = 0,
    /* one triangle: no point is inside, the distance is unsigned (api/points_api.c) */
    TTD_GPU_SIGN_UNSIGNED = 1,
    /* the exact ray count decides (points/ray_impl.h): a closed mesh, or an open one whose
     * boundary cancels by coordinates (its caps have no triangle: the count is its winding number) */
    TTD_GPU_SIGN_RAY = 2
};

static inline int ttd_gpu_sign_mode(const struct ttd_mesh *m, const ttd_points_data *pd)
{
    if (pd == NULL)
        return TTD_GPU_SIGN_NONE;
    if (m->nt == 1)
        return TTD_GPU_SIGN_UNSIGNED;
    /* mesh/solid.c's cache: 0 not known yet, 1 closed, 2 not */
    const int closed = __atomic_load_n((const int *)&m->closed, __ATOMIC_ACQUIRE);
    if (closed == 1)
        return TTD_GPU_SIGN_RAY;
    if (closed == 2) {
        const ttd_points_caps *c = __atomic_load_n((ttd_points_caps *const *)&pd->caps, __ATOMIC_ACQUIRE);
        if (c != NULL && c->ntri == 0)
            return TTD_GPU_SIGN_RAY;
    }
    return TTD_GPU_SIGN_NONE;
}

#endif /* TTD_GPU_SIGN_MODE_H */

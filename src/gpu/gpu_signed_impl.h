/* SPDX-License-Identifier: MIT */
/* The signed distance of a point to a mesh, what one CUDA thread runs for it, from one source
 * with the host (tests/cuda_host/): the closest point of gpu_points_impl.h, then the side as
 * the CPU decides it (api/points_api.c's signed distance, points/winding.c's
 * ttd_points_winding_value): for a mesh of one triangle none (unsigned); for a closed mesh, or an
 * open one whose caps have no triangle, the exact ray count of points/ray_impl.h, the CPU's own
 * source, inside where |count| >= 1/2 (ttd_winding_inside). The mode is chosen on the host
 * (gpu_sign_mode.h); other meshes are refused by the entry. Where the count cannot be made exact
 * (products below the subnormal range, or the walk's stack of RAY_STACK nodes full) the CPU goes
 * on with the hierarchical winding number, which the device does not have: that point alone is
 * refused (TTD_GPU_POINT_SIDE_REFUSED in its flags, signed distance NaN), as a pose the CPU would
 * refuse is (gpu_walk_impl.h).
 *
 * Included after gpu_points_impl.h for one precision; every function TTDW_FN. */

/* The float rows' ray_node on one lane: comparisons only, so every row's mask (kernel_point.h). */
TTDW_FN unsigned gs_ray_node(const float lo[3], const float hi[3], int k, int sigma, const ttd_rnode *y)
{
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    unsigned hit = 0;
    for (int s = 0; s < TTD_NODE_WIDTH; ++s) {
        const int across = (y->lo[i][s] <= hi[i]) & (y->hi[i][s] >= lo[i]) & (y->lo[j][s] <= hi[j]) & (y->hi[j][s] >= lo[j]);
        const int ahead = sigma > 0 ? y->hi[k][s] >= lo[k] : y->lo[k][s] <= hi[k];
        hit |= (unsigned)(across & ahead) << s;
    }
    return hit;
}

#ifndef TTD_RAY_NODE
#define TTD_RAY_NODE(fn, lo, hi, k, sigma, y) ((void)(fn), gs_ray_node(lo, hi, k, sigma, y))
#define TTD_RAY_NODE_ARG int
#endif
#include "points/ray_impl.h"

/* The modes of gpu_sign_mode.h (repeated here: the device side never includes the library's
 * mesh headers). */
#define GS_UNSIGNED 1
#define GS_RAY 2

/* The point's side bit in ttd_gpu.h (TTD_GPU_POINT_SIDE_REFUSED). */
#define GS_SIDE_REFUSED 0x80u

typedef struct gs_mesh {
    gp_mesh closest;  /* the closest point's view (gpu_points_impl.h) */
    ttd_ray_mesh ray; /* the ray count's (points/ray_impl.h) */
    int mode;         /* GS_UNSIGNED or GS_RAY */
} gs_mesh;

/* The signed distance of P (the mesh's frame) within ub into *distance (when not NULL) and the
 * closest point with TTD_POINT_INSIDE for a point inside into *r: api/points_api.c's signed_##sfx
 * for one point. */
TTDW_FN void gs_signed(const gs_mesh *m, const real P[3], real ub, real *distance, gp_point_result *r)
{
    gp_closest(&m->closest, P, ub, r);
    real d = r->distance;
    if (m->mode == GS_RAY && !(r->flags & TTD_POINT_NONFINITE)) {
        const double x[3] = {(double)P[0], (double)P[1], (double)P[2]};
        int w = 0;
        if (ttd_ray_winding(&m->ray, 0, x, &w) != 0) {
            r->flags |= GS_SIDE_REFUSED;
            d = (real)NAN;
        } else if (fabs((double)w) >= 0.5) { /* ttd_winding_inside: |w| >= 1/2 */
            r->flags |= TTD_POINT_INSIDE;
            d = -d;
        }
    }
    if (distance)
        *distance = d;
}

/* SPDX-License-Identifier: MIT */
/* The exact winding number of a closed mesh about a point (points/points.h; docs/points.md,
 * section 5): the signed count of the triangles an axis-aligned ray from the point crosses.
 *
 * For a closed mesh (every directed edge (u, v) of a triangle appears once and (v, u) once: a
 * chain without boundary) the winding number about x is an integer, constant off the surface, and
 * it changes by the orientation of the surface wherever a path crosses it. A ray from x to
 * infinity, where the winding number is 0, therefore crosses triangles whose orientations along
 * the ray add up to w(x). The count is made exact:
 *  - the ray is x + s d, s > 0, d = +-e_k: its crossing of a triangle is decided in the plane of
 *    the two other coordinates, where the triangle is crossed when the point lies strictly inside
 *    its projection, and ahead of x along d. Both are signs of polynomials of the coordinates
 *    (2D orientations; the orientations times the triangle's coordinates along d, a degree-3
 *    polynomial), evaluated in double with an error bound and, where that cannot tell the sign,
 *    exactly, with Shewchuk's expansions (each product split by fma into its rounded value and
 *    its exact error, and the terms summed without loss);
 *  - where a sign is exactly zero (the ray through an edge or a vertex, a grid of points against
 *    an axis-aligned mesh), the point is moved by (eps, eps^2) in the two other coordinates,
 *    eps infinitesimal (simulation of simplicity): the sign is then that of the first nonzero
 *    coefficient of eps's powers, plain comparisons of coordinates. An edge shared by two
 *    triangles gets opposite signs from them, so the perturbed ray crosses exactly one of two
 *    triangles meeting along an edge it grazes, and none whose projection is a segment;
 *  - the tree is walked with axis-aligned float boxes around every slot, rounded outward and
 *    widened by the rounding of the point's and the vertices' shift to the mesh's origin, so that
 *    no triangle the exact ray crosses is skipped.
 * So the count is w of the point moved by (eps, eps^2) across the ray: w(x) itself for every x
 * off the surface. A point exactly on the plane of a triangle it would cross (on the surface) is
 * taken as behind it. Differences far smaller than the coordinates are scaled up by powers of two
 * (ray_triangle_local, orient2, and the exact sums formed again), so that a part of a mesh down to
 * about 2^-600 the size of the rest is counted exactly; the one case left out is a product that
 * underflows all the same: the function then says so, and the caller uses the hierarchical
 * winding number. A count through a mesh that is not closed is no winding number, but it is exact
 * all the same: points/caps.c adds one through the caps that close it (ttd_points_ray_count).
 *
 * The per-point count is points/ray_impl.h, which the device compiles too (src/gpu/,
 * gpu_signed_impl.h); this file gives it the mesh's arrays. */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "points/points.h"
#include "points/ray_impl.h"

/* The count's view of the mesh and its point data. */
static ttd_ray_mesh ray_view(const struct ttd_mesh *m, const ttd_points_data *pd)
{
    ttd_ray_mesh v;
    v.rnodes = pd->rnodes;
    v.verts = m->verts;
    v.tris = m->tris;
    v.bytes = m->bytes;
    for (int c = 0; c < 3; ++c)
        v.origin[c] = m->origin[c];
    v.radius = m->radius;
    v.scale = pd->scale;
    v.coord_max = pd->coord_max;
    return v;
}

void ttd_points_ray_direction(const struct ttd_mesh *m, const ttd_points_data *pd, const double x[3], int *k, int *sigma)
{
    const ttd_ray_mesh v = ray_view(m, pd);
    ttd_ray_direction(&v, x, k, sigma);
}

int ttd_points_ray_winding(const struct ttd_mesh *m, const ttd_points_data *pd, ttd_ray_node_fn ray_node,
                           const double x[3], int *w)
{
    const ttd_ray_mesh v = ray_view(m, pd);
    return ttd_ray_winding(&v, ray_node, x, w);
}

int ttd_points_ray_count(const struct ttd_mesh *m, const ttd_points_data *pd, ttd_ray_node_fn ray_node,
                         const double x[3], int k, int sigma, int *w)
{
    const ttd_ray_mesh v = ray_view(m, pd);
    return ttd_ray_count(&v, ray_node, x, k, sigma, w);
}

/* SPDX-License-Identifier: MIT */
/* Point queries against a mesh (include/ttd/ttd.h, "Point queries"; docs/points.md): what
 * src/api/points_api.c calls once it has checked its arguments.
 *
 * A mesh's point data is made from its hierarchy and vertices on the first point query and kept
 * in the mesh (struct ttd_mesh.points, set atomically: meshes are shared between threads):
 *  - the walk's nodes (core/point_layout.h's ttd_pnode): the hierarchy's nodes, one for one,
 *    with every child slot's box made axis-aligned, in float, from the vertices below it;
 *  - every node's triangle children prepared for the point kernel (core/point_layout.h), one
 *    block of TTD_PT_LANES per node that has any (the other slots hold a copy of its first
 *    triangle, harmless in the lanes), so a node's triangles are measured in one kernel call;
 *  - every child slot's winding-number moments (WM_* below): area vector, centre, second moment,
 *    area and radius, summed bottom-up, for the hierarchical winding number.
 * Both depend on the vertices: a change of vertices in place must call ttd_points_data_refresh. */
#ifndef TTD_POINTS_POINTS_H
#define TTD_POINTS_POINTS_H

#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "core/point_layout.h"
#include "points/point_math.h"
#include "engine/batch.h"
#include "mesh/mesh.h"

/* Winding-number moments of one child slot (a triangle or a subtree), in double, in the walk's
 * frame ((x - the mesh's origin) times ttd_points_data.scale, so that their powers stay in range at
 * every scale): the area vector N = sum of (1/2) cross(B - A, C - A), the centre pc (area-weighted
 * centroid), the second moment M[i][j] = integral of (x - pc)_i n_j dA (row-major), the
 * (unsigned) area, a radius about pc that holds every vertex below, and the polar moment
 * I = integral of |x - pc|^2 dA (rounded up), which the remainder's bound uses. */
enum {
    WM_N = 0,      /* 3 */
    WM_C = 3,      /* 3 */
    WM_M = 6,      /* 9 */
    WM_AREA = 15,
    WM_RADIUS = 16,
    WM_I = 17,
    WM_COUNT = 18
};

/* Meshes of at most this many triangles measure their points 8 at a time, one per lane, against
 * every triangle (points/closest_impl.h; docs/points.md, section 4). */
#define TTD_POINTS_TINY 8

typedef struct ttd_points_data ttd_points_data_s;

/* The caps of an open mesh (points/caps.c; docs/points.md, section 5.4): a cone from each boundary
 * loop's mean vertex over its edges, so that the mesh and its caps have no boundary. */
typedef struct ttd_points_caps {
    size_t ntri;               /* the caps' triangles: one per boundary edge (0: no boundary) */
    struct ttd_mesh *mesh;     /* the caps as a mesh of the mesh's precision (NULL when ntri = 0) */
    const ttd_points_data_s *pd; /* its point data, moments made */
} ttd_points_caps;

typedef struct ttd_points_data {
    void (*destroy)(void *self); /* first: the mesh frees its point data through it (mesh/build.c) */
    int bytes;             /* the mesh's precision */
    size_t nnodes;
    ttd_pnode *pnodes;     /* nnodes walk nodes, 64-byte aligned: node n's slots' boxes, children,
                            * block and triangle mask */
    double scale;          /* the walk nodes' frame: x -> (x - the mesh's origin) scale, a power of
                            * two that puts every vertex within [-1, 1] */
    double stretch;        /* every walk box's axes U have |U| <= stretch (1 + a few float eps) */
    ttd_rnode *rnodes;     /* nnodes ray walk nodes (points/ray.c) */
    double coord_max;      /* the largest vertex coordinate's magnitude (the ray's exact signs) */
    void *tiny;            /* a mesh of at most TTD_POINTS_TINY triangles: each prepared (stride 1),
                            * in index order, for the points-per-lane path (else NULL) */
    size_t nblocks;
    void *blocks;          /* nblocks x TTD_PT_ROWS x TTD_PT_LANES reals of the mesh's precision */
    double *moments;       /* nnodes x WM_COUNT x TTD_NODE_WIDTH: moment f of slot j of node n at
                            * [(n * WM_COUNT + f) * TTD_NODE_WIDTH + j]; made by the first winding
                            * walk (ttd_points_moments; NULL until then, atomic): a closed mesh's
                            * winding number is counted by a ray and seldom needs them */
    ttd_points_caps *caps; /* an open mesh's caps, made by its first winding number
                            * (ttd_points_caps_get; NULL until then, atomic) */
} ttd_points_data;

/// The mesh's point data, made on first use with `threads` workers; NULL when out of memory.
const ttd_points_data *ttd_points_data_get(const struct ttd_mesh *mesh, int threads);

/// The point data's winding-number moments, made on first use (NULL when out of memory).
const double *ttd_points_moments(const struct ttd_mesh *mesh, const ttd_points_data *pd);

/// The caps of the mesh (points/caps.c), made on first use and kept in pd; NULL when out of memory.
const ttd_points_caps *ttd_points_caps_get(const struct ttd_mesh *mesh, const ttd_points_data *pd);
void ttd_points_caps_free(ttd_points_caps *caps);

/// Recomputes the point data of a mesh whose vertices changed in place (same triangles, same
/// hierarchy shape, refitted boxes): a no-op when no point query has made it yet. The one function
/// that computes it, from the hierarchy and the vertices, bottom-up.
void ttd_points_data_refresh(struct ttd_mesh *mesh, int threads);

/* The closest point of mesh to each of n points (3n reals of the mesh's precision, in its frame)
 * within upper_bound, into results (ttd_point_result_d or _f). Points must be finite or flagged
 * NaN by the caller: a point with a NaN coordinate gets NaN outputs and TTD_POINT_NONFINITE.
 * Returns TTD_OK or TTD_ERR_OUT_OF_MEMORY. points/closest_d.c, closest_f.c. */
ttd_status ttd_points_query_closest_d(const ttd_engine_config *cfg, const struct ttd_mesh *mesh, size_t n,
                                      const double *points, double upper_bound, ttd_point_result_d *results);
ttd_status ttd_points_query_closest_f(const ttd_engine_config *cfg, const struct ttd_mesh *mesh, size_t n,
                                      const float *points, float upper_bound, ttd_point_result_f *results);

/* The winding number of the mesh about x (the mesh's coordinates, in double), hierarchically
 * (points/winding.c; docs/points.md): far subtrees by their moments, near triangles exactly.
 * *bound (when not NULL) gets a rigorous bound on the error of the far-field terms. */
double ttd_points_winding(const struct ttd_mesh *mesh, const ttd_points_data *pd, const double x[3], double *bound);

/* The winding number of a closed mesh about x (the mesh's coordinates), exactly: the signed count
 * of the triangles an axis-aligned ray from x crosses, with exact predicates (points/ray.c). For x
 * on the surface, the count of x moved by an infinitesimal across the ray. Returns 0 with *w set,
 * or -1 where it cannot be made exact (products below the subnormal range, or a stack overflow). */
int ttd_points_ray_winding(const struct ttd_mesh *mesh, const ttd_points_data *pd, ttd_ray_node_fn ray_node,
                           const double x[3], int *w);
/* The ray's axis k and sense sigma for x that ttd_points_ray_winding takes (where x leaves the
 * mesh's box soonest), and the signed count of the crossings of the ray x + s sigma e_k, s > 0,
 * for any mesh, any axis (for an open mesh the count is not its winding number: points/caps.c).
 * ttd_points_ray_count returns 0, or -1 as ttd_points_ray_winding. */
void ttd_points_ray_direction(const struct ttd_mesh *mesh, const ttd_points_data *pd, const double x[3], int *k, int *sigma);
int ttd_points_ray_count(const struct ttd_mesh *mesh, const ttd_points_data *pd, ttd_ray_node_fn ray_node,
                         const double x[3], int k, int sigma, int *count);


/* The n points (3n reals, double when bytes is 8, else float, in the mesh's frame) in order along
 * a Morton curve over the mesh's box (points/order.c): a malloc'd array of n indices (free it), or
 * NULL when out of memory (the caller goes in input order: the same answers). */
size_t *ttd_points_order(const struct ttd_mesh *mesh, const ttd_points_data *pd, size_t n, const void *points, int bytes);

/* The winding number about x, the one every query reports and decides a side by (the inside rule,
 * ttd_winding_inside: |w| >= 1/2): the exact count for a closed mesh; else the fast walk, and where
 * its bound does not settle the side of |w| = 1/2, the walk tightened until it does (down to every
 * triangle exactly). *proven: 1 when that side is proven (always off the surface of a closed
 * mesh), 0 where rounding leaves it open (a point within rounding of the surface, or of where an
 * open mesh's |w| is 1/2). A mesh of one triangle, whose |w| is below 1/2 everywhere, gets 0 and
 * proven at once. docs/points.md, section 5. */
/* ttd_points_winding_sign's value with *bound (when not NULL), a bound on its error: 0 for an exact
 * count, the walk's or the caps' bound otherwise (1/2 for a mesh of one triangle, given as 0). */
double ttd_points_winding_value(const struct ttd_mesh *mesh, const ttd_points_data *pd, int closed, ttd_ray_node_fn ray,
                                const double x[3], int *proven, double *bound);
double ttd_points_winding_sign(const struct ttd_mesh *mesh, const ttd_points_data *pd, int closed, ttd_ray_node_fn ray,
                               const double x[3], int *proven);

/* Whether x (the mesh's coordinates) lies inside closed mesh m: within its bounding sphere (the
 * cheap test that settles far points), then the inside rule on ttd_points_winding_sign's winding
 * number (a traversal rather than a pass over the triangles; the pass, mesh/solid.c's
 * ttd_mesh_winding, only when the point data cannot be had: out of memory). For the solid modes
 * of the mesh and scene queries, so that they decide as the point queries do. */
int ttd_points_inside(const struct ttd_mesh *m, const double x[3]);

/* A point p of the points' frame moved into the mesh's frame for the mesh's pose P = [R | t]
 * (12 reals of the query's precision): x_c = ((r0c (p0 - t0) + r1c (p1 - t1)) + r2c (p2 - t2));
 * and a point y of the mesh's frame moved back: ((rc0 y0 + rc1 y1) + rc2 y2) + tc, in place. The
 * arithmetic of the point queries' poses (include/ttd/ttd.h), written once. */
#define TTD_POINT_INTO(P, p, x)                                                                    \
    for (int c_ = 0; c_ < 3; ++c_)                                                             \
        (x)[c_] = ((P)[c_] * ((p)[0] - (P)[3]) + (P)[4 + c_] * ((p)[1] - (P)[7])) + (P)[8 + c_] * ((p)[2] - (P)[11]);
#define TTD_POINT_BACK(real, P, y)                                                                 \
    do {                                                                                       \
        const real y_[3] = {(y)[0], (y)[1], (y)[2]};                                           \
        for (int c_ = 0; c_ < 3; ++c_)                                                         \
            (y)[c_] = (((P)[4 * c_] * y_[0] + (P)[4 * c_ + 1] * y_[1]) + (P)[4 * c_ + 2] * y_[2]) + (P)[4 * c_ + 3]; \
    } while (0)

/* The winding numbers of mesh about n points (3n reals of the mesh's precision, in its frame) into
 * winding (double), over the threads: ttd_points_winding_sign's, and with proven not NULL
 * whether each side is proven. TTD_OK or TTD_ERR_OUT_OF_MEMORY. NaN
 * for a NaN point. */
ttd_status ttd_points_query_winding(const ttd_engine_config *cfg, const struct ttd_mesh *mesh, size_t n,
                                    const void *points, double *winding, uint8_t *proven);

#endif /* TTD_POINTS_POINTS_H */

/* SPDX-License-Identifier: MIT */
/* A mesh and its bounding-volume hierarchy (the opaque ttd_mesh of ttd/ttd.h), and the entries
 * that build and query it. The public entries (src/api/mesh_api.c) check every argument and
 * call these.
 *
 * The hierarchy: nodes of up to TTD_NODE_WIDTH children (core/kernels.h), each child an
 * oriented box around a triangle or a subtree, stored one array per coordinate so that one node
 * test bounds all children at once on every instruction set. Boxes live in the mesh's own frame
 * moved to its origin (the centre of the vertices' bounding box), so that a query's arithmetic
 * runs on magnitudes of the meshes' sizes and their distance, not of where they sit. Node 0
 * holds the root's box in slot 0; the tree starts at node 1 (a mesh of one triangle has node 0
 * only, its slot 0 the triangle). Triangles keep the caller's coordinates and indices: a query
 * hands the exact kernel the same triangles a brute force over all pairs would. */
#ifndef TTD_MESH_MESH_H
#define TTD_MESH_MESH_H

#include <float.h>
#include <math.h>
#include <stddef.h>
#include <stdint.h>

#include "core/kernels.h"
#include "engine/batch.h"
#include "mesh/edges.h"

struct ttd_mesh {
    int bytes;          /* 8: built from double vertices and queried in double; 4: float */
    size_t nv, nt;
    void *verts;        /* 3 nv reals: a copy of the caller's */
    uint32_t *tris;     /* 3 nt indices: a copy */
    void *nodes;        /* nnodes ttd_node_d or ttd_node_f, 64-byte aligned */
    size_t nnodes;
    double origin[3];   /* the boxes' origin, in the mesh's coordinates */
    double radius;      /* every vertex is within radius of origin (rounded up) */
    int closed;         /* solid queries: 0 not known yet, 1 closed, 2 not (mesh/solid.c; atomic) */
    ttd_mesh_edges *edges; /* neighbours across edges, flat or real edges and corners, normals
                            * (mesh/edges.h): made on first use by ttd_mesh_edges_get (atomically:
                            * meshes are shared between threads); NULL until then */
    /* the point queries' data (src/points/points.h: prepared triangles, winding-number moments),
     * made on first use (atomic); its first member is the function that frees it */
    void *points;
    /* the self-contact queries' arrays (mesh/self_grid_impl.h), kept between queries; taken and
     * given back atomically; its first member is the function that frees it; NULL until then */
    void *self_scratch;
    /* Deforming meshes (ttd_mesh_refit): */
    uint64_t generation; /* vertex updates so far: a scene's bodies compare it with theirs */
    uint64_t rebuilds;   /* of those, the ones whose refit triggered a rebuild */
    double quality;      /* the tree's quality measure (build.c, tree_quality), now */
    double quality_built; /* and when the tree was last built */
    uint32_t *leaf_vix;   /* per node, 24: a leaf's triangles' vertex indices in slot order (build.c,
                           * leaf_indices), for the refit to read in the order it walks the tree;
                           * made by the first refit, dropped with the tree by a rebuild; NULL
                           * until then (the entries of nodes that are not leaves are not set) */
    void *refit_scratch;  /* the refit's per-node sums and measure parts (build.c, refit_scratch),
                           * made by the mesh's first refit and kept for the next ones (a rebuild
                           * keeps it; sized again where the node count differs), freed with the
                           * mesh; NULL until then */
};

/* A refit rebuilds the tree when its quality measure has grown past this factor of what it was
 * at the last build (docs/mesh-queries.md, section 2b). */
#define TTD_MESH_REBUILD_RATIO 2.0

/* The largest coordinate magnitude a mesh query works on, a's vertices and b's moved by a pose
 * alike: 2^60 in float, 2^508 in double. Below it no square or product of a node test or of the
 * traversal overflows (coordinate differences stay below 2^61 or 2^509, a squared distance below
 * 3 * 2^122 or 3 * 2^1018); beyond it a lower bound could overflow and prune a pair wrongly. */
static inline double ttd_mesh_range(int bytes)
{
    return bytes == 8 ? 0x1p508 : 0x1p60;
}

/// Builds the mesh from checked arguments (indices in range, coordinates finite and within ttd_mesh_range, nv, nt > 0):
/// TTD_OK, or TTD_ERR_OUT_OF_MEMORY (*out NULL). verts holds 3 nv reals of bytes each.
ttd_status ttd_mesh_build(const ttd_engine_config *cfg, int bytes, const void *verts, size_t nv,
                          const uint32_t *tris, size_t nt, struct ttd_mesh **out);

/// New positions for a built mesh's vertices (checked as the build checks them; 3 nv reals of the
/// mesh's precision), the same triangles: the hierarchy is refitted (its shape kept, every box
/// fitted again as the build fits it), and rebuilt when that has degraded it past
/// TTD_MESH_REBUILD_RATIO. TTD_OK, or TTD_ERR_OUT_OF_MEMORY with the mesh as it was.
ttd_status ttd_mesh_refit(const ttd_engine_config *cfg, struct ttd_mesh *mesh, const void *verts);

/// Frees a mesh built by ttd_mesh_build.
void ttd_mesh_free(struct ttd_mesh *mesh);

/// The mesh's edge information (mesh/edges.h), made on first use from its vertices and triangles
/// (ttd_mesh_edges_build) and kept: the first caller's, set by compare-and-swap, so that any number
/// of threads may ask at once (a thread that loses the race frees its copy, the same arrays).
/// NULL when out of memory. A mesh build does not pay for it: only the scene's manifolds read it.
/// A mesh whose vertices change frees it (and sets NULL) for the next use to make again.
const ttd_mesh_edges *ttd_mesh_edges_get(const struct ttd_mesh *mesh);

/// The edge information once ttd_mesh_edges_get has made it (NULL before), read as it is
/// published: an acquire load, so that a reader on one thread and another thread's
/// compare-and-swap (which ThreadSanitizer counts as a write even when it fails) are ordered.
static inline const ttd_mesh_edges *ttd_mesh_edges_made(const struct ttd_mesh *mesh)
{
    return __atomic_load_n(&mesh->edges, __ATOMIC_ACQUIRE);
}

/* The queries, from checked arguments (meshes of the query's precision, k >= 1 rigid poses,
 * outputs present); defects[i] is max |R^T R - I| of pose i, which the traversal's rounding
 * margin covers. poses_a is NULL (b's poses map it into a's frame, and results are in a's frame)
 * or a's k poses (scenes: both map into the world, results are in the world frame, and
 * defects[i] covers the relative pose of b in a's frame). Each fills out (k results, or the contact set) and returns TTD_OK or
 * TTD_ERR_OUT_OF_MEMORY. The double and float entries are written out in mesh/query_d.c and
 * query_f.c. */
ttd_status ttd_mesh_query_distance_d(const ttd_engine_config *cfg, const struct ttd_mesh *a, const struct ttd_mesh *b,
                                     size_t k, const double *poses, const double *poses_a, const double *defects, double upper_bound,
                                     double rel_tol, ttd_mesh_result_d *out);
ttd_status ttd_mesh_query_distance_f(const ttd_engine_config *cfg, const struct ttd_mesh *a, const struct ttd_mesh *b,
                                     size_t k, const float *poses, const float *poses_a, const double *defects, float upper_bound,
                                     float rel_tol, ttd_mesh_result_f *out);
ttd_status ttd_mesh_query_collide_d(const ttd_engine_config *cfg, const struct ttd_mesh *a, const struct ttd_mesh *b,
                                    size_t k, const double *poses, const double *poses_a, const double *defects, double margin,
                                    ttd_collision *out);
ttd_status ttd_mesh_query_collide_f(const ttd_engine_config *cfg, const struct ttd_mesh *a, const struct ttd_mesh *b,
                                    size_t k, const float *poses, const float *poses_a, const double *defects, float margin,
                                    ttd_collision *out);
ttd_status ttd_mesh_query_contacts_d(const ttd_engine_config *cfg, const struct ttd_mesh *a, const struct ttd_mesh *b,
                                     size_t k, const double *poses, const double *poses_a, const double *defects, double margin,
                                     ttd_contacts_d *out);
ttd_status ttd_mesh_query_contacts_f(const ttd_engine_config *cfg, const struct ttd_mesh *a, const struct ttd_mesh *b,
                                     size_t k, const float *poses, const float *poses_a, const double *defects, float margin,
                                     ttd_contacts_f *out);

/* Only each pose's number of contacts, into counts[0 .. k): the pairs are counted, not held. */
ttd_status ttd_mesh_query_contacts_count_d(const ttd_engine_config *cfg, const struct ttd_mesh *a, const struct ttd_mesh *b,
                                           size_t k, const double *poses, const double *defects, double margin,
                                           size_t *counts);
ttd_status ttd_mesh_query_contacts_count_f(const ttd_engine_config *cfg, const struct ttd_mesh *a, const struct ttd_mesh *b,
                                           size_t k, const float *poses, const double *defects, float margin,
                                           size_t *counts);

/* One pose's contacts (pose_a as above, or NULL), walked from the root on the calling thread, into
 * out in the walk's order: the same set as ttd_mesh_query_contacts_*, in another order, for a
 * caller that sorts them (a scene's body pair); tests[0] and [1]: the walk's node tests and the
 * triangle pairs it gave the exact method. */
ttd_status ttd_mesh_query_contacts_walk_d(const ttd_engine_config *cfg, const struct ttd_mesh *a,
                                          const struct ttd_mesh *b, const double *pose, const double *pose_a,
                                          double defect, double margin, ttd_contacts_d *out,
                                          uint64_t tests[2]);
ttd_status ttd_mesh_query_contacts_walk_f(const ttd_engine_config *cfg, const struct ttd_mesh *a,
                                          const struct ttd_mesh *b, const float *pose, const float *pose_a,
                                          double defect, float margin, ttd_contacts_f *out,
                                          uint64_t tests[2]);
/* ttd_mesh_query_contacts_walk_*'s number of contacts alone, into *count (counted, not held). */
ttd_status ttd_mesh_query_contacts_walk_count_d(const ttd_engine_config *cfg, const struct ttd_mesh *a,
                                                const struct ttd_mesh *b, const double *pose, const double *pose_a,
                                                double defect, double margin, size_t *count, uint64_t tests[2]);
ttd_status ttd_mesh_query_contacts_walk_count_f(const ttd_engine_config *cfg, const struct ttd_mesh *a,
                                                const struct ttd_mesh *b, const float *pose, const float *pose_a,
                                                double defect, float margin, size_t *count, uint64_t tests[2]);
/* Self queries: pairs of one mesh's triangles (i < j) that share no vertex, and with shared
 * (TTD_SELF_SHARED_VERTEX) those that share one, by their edges opposite it (ttd/ttd.h); from
 * checked arguments. Written out in mesh/query_d.c and query_f.c. */
ttd_status ttd_mesh_query_self_contacts_d(const ttd_engine_config *cfg, const struct ttd_mesh *m, double margin,
                                          unsigned shared, ttd_contacts_d *out);
ttd_status ttd_mesh_query_self_contacts_f(const ttd_engine_config *cfg, const struct ttd_mesh *m, float margin,
                                          unsigned shared, ttd_contacts_f *out);
ttd_status ttd_mesh_query_self_contacts_count_d(const ttd_engine_config *cfg, const struct ttd_mesh *m, double margin,
                                                unsigned shared, size_t *count);
ttd_status ttd_mesh_query_self_contacts_count_f(const ttd_engine_config *cfg, const struct ttd_mesh *m, float margin,
                                                unsigned shared, size_t *count);
/* The self-contacts by the walk alone (query_impl.h): what ttd_mesh_query_self_contacts_* give
 * where the grid of leaves would do no better (mesh/self_grid_impl.h), for the tests to compare
 * the two ways. */
ttd_status ttd_mesh_query_self_contacts_walk_d(const ttd_engine_config *cfg, const struct ttd_mesh *m, double margin,
                                               unsigned shared, ttd_contacts_d *out);
ttd_status ttd_mesh_query_self_contacts_walk_f(const ttd_engine_config *cfg, const struct ttd_mesh *m, float margin,
                                               unsigned shared, ttd_contacts_f *out);
ttd_status ttd_mesh_query_self_collide_d(const ttd_engine_config *cfg, const struct ttd_mesh *m, double margin,
                                         unsigned shared, ttd_collision *out);
ttd_status ttd_mesh_query_self_collide_f(const ttd_engine_config *cfg, const struct ttd_mesh *m, float margin,
                                         unsigned shared, ttd_collision *out);

/* Solids (mesh/solid.c). Whether the mesh is closed: every directed edge (u, v) of a triangle
 * appears once, and so does (v, u), by vertex index. Found on first use and kept (meshes are
 * shared between threads: the flag is written atomically, and racing first uses compute the same
 * answer). */
int ttd_mesh_closed(const struct ttd_mesh *mesh); /* 1, 0, or -1 out of memory */
/* How the mesh's triangles are oriented (include/ttd/ttd.h, ttd_mesh_orientation): closed (above)
 * and by the sign of its volume outward, inward or flat; else inconsistent where every edge is on
 * two triangles, open otherwise. (ttd_orientation)-1 when out of memory. Not kept: the volume's
 * sign is the vertices'. */
ttd_orientation ttd_mesh_orientation_of(const struct ttd_mesh *mesh);
/* The winding number of a closed mesh about point x (the mesh's own coordinates): the sum of
 * its triangles' signed solid angles over 4 pi; near +-1 inside, near 0 outside, for x not on
 * the surface. */
double ttd_mesh_winding(const struct ttd_mesh *mesh, const double x[3]);
/* The signed solid angle of triangle t seen from x (van Oosterom and Strackee, at unit scale),
 * positive when x sees the triangle's back (the side its counter-clockwise normal points away
 * from): the term the winding number sums. */
double ttd_mesh_solid_angle(const struct ttd_mesh *mesh, size_t t, const double x[3]);

#endif /* TTD_MESH_MESH_H */

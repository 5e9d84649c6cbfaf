/* SPDX-License-Identifier: MIT */
/* A scene (the opaque ttd_scene of ttd/ttd.h): bodies, each a mesh at a world pose, with their
 * filters, and the broad phase over them. The public entries (src/api/scene_api.c) check every
 * argument and call these; the queries over body pairs (scene/query_impl.h, compiled per
 * precision) hand each candidate body pair to the mesh traversal with both bodies' poses.
 *
 * The broad phase (docs/scenes.md): every body has a world box (axis-aligned) around its mesh's
 * root box moved by its pose, recomputed when the pose changes or the mesh's vertices moved
 * (ttd_mesh_set_vertices_*: the body's generation no longer the mesh's, seen by every query); the present bodies are kept
 * sorted by their boxes' lower end along one axis, and a query sweeps that order (sweep and
 * prune). A step of small moves leaves the order nearly sorted, so it is repaired by insertion
 * sort, in time linear in the bodies and the swaps, instead of being rebuilt. */
#ifndef TTD_SCENE_SCENE_H
#define TTD_SCENE_SCENE_H

#include <stddef.h>
#include <stdint.h>

#include "engine/batch.h"
#include "engine/parallel.h"
#include "mesh/mesh.h"

typedef struct scene_body {
    const struct ttd_mesh *mesh; /* NULL: removed */
    double pose[12];             /* as given, in double (a float scene's are floats widened) */
    float pose_f[12];            /* a float scene's, as given */
    double defect;               /* max |R^T R - I| */
    uint32_t group, mask;
    int solid;                   /* a solid (its mesh closed): pairs of solids are solid pairs */
    uint64_t generation;         /* the mesh's generation (vertex updates) its world box was
                                  * computed for: a query recomputes the box when they differ */
} scene_body;

struct ttd_scene {
    int bytes;                   /* 8 or 4: the precision of every mesh and pose */
    scene_body *body;            /* indexed by id */
    size_t nbody, cap;           /* ids given so far, room */
    size_t present;              /* bodies not removed */
    double *box;                 /* 6 per id: its world box, lo[3] then hi[3], with a rounding
                                  * margin; apart from the bodies' records, so that the sweep
                                  * reads 48 bytes a body */
    uint32_t *order;             /* present bodies sorted by lo[axis] (sweep and prune) */
    size_t norder;
    int order_stale;             /* a body was added or removed: order to be rebuilt */
    int axis;
    void *sweep_d, *sweep_i, *sweep_b; /* the sweep's scratch (scene.c), kept between queries */
    size_t sweep_d_cap, sweep_i_cap, sweep_b_cap;
    uint64_t *excluded;          /* excluded pairs, i << 32 | j with i < j, sorted */
    size_t nexcluded, excluded_cap;
    ttd_scene_stats stats;       /* what the last query did (ttd_scene_get_stats) */
    struct ttd_pool *pool;       /* worker threads kept between queries (engine/parallel.h) */
    void *scratch;               /* the contact and manifold queries' per-worker memory, kept
                                  * between queries (scene/query_impl.h, of the scene's precision) */
    void (*scratch_free)(void *); /* frees it: set with it */
    size_t (*scratch_held)(const void *); /* the bytes of contact blocks it holds: set with it */
};

/* The bound on s->scratch (scene/query_impl.h, scratch_done): after SCRATCH_THIN_QUERIES queries
 * in a row that each fill under a quarter of the contact blocks held, the scene frees it; blocks
 * of SCRATCH_SMALL contacts or fewer in all are kept whatever the queries use. */
#define SCRATCH_THIN_QUERIES 8
#define SCRATCH_SMALL 4096

/// The bytes of contact blocks the scene's query scratch holds (0: none held): what its bound
/// measures; for the tests.
size_t ttd_scene_scratch_held(const struct ttd_scene *s);

/// A candidate body pair (i < j) of a sweep.
typedef struct scene_pair {
    uint32_t i, j;
} scene_pair;

/// Sets body id's pose (checked) from 12 reals of the scene's precision, and its world box (for
/// its mesh's vertices as they are now: the body's generation becomes the mesh's).
void ttd_scene_place(struct ttd_scene *s, uint32_t id, const void *pose, double defect);

/// The eligible body pairs whose world boxes are within margin on every axis (so every pair of
/// bodies at distance <= margin), restricted to pairs with a body in `only` (NULL: all; else
/// only[id] != 0), sorted by (i, j), into *out (malloc'd, *n of them). 0 when out of memory.
int ttd_scene_sweep(struct ttd_scene *s, double margin, const unsigned char *only, scene_pair **out, size_t *n);
/// ttd_scene_sweep with its inner loop on `threads` of the scene's pool (the same pairs in the same
/// order); not from inside a task of that pool.
int ttd_scene_sweep_on(struct ttd_scene *s, int threads, double margin, const unsigned char *only, scene_pair **out,
                       size_t *n);

/// Whether bodies i and j (both present) may touch: the filters and the exclusions.
int ttd_scene_eligible(const struct ttd_scene *s, uint32_t i, uint32_t j);

/// A bound on the scene's extent: the diagonal of the box around every present body's box.
double ttd_scene_extent(const struct ttd_scene *s);

/* The queries, from checked arguments (a scene of the query's precision, a margin or bound
 * within range, outputs present); each returns TTD_OK or TTD_ERR_OUT_OF_MEMORY. */
ttd_status ttd_scene_query_collide_d(const ttd_engine_config *cfg, struct ttd_scene *s, double margin,
                                     ttd_scene_array *out);
ttd_status ttd_scene_query_collide_f(const ttd_engine_config *cfg, struct ttd_scene *s, float margin,
                                     ttd_scene_array *out);
ttd_status ttd_scene_query_contacts_d(const ttd_engine_config *cfg, struct ttd_scene *s, double margin,
                                      ttd_scene_array *out);
ttd_status ttd_scene_query_contacts_f(const ttd_engine_config *cfg, struct ttd_scene *s, float margin,
                                      ttd_scene_array *out);
ttd_status ttd_scene_query_contacts_count_d(const ttd_engine_config *cfg, struct ttd_scene *s, double margin,
                                            size_t *count);
ttd_status ttd_scene_query_contacts_count_f(const ttd_engine_config *cfg, struct ttd_scene *s, float margin,
                                            size_t *count);
ttd_status ttd_scene_query_distance_d(const ttd_engine_config *cfg, struct ttd_scene *s, double upper_bound,
                                      ttd_scene_contact_d *closest, ttd_scene_contact_d *nearest);
ttd_status ttd_scene_query_distance_f(const ttd_engine_config *cfg, struct ttd_scene *s, float upper_bound,
                                      ttd_scene_contact_f *closest, ttd_scene_contact_f *nearest);
ttd_status ttd_scene_query_manifold_d(const ttd_engine_config *cfg, struct ttd_scene *s, double margin,
                                      size_t max_points, ttd_scene_array *out);
ttd_status ttd_scene_query_manifold_f(const ttd_engine_config *cfg, struct ttd_scene *s, float margin,
                                      size_t max_points, ttd_scene_array *out);

#endif /* TTD_SCENE_SCENE_H */

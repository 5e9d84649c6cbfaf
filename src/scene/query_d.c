/* SPDX-License-Identifier: MIT */
/* The scene queries in double: scene/query_impl.h compiled for this precision, and its entries
 * (scene/scene.h) written out. */
#include <math.h>
#include <stdatomic.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define TTD_PRECISION_DOUBLE
#include "core/precision.h"
#include "engine/dispatch.h"
#include "engine/parallel.h"
#include "mesh/mesh.h"
#include "points/points.h"
#include "scalar/scalar.h"
#include "scene/scene.h"

typedef ttd_scene_contact_d ttd_scene_contact;
typedef ttd_scene_point_d ttd_scene_point;
typedef ttd_contacts_d ttd_mesh_contacts;
typedef ttd_contact_d ttd_mesh_contact;
typedef ttd_mesh_result_d ttd_mesh_result;
#define TTD_QUERY(name) ttd_mesh_query_##name##_d
#define TTD_CONTACTS_FREE ttd_contacts_free_d
#define TTD_EXACT_PAIR ttd_exact_pair_d
#define TTD_EXACT_PAIR_DUPS ttd_exact_pair_dups_d
#define TTD_EXACT_KERNEL(isa) ttd_dispatch_kernel_d(isa, TTD_METHOD_EXACT)
typedef ttd_kernel_d_fn ttd_exact_kernel_fn;
typedef ttd_out_d ttd_kernel_out;
typedef ttd_result_d ttd_result;
typedef ttd_point_result_d ttd_point_result;
#define TTD_POINTS_CLOSEST ttd_points_query_closest_d
#include "scene/query_impl.h"

ttd_status ttd_scene_query_collide_d(const ttd_engine_config *cfg, struct ttd_scene *s, double margin, ttd_scene_array *out)
{
    return query_collide(cfg, s, margin, out);
}

ttd_status ttd_scene_query_contacts_d(const ttd_engine_config *cfg, struct ttd_scene *s, double margin, ttd_scene_array *out)
{
    return query_contacts(cfg, s, margin, out);
}

ttd_status ttd_scene_query_contacts_count_d(const ttd_engine_config *cfg, struct ttd_scene *s, double margin,
                                            size_t *count)
{
    return query_contacts_count(cfg, s, margin, count);
}

ttd_status ttd_scene_query_distance_d(const ttd_engine_config *cfg, struct ttd_scene *s, double upper_bound,
                                      ttd_scene_contact_d *closest, ttd_scene_contact_d *nearest)
{
    return query_distance(cfg, s, upper_bound, closest, nearest);
}

ttd_status ttd_scene_query_manifold_d(const ttd_engine_config *cfg, struct ttd_scene *s, double margin, size_t max_points,
                                      ttd_scene_array *out)
{
    return query_manifold(cfg, s, margin, max_points, out);
}

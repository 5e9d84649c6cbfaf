/* SPDX-License-Identifier: MIT */
/* The scene queries in float: scene/query_impl.h compiled for this precision, and its entries
 * (scene/scene.h) written out. */
#include <math.h>
#include <stdatomic.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define TTD_PRECISION_FLOAT
#include "core/precision.h"
#include "engine/dispatch.h"
#include "engine/parallel.h"
#include "mesh/mesh.h"
#include "points/points.h"
#include "scalar/scalar.h"
#include "scene/scene.h"

typedef ttd_scene_contact_f ttd_scene_contact;
typedef ttd_scene_point_f ttd_scene_point;
typedef ttd_contacts_f ttd_mesh_contacts;
typedef ttd_contact_f ttd_mesh_contact;
typedef ttd_mesh_result_f ttd_mesh_result;
#define TTD_QUERY(name) ttd_mesh_query_##name##_f
#define TTD_CONTACTS_FREE ttd_contacts_free_f
#define TTD_EXACT_PAIR ttd_exact_pair_f
#define TTD_EXACT_PAIR_DUPS ttd_exact_pair_dups_f
#define TTD_EXACT_KERNEL(isa) ttd_dispatch_kernel_f(isa, TTD_METHOD_EXACT)
typedef ttd_kernel_f_fn ttd_exact_kernel_fn;
typedef ttd_out_f ttd_kernel_out;
typedef ttd_result_f ttd_result;
typedef ttd_point_result_f ttd_point_result;
#define TTD_POINTS_CLOSEST ttd_points_query_closest_f
#include "scene/query_impl.h"

ttd_status ttd_scene_query_collide_f(const ttd_engine_config *cfg, struct ttd_scene *s, float margin, ttd_scene_array *out)
{
    return query_collide(cfg, s, margin, out);
}

ttd_status ttd_scene_query_contacts_f(const ttd_engine_config *cfg, struct ttd_scene *s, float margin, ttd_scene_array *out)
{
    return query_contacts(cfg, s, margin, out);
}

ttd_status ttd_scene_query_contacts_count_f(const ttd_engine_config *cfg, struct ttd_scene *s, float margin,
                                            size_t *count)
{
    return query_contacts_count(cfg, s, margin, count);
}

ttd_status ttd_scene_query_distance_f(const ttd_engine_config *cfg, struct ttd_scene *s, float upper_bound,
                                      ttd_scene_contact_f *closest, ttd_scene_contact_f *nearest)
{
    return query_distance(cfg, s, upper_bound, closest, nearest);
}

ttd_status ttd_scene_query_manifold_f(const ttd_engine_config *cfg, struct ttd_scene *s, float margin, size_t max_points,
                                      ttd_scene_array *out)
{
    return query_manifold(cfg, s, margin, max_points, out);
}
